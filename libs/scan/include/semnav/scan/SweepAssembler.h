/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/scan/Sweep.h>

#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
/** Turns a stream of tilted 2D scan lines (CObservation2DRangeScan whose
 * sensorPose carries the tilt, see TiltGeometry.h) and odometry into Sweeps.
 *
 * A sweep is the run of consecutive lines of one sensor between two
 * reversals of the tilt direction. A line with the same tilt as the previous
 * one is a repeat and is dropped, unless the next line reverses direction:
 * then it opens the new sweep (a nodding head may scan its end tilt twice).
 * When the robot moves (the odometry leaves the sweep's first reading by
 * more than the motion tolerance) the current sweep ends; incomplete sweeps
 * cut that way or begun after such a cut were taken while driving: with
 * dropMotionFragments (semnav-map's default) they are dropped, so a robot's
 * recording yields the sweeps taken standing.
 * Gaps in the tilt sequence become invalid rows (quality().missingLines);
 * a sweep spanning less than `complete_span_fraction` of the reference span
 * is emitted with quality().complete == false, never dropped.
 *
 * Push observations with push(), take finished sweeps with pop(); call
 * finish() at the end of the stream to flush the last sweep. */
class SweepAssembler : public mrpt::system::COutputLogger
{
public:
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** Only lines with this sensorLabel; empty = the first seen. */
		std::string sensorLabel;
		/** Tilts closer than this are "the same line" (rad). */
		double sameTiltTolerance = 0.05 * M_PI / 180;
		/** Returns closer than this are invalid (robot body), m. */
		double minValidRange = 0.05;
		/** Tilt span of a complete sweep (rad); 0 = the largest span seen
		 * so far in the stream. */
		double nominalSpan = 0;
		/** A sweep is complete when its span reaches this fraction of the
		 * reference span. */
		double completeSpanFraction = 0.95;
		/** End the sweep when the odometry moves (stop-and-scan). */
		bool splitOnMotion = true;
		/** Drop (never emit) incomplete sweeps cut by motion, or begun at
		 * such a cut and ended by a reversal: the pieces of nods taken
		 * while driving. */
		bool dropMotionFragments = false;

		/** The defaults for reprocessing a robot's recording (semnav-map):
		 * dropMotionFragments on. */
		static TOptions forRecordings()
		{
			TOptions o;
			o.dropMotionFragments = true;
			return o;
		}
		/** Odometry changes below these are not motion (m, rad). */
		double motionTolerance = 0.005;
		double motionToleranceYaw = 0.2 * M_PI / 180;
	};

	SweepAssembler();
	explicit SweepAssembler(const TOptions& options);

	/** Feeds one observation: 2D scans of the selected sensor and
	 * CObservationOdometry are used, anything else is ignored. */
	void push(const mrpt::obs::CObservation::Ptr& obs);
	/** Feeds an absolute odometry reading (e.g. from a rawlog action). */
	void pushOdometry(const mrpt::poses::CPose2D& odometry);
	/** Ends the stream: the sweep in progress is emitted. */
	void finish();

	/** True when a finished sweep is waiting. */
	bool hasSweep() const { return !m_ready.empty(); }
	/** Takes the oldest finished sweep (precondition: hasSweep()). */
	Sweep pop();

	std::size_t sweepsEmitted() const { return m_emitted; }
	/** Scan lines dropped because their beam count changed mid-sweep or
	 * they came from another sensor. */
	std::size_t linesIgnored() const { return m_linesIgnored; }
	/** Incomplete sweeps dropped because they were taken while driving
	 * (TOptions::dropMotionFragments). */
	std::size_t sweepsDroppedMoving() const { return m_droppedMoving; }

	const TOptions& options() const { return m_options; }

private:
	struct Line
	{
		double theta;
		mrpt::obs::CObservation2DRangeScan::Ptr scan;
	};
	enum class EndReason
	{
		Reversal,
		Motion,
		Other
	};
	void pushLine(const mrpt::obs::CObservation2DRangeScan::Ptr& scan);
	void startSweep(std::vector<Line> lines);
	void closeSweep(EndReason why);
	Sweep build(const std::vector<Line>& lines, EndReason why);
	/** The current lines are a piece of a nod taken while driving. */
	bool isMotionFragment(EndReason why) const;
	double referenceSpan() const
	{
		return m_options.nominalSpan > 0 ? m_options.nominalSpan
		                                 : m_largestSpan;
	}
	bool spanIsComplete(double span) const;

	TOptions m_options;
	std::string m_label;
	std::vector<Line> m_lines;
	std::optional<Line> m_pending;
	int m_direction = 0;
	std::size_t m_repeated = 0;
	std::optional<mrpt::poses::CPose2D> m_odometry, m_sweepOdometry;
	double m_largestSpan = 0;
	std::deque<Sweep> m_ready;
	std::size_t m_emitted = 0;
	std::size_t m_linesIgnored = 0;
	std::size_t m_droppedMoving = 0;
	/** The last sweep was cut by motion / the current one began then. */
	bool m_afterMotion = false, m_startedAfterMotion = false;
};

}  // namespace semnav

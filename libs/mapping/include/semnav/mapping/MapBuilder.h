/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/detection/SweepPerception.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/localization/TrajectoryError.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/GroundTruthScorer.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/SweepAssembler.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
/** A map-building run (semnav-map): every sweep of a rawlog or of 3DTK
 * scans goes through SweepPerception (rules, and the cascades with their
 * 3D checks when configured) and into a SemanticMap at the robot pose from
 * odometry, from semnav-sim's ground truth, or from localization against
 * the map built so far (MappingLocalizer). With semnav-sim's ground truth
 * (`gtDir`) the run also scores the labels per class and the poses.
 *
 * A corrupt or truncated rawlog ends the run at the last good sweep; the
 * map of the sweeps before it is kept and readError() says what happened. */
class MapBuilder
{
public:
	/** Where the pose of each sweep comes from. */
	enum class PoseSource
	{
		Odometry,
		GroundTruth,
		Localization
	};
	/** "odometry", "gt", "pf". */
	static std::string poseSourceName(PoseSource p);
	/** The inverse of poseSourceName(); nothing for another name. */
	static std::optional<PoseSource> poseSourceFromName(const std::string& s);

	/** What a run is made of. */
	struct Settings
	{
		SemanticMap::TOptions map;
		PerceptionPipeline::TOptions perception;
		SweepAssembler::TOptions assembler =
		    SweepAssembler::TOptions::forRecordings();
		/** Object detection; nothing: rules only. */
		std::optional<CascadeDetector::TOptions> cascades;
		MappingLocalizer::TOptions localization;
		PoseSource poses = PoseSource::Odometry;
		/** The input: a rawlog, or else 3DTK scans (in this order). */
		std::string rawlog;
		std::vector<std::string> scans3dtk;
		/** semnav-sim's output directory: scores labels and poses. */
		std::string gtDir;
	};

	/** Loads the ground truth and the detector; throws IoError,
	 * ConfigError or CascadeError naming the file that cannot be read. */
	explicit MapBuilder(const Settings& settings);
	~MapBuilder();

	/** Sweeps the run expects (0 when unknown). */
	std::size_t expectedSweeps() const;

	/** Runs over every sweep; `progress(done)` after each. */
	void run(const std::function<void(std::size_t)>& progress = {});

	const SemanticMap& map() const { return m_map; }
	/** Time per sweep (perception, localization, insertion), ms. */
	const std::vector<double>& msPerSweep() const { return m_ms; }
	/** Time of each localization update after the first sweep, ms. */
	const std::vector<double>& msPerLocalization() const { return m_locMs; }
	/** Each localization update after the first sweep (pose, covariance,
	 * directions that followed the prediction). */
	const std::vector<LocalizationUpdate>& localizationUpdates() const
	{
		return m_updates;
	}
	/** Whether the run was scored against ground truth (gtDir given). */
	bool scored() const { return !m_settings.gtDir.empty(); }
	const GroundTruthScorer& labelScores() const { return m_scorer; }
	/** Error of the poses used, and of the odometry (when scored()). */
	const TrajectoryError& poseError() const { return m_poseError; }
	const TrajectoryError& odometryError() const { return m_odometryError; }
	/** Incomplete sweeps of the rawlog skipped, as the robot skips them
	 * (head reversed early, cut by a fault or the end of the log). */
	std::size_t sweepsSkippedIncomplete() const { return m_skippedIncomplete; }
	/** Sweeps whose perception threw (skipped with a warning on stderr). */
	std::size_t sweepsFailed() const { return m_failed; }
	/** Pieces of sweeps taken while the robot drove, dropped by the
	 * assembler (SweepAssembler::sweepsDroppedMoving()). */
	std::size_t sweepsDroppedMoving() const;
	/** The rawlog error that ended the run early ("" if none). */
	const std::string& readError() const { return m_readError; }

private:
	bool nextSweep(Sweep& sweep);
	mrpt::poses::CPose2D insert(const Sweep& sweep, const LabeledSweep& ls);

	Settings m_settings;
	std::optional<GroundTruthLog> m_gt;
	std::unique_ptr<class RawlogSweepReader> m_reader;
	std::size_t m_next3dtk = 0;
	SweepPerception m_perception;
	SemanticMap m_map;
	std::unique_ptr<MappingLocalizer> m_localizer;
	std::vector<double> m_ms, m_locMs;
	std::vector<LocalizationUpdate> m_updates;
	GroundTruthScorer m_scorer;
	TrajectoryError m_poseError, m_odometryError;
	std::string m_readError;
	std::size_t m_skippedIncomplete = 0, m_failed = 0;
};

}  // namespace semnav

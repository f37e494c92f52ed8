/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/sim/Scene.h>
#include <semnav/sim/TiltingLaserSimulator.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
class SemanticMap;
class SimulatedRobot;

/** Localization of a SimulatedRobot in a known semantic map, the way the
 * paper's robot does it (sec. 2.3): stop, take a tilting-laser sweep
 * (TiltingLaserSimulator on the scene, at the robot's true pose), run
 * perception (PerceptionPipeline) and the wall extractor, and update the
 * wall-landmark particle filter (Localizer on the map's walls) with the
 * robot's odometry since the previous sweep.
 *
 * - start(): global (particles over the map's free cells) or tracking
 *   (particles around a rough guess). While the filter has not converged
 *   the robot turns on the spot by turn_deg and sweeps again, at most
 *   max_sweeps sweeps; then LocalizationFailedError. On success the robot
 *   reports the estimate (SimulatedRobot::setPoseEstimate).
 * - rescan(): one more stop-and-scan update during navigation; the robot's
 *   reported pose jumps to the new estimate.
 *
 * Options: INI section [StopAndScan] (config/navigation.ini). */
class StopAndScanLocalizer : public mrpt::system::COutputLogger
{
public:
	enum class Mode
	{
		Global,
		Tracking
	};
	static std::string modeName(Mode m);
	/** "global" or "tracking"; throws Error otherwise. */
	static Mode modeFromName(const std::string& name);

	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** converged_fraction, converged_radius_m, converged_yaw_deg: a
		 * start has converged when the filter's spread is below its
		 * thresholds ([Localizer]) or when at least this fraction of the
		 * particle weight lies within this distance and heading of the
		 * estimate (one dominant hypothesis; a few stray particles far
		 * away keep the spread large for many sweeps). */
		double convergedFraction = 0.95;
		double convergedRadius = 0.25;
		double convergedYaw = mrpt::DEG2RAD(3.0);
		/** max_sweeps: sweeps of a start before giving up. */
		int maxSweeps = 8;
		/** turn_deg: turn on the spot between start sweeps (rad). */
		double turnAngle = mrpt::DEG2RAD(60.0);
		/** turn_speed_deg_s (rad/s). */
		double turnSpeed = mrpt::DEG2RAD(45.0);
		/** line_period_s: time of one scan line; a sweep stops the robot
		 * for lines x period of simulated time. */
		double linePeriod = 1.0 / 75;
		/** guess_std_xy_m, guess_std_yaw_deg, guess_particles: the particle
		 * cloud of a tracking start around --start-guess. */
		double guessStdXY = 0.5;
		double guessStdYaw = mrpt::DEG2RAD(15.0);
		int guessParticles = 4000;
		/** rescan_distance_m: during navigation, stop and scan after this
		 * much odometry travel (0: never). */
		double rescanDistance = 2.0;
		/** odometry_noise: the robot's odometry gets the scene's odometry
		 * errors (heading bias and noise) while localizing. */
		bool odometryNoise = true;
		/** seed: laser range noise and odometry noise. */
		int seed = 1;
	};

	/** One sweep and its filter update. */
	struct SweepRecord
	{
		mrpt::math::TPose2D truePose, estimate;
		double stdXY = 0, stdYaw = 0;
		std::size_t segments = 0;
		std::size_t particles = 0;
		/** Fraction of the particle weight near the estimate (see
		 * converged_fraction). */
		double massNear = 0;
		bool converged = false;
		/** Sweep simulation + perception + walls + update, wall clock. */
		double ms = 0;
		/** Filter update alone (Localizer), ms. */
		double updateMs = 0;
		/** Error of the estimate against the true pose (m, rad). */
		double errorXY = 0, errorYaw = 0;
	};

	/** Outcome of start(). */
	struct Report
	{
		Mode mode = Mode::Global;
		int sweeps = 0;
		bool converged = false;
		mrpt::math::TPose2D estimate, truth;
		/** Estimate minus truth at the end of the start (m, rad). */
		double errorXY = 0, errorYaw = 0;
		/** Wall clock of the whole start, ms. */
		double ms = 0;
		std::vector<SweepRecord> records;
	};

	/** `map` is the known map (its walls and free cells); `scene` is what
	 * the laser sees. Both must outlive the localizer. Throws
	 * LocalizationFailedError when the map has no walls. */
	StopAndScanLocalizer(
	    const Scene& scene, const SemanticMap& map, const TOptions& options,
	    const MappingLocalizer::TOptions& localization,
	    const PerceptionPipeline::TOptions& perception);
	~StopAndScanLocalizer() override;

	/** Localizes the robot where it stands (see the class comment). A
	 * tracking start needs `guess`. Throws LocalizationFailedError. */
	Report start(
	    SimulatedRobot& robot, Mode mode,
	    const std::optional<mrpt::math::TPose2D>& guess = std::nullopt);

	/** One stop-and-scan update: stops the robot, sweeps, updates the
	 * filter and the robot's estimate. */
	SweepRecord rescan(SimulatedRobot& robot);

	/** Every sweep so far (start and rescans). */
	const std::vector<SweepRecord>& records() const { return m_records; }
	const TOptions& options() const { return m_options; }
	const Localizer& localizer() const { return *m_localizer; }

private:
	SweepRecord sweepAndUpdate(SimulatedRobot& robot);
	/** Fraction of the particle weight within convergedRadius and
	 * convergedYaw of `estimate`. */
	double massNear(const mrpt::math::TPose2D& estimate) const;

	const Scene& m_scene;
	const SemanticMap& m_map;
	TOptions m_options;
	MappingLocalizer::TOptions m_locOptions;
	PerceptionPipeline m_perception;
	WallExtractor m_extractor;
	std::unique_ptr<Localizer> m_localizer;
	const RayCaster* m_caster = nullptr;
	std::unique_ptr<TiltingLaserSimulator> m_laser;
	LabeledSweep m_labeled;
	std::vector<SweepRecord> m_records;
	mrpt::math::TPose2D m_lastOdometry;
	std::size_t m_sweepIndex = 0;
};

}  // namespace semnav

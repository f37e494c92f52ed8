/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <semnav/common/Label.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/nav/NavCommand.h>
#include <semnav/nav/NavigationLoop.h>
#include <semnav/nav/SemanticNavigator.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/navsim/SimulationConfig.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/sim/Scene.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
class SemanticMap;
class SimulatedRobot;

/** A headless navigation run in simulation: a SimulatedRobot in `scene`,
 * plugged through its seams into the runtime's own pieces (MRPT's
 * navigator over RobotNavInterface, SemanticNavigator planning on `map`,
 * StopAndScanLocalizer, NavigationLoop), in simulated time, until the goal
 * is reached, the navigator stops, or [SimulatedRobot] max_time_s passes.
 * Only the evaluation (collisions, true trajectory, errors) reads the
 * simulated world. */
class SimulatedNavigation
{
public:
	struct Result
	{
		/** True arrival: the robot believes it reached the goal
		 * (believedReached) and truly stands within arrivalTolerance of
		 * it (trueDistance). */
		bool success = false;
		/** What the robot believes: the navigator stopped with Reached,
		 * at the pose it reported (its estimate; the truth without
		 * localization). */
		bool believedReached = false;
		mrpt::math::TPose2D believedFinalPose;
		/** Believed reached, but not truly within arrivalTolerance. */
		bool falseArrival = false;
		/** The scene's object the goal stands for: of the goal's label,
		 * the one nearest the map instance (0: the scene has none, or a
		 * point goal). */
		int trueObjectId = 0;
		mrpt::math::TPoint2D trueObjectXY{0, 0};
		/** From the true final position to that object's footprint (to
		 * the point of a point goal); nothing without a true object. */
		std::optional<double> trueDistance;
		/** From the true final position to the nearest footprint of the
		 * scene's objects of the goal's label (nothing if none). */
		std::optional<double> trueNearestOfLabel;
		double arrivalTolerance = 0;
		SemanticNavigator::StopReason reason =
		    SemanticNavigator::StopReason::None;
		std::string message;
		NavCommand command;
		/** Object of the last plan (0 for a point goal). */
		int objectId = 0;
		Label objectLabel = Label::Unknown;
		mrpt::math::TPoint2D objectXY{0, 0};
		/** True poses. */
		mrpt::math::TPose2D start, finalPose;
		/** From the true final position to the map instance's footprint
		 * (or to the goal point). */
		double distanceToGoal = 0;
		int collisions = 0;
		std::vector<mrpt::math::TPose2D> collisionPoses;
		double simTime = 0;
		int replans = 0;
		int steps = 0;
		double wallSeconds = 0;
		/** Median wall time of one step (navigator + replan check), ms. */
		double medianStepMs = 0;
		std::vector<mrpt::math::TPose2D> trajectory;
		std::vector<SemanticNavigator::PlanRecord> plans;
		/** Obstacles the robot sensed that the map lacked. */
		std::vector<mrpt::math::TPoint2D> sensedObstacles;
		/** MRPT navlog written (empty if none). */
		std::string navlog;
		/** With setLocalization(): the start's localization, the
		 * stop-and-scan updates on the way, and the pose the navigator saw
		 * after every step (estimate; the trajectory above is the truth). */
		std::optional<StopAndScanLocalizer::Report> localization;
		std::vector<StopAndScanLocalizer::SweepRecord> rescans;
		/** Rescans that found the robot lost and relocalized it (turning
		 * and sweeping). */
		int recoveries = 0;
		/** The sweeps at the goal that confirmed (or not) each believed
		 * arrival. */
		std::vector<StopAndScanLocalizer::ArrivalCheck> arrivals;
		std::vector<mrpt::math::TPose2D> estimatedTrajectory;

		/** The outcome in words, naming the goal `object` (e.g. "
		 * wastebasket 6 at (11.16, 2.64)") after its verb:
		 * "reached<object>", "believed reached<object> but truly 5.30 m
		 * from the wastebasket: FALSE ARRIVAL", or the navigator's stop
		 * message followed by `object`. */
		std::string outcome(const std::string& object = "") const;
	};

	/** Called after every step with the simulated time; may change the
	 * map and call notifyMapChanged(). */
	using StepHook = NavigationLoop::StepHook;

	SimulatedNavigation(
	    const SemanticMap& map, const Scene& scene,
	    const SimulationConfig& config);

	/** The robot does not know its start pose: before the run a
	 * StopAndScanLocalizer (options from the config, `localization` and
	 * `perception`) localizes it where it stands (`mode`; a tracking start
	 * from `guess`), and the navigator sees that estimate composed with the
	 * robot's odometry (which gets the scene's odometry errors); its
	 * sweeps' objects are detected with `cascades` (none without); with
	 * [StopAndScan] rescan_distance_m > 0 the robot stops and scans again on
	 * the way. Without this call the navigator sees the true pose. The
	 * localizer lives as long as this object (localizer()). Throws
	 * LocalizationFailedError when the map has no walls. */
	void setLocalization(
	    StopAndScanLocalizer::Mode mode,
	    const MappingLocalizer::TOptions& localization,
	    const PerceptionPipeline::TOptions& perception,
	    const std::optional<mrpt::math::TPose2D>& guess = std::nullopt,
	    const std::optional<CascadeDetector::TOptions>& cascades =
	        std::nullopt);

	/** Runs one command from `start` (the true pose). With `navlogPath`, MRPT's
	 * navigation log is written there (atomically, at the end). Throws the
	 * first plan's errors (NoInstanceError, StartBlockedError, NoPathError...)
	 * and LocalizationFailedError. */
	Result run(
	    const NavCommand& command, const mrpt::math::TPose2D& start,
	    const std::string& navlogPath = "", const StepHook& hook = {});

	/** A kidnapping: at simulated time `atTime` (s) the robot is carried
	 * to `to` while its odometry notices nothing (the next stop-and-scan
	 * must find it lost and relocalize it). */
	void setKidnapping(double atTime, const mrpt::math::TPose2D& to)
	{
		m_kidnapAt = atTime;
		m_kidnapTo = to;
	}

	/** The localizer of setLocalization() (nullptr without). */
	const StopAndScanLocalizer* localizer() const { return m_localizer.get(); }
	StopAndScanLocalizer* localizer() { return m_localizer.get(); }

private:
	/** The result's outcome and evaluation fields. */
	void evaluate(
	    const SemanticNavigator& nav, const SimulatedRobot& robot,
	    Result& r) const;
	/** Believed against true arrival (after evaluate()'s fields). */
	void judgeArrival(Result& r) const;

	const SemanticMap& m_map;
	const Scene& m_scene;
	const SimulationConfig& m_config;
	std::unique_ptr<StopAndScanLocalizer> m_localizer;
	StopAndScanLocalizer::Mode m_mode = StopAndScanLocalizer::Mode::Global;
	std::optional<mrpt::math::TPose2D> m_guess;
	std::optional<double> m_kidnapAt;
	mrpt::math::TPose2D m_kidnapTo;
};

}  // namespace semnav

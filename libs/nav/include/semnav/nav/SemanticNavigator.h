/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/nav/reactive/CReactiveNavigationSystem.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/nav/NavCommand.h>
#include <semnav/nav/NavInterfaceMonitor.h>
#include <semnav/planning/SemanticPlanner.h>

#include <memory>
#include <string>
#include <vector>

namespace semnav
{
class SemanticMap;

/** Executes semantic commands: the CNN planner (SemanticPlanner) plans on
 * the semantic map, the path is thinned into a TWaypointSequence and
 * handed to MRPT's CReactiveNavigationSystem (PTGs for a differential
 * drive), which drives the robot through any CRobot2NavInterface.
 *
 * It replans from the current pose when
 * - the navigator reports the way blocked, the target blocked or a
 *   navigation error (CRobot2NavInterface events, seen through a
 *   NavInterfaceMonitor),
 * - the robot senses, within path_check_distance_m ahead on the path, an
 *   obstacle the map does not hold (it is then added to the planner's
 *   extra obstacles),
 * - the owner calls notifyMapChanged();
 * and stops with a typed StopReason when the goal turns out blocked, no path
 * exists, or it makes no progress (max_stalled_replans).
 *
 * Call start(), then step() once per control period until it returns
 * something other than State::Navigating.
 *
 * MRPT's PTG collision grids (about 1 s to build) are cached in
 * <tmp>/semnav-ptg-cache/<hash of the MRPT sections>/ and published there
 * atomically; nothing is written to the working directory. */
class SemanticNavigator : public mrpt::system::COutputLogger
{
public:
	/** Options, INI section [SemanticNavigator] (config/navigation.ini). */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** profile: cost profile of the navigation plans: shortest | safe |
		 * planning (the [Traversability] profile of planning.ini). */
		std::string profile = "safe";
		/** max_waypoint_spacing_m: longest straight leg between waypoints. */
		double maxWaypointSpacing = 1.5;
		/** waypoint_allowed_distance_m: intermediate waypoints. */
		double waypointAllowedDistance = 0.35;
		/** goal_allowed_distance_m: the last waypoint (in the goal region). */
		double goalAllowedDistance = 0.15;
		/** max_stalled_replans: give up after this many replans in a row
		 * without progress. A replan makes progress when its path is
		 * progress_m shorter than the shortest since the last progress,
		 * or when the map has observed progress_area_m2 more of the world
		 * since then (exploring: a plan through unseen space grows as
		 * walls appear, and each stop-and-scan shows new space). */
		int maxStalledReplans = 25;
		double progressDistance = 0.25;
		double progressArea = 1.0;
		/** path_check_distance_m: look-ahead along the path for sensed
		 * obstacles the map does not hold. */
		double pathCheckDistance = 2.0;
		/** path_clearance_m: such an obstacle closer than this to the path
		 * blocks it. */
		double pathClearance = 0.22;
		/** path_blocked_steps: consecutive steps the path must be seen
		 * blocked before replanning. */
		int pathBlockedSteps = 2;
		/** sensed_obstacle_range_m: sensed points within this distance of
		 * the robot become planner obstacles on a replan. */
		double sensedObstacleRange = 3.0;
		/** align_threshold_deg: when the first waypoint of a (re)plan lies
		 * more than this off the robot's heading, the robot first turns on
		 * the spot toward it (CRobot2NavInterface::getAlignCmd(); skipped
		 * if the robot returns no such command). */
		double alignThresholdDeg = 80;
		/** start_snap_m: a replan from a blocked cell (the robot brushed an
		 * inflated obstacle) starts from the nearest free cell this close. */
		double startSnap = 0.4;
	};

	enum class State
	{
		Idle,
		Navigating,
		Reached,
		Failed
	};

	enum class StopReason
	{
		None,
		Reached,
		/** No path from the current pose to the goal (any more). */
		NoPath,
		/** Every cell of the goal region is blocked (the goal lies in an
		 * obstacle, or too close to one for the robot). */
		GoalBlocked,
		/** The robot stands where it cannot plan from. */
		StartBlocked,
		/** max_stalled_replans replans in a row without progress. */
		NoProgress,
		/** The caller gave up (time limit). */
		Timeout,
		Cancelled,
		/** The navigator arrived by the robot's belief, but the sweep taken
		 * there did not confirm it (refuseArrival()). */
		ArrivalNotConfirmed
	};

	enum class ReplanReason
	{
		Initial,
		WayBlocked,
		TargetBlocked,
		NavigatorError,
		PathBlockedBySensedObstacle,
		MapChanged,
		/** The arrival was not confirmed: navigate again (retry()). */
		ArrivalNotConfirmed,
		/** The robot was relocalized after the navigator had stopped
		 * (retry()). */
		Relocalized
	};

	/** One plan of a run. */
	struct PlanRecord
	{
		ReplanReason reason = ReplanReason::Initial;
		double time = 0;
		mrpt::math::TPose2D from;
		std::vector<mrpt::math::TPoint2D> path;
		std::vector<mrpt::math::TPoint2D> waypoints;
		double cost = 0;
		double lengthM = 0;
		int goalObjectId = 0;
		double milliseconds = 0;
	};

	/** `navConfig` holds MRPT's reactive sections
	 * ([CAbstractNavigator], [CAbstractPTGBasedReactive],
	 * [CReactiveNavigationSystem] with the PTGs, ...). */
	SemanticNavigator(
	    mrpt::nav::CRobot2NavInterface& robot, const SemanticMap& map,
	    const mrpt::config::CConfigFileBase& navConfig,
	    const CnnPlanner::TOptions& cnn,
	    const TraversabilityBuilder::TOptions& traversability,
	    const TOptions& options);
	~SemanticNavigator() override;

	/** Writes MRPT's navigation log (.reactivenavlog, navlog-viewer) into
	 * `dir` from now on; "" stops it. */
	void setNavLogDirectory(const std::string& dir);

	/** Plans from the robot's pose and starts. Throws NoInstanceError (a
	 * label with no object), StartOutsideMapError, StartBlockedError,
	 * NoPathError, Error (unknown object id), PlanningError (goal outside
	 * the map). */
	void start(const NavCommand& command);
	/** One control step. */
	State step();
	/** The map changed: replan at the next step. */
	void notifyMapChanged() { m_mapChanged = true; }
	/** The robot's pose estimate was corrected (relocalization): the
	 * obstacles sensed so far were placed with the old estimate, forget
	 * them (the scan senses what is still there again) and replan at the
	 * next step. */
	void notifyPoseCorrected()
	{
		m_planner.setExtraObstacles({});
		m_mapChanged = true;
	}
	void cancel(StopReason reason = StopReason::Cancelled);
	/** After State::Reached (the arrival was not confirmed) or State::Failed
	 * (the pose was corrected since): replans from the robot's pose for
	 * the same command and navigates on (`reason`: ArrivalNotConfirmed or
	 * Relocalized). Returns false when no path is left (state Failed). */
	bool retry(ReplanReason reason = ReplanReason::ArrivalNotConfirmed);
	/** After State::Reached: the arrival was not confirmed and no retry is
	 * left: State::Failed with StopReason::ArrivalNotConfirmed. */
	void refuseArrival(const std::string& why);

	State state() const { return m_state; }
	StopReason stopReason() const { return m_reason; }
	/** One line on why it stopped. */
	const std::string& stopMessage() const { return m_message; }
	int replans() const
	{
		return m_plans.empty() ? 0 : static_cast<int>(m_plans.size()) - 1;
	}
	const std::vector<PlanRecord>& plans() const { return m_plans; }
	/** Object of the current plan (0 for a point). */
	int goalObjectId() const { return m_goalObjectId; }
	const NavCommand& command() const { return m_command; }
	const SemanticPlanner& planner() const { return m_planner; }
	CostProfile profile() const { return m_profile; }
	mrpt::nav::CReactiveNavigationSystem& navigator() { return *m_nav; }
	/** Wall time of the last replan and of the last step (ms). */
	double lastPlanMs() const { return m_lastPlanMs; }
	double lastStepMs() const { return m_lastStepMs; }
	/** Robot pose as the navigator sees it. */
	mrpt::math::TPose2D robotPose();

	static const char* stopReasonName(StopReason r);
	static const char* replanReasonName(ReplanReason r);

	/** Replans now (public for benchmarks and tests). Returns false when
	 * the navigator stopped (no path). */
	bool replan(ReplanReason reason);

private:
	/** planFrom the pose or, when it is blocked (inflated obstacle), from
	 * the nearest free cell within start_snap_m. */
	SemanticPlanner::SharedPlan planFromNearestFree(
	    const mrpt::math::TPose2D& pose);
	SemanticPlanner::SharedPlan planFrom(double x, double y);
	bool pathBlocked();
	/** Hands the last plan's waypoints to MRPT, after turning toward the
	 * first one if needed. */
	void sendWaypoints();
	/** Bearing of the first waypoint of the last plan (rad, robot frame). */
	double bearingToFirstWaypoint();
	/** A map obstacle within one cell of (x, y). */
	bool knownObstacle(double x, double y) const;
	void addSensedObstacles();
	void stopWith(StopReason r, const std::string& message);
	/** Progress bookkeeping after a plan of `lengthM` (see
	 * max_stalled_replans); `first` starts it over. */
	void trackProgress(double lengthM, bool first);
	/** Cells of the map observed at least once. */
	std::size_t observedCells() const;

	NavInterfaceMonitor m_monitor;
	const SemanticMap& m_map;
	SemanticPlanner m_planner;
	TOptions m_options;
	CostProfile m_profile;
	std::unique_ptr<mrpt::nav::CReactiveNavigationSystem> m_nav;
	std::string m_ptgCacheDir;

	NavCommand m_command;
	State m_state = State::Idle;
	StopReason m_reason = StopReason::None;
	std::string m_message;
	std::vector<PlanRecord> m_plans;
	int m_goalObjectId = 0;
	bool m_mapChanged = false;
	bool m_aligning = false;
	int m_blockedSteps = 0;
	/** Replans since the last progress, the shortest path since then and
	 * the observed cells then. */
	int m_stalled = 0;
	double m_bestLength = 0;
	std::size_t m_seenAtProgress = 0;
	double m_lastPlanMs = 0, m_lastStepMs = 0;
};

}  // namespace semnav

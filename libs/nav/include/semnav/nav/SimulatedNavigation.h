/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <semnav/common/Label.h>
#include <semnav/nav/NavCommand.h>
#include <semnav/nav/NavigationConfig.h>
#include <semnav/nav/SemanticNavigator.h>
#include <semnav/sim/Scene.h>

#include <functional>
#include <string>
#include <vector>

namespace semnav
{
class SemanticMap;

/** A headless navigation run: a SimulatedRobot in `scene` driven by a
 * SemanticNavigator planning on `map`, in simulated time, until the goal is
 * reached, the navigator stops, or [SimulatedRobot] max_time_s passes. */
class SimulatedNavigation
{
public:
	struct Result
	{
		bool success = false;
		SemanticNavigator::StopReason reason =
		    SemanticNavigator::StopReason::None;
		std::string message;
		NavCommand command;
		/** Object of the last plan (0 for a point goal). */
		int objectId = 0;
		Label objectLabel = Label::Unknown;
		mrpt::math::TPoint2D objectXY{0, 0};
		mrpt::math::TPose2D start, finalPose;
		/** From the final position to the object's footprint (or to the
		 * goal point). */
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
	};

	/** Called after every step with the simulated time; may change the
	 * map and call notifyMapChanged(). */
	using StepHook = std::function<void(double simTime, SemanticNavigator&)>;

	SimulatedNavigation(
	    const SemanticMap& map, const Scene& scene,
	    const NavigationConfig& config);

	/** Runs one command from `start`. With `navlogPath`, MRPT's navigation
	 * log is written there (atomically, at the end). Throws the first
	 * plan's errors (NoInstanceError, StartBlockedError, NoPathError...). */
	Result run(
	    const NavCommand& command, const mrpt::math::TPose2D& start,
	    const std::string& navlogPath = "", const StepHook& hook = {});

private:
	const SemanticMap& m_map;
	const Scene& m_scene;
	const NavigationConfig& m_config;
};

}  // namespace semnav

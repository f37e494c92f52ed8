/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavLogFile.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/RobotNavInterface.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/navsim/SimulatedNavigation.h>
#include <semnav/planning/SemanticPlanner.h>
#include <semnav/sim/SimulatedRobot.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace semnav
{
namespace
{
double distanceToBox(
    const mrpt::math::TPoint2D& p, const mrpt::math::TPoint3D& lo,
    const mrpt::math::TPoint3D& hi)
{
	const double dx = std::max({lo.x - p.x, 0.0, p.x - hi.x});
	const double dy = std::max({lo.y - p.y, 0.0, p.y - hi.y});
	return std::hypot(dx, dy);
}

double distanceToSceneObject(
    const mrpt::math::TPoint2D& p, const SceneObject& o)
{
	mrpt::math::TPoint3D lo, hi;
	SceneMapBuilder::bounds(o, lo, hi);
	return distanceToBox(p, lo, hi);
}
}  // namespace

std::string SimulatedNavigation::Result::outcome(
    const std::string& object) const
{
	if (success) return "reached" + object;
	if (!falseArrival) return message + object;
	if (!trueDistance)
		return "believed reached" + object +
		       " but the scene has no such object: FALSE ARRIVAL";
	char buf[160];
	std::snprintf(
	    buf, sizeof(buf), " but truly %.2f m from the %s: FALSE ARRIVAL",
	    *trueDistance,
	    trueObjectId ? labelName(objectLabel).c_str() : "goal point");
	return "believed reached" + object + buf;
}

SimulatedNavigation::SimulatedNavigation(
    const SemanticMap& map, const Scene& scene, const SimulationConfig& config)
    : m_map(map), m_scene(scene), m_config(config)
{
}

void SimulatedNavigation::setLocalization(
    StopAndScanLocalizer::Mode mode,
    const MappingLocalizer::TOptions& localization,
    const PerceptionPipeline::TOptions& perception,
    const std::optional<mrpt::math::TPose2D>& guess,
    const std::optional<CascadeDetector::TOptions>& cascades)
{
	m_localizer = std::make_unique<StopAndScanLocalizer>(
	    m_map, m_config.stopAndScan, localization, perception, cascades);
	if (m_config.viewPlanner.enabled)
		m_localizer->enableViewPlanning(
		    m_config.navigationTraversability(m_map), m_config.viewPlanner);
	m_mode = mode;
	m_guess = guess;
}

SimulatedNavigation::Result SimulatedNavigation::run(
    const NavCommand& command, const mrpt::math::TPose2D& start,
    const std::string& navlogPath, const StepHook& hook)
{
	const auto wall0 = std::chrono::steady_clock::now();
	Result r;
	r.command = command;
	r.start = start;

	SimulatedRobot robot(m_scene, m_config.robot, start);
	robot.base().setMinLoggingLevel(mrpt::system::LVL_ERROR);
	if (robot.base().inCollision(start))
		throw NavigationError(
		    "start (" + std::to_string(start.x) + ", " +
		    std::to_string(start.y) + ") is inside an obstacle of the scene");
	const RobotInterfaces io = robot.interfaces();
	// Without localization the robot knows its pose.
	const PoseSource* reported = &robot.truePose();
	if (m_localizer)
	{
		robot.enableOdometryNoise(m_scene.odometry);
		r.localization = m_localizer->start(io, m_mode, m_guess);
		reported = &robot.localizedPose();
	}
	RobotNavInterface robotInterface(
	    robot.base(), *reported, robot.obstacles(), robot,
	    m_config.robotInterface);
	robotInterface.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	SemanticNavigator nav(
	    robotInterface, m_map, *m_config.mrptSections, m_config.cnn,
	    m_config.traversability, m_config.navigator);
	nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	NavLogFile navlog(nav, navlogPath);

	nav.start(command);
	NavigationLoop loop(nav, io, m_localizer.get());
	bool kidnapped = false;
	const auto step = [&](double t, SemanticNavigator& n)
	{
		if (m_kidnapAt && !kidnapped && t >= *m_kidnapAt)
		{
			robot.base().carryTo(m_kidnapTo);
			kidnapped = true;
		}
		if (hook) hook(t, n);
	};
	const NavigationLoop::Result lr = loop.run(m_config.robot.maxTime, step);
	// Let the robot come to rest.
	robot.tick();

	r.steps = lr.steps;
	r.medianStepMs = lr.medianStepMs;
	r.rescans = lr.rescans;
	r.recoveries = lr.recoveries;
	r.arrivals = lr.arrivals;
	evaluate(nav, robot, r);
	r.navlog = navlog.finish();
	r.wallSeconds =
	    std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0)
	        .count();
	return r;
}

void SimulatedNavigation::evaluate(
    const SemanticNavigator& nav, const SimulatedRobot& robot, Result& r) const
{
	r.reason = nav.stopReason();
	r.believedReached = r.reason == SemanticNavigator::StopReason::Reached;
	r.message = nav.stopMessage();
	r.objectId = nav.goalObjectId();
	const SimulatedBase& base = robot.base();
	r.finalPose = base.pose();
	const mrpt::math::TPoint2D fin{r.finalPose.x, r.finalPose.y};
	if (r.objectId)
	{
		const ObjectInstance& o = m_map.instance(r.objectId);
		r.objectLabel = o.label;
		r.objectXY = {o.centroid.x, o.centroid.y};
		r.distanceToGoal = distanceToBox(fin, o.minCorner, o.maxCorner);
	}
	else if (r.command.kind == NavCommand::Kind::Point)
	{
		r.objectXY = {r.command.x, r.command.y};
		r.distanceToGoal = std::hypot(fin.x - r.command.x, fin.y - r.command.y);
	}
	r.collisions = base.collisions();
	r.collisionPoses = base.collisionPoses();
	r.simTime = base.time();
	r.replans = nav.replans();
	r.trajectory = base.trajectory();
	r.estimatedTrajectory = robot.estimatedTrajectory();
	r.believedFinalPose = r.estimatedTrajectory.empty()
	                          ? r.finalPose
	                          : r.estimatedTrajectory.back();
	r.plans = nav.plans();
	r.sensedObstacles = nav.planner().extraObstacles();
	judgeArrival(r);
}

void SimulatedNavigation::judgeArrival(Result& r) const
{
	const mrpt::math::TPoint2D fin{r.finalPose.x, r.finalPose.y};
	if (r.objectId)
	{
		const ObjectInstance& goal = m_map.instance(r.objectId);
		const mrpt::math::TPoint2D goalXY{goal.centroid.x, goal.centroid.y};
		const SceneObject* truth = nullptr;
		double nearestToGoal = 0;
		for (const auto& o : m_scene.objects)
		{
			if (o.label != r.objectLabel) continue;
			const double d = distanceToSceneObject(goalXY, o);
			if (!truth || d < nearestToGoal)
			{
				truth = &o;
				nearestToGoal = d;
			}
			const double fromRobot = distanceToSceneObject(fin, o);
			if (!r.trueNearestOfLabel || fromRobot < *r.trueNearestOfLabel)
				r.trueNearestOfLabel = fromRobot;
		}
		if (truth)
		{
			mrpt::math::TPoint3D lo, hi;
			SceneMapBuilder::bounds(*truth, lo, hi);
			r.trueObjectId = truth->id;
			r.trueObjectXY = {(lo.x + hi.x) / 2, (lo.y + hi.y) / 2};
			r.trueDistance = distanceToBox(fin, lo, hi);
		}
	}
	else if (r.command.kind == NavCommand::Kind::Point)
	{
		r.trueObjectXY = r.objectXY;
		r.trueDistance = r.distanceToGoal;
	}
	r.arrivalTolerance = m_config.arrivalTolerance(r.objectId != 0);
	const bool trulyThere =
	    r.trueDistance && *r.trueDistance <= r.arrivalTolerance;
	r.success = r.believedReached && trulyThere;
	r.falseArrival = r.believedReached && !trulyThere;
}

}  // namespace semnav

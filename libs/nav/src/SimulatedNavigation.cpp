/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/SimulatedNavigation.h>
#include <semnav/nav/SimulatedRobot.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

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
}  // namespace

SimulatedNavigation::SimulatedNavigation(
    const SemanticMap& map, const Scene& scene, const NavigationConfig& config)
    : m_map(map), m_scene(scene), m_config(config)
{
}

void SimulatedNavigation::setLocalization(
    StopAndScanLocalizer* localizer, StopAndScanLocalizer::Mode mode,
    const std::optional<mrpt::math::TPose2D>& guess)
{
	m_localizer = localizer;
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
	robot.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	if (robot.inCollision(start))
		throw NavigationError(
		    "start (" + std::to_string(start.x) + ", " +
		    std::to_string(start.y) + ") is inside an obstacle of the scene");
	if (m_localizer)
		r.localization = m_localizer->start(robot, m_mode, m_guess);
	const double rescanDistance =
	    m_localizer ? m_localizer->options().rescanDistance : 0.0;
	double lastScanAt = robot.odometryDistance();
	SemanticNavigator nav(
	    robot, m_map, *m_config.mrptSections, m_config.cnn,
	    m_config.traversability, m_config.navigator);
	nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	std::string logDir;
	if (!navlogPath.empty())
	{
		const auto parent =
		    std::filesystem::path(navlogPath).parent_path().string();
		createDirectories(parent.empty() ? "." : parent);
		logDir = (std::filesystem::path(parent.empty() ? "." : parent) /
		          (".navlog-" + std::to_string(::getpid())))
		             .string();
		std::filesystem::remove_all(logDir);
		nav.setNavLogDirectory(logDir);
	}

	nav.start(command);
	std::vector<double> stepMs;
	while (nav.state() == SemanticNavigator::State::Navigating)
	{
		if (robot.simTime() >= m_config.robot.maxTime)
		{
			nav.cancel(SemanticNavigator::StopReason::Timeout);
			break;
		}
		nav.step();
		stepMs.push_back(nav.lastStepMs());
		r.steps++;
		if (nav.state() != SemanticNavigator::State::Navigating) break;
		robot.simulate();
		if (rescanDistance > 0 &&
		    robot.odometryDistance() - lastScanAt >= rescanDistance)
		{
			const auto rep = m_localizer->rescan(robot);
			r.rescans.insert(
			    r.rescans.end(), rep.records.begin(), rep.records.end());
			if (rep.recovery) r.recoveries++;
			nav.notifyPoseCorrected();
			lastScanAt = robot.odometryDistance();
		}
		if (hook) hook(robot.simTime(), nav);
	}
	// Let the robot come to rest.
	robot.simulate();

	r.reason = nav.stopReason();
	r.success = r.reason == SemanticNavigator::StopReason::Reached;
	r.message = nav.stopMessage();
	r.objectId = nav.goalObjectId();
	r.finalPose = robot.pose();
	const mrpt::math::TPoint2D fin{r.finalPose.x, r.finalPose.y};
	if (r.objectId)
	{
		const ObjectInstance& o = m_map.instance(r.objectId);
		r.objectLabel = o.label;
		r.objectXY = {o.centroid.x, o.centroid.y};
		r.distanceToGoal = distanceToBox(fin, o.minCorner, o.maxCorner);
	}
	else if (command.kind == NavCommand::Kind::Point)
	{
		r.objectXY = {command.x, command.y};
		r.distanceToGoal = std::hypot(fin.x - command.x, fin.y - command.y);
	}
	r.collisions = robot.collisions();
	r.collisionPoses = robot.collisionPoses();
	r.simTime = robot.simTime();
	r.replans = nav.replans();
	r.trajectory = robot.trajectory();
	r.estimatedTrajectory = robot.estimatedTrajectory();
	r.plans = nav.plans();
	r.sensedObstacles = nav.planner().extraObstacles();
	if (!stepMs.empty())
	{
		std::nth_element(
		    stepMs.begin(), stepMs.begin() + stepMs.size() / 2, stepMs.end());
		r.medianStepMs = stepMs[stepMs.size() / 2];
	}

	if (!logDir.empty())
	{
		nav.setNavLogDirectory("");  // closes the file
		std::string written;
		for (const auto& e : std::filesystem::directory_iterator(logDir))
			if (e.path().extension() == ".reactivenavlog")
				written = e.path().string();
		if (written.empty())
			throw IoError("MRPT wrote no navigation log in " + logDir);
		std::filesystem::rename(written, navlogPath);
		std::filesystem::remove_all(logDir);
		r.navlog = navlogPath;
	}
	r.wallSeconds =
	    std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0)
	        .count();
	return r;
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
// The runtime against fake seams, no simulator linked: a recording
// differential-drive base on a fake clock and a scripted tilting-laser
// sweep source in a small asymmetric room (FakeRobot.h, FakeSweeps.h). The
// known map is built by the runtime's own perception and mapping from fake
// sweeps at known poses; then StopAndScanLocalizer localizes the robot from
// an unknown pose and SemanticNavigator, driven by NavigationLoop over
// RobotNavInterface, takes it to a point with stop-and-scan rescans.
#include <gtest/gtest.h>
#include <mrpt/math/wrap2pi.h>
#include <semnav/localization/WallMap.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavCommand.h>
#include <semnav/nav/NavigationConfig.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/NavigationLoop.h>
#include <semnav/nav/RobotNavInterface.h>
#include <semnav/nav/SemanticNavigator.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/robot/LocalizedPose.h>
#include <semnav/robot/SweepObstacles.h>

#include <cmath>
#include <iostream>
#include <memory>

#include "../TestPaths.h"
#include "FakeRobot.h"
#include "FakeSweeps.h"
#include "ShippedOptions.h"

using namespace semnav;
using semnav::test::FakeBase;
using semnav::test::ScriptedSweepSource;
using Mode = StopAndScanLocalizer::Mode;
using Call = FakeBase::Call;

namespace
{
constexpr double kPeriod = 0.1;
constexpr double kWatchdog = 1.0;
constexpr double kRobotRadius = 0.25;

const NavigationConfig& config()
{
	static const NavigationConfig c = NavigationConfig::load(
	    test::kSourceDir + "/config/navigation.ini",
	    test::kSourceDir + "/config/planning.ini");
	return c;
}

const MappingLocalizer::TOptions& locOptions()
{
	return test::shippedLocalizationOptions();
}

const PerceptionPipeline::TOptions& perceptionOptions()
{
	return test::shippedPerceptionOptions();
}

const test::FakeRoom& room()
{
	static const test::FakeRoom r = test::asymmetricRoom();
	return r;
}

/** The fake seams of one robot standing at `start` in the room. */
struct FakeRobot
{
	FakeRobot(
	    const mrpt::math::TPose2D& start,
	    const ScriptedSweepSource::Script& script = {},
	    double headingDriftPerM = 0, const test::FakeRoom& world = room())
	    : base(start, kWatchdog, headingDriftPerM),
	      clock(base, kPeriod),
	      sweeps(base, clock, world, script),
	      pose(base),
	      truth(base)
	{
	}

	RobotInterfaces interfaces()
	{
		RobotInterfaces r;
		r.base = &base;
		r.sweeps = &sweeps;
		r.clock = &clock;
		r.pose = &pose;
		r.truth = &truth;
		return r;
	}

	FakeBase base;
	test::FakeClock clock;
	ScriptedSweepSource sweeps;
	LocalizedPose pose;
	test::FakeTruth truth;
};

/** The known map: one fake sweep at each of a few known poses, labelled by
 * the runtime's perception and inserted at that pose (as semnav-map does
 * with ground-truth poses). */
const SemanticMap& knownMap()
{
	static const std::unique_ptr<SemanticMap> m = []
	{
		auto map = std::make_unique<SemanticMap>(config().map);
		PerceptionPipeline perception(perceptionOptions());
		perception.setMinLoggingLevel(mrpt::system::LVL_ERROR);
		const std::vector<mrpt::math::TPose2D> poses{
		    {1.0, 1.2, 0.6},  {3.5, 2.6, 0.0},  {6.0, 2.6, -1.9},
		    {5.6, 1.0, 1.9},  {3.3, 4.0, M_PI}, {1.2, 2.4, -1.4},
		    {2.2, 4.3, -0.3}, {6.2, 4.4, -2.6}};
		for (const auto& p : poses)
		{
			FakeRobot robot(p);
			Sweep sweep;
			EXPECT_TRUE(robot.sweeps.next(sweep));
			LabeledSweep labeled;
			perception.process(sweep, labeled);
			map->insert(sweep, labeled, mrpt::poses::CPose2D(p));
		}
		return map;
	}();
	return *m;
}

double yawErr(double a, double b)
{
	return std::abs(mrpt::math::wrapToPi(a - b));
}

double distance(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b)
{
	return std::hypot(a.x - b.x, a.y - b.y);
}

/** Distance from p to the segment a-b. */
double toSegment(
    const mrpt::math::TPoint2D& p, const mrpt::math::TPoint2D& a,
    const mrpt::math::TPoint2D& b)
{
	const auto ab = b - a;
	const double t = std::clamp(
	    ((p - a).x * ab.x + (p - a).y * ab.y) / ab.sqrNorm(), 0.0, 1.0);
	return (p - (a + ab * t)).norm();
}

/** Share of the room wall from a to b (sampled every 5 cm) that the map's
 * wall segments lying along it (both ends within `tol`) cover. */
double wallCoverage(
    const WallMap& walls, const mrpt::math::TPoint2D& a,
    const mrpt::math::TPoint2D& b, double tol = 0.2)
{
	std::vector<WallSegment> along;
	for (const auto& s : walls.segments())
		if (toSegment(s.p0, a, b) < tol && toSegment(s.p1, a, b) < tol)
			along.push_back(s);
	const int n = std::max(1, static_cast<int>((b - a).norm() / 0.05));
	int covered = 0;
	for (int i = 0; i <= n; i++)
	{
		const auto p = a + (b - a) * (double(i) / n);
		for (const auto& s : along)
			if (toSegment(p, s.p0, s.p1) < tol)
			{
				covered++;
				break;
			}
	}
	return covered / double(n + 1);
}

/** What every test asks of the base's log: no command refused, none beyond
 * MRPT's configured speeds, no watchdog or emergency stop. */
void expectOrderlyCommands(const FakeBase& base)
{
	const auto& mrpt = *config().mrptSections;
	const double vMax =
	    mrpt.read_double("CAbstractPTGBasedReactive", "robotMax_V_mps", 0);
	const double wMax = mrpt::DEG2RAD(
	    mrpt.read_double("CAbstractPTGBasedReactive", "robotMax_W_degps", 0));
	ASSERT_GT(vMax, 0);
	ASSERT_GT(wMax, 0);
	int commands = 0;
	for (const auto& c : base.calls())
	{
		EXPECT_NE(c.kind, Call::Kind::WatchdogStop) << "at t = " << c.time;
		EXPECT_NE(c.kind, Call::Kind::EmergencyStop) << "at t = " << c.time;
		if (c.kind != Call::Kind::SetVelocity) continue;
		commands++;
		EXPECT_TRUE(c.accepted) << "at t = " << c.time;
		EXPECT_LE(std::abs(c.v), vMax + 1e-6) << "at t = " << c.time;
		EXPECT_LE(std::abs(c.w), wMax + 1e-6) << "at t = " << c.time;
	}
	EXPECT_GT(commands, 0);
}

/** Every sweep was taken with the base stopped and still, and begun when
 * the localizer asked for it. */
void expectStopAndScan(const ScriptedSweepSource& sweeps)
{
	for (std::size_t i = 0; i < sweeps.taken().size(); i++)
	{
		const auto& t = sweeps.taken()[i];
		EXPECT_TRUE(t.stoppedBefore) << "sweep " << i << " at t = " << t.start;
		EXPECT_TRUE(t.stillDuring) << "sweep " << i << " at t = " << t.start;
		EXPECT_TRUE(t.notBeforeMet) << "sweep " << i << " at t = " << t.start;
	}
}

StopAndScanLocalizer makeLocalizer()
{
	return StopAndScanLocalizer(
	    knownMap(), config().stopAndScan, locOptions(), perceptionOptions());
}

/** A run of navigate(). */
struct Navigation
{
	StopAndScanLocalizer::Report start;
	NavigationLoop::Result loop;
	SemanticNavigator::StopReason reason = SemanticNavigator::StopReason::None;
	std::string message;
	std::vector<SemanticNavigator::PlanRecord> plans;
	/** True pose after every control period, and the distance driven. */
	std::vector<mrpt::math::TPose2D> path;
	double driven = 0;
};

/** The runtime's navigation over the fake seams: a global start, then
 * SemanticNavigator (over RobotNavInterface with the localized pose and
 * the sweeps' obstacles) driven to `goal` by NavigationLoop, with
 * stop-and-scan rescans. */
Navigation navigate(FakeRobot& robot, const NavCommand& goal)
{
	Navigation n;
	SweepObstacles obstacles(robot.base, config().sweepObstacles);
	robot.sweeps.onSweep([&](const Sweep& s) { obstacles.update(s); });
	StopAndScanLocalizer localizer = makeLocalizer();
	const auto io = robot.interfaces();
	n.start = localizer.start(io, Mode::Global);
	EXPECT_GT(obstacles.size(), 0u);

	RobotNavInterface robotInterface(
	    robot.base, robot.pose, obstacles, robot.clock,
	    config().robotInterface);
	robotInterface.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	SemanticNavigator nav(
	    robotInterface, knownMap(), *config().mrptSections, config().cnn,
	    config().traversability, config().navigator);
	nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	nav.start(goal);
	NavigationLoop loop(nav, io, &localizer);
	n.path.push_back(robot.base.truePose());
	n.loop = loop.run(
	    robot.clock.now() + 240, [&](double, SemanticNavigator&)
	    { n.path.push_back(robot.base.truePose()); });
	robot.sweeps.onSweep({});
	n.reason = nav.stopReason();
	n.message = nav.stopMessage();
	n.plans = nav.plans();
	for (std::size_t i = 1; i < n.path.size(); i++)
		n.driven += distance(n.path[i], n.path[i - 1]);
	const auto& truth = robot.base.truePose();
	std::cerr << "navigation: " << SemanticNavigator::stopReasonName(n.reason)
	          << " after " << n.loop.steps << " steps, " << n.driven
	          << " m, t = " << robot.clock.now() << " s, "
	          << n.loop.rescans.size() << " rescans, " << n.plans.size() - 1
	          << " replans, final (" << truth.x << ", " << truth.y << ")\n";
	return n;
}

/** No pose of the path brings the robot's disc into contact with `world`
 * (between floor and robot height). */
void expectNoContact(
    const test::FakeRoom& world, const std::vector<mrpt::math::TPose2D>& path)
{
	for (const auto& p : path)
		EXPECT_FALSE(world.blocks(p.x, p.y, kRobotRadius, 0.02, 1.0))
		    << "(" << p.x << ", " << p.y << ")";
}
}  // namespace

TEST(FakeRobot, FakeBaseMovesAsCommandedAndEnforcesItsWatchdog)
{
	FakeBase base({1, 1, M_PI / 2}, kWatchdog);
	test::FakeClock clock(base, kPeriod);
	// Straight ahead (+y) for 0.5 s at 0.2 m/s, kept alive.
	ASSERT_TRUE(base.setVelocity(0.2, 0));
	clock.waitFor(0.5);
	base.keepAlive();
	clock.waitFor(0.5);
	EXPECT_NEAR(base.truePose().x, 1.0, 1e-9);
	EXPECT_NEAR(base.truePose().y, 1.2, 1e-9);
	EXPECT_NEAR(base.odometry().pose.x, 0.2, 1e-9);
	EXPECT_NEAR(base.odometry().distance, 0.2, 1e-9);
	EXPECT_NEAR(
	    mrpt::Clock::toDouble(mrpt::Clock::now()),
	    mrpt::Clock::toDouble(test::fakeTimestamp(1.0)), 1e-6);
	// A quarter turn on the spot.
	ASSERT_TRUE(base.setVelocity(0, M_PI / 2));
	clock.waitFor(1.0);
	EXPECT_NEAR(yawErr(base.truePose().phi, M_PI), 0, 1e-9);
	EXPECT_NEAR(base.truePose().y, 1.2, 1e-9);
	// No command for longer than the watchdog: the base stops by itself.
	ASSERT_TRUE(base.setVelocity(0.2, 0));
	clock.waitFor(3.0);
	EXPECT_FALSE(base.moving());
	// (It moved for the watchdog period, up to one step more.)
	const double moved = 1.0 - base.truePose().x;
	EXPECT_GE(moved, 0.2 * kWatchdog - 1e-9);
	EXPECT_LE(moved, 0.2 * (kWatchdog + kPeriod) + 1e-9);
	EXPECT_EQ(base.calls().back().kind, Call::Kind::WatchdogStop);
	// An emergency stop latches: commands are refused until reset.
	EXPECT_TRUE(base.emergencyStop());
	EXPECT_FALSE(base.setVelocity(0.1, 0));
	EXPECT_FALSE(base.calls().back().accepted);
	EXPECT_FALSE(base.moving());
	base.resetEmergencyStop();
	EXPECT_TRUE(base.setVelocity(0.1, 0));
}

TEST(FakeRobot, KnownMapHoldsTheWallsPerceptionFound)
{
	const SemanticMap& map = knownMap();
	EXPECT_EQ(map.sweepsInserted(), 8u);
	WallMap walls;
	walls.buildFromSemanticMap(map);
	std::cerr << walls.segments().size() << " wall segments in the map\n";
	// The four walls (7 m and 5 m) and the 1.8 m partition were labelled
	// wall by perception and are in the map where they stand.
	EXPECT_GT(wallCoverage(walls, {0, 0}, {0, 5}), 0.8);
	EXPECT_GT(wallCoverage(walls, {7, 0}, {7, 5}), 0.8);
	EXPECT_GT(wallCoverage(walls, {0, 0}, {7, 0}), 0.8);
	EXPECT_GT(wallCoverage(walls, {0, 5}, {7, 5}), 0.8);
	EXPECT_GT(wallCoverage(walls, {4.57, 0}, {4.57, 1.8}), 0.8);
	// Nothing runs across the open middle of the room.
	EXPECT_EQ(wallCoverage(walls, {1.0, 2.5}, {6.0, 2.5}, 0.5), 0.0);
}

TEST(FakeRobot, GlobalStartFromAnUnknownPoseConvergesNearTheTruth)
{
	const mrpt::math::TPose2D start(1.8, 2.6, 2.4);
	FakeRobot robot(start);
	// Still turning when the localizer starts: it must stop the base first.
	ASSERT_TRUE(robot.base.setVelocity(0, 0.3));
	StopAndScanLocalizer localizer = makeLocalizer();
	const auto io = robot.interfaces();
	const auto rep = localizer.start(io, Mode::Global);
	std::cerr << "global start: " << rep.sweeps << " sweeps, error "
	          << rep.errorXY << " m " << mrpt::RAD2DEG(rep.errorYaw) << " deg, "
	          << rep.ms << " ms\n";

	EXPECT_TRUE(rep.converged);
	EXPECT_FALSE(rep.ambiguous);
	EXPECT_LE(rep.sweeps, config().stopAndScan.maxSweeps);
	EXPECT_EQ(robot.sweeps.taken().size(), std::size_t(rep.sweeps));
	// Truth came only through RobotInterfaces::truth: the records hold the
	// fake base's true pose at each sweep.
	ASSERT_EQ(rep.records.size(), robot.sweeps.taken().size());
	for (std::size_t i = 0; i < rep.records.size(); i++)
		EXPECT_LT(
		    distance(rep.records[i].truePose, robot.sweeps.taken()[i].truth),
		    1e-9);
	// The robot turned on the spot by turn_deg between sweeps.
	const auto& truth = robot.base.truePose();
	EXPECT_NEAR(truth.x, start.x, 1e-6);
	EXPECT_NEAR(truth.y, start.y, 1e-6);
	for (std::size_t i = 1; i < robot.sweeps.taken().size(); i++)
		EXPECT_NEAR(
		    mrpt::math::wrapToPi(
		        robot.sweeps.taken()[i].truth.phi -
		        robot.sweeps.taken()[i - 1].truth.phi),
		    config().stopAndScan.turnAngle, mrpt::DEG2RAD(1.0));
	// Near the truth; the robot reports the estimate, though its odometry
	// frame is not the map's.
	EXPECT_LT(rep.errorXY, 0.15);
	EXPECT_LT(rep.errorYaw, mrpt::DEG2RAD(3));
	EXPECT_NEAR(rep.errorXY, distance(rep.estimate, truth), 1e-9);
	const auto reported = robot.pose.pose();
	EXPECT_LT(distance(reported, truth), 0.15);
	EXPECT_LT(yawErr(reported.phi, truth.phi), mrpt::DEG2RAD(3));
	EXPECT_GT(distance(robot.base.odometry().pose, truth), 1.0);

	expectStopAndScan(robot.sweeps);
	expectOrderlyCommands(robot.base);
	// The turn in progress was stopped before the first sweep.
	ASSERT_GE(robot.base.calls().size(), 2u);
	EXPECT_EQ(robot.base.calls()[1].kind, Call::Kind::Stop);
}

TEST(FakeRobot, NavigatesToAPointWithRescansOnTheWay)
{
	// The odometry drifts 3 deg per metre: the rescans keep the belief on
	// the map.
	const mrpt::math::TPose2D start(1.8, 2.6, 2.4);
	const double drift = mrpt::DEG2RAD(3.0);
	FakeRobot robot(start, {}, drift);
	const NavCommand goal = NavCommand::parse("go to 5.6 1.0");
	const Navigation n = navigate(robot, goal);
	ASSERT_TRUE(n.start.converged);
	const auto& truth = robot.base.truePose();

	EXPECT_EQ(n.reason, SemanticNavigator::StopReason::Reached) << n.message;
	// Reached in truth: the plan ends in the goal region (goal_reach_m
	// around the point) and the robot stands at its end within the goal
	// tolerance plus the localization error.
	ASSERT_FALSE(n.plans.empty());
	const auto& end = n.plans.back().waypoints.back();
	const double reach = config().traversability.goalReach;
	EXPECT_LT(std::hypot(end.x - goal.x, end.y - goal.y), reach + 0.05);
	EXPECT_LT(
	    std::hypot(truth.x - end.x, truth.y - end.y),
	    config().navigator.goalAllowedDistance + 0.1);
	// The partition stands on the straight line: the robot went round its
	// end (y = 1.8).
	bool roundTheEnd = false;
	for (std::size_t i = 1; i < n.path.size(); i++)
		if (n.path[i - 1].x < 4.575 && n.path[i].x >= 4.575)
			roundTheEnd = n.path[i].y > 1.8 + kRobotRadius;
	EXPECT_TRUE(roundTheEnd);
	// The map is right: the only replans are those after each rescan.
	for (std::size_t i = 1; i < n.plans.size(); i++)
		EXPECT_EQ(
		    n.plans[i].reason, SemanticNavigator::ReplanReason::MapChanged)
		    << SemanticNavigator::replanReasonName(n.plans[i].reason);
	// The arrival was confirmed by one more sweep at the goal (no replan).
	ASSERT_EQ(n.loop.arrivals.size(), 1u);
	EXPECT_TRUE(n.loop.arrivals.front().confirmed);
	const std::size_t atGoal = n.loop.arrivals.front().records.size();
	EXPECT_EQ(atGoal, 1u);
	EXPECT_EQ(n.plans.size(), n.loop.rescans.size() - atGoal + 1);
	// One rescan per rescan_distance_m driven (the last metre may not
	// have ended), each near the truth.
	const double every = config().stopAndScan.rescanDistance;
	ASSERT_GT(every, 0);
	const int rescans = static_cast<int>(n.loop.rescans.size());
	EXPECT_GE(rescans, static_cast<int>(n.driven / every) - 1);
	EXPECT_LE(rescans, static_cast<int>(n.driven / every) + 1);
	for (const auto& r : n.loop.rescans)
	{
		EXPECT_LT(r.errorXY, 0.2);
		EXPECT_LT(r.errorYaw, mrpt::DEG2RAD(4));
	}
	// Without the rescans the belief would have drifted with the odometry:
	// the start's estimate composed with the odometry since is off by the
	// drift x distance in heading; the reported pose is not.
	const mrpt::poses::CPose2D odoStart(n.start.records.back().odometry);
	const auto deadReckoned =
	    (mrpt::poses::CPose2D(n.start.estimate) +
	     (mrpt::poses::CPose2D(robot.base.odometry().pose) - odoStart))
	        .asTPose();
	EXPECT_GT(yawErr(deadReckoned.phi, truth.phi), 0.5 * drift * n.driven);
	EXPECT_LT(yawErr(robot.pose.pose().phi, truth.phi), mrpt::DEG2RAD(3));
	EXPECT_LT(distance(robot.pose.pose(), truth), 0.1);

	expectNoContact(room(), n.path);
	expectStopAndScan(robot.sweeps);
	expectOrderlyCommands(robot.base);
	EXPECT_GT(robot.sweeps.taken().size(), std::size_t(n.start.sweeps));
}

TEST(FakeRobot, SweepObstaclesSteerAroundABoxTheMapLacks)
{
	// A box on the way that was not there when the map was made: only the
	// sweeps' obstacles (SweepObstacles) tell the navigator about it.
	test::FakeRoom world = room();
	world.boxes.push_back({{3.05, 2.15, 0}, {3.55, 2.65, 0.8}});
	// The robot starts facing it: the start's first sweep sees it, the
	// later ones turn away (a stop's sweeps add up in SweepObstacles).
	const mrpt::math::TPose2D start(1.8, 2.6, -0.2);
	FakeRobot robot(start, {}, 0, world);
	const Navigation n = navigate(robot, NavCommand::parse("go to 5.6 1.0"));
	ASSERT_TRUE(n.start.converged);
	EXPECT_EQ(n.reason, SemanticNavigator::StopReason::Reached) << n.message;
	expectNoContact(world, n.path);
	// The planner was told: the box blocked the path ahead and it replanned
	// (the sensed obstacles are forgotten again at each rescan).
	int blocked = 0;
	for (const auto& p : n.plans)
		blocked += p.reason ==
		           SemanticNavigator::ReplanReason::PathBlockedBySensedObstacle;
	EXPECT_GT(blocked, 0);
	expectStopAndScan(robot.sweeps);
	expectOrderlyCommands(robot.base);
}

TEST(FakeRobot, LostSweepSourceFailsLocalizationNamingIt)
{
	{
		// The laser never answers: the start fails and says why.
		ScriptedSweepSource::Script script;
		script.deviceLostAfter = 0;
		FakeRobot robot({1.8, 2.6, 2.4}, script);
		StopAndScanLocalizer localizer = makeLocalizer();
		try
		{
			localizer.start(robot.interfaces(), Mode::Global);
			ADD_FAILURE() << "no LocalizationFailedError";
		}
		catch (const LocalizationFailedError& e)
		{
			const std::string what = e.what();
			EXPECT_NE(what.find("device lost"), std::string::npos) << what;
			EXPECT_NE(what.find("/dev/fake-lms200"), std::string::npos) << what;
		}
		EXPECT_EQ(robot.sweeps.end(), SweepSource::End::DeviceLost);
		EXPECT_TRUE(robot.sweeps.taken().empty());
	}
	{
		// Lost after a tracking start: the next rescan fails.
		const mrpt::math::TPose2D start(5.8, 2.8, -2.0);
		FakeRobot robot(start);
		StopAndScanLocalizer localizer = makeLocalizer();
		const auto io = robot.interfaces();
		const auto rep = localizer.start(io, Mode::Tracking, start);
		EXPECT_TRUE(rep.converged);
		EXPECT_LT(rep.errorXY, 0.15);
		robot.sweeps.loseDevice();
		try
		{
			localizer.rescan(io);
			ADD_FAILURE() << "no LocalizationFailedError";
		}
		catch (const LocalizationFailedError& e)
		{
			const std::string what = e.what();
			EXPECT_NE(what.find("device lost"), std::string::npos) << what;
		}
		EXPECT_EQ(robot.sweeps.end(), SweepSource::End::DeviceLost);
		EXPECT_EQ(robot.sweeps.taken().size(), std::size_t(rep.sweeps));
		expectStopAndScan(robot.sweeps);
	}
}

/* semnav: semantic navigation from tilting-laser sweeps */
// RobotSession (semnav-robot's loop) on the simulated robot: the same seams
// as on the robot (base, sweeps, clock, localized pose; obstacles from the
// sweeps), checked against the simulator's ground truth.
#include <gtest/gtest.h>
#include <semnav/common/Printable.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/runtime/CommandQueue.h>
#include <semnav/runtime/RobotSession.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulatedRobot.h>

#include <cmath>
#include <iostream>
#include <mutex>

#include "../nav/ShippedOptions.h"
#include "../navsim/NavTestUtils.h"

using namespace semnav;
using nlohmann::json;

namespace
{
/** A 9 x 5 m room. The map knows wastebasket A in the far corner; the
 * scene also holds wastebasket B and a box on the way, which the map
 * lacks. */
const char* kRoom = R"(
name: growroom
bounds: [0, 0, 9, 5]
ceiling_height: 2.7
objects:
  - {label: wall, box: {center: [4.5, 0.05, 1.35], size: [9, 0.1, 2.7]}}
  - {label: wall, box: {center: [4.5, 4.95, 1.35], size: [9, 0.1, 2.7]}}
  - {label: wall, box: {center: [0.05, 2.5, 1.35], size: [0.1, 4.8, 2.7]}}
  - {label: wall, box: {center: [8.95, 2.5, 1.35], size: [0.1, 4.8, 2.7]}}
  - {label: wastebasket, cylinder: {center: [8.4, 4.4, 0.2], radius: 0.15, height: 0.4}}
  - {label: wastebasket, cylinder: {center: [5.0, 0.45, 0.2], radius: 0.15, height: 0.4}}
  - {label: obstacle, box: {center: [3.2, 2.5, 0.375], size: [0.6, 0.8, 0.75]}}
trajectory:
  - [1.0, 2.5, 0]
odometry: {trans_noise: 0.02, rot_noise_deg_per_m: 2.0, rot_bias_deg_per_m: 1.0}
)";
const mrpt::math::TPoint2D kNewWastebasket{5.0, 0.45};
const mrpt::math::TPoint2D kBox{3.2, 2.5};

const Scene& room()
{
	static const Scene s = SceneLoader::parse(kRoom, "growroom");
	return s;
}

/** The room as the starting map knows it: without B and the box. */
std::unique_ptr<SemanticMap> startingMap()
{
	Scene known = room();
	known.objects.erase(known.objects.begin() + 5, known.objects.end());
	auto map =
	    std::make_unique<SemanticMap>(test::shippedNavigationConfig().map);
	SceneMapBuilder::build(known, *map);
	return map;
}

/** Every command the base was given, with the clock's time. */
class RecordingBase : public RobotBase
{
public:
	struct Command
	{
		double t, v, w;
	};
	RecordingBase(RobotBase& base, const ControlClock& clock)
	    : m_base(base), m_clock(clock)
	{
	}
	bool setVelocity(double v, double w) override
	{
		record(v, w);
		return m_base.setVelocity(v, w);
	}
	void keepAlive() override { m_base.keepAlive(); }
	bool stop() override
	{
		record(0, 0);
		return m_base.stop();
	}
	bool emergencyStop() override { return m_base.emergencyStop(); }
	void resetEmergencyStop() override { m_base.resetEmergencyStop(); }
	bool emergencyStopped() const override { return m_base.emergencyStopped(); }
	Odometry odometry() const override { return m_base.odometry(); }
	double watchdogPeriod() const override { return m_base.watchdogPeriod(); }
	std::vector<Command> commands;

private:
	void record(double v, double w)
	{
		commands.push_back({m_clock.now(), v, w});
	}
	RobotBase& m_base;
	const ControlClock& m_clock;
};

/** A session on the simulated robot in the room, tracking start. */
struct SessionRun
{
	std::unique_ptr<SemanticMap> map = startingMap();
	SimulatedRobot robot{
	    room(), test::shippedNavigationConfig().robot, {1.0, 2.5, 0}};
	RecordingBase base{robot.base(), robot};
	SweepObstacles obstacles{
	    base, test::shippedNavigationConfig().sweepObstacles};
	std::vector<json> events;
	std::unique_ptr<RobotSession> session;
	/** Called with each event (may push commands). */
	std::function<void(const json&)> onEvent;

	SessionRun()
	{
		robot.base().setMinLoggingLevel(mrpt::system::LVL_ERROR);
		robot.enableOdometryNoise(room().odometry);
		RobotInterfaces io = robot.interfaces();
		io.base = &base;
		RobotSession::TOptions o;
		o.localize = StopAndScanLocalizer::Mode::Tracking;
		o.startPose = {1.0, 2.5, 0};
		session = std::make_unique<RobotSession>(
		    *map, io, obstacles, test::shippedNavigationConfig(),
		    test::shippedLocalizationOptions(),
		    test::shippedPerceptionOptions(), cascades(), o,
		    [this](const json& e)
		    {
			    events.push_back(e);
			    if (e["event"] != "sweep" && e["event"] != "status")
				    std::cerr << e.dump() << "\n";
			    if (onEvent) onEvent(e);
		    });
	}
	static std::optional<CascadeDetector::TOptions> cascades()
	{
		return CascadeDetector::TOptions::fromIniFile(
		    test::sourceDir() + "/config/cascade.ini");
	}
	std::vector<json> all(const std::string& kind) const
	{
		std::vector<json> out;
		for (const auto& e : events)
			if (e["event"] == kind) out.push_back(e);
		return out;
	}
	double trueDistanceTo(const mrpt::math::TPoint2D& p) const
	{
		const auto& t = robot.base().pose();
		return std::hypot(t.x - p.x, t.y - p.y);
	}
};

std::atomic<bool> kNoStop{false};
}  // namespace

TEST(RobotSession, TheMapGrowsAndTheNewWastebasketIsTheNearest)
{
	SessionRun run;
	ASSERT_TRUE(run.session->localize());
	const std::size_t before = run.map->instances(Label::Wastebasket).size();
	ASSERT_EQ(before, 1u);
	run.session->handle("go to the nearest wastebasket", kNoStop);

	const auto arrived = run.all("arrived");
	ASSERT_EQ(arrived.size(), 1u) << "the command did not arrive";
	// B, which the starting map lacked, is now in the map and was reached.
	const auto bins = run.map->instances(Label::Wastebasket);
	EXPECT_EQ(bins.size(), 2u);
	const ObjectInstance& reached =
	    run.map->instance(arrived[0]["object"].get<int>());
	EXPECT_LT(
	    std::hypot(
	        reached.centroid.x - kNewWastebasket.x,
	        reached.centroid.y - kNewWastebasket.y),
	    0.5);
	// Within the arrival tolerance of its footprint (radius 0.15 m).
	EXPECT_LT(
	    run.trueDistanceTo(kNewWastebasket) - 0.15,
	    test::shippedNavigationConfig().arrivalTolerance(true));
	// The box is in the map (occupied cells at its centre), and the robot
	// drove around it.
	// The box's faces are in the map: labelled obstacle, their occupancy
	// raised from the starting map's free prior.
	const auto boxCells = [](const SemanticMap& m, double minOccupancy)
	{
		const auto& g = m.geometry();
		int n = 0;
		for (double x = kBox.x - 0.35; x <= kBox.x + 0.35; x += g.resolution)
			for (double y = kBox.y - 0.45; y <= kBox.y + 0.45;
			     y += g.resolution)
			{
				int cx, cy;
				if (g.worldToCell(x, y, cx, cy) &&
				    LabelSet(
				        static_cast<LabelSet::mask_t>(m.at("labels", cx, cy)))
				        .contains(Label::Obstacle) &&
				    m.occupancy(cx, cy) > minOccupancy)
					n++;
			}
		return n;
	};
	EXPECT_EQ(boxCells(*startingMap(), 0), 0);
	EXPECT_GE(boxCells(*run.map, 0.1), 5) << "the box is not in the map";
	EXPECT_EQ(run.robot.base().collisions(), 0);
	EXPECT_GE(run.session->sweepsInserted(), 2);
	EXPECT_FALSE(run.all("new_object").empty());
}

TEST(RobotSession, MalformedCommandsAreOneLineErrorsAndTheRunGoesOn)
{
	SessionRun run;
	ASSERT_TRUE(run.session->localize());
	const std::vector<std::string> bad = {
	    "fly to the moon",
	    "go to",
	    "go to the nearest unicorn",
	    "go to wastebasket 999",
	    "go to 100 100",
	    "go to 1.0",
	    "go to x y",
	    "go to the nearest wall",
	    "go to 0.02 2.5",
	    "save",
	    "go to \x01\xff\x1b[2J"};
	CommandQueue q;
	for (const auto& b : bad) q.push(b);
	q.push("go to 4.5 1.2");
	q.close();
	run.session->run(q, kNoStop);
	const auto errors = run.all("error");
	ASSERT_EQ(errors.size(), bad.size());
	for (std::size_t i = 0; i < errors.size(); i++)
	{
		EXPECT_EQ(errors[i]["command"], printable(bad[i]));
		const std::string why = errors[i]["error"];
		EXPECT_FALSE(why.empty());
		EXPECT_EQ(why.find('\n'), std::string::npos) << why;
		EXPECT_EQ(why, printable(why)) << "input echoed raw";
	}
	ASSERT_EQ(run.all("arrived").size(), 1u);
	EXPECT_LT(run.trueDistanceTo({4.5, 1.2}), 0.6);
}

TEST(RobotSession, ASilentLaserStopsTheBaseUntilLinesReturn)
{
	SessionRun run;
	// The laser's pulse: 37.5 lines/s, silent for 2 s from the first sweep
	// taken while driving.
	double silentFrom = -1;
	run.session->monitorLaser(
	    [&]
	    {
		    const double t = run.robot.now();
		    if (silentFrom >= 0 && t >= silentFrom && t < silentFrom + 2.0)
			    return static_cast<std::size_t>(silentFrom * 37.5);
		    return static_cast<std::size_t>(t * 37.5);
	    });
	int sweepsWhileDriving = 0;
	run.onEvent = [&](const json& e)
	{
		if (e["event"] == "sweep" && run.all("goal").size() == 1 &&
		    ++sweepsWhileDriving == 1)
			silentFrom = e["t"].get<double>() + 1.0;
	};
	ASSERT_TRUE(run.session->localize());
	run.session->handle("go to 7.5 2.5", kNoStop);
	const auto paused = run.all("paused");
	const auto resumed = run.all("resumed");
	ASSERT_EQ(paused.size(), 1u);
	ASSERT_EQ(resumed.size(), 1u);
	EXPECT_EQ(paused[0]["reason"], "laser silent");
	const double tPause = paused[0]["t"].get<double>();
	const double tResume = resumed[0]["t"].get<double>();
	EXPECT_LE(tPause - silentFrom, 0.5);
	EXPECT_GE(tResume - silentFrom, 2.0);
	// Stopped at the pause, and no motion commanded until lines returned.
	bool stopped = false;
	for (const auto& c : run.base.commands)
	{
		if (c.t < tPause - 1e-9 || c.t >= tResume - 1e-9) continue;
		if (c.v == 0 && c.w == 0)
			stopped = true;
		else
			ADD_FAILURE() << "moving at " << c.t << " while paused (" << tPause
			              << " .. " << tResume << "): " << c.v << " " << c.w;
	}
	EXPECT_TRUE(stopped);
	EXPECT_EQ(run.all("arrived").size(), 1u);
}

TEST(RobotSession, StopAndANewGoalWhileDriving)
{
	SessionRun run;
	CommandQueue q;
	int sweeps = 0;
	run.onEvent = [&](const json& e)
	{
		if (e["event"] == "sweep" && run.all("goal").size() == 1 &&
		    ++sweeps == 1)
		{
			q.push("status");
			q.push("go to 2.0 4.0");
		}
		if (e["event"] == "goal" && run.all("goal").size() == 2)
		{
			q.push("stop");
			q.close();
		}
	};
	ASSERT_TRUE(run.session->localize());
	q.push("go to 7.5 2.5");
	run.session->run(q, kNoStop);
	const auto failed = run.all("failed");
	ASSERT_EQ(failed.size(), 2u);
	EXPECT_NE(
	    failed[0]["reason"].get<std::string>().find("replaced"),
	    std::string::npos);
	EXPECT_NE(
	    failed[1]["reason"].get<std::string>().find("operator"),
	    std::string::npos);
	EXPECT_FALSE(run.all("status").empty());
	EXPECT_TRUE(run.all("arrived").empty());
}

TEST(RobotSession, FromAnEmptyMapTheFirstSweepStartsTheMap)
{
	const Scene scene = test::sourceScene("datasets/nav-trials/two_rooms.yaml");
	// The shipped planning config blocks never-observed cells.
	const NavigationConfig& config = test::shippedNavigationConfig();
	ASSERT_GE(config.traversability.uUnobserved, config.traversability.L);
	SemanticMap map(config.map);
	SimulatedRobot robot(
	    scene, test::shippedNavigationConfig().robot, {1.0, 1.0, 0});
	robot.base().setMinLoggingLevel(mrpt::system::LVL_ERROR);
	robot.enableOdometryNoise(scene.odometry);
	SweepObstacles obstacles(robot.base(), config.sweepObstacles);
	std::vector<json> events;
	RobotSession session(
	    map, robot.interfaces(), obstacles, config,
	    test::shippedLocalizationOptions(), test::shippedPerceptionOptions(),
	    SessionRun::cascades(), RobotSession::TOptions(),
	    [&](const json& e) { events.push_back(e); });
	// With no map the session lets the planner cross them, at a cost.
	EXPECT_TRUE(session.mapping());
	EXPECT_LT(
	    session.config().traversability.uUnobserved, config.traversability.L);
	ASSERT_TRUE(session.localize());
	ASSERT_FALSE(events.empty());
	EXPECT_EQ(events.front()["event"], "new_object");
	// The map frame is the odometry frame (which the simulator starts at
	// the true pose): a goal across room A, behind the table.
	EXPECT_TRUE(session.handle("go to 3.5 3.8", kNoStop));
	int arrived = 0;
	for (const auto& e : events) arrived += e["event"] == "arrived";
	EXPECT_EQ(arrived, 1);
	const auto& t = robot.base().pose();
	EXPECT_LT(std::hypot(t.x - 3.5, t.y - 3.8), 0.6);
	EXPECT_EQ(robot.base().collisions(), 0);
	EXPECT_GE(session.sweepsInserted(), 3);
	// Room A's washbasin and wastebasket are in the map it built.
	EXPECT_GE(map.instances(Label::Washbasin).size(), 1u);
	EXPECT_GE(map.instances(Label::Wastebasket).size(), 1u);
}

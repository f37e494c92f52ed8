/* semnav: semantic navigation from tilting-laser sweeps */
// RobotSession with no map at all, on the simulated robot in two_rooms: "go
// to x y" through both rooms, the plan crossing space never seen; the map
// it builds against semnav-map's map of the same recorded sweeps, both
// scored against the scene's truth.
#include <gtest/gtest.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/mapping/MapBuilder.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/runtime/RobotSession.h>
#include <semnav/scan/RawlogWriter.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulatedRobot.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "../nav/ShippedOptions.h"
#include "../navsim/NavTestUtils.h"
#include "MapTruthScore.h"

using namespace semnav;
using nlohmann::json;
namespace fs = std::filesystem;

namespace
{
std::optional<CascadeDetector::TOptions> cascades()
{
	return CascadeDetector::TOptions::fromIniFile(
	    test::sourceDir() + "/config/cascade.ini");
}

/** A session on an empty map in two_rooms, the robot at (1, 1, 0) in room
 * A; with `rawlog`, every sweep is recorded into it. */
struct EmptyStart
{
	Scene scene = test::sourceScene("datasets/nav-trials/two_rooms.yaml");
	SemanticMap map{test::shippedNavigationConfig().map};
	SimulatedRobot robot{
	    scene, test::shippedNavigationConfig().robot, {1.0, 1.0, 0}};
	SweepObstacles obstacles{
	    robot.base(), test::shippedNavigationConfig().sweepObstacles};
	std::vector<json> events;
	std::unique_ptr<RobotSession> session;

	explicit EmptyStart(RawlogWriter* rawlog = nullptr)
	{
		robot.base().setMinLoggingLevel(mrpt::system::LVL_ERROR);
		robot.enableOdometryNoise(scene.odometry);
		robot.sweeps().record(rawlog);
		session = std::make_unique<RobotSession>(
		    map, robot.interfaces(), obstacles, test::shippedNavigationConfig(),
		    test::shippedLocalizationOptions(),
		    test::shippedPerceptionOptions(), cascades(),
		    RobotSession::TOptions(),
		    [this](const json& e)
		    {
			    events.push_back(e);
			    if (e["event"] != "sweep") std::cerr << e.dump() << "\n";
		    });
	}
	std::vector<json> all(const std::string& kind) const
	{
		std::vector<json> out;
		for (const auto& e : events)
			if (e["event"] == kind) out.push_back(e);
		return out;
	}
	double trueDistanceTo(double x, double y) const
	{
		const auto& t = robot.base().pose();
		return std::hypot(t.x - x, t.y - y);
	}
};

std::atomic<bool> kNoStopRequest{false};

/** semnav-map --poses pf of `rawlog` with the shipped configs (the
 * library code semnav-map runs). */
std::unique_ptr<MapBuilder> semnavMap(const std::string& rawlog)
{
	MapBuilder::Settings s;
	s.map = test::shippedNavigationConfig().map;
	s.assembler.loadFromConfigFile(
	    *openIniFile(
	        test::sourceDir() + "/config/map.ini",
	        {"SemanticMap", "TravelCost", "SweepAssembler"}),
	    "SweepAssembler");
	s.perception = test::shippedPerceptionOptions();
	s.cascades = cascades();
	s.localization = test::shippedLocalizationOptions();
	s.poses = MapBuilder::PoseSource::Localization;
	s.rawlog = rawlog;
	auto b = std::make_unique<MapBuilder>(s);
	b->run();
	return b;
}

void print(const char* who, const test::MapTruthScore& s)
{
	std::cout << "[ MEASURED ] " << who << ":";
	for (const auto& [label, o] : s.objects)
		std::cout << " " << labelName(label) << " " << o.found << "/" << o.truth
		          << " found (" << o.instances << " instances, " << o.spurious
		          << " spurious);";
	std::cout << " true obstacle cells mapped " << s.trueOccupiedMapped << "/"
	          << s.trueOccupied << " = " << s.obstacleRecall()
	          << ", occupied cells on true obstacles " << s.occupiedRight << "/"
	          << s.occupied << " = " << s.occupiedPrecision()
	          << ", free cells truly free " << s.freeRight << "/" << s.free
	          << " = " << s.freePrecision() << ", observed " << s.knownArea
	          << " m^2\n";
}
}  // namespace

TEST(RobotEmptyStart, GoToThroughTwoRoomsMapsLikeSemnavMap)
{
	const fs::path dir = fs::temp_directory_path() /
	                     ("semnav_empty_start_" + std::to_string(::getpid()));
	fs::create_directories(dir);
	const std::string rawlogPath = (dir / "robot.rawlog").string();
	RawlogWriter rawlog(rawlogPath);
	EmptyStart run(&rawlog);
	ASSERT_TRUE(run.session->localize());
	// Across room A behind its table, through the opening to room B's
	// washbasin corner, then room B's south-east corner by its door: the
	// first plans cross space no sweep has seen.
	const std::vector<std::pair<double, double>> goals = {
	    {3.5, 3.8}, {8.0, 3.6}, {9.3, 1.0}};
	for (const auto& [x, y] : goals)
	{
		const std::size_t before = run.all("arrived").size();
		EXPECT_TRUE(run.session->handle(
		    "go to " + std::to_string(x) + " " + std::to_string(y),
		    kNoStopRequest));
		EXPECT_EQ(run.all("arrived").size(), before + 1)
		    << "go to " << x << " " << y;
		EXPECT_LT(run.trueDistanceTo(x, y), 0.6) << "go to " << x << " " << y;
	}
	EXPECT_EQ(run.robot.base().collisions(), 0);
	EXPECT_TRUE(run.all("failed").empty());
	rawlog.commit();

	// semnav-map's map of the same sweeps.
	const auto offline = semnavMap(rawlogPath);
	ASSERT_TRUE(offline->readError().empty()) << offline->readError();
	EXPECT_EQ(offline->map().sweepsInserted(), run.map.sweepsInserted());

	SemanticMap truth(test::shippedNavigationConfig().map);
	SceneMapBuilder::build(run.scene, truth);
	const std::vector<Label> labels = {
	    Label::Washbasin, Label::Wastebasket, Label::Door};
	const auto robot = test::scoreAgainstTruth(run.map, truth, labels);
	const auto mapped = test::scoreAgainstTruth(offline->map(), truth, labels);
	print("semnav-robot, empty start", robot);
	print("semnav-map --poses pf, its rawlog", mapped);
	std::cout << "[ MEASURED ] sweeps " << run.map.sweepsInserted()
	          << ", sim time " << run.robot.now() << " s\n";

	// Both rooms were seen: both washbasins found, nothing spurious.
	EXPECT_EQ(robot.objects.at(Label::Washbasin).found, 2);
	// The robot's map scores like semnav-map's: the same sweeps through
	// the same localization and insertion code, so what may differ is the
	// sweep assembly from the recorded lines and the filter's random draws
	// (a few cm of pose): the same objects found, no more spurious ones,
	// occupancy precision and the share of true obstacles mapped within 2
	// points, the observed area within 5 %.
	for (const Label l : labels)
	{
		EXPECT_GE(robot.objects.at(l).found, mapped.objects.at(l).found)
		    << labelName(l);
		EXPECT_LE(robot.objects.at(l).spurious, mapped.objects.at(l).spurious)
		    << labelName(l);
	}
	EXPECT_GE(robot.occupiedPrecision(), mapped.occupiedPrecision() - 0.02);
	EXPECT_GE(robot.obstacleRecall(), mapped.obstacleRecall() - 0.02);
	EXPECT_GE(robot.freePrecision(), mapped.freePrecision() - 0.02);
	EXPECT_NEAR(robot.knownArea, mapped.knownArea, 0.05 * mapped.knownArea);
	EXPECT_GE(robot.occupiedPrecision(), 0.9);
	EXPECT_GE(robot.freePrecision(), 0.97);
	fs::remove_all(dir);
}

TEST(RobotEmptyStart, AGoalThatTurnsOutInAnObstacleEndsGoalBlocked)
{
	EmptyStart run;
	ASSERT_TRUE(run.session->localize());
	// Room B's table, unseen from the start: the plan heads there until
	// a sweep shows the table top covering the goal.
	EXPECT_TRUE(run.session->handle("go to 7.6 2.0", kNoStopRequest));
	const auto failed = run.all("failed");
	ASSERT_EQ(failed.size(), 1u);
	EXPECT_EQ(failed[0]["stop_reason"], "goal_blocked");
	EXPECT_EQ(run.robot.base().collisions(), 0);
}

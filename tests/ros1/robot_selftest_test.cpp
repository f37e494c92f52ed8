/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-robot hardware in the loop (scripts/robot-selftest): the emulated
// LMS200 + PTU on pseudo-terminals riding the emulated ROS 1 base in the
// office, a map from an earlier semnav-map run, semnav-robot with
// config/robot-emulated.ini through the real drivers and real ROS transport.
// Each run starts its own rosmaster on a free port.
#include <gtest/gtest.h>
#include <mrpt/core/format.h>
#include <semnav/common/LabelSet.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/SemanticPlanner.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "../dataset/AppRunner.h"
#include "../navsim/NavTestUtils.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace semnav;

namespace
{
const fs::path kTmp = fs::temp_directory_path() /
                      ("semnav_robot_hil_" + std::to_string(::getpid()));
const mrpt::math::TPose2D kStart{2.2, 1.5, 0};
/** The box added to the emulated office: centre, size (m). */
const mrpt::math::TPoint2D kBox{4.5, 1.4};
const mrpt::math::TPoint3D kBoxSize{0.4, 0.4, 0.6};

/** Cells of the box's footprint (and a cell around it) labelled obstacle
 * with occupancy above `minOccupancy`. */
int obstacleCellsInBox(const SemanticMap& m, double minOccupancy)
{
	const auto& g = m.geometry();
	int n = 0;
	const double hx = kBoxSize.x / 2 + g.resolution,
	             hy = kBoxSize.y / 2 + g.resolution;
	for (double x = kBox.x - hx; x <= kBox.x + hx; x += g.resolution)
		for (double y = kBox.y - hy; y <= kBox.y + hy; y += g.resolution)
		{
			int cx, cy;
			if (g.worldToCell(x, y, cx, cy) &&
			    LabelSet(static_cast<LabelSet::mask_t>(m.at("labels", cx, cy)))
			        .contains(Label::Obstacle) &&
			    m.occupancy(cx, cy) > minOccupancy)
				n++;
		}
	return n;
}

/** The office map of the demo: semnav-sim, then semnav-map --poses pf. */
const fs::path& officeMap()
{
	static const fs::path map = []
	{
		const fs::path sim = kTmp / "sim", out = kTmp / "map";
		const auto s = test::runApp(
		    "semnav-sim", "--scene " + test::sourceDir() +
		                      "/datasets/office/office.yaml --out " +
		                      sim.string() + " --seed 1");
		EXPECT_EQ(s.code, 0) << s.err;
		fs::path rawlog;
		for (const auto& e : fs::directory_iterator(sim))
			if (e.path().extension() == ".rawlog") rawlog = e.path();
		const auto m = test::runApp(
		    "semnav-map", "--rawlog " + rawlog.string() + " --out " +
		                      out.string() + " --poses pf --gt-dir " +
		                      sim.string());
		EXPECT_EQ(m.code, 0) << m.err;
		return out;
	}();
	return map;
}

/** scripts/robot-selftest with `args` (shell words), its JSON report. */
json selftest(const std::string& name, const std::string& args)
{
	const fs::path out = kTmp / name;
	const std::string cmd = test::sourceDir() +
	                        "/scripts/robot-selftest --build " +
	                        std::string(SEMNAV_BINARY_DIR) + " --out " +
	                        out.string() + " --map " + officeMap().string() +
	                        " --json " + args + " 2>" + (out.string() + ".err");
	fs::create_directories(out);
	FILE* p = ::popen(cmd.c_str(), "r");
	std::string text;
	char buf[4096];
	std::size_t n;
	while ((n = std::fread(buf, 1, sizeof(buf), p)) > 0) text.append(buf, n);
	::pclose(p);
	std::cerr << name << ": " << text << "\n";
	try
	{
		return json::parse(text);
	}
	catch (const std::exception&)
	{
		ADD_FAILURE() << "no report from robot-selftest: " << text;
		return json::object();
	}
}

class RobotSelftest : public ::testing::Test
{
protected:
	static void TearDownTestSuite() { fs::remove_all(kTmp); }
};
}  // namespace

TEST_F(RobotSelftest, OfficeUnlocalizedMalformedCommandsAndTheLaserUnplugged)
{
	std::string bad;
	for (const char* c :
	     {"fly to the moon", "go to", "go to the nearest unicorn",
	      "go to wastebasket 999", "go to 100 100", "go to 1.0", "go to x y",
	      "go to the nearest wall", "go to 0 0", "save"})
		bad += std::string(" --bad-command '") + c + "'";
	// A box the starting map lacks, 2.3 m ahead of the start: in view of
	// the first sweep, on the way east (when the start sees no other
	// wastebasket first).
	const json r = selftest(
	    "office", bad + " --emulator-arg=--disconnect-at=22 --add-box " +
	                  mrpt::format(
	                      "%g,%g,%g,%g,%g", kBox.x, kBox.y, kBoxSize.x,
	                      kBoxSize.y, kBoxSize.z));
	ASSERT_TRUE(r.value("success", false)) << r.dump();
	EXPECT_EQ(r["bad_commands"].size(), 10u);
	EXPECT_EQ(r["collisions"], 0);
	EXPECT_LT(r["localization_error_m"].get<double>(), 0.3);
	// The laser unplugged for 2 s: the base stood still within 0.5 s. When
	// that happened while driving (not during a stop-and-scan, where the
	// robot stands anyway) the robot paused and resumed.
	ASSERT_TRUE(r.contains("stop_after_laser_silent_s")) << r.dump();
	EXPECT_LE(r["stop_after_laser_silent_s"].get<double>(), 0.5);
	const auto& paused = r["paused"];
	ASSERT_EQ(paused.size() % 2, 0u) << "a pause without its resume";
	for (std::size_t i = 0; i < paused.size(); i += 2)
	{
		EXPECT_EQ(paused[i]["event"], "paused");
		EXPECT_EQ(paused[i]["reason"], "laser silent");
		EXPECT_EQ(paused[i + 1]["event"], "resumed");
	}
	// The reached wastebasket is the path-nearest from the start in the
	// map the robot saved (which holds what it added on the way).
	SemanticMap saved(test::shippedNavigationConfig().map);
	MapIO::load((kTmp / "office" / "map").string(), saved);
	const auto& c = test::shippedNavigationConfig();
	const auto plan =
	    SemanticPlanner(saved, c.cnn, c.traversability)
	        .toLabel(
	            kStart.x, kStart.y, Label::Wastebasket, c.navigationProfile());
	EXPECT_EQ(r["reached_object"].get<int>(), plan.goalObjectId);
	EXPECT_LT(
	    r["true_distance_to_nearest_m"].get<double>() - 0.15,
	    c.arrivalTolerance(true));
	// The box: never touched, and in the saved map (obstacle-labelled cells
	// with some occupancy where the starting map has none).
	ASSERT_EQ(r["boxes"].size(), 1u) << r.dump();
	EXPECT_GT(r["boxes"][0]["true_clearance_m"].get<double>(), 0.05);
	SemanticMap start(c.map);
	MapIO::load(officeMap().string(), start);
	EXPECT_EQ(obstacleCellsInBox(start, 0), 0);
	EXPECT_GE(obstacleCellsInBox(saved, 0.1), 3) << "the box is not in the map";
}

TEST_F(RobotSelftest, KilledWhileDrivingTheBaseStopsAndTheRecordingIsReadable)
{
	const json r = selftest("kill", "--kill-robot-after 3");
	ASSERT_TRUE(r.contains("stop_after_kill_s")) << r.dump();
	EXPECT_LE(r["stop_after_kill_s"].get<double>(), 0.5);
	EXPECT_TRUE(r.value("rawlog_readable", false)) << r.dump();
	EXPECT_TRUE(r.value("success", false));
}

TEST_F(RobotSelftest, OdometryStoppedStopsTheBaseAndTheCommandFails)
{
	const json r = selftest(
	    "odom",
	    "--emulator-arg=--odom-silent-at=25 "
	    "--emulator-arg=--odom-silent-for=8");
	ASSERT_EQ(r["results"].size(), 1u) << r.dump();
	EXPECT_EQ(r["results"][0]["event"], "failed");
	EXPECT_NE(
	    r["results"][0].value("reason", "").find("odometry"), std::string::npos)
	    << r.dump();
	EXPECT_EQ(r["collisions"], 0);
}

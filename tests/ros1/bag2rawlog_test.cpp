/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-bag2rawlog on bags written from a simulated run (semnav-sim's
// rawlog of a small room as LaserScan + JointState or tf + Odometry or tf):
// the converted rawlog has the simulator's sweeps, and semnav-map makes the
// same map of both (objects, occupancy within one cell); a bag without the
// topics, joint or frames is one line naming them, exit 1, no rawlog.
#include <gtest/gtest.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "../dataset/AppRunner.h"
#include "SimBag.h"

using namespace semnav;
using namespace semnav::test;
namespace fs = std::filesystem;

namespace
{
const fs::path kTmp = fs::temp_directory_path() /
                      ("semnav_bag2rawlog_" + std::to_string(::getpid()));

/** A 6 m x 4 m room with a washbasin, a wastebasket and a box; 3 stops,
 * tilt step 1 deg (76 lines a sweep). */
const char* kScene = R"(name: bag_room
bounds: [0, 0, 6, 4]
ceiling_height: 2.5
objects:
  - {label: wall, box: {center: [3.0, 0.05, 1.25], size: [6.0, 0.1, 2.5]}}
  - {label: wall, box: {center: [3.0, 3.95, 1.25], size: [6.0, 0.1, 2.5]}}
  - {label: wall, box: {center: [0.05, 2.0, 1.25], size: [0.1, 3.8, 2.5]}}
  - {label: wall, box: {center: [5.95, 2.0, 1.25], size: [0.1, 3.8, 2.5]}}
  - label: washbasin
    parts:
      - {box: {center: [5.7, 2.0, 0.775], size: [0.4, 0.5, 0.15]}}
      - {cylinder: {center: [5.78, 2.0, 0.35], radius: 0.08, height: 0.7}}
  - {label: wastebasket, cylinder: {center: [3.0, 3.5, 0.2], radius: 0.15, height: 0.4}}
  - {label: obstacle, box: {center: [2.0, 0.6, 0.4], size: [1.0, 0.6, 0.8]}}
sensor:
  theta: [-15, 60, 1.0]
odometry: {trans_noise: 0.02, rot_noise_deg_per_m: 2.0, rot_bias_deg_per_m: 0.0}
trajectory:
  - [1.5, 2.0, 0]
  - [3.5, 2.0, 0]
  - [4.0, 2.5, 60]
)";

class Bag2Rawlog : public ::testing::Test
{
protected:
	static void SetUpTestSuite()
	{
		fs::create_directories(kTmp);
		std::ofstream(kTmp / "bag_room.yaml") << kScene;
		const AppRun r = runApp(
		    "semnav-sim", "--scene " + (kTmp / "bag_room.yaml").string() +
		                      " --out " + kTmp.string() + " --seed 1");
		ASSERT_EQ(r.code, 0) << r.err;
		simRawlog = (kTmp / "bag_room.rawlog").string();
		lines = readSimLines(simRawlog);
	}
	static void TearDownTestSuite() { fs::remove_all(kTmp); }

	static AppRun convert(const fs::path& bag, const std::string& args = "")
	{
		return runApp(
		    "semnav-bag2rawlog", bag.string() + " --out " +
		                             (kTmp / "bag.rawlog").string() +
		                             " --json " + args);
	}

	static std::string simRawlog;
	static std::vector<SimLine> lines;
};
std::string Bag2Rawlog::simRawlog;
std::vector<SimLine> Bag2Rawlog::lines;

/** The two rawlogs give the same sweeps: tilts, ranges, validity, odometry,
 * timestamps. */
void expectSameSweeps(const std::string& expected, const std::string& actual)
{
	const auto a = readRawlogSweeps(expected), b = readRawlogSweeps(actual);
	ASSERT_EQ(a.size(), b.size());
	ASSERT_GE(a.size(), 3u);
	for (std::size_t k = 0; k < a.size(); k++)
	{
		SCOPED_TRACE("sweep " + std::to_string(k));
		ASSERT_EQ(a[k].rows(), b[k].rows());
		ASSERT_EQ(a[k].cols(), b[k].cols());
		EXPECT_EQ(a[k].ranges(), b[k].ranges());
		EXPECT_EQ(a[k].validity(), b[k].validity());
		EXPECT_GT(b[k].validCount(), a[k].ranges().size() / 3);
		// Tilts interpolated in time: stamps through double seconds (MRPT's
		// ros1bridge, ~0.2 us) times a tilt rate of ~1 rad/s.
		for (std::size_t r = 0; r < a[k].rows(); r++)
		{
			ASSERT_NEAR(a[k].theta(r), b[k].theta(r), 1e-6) << "row " << r;
			// The rest of the pose exact: perception amplifies 1e-7 rad (a
			// door moved 0.6 m on the office with the scan's centre bearing
			// taken from the float increment).
			const auto &pa = a[k].sensorPose(r), &pb = b[k].sensorPose(r);
			ASSERT_NEAR(pa.yaw(), pb.yaw(), 1e-10) << "row " << r;
			ASSERT_NEAR(pa.roll(), pb.roll(), 1e-10) << "row " << r;
			ASSERT_NEAR((pa.translation() - pb.translation()).norm(), 0, 1e-10);
		}
		EXPECT_EQ(a[k].phis(), b[k].phis());
		ASSERT_TRUE(b[k].hasOdometry());
		EXPECT_NEAR(a[k].odometry().x(), b[k].odometry().x(), 1e-9);
		EXPECT_NEAR(a[k].odometry().y(), b[k].odometry().y(), 1e-9);
		EXPECT_NEAR(a[k].odometry().phi(), b[k].odometry().phi(), 1e-9);
		EXPECT_LT(
		    std::abs(mrpt::system::timeDifference(
		        a[k].timestamp(), b[k].timestamp())),
		    1e-6);
		EXPECT_TRUE(b[k].quality().complete);
	}
}

/** The occupied cells (value 0) of occupancy.png as world cell centres. */
std::vector<mrpt::math::TPoint2D> occupiedCells(
    const fs::path& map, double& res)
{
	const cv::Mat img =
	    cv::imread((map / "occupancy.png").string(), cv::IMREAD_GRAYSCALE);
	std::ifstream in(map / "map.yaml");
	double ox = 0, oy = 0;
	for (std::string line; std::getline(in, line);)
	{
		if (line.rfind("resolution:", 0) == 0) res = std::stod(line.substr(11));
		if (line.rfind("origin:", 0) == 0)
			std::sscanf(line.c_str(), "origin: [%lf, %lf", &ox, &oy);
	}
	std::vector<mrpt::math::TPoint2D> cells;
	for (int r = 0; r < img.rows; r++)
		for (int c = 0; c < img.cols; c++)
			if (img.at<uint8_t>(r, c) == 0)
				cells.emplace_back(
				    ox + (c + 0.5) * res, oy + (img.rows - 1 - r + 0.5) * res);
	return cells;
}

/** Occupied cells of `a` with no occupied cell of `b` within one cell. */
std::size_t unmatchedCells(
    const std::vector<mrpt::math::TPoint2D>& a,
    const std::vector<mrpt::math::TPoint2D>& b, double res)
{
	std::size_t unmatched = 0;
	for (const auto& p : a)
	{
		bool near = false;
		for (const auto& q : b)
			if (std::abs(p.x - q.x) < 1.5 * res &&
			    std::abs(p.y - q.y) < 1.5 * res)
			{
				near = true;
				break;
			}
		unmatched += near ? 0 : 1;
	}
	return unmatched;
}

}  // namespace

TEST_F(Bag2Rawlog, JointStatesAndOdometryGiveTheSimulatorsSweeps)
{
	ASSERT_GT(lines.size(), 200u);
	writeJointStatesBag(lines, (kTmp / "js.bag").string());
	const AppRun r = convert(kTmp / "js.bag");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	EXPECT_EQ(j.at("lines"), lines.size());
	EXPECT_EQ(j.at("scans"), lines.size());
	EXPECT_EQ(j.at("odometry"), 3u);  // one per stop: it only changes there
	expectSameSweeps(simRawlog, (kTmp / "bag.rawlog").string());

	// The tilt is the joint's: an offset moves every line by it.
	ASSERT_EQ(convert(kTmp / "js.bag", "--tilt-offset-deg 2").code, 0);
	const auto a = readRawlogSweeps(simRawlog);
	const auto b = readRawlogSweeps((kTmp / "bag.rawlog").string());
	ASSERT_EQ(a.size(), b.size());
	for (std::size_t r = 0; r < a[0].rows(); r++)
		EXPECT_NEAR(b[0].theta(r) - a[0].theta(r), mrpt::DEG2RAD(2.0), 1e-6);
}

TEST_F(Bag2Rawlog, TfTiltAndTfOdometryGiveTheSimulatorsSweeps)
{
	writeTfBag(lines, (kTmp / "tf.bag").string());
	const AppRun r = convert(kTmp / "tf.bag", "--tilt-from tf --odom-from tf");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	EXPECT_EQ(j.at("lines"), lines.size());
	EXPECT_EQ(j.at("odometry"), 3u);
	expectSameSweeps(simRawlog, (kTmp / "bag.rawlog").string());
}

TEST_F(Bag2Rawlog, ClockwiseScansInACompressedBagGiveTheSimulatorsSweeps)
{
	JointStatesBag how;
	how.clockwise = true;
	how.compression = rosbag::compression::LZ4;
	writeJointStatesBag(lines, (kTmp / "cw.bag").string(), how);
	const AppRun r = convert(kTmp / "cw.bag");
	ASSERT_EQ(r.code, 0) << r.err;
	expectSameSweeps(simRawlog, (kTmp / "bag.rawlog").string());
}

TEST_F(Bag2Rawlog, SemnavMapOfTheBagEqualsTheMapOfTheSimulatorsRawlog)
{
	writeJointStatesBag(lines, (kTmp / "js.bag").string());
	ASSERT_EQ(convert(kTmp / "js.bag").code, 0);
	const AppRun a = runApp(
	    "semnav-map", "--rawlog " + simRawlog + " --out " +
	                      (kTmp / "map_sim").string() + " --json");
	const AppRun b = runApp(
	    "semnav-map", "--rawlog " + (kTmp / "bag.rawlog").string() + " --out " +
	                      (kTmp / "map_bag").string() + " --json");
	ASSERT_EQ(a.code, 0) << a.err;
	ASSERT_EQ(b.code, 0) << b.err;
	const auto ja = nlohmann::json::parse(a.out),
	           jb = nlohmann::json::parse(b.out);
	EXPECT_EQ(ja.at("sweeps"), 3);
	EXPECT_EQ(jb.at("sweeps"), ja.at("sweeps"));
	const auto& oa = ja.at("objects");
	const auto& ob = jb.at("objects");
	ASSERT_GE(oa.size(), 2u);  // the washbasin and the wastebasket
	ASSERT_EQ(oa.size(), ob.size());
	for (std::size_t i = 0; i < oa.size(); i++)
	{
		EXPECT_EQ(oa[i].at("label"), ob[i].at("label"));
		EXPECT_NEAR(
		    oa[i].at("x").get<double>(), ob[i].at("x").get<double>(), 0.03);
		EXPECT_NEAR(
		    oa[i].at("y").get<double>(), ob[i].at("y").get<double>(), 0.03);
	}
	double resA = 0, resB = 0;
	const auto ca = occupiedCells(kTmp / "map_sim", resA);
	const auto cb = occupiedCells(kTmp / "map_bag", resB);
	ASSERT_GT(resA, 0);
	EXPECT_EQ(resA, resB);
	EXPECT_GT(ca.size(), 100u);  // the walls at least
	EXPECT_EQ(unmatchedCells(ca, cb, resA), 0u);
	EXPECT_EQ(unmatchedCells(cb, ca, resA), 0u);
}

TEST_F(Bag2Rawlog, LinesWithoutATiltAreSkippedAndCounted)
{
	// The joint stops after the second sweep: the third is skipped.
	std::size_t twoSweeps = 0;
	while (lines[twoSweeps].sweep < 2) twoSweeps++;
	JointStatesBag how;
	how.tiltUntil = lines[twoSweeps - 1].stamp;
	writeJointStatesBag(lines, (kTmp / "short.bag").string(), how);
	const AppRun r = convert(kTmp / "short.bag");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	EXPECT_EQ(j.at("lines"), twoSweeps);
	EXPECT_EQ(j.at("skipped_no_tilt"), lines.size() - twoSweeps);
	EXPECT_NE(
	    j.at("first_skip")
	        .get<std::string>()
	        .find("no tilt_joint position after the line"),
	    std::string::npos)
	    << j.dump();
	EXPECT_EQ(readRawlogSweeps((kTmp / "bag.rawlog").string()).size(), 2u);

	// Joint positions further apart than --max-gap: only the lines with a
	// position at their own time (first and last of each sweep) are kept.
	writeJointStatesBag(lines, (kTmp / "js.bag").string());
	const AppRun g = convert(kTmp / "js.bag", "--max-gap 0.000001");
	ASSERT_EQ(g.code, 0) << g.err;
	const auto jg = nlohmann::json::parse(g.out);
	EXPECT_EQ(jg.at("lines"), 6u);
	EXPECT_EQ(jg.at("skipped_no_tilt"), lines.size() - 6);
	EXPECT_NE(
	    jg.at("first_skip")
	        .get<std::string>()
	        .find("positions around the line are"),
	    std::string::npos)
	    << jg.dump();
}

/** Runs a conversion that must fail: exit 1, one line on stderr holding
 * every `expected` piece, no rawlog (nor its temporary) left behind. */
void expectError(const AppRun& r, const std::vector<std::string>& expected)
{
	EXPECT_EQ(r.code, 1) << r.err;
	EXPECT_EQ(lineCount(r.err), 1u) << r.err;
	for (const auto& e : expected)
		EXPECT_NE(r.err.find(e), std::string::npos)
		    << "'" << e << "' not in: " << r.err;
	EXPECT_FALSE(fs::exists(kTmp / "bag.rawlog"));
	for (const auto& f : fs::directory_iterator(kTmp))
		EXPECT_EQ(f.path().filename().string().find(".tmp"), std::string::npos)
		    << f.path();
}

TEST_F(Bag2Rawlog, ABagWithoutTheTopicsJointOrFramesIsOneLineNamingThem)
{
	const fs::path js = kTmp / "js.bag", tf = kTmp / "tf.bag";
	fs::remove(kTmp / "bag.rawlog");
	writeJointStatesBag(lines, js.string());
	writeTfBag(lines, tf.string());
	expectError(
	    convert(js, "--scan-topic /laser"),
	    {"bag " + js.string() + " has no topic /laser (sensor_msgs/LaserScan",
	     "its topics: /joint_states (sensor_msgs/JointState), /odom "
	     "(nav_msgs/Odometry), /scan (sensor_msgs/LaserScan)"});
	expectError(
	    convert(js, "--odom-topic /wheel_odom"),
	    {"has no topic /wheel_odom (nav_msgs/Odometry", "--odom-from tf"});
	expectError(
	    convert(js, "--joint-states-topic /odom"),
	    {"topic /odom of bag " + js.string() +
	     " is nav_msgs/Odometry, expected sensor_msgs/JointState"});
	expectError(
	    convert(js, "--tilt-joint head_tilt"),
	    {"joint 'head_tilt' is not in /joint_states of bag " + js.string(),
	     "its joints: tilt_joint, wheel_left_joint"});
	expectError(
	    convert(js, "--tilt-from tf"),
	    {"has no topic /tf (tf2_msgs/TFMessage"});
	expectError(
	    convert(
	        tf, "--tilt-from tf --odom-from tf --base-frame base_footprint"),
	    {"bag " + tf.string() + " has no tf frame 'base_footprint'",
	     "its frames: base_link, laser, laser_mount, odom"});
	expectError(
	    convert(tf, "--tilt-from tf --odom-from tf --laser-frame lms"),
	    {"has no tf frame 'lms' (--laser-frame"});
	// Every line skipped (the joint's only position is 5 s before the
	// scans): the error says why the first one was.
	const fs::path early = kTmp / "early.bag";
	{
		rosbag::Bag bag(early.string(), rosbag::bagmode::Write);
		sensor_msgs::JointState j;
		j.header.stamp = lines.front().stamp - ros::Duration(5);
		j.name = {"tilt_joint"};
		j.position = {0.0};
		bag.write("/joint_states", j.header.stamp, j);
		for (const auto& l : lines)
		{
			bag.write("/odom", l.stamp, odometryMsg(l.odometry, l.stamp));
			bag.write("/scan", l.stamp, laserScanOf(l, 0, "laser"));
		}
	}
	expectError(
	    convert(early),
	    {"no scan line of /scan in bag " + early.string() +
	         " could be converted (" + std::to_string(lines.size()) +
	         " scans; first: line at ",
	     ": no tilt_joint position after the line"});
}

TEST_F(Bag2Rawlog, AnUnreadableBagOrOutputIsOneLine)
{
	const fs::path js = kTmp / "js.bag";
	writeJointStatesBag(lines, js.string());
	fs::remove(kTmp / "bag.rawlog");
	expectError(
	    convert(kTmp / "none.bag"),
	    {"cannot read bag " + (kTmp / "none.bag").string()});
	std::ofstream(kTmp / "text.bag") << "not a bag\n";
	expectError(
	    convert(kTmp / "text.bag"),
	    {"cannot read bag " + (kTmp / "text.bag").string()});
	// A bag cut in the middle (a recording killed while writing).
	const fs::path cut = kTmp / "cut.bag";
	fs::copy_file(js, cut, fs::copy_options::overwrite_existing);
	fs::resize_file(cut, fs::file_size(js) / 2);
	expectError(convert(cut), {"cannot read bag " + cut.string()});
	const AppRun r = runApp(
	    "semnav-bag2rawlog",
	    js.string() + " --out " + (kTmp / "no/such/dir/x.rawlog").string());
	EXPECT_EQ(r.code, 1);
	EXPECT_NE(r.err.find("cannot create rawlog"), std::string::npos) << r.err;
	const AppRun u = runApp("semnav-bag2rawlog", js.string());
	EXPECT_EQ(u.code, 2);
	EXPECT_NE(u.err.find("missing --out"), std::string::npos) << u.err;
}

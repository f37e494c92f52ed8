/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-robot for ROS 1 operators (Ros1Operator) in the loop: a private
// rosmaster, the emulated robot (LMS200 + PTU + ROS base) in the office, the
// office map from semnav-sim + semnav-map, semnav-robot --no-stdin with
// config/robot-emulated.ini (a tracking start, to keep it short). A roscpp
// node in the test reads what semnav publishes and commands it like rviz.
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <mrpt/poses/CPose2D.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <semnav/common/Label.h>
#include <semnav/common/LabelSet.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/SemanticPlanner.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>

#include "../dataset/AppRunner.h"
#include "../navsim/NavTestUtils.h"
#include "RosTestProcesses.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace semnav;

namespace
{
const std::string kSource = SEMNAV_SOURCE_DIR;
const std::string kScene = kSource + "/datasets/office/office.yaml";
/** Where the emulated robot truly starts (and semnav is told it starts). */
const char* kStartPose = "2.2,1.5,0";
/** The pose goal: 1.1 m ahead of the start. */
const mrpt::math::TPoint2D kPoint{3.3, 1.5};

/** The office map of the demo: semnav-sim, then semnav-map --poses pf. */
std::string officeMap(const std::string& dir)
{
	const auto s = test::runApp(
	    "semnav-sim", "--scene " + kScene + " --out " + dir + "/sim --seed 1");
	EXPECT_EQ(s.code, 0) << s.err;
	const auto m = test::runApp(
	    "semnav-map", "--rawlog " + dir + "/sim/office.rawlog --out " + dir +
	                      "/map --poses pf --gt-dir " + dir + "/sim");
	EXPECT_EQ(m.code, 0) << m.err;
	return dir + "/map";
}

/** config/robot-emulated.ini for this run: paths in `dir`, the map, a
 * tracking start at the true start pose. */
std::string robotIni(const std::string& dir, const std::string& map)
{
	std::ifstream in(kSource + "/config/robot-emulated.ini");
	std::stringstream ss;
	ss << in.rdbuf();
	std::string text = std::regex_replace(
	    ss.str(), std::regex("/tmp/semnav-robot/"), dir + "/");
	const auto set = [&](const std::string& key, const std::string& value)
	{
		text = std::regex_replace(
		    text, std::regex("\n" + key + " = [^\n]*"),
		    "\n" + key + " = " + value);
	};
	set("map_dir", map);
	set("localize", "tracking");
	set("start_pose", "2.2 1.5 0");
	const std::string path = dir + "/robot.ini";
	std::ofstream(path) << text;
	return path;
}

/** The last line of the emulator's true trajectory: x, y. */
mrpt::math::TPoint2D truePosition(const std::string& trajectory)
{
	// The emulator writes as it goes: the last line may be partial.
	std::this_thread::sleep_for(std::chrono::milliseconds(300));
	std::ifstream f(trajectory);
	mrpt::math::TPoint2D last{NAN, NAN};
	for (std::string l; std::getline(f, l);)
	{
		std::istringstream in(l);
		double v[6];
		if (in >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5])
			last = {v[1], v[2]};
	}
	return last;
}

/** What the test's node received (the latest of each topic, all events). */
class Received
{
public:
	explicit Received(ros::NodeHandle& n)
	{
		sub<nav_msgs::OccupancyGrid>(n, "map", m_map);
		sub<nav_msgs::OccupancyGrid>(n, "semnav/labels/wall", m_wall);
		sub<nav_msgs::OccupancyGrid>(n, "semnav/labels/door", m_door);
		sub<nav_msgs::OccupancyGrid>(n, "semnav/cost", m_cost);
		sub<visualization_msgs::MarkerArray>(n, "semnav/objects", m_objects);
		sub<nav_msgs::Path>(n, "semnav/path", m_path);
		sub<geometry_msgs::PoseWithCovarianceStamped>(n, "semnav/pose", m_pose);
		sub<sensor_msgs::PointCloud2>(n, "semnav/sweep", m_sweep);
		sub<tf2_msgs::TFMessage>(n, "/tf", m_tf);
		sub<nav_msgs::Odometry>(n, "odom", m_odom);
		m_subs.push_back(n.subscribe<std_msgs::String>(
		    "semnav/events", 1000,
		    [this](const std_msgs::String::ConstPtr& m)
		    {
			    std::lock_guard<std::mutex> lk(m_mutex);
			    m_events.push_back(json::parse(m->data));
		    }));
	}

	template <class M>
	using Latest = boost::shared_ptr<const M>;

	/** Waits up to `timeout` s for `ok` (called with the lock held). */
	bool waitFor(double timeout, const std::function<bool()>& ok)
	{
		const auto end = std::chrono::steady_clock::now() +
		                 std::chrono::duration<double>(timeout);
		while (std::chrono::steady_clock::now() < end)
		{
			{
				std::lock_guard<std::mutex> lk(m_mutex);
				if (ok()) return true;
			}
			std::this_thread::sleep_for(std::chrono::milliseconds(50));
		}
		return false;
	}
	/** The first event after `from` (index) with event == `kind`, waiting
	 * up to `timeout` s; null when none came. */
	json event(const std::string& kind, std::size_t from, double timeout)
	{
		json found;
		waitFor(
		    timeout,
		    [&]
		    {
			    for (std::size_t i = from; i < m_events.size(); i++)
				    if (m_events[i].value("event", "") == kind)
				    {
					    found = m_events[i];
					    return true;
				    }
			    return false;
		    });
		return found;
	}
	std::size_t eventCount()
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		return m_events.size();
	}
	template <class M>
	Latest<M> get(const Latest<M>& member)
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		return member;
	}

	Latest<nav_msgs::OccupancyGrid> m_map, m_wall, m_door, m_cost;
	Latest<visualization_msgs::MarkerArray> m_objects;
	Latest<nav_msgs::Path> m_path;
	Latest<geometry_msgs::PoseWithCovarianceStamped> m_pose;
	Latest<sensor_msgs::PointCloud2> m_sweep;
	Latest<tf2_msgs::TFMessage> m_tf;
	Latest<nav_msgs::Odometry> m_odom;
	std::vector<json> m_events;
	std::mutex m_mutex;

private:
	template <class M>
	void sub(ros::NodeHandle& n, const std::string& topic, Latest<M>& into)
	{
		m_subs.push_back(n.subscribe<M>(
		    topic, 10,
		    [this, &into](const typename M::ConstPtr& m)
		    {
			    std::lock_guard<std::mutex> lk(m_mutex);
			    into = m;
		    }));
	}
	std::vector<ros::Subscriber> m_subs;
};

/** (id, label) of the instances a MarkerArray shows (its text markers). */
std::set<std::pair<int, std::string>> shownObjects(
    const visualization_msgs::MarkerArray& a)
{
	std::set<std::pair<int, std::string>> out;
	for (const auto& m : a.markers)
		if (m.ns == "labels")
			out.insert({m.id, m.text.substr(0, m.text.find(' '))});
	return out;
}

std::set<std::pair<int, std::string>> savedObjects(const SemanticMap& m)
{
	std::set<std::pair<int, std::string>> out;
	for (const auto& o : m.instances()) out.insert({o.id, labelName(o.label)});
	return out;
}

void expectSameGeometry(
    const nav_msgs::OccupancyGrid& g, const SemanticMap& m,
    const std::string& what)
{
	SCOPED_TRACE(what);
	const auto& geo = m.geometry();
	EXPECT_EQ(g.info.width, static_cast<uint32_t>(geo.cols));
	EXPECT_EQ(g.info.height, static_cast<uint32_t>(geo.rows));
	EXPECT_NEAR(g.info.resolution, geo.resolution, 1e-6);
	EXPECT_NEAR(g.info.origin.position.x, geo.originX, 1e-3);
	EXPECT_NEAR(g.info.origin.position.y, geo.originY, 1e-3);
	EXPECT_EQ(g.header.frame_id, "map");
}

/** Cells whose label grid says `label` differ from the map's labels. */
int labelMismatches(
    const nav_msgs::OccupancyGrid& g, const SemanticMap& m, Label label)
{
	int bad = 0;
	const auto& labels = m.get("labels");
	for (std::size_t i = 0; i < labels.size() && i < g.data.size(); i++)
		if ((g.data[i] == 100) !=
		    LabelSet(static_cast<LabelSet::mask_t>(labels[i])).contains(label))
			bad++;
	return bad;
}

/** Cells whose occupancy differs (0-100 of the probability, -1 never
 * observed). */
int occupancyMismatches(const nav_msgs::OccupancyGrid& g, const SemanticMap& m)
{
	int bad = 0;
	const auto& geo = m.geometry();
	const auto& observations = m.get("observations");
	for (int r = 0; r < geo.rows; r++)
		for (int c = 0; c < geo.cols; c++)
		{
			const auto i = geo.index(r, c);
			const int expected =
			    observations[i] > 0
			        ? static_cast<int>(std::lround(100 * m.occupancy(c, r)))
			        : -1;
			if (std::abs(g.data[i] - expected) > 1) bad++;
		}
	return bad;
}

/** Cells whose cost grid value is not the map's travel cost u scaled to
 * 0-100 of L (100: blocked; -1 never observed). */
int costMismatches(const nav_msgs::OccupancyGrid& g, const SemanticMap& m)
{
	int bad = 0, blocked = 0;
	const auto& cost = m.get("cost");
	const auto& observations = m.get("observations");
	const double L = m.options().cost.lethalCost;
	for (std::size_t i = 0; i < cost.size() && i < g.data.size(); i++)
	{
		const long expected =
		    observations[i] > 0
		        ? std::clamp(std::lround(100 * cost[i] / L), 0L, 100L)
		        : -1;
		bad += g.data[i] != expected;
		blocked += g.data[i] == 100;
	}
	EXPECT_GT(blocked, 100) << "no blocked cells in the cost grid";
	return bad;
}

class Ros1Operator : public ::testing::Test
{
protected:
	void SetUp() override
	{
		dir = test::testDir("operator");
		mapDir = officeMap(dir);
		master = std::make_unique<test::PrivateRosMaster>(dir);
		robot = std::make_unique<test::EmulatedRobot>(
		    dir, kScene, kStartPose,
		    std::vector<std::string>{
		        "--lms-link", dir + "/lms", "--ptu-link", dir + "/ptu"});
		if (!ros::isInitialized())
		{
			ros::M_string remappings;
			ros::init(
			    remappings, "semnav_operator_test",
			    ros::init_options::NoSigintHandler |
			        ros::init_options::NoRosout |
			        ros::init_options::AnonymousName);
		}
		for (int i = 0; i < 100 && !ros::master::check(); i++)
			std::this_thread::sleep_for(std::chrono::milliseconds(100));
		ASSERT_TRUE(ros::master::check());
		ros::start();
		node = std::make_unique<ros::NodeHandle>();
		received = std::make_unique<Received>(*node);
		spinner = std::make_unique<ros::AsyncSpinner>(2);
		spinner->start();
		commands = node->advertise<std_msgs::String>("semnav/command", 10);
		goals = node->advertise<geometry_msgs::PoseStamped>(
		    "move_base_simple/goal", 10);
		semnav = std::make_unique<test::ChildProcess>(
		    std::vector<std::string>{
		        std::string(SEMNAV_BINARY_DIR) +
		            "/apps/semnav-robot/semnav-robot",
		        "--config", robotIni(dir, mapDir), "--out", dir + "/out",
		        "--no-stdin"},
		    dir + "/robot.log");
	}
	void TearDown() override
	{
		if (semnav) semnav->terminate(30);
		spinner->stop();
		robot.reset();
	}

	/** Sends a line on semnav/command once semnav listens. */
	void command(const std::string& line)
	{
		waitForSubscriber(commands);
		std_msgs::String m;
		m.data = line;
		commands.publish(m);
	}
	void poseGoal(double x, double y, const std::string& frame)
	{
		waitForSubscriber(goals);
		geometry_msgs::PoseStamped g;
		g.header.frame_id = frame;
		g.header.stamp = ros::Time::now();
		g.pose.position.x = x;
		g.pose.position.y = y;
		g.pose.orientation.w = 1;
		goals.publish(g);
	}
	static void waitForSubscriber(const ros::Publisher& p)
	{
		for (int i = 0; i < 100 && p.getNumSubscribers() == 0; i++)
			std::this_thread::sleep_for(std::chrono::milliseconds(50));
	}

	/** Map, label layers, cost, objects, pose, tf and sweep after the
	 * start, checked against the starting map `start`. */
	void checkStartTopics(const SemanticMap& start)
	{
		auto& rx = *received;
		// Map, label layers, cost and objects arrive (latched) and agree with
		// the starting map directory (the robot may have grown the map with
		// its first sweeps: the grid may only have grown).
		ASSERT_TRUE(rx.waitFor(
		    10,
		    [&] {
			    return rx.m_map && rx.m_wall && rx.m_door && rx.m_cost &&
			           rx.m_objects;
		    }));
		{
			const auto m = rx.get(rx.m_map);
			EXPECT_NEAR(m->info.resolution, start.geometry().resolution, 1e-6);
			EXPECT_GE(
			    m->info.width, static_cast<uint32_t>(start.geometry().cols));
			EXPECT_GE(
			    m->info.height, static_cast<uint32_t>(start.geometry().rows));
			const auto o = rx.get(rx.m_objects);
			EXPECT_EQ(shownObjects(*o), savedObjects(start));
		}
		// Pose (with the localization's covariance), tf map -> odom, a sweep
		// with labels.
		ASSERT_TRUE(
		    rx.waitFor(10, [&] { return rx.m_pose && rx.m_tf && rx.m_sweep; }));
		{
			const auto p = rx.get(rx.m_pose);
			EXPECT_EQ(p->header.frame_id, "map");
			EXPECT_NEAR(p->pose.pose.position.x, 2.2, 0.3);
			EXPECT_NEAR(p->pose.pose.position.y, 1.5, 0.3);
			EXPECT_GT(p->pose.covariance[0], 0);
			const auto tf = rx.get(rx.m_tf);
			ASSERT_EQ(tf->transforms.size(), 1u);
			EXPECT_EQ(tf->transforms[0].header.frame_id, "map");
			EXPECT_EQ(tf->transforms[0].child_frame_id, "odom");
			// map -> odom composed with the (standing) robot's odometry is
			// the published pose.
			const auto odom = rx.get(rx.m_odom);
			ASSERT_TRUE(odom);
			const auto& t = tf->transforms[0].transform;
			const mrpt::poses::CPose2D mapToOdom(
			    t.translation.x, t.translation.y,
			    2 * std::atan2(t.rotation.z, t.rotation.w));
			const auto& o = odom->pose.pose;
			const mrpt::poses::CPose2D inOdom(
			    o.position.x, o.position.y,
			    2 * std::atan2(o.orientation.z, o.orientation.w));
			const auto inMap = mapToOdom + inOdom;
			EXPECT_NEAR(inMap.x(), p->pose.pose.position.x, 0.02);
			EXPECT_NEAR(inMap.y(), p->pose.pose.position.y, 0.02);
			const auto s = rx.get(rx.m_sweep);
			ASSERT_EQ(s->fields.size(), 4u);
			EXPECT_EQ(s->fields[3].name, "label");
			EXPECT_GT(s->width, 1000u);
			std::set<float> labels;
			for (uint32_t i = 0; i < s->width; i++)
			{
				float l;
				std::memcpy(&l, &s->data[i * s->point_step + 12], 4);
				labels.insert(l);
			}
			EXPECT_TRUE(labels.count(static_cast<float>(Label::Wall)));
			EXPECT_TRUE(labels.count(static_cast<float>(Label::Floor)));
		}
	}

	void checkBadGoals()
	{
		auto& rx = *received;
		// Bad goals: a pose in another frame, an unknown label: errors on the
		// events topic, the robot stays.
		std::size_t from = rx.eventCount();
		poseGoal(3.5, 1.5, "odom");
		json e = rx.event("error", from, 10);
		ASSERT_FALSE(e.is_null());
		EXPECT_NE(
		    e.value("command", "").find("move_base_simple/goal"),
		    std::string::npos);
		EXPECT_NE(e.value("error", "").find("map frame"), std::string::npos);
		from = rx.eventCount();
		command("go to the nearest unicorn");
		e = rx.event("error", from, 10);
		ASSERT_FALSE(e.is_null());
		EXPECT_EQ(e.value("command", ""), "go to the nearest unicorn");
	}

	void checkPoseGoal()
	{
		auto& rx = *received;
		// A pose goal (rviz's 2D Nav Goal): "go to x y", the path arrives,
		// the robot truly stands there.
		const std::size_t from = rx.eventCount();
		poseGoal(kPoint.x, kPoint.y, "map");
		json e = rx.event("goal", from, 10);
		ASSERT_FALSE(e.is_null());
		EXPECT_EQ(e.value("command", ""), "go to 3.300 1.500");
		ASSERT_TRUE(rx.waitFor(
		    20, [&] { return rx.m_path && rx.m_path->poses.size() > 1; }));
		{
			const auto path = rx.get(rx.m_path);
			EXPECT_EQ(path->header.frame_id, "map");
			EXPECT_NEAR(path->poses.front().pose.position.x, 2.2, 0.5);
			EXPECT_NEAR(path->poses.back().pose.position.x, kPoint.x, 0.5);
			EXPECT_NEAR(path->poses.back().pose.position.y, kPoint.y, 0.5);
		}
		e = rx.event("arrived", from, 60);
		ASSERT_FALSE(e.is_null()) << "see " << dir << "/robot.log";
		const auto atPoint = truePosition(robot->trajectoryFile());
		// Within arrival_tolerance_m of config/navigation.ini.
		EXPECT_LT(std::hypot(atPoint.x - kPoint.x, atPoint.y - kPoint.y), 0.6);
	}

	void checkSemanticGoal(const SemanticMap& start)
	{
		auto& rx = *received;
		// A semantic goal (std_msgs/String): the robot truly stands by the
		// door it reports.
		const auto atCommand = truePosition(robot->trajectoryFile());
		const std::size_t from = rx.eventCount();
		command("go to the nearest door");
		const json e = rx.event("arrived", from, 90);
		ASSERT_FALSE(e.is_null()) << "see " << dir << "/robot.log";
		const int door = e.value("object", 0);
		ASSERT_GT(door, 0);
		const auto& d = start.instance(door);
		EXPECT_EQ(labelName(d.label), "door");
		const auto atDoor = truePosition(robot->trajectoryFile());
		// The door is the path-nearest one from where the command was
		// given, and the robot truly stands close to its goal region (the
		// navigator's arrival leaves up to ~1 m: the other doors are 5 m and
		// more away).
		const auto& c = test::shippedNavigationConfig();
		const SemanticPlanner planner(start, c.cnn, c.traversability);
		EXPECT_EQ(
		    planner
		        .toLabel(
		            atCommand.x, atCommand.y, Label::Door,
		            c.navigationProfile())
		        .goalObjectId,
		    door);
		EXPECT_LE(
		    planner.toObject(atDoor.x, atDoor.y, door, c.navigationProfile())
		        .path.lengthM,
		    1.2);
		const auto believed = e["pose"];
		EXPECT_LT(
		    std::hypot(
		        believed[0].get<double>() - atDoor.x,
		        believed[1].get<double>() - atDoor.y),
		    0.3);
	}

	/** Ends semnav-robot; the last map topics equal the map it saved. */
	void checkEnd()
	{
		auto& rx = *received;
		// At the end the map topics show the map semnav-robot saves: same
		// grid, occupancy, label layers and objects.
		std::this_thread::sleep_for(std::chrono::milliseconds(2500));
		const auto finalMap = rx.get(rx.m_map);
		const auto finalWall = rx.get(rx.m_wall);
		const auto finalDoor = rx.get(rx.m_door);
		const auto finalCost = rx.get(rx.m_cost);
		const auto finalObjects = rx.get(rx.m_objects);
		EXPECT_EQ(semnav->terminate(30), 0);
		// Publishing held the control loop only briefly (under half its 0.1 s
		// period even on a loaded machine; ~1 ms on an idle one).
		json end;
		for (const auto& l : semnav->lines())
			if (!l.empty() && l[0] == '{' &&
			    l.find("\"event\":\"end\"") != std::string::npos)
				end = json::parse(l);
		ASSERT_TRUE(end.contains("ros")) << "see " << dir << "/robot.log";
		std::cerr << "ros: " << end["ros"].dump() << "\n";
		EXPECT_GE(end["ros"]["goals"].get<int>(), 1);
		EXPECT_LT(end["ros"]["max_hook_ms"].get<double>(), 50);
		semnav.reset();
		SemanticMap saved;
		MapIO::load(dir + "/out/map", saved);
		expectSameGeometry(*finalMap, saved, "map");
		expectSameGeometry(*finalWall, saved, "wall layer");
		EXPECT_EQ(occupancyMismatches(*finalMap, saved), 0);
		EXPECT_EQ(labelMismatches(*finalWall, saved, Label::Wall), 0);
		EXPECT_EQ(labelMismatches(*finalDoor, saved, Label::Door), 0);
		EXPECT_EQ(costMismatches(*finalCost, saved), 0);
		EXPECT_EQ(shownObjects(*finalObjects), savedObjects(saved));
	}

	std::string dir, mapDir;
	std::unique_ptr<test::PrivateRosMaster> master;
	std::unique_ptr<test::EmulatedRobot> robot;
	std::unique_ptr<ros::NodeHandle> node;
	std::unique_ptr<Received> received;
	std::unique_ptr<ros::AsyncSpinner> spinner;
	ros::Publisher commands, goals;
	std::unique_ptr<test::ChildProcess> semnav;
};
}  // namespace

TEST_F(Ros1Operator, TopicsAgreeWithTheMapAndGoalsMoveTheRobot)
{
	const json localized = received->event("localized", 0, 60);
	ASSERT_FALSE(localized.is_null()) << "see " << dir << "/robot.log";
	SemanticMap start;
	MapIO::load(mapDir, start);
	checkStartTopics(start);
	ASSERT_FALSE(HasFatalFailure());
	checkBadGoals();
	ASSERT_FALSE(HasFatalFailure());
	checkPoseGoal();
	ASSERT_FALSE(HasFatalFailure());
	checkSemanticGoal(start);
	ASSERT_FALSE(HasFatalFailure());
	checkEnd();
}

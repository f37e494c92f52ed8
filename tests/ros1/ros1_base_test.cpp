/* semnav: semantic navigation from tilting-laser sweeps */
// Ros1Base against the emulated differential-drive base over real ROS 1
// transport: a private rosmaster on a free port, semnav-device-emulator
// --base as a separate process, Ros1Base in this one. One process per test
// (gtest_discover_tests), as roscpp starts once per process.
#include <geometry_msgs/Twist.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/hwdrivers/CSickLaserSerial.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/ros1bridge/pose.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <semnav/common/Error.h>
#include <semnav/emulation/SceneLineCaster.h>
#include <semnav/hwdrivers/MonitoredSerialPort.h>
#include <semnav/ros1/Ros1Base.h>
#include <semnav/ros1/RosNode.h>
#include <semnav/scan/TiltGeometry.h>
#include <semnav/sim/SceneLoader.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

#include "RosTestProcesses.h"

using namespace semnav;
using namespace semnav::test;
using namespace std::chrono_literals;
using SteadyClock = std::chrono::steady_clock;

namespace
{
const std::string kScene =
    std::string(SEMNAV_SOURCE_DIR) + "/datasets/nav-trials/rect_room.yaml";
const std::string kStart = "1.5,1.5,0";

double since(SteadyClock::time_point t)
{
	return std::chrono::duration<double>(SteadyClock::now() - t).count();
}

/** The emulator's truth (base_pose_ground_truth) as it arrives here. */
class TruthListener
{
public:
	struct Sample
	{
		SteadyClock::time_point arrival;
		mrpt::math::TPose2D pose;
		double v = 0, w = 0;
	};
	TruthListener()
	{
		m_sub = m_node.subscribe(
		    "base_pose_ground_truth", 100, &TruthListener::on, this);
	}
	std::vector<Sample> samples() const
	{
		std::lock_guard<std::mutex> lock(m_mutex);
		return m_samples;
	}
	/** Waits up to `timeout` for a sample; throws when none comes. */
	Sample latest(std::chrono::milliseconds timeout = 3000ms) const
	{
		const auto end = SteadyClock::now() + timeout;
		while (SteadyClock::now() < end)
		{
			{
				std::lock_guard<std::mutex> lock(m_mutex);
				if (!m_samples.empty()) return m_samples.back();
			}
			std::this_thread::sleep_for(10ms);
		}
		throw std::runtime_error("no ground truth from the emulator");
	}

private:
	void on(const nav_msgs::Odometry::ConstPtr& m)
	{
		const auto p = mrpt::ros1bridge::fromROS(m->pose.pose);
		std::lock_guard<std::mutex> lock(m_mutex);
		m_samples.push_back(
		    {SteadyClock::now(),
		     {p.x(), p.y(), p.yaw()},
		     m->twist.twist.linear.x,
		     m->twist.twist.angular.z});
	}
	ros::NodeHandle m_node;
	ros::Subscriber m_sub;
	mutable std::mutex m_mutex;
	std::vector<Sample> m_samples;
};

/** The velocity commands seen on cmd_vel, as they arrive here. */
class CommandListener
{
public:
	struct Command
	{
		SteadyClock::time_point arrival;
		double v = 0, w = 0;
	};
	CommandListener()
	{
		m_sub = m_node.subscribe("cmd_vel", 100, &CommandListener::on, this);
	}
	std::vector<Command> commands() const
	{
		std::lock_guard<std::mutex> lock(m_mutex);
		return m_commands;
	}

private:
	void on(const geometry_msgs::Twist::ConstPtr& m)
	{
		std::lock_guard<std::mutex> lock(m_mutex);
		m_commands.push_back({SteadyClock::now(), m->linear.x, m->angular.z});
	}
	ros::NodeHandle m_node;
	ros::Subscriber m_sub;
	mutable std::mutex m_mutex;
	std::vector<Command> m_commands;
};

/** When the truth first says "speed 0" after `t` (s after t; -1: never). */
double stoppedAfter(
    const std::vector<TruthListener::Sample>& samples,
    SteadyClock::time_point t)
{
	for (const auto& s : samples)
		if (s.arrival > t && s.v == 0)
			return std::chrono::duration<double>(s.arrival - t).count();
	return -1;
}

bool g_rosUsed = false;

/** A private master, this process's ROS node and the truth listener. */
class Ros1BaseTest : public ::testing::Test
{
protected:
	void SetUp() override
	{
		// roscpp starts once per process: ctest runs each test alone.
		if (g_rosUsed)
			GTEST_SKIP() << "one ROS test per process (use ctest, or "
			                "--gtest_filter for one test)";
		g_rosUsed = true;
		const auto* info =
		    ::testing::UnitTest::GetInstance()->current_test_info();
		m_dir = testDir(info->name());
		m_master = std::make_unique<PrivateRosMaster>(m_dir);
		startRosNode("semnav_test_" + std::to_string(::getpid()), 10);
		m_spinner = std::make_unique<ros::AsyncSpinner>(1);
		m_spinner->start();
		m_truth = std::make_unique<TruthListener>();
		m_commands = std::make_unique<CommandListener>();
	}
	void TearDown() override
	{
		if (!m_master) return;
		m_commands.reset();
		m_truth.reset();
		m_spinner.reset();
		ros::shutdown();
		m_master.reset();
		if (!HasFailure()) std::system(("rm -rf '" + m_dir + "'").c_str());
	}
	/** The shipped [Ros1Base] of config/robot.ini. */
	Ros1Base::TOptions options() const
	{
		Ros1Base::TOptions o;
		mrpt::config::CConfigFile ini(
		    std::string(SEMNAV_SOURCE_DIR) + "/config/robot.ini");
		o.loadFromConfigFile(ini, "Ros1Base");
		return o;
	}
	/** Waits until `base` has fresh odometry and the emulator listens to
	 * its commands (cmd_vel's subscribers: the emulator and this test). */
	static void waitForOdometry(const Ros1Base& base)
	{
		const auto t0 = SteadyClock::now();
		while ((base.odometryStale() || base.commandSubscribers() < 2) &&
		       since(t0) < 10)
			std::this_thread::sleep_for(10ms);
		ASSERT_FALSE(base.odometryStale()) << "no odometry from the emulator";
		ASSERT_GE(base.commandSubscribers(), 2u) << "cmd_vel not connected";
	}
	/** Commands (v, w) every 0.1 s for `seconds`, as a navigator does;
	 * returns the time from the first command to the stop. */
	static double drive(Ros1Base& base, double v, double w, double seconds)
	{
		const auto t0 = SteadyClock::now();
		while (since(t0) < seconds)
		{
			EXPECT_TRUE(base.setVelocity(v, w));
			std::this_thread::sleep_for(100ms);
		}
		base.stop();
		return since(t0);
	}

	std::string m_dir;
	std::unique_ptr<PrivateRosMaster> m_master;
	std::unique_ptr<ros::AsyncSpinner> m_spinner;
	std::unique_ptr<TruthListener> m_truth;
	std::unique_ptr<CommandListener> m_commands;
};
}  // namespace

TEST(Ros1BaseOptions, UnknownKeysAndOutOfRangeValuesAreErrors)
{
	Ros1BaseOptions o;
	mrpt::config::CConfigFileMemory ok(
	    "[Ros1Base]\ncommand_rate_hz = 20\nodom_topic = wheel_odom\n");
	o.loadFromConfigFile(ok, "Ros1Base");
	EXPECT_EQ(o.commandRate, 20);
	EXPECT_EQ(o.odomTopic, "wheel_odom");
	mrpt::config::CConfigFileMemory slow("[Ros1Base]\ncommand_rate_hz = 2\n");
	EXPECT_THROW(o.loadFromConfigFile(slow, "Ros1Base"), ConfigError);
	mrpt::config::CConfigFileMemory typo("[Ros1Base]\ncmd_topic = x\n");
	EXPECT_THROW(o.loadFromConfigFile(typo, "Ros1Base"), ConfigError);
	EXPECT_EQ(o.commandRate, 20);  // unchanged by the failed loads
}

TEST(Ros1Base, AMasterThatDoesNotAnswerIsAnErrorNamingIt)
{
	const std::string uri = "http://127.0.0.1:" + std::to_string(freePort());
	::setenv("ROS_MASTER_URI", uri.c_str(), 1);
	::setenv("ROS_IP", "127.0.0.1", 1);
	Ros1Base::TOptions o;
	o.nodeName = "semnav_no_master_" + std::to_string(::getpid());
	o.masterTimeout = 0.3;
	try
	{
		Ros1Base base(o);
		FAIL() << "no error without a master";
	}
	catch (const IoError& e)
	{
		EXPECT_NE(std::string(e.what()).find(uri), std::string::npos)
		    << e.what();
	}
}

TEST(DeviceEmulatorBaseCli, BadInputIsOneLineAndNonZeroExit)
{
	const std::string dir = testDir("cli");
	const std::string uri = "http://127.0.0.1:" + std::to_string(freePort());
	::setenv("ROS_MASTER_URI", uri.c_str(), 1);
	const auto run = [&](const std::string& args, std::string& err)
	{
		const int status = std::system(
		    (std::string(SEMNAV_BINARY_DIR) +
		     "/apps/semnav-device-emulator/semnav-device-emulator --scene " +
		     kScene + " --base " + args + " >/dev/null 2>" + dir + "/err")
		        .c_str());
		std::ifstream f(dir + "/err");
		err.assign(std::istreambuf_iterator<char>(f), {});
		return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
	};
	const auto lines = [](const std::string& t)
	{ return std::count(t.begin(), t.end(), '\n'); };
	std::string err;
	EXPECT_EQ(run("--base-watchdog 0", err), 2);
	EXPECT_EQ(lines(err), 1) << err;
	EXPECT_EQ(run("--odom-rate fast", err), 2);
	EXPECT_EQ(lines(err), 1) << err;
	EXPECT_EQ(run("--odom-silent-for -1", err), 2);
	EXPECT_EQ(lines(err), 1) << err;
	// No master: one line naming it (after the 5 s wait).
	EXPECT_EQ(run("--duration 1", err), 1);
	EXPECT_EQ(lines(err), 1) << err;
	EXPECT_NE(err.find(uri), std::string::npos) << err;
	std::system(("rm -rf '" + dir + "'").c_str());
}

TEST_F(Ros1BaseTest, OdometryInOtherFramesIsIgnored)
{
	EmulatedRobot robot(m_dir, kScene, kStart);
	auto o = options();
	o.odomFrame = "map";  // the emulator publishes odom -> base_link
	Ros1Base base(o);
	const auto t0 = SteadyClock::now();
	while (base.stats().odometryRejected < 10 && since(t0) < 10)
		std::this_thread::sleep_for(10ms);
	EXPECT_GE(base.stats().odometryRejected, 10u);
	EXPECT_EQ(base.stats().odometryReceived, 0u);
	EXPECT_TRUE(base.odometryStale());
	EXPECT_FALSE(base.setVelocity(0.2, 0));
}

TEST_F(Ros1BaseTest, EmergencyStopStopsTheBaseAndLatches)
{
	EmulatedRobot robot(m_dir, kScene, kStart, {"--base-watchdog", "5"});
	Ros1Base base(options());
	waitForOdometry(base);
	ASSERT_TRUE(base.setVelocity(0.3, 0.2));
	std::this_thread::sleep_for(400ms);
	ASSERT_NEAR(m_truth->latest().v, 0.3, 1e-6);
	const auto stopped = SteadyClock::now();
	EXPECT_FALSE(base.setVelocity(std::nan(""), 0));  // refused, still moving
	EXPECT_TRUE(base.emergencyStop());
	EXPECT_TRUE(base.emergencyStopped());
	EXPECT_FALSE(base.setVelocity(0.3, 0));
	std::this_thread::sleep_for(300ms);
	const double after = stoppedAfter(m_truth->samples(), stopped);
	ASSERT_GE(after, 0) << "the base kept moving";
	EXPECT_LT(after, 0.1);
	EXPECT_EQ(m_truth->latest().v, 0);
	base.resetEmergencyStop();
	EXPECT_TRUE(base.setVelocity(0.3, 0));
	base.stop();
}

TEST_F(Ros1BaseTest, DrivesTheEmulatedBaseAndOdometryFollowsWithinTheSceneDrift)
{
	const Scene scene = SceneLoader::loadFile(kScene);
	EmulatedRobot robot(m_dir, kScene, kStart);
	Ros1Base base(options());
	waitForOdometry(base);
	const auto truth0 = m_truth->latest();
	const auto odo0 = base.odometry();
	const auto received0 = base.stats().odometryReceived;
	const auto t0 = SteadyClock::now();

	const double v = 0.4, w = 0.1;
	std::vector<RobotBase::Odometry> moving;
	const auto tDrive = SteadyClock::now();
	while (since(tDrive) < 3.0)
	{
		ASSERT_TRUE(base.setVelocity(v, w));
		std::this_thread::sleep_for(100ms);
		if (since(tDrive) > 0.5) moving.push_back(base.odometry());
	}
	const double driven = since(tDrive);
	base.stop();
	std::this_thread::sleep_for(500ms);
	const double odometryRate =
	    (base.stats().odometryReceived - received0) / since(t0);

	// The first command moved the base within a few odometry periods.
	double commandLatency = -1;
	for (const auto& t : m_truth->samples())
		if (t.arrival > tDrive && t.v > 0)
		{
			commandLatency =
			    std::chrono::duration<double>(t.arrival - tDrive).count();
			break;
		}
	EXPECT_GE(commandLatency, 0);
	EXPECT_LT(commandLatency, 0.2);

	// Odometry carries the base's real velocities while moving.
	ASSERT_FALSE(moving.empty());
	for (const auto& o : moving)
	{
		EXPECT_NEAR(o.velocity.vx, v, 1e-6);
		EXPECT_NEAR(o.velocity.omega, w, 1e-6);
	}
	EXPECT_EQ(base.odometry().velocity.vx, 0);
	EXPECT_GT(odometryRate, 40) << "odometry messages per second";

	// The base drove v x (time commanded), within the commands' latency.
	const auto truth1 = m_truth->latest();
	const double trueDistance = std::hypot(
	    truth1.pose.x - truth0.pose.x, truth1.pose.y - truth0.pose.y);
	EXPECT_NEAR(trueDistance, v * driven, 0.06);
	EXPECT_NEAR(
	    mrpt::math::wrapToPi(truth1.pose.phi - truth0.pose.phi), w * driven,
	    0.03);

	// Odometry against the truth: within the scene's drift (3 sigma).
	const auto odo1 = base.odometry();
	const double odoDistance =
	    std::hypot(odo1.pose.x - odo0.pose.x, odo1.pose.y - odo0.pose.y);
	const double d = trueDistance;
	const auto& spec = scene.odometry;
	EXPECT_NEAR(
	    odoDistance, trueDistance, 3 * spec.transNoise * std::sqrt(d) + 0.01);
	const double headingError = mrpt::math::wrapToPi(
	    (odo1.pose.phi - odo0.pose.phi) - (truth1.pose.phi - truth0.pose.phi));
	EXPECT_NEAR(
	    headingError, spec.rotBiasPerM * d,
	    3 * spec.rotNoisePerM * std::sqrt(d) + 0.005);
	EXPECT_NEAR(odo1.distance - odo0.distance, odoDistance, 0.02);

	const auto counters = robot.finish();
	EXPECT_EQ(counters.value("collisions", -1), 0);
	EXPECT_GE(
	    counters.value("base_commands", 0), static_cast<int>(driven * 10) - 2);
	// The true trajectory file ends where the truth topic says.
	std::ifstream f(robot.trajectoryFile());
	double t, x, y, phi, vv, ww, lx = 0, ly = 0;
	int n = 0;
	while (f >> t >> x >> y >> phi >> vv >> ww)
	{
		lx = x;
		ly = y;
		n++;
	}
	EXPECT_GT(n, 100);
	EXPECT_NEAR(lx, truth1.pose.x, 0.01);
	EXPECT_NEAR(ly, truth1.pose.y, 0.01);
	std::cout << "[ figures ] drove " << trueDistance << " m true in " << driven
	          << " s; odometry " << odoDistance << " m, heading error "
	          << mrpt::RAD2DEG(headingError) << " deg; odometry rate "
	          << odometryRate << " Hz; the first command moved the base after "
	          << commandLatency << " s" << std::endl;
}

TEST_F(Ros1BaseTest, BaseStopsByItsOwnWatchdogWhenTheDriverIsKilled)
{
	EmulatedRobot robot(m_dir, kScene, kStart);
	ChildProcess driver(
	    {std::string(SEMNAV_BINARY_DIR) + "/tests/ros1_drive",
	     "semnav_driver_" + std::to_string(::getpid()), "0.3", "0"},
	    m_dir + "/driver.log");
	// Moving for a while, then the driver dies without a word.
	const auto t0 = SteadyClock::now();
	while (m_truth->latest().v < 0.29 && since(t0) < 15)
		std::this_thread::sleep_for(10ms);
	ASSERT_NEAR(m_truth->latest().v, 0.3, 1e-6)
	    << "the driver never moved the base";
	std::this_thread::sleep_for(500ms);
	const auto killed = SteadyClock::now();
	driver.kill();
	std::this_thread::sleep_for(1500ms);

	// The last command the driver sent before it died.
	SteadyClock::time_point lastCommand{};
	for (const auto& c : m_commands->commands())
		if (c.arrival < killed) lastCommand = c.arrival;
	ASSERT_NE(lastCommand, SteadyClock::time_point{}) << "no cmd_vel seen";
	const double afterKill = stoppedAfter(m_truth->samples(), killed);
	const double afterLast = stoppedAfter(m_truth->samples(), lastCommand);
	ASSERT_GE(afterKill, 0) << "the base kept moving";
	EXPECT_LT(afterKill, 0.5);
	EXPECT_LT(afterLast, 0.5);
	EXPECT_GT(afterLast, 0.2);  // it kept moving on the last command a while
	const auto counters = robot.finish();
	EXPECT_GE(counters.value("watchdog_stops", 0), 1);
	std::cout << "[ figures ] driver SIGKILLed: base speed 0 after "
	          << afterKill << " s (" << afterLast
	          << " s after its last cmd_vel; base watchdog 0.3 s, commands "
	             "every 0.1 s)"
	          << std::endl;
}

TEST_F(Ros1BaseTest, DestroyedWhileMovingItSendsAZeroCommand)
{
	EmulatedRobot robot(m_dir, kScene, kStart, {"--base-watchdog", "5"});
	auto base = std::make_unique<Ros1Base>(options());
	waitForOdometry(*base);
	ASSERT_TRUE(base->setVelocity(0.3, 0));
	std::this_thread::sleep_for(500ms);
	ASSERT_NEAR(m_truth->latest().v, 0.3, 1e-6);
	const auto destroyed = SteadyClock::now();
	base.reset();  // no stop(): the destructor's zero command
	std::this_thread::sleep_for(1000ms);
	const double after = stoppedAfter(m_truth->samples(), destroyed);
	ASSERT_GE(after, 0) << "the base kept moving";
	EXPECT_LT(after, 0.2);  // well before the base's 5 s watchdog
	const auto counters = robot.finish();
	EXPECT_EQ(counters.value("watchdog_stops", -1), 0);
	std::cout << "[ figures ] Ros1Base destroyed: base speed 0 after " << after
	          << " s" << std::endl;
}

TEST_F(Ros1BaseTest, StaleOdometryStopsTheBaseAndRefusesMotionUntilItReturns)
{
	EmulatedRobot robot(m_dir, kScene, kStart);
	Ros1Base base(options());
	waitForOdometry(base);
	ASSERT_TRUE(base.setVelocity(0.2, 0));
	std::this_thread::sleep_for(300ms);
	robot.process().signal(SIGSTOP);  // odometry stops (and the base with it)
	const auto paused = SteadyClock::now();
	while (!base.odometryStale() && since(paused) < 5)
	{
		base.keepAlive();
		std::this_thread::sleep_for(5ms);
	}
	const double staleAfter = since(paused);
	EXPECT_TRUE(base.odometryStale());
	EXPECT_LT(staleAfter, base.options().odometryTimeout + 0.1);
	std::this_thread::sleep_for(50ms);
	EXPECT_GE(base.stats().staleStops, 1u);
	EXPECT_FALSE(base.setVelocity(0.2, 0));
	EXPECT_GE(base.stats().refused, 1u);
	// A zero command went out within the timeout of the last odometry.
	bool zeroSent = false;
	for (const auto& c : m_commands->commands())
		if (c.arrival > paused && c.v == 0 && c.w == 0 &&
		    std::chrono::duration<double>(c.arrival - paused).count() <
		        base.options().odometryTimeout + 0.1)
			zeroSent = true;
	EXPECT_TRUE(zeroSent);

	robot.process().signal(SIGCONT);
	const auto resumed = SteadyClock::now();
	while (base.odometryStale() && since(resumed) < 5)
		std::this_thread::sleep_for(5ms);
	EXPECT_FALSE(base.odometryStale());
	// The stop sent while the emulator was paused reached it: it stands.
	std::this_thread::sleep_for(200ms);
	EXPECT_EQ(m_truth->latest().v, 0);
	EXPECT_TRUE(base.setVelocity(0.2, 0));
	base.stop();
	std::cout << "[ figures ] emulator paused: odometry stale after "
	          << staleAfter << " s (timeout " << base.options().odometryTimeout
	          << " s)" << std::endl;
}

TEST_F(Ros1BaseTest, SilentOdometryStopsTheMovingBaseWithinHalfASecond)
{
	// The emulator's odometry stops 1 s after the first cmd_vel, for 1.5 s;
	// the base itself goes on (its ground truth too).
	EmulatedRobot robot(
	    m_dir, kScene, kStart,
	    {"--odom-silent-at", "1", "--odom-silent-for", "1.5"});
	Ros1Base base(options());
	waitForOdometry(base);
	const auto t0 = SteadyClock::now();
	SteadyClock::time_point silence{}, staleSeen{}, resumedAt{};
	while (since(t0) < 5)
	{
		const bool accepted = base.setVelocity(0.3, 0);
		if (!accepted && silence == SteadyClock::time_point{})
		{
			staleSeen = SteadyClock::now();
			silence = staleSeen -
			          std::chrono::duration_cast<SteadyClock::duration>(
			              std::chrono::duration<double>(base.odometryAge()));
		}
		if (accepted && silence != SteadyClock::time_point{} &&
		    resumedAt == SteadyClock::time_point{})
			resumedAt = SteadyClock::now();
		std::this_thread::sleep_for(50ms);
	}
	base.stop();
	ASSERT_NE(silence, SteadyClock::time_point{})
	    << "odometry never went stale";
	const double staleAfter =
	    std::chrono::duration<double>(staleSeen - silence).count();
	const double stopAfter = stoppedAfter(m_truth->samples(), silence);
	EXPECT_LT(staleAfter, base.options().odometryTimeout + 0.1);
	ASSERT_GE(stopAfter, 0) << "the base kept moving";
	EXPECT_LT(stopAfter, 0.5);
	EXPECT_GE(base.stats().staleStops, 1u);
	// Odometry came back: motion accepted again, about 1.5 s later.
	ASSERT_NE(resumedAt, SteadyClock::time_point{})
	    << "motion never accepted again";
	EXPECT_NEAR(
	    std::chrono::duration<double>(resumedAt - silence).count(), 1.5, 0.3);
	const auto counters = robot.finish();
	EXPECT_EQ(counters.value("watchdog_stops", -1), 0);  // Ros1Base stopped it
	std::cout << "[ figures ] odometry silent: stale after " << staleAfter
	          << " s, base speed 0 after " << stopAfter
	          << " s (odometry_timeout_s " << base.options().odometryTimeout
	          << ")" << std::endl;
}

namespace
{
/** A fresh scan from MRPT's driver: the first after `after`. */
bool scanAfter(
    mrpt::hwdrivers::CSickLaserSerial& lms,
    mrpt::obs::CObservation2DRangeScan& obs, SteadyClock::time_point after)
{
	const auto end = SteadyClock::now() + 3s;
	while (SteadyClock::now() < end)
	{
		bool has = false, hw = false;
		lms.doProcessSimple(has, obs, hw);
		if (has && SteadyClock::now() > after + 100ms) return true;
	}
	return false;
}

/** Median |scan - scene cast from `pose` at tilt 0| over beams with both. */
double medianError(
    const mrpt::obs::CObservation2DRangeScan& obs,
    const SceneLineCaster& caster, const mrpt::math::TPose2D& pose)
{
	std::vector<double> bearings(obs.getScanSize());
	for (std::size_t i = 0; i < bearings.size(); i++)
		bearings[i] = -M_PI / 2 + i * M_PI / (bearings.size() - 1);
	const auto& spec = caster.spec();
	const auto truth = caster.cast(
	    pose, tiltedSensorPose(spec.mount, 0), bearings, spec.maxRange);
	std::vector<double> e;
	for (std::size_t i = 0; i < bearings.size(); i++)
		if (truth[i] > 0 && obs.getScanRangeValidity(i))
			e.push_back(std::abs(obs.getScanRange(i) - truth[i]));
	if (e.size() < bearings.size() / 2) return 1e9;
	std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
	return e[e.size() / 2];
}
}  // namespace

TEST_F(Ros1BaseTest, LaserRangesAreCastFromWhereTheBaseReallyStands)
{
	const Scene scene = SceneLoader::loadFile(kScene);
	const SceneLineCaster caster(scene);
	EmulatedRobot robot(m_dir, kScene, kStart);
	Ros1Base base(options());
	waitForOdometry(base);

	auto port = std::make_shared<MonitoredSerialPort>();
	mrpt::hwdrivers::CSickLaserSerial lms;
	lms.setSerialPort(robot.lmsPath());
	lms.setBaudRate(500000);
	lms.setMillimeterMode(true);
	lms.setScanResolution(50);
	lms.bindIO(port);
	ASSERT_NO_THROW(lms.initialize());
	mrpt::obs::CObservation2DRangeScan before, after;
	ASSERT_TRUE(scanAfter(lms, before, SteadyClock::now()));
	const auto poseBefore = m_truth->latest().pose;

	drive(base, 0.5, 0.3, 2.5);  // ~1.2 m on an arc
	std::this_thread::sleep_for(300ms);
	const auto poseAfter = m_truth->latest().pose;
	ASSERT_TRUE(scanAfter(lms, after, SteadyClock::now()));
	ASSERT_GT(
	    std::hypot(poseAfter.x - poseBefore.x, poseAfter.y - poseBefore.y),
	    1.0);

	const double noise = scene.sensor.rangeNoise;
	const double beforeFit = medianError(before, caster, poseBefore);
	const double afterFit = medianError(after, caster, poseAfter);
	const double afterVsOldPose = medianError(after, caster, poseBefore);
	EXPECT_LT(beforeFit, 3 * noise);
	EXPECT_LT(afterFit, 3 * noise);
	EXPECT_GT(afterVsOldPose, 0.1);  // the scan did change with the drive
	std::cout << "[ figures ] scan median |error|: before " << beforeFit
	          << " m, after " << afterFit << " m (vs the start pose "
	          << afterVsOldPose << " m)" << std::endl;
}

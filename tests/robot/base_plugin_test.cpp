/* semnav: semantic navigation from tilting-laser sweeps */
// RobotBasePlugin: the example driver (examples/robot-base-plugin, compiled
// by this suite as a MODULE library) loaded with dlopen and driven through
// RobotBase: commands move its odometry, its watchdog stops it within its
// period, the emergency stop latches, bad keys are one-line ConfigErrors;
// missing files, libraries that are no plugin, other ABIs or MRPTs and
// failing factories are one-line errors naming the file.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/datetime.h>
#include <semnav/common/Error.h>
#include <semnav/robot/RobotBasePlugin.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

using namespace semnav;

namespace
{
using SteadyClock = std::chrono::steady_clock;

const std::string examplePath = SEMNAV_EXAMPLE_BASE;

mrpt::config::CConfigFileMemory ini(const std::string& text)
{
	return mrpt::config::CConfigFileMemory(text);
}

/** The example at 100 Hz with a watchdog of `watchdog` s. */
std::shared_ptr<RobotBase> exampleBase(double watchdog = 0.5)
{
	RobotBasePlugin plugin(examplePath);
	return plugin.create(
	    ini("[ExampleBase]\nrate_hz = 100\nmax_speed_mps = 0.5\n"
	        "max_turn_rate_deg_s = 90\nwatchdog_s = " +
	        std::to_string(watchdog) + "\n"));
}

double secondsSince(SteadyClock::time_point t)
{
	return std::chrono::duration<double>(SteadyClock::now() - t).count();
}

void sleepFor(double s)
{
	std::this_thread::sleep_for(std::chrono::duration<double>(s));
}

/** Seconds until the base reports zero speed (polled every 2 ms); -1 when
 * it still moves after `limit` s. */
double secondsUntilStopped(const RobotBase& base, double limit)
{
	const auto start = SteadyClock::now();
	while (secondsSince(start) < limit)
	{
		const auto v = base.odometry().velocity;
		if (v.vx == 0 && v.omega == 0) return secondsSince(start);
		sleepFor(0.002);
	}
	return -1;
}

/** The message of the `E` that `f` throws ("" when none); one line. */
template <class E>
std::string errorOf(const std::function<void()>& f)
{
	try
	{
		f();
	}
	catch (const E& e)
	{
		const std::string what = e.what();
		EXPECT_EQ(what.find('\n'), std::string::npos) << what;
		return what;
	}
	ADD_FAILURE() << "no exception of the expected type";
	return "";
}

bool contains(const std::string& text, const std::string& part)
{
	return text.find(part) != std::string::npos;
}
}  // namespace

TEST(RobotBasePlugin, TheExampleLoadsAndItsNameIsItsSection)
{
	RobotBasePlugin plugin(examplePath);
	EXPECT_EQ(plugin.name(), "ExampleBase");
	EXPECT_EQ(plugin.path(), examplePath);
	auto base = plugin.create(ini(""));  // every key has a default
	EXPECT_DOUBLE_EQ(base->watchdogPeriod(), 0.3);
	auto other =
	    plugin.create(ini("[LeftBase]\nwatchdog_s = 0.7\n"), "LeftBase");
	EXPECT_DOUBLE_EQ(other->watchdogPeriod(), 0.7);
}

TEST(RobotBasePlugin, CommandsMoveTheExampleOdometry)
{
	auto base = exampleBase();
	const auto start = SteadyClock::now();
	ASSERT_TRUE(base->setVelocity(0.4, 0));
	sleepFor(0.3);
	base->keepAlive();
	sleepFor(0.3);
	auto odo = base->odometry();
	const double driven = 0.4 * secondsSince(start);
	std::cout << "odometry " << odo.pose.x << " m after " << driven
	          << " m commanded\n";
	// Within 50 ms of driving (odometry lags by one control period, more
	// when a loaded machine delays the base's thread).
	EXPECT_NEAR(odo.pose.x, driven, 0.4 * 0.05);
	EXPECT_NEAR(odo.pose.y, 0, 1e-9);
	EXPECT_NEAR(odo.distance, odo.pose.x, 1e-9);
	EXPECT_DOUBLE_EQ(odo.velocity.vx, 0.4);
	EXPECT_LT(mrpt::system::timeDifference(odo.time, mrpt::Clock::now()), 0.05)
	    << "odometry is not fresh";

	// A turn on the spot; commands beyond the limits are clamped.
	const double x = base->odometry().pose.x;
	const auto turnStart = SteadyClock::now();
	ASSERT_TRUE(base->setVelocity(0, 3.0));
	sleepFor(0.4);
	odo = base->odometry();
	EXPECT_DOUBLE_EQ(odo.velocity.omega, M_PI / 2);
	EXPECT_NEAR(odo.pose.phi, M_PI / 2 * secondsSince(turnStart), 0.06);
	EXPECT_NEAR(odo.pose.x, x, 1e-9);
	ASSERT_TRUE(base->setVelocity(9, 0));
	sleepFor(0.05);
	EXPECT_DOUBLE_EQ(base->odometry().velocity.vx, 0.5);
	EXPECT_FALSE(base->setVelocity(NAN, 0));
	ASSERT_TRUE(base->stop());
	EXPECT_GE(secondsUntilStopped(*base, 0.1), 0);
}

TEST(RobotBasePlugin, TheExampleWatchdogStopsItWithinItsPeriod)
{
	const double watchdog = 0.2;
	auto base = exampleBase(watchdog);
	// keepAlive() holds the command for longer than the watchdog.
	ASSERT_TRUE(base->setVelocity(0.3, 0.1));
	for (int i = 0; i < 8; i++)
	{
		sleepFor(0.05);
		base->keepAlive();
	}
	ASSERT_DOUBLE_EQ(base->odometry().velocity.vx, 0.3) << "stopped early";
	// Then silence: stopped after the period, within one control period
	// (10 ms) and what a loaded machine adds.
	const double stoppedAfter = secondsUntilStopped(*base, 1.0);
	ASSERT_GE(stoppedAfter, 0) << "the watchdog did not stop the base";
	std::cout << "watchdog " << watchdog << " s: stopped after " << stoppedAfter
	          << " s of silence\n";
	EXPECT_GT(stoppedAfter, watchdog - 0.01);
	EXPECT_LT(stoppedAfter, watchdog + 0.05);
	const double x = base->odometry().pose.x;
	sleepFor(0.1);
	EXPECT_DOUBLE_EQ(base->odometry().pose.x, x) << "moves after the stop";
}

TEST(RobotBasePlugin, TheExampleEmergencyStopLatchesAndRefusesMotion)
{
	auto base = exampleBase();
	ASSERT_TRUE(base->setVelocity(0.3, 0));
	sleepFor(0.05);
	ASSERT_TRUE(base->emergencyStop());
	EXPECT_TRUE(base->emergencyStopped());
	EXPECT_GE(secondsUntilStopped(*base, 0.05), 0);
	EXPECT_FALSE(base->setVelocity(0.3, 0));
	base->keepAlive();
	const double x = base->odometry().pose.x;
	sleepFor(0.1);
	EXPECT_DOUBLE_EQ(base->odometry().pose.x, x);
	EXPECT_TRUE(base->emergencyStopped()) << "the stop did not latch";
	base->resetEmergencyStop();
	EXPECT_FALSE(base->emergencyStopped());
	EXPECT_TRUE(base->setVelocity(0.3, 0));
	sleepFor(0.05);
	EXPECT_GT(base->odometry().pose.x, x);
}

TEST(RobotBasePlugin, ABadExampleKeyIsAConfigErrorNamingFileAndKey)
{
	RobotBasePlugin plugin(examplePath);
	std::string what = errorOf<ConfigError>(
	    [&] { plugin.create(ini("[ExampleBase]\nmax_sped_mps = 1\n")); });
	EXPECT_TRUE(contains(what, examplePath)) << what;
	EXPECT_TRUE(contains(what, "[ExampleBase] max_sped_mps")) << what;
	EXPECT_TRUE(contains(what, "max_speed_mps")) << what;  // the known ones
	what = errorOf<ConfigError>(
	    [&] { plugin.create(ini("[ExampleBase]\nrate_hz = 0\n")); });
	EXPECT_TRUE(contains(what, "rate_hz")) << what;
}

TEST(RobotBasePlugin, AMissingFileIsAnIoErrorNamingIt)
{
	const std::string missing = "/nonexistent/libsemnav_no_base.so";
	std::string what =
	    errorOf<IoError>([&] { RobotBasePlugin plugin(missing); });
	EXPECT_EQ(what, "robot base plugin " + missing + ": no such file");
	// A bare name is searched as dlopen does.
	what = errorOf<IoError>(
	    [&] { RobotBasePlugin plugin("libsemnav_no_base.so"); });
	EXPECT_TRUE(contains(what, "libsemnav_no_base.so: cannot load:")) << what;
}

TEST(RobotBasePlugin, ALibraryThatIsNoPluginIsRefused)
{
	const std::string notPlugin = SEMNAV_TEST_NOT_A_PLUGIN;
	std::string what =
	    errorOf<Error>([&] { RobotBasePlugin plugin(notPlugin); });
	EXPECT_TRUE(contains(what, notPlugin)) << what;
	EXPECT_TRUE(contains(what, "not a semnav robot base plugin")) << what;
	EXPECT_TRUE(contains(what, "semnav_robot_base_abi")) << what;
	// A file that is no shared library at all.
	const std::string source = SEMNAV_SOURCE_DIR "/README.md";
	what = errorOf<IoError>([&] { RobotBasePlugin plugin(source); });
	EXPECT_TRUE(contains(what, source + ": cannot load:")) << what;
}

TEST(RobotBasePlugin, AnotherAbiOrMrptIsRefused)
{
	const std::string wrongAbi = SEMNAV_TEST_WRONG_ABI_PLUGIN;
	std::string what =
	    errorOf<Error>([&] { RobotBasePlugin plugin(wrongAbi); });
	EXPECT_EQ(
	    what, "robot base plugin " + wrongAbi + ": plugin ABI " +
	              std::to_string(SEMNAV_ROBOT_BASE_ABI + 1) +
	              ", this semnav needs " +
	              std::to_string(SEMNAV_ROBOT_BASE_ABI) +
	              " (rebuild the plugin against this semnav)");
	const std::string wrongMrpt = SEMNAV_TEST_WRONG_MRPT_PLUGIN;
	what = errorOf<Error>([&] { RobotBasePlugin plugin(wrongMrpt); });
	EXPECT_TRUE(contains(what, wrongMrpt)) << what;
	EXPECT_TRUE(contains(what, "built against MRPT 2.6")) << what;
	EXPECT_TRUE(contains(what, "uses MRPT 2.5")) << what;
}

TEST(RobotBasePlugin, AFailingFactoryIsOneLineWithItsMessage)
{
	RobotBasePlugin plugin(SEMNAV_TEST_FAILING_PLUGIN);
	EXPECT_EQ(plugin.name(), "TestBase");
	std::string what = errorOf<Error>([&] { plugin.create(ini("")); });
	EXPECT_TRUE(contains(what, plugin.path())) << what;
	EXPECT_TRUE(contains(
	    what, "making [TestBase]: no motor controller on /dev/ttyUSB7"))
	    << what;
	what = errorOf<Error>([&] { plugin.create(ini(""), "ReturnsNull"); });
	EXPECT_TRUE(contains(what, "returned no base")) << what;
}

TEST(RobotBasePlugin, TheLibraryStaysLoadedWhileItsBaseLives)
{
	const auto loaded = []
	{
		void* h = dlopen(examplePath.c_str(), RTLD_NOW | RTLD_NOLOAD);
		if (h) dlclose(h);
		return h != nullptr;
	};
	ASSERT_FALSE(loaded());
	std::shared_ptr<RobotBase> base = exampleBase();  // the plugin is gone
	EXPECT_TRUE(loaded());
	ASSERT_TRUE(base->setVelocity(0.2, 0));
	sleepFor(0.1);
	EXPECT_GT(base->odometry().pose.x, 0.01) << "its thread does not run";
	base.reset();
	EXPECT_FALSE(loaded()) << "unloaded only with its last base";
}

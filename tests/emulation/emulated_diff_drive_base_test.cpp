/* semnav: semantic navigation from tilting-laser sweeps */
// The emulated differential-drive base in real time, without ROS: it moves
// as commanded, stops itself by its watchdog, counts collisions, writes its
// true trajectory and leaves MRPT's clock on wall time.
#include <gtest/gtest.h>
#include <semnav/emulation/EmulatedDiffDriveBase.h>
#include <semnav/sim/SceneLoader.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>

using namespace semnav;
using namespace std::chrono_literals;
using SteadyClock = std::chrono::steady_clock;

namespace
{
Scene rectRoom()
{
	return SceneLoader::loadFile(
	    std::string(SEMNAV_SOURCE_DIR) + "/datasets/nav-trials/rect_room.yaml");
}

/** Commands (v, w) every 0.1 s for `seconds`; returns the time taken. */
double drive(EmulatedDiffDriveBase& base, double v, double w, double seconds)
{
	const auto t0 = SteadyClock::now();
	while (std::chrono::duration<double>(SteadyClock::now() - t0).count() <
	       seconds)
	{
		base.command(v, w);
		std::this_thread::sleep_for(100ms);
	}
	return std::chrono::duration<double>(SteadyClock::now() - t0).count();
}
}  // namespace

TEST(EmulatedDiffDriveBase, MovesAsCommandedAndStopsByItsWatchdog)
{
	EmulatedDiffDriveBase::Options o;
	o.watchdog = 0.3;
	o.trajectoryFile =
	    "/tmp/semnav_base_trajectory_" + std::to_string(::getpid()) + ".txt";
	EmulatedDiffDriveBase base(rectRoom(), {1.5, 1.5, 0}, o);
	EXPECT_EQ(mrpt::Clock::getActiveClock(), mrpt::Clock::Realtime);
	base.start();
	const double t = drive(base, 0.5, 0, 1.0);
	const auto moving = base.state();
	EXPECT_NEAR(moving.velocity.vx, 0.5, 1e-9);
	// Moved for the commanded time, give or take a step and the sleeps.
	EXPECT_NEAR(moving.truePose.x - 1.5, 0.5 * t, 0.1);

	const auto silent = SteadyClock::now();
	while (base.state().velocity.vx != 0 && SteadyClock::now() - silent < 2s)
		std::this_thread::sleep_for(5ms);
	const double stopAfter =
	    std::chrono::duration<double>(SteadyClock::now() - silent).count();
	EXPECT_EQ(base.state().velocity.vx, 0);
	EXPECT_LT(stopAfter, o.watchdog + 0.15);  // loaded machines: slack
	EXPECT_GT(stopAfter, o.watchdog - 0.1 - o.step);
	const auto stopped = base.state();
	EXPECT_EQ(stopped.watchdogStops, 1);
	EXPECT_EQ(stopped.collisions, 0);
	base.stop();

	std::ifstream f(o.trajectoryFile);
	double time, x, y, phi, v, w, lastX = 0;
	int n = 0;
	while (f >> time >> x >> y >> phi >> v >> w)
	{
		lastX = x;
		n++;
	}
	EXPECT_GT(n, static_cast<int>((t + stopAfter) / o.step * 0.8));
	EXPECT_NEAR(lastX, stopped.truePose.x, 1e-9);
	std::remove(o.trajectoryFile.c_str());
}

TEST(EmulatedDiffDriveBase, AWallStopsItAndCountsOneCollision)
{
	EmulatedDiffDriveBase::Options o;
	EmulatedDiffDriveBase base(rectRoom(), {7.2, 2.5, 0}, o);
	base.start();
	drive(base, 0.5, 0, 1.5);  // 0.75 m toward the east wall (x = 7.9)
	const auto s = base.state();
	base.stop();
	EXPECT_EQ(s.collisions, 1);
	EXPECT_LT(s.truePose.x, 7.9 - o.robot.robotRadius);
	EXPECT_GT(s.truePose.x, 7.9 - o.robot.robotRadius - 0.1);
}

/* semnav: semantic navigation from tilting-laser sweeps */
// SweepObstacles: the obstacles of the latest stop's sweeps (points
// between floor and robot height, within range, thinned), handed over in
// the robot frame of now through the odometry since the sweep; too old or
// none: blocked.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <semnav/common/Error.h>
#include <semnav/robot/RobotBase.h>
#include <semnav/robot/SweepObstacles.h>
#include <semnav/scan/Sweep.h>

#include <cmath>
#include <vector>

#include "../common/SavedAndLoaded.h"

using namespace semnav;

namespace
{
/** A base whose odometry the test sets. */
class StubBase : public RobotBase
{
public:
	bool setVelocity(double, double) override { return true; }
	void keepAlive() override {}
	bool stop() override { return true; }
	bool emergencyStop() override { return true; }
	void resetEmergencyStop() override {}
	bool emergencyStopped() const override { return false; }
	Odometry odometry() const override { return odo; }
	double watchdogPeriod() const override { return 1.0; }

	void at(double x, double y, double phi, double t)
	{
		odo.pose = {x, y, phi};
		odo.time = mrpt::Clock::fromDouble(t);
	}
	Odometry odo;
};

struct Beam
{
	double height, bearing, range;
	bool valid = true;
};

/** One row per beam: a horizontal scanner at the beam's height, so pixel
 * (r, 0) is the point (range cos bearing, range sin bearing, height) in the
 * robot frame. */
Sweep sweepOf(
    const std::vector<Beam>& beams, const mrpt::poses::CPose2D& odometry,
    double time)
{
	Sweep s(beams.size(), 1);
	for (std::size_t r = 0; r < beams.size(); r++)
	{
		// Bearing as the scanner's yaw (one column at phi = 0).
		s.setRow(
		    r, 0,
		    mrpt::poses::CPose3D(
		        0, 0, beams[r].height, beams[r].bearing, 0, 0));
		s.setRange(r, 0, static_cast<float>(beams[r].range), beams[r].valid);
	}
	s.setPhis({0.0});
	s.setOdometry(odometry);
	s.setTimestamp(mrpt::Clock::fromDouble(time));
	return s;
}

SweepObstacles::TOptions options()
{
	SweepObstacles::TOptions o;
	o.minHeight = 0.05;
	o.maxHeight = 1.0;
	o.maxRange = 5.0;
	o.maxAge = 10.0;
	o.cell = 0.05;
	return o;
}

void expectXY(const mrpt::math::TPoint3D& p, double x, double y)
{
	EXPECT_NEAR(p.x, x, 1e-5);
	EXPECT_NEAR(p.y, y, 1e-5);
}

std::vector<mrpt::math::TPoint3D> sensed(SweepObstacles& obs, bool& ok)
{
	mrpt::maps::CSimplePointsMap m;
	mrpt::Clock::time_point t{};
	ok = obs.sense(m, t);
	std::vector<mrpt::math::TPoint3D> pts;
	for (std::size_t i = 0; i < m.size(); i++)
	{
		float x, y, z;
		m.getPoint(i, x, y, z);
		pts.push_back({x, y, z});
	}
	return pts;
}
}  // namespace

TEST(SweepObstacles, NothingBeforeTheFirstSweepCountsAsBlocked)
{
	StubBase base;
	base.at(0, 0, 0, 100);
	SweepObstacles obs(base, options());
	bool ok = true;
	EXPECT_TRUE(sensed(obs, ok).empty());
	EXPECT_FALSE(ok);
	EXPECT_EQ(obs.size(), 0u);
}

TEST(SweepObstacles, KeepsPointsBetweenFloorAndRobotHeightWithinRange)
{
	StubBase base;
	base.at(0, 0, 0, 100);
	SweepObstacles obs(base, options());
	obs.update(sweepOf(
	    {{0.5, 0, 2.0},
	     {0.02, 0, 2.0},               // floor
	     {1.5, 0, 2.0},                // above the robot
	     {0.5, M_PI / 2, 6.0},         // out of range
	     {0.5, M_PI / 2, 3.0, false},  // no return
	     {0.9, M_PI / 2, 4.9}},
	    mrpt::poses::CPose2D(0, 0, 0), 100));
	ASSERT_EQ(obs.size(), 2u);
	bool ok = false;
	const auto pts = sensed(obs, ok);
	EXPECT_TRUE(ok);
	ASSERT_EQ(pts.size(), 2u);
	expectXY(pts[0], 2.0, 0.0);
	EXPECT_NEAR(pts[0].z, 0.5, 1e-5);
	expectXY(pts[1], 0.0, 4.9);
	EXPECT_NEAR(pts[1].z, 0.9, 1e-5);
}

TEST(SweepObstacles, PointsOfOneCellAreThinnedToOne)
{
	StubBase base;
	SweepObstacles obs(base, options());
	// 2 mm apart, and 0.5 m apart.
	obs.update(sweepOf(
	    {{0.5, 0, 2.0}, {0.5, 0.001, 2.0}, {0.5, 0.25, 2.0}},
	    mrpt::poses::CPose2D(), 0));
	EXPECT_EQ(obs.size(), 2u);
}

TEST(SweepObstacles, MovesPointsIntoTheRobotFrameOfNowByOdometry)
{
	StubBase base;
	SweepObstacles obs(base, options());
	// Swept at odometry (1, 2, 90 deg): a point 2 m ahead is at (1, 4).
	obs.update(
	    sweepOf({{0.5, 0, 2.0}}, mrpt::poses::CPose2D(1, 2, M_PI / 2), 100));
	// One metre further ahead it is 1 m ahead...
	base.at(1, 3, M_PI / 2, 101);
	bool ok = false;
	auto pts = sensed(obs, ok);
	EXPECT_TRUE(ok);
	ASSERT_EQ(pts.size(), 1u);
	expectXY(pts[0], 1.0, 0.0);
	EXPECT_NEAR(pts[0].z, 0.5, 1e-5);
	// ...and after turning left by 90 deg on the spot, 1 m to the right.
	base.at(1, 3, M_PI, 102);
	pts = sensed(obs, ok);
	ASSERT_EQ(pts.size(), 1u);
	expectXY(pts[0], 0.0, -1.0);
}

TEST(SweepObstacles, SensedAtTheSweepsTimeAndTooOldCountsAsBlocked)
{
	StubBase base;
	SweepObstacles obs(base, options());
	obs.update(sweepOf({{0.5, 0, 2.0}}, mrpt::poses::CPose2D(), 100));
	mrpt::maps::CSimplePointsMap m;
	mrpt::Clock::time_point t{};
	base.at(0, 0, 0, 100 + 9.5);
	EXPECT_TRUE(obs.sense(m, t));
	EXPECT_NEAR(mrpt::Clock::toDouble(t), 100, 1e-6);
	EXPECT_EQ(m.size(), 1u);
	base.at(0, 0, 0, 100 + 10.5);
	EXPECT_FALSE(obs.sense(m, t));
	EXPECT_EQ(m.size(), 0u);
	// A new sweep is fresh again.
	obs.update(sweepOf({{0.5, 0, 3.0}}, mrpt::poses::CPose2D(), 110));
	EXPECT_TRUE(obs.sense(m, t));
	EXPECT_NEAR(mrpt::Clock::toDouble(t), 110, 1e-6);
}

TEST(SweepObstacles, SweepsOfOneStopAddUpAndTheNextStopReplacesThem)
{
	StubBase base;
	SweepObstacles obs(base, options());
	// A start: sweeps ahead, then after turning on the spot by 90 deg
	// (what is now ahead was on the left).
	obs.update(sweepOf({{0.5, 0, 2.0}}, mrpt::poses::CPose2D(1, 1, 0), 100));
	obs.update(
	    sweepOf({{0.5, 0, 3.0}}, mrpt::poses::CPose2D(1, 1, M_PI / 2), 103));
	base.at(1, 1, M_PI / 2, 104);
	bool ok = false;
	auto pts = sensed(obs, ok);
	EXPECT_TRUE(ok);
	ASSERT_EQ(pts.size(), 2u);
	// The first sweep's point is now on the right, the second's ahead.
	expectXY(pts[0], 0.0, -2.0);
	expectXY(pts[1], 3.0, 0.0);
	// The same point seen twice is kept once.
	obs.update(sweepOf(
	    {{0.5, -M_PI / 2, 2.0}}, mrpt::poses::CPose2D(1, 1, M_PI / 2), 106));
	EXPECT_EQ(obs.size(), 2u);
	// A sweep one metre further on replaces them.
	obs.update(
	    sweepOf({{0.5, 0, 1.5}}, mrpt::poses::CPose2D(1, 2, M_PI / 2), 110));
	base.at(1, 2, M_PI / 2, 110);
	pts = sensed(obs, ok);
	ASSERT_EQ(pts.size(), 1u);
	expectXY(pts[0], 1.5, 0.0);
}

TEST(SweepObstacles, OptionsRoundTripAndRejectOutOfRange)
{
	SweepObstacles::TOptions o = options();
	o.maxAge = 3.5;
	o.maxRange = 2.5;
	const auto back = test::savedAndLoaded(o, "SweepObstacles");
	EXPECT_DOUBLE_EQ(back.maxAge, 3.5);
	EXPECT_DOUBLE_EQ(back.maxRange, 2.5);
	EXPECT_DOUBLE_EQ(back.minHeight, o.minHeight);
	mrpt::config::CConfigFileMemory mem;
	mem.write("SweepObstacles", "max_age_s", "0");
	SweepObstacles::TOptions bad;
	EXPECT_THROW(bad.loadFromConfigFile(mem, "SweepObstacles"), ConfigError);
}

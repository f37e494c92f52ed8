/* semnav: semantic navigation from tilting-laser sweeps */
// SimulatedRobot behind the robot seams, as MRPT's navigator sees it through
// RobotNavInterface: the horizontal scan sees the scene, contacts stop the
// robot and are counted once, time is simulated (MRPT's clock follows), the
// watchdog stops a base left without commands.
#include <gtest/gtest.h>
#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <semnav/nav/RobotNavInterface.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulatedRobot.h>

#include <cmath>

using namespace semnav;

namespace
{
/** A 6 x 4 m room with a box whose west face is at x = 4. */
Scene room()
{
	return SceneLoader::parse(
	    "name: room\n"
	    "bounds: [0, 0, 6, 4]\n"
	    "objects:\n"
	    "  - {label: wall, box: {center: [3, -0.05, 1], size: [6, 0.1, 2]}}\n"
	    "  - {label: wall, box: {center: [3, 4.05, 1], size: [6, 0.1, 2]}}\n"
	    "  - {label: wall, box: {center: [-0.05, 2, 1], size: [0.1, 4, 2]}}\n"
	    "  - {label: wall, box: {center: [6.05, 2, 1], size: [0.1, 4, 2]}}\n"
	    "  - {label: obstacle, box: {center: [4.5, 2, 0.4], size: [1, 1, "
	    "0.8]}}\n"
	    "trajectory: [[1, 2, 0]]\n",
	    "room");
}

mrpt::kinematics::CVehicleVelCmd_DiffDriven cmd(double v, double w)
{
	mrpt::kinematics::CVehicleVelCmd_DiffDriven c;
	c.lin_vel = v;
	c.ang_vel = w;
	return c;
}

/** The simulated robot and MRPT's interface over its seams (reporting the
 * localized pose: the odometry until an estimate comes). */
struct Rig
{
	Rig(const Scene& s, const SimulatedRobot::TOptions& o,
	    const mrpt::math::TPose2D& start)
	    : robot(s, o, start),
	      nav(robot.base(), robot.localizedPose(), robot.obstacles(), robot,
	          RobotNavInterface::TOptions())
	{
		nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	}
	void simulate(int steps)
	{
		for (int i = 0; i < steps; i++) robot.waitFor(0.1);
	}
	const mrpt::math::TPose2D& pose() const { return robot.base().pose(); }
	SimulatedRobot robot;
	RobotNavInterface nav;
};
}  // namespace

TEST(SimulatedRobot, ScanSeesTheSceneNotTheMap)
{
	const Scene s = room();
	SimulatedRobot::TOptions o;
	o.scanMaxRange = 10;
	Rig rig(s, o, {1.0, 2.0, 0.0});
	mrpt::maps::CSimplePointsMap obs;
	mrpt::system::TTimeStamp t;
	ASSERT_TRUE(rig.nav.senseObstacles(obs, t));
	EXPECT_EQ(obs.size(), o.scanHeights.size() * o.scanBeams);  // closed room
	// Straight ahead (robot frame +x) at the low plane: the box at 3 m.
	double best = 1e9;
	for (std::size_t i = 0; i < obs.size(); i++)
	{
		float x, y, z;
		obs.getPoint(i, x, y, z);
		if (std::abs(y) < 0.01 && x > 0 && std::abs(z - 0.15) < 1e-3)
			best = std::min(best, static_cast<double>(x));
	}
	EXPECT_NEAR(best, 3.0, 1e-3);
}

TEST(SimulatedRobot, ContactStopsTheRobotAndCountsOnce)
{
	const Scene s = room();
	SimulatedRobot::TOptions o;
	Rig rig(s, o, {3.0, 2.0, 0.0});
	const SimulatedBase& base = rig.robot.base();
	EXPECT_FALSE(base.inCollision({3.0, 2.0, 0.0}));
	EXPECT_TRUE(base.inCollision({3.8, 2.0, 0.0}));  // disc reaches x = 4.05
	EXPECT_TRUE(base.inCollision({4.2, 2.0, 0.0}));  // centre inside
	// (Keeping the command alive: the base's watchdog would stop it.)
	rig.nav.changeSpeeds(cmd(0.5, 0));
	for (int i = 0; i < 60; i++, rig.nav.changeSpeedsNOP()) rig.simulate(1);
	EXPECT_EQ(base.collisions(), 1);
	EXPECT_LT(rig.pose().x, 4.0 - o.robotRadius + 1e-6);
	EXPECT_GT(rig.pose().x, 3.6);
	// Backing off and hitting again is a second contact.
	rig.nav.changeSpeeds(cmd(-0.5, 0));
	rig.simulate(10);
	rig.nav.changeSpeeds(cmd(0.5, 0));
	for (int i = 0; i < 30; i++, rig.nav.changeSpeedsNOP()) rig.simulate(1);
	EXPECT_EQ(base.collisions(), 2);
	EXPECT_EQ(base.collisionPoses().size(), 2u);
	EXPECT_EQ(base.watchdogStops(), 0);
}

TEST(SimulatedRobot, WatchdogStopsABaseLeftWithoutCommands)
{
	const Scene s = room();
	SimulatedRobot::TOptions o;
	o.watchdog = 0.5;
	Rig rig(s, o, {1.0, 2.0, 0.0});
	rig.nav.changeSpeeds(cmd(0.4, 0));
	rig.simulate(30);
	// It ran for the watchdog period (plus at most one step), then stopped.
	EXPECT_EQ(rig.robot.base().watchdogStops(), 1);
	EXPECT_GT(rig.pose().x, 1.0 + 0.4 * 0.5 - 0.01);
	EXPECT_LT(rig.pose().x, 1.0 + 0.4 * 0.7);
	// An emergency stop latches: commands are refused until reset.
	ASSERT_TRUE(rig.robot.base().emergencyStop());
	EXPECT_FALSE(rig.nav.changeSpeeds(cmd(0.4, 0)));
	const double x = rig.pose().x;
	rig.simulate(5);
	EXPECT_NEAR(rig.pose().x, x, 1e-9);
	rig.robot.base().resetEmergencyStop();
	EXPECT_TRUE(rig.nav.changeSpeeds(cmd(0.4, 0)));
	rig.simulate(3);
	EXPECT_GT(rig.pose().x, x + 0.05);
}

TEST(SimulatedRobot, TimeIsSimulated)
{
	const auto before = mrpt::Clock::getActiveClock();
	{
		const Scene s = room();
		Rig rig(s, SimulatedRobot::TOptions(), {1.0, 2.0, 0.0});
		EXPECT_EQ(mrpt::Clock::getActiveClock(), mrpt::Clock::Simulated);
		rig.simulate(25);
		// (MRPT's vehicle integrates in 0.5 ms firmware steps.)
		const double t = rig.robot.now();
		EXPECT_NEAR(t, 2.5, 0.02);
		EXPECT_NEAR(rig.nav.getNavigationTime(), t, 1e-9);
		EXPECT_NEAR(
		    mrpt::Clock::toDouble(mrpt::Clock::now()) -
		        mrpt::Clock::toDouble(SimulatedBase::timestampOf(0)),
		    t, 1e-5);
		// Turning on the spot toward a heading behind.
		rig.nav.changeSpeeds(*rig.nav.getAlignCmd(M_PI / 2));
		rig.simulate(10);
		EXPECT_GT(rig.pose().phi, 0.3);
		EXPECT_NEAR(rig.pose().x, 1.0, 1e-6);
	}
	EXPECT_EQ(mrpt::Clock::getActiveClock(), before);
}

TEST(SimulatedRobot, ReportsTheOdometryUntilGivenAnEstimate)
{
	const Scene s = room();
	Rig rig(s, SimulatedRobot::TOptions(), {1.0, 2.0, 0.0});
	SimulatedRobot& robot = rig.robot;
	mrpt::math::TPose2D pose, odo;
	mrpt::math::TTwist2D vel;
	mrpt::system::TTimeStamp t;
	std::string frame;
	rig.nav.changeSpeeds(cmd(0.3, 0));
	rig.simulate(10);
	ASSERT_TRUE(rig.nav.getCurrentPoseAndSpeeds(pose, vel, t, odo, frame));
	// Noise-free odometry follows the truth.
	EXPECT_NEAR(pose.x, rig.pose().x, 1e-9);
	EXPECT_NEAR(pose.y, rig.pose().y, 1e-9);
	EXPECT_NEAR(vel.vx, 0.3, 1e-3);
	EXPECT_FALSE(robot.localizedPose().hasEstimate());
	EXPECT_NEAR(odo.x, rig.pose().x, 1e-9);
	EXPECT_NEAR(robot.base().odometry().distance, rig.pose().x - 1.0, 1e-9);

	// The robot now believes it is 1 m further north and facing north: it
	// reports that belief moved by its odometry (forward = +y), velocity
	// in the belief's heading; the truth goes on east.
	const mrpt::math::TPose2D truthBefore = rig.pose();
	robot.localizedPose().setEstimate(
	    {truthBefore.x, truthBefore.y + 1, M_PI / 2},
	    robot.base().odometry().pose);
	rig.nav.changeSpeedsNOP();
	rig.simulate(10);
	ASSERT_TRUE(rig.nav.getCurrentPoseAndSpeeds(pose, vel, t, odo, frame));
	const double moved = rig.pose().x - truthBefore.x;
	EXPECT_GT(moved, 0.25);
	EXPECT_NEAR(rig.pose().y, 2.0, 1e-6);
	EXPECT_NEAR(pose.x, truthBefore.x, 1e-6);
	EXPECT_NEAR(pose.y, truthBefore.y + 1 + moved, 1e-6);
	EXPECT_NEAR(pose.phi, M_PI / 2, 1e-6);
	EXPECT_NEAR(vel.vx, 0, 1e-3);
	EXPECT_NEAR(vel.vy, 0.3, 1e-3);
	EXPECT_EQ(frame, "map");
	EXPECT_TRUE(robot.localizedPose().hasEstimate());
	EXPECT_EQ(robot.estimatedTrajectory().size(), 11u);
	// The scan is still taken at the true pose (the box face at x = 4).
	mrpt::maps::CSimplePointsMap pts;
	ASSERT_TRUE(rig.nav.senseObstacles(pts, t));
	float x, y, z;
	double ahead = 1e9;
	for (std::size_t i = 0; i < pts.size(); i++)
	{
		pts.getPoint(i, x, y, z);
		if (std::abs(y) < 0.05 && x > 0) ahead = std::min<double>(ahead, x);
	}
	EXPECT_NEAR(ahead, 4.0 - rig.pose().x, 0.05);
}

TEST(SimulatedRobot, OdometryNoiseDriftsTheHeadingByTheBias)
{
	const Scene s = room();
	const RayCaster caster(s);
	SimulatedBase base(caster, SimulatedRobot::TOptions(), {0.5, 1.0, 0.0});
	OdometrySpec spec;
	spec.transNoise = 0;
	spec.rotNoisePerM = 0;
	spec.rotBiasPerM = 3.5 * M_PI / 180;
	base.setOdometryNoise(spec, 3);
	for (int i = 0; i < 75; i++)  // ~3 m east
	{
		base.setVelocity(0.4, 0);
		base.simulate(0.1);
	}
	const double d = base.pose().x - 0.5;
	ASSERT_GT(d, 2.5);
	EXPECT_NEAR(base.pose().phi, 0, 1e-9);
	const RobotBase::Odometry odo = base.odometry();
	EXPECT_NEAR(odo.pose.phi, spec.rotBiasPerM * d, 1e-6);
	EXPECT_NEAR(odo.distance, d, 1e-6);
	// The odometry curves left: it ends north of the truth.
	EXPECT_GT(odo.pose.y, base.pose().y + 0.1);
}

/* semnav: semantic navigation from tilting-laser sweeps */
// SimulatedRobot: the horizontal scan sees the scene, contacts stop the
// robot and are counted once, time is simulated (MRPT's clock follows).
#include <gtest/gtest.h>
#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <semnav/nav/SimulatedRobot.h>
#include <semnav/sim/SceneLoader.h>

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
}  // namespace

TEST(SimulatedRobot, ScanSeesTheSceneNotTheMap)
{
	const Scene s = room();
	SimulatedRobot::TOptions o;
	o.scanMaxRange = 10;
	SimulatedRobot robot(s, o, {1.0, 2.0, 0.0});
	mrpt::maps::CSimplePointsMap obs;
	mrpt::system::TTimeStamp t;
	ASSERT_TRUE(robot.senseObstacles(obs, t));
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
	SimulatedRobot robot(s, o, {3.0, 2.0, 0.0});
	EXPECT_FALSE(robot.inCollision({3.0, 2.0, 0.0}));
	EXPECT_TRUE(robot.inCollision({3.8, 2.0, 0.0}));  // disc reaches x = 4.05
	EXPECT_TRUE(robot.inCollision({4.2, 2.0, 0.0}));  // centre inside
	robot.changeSpeeds(cmd(0.5, 0));
	for (int i = 0; i < 60; i++) robot.simulate(0.1);
	EXPECT_EQ(robot.collisions(), 1);
	EXPECT_LT(robot.pose().x, 4.0 - o.robotRadius + 1e-6);
	EXPECT_GT(robot.pose().x, 3.6);
	// Backing off and hitting again is a second contact.
	robot.changeSpeeds(cmd(-0.5, 0));
	for (int i = 0; i < 10; i++) robot.simulate(0.1);
	robot.changeSpeeds(cmd(0.5, 0));
	for (int i = 0; i < 30; i++) robot.simulate(0.1);
	EXPECT_EQ(robot.collisions(), 2);
	EXPECT_EQ(robot.collisionPoses().size(), 2u);
}

TEST(SimulatedRobot, TimeIsSimulated)
{
	const auto before = mrpt::Clock::getActiveClock();
	{
		const Scene s = room();
		SimulatedRobot robot(s, SimulatedRobot::TOptions(), {1.0, 2.0, 0.0});
		EXPECT_EQ(mrpt::Clock::getActiveClock(), mrpt::Clock::Simulated);
		for (int i = 0; i < 25; i++) robot.simulate(0.1);
		// (MRPT's vehicle integrates in 0.5 ms firmware steps.)
		EXPECT_NEAR(robot.simTime(), 2.5, 0.02);
		EXPECT_NEAR(robot.getNavigationTime(), robot.simTime(), 1e-9);
		EXPECT_NEAR(
		    mrpt::Clock::toDouble(mrpt::Clock::now()) -
		        mrpt::Clock::toDouble(SimulatedRobot::timestampOf(0)),
		    robot.simTime(), 1e-5);
		// Turning on the spot toward a heading behind.
		robot.changeSpeeds(*robot.getAlignCmd(M_PI / 2));
		for (int i = 0; i < 10; i++) robot.simulate(0.1);
		EXPECT_GT(robot.pose().phi, 0.3);
		EXPECT_NEAR(robot.pose().x, 1.0, 1e-6);
	}
	EXPECT_EQ(mrpt::Clock::getActiveClock(), before);
}

TEST(SimulatedRobot, ReportsTheTruePoseUntilGivenAnEstimate)
{
	const Scene s = room();
	SimulatedRobot robot(s, SimulatedRobot::TOptions(), {1.0, 2.0, 0.0});
	mrpt::math::TPose2D pose, odo;
	mrpt::math::TTwist2D vel;
	mrpt::system::TTimeStamp t;
	std::string frame;
	robot.changeSpeeds(cmd(0.3, 0));
	for (int i = 0; i < 10; i++) robot.simulate(0.1);
	ASSERT_TRUE(robot.getCurrentPoseAndSpeeds(pose, vel, t, odo, frame));
	EXPECT_NEAR(pose.x, robot.pose().x, 1e-9);
	EXPECT_NEAR(pose.y, robot.pose().y, 1e-9);
	EXPECT_NEAR(vel.vx, 0.3, 1e-3);
	EXPECT_FALSE(robot.reportsEstimate());
	// Noise-free odometry follows the truth.
	EXPECT_NEAR(robot.odometry().x, robot.pose().x, 1e-9);
	EXPECT_NEAR(robot.odometryDistance(), robot.pose().x - 1.0, 1e-9);

	// The robot now believes it is 1 m further north and facing north: it
	// reports that belief moved by its odometry (forward = +y), velocity
	// in the belief's heading; the truth goes on east.
	const mrpt::math::TPose2D truthBefore = robot.pose();
	robot.setPoseEstimate({truthBefore.x, truthBefore.y + 1, M_PI / 2});
	for (int i = 0; i < 10; i++) robot.simulate(0.1);
	ASSERT_TRUE(robot.getCurrentPoseAndSpeeds(pose, vel, t, odo, frame));
	const double moved = robot.pose().x - truthBefore.x;
	EXPECT_GT(moved, 0.25);
	EXPECT_NEAR(robot.pose().y, 2.0, 1e-6);
	EXPECT_NEAR(pose.x, truthBefore.x, 1e-6);
	EXPECT_NEAR(pose.y, truthBefore.y + 1 + moved, 1e-6);
	EXPECT_NEAR(pose.phi, M_PI / 2, 1e-6);
	EXPECT_NEAR(vel.vx, 0, 1e-3);
	EXPECT_NEAR(vel.vy, 0.3, 1e-3);
	EXPECT_EQ(frame, "map");
	EXPECT_TRUE(robot.reportsEstimate());
	EXPECT_EQ(robot.estimatedTrajectory().size(), 11u);
	// The scan is still taken at the true pose (the box face at x = 4).
	mrpt::maps::CSimplePointsMap pts;
	ASSERT_TRUE(robot.senseObstacles(pts, t));
	float x, y, z;
	double ahead = 1e9;
	for (std::size_t i = 0; i < pts.size(); i++)
	{
		pts.getPoint(i, x, y, z);
		if (std::abs(y) < 0.05 && x > 0) ahead = std::min<double>(ahead, x);
	}
	EXPECT_NEAR(ahead, 4.0 - robot.pose().x, 0.05);
}

TEST(SimulatedRobot, OdometryNoiseDriftsTheHeadingByTheBias)
{
	const Scene s = room();
	SimulatedRobot robot(s, SimulatedRobot::TOptions(), {0.5, 1.0, 0.0});
	OdometrySpec spec;
	spec.transNoise = 0;
	spec.rotNoisePerM = 0;
	spec.rotBiasPerM = 3.5 * M_PI / 180;
	robot.setOdometryNoise(spec, 3);
	robot.changeSpeeds(cmd(0.4, 0));
	for (int i = 0; i < 75; i++) robot.simulate(0.1);  // ~3 m east
	const double d = robot.pose().x - 0.5;
	ASSERT_GT(d, 2.5);
	EXPECT_NEAR(robot.pose().phi, 0, 1e-9);
	EXPECT_NEAR(robot.odometry().phi, spec.rotBiasPerM * d, 1e-6);
	EXPECT_NEAR(robot.odometryDistance(), d, 1e-6);
	// The odometry curves left: it ends north of the truth.
	EXPECT_GT(robot.odometry().y, robot.pose().y + 0.1);
	// Turning on the spot by odometry.
	const double phi0 = robot.odometry().phi;
	robot.turnInPlace(M_PI / 3, M_PI / 4);
	EXPECT_NEAR(robot.odometry().phi - phi0, M_PI / 3, 0.02);
	EXPECT_NEAR(robot.pose().phi, M_PI / 3, 0.02);
	EXPECT_NEAR(robot.pose().x, 0.5 + d, 0.01);
}

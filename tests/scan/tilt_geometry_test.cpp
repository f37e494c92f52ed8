/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/scan/TiltGeometry.h>

#include <cmath>

using namespace semnav;

TEST(TiltGeometry, TiltRoundTripsThroughSensorPose)
{
	for (double deg = -89; deg <= 89; deg += 7.3)
	{
		const double theta = deg * M_PI / 180;
		EXPECT_NEAR(
		    tiltOfSensorPose(tiltedSensorPose({0.1, 0, 0.45}, theta)), theta,
		    1e-12);
		EXPECT_NEAR(
		    tiltOfSensorPose(tiltedSensorPose({0, 0, 0.45}, theta, 0.3)), theta,
		    1e-12);
	}
}

TEST(TiltGeometry, PositiveTiltRaisesTheCentralBeam)
{
	const double theta = 30 * M_PI / 180;
	const auto pose = tiltedSensorPose({0, 0, 0.45}, theta);
	double x, y, z;
	pose.composePoint(1.0, 0.0, 0.0, x, y, z);  // beam at phi = 0, 1 m
	EXPECT_NEAR(x, std::cos(theta), 1e-12);
	EXPECT_NEAR(y, 0, 1e-12);
	EXPECT_NEAR(z, 0.45 + std::sin(theta), 1e-12);
	// Beams at +-90 deg lie on the tilt axis (the robot's y axis) at any tilt.
	pose.composePoint(0.0, 1.0, 0.0, x, y, z);
	EXPECT_NEAR(x, 0, 1e-12);
	EXPECT_NEAR(y, 1, 1e-12);
	EXPECT_NEAR(z, 0.45, 1e-12);
}

TEST(TiltGeometry, PhiCenterYawsTheScannerInsideItsPlane)
{
	const double theta = 20 * M_PI / 180, phi0 = 0.4;
	const auto pose = tiltedSensorPose({0, 0, 0}, theta, phi0);
	double x, y, z;
	pose.composePoint(1.0, 0.0, 0.0, x, y, z);  // bearing phi0 in the plane
	EXPECT_NEAR(x, std::cos(phi0) * std::cos(theta), 1e-12);
	EXPECT_NEAR(y, std::sin(phi0), 1e-12);
	EXPECT_NEAR(z, std::cos(phi0) * std::sin(theta), 1e-12);
}

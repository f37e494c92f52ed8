/* semnav: semantic navigation from tilting-laser sweeps */
// LaserScan -> semnav scan line (semnav-bag2rawlog): beam order, clockwise
// and off-centre scans, REP 117 validity, the line's middle time.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "LaserScanLine.h"

using namespace semnav;

namespace
{
/** n beams from angleMin by `step`, range of beam i = 1 + i / 100. */
sensor_msgs::LaserScan scanOf(std::size_t n, double angleMin, double step)
{
	sensor_msgs::LaserScan m;
	m.angle_min = static_cast<float>(angleMin);
	m.angle_increment = static_cast<float>(step);
	m.angle_max = static_cast<float>(angleMin + step * (n - 1));
	m.range_min = 0.1f;
	m.range_max = 8.0f;
	for (std::size_t i = 0; i < n; i++) m.ranges.push_back(1.0f + i / 100.0f);
	return m;
}

const ros::Time kStamp(1577836800, 500000000);
}  // namespace

TEST(LaserScanLine, BeamsKeepTheirOrderAndACentredScanLooksAhead)
{
	const auto m = scanOf(361, -M_PI / 2, M_PI / 360);
	mrpt::obs::CObservation2DRangeScan out;
	ASSERT_EQ(toScanLine(m, mrpt::poses::CPose3D(), kStamp, "L", out), "");
	ASSERT_EQ(out.getScanSize(), 361u);
	for (std::size_t i = 0; i < 361; i++)
		ASSERT_EQ(out.getScanRange(i), m.ranges[i]) << i;
	EXPECT_EQ(out.aperture, m.angle_max - m.angle_min);
	EXPECT_EQ(out.sensorPose.yaw(), 0);
	EXPECT_TRUE(out.rightToLeft);
	EXPECT_EQ(out.sensorLabel, "L");
	EXPECT_EQ(out.maxRange, 8.0f);
}

TEST(LaserScanLine, AClockwiseScanIsReversed)
{
	const auto m = scanOf(181, M_PI / 2, -M_PI / 180);
	mrpt::obs::CObservation2DRangeScan out;
	ASSERT_EQ(toScanLine(m, mrpt::poses::CPose3D(), kStamp, "L", out), "");
	for (std::size_t i = 0; i < 181; i++)
		ASSERT_EQ(out.getScanRange(i), m.ranges[180 - i]) << i;
	EXPECT_NEAR(out.aperture, M_PI, 1e-6);
	EXPECT_NEAR(out.sensorPose.yaw(), 0, 1e-7);
}

TEST(LaserScanLine, AnOffCentreScanTurnsTheSensorPose)
{
	// 0 .. 180 deg: the scanner's axis looks left (yaw 90 deg) on a head
	// tilted up by 10 deg at (0.1, 0, 0.45).
	const auto m = scanOf(181, 0, M_PI / 180);
	const mrpt::poses::CPose3D head(0.1, 0, 0.45, 0, -10 * M_PI / 180, 0);
	mrpt::obs::CObservation2DRangeScan out;
	ASSERT_EQ(toScanLine(m, head, kStamp, "L", out), "");
	const auto expected = head + mrpt::poses::CPose3D(0, 0, 0, M_PI / 2, 0, 0);
	EXPECT_NEAR(
	    (out.sensorPose.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>() -
	     expected.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>())
	        .norm(),
	    0, 1e-6);
	// The first beam (ROS angle 0) points along the head's x axis.
	EXPECT_EQ(out.getScanRange(0), m.ranges[0]);
}

TEST(LaserScanLine, EndsThatDisagreeWithTheIncrementYieldToIt)
{
	auto m = scanOf(181, -M_PI / 2, M_PI / 180);
	m.angle_max = static_cast<float>(M_PI);  // 90 deg off
	mrpt::obs::CObservation2DRangeScan out;
	ASSERT_EQ(toScanLine(m, mrpt::poses::CPose3D(), kStamp, "L", out), "");
	EXPECT_NEAR(out.aperture, M_PI, 1e-6);
	EXPECT_NEAR(out.sensorPose.yaw(), 0, 1e-6);
}

TEST(LaserScanLine, ReturnsOutsideTheRangeOrNotFiniteAreInvalid)
{
	auto m = scanOf(8, -0.1, 0.03);
	const float inf = std::numeric_limits<float>::infinity();
	m.ranges = {0.05f, 0.1f, 8.0f, 8.01f, inf, std::nanf(""), 0.0f, 3.0f};
	mrpt::obs::CObservation2DRangeScan out;
	ASSERT_EQ(toScanLine(m, mrpt::poses::CPose3D(), kStamp, "L", out), "");
	const bool valid[] = {false, true, true, false, false, false, false, true};
	for (std::size_t i = 0; i < 8; i++)
	{
		EXPECT_EQ(out.getScanRangeValidity(i), valid[i]) << i;
		EXPECT_EQ(out.getScanRange(i), valid[i] ? m.ranges[i] : 8.0f) << i;
	}
}

TEST(LaserScanLine, AScanWithoutBeamsOrStepIsRefused)
{
	mrpt::obs::CObservation2DRangeScan out;
	EXPECT_EQ(
	    toScanLine(
	        scanOf(1, 0, 0.01), mrpt::poses::CPose3D(), kStamp, "L", out),
	    "a scan with 1 ranges");
	auto m = scanOf(10, 0, 0);
	m.angle_max = 0;
	EXPECT_EQ(
	    toScanLine(m, mrpt::poses::CPose3D(), kStamp, "L", out),
	    "a scan with no angle increment");
}

TEST(LaserScanLine, TheLineIsTakenAtItsMiddleBeam)
{
	auto m = scanOf(361, -M_PI / 2, M_PI / 360);
	m.header.stamp = kStamp;
	const ros::Time recorded(1577836801, 0);
	EXPECT_EQ(scanMidTime(m, recorded), kStamp);  // time_increment 0
	m.time_increment = 1e-5f;
	EXPECT_NEAR((scanMidTime(m, recorded) - kStamp).toSec(), 180e-5, 1e-9);
	m.header.stamp = ros::Time();  // a driver without stamps
	EXPECT_NEAR((scanMidTime(m, recorded) - recorded).toSec(), 180e-5, 1e-9);
}

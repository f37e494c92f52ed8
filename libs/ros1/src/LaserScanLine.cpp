/* semnav: semantic navigation from tilting-laser sweeps */
#include "LaserScanLine.h"

#include <mrpt/ros1bridge/time.h>

#include <cmath>

namespace semnav
{
ros::Time scanMidTime(
    const sensor_msgs::LaserScan& msg, const ros::Time& fallback)
{
	const ros::Time start =
	    msg.header.stamp.isZero() ? fallback : msg.header.stamp;
	const double half = 0.5 *
	                    (msg.ranges.size() > 0 ? msg.ranges.size() - 1 : 0) *
	                    msg.time_increment;
	if (!std::isfinite(half) || half <= 0) return start;
	return start + ros::Duration(half);
}

std::string toScanLine(
    const sensor_msgs::LaserScan& msg, const mrpt::poses::CPose3D& headPose,
    const ros::Time& stamp, const std::string& sensorLabel,
    mrpt::obs::CObservation2DRangeScan& out)
{
	// Not mrpt::ros1bridge::fromROS(LaserScan): MRPT 2.5.8's maps ROS beam
	// i to MRPT beam i + 1 on 181/361-beam 180 deg scans (rounding).
	const std::size_t n = msg.ranges.size();
	if (n < 2) return "a scan with " + std::to_string(n) + " ranges";
	double step = msg.angle_increment;
	if (!std::isfinite(step) || step == 0)
		step = (msg.angle_max - msg.angle_min) / (n - 1);
	if (!std::isfinite(step) || step == 0)
		return "a scan with no angle increment";
	if (!(msg.range_max > 0))
		return "a scan with range_max " + std::to_string(msg.range_max);
	const bool clockwise = step < 0;
	// The ends as given (in float, as MRPT's aperture) unless they disagree
	// with the increment by half a step or more.
	float aperture = std::abs(msg.angle_max - msg.angle_min);
	double centre = 0.5 * (static_cast<double>(msg.angle_min) + msg.angle_max);
	if (!(std::abs(aperture - std::abs(step) * (n - 1)) < 0.5 * std::abs(step)))
	{
		aperture = static_cast<float>(std::abs(step) * (n - 1));
		centre = msg.angle_min + 0.5 * step * (n - 1);
	}

	out = mrpt::obs::CObservation2DRangeScan();
	out.sensorLabel = sensorLabel;
	out.timestamp = mrpt::ros1bridge::fromROS(stamp);
	out.rightToLeft = true;
	out.aperture = aperture;
	out.maxRange = msg.range_max;
	out.sensorPose = headPose + mrpt::poses::CPose3D(0, 0, 0, centre, 0, 0);
	out.resizeScan(n);
	for (std::size_t i = 0; i < n; i++)
	{
		const float r = msg.ranges[clockwise ? n - 1 - i : i];
		const bool valid = std::isfinite(r) && r > 0 && r >= msg.range_min &&
		                   r <= msg.range_max;
		out.setScanRange(i, valid ? r : msg.range_max);
		out.setScanRangeValidity(i, valid);
	}
	return "";
}

}  // namespace semnav

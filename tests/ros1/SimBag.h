/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// A semnav-sim rawlog written as a ROS 1 bag (rosbag C++ API), the way a
// robot's drivers would record it: LaserScan per tilt line, the tilt as a
// JointState joint or as tf, odometry as nav_msgs/Odometry or as tf.

#include <geometry_msgs/TransformStamped.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/ros1bridge/pose.h>
#include <mrpt/ros1bridge/time.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <semnav/scan/TiltGeometry.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace semnav::test
{
/** One scan line of a simulated rawlog with the odometry before it. */
struct SimLine
{
	mrpt::obs::CObservation2DRangeScan::Ptr scan;
	mrpt::poses::CPose2D odometry;
	std::size_t sweep = 0;
	ros::Time stamp;
	double theta = 0;
};

/** The scan lines of a semnav-sim rawlog, in order. */
inline std::vector<SimLine> readSimLines(const std::string& rawlog)
{
	mrpt::obs::CRawlog log;
	if (!log.loadFromRawLogFile(rawlog)) return {};
	std::vector<SimLine> lines;
	mrpt::poses::CPose2D odometry;
	std::size_t sweeps = 0;
	for (std::size_t i = 0; i < log.size(); i++)
	{
		const auto obs = log.getAsObservation(i);
		if (auto o =
		        std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs))
		{
			odometry = o->odometry;
			sweeps++;
		}
		else if (
		    auto s =
		        std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(
		            obs))
			lines.push_back(
			    {s, odometry, sweeps - 1, mrpt::ros1bridge::toROS(s->timestamp),
			     tiltOfSensorPose(s->sensorPose)});
	}
	return lines;
}

/** The line as a LaserScan whose middle beam is at l.stamp (the first at
 * stamp - (n - 1) / 2 * timeIncrement); no return = +inf (REP 117). A
 * clockwise scan lists the beams from the left (negative increment). */
inline sensor_msgs::LaserScan laserScanOf(
    const SimLine& l, double timeIncrement, const std::string& frame,
    bool clockwise = false)
{
	const auto& s = *l.scan;
	const std::size_t n = s.getScanSize();
	sensor_msgs::LaserScan m;
	m.header.frame_id = frame;
	m.header.stamp = l.stamp - ros::Duration(0.5 * (n - 1) * timeIncrement);
	m.angle_min = -0.5f * s.aperture;
	m.angle_max = 0.5f * s.aperture;
	m.angle_increment = s.aperture / (n - 1);
	m.time_increment = static_cast<float>(timeIncrement);
	m.range_min = 0;
	m.range_max = s.maxRange;
	for (std::size_t i = 0; i < n; i++)
		m.ranges.push_back(
		    s.getScanRangeValidity(i) ? s.getScanRange(i)
		                              : std::numeric_limits<float>::infinity());
	if (clockwise)
	{
		std::swap(m.angle_min, m.angle_max);
		m.angle_increment = -m.angle_increment;
		std::reverse(m.ranges.begin(), m.ranges.end());
	}
	return m;
}

inline ros::Time midway(const ros::Time& a, const ros::Time& b)
{
	return a + ros::Duration(0.5 * (b - a).toSec());
}

/** Tilts (theta) sampled at the first and last line of each sweep and
 * midway between lines, as a joint publisher at its own rate would: the
 * converter must interpolate. */
inline std::vector<std::pair<ros::Time, double>> tiltSamples(
    const std::vector<SimLine>& lines)
{
	std::vector<std::pair<ros::Time, double>> out;
	for (std::size_t i = 0; i < lines.size(); i++)
	{
		const bool first = i == 0 || lines[i - 1].sweep != lines[i].sweep;
		const bool last =
		    i + 1 == lines.size() || lines[i + 1].sweep != lines[i].sweep;
		if (first) out.emplace_back(lines[i].stamp, lines[i].theta);
		if (!last)
			out.emplace_back(
			    midway(lines[i].stamp, lines[i + 1].stamp),
			    0.5 * (lines[i].theta + lines[i + 1].theta));
		else
			out.emplace_back(lines[i].stamp, lines[i].theta);
	}
	return out;
}

inline nav_msgs::Odometry odometryMsg(
    const mrpt::poses::CPose2D& p, const ros::Time& t)
{
	nav_msgs::Odometry m;
	m.header.stamp = t;
	m.header.frame_id = "odom";
	m.child_frame_id = "base_link";
	m.pose.pose = mrpt::ros1bridge::toROS_Pose(p);
	return m;
}

inline geometry_msgs::TransformStamped transformMsg(
    const std::string& parent, const std::string& child,
    const mrpt::poses::CPose3D& p, const ros::Time& t)
{
	geometry_msgs::TransformStamped m;
	m.header.stamp = t;
	m.header.frame_id = parent;
	m.child_frame_id = child;
	const auto pose = mrpt::ros1bridge::toROS_Pose(p);
	m.transform.translation.x = pose.position.x;
	m.transform.translation.y = pose.position.y;
	m.transform.translation.z = pose.position.z;
	m.transform.rotation = pose.orientation;
	return m;
}

/** How writeJointStatesBag() records. */
struct JointStatesBag
{
	/** The joint is published until then only. */
	ros::Time tiltUntil = ros::TIME_MAX;
	bool clockwise = false;
	rosbag::compression::CompressionType compression =
	    rosbag::compression::Uncompressed;
};

/** /scan (stamps spread by time_increment), /joint_states (wheel joint and
 * tilt_joint, axis +y: position = -theta) and /odom at every line. */
inline void writeJointStatesBag(
    const std::vector<SimLine>& lines, const std::string& path,
    const JointStatesBag& how = {})
{
	rosbag::Bag bag(path, rosbag::bagmode::Write);
	bag.setCompression(how.compression);
	for (const auto& [t, theta] : tiltSamples(lines))
	{
		if (t > how.tiltUntil) break;
		sensor_msgs::JointState js;
		js.header.stamp = t;
		js.name = {"wheel_left_joint", "tilt_joint"};
		js.position = {0.0, -theta};
		bag.write("/joint_states", t, js);
	}
	for (const auto& l : lines)
	{
		bag.write("/odom", l.stamp, odometryMsg(l.odometry, l.stamp));
		bag.write(
		    "/scan", l.stamp, laserScanOf(l, 2e-5, "laser", how.clockwise));
	}
}

/** /scan in frame "laser"; /tf_static base_link -> laser_mount (the mount);
 * /tf laser_mount -> laser (pitch -theta, at the tilt samples) and odom ->
 * base_link (at every line). */
inline void writeTfBag(
    const std::vector<SimLine>& lines, const std::string& path)
{
	rosbag::Bag bag(path, rosbag::bagmode::Write);
	const auto mount = lines.front().scan->sensorPose.translation();
	const ros::Time t0 = lines.front().stamp;
	tf2_msgs::TFMessage fixed;
	fixed.transforms.push_back(transformMsg(
	    "base_link", "laser_mount",
	    mrpt::poses::CPose3D(mount[0], mount[1], mount[2], 0, 0, 0), t0));
	bag.write("/tf_static", t0, fixed);
	for (const auto& [t, theta] : tiltSamples(lines))
	{
		tf2_msgs::TFMessage m;
		m.transforms.push_back(transformMsg(
		    "laser_mount", "laser", mrpt::poses::CPose3D(0, 0, 0, 0, -theta, 0),
		    t));
		bag.write("/tf", t, m);
	}
	for (const auto& l : lines)
	{
		tf2_msgs::TFMessage m;
		m.transforms.push_back(transformMsg(
		    "odom", "base_link", mrpt::poses::CPose3D(l.odometry), l.stamp));
		bag.write("/tf", l.stamp, m);
		bag.write("/scan", l.stamp, laserScanOf(l, 0, "laser"));
	}
}

}  // namespace semnav::test

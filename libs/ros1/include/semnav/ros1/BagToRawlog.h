/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint3D.h>

#include <cstddef>
#include <functional>
#include <string>

namespace semnav
{
/** Converts a ROS 1 bag of a tilting laser into the rawlog semnav-map reads
 * (docs/ros-bags.md).
 *
 * Each sensor_msgs/LaserScan becomes one CObservation2DRangeScan whose
 * sensorPose carries the tilt at the scan's mid time (TiltGeometry.h):
 * from a sensor_msgs/JointState joint (linear interpolation between the two
 * positions around that time, mount from the options) or from tf (the
 * laser frame in the base frame, the whole pose). Before a line whose
 * odometry differs from the last one written, a CObservationOdometry with
 * the odometry at that time: the latest nav_msgs/Odometry message at or
 * before it, or the odom -> base transform from tf. Lines without a tilt or
 * an odometry reading are skipped and counted.
 *
 * The bag is read twice: first the tilt, odometry and tf messages (kept in
 * memory), then the scans in bag order. */
class BagToRawlog
{
public:
	/** Where the tilt or the odometry comes from. */
	enum class Source
	{
		Topic,  ///< sensor_msgs/JointState or nav_msgs/Odometry
		Tf      ///< /tf and /tf_static
	};

	struct TOptions
	{
		std::string scanTopic = "/scan";
		Source tiltFrom = Source::Topic;
		std::string jointStatesTopic = "/joint_states";
		std::string tiltJoint = "tilt_joint";
		/** The joint's axis is -y (positive position raises the beam)
		 * instead of +y (REP 103: positive position lowers it). */
		bool tiltAxisNegative = false;
		/** Added to the tilt read from the joint (rad). */
		double tiltOffset = 0;
		/** Tilt axis position in the base frame (JointState tilt), m. */
		mrpt::math::TPoint3D mount{0, 0, 0.45};
		Source odomFrom = Source::Topic;
		std::string odomTopic = "/odom";
		std::string baseFrame = "base_link";
		std::string odomFrame = "odom";
		/** Laser frame for the tf tilt; empty = the scans' frame_id. */
		std::string laserFrame;
		/** sensorLabel of the scan lines written. */
		std::string sensorLabel = "TILT_LMS";
		/** Longest gap between the two tilt samples around a line, and
		 * largest age of the odometry reading used for it (s). */
		double maxGap = 0.5;
	};

	/** What one conversion did. */
	struct Result
	{
		std::size_t scans = 0;     ///< LaserScan messages read
		std::size_t lines = 0;     ///< scan lines written
		std::size_t odometry = 0;  ///< odometry readings written
		std::size_t skippedNoTilt = 0;
		std::size_t skippedNoOdometry = 0;
		std::size_t skippedBadScan = 0;
		/** Why the first skipped line was skipped ("" when none was). */
		std::string firstSkip;
		/** Stamps of the first and last line written (s since 1970). */
		double firstStamp = 0, lastStamp = 0;

		std::size_t skipped() const
		{
			return skippedNoTilt + skippedNoOdometry + skippedBadScan;
		}
	};

	/** Called after each scan message: (scans read, scans in the bag). */
	using ProgressCallback = std::function<void(std::size_t, std::size_t)>;

	explicit BagToRawlog(const TOptions& options);

	/** Converts `bagPath` into the rawlog `rawlogPath`, written atomically.
	 * Throws IoError when the bag cannot be read or the rawlog written, and
	 * Error naming the topic (and listing the bag's topics) when the bag
	 * lacks a topic, the tilt joint or the tf frames, or when no line could
	 * be converted. */
	Result convert(
	    const std::string& bagPath, const std::string& rawlogPath,
	    const ProgressCallback& progress = {});

	const TOptions& options() const { return m_options; }

private:
	TOptions m_options;
};

}  // namespace semnav

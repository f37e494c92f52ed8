/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/emulation/EmulatedDiffDriveBase.h>

#include <cstddef>
#include <memory>
#include <string>

namespace semnav
{
/** EmulatedDiffDriveBase speaking ROS 1 as a real base's driver does:
 * geometry_msgs/Twist on cmd_vel become commands; nav_msgs/Odometry is
 * published on odom at odom_rate_hz (the drifting odometry pose, the true
 * velocities, wall-clock stamps), and the true pose likewise on
 * base_pose_ground_truth (as Stage's ROS node names it). Built with ROS 1
 * only (SEMNAV_HAVE_ROS1). */
class Ros1BaseEmulator
{
public:
	struct Options
	{
		std::string nodeName = "semnav_emulated_base";
		std::string cmdVelTopic = "cmd_vel";
		std::string odomTopic = "odom";
		std::string truthTopic = "base_pose_ground_truth";
		std::string odomFrame = "odom";
		std::string baseFrame = "base_link";
		double odomRate = 50;
		/** Fault: odometry goes silent odomSilentAt s after the first
		 * cmd_vel, for odomSilentFor s (< 0: never); the base and the
		 * ground truth go on. */
		double odomSilentAt = -1, odomSilentFor = 0;
		/** Waiting for the ROS master at start (s). */
		double masterTimeout = 5;
	};

	/** `base` must outlive this. Throws IoError when the master does not
	 * answer. */
	Ros1BaseEmulator(EmulatedDiffDriveBase& base, const Options& options);
	~Ros1BaseEmulator();
	Ros1BaseEmulator(const Ros1BaseEmulator&) = delete;
	Ros1BaseEmulator& operator=(const Ros1BaseEmulator&) = delete;

	/** Odometry messages published so far. */
	std::size_t odometrySent() const;

private:
	struct Impl;
	std::unique_ptr<Impl> m_impl;
};

}  // namespace semnav

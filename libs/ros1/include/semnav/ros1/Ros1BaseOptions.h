/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <string>

namespace semnav
{
/** Options of Ros1Base, INI section [Ros1Base] (config/robot.ini). Built
 * with or without ROS 1, so configurations are checked everywhere. */
struct Ros1BaseOptions : public mrpt::config::CLoadableOptions
{
	void loadFromConfigFile(
	    const mrpt::config::CConfigFileBase& c,
	    const std::string& section) override;
	void saveToConfigFile(
	    mrpt::config::CConfigFileBase& c,
	    const std::string& section) const override;

	/** node_name: the ROS node's name when semnav starts roscpp. */
	std::string nodeName = "semnav";
	/** cmd_vel_topic: geometry_msgs/Twist commands go here. */
	std::string cmdVelTopic = "cmd_vel";
	/** odom_topic: nav_msgs/Odometry is read from here. */
	std::string odomTopic = "odom";
	/** command_topic, events_topic: semnav-robot's operator commands
	 * (std_msgs/String, one line each) and progress (JSON events). */
	std::string commandTopic = "semnav/command";
	std::string eventsTopic = "semnav/events";
	/** odom_frame: expected header.frame_id of odometry ("" = any). */
	std::string odomFrame = "odom";
	/** base_frame: expected child_frame_id of odometry ("" = any). */
	std::string baseFrame = "base_link";
	/** command_rate_hz: a non-zero command is re-sent this often. */
	double commandRate = 10;
	/** watchdog_s: with no setVelocity()/keepAlive() for this long, a zero
	 * command is sent and re-sending stops. */
	double watchdog = 0.5;
	/** odometry_timeout_s: older odometry is stale: the base stops and
	 * refuses motion until it is fresh again. 0.3 s stops the robot within
	 * 0.5 s of its odometry's last message; a base publishing odometry
	 * slower than ~10 Hz needs more. */
	double odometryTimeout = 0.3;
	/** master_timeout_s: how long to wait for the ROS master at start. */
	double masterTimeout = 5;
};

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/OptionTable.h>
#include <semnav/ros1/Ros1BaseOptions.h>

namespace semnav
{
namespace
{
using O = Ros1BaseOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .text(
	            "node_name", &O::nodeName,
	            "ROS node name when semnav starts roscpp itself.")
	        .text(
	            "cmd_vel_topic", &O::cmdVelTopic,
	            "geometry_msgs/Twist velocity commands are published here.")
	        .text(
	            "odom_topic", &O::odomTopic,
	            "nav_msgs/Odometry (pose, real velocities, stamps) is read "
	            "from here.")
	        .text(
	            "command_topic", &O::commandTopic,
	            "semnav-robot: operator commands, one std_msgs/String each "
	            "(empty: none).")
	        .text(
	            "events_topic", &O::eventsTopic,
	            "semnav-robot: progress, one JSON event per std_msgs/String "
	            "(empty: none).")
	        .text(
	            "odom_frame", &O::odomFrame,
	            "Odometry with another header.frame_id is rejected (empty: "
	            "any).")
	        .text(
	            "base_frame", &O::baseFrame,
	            "Odometry with another child_frame_id is rejected (empty: "
	            "any).")
	        .real(
	            "command_rate_hz", &O::commandRate, 5, 100,
	            "A non-zero command is re-sent this often (feeds the base's "
	            "watchdog).")
	        .real(
	            "watchdog_s", &O::watchdog, 0.05, 10,
	            "No setVelocity()/keepAlive() for this long: a zero command "
	            "is sent.")
	        .real(
	            "odometry_timeout_s", &O::odometryTimeout, 0.02, 10,
	            "Older odometry is stale: the base is stopped and motion "
	            "refused.")
	        .real(
	            "master_timeout_s", &O::masterTimeout, 0, 600,
	            "Waiting this long for the ROS master at start, then an "
	            "error.")
	        .check(
	            [](const O& o)
	            { return !o.cmdVelTopic.empty() && !o.odomTopic.empty(); },
	            "cmd_vel_topic and odom_topic must not be empty");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(Ros1BaseOptions, optionTable())

}  // namespace semnav

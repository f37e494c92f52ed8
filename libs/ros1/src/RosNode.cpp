/* semnav: semantic navigation from tilting-laser sweeps */
#include <ros/ros.h>
#include <semnav/common/Error.h>
#include <semnav/ros1/RosNode.h>

#include <chrono>
#include <mutex>
#include <thread>

namespace semnav
{
void startRosNode(const std::string& name, double masterTimeout)
{
	static std::mutex mutex;
	std::lock_guard<std::mutex> lock(mutex);
	if (!ros::isInitialized())
	{
		ros::M_string remappings;
		ros::init(
		    remappings, name,
		    ros::init_options::NoSigintHandler | ros::init_options::NoRosout);
		ros::master::setRetryTimeout(ros::WallDuration(1.0));
	}
	const auto end = std::chrono::steady_clock::now() +
	                 std::chrono::duration<double>(masterTimeout);
	while (!ros::master::check())
	{
		if (std::chrono::steady_clock::now() >= end)
			throw IoError(
			    "ROS master " + ros::master::getURI() +
			    " does not answer (ROS_MASTER_URI)");
		std::this_thread::sleep_for(std::chrono::milliseconds(50));
	}
	ros::start();
}

}  // namespace semnav

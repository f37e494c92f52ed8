/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <functional>
#include <memory>
#include <string>

namespace semnav
{
/** Operator commands and progress over ROS 1: each std_msgs/String on the
 * command topic is one command line for `onCommand` (called on the
 * channel's own thread); publish() sends one progress line (a JSON event)
 * as std_msgs/String on the events topic. Starts roscpp when needed
 * (startRosNode; IoError when the master does not answer). */
class Ros1CommandChannel
{
public:
	Ros1CommandChannel(
	    const std::string& nodeName, double masterTimeout,
	    const std::string& commandTopic, const std::string& eventsTopic,
	    std::function<void(const std::string&)> onCommand);
	~Ros1CommandChannel();
	Ros1CommandChannel(const Ros1CommandChannel&) = delete;
	Ros1CommandChannel& operator=(const Ros1CommandChannel&) = delete;

	/** Publishes one line on the events topic. Thread-safe. */
	void publish(const std::string& line);

private:
	struct Impl;
	std::unique_ptr<Impl> m_impl;
};

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <semnav/ros1/Ros1CommandChannel.h>
#include <semnav/ros1/RosNode.h>
#include <std_msgs/String.h>

#include <atomic>
#include <mutex>
#include <thread>

namespace semnav
{
struct Ros1CommandChannel::Impl
{
	Impl(
	    const std::string& commandTopic, const std::string& eventsTopic,
	    std::function<void(const std::string&)> cb)
	    : onCommand(std::move(cb))
	{
		node.setCallbackQueue(&queue);
		publisher = node.advertise<std_msgs::String>(eventsTopic, 100);
		subscriber = node.subscribe(commandTopic, 100, &Impl::onMessage, this);
		thread = std::thread(
		    [this]
		    {
			    while (running) queue.callAvailable(ros::WallDuration(0.02));
		    });
	}
	~Impl()
	{
		running = false;
		thread.join();
		subscriber.shutdown();
		publisher.shutdown();
	}
	void onMessage(const std_msgs::String::ConstPtr& m)
	{
		if (onCommand) onCommand(m->data);
	}

	std::function<void(const std::string&)> onCommand;
	ros::CallbackQueue queue;
	ros::NodeHandle node;
	ros::Publisher publisher;
	ros::Subscriber subscriber;
	std::mutex mutex;
	std::thread thread;
	std::atomic<bool> running{true};
};

Ros1CommandChannel::Ros1CommandChannel(
    const std::string& nodeName, double masterTimeout,
    const std::string& commandTopic, const std::string& eventsTopic,
    std::function<void(const std::string&)> onCommand)
{
	startRosNode(nodeName, masterTimeout);
	m_impl =
	    std::make_unique<Impl>(commandTopic, eventsTopic, std::move(onCommand));
}

Ros1CommandChannel::~Ros1CommandChannel() = default;

void Ros1CommandChannel::publish(const std::string& line)
{
	std_msgs::String m;
	m.data = line;
	std::lock_guard<std::mutex> lk(m_impl->mutex);
	m_impl->publisher.publish(m);
}

}  // namespace semnav

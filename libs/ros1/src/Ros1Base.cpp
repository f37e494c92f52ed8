/* semnav: semantic navigation from tilting-laser sweeps */
#include <geometry_msgs/Twist.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/ros1bridge/pose.h>
#include <mrpt/ros1bridge/time.h>
#include <nav_msgs/Odometry.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <semnav/ros1/Ros1Base.h>
#include <semnav/ros1/RosNode.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <thread>

namespace semnav
{
namespace
{
using SteadyClock = std::chrono::steady_clock;

double secondsSince(SteadyClock::time_point t)
{
	return std::chrono::duration<double>(SteadyClock::now() - t).count();
}
}  // namespace

struct Ros1Base::Impl
{
	explicit Impl(const TOptions& o) : options(o)
	{
		startRosNode(o.nodeName, o.masterTimeout);
		node = std::make_unique<ros::NodeHandle>();
		node->setCallbackQueue(&queue);
		publisher = node->advertise<geometry_msgs::Twist>(o.cmdVelTopic, 10);
		subscriber = node->subscribe(
		    o.odomTopic, 10, &Impl::onOdometry, this,
		    ros::TransportHints().tcpNoDelay());
		thread = std::thread([this] { run(); });
	}

	~Impl()
	{
		running = false;
		thread.join();
		std::lock_guard<std::mutex> lock(mutex);
		publish(0, 0);
		// roscpp has no flush: give the last zero a moment to leave.
		if (publisher.getNumSubscribers() > 0)
			std::this_thread::sleep_for(std::chrono::milliseconds(50));
		subscriber.shutdown();
		publisher.shutdown();
	}

	/** Publishes (v, w); called with `mutex` held. */
	void publish(double v, double w)
	{
		geometry_msgs::Twist t;
		t.linear.x = v;
		t.angular.z = w;
		publisher.publish(t);
		lastSent = SteadyClock::now();
		stats.commandsSent++;
	}

	/** Stops with a zero command; called with `mutex` held. */
	void halt()
	{
		moving = false;
		v = w = 0;
		publish(0, 0);
	}

	bool staleLocked() const
	{
		return !hasOdometry ||
		       secondsSince(lastOdometry) > options.odometryTimeout;
	}

	void onOdometry(const nav_msgs::Odometry::ConstPtr& msg)
	{
		std::lock_guard<std::mutex> lock(mutex);
		if ((!options.odomFrame.empty() &&
		     msg->header.frame_id != options.odomFrame) ||
		    (!options.baseFrame.empty() &&
		     msg->child_frame_id != options.baseFrame))
		{
			stats.odometryRejected++;
			ROS_WARN_THROTTLE(
			    5, "Ros1Base: odometry in frames '%s' -> '%s' ignored",
			    msg->header.frame_id.c_str(), msg->child_frame_id.c_str());
			return;
		}
		const mrpt::poses::CPose3D p =
		    mrpt::ros1bridge::fromROS(msg->pose.pose);
		const mrpt::math::TPose2D pose(p.x(), p.y(), p.yaw());
		if (hasOdometry)
			cache.distance +=
			    std::hypot(pose.x - cache.pose.x, pose.y - cache.pose.y);
		cache.pose = pose;
		cache.velocity = mrpt::math::TTwist2D(
		    msg->twist.twist.linear.x, msg->twist.twist.linear.y,
		    msg->twist.twist.angular.z);
		cache.time = msg->header.stamp.isZero()
		                 ? mrpt::Clock::now()
		                 : mrpt::ros1bridge::fromROS(msg->header.stamp);
		hasOdometry = true;
		lastOdometry = SteadyClock::now();
		stats.odometryReceived++;
	}

	/** One pass of the thread: stale odometry, watchdog, re-sending. */
	void tick()
	{
		std::lock_guard<std::mutex> lock(mutex);
		if (!moving) return;
		if (staleLocked())
		{
			ROS_WARN(
			    "Ros1Base: odometry stale (%.2f s), stopping",
			    hasOdometry ? secondsSince(lastOdometry) : -1.0);
			stats.staleStops++;
			halt();
		}
		else if (secondsSince(lastCommand) > options.watchdog)
		{
			ROS_WARN(
			    "Ros1Base: no command for %.2f s, stopping",
			    secondsSince(lastCommand));
			stats.watchdogStops++;
			halt();
		}
		else if (secondsSince(lastSent) >= 1.0 / options.commandRate)
			publish(v, w);
	}

	void run()
	{
		while (running)
		{
			queue.callAvailable(ros::WallDuration(0.005));
			tick();
		}
	}

	const TOptions options;
	ros::CallbackQueue queue;
	std::unique_ptr<ros::NodeHandle> node;
	ros::Publisher publisher;
	ros::Subscriber subscriber;
	std::thread thread;
	std::atomic<bool> running{true};

	mutable std::mutex mutex;
	double v = 0, w = 0;
	bool moving = false;
	bool emergency = false;
	SteadyClock::time_point lastCommand, lastSent;
	bool hasOdometry = false;
	SteadyClock::time_point lastOdometry;
	Odometry cache;
	Stats stats;
};

Ros1Base::Ros1Base(const TOptions& options)
    : m_options(options), m_impl(std::make_unique<Impl>(options))
{
}

Ros1Base::~Ros1Base() = default;

bool Ros1Base::setVelocity(double v, double w)
{
	if (!std::isfinite(v) || !std::isfinite(w)) return false;
	if (v == 0 && w == 0) return stop();
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	if (m_impl->emergency) return false;
	if (m_impl->staleLocked())
	{
		m_impl->stats.refused++;
		if (m_impl->moving) m_impl->stats.staleStops++;
		m_impl->halt();
		return false;
	}
	m_impl->v = v;
	m_impl->w = w;
	m_impl->moving = true;
	m_impl->lastCommand = SteadyClock::now();
	m_impl->publish(v, w);
	return true;
}

void Ros1Base::keepAlive()
{
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	m_impl->lastCommand = SteadyClock::now();
}

bool Ros1Base::stop()
{
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	m_impl->halt();
	return true;
}

bool Ros1Base::emergencyStop()
{
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	m_impl->halt();
	m_impl->emergency = true;
	return true;
}

void Ros1Base::resetEmergencyStop()
{
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	m_impl->emergency = false;
}

bool Ros1Base::emergencyStopped() const
{
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	return m_impl->emergency;
}

RobotBase::Odometry Ros1Base::odometry() const
{
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	return m_impl->cache;
}

bool Ros1Base::odometryStale() const
{
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	return m_impl->staleLocked();
}

double Ros1Base::odometryAge() const
{
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	return m_impl->hasOdometry ? secondsSince(m_impl->lastOdometry)
	                           : std::numeric_limits<double>::infinity();
}

std::size_t Ros1Base::commandSubscribers() const
{
	return m_impl->publisher.getNumSubscribers();
}

Ros1Base::Stats Ros1Base::stats() const
{
	std::lock_guard<std::mutex> lock(m_impl->mutex);
	return m_impl->stats;
}

}  // namespace semnav

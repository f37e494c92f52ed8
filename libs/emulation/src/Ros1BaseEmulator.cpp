/* semnav: semantic navigation from tilting-laser sweeps */
#include <geometry_msgs/Twist.h>
#include <mrpt/ros1bridge/pose.h>
#include <nav_msgs/Odometry.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <semnav/emulation/Ros1BaseEmulator.h>
#include <semnav/ros1/RosNode.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <thread>

namespace semnav
{
struct Ros1BaseEmulator::Impl
{
	Impl(EmulatedDiffDriveBase& b, const Options& o) : base(b), options(o)
	{
		startRosNode(o.nodeName, o.masterTimeout);
		node = std::make_unique<ros::NodeHandle>();
		node->setCallbackQueue(&queue);
		odom = node->advertise<nav_msgs::Odometry>(o.odomTopic, 10);
		truth = node->advertise<nav_msgs::Odometry>(o.truthTopic, 10);
		cmdVel = node->subscribe(
		    o.cmdVelTopic, 10, &Impl::onCommand, this,
		    ros::TransportHints().tcpNoDelay());
		thread = std::thread([this] { run(); });
	}

	~Impl()
	{
		running = false;
		thread.join();
		cmdVel.shutdown();
		odom.shutdown();
		truth.shutdown();
	}

	void onCommand(const geometry_msgs::Twist::ConstPtr& msg)
	{
		if (!std::isfinite(msg->linear.x) || !std::isfinite(msg->angular.z))
			return;  // as a base driver ignores a garbled command
		if (!firstCommand) firstCommand = std::chrono::steady_clock::now();
		base.command(msg->linear.x, msg->angular.z);
	}

	/** True inside the odometry-silence fault. */
	bool silent() const
	{
		if (options.odomSilentAt < 0 || !firstCommand) return false;
		const double t = std::chrono::duration<double>(
		                     std::chrono::steady_clock::now() - *firstCommand)
		                     .count();
		return t >= options.odomSilentAt &&
		       t < options.odomSilentAt + options.odomSilentFor;
	}

	nav_msgs::Odometry message(
	    const mrpt::math::TPose2D& pose, const mrpt::math::TTwist2D& v,
	    const ros::Time& stamp) const
	{
		nav_msgs::Odometry m;
		m.header.stamp = stamp;
		m.header.frame_id = options.odomFrame;
		m.child_frame_id = options.baseFrame;
		m.pose.pose = mrpt::ros1bridge::toROS_Pose(pose);
		m.twist.twist.linear.x = v.vx;
		m.twist.twist.linear.y = v.vy;
		m.twist.twist.angular.z = v.omega;
		return m;
	}

	void run()
	{
		using Clock = std::chrono::steady_clock;
		const auto period = std::chrono::duration_cast<Clock::duration>(
		    std::chrono::duration<double>(1.0 / options.odomRate));
		auto next = Clock::now();
		while (running)
		{
			queue.callAvailable(ros::WallDuration(0.002));
			if (Clock::now() < next) continue;
			next += period;
			const auto s = base.state();
			const ros::Time now = ros::Time::now();
			truth.publish(message(s.truePose, s.velocity, now));
			if (silent()) continue;
			odom.publish(message(s.odometry.pose, s.velocity, now));
			sent++;
		}
	}

	EmulatedDiffDriveBase& base;
	const Options options;
	ros::CallbackQueue queue;
	std::unique_ptr<ros::NodeHandle> node;
	ros::Publisher odom, truth;
	ros::Subscriber cmdVel;
	std::thread thread;
	std::atomic<bool> running{true};
	std::atomic<std::size_t> sent{0};
	/** When the first cmd_vel came (the callback thread's only). */
	std::optional<std::chrono::steady_clock::time_point> firstCommand;
};

Ros1BaseEmulator::Ros1BaseEmulator(
    EmulatedDiffDriveBase& base, const Options& options)
    : m_impl(std::make_unique<Impl>(base, options))
{
}

Ros1BaseEmulator::~Ros1BaseEmulator() = default;

std::size_t Ros1BaseEmulator::odometrySent() const
{
	return m_impl->sent;
}

}  // namespace semnav

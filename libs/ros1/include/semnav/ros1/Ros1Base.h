/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/robot/RobotBase.h>
#include <semnav/ros1/Ros1BaseOptions.h>

#include <cstddef>
#include <memory>

namespace semnav
{
/** A robot base over ROS 1: velocity commands as geometry_msgs/Twist on
 * cmd_vel, odometry from nav_msgs/Odometry on odom ([Ros1Base] of
 * config/robot.ini names topics, frames and rates).
 *
 * - A non-zero command is re-sent at command_rate_hz until the next one
 *   (feeding the real base's own watchdog); a zero command is sent on
 *   stop(), emergencyStop(), by the watchdog, on stale odometry and by the
 *   destructor.
 * - The watchdog: no setVelocity() or keepAlive() for watchdog_s sends a
 *   zero command and stops re-sending. If this process dies, re-sending
 *   stops and the base's own watchdog must stop the robot.
 * - Odometry (pose, the base's real velocities, its stamp) is cached as it
 *   arrives; odometry() never blocks. Odometry older than
 *   odometry_timeout_s (or none yet) is stale: a moving base is stopped
 *   and setVelocity() refused until fresh odometry arrives. Non-finite
 *   commands are refused too.
 *
 * Starts roscpp when needed (startRosNode) and throws IoError when the
 * master does not answer. Its own thread serves the subscription and the
 * re-sending; everything is thread-safe. */
class Ros1Base : public RobotBase
{
public:
	using TOptions = Ros1BaseOptions;

	/** Counters since construction. */
	struct Stats
	{
		std::size_t commandsSent = 0;
		std::size_t odometryReceived = 0;
		/** Odometry with unexpected frames, ignored. */
		std::size_t odometryRejected = 0;
		/** Stops because odometry went stale while moving. */
		std::size_t staleStops = 0;
		std::size_t watchdogStops = 0;
		/** setVelocity() refused on stale odometry. */
		std::size_t refused = 0;
	};

	explicit Ros1Base(const TOptions& options = TOptions());
	/** Sends a zero command, then leaves the topics. */
	~Ros1Base() override;
	Ros1Base(const Ros1Base&) = delete;
	Ros1Base& operator=(const Ros1Base&) = delete;

	bool setVelocity(double v, double w) override;
	void keepAlive() override;
	bool stop() override;
	bool emergencyStop() override;
	void resetEmergencyStop() override;
	bool emergencyStopped() const override;
	Odometry odometry() const override;
	double watchdogPeriod() const override { return m_options.watchdog; }

	/** True when no odometry came for odometry_timeout_s (or none yet). */
	bool odometryStale() const;
	/** Seconds since the last odometry arrived; infinity before the
	 * first. */
	double odometryAge() const;
	/** Subscribers of cmd_vel now (the base's driver, once connected:
	 * commands sent before are lost, a start may wait for it). */
	std::size_t commandSubscribers() const;
	Stats stats() const;
	const TOptions& options() const { return m_options; }

private:
	struct Impl;
	const TOptions m_options;
	std::unique_ptr<Impl> m_impl;
};

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/math/TTwist2D.h>

namespace semnav
{
/** A differential-drive robot base: velocity commands with a watchdog,
 * stop, emergency stop and odometry. One of the two seams between semnav's
 * runtime and a robot (the other is SweepSource). Implementations:
 * SimulatedBase (semnav::sim) and the real drivers of semnav-robot.
 *
 * Contract:
 * - setVelocity() commands (v, w) until the next command; the base itself
 *   stops when neither a command nor keepAlive() came for watchdogPeriod().
 * - emergencyStop() stops at once and latches: setVelocity() is refused
 *   (returns false) until resetEmergencyStop().
 * - odometry() answers from a cache and never blocks (MRPT's navigator
 *   asks it every control step and wants an answer in well under 10 ms).
 *
 * Everything may be called from any thread. */
class RobotBase
{
public:
	/** One odometry reading. */
	struct Odometry
	{
		/** Pose in the odometry frame. */
		mrpt::math::TPose2D pose;
		/** Velocity in the robot frame (vx, vy = 0, omega). */
		mrpt::math::TTwist2D velocity;
		/** When it was measured (mrpt::Clock). */
		mrpt::Clock::time_point time{};
		/** Path length travelled since the base started (m). */
		double distance = 0;
	};

	virtual ~RobotBase() = default;

	/** Linear speed v (m/s) and turn rate w (rad/s). False when refused
	 * (emergency stop latched, base gone). */
	virtual bool setVelocity(double v, double w) = 0;
	/** Keeps the current command alive (feeds the watchdog). */
	virtual void keepAlive() = 0;
	/** Commands zero velocity. */
	virtual bool stop() = 0;
	/** Stops at once and latches until resetEmergencyStop(). */
	virtual bool emergencyStop() = 0;
	virtual void resetEmergencyStop() = 0;
	/** True while an emergency stop is latched. */
	virtual bool emergencyStopped() const = 0;
	/** The latest odometry reading (cached; never blocks). */
	virtual Odometry odometry() const = 0;
	/** The base stops when no command comes for this long (s). */
	virtual double watchdogPeriod() const = 0;
};

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/kinematics/CVehicleSimul_DiffDriven.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/robot/RobotBase.h>
#include <semnav/sim/Scene.h>
#include <semnav/sim/SimulatedRobotOptions.h>

#include <cstdint>
#include <random>
#include <vector>

namespace semnav
{
class RayCaster;

/** A simulated differential-drive base in a scene: MRPT's
 * CVehicleSimul_DiffDriven behind the RobotBase seam.
 *
 * - Time is simulated: simulate(dt) advances it and, while the base exists,
 *   MRPT's clock (mrpt::Clock, Simulated source) follows it, so MRPT's
 *   navigator and all timestamps run on simulated time. The previous clock
 *   source is restored by the destructor.
 * - Collisions are checked after every step against the scene: the robot is
 *   a vertical cylinder of robot_radius_m; rays along its radius at each
 *   collision height test it. A step that would collide is undone (the
 *   robot stops at the obstacle) and counted once per contact.
 * - Odometry is integrated from the true motion of each step;
 *   setOdometryNoise() adds a scene's odometry errors to it.
 * - The watchdog: at each step, a non-zero command older than watchdog_s
 *   (no setVelocity() or keepAlive() since) is replaced by a stop.
 * Single-threaded, like the rest of the simulation. */
class SimulatedBase : public RobotBase, public mrpt::system::COutputLogger
{
public:
	/** `caster` (the scene) must outlive the base. */
	SimulatedBase(
	    const RayCaster& caster, const SimulatedRobotOptions& options,
	    const mrpt::math::TPose2D& start);
	~SimulatedBase() override;
	SimulatedBase(const SimulatedBase&) = delete;
	SimulatedBase& operator=(const SimulatedBase&) = delete;

	bool setVelocity(double v, double w) override;
	void keepAlive() override;
	bool stop() override;
	bool emergencyStop() override;
	void resetEmergencyStop() override { m_emergency = false; }
	bool emergencyStopped() const override { return m_emergency; }
	Odometry odometry() const override;
	double watchdogPeriod() const override { return m_options.watchdog; }

	/** Advances the simulation by dt seconds (collision check included). */
	void simulate(double dt);
	/** From now on the odometry of every step gets the errors of `spec`
	 * (per metre travelled in the step: heading bias, heading noise with
	 * std rotNoisePerM * sqrt(d / 1 m), translation noise likewise), drawn
	 * from a generator seeded with `seed`. */
	void setOdometryNoise(const OdometrySpec& spec, uint64_t seed);

	/** The robot is carried to `pose` (kidnapped): the true pose jumps,
	 * the odometry notices nothing. */
	void carryTo(const mrpt::math::TPose2D& pose)
	{
		m_vehicle.setCurrentGTPose(pose);
	}
	/** True when the robot's cylinder at `pose` touches the scene. */
	bool inCollision(const mrpt::math::TPose2D& pose) const;
	/** The true pose. */
	const mrpt::math::TPose2D& pose() const
	{
		return m_vehicle.getCurrentGTPose();
	}
	/** Simulated time (s since the base was made). */
	double time() const { return m_vehicle.getTime(); }
	/** Contacts with the scene (a contact lasting several steps counts
	 * once) and where they happened. */
	int collisions() const { return m_collisions; }
	const std::vector<mrpt::math::TPose2D>& collisionPoses() const
	{
		return m_collisionPoses;
	}
	/** True pose after every step, the start included. */
	const std::vector<mrpt::math::TPose2D>& trajectory() const
	{
		return m_trajectory;
	}
	/** Times the watchdog stopped the base. */
	int watchdogStops() const { return m_watchdogStops; }
	const SimulatedRobotOptions& options() const { return m_options; }
	const RayCaster& caster() const { return m_caster; }

	/** Simulated time t as an MRPT timestamp (t = 0 at 2020-01-01). */
	static mrpt::Clock::time_point timestampOf(double t);

private:
	void send(double v, double w);

	mrpt::kinematics::CVehicleSimul_DiffDriven m_vehicle;
	const RayCaster& m_caster;
	SimulatedRobotOptions m_options;
	int m_collisions = 0;
	bool m_inContact = false;
	std::vector<mrpt::math::TPose2D> m_trajectory;
	std::vector<mrpt::math::TPose2D> m_collisionPoses;
	mrpt::Clock::Source m_previousClock;
	mrpt::math::TPose2D m_odometry;
	double m_odometryDistance = 0;
	bool m_odometryNoise = false;
	OdometrySpec m_odometrySpec;
	std::mt19937_64 m_rng;
	bool m_emergency = false;
	bool m_moving = false;
	double m_lastCommand = 0;
	int m_watchdogStops = 0;
};

}  // namespace semnav

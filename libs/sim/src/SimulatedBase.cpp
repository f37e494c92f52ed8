/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/SimulatedBase.h>

#include <cmath>

namespace semnav
{
namespace
{
constexpr double kEpoch = 1577836800.0;  // 2020-01-01T00:00:00Z
}  // namespace

mrpt::Clock::time_point SimulatedBase::timestampOf(double t)
{
	return mrpt::Clock::fromDouble(kEpoch + t);
}

SimulatedBase::SimulatedBase(
    const RayCaster& caster, const SimulatedRobotOptions& options,
    const mrpt::math::TPose2D& start)
    : mrpt::system::COutputLogger("SimulatedBase"),
      m_caster(caster),
      m_options(options),
      m_previousClock(mrpt::Clock::getActiveClock()),
      m_odometry(start)
{
	m_vehicle.setCurrentGTPose(start);
	m_vehicle.setCurrentOdometricPose(start);
	mrpt::Clock::setSimulatedTime(timestampOf(0));
	mrpt::Clock::setActiveClock(mrpt::Clock::Simulated);
	m_trajectory.push_back(start);
	if (inCollision(start))
	{
		m_collisions = 1;
		m_inContact = true;
		m_collisionPoses.push_back(start);
	}
}

SimulatedBase::~SimulatedBase()
{
	mrpt::Clock::setActiveClock(m_previousClock);
}

void SimulatedBase::send(double v, double w)
{
	mrpt::kinematics::CVehicleVelCmd_DiffDriven cmd;
	cmd.lin_vel = v;
	cmd.ang_vel = w;
	m_vehicle.sendVelCmd(cmd);
	m_moving = v != 0 || w != 0;
	m_lastCommand = m_vehicle.getTime();
}

bool SimulatedBase::setVelocity(double v, double w)
{
	if (m_emergency) return false;
	send(v, w);
	return true;
}

void SimulatedBase::keepAlive()
{
	m_lastCommand = m_vehicle.getTime();
}

bool SimulatedBase::stop()
{
	send(0, 0);
	return true;
}

bool SimulatedBase::emergencyStop()
{
	send(0, 0);
	m_emergency = true;
	return true;
}

RobotBase::Odometry SimulatedBase::odometry() const
{
	Odometry o;
	o.pose = m_odometry;
	o.velocity = m_vehicle.getCurrentGTVelLocal();
	o.time = timestampOf(m_vehicle.getTime());
	o.distance = m_odometryDistance;
	return o;
}

void SimulatedBase::simulate(double dt)
{
	if (m_moving && m_vehicle.getTime() - m_lastCommand > m_options.watchdog)
	{
		MRPT_LOG_WARN_FMT(
		    "watchdog: no command for %.2f s, stopping",
		    m_vehicle.getTime() - m_lastCommand);
		send(0, 0);
		m_watchdogStops++;
	}
	const mrpt::math::TPose2D before = m_vehicle.getCurrentGTPose();
	const mrpt::math::TPose2D odoBefore = m_vehicle.getCurrentOdometricPose();
	m_vehicle.simulateOneTimeStep(dt);
	mrpt::Clock::setSimulatedTime(timestampOf(m_vehicle.getTime()));
	const mrpt::math::TPose2D after = m_vehicle.getCurrentGTPose();
	if (inCollision(after))
	{
		if (!m_inContact)
		{
			m_collisions++;
			m_collisionPoses.push_back(after);
			MRPT_LOG_WARN_FMT(
			    "collision at (%.2f, %.2f), t = %.1f s", after.x, after.y,
			    m_vehicle.getTime());
		}
		m_inContact = true;
		// The obstacle stops the robot: undo the step.
		m_vehicle.setCurrentGTPose(before);
		m_vehicle.setCurrentOdometricPose(odoBefore);
	}
	else
		m_inContact = false;
	m_trajectory.push_back(m_vehicle.getCurrentGTPose());

	// Odometry: the true motion of the step, in the robot frame, with the
	// odometry errors.
	mrpt::poses::CPose2D delta =
	    mrpt::poses::CPose2D(m_vehicle.getCurrentGTPose()) -
	    mrpt::poses::CPose2D(before);
	const double d = delta.norm();
	if (m_odometryNoise && d > 0)
	{
		std::normal_distribution<double> n01(0.0, 1.0);
		const double s = std::sqrt(d);
		const double dt = m_odometrySpec.transNoise * s * n01(m_rng);
		const double k = (d + dt) / d;
		delta = mrpt::poses::CPose2D(
		    delta.x() * k, delta.y() * k,
		    delta.phi() + m_odometrySpec.rotBiasPerM * d +
		        m_odometrySpec.rotNoisePerM * s * n01(m_rng));
	}
	m_odometryDistance += d;
	m_odometry = (mrpt::poses::CPose2D(m_odometry) + delta).asTPose();
	m_odometry.phi = mrpt::math::wrapToPi(m_odometry.phi);
}

void SimulatedBase::setOdometryNoise(const OdometrySpec& spec, uint64_t seed)
{
	m_odometrySpec = spec;
	m_odometryNoise = true;
	m_rng.seed(seed);
}

bool SimulatedBase::inCollision(const mrpt::math::TPose2D& p) const
{
	const double R = m_options.robotRadius;
	const int n = m_options.collisionRays;
	for (double h : m_options.collisionHeights)
		for (int k = 0; k < n; k++)
		{
			const double a = 2 * M_PI * k / n;
			const mrpt::math::TPoint3D d{std::cos(a), std::sin(a), 0};
			const mrpt::math::TPoint3D c{p.x, p.y, h};
			// Outward from the centre, and inward from the rim (catches a
			// solid holding the centre).
			if (m_caster.cast(c, d, R).hit) return true;
			const mrpt::math::TPoint3D rim{c.x + R * d.x, c.y + R * d.y, h};
			if (m_caster.cast(rim, {-d.x, -d.y, 0}, R).hit) return true;
		}
	return false;
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/sim/SimulatedRobot.h>

namespace semnav
{
SimulatedRobot::SimulatedRobot(
    const Scene& scene, const TOptions& options,
    const mrpt::math::TPose2D& start)
    : m_options(options),
      m_caster(scene),
      m_base(m_caster, options, start),
      m_obstacles(m_base),
      m_sweeps(
          m_base, *this, scene.sensor, static_cast<uint64_t>(options.seed),
          options.linePeriod),
      m_localized(m_base),
      m_truth(m_base)
{
}

RobotInterfaces SimulatedRobot::interfaces()
{
	RobotInterfaces r;
	r.base = &m_base;
	r.sweeps = &m_sweeps;
	r.clock = this;
	r.pose = &m_localized;
	r.truth = &m_truth;
	return r;
}

void SimulatedRobot::waitFor(double seconds)
{
	m_base.simulate(seconds);
	if (m_localized.hasEstimate())
		m_localized.trajectory.push_back(m_localized.pose());
}

void SimulatedRobot::enableOdometryNoise(const OdometrySpec& spec)
{
	if (m_options.odometryNoise)
		m_base.setOdometryNoise(
		    spec, static_cast<uint64_t>(m_options.seed) + 7919);
}

void SimulatedRobot::RecordedPose::setEstimate(
    const mrpt::math::TPose2D& mapPose, const mrpt::math::TPose2D& odometry)
{
	LocalizedPose::setEstimate(mapPose, odometry);
	trajectory.push_back(pose());
}

}  // namespace semnav

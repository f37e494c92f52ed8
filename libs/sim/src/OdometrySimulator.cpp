/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/sim/OdometrySimulator.h>

#include <cmath>

namespace semnav
{
OdometrySimulator::OdometrySimulator(
    const OdometrySpec& spec, const mrpt::math::TPose2D& start, uint64_t seed)
    : m_spec(spec), m_odo(start), m_rng(seed ^ 0x0D0E7E1234ULL)
{
}

const mrpt::poses::CPose2D& OdometrySimulator::move(
    const mrpt::math::TPose2D& p0, const mrpt::math::TPose2D& p1)
{
	const mrpt::poses::CPose2D d =
	    mrpt::poses::CPose2D(p1) - mrpt::poses::CPose2D(p0);
	const double s = std::hypot(d.x(), d.y());
	// Always draw three numbers so the stream does not depend on s.
	const double ex = m_normal(m_rng), ey = m_normal(m_rng),
	             ephi = m_normal(m_rng);
	const mrpt::poses::CPose2D noisy(
	    d.x() + m_spec.transNoise * s * ex, d.y() + m_spec.transNoise * s * ey,
	    d.phi() + m_spec.rotBiasPerM * s + m_spec.rotNoisePerM * s * ephi);
	m_odo = m_odo + noisy;
	return m_odo;
}

std::vector<mrpt::poses::CPose2D> OdometrySimulator::simulate(
    const OdometrySpec& spec,
    const std::vector<mrpt::math::TPose2D>& trajectory, uint64_t seed)
{
	std::vector<mrpt::poses::CPose2D> out;
	if (trajectory.empty()) return out;
	OdometrySimulator sim(spec, trajectory.front(), seed);
	out.push_back(sim.odometry());
	for (std::size_t i = 1; i < trajectory.size(); i++)
		out.push_back(sim.move(trajectory[i - 1], trajectory[i]));
	return out;
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/sim/RayCastObstacles.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/SimulatedBase.h>

#include <cmath>

namespace semnav
{
RayCastObstacles::RayCastObstacles(const SimulatedBase& base) : m_base(base) {}

bool RayCastObstacles::sense(
    mrpt::maps::CSimplePointsMap& obstacles, mrpt::Clock::time_point& sensedAt)
{
	obstacles.clear();
	sensedAt = SimulatedBase::timestampOf(m_base.time());
	const SimulatedRobotOptions& o = m_base.options();
	const mrpt::math::TPose2D p = m_base.pose();
	const double fov = o.scanFovDeg * M_PI / 180;
	const int n = o.scanBeams;
	const bool full = o.scanFovDeg >= 360;
	for (double h : o.scanHeights)
		for (int k = 0; k < n; k++)
		{
			const double rel =
			    full ? 2 * M_PI * k / n : -fov / 2 + fov * k / (n - 1);
			const double a = p.phi + rel;
			const RayHit hit = m_base.caster().cast(
			    {p.x, p.y, h}, {std::cos(a), std::sin(a), 0}, o.scanMaxRange);
			if (!hit.hit) continue;
			obstacles.insertPoint(
			    static_cast<float>(hit.range * std::cos(rel)),
			    static_cast<float>(hit.range * std::sin(rel)),
			    static_cast<float>(h));
		}
	return true;
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace semnav
{
/** Errors of an estimated trajectory against ground truth, pose by pose:
 * RMSE of the position, final and maximum absolute heading error. */
class TrajectoryError
{
public:
	void add(const mrpt::poses::CPose2D& est, const mrpt::poses::CPose2D& gt)
	{
		m_sumSq +=
		    mrpt::square(est.x() - gt.x()) + mrpt::square(est.y() - gt.y());
		m_finalYaw = std::abs(mrpt::math::wrapToPi(est.phi() - gt.phi()));
		m_maxYaw = std::max(m_maxYaw, m_finalYaw);
		m_n++;
	}
	std::size_t size() const { return m_n; }
	/** m */
	double rmseXY() const { return m_n ? std::sqrt(m_sumSq / m_n) : 0.0; }
	/** rad */
	double finalYaw() const { return m_finalYaw; }
	double maxYaw() const { return m_maxYaw; }

private:
	double m_sumSq = 0, m_finalYaw = 0, m_maxYaw = 0;
	std::size_t m_n = 0;
};

}  // namespace semnav

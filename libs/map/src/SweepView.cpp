/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/map/SweepView.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace semnav
{
namespace
{
/** A return this far short of the object still sees it (m). */
constexpr double kObjectDepth = 0.4;

/** Index of the value of the sorted `v` nearest to `x`. */
std::size_t nearest(const std::vector<double>& v, double x)
{
	const auto it = std::lower_bound(v.begin(), v.end(), x);
	if (it == v.begin()) return 0;
	if (it == v.end()) return v.size() - 1;
	return static_cast<std::size_t>(
	    (x - *(it - 1) < *it - x) ? it - 1 - v.begin() : it - v.begin());
}

/** Mean step of the sorted angles `v` (1 with fewer than two). */
double stepOf(const std::vector<double>& v)
{
	return v.size() > 1 ? (v.back() - v.front()) / double(v.size() - 1) : 1;
}
/** Where `p` lies from the sweep's tilt axis. */
struct Direction
{
	double dx, dy, d, theta, phi;
};

/** The direction of `p`, when it is in range and in the field of view.
 * (The tilt axis: rows differ by a few cm, the laser's offset from it.) */
std::optional<Direction> directionIn(
    const Sweep& s, const mrpt::math::TPoint3D& p)
{
	const auto& axis = s.sensorPose(s.rows() / 2);
	Direction v;
	v.dx = p.x - axis.x();
	v.dy = p.y - axis.y();
	const double dz = p.z - axis.z();
	v.d = std::sqrt(v.dx * v.dx + v.dy * v.dy + dz * dz);
	if (v.d < 0.2 || v.d > s.maxRange() - kObjectDepth) return std::nullopt;
	v.theta = std::atan2(dz, v.dx);
	v.phi = std::asin(v.dy / v.d);
	const auto& thetas = s.thetas();
	const auto& phis = s.phis();
	if (v.theta < thetas.front() || v.theta > thetas.back() ||
	    v.phi < phis.front() || v.phi > phis.back())
		return std::nullopt;
	return v;
}
}  // namespace

SweepView::SweepView(const Sweep& sweep, double maxBearing, double minPixels)
    : m_sweep(sweep),
      m_maxBearing(maxBearing),
      m_minPixels(minPixels),
      m_phiStep(stepOf(sweep.phis())),
      m_thetaStep(stepOf(sweep.thetas()))
{
}

bool SweepView::unhidden(const mrpt::math::TPoint3D& p) const
{
	const Sweep& s = m_sweep;
	const auto v = directionIn(s, p);
	if (!v) return false;
	const double d = v->d;
	const std::size_t r0 = nearest(s.thetas(), v->theta),
	                  c0 = nearest(s.phis(), v->phi);
	for (std::size_t r = r0 > 0 ? r0 - 1 : 0;
	     r <= std::min(r0 + 1, s.rows() - 1); r++)
		for (std::size_t c = c0 > 0 ? c0 - 1 : 0;
		     c <= std::min(c0 + 1, s.cols() - 1); c++)
			if (!s.valid(r, c) || s.range(r, c) >= d - kObjectDepth)
				return true;
	return false;
}

bool SweepView::inField(
    const mrpt::math::TPoint3D& centroid,
    const mrpt::math::TPoint3D& size) const
{
	const Sweep& s = m_sweep;
	if (s.empty()) return false;
	const auto v = directionIn(s, centroid);
	if (!v || std::abs(std::atan2(v->dy, v->dx)) > m_maxBearing) return false;
	const double d = v->d;
	// Pixels the object would cover at this distance (its typical detection
	// size: from where a real one is too small for the cascades, no view).
	const double wide = std::max(size.x, 0.2), high = std::max(size.z, 0.3);
	const double px = (wide / d) / m_phiStep * (high / d) / m_thetaStep;
	return px >= m_minPixels;
}

bool SweepView::sees(
    const mrpt::math::TPoint3D& centroid,
    const mrpt::math::TPoint3D& size) const
{
	return inField(centroid, size) && unhidden(centroid);
}

double SweepView::visibleShare(
    const mrpt::math::TPoint3D& centroid,
    const mrpt::math::TPoint3D& size) const
{
	if (!inField(centroid, size)) return 0;
	const auto& axis = m_sweep.sensorPose(m_sweep.rows() / 2);
	// Across the line of sight, horizontally.
	const double lx = centroid.x - axis.x(), ly = centroid.y - axis.y();
	const double ln = std::max(std::hypot(lx, ly), 1e-6);
	const double ax = -ly / ln, ay = lx / ln;
	int seen = 0;
	for (int i = -1; i <= 1; i++)
		for (int k = -1; k <= 1; k++)
		{
			const double u = i * size.x / 3, v = k * size.z / 3;
			if (unhidden(
			        {centroid.x + u * ax, centroid.y + u * ay, centroid.z + v}))
				seen++;
		}
	return seen / 9.0;
}

}  // namespace semnav

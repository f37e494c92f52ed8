/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/nav/WaypointBuilder.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
bool WaypointBuilder::lineOfSight(
    const TraversabilityGrid& u, const mrpt::math::TPoint2D& a,
    const mrpt::math::TPoint2D& b, double maxU)
{
	const GridGeometry& g = u.geometry();
	const double len = std::hypot(b.x - a.x, b.y - a.y);
	// Samples every quarter cell: no cell the segment crosses is missed by
	// more than a corner.
	const int n =
	    std::max(1, static_cast<int>(std::ceil(len / (0.25 * g.resolution))));
	for (int k = 0; k <= n; k++)
	{
		const double t = static_cast<double>(k) / n;
		const auto c = g.cellOf(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
		if (!c) return false;
		const double v = u.u(c->row, c->col);
		if (u.blocked(*c) || v > maxU) return false;
	}
	return true;
}

std::vector<mrpt::math::TPoint2D> WaypointBuilder::thin(
    const PlannedPath& path, const TraversabilityGrid& u, double maxSpacing)
{
	std::vector<mrpt::math::TPoint2D> out;
	const auto& p = path.points;
	if (p.empty()) return out;
	out.push_back(p.front());
	std::size_t i = 0;
	while (i + 1 < p.size())
	{
		// Farthest j visible from i whose replaced cells are no cheaper
		// than the segment.
		std::size_t best = i + 1;
		double maxU = 0;
		for (std::size_t j = i + 1; j < p.size(); j++)
		{
			const auto& c = path.cells[j];
			maxU = std::max(maxU, u.u(c.row, c.col));
			if (std::hypot(p[j].x - p[i].x, p[j].y - p[i].y) > maxSpacing)
				break;
			if (lineOfSight(u, p[i], p[j], maxU + 1e-9)) best = j;
		}
		out.push_back(p[best]);
		i = best;
	}
	return out;
}

mrpt::nav::TWaypointSequence WaypointBuilder::toSequence(
    const std::vector<mrpt::math::TPoint2D>& points, double allowedDistance,
    double finalAllowedDistance)
{
	mrpt::nav::TWaypointSequence seq;
	for (std::size_t k = 1; k < points.size(); k++)
	{
		const bool last = k + 1 == points.size();
		seq.waypoints.emplace_back(
		    points[k].x, points[k].y,
		    last ? finalAllowedDistance : allowedDistance, !last);
	}
	return seq;
}

}  // namespace semnav

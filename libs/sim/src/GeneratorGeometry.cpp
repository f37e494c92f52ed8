/* semnav: semantic navigation from tilting-laser sweeps */
#include "GeneratorGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace semnav::detail
{
using mrpt::math::TPoint2D;

Polygon2D rectPolygon(double cx, double cy, double sx, double sy, double yaw)
{
	const double c = std::cos(yaw), s = std::sin(yaw);
	Polygon2D p;
	for (const auto& [u, v] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
	{
		const double lx = 0.5 * u * sx, ly = 0.5 * v * sy;
		p.emplace_back(cx + c * lx - s * ly, cy + s * lx + c * ly);
	}
	return p;
}

Polygon2D circlePolygon(double cx, double cy, double r)
{
	constexpr int kSides = 12;
	const double R = r / std::cos(M_PI / kSides);
	Polygon2D p;
	for (int k = 0; k < kSides; k++)
	{
		const double a = 2 * M_PI * k / kSides;
		p.emplace_back(cx + R * std::cos(a), cy + R * std::sin(a));
	}
	return p;
}

double distPointSegment(const TPoint2D& p, const TPoint2D& a, const TPoint2D& b)
{
	const double dx = b.x - a.x, dy = b.y - a.y;
	const double len2 = dx * dx + dy * dy;
	double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0;
	t = std::clamp(t, 0.0, 1.0);
	return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

namespace
{
double cross(const TPoint2D& o, const TPoint2D& a, const TPoint2D& b)
{
	return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

bool insideConvex(const TPoint2D& p, const Polygon2D& poly)
{
	bool pos = false, neg = false;
	for (std::size_t i = 0; i < poly.size(); i++)
	{
		const double c = cross(poly[i], poly[(i + 1) % poly.size()], p);
		pos = pos || c > 0;
		neg = neg || c < 0;
	}
	return !(pos && neg);
}

bool segmentsCross(
    const TPoint2D& a, const TPoint2D& b, const TPoint2D& c, const TPoint2D& d)
{
	const double d1 = cross(c, d, a), d2 = cross(c, d, b);
	const double d3 = cross(a, b, c), d4 = cross(a, b, d);
	return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}
}  // namespace

double distPointPolygon(const TPoint2D& p, const Polygon2D& poly)
{
	if (insideConvex(p, poly)) return 0;
	double d = std::numeric_limits<double>::infinity();
	for (std::size_t i = 0; i < poly.size(); i++)
		d = std::min(
		    d, distPointSegment(p, poly[i], poly[(i + 1) % poly.size()]));
	return d;
}

double distSegmentPolygon(
    const TPoint2D& a, const TPoint2D& b, const Polygon2D& poly)
{
	if (insideConvex(a, poly) || insideConvex(b, poly)) return 0;
	double d = std::min(distPointPolygon(a, poly), distPointPolygon(b, poly));
	for (std::size_t i = 0; i < poly.size(); i++)
	{
		const auto& c = poly[i];
		const auto& e = poly[(i + 1) % poly.size()];
		if (segmentsCross(a, b, c, e)) return 0;
		d = std::min(d, distPointSegment(c, a, b));
	}
	return d;
}

double distPolygons(const Polygon2D& p, const Polygon2D& q)
{
	if (!q.empty() && insideConvex(q[0], p)) return 0;
	double d = std::numeric_limits<double>::infinity();
	for (std::size_t i = 0; i < p.size(); i++)
		d = std::min(d, distSegmentPolygon(p[i], p[(i + 1) % p.size()], q));
	return d;
}

}  // namespace semnav::detail

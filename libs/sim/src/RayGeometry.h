/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
/* RayCaster's geometry: rays, bounding boxes and the primitives (boxes,
 * cylinders, terrain patches) with their ray intersections. Internal to
 * the sim library. */

#include <mrpt/math/TPoint2D.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace semnav::detail
{
constexpr double kInf = std::numeric_limits<double>::infinity();
/** Terrain roots are refined until the bracket is shorter than this (m). */
constexpr double kBisectTol = 1e-5;
/** A terrain root this close to its polygon (m) still counts as terrain:
 * the floor stops exactly at the polygon, so no ray slips between. */
constexpr double kTerrainEdgeTol = 1e-3;

struct Aabb
{
	std::array<double, 3> lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};

	void add(double x, double y, double z)
	{
		lo[0] = std::min(lo[0], x);
		lo[1] = std::min(lo[1], y);
		lo[2] = std::min(lo[2], z);
		hi[0] = std::max(hi[0], x);
		hi[1] = std::max(hi[1], y);
		hi[2] = std::max(hi[2], z);
	}
	void add(const Aabb& b)
	{
		add(b.lo[0], b.lo[1], b.lo[2]);
		add(b.hi[0], b.hi[1], b.hi[2]);
	}
	void pad(double p)
	{
		for (int k = 0; k < 3; k++)
		{
			lo[k] -= p;
			hi[k] += p;
		}
	}
	double centre(int k) const { return 0.5 * (lo[k] + hi[k]); }
};

/** A ray with precomputed inverse direction. */
struct Ray
{
	std::array<double, 3> o, d, inv;
	double maxRange;
};

/** Slab test; the entry parameter (clamped at 0) in `tEnter`. */
inline bool hitAabb(const Aabb& b, const Ray& r, double tMax, double& tEnter)
{
	double t0 = 0, t1 = tMax;
	for (int k = 0; k < 3; k++)
	{
		if (r.d[k] == 0)
		{
			if (r.o[k] < b.lo[k] || r.o[k] > b.hi[k]) return false;
			continue;
		}
		double a = (b.lo[k] - r.o[k]) * r.inv[k];
		double c = (b.hi[k] - r.o[k]) * r.inv[k];
		if (a > c) std::swap(a, c);
		t0 = std::max(t0, a);
		t1 = std::min(t1, c);
		if (t0 > t1) return false;
	}
	tEnter = t0;
	return true;
}

/** Entry/exit of the ray in the slab lo <= o + t d <= hi (one axis). */
inline bool slab(
    double o, double d, double lo, double hi, double& t0, double& t1)
{
	if (d == 0) return o >= lo && o <= hi;
	double a = (lo - o) / d, c = (hi - o) / d;
	if (a > c) std::swap(a, c);
	t0 = std::max(t0, a);
	t1 = std::min(t1, c);
	return t0 <= t1;
}

struct BoxPrim
{
	double cx, cy, cz, c, s, hx, hy, hz;
};

struct CylPrim
{
	double cx, cy, zlo, zhi, r;
};

/** Crossing-number point-in-polygon test. */
inline bool insidePolygon(
    const std::vector<mrpt::math::TPoint2D>& poly, double x, double y)
{
	bool in = false;
	const std::size_t n = poly.size();
	for (std::size_t i = 0, j = n - 1; i < n; j = i++)
	{
		const auto& a = poly[i];
		const auto& b = poly[j];
		if ((a.y > y) != (b.y > y))
		{
			const double xc = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
			if (x < xc) in = !in;
		}
	}
	return in;
}

inline double distToPolygon(
    const std::vector<mrpt::math::TPoint2D>& poly, double x, double y)
{
	double best = kInf;
	const std::size_t n = poly.size();
	for (std::size_t i = 0, j = n - 1; i < n; j = i++)
	{
		const double ax = poly[j].x, ay = poly[j].y;
		const double ex = poly[i].x - ax, ey = poly[i].y - ay;
		const double l2 = ex * ex + ey * ey;
		double u = l2 > 0 ? ((x - ax) * ex + (y - ay) * ey) / l2 : 0;
		u = std::clamp(u, 0.0, 1.0);
		const double dx = x - (ax + u * ex), dy = y - (ay + u * ey);
		best = std::min(best, dx * dx + dy * dy);
	}
	return std::sqrt(best);
}

enum CellKind : uint8_t
{
	kExterior = 0,
	kInterior = 1,
	kBoundary = 2
};

/** Height field of one terrain patch (see RayCaster.h). */
struct TerrainPrim
{
	std::vector<mrpt::math::TPoint2D> poly;
	double pxmin, pymin, pxmax, pymax;  // polygon bounding box
	double x0, y0, cell, taper;
	int cx, cy;  // cells; nodes are (cx + 1) x (cy + 1)
	std::vector<double> node;
	std::vector<uint8_t> kind;
	std::vector<double> cellLo, cellHi;
	double hmin = 0, hmax = 0;

	bool inBox(double x, double y) const
	{
		return x >= pxmin && x <= pxmax && y >= pymin && y <= pymax;
	}
	bool inside(double x, double y) const
	{
		return inBox(x, y) && insidePolygon(poly, x, y);
	}
	double nodeAt(int i, int j) const { return node[j * (cx + 1) + i]; }

	/** Height at (x, y); 0 outside the polygon. */
	double height(double x, double y) const
	{
		const double fx = (x - x0) / cell, fy = (y - y0) / cell;
		if (!(fx >= 0 && fy >= 0 && fx <= cx && fy <= cy)) return 0;
		const int i = std::min(static_cast<int>(fx), cx - 1);
		const int j = std::min(static_cast<int>(fy), cy - 1);
		const uint8_t k = kind[j * cx + i];
		if (k == kExterior) return 0;
		const double u = fx - i, v = fy - j;
		const double g =
		    (1 - v) * ((1 - u) * nodeAt(i, j) + u * nodeAt(i + 1, j)) +
		    v * ((1 - u) * nodeAt(i, j + 1) + u * nodeAt(i + 1, j + 1));
		if (k == kInterior) return g;
		if (!insidePolygon(poly, x, y)) return 0;
		return g * std::min(1.0, distToPolygon(poly, x, y) / taper);
	}
};

inline bool intersectBox(const BoxPrim& b, const Ray& r, double& t)
{
	const double px = r.o[0] - b.cx, py = r.o[1] - b.cy, pz = r.o[2] - b.cz;
	const double lx = b.c * px + b.s * py, ly = -b.s * px + b.c * py;
	const double dx = b.c * r.d[0] + b.s * r.d[1];
	const double dy = -b.s * r.d[0] + b.c * r.d[1];
	double t0 = -kInf, t1 = kInf;
	if (!slab(lx, dx, -b.hx, b.hx, t0, t1)) return false;
	if (!slab(ly, dy, -b.hy, b.hy, t0, t1)) return false;
	if (!slab(pz, r.d[2], -b.hz, b.hz, t0, t1)) return false;
	if (t0 < 0) return false;  // behind, or origin inside the solid
	t = t0;
	return true;
}

inline bool intersectCyl(const CylPrim& c, const Ray& r, double& t)
{
	const double px = r.o[0] - c.cx, py = r.o[1] - c.cy;
	const double a = r.d[0] * r.d[0] + r.d[1] * r.d[1];
	const double cc = px * px + py * py - c.r * c.r;
	double t0 = -kInf, t1 = kInf;
	if (a < 1e-18)
	{
		if (cc > 0) return false;
	}
	else
	{
		const double b = px * r.d[0] + py * r.d[1];
		const double disc = b * b - a * cc;
		if (disc < 0) return false;
		const double sq = std::sqrt(disc);
		t0 = (-b - sq) / a;
		t1 = (-b + sq) / a;
	}
	if (!slab(r.o[2], r.d[2], c.zlo, c.zhi, t0, t1)) return false;
	if (t0 < 0) return false;
	t = t0;
	return true;
}

/** First crossing of the terrain surface with t in [0, r.maxRange];
 * cells starting beyond `stopAt` are not visited (they cannot win). The
 * arithmetic does not depend on `stopAt`, so both caster modes agree. */
bool intersectTerrain(
    const TerrainPrim& T, const Ray& r, double stopAt, double& tHit);

}  // namespace semnav::detail

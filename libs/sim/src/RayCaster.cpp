/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/sim/RayCaster.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>

namespace semnav
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
/** Padding of bounding boxes, so culling never rejects an exact hit. */
constexpr double kPad = 1e-6;
/** Terrain roots are refined until the bracket is shorter than this (m). */
constexpr double kBisectTol = 1e-5;
/** A terrain root this close to its polygon (m) still counts as terrain:
 * the floor stops exactly at the polygon, so no ray slips between. */
constexpr double kTerrainEdgeTol = 1e-3;

uint64_t splitMix64(uint64_t x)
{
	x += 0x9E3779B97F4A7C15ULL;
	x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
	x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
	return x ^ (x >> 31);
}

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
bool hitAabb(const Aabb& b, const Ray& r, double tMax, double& tEnter)
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
bool slab(double o, double d, double lo, double hi, double& t0, double& t1)
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
bool insidePolygon(
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

double distToPolygon(
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

/** Primitive reference: type, index into the per-type arrays, label. */
struct Prim
{
	enum Type : uint8_t
	{
		kBox,
		kCyl,
		kTerrain
	} type;
	int index;
	Label label;
	int instance;
	Aabb box;
};

struct BvhNode
{
	Aabb box;
	int left = -1, right = -1;  // children (internal nodes)
	int first = 0, count = 0;   // primitive range (leaves)
};

/** Nearest hit so far; ties go to the lowest `order`. */
struct Best
{
	double t;
	int order = INT_MAX;
	Label label = Label::Unknown;
	int instance = 0;

	void offer(double tt, int ord, Label l, int inst)
	{
		if (tt < t || (tt == t && ord < order))
		{
			t = tt;
			order = ord;
			label = l;
			instance = inst;
		}
	}
};

bool intersectBox(const BoxPrim& b, const Ray& r, double& t)
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

bool intersectCyl(const CylPrim& c, const Ray& r, double& t)
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
    const TerrainPrim& T, const Ray& r, double stopAt, double& tHit)
{
	// Clip to the grid area and the z band the surface can occupy.
	double t0 = 0, t1 = r.maxRange;
	const double eps = 1e-9;
	if (!slab(r.o[0], r.d[0], T.x0, T.x0 + T.cx * T.cell, t0, t1)) return false;
	if (!slab(r.o[1], r.d[1], T.y0, T.y0 + T.cy * T.cell, t0, t1)) return false;
	if (!slab(r.o[2], r.d[2], T.hmin - eps, T.hmax + eps, t0, t1)) return false;
	if (t0 > stopAt) return false;

	auto f = [&](double t)
	{
		return r.o[2] + t * r.d[2] -
		       T.height(r.o[0] + t * r.d[0], r.o[1] + t * r.d[1]);
	};
	// Bisection on a bracket whose ends lie on different sides of the
	// surface; accepts the root if it lies on the patch.
	auto tryRoot = [&](double lo, double hi, bool loAbove, double& t)
	{
		while (hi - lo > kBisectTol)
		{
			const double mid = 0.5 * (lo + hi);
			if ((f(mid) > 0) == loAbove)
				lo = mid;
			else
				hi = mid;
		}
		t = 0.5 * (lo + hi);
		const double x = r.o[0] + t * r.d[0], y = r.o[1] + t * r.d[1];
		return T.inside(x, y) || distToPolygon(T.poly, x, y) < kTerrainEdgeTol;
	};
	const double dxy = std::hypot(r.d[0], r.d[1]);
	// March step: a quarter cell horizontally.
	const double step = dxy > 1e-12 ? 0.25 * T.cell / dxy : kInf;

	// 2D DDA over the grid cells.
	const double sx = r.o[0] + t0 * r.d[0], sy = r.o[1] + t0 * r.d[1];
	int i = std::clamp(
	    static_cast<int>(std::floor((sx - T.x0) / T.cell)), 0, T.cx - 1);
	int j = std::clamp(
	    static_cast<int>(std::floor((sy - T.y0) / T.cell)), 0, T.cy - 1);
	const int di = r.d[0] > 0 ? 1 : (r.d[0] < 0 ? -1 : 0);
	const int dj = r.d[1] > 0 ? 1 : (r.d[1] < 0 ? -1 : 0);
	auto nextX = [&](int ii)
	{
		if (di == 0) return kInf;
		const double xb = T.x0 + (di > 0 ? ii + 1 : ii) * T.cell;
		return (xb - r.o[0]) / r.d[0];
	};
	auto nextY = [&](int jj)
	{
		if (dj == 0) return kInf;
		const double yb = T.y0 + (dj > 0 ? jj + 1 : jj) * T.cell;
		return (yb - r.o[1]) / r.d[1];
	};
	double tx = nextX(i), ty = nextY(j);
	double ta = t0;
	const int maxIter = T.cx + T.cy + 4;
	for (int it = 0; it < maxIter; it++)
	{
		if (ta > stopAt) return false;
		const double tb = std::min({tx, ty, t1});
		const uint8_t kind = T.kind[j * T.cx + i];
		if (kind != kExterior && tb >= ta)
		{
			const double za = r.o[2] + ta * r.d[2], zb = r.o[2] + tb * r.d[2];
			const double zlo = std::min(za, zb), zhi = std::max(za, zb);
			if (zhi >= T.cellLo[j * T.cx + i] - eps &&
			    zlo <= T.cellHi[j * T.cx + i] + eps)
			{
				if (kind == kInterior)
				{
					// Inside a cell the surface is bilinear, so f is a
					// quadratic in t: fit it through 3 samples and bracket its
					// first root, also when the ray dips under a bump and out
					// again.
					const double fa = f(ta), fb = f(tb),
					             fm = f(0.5 * (ta + tb));
					const double B = -3 * fa + 4 * fm - fb,
					             C = 2 * fa - 4 * fm + 2 * fb;
					double hi = -1;
					if ((fa > 0) != (fb > 0))
						hi = tb;
					else if (C != 0)
					{
						const double sv = -B / (2 * C);
						if (sv > 0 && sv < 1 &&
						    ((fa - B * B / (4 * C)) > 0) != (fa > 0))
							hi = ta + sv * (tb - ta);
					}
					if (hi >= 0 && (f(hi) > 0) != (fa > 0) &&
					    tryRoot(ta, hi, fa > 0, tHit))
						return true;
				}
				else
				{
					// Boundary cell (tapered): march a quarter cell at a time.
					const int n = std::max(
					    1, static_cast<int>(std::ceil((tb - ta) / step)));
					double tp = ta, fp = f(ta);
					for (int k = 1; k <= n; k++)
					{
						const double tc =
						    (k == n) ? tb : ta + (tb - ta) * k / n;
						const double fc = f(tc);
						if ((fp > 0) != (fc > 0) &&
						    tryRoot(tp, tc, fp > 0, tHit))
							return true;
						tp = tc;
						fp = fc;
					}
				}
			}
		}
		if (tb >= t1) break;
		if (tx <= ty)
		{
			i += di;
			tx = nextX(i);
		}
		else
		{
			j += dj;
			ty = nextY(j);
		}
		if (i < 0 || j < 0 || i >= T.cx || j >= T.cy) break;
		ta = tb;
	}
	return false;
}

std::string what(const SceneObject& o, std::size_t idx)
{
	return "scene object " + std::to_string(idx + 1) + " (" +
	       labelName(o.label) +
	       (o.line > 0 ? ", line " + std::to_string(o.line) : std::string()) +
	       ")";
}

}  // namespace

struct RayCaster::Impl
{
	SceneBounds bounds;
	bool hasFloor = false;
	bool hasCeiling = false;
	double ceiling = 0;
	std::vector<BoxPrim> boxes;
	std::vector<CylPrim> cyls;
	std::vector<TerrainPrim> terrains;
	std::vector<Prim> prims;    // scene order; index = tie-break order
	std::vector<int> bvhPrims;  // primitive indices ordered by leaves
	std::vector<BvhNode> bvh;

	void addBox(const BoxShape& b, Label l, int inst)
	{
		BoxPrim p{b.center.x,      b.center.y,      b.center.z,
		          std::cos(b.yaw), std::sin(b.yaw), 0.5 * b.size.x,
		          0.5 * b.size.y,  0.5 * b.size.z};
		Prim pr{Prim::kBox, static_cast<int>(boxes.size()), l, inst, {}};
		for (int sx = -1; sx <= 1; sx += 2)
			for (int sy = -1; sy <= 1; sy += 2)
			{
				const double lx = sx * p.hx, ly = sy * p.hy;
				pr.box.add(
				    p.cx + p.c * lx - p.s * ly, p.cy + p.s * lx + p.c * ly,
				    p.cz - p.hz);
				pr.box.add(
				    p.cx + p.c * lx - p.s * ly, p.cy + p.s * lx + p.c * ly,
				    p.cz + p.hz);
			}
		pr.box.pad(kPad);
		boxes.push_back(p);
		prims.push_back(pr);
	}

	void addCyl(const CylinderShape& c, Label l, int inst)
	{
		CylPrim p{
		    c.center.x, c.center.y, c.center.z - 0.5 * c.height,
		    c.center.z + 0.5 * c.height, c.radius};
		Prim pr{Prim::kCyl, static_cast<int>(cyls.size()), l, inst, {}};
		pr.box.add(p.cx - p.r, p.cy - p.r, p.zlo);
		pr.box.add(p.cx + p.r, p.cy + p.r, p.zhi);
		pr.box.pad(kPad);
		cyls.push_back(p);
		prims.push_back(pr);
	}

	void addTerrain(
	    const TerrainShape& t, Label l, int inst, double cell, uint64_t seed)
	{
		TerrainPrim T;
		T.poly = t.polygon;
		T.pxmin = T.pymin = kInf;
		T.pxmax = T.pymax = -kInf;
		for (const auto& p : t.polygon)
		{
			T.pxmin = std::min(T.pxmin, p.x);
			T.pymin = std::min(T.pymin, p.y);
			T.pxmax = std::max(T.pxmax, p.x);
			T.pymax = std::max(T.pymax, p.y);
		}
		T.cell = cell;
		T.taper = kTerrainTaperCells * cell;
		T.x0 = T.pxmin;
		T.y0 = T.pymin;
		T.cx = std::max(
		    1, static_cast<int>(std::ceil((T.pxmax - T.pxmin) / cell)));
		T.cy = std::max(
		    1, static_cast<int>(std::ceil((T.pymax - T.pymin) / cell)));
		if (static_cast<double>(T.cx) * T.cy > 2e8)
			throw Error(
			    "terrain patch too large for a grid of " +
			    std::to_string(cell) + " m");

		// Node heights: i.i.d. Gaussian, std 1.5 * roughness (see header).
		std::mt19937_64 rng(seed);
		std::normal_distribution<double> nd(0.0, 1.0);
		const double sigma = 1.5 * t.roughness;
		T.node.resize(static_cast<std::size_t>(T.cx + 1) * (T.cy + 1));
		for (auto& v : T.node) v = sigma * nd(rng);

		const double halfDiag = 0.5 * std::sqrt(2.0) * cell;
		T.kind.resize(static_cast<std::size_t>(T.cx) * T.cy);
		T.cellLo.assign(T.kind.size(), 0);
		T.cellHi.assign(T.kind.size(), 0);
		for (int j = 0; j < T.cy; j++)
			for (int i = 0; i < T.cx; i++)
			{
				const double x = T.x0 + (i + 0.5) * cell,
				             y = T.y0 + (j + 0.5) * cell;
				const bool in = insidePolygon(T.poly, x, y);
				const double d = distToPolygon(T.poly, x, y);
				uint8_t k = kBoundary;
				if (in && d >= T.taper + halfDiag)
					k = kInterior;
				else if (!in && d >= halfDiag)
					k = kExterior;
				const std::size_t c = static_cast<std::size_t>(j) * T.cx + i;
				T.kind[c] = k;
				if (k == kExterior) continue;
				const double a = T.nodeAt(i, j), b = T.nodeAt(i + 1, j);
				const double e = T.nodeAt(i, j + 1), g = T.nodeAt(i + 1, j + 1);
				double lo = std::min({a, b, e, g}), hi = std::max({a, b, e, g});
				if (k == kBoundary)
				{
					lo = std::min(lo, 0.0);
					hi = std::max(hi, 0.0);
				}
				T.cellLo[c] = lo;
				T.cellHi[c] = hi;
				T.hmin = std::min(T.hmin, lo);
				T.hmax = std::max(T.hmax, hi);
			}

		Prim pr{Prim::kTerrain, static_cast<int>(terrains.size()), l, inst, {}};
		pr.box.add(T.x0, T.y0, T.hmin);
		pr.box.add(T.x0 + T.cx * cell, T.y0 + T.cy * cell, T.hmax);
		pr.box.pad(kPad);
		terrains.push_back(std::move(T));
		prims.push_back(pr);
	}

	int buildBvh(int first, int count)
	{
		BvhNode node;
		for (int k = first; k < first + count; k++)
			node.box.add(prims[bvhPrims[k]].box);
		const int idx = static_cast<int>(bvh.size());
		bvh.push_back(node);
		if (count <= 2)
		{
			bvh[idx].first = first;
			bvh[idx].count = count;
			return idx;
		}
		Aabb cb;
		for (int k = first; k < first + count; k++)
		{
			const auto& b = prims[bvhPrims[k]].box;
			cb.add(b.centre(0), b.centre(1), b.centre(2));
		}
		int axis = 0;
		for (int a = 1; a < 3; a++)
			if (cb.hi[a] - cb.lo[a] > cb.hi[axis] - cb.lo[axis]) axis = a;
		const int mid = first + count / 2;
		std::nth_element(
		    bvhPrims.begin() + first, bvhPrims.begin() + mid,
		    bvhPrims.begin() + first + count,
		    [&](int a, int b)
		    {
			    const double ca = prims[a].box.centre(axis),
			                 cbv = prims[b].box.centre(axis);
			    return ca < cbv || (ca == cbv && a < b);
		    });
		const int l = buildBvh(first, mid - first);
		const int r = buildBvh(mid, first + count - mid);
		bvh[idx].left = l;
		bvh[idx].right = r;
		return idx;
	}

	void testPrim(int pi, const Ray& r, Best& best) const
	{
		const Prim& p = prims[pi];
		double t = 0;
		bool h = false;
		switch (p.type)
		{
			case Prim::kBox:
				h = intersectBox(boxes[p.index], r, t);
				break;
			case Prim::kCyl:
				h = intersectCyl(cyls[p.index], r, t);
				break;
			case Prim::kTerrain:
				h = intersectTerrain(terrains[p.index], r, best.t, t);
				break;
		}
		if (h && t <= r.maxRange) best.offer(t, pi, p.label, p.instance);
	}

	void testPlanes(const Ray& r, Best& best) const
	{
		if (r.d[2] == 0) return;
		if (hasFloor)
		{
			const double t = -r.o[2] / r.d[2];
			if (t >= 0 && t <= r.maxRange)
			{
				const double x = r.o[0] + t * r.d[0], y = r.o[1] + t * r.d[1];
				bool ok = bounds.contains(x, y);
				for (std::size_t k = 0; ok && k < terrains.size(); k++)
					if (terrains[k].inside(x, y)) ok = false;
				if (ok) best.offer(t, -2, Label::Floor, 0);
			}
		}
		if (hasCeiling)
		{
			const double t = (ceiling - r.o[2]) / r.d[2];
			if (t >= 0 && t <= r.maxRange)
			{
				const double x = r.o[0] + t * r.d[0], y = r.o[1] + t * r.d[1];
				if (bounds.contains(x, y)) best.offer(t, -1, Label::Ceiling, 0);
			}
		}
	}
};

RayCaster::RayCaster(const Scene& scene, uint64_t seed, double terrainCell)
    : m_impl(std::make_unique<Impl>())
{
	if (!(terrainCell > 0))
		throw Error("RayCaster: terrain cell size must be > 0");
	Impl& I = *m_impl;
	I.bounds = scene.bounds;
	I.hasFloor = scene.bounds.xmax > scene.bounds.xmin &&
	             scene.bounds.ymax > scene.bounds.ymin;
	I.hasCeiling = I.hasFloor && scene.ceilingHeight.has_value();
	I.ceiling = scene.ceilingHeight.value_or(0);

	for (std::size_t oi = 0; oi < scene.objects.size(); oi++)
	{
		const SceneObject& o = scene.objects[oi];
		m_maxInstance = std::max(m_maxInstance, o.id);
		for (std::size_t pi = 0; pi < o.parts.size(); pi++)
		{
			const auto& part = o.parts[pi];
			if (const auto* b = std::get_if<BoxShape>(&part))
			{
				if (!(b->size.x > 0 && b->size.y > 0 && b->size.z > 0))
					throw SceneError(what(o, oi) + ": box size must be > 0");
				I.addBox(*b, o.label, o.id);
			}
			else if (const auto* c = std::get_if<CylinderShape>(&part))
			{
				if (!(c->radius > 0 && c->height > 0))
					throw SceneError(
					    what(o, oi) +
					    ": cylinder radius and height must be > 0");
				I.addCyl(*c, o.label, o.id);
			}
			else if (const auto* s = std::get_if<StairsShape>(&part))
			{
				if (!(s->steps > 0 && s->rise > 0 && s->run > 0 &&
				      s->width > 0))
					throw SceneError(
					    what(o, oi) +
					    ": stairs need steps, rise, run, width > 0");
				// Step k: solid block [k run, (k+1) run] along the climb,
				// full width, from the floor to (k+1) rise.
				const double c = std::cos(s->yaw), sn = std::sin(s->yaw);
				for (int k = 0; k < s->steps; k++)
				{
					const double u = (k + 0.5) * s->run;
					BoxShape b;
					b.center = {
					    s->origin.x + c * u, s->origin.y + sn * u,
					    0.5 * (k + 1) * s->rise};
					b.size = {s->run, s->width, (k + 1) * s->rise};
					b.yaw = s->yaw;
					I.addBox(b, o.label, o.id);
				}
			}
			else if (const auto* t = std::get_if<TerrainShape>(&part))
			{
				if (t->polygon.size() < 3)
					throw SceneError(
					    what(o, oi) + ": terrain polygon needs >= 3 vertices");
				if (!(t->roughness >= 0))
					throw SceneError(
					    what(o, oi) + ": terrain roughness must be >= 0");
				const uint64_t s =
				    splitMix64(splitMix64(splitMix64(seed) ^ oi) ^ pi);
				I.addTerrain(*t, o.label, o.id, terrainCell, s);
			}
		}
	}

	I.bvhPrims.resize(I.prims.size());
	std::iota(I.bvhPrims.begin(), I.bvhPrims.end(), 0);
	if (!I.prims.empty()) I.buildBvh(0, static_cast<int>(I.prims.size()));
}

RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

std::size_t RayCaster::primitiveCount() const
{
	return m_impl->prims.size();
}

double RayCaster::groundHeight(double x, double y) const
{
	for (const auto& T : m_impl->terrains)
		if (T.inside(x, y)) return T.height(x, y);
	return 0;
}

RayHit RayCaster::cast(
    const mrpt::math::TPoint3D& origin, const mrpt::math::TPoint3D& unitDir,
    double maxRange) const
{
	const Impl& I = *m_impl;
	Ray r;
	r.o = {origin.x, origin.y, origin.z};
	r.d = {unitDir.x, unitDir.y, unitDir.z};
	for (int k = 0; k < 3; k++) r.inv[k] = r.d[k] != 0 ? 1.0 / r.d[k] : kInf;
	r.maxRange = maxRange;

	Best best;
	best.t = maxRange;
	I.testPlanes(r, best);

	if (m_mode == Mode::BruteForce)
	{
		for (int pi = 0; pi < static_cast<int>(I.prims.size()); pi++)
			I.testPrim(pi, r, best);
	}
	else if (!I.bvh.empty())
	{
		// Nearest-first traversal; a node is skipped when it starts beyond
		// the best hit (>=, not >, would lose exact ties).
		int stack[64];
		double stackT[64];
		int sp = 0;
		double t0 = 0;
		if (hitAabb(I.bvh[0].box, r, best.t, t0))
		{
			stack[sp] = 0;
			stackT[sp++] = t0;
		}
		while (sp > 0)
		{
			--sp;
			if (stackT[sp] > best.t) continue;
			const BvhNode& n = I.bvh[stack[sp]];
			if (n.left < 0)
			{
				for (int k = n.first; k < n.first + n.count; k++)
				{
					const int pi = I.bvhPrims[k];
					double te = 0;
					if (hitAabb(I.prims[pi].box, r, best.t, te))
						I.testPrim(pi, r, best);
				}
				continue;
			}
			double tl = 0, tr = 0;
			const bool hl = hitAabb(I.bvh[n.left].box, r, best.t, tl);
			const bool hr = hitAabb(I.bvh[n.right].box, r, best.t, tr);
			// Push the far child first so the near one is popped first.
			if (hl && hr)
			{
				const bool leftNear = tl <= tr;
				stack[sp] = leftNear ? n.right : n.left;
				stackT[sp++] = leftNear ? tr : tl;
				stack[sp] = leftNear ? n.left : n.right;
				stackT[sp++] = leftNear ? tl : tr;
			}
			else if (hl)
			{
				stack[sp] = n.left;
				stackT[sp++] = tl;
			}
			else if (hr)
			{
				stack[sp] = n.right;
				stackT[sp++] = tr;
			}
		}
	}

	RayHit h;
	if (best.order != INT_MAX)
	{
		h.hit = true;
		h.range = best.t;
		h.label = best.label;
		h.instance = best.instance;
	}
	return h;
}

}  // namespace semnav

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
#include <sstream>
#include <string>

#include "RayGeometry.h"

namespace semnav
{
namespace
{
using namespace detail;
/** Padding of bounding boxes, so culling never rejects an exact hit. */
constexpr double kPad = 1e-6;
/** Most cells of one terrain height field (about 25 bytes each). */
constexpr double kMaxTerrainCells = 2e7;

uint64_t splitMix64(uint64_t x)
{
	x += 0x9E3779B97F4A7C15ULL;
	x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
	x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
	return x ^ (x >> 31);
}

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

	/** `name` names the object in errors. */
	void addTerrain(
	    const TerrainShape& t, Label l, int inst, double cell, uint64_t seed,
	    const std::string& name)
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
		if (static_cast<double>(T.cx) * T.cy > kMaxTerrainCells)
		{
			std::ostringstream os;
			os << name << ": terrain patch " << T.pxmax - T.pxmin << " x "
			   << T.pymax - T.pymin << " m needs " << double(T.cx) * T.cy
			   << " cells of terrain_cell_m = " << cell << " m, at most "
			   << kMaxTerrainCells
			   << " (a smaller polygon or a larger terrain_cell_m)";
			throw SceneError(os.str());
		}

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
				I.addTerrain(*t, o.label, o.id, terrainCell, s, what(o, oi));
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
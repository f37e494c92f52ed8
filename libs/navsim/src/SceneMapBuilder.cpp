/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/LabelSet.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/navsim/SceneMapBuilder.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace semnav
{
namespace
{
/** Does the primitive cover (x, y), and over which heights. */
bool covers(
    const ScenePrimitive& prim, double x, double y, double& z0, double& z1)
{
	if (const auto* b = std::get_if<BoxShape>(&prim))
	{
		const double dx = x - b->center.x, dy = y - b->center.y;
		const double c = std::cos(b->yaw), s = std::sin(b->yaw);
		const double lx = c * dx + s * dy, ly = -s * dx + c * dy;
		z0 = b->center.z - b->size.z / 2;
		z1 = b->center.z + b->size.z / 2;
		return std::abs(lx) <= b->size.x / 2 && std::abs(ly) <= b->size.y / 2;
	}
	if (const auto* cy = std::get_if<CylinderShape>(&prim))
	{
		z0 = cy->center.z - cy->height / 2;
		z1 = cy->center.z + cy->height / 2;
		return std::hypot(x - cy->center.x, y - cy->center.y) <= cy->radius;
	}
	if (const auto* st = std::get_if<StairsShape>(&prim))
	{
		const double dx = x - st->origin.x, dy = y - st->origin.y;
		const double c = std::cos(st->yaw), s = std::sin(st->yaw);
		const double along = c * dx + s * dy, across = -s * dx + c * dy;
		z0 = 0;
		z1 = st->steps * st->rise;
		return along >= 0 && along <= st->steps * st->run &&
		       std::abs(across) <= st->width / 2;
	}
	if (const auto* t = std::get_if<TerrainShape>(&prim))
	{
		// Point in polygon (even-odd).
		bool in = false;
		const auto& p = t->polygon;
		for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
			if (((p[i].y > y) != (p[j].y > y)) &&
			    x < (p[j].x - p[i].x) * (y - p[i].y) / (p[j].y - p[i].y) +
			            p[i].x)
				in = !in;
		z0 = z1 = 0;
		return in;
	}
	return false;
}

/** Ground truth is seen "always": passes any min_observations (the
 * option's maximum is 1000). */
constexpr std::size_t kGroundTruthObservations = 1000;

bool isInstanceLabel(Label l)
{
	return classInfo(l).hasInstances();
}
}  // namespace

void SceneMapBuilder::bounds(
    const SceneObject& o, mrpt::math::TPoint3D& lo, mrpt::math::TPoint3D& hi)
{
	const double inf = std::numeric_limits<double>::infinity();
	lo = {inf, inf, inf};
	hi = {-inf, -inf, -inf};
	const auto grow = [&](double x, double y, double z)
	{
		lo.x = std::min(lo.x, x);
		lo.y = std::min(lo.y, y);
		lo.z = std::min(lo.z, z);
		hi.x = std::max(hi.x, x);
		hi.y = std::max(hi.y, y);
		hi.z = std::max(hi.z, z);
	};
	for (const auto& prim : o.parts)
	{
		if (const auto* b = std::get_if<BoxShape>(&prim))
		{
			const double c = std::cos(b->yaw), s = std::sin(b->yaw);
			for (int sx : {-1, 1})
				for (int sy : {-1, 1})
				{
					const double lx = sx * b->size.x / 2,
					             ly = sy * b->size.y / 2;
					for (int sz : {-1, 1})
						grow(
						    b->center.x + c * lx - s * ly,
						    b->center.y + s * lx + c * ly,
						    b->center.z + sz * b->size.z / 2);
				}
		}
		else if (const auto* cy = std::get_if<CylinderShape>(&prim))
		{
			grow(
			    cy->center.x - cy->radius, cy->center.y - cy->radius,
			    cy->center.z - cy->height / 2);
			grow(
			    cy->center.x + cy->radius, cy->center.y + cy->radius,
			    cy->center.z + cy->height / 2);
		}
		else if (const auto* st = std::get_if<StairsShape>(&prim))
		{
			const double c = std::cos(st->yaw), s = std::sin(st->yaw);
			const double L = st->steps * st->run, w = st->width / 2;
			for (double a : {0.0, L})
				for (double b : {-w, w})
					for (double z : {0.0, st->steps * st->rise})
						grow(
						    st->origin.x + c * a - s * b,
						    st->origin.y + s * a + c * b, z);
		}
		else if (const auto* t = std::get_if<TerrainShape>(&prim))
			for (const auto& p : t->polygon) grow(p.x, p.y, 0);
	}
}

void SceneMapBuilder::build(const Scene& scene, SemanticMap& map)
{
	const auto& b = scene.bounds;
	map.growToInclude(b.xmin, b.ymin, b.xmax, b.ymax);
	const GridGeometry& g = map.geometry();
	const double zLo = map.options().obstacleMinHeight;
	const double zHi = map.options().robotHeight;
	auto& labels = map.get("labels");
	auto& observations = map.get("observations");
	auto& grid = map.occupancyGrid();
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
		{
			const double x = g.centerX(cx), y = g.centerY(cy);
			if (!b.contains(x, y)) continue;
			LabelSet ls;
			bool occupied = false;
			Label ground = Label::Floor;
			for (const auto& o : scene.objects)
				for (const auto& prim : o.parts)
				{
					double z0 = 0, z1 = 0;
					if (!covers(prim, x, y, z0, z1)) continue;
					if (std::holds_alternative<TerrainShape>(prim))
						ground = o.label;
					else if (z1 > zLo && z0 < zHi)
					{
						occupied = true;
						ls.insert(o.label);
					}
				}
			if (!occupied) ls.insert(ground);
			const std::size_t i = g.index(cy, cx);
			labels[i] = static_cast<float>(ls.mask());
			observations[i] = 1;
			grid.setCell(cx, cy, occupied ? 0.95f : 0.05f);
		}
	for (const auto& o : scene.objects)
	{
		if (!isInstanceLabel(o.label)) continue;
		mrpt::math::TPoint3D lo, hi;
		bounds(o, lo, hi);
		map.addInstance(o.label, lo, hi, kGroundTruthObservations);
	}
	map.updateCosts();
}

int SceneMapBuilder::addInstances(
    const Scene& scene, Label label, SemanticMap& map)
{
	int n = 0;
	for (const auto& o : scene.objects)
	{
		if (o.label != label || !isInstanceLabel(o.label)) continue;
		mrpt::math::TPoint3D lo, hi;
		bounds(o, lo, hi);
		map.addInstance(o.label, lo, hi, kGroundTruthObservations);
		n++;
	}
	return n;
}

}  // namespace semnav

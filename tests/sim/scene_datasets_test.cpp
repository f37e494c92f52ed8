/* semnav: semantic navigation from tilting-laser sweeps */
// The shipped scenes (datasets/*/*.yaml) load and are well formed.
#include <gtest/gtest.h>
#include <semnav/sim/SceneLoader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

using namespace semnav;

namespace
{
std::vector<std::filesystem::path> datasetScenes()
{
	std::vector<std::filesystem::path> files;
	const std::filesystem::path root =
	    std::filesystem::path(SEMNAV_SOURCE_DIR) / "datasets";
	for (const auto& dir : std::filesystem::directory_iterator(root))
	{
		if (!dir.is_directory()) continue;
		for (const auto& f : std::filesystem::directory_iterator(dir.path()))
			if (f.is_regular_file() && f.path().extension() == ".yaml")
				files.push_back(f.path());
	}
	std::sort(files.begin(), files.end());
	return files;
}

/** Distance from (x, y) to the floor footprint of a primitive (0 inside);
 * terrain has no footprint (it is floor): +inf. */
double footprintDistance(const ScenePrimitive& p, double x, double y)
{
	auto rectDist =
	    [](double u, double v, double u0, double u1, double v0, double v1)
	{
		const double du = std::max({u0 - u, 0.0, u - u1});
		const double dv = std::max({v0 - v, 0.0, v - v1});
		return std::hypot(du, dv);
	};
	if (const auto* b = std::get_if<BoxShape>(&p))
	{
		const double dx = x - b->center.x, dy = y - b->center.y;
		const double c = std::cos(b->yaw), s = std::sin(b->yaw);
		return rectDist(
		    c * dx + s * dy, -s * dx + c * dy, -b->size.x / 2, b->size.x / 2,
		    -b->size.y / 2, b->size.y / 2);
	}
	if (const auto* c = std::get_if<CylinderShape>(&p))
		return std::max(
		    0.0, std::hypot(x - c->center.x, y - c->center.y) - c->radius);
	if (const auto* st = std::get_if<StairsShape>(&p))
	{
		const double dx = x - st->origin.x, dy = y - st->origin.y;
		const double c = std::cos(st->yaw), s = std::sin(st->yaw);
		return rectDist(
		    c * dx + s * dy, -s * dx + c * dy, 0, st->steps * st->run,
		    -st->width / 2, st->width / 2);
	}
	return std::numeric_limits<double>::infinity();
}

/** Footprint corners (or samples) of a primitive, and its z range. */
void extent(
    const ScenePrimitive& p, std::vector<mrpt::math::TPoint2D>& pts,
    double& zmin, double& zmax)
{
	pts.clear();
	zmin = 0;
	zmax = 0;
	auto rect = [&](double cx, double cy, double yaw, double u0, double u1,
	                double v0, double v1)
	{
		const double c = std::cos(yaw), s = std::sin(yaw);
		for (double u : {u0, u1})
			for (double v : {v0, v1})
				pts.push_back({cx + c * u - s * v, cy + s * u + c * v});
	};
	if (const auto* b = std::get_if<BoxShape>(&p))
	{
		rect(
		    b->center.x, b->center.y, b->yaw, -b->size.x / 2, b->size.x / 2,
		    -b->size.y / 2, b->size.y / 2);
		zmin = b->center.z - b->size.z / 2;
		zmax = b->center.z + b->size.z / 2;
	}
	else if (const auto* c = std::get_if<CylinderShape>(&p))
	{
		rect(
		    c->center.x, c->center.y, 0, -c->radius, c->radius, -c->radius,
		    c->radius);
		zmin = c->center.z - c->height / 2;
		zmax = c->center.z + c->height / 2;
	}
	else if (const auto* st = std::get_if<StairsShape>(&p))
	{
		rect(
		    st->origin.x, st->origin.y, st->yaw, 0, st->steps * st->run,
		    -st->width / 2, st->width / 2);
		zmax = st->steps * st->rise;
	}
	else if (const auto* t = std::get_if<TerrainShape>(&p))
		pts = t->polygon;
}
}  // namespace

TEST(SceneDatasets, AllShippedScenesLoad)
{
	const auto files = datasetScenes();
	EXPECT_GE(files.size(), 2u) << "office and outdoor at least";
	for (const auto& f : files)
	{
		SCOPED_TRACE(f.string());
		Scene s;
		ASSERT_NO_THROW(s = SceneLoader::loadFile(f.string()));
		EXPECT_GE(s.trajectory.size(), 1u);
		EXPECT_FALSE(s.objects.empty());
	}
}

TEST(SceneDatasets, ObjectsInsideBoundsAndUnderCeiling)
{
	// Scene files give lengths to the millimetre.
	constexpr double eps = 1e-3;
	for (const auto& f : datasetScenes())
	{
		const Scene s = SceneLoader::loadFile(f.string());
		for (const auto& o : s.objects)
			for (const auto& p : o.parts)
			{
				SCOPED_TRACE(f.string() + " line " + std::to_string(o.line));
				std::vector<mrpt::math::TPoint2D> pts;
				double zmin = 0, zmax = 0;
				extent(p, pts, zmin, zmax);
				for (const auto& q : pts)
				{
					EXPECT_GE(q.x, s.bounds.xmin - eps);
					EXPECT_LE(q.x, s.bounds.xmax + eps);
					EXPECT_GE(q.y, s.bounds.ymin - eps);
					EXPECT_LE(q.y, s.bounds.ymax + eps);
				}
				EXPECT_GE(zmin, -eps);
				if (s.ceilingHeight) EXPECT_LE(zmax, *s.ceilingHeight + eps);
			}
	}
}

/** datasets/cascade-scenes/ are viewpoint sets for detector training (their
 * odometry is not used), not drives. */
bool isViewpointSet(const std::filesystem::path& f)
{
	return f.parent_path().filename() == "cascade-scenes";
}

TEST(SceneDatasets, TrajectoryKeepsClearOfObjects)
{
	// Poses at least 0.5 m from any object (0.3 m, the robot's radius, for a
	// viewpoint set); the straight moves between them at least 0.3 m.
	for (const auto& f : datasetScenes())
	{
		const bool viewpoints = isViewpointSet(f);
		const Scene s = SceneLoader::loadFile(f.string());
		auto clearance = [&](double x, double y, int& line)
		{
			double d = std::numeric_limits<double>::infinity();
			for (const auto& o : s.objects)
				for (const auto& p : o.parts)
				{
					const double dp = footprintDistance(p, x, y);
					if (dp < d)
					{
						d = dp;
						line = o.line;
					}
				}
			return d;
		};
		for (std::size_t i = 0; i < s.trajectory.size(); i++)
		{
			const auto& a = s.trajectory[i];
			int line = 0;
			EXPECT_GE(clearance(a.x, a.y, line), viewpoints ? 0.3 : 0.5)
			    << f.string() << " pose " << i << " near object at line "
			    << line;
			if (viewpoints || i + 1 == s.trajectory.size()) continue;
			const auto& b = s.trajectory[i + 1];
			for (int k = 1; k < 50; k++)
			{
				const double t = k / 50.0;
				const double d = clearance(
				    a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), line);
				EXPECT_GE(d, 0.3) << f.string() << " move " << i << " -> "
				                  << i + 1 << " near object at line " << line;
			}
		}
	}
}

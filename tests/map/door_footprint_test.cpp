/* semnav: semantic navigation from tilting-laser sweeps */
// A door region's footprint: the world box of its points, not the world box
// around its robot-frame box (SemanticMap::TOptions::doorFootprintFromPoints;
// docs/mapping.md, "Objects in the map").
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "MapTestUtils.h"

using namespace semnav;

namespace
{
/** Appends to `pts` a 1 x 2 m door in a world-aligned wall (from (x0, y0)
 * to (x1, y1)) seen by a robot at the origin turned by `yaw`, and returns
 * its region (robot frame, id `id`, its points' ids set in `ids`). */
LabeledRegion doorSeenFrom(
    double yaw, double x0, double y0, double x1, double y1, int id,
    std::vector<test::FakePoint>& pts, std::vector<int>& ids)
{
	LabeledRegion reg;
	reg.id = id;
	reg.label = Label::Door;
	reg.minCorner = {1e9, 1e9, 1e9};
	reg.maxCorner = {-1e9, -1e9, -1e9};
	const int first = static_cast<int>(pts.size());
	mrpt::math::TPoint3D sum(0, 0, 0);
	for (double t = 0; t <= 1.0 + 1e-9; t += 0.05)
		for (double z = 0.05; z <= 2.0 + 1e-9; z += 0.25)
		{
			const double wx = x0 + t * (x1 - x0), wy = y0 + t * (y1 - y0);
			const double rx = std::cos(yaw) * wx + std::sin(yaw) * wy,
			             ry = -std::sin(yaw) * wx + std::cos(yaw) * wy;
			pts.push_back({rx, ry, z, Label::Door});
			ids.push_back(id);
			reg.minCorner = {
			    std::min(reg.minCorner.x, rx), std::min(reg.minCorner.y, ry),
			    std::min(reg.minCorner.z, z)};
			reg.maxCorner = {
			    std::max(reg.maxCorner.x, rx), std::max(reg.maxCorner.y, ry),
			    std::max(reg.maxCorner.z, z)};
			sum = sum + mrpt::math::TPoint3D(rx, ry, z);
		}
	reg.pixels = pts.size() - static_cast<std::size_t>(first);
	reg.centroid = sum * (1.0 / static_cast<double>(reg.pixels));
	reg.imageBox = cv::Rect(first, 0, static_cast<int>(reg.pixels), 1);
	reg.width = 1.0;
	reg.height = reg.maxCorner.z - reg.minCorner.z;
	// Facing the robot: the wall's normal towards the origin, robot frame.
	double nx = y1 - y0, ny = -(x1 - x0);
	if (nx * (x0 + x1) + ny * (y0 + y1) > 0)
	{
		nx = -nx;
		ny = -ny;
	}
	const double n = std::hypot(nx, ny);
	reg.meanNormal = {
	    (std::cos(yaw) * nx + std::sin(yaw) * ny) / n,
	    (-std::sin(yaw) * nx + std::cos(yaw) * ny) / n, 0};
	return reg;
}

/** The door instances after one sweep, the robot at the origin turned by
 * 45 deg, seeing a door in the wall x = 2 (y 0.5..1.5) and one in the wall
 * y = 1.9 (x 0.6..1.6): 1.27 m apart, their points' boxes apart, the world
 * boxes around their robot-frame boxes (1 x 1 m) overlapping. */
std::vector<ObjectInstance> twoDoorsAt45(bool fromPoints)
{
	const double yaw = M_PI / 4;
	std::vector<test::FakePoint> pts = test::floorFan(1.0);
	std::vector<int> ids(pts.size(), -1);
	const auto a = doorSeenFrom(yaw, 2.0, 0.5, 2.0, 1.5, 0, pts, ids);
	const auto b = doorSeenFrom(yaw, 0.6, 1.9, 1.6, 1.9, 1, pts, ids);
	auto f = test::makeFakeSweep(pts);
	for (std::size_t i = 0; i < ids.size(); i++)
		f.labeled.regionIds.at<int32_t>(0, static_cast<int>(i)) = ids[i];
	f.labeled.regions = {a, b};
	SemanticMap::TOptions o;
	o.doorFootprintFromPoints = fromPoints;
	SemanticMap m(o);
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, yaw));
	return m.instances(Label::Door);
}
}  // namespace

TEST(SemanticMap, DoorFootprintIsTheBoxOfItsPoints)
{
	auto d = twoDoorsAt45(true);
	ASSERT_EQ(d.size(), 2u) << "two doors";
	std::sort(
	    d.begin(), d.end(),
	    [](const ObjectInstance& p, const ObjectInstance& q)
	    { return p.centroid.x > q.centroid.x; });
	EXPECT_NEAR(d[0].centroid.x, 2.0, 0.02);
	EXPECT_NEAR(d[0].centroid.y, 1.0, 0.02);
	EXPECT_NEAR(d[1].centroid.x, 1.1, 0.02);
	EXPECT_NEAR(d[1].centroid.y, 1.9, 0.02);
	// The footprint hugs the wall.
	EXPECT_LT(d[0].maxCorner.x - d[0].minCorner.x, 0.05);
	EXPECT_LT(d[1].maxCorner.y - d[1].minCorner.y, 0.05);
	// Off: the boxes around the robot-frame boxes overlap, and the second
	// door joins the first (one instance between them).
	d = twoDoorsAt45(false);
	EXPECT_EQ(d.size(), 1u);
}

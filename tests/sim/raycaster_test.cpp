/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/sim/RayCaster.h>

#include <cmath>
#include <random>

#include "ClutteredScene.h"

using namespace semnav;
using mrpt::math::TPoint3D;

namespace
{
TPoint3D unit(double x, double y, double z)
{
	const double n = std::sqrt(x * x + y * y + z * z);
	return {x / n, y / n, z / n};
}

Scene emptyRoom(double half = 10.0)
{
	Scene s;
	s.name = "test";
	s.bounds = {-half, -half, half, half};
	return s;
}

SceneObject object(Label l, int id, ScenePrimitive p)
{
	SceneObject o;
	o.label = l;
	o.id = id;
	o.parts.push_back(std::move(p));
	return o;
}

BoxShape box(TPoint3D c, TPoint3D size, double yaw = 0)
{
	BoxShape b;
	b.center = c;
	b.size = size;
	b.yaw = yaw;
	return b;
}

CylinderShape cylinder(TPoint3D c, double r, double h)
{
	CylinderShape cy;
	cy.center = c;
	cy.radius = r;
	cy.height = h;
	return cy;
}

TerrainShape terrain(
    double x0, double y0, double x1, double y1, double roughness)
{
	TerrainShape t;
	t.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
	t.roughness = roughness;
	return t;
}

const double kTol = 1e-9;
}  // namespace

TEST(RayCaster, FloorPlane)
{
	const RayCaster rc(emptyRoom());
	std::mt19937_64 rng(1);
	std::uniform_real_distribution<double> u(-1, 1);
	for (int k = 0; k < 200; k++)
	{
		const TPoint3D o(u(rng) * 3, u(rng) * 3, 0.2 + std::abs(u(rng)));
		const TPoint3D d = unit(u(rng), u(rng), -0.3 - std::abs(u(rng)));
		const RayHit h = rc.cast(o, d, 100.0);
		const double t = o.z / -d.z;
		const bool inside =
		    std::abs(o.x + t * d.x) <= 10 && std::abs(o.y + t * d.y) <= 10;
		ASSERT_EQ(h.hit, inside);
		if (!inside) continue;
		EXPECT_NEAR(h.range, t, kTol);
		EXPECT_EQ(h.label, Label::Floor);
		EXPECT_EQ(h.instance, 0);
	}
	// Upwards without a ceiling, and beyond the floor bounds: misses.
	EXPECT_FALSE(rc.cast({0, 0, 1}, unit(0.3, 0, 1), 100).hit);
	EXPECT_FALSE(
	    rc.cast({0, 0, 1}, unit(1, 0, -0.05), 100).hit);  // lands at x = 20
}

TEST(RayCaster, Ceiling)
{
	Scene s = emptyRoom();
	s.ceilingHeight = 2.5;
	const RayCaster rc(s);
	RayHit h = rc.cast({1, 1, 1}, {0, 0, 1}, 10);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 1.5, kTol);
	EXPECT_EQ(h.label, Label::Ceiling);
	EXPECT_EQ(h.instance, 0);
	const TPoint3D d = unit(1, 2, 1.5);
	h = rc.cast({0, 0, 0.5}, d, 10);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 2.0 / d.z, kTol);
}

TEST(RayCaster, MaxRange)
{
	Scene s = emptyRoom();
	s.objects.push_back(object(Label::Wall, 1, box({5, 0, 1}, {2, 2, 2})));
	const RayCaster rc(s);
	EXPECT_TRUE(rc.cast({0, 0, 1}, {1, 0, 0}, 4.5).hit);
	EXPECT_FALSE(rc.cast({0, 0, 1}, {1, 0, 0}, 3.9).hit);
	const TPoint3D d = unit(1, 0, -1);  // floor at sqrt(2)
	EXPECT_TRUE(rc.cast({0, 0, 1}, d, 1.5).hit);
	EXPECT_FALSE(rc.cast({0, 0, 1}, d, 1.4).hit);
}

TEST(RayCaster, AxisAlignedBox)
{
	Scene s = emptyRoom();
	s.objects.push_back(object(Label::Wall, 3, box({5, 0, 1}, {2, 2, 2})));
	const RayCaster rc(s);
	RayHit h = rc.cast({0, 0.5, 1.2}, {1, 0, 0}, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 4.0, kTol);
	EXPECT_EQ(h.label, Label::Wall);
	EXPECT_EQ(h.instance, 3);
	// From above onto its top face (z = 2).
	h = rc.cast({5.5, -0.5, 3}, {0, 0, -1}, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 1.0, kTol);
	EXPECT_EQ(h.instance, 3);
	// Passing beside it reaches the floor.
	h = rc.cast({0, 1.2, 1}, unit(1, 0, -0.1), 20);
	ASSERT_TRUE(h.hit);
	EXPECT_EQ(h.label, Label::Floor);
	// Slanted onto the face x = 4.
	const TPoint3D d = unit(1, 0.1, 0.05);
	h = rc.cast({0, 0, 1}, d, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 4.0 / d.x, kTol);
	// A ray starting inside the solid does not see it.
	h = rc.cast({5, 0, 1}, {0, 0, -1}, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_EQ(h.label, Label::Floor);
	EXPECT_NEAR(h.range, 1.0, kTol);
}

TEST(RayCaster, YawedBox)
{
	Scene s = emptyRoom();
	// 2 x 2 x 2 box turned 45 deg: its corner faces the x axis.
	s.objects.push_back(
	    object(Label::Obstacle, 1, box({5, 0, 1}, {2, 2, 2}, M_PI / 4)));
	// Same box turned 45 deg on the diagonal: a face looks at the origin.
	s.objects.push_back(
	    object(Label::Door, 2, box({-4, -4, 1}, {2, 3, 2}, M_PI / 4)));
	const RayCaster rc(s);
	RayHit h = rc.cast({0, 0, 1}, {1, 0, 0}, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 5 - std::sqrt(2.0), kTol);
	EXPECT_EQ(h.label, Label::Obstacle);
	// Off-axis: the corner face x' = -1 (box frame) along y = 0.3.
	// Box frame of the point (x, 0.3): x' = (x-5+0.3)/sqrt2, y' =
	// (0.3-x+5)/sqrt2; the face y' = 1 is met first at x = 5.3 - sqrt2.
	h = rc.cast({0, 0.3, 1}, {1, 0, 0}, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 5.3 - std::sqrt(2.0), kTol);
	h = rc.cast({0, 0, 1}, unit(-1, -1, 0), 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 4 * std::sqrt(2.0) - 1.0, kTol);
	EXPECT_EQ(h.label, Label::Door);
	EXPECT_EQ(h.instance, 2);
}

TEST(RayCaster, Cylinder)
{
	Scene s = emptyRoom();
	s.objects.push_back(
	    object(Label::Wastebasket, 7, cylinder({3, 0, 0.5}, 0.5, 1.0)));
	const RayCaster rc(s);
	RayHit h = rc.cast({0, 0, 0.5}, {1, 0, 0}, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 2.5, kTol);
	EXPECT_EQ(h.label, Label::Wastebasket);
	EXPECT_EQ(h.instance, 7);
	h = rc.cast({0, 0.3, 0.2}, {1, 0, 0}, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 3 - 0.4, kTol);
	// Top cap (z = 1), straight and slanted.
	h = rc.cast({3.2, 0.1, 2}, {0, 0, -1}, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 1.0, kTol);
	EXPECT_EQ(h.instance, 7);
	const double a = 0.2;
	h = rc.cast({3, 0, 2}, {std::sin(a), 0, -std::cos(a)}, 20);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 1.0 / std::cos(a), kTol);
	// Just over the top: floor behind it.
	h = rc.cast({0, 0, 2}, unit(1, 0, -0.25), 20);
	ASSERT_TRUE(h.hit);
	EXPECT_EQ(h.label, Label::Floor);
}

TEST(RayCaster, Stairs)
{
	StairsShape st;
	st.origin = {2, 0};
	st.yaw = 0;
	st.steps = 4;
	st.rise = 0.2;
	st.run = 0.3;
	st.width = 1.0;
	StairsShape st2 = st;
	st2.origin = {0, -3};
	st2.yaw = -M_PI / 2;  // climbs towards -y
	Scene s = emptyRoom();
	s.objects.push_back(object(Label::Stairs, 4, st));
	s.objects.push_back(object(Label::Stairs, 5, st2));
	const RayCaster rc(s);
	for (int k = 0; k < 4; k++)
	{
		// Riser of step k: horizontal ray between k rise and (k+1) rise.
		const double z = (k + 0.5) * st.rise;
		RayHit h = rc.cast({0, 0.2, z}, {1, 0, 0}, 20);
		ASSERT_TRUE(h.hit) << k;
		EXPECT_NEAR(h.range, 2 + k * st.run, kTol) << k;
		EXPECT_EQ(h.label, Label::Stairs);
		EXPECT_EQ(h.instance, 4);
		// Tread of step k: vertical ray onto (k+1) rise.
		h = rc.cast({2 + (k + 0.5) * st.run, -0.4, 3}, {0, 0, -1}, 20);
		ASSERT_TRUE(h.hit) << k;
		EXPECT_NEAR(h.range, 3 - (k + 1) * st.rise, kTol) << k;
		// Rotated stairs.
		h = rc.cast({0.3, -3 - (k + 0.5) * st.run, 3}, {0, 0, -1}, 20);
		ASSERT_TRUE(h.hit) << k;
		EXPECT_NEAR(h.range, 3 - (k + 1) * st.rise, kTol) << k;
		EXPECT_EQ(h.instance, 5);
	}
	// Beside the stairs (|y| > width / 2): floor.
	RayHit h = rc.cast({2.5, 0.6, 3}, {0, 0, -1}, 20);
	EXPECT_EQ(h.label, Label::Floor);
}

TEST(RayCaster, FlatTerrainEqualsFloor)
{
	Scene s = emptyRoom(50);
	s.objects.push_back(object(Label::Grass, 2, terrain(0, 0, 4, 4, 0.0)));
	const RayCaster rc(s, 5);
	std::mt19937_64 rng(2);
	std::uniform_real_distribution<double> u(0, 1);
	int grass = 0, floor = 0;
	for (int k = 0; k < 500; k++)
	{
		const TPoint3D o(u(rng) * 6 - 1, u(rng) * 6 - 1, 0.3 + u(rng));
		const TPoint3D d = unit(u(rng) - 0.5, u(rng) - 0.5, -0.05 - u(rng));
		const RayHit h = rc.cast(o, d, 50);
		ASSERT_TRUE(h.hit);
		const double t = o.z / -d.z;
		EXPECT_NEAR(h.range, t, 1e-4);
		const double x = o.x + t * d.x, y = o.y + t * d.y;
		const bool in = x > 0 && x < 4 && y > 0 && y < 4;
		const bool nearEdge = std::min(
		                          {std::abs(x), std::abs(x - 4), std::abs(y),
		                           std::abs(y - 4)}) < 1e-3;
		if (nearEdge) continue;
		EXPECT_EQ(h.label, in ? Label::Grass : Label::Floor) << x << " " << y;
		EXPECT_EQ(h.instance, in ? 2 : 0);
		(in ? grass : floor)++;
	}
	EXPECT_GT(grass, 50);
	EXPECT_GT(floor, 50);
}

TEST(RayCaster, RoughTerrain)
{
	const double rough = 0.04;
	Scene s = emptyRoom(30);
	s.objects.push_back(object(Label::Grass, 1, terrain(0, 0, 20, 20, rough)));
	const RayCaster rc(s, 11);
	std::mt19937_64 rng(3);
	std::uniform_real_distribution<double> u(0, 1);
	// Vertical rays over the interior (away from the taper).
	double sum = 0, sum2 = 0;
	const int n = 4000;
	for (int k = 0; k < n; k++)
	{
		const double x = 1 + 18 * u(rng), y = 1 + 18 * u(rng);
		const RayHit h = rc.cast({x, y, 2}, {0, 0, -1}, 10);
		ASSERT_TRUE(h.hit);
		EXPECT_EQ(h.label, Label::Grass);
		const double z = 2 - h.range;
		EXPECT_NEAR(z, rc.groundHeight(x, y), 1e-4);
		sum += z;
		sum2 += z * z;
	}
	const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
	EXPECT_NEAR(mean, 0.0, 0.15 * rough);
	EXPECT_NEAR(sd, rough, 0.1 * rough);

	// Slanted rays land on the surface, not merely in its band.
	int onSurface = 0;
	for (int k = 0; k < 1000; k++)
	{
		const TPoint3D o(2 + 16 * u(rng), 2 + 16 * u(rng), 0.45);
		const double a = 2 * M_PI * u(rng);
		const TPoint3D d = unit(std::cos(a), std::sin(a), -0.05 - 0.5 * u(rng));
		const RayHit h = rc.cast(o, d, 20);
		if (!h.hit) continue;
		const double x = o.x + h.range * d.x, y = o.y + h.range * d.y;
		if (x < 0 || x > 20 || y < 0 || y > 20) continue;
		EXPECT_NEAR(o.z + h.range * d.z, rc.groundHeight(x, y), 1e-4);
		onSurface++;
	}
	EXPECT_GT(onSurface, 500);

	// Taper: zero on the boundary, joined to the floor.
	EXPECT_NEAR(rc.groundHeight(0, 7.3), 0.0, 1e-12);
	EXPECT_NEAR(rc.groundHeight(20, 3.1), 0.0, 1e-12);
	double edge = 0, inner = 0;
	for (int k = 0; k < 200; k++)
	{
		const double y = 1 + 18 * u(rng);
		edge += std::abs(rc.groundHeight(0.01, y));
		inner += std::abs(rc.groundHeight(1.0 + 0.1 * u(rng), y));
	}
	EXPECT_LT(edge, 0.1 * inner);
	EXPECT_EQ(rc.groundHeight(-1, 5), 0.0);

	// The heights come from the seed.
	const RayCaster same(s, 11), other(s, 12);
	double diff = 0, diffSame = 0;
	for (int k = 0; k < 100; k++)
	{
		const double x = 1 + 18 * u(rng), y = 1 + 18 * u(rng);
		diffSame += std::abs(same.groundHeight(x, y) - rc.groundHeight(x, y));
		diff += std::abs(other.groundHeight(x, y) - rc.groundHeight(x, y));
	}
	EXPECT_EQ(diffSame, 0.0);
	EXPECT_GT(diff, 100 * 0.2 * rough);
}

TEST(RayCaster, RoughTerrainFindsTheFirstCrossing)
{
	// Grazing rays against a dense 1 mm march of groundHeight(): the caster
	// must find the first crossing, not a later one (dips under a bump).
	Scene s = emptyRoom(30);
	s.objects.push_back(object(Label::Grass, 1, terrain(0, 0, 20, 20, 0.04)));
	const RayCaster rc(s, 21);
	std::mt19937_64 rng(5);
	std::uniform_real_distribution<double> u(0, 1);
	int agree = 0, n = 0;
	for (int k = 0; k < 300; k++)
	{
		const TPoint3D o(6 + 8 * u(rng), 6 + 8 * u(rng), 0.45);
		const double a = 2 * M_PI * u(rng), el = -(0.03 + 0.2 * u(rng));
		const TPoint3D d(
		    std::cos(el) * std::cos(a), std::cos(el) * std::sin(a),
		    std::sin(el));
		const RayHit h = rc.cast(o, d, 5.5);
		double first = -1;
		for (double t = 1e-3; t <= 5.5; t += 1e-3)
			if (o.z + t * d.z < rc.groundHeight(o.x + t * d.x, o.y + t * d.y))
			{
				first = t;
				break;
			}
		if (first < 0) continue;
		n++;
		ASSERT_TRUE(h.hit);
		EXPECT_LE(h.range, first + 1e-4);  // never a later crossing
		if (h.range > first - 2e-3) agree++;
	}
	EXPECT_GT(n, 200);
	// Only dips shorter than the 1 mm oracle step may differ.
	EXPECT_GE(agree, n - 2);
}

TEST(RayCaster, PartsShareTheInstance)
{
	SceneObject basin;
	basin.label = Label::Washbasin;
	basin.id = 9;
	basin.parts.push_back(box({3, 0, 0.8}, {0.5, 0.4, 0.15}));
	basin.parts.push_back(cylinder({3, 0, 0.36}, 0.08, 0.72));
	Scene s = emptyRoom();
	s.objects.push_back(basin);
	const RayCaster rc(s);
	RayHit h = rc.cast({0, 0, 0.8}, {1, 0, 0}, 10);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 2.75, kTol);
	EXPECT_EQ(h.label, Label::Washbasin);
	EXPECT_EQ(h.instance, 9);
	h = rc.cast({0, 0, 0.3}, {1, 0, 0}, 10);
	ASSERT_TRUE(h.hit);
	EXPECT_NEAR(h.range, 2.92, kTol);
	EXPECT_EQ(h.instance, 9);
	EXPECT_EQ(rc.primitiveCount(), 2u);
	EXPECT_EQ(rc.maxInstanceId(), 9);
}

TEST(RayCaster, RejectsDegeneratePrimitives)
{
	Scene s = emptyRoom();
	s.objects.push_back(object(Label::Wall, 1, box({0, 0, 0}, {1, 0, 1})));
	EXPECT_THROW(RayCaster{s}, SceneError);
	s.objects[0] = object(Label::Grass, 1, TerrainShape{{{0, 0}, {1, 1}}, 0.1});
	EXPECT_THROW(RayCaster{s}, SceneError);
}

TEST(RayCaster, TooLargeTerrainNamesObjectAndCellBeforeAllocating)
{
	Scene s;
	s.bounds = {0, 0, 9000, 9000};
	SceneObject o;
	o.label = Label::Grass;
	o.id = 1;
	o.line = 7;
	o.parts.push_back(
	    TerrainShape{{{0, 0}, {9000, 0}, {9000, 9000}, {0, 9000}}, 0.01});
	s.objects.push_back(o);
	try
	{
		RayCaster c(s);
		ADD_FAILURE() << "a 9 km terrain patch at 0.1 m cells was accepted";
	}
	catch (const SceneError& e)
	{
		const std::string m = e.what();
		EXPECT_NE(m.find("line 7"), std::string::npos) << m;
		EXPECT_NE(m.find("terrain_cell_m = 0.1 m"), std::string::npos) << m;
		EXPECT_NE(m.find("at most 2e+07"), std::string::npos) << m;
	}
}

TEST(RayCaster, AcceleratedEqualsBruteForce)
{
	const Scene s = test::clutteredScene();
	ASSERT_EQ(s.objects.size(), 30u);
	RayCaster fast(s, 3), brute(s, 3);
	brute.setMode(RayCaster::Mode::BruteForce);
	ASSERT_EQ(fast.mode(), RayCaster::Mode::Accelerated);
	std::mt19937_64 rng(4);
	std::uniform_real_distribution<double> u(0, 1);
	int objectHits = 0, terrainHits = 0, misses = 0;
	const int n = 6000;
	for (int k = 0; k < n; k++)
	{
		const TPoint3D o(
		    0.2 + 11.6 * u(rng), 0.2 + 7.6 * u(rng), 0.1 + 2.5 * u(rng));
		const TPoint3D d = unit(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.6);
		const double maxRange = 2 + 8 * u(rng);
		const RayHit a = fast.cast(o, d, maxRange),
		             b = brute.cast(o, d, maxRange);
		ASSERT_EQ(a.hit, b.hit) << k;
		ASSERT_EQ(a.range, b.range) << k;
		ASSERT_EQ(a.label, b.label) << k;
		ASSERT_EQ(a.instance, b.instance) << k;
		if (!a.hit)
			misses++;
		else if (a.label == Label::Grass || a.label == Label::Sidewalk)
			terrainHits++;
		else if (a.instance > 0)
			objectHits++;
	}
	// The comparison is meaningful only if all kinds of hits occur.
	EXPECT_GT(objectHits, n / 4);
	EXPECT_GT(terrainHits, 20);
	EXPECT_GT(misses, 20);
}

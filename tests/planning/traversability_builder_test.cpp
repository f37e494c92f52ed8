/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/PlanningErrors.h>
#include <semnav/planning/TraversabilityBuilder.h>

#include <cmath>
#include <random>

using namespace semnav;

namespace
{
/** Distance from the centre of cell a to the square of cell b (m). */
double squareDistance(const GridGeometry& g, CellIndex a, CellIndex b)
{
	const double ex = std::max(
	    0.0, std::abs(a.col - b.col) * g.resolution - 0.5 * g.resolution);
	const double ey = std::max(
	    0.0, std::abs(a.row - b.row) * g.resolution - 0.5 * g.resolution);
	return std::hypot(ex, ey);
}

/** u around obstacles by brute force over every obstacle cell. */
double expectedU(
    const TraversabilityBuilder::TOptions& o, CostProfile p, double d)
{
	const double r1 = d - o.robotRadius;  // clearance of the robot's disc
	if (p == CostProfile::Shortest) return r1 < o.shortestRadius ? o.L : 0.0;
	if (r1 < 0.5 * o.safeRadius) return o.L;
	return r1 < o.safeRadius ? o.safeRingCost : 0.0;
}
}  // namespace

TEST(TraversabilityBuilder, InflationAndProfilesMatchBruteForce)
{
	const GridGeometry g(0.05, 0, 0, 70, 60);
	std::vector<CellOccupancy> occ(g.cellCount(), CellOccupancy::Free);
	std::mt19937_64 rng(3);
	std::vector<CellIndex> obstacles;
	for (int k = 0; k < 6; k++)  // random rectangles, some at the border
	{
		const int r0 = static_cast<int>(rng() % 60),
		          c0 = static_cast<int>(rng() % 70);
		const int h = 1 + static_cast<int>(rng() % 8),
		          w = 1 + static_cast<int>(rng() % 8);
		for (int r = r0; r < std::min(60, r0 + h); r++)
			for (int c = c0; c < std::min(70, c0 + w); c++)
				occ[g.index(r, c)] = CellOccupancy::Occupied;
	}
	for (std::size_t i = 0; i < occ.size(); i++)
		if (occ[i] == CellOccupancy::Occupied) obstacles.push_back(g.cellAt(i));
	ASSERT_GT(obstacles.size(), 20u);

	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.22;
	const TraversabilityBuilder b(o);
	for (auto p : {CostProfile::Shortest, CostProfile::Safe})
	{
		const auto u = b.build(g, {}, occ, p);
		std::size_t ring = 0, mismatches = 0;
		for (std::size_t i = 0; i < occ.size(); i++)
		{
			const auto c = g.cellAt(i);
			double d = 1e9;
			for (const auto& ob : obstacles)
				d = std::min(d, squareDistance(g, c, ob));
			const double e = expectedU(o, p, d);
			if (u.u(i) != e) mismatches++;
			if (e == o.safeRingCost) ring++;
		}
		EXPECT_EQ(mismatches, 0u) << costProfileName(p);
		if (p == CostProfile::Safe) EXPECT_GT(ring, 50u);
	}
}

TEST(TraversabilityBuilder, LabelCostsRobotTypeAndScales)
{
	const GridGeometry g(0.05, 0, 0, 60, 20);
	std::vector<LabelSet> labels(g.cellCount());
	const auto put = [&](int r, int c, std::initializer_list<Label> ls)
	{
		for (Label l : ls) labels[g.index(r, c)].insert(l);
	};
	for (int c = 0; c < 60; c++) put(0, c, {Label::Floor});
	put(10, 5, {Label::Floor, Label::Grass});
	put(10, 10, {Label::Floor, Label::Ceiling});
	put(10, 30, {Label::Stairs});
	put(10, 50, {Label::Floor, Label::Wastebasket});

	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.1;
	o.labelU[static_cast<int>(Label::Grass)] = 0.3;
	o.labelU[static_cast<int>(Label::Stairs)] = 0.7;
	o.labelRadiusScale[static_cast<int>(Label::Wastebasket)] = 3;
	const std::vector<CellOccupancy> noOcc;
	{
		const TraversabilityBuilder wheeled(o);
		EXPECT_EQ(wheeled.labelCost(Label::Stairs), o.L);
		EXPECT_EQ(wheeled.labelCost(Label::Wall), o.L);
		const auto u = wheeled.build(g, labels, noOcc, CostProfile::Shortest);
		EXPECT_EQ(u.u(0, 0), 0.0);
		EXPECT_EQ(u.u(10, 5), 0.3);      // grass on floor: the costlier label
		EXPECT_EQ(u.u(10, 10), 0.0);     // ceiling does not block
		EXPECT_TRUE(u.blocked(10, 30));  // stairs, wheeled
		EXPECT_TRUE(u.blocked(10, 33));  // within radius + 5 cm
		EXPECT_FALSE(u.blocked(10, 35));
		EXPECT_TRUE(u.blocked(10, 50));
		// Wastebasket with r_scale 3: blocked while clearance < 15 cm.
		EXPECT_TRUE(u.blocked(10, 55));
		EXPECT_FALSE(u.blocked(10, 56));
	}
	o.robotType = RobotType::Walking;
	{
		const TraversabilityBuilder walking(o);
		EXPECT_EQ(walking.labelCost(Label::Stairs), 0.7);
		const auto u = walking.build(g, labels, noOcc, CostProfile::Shortest);
		EXPECT_EQ(u.u(10, 30), 0.7);
		EXPECT_EQ(u.u(10, 31), 0.0);
	}
}

TEST(TraversabilityBuilder, UnobservedCellsAndBadInput)
{
	const GridGeometry g(0.05, 0, 0, 30, 30);
	std::vector<CellOccupancy> occ(g.cellCount(), CellOccupancy::Free);
	occ[g.index(15, 15)] = CellOccupancy::Unknown;
	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.1;
	// By default an unseen cell is not entered but not inflated either.
	const auto plain = TraversabilityBuilder(o).build(g, {}, occ);
	EXPECT_TRUE(plain.blocked(15, 15));
	EXPECT_FALSE(plain.blocked(15, 16));
	EXPECT_EQ(plain.blockedCount(), 1u);
	o.inflateUnobserved = true;
	EXPECT_TRUE(TraversabilityBuilder(o).build(g, {}, occ).blocked(15, 17));
	o.uUnobserved = 0.2;
	const auto u = TraversabilityBuilder(o).build(g, {}, occ);
	EXPECT_EQ(u.u(15, 15), 0.2);
	EXPECT_EQ(u.u(15, 17), 0.0);
	EXPECT_EQ(u.blockedCount(), 0u);

	// Exploring (finite u_unobserved), an unobserved cell carrying an
	// obstacle label (points above the robot) is not entered but not
	// inflated; a known map's (blocked u_unobserved) is an obstacle.
	std::vector<LabelSet> labels(g.cellCount());
	labels[g.index(15, 15)].insert(Label::Obstacle);
	const auto exploring = TraversabilityBuilder(o).build(g, labels, occ);
	EXPECT_TRUE(exploring.blocked(15, 15));
	EXPECT_EQ(exploring.blockedCount(), 1u);
	o.uUnobserved = TraversabilityBuilder::kBlocked;
	EXPECT_TRUE(TraversabilityBuilder(o).build(g, labels, occ).blocked(15, 17));

	EXPECT_THROW(
	    TraversabilityBuilder().build(g, {}, std::vector<CellOccupancy>(5)),
	    PlanningError);
	EXPECT_THROW(
	    TraversabilityBuilder().build(g, std::vector<LabelSet>(7), {}),
	    PlanningError);
	EXPECT_THROW(
	    TraversabilityBuilder().build(GridGeometry(0, 0, 0, 3, 3), {}, {}),
	    PlanningError);
	EXPECT_EQ(costProfileFromName("safe"), CostProfile::Safe);
	EXPECT_THROW(costProfileFromName("fast"), PlanningError);
}

TEST(TraversabilityBuilder, GoalRegionAroundAnObjectIsReachable)
{
	// A wastebasket (3 x 3 cells) in a room; goals around it for both
	// profiles: some goal cells are free and the path ends within the
	// goal-region radius of the object.
	const GridGeometry g(0.05, 0, 0, 80, 80);
	std::vector<LabelSet> labels(g.cellCount());
	std::vector<CellIndex> basket;
	for (int r = 40; r < 43; r++)
		for (int c = 60; c < 63; c++)
		{
			labels[g.index(r, c)].insert(Label::Wastebasket);
			basket.push_back({r, c});
		}
	const TraversabilityBuilder b;
	for (auto p : {CostProfile::Shortest, CostProfile::Safe})
	{
		const auto u = b.build(g, labels, {}, p);
		GoalLayer goals(g);
		const double radius = b.goalRegionRadius(p);
		EXPECT_GT(goals.addRegionAround(basket, radius, 4), 0u);
		const auto path = CnnPlanner().plan(u, goals, CellIndex{10, 10});
		EXPECT_EQ(path.goalId, 4);
		double d = 1e9;
		for (const auto& c : basket)
		{
			const double ex =
			    std::max(0.0, std::abs(c.col - path.cells.back().col) - 0.5);
			const double ey =
			    std::max(0.0, std::abs(c.row - path.cells.back().row) - 0.5);
			d = std::min(d, std::hypot(ex, ey) * g.resolution);
		}
		EXPECT_LE(d, radius + 1e-9);
		EXPECT_GE(d, b.options().robotRadius);
	}
}

/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/PlanningErrors.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <cmath>

using namespace semnav;

TEST(GridGeometry, CellsOfPointsAndCentres)
{
	const GridGeometry g(0.1, -2.0, 1.0, 30, 20);
	EXPECT_EQ(g.cellCount(), 600u);
	const auto c = g.cellOf(-2.0, 1.0);
	ASSERT_TRUE(c);
	EXPECT_EQ(*c, (CellIndex{0, 0}));
	EXPECT_EQ(*g.cellOf(0.95, 2.95), (CellIndex{19, 29}));
	EXPECT_FALSE(g.cellOf(1.001, 2.0));
	EXPECT_FALSE(g.cellOf(-2.01, 1.5));
	EXPECT_NEAR(g.centerX(0), -1.95, 1e-12);
	EXPECT_NEAR(g.centerY(19), 2.95, 1e-12);
	for (std::size_t i : {0u, 29u, 30u, 599u})
		EXPECT_EQ(g.index(g.cellAt(i)), i);
	EXPECT_THROW(GridGeometry(0.1, 0, 0, 0, 3).validate(), Error);
}

TEST(GoalLayer, DiscRegionIdsAndMask)
{
	const GridGeometry g(0.05, 0, 0, 40, 40);
	GoalLayer goals(g);
	const std::size_t n = goals.addDisc(1.0, 1.0, 0.2, 2);
	std::size_t brute = 0;
	for (int r = 0; r < 40; r++)
		for (int c = 0; c < 40; c++)
			if (std::hypot(g.centerX(c) - 1.0, g.centerY(r) - 1.0) <= 0.2)
				brute++;
	EXPECT_EQ(n, brute);
	EXPECT_EQ(goals.count(), n);
	EXPECT_EQ(goals.id(*g.cellOf(1.01, 1.01)), 2);
	// Overlapping region keeps the first id; only new cells are counted.
	const std::size_t m = goals.addDisc(1.2, 1.0, 0.2, 5);
	EXPECT_LT(m, n);
	EXPECT_EQ(goals.id(*g.cellOf(1.01, 1.01)), 2);
	EXPECT_EQ(goals.id(*g.cellOf(1.39, 1.01)), 5);
	// Clipped at the border.
	EXPECT_GT(goals.addDisc(0.0, 0.0, 0.1, 1), 0u);
	const auto mask = goals.mask();
	std::size_t ones = 0;
	for (auto v : mask) ones += v;
	EXPECT_EQ(ones, goals.count());

	GoalLayer around(g);
	EXPECT_EQ(around.addRegionAround({{10, 10}}, 0.0, 1), 1u);
	// Within 1 cell of the square: centres at distance <= 0.05 m.
	EXPECT_EQ(around.addRegionAround({{20, 20}}, 0.05, 1), 9u);
	EXPECT_THROW(around.addCell({40, 0}), PlanningError);
	EXPECT_THROW(around.addCell({0, 0}, 0), PlanningError);
	EXPECT_THROW(around.addPoint(-0.1, 0.5), PlanningError);
	around.clear();
	EXPECT_EQ(around.count(), 0u);
}

TEST(TraversabilityGrid, ClampsAndBlocks)
{
	const GridGeometry g(0.05, 0, 0, 5, 4);
	TraversabilityGrid u(g, 10, 0.5);
	EXPECT_EQ(u.u(3, 4), 0.5);
	u.setU(1, 1, 25);
	EXPECT_TRUE(u.blocked(1, 1));
	EXPECT_EQ(u.u(1, 1), 10);
	u.setU(1, 2, -3);
	EXPECT_EQ(u.u(1, 2), 0);
	u.block(0, 0);
	EXPECT_EQ(u.blockedCount(), 2u);
	EXPECT_THROW(u.setU(0, 1, std::nan("")), PlanningError);
	EXPECT_THROW(TraversabilityGrid(g, 0), PlanningError);
}

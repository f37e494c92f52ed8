/* semnav: semantic navigation from tilting-laser sweeps */
// The paper's claim (sec. 3, conclusions): unlike potential fields, the CNN
// planner has no local minima. A U-shaped obstacle opens toward the start;
// the goal is behind it.
#include <gtest/gtest.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/TraversabilityBuilder.h>

#include <cmath>
#include <limits>

using namespace semnav;

namespace
{
struct Trap
{
	GridGeometry g{0.05, 0, 0, 100, 80};
	std::vector<CellOccupancy> occ;
	CellIndex start{40, 10}, goal{40, 85};
	explicit Trap(bool cup = true) : occ(g.cellCount(), CellOccupancy::Free)
	{
		if (!cup) return;
		// Cup bottom at col 55 (rows 20..60), arms along rows 20 and 60 from
		// col 30 to 55: open toward the start (left).
		for (int r = 20; r <= 60; r++)
			occ[g.index(r, 55)] = CellOccupancy::Occupied;
		for (int c = 30; c <= 55; c++)
		{
			occ[g.index(20, c)] = CellOccupancy::Occupied;
			occ[g.index(60, c)] = CellOccupancy::Occupied;
		}
	}
};

/** Greedy descent on an attractive (distance to goal) plus repulsive
 * (Khatib, influence d0) potential; returns the cell where it stops. */
CellIndex potentialFieldDescent(
    const Trap& t, const TraversabilityGrid& u, int maxSteps, bool& arrived)
{
	const auto& g = t.g;
	std::vector<CellIndex> obstacles;
	for (int r = 0; r < g.rows; r++)
		for (int c = 0; c < g.cols; c++)
			if (t.occ[g.index(r, c)] == CellOccupancy::Occupied)
				obstacles.push_back({r, c});
	const double d0 = 0.5, kAtt = 1.0, kRep = 0.05;
	const auto potential = [&](const CellIndex& c)
	{
		const double x = g.centerX(c.col), y = g.centerY(c.row);
		double p =
		    kAtt *
		    std::hypot(x - g.centerX(t.goal.col), y - g.centerY(t.goal.row));
		for (const auto& o : obstacles)
		{
			const double d = std::max(
			    1e-3, std::hypot(x - g.centerX(o.col), y - g.centerY(o.row)));
			if (d < d0) p += 0.5 * kRep * std::pow(1 / d - 1 / d0, 2);
		}
		return p;
	};
	CellIndex cur = t.start;
	arrived = false;
	for (int step = 0; step < maxSteps; step++)
	{
		if (cur == t.goal)
		{
			arrived = true;
			break;
		}
		CellIndex best = cur;
		double pBest = potential(cur);
		for (int dr = -1; dr <= 1; dr++)
			for (int dc = -1; dc <= 1; dc++)
			{
				const CellIndex n{cur.row + dr, cur.col + dc};
				if (!g.contains(n) || u.blocked(n)) continue;
				const double pn = potential(n);
				if (pn < pBest)
				{
					pBest = pn;
					best = n;
				}
			}
		if (best == cur) break;  // local minimum
		cur = best;
	}
	return cur;
}
}  // namespace

TEST(LocalMinima, PotentialFieldIsTrappedCnnArrives)
{
	const Trap t;
	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.1;
	const auto u =
	    TraversabilityBuilder(o).build(t.g, {}, t.occ, CostProfile::Shortest);
	ASSERT_FALSE(u.blocked(t.start));
	ASSERT_FALSE(u.blocked(t.goal));

	bool arrived = true;
	const CellIndex stuck = potentialFieldDescent(t, u, 2000, arrived);
	EXPECT_FALSE(arrived);
	// Stuck inside the cup, in front of its bottom.
	EXPECT_GT(stuck.row, 20);
	EXPECT_LT(stuck.row, 60);
	EXPECT_GT(stuck.col, 30);
	EXPECT_LT(stuck.col, 55);

	// Control: without the cup the same descent arrives.
	const Trap open(false);
	const auto uOpen = TraversabilityBuilder(o).build(
	    open.g, {}, open.occ, CostProfile::Shortest);
	bool openArrived = false;
	potentialFieldDescent(open, uOpen, 2000, openArrived);
	EXPECT_TRUE(openArrived);

	GoalLayer goals(t.g);
	goals.addCell(t.goal);
	for (auto s : {CnnSchedule::Sweep, CnnSchedule::Jacobi})
	{
		CnnPlanner::TOptions po;
		po.schedule = s;
		const auto path = CnnPlanner(po).plan(u, goals, t.start);
		EXPECT_EQ(path.cells.back(), t.goal);
		bool aroundCup = false;
		for (const auto& c : path.cells)
		{
			EXPECT_FALSE(u.blocked(c));
			aroundCup = aroundCup || c.row < 20 || c.row > 60;
		}
		EXPECT_TRUE(aroundCup);
		EXPECT_LT(path.lengthM, 2 * 0.05 * (t.goal.col - t.start.col) + 3.0);
	}
}

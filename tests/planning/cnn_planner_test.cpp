/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/DijkstraPlanner.h>
#include <semnav/planning/PlanningErrors.h>

#include <cmath>
#include <functional>
#include <random>

#include "WallSegments.h"

using namespace semnav;

namespace
{
struct Problem
{
	TraversabilityGrid u;
	GoalLayer goals;
};

/** Random u in [0, uMax], a fraction of blocked cells (some as wall
 * segments), `nGoals` goal cells with ids 1..nGoals. */
Problem randomProblem(
    int rows, int cols, double blocked, double uMax, int nGoals, uint64_t seed)
{
	std::mt19937_64 rng(seed);
	std::uniform_real_distribution<double> U(0, 1);
	const GridGeometry g(0.05, -1.0, 2.0, cols, rows);
	Problem p{TraversabilityGrid(g, 1e6), GoalLayer(g)};
	for (int r = 0; r < rows; r++)
		for (int c = 0; c < cols; c++)
		{
			if (U(rng) < blocked)
				p.u.block(r, c);
			else
				p.u.setU(r, c, U(rng) < 0.5 ? 0.0 : uMax * U(rng));
		}
	test::addWallSegments(p.u, rows / 4, rng);  // walls: long blocked segments
	for (int k = 1; k <= nGoals; k++)  // free goal cells, with their own u
	{
		const CellIndex c{
		    static_cast<int>(U(rng) * rows), static_cast<int>(U(rng) * cols)};
		p.u.setU(c.row, c.col, uMax * U(rng));
		p.goals.addCell(c, k);
	}
	return p;
}

DiffusionField field(const Problem& p, CnnSchedule s, int threads)
{
	CnnPlanner::TOptions o;
	o.schedule = s;
	o.threads = threads;
	return CnnPlanner(o).computeField(p.u, p.goals);
}

/** Cost of a path recomputed from its cells; fails the test when a step is
 * not between 8-neighbours or enters a blocked cell. */
double recomputedCost(const PlannedPath& path, const TraversabilityGrid& u)
{
	const double res = u.geometry().resolution;
	double cost = 0;
	for (std::size_t k = 1; k < path.cells.size(); k++)
	{
		const auto& a = path.cells[k - 1];
		const auto& b = path.cells[k];
		const int dr = std::abs(a.row - b.row), dc = std::abs(a.col - b.col);
		EXPECT_TRUE(dr <= 1 && dc <= 1 && dr + dc > 0) << "step " << k;
		EXPECT_FALSE(u.blocked(b)) << "step " << k << " enters a blocked cell";
		cost += (dr + dc == 2 ? res * std::sqrt(2.0) : res) + u.u(b.row, b.col);
	}
	return cost;
}

std::string messageOf(const std::function<void()>& f)
{
	try
	{
		f();
	}
	catch (const Error& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(CnnPlanner, SweepFieldEqualsJacobiFieldOnRandomMaps)
{
	int maps = 0;
	for (uint64_t seed = 1; seed <= 12; seed++)
	{
		const int rows = 20 + static_cast<int>(seed * 7 % 50);
		const int cols = 15 + static_cast<int>(seed * 13 % 60);
		const auto p = randomProblem(
		    rows, cols, 0.05 + 0.03 * (seed % 5), seed % 3 == 0 ? 0 : 2.0,
		    1 + static_cast<int>(seed % 4), seed);
		const auto ref = field(p, CnnSchedule::Jacobi, 1);
		EXPECT_EQ(ref.x, field(p, CnnSchedule::Jacobi, 3).x) << "seed " << seed;
		for (int threads : {1, 2, 3})
		{
			const auto f = field(p, CnnSchedule::Sweep, threads);
			ASSERT_EQ(f.x.size(), ref.x.size());
			std::size_t differ = 0;
			for (std::size_t i = 0; i < f.x.size(); i++)
				if (f.x[i] != ref.x[i]) differ++;  // exact, -inf included
			EXPECT_EQ(differ, 0u) << "seed " << seed << " threads " << threads;
		}
		maps++;
	}
	EXPECT_EQ(maps, 12);
}

TEST(CnnPlanner, CostsEqualDijkstraOnRandomMaps)
{
	std::mt19937_64 rng(99);
	for (uint64_t seed = 21; seed <= 30; seed++)
	{
		const auto p = randomProblem(45, 60, 0.15, 3.0, 3, seed);
		const auto f = field(p, CnnSchedule::Sweep, 2);
		const auto V = DijkstraPlanner::costField(p.u, p.goals);
		const auto& g = p.u.geometry();
		std::size_t reached = 0;
		for (std::size_t i = 0; i < V.size(); i++)
		{
			const auto c = g.cellAt(i);
			ASSERT_EQ(std::isfinite(V[i]), f.reached(c)) << "cell " << i;
			if (!std::isfinite(V[i])) continue;
			reached++;
			EXPECT_NEAR(f.costToGo(c), V[i], 1e-6 * std::max(1.0, V[i]));
		}
		EXPECT_GT(reached, V.size() / 4);

		// Paths from random reachable starts.
		int paths = 0;
		for (int k = 0; k < 200 && paths < 5; k++)
		{
			const CellIndex s{
			    static_cast<int>(rng() % g.rows),
			    static_cast<int>(rng() % g.cols)};
			if (!f.reached(s)) continue;
			const auto path = CnnPlanner::extractPath(f, p.u, p.goals, s);
			const auto dij = DijkstraPlanner::plan(p.u, p.goals, s);
			EXPECT_EQ(path.cells.front(), s);
			EXPECT_TRUE(p.goals.isGoal(path.cells.back()));
			EXPECT_EQ(path.goalId, p.goals.id(path.cells.back()));
			EXPECT_NEAR(path.cost, recomputedCost(path, p.u), 1e-9);
			EXPECT_NEAR(
			    path.cost, f.costToGo(s), 1e-9 * std::max(1.0, path.cost));
			EXPECT_NEAR(path.cost, dij.cost, 1e-6 * std::max(1.0, dij.cost));
			EXPECT_NEAR(dij.cost, recomputedCost(dij, p.u), 1e-9);
			paths++;
		}
		EXPECT_EQ(paths, 5) << "seed " << seed;
	}
}

TEST(CnnPlanner, EveryEnteredCellIsChargedOnceGoalIncluded)
{
	// 1 x n corridor, goal at the right end with its own u.
	const int n = 40;
	const GridGeometry g(0.1, 0, 0, n, 1);
	TraversabilityGrid u(g, 1000);
	std::mt19937_64 rng(5);
	std::uniform_real_distribution<double> U(0.1, 2.0);
	for (int c = 0; c < n; c++) u.setU(0, c, U(rng));
	GoalLayer goals(g);
	goals.addCell({0, n - 1}, 7);
	double expected = 0;
	for (int c = 1; c < n; c++) expected += g.resolution + u.u(0, c);

	for (auto s : {CnnSchedule::Sweep, CnnSchedule::Jacobi})
	{
		CnnPlanner::TOptions o;
		o.schedule = s;
		DiffusionField f;
		const auto path = CnnPlanner(o).plan(u, goals, CellIndex{0, 0}, &f);
		EXPECT_NEAR(path.cost, expected, 1e-12);
		EXPECT_NEAR(f.costToGo({0, 0}), expected, 1e-9);
		EXPECT_NEAR(path.lengthM, (n - 1) * g.resolution, 1e-12);
		EXPECT_EQ(path.cells.size(), static_cast<std::size_t>(n));
		EXPECT_EQ(path.goalId, 7);
		EXPECT_EQ(f.at({0, n - 1}), u.L());  // goal cells hold L
		// Jacobi: one update per cell of distance, plus the one of eq. (11).
		if (s == CnnSchedule::Jacobi) EXPECT_EQ(f.iterations, n);
	}
}

TEST(CnnPlanner, ChoosesLeastCostGoalNotNearest)
{
	// Goal 1 is 1 m away behind a wall (a long detour), goal 2 is 2.5 m away
	// in the open.
	const GridGeometry g(0.05, 0, 0, 120, 120);
	TraversabilityGrid u(g, 1e6);
	for (int r = 10; r < 110; r++) u.block(r, 60);  // wall at x = 3 m
	GoalLayer goals(g);
	goals.addDisc(3.6, 3.0, 0.1, 1);  // 1 m right, behind the wall
	goals.addDisc(2.6, 0.6, 0.1, 2);  // 2.5 m down, open
	const CellIndex start = *g.cellOf(2.6, 3.0);
	const auto path = CnnPlanner().plan(u, goals, start);
	EXPECT_EQ(path.goalId, 2);
	// Planning to goal 1 alone costs more.
	GoalLayer only1(g);
	only1.addDisc(3.6, 3.0, 0.1, 1);
	const auto p1 = CnnPlanner().plan(u, only1, start);
	EXPECT_EQ(p1.goalId, 1);
	EXPECT_GT(p1.cost, path.cost);
	const auto& a = path.points.back();
	EXPECT_LT(std::hypot(a.x - 2.6, a.y - 0.6), 0.11);
}

TEST(CnnPlanner, TypedErrorsWithOneLineMessages)
{
	const GridGeometry g(0.05, 0, 0, 40, 30);
	TraversabilityGrid u(g, 1e6);
	for (int r = 10; r < 20; r++)
		for (int c = 10; c < 20; c++)
			if (r == 10 || r == 19 || c == 10 || c == 19) u.block(r, c);
	u.block(0, 0);
	GoalLayer goals(g);
	goals.addCell({15, 15});  // enclosed
	const CnnPlanner planner;

	const auto check = [](const std::string& m, const char* word)
	{
		EXPECT_NE(m.find(word), std::string::npos) << m;
		EXPECT_EQ(m.find('\n'), std::string::npos) << m;
	};
	EXPECT_THROW(planner.plan(u, goals, 5.0, 0.5), StartOutsideMapError);
	EXPECT_THROW(planner.plan(u, goals, -0.01, 0.5), StartOutsideMapError);
	check(
	    messageOf([&] { planner.plan(u, goals, 5.0, 0.5); }),
	    "outside the map");
	EXPECT_THROW(planner.plan(u, goals, CellIndex{0, 0}), StartBlockedError);
	check(
	    messageOf(
	        [&] {
		        planner.plan(u, goals, CellIndex{0, 0});
	        }),
	    "blocked");
	EXPECT_THROW(planner.plan(u, goals, CellIndex{2, 2}), NoPathError);
	check(
	    messageOf(
	        [&] {
		        planner.plan(u, goals, CellIndex{2, 2});
	        }),
	    "no path");
	EXPECT_THROW(DijkstraPlanner::plan(u, goals, CellIndex{2, 2}), NoPathError);

	GoalLayer none(g);
	EXPECT_THROW(planner.plan(u, none, CellIndex{2, 2}), EmptyGoalError);
	check(messageOf([&] { planner.plan(u, none, CellIndex{2, 2}); }), "empty");
	GoalLayer onWall(g);
	onWall.addCell({10, 12});
	EXPECT_THROW(planner.plan(u, onWall, CellIndex{2, 2}), EmptyGoalError);
	EXPECT_THROW(planner.computeField(u, onWall), EmptyGoalError);

	// All are semnav::Error (apps print what() and exit 1).
	EXPECT_FALSE(messageOf(
	                 [&] {
		                 planner.plan(u, none, CellIndex{2, 2});
	                 })
	                 .empty());

	GoalLayer far(g);
	far.addCell({29, 39});
	CnnPlanner::TOptions o;
	o.schedule = CnnSchedule::Jacobi;
	o.maxIterations = 3;
	EXPECT_THROW(CnnPlanner(o).computeField(u, far), NotConvergedError);
	o.schedule = CnnSchedule::Sweep;
	o.maxIterations = 1;
	EXPECT_THROW(CnnPlanner(o).computeField(u, far), NotConvergedError);
	o.maxIterations = 0;
	EXPECT_NO_THROW(CnnPlanner(o).plan(u, far, CellIndex{2, 2}));
	EXPECT_THROW(far.addPoint(2.1, 0.5), PlanningError);
}

TEST(CnnPlanner, StartOnGoalIsAZeroCostPath)
{
	const GridGeometry g(0.05, 0, 0, 10, 10);
	TraversabilityGrid u(g, 100, 0.5);
	GoalLayer goals(g);
	goals.addCell({4, 4}, 3);
	const auto p = CnnPlanner().plan(u, goals, CellIndex{4, 4});
	EXPECT_EQ(p.cells.size(), 1u);
	EXPECT_EQ(p.cost, 0);
	EXPECT_EQ(p.goalId, 3);
}

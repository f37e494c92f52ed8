/* semnav: semantic navigation from tilting-laser sweeps */
// CnnPlanner::repairField: the repaired field is the full recompute's fixed
// point, bit for bit, after random changes of every kind.
#include <gtest/gtest.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/PlanningErrors.h>
#include <semnav/planning/TraversabilityBuilder.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "WallSegments.h"

using namespace semnav;

namespace
{
constexpr double kNoLimit = std::numeric_limits<double>::infinity();
/** Grid sizes (rows, cols) of the random runs. */
constexpr int kSizes[][2] = {{1, 9}, {7, 3}, {24, 31}, {57, 40}, {96, 128}};

struct RepairProblem
{
	TraversabilityGrid u;
	GoalLayer goals;
};

/** Random costs (half of the cells free of cost), blocked cells, a few
 * wall segments and `nGoals` goal discs. */
RepairProblem randomProblem(
    int rows, int cols, double L, uint64_t seed, int nGoals)
{
	std::mt19937_64 rng(seed);
	std::uniform_real_distribution<double> U(0, 1);
	const GridGeometry g(0.05, 1.0, -2.0, cols, rows);
	RepairProblem p{TraversabilityGrid(g, L), GoalLayer(g)};
	for (int r = 0; r < rows; r++)
		for (int c = 0; c < cols; c++)
		{
			if (U(rng) < 0.08)
				p.u.block(r, c);
			else if (U(rng) < 0.5)
				p.u.setU(r, c, 3.0 * U(rng));
		}
	test::addWallSegments(p.u, rows / 8, rng);
	for (int k = 1; k <= nGoals; k++)
	{
		const CellIndex c{
		    static_cast<int>(U(rng) * rows), static_cast<int>(U(rng) * cols)};
		p.u.setU(c.row, c.col, 0);
		p.goals.addDisc(g.centerX(c.col), g.centerY(c.row), 0.08, k);
	}
	return p;
}

std::size_t cellsDiffering(const DiffusionField& a, const DiffusionField& b)
{
	EXPECT_EQ(a.x.size(), b.x.size());
	std::size_t n = 0;
	for (std::size_t i = 0; i < std::min(a.x.size(), b.x.size()); i++)
		n += a.x[i] != b.x[i];  // exact, -inf included
	return n;
}

/** A random rectangle of up to `maxSide` cells a side inside the grid. */
CellRect randomRect(const GridGeometry& g, int maxSide, std::mt19937_64& rng)
{
	const int h = 1 + static_cast<int>(rng() % std::min(maxSide, g.rows));
	const int w = 1 + static_cast<int>(rng() % std::min(maxSide, g.cols));
	const int r = static_cast<int>(rng() % (g.rows - h + 1));
	const int c = static_cast<int>(rng() % (g.cols - w + 1));
	return {r, c, r + h, c + w};
}

template <class F>
void forCells(const CellRect& r, const F& f)
{
	for (int row = r.row0; row < r.row1; row++)
		for (int col = r.col0; col < r.col1; col++) f(row, col);
}

enum class Change
{
	AddObstacle,
	RemoveObstacles,
	CostsUp,
	CostsDown,
	CostsMixed,
	GoalAdded,
	GoalCellsRemoved,
	GoalBlocked,
	WallAcross,
	Scattered,
	Count
};

/** Applies a random change of kind `kind` to p; returns the rectangle
 * holding every changed cell. */
CellRect applyChange(RepairProblem& p, Change kind, std::mt19937_64& rng)
{
	const auto& g = p.u.geometry();
	std::uniform_real_distribution<double> U(0, 1);
	CellRect rect = randomRect(g, 9, rng);
	switch (kind)
	{
		case Change::AddObstacle:
			forCells(rect, [&](int r, int c) { p.u.block(r, c); });
			break;
		case Change::RemoveObstacles:
			forCells(
			    rect,
			    [&](int r, int c)
			    {
				    if (p.u.blocked(r, c)) p.u.setU(r, c, 2.0 * U(rng));
			    });
			break;
		case Change::CostsUp:
		case Change::CostsDown:
		case Change::CostsMixed:
			forCells(
			    rect,
			    [&](int r, int c)
			    {
				    if (p.u.blocked(r, c)) return;
				    const double old = p.u.u(r, c);
				    const double d = 1.5 * U(rng);
				    const double s = kind == Change::CostsUp     ? 1
				                     : kind == Change::CostsDown ? -1
				                     : U(rng) < 0.5              ? 1
				                                                 : -1;
				    p.u.setU(r, c, std::max(0.0, old + s * d));
			    });
			break;
		case Change::GoalAdded:
		{
			const CellIndex c{rect.row0, rect.col0};
			p.u.setU(c.row, c.col, 0);
			p.goals.addCell(c, 99);
			rect = {c.row, c.col, c.row + 1, c.col + 1};
			break;
		}
		case Change::GoalCellsRemoved:
		case Change::GoalBlocked:
		{
			// Around a random goal cell: drop (or block) the goal cells of
			// the rectangle, keeping at least one goal cell.
			std::vector<std::size_t> goalCells;
			for (std::size_t i = 0; i < g.cellCount(); i++)
				if (p.goals.isGoal(i)) goalCells.push_back(i);
			const auto at = g.cellAt(goalCells[rng() % goalCells.size()]);
			rect = CellRect{at.row - 1, at.col - 1, at.row + 2, at.col + 2}
			           .clipped(g);
			GoalLayer kept(g);
			std::size_t dropped = 0;
			for (const std::size_t i : goalCells)
			{
				const auto c = g.cellAt(i);
				const bool inside = c.row >= rect.row0 && c.row < rect.row1 &&
				                    c.col >= rect.col0 && c.col < rect.col1;
				const bool drop = inside && dropped + 1 < goalCells.size();
				dropped += drop;
				if (drop && kind == Change::GoalBlocked)
					p.u.block(c.row, c.col);
				if (!drop || kind == Change::GoalBlocked)
					kept.addCell(c, p.goals.id(i));
			}
			p.goals = kept;
			break;
		}
		case Change::WallAcross:
		{
			// A full row or column: disconnects the grid (until a later
			// RemoveObstacles reconnects it).
			const bool vertical = U(rng) < 0.5;
			const int at =
			    static_cast<int>(U(rng) * (vertical ? g.cols : g.rows));
			rect = vertical ? CellRect{0, at, g.rows, at + 1}
			                : CellRect{at, 0, at + 1, g.cols};
			forCells(rect, [&](int r, int c) { p.u.block(r, c); });
			break;
		}
		case Change::Scattered:
		{
			CellRect box;
			for (int k = 0; k < 6; k++)
			{
				const int r = static_cast<int>(rng() % g.rows);
				const int c = static_cast<int>(rng() % g.cols);
				if (U(rng) < 0.4)
					p.u.block(r, c);
				else
					p.u.setU(r, c, 3.0 * U(rng));
				box.add(r, c);
			}
			rect = box;
			break;
		}
		case Change::Count:
			break;
	}
	return rect;
}

bool anyTraversableGoal(const RepairProblem& p)
{
	for (std::size_t i = 0; i < p.u.values().size(); i++)
		if (p.goals.isGoal(i) && !p.u.blocked(i)) return true;
	return false;
}

/** A random change applied to p, with p before it and the rectangle
 * holding it; nullopt (p unchanged) when it left no traversable goal. */
struct Step
{
	RepairProblem before;
	Change kind;
	CellRect rect;
};
std::optional<Step> randomStep(RepairProblem& p, std::mt19937_64& rng)
{
	Step s{p, static_cast<Change>(rng() % static_cast<int>(Change::Count)), {}};
	s.rect = applyChange(p, s.kind, rng);
	if (anyTraversableGoal(p)) return s;
	p = s.before;
	return std::nullopt;
}

std::string whereText(uint64_t seed, int step, Change kind)
{
	return "seed " + std::to_string(seed) + " step " + std::to_string(step) +
	       " change " + std::to_string(static_cast<int>(kind));
}

/** Paths from up to `n` random reached starts: the same cells and cost on
 * both fields. */
void expectSamePaths(
    const DiffusionField& repaired, const DiffusionField& full,
    const RepairProblem& p, std::mt19937_64& rng, int n)
{
	const auto& g = p.u.geometry();
	int found = 0;
	for (int k = 0; k < 50 * n && found < n; k++)
	{
		const CellIndex s{
		    static_cast<int>(rng() % g.rows), static_cast<int>(rng() % g.cols)};
		if (p.u.blocked(s) || !full.reached(s)) continue;
		const auto a = CnnPlanner::extractPath(repaired, p.u, p.goals, s);
		const auto b = CnnPlanner::extractPath(full, p.u, p.goals, s);
		EXPECT_EQ(a.cells, b.cells);
		EXPECT_EQ(a.cost, b.cost);
		EXPECT_EQ(a.goalId, b.goalId);
		found++;
	}
}

struct RunTally
{
	int repairs = 0, fallbacks = 0, invalidating = 0;
};

/** `steps` random changes in a row on one field, each repaired (with the
 * changed rectangle or, every third step, without) and compared with the
 * full recompute. */
RunTally randomRun(
    int rows, int cols, double L, uint64_t seed, int steps, double workLimit)
{
	RunTally t;
	std::mt19937_64 rng(seed * 7919);
	RepairProblem p = randomProblem(rows, cols, L, seed, 1 + seed % 3);
	const CnnPlanner planner;
	DiffusionField f = planner.computeField(p.u, p.goals);
	for (int step = 0; step < steps; step++)
	{
		const auto change = randomStep(p, rng);
		if (!change) continue;
		const auto& [before, kind, rect] = *change;
		const bool withRect = step % 3 != 0;
		const auto stats = planner.repairField(
		    f, before.u, before.goals, p.u, p.goals, withRect ? &rect : nullptr,
		    workLimit);
		const auto full = planner.computeField(p.u, p.goals);
		const std::string where = whereText(seed, step, kind);
		EXPECT_EQ(cellsDiffering(f, full), 0u) << where;
		expectSamePaths(f, full, p, rng, 3);
		(stats.fullRecompute ? t.fallbacks : t.repairs)++;
		t.invalidating += stats.invalidatedCells > 0;
	}
	return t;
}
}  // namespace

TEST(FieldRepair, RandomChangesReachTheFullRecomputesFixedPoint)
{
	RunTally total;
	for (const auto& s : kSizes)
		for (uint64_t seed = 1; seed <= 6; seed++)
		{
			const auto t = randomRun(s[0], s[1], 1e6, seed, 30, kNoLimit);
			total.repairs += t.repairs;
			total.fallbacks += t.fallbacks;
			total.invalidating += t.invalidating;
		}
	// Without a work limit every change is repaired (no goal moves here).
	EXPECT_EQ(total.fallbacks, 0);
	EXPECT_GT(total.repairs, 700);
	EXPECT_GT(total.invalidating, 100);  // the increase phase ran
}

TEST(FieldRepair, RandomChangesWithTheDefaultWorkLimitAndASmallL)
{
	// L = 40: costs of a few units are a large share of L; with the default
	// limit, some repairs fall back and the result is the same either way.
	RunTally total;
	for (uint64_t seed = 11; seed <= 16; seed++)
	{
		const auto t = randomRun(
		    80, 70, 40.0, seed, 25, CnnPlanner::kRepairMaxWorkFraction);
		total.repairs += t.repairs;
		total.fallbacks += t.fallbacks;
	}
	EXPECT_GT(total.repairs, 50);
}

namespace
{
/** A random traversable cell that `full` reaches; nullopt when none is
 * found. */
std::optional<CellIndex> reachedStart(
    const DiffusionField& full, const RepairProblem& p, std::mt19937_64& rng)
{
	const auto& g = p.u.geometry();
	for (int k = 0; k < 200; k++)
	{
		const CellIndex s{
		    static_cast<int>(rng() % g.rows), static_cast<int>(rng() % g.cols)};
		if (!p.u.blocked(s) && full.reached(s)) return s;
	}
	return std::nullopt;
}

/** After a start-bounded repair: every cell whose full-recompute cost to
 * go plus focus (PendingRepair::kFocusWeight times its octile distance to
 * the start) is at most the start's cost is exact, which holds every best
 * path from the start; the path from the start is the full recompute's. */
void expectExactForStart(
    const DiffusionField& f, const DiffusionField& full,
    const PendingRepair& pending, const RepairProblem& p, const CellIndex& s,
    const std::string& where)
{
	const auto& g = p.u.geometry();
	const double startCost = full.costToGo(s);
	std::size_t wrong = 0, inside = 0;
	for (std::size_t i = 0; i < f.x.size(); i++)
	{
		const CellIndex c = g.cellAt(i);
		const int dr = std::abs(c.row - s.row), dc = std::abs(c.col - s.col);
		const int d = std::min(dr, dc);
		const double octile =
		    g.resolution * (std::sqrt(2.0) * d + std::max(dr, dc) - d);
		if (full.costToGo(c) + PendingRepair::kFocusWeight * octile > startCost)
			continue;
		inside++;
		wrong += f.x[i] != full.x[i];
	}
	EXPECT_EQ(wrong, 0u) << where << " (" << inside << " cells)";
	EXPECT_GT(pending.settledCost(), startCost) << where;
	const auto a = CnnPlanner::extractPath(f, p.u, p.goals, s);
	const auto b = CnnPlanner::extractPath(full, p.u, p.goals, s);
	EXPECT_EQ(a.cells, b.cells) << where;
	EXPECT_EQ(a.cost, b.cost) << where;
}

struct BoundedTally
{
	int repairs = 0, leftPending = 0;
	std::size_t boundedWork = 0, fullWork = 0;
};

/** `steps` random changes on one field, each repaired bounded by a random
 * reached start, checked for it, bounded again by a second start, then
 * finished (every other time on a copy of the field) and compared with the
 * full recompute; the unbounded repair's work on a copy, for reference. */
void boundedRun(int rows, int cols, uint64_t seed, int steps, BoundedTally& t)
{
	std::mt19937_64 rng(seed * 104729);
	RepairProblem p = randomProblem(rows, cols, 1e6, seed, 1 + seed % 3);
	const CnnPlanner planner;
	DiffusionField f = planner.computeField(p.u, p.goals);
	for (int step = 0; step < steps; step++)
	{
		const auto change = randomStep(p, rng);
		if (!change) continue;
		const auto& [before, kind, rect] = *change;
		const std::string where = whereText(seed, step, kind);
		const auto full = planner.computeField(p.u, p.goals);
		DiffusionField unbounded = f;
		t.fullWork += planner
		                  .repairField(
		                      unbounded, before.u, before.goals, p.u, p.goals,
		                      &rect, kNoLimit)
		                  .poppedCells;
		const auto s = reachedStart(full, p, rng);
		const CellIndex start = s ? *s : CellIndex{0, 0};
		PendingRepair pending;
		const auto st = planner.repairFieldFrom(
		    start, f, before.u, before.goals, p.u, p.goals, pending,
		    step % 3 ? &rect : nullptr, kNoLimit);
		EXPECT_FALSE(st.fullRecompute) << where;
		t.boundedWork += st.poppedCells;
		t.repairs++;
		t.leftPending += !pending.empty();
		if (s) expectExactForStart(f, full, pending, p, start, where);
		// The same start: nothing more to do; another: all of it.
		if (s && !pending.empty())
		{
			planner.finishRepair(f, pending, &start);
			expectExactForStart(f, full, pending, p, start, where + " (again)");
		}
		const auto s2 = reachedStart(full, p, rng);
		if (s2 && !(*s2 == start))
		{
			planner.finishRepair(f, pending, &*s2);
			EXPECT_TRUE(pending.empty()) << where;
		}
		if (step % 2)
		{
			DiffusionField copy = f;
			planner.finishRepair(copy, pending);
			f = copy;
		}
		else
			planner.finishRepair(f, pending);
		EXPECT_TRUE(pending.empty()) << where;
		EXPECT_EQ(cellsDiffering(f, full), 0u) << where;
	}
}
}  // namespace

TEST(FieldRepair, StartBoundedRepairIsExactForTheStartsPath)
{
	BoundedTally t;
	for (const auto& s : kSizes)
		for (uint64_t seed = 1; seed <= 6; seed++)
			boundedRun(s[0], s[1], seed, 30, t);
	EXPECT_GT(t.repairs, 700);
	// Work was left for later, and the bounded repairs did less in all.
	EXPECT_GT(t.leftPending, 100);
	EXPECT_LT(t.boundedWork, t.fullWork);
}

TEST(FieldRepair, StartBoundedRepairNeedsNoPendingWork)
{
	RepairProblem p = randomProblem(40, 50, 1e6, 5, 1);
	const CnnPlanner planner;
	DiffusionField f = planner.computeField(p.u, p.goals);
	PendingRepair pending;
	for (int k = 0; k < 20 && pending.empty(); k++)
	{
		const RepairProblem before = p;
		std::mt19937_64 rng(k);
		const CellRect r = applyChange(p, Change::AddObstacle, rng);
		planner.repairFieldFrom(
		    {39, 49}, f, before.u, before.goals, p.u, p.goals, pending, &r);
	}
	ASSERT_FALSE(pending.empty());
	EXPECT_THROW(
	    planner.repairFieldFrom({0, 0}, f, p.u, p.goals, p.u, p.goals, pending),
	    PlanningError);
	planner.finishRepair(f, pending);
	EXPECT_EQ(cellsDiffering(f, planner.computeField(p.u, p.goals)), 0u);
}

TEST(FieldRepair, NoChangeTouchesNothing)
{
	const RepairProblem p = randomProblem(40, 50, 1e6, 3, 2);
	const CnnPlanner planner;
	DiffusionField f = planner.computeField(p.u, p.goals);
	const auto ref = f;
	const CellRect rect{5, 5, 20, 30};
	for (const CellRect* r : {&rect, static_cast<const CellRect*>(nullptr)})
	{
		const auto st = planner.repairField(f, p.u, p.goals, p.u, p.goals, r);
		EXPECT_FALSE(st.fullRecompute);
		EXPECT_EQ(st.changedCells, 0u);
		EXPECT_EQ(st.invalidatedCells, 0u);
		EXPECT_EQ(st.raisedCells, 0u);
		EXPECT_EQ(f.x, ref.x);
	}
	// An empty or outside rectangle: nothing compared, nothing changed.
	const CellRect outside{100, 100, 120, 130};
	const auto st =
	    planner.repairField(f, p.u, p.goals, p.u, p.goals, &outside);
	EXPECT_EQ(st.changedCells, 0u);
	EXPECT_EQ(f.x, ref.x);
}

TEST(FieldRepair, ChangeEverywhereFallsBackUnlessUnlimited)
{
	const RepairProblem before = randomProblem(60, 60, 1e6, 4, 2);
	RepairProblem after = randomProblem(60, 60, 1e6, 5, 2);
	after.goals = before.goals;
	for (std::size_t i = 0; i < after.u.values().size(); i++)
		if (before.goals.isGoal(i)) after.u.values()[i] = 0;
	const CnnPlanner planner;
	const auto full = planner.computeField(after.u, after.goals);

	DiffusionField f = planner.computeField(before.u, before.goals);
	auto st =
	    planner.repairField(f, before.u, before.goals, after.u, after.goals);
	EXPECT_TRUE(st.fullRecompute);
	EXPECT_NE(st.fallbackReason.find("changed cells"), std::string::npos)
	    << st.fallbackReason;
	EXPECT_GT(st.changedCells, 60u * 60u / 2);
	EXPECT_EQ(cellsDiffering(f, full), 0u);

	// The repair itself, over the whole grid, reaches the same field.
	f = planner.computeField(before.u, before.goals);
	st = planner.repairField(
	    f, before.u, before.goals, after.u, after.goals, nullptr, kNoLimit);
	EXPECT_FALSE(st.fullRecompute);
	EXPECT_GT(st.invalidatedCells, 0u);
	EXPECT_EQ(cellsDiffering(f, full), 0u);
}

TEST(FieldRepair, GoalMovedFallsBackToAFullRecompute)
{
	RepairProblem p = randomProblem(50, 50, 1e6, 6, 1);
	const CnnPlanner planner;
	DiffusionField f = planner.computeField(p.u, p.goals);
	const RepairProblem before = p;
	p.goals = GoalLayer(p.u.geometry());
	p.u.setU(40, 8, 0);
	p.goals.addCell({40, 8}, 1);
	const auto st = planner.repairField(
	    f, before.u, before.goals, p.u, p.goals, nullptr, kNoLimit);
	EXPECT_TRUE(st.fullRecompute);
	EXPECT_NE(st.fallbackReason.find("goal moved"), std::string::npos);
	EXPECT_EQ(cellsDiffering(f, planner.computeField(p.u, p.goals)), 0u);
}

TEST(FieldRepair, DisconnectAndReconnectTwoRooms)
{
	// Two rooms joined by a one-cell door; the goal in the left room.
	const GridGeometry g(0.1, 0, 0, 41, 20);
	TraversabilityGrid open(g, 1e6, 0.5);
	for (int r = 0; r < 20; r++)
		if (r != 9) open.block(r, 20);
	GoalLayer goals(g);
	goals.addCell({3, 3}, 1);
	TraversabilityGrid closed = open;
	closed.block(9, 20);
	const CellRect door{9, 20, 10, 21};
	const CnnPlanner planner;
	const auto openField = planner.computeField(open, goals);
	ASSERT_TRUE(openField.reached({10, 35}));

	DiffusionField f = openField;
	auto st = planner.repairField(f, open, goals, closed, goals, &door, 1.0);
	EXPECT_FALSE(st.fullRecompute);
	EXPECT_FALSE(f.reached({10, 35}));
	EXPECT_GT(st.invalidatedCells, 19u * 20u - 1);  // the whole right room
	EXPECT_EQ(cellsDiffering(f, planner.computeField(closed, goals)), 0u);

	st = planner.repairField(f, closed, goals, open, goals, &door, 1.0);
	EXPECT_FALSE(st.fullRecompute);
	EXPECT_EQ(st.invalidatedCells, 0u);  // reconnecting only lowers costs
	EXPECT_EQ(cellsDiffering(f, openField), 0u);
}

TEST(FieldRepair, WorkLimitFallsBackWithTheSameField)
{
	// Closing the door changes the whole right room: over a 1 % limit.
	const GridGeometry g(0.1, 0, 0, 41, 20);
	TraversabilityGrid open(g, 1e6);
	for (int r = 0; r < 20; r++)
		if (r != 9) open.block(r, 20);
	TraversabilityGrid closed = open;
	closed.block(9, 20);
	GoalLayer goals(g);
	goals.addCell({3, 3}, 1);
	const CnnPlanner planner;
	DiffusionField f = planner.computeField(open, goals);
	const auto st =
	    planner.repairField(f, open, goals, closed, goals, nullptr, 0.01);
	EXPECT_TRUE(st.fullRecompute);
	EXPECT_NE(st.fallbackReason.find("work limit"), std::string::npos);
	EXPECT_EQ(cellsDiffering(f, planner.computeField(closed, goals)), 0u);
}

TEST(FieldRepair, EqualsTheJacobiReference)
{
	RepairProblem p = randomProblem(45, 38, 1e6, 8, 2);
	const CnnPlanner planner;
	DiffusionField f = planner.computeField(p.u, p.goals);
	const RepairProblem before = p;
	std::mt19937_64 rng(8);
	const CellRect r = applyChange(p, Change::AddObstacle, rng);
	planner.repairField(f, before.u, before.goals, p.u, p.goals, &r);
	CnnPlanner::TOptions o;
	o.schedule = CnnSchedule::Jacobi;
	EXPECT_EQ(cellsDiffering(f, CnnPlanner(o).computeField(p.u, p.goals)), 0u);
}

TEST(FieldRepair, BadInput)
{
	const RepairProblem p = randomProblem(20, 20, 1e6, 9, 1);
	const CnnPlanner planner;
	DiffusionField f = planner.computeField(p.u, p.goals);
	const auto ref = f;

	// Every goal cell blocked: EmptyGoalError as computeField, field kept.
	RepairProblem blocked = p;
	for (std::size_t i = 0; i < p.u.values().size(); i++)
		if (p.goals.isGoal(i)) blocked.u.values()[i] = p.u.L();
	EXPECT_THROW(
	    planner.repairField(f, p.u, p.goals, blocked.u, blocked.goals),
	    EmptyGoalError);
	EXPECT_EQ(f.x, ref.x);

	// A field of another grid.
	const RepairProblem other = randomProblem(21, 20, 1e6, 9, 1);
	EXPECT_THROW(
	    planner.repairField(f, other.u, other.goals, p.u, p.goals),
	    PlanningError);

	// A new grid of another size: a full recompute.
	const auto st = planner.repairField(f, p.u, p.goals, other.u, other.goals);
	EXPECT_TRUE(st.fullRecompute);
	EXPECT_EQ(
	    cellsDiffering(f, planner.computeField(other.u, other.goals)), 0u);
}

TEST(FieldRepair, OrderTooCoarseForLargeValuesFallsBack)
{
	const CnnPlanner planner;
	// L's rounding unit (~0.016 at 1e14) exceeds 1/64 of a 5 cm cell.
	{
		const GridGeometry g(0.05, 0, 0, 30, 20);
		TraversabilityGrid before(g, 1e14), after(g, 1e14);
		after.block(10, 10);
		GoalLayer goals(g);
		goals.addCell({2, 2}, 1);
		DiffusionField f = planner.computeField(before, goals);
		const auto st = planner.repairField(f, before, goals, after, goals);
		EXPECT_TRUE(st.fullRecompute);
		EXPECT_NE(st.fallbackReason.find("L is too large"), std::string::npos)
		    << st.fallbackReason;
		EXPECT_EQ(cellsDiffering(f, planner.computeField(after, goals)), 0u);
	}
	// Costs of ~1e9 per cell at 1 mm: after ~70 cells a value's rounding
	// unit exceeds 1/64 of a cell; the increase phase stops there.
	{
		const GridGeometry g(0.001, 0, 0, 300, 1);
		TraversabilityGrid before(g, 1e9, 0.999e9);
		GoalLayer goals(g);
		goals.addCell({0, 0}, 1);
		TraversabilityGrid after = before;
		after.setU(0, 5, 0.9995e9);
		DiffusionField f = planner.computeField(before, goals);
		const auto st = planner.repairField(
		    f, before, goals, after, goals, nullptr, kNoLimit);
		EXPECT_TRUE(st.fullRecompute);
		EXPECT_NE(st.fallbackReason.find("rounding unit"), std::string::npos)
		    << st.fallbackReason;
		EXPECT_EQ(cellsDiffering(f, planner.computeField(after, goals)), 0u);
	}
}

TEST(FieldRepair, BoxesInsertedIntoAnOfficeWithTheSafeProfile)
{
	// 3 x 3 rooms of 2 m with 1 m doors at 5 cm; u from the builder (safe
	// profile: C-space plus a cost ring); boxes of 0.3-1 m appear one by
	// one, then disappear in the same order.
	const int n = 120, room = 40;
	const GridGeometry g(0.05, 0, 0, n, n);
	std::vector<CellOccupancy> occ(g.cellCount(), CellOccupancy::Free);
	const auto fill = [&](int r0, int c0, int r1, int c1, CellOccupancy v)
	{
		for (int r = std::max(0, r0); r < std::min(n, r1); r++)
			for (int c = std::max(0, c0); c < std::min(n, c1); c++)
				occ[g.index(r, c)] = v;
	};
	for (int k = 0; k <= 3; k++)
	{
		fill(k * room - 1, 0, k * room + 1, n, CellOccupancy::Occupied);
		fill(0, k * room - 1, n, k * room + 1, CellOccupancy::Occupied);
	}
	for (int i = 0; i < 3; i++)
		for (int k = 1; k < 3; k++)
		{
			fill(
			    i * room + 10, k * room - 1, i * room + 30, k * room + 1,
			    CellOccupancy::Free);
			fill(
			    k * room - 1, i * room + 10, k * room + 1, i * room + 30,
			    CellOccupancy::Free);
		}
	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.2;
	const TraversabilityBuilder builder(o);
	GoalLayer goals(g);
	goals.addDisc(g.centerX(100), g.centerY(100), 0.1, 1);
	const CnnPlanner planner;
	auto u = builder.build(g, {}, occ, CostProfile::Safe);
	DiffusionField f = planner.computeField(u, goals);
	std::mt19937_64 rng(12);
	std::vector<std::vector<CellOccupancy>> history{occ};
	int repaired = 0;
	const auto step = [&](const std::vector<CellOccupancy>& next)
	{
		auto nu = builder.build(g, {}, next, CostProfile::Safe);
		CellRect changed;
		for (std::size_t i = 0; i < g.cellCount(); i++)
			if (nu.values()[i] != u.values()[i])
				changed.add(g.cellAt(i).row, g.cellAt(i).col);
		const auto st =
		    planner.repairField(f, u, goals, nu, goals, &changed, kNoLimit);
		repaired += !st.fullRecompute;
		u = nu;
		EXPECT_EQ(cellsDiffering(f, planner.computeField(u, goals)), 0u);
		expectSamePaths(f, planner.computeField(u, goals), {u, goals}, rng, 3);
	};
	for (int k = 0; k < 12; k++)
	{
		const int h = 6 + static_cast<int>(rng() % 15);
		const int w = 6 + static_cast<int>(rng() % 15);
		const int r = static_cast<int>(rng() % (n - h));
		const int c = static_cast<int>(rng() % (n - w));
		occ = history.back();
		fill(r, c, r + h, c + w, CellOccupancy::Occupied);
		occ[g.index(100, 100)] = CellOccupancy::Free;
		history.push_back(occ);
		step(occ);
	}
	for (int k = static_cast<int>(history.size()) - 2; k >= 0; k--)
		step(history[k]);
	EXPECT_EQ(repaired, 24);
}

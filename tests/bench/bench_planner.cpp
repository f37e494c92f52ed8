/* semnav: semantic navigation from tilting-laser sweeps */
// CNN path planner (paper sec. 3) against a binary-heap Dijkstra and MRPT's
// PlannerSimple2D on the same generated office map: 1000 x 1000 cells (50 m
// x 50 m at 5 cm), 10 x 10 rooms with 1 m doors, 400 boxes; robot radius
// 0.2 m, shortest profile; one goal cell in the far room. The synchronous
// (Jacobi) reference runs once on it and on a 250 x 250 map of the same
// kind. The incremental repair (CnnPlanner::repairField) of a 1 m x 1 m box
// added to (or removed from) the map runs against the full field in the
// same run, on 16 random free spots and on 8 spots along the start-goal
// path, unbounded (repairField) and bounded by the start (repairFieldFrom,
// then finishRepair, timed apart). SemanticPlanner replans after a 1 m x
// 1 m box is inserted into a SemanticMap of the same office
// (SemanticMap::insert of a sweep seeing it),
// on the current path or at random free spots, incrementally (cached u,
// goals and field, repaired) against from scratch (u, goals and field
// rebuilt), in the same run. Run with
//   bench_planner --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
// A summary (time ratios, path costs) is printed at the end.
#include <benchmark/benchmark.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/nav/planners/PlannerSimple2D.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/DijkstraPlanner.h>
#include <semnav/planning/SemanticPlanner.h>
#include <semnav/planning/TraversabilityBuilder.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numeric>
#include <random>

#include "OfficeGrid.h"
#include "SemanticReplanBench.h"

using namespace semnav;
using semnav::test::makeOffice;
using semnav::test::OfficeMap;
using semnav::test::Replan;

namespace
{
const OfficeMap& office1000()
{
	static const auto m = makeOffice(10, 100, 400);
	return *m;
}
const OfficeMap& office250()
{
	static const auto m = makeOffice(5, 50, 25);
	return *m;
}

/** Path costs and iteration counts reported in the summary. */
std::map<std::string, double> g_figures;
/** The SemanticPlanner replans' times and counts. */
test::ReplanRecord g_replan;

CnnPlanner cnn(CnnSchedule s, int threads)
{
	CnnPlanner::TOptions o;
	o.schedule = s;
	o.threads = threads;
	return CnnPlanner(o);
}

void runCnn(
    benchmark::State& st, const OfficeMap& m, CnnSchedule s, int threads,
    const std::string& name)
{
	const CnnPlanner p = cnn(s, threads);
	DiffusionField f;
	for (auto _ : st)
	{
		f = p.computeField(m.u, m.goals);
		benchmark::DoNotOptimize(f.x.data());
	}
	const auto path = CnnPlanner::extractPath(f, m.u, m.goals, m.start);
	if (s == CnnSchedule::Jacobi)
	{
		// The production field must be the same, bit for bit.
		const auto sweep =
		    cnn(CnnSchedule::Sweep, 2).computeField(m.u, m.goals);
		std::size_t differ = 0;
		for (std::size_t i = 0; i < f.x.size(); i++)
			differ += sweep.x[i] != f.x[i];
		st.counters["cells_differing_from_sweep"] = static_cast<double>(differ);
		g_figures[name + " cells differing from sweep"] =
		    static_cast<double>(differ);
	}
	st.counters["iterations"] = f.iterations;
	st.counters["row_updates"] = static_cast<double>(f.rowUpdates);
	st.counters["cost"] = path.cost;
	g_figures[name + " cost"] = path.cost;
	g_figures[name + " iterations"] = f.iterations;
}

void BM_CnnSweep_1000(benchmark::State& st)
{
	runCnn(st, office1000(), CnnSchedule::Sweep, 1, "BM_CnnSweep_1000");
}
void BM_CnnSweep2Threads_1000(benchmark::State& st)
{
	runCnn(st, office1000(), CnnSchedule::Sweep, 2, "BM_CnnSweep2Threads_1000");
}
/** The full field into a reused field (the reference of the repairs). */
void BM_CnnSweepInto_1000(benchmark::State& st)
{
	const auto& m = office1000();
	const CnnPlanner p = cnn(CnnSchedule::Sweep, 1);
	DiffusionField f = p.computeField(m.u, m.goals);
	for (auto _ : st)
	{
		p.computeFieldInto(m.u, m.goals, f);
		benchmark::DoNotOptimize(f.x.data());
	}
	st.counters["iterations"] = f.iterations;
}
void BM_CnnPlan_1000(benchmark::State& st)
{
	const auto& m = office1000();
	const CnnPlanner p = cnn(CnnSchedule::Sweep, 1);
	PlannedPath path;
	for (auto _ : st) path = p.plan(m.u, m.goals, m.start);
	st.counters["cost"] = path.cost;
}
void BM_Dijkstra_1000(benchmark::State& st)
{
	const auto& m = office1000();
	std::vector<double> V;
	for (auto _ : st)
	{
		V = DijkstraPlanner::costField(m.u, m.goals);
		benchmark::DoNotOptimize(V.data());
	}
	st.counters["cost"] = V[m.geometry.index(m.start)];
	g_figures["dijkstra cost"] = V[m.geometry.index(m.start)];
}
void BM_DijkstraToStart_1000(benchmark::State& st)
{
	const auto& m = office1000();
	PlannedPath path;
	for (auto _ : st) path = DijkstraPlanner::plan(m.u, m.goals, m.start);
	st.counters["cost"] = path.cost;
}
void BM_MrptPlannerSimple2D_1000(benchmark::State& st)
{
	// MRPT plans on the same C-space: blocked cells become occupied and its
	// own obstacle growing is off (robotRadius = 0).
	const auto& m = office1000();
	const auto& g = m.geometry;
	mrpt::maps::COccupancyGridMap2D grid;
	grid.setSize(g.originX, g.maxX(), g.originY, g.maxY(), g.resolution, 1.0f);
	if (static_cast<int>(grid.getSizeX()) != g.cols ||
	    static_cast<int>(grid.getSizeY()) != g.rows)
	{
		st.SkipWithError("MRPT grid size differs");
		return;
	}
	for (int r = 0; r < g.rows; r++)
		for (int c = 0; c < g.cols; c++)
			grid.setCell(c, r, m.u.blocked(r, c) ? 0.0f : 1.0f);
	mrpt::nav::PlannerSimple2D planner;
	planner.robotRadius = 0;
	planner.minStepInReturnedPath = 0;
	const mrpt::poses::CPose2D from(
	    g.centerX(m.start.col), g.centerY(m.start.row), 0);
	const mrpt::poses::CPose2D to(
	    g.centerX(m.goal.col), g.centerY(m.goal.row), 0);
	std::deque<mrpt::math::TPoint2D> path;
	bool notFound = true;
	for (auto _ : st) planner.computePath(grid, from, to, path, notFound);
	if (notFound)
	{
		st.SkipWithError("PlannerSimple2D found no path");
		return;
	}
	double len = 0, px = from.x(), py = from.y();
	bool collision = false;
	for (const auto& p : path)
	{
		len += std::hypot(p.x - px, p.y - py);
		px = p.x;
		py = p.y;
		const auto c = g.cellOf(p.x, p.y);
		collision = collision || !c || m.u.blocked(*c);
	}
	st.counters["cost"] = len;
	st.counters["collisions"] = collision ? 1 : 0;
	g_figures["mrpt cost"] = len;
}
void BM_CnnJacobi_1000(benchmark::State& st)
{
	runCnn(st, office1000(), CnnSchedule::Jacobi, 1, "BM_CnnJacobi_1000");
}
void BM_CnnJacobi_250(benchmark::State& st)
{
	runCnn(st, office250(), CnnSchedule::Jacobi, 1, "BM_CnnJacobi_250");
}
void BM_CnnJacobi2Threads_250(benchmark::State& st)
{
	runCnn(st, office250(), CnnSchedule::Jacobi, 2, "BM_CnnJacobi2Threads_250");
}
void BM_CnnSweep_250(benchmark::State& st)
{
	runCnn(st, office250(), CnnSchedule::Sweep, 1, "BM_CnnSweep_250");
}
void BM_Dijkstra_250(benchmark::State& st)
{
	const auto& m = office250();
	for (auto _ : st)
		benchmark::DoNotOptimize(DijkstraPlanner::costField(m.u, m.goals));
}
/** A 1 m x 1 m box on the office map: u with it, the changed rectangle
 * and the converged fields without and with it. */
struct BoxChange
{
	TraversabilityGrid u;
	CellRect changed;
	DiffusionField fieldWith;
	/** Cells whose value differs between the two fields. */
	std::size_t cellsChanging = 0;
	/** Where a robot driving the start-goal path stands when it senses
	 * the box: 3 m before it on the path (path spots; else the start). */
	CellIndex robot;
	/** Of these, the cells in the focus (inFocus) of the start, then of
	 * the robot, in the field with the box (added) and without it
	 * (removed). */
	std::size_t cellsChangingForStart[4] = {0, 0, 0, 0};
};

struct BoxChanges
{
	DiffusionField fieldWithout;
	std::vector<BoxChange> spots;
};

/** Whether cell i's cost to go in f plus its focus (PendingRepair::
 * kFocusWeight times its octile distance to s) is at most s's cost to go:
 * the cells a repair bounded by s must get exact (every best path). */
bool inFocus(const DiffusionField& f, std::size_t i, const CellIndex& s)
{
	const CellIndex c = f.geometry.cellAt(i);
	const int dr = std::abs(c.row - s.row), dc = std::abs(c.col - s.col);
	const int d = std::min(dr, dc);
	const double octile =
	    f.geometry.resolution * (std::sqrt(2.0) * d + std::max(dr, dc) - d);
	return f.costToGo(c) + PendingRepair::kFocusWeight * octile <=
	       f.costToGo(s);
}

/** Boxes of 20 x 20 cells (1 m^2 at 5 cm) whose footprint is free in the
 * occupancy: `n` random spots, or centred on `n` cells spread along the
 * start-goal path (spots touching a wall, e.g. in a door, are skipped). */
BoxChanges makeBoxChanges(const OfficeMap& m, int n, bool onPath)
{
	const auto& g = m.geometry;
	const CnnPlanner planner = cnn(CnnSchedule::Sweep, 2);
	BoxChanges b;
	b.fieldWithout = planner.computeField(m.u, m.goals);
	std::vector<std::pair<CellIndex, CellIndex>> centres;  // and robot
	std::mt19937_64 rng(77);
	if (onPath)
	{
		const auto path =
		    CnnPlanner::extractPath(b.fieldWithout, m.u, m.goals, m.start);
		const std::size_t ahead = 60;  // 3 m
		for (int k = 1; k < 4 * n; k++)
		{
			const std::size_t at = path.cells.size() * k / (4 * n);
			centres.emplace_back(
			    path.cells[at], path.cells[at >= ahead ? at - ahead : 0]);
		}
	}
	else
		for (int k = 0; k < 100 * n; k++)
			centres.emplace_back(
			    CellIndex{
			        static_cast<int>(rng() % (g.rows - 40)) + 20,
			        static_cast<int>(rng() % (g.cols - 40)) + 20},
			    m.start);
	const int side = 20;
	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.2;
	const TraversabilityBuilder builder(o);
	for (const auto& [c, robot] : centres)
	{
		if (static_cast<int>(b.spots.size()) == n) break;
		const int r0 = c.row - side / 2, c0 = c.col - side / 2;
		bool free = true;
		for (int r = r0 - 2; r < r0 + side + 2; r++)
			for (int cc = c0 - 2; cc < c0 + side + 2; cc++)
				free =
				    free && m.occupancy[g.index(r, cc)] == CellOccupancy::Free;
		if (!free) continue;
		auto occupancy = m.occupancy;
		for (int r = r0; r < r0 + side; r++)
			for (int cc = c0; cc < c0 + side; cc++)
				occupancy[g.index(r, cc)] = CellOccupancy::Occupied;
		BoxChange s;
		s.u = builder.build(g, {}, occupancy, CostProfile::Shortest);
		for (std::size_t i = 0; i < g.cellCount(); i++)
			if (s.u.values()[i] != m.u.values()[i])
			{
				const auto ci = g.cellAt(i);
				s.changed.add(ci.row, ci.col);
			}
		if (s.u.blocked(m.start) || s.u.blocked(robot)) continue;
		s.robot = robot;
		s.fieldWith = planner.computeField(s.u, m.goals);
		for (std::size_t i = 0; i < g.cellCount(); i++)
		{
			const bool changes = s.fieldWith.x[i] != b.fieldWithout.x[i];
			s.cellsChanging += changes;
			for (int k = 0; k < 2; k++)
			{
				const CellIndex& from = k ? robot : m.start;
				s.cellsChangingForStart[2 * k] +=
				    changes && inFocus(s.fieldWith, i, from);
				s.cellsChangingForStart[2 * k + 1] +=
				    changes && inFocus(b.fieldWithout, i, from);
			}
		}
		b.spots.push_back(std::move(s));
	}
	return b;
}

const BoxChanges& randomBoxes()
{
	static const BoxChanges b = makeBoxChanges(office1000(), 16, false);
	return b;
}
const BoxChanges& pathBoxes()
{
	static const BoxChanges b = makeBoxChanges(office1000(), 8, true);
	return b;
}

/** Per benchmark, per spot: the repair times (ms) of every iteration;
 * for the start-bounded repairs also those of finishing the pending
 * work (under the name + " finish"). */
std::map<std::string, std::vector<std::vector<double>>> g_spotMs;

double secondsSince(std::chrono::steady_clock::time_point t0)
{
	return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
	    .count();
}

/** Cells in the start's focus in `ref` (inFocus) that differ in f, and
 * whether the paths from the start differ (a box may cut the start off
 * the goal: then only the start's value is compared). */
std::pair<std::size_t, bool> differencesForStart(
    const DiffusionField& f, const DiffusionField& ref,
    const TraversabilityGrid& u, const GoalLayer& goals, const CellIndex& s)
{
	if (!ref.reached(s)) return {f.reached(s), false};
	std::size_t n = 0;
	for (std::size_t i = 0; i < f.x.size(); i++)
		n += f.x[i] != ref.x[i] && inFocus(ref, i, s);
	const auto a = CnnPlanner::extractPath(f, u, goals, s);
	const auto b = CnnPlanner::extractPath(ref, u, goals, s);
	return {n, a.cells != b.cells || a.cost != b.cost};
}

/** Repairs the field after adding (or removing) the box of spot
 * k = iteration % spots, the field copy outside the timing; every spot's
 * result is checked bit for bit against its full recompute. `bounded`:
 * the repair bounded by the start (by the robot 3 m before the box when
 * `fromRobot`; repairFieldFrom), checked on the cells of its focus and on
 * its path, then finished (finishRepair, timed apart) and checked on the
 * whole field. */
void runRepair(
    benchmark::State& st, const BoxChanges& b, bool add, bool useRect,
    const std::string& name, bool bounded = false, bool fromRobot = false)
{
	const auto& m = office1000();
	const CnnPlanner p = cnn(CnnSchedule::Sweep, 1);
	auto& spotMs = g_spotMs[name];
	auto& finishMs = g_spotMs[name + " finish"];
	spotMs.resize(b.spots.size());
	finishMs.resize(bounded ? b.spots.size() : 0);
	std::size_t k = 0, differ = 0, fallbacks = 0, overInvalidated = 0;
	std::size_t differAbove = 0, pathsDiffer = 0;
	double invalidated = 0, raised = 0, popped = 0;
	DiffusionField f;
	PendingRepair pending;
	for (auto _ : st)
	{
		const std::size_t spot = k++ % b.spots.size();
		const BoxChange& s = b.spots[spot];
		f = add ? b.fieldWithout : s.fieldWith;  // reuses f's storage
		const auto& oldU = add ? m.u : s.u;
		const auto& newU = add ? s.u : m.u;
		const auto& ref = add ? s.fieldWith : b.fieldWithout;
		const CellRect* rect = useRect ? &s.changed : nullptr;
		const CellIndex& start = fromRobot ? s.robot : m.start;
		const auto t0 = std::chrono::steady_clock::now();
		const auto stats =
		    bounded ? p.repairFieldFrom(
		                  start, f, oldU, m.goals, newU, m.goals, pending, rect)
		            : p.repairField(f, oldU, m.goals, newU, m.goals, rect);
		const double sec = secondsSince(t0);
		st.SetIterationTime(sec);
		spotMs[spot].push_back(1e3 * sec);
		if (bounded)
		{
			if (k <= b.spots.size())
			{
				const auto [n, path] =
				    differencesForStart(f, ref, newU, m.goals, start);
				differAbove += n;
				pathsDiffer += path;
			}
			const auto t1 = std::chrono::steady_clock::now();
			p.finishRepair(f, pending);
			finishMs[spot].push_back(1e3 * secondsSince(t1));
		}
		if (k <= b.spots.size())
			for (std::size_t i = 0; i < f.x.size(); i++)
				differ += f.x[i] != ref.x[i];
		fallbacks += stats.fullRecompute;
		// Phase 1 invalidates exactly the cells whose value changes.
		overInvalidated += add && !bounded && !stats.fullRecompute &&
		                   stats.invalidatedCells != s.cellsChanging;
		invalidated += static_cast<double>(stats.invalidatedCells);
		raised += static_cast<double>(stats.raisedCells);
		popped += static_cast<double>(stats.poppedCells);
	}
	const double n = static_cast<double>(std::max<std::size_t>(k, 1));
	st.counters["spots"] = static_cast<double>(b.spots.size());
	st.counters["invalidated"] = invalidated / n;
	st.counters["raised"] = raised / n;
	st.counters["popped"] = popped / n;
	st.counters["full_recomputes"] = static_cast<double>(fallbacks);
	st.counters["cells_differing_from_full"] = static_cast<double>(differ);
	g_figures[name + " cells differing from full"] =
	    static_cast<double>(differ);
	g_figures[name + " repairs invalidating other cells than those changing"] =
	    static_cast<double>(overInvalidated);
	g_figures[name + " full recomputes / iterations"] =
	    static_cast<double>(fallbacks) / n;
	if (!bounded) return;
	g_figures[name + " cells in the start's focus differing before finishing"] =
	    static_cast<double>(differAbove);
	g_figures[name + " paths from the start differing before finishing"] =
	    static_cast<double>(pathsDiffer);
}

void BM_CnnRepairBoxAdded_1000(benchmark::State& st)
{
	runRepair(st, randomBoxes(), true, true, "BM_CnnRepairBoxAdded_1000");
}
void BM_CnnRepairBoxRemoved_1000(benchmark::State& st)
{
	runRepair(st, randomBoxes(), false, true, "BM_CnnRepairBoxRemoved_1000");
}
void BM_CnnRepairBoxAddedNoRect_1000(benchmark::State& st)
{
	runRepair(
	    st, randomBoxes(), true, false, "BM_CnnRepairBoxAddedNoRect_1000");
}
void BM_CnnRepairBoxOnPathAdded_1000(benchmark::State& st)
{
	runRepair(st, pathBoxes(), true, true, "BM_CnnRepairBoxOnPathAdded_1000");
}
void BM_CnnRepairBoxOnPathRemoved_1000(benchmark::State& st)
{
	runRepair(
	    st, pathBoxes(), false, true, "BM_CnnRepairBoxOnPathRemoved_1000");
}

void BM_CnnRepairBoxAddedBounded_1000(benchmark::State& st)
{
	runRepair(
	    st, randomBoxes(), true, true, "BM_CnnRepairBoxAddedBounded_1000",
	    true);
}
void BM_CnnRepairBoxRemovedBounded_1000(benchmark::State& st)
{
	runRepair(
	    st, randomBoxes(), false, true, "BM_CnnRepairBoxRemovedBounded_1000",
	    true);
}
void BM_CnnRepairBoxAheadAddedBounded_1000(benchmark::State& st)
{
	runRepair(
	    st, pathBoxes(), true, true, "BM_CnnRepairBoxAheadAddedBounded_1000",
	    true, true);
}
void BM_CnnRepairBoxAheadRemovedBounded_1000(benchmark::State& st)
{
	runRepair(
	    st, pathBoxes(), false, true, "BM_CnnRepairBoxAheadRemovedBounded_1000",
	    true, true);
}
void BM_CnnRepairBoxOnPathAddedBounded_1000(benchmark::State& st)
{
	runRepair(
	    st, pathBoxes(), true, true, "BM_CnnRepairBoxOnPathAddedBounded_1000",
	    true);
}
void BM_CnnRepairBoxOnPathRemovedBounded_1000(benchmark::State& st)
{
	runRepair(
	    st, pathBoxes(), false, true,
	    "BM_CnnRepairBoxOnPathRemovedBounded_1000", true);
}

void BM_TraversabilityShortest_1000(benchmark::State& st)
{
	const auto& m = office1000();
	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.2;
	const TraversabilityBuilder b(o);
	for (auto _ : st)
		benchmark::DoNotOptimize(
		    b.build(m.geometry, {}, m.occupancy, CostProfile::Shortest));
}
void BM_TraversabilitySafe_1000(benchmark::State& st)
{
	const auto& m = office1000();
	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.2;
	const TraversabilityBuilder b(o);
	for (auto _ : st)
		benchmark::DoNotOptimize(
		    b.build(m.geometry, {}, m.occupancy, CostProfile::Safe));
}

/** Semantic replans: 12 boxes inserted per run, timed by hand. */
void semanticReplanSettings(benchmark::internal::Benchmark* b)
{
	b->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(12);
}

/** Repairs: 64 iterations (4 or 8 per spot), timed by hand. */
void repairSettings(benchmark::internal::Benchmark* b)
{
	b->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(64);
}

BENCHMARK(BM_CnnSweep_1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CnnSweep2Threads_1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CnnSweepInto_1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CnnPlan_1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Dijkstra_1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DijkstraToStart_1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MrptPlannerSimple2D_1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_CnnJacobi_1000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_CnnJacobi_250)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CnnJacobi2Threads_250)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CnnSweep_250)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Dijkstra_250)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CnnRepairBoxAdded_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxRemoved_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxAddedNoRect_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxOnPathAdded_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxOnPathRemoved_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxAddedBounded_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxRemovedBounded_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxOnPathAddedBounded_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxOnPathRemovedBounded_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxAheadAddedBounded_1000)->Apply(repairSettings);
BENCHMARK(BM_CnnRepairBoxAheadRemovedBounded_1000)->Apply(repairSettings);
BENCHMARK(BM_TraversabilityShortest_1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TraversabilitySafe_1000)->Unit(benchmark::kMillisecond);

/** Console output plus the real time per benchmark (median when
 * aggregates are reported) for the summary. */
class SummaryReporter : public benchmark::ConsoleReporter
{
public:
	std::map<std::string, double> ms;
	void ReportRuns(const std::vector<Run>& runs) override
	{
		ConsoleReporter::ReportRuns(runs);
		for (const auto& r : runs)
		{
			if (r.error_occurred) continue;
			const double t = r.GetAdjustedRealTime() *
			                 (r.time_unit == benchmark::kMillisecond   ? 1.0
			                  : r.time_unit == benchmark::kMicrosecond ? 1e-3
			                  : r.time_unit == benchmark::kNanosecond  ? 1e-6
			                                                           : 1e3);
			const std::string name = r.run_name.function_name;
			if (r.run_type == Run::RT_Aggregate)
			{
				if (r.aggregate_name == "median") ms[name] = t;
			}
			else if (!medianSeen(name))
				ms[name] = t;
		}
	}

private:
	bool medianSeen(const std::string&) const { return false; }
};

void printRatio(
    const SummaryReporter& r, const char* what, const std::string& a,
    const std::string& b)
{
	const auto ia = r.ms.find(a), ib = r.ms.find(b);
	if (ia == r.ms.end() || ib == r.ms.end()) return;
	std::printf(
	    "  %-44s %9.2f ms / %9.2f ms = %.3f\n", what, ia->second, ib->second,
	    ia->second / ib->second);
}
/** Median over the spots of each spot's median repair time, its 75th
 * percentile and maximum, and the full field's time over the median;
 * the cells changing value: all, or (forStart 0 added, 1 removed; 2, 3
 * the same from the robot) those in the start's focus. */
void printRepairs(
    const char* what, const std::string& name, const BoxChanges& (*spots)(),
    double fullMs, int forStart)
{
	const auto it = g_spotMs.find(name);
	if (it == g_spotMs.end()) return;
	const BoxChanges& b = spots();
	const auto median = [](std::vector<double> v)
	{
		std::sort(v.begin(), v.end());
		return v.empty() ? 0.0
		                 : 0.5 * (v[(v.size() - 1) / 2] + v[v.size() / 2]);
	};
	std::vector<double> perSpot, changing;
	for (const auto& t : it->second) perSpot.push_back(median(t));
	for (const auto& s : b.spots)
		changing.push_back(static_cast<double>(
		    forStart < 0 ? s.cellsChanging
		                 : s.cellsChangingForStart[forStart]));
	std::sort(perSpot.begin(), perSpot.end());
	const double med = median(perSpot);
	std::printf(
	    "    %-34s median %7.3f ms, p75 %7.3f, max %7.2f; full / median = "
	    "%6.1f (median %.0f cells change value%s)\n",
	    what, med, perSpot[(perSpot.size() * 3) / 4], perSpot.back(),
	    fullMs / med, median(changing),
	    forStart < 0   ? ""
	    : forStart < 2 ? " in the start's focus"
	                   : " in the robot's focus");
}
}  // namespace

int main(int argc, char** argv)
{
	benchmark::Initialize(&argc, argv);
	if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
	const auto& m = office1000();
	std::printf(
	    "office map %d x %d cells (%.0f m x %.0f m), %zu boxes, %.1f %% of "
	    "cells blocked (C-space, robot radius 0.2 m)\n",
	    m.geometry.cols, m.geometry.rows, m.geometry.maxX(), m.geometry.maxY(),
	    m.boxes, 100.0 * m.u.blockedCount() / m.geometry.cellCount());
	// SemanticPlanner replans: where the boxes go, how it replans, the goal.
	const struct
	{
		const char* name;
		bool onPath;
		Replan mode;
		bool toLabel;
	} replans[] = {
	    {"BM_SemanticReplanOnPathScratch_1000", true, Replan::Scratch, false},
	    {"BM_SemanticReplanOnPathIncremental_1000", true, Replan::Incremental,
	     false},
	    {"BM_SemanticReplanOnPathShared_1000", true, Replan::Shared, false},
	    {"BM_SemanticReplanRandomScratch_1000", false, Replan::Scratch, false},
	    {"BM_SemanticReplanRandomIncremental_1000", false, Replan::Incremental,
	     false},
	    {"BM_SemanticReplanRandomShared_1000", false, Replan::Shared, false},
	    {"BM_SemanticReplanRandomLabelScratch_1000", false, Replan::Scratch,
	     true},
	    {"BM_SemanticReplanRandomLabelShared_1000", false, Replan::Shared,
	     true}};
	for (const auto& r : replans)
		benchmark::RegisterBenchmark(
		    r.name,
		    [r](benchmark::State& st)
		    {
			    test::runSemanticReplan(
			        st, office1000(), r.onPath, r.mode, r.toLabel, r.name,
			        g_replan);
		    })
		    ->Apply(semanticReplanSettings);
	SummaryReporter rep;
	benchmark::RunSpecifiedBenchmarks(&rep);
	std::printf("\nsummary (median real time when repetitions are used):\n");
	printRatio(
	    rep, "CNN sweep 1 thread / Dijkstra field (1000)", "BM_CnnSweep_1000",
	    "BM_Dijkstra_1000");
	printRatio(
	    rep, "CNN sweep 2 threads / Dijkstra field (1000)",
	    "BM_CnnSweep2Threads_1000", "BM_Dijkstra_1000");
	printRatio(
	    rep, "CNN sweep 1 thread / Dijkstra to start (1000)",
	    "BM_CnnSweep_1000", "BM_DijkstraToStart_1000");
	printRatio(
	    rep, "CNN plan 1 thread / MRPT PlannerSimple2D (1000)",
	    "BM_CnnPlan_1000", "BM_MrptPlannerSimple2D_1000");
	printRatio(
	    rep, "CNN Jacobi 1 thread / CNN sweep (1000)", "BM_CnnJacobi_1000",
	    "BM_CnnSweep_1000");
	printRatio(
	    rep, "CNN Jacobi 1 thread / CNN sweep (250)", "BM_CnnJacobi_250",
	    "BM_CnnSweep_250");
	printRatio(
	    rep, "CNN Jacobi 1 thread / Dijkstra field (250)", "BM_CnnJacobi_250",
	    "BM_Dijkstra_250");
	const auto full = rep.ms.find("BM_CnnSweepInto_1000");
	if (full != rep.ms.end())
	{
		std::printf(
		    "  repairs of a 1 m x 1 m box: per spot the median time, then over "
		    "the spots (full field into a reused field, 1 thread: %.2f ms):\n",
		    full->second);
		const struct
		{
			const char* what;
			const char* name;
			const BoxChanges& (*spots)();
			int forStart = -1;
		} repairs[] = {
		    {"box added, 16 random spots", "BM_CnnRepairBoxAdded_1000",
		     randomBoxes},
		    {"box removed, 16 random spots", "BM_CnnRepairBoxRemoved_1000",
		     randomBoxes},
		    {"box added, no rectangle given", "BM_CnnRepairBoxAddedNoRect_1000",
		     randomBoxes},
		    {"box added, 8 spots on the path",
		     "BM_CnnRepairBoxOnPathAdded_1000", pathBoxes},
		    {"box removed, 8 spots on the path",
		     "BM_CnnRepairBoxOnPathRemoved_1000", pathBoxes},
		    {"added, random spots, start-bounded",
		     "BM_CnnRepairBoxAddedBounded_1000", randomBoxes, 0},
		    {"  then finishing the pending work",
		     "BM_CnnRepairBoxAddedBounded_1000 finish", randomBoxes},
		    {"removed, random spots, start-bounded",
		     "BM_CnnRepairBoxRemovedBounded_1000", randomBoxes, 1},
		    {"  then finishing the pending work",
		     "BM_CnnRepairBoxRemovedBounded_1000 finish", randomBoxes},
		    {"added, on the path, start-bounded",
		     "BM_CnnRepairBoxOnPathAddedBounded_1000", pathBoxes, 0},
		    {"  then finishing the pending work",
		     "BM_CnnRepairBoxOnPathAddedBounded_1000 finish", pathBoxes},
		    {"removed, on the path, start-bounded",
		     "BM_CnnRepairBoxOnPathRemovedBounded_1000", pathBoxes, 1},
		    {"  then finishing the pending work",
		     "BM_CnnRepairBoxOnPathRemovedBounded_1000 finish", pathBoxes},
		    {"added, 3 m ahead, robot-bounded",
		     "BM_CnnRepairBoxAheadAddedBounded_1000", pathBoxes, 2},
		    {"  then finishing the pending work",
		     "BM_CnnRepairBoxAheadAddedBounded_1000 finish", pathBoxes},
		    {"removed, 3 m ahead, robot-bounded",
		     "BM_CnnRepairBoxAheadRemovedBounded_1000", pathBoxes, 3},
		    {"  then finishing the pending work",
		     "BM_CnnRepairBoxAheadRemovedBounded_1000 finish", pathBoxes}};
		for (const auto& r : repairs)
			printRepairs(r.what, r.name, r.spots, full->second, r.forStart);
	}
	for (const char* where : {"OnPath", "Random", "RandomLabel"})
		for (const char* how : {"Incremental", "Shared"})
			printRatio(
			    rep,
			    (std::string("SemanticPlanner ") + where + ": scratch / " + how)
			        .c_str(),
			    std::string("BM_SemanticReplan") + where + "Scratch_1000",
			    std::string("BM_SemanticReplan") + where + how + "_1000");
	const auto median = [](std::vector<double> t)
	{
		std::sort(t.begin(), t.end());
		return t.empty() ? 0.0
		                 : 0.5 * (t[(t.size() - 1) / 2] + t[t.size() / 2]);
	};
	for (const auto& [name, v] : g_replan.replanMs)
		std::printf(
		    "  %-42s replan median %6.2f ms, planner's own part %6.2f ms\n",
		    name.c_str(), median(v), median(g_replan.refreshMs[name]));
	g_figures.insert(g_replan.figures.begin(), g_replan.figures.end());
	for (const auto& [k, v] : g_figures)
		std::printf("  %-50s %.6f\n", k.c_str(), v);
	const auto c = g_figures.find("BM_CnnSweep_1000 cost");
	const auto d = g_figures.find("mrpt cost");
	if (c != g_figures.end() && d != g_figures.end())
		std::printf(
		    "  MRPT path length - CNN path cost: %.6f m (%+.4f %%)\n",
		    d->second - c->second, 100.0 * (d->second - c->second) / c->second);
	benchmark::Shutdown();
	return 0;
}

/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/common/ParallelFor.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/PlanningErrors.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>

#include "DiffusionKernels.h"
#include "FieldRepair.h"

namespace semnav
{
using detail::kInf;

CnnSchedule cnnScheduleFromName(const std::string& name)
{
	if (name == "sweep") return CnnSchedule::Sweep;
	if (name == "jacobi") return CnnSchedule::Jacobi;
	throw PlanningError(
	    "unknown CNN schedule '" + name + "' (known: sweep, jacobi)");
}

const char* cnnScheduleName(CnnSchedule s)
{
	return s == CnnSchedule::Jacobi ? "jacobi" : "sweep";
}

namespace
{
using O = CnnPlanner::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .choice(
	            "schedule", &O::schedule,
	            {{CnnSchedule::Sweep, "sweep"},
	             {CnnSchedule::Jacobi, "jacobi"}},
	            "Diffusion update: sweep (in-place raster passes) | "
	            "jacobi (eq. (10), reference).")
	        .integer(
	            "threads", &O::threads, 0, 1024,
	            "Threads (bands of the grid); 0 = all cores.")
	        .integer(
	            "max_iterations", &O::maxIterations, 0, 1000000000,
	            "Passes or updates before giving up; 0 = no limit.");
	return t;
}
}  // namespace

const std::vector<std::string>& CnnPlanner::TOptions::knownKeys()
{
	static const std::vector<std::string> keys = optionTable().keys();
	return keys;
}

SEMNAV_OPTIONS_FROM_TABLE(CnnPlanner::TOptions, optionTable())

CnnPlanner::CnnPlanner() : CnnPlanner(TOptions()) {}

CnnPlanner::CnnPlanner(const TOptions& options)
    : mrpt::system::COutputLogger("CnnPlanner"), m_options(options)
{
}

namespace
{
std::string cellText(const GridGeometry& g, const CellIndex& c)
{
	char buf[160];
	std::snprintf(
	    buf, sizeof(buf), "(%.3f, %.3f) [row %d, col %d]", g.centerX(c.col),
	    g.centerY(c.row), c.row, c.col);
	return buf;
}

void checkSameGeometry(const GridGeometry& a, const GridGeometry& b)
{
	if (a.rows != b.rows || a.cols != b.cols || a.resolution != b.resolution ||
	    a.originX != b.originX || a.originY != b.originY)
		throw PlanningError(
		    "goal layer and traversability layer have different grids");
}

std::size_t traversableGoals(const TraversabilityGrid& u, const GoalLayer& g)
{
	std::size_t n = 0;
	for (std::size_t i = 0; i < u.values().size(); i++)
		if (g.isGoal(i) && !u.blocked(i)) n++;
	return n;
}

double msSince(std::chrono::steady_clock::time_point t0)
{
	return std::chrono::duration<double, std::milli>(
	           std::chrono::steady_clock::now() - t0)
	    .count();
}

void throwEmptyGoals(const GoalLayer& goals)
{
	throw EmptyGoalError(
	    goals.count() == 0
	        ? std::string("the goal set is empty")
	        : "the goal set is empty: all " + std::to_string(goals.count()) +
	              " goal cells are blocked (obstacle or within the robot "
	              "radius)");
}

}  // namespace

CellIndex CnnPlanner::startCell(const GridGeometry& g, double x, double y)
{
	const auto c = g.cellOf(x, y);
	if (!c)
	{
		char buf[200];
		std::snprintf(
		    buf, sizeof(buf),
		    "start (%.3f, %.3f) is outside the map [%.3f, %.3f] x [%.3f, "
		    "%.3f]",
		    x, y, g.originX, g.maxX(), g.originY, g.maxY());
		throw StartOutsideMapError(buf);
	}
	return *c;
}

void CnnPlanner::checkInputs(
    const TraversabilityGrid& u, const GoalLayer& goals, const CellIndex& start)
{
	checkSameGeometry(u.geometry(), goals.geometry());
	checkStart(u, start);
	if (traversableGoals(u, goals) == 0) throwEmptyGoals(goals);
}

void CnnPlanner::checkStart(const TraversabilityGrid& u, const CellIndex& start)
{
	const auto& g = u.geometry();
	if (!g.contains(start))
		throw StartOutsideMapError(
		    "start cell [row " + std::to_string(start.row) + ", col " +
		    std::to_string(start.col) + "] is outside the " +
		    std::to_string(g.cols) + " x " + std::to_string(g.rows) + " grid");
	if (u.blocked(start))
		throw StartBlockedError(
		    "start " + cellText(g, start) +
		    " is blocked (obstacle or within the robot radius of one)");
}

DiffusionField CnnPlanner::computeField(
    const TraversabilityGrid& u, const GoalLayer& goals) const
{
	DiffusionField f;
	computeFieldInto(u, goals, f);
	return f;
}

void CnnPlanner::computeFieldInto(
    const TraversabilityGrid& u, const GoalLayer& goals,
    DiffusionField& f) const
{
	const auto& g = u.geometry();
	checkSameGeometry(g, goals.geometry());
	const auto t0 = std::chrono::steady_clock::now();
	f.geometry = g;
	f.L = u.L();
	f.rowUpdates = 0;
	if (detail::initialField(u, goals, f.x) == 0) throwEmptyGoals(goals);
	const auto ue = detail::effectiveU(u);
	const int threads = resolveThreads(m_options.threads);
	f.iterations =
	    m_options.schedule == CnnSchedule::Jacobi
	        ? detail::diffuseJacobi(
	              g, ue, f.x, m_options.maxIterations, threads)
	        : detail::diffuseSweep(
	              g, ue, f.x, m_options.maxIterations, threads, f.rowUpdates);
	if (f.iterations < 0)
		throw NotConvergedError(
		    std::string("CNN diffusion (") +
		    cnnScheduleName(m_options.schedule) +
		    ") did not converge within max_iterations = " +
		    std::to_string(m_options.maxIterations));
	f.milliseconds = msSince(t0);
	MRPT_LOG_DEBUG_FMT(
	    "diffusion (%s): %d iterations, %.1f ms",
	    cnnScheduleName(m_options.schedule), f.iterations, f.milliseconds);
}

FieldRepairStats CnnPlanner::repairField(
    DiffusionField& field, const TraversabilityGrid& oldU,
    const GoalLayer& oldGoals, const TraversabilityGrid& newU,
    const GoalLayer& newGoals, const CellRect* changed,
    double maxWorkFraction) const
{
	return repair(
	    field, oldU, oldGoals, newU, newGoals, changed, maxWorkFraction,
	    nullptr, nullptr);
}

FieldRepairStats CnnPlanner::repairFieldFrom(
    const CellIndex& start, DiffusionField& field,
    const TraversabilityGrid& oldU, const GoalLayer& oldGoals,
    const TraversabilityGrid& newU, const GoalLayer& newGoals,
    PendingRepair& pending, const CellRect* changed,
    double maxWorkFraction) const
{
	if (!pending.empty())
		throw PlanningError(
		    "field repair: the previous repair's work is still pending "
		    "(finishRepair first)");
	pending.clear();
	return repair(
	    field, oldU, oldGoals, newU, newGoals, changed, maxWorkFraction, &start,
	    &pending);
}

FieldRepairStats CnnPlanner::repair(
    DiffusionField& field, const TraversabilityGrid& oldU,
    const GoalLayer& oldGoals, const TraversabilityGrid& newU,
    const GoalLayer& newGoals, const CellRect* changed, double maxWorkFraction,
    const CellIndex* start, PendingRepair* pending) const
{
	const auto t0 = std::chrono::steady_clock::now();
	const auto& g = newU.geometry();
	checkSameGeometry(g, newGoals.geometry());
	checkSameGeometry(oldU.geometry(), oldGoals.geometry());
	if (!(field.geometry == oldU.geometry()) || field.L != oldU.L() ||
	    field.x.size() != oldU.geometry().cellCount())
		throw PlanningError(
		    "field repair: the field was not computed on the old "
		    "traversability grid (geometry or L differ)");
	FieldRepairStats stats;
	const auto recompute = [&](const std::string& why)
	{
		computeFieldInto(newU, newGoals, field);
		stats.fullRecompute = true;
		stats.fallbackReason = why;
		stats.milliseconds = msSince(t0);
		MRPT_LOG_DEBUG_FMT("field repair: full recompute (%s)", why.c_str());
		return stats;
	};
	if (!(oldU.geometry() == g) || oldU.L() != newU.L())
		return recompute("the grid's geometry or L changed");
	if (!detail::FieldRepairer::applicable(g, newU.L()))
		return recompute(
		    "L is too large for the resolution (its rounding unit exceeds "
		    "1/64 of a cell) or the grid exceeds 2^32 cells");

	// A start the field cannot serve bounds nothing: the whole field.
	const bool bounded = start && g.contains(*start) && !newU.blocked(*start);
	auto repairer = std::make_unique<detail::FieldRepairer>(
	    newU, newGoals, bounded ? start : nullptr);
	repairer->collectChanges(
	    changed ? *changed : CellRect::all(g), oldU, oldGoals);
	stats.changedCells = repairer->changedCount();
	if (repairer->lostSources() > 0 && traversableGoals(newU, newGoals) == 0)
		throwEmptyGoals(newGoals);
	if (oldGoals.count() > 0 &&
	    repairer->removedGoalCells() == oldGoals.count())
		return recompute("every goal cell was removed (the goal moved)");
	const double limit =
	    std::max(0.0, maxWorkFraction) * static_cast<double>(g.cellCount());
	if (static_cast<double>(stats.changedCells) > limit)
		return recompute(
		    std::to_string(stats.changedCells) +
		    " changed cells, over the work limit");
	const auto workLimit = limit >= static_cast<double>(SIZE_MAX)
	                           ? SIZE_MAX
	                           : static_cast<std::size_t>(limit);
	repairer->seed(field.x);
	if (const char* stopped = repairer->run(field.x, workLimit, bounded, stats))
		return recompute(stopped);
	if (pending && !repairer->done())
	{
		pending->m_repairer = std::move(repairer);
		pending->m_u = &newU;
		pending->m_goals = &newGoals;
		pending->m_workLimit = workLimit;
	}
	field.iterations = 0;
	field.rowUpdates = 0;
	field.milliseconds = stats.milliseconds = msSince(t0);
	MRPT_LOG_DEBUG_FMT(
	    "field repair: %zu changed, %zu invalidated, %zu raised, %.2f ms%s",
	    stats.changedCells, stats.invalidatedCells, stats.raisedCells,
	    stats.milliseconds, pending && !pending->empty() ? " (bounded)" : "");
	return stats;
}

FieldRepairStats CnnPlanner::finishRepair(
    DiffusionField& field, PendingRepair& pending, const CellIndex* start) const
{
	FieldRepairStats stats;
	if (pending.empty()) return stats;
	const auto t0 = std::chrono::steady_clock::now();
	const auto& g = pending.m_u->geometry();
	if (!(field.geometry == g) || field.x.size() != g.cellCount())
		throw PlanningError(
		    "field repair: the field does not match the pending repair's grid");
	// The order is focused on the repair's start: another start finishes
	// all of it.
	const bool bounded = start && *start == pending.m_repairer->start();
	if (const char* stopped = pending.m_repairer->run(
	        field.x, pending.m_workLimit, bounded, stats))
	{
		const TraversabilityGrid& u = *pending.m_u;
		const GoalLayer& goals = *pending.m_goals;
		pending.clear();
		computeFieldInto(u, goals, field);
		stats.fullRecompute = true;
		stats.fallbackReason = stopped;
	}
	else if (pending.m_repairer->done())
		pending.clear();
	field.milliseconds = stats.milliseconds = msSince(t0);
	return stats;
}

PlannedPath CnnPlanner::extractPath(
    const DiffusionField& field, const TraversabilityGrid& u,
    const GoalLayer& goals, const CellIndex& start)
{
	checkInputs(u, goals, start);
	return tracePath(field, u, goals, start);
}

PlannedPath CnnPlanner::tracePath(
    const DiffusionField& field, const TraversabilityGrid& u,
    const GoalLayer& goals, const CellIndex& start)
{
	const auto& g = u.geometry();
	checkSameGeometry(g, field.geometry);
	checkSameGeometry(g, goals.geometry());
	if (!field.reached(start))
		throw NoPathError(
		    "no path from " + cellText(g, start) + " to any of " +
		    std::to_string(goals.count()) + " goal cells");
	const detail::Steps a(g.resolution);
	const auto& U = u.values();
	const double L = u.L();
	PlannedPath p;
	CellIndex cur = start;
	p.cells.push_back(cur);
	while (!goals.isGoal(cur))
	{
		// Eq. (12) with the neighbour term of eq. (10).
		double best = -kInf;
		int bestK = -1;
		for (int k = 0; k < 8; k++)
		{
			const CellIndex n{
			    cur.row + detail::kDr[k], cur.col + detail::kDc[k]};
			if (!g.contains(n)) continue;
			const std::size_t j = g.index(n);
			if (U[j] >= L) continue;
			const double t = field.x[j] - (a[k] + U[j]);
			if (t > best)
			{
				best = t;
				bestK = k;
			}
		}
		if (bestK < 0 || p.cells.size() > g.cellCount())
			throw PlanningError(
			    "path extraction failed at " + cellText(g, cur) +
			    ": the field is not a converged diffusion field");
		cur = {cur.row + detail::kDr[bestK], cur.col + detail::kDc[bestK]};
		p.cost += a[bestK] + U[g.index(cur)];
		p.lengthM += a[bestK];
		p.cells.push_back(cur);
	}
	p.goalId = goals.id(cur);
	p.points.reserve(p.cells.size());
	for (const auto& c : p.cells)
		p.points.emplace_back(g.centerX(c.col), g.centerY(c.row));
	return p;
}

PlannedPath CnnPlanner::plan(
    const TraversabilityGrid& u, const GoalLayer& goals, const CellIndex& start,
    DiffusionField* field) const
{
	checkInputs(u, goals, start);
	if (!field) return extractPath(computeField(u, goals), u, goals, start);
	*field = computeField(u, goals);  // kept for the caller on NoPathError
	return extractPath(*field, u, goals, start);
}

PlannedPath CnnPlanner::plan(
    const TraversabilityGrid& u, const GoalLayer& goals, double startX,
    double startY, DiffusionField* field) const
{
	return plan(u, goals, startCell(u.geometry(), startX, startY), field);
}

}  // namespace semnav

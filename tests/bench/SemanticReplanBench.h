/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// bench_planner's SemanticPlanner replans: the generated office as a
// SemanticMap, 1 m^2 boxes inserted into it by sweeps, replans timed from
// scratch, incrementally (Plan) and incrementally (SharedPlan).
#include <benchmark/benchmark.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/SemanticPlanner.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../map/MapTestUtils.h"
#include "OfficeGrid.h"

namespace semnav::test
{
/** The office as a SemanticMap: occupied cells labelled obstacle, free
 * cells floor, every cell observed once. */
inline std::unique_ptr<SemanticMap> officeSemanticMap(const OfficeMap& m)
{
	const auto& g = m.geometry;
	std::vector<float> labels(g.cellCount()), seen(g.cellCount(), 1.0f);
	LabelSet floor, obstacle;
	floor.insert(Label::Floor);
	obstacle.insert(Label::Obstacle);
	for (std::size_t i = 0; i < g.cellCount(); i++)
		labels[i] = static_cast<float>(
		    (m.occupancy[i] == CellOccupancy::Occupied ? obstacle : floor)
		        .mask());
	auto map = std::make_unique<SemanticMap>();
	map->restore(
	    g, {{"labels", labels}, {"observations", seen}},
	    std::vector<int8_t>(g.cellCount(), 0), {}, 0);
	auto& grid = map->occupancyGrid();
	for (int r = 0; r < g.rows; r++)
		for (int c = 0; c < g.cols; c++)
			grid.setCell(
			    c, r,
			    m.occupancy[g.index(r, c)] == CellOccupancy::Occupied ? 0.95f
			                                                          : 0.05f);
	map->updateCosts();
	// Three wastebaskets: in the goal's room and two other corner rooms.
	const double far = g.maxX() - 2.5;
	for (const auto& [x, y] :
	     {std::pair<double, double>{far, far}, {far, 2.5}, {2.5, far}})
		map->addInstance(
		    Label::Wastebasket, {x - 0.15, y - 0.15, 0},
		    {x + 0.15, y + 0.15, 0.4}, 5);
	return map;
}

/** Inserts a sweep seeing a 1 m x 1 m box centred on (x, y) from 1.5 m
 * away (its top at 0.3 m, seen as obstacle points every 2.5 cm). */
inline void insertBox(SemanticMap& map, double x, double y, double heading)
{
	std::vector<test::FakePoint> pts;
	for (double dx = -0.4875; dx < 0.5; dx += 0.025)
		for (double dy = -0.4875; dy < 0.5; dy += 0.025)
			pts.push_back({1.5 + dx, dy, 0.3, Label::Obstacle});
	const auto f = test::makeFakeSweep(pts);
	map.insert(
	    f.sweep, f.labeled,
	    mrpt::poses::CPose2D(
	        x - 1.5 * std::cos(heading), y - 1.5 * std::sin(heading), heading));
}

/** The box at (x, y) (with 0.1 m around it) and the robot 1.5 m before
 * it (heading) lie in free space away from the start and the goal. */
inline bool clearSpot(const OfficeMap& m, double x, double y, double heading)
{
	const auto& g = m.geometry;
	const double sx = g.centerX(m.start.col), sy = g.centerY(m.start.row);
	const double gx = g.centerX(m.goal.col), gy = g.centerY(m.goal.row);
	if (std::hypot(x - sx, y - sy) < 2.5 || std::hypot(x - gx, y - gy) < 2.5)
		return false;
	const auto freeAround = [&](double cx, double cy, int half)
	{
		for (int r = -half; r <= half; r++)
			for (int c = -half; c <= half; c++)
			{
				const auto cell =
				    g.cellOf(cx + c * g.resolution, cy + r * g.resolution);
				if (!cell || m.occupancy[g.index(*cell)] != CellOccupancy::Free)
					return false;
			}
		return true;
	};
	return freeAround(x, y, 12) &&
	       freeAround(
	           x - 1.5 * std::cos(heading), y - 1.5 * std::sin(heading), 6);
}

/** What the replan benchmarks record, per benchmark name. */
struct ReplanRecord
{
	/** Wall time of each replan (ms). */
	std::map<std::string, std::vector<double>> replanMs;
	/** The planner's own time (u, goals, field) of each replan (ms). */
	std::map<std::string, std::vector<double>> refreshMs;
	/** Counts for the summary. */
	std::map<std::string, double> figures;
};

/** How the benchmark replans. */
enum class Replan
{
	/** clearCache() + toPointShared: u, goals and field from scratch. */
	Scratch,
	/** toPoint: cached and repaired, the Plan's grids copied out. */
	Incremental,
	/** toPointShared: cached and repaired, the grids shared. */
	Shared
};

/** 12 boxes inserted one after the other, each on the current path (near
 * k/13 of it) or at a random free spot; after each the planner replans
 * from the start to the goal. Timed: the replan only. */
inline void runSemanticReplan(
    benchmark::State& st, const OfficeMap& m, bool onPath, Replan mode,
    bool toLabel, const std::string& name, ReplanRecord& record)
{
	const auto& g = m.geometry;
	const auto map = officeSemanticMap(m);
	TraversabilityBuilder::TOptions to;
	to.robotRadius = 0.2;
	CnnPlanner::TOptions co;
	co.threads = 1;
	SemanticPlanner planner(*map, co, to);
	const double sx = g.centerX(m.start.col), sy = g.centerY(m.start.row);
	const double gx = g.centerX(m.goal.col), gy = g.centerY(m.goal.row);
	const auto planShared = [&]
	{
		return toLabel ? planner.toLabelShared(
		                     sx, sy, Label::Wastebasket, CostProfile::Shortest)
		               : planner.toPointShared(
		                     sx, sy, gx, gy, CostProfile::Shortest);
	};
	std::vector<mrpt::math::TPoint2D> path = planShared().path.points;
	std::mt19937_64 rng(5);
	std::size_t k = 0, differ = 0, noPath = 0, spotsOnPath = 0;
	auto& refreshMs = record.refreshMs[name];
	for (auto _ : st)
	{
		k++;
		double x = 0, y = 0, heading = 0;
		bool found = false;
		// On the path: the path points nearest to k/13 of it first.
		const std::size_t j0 = path.size() * k / 13;
		for (std::size_t a = 0; onPath && !found && a < 2 * path.size(); a++)
		{
			const std::size_t j =
			    a % 2 ? j0 + (a + 1) / 2 : j0 - std::min(j0, a / 2);
			if (j + 1 >= path.size()) continue;
			x = path[j].x;
			y = path[j].y;
			heading = std::atan2(path[j + 1].y - y, path[j + 1].x - x);
			found = clearSpot(m, x, y, heading);
		}
		if (onPath) spotsOnPath += found;
		while (!found)
		{
			x = 2 + static_cast<double>(rng() % 4600) / 100;
			y = 2 + static_cast<double>(rng() % 4600) / 100;
			heading = static_cast<double>(rng() % 628) / 100;
			found = clearSpot(m, x, y, heading);
		}
		// Seen in three sweeps: the cells turn occupied.
		for (int sweep = 0; sweep < 3; sweep++) insertBox(*map, x, y, heading);
		if (mode == Replan::Scratch) planner.clearCache();
		// Plans are held past the timing (the check below), then dropped:
		// a held SharedPlan would make the next repair copy its field.
		SemanticPlanner::SharedPlan shared;
		SemanticPlanner::Plan copied;
		const auto t0 = std::chrono::steady_clock::now();
		try
		{
			if (mode == Replan::Incremental)
				copied = planShared().copy();
			else
				shared = planShared();
		}
		catch (const NoPathError&)
		{
			noPath++;  // the field is repaired all the same
		}
		const double sec =
		    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
		        .count();
		st.SetIterationTime(sec);
		record.replanMs[name].push_back(1e3 * sec);
		if (shared.field) path = shared.path.points;
		if (!copied.path.points.empty()) path = copied.path.points;
		const std::vector<double>* field =
		    shared.field ? &shared.field->x : &copied.field.x;
		refreshMs.push_back(planner.counters().lastMilliseconds);
		if (mode != Replan::Scratch && k <= 4 && !field->empty())
		{
			SemanticPlanner fresh(*map, co, to);
			const auto ref =
			    toLabel ? fresh.toLabelShared(
			                  sx, sy, Label::Wastebasket, CostProfile::Shortest)
			            : fresh.toPointShared(
			                  sx, sy, gx, gy, CostProfile::Shortest);
			for (std::size_t i = 0; i < field->size(); i++)
				differ += ref.field->x[i] != (*field)[i];
		}
	}
	const auto c = planner.counters();
	st.counters["repairs"] = static_cast<double>(c.repairs);
	st.counters["full_fields"] = static_cast<double>(c.fullFields);
	st.counters["u_partial"] = static_cast<double>(c.partialTraversability);
	st.counters["cells_differing_from_fresh"] = static_cast<double>(differ);
	record.figures[name + " cells differing from a fresh planner"] =
	    static_cast<double>(differ);
	record.figures[name + " repair fallbacks"] =
	    static_cast<double>(c.repairFallbacks);
	record.figures[name + " replans without a path"] =
	    static_cast<double>(noPath);
	if (onPath)
		record.figures[name + " boxes on the path / 12"] =
		    static_cast<double>(spotsOnPath);
}

}  // namespace semnav::test

/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/DijkstraPlanner.h>
#include <semnav/planning/PlanningErrors.h>

#include <cstdint>
#include <functional>
#include <queue>
#include <utility>

#include "DiffusionKernels.h"

namespace semnav
{
using detail::kInf;

namespace
{
/** Backward search from the goal set: settling cell c relaxes every
 * neighbour n with V(c) + (a + u(c)), the cost of the step n -> c. Stops
 * when `stop` is settled (stop < 0: never). next[n] = the cell after n on
 * its best path. */
void search(
    const TraversabilityGrid& u, const GoalLayer& goals, long stop,
    std::vector<double>& V, std::vector<int64_t>* next)
{
	const auto& g = u.geometry();
	const auto ue = detail::effectiveU(u);
	const detail::Steps a(g.resolution);
	V.assign(ue.size(), kInf);
	if (next) next->assign(ue.size(), -1);
	using Item = std::pair<double, int64_t>;
	std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
	for (std::size_t i = 0; i < ue.size(); i++)
		if (goals.isGoal(i) && ue[i] != kInf)
		{
			V[i] = 0;
			heap.push({0.0, static_cast<int64_t>(i)});
		}
	if (heap.empty())
		throw EmptyGoalError(
		    goals.count() == 0 ? "the goal set is empty"
		                       : "the goal set is empty: all goal cells are "
		                         "blocked");
	while (!heap.empty())
	{
		const auto [d, i] = heap.top();
		heap.pop();
		if (d > V[i]) continue;  // stale entry
		if (i == stop) return;
		const int r = static_cast<int>(i / g.cols);
		const int c = static_cast<int>(i % g.cols);
		for (int k = 0; k < 8; k++)
		{
			const int rr = r + detail::kDr[k], cc = c + detail::kDc[k];
			if (!g.contains(rr, cc)) continue;
			const std::size_t j = g.index(rr, cc);
			if (ue[j] == kInf) continue;
			const double cand = d + (a[k] + ue[i]);
			if (cand < V[j])
			{
				V[j] = cand;
				if (next) (*next)[j] = i;
				heap.push({cand, static_cast<int64_t>(j)});
			}
		}
	}
}
}  // namespace

std::vector<double> DijkstraPlanner::costField(
    const TraversabilityGrid& u, const GoalLayer& goals)
{
	std::vector<double> V;
	search(u, goals, -1, V, nullptr);
	return V;
}

PlannedPath DijkstraPlanner::plan(
    const TraversabilityGrid& u, const GoalLayer& goals, const CellIndex& start)
{
	CnnPlanner::checkInputs(u, goals, start);
	const auto& g = u.geometry();
	std::vector<double> V;
	std::vector<int64_t> next;
	search(u, goals, static_cast<long>(g.index(start)), V, &next);
	if (V[g.index(start)] == kInf)
		throw NoPathError("no path from the start to any goal cell");
	PlannedPath p;
	const detail::Steps a(g.resolution);
	int64_t i = static_cast<int64_t>(g.index(start));
	p.cells.push_back(g.cellAt(i));
	while (!goals.isGoal(static_cast<std::size_t>(i)))
	{
		const int64_t j = next[i];
		const CellIndex ci = g.cellAt(i), cj = g.cellAt(j);
		const bool diagonal = ci.row != cj.row && ci.col != cj.col;
		const double step = diagonal ? a.diagonal : a.straight;
		p.cost += step + u.u(static_cast<std::size_t>(j));
		p.lengthM += step;
		p.cells.push_back(cj);
		i = j;
	}
	p.goalId = goals.id(static_cast<std::size_t>(i));
	for (const auto& c : p.cells)
		p.points.emplace_back(g.centerX(c.col), g.centerY(c.row));
	return p;
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/PlannedPath.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <vector>

namespace semnav
{
/** Plain binary-heap Dijkstra from the goal set, with CnnPlanner's cost
 * convention (entering cell c by a step of length a costs a + u(c); blocked
 * cells are never entered). Test oracle and benchmark baseline. */
class DijkstraPlanner
{
public:
	/** Min cost from every cell to the goal set; +infinity where
	 * unreachable and on blocked cells. Throws EmptyGoalError. */
	static std::vector<double> costField(
	    const TraversabilityGrid& u, const GoalLayer& goals);

	/** Optimal path from `start`; the search stops when the start is
	 * settled. Throws as CnnPlanner::checkInputs and NoPathError. */
	static PlannedPath plan(
	    const TraversabilityGrid& u, const GoalLayer& goals,
	    const CellIndex& start);
};

}  // namespace semnav

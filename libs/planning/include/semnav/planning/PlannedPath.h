/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <semnav/common/CellIndex.h>

#include <vector>

namespace semnav
{
/** A path from the start cell to a goal cell (both included). */
struct PlannedPath
{
	std::vector<CellIndex> cells;
	/** Cell centres (m), same order as cells. */
	std::vector<mrpt::math::TPoint2D> points;
	/** Sum over steps of (step length + u(cell entered)); the start cell's
	 * u is not charged, the goal cell's is. */
	double cost = 0;
	/** Sum of the step lengths (m). */
	double lengthM = 0;
	/** GoalLayer id of the last cell. */
	int goalId = 0;
};

}  // namespace semnav

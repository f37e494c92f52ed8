/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/GridGeometry.h>

#include <cmath>
#include <limits>
#include <vector>

namespace semnav
{
/** The diffusion layer x of the paper at the fixed point of eq. (10), see
 * CnnPlanner for the convention: x = L - (min cost from the cell to the goal
 * set); -infinity where no goal is reachable and on blocked cells. */
struct DiffusionField
{
	GridGeometry geometry;
	double L = 0;
	/** Row-major x. */
	std::vector<double> x;
	/** Jacobi: synchronous updates until eq. (11) held (the last one changed
	 * nothing). Sweep: raster passes run. */
	int iterations = 0;
	/** Sweep: rows relaxed over all passes (0 for Jacobi). */
	long rowUpdates = 0;
	/** Wall time of the diffusion (ms). */
	double milliseconds = 0;

	double at(const CellIndex& c) const { return x[geometry.index(c)]; }
	bool reached(const CellIndex& c) const { return std::isfinite(at(c)); }
	/** L - x: the min cost to the goal set; +infinity when unreachable. */
	double costToGo(const CellIndex& c) const
	{
		return reached(c) ? L - at(c) : std::numeric_limits<double>::infinity();
	}
};

}  // namespace semnav

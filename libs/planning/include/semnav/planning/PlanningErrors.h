/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Error.h>
#include <semnav/common/GridGeometry.h>

namespace semnav
{
/** Base of the errors of the planning module (bad grids, bad options). */
class PlanningError : public Error
{
	using Error::Error;
};

/** The start position lies outside the grid. */
class StartOutsideMapError : public PlanningError
{
	using PlanningError::PlanningError;
};

/** The start cell is not traversable (u = L: an obstacle, or the robot's
 * disc would touch one). */
class StartBlockedError : public PlanningError
{
	using PlanningError::PlanningError;
};

/** The goal layer has no traversable goal cell. */
class EmptyGoalError : public PlanningError
{
	using PlanningError::PlanningError;
};

/** No goal cell can be reached from the start. */
class NoPathError : public PlanningError
{
	using PlanningError::PlanningError;
};

/** The diffusion did not reach eq. (11) within max_iterations. */
class NotConvergedError : public PlanningError
{
	using PlanningError::PlanningError;
};

/** GridGeometry::validate() with the failure as a PlanningError. */
void validatePlanningGrid(const GridGeometry& g);

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/planning/SemanticPlanner.h>

#include <string>

namespace semnav
{
/** Writes a plan's grids for outside tools (NumPy, Python planners):
 * `<prefix>_u.npy` (float32, rows = cell y index, cols = cell x index,
 * blocked = +inf), `<prefix>_goal.npy` (uint8 goal mask) and
 * `<prefix>_meta.json` {"resolution", "origin_x", "origin_y", "L",
 * "start": [row, col], "path": [[row, col], ...]}. Files are written
 * atomically. */
void exportPlanGrids(
    const std::string& prefix, const SemanticPlanner::Plan& plan);

/** An .npy (format 1.0) image of a row-major array; `descr` is NumPy's
 * type string ("<f4", "|u1"). */
std::string npyBytes(
    const void* data, std::size_t elementSize, const std::string& descr,
    int rows, int cols);

}  // namespace semnav

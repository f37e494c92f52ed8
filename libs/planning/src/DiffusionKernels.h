/* semnav: semantic navigation from tilting-laser sweeps */
// Internal: the diffusion schedules and helpers shared by the planners.
#pragma once

#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <cmath>
#include <limits>
#include <vector>

namespace semnav::detail
{
constexpr double kInf = std::numeric_limits<double>::infinity();

/** 8-neighbourhood: 4 straight steps first, then the diagonals. */
constexpr int kDr[8] = {-1, 1, 0, 0, -1, -1, 1, 1};
constexpr int kDc[8] = {0, 0, -1, 1, -1, 1, -1, 1};

/** Step lengths a of eq. (8). */
struct Steps
{
	double straight, diagonal;
	explicit Steps(double res) : straight(res), diagonal(res * std::sqrt(2.0))
	{
	}
	double operator[](int k) const { return k < 4 ? straight : diagonal; }
};

/** u with blocked cells (u >= L) at +infinity: every step cost is then
 * x - (a + ue), the same expression in every schedule. */
std::vector<double> effectiveU(const TraversabilityGrid& u);

/** x(0): L on traversable goal cells, -infinity elsewhere. Returns the
 * number of traversable goal cells. */
std::size_t initialField(
    const TraversabilityGrid& u, const GoalLayer& goals,
    std::vector<double>& x);

/** Synchronous eq. (10) from x = x(0) until eq. (11); x(0) is the source
 * term g - u of eq. (10). Returns the number of updates (the
 * last one changed nothing), or -1 when maxIterations (> 0) was reached. */
int diffuseJacobi(
    const GridGeometry& g, const std::vector<double>& ue,
    std::vector<double>& x, int maxIterations, int threads);

/** Alternating in-place raster passes (down, up) over horizontal bands, one
 * thread each, until no cell's eq. (10) is left unverified. Returns the
 * number of passes, or -1 when maxIterations (> 0) was reached. */
int diffuseSweep(
    const GridGeometry& g, const std::vector<double>& ue,
    std::vector<double>& x, int maxIterations, int threads, long& rowUpdates);

}  // namespace semnav::detail

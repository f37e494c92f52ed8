/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/planning/PlanningErrors.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace semnav
{
TraversabilityGrid::TraversabilityGrid(
    const GridGeometry& geometry, double L, double initialU)
    : m_geometry(geometry), m_L(L)
{
	validatePlanningGrid(geometry);
	if (!(L > 0) || !std::isfinite(L))
		throw PlanningError(
		    "L must be a finite value > 0 (got " + std::to_string(L) + ")");
	m_u.assign(geometry.cellCount(), std::clamp(initialU, 0.0, L));
}

void TraversabilityGrid::setU(int row, int col, double u)
{
	if (std::isnan(u)) throw PlanningError("traversability u is NaN");
	m_u[m_geometry.index(row, col)] = std::clamp(u, 0.0, m_L);
}

std::size_t TraversabilityGrid::blockedCount() const
{
	return static_cast<std::size_t>(std::count_if(
	    m_u.begin(), m_u.end(), [this](double v) { return v >= m_L; }));
}

}  // namespace semnav

namespace semnav
{
void validatePlanningGrid(const GridGeometry& g)
{
	try
	{
		g.validate();
	}
	catch (const Error& e)
	{
		throw PlanningError(e.what());
	}
}
}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/GridGeometry.h>

#include <cstddef>
#include <vector>

namespace semnav
{
/** The traversability layer u of the paper (sec. 3): per cell the cost
 * u in [0, L] charged when the robot enters the cell; u = L (or more) marks
 * a blocked cell of C_occ, which is never entered (u = infinity in eq. (7)).
 * u is charged per cell, so its scale depends on the resolution. */
class TraversabilityGrid
{
public:
	TraversabilityGrid() = default;
	/** All cells at `initialU`. Throws PlanningError on a bad geometry or
	 * L <= 0. */
	TraversabilityGrid(
	    const GridGeometry& geometry, double L, double initialU = 0);

	const GridGeometry& geometry() const { return m_geometry; }
	/** The paper's L: the value of goal cells in g and of blocked cells in
	 * u. */
	double L() const { return m_L; }

	double u(int row, int col) const { return m_u[m_geometry.index(row, col)]; }
	double u(std::size_t i) const { return m_u[i]; }
	/** Sets u, clamped to [0, L]. Throws PlanningError on NaN. */
	void setU(int row, int col, double u);
	void block(int row, int col) { m_u[m_geometry.index(row, col)] = m_L; }

	bool blocked(std::size_t i) const { return m_u[i] >= m_L; }
	bool blocked(int row, int col) const
	{
		return blocked(m_geometry.index(row, col));
	}
	bool blocked(const CellIndex& c) const
	{
		return blocked(m_geometry.index(c));
	}
	std::size_t blockedCount() const;

	/** Row-major values (see GridGeometry); values >= L are blocked. */
	const std::vector<double>& values() const { return m_u; }
	std::vector<double>& values() { return m_u; }

private:
	GridGeometry m_geometry;
	double m_L = 1;
	std::vector<double> m_u;
};

}  // namespace semnav

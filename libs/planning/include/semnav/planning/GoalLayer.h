/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/GridGeometry.h>

#include <cstdint>
#include <vector>

namespace semnav
{
/** The goal layer g of the paper (g = L on goal cells, 0 elsewhere). Each
 * goal cell carries an id > 0 (e.g. the object instance it belongs to) so
 * the caller learns which goal the path reached; a cell already holding a
 * goal keeps its first id. Goal cells that are blocked in u are ignored by
 * the planners. */
class GoalLayer
{
public:
	GoalLayer() = default;
	explicit GoalLayer(const GridGeometry& geometry);

	const GridGeometry& geometry() const { return m_geometry; }

	/** Adds one cell; throws PlanningError when it is outside the grid or
	 * id <= 0. */
	void addCell(const CellIndex& c, int id = 1);
	/** Adds the cell holding (x, y); throws PlanningError outside the
	 * grid. */
	void addPoint(double x, double y, int id = 1);
	/** Adds the cells whose centre is within `radius` (m) of (x, y), clipped
	 * to the grid. Returns the number of cells that became goals. */
	std::size_t addDisc(double x, double y, double radius, int id = 1);
	/** Adds the given cells (those outside the grid are skipped). Returns the
	 * number of cells that became goals. */
	std::size_t addCells(const std::vector<CellIndex>& cells, int id = 1);
	/** Adds every cell whose centre is within `distance` (m) of the square
	 * of any of `cells` (e.g. the cells of an object instance, with distance
	 * = TraversabilityBuilder::goalRegionRadius()). Returns the number of
	 * cells that became goals. */
	std::size_t addRegionAround(
	    const std::vector<CellIndex>& cells, double distance, int id = 1);
	void clear();
	/** Sets the goal id of cell i, replacing any (0: no goal). */
	void setId(std::size_t i, int id);

	bool isGoal(std::size_t i) const { return m_id[i] != 0; }
	bool isGoal(const CellIndex& c) const
	{
		return m_id[m_geometry.index(c)] != 0;
	}
	/** Goal id of a cell, 0 when it is not a goal. */
	int id(const CellIndex& c) const { return m_id[m_geometry.index(c)]; }
	int id(std::size_t i) const { return m_id[i]; }
	/** Number of goal cells. */
	std::size_t count() const { return m_count; }

	/** Row-major goal ids (0 = not a goal). */
	const std::vector<int32_t>& ids() const { return m_id; }
	/** Row-major 0/1 mask. */
	std::vector<uint8_t> mask() const;

private:
	bool set(std::size_t i, int id);

	GridGeometry m_geometry;
	std::vector<int32_t> m_id;
	std::size_t m_count = 0;
};

}  // namespace semnav

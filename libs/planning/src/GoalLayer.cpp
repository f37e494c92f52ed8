/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/PlanningErrors.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace semnav
{
GoalLayer::GoalLayer(const GridGeometry& geometry) : m_geometry(geometry)
{
	validatePlanningGrid(geometry);
	m_id.assign(geometry.cellCount(), 0);
}

bool GoalLayer::set(std::size_t i, int id)
{
	if (id <= 0)
		throw PlanningError(
		    "goal id must be > 0 (got " + std::to_string(id) + ")");
	if (m_id[i] != 0) return false;
	m_id[i] = id;
	m_count++;
	return true;
}

void GoalLayer::addCell(const CellIndex& c, int id)
{
	if (!m_geometry.contains(c))
		throw PlanningError(
		    "goal cell (row " + std::to_string(c.row) + ", col " +
		    std::to_string(c.col) + ") is outside the " +
		    std::to_string(m_geometry.cols) + " x " +
		    std::to_string(m_geometry.rows) + " grid");
	set(m_geometry.index(c), id);
}

void GoalLayer::addPoint(double x, double y, int id)
{
	const auto c = m_geometry.cellOf(x, y);
	if (!c)
	{
		char buf[200];
		std::snprintf(
		    buf, sizeof(buf),
		    "goal (%.3f, %.3f) is outside the map [%.3f, %.3f] x [%.3f, %.3f]",
		    x, y, m_geometry.originX, m_geometry.maxX(), m_geometry.originY,
		    m_geometry.maxY());
		throw PlanningError(buf);
	}
	set(m_geometry.index(*c), id);
}

std::size_t GoalLayer::addDisc(double x, double y, double radius, int id)
{
	const auto& g = m_geometry;
	const double r2 = radius * radius;
	const int c0 = std::max(
	    0,
	    static_cast<int>(std::floor((x - radius - g.originX) / g.resolution)));
	const int c1 = std::min(
	    g.cols - 1,
	    static_cast<int>(std::floor((x + radius - g.originX) / g.resolution)));
	const int r0 = std::max(
	    0,
	    static_cast<int>(std::floor((y - radius - g.originY) / g.resolution)));
	const int r1 = std::min(
	    g.rows - 1,
	    static_cast<int>(std::floor((y + radius - g.originY) / g.resolution)));
	std::size_t added = 0;
	for (int r = r0; r <= r1; r++)
		for (int c = c0; c <= c1; c++)
		{
			const double dx = g.centerX(c) - x, dy = g.centerY(r) - y;
			if (dx * dx + dy * dy <= r2 && set(g.index(r, c), id)) added++;
		}
	return added;
}

std::size_t GoalLayer::addCells(const std::vector<CellIndex>& cells, int id)
{
	std::size_t added = 0;
	for (const auto& c : cells)
		if (m_geometry.contains(c) && set(m_geometry.index(c), id)) added++;
	return added;
}

std::size_t GoalLayer::addRegionAround(
    const std::vector<CellIndex>& cells, double distance, int id)
{
	const double res = m_geometry.resolution;
	const int k = static_cast<int>(std::ceil(distance / res)) + 1;
	const double d2 = (distance / res) * (distance / res);
	std::size_t added = 0;
	for (const auto& c : cells)
		for (int dr = -k; dr <= k; dr++)
			for (int dc = -k; dc <= k; dc++)
			{
				// Distance (in cells) from the neighbour's centre to c's
				// square.
				const double ex = std::max(0.0, std::abs(dc) - 0.5);
				const double ey = std::max(0.0, std::abs(dr) - 0.5);
				if (ex * ex + ey * ey > d2) continue;
				const CellIndex n{c.row + dr, c.col + dc};
				if (m_geometry.contains(n) && set(m_geometry.index(n), id))
					added++;
			}
	return added;
}

void GoalLayer::setId(std::size_t i, int id)
{
	if (id < 0)
		throw PlanningError(
		    "goal id must be >= 0 (got " + std::to_string(id) + ")");
	if (m_id[i] != 0) m_count--;
	if (id != 0) m_count++;
	m_id[i] = id;
}

void GoalLayer::clear()
{
	std::fill(m_id.begin(), m_id.end(), 0);
	m_count = 0;
}

std::vector<uint8_t> GoalLayer::mask() const
{
	std::vector<uint8_t> m(m_id.size());
	for (std::size_t i = 0; i < m_id.size(); i++) m[i] = m_id[i] != 0 ? 1 : 0;
	return m;
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/GridGeometry.h>

#include <algorithm>

namespace semnav
{
/** A rectangle of grid cells: rows [row0, row1) x columns [col0, col1);
 * empty when row0 >= row1 or col0 >= col1. */
struct CellRect
{
	int row0 = 0, col0 = 0, row1 = 0, col1 = 0;

	/** The whole grid. */
	static CellRect all(const GridGeometry& g)
	{
		return {0, 0, g.rows, g.cols};
	}

	bool empty() const { return row0 >= row1 || col0 >= col1; }
	/** The part inside the grid. */
	CellRect clipped(const GridGeometry& g) const
	{
		return {
		    std::max(row0, 0), std::max(col0, 0), std::min(row1, g.rows),
		    std::min(col1, g.cols)};
	}
	bool contains(int row, int col) const
	{
		return row >= row0 && row < row1 && col >= col0 && col < col1;
	}
	bool intersects(const CellRect& o) const
	{
		return !empty() && !o.empty() && row0 < o.row1 && o.row0 < row1 &&
		       col0 < o.col1 && o.col0 < col1;
	}
	/** Grown by `margin` cells on every side (not clipped). */
	CellRect dilated(int margin) const
	{
		return empty() ? *this
		               : CellRect{
		                     row0 - margin, col0 - margin, row1 + margin,
		                     col1 + margin};
	}
	/** The smallest rectangle holding both. */
	CellRect united(const CellRect& o) const
	{
		if (empty()) return o;
		if (o.empty()) return *this;
		return {
		    std::min(row0, o.row0), std::min(col0, o.col0),
		    std::max(row1, o.row1), std::max(col1, o.col1)};
	}
	/** Grows the rectangle to hold cell (row, col). */
	void add(int row, int col)
	{
		if (empty())
		{
			*this = {row, col, row + 1, col + 1};
			return;
		}
		row0 = std::min(row0, row);
		col0 = std::min(col0, col);
		row1 = std::max(row1, row + 1);
		col1 = std::max(col1, col + 1);
	}
};

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/CellIndex.h>

#include <cstddef>
#include <optional>

namespace semnav
{
/** Geometry of a 2D grid (the semantic map's layers, the planner's
 * layers), as MRPT's COccupancyGridMap2D: cell (row,
 * col) covers x in [originX + col res, originX + (col + 1) res) and y in
 * [originY + row res, originY + (row + 1) res). Layers are stored row-major:
 * index = row * cols + col. */
struct GridGeometry
{
	/** Cell size (m). */
	double resolution = 0.05;
	/** World coordinates of the corner of cell (0, 0) (m). */
	double originX = 0;
	double originY = 0;
	/** Number of cells along x (columns) and y (rows). */
	int cols = 0;
	int rows = 0;

	GridGeometry() = default;
	GridGeometry(double res, double ox, double oy, int nCols, int nRows)
	    : resolution(res), originX(ox), originY(oy), cols(nCols), rows(nRows)
	{
	}

	/** Throws Error unless resolution > 0 and both sizes >= 1. */
	void validate() const;

	std::size_t cellCount() const
	{
		return static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
	}
	bool contains(int row, int col) const
	{
		return row >= 0 && col >= 0 && row < rows && col < cols;
	}
	bool contains(const CellIndex& c) const { return contains(c.row, c.col); }
	std::size_t index(int row, int col) const
	{
		return static_cast<std::size_t>(row) * static_cast<std::size_t>(cols) +
		       static_cast<std::size_t>(col);
	}
	std::size_t index(const CellIndex& c) const { return index(c.row, c.col); }
	CellIndex cellAt(std::size_t i) const
	{
		return {static_cast<int>(i / cols), static_cast<int>(i % cols)};
	}

	/** Cell holding the point (x, y); nullopt outside the grid. */
	std::optional<CellIndex> cellOf(double x, double y) const;

	double centerX(int col) const { return originX + (col + 0.5) * resolution; }
	double centerY(int row) const { return originY + (row + 0.5) * resolution; }
	/** Cell (col = x index, row = y index) of a world point; false (the
	 * indices still set) outside the grid. */
	bool worldToCell(double x, double y, int& col, int& row) const;
	/** Centre of a cell; false outside the grid. */
	bool cellToWorld(int col, int row, double& x, double& y) const
	{
		x = centerX(col);
		y = centerY(row);
		return contains(row, col);
	}
	bool operator==(const GridGeometry& o) const
	{
		return resolution == o.resolution && originX == o.originX &&
		       originY == o.originY && cols == o.cols && rows == o.rows;
	}
	double maxX() const { return originX + cols * resolution; }
	double maxY() const { return originY + rows * resolution; }
};

}  // namespace semnav

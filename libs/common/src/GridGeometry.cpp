/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/common/GridGeometry.h>

#include <cmath>
#include <string>

namespace semnav
{
void GridGeometry::validate() const
{
	if (!(resolution > 0) || !std::isfinite(resolution))
		throw Error(
		    "grid resolution must be > 0 (got " + std::to_string(resolution) +
		    ")");
	if (rows < 1 || cols < 1)
		throw Error(
		    "grid size must be at least 1 x 1 (got " + std::to_string(cols) +
		    " x " + std::to_string(rows) + ")");
}

bool GridGeometry::worldToCell(double x, double y, int& col, int& row) const
{
	col = static_cast<int>(std::floor((x - originX) / resolution));
	row = static_cast<int>(std::floor((y - originY) / resolution));
	return contains(row, col);
}

std::optional<CellIndex> GridGeometry::cellOf(double x, double y) const
{
	const double fx = std::floor((x - originX) / resolution);
	const double fy = std::floor((y - originY) / resolution);
	if (!(fx >= 0 && fy >= 0 && fx < cols && fy < rows)) return std::nullopt;
	return CellIndex{static_cast<int>(fy), static_cast<int>(fx)};
}

}  // namespace semnav

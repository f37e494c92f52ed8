/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

namespace semnav
{
/** A grid cell: row = cell y index, col = cell x index. */
struct CellIndex
{
	int row = 0;
	int col = 0;

	bool operator==(const CellIndex& o) const
	{
		return row == o.row && col == o.col;
	}
	bool operator!=(const CellIndex& o) const { return !(*this == o); }
};

}  // namespace semnav

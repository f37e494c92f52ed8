/* semnav: semantic navigation from tilting-laser sweeps */
// Test helper: random walls on a traversability grid.
#pragma once

#include <semnav/planning/TraversabilityGrid.h>

#include <algorithm>
#include <random>

namespace semnav::test
{
/** Blocks `count` straight segments of half the grid's larger side, each
 * from a random cell, down or right (clipped to the grid). */
inline void addWallSegments(
    TraversabilityGrid& u, int count, std::mt19937_64& rng)
{
	const auto& g = u.geometry();
	std::uniform_real_distribution<double> U(0, 1);
	for (int k = 0; k < count; k++)
	{
		const int r = static_cast<int>(U(rng) * g.rows);
		const int c = static_cast<int>(U(rng) * g.cols);
		const bool vertical = U(rng) < 0.5;
		for (int s = 0; s < std::max(g.rows, g.cols) / 2; s++)
		{
			const int rr = vertical ? r + s : r, cc = vertical ? c : c + s;
			if (g.contains(rr, cc)) u.block(rr, cc);
		}
	}
}
}  // namespace semnav::test

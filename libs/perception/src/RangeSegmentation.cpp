/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/perception/RangeSegmentation.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
void RangeSegmentation::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	checkKnownKeys(
	    c, s, {"max_neighbour_difference_m", "min_area_px", "connectivity"});
	maxNeighbourDifference = readChecked(
	    c, s, "max_neighbour_difference_m", maxNeighbourDifference, 0, 10);
	minAreaPixels =
	    readCheckedInt(c, s, "min_area_px", minAreaPixels, 0, 1000000);
	connectivity = readCheckedInt(c, s, "connectivity", connectivity, 4, 8);
	if (connectivity != 4 && connectivity != 8)
		throw ConfigError("[" + s + "] connectivity must be 4 or 8");
}

void RangeSegmentation::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	c.write(s, "max_neighbour_difference_m", maxNeighbourDifference);
	c.write(s, "min_area_px", minAreaPixels);
	c.write(s, "connectivity", connectivity);
}

RangeSegmentation::RangeSegmentation() : RangeSegmentation(TOptions()) {}

RangeSegmentation::RangeSegmentation(const TOptions& options)
    : m_options(options)
{
}

void RangeSegmentation::compute(const Sweep& sweep)
{
	const int rows = static_cast<int>(sweep.rows());
	const int cols = static_cast<int>(sweep.cols());
	m_ids.create(rows, cols, CV_32S);
	m_sizes.assign(1, 0);
	m_fills = 0;
	m_singletons = 0;
	if (rows == 0 || cols == 0) return;

	// The areas are the connected components of the graph joining valid
	// 4- (or 8-) neighbours whose ranges differ by at most
	// max_neighbour_difference_m: exactly what cv::floodFill with a floating
	// range finds from each first unassigned pixel (the same float test,
	// -diff <= a - b <= diff), found here by union-find in one row-major
	// scan instead of one fill per area. The root of a component is its
	// first pixel in row-major order, so areas are numbered in the order
	// the fills would number them.
	const int n = rows * cols;
	m_range.create(rows, cols, CV_32F);
	m_parent.resize(static_cast<std::size_t>(n));
	const float diff = static_cast<float>(m_options.maxNeighbourDifference);
	const bool eight = m_options.connectivity == 8;
	const float* rng = sweep.ranges().data();
	const uint8_t* val = sweep.validity().data();
	float* R = m_range.ptr<float>(0);
	int* U = m_parent.data();
	auto find = [U](int x)
	{
		while (U[x] != x)
		{
			U[x] = U[U[x]];
			x = U[x];
		}
		return x;
	};
	auto unite = [&](int a, int b)
	{
		a = find(a);
		b = find(b);
		if (a != b) U[std::max(a, b)] = std::min(a, b);
	};
	auto joins = [&](int p, int q)
	{
		const float d = R[p] - R[q];
		return U[q] >= 0 && -diff <= d && d <= diff;
	};
	for (int r = 0; r < rows; r++)
	{
		const int base = r * cols;
		for (int c = 0; c < cols; c++)
		{
			const int p = base + c;
			const float d = rng[p];
			const bool ok = val[p] && std::isfinite(d) && d > 0;
			R[p] = ok ? d : 0.0f;
			U[p] = ok ? p : -1;  // -1: invalid, in no area
			if (!ok) continue;
			// p is new (its own root, above all others): it hangs under
			// its left neighbour's root; the upper neighbour's tree is
			// united with that.
			int root = p;
			if (c > 0 && joins(p, p - 1)) root = find(p - 1);
			if (r > 0 && joins(p, p - cols))
			{
				const int up = find(p - cols);
				if (root == p)
					root = up;
				else if (up != root)
				{
					U[std::max(up, root)] = std::min(up, root);
					root = std::min(up, root);
				}
			}
			U[p] = root;
			if (eight && r > 0)
			{
				if (c > 0 && joins(p, p - cols - 1)) unite(p - cols - 1, p);
				if (c + 1 < cols && joins(p, p - cols + 1))
					unite(p - cols + 1, p);
			}
		}
	}
	// Component sizes (at the roots), then ids in row-major order of the
	// roots.
	int* I = m_ids.ptr<int>(0);
	for (int p = 0; p < n; p++)
	{
		I[p] = 0;
		if (U[p] < 0) continue;
		const int root = find(p);
		U[p] = root;
		I[root]++;
	}
	for (int p = 0; p < n; p++)
	{
		if (U[p] < 0)
		{
			m_sizes[0]++;
			continue;
		}
		if (U[p] == p)
		{
			const int size = I[p];
			if (size == 1 && m_options.minAreaPixels >= 1)
				m_singletons++;
			else
				m_fills++;
			if (size > m_options.minAreaPixels)
			{
				I[p] = static_cast<int>(m_sizes.size());
				m_sizes.push_back(size);
			}
			else
			{
				I[p] = 0;
				m_sizes[0] += size;
			}
		}
		else
			I[p] = I[U[p]];
	}
}

}  // namespace semnav

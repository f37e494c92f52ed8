/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace semnav
{
/** The rank round(p (n - 1)) of the p-th percentile (p in 0..1) of n > 0
 * values. */
inline std::size_t percentileRank(std::size_t n, double p)
{
	return std::min(n - 1, static_cast<std::size_t>(p * double(n - 1) + 0.5));
}

/** The p-th percentile (p in 0..1) of a non-empty `v`: the element of rank
 * percentileRank(). Reorders `v` (std::nth_element). */
template <typename T>
T percentile(std::vector<T>& v, double p)
{
	const std::size_t k = percentileRank(v.size(), p);
	std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
	return v[k];
}

/** {percentile(v, pLo), percentile(v, pHi)} for pLo <= pHi, the second
 * selection within the part the first left below its element. */
template <typename T>
std::pair<T, T> percentiles(std::vector<T>& v, double pLo, double pHi)
{
	const std::size_t hi = percentileRank(v.size(), pHi),
	                  lo = percentileRank(v.size(), pLo);
	std::nth_element(v.begin(), v.begin() + static_cast<long>(hi), v.end());
	std::nth_element(
	    v.begin(), v.begin() + static_cast<long>(lo),
	    v.begin() + static_cast<long>(hi));
	return {v[lo], v[hi]};
}

}  // namespace semnav

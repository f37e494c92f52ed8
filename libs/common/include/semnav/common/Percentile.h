/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace semnav
{
/** The p-th percentile (p in 0..1) of a non-empty `v`: the element of rank
 * round(p (n - 1)). Reorders `v` (std::nth_element). */
template <typename T>
T percentile(std::vector<T>& v, double p)
{
	const std::size_t k = std::min(
	    v.size() - 1, static_cast<std::size_t>(p * double(v.size() - 1) + 0.5));
	std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
	return v[k];
}

/** percentile(v, pHi) - percentile(v, pLo) for pLo <= pHi, the second
 * selection within the part the first left below its element. */
template <typename T>
T percentileSpread(std::vector<T>& v, double pLo, double pHi)
{
	const auto rank = [&](double p)
	{
		return std::min(
		    v.size() - 1,
		    static_cast<std::size_t>(p * double(v.size() - 1) + 0.5));
	};
	const std::size_t hi = rank(pHi), lo = rank(pLo);
	std::nth_element(v.begin(), v.begin() + static_cast<long>(hi), v.end());
	std::nth_element(
	    v.begin(), v.begin() + static_cast<long>(lo),
	    v.begin() + static_cast<long>(hi));
	return v[hi] - v[lo];
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
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

/** The median of `v` (the mean of the two middle values of an even count);
 * 0 when `v` is empty. */
inline double median(std::vector<double> v)
{
	if (v.empty()) return 0;
	std::sort(v.begin(), v.end());
	const std::size_t n = v.size();
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
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

/** {percentile(v, pLo), percentile(v, pHi)} (pLo <= pHi) of a non-empty
 * floating-point `v`, leaving `v` as it is (the value of a rank is the
 * same whatever selects it; with a NaN, percentiles() on a copy in
 * `scratch[0]`, as on `v` itself): the values are counted into 256
 * buckets of equal width between the smallest and the largest (a map that
 * never decreases, so each rank lies in a known bucket), then the buckets
 * of the two ranks are selected from. Its comparisons mostly go the same
 * way, nth_element's do not: several times faster on a few hundred values.
 * `scratch` is reused between calls. */
template <typename T>
std::pair<T, T> percentilesOf(
    const std::vector<T>& v, double pLo, double pHi,
    std::vector<T> (&scratch)[2], std::vector<uint8_t>& buckets)
{
	const std::size_t n = v.size();
	const std::size_t rank[2] = {
	    percentileRank(n, pLo), percentileRank(n, pHi)};
	T lo = v[0], hi = v[0];
	bool nan = false;
	for (const T& x : v)
	{
		lo = x < lo ? x : lo;
		hi = x > hi ? x : hi;
		nan |= x != x;
	}
	const T width = hi - lo;
	const T scale = T(256) / width;
	if (nan || !(width > 0) || !(width < std::numeric_limits<T>::infinity()) ||
	    !(scale < std::numeric_limits<T>::infinity()))
	{
		if (!nan && !(width > 0)) return {lo, lo};  // all equal
		scratch[0].assign(v.begin(), v.end());
		return percentiles(scratch[0], pLo, pHi);
	}
	std::size_t count[256] = {};
	buckets.resize(n);
	for (std::size_t i = 0; i < n; i++)
	{
		const int b = static_cast<int>((v[i] - lo) * scale);
		buckets[i] = static_cast<uint8_t>(b < 255 ? b : 255);
		count[buckets[i]]++;
	}
	// The bucket of each rank and the rank within it.
	int b[2] = {-1, -1};
	std::size_t within[2] = {0, 0};
	std::size_t below = 0;
	for (int i = 0; b[1] < 0; i++)
	{
		const std::size_t upTo = below + count[i];
		for (int j = 0; j < 2; j++)
			if (b[j] < 0 && rank[j] < upTo)
			{
				b[j] = i;
				within[j] = rank[j] - below;
			}
		below = upTo;
	}
	T out[2];
	for (int j = 0; j < 2; j++)
	{
		if (j == 1 && b[1] == b[0] && within[1] == within[0])
		{
			out[1] = out[0];
			break;
		}
		auto& s = scratch[j];
		s.clear();
		for (std::size_t i = 0; i < n; i++)
			if (buckets[i] == b[j]) s.push_back(v[i]);
		std::nth_element(
		    s.begin(), s.begin() + static_cast<long>(within[j]), s.end());
		out[j] = s[within[j]];
	}
	return {out[0], out[1]};
}

}  // namespace semnav

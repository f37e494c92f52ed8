/* semnav: semantic navigation from tilting-laser sweeps */
// Internal: a seeded generator whose sequence is fixed by the C++ standard
// (std::mt19937_64) with our own mappings to ranges (the standard
// distributions are implementation-defined), so a seed gives the same
// result on every platform.
#pragma once

#include <cstdint>
#include <random>

namespace semnav::detail
{
class Random
{
public:
	explicit Random(uint64_t seed) : m_gen(seed) {}
	uint64_t next() { return m_gen(); }
	/** Uniform in [0, n) (n > 0). */
	uint64_t below(uint64_t n)
	{
		return static_cast<uint64_t>(
		    (static_cast<unsigned __int128>(m_gen()) * n) >> 64);
	}
	/** Uniform in [0, 1). */
	double uniform() { return double(m_gen() >> 11) * 0x1.0p-53; }
	/** Uniform in [lo, hi). */
	double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
	/** A seed for a sub-generator. */
	uint64_t fork() { return m_gen() ^ 0x9e3779b97f4a7c15ULL; }

private:
	std::mt19937_64 m_gen;
};

}  // namespace semnav::detail

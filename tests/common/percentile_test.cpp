/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/Percentile.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <utility>

using namespace semnav;

TEST(Percentile, RankOfTheSortedValues)
{
	std::vector<int> v{5, 1, 4, 2, 3};
	EXPECT_EQ(percentile(v, 0.0), 1);
	EXPECT_EQ(percentile(v, 0.5), 3);
	EXPECT_EQ(percentile(v, 1.0), 5);
	EXPECT_EQ(percentile(v, 0.3), 2);  // rank round(1.2) = 1
}

TEST(Percentile, TwoAtOnceAreTheTwoPercentiles)
{
	std::mt19937 rng(3);
	std::uniform_real_distribution<double> u(-5, 5);
	for (std::size_t n : {1u, 2u, 7u, 100u, 3001u})
	{
		std::vector<double> v(n);
		for (auto& x : v) x = u(rng);
		std::vector<double> a = v, b = v, c = v;
		const double lo = percentile(a, 0.05), hi = percentile(b, 0.95);
		EXPECT_EQ(percentiles(c, 0.05, 0.95), std::make_pair(lo, hi)) << n;
		std::sort(v.begin(), v.end());
		const auto rank = [&](double p)
		{ return std::min(n - 1, std::size_t(p * double(n - 1) + 0.5)); };
		EXPECT_EQ(lo, v[rank(0.05)]) << n;
		EXPECT_EQ(hi, v[rank(0.95)]) << n;
	}
}

TEST(Percentile, BucketedAreTheSamePercentiles)
{
	// percentilesOf: the values of percentiles(), `v` unchanged, with ties,
	// a lone outlier (one crowded bucket), all equal, infinities and a NaN
	// (percentiles() on a copy; NaN results compare equal here).
	std::mt19937 rng(5);
	std::uniform_real_distribution<double> u(-5, 5);
	std::vector<double> s[2];
	std::vector<uint8_t> buckets;
	const auto same = [](double a, double b)
	{ return a == b || (std::isnan(a) && std::isnan(b)); };
	const auto check = [&](const std::vector<double>& v, double lo, double hi)
	{
		std::vector<double> c = v;
		const auto expected = percentiles(c, lo, hi);
		const std::vector<double> before = v;
		const auto got = percentilesOf(v, lo, hi, s, buckets);
		EXPECT_TRUE(same(got.first, expected.first)) << v.size();
		EXPECT_TRUE(same(got.second, expected.second)) << v.size();
		EXPECT_EQ(
		    std::memcmp(v.data(), before.data(), v.size() * sizeof(double)), 0);
	};
	for (std::size_t n : {1u, 2u, 3u, 7u, 100u, 470u, 3001u})
	{
		std::vector<double> v(n);
		for (auto& x : v) x = u(rng);
		check(v, 0.05, 0.95);
		check(v, 0.1, 0.1);
		check(v, 0.0, 1.0);
		for (auto& x : v) x = std::round(x);  // ties
		check(v, 0.05, 0.95);
		v[0] = 1e12;  // everything else in the first bucket
		check(v, 0.05, 0.95);
		v[n / 2] = std::numeric_limits<double>::infinity();
		check(v, 0.05, 0.95);
		std::fill(v.begin(), v.end(), 2.5);
		check(v, 0.05, 0.95);
		for (auto& x : v) x = u(rng);
		v[n - 1] = std::numeric_limits<double>::quiet_NaN();
		check(v, 0.05, 0.95);
		check(v, 0.1, 0.1);
	}
}

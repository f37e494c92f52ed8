/* semnav: semantic navigation from tilting-laser sweeps */
// The perception's vector kernels: every build (baseline SSE2, AVX2 where
// the CPU has it) gives the same results bit for bit, and the box sums
// equal OpenCV's box filter.
#include <gtest/gtest.h>
#include <semnav/perception/NormalImage.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/perception/RangeSegmentation.h>
#include <semnav/perception/Roughness.h>

#include <cstring>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "../../libs/perception/src/BoxSum.h"
#include "../../libs/perception/src/SimdKernels.h"
#include "SyntheticScene.h"

using namespace semnav;

namespace
{
Sweep room()
{
	test::SynthScene sc = test::boxRoom(-2, 6, -2.5, 3, 2.7);
	sc.noise = 0.005;
	sc.boxes.push_back({{1.5, -1.5, 0}, {3.1, -0.7, 0.75}, Label::Obstacle});
	return test::renderSweep(sc);
}

bool sameBits(const cv::Mat& a, const cv::Mat& b)
{
	return a.size() == b.size() && a.type() == b.type() &&
	       std::memcmp(a.data, b.data, a.total() * a.elemSize()) == 0;
}

/** Runs f() with the widest kernels and with the baseline ones. */
template <class F>
void bothBuilds(F&& f)
{
	f(false);
	detail::setKernelsBaselineOnly(true);
	EXPECT_STREQ(detail::simdKernels().name, "baseline");
	f(true);
	detail::setKernelsBaselineOnly(false);
}
}  // namespace

TEST(SimdKernels, AllBuildsGiveTheSamePointsAndNormalsBitForBit)
{
	const Sweep sweep = room();
	std::cout << "[ MEASURED ] widest kernels on this CPU: "
	          << detail::simdKernels().name << "\n";
	NormalImage ni[2];
	bothBuilds([&](bool baseline) { ni[baseline].compute(sweep); });
	ASSERT_GT(ni[1].validNormals(), 50000u);
	EXPECT_EQ(ni[0].validNormals(), ni[1].validNormals());
	EXPECT_EQ(ni[0].validPoints(), ni[1].validPoints());
	// (NaN where invalid: compared as bits.)
	EXPECT_TRUE(sameBits(ni[0].points(), ni[1].points()));
	EXPECT_TRUE(sameBits(ni[0].ranges(), ni[1].ranges()));
	EXPECT_TRUE(sameBits(ni[0].pointMask(), ni[1].pointMask()));
	EXPECT_TRUE(sameBits(ni[0].normals(), ni[1].normals()));
	EXPECT_TRUE(sameBits(ni[0].normalMask(), ni[1].normalMask()));
}

TEST(SimdKernels, BoxSumsAreOpenCvsBoxFilterInEveryBuild)
{
	NormalImage ni;
	ni.compute(room());
	cv::Mat mask;
	ni.normalMask().convertTo(mask, CV_32F);
	for (const cv::Mat* src :
	     {&ni.normals(), const_cast<const cv::Mat*>(&mask)})
		for (int k : {1, 2, 5})
		{
			cv::Mat sums[2];
			std::vector<float> tmp;
			bothBuilds([&](bool baseline)
			           { detail::boxSum(*src, k, sums[baseline], tmp); });
			EXPECT_TRUE(sameBits(sums[0], sums[1]))
			    << "channels " << src->channels() << " k " << k;
			cv::Mat ref;
			cv::boxFilter(
			    *src, ref, CV_32F, cv::Size(2 * k + 1, 2 * k + 1),
			    cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
			// (Running sums: rounding differs from OpenCV's in the last
			// bits.)
			EXPECT_LT(cv::norm(sums[1], ref, cv::NORM_INF), 1e-3)
			    << "channels " << src->channels() << " k " << k;
		}
}

TEST(SimdKernels, AllBuildsGiveTheSameRoughnessBitForBit)
{
	const Sweep sweep = room();
	NormalImage ni;
	ni.compute(sweep);
	RangeSegmentation seg;
	seg.compute(sweep);
	Roughness r[2];
	bothBuilds([&](bool baseline) { r[baseline].compute(ni, seg.areaIds()); });
	ASSERT_GT(cv::countNonZero(r[1].r() == r[1].r()), 50000);  // not NaN
	EXPECT_TRUE(sameBits(r[0].r(), r[1].r()));
	EXPECT_TRUE(sameBits(r[0].rBar(), r[1].rBar()));
}

TEST(SimdKernels, AllBuildsGiveTheSameLabelsAndRegions)
{
	const Sweep sweep = room();
	PerceptionPipeline pipeline;
	LabeledSweep out[2];
	bothBuilds([&](bool baseline) { pipeline.process(sweep, out[baseline]); });
	ASSERT_GT(out[1].regions.size(), 5u);
	EXPECT_TRUE(sameBits(out[0].labels, out[1].labels));
	EXPECT_TRUE(sameBits(out[0].regionIds, out[1].regionIds));
	ASSERT_EQ(out[0].regions.size(), out[1].regions.size());
	for (std::size_t i = 0; i < out[0].regions.size(); i++)
		EXPECT_EQ(out[0].regions[i].centroid, out[1].regions[i].centroid);
}

TEST(SimdKernels, DistanceBinsAreFloorOfTheDoubleProductInEveryBuild)
{
	// Distances around bin edges (d * 1000 near integers), far outside the
	// histogram and negative, with a count that leaves a scalar tail.
	std::vector<float> x, y;
	for (int i = 0; i < 1003; i++)
	{
		const float base = -0.2f + 0.0004f * static_cast<float>(i);
		x.push_back(base + (i % 3 == 0 ? 1e-7f : i % 3 == 1 ? -1e-7f : 0.f));
		y.push_back(i % 7 == 0 ? 50.0f : 0.25f * static_cast<float>(i % 5));
	}
	const float mx = 0.8f, my = 0.6f, off = 0.15f;
	std::vector<int> expected(x.size());
	for (std::size_t i = 0; i < x.size(); i++)
	{
		const float d = mx * x[i] + my * y[i] - off;
		const int b = static_cast<int>(std::floor(d * 1000.0)) + 150;
		expected[i] = b >= 0 && b < 300 ? b : 300;
	}
	int inside = 0;
	for (int b : expected) inside += b < 300;
	ASSERT_GT(inside, 100);
	ASSERT_LT(inside, 900);
	bothBuilds(
	    [&](bool)
	    {
		    std::vector<int> bins(x.size(), -1);
		    detail::simdKernels().distanceBins(
		        x.data(), y.data(), static_cast<int>(x.size()), mx, my, off,
		        1000.0, 150, 300, bins.data());
		    EXPECT_EQ(bins, expected) << detail::simdKernels().name;
	    });
}

TEST(SimdKernels, BandBitsAreTheDoubleBandTestInEveryBuild)
{
	// Points across a band of +-6 mm around a line, some exactly on its
	// edges, with a count that is not a multiple of 64.
	std::vector<float> x, y;
	for (int i = 0; i < 1001; i++)
	{
		x.push_back(0.5f + 0.002f * static_cast<float>(i % 97));
		y.push_back(-1.0f + 0.0003f * static_cast<float>(i));
	}
	const double mx = 0.6, my = 0.8, d = -0.3, half = 0.006;
	std::vector<uint64_t> expected((x.size() + 63) / 64, 0);
	int inside = 0;
	for (std::size_t i = 0; i < x.size(); i++)
	{
		const double xi = x[i], yi = y[i];
		if (std::abs(mx * xi + my * yi - d) <= half)
		{
			expected[i / 64] |= uint64_t{1} << (i % 64);
			inside++;
		}
	}
	ASSERT_GT(inside, 20);
	ASSERT_LT(inside, 900);
	bothBuilds(
	    [&](bool)
	    {
		    std::vector<uint64_t> bits(expected.size(), ~uint64_t{0});
		    detail::simdKernels().bandBits(
		        x.data(), y.data(), static_cast<int>(x.size()), mx, my, d, half,
		        bits.data());
		    EXPECT_EQ(bits, expected) << detail::simdKernels().name;
	    });
}

/* semnav: semantic navigation from tilting-laser sweeps */
// The normal kernel's builds (baseline SSE2, AVX2 where the CPU has it)
// give the same normals bit for bit.
#include <gtest/gtest.h>
#include <semnav/perception/NormalImage.h>

#include <cstring>
#include <opencv2/core.hpp>

#include "../../libs/perception/src/NormalKernel.h"
#include "SyntheticScene.h"

using namespace semnav;

TEST(NormalKernel, AllBuildsGiveTheSameNormalsBitForBit)
{
	test::SynthScene sc = test::boxRoom(-2, 6, -2.5, 3, 2.7);
	sc.noise = 0.005;
	sc.boxes.push_back({{1.5, -1.5, 0}, {3.1, -0.7, 0.75}, Label::Obstacle});
	const Sweep sweep = test::renderSweep(sc);

	NormalImage widest, baseline;
	widest.compute(sweep);
	detail::setKernelsBaselineOnly(true);
	EXPECT_FALSE(detail::normalKernelUsesAvx2());
	baseline.compute(sweep);
	detail::setKernelsBaselineOnly(false);
	std::cout << "[ MEASURED ] normal kernel build in use: "
	          << (detail::normalKernelUsesAvx2() ? "AVX2" : "baseline") << "\n";

	ASSERT_GT(baseline.validNormals(), 50000u);
	EXPECT_EQ(widest.validNormals(), baseline.validNormals());
	const cv::Mat& a = widest.normals();
	const cv::Mat& b = baseline.normals();
	ASSERT_EQ(a.size(), b.size());
	EXPECT_EQ(0, std::memcmp(a.data, b.data, a.total() * a.elemSize()));
	EXPECT_EQ(
	    0, cv::norm(widest.normalMask(), baseline.normalMask(), cv::NORM_INF));
}

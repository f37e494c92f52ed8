/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/HaarFeature.h>

#include <map>

#include "CascadeTestUtils.h"

using namespace semnav;

namespace
{
/** Feature type as in OpenCV's generateFeatures comments. */
std::string typeOf(const HaarFeature& f)
{
	const cv::Rect a = f.rects[0].rect, b = f.rects[1].rect;
	const float w1 = f.rects[1].weight;
	const std::string t = f.tilted ? "tilted_" : "";
	if (f.count == 3) return t + "x2_y2";
	if (w1 == 9) return t + "centre";
	const bool xAxis = a.height == b.height;
	const std::string axis = xAxis ? "x" : "y";
	if (w1 == 3) return t + "haar_" + axis + "3";
	// x2 and x4 both have a sub-rectangle half as long: x2's starts one
	// sub-rectangle in (upright) or at the origin (tilted), x4's a quarter.
	bool two;
	if (f.tilted)
		two = a.tl() == b.tl();
	else
		two = xAxis ? b.x - a.x == b.width : b.y - a.y == b.height;
	return t + "haar_" + axis + (two ? "2" : "4");
}
}  // namespace

TEST(HaarFeature, PoolSizesMatchOpenCvTraincascade)
{
	// 24x24 BASIC is the classic Viola-Jones count.
	EXPECT_EQ(generateHaarFeatures({24, 24}, HaarMode::Basic).size(), 162336u);
	EXPECT_EQ(generateHaarFeatures({20, 20}, HaarMode::Basic).size(), 78460u);
	EXPECT_EQ(generateHaarFeatures({20, 20}, HaarMode::Core).size(), 101329u);
	EXPECT_EQ(generateHaarFeatures({20, 20}, HaarMode::All).size(), 125199u);
	for (const auto& f : generateHaarFeatures({20, 20}, HaarMode::All))
		ASSERT_TRUE(f.fitsIn({20, 20}));
}

TEST(HaarFeature, EveryFeatureTypeMatchesBruteForce)
{
	// Every feature of the ALL pool of a 12x14 window, on windows at three
	// places of a random image: integral-image value == pixel-by-pixel sum.
	const cv::Size win(12, 14);
	const auto pool = generateHaarFeatures(win, HaarMode::All);
	const cv::Mat img = test::randomImage({40, 30}, 11);
	const IntegralImages ii(img, true);
	std::map<std::string, int> perType;
	for (const cv::Point o :
	     {cv::Point(0, 0), cv::Point(7, 3), cv::Point(28, 16)})
	{
		const cv::Mat window = img(cv::Rect(o, win));
		for (const auto& f : pool)
		{
			const double ref = f.bruteForce(window);
			// The float result of OpenCV's formula is exact for these
			// integer sums (< 2^24).
			ASSERT_EQ(double(f.evaluate(ii, o)), ref)
			    << typeOf(f) << " rect0 " << f.rects[0].rect << " at " << o;
			perType[typeOf(f)]++;
		}
	}
	// All 14 feature types (8 upright incl. x2_y2 and centre, 6 tilted)
	// were covered.
	for (const char* t :
	     {"haar_x2", "haar_y2", "haar_x3", "haar_y3", "haar_x4", "haar_y4",
	      "x2_y2", "centre", "tilted_haar_x2", "tilted_haar_y2",
	      "tilted_haar_x3", "tilted_haar_y3", "tilted_haar_x4",
	      "tilted_haar_y4"})
		EXPECT_GT(perType[t], 0) << t;
	EXPECT_EQ(perType.size(), 14u);
}

TEST(HaarFeature, ModesAreNested)
{
	const auto basic = generateHaarFeatures({10, 10}, HaarMode::Basic);
	const auto core = generateHaarFeatures({10, 10}, HaarMode::Core);
	const auto all = generateHaarFeatures({10, 10}, HaarMode::All);
	EXPECT_LT(basic.size(), core.size());
	EXPECT_LT(core.size(), all.size());
	for (const auto& f : basic) EXPECT_FALSE(f.tilted);
	std::size_t tilted = 0;
	for (const auto& f : all) tilted += f.tilted;
	EXPECT_EQ(tilted, all.size() - core.size());
}

TEST(HaarFeature, ModeNames)
{
	EXPECT_EQ(haarModeFromName("all"), HaarMode::All);
	EXPECT_EQ(haarModeFromName("BASIC"), HaarMode::Basic);
	EXPECT_EQ(haarModeName(HaarMode::Core), "CORE");
	EXPECT_THROW(haarModeFromName("tilted"), CascadeError);
}

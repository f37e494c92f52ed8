/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/perception/NormalImage.h>
#include <semnav/perception/RangeSegmentation.h>
#include <semnav/perception/Roughness.h>

#include <algorithm>
#include <cmath>

#include "SyntheticScene.h"

using namespace semnav;
using namespace semnav::test;

namespace
{
/** Median of the finite values of `img` over near-floor pixels (range <
 * 3 m) of label l. */
double medianNearFloor(
    const cv::Mat& img, const cv::Mat& truth, const Sweep& sw, Label l)
{
	std::vector<float> v;
	for (int r = 0; r < img.rows; r++)
		for (int c = 0; c < img.cols; c++)
			if (truth.at<uint8_t>(r, c) == static_cast<uint8_t>(l) &&
			    sw.valid(r, c) && sw.range(r, c) < 3.0f &&
			    std::isfinite(img.at<float>(r, c)))
				v.push_back(img.at<float>(r, c));
	if (v.empty()) return NAN;
	std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
	return v[v.size() / 2];
}

struct Computed
{
	Sweep sweep;
	cv::Mat truth;
	NormalImage normals;
	RangeSegmentation segmentation;
	Roughness roughness;
};

void run(Computed& k, const SynthScene& sc, const Roughness::TOptions& o = {})
{
	k.sweep = renderSweep(sc, &k.truth);
	k.normals.compute(k.sweep);
	k.segmentation.compute(k.sweep);
	k.roughness = Roughness(o);
	k.roughness.compute(k.normals, k.segmentation.areaIds());
}
}  // namespace

TEST(Roughness, FlatIsOneBumpyIsLess)
{
	SynthScene flat;
	Computed a;
	run(a, flat);
	// Noise-free flat floor: every dot product is 1.
	EXPECT_NEAR(
	    medianNearFloor(a.roughness.r(), a.truth, a.sweep, Label::Floor), 1.0,
	    1e-4);

	SynthScene bumpy;
	bumpy.height = [](double x, double y)
	{ return 0.03 * std::sin(x * 25) * std::sin(y * 25); };
	bumpy.noise = 0.005;
	Computed b;
	run(b, bumpy);
	flat.noise = 0.005;
	Computed c;
	run(c, flat);
	const double rFlat =
	    medianNearFloor(c.roughness.rBar(), c.truth, c.sweep, Label::Floor);
	const double rBumpy =
	    medianNearFloor(b.roughness.rBar(), b.truth, b.sweep, Label::Floor);
	EXPECT_GT(rFlat, 0.98) << "5 mm noise on a flat floor";
	EXPECT_LT(rBumpy, 0.95);
	EXPECT_LT(rBumpy, rFlat - 0.05);

	// Smoothed normals: the flat floor gets closer to 1, bumps still show.
	Roughness::TOptions o;
	o.smoothNormals = true;
	Computed d;
	run(d, flat, o);
	Computed e;
	run(e, bumpy, o);
	const double sFlat =
	    medianNearFloor(d.roughness.rBar(), d.truth, d.sweep, Label::Floor);
	EXPECT_GE(sFlat, rFlat);
	EXPECT_LT(
	    medianNearFloor(e.roughness.rBar(), e.truth, e.sweep, Label::Floor),
	    sFlat - 0.01);
}

TEST(Roughness, SquareMeansPerGroup)
{
	// 10 x 10 image, squares of 5: group 1 left half, 2 right half, 0 row 0.
	cv::Mat r(10, 10, CV_32F), g(10, 10, CV_32S);
	for (int y = 0; y < 10; y++)
		for (int x = 0; x < 10; x++)
		{
			r.at<float>(y, x) = static_cast<float>(y * 10 + x);
			g.at<int>(y, x) = y == 0 ? 0 : (x < 3 ? 1 : 2);
		}
	r.at<float>(1, 0) = NAN;  // ignored
	cv::Mat out;
	Roughness::squareMeans(r, g, 5, 1, out);
	EXPECT_TRUE(std::isnan(out.at<float>(0, 0)));  // group 0: left out
	// Square (0,0), group 1: rows 1-4, cols 0-2 minus the NaN.
	double s = 0;
	int n = 0;
	for (int y = 1; y < 5; y++)
		for (int x = 0; x < 3; x++)
			if (!(y == 1 && x == 0))
			{
				s += y * 10 + x;
				n++;
			}
	EXPECT_FLOAT_EQ(out.at<float>(2, 1), static_cast<float>(s / n));
	EXPECT_FLOAT_EQ(
	    out.at<float>(1, 0),
	    static_cast<float>(s / n));  // own value NaN, square's not
	// Square (0,0), group 2: rows 1-4, cols 3-4.
	EXPECT_FLOAT_EQ(
	    out.at<float>(4, 4), (13 + 14 + 23 + 24 + 33 + 34 + 43 + 44) / 8.0f);
	// Too few pixels -> NaN.
	Roughness::squareMeans(r, g, 5, 9, out);
	EXPECT_TRUE(std::isnan(out.at<float>(4, 4)));
	EXPECT_FALSE(std::isnan(out.at<float>(2, 1)));
}

TEST(Roughness, BadInput)
{
	NormalImage ni;
	RangeSegmentation seg;
	Roughness rough;
	for (const Sweep& sw : {Sweep(), Sweep(211, 361)})
	{
		ni.compute(sw);
		seg.compute(sw);
		rough.compute(ni, seg.areaIds());
		EXPECT_EQ(rough.r().rows, static_cast<int>(sw.rows()));
		for (int y = 0; y < rough.r().rows; y++)
			for (int x = 0; x < rough.r().cols; x++)
			{
				ASSERT_TRUE(std::isnan(rough.r().at<float>(y, x)));
				ASSERT_TRUE(std::isnan(rough.rBar().at<float>(y, x)));
			}
	}
}

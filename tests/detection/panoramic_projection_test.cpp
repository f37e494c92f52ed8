/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/detection/PanoramicProjection.h>

#include <cmath>
#include <cstring>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

using namespace semnav;

namespace
{
constexpr double kDeg = M_PI / 180.0;
/** The LMS200 grid of the simulator: phi -90..90, theta -15..90, 0.5 deg. */
void grid(std::vector<double>& phis, std::vector<double>& thetas)
{
	for (int c = 0; c <= 360; c++) phis.push_back((-90.0 + 0.5 * c) * kDeg);
	for (int r = 0; r <= 210; r++) thetas.push_back((-15.0 + 0.5 * r) * kDeg);
}
}  // namespace

TEST(PanoramicProjection, StraightAheadIsUnchanged)
{
	std::vector<double> phis, thetas;
	grid(phis, thetas);
	const PanoramicProjection p(phis, thetas);
	ASSERT_EQ(p.size(), cv::Size(361, 211));
	// phi = 0: azimuth 0, elevation = theta.
	for (int r = 0; r < 200; r += 10)  // the pole (90 deg) excluded
	{
		const cv::Vec2f f = p.forward().at<cv::Vec2f>(r, 180);
		EXPECT_NEAR(f[0], 180, 1e-3);
		EXPECT_NEAR(f[1], r, 1e-3);
		EXPECT_NEAR(p.inverseX().at<float>(r, 180), 180, 1e-3);
		EXPECT_NEAR(p.inverseY().at<float>(r, 180), r, 1e-3);
	}
}

TEST(PanoramicProjection, ForwardAndInverseAgree)
{
	std::vector<double> phis, thetas;
	grid(phis, thetas);
	const PanoramicProjection p(phis, thetas);
	int checked = 0;
	// Up to 55 deg elevation (near the pole azimuth is ill-conditioned).
	for (int v = 0; v <= 140; v += 7)
		for (int u = 0; u < 361; u += 7)
		{
			const float x = p.inverseX().at<float>(v, u);
			const float y = p.inverseY().at<float>(v, u);
			if (x < 0) continue;
			// The forward map at the (nearest) source returns close to (u, v).
			const int c = std::min(360, int(std::lround(x)));
			const int r = std::min(210, int(std::lround(y)));
			const cv::Vec2f f = p.forward().at<cv::Vec2f>(r, c);
			EXPECT_NEAR(f[0], u, 1.5) << u << "," << v;
			EXPECT_NEAR(f[1], v, 1.5) << u << "," << v;
			checked++;
		}
	EXPECT_GT(checked, 300);
}

TEST(PanoramicProjection, ObjectsBesideTheRobotAreNotSmeared)
{
	std::vector<double> phis, thetas;
	grid(phis, thetas);
	const PanoramicProjection p(phis, thetas);
	// A sweep column near phi = 80 deg spans all tilt rows; in panoramic
	// coordinates it covers a much smaller elevation range.
	const int c = 340;
	float vmin = 1e9f, vmax = -1e9f;
	for (int r = 0; r < 211; r++)
	{
		const cv::Vec2f f = p.forward().at<cv::Vec2f>(r, c);
		vmin = std::min(vmin, f[1]);
		vmax = std::max(vmax, f[1]);
	}
	EXPECT_LT(vmax - vmin, 211 * 0.25);
	// Labels survive nearest-neighbour resampling unchanged.
	cv::Mat labels(211, 361, CV_16U, cv::Scalar(0));
	labels(cv::Rect(170, 20, 20, 30)).setTo(cv::Scalar(7 | (3 << 8)));
	const cv::Mat pano = p.toPanoramic(labels, cv::INTER_NEAREST);
	double mn, mx;
	cv::minMaxLoc(pano, &mn, &mx);
	EXPECT_EQ(mx, double(7 | (3 << 8)));
	EXPECT_GT(cv::countNonZero(pano), 400);
	// sweepPixelsIn returns the sweep pixels mapped into a box.
	const auto px = p.sweepPixelsIn(cv::Rect2d(170, 20, 20, 30));
	EXPECT_GT(px.size(), 500u);
	for (const auto& q : px)
	{
		const cv::Vec2f f = p.forward().at<cv::Vec2f>(q);
		EXPECT_TRUE(f[0] >= 170 && f[0] < 190 && f[1] >= 20 && f[1] < 50);
	}
	EXPECT_TRUE(p.sameGrid(phis, thetas));
	thetas.back() += 0.01;
	EXPECT_FALSE(p.sameGrid(phis, thetas));
}

TEST(PanoramicProjection, SweepPixelsInFindsEverySourcePixel)
{
	std::vector<double> phis, thetas;
	grid(phis, thetas);
	const PanoramicProjection p(phis, thetas);
	const cv::Mat& fwd = p.forward();
	const auto brute = [&](const cv::Rect2d& b)
	{
		std::vector<cv::Point> out;
		for (int r = 0; r < fwd.rows; r++)
			for (int c = 0; c < fwd.cols; c++)
			{
				const cv::Vec2f f = fwd.at<cv::Vec2f>(r, c);
				if (f[0] >= b.x && f[0] < b.x + b.width && f[1] >= b.y &&
				    f[1] < b.y + b.height)
					out.emplace_back(c, r);
			}
		return out;
	};
	cv::RNG rng(5);
	std::vector<cv::Point> pixels, inner;
	std::size_t found = 0;
	for (int k = 0; k < 200; k++)
	{
		// Boxes anywhere, beside the robot and at the image's edges too.
		const double w = rng.uniform(1.0, 150.0), h = rng.uniform(1.0, 150.0);
		const cv::Rect2d box(
		    rng.uniform(-20.0, 370.0) - w / 2,
		    rng.uniform(-20.0, 220.0) - h / 2, w, h);
		const cv::Rect2d centre(
		    box.x + box.width / 4, box.y + box.height / 4, box.width / 2,
		    box.height / 2);
		const auto expected = brute(box);
		EXPECT_EQ(p.sweepPixelsIn(box), expected) << k;
		p.sweepPixelsIn(box, centre, pixels, inner);
		EXPECT_EQ(pixels, expected) << k;
		EXPECT_EQ(inner, brute(centre)) << k;
		found += expected.size();
	}
	EXPECT_GT(found, 100000u);
}

namespace
{
/** toPanoramic(img, interpolation) gives cv::remap's image with the
 * inverse maps, byte for byte, for random images of each type. */
void expectSameAsRemap(
    const PanoramicProjection& p, int interpolation,
    std::initializer_list<int> types, uint64_t seed, double lo, double hi)
{
	cv::RNG rng(seed);
	for (const int type : types)
	{
		cv::Mat img(211, 361, type);
		rng.fill(img, cv::RNG::UNIFORM, lo, hi);
		cv::Mat expected;
		cv::remap(
		    img, expected, p.inverseX(), p.inverseY(), interpolation,
		    cv::BORDER_CONSTANT, cv::Scalar::all(0));
		const cv::Mat got = p.toPanoramic(img, interpolation);
		ASSERT_EQ(got.type(), type);
		EXPECT_EQ(
		    std::memcmp(got.data, expected.data, got.total() * got.elemSize()),
		    0)
		    << type;
	}
}
}  // namespace

TEST(PanoramicProjection, NearestIsRemapsNearest)
{
	// toPanoramic(INTER_NEAREST) copies nearestSource()'s pixels: the same
	// images as cv::remap with the inverse maps, for every pixel size.
	std::vector<double> phis, thetas;
	grid(phis, thetas);
	const PanoramicProjection p(phis, thetas);
	expectSameAsRemap(
	    p, cv::INTER_NEAREST, {CV_8U, CV_16U, CV_32F, CV_32FC2, CV_64F}, 3, 1,
	    200);
	// Pixels without a source are -1 in the map and 0 in the image.
	double mn, mx;
	cv::minMaxLoc(p.nearestSource(), &mn, &mx);
	EXPECT_EQ(mn, -1);
	EXPECT_LT(mx, 211 * 361);
}

TEST(PanoramicProjection, LinearIsRemapsLinear)
{
	// toPanoramic(INTER_LINEAR) remaps with fixed-point maps made once:
	// the same images as cv::remap with the float inverse maps.
	std::vector<double> phis, thetas;
	grid(phis, thetas);
	const PanoramicProjection p(phis, thetas);
	expectSameAsRemap(
	    p, cv::INTER_LINEAR, {CV_8U, CV_16U, CV_32F, CV_8UC3}, 4, 0, 256);
}

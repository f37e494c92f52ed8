/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/IntegralImages.h>

#include <cstdlib>
#include <opencv2/imgproc.hpp>

#include "CascadeTestUtils.h"

using namespace semnav;

namespace
{
/** The definitions, pixel by pixel. */
int64_t bruteSum(const cv::Mat& m, int X, int Y)
{
	int64_t s = 0;
	for (int y = 0; y < Y; y++)
		for (int x = 0; x < X; x++) s += m.at<uint8_t>(y, x);
	return s;
}
double bruteSqSum(const cv::Mat& m, int X, int Y)
{
	double s = 0;
	for (int y = 0; y < Y; y++)
		for (int x = 0; x < X; x++)
			s += double(m.at<uint8_t>(y, x)) * m.at<uint8_t>(y, x);
	return s;
}
int64_t bruteTilted(const cv::Mat& m, int X, int Y)
{
	int64_t s = 0;
	for (int y = 0; y < Y && y < m.rows; y++)
		for (int x = 0; x < m.cols; x++)
			if (std::abs(x - X + 1) <= Y - y - 1) s += m.at<uint8_t>(y, x);
	return s;
}
}  // namespace

TEST(IntegralImages, MatchBruteForceDefinitions)
{
	for (const cv::Size sz :
	     {cv::Size(1, 1), cv::Size(1, 7), cv::Size(9, 1), cv::Size(13, 5),
	      cv::Size(6, 17), cv::Size(21, 21)})
	{
		const cv::Mat img = test::randomImage(sz, sz.area());
		const IntegralImages ii(img, true);
		ASSERT_EQ(ii.sum().size(), cv::Size(sz.width + 1, sz.height + 1));
		ASSERT_EQ(ii.tilted().size(), ii.sum().size());
		for (int Y = 0; Y <= sz.height; Y++)
			for (int X = 0; X <= sz.width; X++)
			{
				ASSERT_EQ(ii.sum().at<int32_t>(Y, X), bruteSum(img, X, Y))
				    << sz << " at " << X << "," << Y;
				ASSERT_EQ(ii.sqsum().at<double>(Y, X), bruteSqSum(img, X, Y));
				ASSERT_EQ(ii.tilted().at<int32_t>(Y, X), bruteTilted(img, X, Y))
				    << "tilted, " << sz << " at " << X << "," << Y;
			}
	}
}

TEST(IntegralImages, MatchOpenCvIntegral)
{
	for (const cv::Size sz :
	     {cv::Size(2, 3), cv::Size(40, 25), cv::Size(361, 211)})
	{
		const cv::Mat img = test::randomImage(sz, 99 + sz.width);
		const IntegralImages ii(img, true);
		cv::Mat sum, sqsum, tilted;
		cv::integral(img, sum, sqsum, tilted, CV_32S, CV_64F);
		EXPECT_EQ(cv::norm(ii.sum(), sum, cv::NORM_INF), 0) << sz;
		EXPECT_EQ(cv::norm(ii.sqsum(), sqsum, cv::NORM_INF), 0) << sz;
		EXPECT_EQ(cv::norm(ii.tilted(), tilted, cv::NORM_INF), 0) << sz;
	}
}

TEST(IntegralImages, RectangleSumsMatchPixels)
{
	const cv::Mat img = test::randomImage({30, 24}, 5);
	const IntegralImages ii(img, true);
	for (int x = 0; x < 30; x += 3)
		for (int y = 0; y < 24; y += 2)
			for (int w = 1; x + w <= 30; w += 4)
				for (int h = 1; y + h <= 24; h += 5)
				{
					const cv::Rect r(x, y, w, h);
					ASSERT_EQ(ii.rectSum(r), cv::sum(img(r))[0]);
				}
	// 45-degree rectangles: the integral-image corners against the pixel
	// set of IntegralImages::inTiltedRect, and that set against geometry:
	// a w x h tilted rectangle holds 2wh pixels.
	for (int x = 0; x < 30; x++)
		for (int y = 0; y < 24; y++)
			for (int w = 1; w <= 6; w++)
				for (int h = 1; h <= 6; h++)
				{
					const cv::Rect r(x, y, w, h);
					if (x - h < 0 || x + w > 30 || y + w + h > 24) continue;
					int64_t s = 0, n = 0;
					for (int py = 0; py < 24; py++)
						for (int px = 0; px < 30; px++)
							if (IntegralImages::inTiltedRect(r, px, py))
							{
								s += img.at<uint8_t>(py, px);
								n++;
							}
					ASSERT_EQ(ii.tiltedRectSum(r), s) << r;
					ASSERT_EQ(n, 2 * w * h) << r;
				}
}

TEST(IntegralImages, RejectsNonGreyImages)
{
	IntegralImages ii;
	EXPECT_THROW(ii.compute(cv::Mat(4, 4, CV_8UC3)), CascadeError);
	EXPECT_THROW(ii.compute(cv::Mat(4, 4, CV_32F)), CascadeError);
}

TEST(IntegralImages, StridedComputeHasTheSameValues)
{
	// The strided buffers only grow: a large image, then smaller ones
	// (and a continuous compute() in between) keep their values exact.
	IntegralImages strided;
	for (const cv::Size sz :
	     {cv::Size(120, 60), cv::Size(33, 21), cv::Size(119, 60),
	      cv::Size(2, 3)})
	{
		const cv::Mat img = test::randomImage(sz, 7 + sz.width);
		const IntegralImages plain(img, true);
		strided.compute(img, true, 128);
		ASSERT_EQ(strided.sum().size(), plain.sum().size()) << sz;
		EXPECT_EQ(strided.sum().step1(), 128u);
		EXPECT_EQ(strided.tilted().step1(), 128u);
		EXPECT_EQ(strided.sqsum().step1(), 128u);
		EXPECT_EQ(cv::norm(strided.sum(), plain.sum(), cv::NORM_INF), 0) << sz;
		EXPECT_EQ(cv::norm(strided.sqsum(), plain.sqsum(), cv::NORM_INF), 0)
		    << sz;
		EXPECT_EQ(cv::norm(strided.tilted(), plain.tilted(), cv::NORM_INF), 0)
		    << sz;
		// Back to continuous matrices.
		IntegralImages again = strided;
		again.compute(img, false);
		EXPECT_TRUE(again.sum().isContinuous());
		EXPECT_FALSE(again.hasTilted());
		EXPECT_EQ(cv::norm(again.sum(), plain.sum(), cv::NORM_INF), 0) << sz;
	}
	EXPECT_THROW(
	    strided.compute(test::randomImage({128, 4}, 1), true, 128),
	    CascadeError);
}

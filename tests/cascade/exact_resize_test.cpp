/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/ExactResize.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

using namespace semnav;

namespace
{
/** Pixels that differ between ExactResize and cv::resize in `roi`. */
int differing(
    ExactResize& er, const cv::Mat& src, cv::Size size, const cv::Rect& roi)
{
	cv::Mat full, part;
	cv::resize(src, full, size, 0, 0, cv::INTER_LINEAR_EXACT);
	er.resize(src, size, roi, part);
	cv::Mat diff;
	cv::compare(full(roi), part, diff, cv::CMP_NE);
	return cv::countNonZero(diff);
}
}  // namespace

TEST(ExactResize, MatchesOpenCvOnPyramidLevels)
{
	// detectMultiScale's levels (scale 1.1) of band-sized images, whole.
	cv::RNG rng(7);
	ExactResize er;
	std::vector<cv::Size> sizes{{409, 210}, {361, 151}, {902, 75}, {722, 61}};
	for (int i = 0; i < 20; i++)
		sizes.emplace_back(rng.uniform(21, 500), rng.uniform(21, 300));
	for (const cv::Size s : sizes)
	{
		cv::Mat src(s, CV_8UC1);
		rng.fill(src, cv::RNG::UNIFORM, 0, 256);
		for (double f = 1.1; s.width / f > 20 && s.height / f > 20; f *= 1.1)
		{
			const cv::Size sz(cvRound(s.width / f), cvRound(s.height / f));
			EXPECT_EQ(differing(er, src, sz, cv::Rect(cv::Point(), sz)), 0)
			    << s << " -> " << sz;
		}
	}
}

TEST(ExactResize, MatchesOpenCvInRegions)
{
	// Down and up, halving (OpenCV's area path), sizes down to 1, and
	// regions anywhere, including the edges.
	cv::RNG rng(11);
	ExactResize er;
	for (int trial = 0; trial < 400; trial++)
	{
		const cv::Size s(rng.uniform(1, 120), rng.uniform(1, 120));
		cv::Mat src(s, CV_8UC1);
		rng.fill(src, cv::RNG::UNIFORM, 0, 256);
		cv::Size sz(rng.uniform(1, 200), rng.uniform(1, 200));
		if (trial % 10 == 0 && s.width % 2 == 0 && s.height % 2 == 0)
			sz = cv::Size(s.width / 2, s.height / 2);
		if (sz.area() == 0) continue;
		const int x = rng.uniform(0, sz.width), y = rng.uniform(0, sz.height);
		const cv::Rect roi(
		    x, y, rng.uniform(1, sz.width - x + 1),
		    rng.uniform(1, sz.height - y + 1));
		EXPECT_EQ(differing(er, src, sz, roi), 0)
		    << s << " -> " << sz << " in " << roi;
	}
}

TEST(ExactResize, RejectsBadInput)
{
	ExactResize er;
	cv::Mat out;
	const cv::Mat grey(10, 10, CV_8UC1, cv::Scalar(1));
	EXPECT_THROW(
	    er.resize(cv::Mat(10, 10, CV_32F), {5, 5}, {0, 0, 5, 5}, out),
	    CascadeError);
	EXPECT_THROW(er.resize(grey, {5, 5}, {1, 1, 5, 5}, out), CascadeError);
}

/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/detection/DetectionImage.h>
#include <semnav/perception/NormalImage.h>

#include <opencv2/imgproc.hpp>
#include <random>

using namespace semnav;

namespace
{
/** 3 x 4 normals: floor, wall facing the robot, left wall, none. */
void sample(cv::Mat& n, cv::Mat& m)
{
	n = cv::Mat(3, 4, CV_32FC3, cv::Scalar::all(0));
	m = cv::Mat(3, 4, CV_8U, cv::Scalar(1));
	for (int r = 0; r < 3; r++)
	{
		n.at<cv::Vec3f>(r, 0) = {0, 0, 1};   // up: floor
		n.at<cv::Vec3f>(r, 1) = {-1, 0, 0};  // toward the robot
		n.at<cv::Vec3f>(r, 2) = {0, -1, 0};  // wall on the left
		m.at<uint8_t>(r, 3) = 0;
	}
}
}  // namespace

TEST(DetectionImage, ChannelsOfTheNormalImage)
{
	cv::Mat n, m;
	sample(n, m);
	const cv::Mat red =
	    DetectionImage::fromNormals(n, m, DetectionChannel::Red);
	const cv::Mat green =
	    DetectionImage::fromNormals(n, m, DetectionChannel::Green);
	const cv::Mat blue =
	    DetectionImage::fromNormals(n, m, DetectionChannel::Blue);
	const cv::Mat grey =
	    DetectionImage::fromNormals(n, m, DetectionChannel::Grey);
	ASSERT_EQ(red.type(), CV_8UC1);
	for (int c = 0; c < 3; c++)
	{
		const cv::Vec3b rgb = NormalImage::rgbOf(n.at<cv::Vec3f>(0, c));
		EXPECT_EQ(red.at<uint8_t>(1, c), rgb[0]);
		EXPECT_EQ(green.at<uint8_t>(1, c), rgb[1]);
		EXPECT_EQ(blue.at<uint8_t>(1, c), rgb[2]);
		cv::Mat px(1, 1, CV_8UC3, cv::Scalar(rgb[2], rgb[1], rgb[0])), g;
		cv::cvtColor(px, g, cv::COLOR_BGR2GRAY);
		EXPECT_EQ(grey.at<uint8_t>(1, c), g.at<uint8_t>(0, 0));
	}
	EXPECT_EQ(blue.at<uint8_t>(0, 0), 255);  // floor: blue
	EXPECT_EQ(green.at<uint8_t>(0, 1), 1);   // facing the robot: purple
	EXPECT_EQ(red.at<uint8_t>(0, 2), 255);   // left wall: pink
	for (const cv::Mat& img : {red, green, blue, grey})
		EXPECT_EQ(img.at<uint8_t>(1, 3), 0) << "no normal: black";
}

TEST(DetectionImage, SmoothingAveragesNeighbourNormals)
{
	cv::Mat n(5, 5, CV_32FC3, cv::Scalar::all(0)),
	    m(5, 5, CV_8U, cv::Scalar(1));
	for (int r = 0; r < 5; r++)
		for (int c = 0; c < 5; c++) n.at<cv::Vec3f>(r, c) = {-1, 0, 0};
	n.at<cv::Vec3f>(2, 2) = {0, 0, 1};  // one noisy normal
	const cv::Mat raw =
	    DetectionImage::fromNormals(n, m, DetectionChannel::Blue, 0);
	const cv::Mat smooth =
	    DetectionImage::fromNormals(n, m, DetectionChannel::Blue, 1);
	EXPECT_EQ(raw.at<uint8_t>(2, 2), 255);
	EXPECT_LT(smooth.at<uint8_t>(2, 2), 160);  // mostly the 8 neighbours
	EXPECT_EQ(smooth.at<uint8_t>(0, 4), raw.at<uint8_t>(0, 4));
	// The input normals are left alone: the same call, the same image.
	EXPECT_EQ(n.at<cv::Vec3f>(2, 2), cv::Vec3f(0, 0, 1));
	const cv::Mat again =
	    DetectionImage::fromNormals(n, m, DetectionChannel::Blue, 1);
	EXPECT_EQ(cv::norm(smooth, again, cv::NORM_INF), 0);
}

TEST(DetectionImage, NamesAndErrors)
{
	EXPECT_EQ(channelFromName("green"), DetectionChannel::Green);
	EXPECT_EQ(channelName(DetectionChannel::Grey), "grey");
	EXPECT_THROW(channelFromName("gray"), ConfigError);
	EXPECT_THROW(
	    DetectionImage::fromNormals(
	        cv::Mat(2, 2, CV_32FC1), cv::Mat(2, 2, CV_8U),
	        DetectionChannel::Grey),
	    Error);
}

TEST(DetectionImage, ChannelsAreNormalImageRgbBitForBit)
{
	// Every component value whose 128 + 127 v lies at or next to a
	// rounding midpoint (k + 0.5 and its float neighbours), at the clamp
	// limits and beyond, against NormalImage::rgbOf.
	std::vector<float> vs{-2.f, -1.f, -1.0039f, 0.f, -0.f, 1.f, 1.0039f, 2.f};
	for (int k = -2; k <= 257; k++)
	{
		const float v = (k + 0.5f - 128.0f) / 127.0f;
		vs.push_back(v);
		vs.push_back(std::nextafter(v, 2.f));
		vs.push_back(std::nextafter(v, -2.f));
	}
	std::mt19937 g(3);
	std::uniform_real_distribution<float> u(-1.f, 1.f);
	for (int i = 0; i < 2000; i++) vs.push_back(u(g));
	const int n = static_cast<int>(vs.size());
	cv::Mat normals(3, n, CV_32FC3);
	for (int c = 0; c < n; c++)
	{
		// Each value in every component (other components vary too).
		normals.at<cv::Vec3f>(0, c) = {vs[c], vs[(c + 1) % n], vs[(c + 2) % n]};
		normals.at<cv::Vec3f>(1, c) = {vs[(c + 2) % n], vs[c], vs[(c + 1) % n]};
		normals.at<cv::Vec3f>(2, c) = {vs[(c + 1) % n], vs[(c + 2) % n], vs[c]};
	}
	const cv::Mat mask(normals.size(), CV_8U, cv::Scalar(1));
	const cv::Mat red = DetectionImage::fromSmoothedNormals(
	    normals, mask, DetectionChannel::Red);
	const cv::Mat green = DetectionImage::fromSmoothedNormals(
	    normals, mask, DetectionChannel::Green);
	const cv::Mat blue = DetectionImage::fromSmoothedNormals(
	    normals, mask, DetectionChannel::Blue);
	std::size_t mismatches = 0;
	for (int r = 0; r < normals.rows; r++)
		for (int c = 0; c < n; c++)
		{
			const cv::Vec3b rgb =
			    NormalImage::rgbOf(normals.at<cv::Vec3f>(r, c));
			mismatches += red.at<uint8_t>(r, c) != rgb[0];
			mismatches += green.at<uint8_t>(r, c) != rgb[1];
			mismatches += blue.at<uint8_t>(r, c) != rgb[2];
		}
	EXPECT_EQ(mismatches, 0u);
}

TEST(DetectionImage, GreyIsCvtColorOfTheRgbBitForBit)
{
	// The grey channel is made without the colour image, with
	// cv::cvtColor's 8-bit fixed point: first that formula for every
	// colour, then the channel on random normals against cvtColor.
	cv::Mat all(4096, 4096, CV_8UC3);
	for (int i = 0; i < (1 << 24); i++)
		all.at<cv::Vec3b>(i) = {
		    uint8_t(i & 255), uint8_t((i >> 8) & 255), uint8_t(i >> 16)};
	cv::Mat grey;
	cv::cvtColor(all, grey, cv::COLOR_BGR2GRAY);
	std::size_t formula = 0;
	for (int i = 0; i < (1 << 24); i++)
	{
		const cv::Vec3b p = all.at<cv::Vec3b>(i);
		formula +=
		    grey.at<uint8_t>(i) !=
		    ((p[0] * 3735 + p[1] * 19235 + p[2] * 9798 + (1 << 14)) >> 15);
	}
	EXPECT_EQ(formula, 0u);
	std::mt19937 g(5);
	std::uniform_real_distribution<float> u(-1.05f, 1.05f);
	cv::Mat normals(300, 400, CV_32FC3), mask(300, 400, CV_8U);
	for (int i = 0; i < 300 * 400; i++)
	{
		normals.at<cv::Vec3f>(i) = {u(g), u(g), u(g)};
		mask.at<uint8_t>(i) = (i % 7) != 0;
	}
	cv::Mat bgr(normals.size(), CV_8UC3, cv::Scalar::all(0)), expected;
	for (int i = 0; i < 300 * 400; i++)
		if (mask.at<uint8_t>(i))
		{
			const cv::Vec3b rgb = NormalImage::rgbOf(normals.at<cv::Vec3f>(i));
			bgr.at<cv::Vec3b>(i) = {rgb[2], rgb[1], rgb[0]};
		}
	cv::cvtColor(bgr, expected, cv::COLOR_BGR2GRAY);
	const cv::Mat got = DetectionImage::fromSmoothedNormals(
	    normals, mask, DetectionChannel::Grey);
	EXPECT_EQ(cv::countNonZero(got != expected), 0);
}

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/cascade/NegativeImage.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>
#include <vector>

namespace semnav::test
{
/** Random 8-bit image. */
inline cv::Mat randomImage(cv::Size sz, uint64_t seed)
{
	std::mt19937_64 g(seed);
	cv::Mat m(sz, CV_8UC1);
	for (int y = 0; y < sz.height; y++)
		for (int x = 0; x < sz.width; x++)
			m.at<uint8_t>(y, x) = static_cast<uint8_t>(g() & 0xff);
	return m;
}

/** A synthetic "object": a bright horizontal bar over a dark vertical post
 * on a noisy mid-grey background, jittered in position and size. */
inline cv::Mat syntheticPositive(cv::Size win, std::mt19937_64& g)
{
	std::uniform_int_distribution<int> noise(-12, 12), jitter(-1, 1);
	cv::Mat m(win, CV_8UC1);
	for (int y = 0; y < win.height; y++)
		for (int x = 0; x < win.width; x++)
			m.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(120 + noise(g));
	const int w = win.width, h = win.height;
	const int dx = jitter(g), dy = jitter(g);
	cv::rectangle(
	    m, cv::Rect(w / 6 + dx, h / 5 + dy, 2 * w / 3, h / 5), cv::Scalar(230),
	    cv::FILLED);
	cv::rectangle(
	    m, cv::Rect(w / 2 - w / 8 + dx, 2 * h / 5 + dy, w / 4, h / 2),
	    cv::Scalar(30), cv::FILLED);
	return m;
}

/** Background clutter: random rectangles and gradients. */
inline cv::Mat syntheticBackground(cv::Size sz, std::mt19937_64& g)
{
	std::uniform_int_distribution<int> grey(0, 255), noise(-12, 12);
	cv::Mat m(sz, CV_8UC1, cv::Scalar(grey(g)));
	for (int i = 0; i < 25; i++)
	{
		std::uniform_int_distribution<int> px(0, sz.width - 1),
		    py(0, sz.height - 1);
		const cv::Point a(px(g), py(g)), b(px(g), py(g));
		cv::rectangle(m, cv::Rect(a, b), cv::Scalar(grey(g)), cv::FILLED);
	}
	// Near misses: the object's bar or post alone.
	for (int i = 0; i < 6; i++)
	{
		std::uniform_int_distribution<int> px(0, sz.width - 12),
		    py(0, sz.height - 12), len(4, 12);
		const cv::Point a(px(g), py(g));
		if (i % 2)
			cv::rectangle(
			    m, cv::Rect(a.x, a.y, len(g), 2 + i % 3), cv::Scalar(230),
			    cv::FILLED);
		else
			cv::rectangle(
			    m, cv::Rect(a.x, a.y, 2 + i % 3, len(g)), cv::Scalar(30),
			    cv::FILLED);
	}
	for (int y = 0; y < sz.height; y++)
		for (int x = 0; x < sz.width; x++)
			m.at<uint8_t>(y, x) =
			    cv::saturate_cast<uint8_t>(m.at<uint8_t>(y, x) + noise(g));
	return m;
}

/** A tiny training set: `n` positives of size `win` and a few clutter
 * images. */
inline void syntheticTrainingSet(
    cv::Size win, int n, std::vector<cv::Mat>& pos,
    std::vector<NegativeImage>& neg, uint64_t seed = 7)
{
	std::mt19937_64 g(seed);
	for (int i = 0; i < n; i++) pos.push_back(syntheticPositive(win, g));
	for (int i = 0; i < 6; i++)
		neg.push_back({syntheticBackground({120, 90}, g), {}});
}

/** OpenCV's shipped cascades (Debian package opencv-data), or "". */
inline std::string openCvCascade(const std::string& name)
{
	for (const char* dir :
	     {"/usr/share/opencv4/haarcascades/",
	      "/usr/share/opencv/haarcascades/"})
	{
		const std::string p = std::string(dir) + name;
		if (std::filesystem::exists(p)) return p;
	}
	return "";
}

}  // namespace semnav::test

#include <semnav/cascade/CascadeTrainer.h>

namespace semnav::test
{
/** Options for tiny, fast training runs in tests. */
inline CascadeTrainer::TOptions tinyTrainerOptions(cv::Size win = {12, 12})
{
	CascadeTrainer::TOptions o;
	o.windowWidth = win.width;
	o.windowHeight = win.height;
	o.numStages = 4;
	o.negativesPerStage = 150;
	o.maxWeakCount = 20;
	o.minNegatives = 20;
	o.targetFalseAlarm = 1e-9;  // stop on stage count or exhaustion
	return o;
}
}  // namespace semnav::test

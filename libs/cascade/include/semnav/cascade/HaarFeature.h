/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/cascade/IntegralImages.h>

#include <array>
#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** Which Haar-like features a trainer may use, as opencv_traincascade's
 * -mode: BASIC = Viola-Jones (edge x2/y2, line x3/y3, diagonal 2x2),
 * CORE = BASIC + x4/y4 lines and the 3x3 centre-surround, ALL = CORE +
 * Lienhart-Maydt 45-degree rotated features. */
enum class HaarMode
{
	Basic,
	Core,
	All
};

/** "BASIC", "CORE" or "ALL". */
const std::string& haarModeName(HaarMode m);
/** Parses "BASIC", "CORE", "ALL" (case-insensitive); throws CascadeError. */
HaarMode haarModeFromName(const std::string& name);

/** One Haar-like feature in OpenCV's layout: up to three weighted
 * rectangles in window coordinates, upright or all 45-degree tilted
 * (Lienhart's notation, see IntegralImages::tiltedRectSum()). Its value is
 * sum_i weight_i * (pixel sum of rect_i), computed in float as OpenCV's
 * HaarEvaluator::OptFeature::calc(). */
struct HaarFeature
{
	struct WeightedRect
	{
		cv::Rect rect;
		float weight = 0;
	};
	std::array<WeightedRect, 3> rects{};
	/** Number of rectangles in use (2 or 3). */
	int count = 0;
	bool tilted = false;

	/** The feature's value in the window at `origin` of the integral
	 * images, not normalised (float arithmetic as OpenCV). */
	float evaluate(const IntegralImages& ii, cv::Point origin = {}) const;

	/** The same value by summing pixels of `window` (CV_8U) one by one: the
	 * reference for tests. Computed in double. */
	double bruteForce(const cv::Mat& window) const;

	/** True when every rectangle lies inside a window of size `win`. */
	bool fitsIn(cv::Size win) const;

	bool operator==(const HaarFeature& o) const;
};

/** The feature pool of opencv_traincascade (CvHaarEvaluator::
 * generateFeatures) for window `win` and `mode`, in the same order, with
 * the same rectangles and weights. */
std::vector<HaarFeature> generateHaarFeatures(cv::Size win, HaarMode mode);

}  // namespace semnav

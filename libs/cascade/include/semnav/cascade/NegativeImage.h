/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/cascade/RangeGate.h>

#include <opencv2/core/mat.hpp>
#include <vector>

namespace semnav
{
/** An image negative training windows are drawn from: the 8-bit image as
 * the detector sees it, boxes of objects of the class being trained
 * (windows overlapping one of them too much are not negatives), and the
 * pyramid scales the detector searches in it. */
struct NegativeImage
{
	cv::Mat image;
	std::vector<cv::Rect> exclude;
	/** Pyramid scales (window side / training window side) used; maxScale
	 * 0 = up to the image size. */
	double minScale = 1.0, maxScale = 0.0;
	/** Optional (empty: every window): the range of each pixel (CV_32F,
	 * the image's size, 0 = none). Only windows whose range passes `gate`
	 * for their side are negatives, as the detector searches only those
	 * (pyramid levels get the range resized to nearest, windows the
	 * RangeGate::windowRange of it). */
	cv::Mat range;
	RangeGate gate;
};

}  // namespace semnav

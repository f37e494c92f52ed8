/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

namespace semnav
{
/** One cv::CascadeClassifier::detectMultiScale run over a band of rows of
 * a detection image, scaled by `upscale`, for objects (window sides, in
 * detection-image pixels) in [minSide, maxSide]. A class uses a "near"
 * pass over the image and optionally a "far" pass: small objects are far,
 * so near the horizon, and only that band is upscaled further (a
 * wastebasket 3 m away is about 11 x 14 pixels, below the 20 x 20 window).
 * Training scales its samples and negatives with the same passes. */
struct DetectionPass
{
	double upscale = 1.0;
	/** Rows [rowBegin, rowEnd) of the detection image. */
	int rowBegin = 0, rowEnd = 0;
	/** Object side range in detection-image pixels; maxSide 0 = none. */
	double minSide = 0, maxSide = 0;

	bool covers(double side) const
	{
		return side >= minSide && (maxSide <= 0 || side <= maxSide);
	}
	/** The band, upscaled (INTER_LINEAR, as for detection). */
	cv::Mat apply(const cv::Mat& image) const;
	/** A box of the upscaled band -> detection-image pixels. */
	cv::Rect toImage(const cv::Rect& r) const;
	/** A box of the detection image -> the upscaled band. */
	cv::Rect toPass(const cv::Rect& r) const;

	/** The pass covering `side`, else the one whose range is nearest. */
	static const DetectionPass& forSide(
	    const std::vector<DetectionPass>& passes, double side);
};

}  // namespace semnav

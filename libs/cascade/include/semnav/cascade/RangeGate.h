/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <algorithm>
#include <opencv2/core/mat.hpp>

namespace semnav
{
/** Which cascade windows can hold an object of a class, from the range
 * of each pixel: an object's metric size fixes its pixel size. A window of
 * side `side` pixels whose centre is at range r (m) holds an object of
 * larger side r x side / perSide (m), where perSide = 1.15 x upscale / step
 * (the training window is the object's larger side + 15 %, the image is
 * upscaled by `upscale` and its pixels are `step` rad apart); that size must
 * lie within [lo, hi], or [loCut, hi] closer than cutRange (an object cut
 * by the lowest tilt line shows only its top). The detector evaluates only
 * such windows (CascadeDetector, range_scales) and the trainer draws its
 * negatives only from them (NegativeImage::range), so the cascade learns
 * the windows it will see. */
struct RangeGate
{
	double perSide = 1, lo = 0, loCut = 0, hi = 1e9, cutRange = 0;

	/** Whether a window of `side` pixels at range `r` passes (r <= 0: no
	 * range, never). */
	bool accepts(float r, double side) const
	{
		if (!(r > 0)) return false;
		const double s = r * side / perSide;
		return s <= hi && s >= (r < cutRange ? loCut : lo);
	}

	/** The range of the window of size `win` at top-left (x, y) of
	 * `range` (CV_32F, 0 = none): the nearest of five samples in its
	 * central half (its centre and a quarter of its side left, right,
	 * above and below it); 0 when none has a range. */
	static float windowRange(const cv::Mat& range, int x, int y, cv::Size win)
	{
		const int cx = x + win.width / 2, cy = y + win.height / 2;
		const int qx = win.width / 4, qy = win.height / 4;
		const int dx[5] = {0, -qx, qx, 0, 0}, dy[5] = {0, 0, 0, -qy, qy};
		float r = 0;
		for (int i = 0; i < 5; i++)
		{
			const float v = range.at<float>(
			    std::clamp(cy + dy[i], 0, range.rows - 1),
			    std::clamp(cx + dx[i], 0, range.cols - 1));
			if (v > 0 && (r == 0 || v < r)) r = v;
		}
		return r;
	}
};

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
// Internal: Haar features compiled to offsets into integral images of a
// given row stride, as OpenCV's HaarEvaluator::OptFeature.
#pragma once

#include <semnav/cascade/HaarFeature.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace semnav::detail
{
/** Offsets of the four corners of each rectangle relative to a window's
 * top-left entry of the sum (upright) or tilted integral image. */
struct CompiledFeature
{
	int ofs[3][4] = {};
	float weight[3] = {0, 0, 0};
	bool tilted = false;

	CompiledFeature() = default;
	CompiledFeature(const HaarFeature& f, int stride)
	{
		tilted = f.tilted;
		for (int i = 0; i < 3; i++)
		{
			const cv::Rect r = i < f.count ? f.rects[i].rect : cv::Rect();
			weight[i] = i < f.count ? f.rects[i].weight : 0.0f;
			if (!tilted)
			{
				// CV_SUM_OFS: (x, y), (x + w, y), (x, y + h), (x + w, y + h)
				ofs[i][0] = r.x + stride * r.y;
				ofs[i][1] = r.x + r.width + stride * r.y;
				ofs[i][2] = r.x + stride * (r.y + r.height);
				ofs[i][3] = r.x + r.width + stride * (r.y + r.height);
			}
			else
			{
				// CV_TILTED_OFS: (x, y), (x - h, y + h), (x + w, y + w),
				// (x + w - h, y + w + h)
				ofs[i][0] = r.x + stride * r.y;
				ofs[i][1] = r.x - r.height + stride * (r.y + r.height);
				ofs[i][2] = r.x + r.width + stride * (r.y + r.width);
				ofs[i][3] = r.x + r.width - r.height +
				            stride * (r.y + r.width + r.height);
			}
		}
	}

	static int sumAt(const int32_t* p, const int* o)
	{
		return p[o[0]] - p[o[1]] - p[o[2]] + p[o[3]];
	}

	/** OpenCV's OptFeature::calc: `sum` and `tilt` point at the window's
	 * top-left entry of the sum and tilted integral images. */
	float calc(const int32_t* sum, const int32_t* tilt) const
	{
		const int32_t* p = tilted ? tilt : sum;
		float ret = weight[0] * static_cast<float>(sumAt(p, ofs[0])) +
		            weight[1] * static_cast<float>(sumAt(p, ofs[1]));
		if (weight[2] != 0.0f)
			ret += weight[2] * static_cast<float>(sumAt(p, ofs[2]));
		return ret;
	}
};

/** OpenCV's HaarEvaluator::setWindow variance test: the normalisation
 * factor 1 / sqrt(area * sqsum - sum^2) over the window shrunk by one pixel
 * on each side; false (window skipped) when that is not positive or the
 * standard deviation is <= 10 grey levels. */
inline bool varianceNormFactor(
    const int32_t* sum, const double* sqsum, int sumStride, int sqStride,
    cv::Size win, float& nf)
{
	const int x0 = 1, y0 = 1, x1 = win.width - 1, y1 = win.height - 1;
	const int valsum = sum[y0 * sumStride + x0] - sum[y0 * sumStride + x1] -
	                   sum[y1 * sumStride + x0] + sum[y1 * sumStride + x1];
	const double valsqsum =
	    sqsum[y0 * sqStride + x0] - sqsum[y0 * sqStride + x1] -
	    sqsum[y1 * sqStride + x0] + sqsum[y1 * sqStride + x1];
	const double area = double(win.width - 2) * double(win.height - 2);
	double v = area * valsqsum - double(valsum) * valsum;
	if (v > 0.)
	{
		v = std::sqrt(v);
		nf = static_cast<float>(1. / v);
		return area * nf < 1e-1;
	}
	nf = 1.f;
	return false;
}

/** OpenCV's THRESHOLD_EPS, subtracted from every stage threshold on load. */
constexpr float kStageThresholdEps = 1e-5f;

}  // namespace semnav::detail

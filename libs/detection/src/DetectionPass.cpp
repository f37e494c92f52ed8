/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/detection/DetectionPass.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace semnav
{
cv::Mat DetectionPass::apply(const cv::Mat& image) const
{
	const cv::Mat band =
	    image.rowRange(std::max(0, rowBegin), std::min(image.rows, rowEnd));
	if (upscale == 1.0) return band;
	cv::Mat out;
	cv::resize(band, out, cv::Size(), upscale, upscale, cv::INTER_LINEAR);
	return out;
}

cv::Rect DetectionPass::toImage(const cv::Rect& r) const
{
	const int x0 = static_cast<int>(std::floor(r.x / upscale));
	const int y0 = static_cast<int>(std::floor(r.y / upscale));
	const int x1 = static_cast<int>(std::ceil((r.x + r.width) / upscale));
	const int y1 = static_cast<int>(std::ceil((r.y + r.height) / upscale));
	return cv::Rect(x0, y0 + rowBegin, x1 - x0, y1 - y0);
}

cv::Rect DetectionPass::toPass(const cv::Rect& r) const
{
	const int x0 = static_cast<int>(std::floor(r.x * upscale));
	const int y0 = static_cast<int>(std::floor((r.y - rowBegin) * upscale));
	const int x1 = static_cast<int>(std::ceil((r.x + r.width) * upscale));
	const int y1 =
	    static_cast<int>(std::ceil((r.y + r.height - rowBegin) * upscale));
	return cv::Rect(x0, y0, x1 - x0, y1 - y0);
}

const DetectionPass& DetectionPass::forSide(
    const std::vector<DetectionPass>& passes, double side)
{
	if (passes.empty()) throw Error("DetectionPass::forSide: no pass");
	const DetectionPass* best = &passes.front();
	double bestGap = std::numeric_limits<double>::infinity();
	for (const auto& p : passes)
	{
		if (p.covers(side)) return p;
		const double gap = side < p.minSide
		                       ? p.minSide / side
		                       : (p.maxSide > 0 ? side / p.maxSide : 1.0);
		if (gap < bestGap)
		{
			bestGap = gap;
			best = &p;
		}
	}
	return *best;
}

}  // namespace semnav

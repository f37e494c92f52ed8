/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <opencv2/core/types.hpp>

namespace semnav
{
/** Intersection over union of two image boxes; 0 when both are empty. */
inline double boxIou(const cv::Rect& a, const cv::Rect& b)
{
	const double i = (a & b).area();
	const double u = double(a.area()) + double(b.area()) - i;
	return u > 0 ? i / u : 0.0;
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticMap::insert(), door sightings: where along its wall a wide door
// region is (DoorSighting.h).
#include "DoorSighting.h"

#include <semnav/perception/LabeledSweep.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace semnav
{
mrpt::math::TPoint3D doorRegionMiddle(
    const LabeledSweep& ls, const LabeledRegion& reg, double share)
{
	const mrpt::math::TPoint3D box(
	    0.5 * (reg.minCorner.x + reg.maxCorner.x),
	    0.5 * (reg.minCorner.y + reg.maxCorner.y), reg.centroid.z);
	const double nn = std::hypot(reg.meanNormal.x, reg.meanNormal.y);
	if (share <= 0 || nn < 1e-6 || ls.points.empty() || ls.regionIds.empty())
		return box;
	// Along the wall: horizontal and across the normal.
	const double tx = -reg.meanNormal.y / nn, ty = reg.meanNormal.x / nn;
	const double s0 = reg.centroid.x * tx + reg.centroid.y * ty;
	// Columns 5 cm wide along the wall, each with its lowest and highest
	// point.
	constexpr double kColumn = 0.05;
	const double half = 0.5 * reg.width + 2 * kColumn;
	const int n = static_cast<int>(std::ceil(2 * half / kColumn)) + 1;
	std::vector<float> lo(n, std::numeric_limits<float>::infinity());
	std::vector<float> hi(n, -std::numeric_limits<float>::infinity());
	const cv::Rect b =
	    reg.imageBox & cv::Rect(0, 0, ls.regionIds.cols, ls.regionIds.rows);
	for (int r = b.y; r < b.y + b.height; r++)
		for (int c = b.x; c < b.x + b.width; c++)
		{
			if (ls.regionIds.at<int32_t>(r, c) != reg.id) continue;
			const auto& p = ls.points.at<cv::Vec3f>(r, c);
			if (!std::isfinite(p[0])) continue;
			const int k = static_cast<int>(
			    std::floor((p[0] * tx + p[1] * ty - s0 + half) / kColumn));
			if (k < 0 || k >= n) continue;
			lo[k] = std::min(lo[k], p[2]);
			hi[k] = std::max(hi[k], p[2]);
		}
	const float least = static_cast<float>(share * reg.height);
	int first = -1, last = -1;
	for (int k = 0; k < n; k++)
		if (hi[k] - lo[k] >= least)
		{
			if (first < 0) first = k;
			last = k;
		}
	if (first < 0) return box;
	const double s = 0.5 * (first + last + 1) * kColumn - half;
	return {reg.centroid.x + s * tx, reg.centroid.y + s * ty, reg.centroid.z};
}

}  // namespace semnav

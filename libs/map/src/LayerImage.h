/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <limits>
#include <opencv2/core.hpp>
#include <string>

namespace semnav
{
/** Decodes one image of a map directory (`bytes`, read from `path`): a
 * single-channel PFM for CV_32FC1, else a grey PNG of 8 (CV_8UC1) or 16
 * bits (CV_16UC1). The header is checked against the `cols` x `rows` of
 * map.yaml before anything is allocated; throws IoError naming `path` on
 * any mismatch or corruption, and neither OpenCV nor libpng prints. */
cv::Mat decodeLayerImage(
    const std::string& bytes, const std::string& path, int type, int cols,
    int rows);

/** The values a float layer may hold: [lowest, highest], and NaN when
 * `nanMeansNoData`. */
struct LayerRange
{
	float lowest = 0;
	float highest = std::numeric_limits<float>::max();
	bool nanMeansNoData = false;
};

/** Throws IoError naming `path` and the first pixel (column, row of the
 * image) whose value is outside `range` (NaN, infinite, negative...). */
void checkLayerValues(
    const cv::Mat& img, const std::string& path, const LayerRange& range);

}  // namespace semnav

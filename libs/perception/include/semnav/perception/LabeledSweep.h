/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Label.h>
#include <semnav/perception/Detection.h>
#include <semnav/perception/LabeledRegion.h>

#include <cstddef>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <vector>

namespace semnav
{
/** Everything perception knows about one sweep: per-pixel label, area and
 * region, normals and roughness, the regions' statistics and (filled by a
 * later detector stage) object detections. All images have the sweep's
 * layout (rows = tilt lines, row 0 lowest; col 0 = the robot's right). */
class LabeledSweep
{
public:
	/** Index of the sweep in its log. */
	std::size_t sweepIndex = 0;
	/** Label id per pixel (Label enum value), CV_8U; Unknown where the
	 * range is invalid. */
	cv::Mat labels;
	/** Segmentation area per pixel (RangeSegmentation), CV_32S, 0 = none. */
	cv::Mat areaIds;
	/** Region per pixel (index into `regions`), CV_32S, -1 = none. */
	cv::Mat regionIds;
	/** CV_8U, 1 where the range is valid (the pixels that are scored). */
	cv::Mat validMask;
	/** Robot-frame points, CV_32FC3, NaN where invalid. */
	cv::Mat points;
	/** Unit normals CV_32FC3 and their mask CV_8U (NormalImage). */
	cv::Mat normals, normalMask;
	/** Roughness R and R-bar per pixel, CV_32F, NaN where undefined. */
	cv::Mat roughness, roughnessBar;
	std::vector<LabeledRegion> regions;
	/** Objects found by detectors (empty after the rule classifier). */
	std::vector<Detection> detections;

	/** Ground height used by the classifier (robot frame z, m). */
	double groundZ = 0;
	/** True when groundZ was estimated from the sweep (else configured). */
	bool groundEstimated = false;
	/** Mean ceiling height, when a ceiling was found. */
	std::optional<double> ceilingZ;
	/** True when the ground was taken as indoor floor (a ceiling seen or
	 * configured), false when it was split into sidewalk and grass. */
	bool indoor = true;

	std::size_t rows() const { return static_cast<std::size_t>(labels.rows); }
	std::size_t cols() const { return static_cast<std::size_t>(labels.cols); }
	Label label(std::size_t r, std::size_t c) const
	{
		return static_cast<Label>(
		    labels.at<uint8_t>(static_cast<int>(r), static_cast<int>(c)));
	}
	/** Pixels with label l. */
	std::size_t count(Label l) const;
};

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Label.h>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>
#include <vector>

namespace semnav
{
/** One object instance visible in a ground-truth label image. */
struct GroundTruthObject
{
	Label label = Label::Unknown;
	/** Instance id (high byte of the label image). */
	int instance = 0;
	/** Bounding box of its visible pixels (x = column, y = row). */
	cv::Rect box;
	/** Number of visible pixels. */
	int pixels = 0;

	/** The instances of `labels` in a CV_16U ground-truth image (low byte
	 * label id, high byte instance id), sorted by label then instance.
	 * Pixels of these labels with instance 0 are ignored. */
	static std::vector<GroundTruthObject> fromLabelImage(
	    const cv::Mat& groundTruth, const std::vector<Label>& labels);
	/** Mask (CV_8U 255/0) of this instance's pixels. */
	cv::Mat mask(const cv::Mat& groundTruth) const;
	/** The share of `pixels` (x = column, y = row) that are this
	 * instance's (0 for none). */
	double shareOf(
	    const cv::Mat& groundTruth, const std::vector<cv::Point>& pixels) const;
};

}  // namespace semnav

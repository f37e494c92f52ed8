/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Label.h>

#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** Pixel precision / recall / F1 per label, accumulated over sweeps.
 * Only pixels with a valid range are scored; a pixel counts for the label
 * it is predicted as and the label the ground truth gives it. */
class GroundTruthScorer
{
public:
	struct ClassScore
	{
		std::size_t truePositives = 0, falsePositives = 0, falseNegatives = 0;
		/** Ground-truth pixels of the label (tp + fn). */
		std::size_t groundTruthPixels = 0;
		/** Predicted pixels of the label (tp + fp). */
		std::size_t predictedPixels = 0;
		/** 0 when undefined (nothing predicted / nothing to find). */
		double precision = 0, recall = 0, f1 = 0;
	};

	/** Adds one sweep: predicted label ids (CV_8U), ground truth (CV_8U
	 * label ids, or the CV_16U image of semnav-sim whose low byte is the
	 * label id) and the valid-range mask (CV_8U, non-zero = scored).
	 * Throws Error when the sizes differ or a ground-truth id is not a
	 * label. */
	void add(
	    const cv::Mat& predicted, const cv::Mat& groundTruth,
	    const cv::Mat& validMask);

	ClassScore score(Label l) const;
	/** Labels present in the ground truth or the predictions (Unknown
	 * excluded), in id order. */
	std::vector<Label> labelsSeen() const;
	std::size_t sweeps() const { return m_sweeps; }
	std::size_t scoredPixels() const { return m_pixels; }
	/** Confusion count: ground truth `gt` predicted as `pred`. */
	std::size_t confusion(Label gt, Label pred) const;

	/** Reads a semnav-sim label PNG (16-bit, low byte = label id) or an
	 * 8-bit label image as CV_8U label ids; throws IoError. */
	static cv::Mat readLabelImage(const std::string& path);

private:
	std::array<std::array<std::size_t, kMaxLabelCount>, kMaxLabelCount>
	    m_conf{};
	std::size_t m_sweeps = 0, m_pixels = 0;
};

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace semnav
{
/** Integral images of an 8-bit image, with OpenCV's definitions (so that
 * features evaluated on them match cv::CascadeClassifier):
 *
 * - sum(X, Y)    = sum of I(x, y) over x < X, y < Y           (CV_32S)
 * - sqsum(X, Y)  = sum of I(x, y)^2 over x < X, y < Y         (CV_64F)
 * - tilted(X, Y) = sum of I(x, y) over y < Y, |x - X + 1| <= Y - y - 1
 *   (Lienhart-Maydt rotated integral, CV_32S)
 *
 * Each is (rows + 1) x (cols + 1). All are computed by this class (not by
 * cv::integral); tests compare both with brute force and cv::integral. */
class IntegralImages
{
public:
	IntegralImages() = default;
	/** compute(image, withTilted). */
	explicit IntegralImages(const cv::Mat& image, bool withTilted = true);

	/** Computes the integral images of a CV_8UC1 image. Buffers are reused
	 * between calls. Throws CascadeError for another type. */
	void compute(const cv::Mat& image, bool withTilted = true);
	/** The same with rows `stride` entries apart (>= cols + 1) in buffers
	 * that only grow: the levels of a pyramid then share one row stride
	 * (CascadeEvaluator compiles its features once per stride) and no
	 * level allocates. The matrices are then not continuous; the values are
	 * those of compute(). Throws CascadeError when stride < cols + 1. */
	void compute(const cv::Mat& image, bool withTilted, int stride);

	const cv::Mat& sum() const { return m_sum; }
	const cv::Mat& sqsum() const { return m_sqsum; }
	/** Empty when computed without tilted. */
	const cv::Mat& tilted() const { return m_tilted; }
	bool hasTilted() const { return !m_tilted.empty(); }
	/** Size of the source image. */
	cv::Size imageSize() const { return {m_sum.cols - 1, m_sum.rows - 1}; }

	/** Sum of the pixels of an upright rectangle (must lie inside). */
	int64_t rectSum(const cv::Rect& r) const;
	/** Sum of squared pixels of an upright rectangle. */
	double rectSqSum(const cv::Rect& r) const;
	/** Sum of the pixels of a 45-degree rectangle in Lienhart's notation:
	 * top corner (r.x, r.y), r.width pixels along (+1, +1) and r.height
	 * along (-1, +1); the four corners of OpenCV's CV_TILTED_OFS. Needs
	 * hasTilted(). */
	int64_t tiltedRectSum(const cv::Rect& r) const;

	/** The pixels of a 45-degree rectangle, as a brute-force reference:
	 * pixel (px, py) belongs to it iff x - y - 2h <= px - py < x - y and
	 * x + y - 2 < px + py <= x + y + 2w - 2 (derived from the definition of
	 * tilted(); see IntegralImages.cpp). */
	static bool inTiltedRect(const cv::Rect& r, int px, int py);

private:
	void computeInto(const cv::Mat& image, bool withTilted);
	cv::Mat m_sum, m_sqsum, m_tilted;
	/** Storage of the strided compute() (rows x stride); m_sum etc. are
	 * regions of it. */
	cv::Mat m_sumStore, m_sqsumStore, m_tiltedStore;
	bool m_strided = false;
	std::vector<int32_t> m_pad;  ///< scratch for the tilted recurrence
};

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace semnav
{
/** Part of cv::resize(src, dst, size, 0, 0, cv::INTER_LINEAR_EXACT) of an
 * 8-bit one-channel image, bit for bit: only the pixels of `roi` (a
 * rectangle of the resized image, within it) are computed, into `out`
 * (roi.size()). OpenCV 4's fixed-point bilinear resize: per axis, the
 * source position (d + 0.5) / scale - 0.5 in double, its weight rounded to
 * 1/256 (half to even); each source row is interpolated horizontally to
 * 8 fractional bits, then two rows vertically to 16, rounded (exact
 * integers until then: here vertically first). Positions left
 * of (above) the first source pixel take it, right of (below) the last one
 * take the last. A pyramid level searched only in part needs only that part
 * (CascadeDetector's range-gated search). The scratch is kept between
 * calls; not thread-safe. */
class ExactResize
{
public:
	/** Throws CascadeError for another image type or a `roi` outside
	 * `size`. */
	void resize(
	    const cv::Mat& src, cv::Size size, const cv::Rect& roi, cv::Mat& out);

private:
	/** Per position of the roi along one axis: the two source indices and
	 * their weights (256 in all). */
	struct Taps
	{
		std::vector<int> i0, i1;
		std::vector<uint16_t> w0, w1;
	};
	static void taps(int srcSize, int dstSize, int begin, int end, Taps& t);
	Taps m_x, m_y;
	/** Two source rows interpolated vertically (8 fractional bits). */
	std::vector<uint16_t> m_column;
	/** Per column of the region, its first tap in m_column, and (AVX2)
	 * its two weights as a 16-bit pair. */
	std::vector<int> m_offset;
	std::vector<int32_t> m_weights;
};

}  // namespace semnav

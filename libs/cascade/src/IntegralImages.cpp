/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/IntegralImages.h>

#include <algorithm>

namespace semnav
{
IntegralImages::IntegralImages(const cv::Mat& image, bool withTilted)
{
	compute(image, withTilted);
}

void IntegralImages::compute(const cv::Mat& image, bool withTilted)
{
	if (image.type() != CV_8UC1)
		throw CascadeError(
		    "IntegralImages: expected an 8-bit single-channel image");
	if (m_strided)
	{
		// Views into the strided storage: continuous matrices again.
		m_sum.release();
		m_sqsum.release();
		m_tilted.release();
		m_strided = false;
	}
	const int w = image.cols, h = image.rows;
	m_sum.create(h + 1, w + 1, CV_32S);
	m_sqsum.create(h + 1, w + 1, CV_64F);
	if (withTilted) m_tilted.create(h + 1, w + 1, CV_32S);
	computeInto(image, withTilted);
}

void IntegralImages::compute(const cv::Mat& image, bool withTilted, int stride)
{
	if (image.type() != CV_8UC1)
		throw CascadeError(
		    "IntegralImages: expected an 8-bit single-channel image");
	const int w = image.cols, h = image.rows;
	if (stride < w + 1)
		throw CascadeError("IntegralImages: stride below the image width + 1");
	const auto region = [&](cv::Mat& store, int type)
	{
		if (store.cols != stride || store.rows < h + 1 || store.type() != type)
			store.create(
			    std::max(h + 1, store.cols == stride ? store.rows : 0), stride,
			    type);
		return store(cv::Rect(0, 0, w + 1, h + 1));
	};
	m_sum = region(m_sumStore, CV_32S);
	m_sqsum = region(m_sqsumStore, CV_64F);
	if (withTilted) m_tilted = region(m_tiltedStore, CV_32S);
	m_strided = true;
	computeInto(image, withTilted);
}

void IntegralImages::computeInto(const cv::Mat& image, bool withTilted)
{
	const int w = image.cols, h = image.rows;
	std::fill_n(m_sum.ptr<int32_t>(0), w + 1, 0);
	std::fill_n(m_sqsum.ptr<double>(0), w + 1, 0.0);
	for (int y = 0; y < h; y++)
	{
		const uint8_t* src = image.ptr<uint8_t>(y);
		const int32_t* prev = m_sum.ptr<int32_t>(y);
		int32_t* cur = m_sum.ptr<int32_t>(y + 1);
		const double* prevSq = m_sqsum.ptr<double>(y);
		double* curSq = m_sqsum.ptr<double>(y + 1);
		int32_t row = 0;
		// Sums of squares are integers: exact in int64 and in double (below
		// 2^53), so the same doubles as a double running sum, without its
		// four-cycle dependency chain.
		int64_t rowSq = 0;
		cur[0] = 0;
		curSq[0] = 0;
		for (int x = 0; x < w; x++)
		{
			row += src[x];
			rowSq += int32_t(src[x]) * src[x];
			cur[x + 1] = prev[x + 1] + row;
			curSq[x + 1] = prevSq[x + 1] + double(rowSq);
		}
	}
	if (!withTilted)
	{
		m_tilted.release();
		return;
	}

	// Tilted integral by the recurrence (T = tilted, I = image, 0 outside)
	//   T(X, Y) = T(X-1, Y-1) + T(X+1, Y-1) - T(X, Y-2)
	//             + I(X-1, Y-1) + I(X-1, Y-2),   T(., 0) = T(., -1) = 0.
	// The cone of T(X-1, Y-1) and of T(X+1, Y-1) overlap in the cone of
	// T(X, Y-2); the two new pixels are the apex (X-1, Y-1) and the one
	// below it. Cones whose apex lies left or right of the image still
	// reach into it, so T is computed on X in [-h, w + h] (every value the
	// recurrence needs down to row 0) and cropped to [0, w].
	const int pad = h;
	const int wp = w + 1 + 2 * pad;
	m_pad.assign(3 * static_cast<size_t>(wp), 0);
	int32_t* rows[3] = {m_pad.data(), m_pad.data() + wp, m_pad.data() + 2 * wp};
	// rows[Y % 3] holds T(., Y); X = index - pad.
	std::fill_n(m_tilted.ptr<int32_t>(0), w + 1, 0);
	for (int Y = 1; Y <= h; Y++)
	{
		int32_t* cur = rows[Y % 3];
		const int32_t* prev = rows[(Y - 1) % 3];
		const int32_t* prev2 = rows[(Y + 1) % 3];  // (Y - 2) mod 3
		const uint8_t* src1 = image.ptr<uint8_t>(Y - 1);
		const uint8_t* src2 = Y >= 2 ? image.ptr<uint8_t>(Y - 2) : nullptr;
		// Only X within reach of the rows still to compute are needed:
		// i in [Y, wp - 1 - Y], so i - 1 and i + 1 stay inside the row,
		// and rows[] start at 0 (T(., -1) = T(., 0) = 0).
		const int reach = h - Y;
		const int lo = pad - reach, hi = pad + w + reach;
		for (int i = lo; i <= hi; i++)
			cur[i] = prev[i - 1] + prev[i + 1] - prev2[i];
		// The two new pixels, for X in [1, w].
		int32_t* c = cur + pad + 1;
		for (int x = 0; x < w; x++) c[x] += src1[x];
		if (src2)
			for (int x = 0; x < w; x++) c[x] += src2[x];
		std::copy_n(cur + pad, w + 1, m_tilted.ptr<int32_t>(Y));
	}
}

int64_t IntegralImages::rectSum(const cv::Rect& r) const
{
	const auto* a = m_sum.ptr<int32_t>(r.y);
	const auto* b = m_sum.ptr<int32_t>(r.y + r.height);
	return int64_t(a[r.x]) - a[r.x + r.width] - b[r.x] + b[r.x + r.width];
}

double IntegralImages::rectSqSum(const cv::Rect& r) const
{
	const auto* a = m_sqsum.ptr<double>(r.y);
	const auto* b = m_sqsum.ptr<double>(r.y + r.height);
	return a[r.x] - a[r.x + r.width] - b[r.x] + b[r.x + r.width];
}

int64_t IntegralImages::tiltedRectSum(const cv::Rect& r) const
{
	// OpenCV's CV_TILTED_OFS corners: (x, y), (x - h, y + h),
	// (x + w, y + w), (x + w - h, y + w + h).
	const auto t = [&](int X, int Y) -> int64_t
	{ return m_tilted.at<int32_t>(Y, X); };
	return t(r.x, r.y) - t(r.x - r.height, r.y + r.height) -
	       t(r.x + r.width, r.y + r.width) +
	       t(r.x + r.width - r.height, r.y + r.width + r.height);
}

bool IntegralImages::inTiltedRect(const cv::Rect& r, int px, int py)
{
	// With u = px - py and v = px + py, tilted(X, Y) sums the pixels with
	// u >= X - Y and v <= X + Y - 2 (rows y < Y follow). The four corner
	// terms then leave x - y - 2h <= u < x - y, x + y - 2 < v <= x + y +
	// 2w - 2.
	const int u = px - py, v = px + py;
	return u >= r.x - r.y - 2 * r.height && u < r.x - r.y &&
	       v > r.x + r.y - 2 && v <= r.x + r.y + 2 * r.width - 2;
}

}  // namespace semnav

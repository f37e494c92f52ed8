/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/ExactResize.h>

#include <algorithm>
#include <cmath>

#include "StumpBatch.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SEMNAV_EXACT_RESIZE_AVX2 1
#endif

namespace semnav
{
namespace
{
/** One output row from the vertically interpolated row `v` (scalar). */
void horizontal(
    const uint16_t* v, const int* j, const uint16_t* w0, const uint16_t* w1,
    int begin, int end, uint8_t* o)
{
	for (int x = begin; x < end; x++)
	{
		const uint16_t* p = v + j[x];
		o[x] = static_cast<uint8_t>(
		    (uint32_t(w0[x]) * p[0] + uint32_t(w1[x]) * p[1] + (1u << 15)) >>
		    16);
	}
}

#ifdef SEMNAV_EXACT_RESIZE_AVX2
/** The same, eight columns at a time: both taps of a column in one 32-bit
 * gather, their weights in one 16-bit pair (`w`); the taps (up to 65280)
 * offset by -32768 for the signed multiply-add, which the weights' sum
 * (256) gives back. Returns the columns done. */
__attribute__((target("avx2"))) int horizontal8(
    const uint16_t* v, const int* j, const int32_t* w, int n, uint8_t* o)
{
	const __m256i flip = _mm256_set1_epi32(int32_t(0x80008000u));
	const __m256i back = _mm256_set1_epi32((32768 << 8) + (1 << 15));
	int x = 0;
	for (; x + 8 <= n; x += 8)
	{
		const __m256i idx =
		    _mm256_loadu_si256(reinterpret_cast<const __m256i*>(j + x));
		const __m256i pair =
		    _mm256_i32gather_epi32(reinterpret_cast<const int*>(v), idx, 2);
		const __m256i weights =
		    _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w + x));
		const __m256i sum = _mm256_add_epi32(
		    _mm256_madd_epi16(_mm256_xor_si256(pair, flip), weights), back);
		const __m256i px = _mm256_srli_epi32(sum, 16);
		const __m128i p16 = _mm_packus_epi32(
		    _mm256_castsi256_si128(px), _mm256_extracti128_si256(px, 1));
		_mm_storel_epi64(
		    reinterpret_cast<__m128i*>(o + x), _mm_packus_epi16(p16, p16));
	}
	return x;
}
#endif
}  // namespace

void ExactResize::taps(int srcSize, int dstSize, int begin, int end, Taps& t)
{
	const int n = end - begin;
	t.i0.resize(std::size_t(n));
	t.i1.resize(std::size_t(n));
	t.w0.resize(std::size_t(n));
	t.w1.resize(std::size_t(n));
	// OpenCV: inv_scale = dst / src, scale = 1 / inv_scale (softdouble:
	// IEEE double, this file has no fused multiply-add).
	const double invScale = double(dstSize) / double(srcSize);
	const double scale = 1.0 / invScale;
	for (int d = begin; d < end; d++)
	{
		const std::size_t k = std::size_t(d - begin);
		const double f = scale * (double(d) + 0.5) - 0.5;
		const double fl = std::floor(f);
		if (fl >= 0 && srcSize > 1 && fl < srcSize - 1)
		{
			const int i = static_cast<int>(fl);
			// ufixedpoint16(f - i): cvRound (half to even) of (f - i) * 256.
			const int w = static_cast<int>(std::nearbyint((f - fl) * 256.0));
			t.i0[k] = i;
			t.i1[k] = i + 1;
			t.w1[k] = static_cast<uint16_t>(w);
			t.w0[k] = static_cast<uint16_t>(256 - w);
		}
		else
		{
			// Left of the first source pixel (or a single one): the first;
			// right of the last: the last.
			const int i = fl >= 0 && srcSize > 1 ? srcSize - 1 : 0;
			t.i0[k] = t.i1[k] = i;
			t.w0[k] = 256;
			t.w1[k] = 0;
		}
	}
}

void ExactResize::resize(
    const cv::Mat& src, cv::Size size, const cv::Rect& roi, cv::Mat& out)
{
	if (src.type() != CV_8UC1 || src.empty())
		throw CascadeError("ExactResize: expected an 8-bit one-channel image");
	if (roi.x < 0 || roi.y < 0 || roi.width <= 0 || roi.height <= 0 ||
	    roi.x + roi.width > size.width || roi.y + roi.height > size.height)
		throw CascadeError("ExactResize: the region lies outside the image");
	taps(src.cols, size.width, roi.x, roi.x + roi.width, m_x);
	taps(src.rows, size.height, roi.y, roi.y + roi.height, m_y);
	out.create(roi.size(), CV_8UC1);
	const int w = roi.width;
	// The source columns the region reads, and one more (weight 0 where
	// the second tap is the first, at the edges).
	const int c0 = *std::min_element(m_x.i0.begin(), m_x.i0.end());
	const int c1 = *std::max_element(m_x.i1.begin(), m_x.i1.end());
	const int nc = c1 - c0 + 1;
	m_column.assign(std::size_t(nc + 1), 0);
	m_offset.resize(std::size_t(w));
	for (int x = 0; x < w; x++)
		m_offset[std::size_t(x)] = m_x.i0[std::size_t(x)] - c0;
	uint16_t* v = m_column.data();
	const int* j = m_offset.data();
	const bool avx2 = detail::cpuHasAvx2();
	if (avx2)
	{
		m_weights.resize(std::size_t(w));
		for (int x = 0; x < w; x++)
			m_weights[std::size_t(x)] = int32_t(
			    uint32_t(m_x.w0[std::size_t(x)]) |
			    uint32_t(m_x.w1[std::size_t(x)]) << 16);
	}
	const uint16_t* w0 = m_x.w0.data();
	const uint16_t* w1 = m_x.w1.data();
	// OpenCV interpolates each source row horizontally (exact integers,
	// 8 fractional bits), then two rows vertically, rounding once at 16
	// bits: the same integers vertically first (contiguous, vectorised),
	// then horizontally.
	for (int y = 0; y < roi.height; y++)
	{
		const std::size_t k = std::size_t(y);
		const uint8_t* s0 = src.ptr<uint8_t>(m_y.i0[k]) + c0;
		const uint8_t* s1 = src.ptr<uint8_t>(m_y.i1[k]) + c0;
		const uint16_t v0 = m_y.w0[k], v1 = m_y.w1[k];
		for (int c = 0; c < nc; c++)
			v[c] = static_cast<uint16_t>(v0 * s0[c] + v1 * s1[c]);
		uint8_t* o = out.ptr<uint8_t>(y);
		int done = 0;
#ifdef SEMNAV_EXACT_RESIZE_AVX2
		if (avx2) done = horizontal8(v, j, m_weights.data(), w, o);
#endif
		horizontal(v, j, w0, w1, done, w, o);
	}
}

}  // namespace semnav

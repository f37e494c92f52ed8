/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <algorithm>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace semnav::detail
{
/** Unnormalized box sum over a (2k+1) x (2k+1) window with zero outside
 * the image, for CV_32F images of 1 or more interleaved channels, row by
 * row: row r's sums (src.cols x channels floats) are written to
 * rowDest(r), then rowDone(r, sums) is called. The sums equal
 * cv::boxFilter(src, CV_32F, {2k+1, 2k+1}, normalize = false,
 * BORDER_CONSTANT), 3-4x faster for 3 channels (rows as flat float arrays:
 * the vertical running sum vectorizes whatever the channel count). */
template <class RowDest, class RowDone>
void boxSumRows(
    const cv::Mat& src, int k, std::vector<float>& tmp, RowDest&& rowDest,
    RowDone&& rowDone)
{
	const int rows = src.rows, ch = src.channels(), w = src.cols * ch;
	tmp.assign(static_cast<std::size_t>(w), 0.0f);
	float* acc = tmp.data();
	// Vertical: running sum of rows r-k .. r+k.
	for (int r = 0; r < std::min(k, rows); r++)
	{
		const float* s = src.ptr<float>(r);
		for (int i = 0; i < w; i++) acc[i] += s[i];
	}
	for (int r = 0; r < rows; r++)
	{
		if (r + k < rows)
		{
			const float* s = src.ptr<float>(r + k);
			for (int i = 0; i < w; i++) acc[i] += s[i];
		}
		if (r - k - 1 >= 0)
		{
			const float* s = src.ptr<float>(r - k - 1);
			for (int i = 0; i < w; i++) acc[i] -= s[i];
		}
		// Horizontal, per channel (interleaved): o(c) = sum of acc over
		// columns c-k .. c+k; the middle part is 2k+1 shifted adds (no loop
		// dependency: vectorizes), the k columns at each end are clamped.
		float* o = rowDest(r);
		const int cols = src.cols;
		const int head = std::min(k, cols) * ch;
		const int tail = std::max(head, (cols - k) * ch);
		for (int i = head; i < tail; i++) o[i] = acc[i];
		for (int j = 1; j <= k; j++)
		{
			const int d = j * ch;
			for (int i = head; i < tail; i++) o[i] += acc[i - d] + acc[i + d];
		}
		auto edge = [&](int i)
		{
			const int c = i / ch, c0 = i % ch;
			float v = 0;
			for (int cc = std::max(0, c - k); cc <= std::min(cols - 1, c + k);
			     cc++)
				v += acc[cc * ch + c0];
			o[i] = v;
		};
		for (int i = 0; i < head; i++) edge(i);
		for (int i = tail; i < w; i++) edge(i);
		rowDone(r, static_cast<const float*>(o));
	}
}

/** boxSumRows() into an image: out = the box sums of src. */
inline void boxSum(
    const cv::Mat& src, int k, cv::Mat& out, std::vector<float>& tmp)
{
	out.create(src.size(), src.type());
	boxSumRows(
	    src, k, tmp, [&](int r) { return out.ptr<float>(r); },
	    [](int, const float*) {});
}

}  // namespace semnav::detail

/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/OptionTable.h>
#include <semnav/perception/Roughness.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "BoxSum.h"

namespace semnav
{
namespace
{
using O = Roughness::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .integer(
	            "window_half_width_px", &O::windowHalfWidth, 1, 20,
	            "R: mean dot product with the normals of the (2w+1)^2 "
	            "window.")
	        .integer(
	            "square_width_px", &O::squareWidth, 1, 100,
	            "R-bar: mean R over squares of w' x w' pixels.")
	        .integer(
	            "min_square_px", &O::minSquarePixels, 1, 10000,
	            "Squares with fewer pixels of the area have no R-bar.")
	        .flag(
	            "smooth_normals", &O::smoothNormals,
	            "R on normals averaged over (2k+1)^2 pixels first.")
	        .integer(
	            "smoothing_half_width_px", &O::smoothingHalfWidth, 1, 10,
	            "k of smooth_normals.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(Roughness::TOptions, optionTable())

Roughness::Roughness() : Roughness(TOptions()) {}

Roughness::Roughness(const TOptions& options) : m_options(options) {}

void Roughness::compute(const NormalImage& normals, const cv::Mat& areaIds)
{
	const int rows = normals.classifierNormals().rows,
	          cols = normals.classifierNormals().cols;
	m_r.create(rows, cols, CV_32F);
	if (rows == 0 || cols == 0)
	{
		m_rBar.create(rows, cols, CV_32F);
		return;
	}
	const cv::Mat* n = &normals.classifierNormals();
	if (m_options.smoothNormals)
	{
		normals.smoothed(areaIds, m_options.smoothingHalfWidth, m_smooth);
		n = &m_smooth;
	}
	// R = n . (S - n) / (N - 1), S and N the sums of normals and of the
	// normal mask over the window (box filters: O(1) per pixel). Normals are
	// 0 where there is none, so S only counts pixels with a normal.
	// (S row by row: the sums of normals are used once.)
	normals.classifierNormalMask().convertTo(m_mask, CV_32F);
	detail::boxSum(m_mask, m_options.windowHalfWidth, m_sumM, m_tmp);
	m_rowSum.resize(static_cast<std::size_t>(cols) * 3);
	const detail::SimdKernels& K = detail::simdKernels();
	detail::boxSumRows(
	    *n, m_options.windowHalfWidth, m_tmp,
	    [&](int) { return m_rowSum.data(); },
	    [&](int r, const float* sums)
	    {
		    K.roughnessRow(
		        n->ptr<float>(r), sums, m_sumM.ptr<float>(r),
		        normals.classifierNormalMask().ptr<uint8_t>(r),
		        m_r.ptr<float>(r), cols);
	    });
	squareMeans(
	    m_r, areaIds, m_options.squareWidth, m_options.minSquarePixels, m_rBar);
}

void Roughness::squareMeans(
    const cv::Mat& r, const cv::Mat& groups, int w, int minPixels, cv::Mat& out)
{
	constexpr float nan = std::numeric_limits<float>::quiet_NaN();
	const int rows = r.rows, cols = r.cols;
	out.create(rows, cols, CV_32F);
	w = std::max(1, w);
	std::vector<int> ids;
	std::vector<double> sums;
	std::vector<int> counts;
	for (int r0 = 0; r0 < rows; r0 += w)
		for (int c0 = 0; c0 < cols; c0 += w)
		{
			const int r1 = std::min(rows, r0 + w), c1 = std::min(cols, c0 + w);
			// Common case: the whole square in one group.
			const int g0 = groups.ptr<int>(r0)[c0];
			bool uniform = true;
			float sum = 0;
			int cnt = 0;
			for (int rr = r0; rr < r1 && uniform; rr++)
			{
				const int* G = groups.ptr<int>(rr);
				const float* R = r.ptr<float>(rr);
				for (int cc = c0; cc < c1; cc++)
				{
					uniform &= G[cc] == g0;
					const float v = R[cc];
					const bool ok = v == v;  // not NaN
					sum += ok ? v : 0.0f;
					cnt += ok;
				}
			}
			if (uniform)
			{
				const float m = g0 > 0 && cnt >= minPixels ? sum / cnt : nan;
				for (int rr = r0; rr < r1; rr++)
				{
					float* O = out.ptr<float>(rr);
					for (int cc = c0; cc < c1; cc++) O[cc] = m;
				}
				continue;
			}
			ids.clear();
			sums.clear();
			counts.clear();
			for (int rr = r0; rr < r1; rr++)
			{
				const int* G = groups.ptr<int>(rr);
				const float* R = r.ptr<float>(rr);
				for (int cc = c0; cc < c1; cc++)
				{
					if (G[cc] <= 0 || !std::isfinite(R[cc])) continue;
					std::size_t k = 0;
					while (k < ids.size() && ids[k] != G[cc]) k++;
					if (k == ids.size())
					{
						ids.push_back(G[cc]);
						sums.push_back(0);
						counts.push_back(0);
					}
					sums[k] += R[cc];
					counts[k]++;
				}
			}
			for (int rr = r0; rr < r1; rr++)
			{
				const int* G = groups.ptr<int>(rr);
				float* O = out.ptr<float>(rr);
				for (int cc = c0; cc < c1; cc++)
				{
					O[cc] = nan;
					if (G[cc] <= 0) continue;
					for (std::size_t k = 0; k < ids.size(); k++)
						if (ids[k] == G[cc])
						{
							if (counts[k] >= minPixels)
								O[cc] = static_cast<float>(sums[k] / counts[k]);
							break;
						}
				}
			}
		}
}

}  // namespace semnav

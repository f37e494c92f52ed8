/* semnav: semantic navigation from tilting-laser sweeps */
/* RuleClassifier, step 6 outdoors: the sidewalk / grass border refined per
 * pixel. */
#include <semnav/perception/RuleClassifier.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semnav
{
void RuleClassifier::refineGroundBorder(
    const cv::Mat& r, const int* G, int w, const std::vector<int8_t>& sq,
    uint8_t* L)
{
	// The squares' types make a staircase of w' pixels along the border.
	// In squares with a square of the other type among their 8 neighbours,
	// each ground pixel is typed by the mean R over the ground pixels of
	// the (2h+1)^2 window centred on it (h = sidewalk_border_half_width_px):
	// the squares' own test, slid to the pixel. Pixels without R there keep
	// their square's type.
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	const int h = m_options.sidewalkBorderHalfWidth;
	const int sr = (rows + w - 1) / w, sc = (cols + w - 1) / w;
	std::vector<uint8_t> border(sq.size(), 0);
	bool any = false;
	for (int k = 0; k < sr * sc; k++)
	{
		if (sq[k] <= 0) continue;
		const int a = k / sc, b = k % sc;
		for (int da = -1; da <= 1 && !border[k]; da++)
			for (int db = -1; db <= 1; db++)
			{
				const int aa = a + da, bb = b + db;
				if (aa < 0 || aa >= sr || bb < 0 || bb >= sc) continue;
				const int8_t t = sq[aa * sc + bb];
				if (t > 0 && t != sq[k])
				{
					border[k] = 1;
					any = true;
					break;
				}
			}
	}
	if (!any) return;
	m_groundR.create(rows, cols, CV_32F);
	m_groundN.create(rows, cols, CV_32F);
	float* V = m_groundR.ptr<float>(0);
	float* M = m_groundN.ptr<float>(0);
	const float* R = r.ptr<float>(0);
	for (int p = 0; p < n; p++)
	{
		const bool ok = G[p] && std::isfinite(R[p]);
		V[p] = ok ? R[p] : 0.0f;
		M[p] = ok ? 1.0f : 0.0f;
	}
	const cv::Size win(2 * h + 1, 2 * h + 1);
	cv::boxFilter(
	    m_groundR, m_groundR, CV_32F, win, cv::Point(-1, -1), false,
	    cv::BORDER_CONSTANT);
	cv::boxFilter(
	    m_groundN, m_groundN, CV_32F, win, cv::Point(-1, -1), false,
	    cv::BORDER_CONSTANT);
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const float minMean = static_cast<float>(m_options.sidewalkMinRbar);
	for (int p = 0; p < n; p++)
	{
		if (!G[p] || !border[(RO[p] / w) * sc + CO[p] / w]) continue;
		if (M[p] < 0.5f) continue;
		L[p] = static_cast<uint8_t>(
		    V[p] >= minMean * M[p] ? Label::Sidewalk : Label::Grass);
	}
}

void RuleClassifier::typeFlatSquares(
    const int* G, int w, int minSquarePixels, std::vector<int8_t>& sq) const
{
	// R-bar is low where the normals are noise: at the sweep's sides the
	// rows nearly coincide. A grass square (by R-bar) whose ground points'
	// heights spread at most sidewalk_flat_max_height_std_m is sidewalk.
	const auto var = squareHeightVariances(G, w, minSquarePixels, sq, 2);
	const double maxVar =
	    m_options.sidewalkFlatMaxHeightStd * m_options.sidewalkFlatMaxHeightStd;
	for (size_t k = 0; k < sq.size(); k++)
		if (var[k] >= 0 && var[k] <= maxVar) sq[k] = 1;
}

}  // namespace semnav

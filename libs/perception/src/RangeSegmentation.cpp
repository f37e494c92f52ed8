/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/perception/RangeSegmentation.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semnav
{
namespace
{
using O = RangeSegmentation::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "max_neighbour_difference_m", &O::maxNeighbourDifference, 0, 10,
	            "Flood fill joins neighbours with closer ranges.")
	        .integer(
	            "min_area_px", &O::minAreaPixels, 0, 1000000,
	            "Larger areas are numbered 1..n, the others are 0.")
	        .integer("connectivity", &O::connectivity, 4, 8, "4 or 8.")
	        .check(
	            [](const O& o)
	            { return o.connectivity == 4 || o.connectivity == 8; },
	            "connectivity must be 4 or 8");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(RangeSegmentation::TOptions, optionTable())

RangeSegmentation::RangeSegmentation() : RangeSegmentation(TOptions()) {}

RangeSegmentation::RangeSegmentation(const TOptions& options)
    : m_options(options)
{
}

void RangeSegmentation::compute(const Sweep& sweep)
{
	const int rows = static_cast<int>(sweep.rows());
	const int cols = static_cast<int>(sweep.cols());
	m_ids.create(rows, cols, CV_32S);
	m_sizes.assign(1, 0);
	m_fills = 0;
	m_singletons = 0;
	if (rows == 0 || cols == 0) return;
	prepareImages(sweep);
	// Most areas are small (noisy or grazing surfaces): a search bounded to
	// min_area_px + 1 pixels finds them whole, and they are set aside
	// without a fill. Larger areas are filled.
	for (int r = 0; r < rows; r++)
	{
		const int* I = m_ids.ptr<int>(r);
		for (int c = 0; c < cols; c++)
			if (I[c] == -1 && !setAsideSmallArea(r, c)) fillArea(r, c);
	}
}

void RangeSegmentation::prepareImages(const Sweep& sweep)
{
	const int rows = static_cast<int>(sweep.rows());
	const int cols = static_cast<int>(sweep.cols());
	// Range image with invalid pixels blocked in the mask (mask != 0 stops
	// the fill; the 1-pixel frame the mask needs is blocked too).
	m_range.create(rows, cols, CV_32F);
	m_mask.create(rows + 2, cols + 2, CV_8U);
	m_mask.setTo(1);
	const float* rng = sweep.ranges().data();
	const uint8_t* val = sweep.validity().data();
	for (int r = 0; r < rows; r++)
	{
		float* R = m_range.ptr<float>(r);
		uint8_t* M = m_mask.ptr<uint8_t>(r + 1) + 1;
		int* I = m_ids.ptr<int>(r);
		for (int c = 0; c < cols; c++)
		{
			const std::size_t i = static_cast<std::size_t>(r) * cols + c;
			const float d = rng[i];
			const bool ok = val[i] && std::isfinite(d) && d > 0;
			R[c] = ok ? d : 0.0f;
			M[c] = ok ? 0 : 1;
			I[c] = ok ? -1 : 0;
			if (!ok) m_sizes[0]++;
		}
	}
}

bool RangeSegmentation::setAsideSmallArea(int r, int c)
{
	// With cv::floodFill's own test (floating range, d = a - b in float,
	// -diff <= d <= diff).
	const float up = static_cast<float>(m_options.maxNeighbourDifference),
	            lo = -up;
	const int bound = m_options.minAreaPixels + 1;
	const int mstep = static_cast<int>(m_mask.step1());
	const int rstep = static_cast<int>(m_range.step1());
	uint8_t* M0 = m_mask.ptr<uint8_t>(1) + 1;  // pixel (0, 0)
	const float* R0 = m_range.ptr<float>(0);
	static constexpr int nbR[8] = {0, 0, -1, 1, -1, -1, 1, 1};
	static constexpr int nbC[8] = {-1, 1, 0, 0, -1, 1, -1, 1};
	const int nNb = m_options.connectivity == 8 ? 8 : 4;
	// Bounded search (visited pixels marked 3 in the mask).
	m_small.clear();
	m_small.emplace_back(r, c);
	M0[r * mstep + c] = 3;
	for (std::size_t h = 0;
	     h < m_small.size() && static_cast<int>(m_small.size()) <= bound; h++)
	{
		const int pr = m_small[h].first, pc = m_small[h].second;
		const float d = R0[pr * rstep + pc];
		for (int k = 0; k < nNb; k++)
		{
			const int qr = pr + nbR[k], qc = pc + nbC[k];
			uint8_t& mq = M0[qr * mstep + qc];  // frame is 1
			if (mq != 0) continue;
			const float dd = R0[qr * rstep + qc] - d;
			if (!(lo <= dd && dd <= up)) continue;
			mq = 3;
			m_small.emplace_back(qr, qc);
		}
	}
	const int found = static_cast<int>(m_small.size());
	if (found < bound)
	{
		// The whole area, too small to be numbered.
		for (const auto& [pr, pc] : m_small)
		{
			M0[pr * mstep + pc] = 1;
			m_ids.ptr<int>(pr)[pc] = 0;
		}
		m_sizes[0] += found;
		if (found == 1)
			m_singletons++;
		else
			m_fills++;
		return true;
	}
	for (const auto& [pr, pc] : m_small) M0[pr * mstep + pc] = 0;
	return false;
}

void RangeSegmentation::fillArea(int r, int c)
{
	// Fill value 2 marks the pixels of the current fill in the mask; they
	// are collected inside the returned bounding box and re-marked 1.
	const double diff = m_options.maxNeighbourDifference;
	const int flags =
	    m_options.connectivity | cv::FLOODFILL_MASK_ONLY | (2 << 8);
	cv::Rect box;
	const int n = cv::floodFill(
	    m_range, m_mask, cv::Point(c, r), cv::Scalar(0), &box, cv::Scalar(diff),
	    cv::Scalar(diff), flags);
	m_fills++;
	int id = 0;
	if (n > m_options.minAreaPixels)
	{
		id = static_cast<int>(m_sizes.size());
		m_sizes.push_back(n);
	}
	else
		m_sizes[0] += n;
	for (int rr = box.y; rr < box.y + box.height; rr++)
	{
		uint8_t* M = m_mask.ptr<uint8_t>(rr + 1) + 1;
		int* J = m_ids.ptr<int>(rr);
		for (int cc = box.x; cc < box.x + box.width; cc++)
			if (M[cc] == 2)
			{
				M[cc] = 1;
				J[cc] = id;
			}
	}
}

}  // namespace semnav

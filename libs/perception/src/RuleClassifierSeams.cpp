/* semnav: semantic navigation from tilting-laser sweeps */
/* RuleClassifier, step 3: a plane step too small for the plain split (a
 * nearly flush door leaf) is cut along the seams beside it. */
#include <semnav/perception/RuleClassifier.h>

#include <algorithm>
#include <cmath>

#include "RuleClassifierDetail.h"

namespace semnav
{
using namespace detail::rules;

namespace
{
/** A break in a plane seen along a row: where it crosses the plane (u
 * along it, z). */
struct Notch
{
	double u, z;
};

/** A vertical line of notches: its position along the plane and its top. */
struct Seam
{
	double u, top;
};

/** Signed distance of q from the plane (normal, offset). */
double planeResidual(const cv::Vec3d& normal, double offset, const cv::Vec3f& q)
{
	return normal[0] * q[0] + normal[1] * q[1] + normal[2] * q[2] - offset;
}

/** Vertical lines of notches (door_seam_min_height_m tall, notches within
 * kHalfWidth of their mean), left to right. */
std::vector<Seam> findSeams(
    std::vector<Notch>& notches, double minHeight, int minNotches)
{
	constexpr double kHalfWidth = 0.03;
	std::sort(
	    notches.begin(), notches.end(),
	    [](const Notch& a, const Notch& b) { return a.u < b.u; });
	std::vector<Seam> seams;
	const int n = static_cast<int>(notches.size());
	int j0 = 0, j1 = 0;
	double bestU = 0, bestTop = 0;
	int best = 0;
	auto flushBest = [&]
	{
		if (best > 0) seams.push_back({bestU, bestTop});
		best = 0;
	};
	for (int i = 0; i < n; i++)
	{
		// Notches within 2 kHalfWidth starting at i.
		j0 = i;
		while (j1 < n && notches[j1].u <= notches[i].u + 2 * kHalfWidth) j1++;
		const int cnt = j1 - j0;
		double zLo = notches[j0].z, zHi = zLo, su = 0;
		for (int j = j0; j < j1; j++)
		{
			zLo = std::min(zLo, notches[j].z);
			zHi = std::max(zHi, notches[j].z);
			su += notches[j].u;
		}
		const bool seam = cnt >= minNotches && zHi - zLo >= minHeight;
		const double u = su / cnt;
		if (best > 0 && u > bestU + 2 * kHalfWidth) flushBest();
		if (seam && cnt > best)
		{
			best = cnt;
			bestU = u;
			bestTop = zHi;
		}
	}
	flushBest();
	return seams;
}
}  // namespace

double RuleClassifier::seamShare(
    int slot, float threshold, const cv::Vec3d& normal, double offset) const
{
	// Where a row crosses from one side of the step to the other, the
	// boundary is a seam when a pixel within two columns of it leaves the
	// plane by door_seam_depth_m or has no point, with pixels of the group
	// on both sides of it in the row (a gap inside the group: beyond the
	// group's edge every pixel breaks, and a strip along the edge, where
	// the smoothed residuals are biased, would be "seamed"). Noise on a
	// flat wall gives random boundaries without seams.
	constexpr int kMaxGap = 3, kMargin = 2;
	const int cols = m_cols;
	const int group = m_slotGroup[slot];
	auto inGroup = [&](int p)
	{
		const int s = m_surf[p];
		return s >= 0 && m_parent[s] == group;
	};
	// A group pixel within kMaxGap + 1 columns of column c, on side dir.
	auto flank = [&](int rowStart, int c, int dir)
	{
		for (int k = 1; k <= kMaxGap + 1; k++)
		{
			const int cc = c + dir * k;
			if (cc < 0 || cc >= cols) return false;
			if (inGroup(rowStart + cc)) return true;
		}
		return false;
	};
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	const auto* PM = m_pointMask->ptr<uint8_t>(0);
	const float* RS = m_resSum.ptr<float>(0);
	const int* CO = m_colOf.data();
	auto breaks = [&](int p)
	{
		return !PM[p] || std::abs(planeResidual(normal, offset, P[p])) >
		                     m_options.doorSeamDepth;
	};
	int crossings = 0, seams = 0;
	const int* pix = m_slotPix.data();
	for (int i = m_slotStart[slot]; i + 1 < m_slotStart[slot + 1]; i++)
	{
		const int p = pix[i], q = pix[i + 1];
		const int c0 = CO[p], c1 = CO[q];
		// (Row-major: the next pixel of the group in the same row.)
		if (q - p != c1 - c0 || c1 - c0 > kMaxGap) continue;
		if ((RS[p] >= threshold) == (RS[q] >= threshold)) continue;
		crossings++;
		const int rowStart = p - c0;
		for (int c = std::max(0, c0 - kMargin);
		     c <= std::min(cols - 1, c1 + kMargin); c++)
			if (breaks(rowStart + c) && flank(rowStart, c, -1) &&
			    flank(rowStart, c, 1))
			{
				seams++;
				break;
			}
	}
	return crossings >= m_options.minSurfacePixels / 3
	           ? static_cast<double>(seams) / crossings
	           : 0.0;
}

bool RuleClassifier::splitAtSeams(
    int slot, const cv::Vec3d& normal, double offset)
{
	const TOptions& o = m_options;
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	const auto* PM = m_pointMask->ptr<uint8_t>(0);
	const int* CO = m_colOf.data();
	const int* pix = m_slotPix.data();
	const int i0 = m_slotStart[slot], i1 = m_slotStart[slot + 1];
	const cv::Vec3d along(-normal[1], normal[0], 0);
	auto residual = [&](int p) { return planeResidual(normal, offset, P[p]); };
	auto alongOf = [&](int p)
	{ return along[0] * P[p][0] + along[1] * P[p][1]; };
	// Notches: one to three pixels between two pixels of the group on its
	// plane, at least one of them off it by door_seam_depth_m (the gap
	// beside a leaf, its frame) or without a point.
	std::vector<Notch> notches;
	constexpr int kMaxBetween = 3;
	int prev = -1;
	for (int i = i0; i < i1; i++)
	{
		const int p = pix[i];
		if (std::abs(residual(p)) > o.doorSeamDepth) continue;
		if (prev >= 0 && p - prev == CO[p] - CO[prev] && p - prev > 1 &&
		    p - prev <= kMaxBetween + 1)
		{
			bool off = false;
			for (int q = prev + 1; q < p && !off; q++)
				off = !PM[q] || std::abs(residual(q)) > o.doorSeamDepth;
			if (off)
				notches.push_back(
				    {0.5 * (alongOf(prev) + alongOf(p)),
				     0.5 * (P[prev][2] + P[p][2])});
		}
		prev = p;
	}
	std::vector<Seam> seams =
	    findSeams(notches, o.doorSeamMinHeight, o.doorSeamMinNotches);
	if (seams.empty()) return false;
	// The group's extent along the plane bounds the outermost stretches.
	double uLo = 1e30, uHi = -1e30;
	for (int i = i0; i < i1; i++)
	{
		const double u = alongOf(pix[i]);
		uLo = std::min(uLo, u);
		uHi = std::max(uHi, u);
	}
	std::vector<Seam> bounds;
	bounds.push_back({uLo, -1e30});
	bounds.insert(bounds.end(), seams.begin(), seams.end());
	bounds.push_back({uHi, -1e30});
	// A stretch between two bounds, below the top of its seams, is a leaf
	// when its mean residual steps by door_seam_split_offset_m from the
	// plane above it (a lintel), else from the rest of the group.
	bool any = false;
	for (std::size_t b = 0; b + 1 < bounds.size(); b++)
	{
		const double a0 = bounds[b].u, a1 = bounds[b + 1].u;
		const double top = std::max(bounds[b].top, bounds[b + 1].top) + 0.02;
		if (a1 - a0 > o.doorMaxWidth + 0.1 || a1 - a0 < 0.1) continue;
		double sIn = 0, sAbove = 0, sRest = 0;
		int nIn = 0, nAbove = 0, nRest = 0;
		for (int i = i0; i < i1; i++)
		{
			const int p = pix[i];
			const double u = alongOf(p), r = residual(p);
			const bool inside = u > a0 && u < a1;
			if (inside && P[p][2] < top)
			{
				sIn += r;
				nIn++;
			}
			else if (inside && P[p][2] > top + 0.05)
			{
				sAbove += r;
				nAbove++;
			}
			else
			{
				sRest += r;
				nRest++;
			}
		}
		const int minPx = o.minSurfacePixels;
		if (nIn < minPx || nRest + nAbove < minPx) continue;
		const double ref = nAbove >= minPx
		                       ? sAbove / nAbove
		                       : (sRest + sAbove) / (nRest + nAbove);
		const double step = std::abs(sIn / nIn - ref);
		MRPT_LOG_DEBUG_FMT(
		    "seam split %d: stretch %.2f..%.2f m below %.2f m, %d px, step "
		    "%.4f (%s)",
		    slot, a0, a1, top, nIn, step, nAbove >= minPx ? "above" : "rest");
		if (step < o.doorSeamSplitOffset) continue;
		for (int i = i0; i < i1; i++)
		{
			const int p = pix[i];
			const double u = alongOf(p);
			if (u > a0 && u < a1 && P[p][2] < top)
			{
				m_side[p] = 1;
				any = true;
			}
		}
	}
	return any;
}

}  // namespace semnav

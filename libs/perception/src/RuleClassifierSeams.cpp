/* semnav: semantic navigation from tilting-laser sweeps */
/* RuleClassifier, step 3: a plane step too small for the plain split (a
 * nearly flush door leaf) is cut along the seams beside it. */
#include <semnav/perception/RuleClassifier.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

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

/** A slot's pixels (`pix[i0..i1)`, points `P`) and where they lie along
 * the plane with this normal (u: horizontal, along the wall). */
struct SlotAlong
{
	const cv::Vec3f* P;
	const int* pix;
	int i0, i1;
	cv::Vec3d along;
	SlotAlong(
	    const cv::Mat& points, const std::vector<int>& slotPix,
	    const std::vector<int>& slotStart, int slot, const cv::Vec3d& normal)
	    : P(points.ptr<cv::Vec3f>(0)),
	      pix(slotPix.data()),
	      i0(slotStart[slot]),
	      i1(slotStart[slot + 1]),
	      along(-normal[1], normal[0], 0)
	{
	}
	/** Position of pixel p along the plane. */
	double u(int p) const { return along[0] * P[p][0] + along[1] * P[p][1]; }
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
/** Narrows [a0, a1] (along u) to where `side`'s pixels fill the box's
 * slices (kTrimBin wide) between zLo and zHi (along z): the quantiles let
 * in the other side's pixels at a grazing end. Called with u and z swapped
 * it narrows the height. */
void trimBox(
    const std::vector<double> (&u)[2], const std::vector<double> (&z)[2],
    int side, double zLo, double zHi, double& a0, double& a1)
{
	constexpr double kTrimBin = 0.05;
	const int nb = std::max(1, static_cast<int>((a1 - a0) / kTrimBin) + 1);
	std::vector<int> own(nb, 0), all(nb, 0);
	for (int sd = 0; sd < 2; sd++)
		for (std::size_t i = 0; i < u[sd].size(); i++)
		{
			if (u[sd][i] < a0 || u[sd][i] > a1 || z[sd][i] < zLo ||
			    z[sd][i] > zHi)
				continue;
			const int b =
			    std::min(nb - 1, static_cast<int>((u[sd][i] - a0) / kTrimBin));
			all[b]++;
			own[b] += sd == side;
		}
	auto filled = [&](int b) { return all[b] > 0 && 2 * own[b] >= all[b]; };
	int lo = 0, hi = nb - 1;
	while (lo < hi && !filled(lo)) lo++;
	while (hi > lo && !filled(hi)) hi--;
	const double b0 = a0;
	a0 = b0 + lo * kTrimBin;
	a1 = std::min(a1, b0 + (hi + 1) * kTrimBin);
}

/** Robust extents: these quantiles of a side's pixels. */
constexpr double kBoxLo = 0.02, kBoxHi = 0.98;

double quantile(std::vector<double> v, double q)
{
	const std::size_t k = static_cast<std::size_t>(q * (v.size() - 1));
	std::nth_element(v.begin(), v.begin() + k, v.end());
	return v[k];
}

/** The two sides of a group's step (`n` pixels `pix`, smoothed residuals
 * `RS` to the plane normal, offset split at `threshold`) after refitting
 * the plane on the wall. The least-squares plane leans towards a leaf set
 * back over a large part of the group; the wall is the side that spans
 * the wider stretch (it flanks the leaf). A pixel is on the other side
 * when its residual to the wall's plane (the smoothed one shifted by the
 * planes' difference) lies `halfStep` towards that side's mean. False
 * when a side is empty. */
bool refitSides(
    const cv::Vec3f* P, const float* RS, const int* pix, int n, float threshold,
    const cv::Vec3d& normal, double offset, double halfStep,
    std::vector<uint8_t>& sideOf)
{
	const cv::Vec3d along(-normal[1], normal[0], 0);
	sideOf.assign(n, 0);
	std::vector<double> us[2];
	double mean[2] = {0, 0};
	for (int i = 0; i < n; i++)
	{
		const int p = pix[i], sd = RS[p] >= threshold;
		sideOf[i] = static_cast<uint8_t>(sd);
		us[sd].push_back(along[0] * P[p][0] + along[1] * P[p][1]);
		mean[sd] += RS[p];
	}
	if (us[0].size() < 2 || us[1].size() < 2) return false;
	for (int sd = 0; sd < 2; sd++) mean[sd] /= us[sd].size();
	auto span = [&](int sd)
	{ return quantile(us[sd], kBoxHi) - quantile(us[sd], kBoxLo); };
	const int wall = span(0) >= span(1) ? 0 : 1;
	double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
	int cnt = 0;
	for (int i = 0; i < n; i++)
	{
		if (sideOf[i] != wall) continue;
		const double x = P[pix[i]][0], y = P[pix[i]][1];
		sx += x;
		sy += y;
		sxx += x * x;
		sxy += x * y;
		syy += y * y;
		cnt++;
	}
	const double cx = sx / cnt, cy = sy / cnt;
	const double a = sxx / cnt - cx * cx, b = sxy / cnt - cx * cy,
	             d = syy / cnt - cy * cy;
	// Normal: the covariance's smaller eigenvector, facing as before.
	const double lmin =
	    0.5 * (a + d) -
	    std::sqrt(std::max(0.0, 0.25 * (a - d) * (a - d) + b * b));
	cv::Vec2d m = std::abs(b) > 1e-12
	                  ? cv::Vec2d(b, lmin - a)
	                  : (a < d ? cv::Vec2d(1, 0) : cv::Vec2d(0, 1));
	m /= cv::norm(m);
	if (m[0] * normal[0] + m[1] * normal[1] < 0) m = -m;
	const double off = m[0] * cx + m[1] * cy;
	const double toward = mean[1 - wall] > mean[wall] ? 1 : -1;
	for (int i = 0; i < n; i++)
	{
		const int p = pix[i];
		const double x = P[p][0], y = P[p][1];
		const double r = RS[p] - (normal[0] * x + normal[1] * y - offset) +
		                 (m[0] * x + m[1] * y - off);
		sideOf[i] =
		    static_cast<uint8_t>(toward * r >= halfStep ? 1 - wall : wall);
	}
	return true;
}

/** A side's box along the plane (u) and in height (z), and how the other
 * side lies around it. */
struct LeafBox
{
	double a0 = 0, a1 = 0, zLo = 0, zHi = 0;
	int above = 0, beside = 0;  ///< other side's pixels above, beside it
	double purity = 0;          ///< share of the box's pixels on `side`
};

LeafBox leafBoxOf(
    const std::vector<double> (&u)[2], const std::vector<double> (&z)[2],
    int side)
{
	LeafBox b;
	b.a0 = quantile(u[side], kBoxLo);
	b.a1 = quantile(u[side], kBoxHi);
	b.zLo = quantile(z[side], kBoxLo);
	b.zHi = quantile(z[side], kBoxHi);
	trimBox(u, z, side, b.zLo, b.zHi, b.a0, b.a1);
	trimBox(z, u, side, b.a0, b.a1, b.zLo, b.zHi);
	const int other = 1 - side;
	int intruders = 0, own = 0;
	for (std::size_t i = 0; i < u[other].size(); i++)
	{
		const double uu = u[other][i], zz = z[other][i];
		const bool inU = uu > b.a0 && uu < b.a1;
		if (inU && zz > b.zHi + 0.05)
			b.above++;
		else if (!inU)
			b.beside++;
		else if (zz >= b.zLo && zz <= b.zHi)
			intruders++;
	}
	for (std::size_t i = 0; i < u[side].size(); i++)
		own += u[side][i] > b.a0 && u[side][i] < b.a1 && z[side][i] >= b.zLo &&
		       z[side][i] <= b.zHi;
	b.purity = double(own) / std::max(1, own + intruders);
	return b;
}

/** Raw residuals of a group summed in kLintelBin squares along the plane
 * (column, u) and in height (row, z); per column, prefix sums over z. */
struct ResidualGrid
{
	double u0 = 0, z0 = 0;
	int nu = 0, nz = 0;
	std::vector<double> sum;  ///< (nz + 1) x nu, prefix over z
	std::vector<int> cnt;     ///< (nz + 1) x nu, prefix over z
	/** Residual sum and pixel count of column c, rows [z0b, z1b). */
	std::pair<double, int> band(int c, int z0b, int z1b) const
	{
		z0b = std::clamp(z0b, 0, nz);
		z1b = std::clamp(z1b, 0, nz);
		if (z1b <= z0b) return {0.0, 0};
		return {
		    sum[z1b * nu + c] - sum[z0b * nu + c],
		    cnt[z1b * nu + c] - cnt[z0b * nu + c]};
	}
};

/** Bins of the lintel split (m), and its bands: below a candidate height
 * h, rows h - kBelow .. h - kGap; above it, h + kGap .. h + kGap + kAbove
 * (the leaf's top gap and the smoothing stay out of both). */
constexpr double kLintelBin = 0.05;
constexpr int kLintelGap = 2, kLintelBelow = 12, kLintelAbove = 5;
/** A column's band needs this many pixels. */
constexpr int kLintelMinPixels = 5;

/** Per column, the mean residual below height row h minus the mean above
 * it (NaN where either band has too few pixels). */
std::vector<double> lintelSteps(const ResidualGrid& g, int h)
{
	std::vector<double> d(g.nu, std::numeric_limits<double>::quiet_NaN());
	for (int c = 0; c < g.nu; c++)
	{
		const auto lo = g.band(c, h - kLintelBelow, h - kLintelGap);
		const auto hi =
		    g.band(c, h + kLintelGap, h + kLintelGap + kLintelAbove);
		if (lo.second >= kLintelMinPixels && hi.second >= kLintelMinPixels)
			d[c] = lo.first / lo.second - hi.first / hi.second;
	}
	return d;
}

/** A stretch of columns [c0, c1] stepping under row h by `sign`. */
struct LintelRun
{
	int c0 = -1, c1 = -1, h = -1, sign = 0;
	double score = 0;
};

/** The best stretch of `d` (columns stepping by half `step` with the sign,
 * single unseen columns inside allowed) minBins..maxBins wide, whose mean
 * steps by `step`, with a flat flank (two columns within half `step`) on
 * one side and a flat or unseen one on the other. */
LintelRun bestLintelRun(
    const std::vector<double>& d, int h, double step, int minBins, int maxBins)
{
	constexpr int kFlank = 3;
	const int n = static_cast<int>(d.size());
	LintelRun best;
	for (int sign = -1; sign <= 1; sign += 2)
	{
		auto in = [&](int c) { return sign * d[c] >= 0.5 * step; };
		int c = 0;
		while (c < n)
		{
			if (std::isnan(d[c]) || !in(c))
			{
				c++;
				continue;
			}
			int c1 = c;
			double sum = 0;
			int valid = 0;
			for (int k = c; k < n; k++)
			{
				if (std::isnan(d[k]))
				{
					if (k + 1 < n && !std::isnan(d[k + 1]) && in(k + 1))
						continue;
					break;
				}
				if (!in(k)) break;
				sum += sign * d[k];
				valid++;
				c1 = k;
			}
			auto flank = [&](int from, int dir, bool& open)
			{
				int flat = 0, seen = 0;
				for (int k = 1; k <= kFlank; k++)
				{
					const int cc = from + dir * k;
					if (cc < 0 || cc >= n || std::isnan(d[cc])) continue;
					seen++;
					flat += std::abs(d[cc]) < 0.5 * step;
				}
				open = seen == 0;
				return flat >= 2;
			};
			bool openL = false, openR = false;
			const bool flatL = flank(c, -1, openL), flatR = flank(c1, 1, openR);
			const int w = c1 - c + 1;
			const double mean = sum / valid;
			if (w >= minBins && w <= maxBins && mean >= step &&
			    ((flatL && (flatR || openR)) || (flatR && openL)) &&
			    sum > best.score)
				best = {c, c1, h, sign, sum};
			c = c1 + 1;
		}
	}
	return best;
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
	const SlotAlong sa(*m_points, m_slotPix, m_slotStart, slot, normal);
	const auto* P = sa.P;
	const auto* PM = m_pointMask->ptr<uint8_t>(0);
	const int* CO = m_colOf.data();
	const int* pix = sa.pix;
	const int i0 = sa.i0, i1 = sa.i1;
	auto residual = [&](int p) { return planeResidual(normal, offset, P[p]); };
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
				    {0.5 * (sa.u(prev) + sa.u(p)),
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
		const double u = sa.u(pix[i]);
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
			const double u = sa.u(p), r = residual(p);
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
			const double u = sa.u(p);
			if (u > a0 && u < a1 && P[p][2] < top)
			{
				m_side[p] = 1;
				any = true;
			}
		}
	}
	return any;
}

bool RuleClassifier::splitDoorShaped(
    int slot, float threshold, const cv::Vec3d& normal, double offset)
{
	// A side fills its box when this share of the box's pixels are its
	// own (the smoothing blurs the boundary; noise on a flat wall gives
	// scattered sides, not a filled box).
	constexpr double kDoorShapeMinPurity = 0.8;
	const TOptions& o = m_options;
	if (!o.doorShapeSplit) return false;
	const SlotAlong sa(*m_points, m_slotPix, m_slotStart, slot, normal);
	const auto* P = sa.P;
	const int* pix = sa.pix;
	const int i0 = sa.i0, i1 = sa.i1;
	std::vector<uint8_t> sideOf;
	if (!refitSides(
	        P, m_resSum.ptr<float>(0), pix + i0, i1 - i0, threshold, normal,
	        offset, 0.5 * o.doorSeamSplitOffset, sideOf))
		return false;
	std::vector<double> u[2], z[2];
	for (int i = i0; i < i1; i++)
	{
		const int p = pix[i];
		const int side = sideOf[i - i0];
		u[side].push_back(sa.u(p));
		z[side].push_back(P[p][2]);
	}
	const int minPx = o.minSurfacePixels;
	for (int side = 0; side < 2; side++)
	{
		if (static_cast<int>(u[side].size()) < minPx ||
		    static_cast<int>(u[1 - side].size()) < minPx)
			continue;
		const LeafBox b = leafBoxOf(u, z, side);
		MRPT_LOG_DEBUG_FMT(
		    "shape split %d: side %d box %.2f..%.2f m z %.2f..%.2f, above %d "
		    "beside %d, purity %.2f",
		    slot, side, b.a0, b.a1, b.zLo, b.zHi, b.above, b.beside, b.purity);
		if (b.a1 - b.a0 < o.doorSearchMinSize || b.a1 - b.a0 > o.doorMaxWidth ||
		    b.zHi - b.zLo < o.doorSearchMinSize ||
		    b.zHi - b.zLo > o.doorMaxHeight || b.above < minPx ||
		    b.beside < minPx || b.purity < kDoorShapeMinPurity)
			continue;
		bool any = false;
		for (int i = i0; i < i1; i++)
		{
			const int p = pix[i];
			const double uu = sa.u(p);
			const bool in = uu > b.a0 && uu < b.a1 && P[p][2] <= b.zHi + 0.02;
			m_side[p] = in ? 1 : 0;
			any |= in;
		}
		return any;
	}
	return false;
}

bool RuleClassifier::splitUnderLintel(
    int slot, const cv::Vec3d& normal, double offset, int onSide)
{
	const TOptions& o = m_options;
	if (!o.doorLintelSplit || o.doorSeamSplitOffset <= 0) return false;
	// (onSide >= 0: only that side's pixels, and the leaf gets side 2.)
	auto used = [&](int p) { return onSide < 0 || m_side[p] == onSide; };
	const SlotAlong sa(*m_points, m_slotPix, m_slotStart, slot, normal);
	const auto* P = sa.P;
	const int* pix = sa.pix;
	const int i0 = sa.i0, i1 = sa.i1;
	ResidualGrid g;
	double uHi = -1e30, zHi = -1e30;
	g.u0 = g.z0 = 1e30;
	for (int i = i0; i < i1; i++)
	{
		const int p = pix[i];
		if (!used(p)) continue;
		g.u0 = std::min(g.u0, sa.u(p));
		uHi = std::max(uHi, sa.u(p));
		g.z0 = std::min(g.z0, double(P[p][2]));
		zHi = std::max(zHi, double(P[p][2]));
	}
	const int minBins =
	    static_cast<int>(std::ceil(o.doorSearchMinSize / kLintelBin));
	const int maxBins = static_cast<int>(o.doorMaxWidth / kLintelBin);
	g.nu = static_cast<int>((uHi - g.u0) / kLintelBin) + 1;
	g.nz = static_cast<int>((zHi - g.z0) / kLintelBin) + 1;
	if (g.nu < minBins || g.nz < kLintelBelow + kLintelGap + kLintelAbove)
		return false;
	g.sum.assign((g.nz + 1) * g.nu, 0.0);
	g.cnt.assign((g.nz + 1) * g.nu, 0);
	for (int i = i0; i < i1; i++)
	{
		const int p = pix[i];
		if (!used(p)) continue;
		const int c = static_cast<int>((sa.u(p) - g.u0) / kLintelBin);
		const int r = static_cast<int>((P[p][2] - g.z0) / kLintelBin);
		g.sum[(r + 1) * g.nu + c] += planeResidual(normal, offset, P[p]);
		g.cnt[(r + 1) * g.nu + c]++;
	}
	for (int r = 1; r <= g.nz; r++)
		for (int c = 0; c < g.nu; c++)
		{
			g.sum[r * g.nu + c] += g.sum[(r - 1) * g.nu + c];
			g.cnt[r * g.nu + c] += g.cnt[(r - 1) * g.nu + c];
		}
	// Candidate heights: a leaf shows door_search_min_size_m of its height
	// and is at most door_max_height_m high.
	const int hLo = std::max(
	    kLintelBelow,
	    static_cast<int>(std::ceil(o.doorSearchMinSize / kLintelBin)));
	const int hHi = std::min(
	    g.nz - kLintelGap - kLintelAbove,
	    static_cast<int>(o.doorMaxHeight / kLintelBin));
	LintelRun best;
	for (int h = hLo; h <= hHi; h++)
	{
		const LintelRun r = bestLintelRun(
		    lintelSteps(g, h), h, o.doorSeamSplitOffset, minBins, maxBins);
		if (r.score > best.score) best = r;
	}
	if (best.sign == 0) return false;
	const double a0 = g.u0 + best.c0 * kLintelBin,
	             a1 = g.u0 + (best.c1 + 1) * kLintelBin,
	             top = g.z0 + best.h * kLintelBin;
	MRPT_LOG_DEBUG_FMT(
	    "lintel split %d: stretch %.2f..%.2f m below %.2f m, step %.4f", slot,
	    a0, a1, top,
	    best.sign * best.score / std::max(1, best.c1 - best.c0 + 1));
	if (onSide >= 0)
	{
		// A stretch holding the other side's pixels below its top is a
		// leaf that the first cut already cut apart (its seams): kept so.
		int other = 0;
		for (int i = i0; i < i1; i++)
		{
			const int p = pix[i];
			const double u = sa.u(p);
			other += !used(p) && u >= a0 && u < a1 && P[p][2] < top;
		}
		if (other >= o.minSurfacePixels) return false;
	}
	bool any = false;
	for (int i = i0; i < i1; i++)
	{
		const int p = pix[i];
		if (!used(p)) continue;
		const double u = sa.u(p);
		const bool in = u >= a0 && u < a1 && P[p][2] < top;
		if (onSide < 0)
			m_side[p] = in ? 1 : 0;
		else if (in)
			m_side[p] = 2;
		any |= in;
	}
	return any;
}

}  // namespace semnav

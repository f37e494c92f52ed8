/* semnav: semantic navigation from tilting-laser sweeps */
/* RuleClassifier, step 3: coplanar vertical pieces grouped
 * (mergeCoplanar) and groups split where their plane steps (splitPlanes). */
#include <semnav/perception/RuleClassifier.h>

#include <algorithm>
#include <cmath>

#include "BoxSum.h"
#include "RuleClassifierDetail.h"

namespace semnav
{
using namespace detail::rules;

namespace detail::rules
{
OtsuSplit otsuSplit(const std::vector<int>& hist)
{
	const int kBins = static_cast<int>(hist.size());
	OtsuSplit res;
	double total = 0, sumAll = 0;
	for (int b = 0; b < kBins; b++)
	{
		total += hist[b];
		sumAll += hist[b] * (b + 0.5);
	}
	res.total = total;
	double w0 = 0, s0 = 0, best = -1;
	for (int b = 0; b < kBins - 1; b++)
	{
		// (An empty bin changes nothing: its split is the previous one.)
		if (hist[b] == 0) continue;
		w0 += hist[b];
		s0 += hist[b] * (b + 0.5);
		const double w1 = total - w0;
		if (w0 <= 0 || w1 <= 0) continue;
		const double m0 = s0 / w0, m1 = (sumAll - s0) / w1;
		const double between = w0 * w1 * (m1 - m0) * (m1 - m0);
		if (between > best)
		{
			best = between;
			res.bin = b;
			res.lowMean = m0;
			res.highMean = m1;
			res.lowCount = w0;
		}
	}
	return res;
}
}  // namespace detail::rules

namespace
{
/** Horizontal normal of a 2D point scatter with covariance [a b; b d]
 * (its smallest eigenvector); false when the points do not spread along a
 * line (largest eigenvalue under 3 cm squared). */
bool horizontalNormal(double a, double b, double d, cv::Vec3d& m)
{
	const double tr = a + d, det = a * d - b * b;
	const double lmax =
	    0.5 * tr + std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
	if (lmax <= 0.03 * 0.03) return false;
	cv::Vec2d dir = std::abs(b) > 1e-12 ? cv::Vec2d(b, lmax - a)
	                : a >= d            ? cv::Vec2d(1, 0)
	                                    : cv::Vec2d(0, 1);
	dir *= 1.0 / cv::norm(dir);
	m = cv::Vec3d(-dir[1], dir[0], 0);
	return true;
}

/** fitDominantPlane()'s buffers, reused between groups. */
struct PlaneFitScratch
{
	std::vector<int> hist, bins;
	std::vector<uint64_t> inBand;
	std::vector<float> px, py;
};

// (d * 1000 rounds to the same bin as d / 0.001 for every float d: the
// product is exact in double, the quotient is within 2 ulp of it, and
// d * 1000 is never that close to an integer it is not.)
constexpr double kBandBin = 0.001, kBandBinsPerMetre = 1000;
constexpr int kBandBins = 300;  // 1 mm over +-15 cm

/** The direction (angle of the normal, around a0: coarse 0.5 deg over +-3
 * deg, then fine 0.1 deg) and offset of the band of +-half that holds most
 * of (a sample of) the points (xs, ys); offset0: the fit's offset. */
void bestBand(
    const float* xs, const float* ys, int cnt, double a0, double offset0,
    double half, PlaneFitScratch& s, double& bestA, double& bestD)
{
	constexpr double kStep = 0.1 * M_PI / 180;
	constexpr double kBin = kBandBin, kBinsPerMetre = kBandBinsPerMetre;
	constexpr int kBins = kBandBins;
	const int band =
	    std::max(1, static_cast<int>(std::lround(2 * half / kBin)));
	// (Bins 0..kBins-1 and kBins + 1 .. 2 kBins: the two halves; bin
	// kBins and 2 kBins + 1 take the points outside.)
	std::vector<int>& hist = s.hist;
	hist.resize(2 * kBins + 2);
	std::vector<int>& bins = s.bins;
	std::vector<float>&px = s.px, &py = s.py;
	const detail::SimdKernels& K = detail::simdKernels();
	const int stride = std::max(1, cnt / 384);
	px.clear();
	py.clear();
	for (int i = 0; i < cnt; i += stride)
	{
		px.push_back(xs[i]);
		py.push_back(ys[i]);
	}
	bins.resize(px.size());
	int bestScore = -1;
	bestA = a0;
	bestD = offset0;
	auto tryAngle = [&](double ang)
	{
		const float mx = static_cast<float>(std::cos(ang)),
		            my = static_cast<float>(std::sin(ang));
		const float off = static_cast<float>(offset0);
		// (Two histograms, even and odd points, summed after: runs of
		// neighbouring points fall into one bin, and one histogram
		// would wait for each increment before the next.)
		std::fill(hist.begin(), hist.end(), 0);
		const int np = static_cast<int>(px.size());
		K.distanceBins(
		    px.data(), py.data(), np, mx, my, off, kBinsPerMetre, kBins / 2,
		    kBins, bins.data());
		int i = 0;
		for (; i + 1 < np; i += 2)
		{
			hist[bins[i]]++;
			hist[kBins + 1 + bins[i + 1]]++;
		}
		if (i < np) hist[bins[i]]++;
		for (int b = 0; b < kBins; b++) hist[b] += hist[kBins + 1 + b];
		int run = 0;
		for (int b = 0; b < kBins; b++)
		{
			run += hist[b] - (b >= band ? hist[b - band] : 0);
			if (run > bestScore)
			{
				bestScore = run;
				bestA = ang;
				bestD = offset0 + (b - kBins / 2 + 1 - 0.5 * band) * kBin;
			}
		}
	};
	for (int j = -6; j <= 6; j++) tryAngle(a0 + j * 5 * kStep);
	const double coarse = bestA;
	for (int j = -4; j <= 4; j++)
		if (j != 0) tryAngle(coarse + j * kStep);
}

/** The dominant vertical plane of the points (xs, ys): a least-squares fit
 * of all points (normal, offset on entry) tilts to pass through both
 * planes of a wall with a recessed door and turns the step into a ramp
 * (averaged normals and in-plane differences are biased by the range
 * noise, which lies along the rays). So the normal's direction is searched
 * around the fit for the one that packs most points into a band of +-half
 * (bestBand); then least squares on that band (at least minPixels). */
void fitDominantPlane(
    const float* xs, const float* ys, int cnt, double half, int minPixels,
    cv::Vec3d& normal, double& offset, PlaneFitScratch& s)
{
	const double a0 = std::atan2(normal[1], normal[0]);
	double bestA = a0, bestD = offset;
	bestBand(xs, ys, cnt, a0, offset, half, s, bestA, bestD);
	const cv::Vec3d bestM(std::cos(bestA), std::sin(bestA), 0);
	// Least squares on the points of that band.
	// (Points outside the band would add exact zeros: skipped.)
	double s0 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
	s.inBand.resize((cnt + 63) / 64);
	detail::simdKernels().bandBits(
	    xs, ys, cnt, bestM[0], bestM[1], bestD, half, s.inBand.data());
	for (int w = 0; w < static_cast<int>(s.inBand.size()); w++)
		for (uint64_t m = s.inBand[w]; m; m &= m - 1)
		{
			const int i = w * 64 + __builtin_ctzll(m);
			const double x = xs[i], y = ys[i];
			s0 += 1.0;
			sx += x;
			sy += y;
			sxx += x * x;
			sxy += x * y;
			syy += y * y;
		}
	cv::Vec3d m;
	if (s0 >= minPixels &&
	    horizontalNormal(
	        sxx / s0 - sx * sx / (s0 * s0), sxy / s0 - sx * sy / (s0 * s0),
	        syy / s0 - sy * sy / (s0 * s0), m))
	{
		if (m.dot(bestM) < 0) m = -m;
		normal = m;
		offset = (m[0] * sx + m[1] * sy) / s0;
	}
	else
	{
		normal = bestM;
		offset = bestD;
	}
}
}  // namespace

void RuleClassifier::mergeCoplanar()
{
	const int ns = static_cast<int>(m_surfaces.size());
	m_parent.resize(ns);
	m_loose.resize(ns);
	for (int i = 0; i < ns; i++) m_parent[i] = m_loose[i] = i;
	constexpr int kMinPixels = 5;
	std::vector<uint8_t> canMerge(ns);
	for (int i = 0; i < ns; i++)
		canMerge[i] = m_surfaces[i].orient == kVertical &&
		              m_surfaces[i].count >= kMinPixels;
	collectVerticalPairs(canMerge);
	const SurfaceGraph graph = surfaceGraph(canMerge);
	// Strict groups (one plane: a door 2 cm behind its wall stays apart)
	// and loose ones (one wall, for the size rules: real walls are not
	// flat to a centimetre).
	if (m_options.planeMergeTolerance > 0)
		groupCoplanar(
		    graph, m_options.planeMergeTolerance, m_options.planeMergeAngle,
		    m_parent);
	if (m_options.wallGroupTolerance > 0)
		groupCoplanar(
		    graph, m_options.wallGroupTolerance, m_options.wallGroupAngle,
		    m_loose);
}

void RuleClassifier::collectVerticalPairs(const std::vector<uint8_t>& canMerge)
{
	const int rows = m_rows, cols = m_cols;
	const int ns = static_cast<int>(m_surfaces.size());
	auto mergeable = [&](int s) { return canMerge[s] != 0; };
	// Pairs of vertical surfaces with pixels 1 or 2 apart (a row or column
	// of noisy pixels between two pieces of a wall does not part them).
	// (Each surface remembers its last few partners: the same pair shows up
	// along whole boundaries, and sorting all of them is slow.)
	std::vector<uint64_t>& pairs = m_pairs;
	constexpr int kRecent = 4;
	std::vector<int> recent(static_cast<std::size_t>(ns) * kRecent, -1);
	std::vector<uint8_t> recentPos(ns, 0);
	pairs.clear();
	for (int r = 0; r < rows; r++)
	{
		// This row and the next two (null past the last row).
		const int* S0 = m_surf.data() + static_cast<std::size_t>(r) * cols;
		const int* S1 = r + 1 < rows ? S0 + cols : nullptr;
		const int* S2 = r + 2 < rows ? S0 + 2 * cols : nullptr;
		for (int c = 0; c < cols; c++)
		{
			// Four pixels whose four neighbours are all their own surface
			// (a surface's inside, the common case) have nothing to visit.
			constexpr int kLanes = cv::v_int32x4::nlanes;
			if (S2 && c + kLanes + 1 < cols)
			{
				const cv::v_int32x4 v = cv::v_load(S0 + c);
				const cv::v_int32x4 same = (v == cv::v_load(S0 + c + 1)) &
				                           (v == cv::v_load(S0 + c + 2)) &
				                           (v == cv::v_load(S1 + c)) &
				                           (v == cv::v_load(S2 + c));
				if (cv::v_check_all(same))
				{
					c += kLanes - 1;
					continue;
				}
			}
			const int s = S0[c];
			if (s < 0 || !mergeable(s)) continue;
			auto visit = [&](int t)
			{
				// (Inside a surface, the common case: t == s.)
				if (t == s || t < 0 || !mergeable(t)) return;
				int* rs = &recent[static_cast<std::size_t>(s) * kRecent];
				if (rs[0] == t || rs[1] == t || rs[2] == t || rs[3] == t)
					return;
				rs[recentPos[s]] = t;
				recentPos[s] =
				    static_cast<uint8_t>((recentPos[s] + 1) % kRecent);
				const uint64_t a = static_cast<uint64_t>(std::min(s, t)),
				               b = static_cast<uint64_t>(std::max(s, t));
				pairs.push_back(a << 32 | b);
			};
			if (c + 1 < cols) visit(S0[c + 1]);
			if (S1) visit(S1[c]);
			if (c + 2 < cols) visit(S0[c + 2]);
			if (S2) visit(S2[c]);
		}
	}
	std::sort(pairs.begin(), pairs.end());
	pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

RuleClassifier::SurfaceGraph RuleClassifier::surfaceGraph(
    const std::vector<uint8_t>& canMerge) const
{
	const int ns = static_cast<int>(m_surfaces.size());
	const std::vector<uint64_t>& pairs = m_pairs;
	SurfaceGraph graph;
	std::vector<int>&start = graph.start, &adj = graph.adj,
	&order = graph.order;
	start.assign(ns + 1, 0);
	adj.resize(2 * pairs.size());
	for (uint64_t e : pairs)
	{
		start[(e >> 32) + 1]++;
		start[(e & 0xFFFFFFFFu) + 1]++;
	}
	for (int i = 0; i < ns; i++) start[i + 1] += start[i];
	std::vector<int> fill(start.begin(), start.end() - 1);
	for (uint64_t e : pairs)
	{
		const int a = static_cast<int>(e >> 32),
		          b = static_cast<int>(e & 0xFFFFFFFFu);
		adj[fill[a]++] = b;
		adj[fill[b]++] = a;
	}
	for (int i = 0; i < ns; i++)
		if (canMerge[i] && start[i + 1] > start[i]) order.push_back(i);
	std::sort(
	    order.begin(), order.end(),
	    [&](int a, int b)
	    { return m_surfaces[a].count > m_surfaces[b].count; });
	return graph;
}

// Region growing over the surface graph, largest surfaces first: a
// neighbour joins when it is parallel to the group and its centroid
// lies on the group's plane (fitted to all the group's points so far).
// Testing against the group's plane, not the neighbour's, keeps a strip
// that straddles two planes from chaining them together.
void RuleClassifier::groupCoplanar(
    const SurfaceGraph& graph, double tol, double angle,
    std::vector<int>& parent) const
{
	const int ns = static_cast<int>(m_surfaces.size());
	const std::vector<int>&start = graph.start, &adj = graph.adj;
	const double cosMax = std::cos(angle);
	std::vector<uint8_t> grouped(ns, 0);
	std::vector<int> queue;
	for (int seed : graph.order)
	{
		if (grouped[seed]) continue;
		grouped[seed] = 1;
		Surface g = m_surfaces[seed];
		queue.assign(1, seed);
		for (std::size_t h = 0; h < queue.size(); h++)
		{
			const int s = queue[h];
			for (int k = start[s]; k < start[s + 1]; k++)
			{
				const int t = adj[k];
				if (grouped[t]) continue;
				const Surface& b = m_surfaces[t];
				if (b.normal.dot(g.normal) < cosMax) continue;
				if (std::abs(g.normal.dot(b.centroid) - g.planeD()) > tol)
					continue;
				grouped[t] = 1;
				parent[t] = seed;
				queue.push_back(t);
				g.count += b.count;
				g.sumP += b.sumP;
				g.sumN += b.sumN;
				g.sxx += b.sxx;
				g.sxy += b.sxy;
				g.syy += b.syy;
				fitVerticalPlane(g);
			}
		}
	}
}

void RuleClassifier::splitPlanes()
{
	const int n = m_rows * m_cols;
	m_side.assign(n, 0);
	m_groupSplit.assign(m_surfaces.size(), 0);
	m_slotGroup.clear();
	m_slotSeamOnly.clear();
	m_slotStart.assign(1, 0);
	if (m_options.planeSplitOffset <= 0) return;
	std::vector<cv::Vec3d> normal;
	std::vector<double> offset;
	const std::vector<int> slot = selectSplitCandidates(normal, offset);
	if (normal.empty()) return;
	gatherSlotPixels(slot, static_cast<int>(normal.size()));
	// The dominant plane of each group (see fitDominantPlane()).
	PlaneFitScratch scratch;
	for (std::size_t k = 0; k < normal.size(); k++)
	{
		const int cnt = m_slotStart[k + 1] - m_slotStart[k];
		fitDominantPlane(
		    m_slotX.data() + m_slotStart[k], m_slotY.data() + m_slotStart[k],
		    cnt, 0.5 * m_options.planeSplitOffset, m_options.minSurfacePixels,
		    normal[k], offset[k], scratch);
	}
	splitByResiduals(normal, offset);
}

std::vector<int> RuleClassifier::selectSplitCandidates(
    std::vector<cv::Vec3d>& normal, std::vector<double>& offset)
{
	const int ns = static_cast<int>(m_surfaces.size());
	// Group statistics (pass-1 surfaces summed into their group's root;
	// only the sums the plane fit needs: most surfaces are small).
	m_groupSums.assign(ns, GroupSums());
	std::vector<GroupSums>& groups = m_groupSums;
	for (int i = 0; i < ns; i++)
	{
		const Surface& s = m_surfaces[i];
		if (s.orient != kVertical) continue;
		GroupSums& g = groups[m_parent[i]];
		g.count += s.count;
		g.sx += s.sumP[0];
		g.sy += s.sumP[1];
		g.sxx += s.sxx;
		g.sxy += s.sxy;
		g.syy += s.syy;
	}
	std::vector<int> slot(ns, -1);
	int nSlots = 0;
	for (int i = 0; i < ns; i++)
	{
		const GroupSums& g = groups[i];
		// (Only vertical surfaces are summed: count 0 otherwise.)
		if (g.count == 0 || g.count < 2 * m_options.minSurfacePixels) continue;
		const double cx = g.sx / g.count, cy = g.sy / g.count;
		const double a = g.sxx / g.count - cx * cx,
		             b = g.sxy / g.count - cx * cy,
		             d = g.syy / g.count - cy * cy;
		// The least-squares residual (smallest eigenvalue) of a plane with
		// a step of plane_split_offset_m over a fair share of it exceeds
		// this; below it the group is one plane and is not examined.
		const double lmin =
		    0.5 * (a + d) -
		    std::sqrt(std::max(0.0, 0.25 * (a - d) * (a - d) + b * b));
		// (Groups flatter than that are examined for seams only.)
		const double minSpread = 0.25 * m_options.planeSplitOffset;
		const double minSeamSpread = 0.25 * m_options.doorSeamSplitOffset;
		if (lmin < minSeamSpread * minSeamSpread ||
		    (lmin < minSpread * minSpread &&
		     m_options.doorSeamSplitOffset <= 0))
			continue;
		cv::Vec3d m;
		if (!horizontalNormal(a, b, d, m)) continue;
		slot[i] = nSlots++;
		m_slotSeamOnly.push_back(lmin < minSpread * minSpread);
		m_slotGroup.push_back(i);
		normal.push_back(m);
		offset.push_back(m[0] * cx + m[1] * cy);
	}
	return slot;
}

void RuleClassifier::gatherSlotPixels(const std::vector<int>& slot, int nSlots)
{
	const int n = m_rows * m_cols;
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	const int ns = static_cast<int>(m_surfaces.size());
	const std::vector<GroupSums>& groups = m_groupSums;
	// The groups' pixels, grouped by slot, row-major inside (the slots'
	// sizes are their groups' pixel counts; one pass places the pixels).
	// (slotOfSurface is indexed by surface id + 1: -1 is no surface.)
	std::vector<int> slotOfSurface(ns + 1, -1), start(nSlots + 1, 0);
	for (int i = 0; i < ns; i++)
	{
		if (m_surfaces[i].orient == kVertical)
			slotOfSurface[i + 1] = slot[m_parent[i]];
		if (slot[i] >= 0) start[slot[i] + 1] = groups[i].count;
	}
	for (int k = 0; k < nSlots; k++) start[k + 1] += start[k];
	m_slotStart = start;
	// (With their points' x and y alongside: the fits below read them in
	// order.)
	std::vector<int>& pix = m_slotPix;
	pix.resize(start[nSlots]);
	m_slotX.resize(start[nSlots]);
	m_slotY.resize(start[nSlots]);
	{
		std::vector<int> fill(start.begin(), start.end() - 1);
		const int* slotOf = slotOfSurface.data() + 1;
		const int* SF = m_surf.data();
		for (int p = 0; p < n; p++)
		{
			const int k = slotOf[SF[p]];
			if (k < 0) continue;
			const int i = fill[k]++;
			pix[i] = p;
			m_slotX[i] = P[p][0];
			m_slotY[i] = P[p][1];
		}
	}
}

void RuleClassifier::splitByResiduals(
    const std::vector<cv::Vec3d>& normal, const std::vector<double>& offset)
{
	const int rows = m_rows, cols = m_cols;
	const int nSlots = static_cast<int>(normal.size());
	const std::vector<int>& start = m_slotStart;
	const std::vector<int>& pix = m_slotPix;

	// Residuals to that plane, smoothed over a square window (only the
	// groups' pixels count), split by Otsu's threshold; kept when the
	// classes' means differ by at least plane_split_offset_m and both are
	// large enough.
	// (The images are zero outside the groups' pixels: zeroed when
	// allocated, and the pixels written here are reset at the end.)
	if (m_res.rows != rows || m_res.cols != cols)
	{
		m_res = cv::Mat::zeros(rows, cols, CV_32F);
		m_wt = cv::Mat::zeros(rows, cols, CV_32F);
	}
	float* RES = m_res.ptr<float>(0);
	float* WT = m_wt.ptr<float>(0);
	for (int k = 0; k < nSlots; k++)
	{
		// (Groups examined for seams only stay out of the smoothing.)
		if (m_slotSeamOnly[k]) continue;
		const float nx = static_cast<float>(normal[k][0]),
		            ny = static_cast<float>(normal[k][1]),
		            d0 = static_cast<float>(offset[k]);
		for (int i = start[k]; i < start[k + 1]; i++)
		{
			const int p = pix[i];
			RES[p] = nx * m_slotX[i] + ny * m_slotY[i] - d0;
			WT[p] = 1;
		}
	}
	detail::boxSum(m_res, m_options.planeSplitHalfWidth, m_resSum, m_tmp);
	detail::boxSum(m_wt, m_options.planeSplitHalfWidth, m_wtSum, m_tmp);
	float* RS = m_resSum.ptr<float>(0);
	const float* WS = m_wtSum.ptr<float>(0);
	constexpr int kBins = 200;
	constexpr double kRange = 0.1, kBin = 2 * kRange / kBins;
	std::vector<int> hist(kBins);
	for (int k = 0; k < nSlots; k++)
	{
		if (m_slotSeamOnly[k])
		{
			if (splitAtSeams(k, normal[k], offset[k]))
				splitSidesUnderLintel(k, normal[k], offset[k]);
			else if (!splitUnderLintel(k, normal[k], offset[k]))
				continue;
			m_groupSplit[m_parent[m_surf[pix[start[k]]]]] = 1;
			continue;
		}
		std::fill(hist.begin(), hist.end(), 0);
		for (int i = start[k]; i < start[k + 1]; i++)
		{
			const int p = pix[i];
			const float v = RS[p] / WS[p];
			RS[p] = v;
			const int b =
			    std::clamp(static_cast<int>((v + kRange) / kBin), 0, kBins - 1);
			hist[b]++;
		}
		const OtsuSplit split = otsuSplit(hist);
		const int bestB = split.bin;
		const double total = split.total, m0b = split.lowMean,
		             m1b = split.highMean, w0b = split.lowCount;
		if (bestB < 0) continue;
		MRPT_LOG_DEBUG_FMT(
		    "plane split %d: n (%.3f %.3f) d %.3f, %d px, classes %.4f / "
		    "%.4f (%d / %d)",
		    k, normal[k][0], normal[k][1], offset[k], int(total),
		    m0b * kBin - kRange, m1b * kBin - kRange, int(w0b),
		    int(total - w0b));
		const double step = (m1b - m0b) * kBin;
		const bool sized =
		    std::min(w0b, total - w0b) >= m_options.minSurfacePixels;
		const float thr = static_cast<float>((bestB + 1) * kBin - kRange);
		// A smaller step splits where seams run along it (a nearly flush
		// door), or between seams.
		if (step < m_options.planeSplitOffset)
		{
			if (m_options.doorSeamSplitOffset <= 0) continue;
			const bool seamed = sized &&
			                    step >= m_options.doorSeamSplitOffset &&
			                    seamShare(k, thr, normal[k], offset[k]) >=
			                        m_options.doorSeamMinShare;
			if (!seamed)
			{
				// Else a leaf-shaped side under the other (the seams unseen
				// at a grazing angle, or the frame flush).
				// Or a leaf under its lintel (the plane leaning towards
				// a leaf that covers much of the group hides the step).
				if (splitAtSeams(k, normal[k], offset[k]))
					splitSidesUnderLintel(k, normal[k], offset[k]);
				else if (
				    !(sized && step >= m_options.doorSeamSplitOffset &&
				      splitDoorShaped(k, thr, normal[k], offset[k])) &&
				    !splitUnderLintel(k, normal[k], offset[k]))
					continue;
				m_groupSplit[m_parent[m_surf[pix[start[k]]]]] = 1;
				continue;
			}
		}
		else if (!sized)
			continue;
		bool any = false;
		for (int i = start[k]; i < start[k + 1]; i++)
		{
			const bool side = RS[pix[i]] >= thr;
			m_side[pix[i]] = side ? 1 : 0;
			any |= side;
		}
		// Split: pass 2 labels this group's pixels by side.
		if (!any) continue;
		splitSidesUnderLintel(k, normal[k], offset[k]);
		m_groupSplit[m_parent[m_surf[pix[start[k]]]]] = 1;
	}
	for (int p : pix) RES[p] = WT[p] = 0;
}

void RuleClassifier::splitSidesUnderLintel(
    int slot, const cv::Vec3d& normal, double offset)
{
	// A step elsewhere in the group (a recessed leaf, a wall's corner) or
	// a seam cut beside the leaf left a nearly flush leaf in one side.
	if (!m_options.doorLintelAfterCut) return;
	for (int side = 0; side < 2; side++)
		splitUnderLintel(slot, normal, offset, side);
}

}  // namespace semnav

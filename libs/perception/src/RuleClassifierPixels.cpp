/* semnav: semantic navigation from tilting-laser sweeps */
/* RuleClassifier, steps 5 and 6: pixels (surface labels, then leftovers)
 * and the outdoor ground's types. */
#include <semnav/perception/RuleClassifier.h>

#include <algorithm>
#include <cmath>

#include "RuleClassifierDetail.h"

namespace semnav
{
using namespace detail::rules;

namespace
{
/** Undetermined squares (0) of an sr x sc grid take the nearest determined
 * one's type (> 0; -1: no ground). */
void spreadSquareTypes(std::vector<int8_t>& sq, int sr, int sc)
{
	std::vector<int> queue;
	for (int k = 0; k < sr * sc; k++)
		if (sq[k] > 0) queue.push_back(k);
	for (std::size_t h = 0; h < queue.size(); h++)
	{
		const int k = queue[h], r = k / sc, c = k % sc;
		const int nb[4] = {
		    c > 0 ? k - 1 : -1, c + 1 < sc ? k + 1 : -1, r > 0 ? k - sc : -1,
		    r + 1 < sr ? k + sc : -1};
		for (int q : nb)
			if (q >= 0 && sq[q] == 0)
			{
				sq[q] = sq[k];
				queue.push_back(q);
			}
	}
}

/** Patches of one type (4-connected squares) under minSquares inside the
 * other type are absorbed by it. */
void absorbSmallPatches(std::vector<int8_t>& sq, int sr, int sc, int minSquares)
{
	std::vector<int> comp(sr * sc, -1), members;
	for (int k0 = 0; k0 < sr * sc; k0++)
	{
		if (sq[k0] <= 0 || comp[k0] >= 0) continue;
		members.clear();
		members.push_back(k0);
		comp[k0] = k0;
		int other = 0;
		for (std::size_t h = 0; h < members.size(); h++)
		{
			const int k = members[h], r = k / sc, c = k % sc;
			const int nb[4] = {
			    c > 0 ? k - 1 : -1, c + 1 < sc ? k + 1 : -1,
			    r > 0 ? k - sc : -1, r + 1 < sr ? k + sc : -1};
			for (int q : nb)
			{
				if (q < 0 || sq[q] <= 0) continue;
				if (sq[q] != sq[k0])
					other++;
				else if (comp[q] < 0)
				{
					comp[q] = k0;
					members.push_back(q);
				}
			}
		}
		if (other > 0 && static_cast<int>(members.size()) < minSquares)
			for (int k : members) sq[k] = sq[k0] == 1 ? 2 : 1;
	}
}
}  // namespace

void RuleClassifier::labelPixels(double zg)
{
	labelSurfacePixels();
	if (!m_options.classifyLeftoverPixels) return;
	seedLeftovers();
	growLeftovers(zg);
	reclaimWallPlanes();
}

void RuleClassifier::labelSurfacePixels()
{
	const int n = m_rows * m_cols;
	const std::size_t ns = m_surfaces.size();
	const auto* PM = m_pointMask->ptr<uint8_t>(0);
	// (Labels per surface in a compact array: the pixels look them up.)
	m_label.resize(n);
	m_owner.resize(n);
	m_stack.clear();
	m_surfLabel.resize(ns + 1);
	m_surfLabel[0] = kNoLabel;  // no surface (id -1)
	for (std::size_t i = 0; i < ns; i++)
		m_surfLabel[i + 1] = m_surfaces[i].label;
	const int8_t* SL = m_surfLabel.data() + 1;
	int8_t* LB = m_label.data();
	int* OW = m_owner.data();
	const int* SF = m_surf.data();
	// m_seed: 1 on valid pixels without a label (the leftovers).
	m_seed.resize(n);
	uint8_t* FR = m_seed.data();
	for (int p = 0; p < n; p++)
	{
		const int s = SF[p];
		const int8_t l = SL[s];  // s >= -1
		LB[p] = l;
		OW[p] = l != kNoLabel ? s : -1;
		FR[p] = (PM[p] != 0) & (l == kNoLabel);
	}
}

void RuleClassifier::seedLeftovers()
{
	const int rows = m_rows, cols = m_cols;
	// Seeds: labelled pixels next to a leftover, in row-major order.
	const uint8_t* FR = m_seed.data();
	const int8_t* LB = m_label.data();
	m_zeroRow.assign(cols, 0);
	auto seed = [&](int p, int near)
	{
		if ((near != 0) & (LB[p] != kNoLabel)) m_stack.push_back(p);
	};
	for (int r = 0; r < rows; r++)
	{
		const int base = r * cols;
		const uint8_t* F = FR + base;
		const uint8_t* up = r + 1 < rows ? F + cols : m_zeroRow.data();
		const uint8_t* down = r > 0 ? F - cols : m_zeroRow.data();
		if (cols == 1)
		{
			seed(base, up[0] | down[0]);
			continue;
		}
		seed(base, F[1] | up[0] | down[0]);
		// Eight pixels at a time (most have no leftover near them):
		// bit 7 of byte k set where pixel c + k is a seed.
		int c = 1;
		for (; c + 9 <= cols; c += 8)
		{
			const uint64_t near = load64(F + c - 1) | load64(F + c + 1) |
			                      load64(up + c) | load64(down + c);
			if (!near) continue;
			const uint64_t labelled = ~load64(LB + base + c);  // != -1
			constexpr uint64_t k7f = 0x7f7f7f7f7f7f7f7full;
			const uint64_t nonZero = ((labelled & k7f) + k7f) | labelled;
			uint64_t m = nonZero & (near << 7) & ~k7f;
			for (; m; m &= m - 1)
				m_stack.push_back(base + c + (__builtin_ctzll(m) >> 3));
		}
		for (; c + 1 < cols; c++)
			seed(base + c, F[c - 1] | F[c + 1] | up[c] | down[c]);
		seed(base + cols - 1, F[cols - 2] | up[cols - 1] | down[cols - 1]);
	}
}

void RuleClassifier::growLeftovers(double zg)
{
	const TOptions& o = m_options;
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	const std::size_t ns = m_surfaces.size();
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	const int* A = m_areas->ptr<int>(0);
	const float tolG = static_cast<float>(o.groundTolerance);
	const double tolP = o.leftoverPlaneTolerance;
	// Range areas that hold the floor, a wall or the ceiling: an obstacle
	// in one of them is not apart from them by range. Standing on the
	// ground (a cabinet against a wall) it claims the points on its plane,
	// not its whole area; off the ground (a fragment of a wall) nothing.
	int maxArea = 0;
	for (const Surface& S : m_surfaces) maxArea = std::max(maxArea, S.area);
	std::vector<uint8_t> structural(maxArea + 1, 0);
	for (const Surface& S : m_surfaces)
		if (S.label != kNoLabel && S.label != lab(Label::Obstacle) &&
		    S.area > 0)
			structural[S.area] = 1;
	// What each labelled surface accepts, compact (read per pixel).
	m_claim.resize(ns);
	for (std::size_t i = 0; i < ns; i++)
	{
		const Surface& S = m_surfaces[i];
		Claim& cl = m_claim[i];
		cl.label = S.label;
		const bool apart = S.area > 0 && !structural[S.area];
		const bool standing = S.minP[2] <= zg + o.groundTolerance;
		cl.kind = isGround(S.label)                 ? Claim::kGround
		          : S.label != lab(Label::Obstacle) ? Claim::kPlane
		          : apart                           ? Claim::kArea
		          : standing                        ? Claim::kPlane
		                                            : Claim::kNothing;
		cl.area = S.area;
		cl.nx = S.normal[0];
		cl.ny = S.normal[1];
		cl.nz = S.normal[2];
		cl.d = S.planeD();
	}
	auto accepts = [&](const Claim& cl, int q)
	{
		const cv::Vec3f& x = P[q];
		if (cl.kind == Claim::kGround) return std::abs(x[2] - zg) <= tolG;
		if (cl.kind == Claim::kArea) return A[q] >= 1 && A[q] == cl.area;
		if (cl.kind == Claim::kNothing) return false;
		return std::abs(cl.nx * x[0] + cl.ny * x[1] + cl.nz * x[2] - cl.d) <=
		       tolP;
	};
	// FIFO over the seeds in m_stack: the nearest surface claims first.
	// (m_seed is cleared where a pixel is claimed: 1 = still open.)
	uint8_t* open = m_seed.data();
	for (std::size_t head = 0; head < m_stack.size(); head++)
	{
		const int p = m_stack[head];
		const int r = RO[p], c = CO[p], s = m_owner[p];
		const Claim& cl = m_claim[s];
		const int nb[4] = {
		    c > 0 ? p - 1 : -1, c + 1 < cols ? p + 1 : -1,
		    r > 0 ? p - cols : -1, r + 1 < rows ? p + cols : -1};
		for (int q : nb)
		{
			if (q < 0 || !open[q] || !accepts(cl, q)) continue;
			open[q] = 0;
			m_label[q] = cl.label;
			m_owner[q] = s;
			m_stack.push_back(q);
		}
	}
	for (int p = 0; p < n; p++)
	{
		if (!open[p]) continue;
		const float z = P[p][2];
		if (std::abs(z - zg) <= tolG)
			m_label[p] = lab(Label::Floor);
		else if (z > zg + tolG)
			m_label[p] = lab(Label::Obstacle);
	}
}

void RuleClassifier::labelGroundTypes(
    const Roughness& roughness, LabeledSweep& out)
{
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	uint8_t* L = out.labels.ptr<uint8_t>(0);
	const int w = std::max(1, roughness.options().squareWidth);
	// R-bar per square over the ground pixels (one group: the ground).
	cv::Mat groups(rows, cols, CV_32S);
	int* G = groups.ptr<int>(0);
	for (int p = 0; p < n; p++) G[p] = L[p] == lab(Label::Floor) ? 1 : 0;
	cv::Mat rbar;
	if (roughness.r().rows == rows && roughness.r().cols == cols)
		Roughness::squareMeans(
		    roughness.r(), groups, w, roughness.options().minSquarePixels,
		    rbar);
	else
		rbar = cv::Mat(rows, cols, CV_32F, cv::Scalar(NAN));
	const int sr = (rows + w - 1) / w, sc = (cols + w - 1) / w;
	// Per square: -1 no ground, 0 undetermined, 1 sidewalk, 2 grass.
	std::vector<int8_t> sq(sr * sc, -1);
	for (int p = 0; p < n; p++)
	{
		if (!G[p]) continue;
		const int k = (RO[p] / w) * sc + CO[p] / w;
		if (sq[k] <= 0)
		{
			const float v = rbar.ptr<float>(0)[p];
			sq[k] = !std::isfinite(v)                ? 0
			        : v >= m_options.sidewalkMinRbar ? 1
			                                         : 2;
		}
	}
	if (m_options.sidewalkFlatMaxHeightStd > 0)
		typeFlatSquares(G, w, roughness.options().minSquarePixels, sq);
	if (m_options.sidewalkMaxHeightStd > 0)
		typeSquaresByHeight(G, w, roughness.options().minSquarePixels, sq);
	spreadSquareTypes(sq, sr, sc);
	if (m_options.minPatchSquares > 0)
		absorbSmallPatches(sq, sr, sc, m_options.minPatchSquares);
	for (int p = 0; p < n; p++)
	{
		if (!G[p]) continue;
		const int k = (RO[p] / w) * sc + CO[p] / w;
		L[p] =
		    static_cast<uint8_t>(sq[k] == 2 ? Label::Grass : Label::Sidewalk);
	}
	if (m_options.sidewalkBorderHalfWidth > 0 && roughness.r().rows == rows &&
	    roughness.r().cols == cols)
		refineGroundBorder(roughness.r(), G, w, sq, L);
}

void RuleClassifier::typeSquaresByHeight(
    const int* G, int w, int minSquarePixels, std::vector<int8_t>& sq) const
{
	// Squares without R-bar (far ground: rows more than eps1 apart carry no
	// normals) are judged by the spread of their ground points' heights:
	// sidewalk when its standard deviation is at most
	// sidewalk_max_height_std_m (needs min_square_px points).
	const auto var = squareHeightVariances(G, w, minSquarePixels, sq, 0);
	const double maxVar =
	    m_options.sidewalkMaxHeightStd * m_options.sidewalkMaxHeightStd;
	for (size_t k = 0; k < sq.size(); k++)
		if (var[k] >= 0) sq[k] = var[k] <= maxVar ? 1 : 2;
}

std::vector<double> RuleClassifier::squareHeightVariances(
    const int* G, int w, int minSquarePixels, const std::vector<int8_t>& sq,
    int8_t type) const
{
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const int n = m_rows * m_cols, sc = (m_cols + w - 1) / w;
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	std::vector<double> s1(sq.size(), 0.0), s2(sq.size(), 0.0);
	std::vector<int> cnt(sq.size(), 0);
	for (int p = 0; p < n; p++)
	{
		if (!G[p]) continue;
		const int k = (RO[p] / w) * sc + CO[p] / w;
		if (sq[k] != type) continue;
		const double z = P[p][2];
		s1[k] += z;
		s2[k] += z * z;
		cnt[k]++;
	}
	std::vector<double> var(sq.size(), -1.0);
	for (size_t k = 0; k < sq.size(); k++)
	{
		if (sq[k] != type || cnt[k] < minSquarePixels) continue;
		const double m = s1[k] / cnt[k];
		var[k] = std::max(0.0, s2[k] / cnt[k] - m * m);
	}
	return var;
}

void RuleClassifier::reclaimWallPlanes()
{
	const TOptions& o = m_options;
	if (o.wallPlaneReclaimTolerance <= 0) return;
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	const int8_t wall = lab(Label::Wall), obstacle = lab(Label::Obstacle);
	const int8_t ceiling = lab(Label::Ceiling);
	const bool ceilings = o.wallPlaneReclaimCeilings;
	auto claims = [&](int8_t l)
	{ return l == wall || (ceilings && l == ceiling); };
	const float tol = static_cast<float>(o.wallPlaneReclaimTolerance);
	// FIFO from every wall pixel of a surface: the nearest wall claims
	// the obstacle pixels on its plane first.
	m_stack.clear();
	for (int p = 0; p < n; p++)
		if (claims(m_label[p]) && m_owner[p] >= 0) m_stack.push_back(p);
	for (std::size_t head = 0; head < m_stack.size(); head++)
	{
		const int p = m_stack[head];
		const int r = RO[p], c = CO[p], s = m_owner[p];
		const Surface& S = m_surfaces[s];
		const double d = S.planeD();
		const int nb[4] = {
		    c > 0 ? p - 1 : -1, c + 1 < cols ? p + 1 : -1,
		    r > 0 ? p - cols : -1, r + 1 < rows ? p + cols : -1};
		for (int q : nb)
		{
			if (q < 0 || m_label[q] != obstacle) continue;
			const cv::Vec3f& x = P[q];
			const double dist = S.normal[0] * x[0] + S.normal[1] * x[1] +
			                    S.normal[2] * x[2] - d;
			if (std::abs(dist) > tol) continue;
			m_label[q] = m_label[p];
			m_owner[q] = s;
			m_stack.push_back(q);
		}
	}
}

}  // namespace semnav

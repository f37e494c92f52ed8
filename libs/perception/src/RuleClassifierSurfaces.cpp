/* semnav: semantic navigation from tilting-laser sweeps */
/* RuleClassifier, step 3: surfaces (pieces of areas, then coplanar groups
 * split by side) and their statistics. */
#include <semnav/perception/RuleClassifier.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "RuleClassifierDetail.h"

namespace semnav
{
using namespace detail::rules;

void RuleClassifier::Surface::addStats(const Surface& o)
{
	if (count == 0)
	{
		minP = o.minP;
		maxP = o.maxP;
		minR = o.minR;
		maxR = o.maxR;
		minC = o.minC;
		maxC = o.maxC;
	}
	count += o.count;
	sumP += o.sumP;
	sumN += o.sumN;
	sxx += o.sxx;
	sxy += o.sxy;
	syy += o.syy;
	for (int k = 0; k < 3; k++)
	{
		minP[k] = std::min(minP[k], o.minP[k]);
		maxP[k] = std::max(maxP[k], o.maxP[k]);
	}
	minR = std::min(minR, o.minR);
	maxR = std::max(maxR, o.maxR);
	minC = std::min(minC, o.minC);
	maxC = std::max(maxC, o.maxC);
}

void RuleClassifier::fitVerticalPlane(Surface& s)
{
	// Vertical: the normal is horizontal. Averaged pixel normals are biased
	// toward the sensor where they are noisy (each one is turned toward the
	// sensor), so when the points spread along a line in the xy plane the
	// normal comes from that line's fit (2D PCA) instead.
	s.centroid = s.sumP * (1.0 / s.count);
	const double cx = s.centroid[0], cy = s.centroid[1];
	const double a = s.sxx / s.count - cx * cx, b = s.sxy / s.count - cx * cy,
	             d = s.syy / s.count - cy * cy;
	const double tr = a + d, det = a * d - b * b;
	const double lmax =
	    0.5 * tr + std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
	cv::Vec3d nrm(s.sumN[0], s.sumN[1], 0);
	if (lmax > 0.03 * 0.03)
	{
		// Direction of the line = eigenvector of lmax; normal = its
		// perpendicular, on the side of the averaged normal.
		cv::Vec2d dir = std::abs(b) > 1e-12 ? cv::Vec2d(b, lmax - a)
		                : a >= d            ? cv::Vec2d(1, 0)
		                                    : cv::Vec2d(0, 1);
		dir *= 1.0 / cv::norm(dir);
		cv::Vec3d fit(-dir[1], dir[0], 0);
		if (fit.dot(nrm) < 0) fit = -fit;
		nrm = fit;
	}
	const double lnh = cv::norm(nrm);
	s.normal = lnh > 0 ? nrm * (1.0 / lnh) : cv::Vec3d(1, 0, 0);
}

void RuleClassifier::finishSurface(Surface& s) const
{
	s.centroid = s.sumP * (1.0 / s.count);
	const double ln = cv::norm(s.sumN);
	s.normal = ln > 0 ? s.sumN * (1.0 / ln) : cv::Vec3d(0, 0, 0);
	s.height = s.maxP[2] - s.minP[2];
	if (s.orient != kVertical)
	{
		s.width = std::max(s.maxP[0] - s.minP[0], s.maxP[1] - s.minP[1]);
		return;
	}
	fitVerticalPlane(s);
	// Extent along the wall, t = z x n: the projections of the bounding
	// box's corners span exactly the segment a planar vertical surface
	// draws in the xy plane (its endpoints are opposite corners).
	const cv::Vec3d t(-s.normal[1], s.normal[0], 0);
	double lo = std::numeric_limits<double>::max(), hi = -lo;
	for (int k = 0; k < 4; k++)
	{
		const double x = (k & 1) ? s.maxP[0] : s.minP[0];
		const double y = (k & 2) ? s.maxP[1] : s.minP[1];
		const double v = t[0] * x + t[1] * y;
		lo = std::min(lo, v);
		hi = std::max(hi, v);
	}
	s.width = hi - lo;
}

void RuleClassifier::computeJoinMask()
{
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	const int* A = m_areas->ptr<int>(0);
	const auto* NS = m_ns->ptr<cv::Vec3f>(0);
	const float* RG = m_ranges->ptr<float>(0);
	const float cosJoin =
	    static_cast<float>(std::cos(m_options.surfaceJoinAngle));
	const float maxStep = static_cast<float>(m_options.surfaceMaxRangeStep);
	// Which 4-neighbours may join (bit 0 right, 1 left, 2 down, 3 up):
	// same area and orientation, continuous ranges, and for vertical
	// and oblique pixels close normals. Precomputed row by row; only
	// the surface's running mean is checked during the fill.
	m_join.resize(n);
	detail::JoinArgs ja;
	ja.rows = rows;
	ja.cols = cols;
	ja.classes = m_class.data();
	ja.areas = A;
	ja.ranges = RG;
	ja.normals = NS[0].val;
	ja.maxStep = maxStep;
	ja.cosJoin = cosJoin;
	ja.join = m_join.data();
	detail::simdKernels().joinMask(ja);
	// Up- and down-facing pixels need no running mean: their surfaces
	// are the connected components of the join graph, found by
	// union-find in one row-major scan (faster than a fill).
	m_uf.resize(n);
	for (int p = 0; p < n; p++)
	{
		m_uf[p] = p;
		const uint8_t cls = m_class[p];
		if (cls != kUp && cls != kDown) continue;
		const uint8_t j = m_join[p];
		if (j & 2) unite(m_uf.data(), p - 1, p);
		if (j & 8) unite(m_uf.data(), p - cols, p);
	}
}

void RuleClassifier::buildPieces()
{
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	const auto* PM = m_pointMask->ptr<uint8_t>(0);
	const int* A = m_areas->ptr<int>(0);
	const auto* NS = m_ns->ptr<cv::Vec3f>(0);
	// Pass 1: 4-connected pixels of one area and one orientation, with
	// continuous ranges; vertical and oblique ones also with normals
	// close to their neighbour's and to the surface's mean.
	computeJoinMask();
	const float cosSpread2 = static_cast<float>(
	    std::cos(m_options.surfaceMaxAngle) *
	    std::cos(m_options.surfaceMaxAngle));
	m_surf.assign(n, -1);
	m_fillStack.resize(n);
	int count = 0;
	// Numbers the surface of `seed` if it has none yet: an up- or
	// down-facing component by its root, else a fill from it. (Every
	// pixel of a new surface lies at or after its seed.)
	auto number = [&](int seed)
	{
		if (m_surf[seed] != -1 || !PM[seed] || A[seed] < 1 ||
		    m_class[seed] == kNone)
			return;
		const uint8_t cls = m_class[seed];
		const bool angular = cls == kVertical || cls == kOblique;
		if (!angular)
		{
			// Roots are the components' smallest pixels: the root is
			// reached first and numbered as a fill would number it.
			int root = seed;
			while (m_uf[root] != root) root = m_uf[root];
			m_uf[seed] = root;
			if (root == seed)
			{
				m_surf[seed] = count++;
				m_surfaces.emplace_back();
			}
			else
				m_surf[seed] = m_surf[root];
			return;
		}
		fillPiece(seed, count++, cosSpread2);
	};
	// One row-major pass numbers the surfaces and sums them up: a
	// pixel's surface is final once its own turn has come.
	m_surfaces.clear();
	RunSums<Surface> sums(
	    m_surfaces, m_points->ptr<cv::Vec3f>(0), NS, m_class.data(), A, n);
	for (int r = 0, p = 0; r < rows; r++)
	{
		sums.flush();
		for (int c = 0; c < cols; c++, p++)
		{
			number(p);
			const int id = m_surf[p];
			if (id != sums.runId()) sums.flush();
			if (id >= 0) sums.add(p, r, c, id);
		}
	}
	sums.flush();
	computeSurfaceStats(count, count);
}

void RuleClassifier::fillPiece(int seed, int id, float cosSpread2)
{
	const int cols = m_cols;
	const auto* NS = m_ns->ptr<cv::Vec3f>(0);
	m_surfaces.emplace_back();
	cv::Vec3f mean(0, 0, 0);  // running normal sum
	float mean2 = 0;
	m_surf[seed] = id;
	// (A pixel enters the stack once: n slots suffice.)
	int* stack = m_fillStack.data();
	int top = 0;
	stack[top++] = seed;
	while (top > 0)
	{
		const int p = stack[--top];
		const uint8_t j = m_join[p];
		mean += NS[p];
		mean2 = mean.dot(mean);
		const int nb[4] = {p - 1, p + 1, p - cols, p + cols};
		const uint8_t bit[4] = {2, 1, 8, 4};
		for (int k = 0; k < 4; k++)
		{
			const int q = nb[k];
			if (!(j & bit[k]) || m_surf[q] != -1) continue;
			// A corner seen at a grazing angle turns slowly from
			// pixel to pixel and must not chain two walls: the
			// normal must also be close to the surface's mean.
			const float d = NS[q].dot(mean);
			if (d < 0 || d * d < cosSpread2 * mean2) continue;
			m_surf[q] = id;
			stack[top++] = q;
		}
	}
}

void RuleClassifier::buildGroupSurfaces()
{
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const int cols = m_cols, n = m_rows * cols;
	int count = 0, firstAccumulated = 0;
	// Pass 2: a group of coplanar pieces is one surface, unless its
	// plane steps (m_side), where connected pieces of each side are.
	// (Groups with pixels on side 1 are known from splitPlanes().)
	const int ns = static_cast<int>(m_surfaces.size());
	const std::vector<uint8_t>& hasSide = m_groupSplit;
	// Unsplit groups: the sum of their pieces' statistics.
	std::vector<int> newId(ns, -1);
	// (Built in a member buffer, swapped in: no allocation per call.)
	std::vector<Surface>& combined = m_combined;
	combined.clear();
	for (int i = 0; i < ns; i++)
	{
		const int g = m_parent[i];
		if (hasSide[g]) continue;
		if (newId[g] < 0)
		{
			newId[g] = count++;
			combined.push_back(Surface());
		}
		Surface& c = combined[newId[g]];
		const Surface& a = m_surfaces[i];
		if (c.count == 0)
		{
			c.orient = a.orient;
			c.area = a.area;
		}
		c.addStats(a);
	}
	// Pixels of unsplit groups take their group's id, those of split
	// groups -2 (to label below). (finalOf is indexed by id + 1.)
	m_finalOf.assign(ns + 1, -1);
	for (int i = 0; i < ns; i++)
	{
		const int g = m_parent[i];
		m_finalOf[i + 1] = hasSide[g] ? -2 : newId[g];
	}
	{
		const int* F = m_finalOf.data() + 1;
		int* SF = m_surf.data();
		for (int p = 0; p < n; p++) SF[p] = F[SF[p]];
	}
	// The split groups' pixels (their slots' pixels), row-major, are
	// numbered below and summed up in computeSurfaceStats().
	m_splitPix.clear();
	int splitGroups = 0;
	for (std::size_t k = 0; k < m_slotGroup.size(); k++)
	{
		const int g = m_slotGroup[k];
		if (!hasSide[g]) continue;
		splitGroups++;
		if (m_group.size() != static_cast<std::size_t>(n)) m_group.resize(n);
		for (int i = m_slotStart[k]; i < m_slotStart[k + 1]; i++)
		{
			const int p = m_slotPix[i];
			m_group[p] = g;
			m_splitPix.push_back(p);
		}
	}
	if (splitGroups > 1) std::sort(m_splitPix.begin(), m_splitPix.end());
	std::swap(m_surfaces, combined);
	m_surfLoose.assign(count, -1);
	for (int i = 0; i < ns; i++)
		if (!hasSide[m_parent[i]] && m_surfLoose[newId[m_parent[i]]] < 0)
			m_surfLoose[newId[m_parent[i]]] = m_loose[i];
	firstAccumulated = count;
	// Connected pixels of one group and one side: union-find over the
	// split pixels (row-major; a component's root is its first pixel,
	// numbered in that order as a fill from each first pixel would).
	for (const int p : m_splitPix) m_uf[p] = p;
	for (const int p : m_splitPix)
	{
		const int g = m_group[p];
		const uint8_t side = m_side[p];
		auto link = [&](int q)
		{
			if (m_surf[q] != -2 || m_group[q] != g || m_side[q] != side) return;
			unite(m_uf.data(), q, p);
		};
		if (CO[p] > 0) link(p - 1);
		if (RO[p] > 0) link(p - cols);
	}
	for (const int p : m_splitPix)
	{
		const int root = findRoot(m_uf.data(), p);
		if (root == p)
		{
			m_surf[p] = count++;
			m_surfLoose.push_back(m_loose[m_group[p]]);
		}
		else
			m_surf[p] = m_surf[root];
	}
	computeSurfaceStats(count, firstAccumulated);
}

void RuleClassifier::computeSurfaceStats(int count, int firstAccumulated)
{
	// Surfaces below firstAccumulated are already summed up (pass 2 adds
	// the pass-1 pieces of unsplit groups); the others start empty.
	m_surfaces.resize(count);
	for (int i = firstAccumulated; i < count; i++) m_surfaces[i] = Surface();
	if (firstAccumulated < count)
	{
		// The split groups' pixels (row-major); a run also ends at a gap.
		const int* RO = m_rowOf.data();
		const int* CO = m_colOf.data();
		RunSums<Surface> sums(
		    m_surfaces, m_points->ptr<cv::Vec3f>(0), m_ns->ptr<cv::Vec3f>(0),
		    m_class.data(), m_areas->ptr<int>(0), m_rows * m_cols);
		int prev = -2;
		for (const int p : m_splitPix)
		{
			const int id = m_surf[p];
			const int c = CO[p];
			if (id != sums.runId() || c == 0 || p != prev + 1) sums.flush();
			prev = p;
			if (id >= firstAccumulated) sums.add(p, RO[p], c, id);
		}
		sums.flush();
	}
	for (Surface& s : m_surfaces) finishSurface(s);
}

}  // namespace semnav

/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/perception/RuleClassifier.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

#include "BoxSum.h"

namespace semnav
{
using mrpt::DEG2RAD;
using mrpt::RAD2DEG;

namespace
{
/** Orientation class of a pixel. */
enum Orient : uint8_t
{
	kNone = detail::kOrientNone,
	kUp = detail::kOrientUp,
	kDown = detail::kOrientDown,
	kVertical = detail::kOrientVertical,
	kOblique = detail::kOrientOblique
};

constexpr int8_t kNoLabel = -1;

int8_t lab(Label l)
{
	return static_cast<int8_t>(l);
}

uint64_t load64(const void* p)
{
	uint64_t v;
	std::memcpy(&v, p, sizeof v);
	return v;
}

bool isGround(int8_t l)
{
	return l == lab(Label::Floor) || l == lab(Label::Sidewalk) ||
	       l == lab(Label::Grass);
}

/** Union-find (roots are components' smallest pixels): x's root, halving
 * the path on the way. */
int findRoot(int* uf, int x)
{
	while (uf[x] != x)
	{
		uf[x] = uf[uf[x]];
		x = uf[x];
	}
	return x;
}

/** Joins the components of a and b (the larger root under the smaller). */
void unite(int* uf, int a, int b)
{
	a = findRoot(uf, a);
	b = findRoot(uf, b);
	if (a != b) uf[std::max(a, b)] = std::min(a, b);
}

/** Point p and its normal as vectors, x y z in the first three lanes (the
 * fourth is the next pixel's x, unused; the last pixel, which has none, is
 * copied first). */
void loadPointAndNormal(
    const cv::Vec3f* points, const cv::Vec3f* normals, int p, int last,
    cv::v_float32x4& vq, cv::v_float32x4& vn)
{
	const float* q = points[p].val;
	const float* nq = normals[p].val;
	float tail[8];
	if (p == last)
	{
		std::copy(q, q + 3, tail);
		std::copy(nq, nq + 3, tail + 4);
		tail[3] = tail[7] = 0;
		q = tail;
		nq = tail + 4;
	}
	vq = cv::v_load(q);
	vn = cv::v_load(nq);
}

/** Sums pixels into surfaces run by run: consecutive pixels of one
 * surface along a row are accumulated in locals (floats: a run is at most
 * one row long) and added to the surface at the run's end (no
 * store-to-load chain through the surface). */
template <class SurfaceT>
class RunSums
{
public:
	/** `points` and `normals` hold `n` pixels. */
	RunSums(
	    std::vector<SurfaceT>& surfaces, const cv::Vec3f* points,
	    const cv::Vec3f* normals, const uint8_t* orient, const int* areas,
	    int n)
	    : m_surfaces(surfaces),
	      m_p(points),
	      m_n(normals),
	      m_orient(orient),
	      m_areas(areas),
	      m_last(n - 1)
	{
	}
	int runId() const { return m_id; }
	/** Adds pixel p (row r, column c) of surface id >= 0 to the run. */
	void add(int p, int r, int c, int id)
	{
		cv::v_float32x4 vq, vn;
		loadPointAndNormal(m_p, m_n, p, m_last, vq, vn);
		const float* q = m_p[p].val;
		if (m_id < 0)
		{
			m_id = id;
			m_count = 0;
			m_sumP = m_sumN = cv::v_setzero_f32();
			m_xx = m_xy = m_yy = 0;
			SurfaceT& s = m_surfaces[id];
			if (s.count == 0)
			{
				s.orient = m_orient[p];
				s.area = m_areas[p];
			}
			m_lo = m_hi = vq;
			m_r = r;
			m_c0 = c;
		}
		m_c1 = c;
		m_count++;
		m_sumP += vq;
		m_sumN += vn;
		m_xx += q[0] * q[0];
		m_xy += q[0] * q[1];
		m_yy += q[1] * q[1];
		m_lo = cv::v_min(m_lo, vq);
		m_hi = cv::v_max(m_hi, vq);
	}
	/** Ends the run (if any): adds it to its surface. */
	void flush()
	{
		if (m_id < 0) return;
		float sp[4], sn[4], lo[4], hi[4];
		cv::v_store(sp, m_sumP);
		cv::v_store(sn, m_sumN);
		cv::v_store(lo, m_lo);
		cv::v_store(hi, m_hi);
		SurfaceT run;
		run.count = m_count;
		run.sumP = cv::Vec3d(sp[0], sp[1], sp[2]);
		run.sumN = cv::Vec3d(sn[0], sn[1], sn[2]);
		run.sxx = m_xx;
		run.sxy = m_xy;
		run.syy = m_yy;
		run.minP = cv::Vec3f(lo[0], lo[1], lo[2]);
		run.maxP = cv::Vec3f(hi[0], hi[1], hi[2]);
		run.minR = run.maxR = m_r;
		run.minC = m_c0;
		run.maxC = m_c1;
		m_surfaces[m_id].addStats(run);
		m_id = -1;
	}

private:
	std::vector<SurfaceT>& m_surfaces;
	const cv::Vec3f* m_p;
	const cv::Vec3f* m_n;
	const uint8_t* m_orient;
	const int* m_areas;
	const int m_last;
	int m_id = -1, m_count = 0, m_r = 0, m_c0 = 0, m_c1 = 0;
	cv::v_float32x4 m_sumP = cv::v_setzero_f32(), m_sumN = cv::v_setzero_f32(),
	                m_lo = cv::v_setzero_f32(), m_hi = cv::v_setzero_f32();
	float m_xx = 0, m_xy = 0, m_yy = 0;
};

}  // namespace

RuleClassifier::RuleClassifier() : RuleClassifier(TOptions()) {}

RuleClassifier::RuleClassifier(const TOptions& options)
    : mrpt::system::COutputLogger("RuleClassifier"), m_options(options)
{
}

cv::Mat RuleClassifier::surfaceIds() const
{
	if (m_surf.size() != static_cast<std::size_t>(m_rows * m_cols))
		return cv::Mat();
	return cv::Mat(m_rows, m_cols, CV_32S, const_cast<int*>(m_surf.data()));
}

cv::Mat RuleClassifier::orientationClasses() const
{
	if (m_class.size() != static_cast<std::size_t>(m_rows * m_cols))
		return cv::Mat();
	return cv::Mat(m_rows, m_cols, CV_8U, const_cast<uint8_t*>(m_class.data()));
}

cv::Mat RuleClassifier::planeSides() const
{
	if (m_side.size() != static_cast<std::size_t>(m_rows * m_cols))
		return cv::Mat();
	return cv::Mat(m_rows, m_cols, CV_8U, const_cast<uint8_t*>(m_side.data()));
}

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

void RuleClassifier::buildSurfaces(bool byGroup)
{
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	const auto* PM = m_pointMask->ptr<uint8_t>(0);
	const int* A = m_areas->ptr<int>(0);
	const auto* NS = m_ns->ptr<cv::Vec3f>(0);
	const float* RG = m_ranges->ptr<float>(0);
	int count = 0, firstAccumulated = 0;
	if (!byGroup)
	{
		// Pass 1: 4-connected pixels of one area and one orientation, with
		// continuous ranges; vertical and oblique ones also with normals
		// close to their neighbour's and to the surface's mean.
		const float cosJoin =
		    static_cast<float>(std::cos(m_options.surfaceJoinAngle));
		const float cosSpread2 = static_cast<float>(
		    std::cos(m_options.surfaceMaxAngle) *
		    std::cos(m_options.surfaceMaxAngle));
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
		m_surf.assign(n, -1);
		m_fillStack.resize(n);
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
			const int id = count++;
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
		firstAccumulated = count;
	}
	else
	{
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
			if (m_group.size() != static_cast<std::size_t>(n))
				m_group.resize(n);
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
				if (m_surf[q] != -2 || m_group[q] != g || m_side[q] != side)
					return;
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

void RuleClassifier::mergeCoplanar()
{
	const int rows = m_rows, cols = m_cols;
	const int ns = static_cast<int>(m_surfaces.size());
	m_parent.resize(ns);
	m_loose.resize(ns);
	for (int i = 0; i < ns; i++) m_parent[i] = m_loose[i] = i;
	constexpr int kMinPixels = 5;
	std::vector<uint8_t> canMerge(ns);
	for (int i = 0; i < ns; i++)
		canMerge[i] = m_surfaces[i].orient == kVertical &&
		              m_surfaces[i].count >= kMinPixels;
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
	std::vector<int> start(ns + 1, 0), adj(2 * pairs.size());
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
	std::vector<int> order;
	for (int i = 0; i < ns; i++)
		if (mergeable(i) && start[i + 1] > start[i]) order.push_back(i);
	std::sort(
	    order.begin(), order.end(),
	    [&](int a, int b)
	    { return m_surfaces[a].count > m_surfaces[b].count; });
	// Region growing over the surface graph, largest surfaces first: a
	// neighbour joins when it is parallel to the group and its centroid
	// lies on the group's plane (fitted to all the group's points so far).
	// Testing against the group's plane, not the neighbour's, keeps a strip
	// that straddles two planes from chaining them together.
	auto group = [&](double tol, double angle, std::vector<int>& parent)
	{
		const double cosMax = std::cos(angle);
		std::vector<uint8_t> grouped(ns, 0);
		std::vector<int> queue;
		for (int seed : order)
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
	};
	// Strict groups (one plane: a door 2 cm behind its wall stays apart)
	// and loose ones (one wall, for the size rules: real walls are not
	// flat to a centimetre).
	if (m_options.planeMergeTolerance > 0)
		group(
		    m_options.planeMergeTolerance, m_options.planeMergeAngle, m_parent);
	if (m_options.wallGroupTolerance > 0)
		group(m_options.wallGroupTolerance, m_options.wallGroupAngle, m_loose);
}

void RuleClassifier::splitPlanes()
{
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	m_side.assign(n, 0);
	m_groupSplit.assign(m_surfaces.size(), 0);
	m_slotGroup.clear();
	m_slotStart.assign(1, 0);
	if (m_options.planeSplitOffset <= 0) return;
	const auto* P = m_points->ptr<cv::Vec3f>(0);
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
	// Horizontal normal of a 2D point scatter (smallest eigenvector).
	auto normalOf = [](double a, double b, double d, cv::Vec3d& m)
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
	};
	std::vector<int> slot(ns, -1);
	int nSlots = 0;
	std::vector<cv::Vec3d> normal;
	std::vector<double> offset;
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
		const double minSpread = 0.25 * m_options.planeSplitOffset;
		if (lmin < minSpread * minSpread) continue;
		cv::Vec3d m;
		if (!normalOf(a, b, d, m)) continue;
		slot[i] = nSlots++;
		m_slotGroup.push_back(i);
		normal.push_back(m);
		offset.push_back(m[0] * cx + m[1] * cy);
	}
	if (nSlots == 0) return;
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

	// The dominant plane of each group: a least-squares fit of all points
	// tilts to pass through both planes of a wall with a recessed door and
	// turns the step into a ramp (averaged normals and in-plane differences
	// are biased by the range noise, which lies along the rays). So the
	// normal's direction is searched around the fit (+-3 deg, to 0.1 deg)
	// for the one that packs most points into a band of
	// +-0.5 plane_split_offset_m; then least squares on that band.
	{
		const double half = 0.5 * m_options.planeSplitOffset;
		constexpr double kStep = 0.1 * M_PI / 180;
		// (d * 1000 rounds to the same bin as d / 0.001 for every float d:
		// the product is exact in double, the quotient is within 2 ulp of
		// it, and d * 1000 is never that close to an integer it is not.)
		constexpr double kBin = 0.001, kBinsPerMetre = 1000;
		constexpr int kBins = 300;  // 1 mm over +-15 cm
		const int band =
		    std::max(1, static_cast<int>(std::lround(2 * half / kBin)));
		// (Bins 0..kBins-1 and kBins + 1 .. 2 kBins: the two halves; bin
		// kBins and 2 kBins + 1 take the points outside.)
		std::vector<int> hist(2 * kBins + 2), bins;
		std::vector<uint64_t> inBand;
		std::vector<float> px, py;
		const detail::SimdKernels& K = detail::simdKernels();
		for (int k = 0; k < nSlots; k++)
		{
			const int cnt = start[k + 1] - start[k];
			const float* xs = m_slotX.data() + start[k];
			const float* ys = m_slotY.data() + start[k];
			const int stride = std::max(1, cnt / 384);
			px.clear();
			py.clear();
			for (int i = 0; i < cnt; i += stride)
			{
				px.push_back(xs[i]);
				py.push_back(ys[i]);
			}
			bins.resize(px.size());
			const double a0 = std::atan2(normal[k][1], normal[k][0]);
			int bestScore = -1;
			double bestA = a0, bestD = offset[k];
			auto tryAngle = [&](double ang)
			{
				const float mx = static_cast<float>(std::cos(ang)),
				            my = static_cast<float>(std::sin(ang));
				const float off = static_cast<float>(offset[k]);
				// (Two histograms, even and odd points, summed after: runs of
				// neighbouring points fall into one bin, and one histogram
				// would wait for each increment before the next.)
				std::fill(hist.begin(), hist.end(), 0);
				const int np = static_cast<int>(px.size());
				K.distanceBins(
				    px.data(), py.data(), np, mx, my, off, kBinsPerMetre,
				    kBins / 2, kBins, bins.data());
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
						bestD =
						    offset[k] + (b - kBins / 2 + 1 - 0.5 * band) * kBin;
					}
				}
			};
			// Coarse (0.5 deg over +-3 deg), then fine (0.1 deg) around the
			// best.
			for (int j = -6; j <= 6; j++) tryAngle(a0 + j * 5 * kStep);
			const double coarse = bestA;
			for (int j = -4; j <= 4; j++)
				if (j != 0) tryAngle(coarse + j * kStep);
			const cv::Vec3d bestM(std::cos(bestA), std::sin(bestA), 0);
			// Least squares on the points of that band.
			// (Points outside the band would add exact zeros: skipped.)
			double s0 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
			inBand.resize((cnt + 63) / 64);
			K.bandBits(
			    xs, ys, cnt, bestM[0], bestM[1], bestD, half, inBand.data());
			for (int w = 0; w < static_cast<int>(inBand.size()); w++)
				for (uint64_t m = inBand[w]; m; m &= m - 1)
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
			if (s0 >= m_options.minSurfacePixels &&
			    normalOf(
			        sxx / s0 - sx * sx / (s0 * s0),
			        sxy / s0 - sx * sy / (s0 * s0),
			        syy / s0 - sy * sy / (s0 * s0), m))
			{
				if (m.dot(bestM) < 0) m = -m;
				normal[k] = m;
				offset[k] = (m[0] * sx + m[1] * sy) / s0;
			}
			else
			{
				normal[k] = bestM;
				offset[k] = bestD;
			}
		}
	}

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
		double total = 0, sumAll = 0;
		for (int b = 0; b < kBins; b++)
		{
			total += hist[b];
			sumAll += hist[b] * (b + 0.5);
		}
		double w0 = 0, s0 = 0, best = -1, m0b = 0, m1b = 0, w0b = 0;
		int bestB = -1;
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
				bestB = b;
				m0b = m0;
				m1b = m1;
				w0b = w0;
			}
		}
		if (bestB < 0) continue;
		MRPT_LOG_DEBUG_FMT(
		    "plane split %d: n (%.3f %.3f) d %.3f, %d px, classes %.4f / "
		    "%.4f (%d / %d)",
		    k, normal[k][0], normal[k][1], offset[k], int(total),
		    m0b * kBin - kRange, m1b * kBin - kRange, int(w0b),
		    int(total - w0b));
		if ((m1b - m0b) * kBin < m_options.planeSplitOffset ||
		    std::min(w0b, total - w0b) < m_options.minSurfacePixels)
			continue;
		const float thr = static_cast<float>((bestB + 1) * kBin - kRange);
		bool any = false;
		for (int i = start[k]; i < start[k + 1]; i++)
		{
			const bool side = RS[pix[i]] >= thr;
			m_side[pix[i]] = side ? 1 : 0;
			any |= side;
		}
		// Split: pass 2 labels this group's pixels by side.
		if (any) m_groupSplit[m_parent[m_surf[pix[start[k]]]]] = 1;
	}
	for (int p : pix) RES[p] = WT[p] = 0;
}

double RuleClassifier::estimateGround(
    bool floorReferenced, bool& estimated) const
{
	estimated = false;
	if (!m_options.autoGroundLevel) return m_options.groundZ;
	constexpr double binSize = 0.02, zMin = -50.0;
	constexpr int bins = 5000;
	std::vector<int> hist(bins, 0);
	std::vector<double> zsum(bins, 0.0);
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	const int n = m_rows * m_cols;
	const float zLo = floorReferenced
	                      ? m_options.groundZ - m_options.groundSearch
	                      : -HUGE_VALF,
	            zHi = floorReferenced
	                      ? m_options.groundZ + m_options.groundSearch
	                      : HUGE_VALF;
	int total = 0;
	for (int p = 0; p < n; p++)
		if (m_class[p] == kUp && P[p][2] >= zLo && P[p][2] <= zHi)
		{
			const int b = static_cast<int>((P[p][2] - zMin) / binSize);
			if (b >= 0 && b < bins)
			{
				hist[b]++;
				zsum[b] += P[p][2];
				total++;
			}
		}
	if (total < m_options.minGroundPixels) return m_options.groundZ;
	// Window sums over +-2 bins (10 cm): rough ground spreads over bins.
	std::vector<int> win(bins, 0);
	int best = 0;
	for (int b = 0; b < bins; b++)
	{
		for (int k = std::max(0, b - 2); k <= std::min(bins - 1, b + 2); k++)
			win[b] += hist[k];
		best = std::max(best, win[b]);
	}
	// The lowest local maximum with a fair share of the support: the floor,
	// not a larger table top or a terrace further up. Its height: the mean
	// of the points in its window.
	const int need =
	    std::max(m_options.minGroundPixels, static_cast<int>(0.3 * best));
	for (int b = 0; b < bins; b++)
	{
		if (win[b] < need) continue;
		if (b > 0 && win[b - 1] > win[b]) continue;
		if (b + 1 < bins && win[b + 1] > win[b]) continue;
		double sum = 0;
		int cnt = 0;
		for (int k = std::max(0, b - 2); k <= std::min(bins - 1, b + 2); k++)
		{
			sum += zsum[k];
			cnt += hist[k];
		}
		if (cnt == 0) break;
		estimated = true;
		return sum / cnt;
	}
	return m_options.groundZ;
}

RuleClassifier::DoorCheck RuleClassifier::checkDoor(
    int self, const std::vector<int>& wallCandidate,
    const std::vector<uint8_t>& isCeiling) const
{
	const Surface& door = m_surfaces[self];
	DoorCheck res;
	const int cols = m_cols, rows = m_rows;
	const double cosMax = std::cos(m_options.doorMaxAngle);
	const double dDoor = door.planeD();
	std::vector<int8_t> compat(m_surfaces.size(), -1);
	auto wallOk = [&](int s)
	{
		if (s < 0 || !wallCandidate[s]) return false;
		if (compat[s] < 0)
		{
			const Surface& w = m_surfaces[s];
			const double off = std::abs(door.normal.dot(w.centroid) - dDoor);
			compat[s] = w.normal.dot(door.normal) >= cosMax &&
			                    off <= m_options.doorMaxOffset
			                ? 1
			                : 0;
			if (compat[s]) res.maxOffset = std::max(res.maxOffset, off);
		}
		return compat[s] == 1;
	};
	const int nr = door.maxR - door.minR + 1, nc = door.maxC - door.minC + 1;
	std::vector<int> rowMin(nr, cols), rowMax(nr, -1), colMax(nc, -1),
	    colMin(nc, rows);
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	float zLo = std::numeric_limits<float>::max(), zHi = -zLo;
	int pLo = -1, pHi = -1;
	for (int r = door.minR; r <= door.maxR; r++)
		for (int c = door.minC; c <= door.maxC; c++)
		{
			if (m_surf[r * cols + c] != self) continue;
			const float z = P[r * cols + c][2];
			if (z < zLo)
			{
				zLo = z;
				pLo = r * cols + c;
			}
			if (z > zHi)
			{
				zHi = z;
				pHi = r * cols + c;
			}
			rowMin[r - door.minR] = std::min(rowMin[r - door.minR], c);
			rowMax[r - door.minR] = std::max(rowMax[r - door.minR], c);
			colMax[c - door.minC] = std::max(colMax[c - door.minC], r);
			colMin[c - door.minC] = std::min(colMin[c - door.minC], r);
		}
	const int K = m_options.doorSearchPixels;
	// Probes up to K pixels away; `border` when the probe runs out of the
	// image (the field of view cuts the surface there).
	auto probe = [&](int r, int c, int dr, int dc, bool ceilingOk, bool& border)
	{
		for (int k = 1; k <= K; k++)
		{
			const int rr = r + k * dr, cc = c + k * dc;
			if (rr < 0 || rr >= rows || cc < 0 || cc >= cols)
			{
				border = true;
				return false;
			}
			const int s = m_surf[rr * cols + cc];
			if (s == self) return false;
			if (wallOk(s) || (ceilingOk && s >= 0 && isCeiling[s])) return true;
		}
		return false;
	};
	int left = 0, right = 0, top = 0, nRows = 0, nCols = 0;
	int leftB = 0, rightB = 0, topB = 0;
	for (int i = 0; i < nr; i++)
	{
		if (rowMax[i] < 0) continue;
		nRows++;
		const int r = door.minR + i;
		bool border = false;
		// Lower columns are on the robot's right.
		if (probe(r, rowMin[i], 0, -1, false, border))
			right++;
		else if (border)
			rightB++;
		border = false;
		if (probe(r, rowMax[i], 0, 1, false, border))
			left++;
		else if (border)
			leftB++;
	}
	for (int j = 0; j < nc; j++)
	{
		if (colMax[j] < 0) continue;
		nCols++;
		bool border = false;
		if (probe(colMax[j], door.minC + j, 1, 0, true, border))
			top++;
		else if (border)
			topB++;
	}
	if (nRows == 0 || nCols == 0) return res;
	res.left = double(left) / nRows;
	res.right = double(right) / nRows;
	res.top = double(top) / nCols;
	// Cut by the field of view: the surface reaches the image border (the
	// outermost columns, phi near +-90 deg, have degenerate neighbours and
	// rarely carry normals, hence the wider margin there).
	res.leftFov = leftB > 0 || door.maxC >= cols - 1 - 2 * K;
	res.rightFov = rightB > 0 || door.minC <= 2 * K;
	// Also when its lowest (highest) point lies at the image border: at
	// bearings near +-90 deg the field of view cuts surfaces at a slant.
	auto atBorder = [&](int p)
	{
		if (p < 0) return false;
		const int r = p / cols, c = p % cols;
		return r <= K || r >= rows - 1 - K || c <= 2 * K ||
		       c >= cols - 1 - 2 * K;
	};
	res.topFov = topB > 0 || door.maxR >= rows - 1 - K || atBorder(pHi);
	res.bottomFov = door.minR <= K || atBorder(pLo);
	return res;
}

void RuleClassifier::classify(
    const NormalImage& normals, const cv::Mat& areaIds,
    const Roughness& roughness, LabeledSweep& out, bool floorReferenced)
{
	const TOptions& o = m_options;
	m_rows = normals.points().rows;
	m_cols = normals.points().cols;
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	out.labels.create(rows, cols, CV_8U);
	out.labels.setTo(0);
	out.regionIds.create(rows, cols, CV_32S);
	out.regionIds.setTo(-1);
	out.regions.clear();
	out.groundZ = o.groundZ;
	out.groundEstimated = false;
	out.ceilingZ.reset();
	out.indoor = o.environment != TOptions::Environment::Outdoor;
	if (n == 0) return;
	if (areaIds.rows != rows || areaIds.cols != cols ||
	    areaIds.type() != CV_32S)
		throw Error("RuleClassifier: area image does not match the sweep");

	if (m_rowOf.size() != static_cast<std::size_t>(n))
	{
		// Row and column of each pixel index (integer division is slow in
		// the per-pixel loops).
		m_rowOf.resize(n);
		m_colOf.resize(n);
		for (int p = 0; p < n; p++)
		{
			m_rowOf[p] = p / cols;
			m_colOf[p] = p % cols;
		}
	}
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	m_points = &normals.points();
	m_pointMask = &normals.pointMask();
	m_ranges = &normals.ranges();
	m_areas = &areaIds;
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	const auto* PM = m_pointMask->ptr<uint8_t>(0);
	const auto* NM = normals.normalMask().ptr<uint8_t>(0);
	const int* A = areaIds.ptr<int>(0);

	const auto t0 = std::chrono::steady_clock::now();
	// 1. Orientation per pixel on normals averaged inside their area.
	// (A box filter over all pixels: 0 where there is no normal; pixels
	// without their own normal are not classified anyway.)
	detail::OrientThresholds th;
	th.cosUp = static_cast<float>(std::cos(o.groundNormalTolerance));
	th.cosDown = static_cast<float>(std::cos(o.ceilingNormalTolerance));
	th.sinVert = static_cast<float>(std::sin(o.wallNormalTolerance));
	const detail::SimdKernels& K = detail::simdKernels();
	m_class.resize(n);
	auto classifyRow = [&](int r, const float* N)
	{
		const int base = r * cols;
		K.orientRow(N, PM + base, NM + base, &m_class[base], cols, th);
	};
	if (o.normalSmoothingHalfWidth > 0)
	{
		// Box sums normalised and classified row by row.
		m_smoothSum.create(rows, cols, CV_32FC3);
		detail::boxSumRows(
		    normals.normals(), o.normalSmoothingHalfWidth, m_tmp,
		    [&](int r) { return m_smoothSum.ptr<float>(r); },
		    [&](int r, const float*)
		    {
			    float* S = m_smoothSum.ptr<float>(r);
			    K.normalizeRow(S, cols);
			    classifyRow(r, S);
		    });
		m_ns = &m_smoothSum;
	}
	else
	{
		m_ns = &normals.normals();
		for (int r = 0; r < rows; r++) classifyRow(r, m_ns->ptr<float>(r));
	}

	const auto t1 = std::chrono::steady_clock::now();
	// 2. Ground level.
	bool estimated = false;
	const double zg = estimateGround(floorReferenced, estimated);
	out.groundZ = zg;
	out.groundEstimated = estimated;

	const auto t2 = std::chrono::steady_clock::now();
	// 3. Surfaces: pieces of areas; coplanar vertical pieces of different
	// areas (a wall seen at a grazing angle floods into column strips)
	// grouped; groups split where their plane steps (a recessed door).
	buildSurfaces(false);
	const auto t3 = std::chrono::steady_clock::now();
	mergeCoplanar();
	const auto t4 = std::chrono::steady_clock::now();
	splitPlanes();
	const auto t5 = std::chrono::steady_clock::now();
	buildSurfaces(true);

	const auto t6 = std::chrono::steady_clock::now();
	// 4. Rules.
	const std::size_t ns = m_surfaces.size();
	std::vector<uint8_t> isCeiling(ns, 0);
	double ceilSum = 0;
	std::size_t ceilPixels = 0;
	for (std::size_t i = 0; i < ns; i++)
	{
		Surface& s = m_surfaces[i];
		if (s.count < o.minSurfacePixels) continue;
		if (s.orient == kUp &&
		    std::abs(s.centroid[2] - zg) <= o.groundTolerance)
			s.label = lab(Label::Floor);  // ground; typed in step 6
		else if (s.orient == kDown && s.centroid[2] >= zg + o.ceilingMinHeight)
		{
			s.label = lab(Label::Ceiling);
			isCeiling[i] = 1;
			ceilSum += s.centroid[2] * s.count;
			ceilPixels += s.count;
		}
	}
	if (ceilPixels > 0) out.ceilingZ = ceilSum / ceilPixels;
	// Wall size rules on each vertical surface and on its loose group (the
	// pieces of one wall that noise or a plane step cut apart).
	auto wallSized = [&](const Surface& s)
	{
		if (s.width < o.wallMinWidth) return false;
		const bool tall = s.height >= o.wallMinHeight;
		const bool toCeiling =
		    out.ceilingZ && s.maxP[2] >= *out.ceilingZ - o.wallCeilingGap;
		const bool longWall = s.width >= o.wallMinLength;
		return tall || toCeiling || longWall;
	};
	// (Indexed through looseIdx: few of the loose groups are used.)
	std::vector<int> looseIdx(m_loose.size(), -1);
	std::vector<Surface> loose;
	for (std::size_t i = 0; i < ns; i++)
	{
		const Surface& s = m_surfaces[i];
		if (s.orient != kVertical || s.count < o.minSurfacePixels) continue;
		int& li = looseIdx[m_surfLoose[i]];
		if (li < 0)
		{
			li = static_cast<int>(loose.size());
			loose.emplace_back();
		}
		Surface& g = loose[li];
		if (g.count == 0)
		{
			g = s;
			continue;
		}
		g.count += s.count;
		g.sumP += s.sumP;
		g.sumN += s.sumN;
		for (int k = 0; k < 3; k++)
		{
			g.minP[k] = std::min(g.minP[k], s.minP[k]);
			g.maxP[k] = std::max(g.maxP[k], s.maxP[k]);
		}
	}
	std::vector<uint8_t> looseWall(loose.size(), 0);
	for (std::size_t k = 0; k < loose.size(); k++)
		if (loose[k].count > 0)
		{
			finishSurface(loose[k]);
			looseWall[k] = wallSized(loose[k]);
		}
	std::vector<int> wallCandidate(ns, 0);
	for (std::size_t i = 0; i < ns; i++)
	{
		const Surface& s = m_surfaces[i];
		if (s.orient != kVertical || s.count < o.minSurfacePixels) continue;
		wallCandidate[i] = wallSized(s) || looseWall[looseIdx[m_surfLoose[i]]];
	}
	const double f = o.doorMinSideFraction;
	for (std::size_t i = 0; i < ns; i++)
	{
		Surface& s = m_surfaces[i];
		if (s.orient != kVertical || s.count < o.minSurfacePixels) continue;
		bool door = false;
		if (s.width <= o.doorMaxWidth && s.height <= o.doorMaxHeight)
		{
			// Where the field of view cuts the surface (image border) its
			// extent and neighbours there are unknown: accepted when
			// door_allow_truncation, but at least one side must be a wall.
			const DoorCheck dc =
			    checkDoor(static_cast<int>(i), wallCandidate, isCeiling);
			const bool t = o.doorAllowTruncation;
			const bool sides = (dc.left >= f || (t && dc.leftFov)) &&
			                   (dc.right >= f || (t && dc.rightFov)) &&
			                   (dc.top >= f || (t && dc.topFov)) &&
			                   (dc.left >= f || dc.right >= f);
			const bool height = s.height >= o.doorMinHeight ||
			                    (t && (dc.topFov || dc.bottomFov));
			const bool width =
			    s.width >= o.doorMinWidth || (t && (dc.leftFov || dc.rightFov));
			const bool bottom =
			    s.minP[2] <= zg + o.doorBottomTolerance || (t && dc.bottomFov);
			door = sides && height && width && bottom &&
			       dc.maxOffset >= o.doorMinOffset;
			MRPT_LOG_DEBUG_FMT(
			    "door candidate %zu: %d px, rows %d-%d cols %d-%d, width %.2f "
			    "height %.2f z %.2f..%.2f; walls left %.2f right %.2f top "
			    "%.2f, fov %d%d%d%d, offset %.3f -> %s",
			    i, s.count, s.minR, s.maxR, s.minC, s.maxC, s.width, s.height,
			    s.minP[2], s.maxP[2], dc.left, dc.right, dc.top, dc.leftFov,
			    dc.rightFov, dc.topFov, dc.bottomFov, dc.maxOffset,
			    door ? "door" : "no");
		}
		if (door)
			s.label = lab(Label::Door);
		else if (wallCandidate[i])
			s.label = lab(Label::Wall);
	}
	for (Surface& s : m_surfaces)
		if (s.label == kNoLabel && s.count >= o.minSurfacePixels &&
		    s.maxP[2] > zg + o.groundTolerance)
			s.label = lab(Label::Obstacle);
	// A piece next to a wall or ceiling that lies on its plane (its box
	// within leftover_plane_tolerance_m of it) is a fragment of that
	// surface cut off by noisy normals, not an obstacle: its pixels are
	// left to step 5, which joins them to the plane they lie on.
	{
		std::vector<uint8_t> tested(ns, 0);
		auto onPlane = [&](const Surface& a, const Surface& w)
		{
			if (a.normal.dot(w.normal) < std::cos(o.doorMaxAngle * 2))
				return false;
			const double d = w.planeD();
			for (int k = 0; k < 8; k++)
			{
				const cv::Vec3d c(
				    (k & 1) ? a.maxP[0] : a.minP[0],
				    (k & 2) ? a.maxP[1] : a.minP[1],
				    (k & 4) ? a.maxP[2] : a.minP[2]);
				if (std::abs(w.normal.dot(c) - d) > o.leftoverPlaneTolerance)
					return false;
			}
			return true;
		};
		auto planar = [&](int t) { return tested[t] == 3; };
		// 1: an obstacle piece not yet demoted; 3: a wall.
		for (std::size_t i = 0; i < ns; i++)
			tested[i] = m_surfaces[i].label == lab(Label::Obstacle) ? 1
			            : m_surfaces[i].label == lab(Label::Wall)   ? 3
			                                                        : 0;
		for (int p = 0; p < n; p++)
		{
			const int s = m_surf[p];
			if (s < 0 || tested[s] != 1) continue;
			const int r = RO[p], c = CO[p];
			const int nb[4] = {
			    c > 0 ? p - 1 : -1, c + 1 < cols ? p + 1 : -1,
			    r > 0 ? p - cols : -1, r + 1 < rows ? p + cols : -1};
			for (int q : nb)
			{
				const int t = q >= 0 ? m_surf[q] : -1;
				if (t < 0 || t == s || !planar(t)) continue;
				if (onPlane(m_surfaces[s], m_surfaces[t]))
				{
					tested[s] = 2;
					m_surfaces[s].label = kNoLabel;
					break;
				}
			}
		}
	}

	const auto t7 = std::chrono::steady_clock::now();
	// 5. Pixels: surface labels, then leftovers by multi-source growth.
	// (Labels per surface in a compact array: the pixels look them up.)
	m_label.resize(n);
	m_owner.resize(n);
	m_stack.clear();
	m_surfLabel.resize(ns + 1);
	m_surfLabel[0] = kNoLabel;  // no surface (id -1)
	for (std::size_t i = 0; i < ns; i++)
		m_surfLabel[i + 1] = m_surfaces[i].label;
	{
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
	if (o.classifyLeftoverPixels)
	{
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
	if (o.classifyLeftoverPixels)
	{
		const float tolG = static_cast<float>(o.groundTolerance);
		const double tolP = o.leftoverPlaneTolerance;
		// What each labelled surface accepts, compact (read per pixel).
		m_claim.resize(ns);
		for (std::size_t i = 0; i < ns; i++)
		{
			const Surface& S = m_surfaces[i];
			Claim& cl = m_claim[i];
			cl.label = S.label;
			cl.kind = isGround(S.label)                 ? Claim::kGround
			          : S.label == lab(Label::Obstacle) ? Claim::kArea
			                                            : Claim::kPlane;
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
			return std::abs(
			           cl.nx * x[0] + cl.ny * x[1] + cl.nz * x[2] - cl.d) <=
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

	const auto t8 = std::chrono::steady_clock::now();
	// 6. Indoor or outdoor ground.
	if (o.environment == TOptions::Environment::Auto)
		out.indoor =
		    ceilPixels >= static_cast<std::size_t>(o.indoorMinCeilingPixels);
	uint8_t* L = out.labels.ptr<uint8_t>(0);
	for (int p = 0; p < n; p++)
		L[p] = m_label[p] == kNoLabel ? 0 : static_cast<uint8_t>(m_label[p]);
	if (!out.indoor) labelGroundTypes(roughness, out);

	const auto t9 = std::chrono::steady_clock::now();
	buildRegions(out, roughness.rBar());
	const auto t10 = std::chrono::steady_clock::now();
	auto ms = [](auto a, auto b)
	{ return std::chrono::duration<double, std::milli>(b - a).count(); };
	MRPT_LOG_DEBUG_FMT(
	    "timing: smooth+class %.2f ground %.2f pass1 %.2f merge %.2f split "
	    "%.2f pass2 %.2f rules %.2f leftover %.2f ground types %.2f regions "
	    "%.2f",
	    ms(t0, t1), ms(t1, t2), ms(t2, t3), ms(t3, t4), ms(t4, t5), ms(t5, t6),
	    ms(t6, t7), ms(t7, t8), ms(t8, t9), ms(t9, t10));
	MRPT_LOG_DEBUG_FMT(
	    "ground z=%.3f (%s), %zu surfaces, %zu regions, %s", zg,
	    estimated ? "estimated" : "configured", ns, out.regions.size(),
	    out.indoor ? "indoor" : "outdoor");
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
	// Squares without R-bar (far ground: rows more than eps1 apart carry no
	// normals) are judged by the spread of their ground points' heights:
	// sidewalk when its standard deviation is at most
	// sidewalk_max_height_std_m (needs min_square_px points).
	if (m_options.sidewalkMaxHeightStd > 0)
	{
		const auto* P = m_points->ptr<cv::Vec3f>(0);
		std::vector<double> s1(sr * sc, 0.0), s2(sr * sc, 0.0);
		std::vector<int> cnt(sr * sc, 0);
		for (int p = 0; p < n; p++)
		{
			if (!G[p]) continue;
			const int k = (RO[p] / w) * sc + CO[p] / w;
			if (sq[k] != 0) continue;
			const double z = P[p][2];
			s1[k] += z;
			s2[k] += z * z;
			cnt[k]++;
		}
		const double maxVar =
		    m_options.sidewalkMaxHeightStd * m_options.sidewalkMaxHeightStd;
		for (int k = 0; k < sr * sc; k++)
		{
			if (sq[k] != 0 || cnt[k] < roughness.options().minSquarePixels)
				continue;
			const double m = s1[k] / cnt[k];
			sq[k] = s2[k] / cnt[k] - m * m <= maxVar ? 1 : 2;
		}
	}
	// Undetermined squares take the nearest determined one's type.
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
	// Small patches of one type inside the other are absorbed.
	if (m_options.minPatchSquares > 0)
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
			if (other > 0 &&
			    static_cast<int>(members.size()) < m_options.minPatchSquares)
				for (int k : members) sq[k] = sq[k0] == 1 ? 2 : 1;
		}
	}
	for (int p = 0; p < n; p++)
	{
		if (!G[p]) continue;
		const int k = (RO[p] / w) * sc + CO[p] / w;
		L[p] =
		    static_cast<uint8_t>(sq[k] == 2 ? Label::Grass : Label::Sidewalk);
	}
}

void RuleClassifier::buildRegions(LabeledSweep& out, const cv::Mat& rBar)
{
	const float* RB = rBar.rows == m_rows && rBar.cols == m_cols
	                      ? rBar.ptr<float>(0)
	                      : nullptr;
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	const uint8_t* L = out.labels.ptr<uint8_t>(0);
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	const auto* NS = m_ns->ptr<cv::Vec3f>(0);
	const int* A = m_areas->ptr<int>(0);
	int* RI = out.regionIds.ptr<int>(0);
	const double sinVert = std::sin(m_options.wallNormalTolerance);
	// A region is a labelled surface with the pixels it took over, or for
	// the ground (merged over all its surfaces) and for pixels labelled by
	// height alone, 4-connected pixels of one label.
	std::vector<int> regOf(m_surfaces.size(), -1);
	int count = 0;
	for (int p = 0; p < n; p++)
	{
		const int s = m_owner[p];
		if (L[p] == 0 || s < 0 || isGround(static_cast<int8_t>(L[p]))) continue;
		if (regOf[s] < 0) regOf[s] = count++;
		RI[p] = regOf[s];
	}
	// Statistics in the same row-major pass that numbers the other
	// regions (a region's pixels lie at or after its seed, so a pixel's
	// region is final at its turn); plus one pass over the regions for the
	// extent along vertical ones.
	struct Acc
	{
		cv::Vec3d sum{0, 0, 0}, sumN{0, 0, 0};
		cv::Vec3f lo, hi;
		int r0 = 0, r1 = 0, c0 = 0, c1 = 0, first = -1;
		std::size_t n = 0, nRbar = 0;
		double sumRbar = 0;
		double tlo = 0, thi = 0;
		cv::Vec3d t{0, 0, 0};
		bool vertical = false;
	};
	std::vector<Acc> acc(count);
	// Runs of one region along a row are summed in locals first, x y z
	// (and nx ny nz) in the first three lanes of vectors, each lane in
	// double as a scalar sum would be.
	int rid = -1, rn = 0, rr = 0, rc0 = 0, rc1 = 0, rfirst = -1, rnb = 0;
	double sb = 0;
	cv::v_float64x2 sxy = cv::v_setzero_f64(), szw = sxy, nxy = sxy, nzw = sxy;
	cv::v_float32x4 vlo = cv::v_setzero_f32(), vhi = vlo;
	auto flush = [&]()
	{
		if (rid < 0) return;
		Acc& a = acc[rid];
		double xy[2], zw[2], nxy2[2], nzw2[2];
		float lo[4], hi[4];
		cv::v_store(xy, sxy);
		cv::v_store(zw, szw);
		cv::v_store(nxy2, nxy);
		cv::v_store(nzw2, nzw);
		cv::v_store(lo, vlo);
		cv::v_store(hi, vhi);
		if (a.n == 0)
		{
			a.first = rfirst;
			a.lo = cv::Vec3f(lo[0], lo[1], lo[2]);
			a.hi = cv::Vec3f(hi[0], hi[1], hi[2]);
			a.r0 = a.r1 = rr;
			a.c0 = rc0;
			a.c1 = rc1;
		}
		a.n += rn;
		a.nRbar += rnb;
		a.sumRbar += sb;
		a.sum += cv::Vec3d(xy[0], xy[1], zw[0]);
		a.sumN += cv::Vec3d(nxy2[0], nxy2[1], nzw2[0]);
		for (int k = 0; k < 3; k++)
		{
			a.lo[k] = std::min(a.lo[k], lo[k]);
			a.hi[k] = std::max(a.hi[k], hi[k]);
		}
		a.r0 = std::min(a.r0, rr);
		a.r1 = std::max(a.r1, rr);
		a.c0 = std::min(a.c0, rc0);
		a.c1 = std::max(a.c1, rc1);
		rid = -1;
	};
	int* stack = m_fillStack.data();  // n slots
	for (int r = 0, p = 0; r < rows; r++)
		for (int c = 0; c < cols; c++, p++)
		{
			if (RI[p] < 0 && L[p] != 0)
			{
				// A new region: 4-connected pixels of this label.
				const int id = count++;
				acc.emplace_back();
				const uint8_t l = L[p];
				RI[p] = id;
				int top = 0;
				stack[top++] = p;
				while (top > 0)
				{
					const int q0 = stack[--top];
					const int qr = RO[q0], qc = CO[q0];
					const int nb[4] = {
					    qc > 0 ? q0 - 1 : -1, qc + 1 < cols ? q0 + 1 : -1,
					    qr > 0 ? q0 - cols : -1,
					    qr + 1 < rows ? q0 + cols : -1};
					for (int q : nb)
						if (q >= 0 && RI[q] < 0 && L[q] == l)
						{
							RI[q] = id;
							stack[top++] = q;
						}
				}
			}
			const int id = RI[p];
			if (id != rid || c == 0) flush();
			if (id < 0) continue;
			cv::v_float32x4 vq, vn;
			loadPointAndNormal(P, NS, p, n - 1, vq, vn);
			if (rid < 0)
			{
				rid = id;
				rn = 0;
				rr = r;
				rc0 = c;
				rfirst = p;
				rnb = 0;
				sb = 0;
				sxy = szw = nxy = nzw = cv::v_setzero_f64();
				vlo = vhi = vq;
			}
			rc1 = c;
			rn++;
			if (RB)
			{
				const float v = RB[p];
				const bool ok = v == v;  // not NaN
				sb += ok ? v : 0.0f;
				rnb += ok;
			}
			sxy += cv::v_cvt_f64(vq);
			szw += cv::v_cvt_f64_high(vq);
			nxy += cv::v_cvt_f64(vn);
			nzw += cv::v_cvt_f64_high(vn);
			vlo = cv::v_min(vq, vlo);  // (as std::min(lo, q), signed zeros too)
			vhi = cv::v_max(vq, vhi);
		}
	flush();
	// Extent along a vertical region (t = z x n): the projections of its
	// box's corners (exact for a plane, whose xy trace is the box diagonal).
	for (Acc& a : acc)
	{
		const double ln = cv::norm(a.sumN);
		if (ln <= 0) continue;
		const cv::Vec3d nrm = a.sumN * (1.0 / ln);
		const cv::Vec3d t(-nrm[1], nrm[0], 0);
		const double lt = cv::norm(t);
		if (std::abs(nrm[2]) > sinVert || lt <= 0) continue;
		a.vertical = true;
		a.t = t * (1.0 / lt);
		a.tlo = std::numeric_limits<double>::max();
		a.thi = -a.tlo;
		for (int k = 0; k < 4; k++)
		{
			const double v = a.t[0] * ((k & 1) ? a.hi[0] : a.lo[0]) +
			                 a.t[1] * ((k & 2) ? a.hi[1] : a.lo[1]);
			a.tlo = std::min(a.tlo, v);
			a.thi = std::max(a.thi, v);
		}
	}
	out.regions.resize(count);
	for (int id = 0; id < count; id++)
	{
		const Acc& a = acc[id];
		LabeledRegion& reg = out.regions[id];
		reg = LabeledRegion();
		reg.id = id;
		reg.label = static_cast<Label>(L[a.first]);
		reg.area = A[a.first];
		reg.pixels = a.n;
		const cv::Vec3d cen = a.sum * (1.0 / a.n);
		const double ln = cv::norm(a.sumN);
		const cv::Vec3d nrm = ln > 0 ? a.sumN * (1.0 / ln) : cv::Vec3d(0, 0, 0);
		reg.imageBox = cv::Rect(a.c0, a.r0, a.c1 - a.c0 + 1, a.r1 - a.r0 + 1);
		reg.centroid = {cen[0], cen[1], cen[2]};
		reg.minCorner = {a.lo[0], a.lo[1], a.lo[2]};
		reg.maxCorner = {a.hi[0], a.hi[1], a.hi[2]};
		reg.meanNormal = {nrm[0], nrm[1], nrm[2]};
		reg.height = a.hi[2] - a.lo[2];
		reg.width = a.vertical ? a.thi - a.tlo
		                       : std::max(a.hi[0] - a.lo[0], a.hi[1] - a.lo[1]);
		reg.meanRoughness = a.nRbar > 0
		                        ? a.sumRbar / a.nRbar
		                        : std::numeric_limits<double>::quiet_NaN();
	}
}

}  // namespace semnav

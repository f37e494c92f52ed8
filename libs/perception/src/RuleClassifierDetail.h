/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
/* Pieces shared by RuleClassifier's stages (RuleClassifier*.cpp): the
 * orientation classes, label helpers, union-find and the run-wise surface
 * sums. Internal to the perception library. */

#include <semnav/perception/LabeledSweep.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <opencv2/core/hal/intrin.hpp>
#include <vector>

#include "SimdKernels.h"

namespace semnav::detail::rules
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

inline int8_t lab(Label l)
{
	return static_cast<int8_t>(l);
}

inline uint64_t load64(const void* p)
{
	uint64_t v;
	std::memcpy(&v, p, sizeof v);
	return v;
}

inline bool isGround(int8_t l)
{
	return l == lab(Label::Floor) || l == lab(Label::Sidewalk) ||
	       l == lab(Label::Grass);
}

/** Union-find (roots are components' smallest pixels): x's root, halving
 * the path on the way. */
inline int findRoot(int* uf, int x)
{
	while (uf[x] != x)
	{
		uf[x] = uf[uf[x]];
		x = uf[x];
	}
	return x;
}

/** Joins the components of a and b (the larger root under the smaller). */
inline void unite(int* uf, int a, int b)
{
	a = findRoot(uf, a);
	b = findRoot(uf, b);
	if (a != b) uf[std::max(a, b)] = std::min(a, b);
}

/** Point p and its normal as vectors, x y z in the first three lanes (the
 * fourth is the next pixel's x, unused; the last pixel, which has none, is
 * copied first). */
inline void loadPointAndNormal(
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

/** Otsu's threshold on a histogram: the split after bin `bin` (-1: none)
 * maximises the between-class variance; the classes' means in bins (a bin's
 * centre is b + 0.5) and the lower class's count. */
struct OtsuSplit
{
	int bin = -1;
	double total = 0;  ///< all counts
	double lowMean = 0, highMean = 0, lowCount = 0;
};
OtsuSplit otsuSplit(const std::vector<int>& hist);

}  // namespace semnav::detail::rules

/* semnav: semantic navigation from tilting-laser sweeps */
/* RuleClassifier, last step: regions (labelled surfaces with the pixels
 * they took over, connected pixels of one label elsewhere) and their
 * statistics. */
#include <semnav/perception/RuleClassifier.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "RuleClassifierDetail.h"

namespace semnav
{
using namespace detail::rules;

namespace
{
/** A region's sums and bounds. */
struct RegionAcc
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

/** Sums pixels into regions run by run: runs of one region along a row are
 * summed in locals first, x y z (and nx ny nz) in the first three lanes of
 * vectors, each lane in double as a scalar sum would be. */
class RegionRuns
{
public:
	/** `points` and `normals` hold `n` pixels; `rBar` may be null. */
	RegionRuns(
	    std::vector<RegionAcc>& acc, const cv::Vec3f* points,
	    const cv::Vec3f* normals, const float* rBar, int n)
	    : m_acc(acc), m_p(points), m_n(normals), m_rb(rBar), m_last(n - 1)
	{
	}
	int runId() const { return rid; }
	/** Adds pixel p (row r, column c) of region id >= 0 to the run. */
	void add(int p, int r, int c, int id)
	{
		cv::v_float32x4 vq, vn;
		loadPointAndNormal(m_p, m_n, p, m_last, vq, vn);
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
		if (m_rb)
		{
			const float v = m_rb[p];
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
	/** Ends the run (if any): adds it to its region. */
	void flush()
	{
		if (rid < 0) return;
		RegionAcc& a = m_acc[rid];
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
	}

private:
	std::vector<RegionAcc>& m_acc;
	const cv::Vec3f* m_p;
	const cv::Vec3f* m_n;
	const float* m_rb;
	const int m_last;
	int rid = -1, rn = 0, rr = 0, rc0 = 0, rc1 = 0, rfirst = -1, rnb = 0;
	double sb = 0;
	cv::v_float64x2 sxy = cv::v_setzero_f64(), szw = sxy, nxy = sxy, nzw = sxy;
	cv::v_float32x4 vlo = cv::v_setzero_f32(), vhi = vlo;
};

/** Extent along a vertical region (t = z x n): the projections of its
 * box's corners (exact for a plane, whose xy trace is the box diagonal). */
void setVerticalExtent(RegionAcc& a, double sinVert)
{
	const double ln = cv::norm(a.sumN);
	if (ln <= 0) return;
	const cv::Vec3d nrm = a.sumN * (1.0 / ln);
	const cv::Vec3d t(-nrm[1], nrm[0], 0);
	const double lt = cv::norm(t);
	if (std::abs(nrm[2]) > sinVert || lt <= 0) return;
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
}  // namespace

void RuleClassifier::buildRegions(LabeledSweep& out, const cv::Mat& rBar)
{
	const float* RB = rBar.rows == m_rows && rBar.cols == m_cols
	                      ? rBar.ptr<float>(0)
	                      : nullptr;
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
	std::vector<RegionAcc> acc(count);
	RegionRuns runs(acc, P, NS, RB, n);
	for (int r = 0, p = 0; r < rows; r++)
		for (int c = 0; c < cols; c++, p++)
		{
			if (RI[p] < 0 && L[p] != 0)
			{
				acc.emplace_back();
				fillRegion(p, count++, L, RI);
			}
			const int id = RI[p];
			if (id != runs.runId() || c == 0) runs.flush();
			if (id >= 0) runs.add(p, r, c, id);
		}
	runs.flush();
	for (RegionAcc& a : acc) setVerticalExtent(a, sinVert);
	out.regions.resize(count);
	for (int id = 0; id < count; id++)
	{
		const RegionAcc& a = acc[id];
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

void RuleClassifier::fillRegion(int seed, int id, const uint8_t* L, int* RI)
{
	// 4-connected pixels of this label.
	const int* RO = m_rowOf.data();
	const int* CO = m_colOf.data();
	const int rows = m_rows, cols = m_cols;
	int* stack = m_fillStack.data();  // n slots
	const uint8_t l = L[seed];
	RI[seed] = id;
	int top = 0;
	stack[top++] = seed;
	while (top > 0)
	{
		const int q0 = stack[--top];
		const int qr = RO[q0], qc = CO[q0];
		const int nb[4] = {
		    qc > 0 ? q0 - 1 : -1, qc + 1 < cols ? q0 + 1 : -1,
		    qr > 0 ? q0 - cols : -1, qr + 1 < rows ? q0 + cols : -1};
		for (int q : nb)
			if (q >= 0 && RI[q] < 0 && L[q] == l)
			{
				RI[q] = id;
				stack[top++] = q;
			}
	}
}

}  // namespace semnav

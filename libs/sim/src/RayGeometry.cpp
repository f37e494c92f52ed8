/* semnav: semantic navigation from tilting-laser sweeps */
#include "RayGeometry.h"

namespace semnav::detail
{
namespace
{
/** A ray against one terrain patch: its height above the surface along
 * the ray and its crossings of the surface in a cell. */
class TerrainRay
{
public:
	TerrainRay(const TerrainPrim& terrain, const Ray& ray) : T(terrain), r(ray)
	{
	}
	/** The ray's height above the surface at t. */
	double f(double t) const
	{
		return r.o[2] + t * r.d[2] -
		       T.height(r.o[0] + t * r.d[0], r.o[1] + t * r.d[1]);
	}
	/** Bisection on a bracket whose ends lie on different sides of the
	 * surface; accepts the root if it lies on the patch. */
	bool tryRoot(double lo, double hi, bool loAbove, double& t) const
	{
		while (hi - lo > kBisectTol)
		{
			const double mid = 0.5 * (lo + hi);
			if ((f(mid) > 0) == loAbove)
				lo = mid;
			else
				hi = mid;
		}
		t = 0.5 * (lo + hi);
		const double x = r.o[0] + t * r.d[0], y = r.o[1] + t * r.d[1];
		return T.inside(x, y) || distToPolygon(T.poly, x, y) < kTerrainEdgeTol;
	}
	/** The first crossing in an interior cell between ta and tb. Inside a
	 * cell the surface is bilinear, so f is a quadratic in t: fit it
	 * through 3 samples and bracket its first root, also when the ray dips
	 * under a bump and out again. */
	bool interiorCrossing(double ta, double tb, double& tHit) const
	{
		const double fa = f(ta), fb = f(tb), fm = f(0.5 * (ta + tb));
		const double B = -3 * fa + 4 * fm - fb, C = 2 * fa - 4 * fm + 2 * fb;
		double hi = -1;
		if ((fa > 0) != (fb > 0))
			hi = tb;
		else if (C != 0)
		{
			const double sv = -B / (2 * C);
			if (sv > 0 && sv < 1 && ((fa - B * B / (4 * C)) > 0) != (fa > 0))
				hi = ta + sv * (tb - ta);
		}
		return hi >= 0 && (f(hi) > 0) != (fa > 0) &&
		       tryRoot(ta, hi, fa > 0, tHit);
	}
	/** The first crossing in a boundary cell (tapered) between ta and tb,
	 * marching `step` at a time. */
	bool boundaryCrossing(double ta, double tb, double step, double& tHit) const
	{
		const int n =
		    std::max(1, static_cast<int>(std::ceil((tb - ta) / step)));
		double tp = ta, fp = f(ta);
		for (int k = 1; k <= n; k++)
		{
			const double tc = (k == n) ? tb : ta + (tb - ta) * k / n;
			const double fc = f(tc);
			if ((fp > 0) != (fc > 0) && tryRoot(tp, tc, fp > 0, tHit))
				return true;
			tp = tc;
			fp = fc;
		}
		return false;
	}

private:
	const TerrainPrim& T;
	const Ray& r;
};
}  // namespace

bool intersectTerrain(
    const TerrainPrim& T, const Ray& r, double stopAt, double& tHit)
{
	// Clip to the grid area and the z band the surface can occupy.
	double t0 = 0, t1 = r.maxRange;
	const double eps = 1e-9;
	if (!slab(r.o[0], r.d[0], T.x0, T.x0 + T.cx * T.cell, t0, t1)) return false;
	if (!slab(r.o[1], r.d[1], T.y0, T.y0 + T.cy * T.cell, t0, t1)) return false;
	if (!slab(r.o[2], r.d[2], T.hmin - eps, T.hmax + eps, t0, t1)) return false;
	if (t0 > stopAt) return false;
	const TerrainRay ray(T, r);
	const double dxy = std::hypot(r.d[0], r.d[1]);
	// March step in boundary cells: a quarter cell horizontally.
	const double step = dxy > 1e-12 ? 0.25 * T.cell / dxy : kInf;

	// 2D DDA over the grid cells.
	const double sx = r.o[0] + t0 * r.d[0], sy = r.o[1] + t0 * r.d[1];
	int i = std::clamp(
	    static_cast<int>(std::floor((sx - T.x0) / T.cell)), 0, T.cx - 1);
	int j = std::clamp(
	    static_cast<int>(std::floor((sy - T.y0) / T.cell)), 0, T.cy - 1);
	const int di = r.d[0] > 0 ? 1 : (r.d[0] < 0 ? -1 : 0);
	const int dj = r.d[1] > 0 ? 1 : (r.d[1] < 0 ? -1 : 0);
	auto nextX = [&](int ii)
	{
		if (di == 0) return kInf;
		const double xb = T.x0 + (di > 0 ? ii + 1 : ii) * T.cell;
		return (xb - r.o[0]) / r.d[0];
	};
	auto nextY = [&](int jj)
	{
		if (dj == 0) return kInf;
		const double yb = T.y0 + (dj > 0 ? jj + 1 : jj) * T.cell;
		return (yb - r.o[1]) / r.d[1];
	};
	double tx = nextX(i), ty = nextY(j);
	double ta = t0;
	const int maxIter = T.cx + T.cy + 4;
	for (int it = 0; it < maxIter; it++)
	{
		if (ta > stopAt) return false;
		const double tb = std::min({tx, ty, t1});
		const uint8_t kind = T.kind[j * T.cx + i];
		if (kind != kExterior && tb >= ta)
		{
			const double za = r.o[2] + ta * r.d[2], zb = r.o[2] + tb * r.d[2];
			const double zlo = std::min(za, zb), zhi = std::max(za, zb);
			if (zhi >= T.cellLo[j * T.cx + i] - eps &&
			    zlo <= T.cellHi[j * T.cx + i] + eps &&
			    (kind == kInterior ? ray.interiorCrossing(ta, tb, tHit)
			                       : ray.boundaryCrossing(ta, tb, step, tHit)))
				return true;
		}
		if (tb >= t1) break;
		if (tx <= ty)
		{
			i += di;
			tx = nextX(i);
		}
		else
		{
			j += dj;
			ty = nextY(j);
		}
		if (i < 0 || j < 0 || i >= T.cx || j >= T.cy) break;
		ta = tb;
	}
	return false;
}

}  // namespace semnav::detail

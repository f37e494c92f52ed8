/* semnav: semantic navigation from tilting-laser sweeps */
// The normal kernel's body, compiled once per instruction set: include with
// SEMNAV_KERNEL_NS defined (SimdKernelsBaseline.cpp, SimdKernelsAvx2.cpp).
// cv::v_float32 and vx_* are the widest vectors of the including unit.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/core/hal/intrin.hpp>
#include <vector>

#include "SimdKernels.h"

namespace semnav::detail::SEMNAV_KERNEL_NS
{
/** vx_load_expand_q through an aligned copy: OpenCV's SSE version reads the
 * bytes as one int (UBSan: misaligned load). */
inline cv::v_uint32 loadExpandBytes(const uint8_t* p)
{
	alignas(16) uint8_t bytes[cv::v_uint32::nlanes];
	std::memcpy(bytes, p, sizeof bytes);
	return cv::vx_load_expand_q(bytes);
}

std::size_t pointsRow(const PointRowArgs& a)
{
	constexpr int kLanes = cv::v_float32::nlanes;
	constexpr float nan = std::numeric_limits<float>::quiet_NaN();
	const float fmax = std::numeric_limits<float>::max();
	const int cols = a.cols;
	const float *rr = a.ranges, *cphi = a.cosPhi, *sphi = a.sinPhi;
	const uint8_t* vv = a.validity;
	float *X = a.x, *Y = a.y, *Z = a.z, *V = a.valid, *D = a.rangesOut;
	uint8_t* M = a.mask;
	const float a0 = a.a[0], a1 = a.a[1], a2 = a.a[2];
	const float b0 = a.b[0], b1 = a.b[1], b2 = a.b[2];
	const float t0 = a.t[0], t1 = a.t[1], t2 = a.t[2];
	// Branch-free (vectorizes): invalid ranges give 0 in the padded planes
	// and NaN in the outputs.
	for (int c = 0; c < cols; c++)
	{
		const float d = rr[c];
		const bool ok = (vv[c] != 0) & (d > 0.0f) & (d <= fmax);
		const float dd = ok ? d : 0.0f;
		const float u = dd * cphi[c], v = dd * sphi[c];
		X[c] = ok ? t0 + u * a0 + v * b0 : 0.0f;
		Y[c] = ok ? t1 + u * a1 + v * b1 : 0.0f;
		Z[c] = ok ? t2 + u * a2 + v * b2 : 0.0f;
		V[c] = ok ? 1.0f : 0.0f;
		D[c] = ok ? d : nan;
		M[c] = ok ? 1 : 0;
	}
	// Interleaved points, NaN where invalid, kLanes at a time.
	const cv::v_float32 vNan = cv::vx_setall_f32(nan),
	                    vHalf = cv::vx_setall_f32(0.5f);
	float* P = a.points;
	int c = 0;
	for (; c + kLanes <= cols; c += kLanes)
	{
		const cv::v_float32 ok = cv::vx_load(V + c) > vHalf;
		cv::v_store_interleave(
		    P + 3 * c, cv::v_select(ok, cv::vx_load(X + c), vNan),
		    cv::v_select(ok, cv::vx_load(Y + c), vNan),
		    cv::v_select(ok, cv::vx_load(Z + c), vNan));
	}
	for (; c < cols; c++)
	{
		P[3 * c] = M[c] ? X[c] : nan;
		P[3 * c + 1] = M[c] ? Y[c] : nan;
		P[3 * c + 2] = M[c] ? Z[c] : nan;
	}
	std::size_t valid = 0;
	for (c = 0; c < cols; c++) valid += M[c];
	return valid;
}

std::size_t computeNormals(const NormalKernelArgs& a)
{
	constexpr int kLanes = cv::v_float32::nlanes;
	static_assert(kLanes <= kNormalKernelPad);
	const int rows = a.rows, cols = a.cols, pc = a.paddedCols;
	std::size_t validNormals = 0;
	for (int r = 0; r < rows; r++)
	{
		const std::size_t o = static_cast<std::size_t>(r + 1) * pc + 1;
		const float* X = a.x + o;
		const float* Y = a.y + o;
		const float* Z = a.z + o;
		const float* V = a.valid + o;
		float* NX = a.nx;
		float* NY = a.ny;
		float* NZ = a.nz;
		// Neighbours (i-1, j-1), (i-1, j+1), (i+1, j-1), (i+1, j+1),
		// kLanes pixels at a time (the planes are padded so that the last
		// group may run past the row end).
		const float* Xn[4] = {X - pc - 1, X - pc + 1, X + pc - 1, X + pc + 1};
		const float* Yn[4] = {Y - pc - 1, Y - pc + 1, Y + pc - 1, Y + pc + 1};
		const float* Zn[4] = {Z - pc - 1, Z - pc + 1, Z + pc - 1, Z + pc + 1};
		const float* Vn[4] = {V - pc - 1, V - pc + 1, V + pc - 1, V + pc + 1};
		const cv::v_float32 vE0 = cv::vx_setall_f32(a.e0sq),
		                    vE1 = cv::vx_setall_f32(a.e1sq),
		                    vS = cv::vx_setall_f32(a.sinMinSq),
		                    vHalf = cv::vx_setall_f32(0.5f),
		                    vZero = cv::vx_setzero_f32(),
		                    vOne = cv::vx_setall_f32(1.0f),
		                    vMinusOne = cv::vx_setall_f32(-1.0f),
		                    vsx = cv::vx_setall_f32(a.sensor[3 * r]),
		                    vsy = cv::vx_setall_f32(a.sensor[3 * r + 1]),
		                    vsz = cv::vx_setall_f32(a.sensor[3 * r + 2]);
		for (int c = 0; c < cols; c += kLanes)
		{
			const cv::v_float32 px = cv::vx_load(X + c),
			                    py = cv::vx_load(Y + c),
			                    pz = cv::vx_load(Z + c),
			                    pv = cv::vx_load(V + c);
			cv::v_float32 ex[4], ey[4], ez[4], el[4];
			for (int k = 0; k < 4; k++)
			{
				cv::v_float32 dx = cv::vx_load(Xn[k] + c) - px;
				cv::v_float32 dy = cv::vx_load(Yn[k] + c) - py;
				cv::v_float32 dz = cv::vx_load(Zn[k] + c) - pz;
				cv::v_float32 d2 = dx * dx + dy * dy + dz * dz;
				// Accepted when both are valid and eps0 <= |d| <= eps1.
				const cv::v_float32 acc =
				    (cv::vx_load(Vn[k] + c) * pv > vHalf) & (d2 >= vE0) &
				    (d2 <= vE1);
				ex[k] = dx & acc;
				ey[k] = dy & acc;
				ez[k] = dz & acc;
				el[k] = d2 & acc;
			}
			// Evident intent of the paper's sum of cross products: with the
			// four diagonal neighbours the plain sum over all pairs cancels
			// (e1 x e2 = -(e3 x e4) ...), so every pair's product is turned
			// toward the sensor before summing. Near-parallel pairs (e.g.
			// opposite neighbours) only add noise and are skipped; so are
			// pairs with a rejected neighbour (zero edge).
			const cv::v_float32 vx = vsx - px, vy = vsy - py, vz = vsz - pz;
			cv::v_float32 nx = vZero, ny = vZero, nz = vZero;
			for (int i = 0; i < 3; i++)
				for (int j = i + 1; j < 4; j++)
				{
					const cv::v_float32 cx = ey[i] * ez[j] - ez[i] * ey[j];
					const cv::v_float32 cy = ez[i] * ex[j] - ex[i] * ez[j];
					const cv::v_float32 cz = ex[i] * ey[j] - ey[i] * ex[j];
					const cv::v_float32 c2 = cx * cx + cy * cy + cz * cz;
					const cv::v_float32 keep = c2 > vS * el[i] * el[j];
					const cv::v_float32 sgn =
					    cv::v_select(
					        cx * vx + cy * vy + cz * vz >= vZero, vOne,
					        vMinusOne) &
					    keep;
					// (sgn is +-1 or 0: the product is exact, so a fused
					// multiply-add rounds as a multiply and an add.)
					nx = cv::v_fma(sgn, cx, nx);
					ny = cv::v_fma(sgn, cy, ny);
					nz = cv::v_fma(sgn, cz, nz);
				}
			cv::v_store(NX + c, nx);
			cv::v_store(NY + c, ny);
			cv::v_store(NZ + c, nz);
		}
		// Normalise, kLanes at a time, stored interleaved (x y z per pixel).
		float* N = a.normals + r * a.normalsStep;
		uint8_t* NM = a.mask + r * a.maskStep;
		const cv::v_float32 tiny = cv::vx_setall_f32(1e-24f);
		int c = 0;
		for (; c + kLanes <= cols; c += kLanes)
		{
			const cv::v_float32 x = cv::vx_load(NX + c),
			                    y = cv::vx_load(NY + c),
			                    z = cv::vx_load(NZ + c);
			const cv::v_float32 l2 = x * x + y * y + z * z;
			const cv::v_float32 ok = l2 > tiny;
			const cv::v_float32 inv = cv::v_select(
			    ok, cv::v_invsqrt(cv::v_max(l2, tiny)), cv::vx_setzero_f32());
			cv::v_store_interleave(N + 3 * c, x * inv, y * inv, z * inv);
		}
		for (; c < cols; c++)
		{
			const float l2 = NX[c] * NX[c] + NY[c] * NY[c] + NZ[c] * NZ[c];
			const float inv = l2 > 1e-24f ? 1.0f / std::sqrt(l2) : 0.0f;
			N[3 * c] = NX[c] * inv;
			N[3 * c + 1] = NY[c] * inv;
			N[3 * c + 2] = NZ[c] * inv;
		}
		for (c = 0; c < cols; c++)
		{
			const float l2 = NX[c] * NX[c] + NY[c] * NY[c] + NZ[c] * NZ[c];
			NM[c] = l2 > 1e-24f ? 1 : 0;
			validNormals += NM[c];
		}
	}
	return validNormals;
}

void addRow(float* acc, const float* row, int n)
{
	for (int i = 0; i < n; i++) acc[i] += row[i];
}

void subRow(float* acc, const float* row, int n)
{
	for (int i = 0; i < n; i++) acc[i] -= row[i];
}

void boxRow(const float* acc, float* o, int cols, int ch, int k)
{
	// The middle part is 2k+1 shifted adds (no loop dependency:
	// vectorizes), the k columns at each end are clamped.
	const int w = cols * ch;
	const int head = std::min(k, cols) * ch;
	const int tail = std::max(head, (cols - k) * ch);
	for (int i = head; i < tail; i++) o[i] = acc[i];
	for (int j = 1; j <= k; j++)
	{
		const int d = j * ch;
		for (int i = head; i < tail; i++) o[i] += acc[i - d] + acc[i + d];
	}
	auto edge = [&](int i)
	{
		const int c = i / ch, c0 = i % ch;
		float v = 0;
		for (int cc = std::max(0, c - k); cc <= std::min(cols - 1, c + k); cc++)
			v += acc[cc * ch + c0];
		o[i] = v;
	};
	for (int i = 0; i < head; i++) edge(i);
	for (int i = tail; i < w; i++) edge(i);
}

void normalizeRow(float* S, int cols)
{
	constexpr int kLanes = cv::v_float32::nlanes;
	const cv::v_float32 tiny = cv::vx_setall_f32(1e-24f),
	                    one = cv::vx_setall_f32(1.0f),
	                    zero = cv::vx_setzero_f32();
	int c = 0;
	for (; c + kLanes <= cols; c += kLanes)
	{
		cv::v_float32 x, y, z;
		cv::v_load_deinterleave(S + 3 * c, x, y, z);
		const cv::v_float32 l2 = x * x + y * y + z * z;
		const cv::v_float32 inv = one / cv::v_sqrt(l2);
		const cv::v_float32 ok = l2 > tiny;
		cv::v_store_interleave(
		    S + 3 * c, cv::v_select(ok, x * inv, zero),
		    cv::v_select(ok, y * inv, zero), cv::v_select(ok, z * inv, zero));
	}
	for (; c < cols; c++)
	{
		float* n = S + 3 * c;
		const float l2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
		const float inv = 1.0f / std::sqrt(l2);
		for (int k = 0; k < 3; k++) n[k] = l2 > 1e-24f ? n[k] * inv : 0.0f;
	}
}

void orientRow(
    const float* S, const uint8_t* PM, const uint8_t* NM, uint8_t* cls,
    int cols, const OrientThresholds& t)
{
	for (int c = 0; c < cols; c++)
	{
		const float nz = S[3 * c + 2];
		cls[c] = !PM[c] || !NM[c]            ? kOrientNone
		         : nz >= t.cosUp             ? kOrientUp
		         : nz <= -t.cosDown          ? kOrientDown
		         : std::abs(nz) <= t.sinVert ? kOrientVertical
		                                     : kOrientOblique;
	}
}

void joinMask(const JoinArgs& a)
{
	const int rows = a.rows, cols = a.cols;
	const uint8_t* CL = a.classes;
	const int* A = a.areas;
	const float* RG = a.ranges;
	const float* NS = a.normals;
	uint8_t* J = a.join;
	// (Every term is evaluated, without branches: the outcome is
	// unpredictable along surface edges and in noisy parts. A pixel with a
	// class has a point and a normal; q's class equal to p's covers q's
	// validity.)
	auto ok = [&](int p, int q)
	{
		const uint8_t cls = CL[p];
		const bool angular = (cls == kOrientVertical) | (cls == kOrientOblique);
		const float dot = NS[3 * p] * NS[3 * q] +
		                  NS[3 * p + 1] * NS[3 * q + 1] +
		                  NS[3 * p + 2] * NS[3 * q + 2];
		return (A[p] >= 1) & (cls != kOrientNone) & (CL[q] == cls) &
		       (A[q] == A[p]) & (std::abs(RG[p] - RG[q]) <= a.maxStep) &
		       (!angular | (dot >= a.cosJoin));
	};
	// The same test on kLanes pairs (p, p + step) at a time; lane k of the
	// result is 1 where pixel p + k joins its neighbour.
	constexpr int kLanes = cv::v_uint32::nlanes;
	const cv::v_float32 vMaxStep = cv::vx_setall_f32(a.maxStep),
	                    vCosJoin = cv::vx_setall_f32(a.cosJoin);
	const cv::v_uint32 vNone = cv::vx_setall_u32(kOrientNone),
	                   vVert = cv::vx_setall_u32(kOrientVertical),
	                   vObl = cv::vx_setall_u32(kOrientOblique),
	                   vOne = cv::vx_setall_u32(1);
	const cv::v_int32 vZero = cv::vx_setzero_s32();
	auto joinLanes = [&](int p, int step, unsigned* out)
	{
		const int q = p + step;
		const cv::v_uint32 cp = loadExpandBytes(CL + p),
		                   cq = loadExpandBytes(CL + q);
		const cv::v_int32 ap = cv::vx_load(A + p), aq = cv::vx_load(A + q);
		const cv::v_float32 rp = cv::vx_load(RG + p), rq = cv::vx_load(RG + q);
		cv::v_float32 ax, ay, az, bx, by, bz;
		cv::v_load_deinterleave(NS + 3 * p, ax, ay, az);
		cv::v_load_deinterleave(NS + 3 * q, bx, by, bz);
		const cv::v_float32 dot = ax * bx + ay * by + az * bz;
		const cv::v_uint32 angular = (cp == vVert) | (cp == vObl);
		const cv::v_uint32 m =
		    (cp != vNone) & cv::v_reinterpret_as_u32(ap > vZero) & (cq == cp) &
		    cv::v_reinterpret_as_u32(aq == ap) &
		    cv::v_reinterpret_as_u32(cv::v_abs(rp - rq) <= vMaxStep) &
		    (~angular | cv::v_reinterpret_as_u32(dot >= vCosJoin));
		cv::v_store(out, m & vOne);
	};
	// Per row: the joins to the right and downward as bytes (plain stores),
	// then each pixel's four bits from them and from the row above's.
	unsigned bits[kLanes];
	std::vector<uint8_t> rightRow(cols), downRows(2 * cols, 0);
	for (int r = 0; r < rows; r++)
	{
		const int base = r * cols, end = base + cols;
		uint8_t* R = rightRow.data() - base;  // indexed by pixel
		uint8_t* D = downRows.data() + (r & 1) * cols - base;
		const uint8_t* U = downRows.data() + ((r + 1) & 1) * cols;
		int p = base;
		for (; p + kLanes < end; p += kLanes)
		{
			joinLanes(p, 1, bits);
			for (int k = 0; k < kLanes; k++)
				R[p + k] = static_cast<uint8_t>(bits[k]);
		}
		for (; p + 1 < end; p++) R[p] = ok(p, p + 1);
		R[end - 1] = 0;
		if (r + 1 < rows)
		{
			for (p = base; p + kLanes <= end; p += kLanes)
			{
				joinLanes(p, cols, bits);
				for (int k = 0; k < kLanes; k++)
					D[p + k] = static_cast<uint8_t>(bits[k]);
			}
			for (; p < end; p++) D[p] = ok(p, p + cols);
		}
		else
			std::fill(D + base, D + end, 0);
		// (U: the row above's downward joins, 0 above row 0.)
		uint8_t* JR = J + base;
		const uint8_t *RR = R + base, *DR = D + base;
		JR[0] = static_cast<uint8_t>(RR[0] | (DR[0] << 2) | (U[0] << 3));
		for (int c = 1; c < cols; c++)
			JR[c] = static_cast<uint8_t>(
			    RR[c] | (RR[c - 1] << 1) | (DR[c] << 2) | (U[c] << 3));
	}
}

void roughnessRow(
    const float* N, const float* S, const float* C, const uint8_t* NM, float* R,
    int cols)
{
	constexpr int kLanes = cv::v_float32::nlanes;
	constexpr float nan = std::numeric_limits<float>::quiet_NaN();
	auto one = [&](int c)
	{
		const float cnt = C[c] - 1.0f;
		const float* n = N + 3 * c;
		const float* s = S + 3 * c;
		const float ns = n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
		const float nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
		R[c] = !NM[c] || cnt < 0.5f ? nan : (ns - nn) / cnt;
	};
	const cv::v_float32 vOne = cv::vx_setall_f32(1.0f),
	                    vHalf = cv::vx_setall_f32(0.5f),
	                    vNan = cv::vx_setall_f32(nan);
	const cv::v_uint32 vZero = cv::vx_setzero_u32();
	int c = 0;
	for (; c + kLanes <= cols; c += kLanes)
	{
		cv::v_float32 nx, ny, nz, sx, sy, sz;
		cv::v_load_deinterleave(N + 3 * c, nx, ny, nz);
		cv::v_load_deinterleave(S + 3 * c, sx, sy, sz);
		const cv::v_float32 cnt = cv::vx_load(C + c) - vOne;
		const cv::v_float32 ns = nx * sx + ny * sy + nz * sz;
		const cv::v_float32 nn = nx * nx + ny * ny + nz * nz;
		const cv::v_float32 ok =
		    cv::v_reinterpret_as_f32(loadExpandBytes(NM + c) != vZero) &
		    (cnt >= vHalf);
		cv::v_store(R + c, cv::v_select(ok, (ns - nn) / cnt, vNan));
	}
	for (; c < cols; c++) one(c);
}

void distanceBins(
    const float* x, const float* y, int n, float mx, float my, float off,
    double scale, int offset, int outside, int* bins)
{
	auto one = [&](int i)
	{
		const float d = mx * x[i] + my * y[i] - off;
		const int b = static_cast<int>(std::floor(d * scale)) + offset;
		bins[i] = static_cast<unsigned>(b) < static_cast<unsigned>(outside)
		              ? b
		              : outside;
	};
	constexpr int kLanes = cv::v_float32::nlanes;
	const cv::v_float32 vmx = cv::vx_setall_f32(mx),
	                    vmy = cv::vx_setall_f32(my),
	                    voff = cv::vx_setall_f32(off);
	const cv::v_float64 vscale = cv::vx_setall_f64(scale);
	const cv::v_int32 voffset = cv::vx_setall_s32(offset),
	                  vout = cv::vx_setall_s32(outside);
	int i = 0;
	for (; i + kLanes <= n; i += kLanes)
	{
		const cv::v_float32 d =
		    vmx * cv::vx_load(x + i) + vmy * cv::vx_load(y + i) - voff;
		const cv::v_int32 b = cv::v_combine_low(
		                          cv::v_floor(cv::v_cvt_f64(d) * vscale),
		                          cv::v_floor(cv::v_cvt_f64_high(d) * vscale)) +
		                      voffset;
		const cv::v_int32 in = cv::v_reinterpret_as_s32(
		    cv::v_reinterpret_as_u32(b) < cv::v_reinterpret_as_u32(vout));
		cv::v_store(bins + i, cv::v_select(in, b, vout));
	}
	for (; i < n; i++) one(i);
}

void bandBits(
    const float* x, const float* y, int n, double mx, double my, double d,
    double half, uint64_t* bits)
{
	std::fill(bits, bits + (n + 63) / 64, uint64_t{0});
	auto one = [&](int i)
	{
		const double xi = x[i], yi = y[i];
		if (std::abs(mx * xi + my * yi - d) <= half)
			bits[i / 64] |= uint64_t{1} << (i % 64);
	};
	constexpr int kLanes = cv::v_float32::nlanes;  // divides 64
	const cv::v_float64 vmx = cv::vx_setall_f64(mx),
	                    vmy = cv::vx_setall_f64(my), vd = cv::vx_setall_f64(d),
	                    vhalf = cv::vx_setall_f64(half);
	auto inBand = [&](const cv::v_float64& xs, const cv::v_float64& ys)
	{ return cv::v_signmask(cv::v_abs(vmx * xs + vmy * ys - vd) <= vhalf); };
	int i = 0;
	for (; i + kLanes <= n; i += kLanes)
	{
		const cv::v_float32 xs = cv::vx_load(x + i), ys = cv::vx_load(y + i);
		const uint64_t m = static_cast<uint64_t>(
		                       inBand(cv::v_cvt_f64(xs), cv::v_cvt_f64(ys))) |
		                   static_cast<uint64_t>(inBand(
		                       cv::v_cvt_f64_high(xs), cv::v_cvt_f64_high(ys)))
		                       << (kLanes / 2);
		bits[i / 64] |= m << (i % 64);
	}
	for (; i < n; i++) one(i);
}

// (In SimdKernels' member order.)
extern const SimdKernels kKernels = {
    &pointsRow,    &computeNormals, &addRow,    &subRow,
    &boxRow,       &normalizeRow,   &orientRow, &joinMask,
    &roughnessRow, &distanceBins,   &bandBits,  SEMNAV_KERNEL_NAME};

}  // namespace semnav::detail::SEMNAV_KERNEL_NS

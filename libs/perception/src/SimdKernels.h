/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstddef>
#include <cstdint>

namespace semnav::detail
{
/** Floats the normal kernel may read past a row of the padded planes (the
 * widest vectors of any of its builds). */
constexpr int kNormalKernelPad = 16;

/** Input and output of the normal kernel (NormalImage::compute). */
struct NormalKernelArgs
{
	int rows = 0, cols = 0;
	/** Padded point planes x, y, z and validity (1 / 0), (rows + 2) x
	 * paddedCols, one invalid pixel around, kNormalKernelPad floats past
	 * the end. */
	const float *x = nullptr, *y = nullptr, *z = nullptr, *valid = nullptr;
	int paddedCols = 0;
	/** Sensor position per row (x y z). */
	const float* sensor = nullptr;
	/** Squared eps0, eps1 and squared sine of the minimum pair angle. */
	float e0sq = 0, e1sq = 0, sinMinSq = 0;
	/** Per-row scratch, cols + kNormalKernelPad floats each. */
	float *nx = nullptr, *ny = nullptr, *nz = nullptr;
	/** Outputs: unit normals (3 floats per pixel) and mask, row strides in
	 * floats and bytes. */
	float* normals = nullptr;
	std::size_t normalsStep = 0;
	uint8_t* mask = nullptr;
	std::size_t maskStep = 0;
};

/** One row of NormalImage::compute's points. */
struct PointRowArgs
{
	int cols = 0;
	const float* ranges = nullptr;
	const uint8_t* validity = nullptr;
	/** cos and sin of each column's bearing. */
	const float *cosPhi = nullptr, *sinPhi = nullptr;
	/** The row's scanner pose: rotation columns 0 and 1, translation. */
	float a[3] = {0, 0, 0}, b[3] = {0, 0, 0}, t[3] = {0, 0, 0};
	/** Outputs: padded planes (0 where invalid) and validity (1 / 0),
	 * ranges (NaN where invalid), mask, interleaved points (NaN where
	 * invalid). */
	float *x = nullptr, *y = nullptr, *z = nullptr, *valid = nullptr;
	float* rangesOut = nullptr;
	uint8_t* mask = nullptr;
	float* points = nullptr;
};

/** Orientation classes of normals (RuleClassifier). */
enum OrientClass : uint8_t
{
	kOrientNone = 0,
	kOrientUp,
	kOrientDown,
	kOrientVertical,
	kOrientOblique
};

/** Thresholds on a unit normal's z for orientRow(). */
struct OrientThresholds
{
	float cosUp = 0, cosDown = 0, sinVert = 0;
};

/** Input and output of joinMask() (RuleClassifier's surfaces). */
struct JoinArgs
{
	int rows = 0, cols = 0;
	const uint8_t* classes = nullptr;  ///< OrientClass per pixel
	const int* areas = nullptr;        ///< segmentation area ids
	const float* ranges = nullptr;     ///< NaN where invalid
	const float* normals = nullptr;    ///< x y z per pixel
	/** Largest range step and smallest normal dot product (vertical and
	 * oblique pixels) between joined neighbours. */
	float maxStep = 0, cosJoin = 0;
	/** Output: per pixel bit 0 joins the right neighbour, 1 the left, 2 the
	 * one below (next row), 3 the one above. */
	uint8_t* join = nullptr;
};

/** The perception's vector kernels, one build per instruction set (the
 * same results bit for bit: no reordered sums, no fused multiply-adds). */
struct SimdKernels
{
	/** Points of one row; returns the number of valid ones. Invalid, NaN,
	 * infinite or <= 0 ranges are invalid. */
	std::size_t (*pointsRow)(const PointRowArgs& a);
	/** Normals of every row; returns the number of pixels with one. */
	std::size_t (*computeNormals)(const NormalKernelArgs& a);
	/** acc[i] += row[i] (add) or -= (sub), i < n. */
	void (*addRow)(float* acc, const float* row, int n);
	void (*subRow)(float* acc, const float* row, int n);
	/** Box sums along a row of `cols` pixels of `ch` interleaved channels:
	 * out[c] = sum of acc over columns c-k .. c+k inside the row. */
	void (*boxRow)(const float* acc, float* out, int cols, int ch, int k);
	/** Normalises `cols` summed normals (x y z) in place, 0 where the sum
	 * is ~0. */
	void (*normalizeRow)(float* sums, int cols);
	/** Orientation classes of a row of unit normals: kOrientNone without
	 * point or normal (pointMask, normalMask), else up (z >= cosUp), down
	 * (z <= -cosDown), vertical (|z| <= sinVert) or oblique. */
	void (*orientRow)(
	    const float* normals, const uint8_t* pointMask,
	    const uint8_t* normalMask, uint8_t* classes, int cols,
	    const OrientThresholds& t);
	/** Which 4-neighbours may join a pixel's surface: same area (>= 1) and
	 * class (not none), ranges within maxStep, and for vertical and
	 * oblique pixels normals within acos(cosJoin). */
	void (*joinMask)(const JoinArgs& a);
	/** Roughness R of a row: (n . s - n . n) / (count - 1) from the unit
	 * normals n, their window sums s (x y z per pixel) and the window
	 * counts of normals; NaN without a normal (normalMask) or neighbour. */
	void (*roughnessRow)(
	    const float* normals, const float* sums, const float* counts,
	    const uint8_t* normalMask, float* r, int cols);
	/** Histogram bins of the distances d = mx x + my y - off of n points
	 * (float, unfused): floor(d * scale) (in double) + offset, or
	 * `outside` where that is not in [0, outside). */
	void (*distanceBins)(
	    const float* x, const float* y, int n, float mx, float my, float off,
	    double scale, int offset, int outside, int* bins);
	/** Bit i of bits[i / 64] set where |mx x + my y - d| <= half for point
	 * i of n (in double); (n + 63) / 64 words are written. */
	void (*bandBits)(
	    const float* x, const float* y, int n, double mx, double my, double d,
	    double half, uint64_t* bits);
	/** "baseline" (SSE2) or "avx2". */
	const char* name;
};

/** The widest build the CPU runs: AVX2 where it has AVX2, FMA and F16C (8
 * floats per vector instead of 4), else the baseline. */
const SimdKernels& simdKernels();
/** Makes simdKernels() return the baseline build only (tests), or again
 * the widest. */
void setKernelsBaselineOnly(bool baselineOnly);

}  // namespace semnav::detail

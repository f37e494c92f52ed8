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

/** Computes the normals of every row; returns the number of pixels with a
 * normal. Runs the AVX2 build of the kernel where the CPU has AVX2, FMA and
 * F16C (8 floats per vector instead of 4; the same results bit for bit),
 * else the baseline (SSE2) build. */
std::size_t computeNormals(const NormalKernelArgs& a);

/** The builds, for tests and benchmarks. avx2 is null when the compiler
 * could not build it. */
std::size_t computeNormalsBaseline(const NormalKernelArgs& a);
extern std::size_t (*const computeNormalsAvx2)(const NormalKernelArgs& a);
/** Whether computeNormals() runs the AVX2 build on this CPU (and it is not
 * turned off by setKernelsBaselineOnly()). */
bool normalKernelUsesAvx2();
/** Makes the kernels run their baseline builds only (tests: same results
 * bit for bit), or again the widest the CPU has. */
void setKernelsBaselineOnly(bool baselineOnly);

}  // namespace semnav::detail

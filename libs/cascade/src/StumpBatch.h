/* semnav: semantic navigation from tilting-laser sweeps */
// Internal: one cascade stage evaluated on one window or on eight windows
// side by side (CascadeEvaluator::scanWindows), with OpenCV's arithmetic per
// window.
#pragma once

#include <cstddef>
#include <cstdint>

namespace semnav::detail
{
/** A stump with its feature compiled for one integral-image row stride:
 * what CompiledFeature::calc and the leaf of CascadeEvaluator need, in one
 * record (no indirection through the feature index). */
struct FlatStump
{
	/** Corner offsets of rectangle i at ofs[4 * i .. 4 * i + 3]. */
	int32_t ofs[12] = {};
	float weight[3] = {0, 0, 0};
	float threshold = 0;
	/** left (value < threshold), right. */
	float leaf[2] = {0, 0};
	/** Rectangles summed: 2, or 3 when weight[2] != 0 (OpenCV skips a
	 * zero third weight). */
	int32_t rects = 2;
	bool tilted = false;
};

/** Integral images entries a dense eight-window evaluation may read past
 * the last window's (step 2 loads sixteen entries). */
constexpr int kDenseOverread = 16;

/** The stage sum (double, stumps added in order) of `stumps` for the
 * window whose top-left entry is at `base` in the integral images `sum`
 * and `tilted` (may be null without tilted stumps), with variance factor
 * `nf`: exactly CascadeEvaluator::evaluateStages' arithmetic. */
double stageSum(
    const FlatStump* stumps, std::size_t stumpCount, const int32_t* sum,
    const int32_t* tilted, int32_t base, float nf);

/** The same for the eight windows at base + step * i, i = 0..7 (step 1
 * or 2), with factors nf[i], into sums[i]: eight lanes of AVX2, the same
 * operations per lane in the same order (no fused multiply-add), so the
 * same sums bit for bit. Reads up to kDenseOverread entries past the
 * last window's. Needs cpuHasAvx2(). */
void stageSums8(
    const FlatStump* stumps, std::size_t stumpCount, const int32_t* sum,
    const int32_t* tilted, int32_t base, int step, const float* nf,
    double* sums);

/** stageSum() of four windows anywhere (top-left entries bases[i],
 * factors nf[i]) side by side: the same arithmetic per window. */
void stageSumsAt4(
    const FlatStump* stumps, std::size_t stumpCount, const int32_t* sum,
    const int32_t* tilted, const int32_t* bases, const float* nf, double* sums);

/** Whether stageSums8() can run on this CPU. */
bool cpuHasAvx2();

}  // namespace semnav::detail

/* semnav: semantic navigation from tilting-laser sweeps */
#define SEMNAV_KERNEL_NS baseline
#define SEMNAV_KERNEL_NAME "baseline"
#include <atomic>

#include "SimdKernels.impl.h"

namespace semnav::detail
{
#ifdef SEMNAV_HAVE_AVX2_KERNELS
namespace avx2
{
extern const SimdKernels kKernels;
}  // namespace avx2
#endif

namespace
{
std::atomic<bool> baselineOnly{false};

const SimdKernels* widest()
{
#ifdef SEMNAV_HAVE_AVX2_KERNELS
#if defined(__clang__) && __clang_major__ < 15
	// clang 14 (scripts/fuzz) knows no "f16c" here; AVX2 CPUs have F16C.
	const bool f16c = true;
#else
	const bool f16c = __builtin_cpu_supports("f16c");
#endif
	if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && f16c)
		return &avx2::kKernels;
#endif
	return &baseline::kKernels;
}
}  // namespace

void setKernelsBaselineOnly(bool b)
{
	baselineOnly = b;
}

const SimdKernels& simdKernels()
{
	static const SimdKernels* const w = widest();
	return baselineOnly ? baseline::kKernels : *w;
}

}  // namespace semnav::detail

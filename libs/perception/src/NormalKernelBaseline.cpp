/* semnav: semantic navigation from tilting-laser sweeps */
#define SEMNAV_KERNEL_NS baseline
#include <atomic>

#include "NormalKernel.impl.h"

namespace semnav::detail
{
std::size_t computeNormalsBaseline(const NormalKernelArgs& a)
{
	return baseline::computeNormals(a);
}

#ifndef SEMNAV_HAVE_AVX2_KERNELS
std::size_t (*const computeNormalsAvx2)(const NormalKernelArgs&) = nullptr;
#endif

namespace
{
std::atomic<bool> baselineOnly{false};
}  // namespace

void setKernelsBaselineOnly(bool b)
{
	baselineOnly = b;
}

bool normalKernelUsesAvx2()
{
	static const bool cpu = __builtin_cpu_supports("avx2") &&
	                        __builtin_cpu_supports("fma") &&
	                        __builtin_cpu_supports("f16c");
	return computeNormalsAvx2 != nullptr && cpu && !baselineOnly;
}

std::size_t computeNormals(const NormalKernelArgs& a)
{
	return normalKernelUsesAvx2() ? computeNormalsAvx2(a)
	                              : computeNormalsBaseline(a);
}

}  // namespace semnav::detail

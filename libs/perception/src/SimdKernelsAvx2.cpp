/* semnav: semantic navigation from tilting-laser sweeps */
// The kernels at 8 floats per vector. Built with -mavx2 -mfma -mf16c
// -ffp-contract=off (CMakeLists.txt) and, like OpenCV's own *.avx2.cpp
// dispatch units, with its universal intrinsics switched to AVX2 in their
// own namespace (cv::hal_AVX2); called only where the CPU has them.
#define CV_CPU_DISPATCH_MODE AVX2
#define CV_SSE3 1
#define CV_SSSE3 1
#define CV_SSE4_1 1
#define CV_SSE4_2 1
#define CV_POPCNT 1
#define CV_AVX 1
#define CV_FP16 1
#define CV_AVX2 1
#define CV_FMA3 1
#define SEMNAV_KERNEL_NS avx2
#define SEMNAV_KERNEL_NAME "avx2"
#include <immintrin.h>

#include "SimdKernels.impl.h"

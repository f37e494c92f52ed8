/* semnav: semantic navigation from tilting-laser sweeps */
#include "StumpBatch.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SEMNAV_HAVE_AVX2_KERNEL 1
#endif

namespace semnav::detail
{
namespace
{
inline int32_t rectAt(const int32_t* p, const int32_t* o)
{
	return p[o[0]] - p[o[1]] - p[o[2]] + p[o[3]];
}

/** The leaf a stump gives the window at `base` with variance factor `nf`
 * (CompiledFeature::calc's arithmetic, in float). */
inline float stumpLeaf(
    const FlatStump& st, const int32_t* sum, const int32_t* tilted,
    int32_t base, float nf)
{
	const int32_t* p = (st.tilted ? tilted : sum) + base;
	float ret = st.weight[0] * static_cast<float>(rectAt(p, st.ofs)) +
	            st.weight[1] * static_cast<float>(rectAt(p, st.ofs + 4));
	if (st.rects == 3)
		ret += st.weight[2] * static_cast<float>(rectAt(p, st.ofs + 8));
	const float value = ret * nf;
	return st.leaf[!(value < st.threshold)];
}

#ifdef SEMNAV_HAVE_AVX2_KERNEL
#define SEMNAV_AVX2 __attribute__((target("avx2")))

/** a - b - c + d of the corners `o` of one rectangle at eight consecutive
 * entries from p + shift (as the scalar expression; exact in int32). */
SEMNAV_AVX2 inline __m256i corners8(
    const int32_t* p, const int32_t* o, int shift)
{
	const __m256i a =
	    _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + o[0] + shift));
	const __m256i b =
	    _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + o[1] + shift));
	const __m256i c =
	    _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + o[2] + shift));
	const __m256i d =
	    _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + o[3] + shift));
	return _mm256_add_epi32(_mm256_sub_epi32(_mm256_sub_epi32(a, b), c), d);
}

/** The rectangle's sum for eight windows `Step` entries apart. */
template <int Step>
SEMNAV_AVX2 inline __m256i rect8(const int32_t* p, const int32_t* o)
{
	if constexpr (Step == 1)
		return corners8(p, o, 0);
	else
	{
		// Sixteen consecutive windows, then the even ones (the combination
		// is per entry, so it commutes with the selection).
		const __m256 lo = _mm256_castsi256_ps(corners8(p, o, 0));
		const __m256 hi = _mm256_castsi256_ps(corners8(p, o, 8));
		// [lo0 lo2 hi0 hi2 | lo4 lo6 hi4 hi6] -> [lo0 lo2 lo4 lo6 hi0 ...]
		const __m256 t = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0));
		return _mm256_castpd_si256(_mm256_permute4x64_pd(
		    _mm256_castps_pd(t), _MM_SHUFFLE(3, 1, 2, 0)));
	}
}

template <int Step>
SEMNAV_AVX2 void stageSums8Avx2(
    const FlatStump* stumps, std::size_t n, const int32_t* sum,
    const int32_t* tilted, int32_t base, const float* nfp, double* sums)
{
	const __m256 nf = _mm256_loadu_ps(nfp);
	__m256d lo = _mm256_setzero_pd(), hi = _mm256_setzero_pd();
	for (std::size_t s = 0; s < n; s++)
	{
		const FlatStump& st = stumps[s];
		const int32_t* p = (st.tilted ? tilted : sum) + base;
		// Per lane as CompiledFeature::calc: w0 * r0 + w1 * r1 (+ w2 * r2),
		// each product and sum rounded to float.
		__m256 ret = _mm256_add_ps(
		    _mm256_mul_ps(
		        _mm256_set1_ps(st.weight[0]),
		        _mm256_cvtepi32_ps(rect8<Step>(p, st.ofs))),
		    _mm256_mul_ps(
		        _mm256_set1_ps(st.weight[1]),
		        _mm256_cvtepi32_ps(rect8<Step>(p, st.ofs + 4))));
		if (st.rects == 3)
			ret = _mm256_add_ps(
			    ret, _mm256_mul_ps(
			             _mm256_set1_ps(st.weight[2]),
			             _mm256_cvtepi32_ps(rect8<Step>(p, st.ofs + 8))));
		const __m256 value = _mm256_mul_ps(ret, nf);
		const __m256 less =
		    _mm256_cmp_ps(value, _mm256_set1_ps(st.threshold), _CMP_LT_OQ);
		const __m256 leaf = _mm256_blendv_ps(
		    _mm256_set1_ps(st.leaf[1]), _mm256_set1_ps(st.leaf[0]), less);
		lo = _mm256_add_pd(lo, _mm256_cvtps_pd(_mm256_castps256_ps128(leaf)));
		hi = _mm256_add_pd(hi, _mm256_cvtps_pd(_mm256_extractf128_ps(leaf, 1)));
	}
	_mm256_storeu_pd(sums, lo);
	_mm256_storeu_pd(sums + 4, hi);
}
#endif
}  // namespace

double stageSum(
    const FlatStump* stumps, std::size_t n, const int32_t* sum,
    const int32_t* tilted, int32_t base, float nf)
{
	double tmp = 0;
	for (std::size_t s = 0; s < n; s++)
		tmp += stumpLeaf(stumps[s], sum, tilted, base, nf);
	return tmp;
}

void stageSumsAt4(
    const FlatStump* stumps, std::size_t n, const int32_t* sum,
    const int32_t* tilted, const int32_t* bases, const float* nf, double* sums)
{
	double t0 = 0, t1 = 0, t2 = 0, t3 = 0;
	const int32_t b0 = bases[0], b1 = bases[1], b2 = bases[2], b3 = bases[3];
	const float n0 = nf[0], n1 = nf[1], n2 = nf[2], n3 = nf[3];
	for (std::size_t s = 0; s < n; s++)
	{
		const FlatStump& st = stumps[s];
		t0 += stumpLeaf(st, sum, tilted, b0, n0);
		t1 += stumpLeaf(st, sum, tilted, b1, n1);
		t2 += stumpLeaf(st, sum, tilted, b2, n2);
		t3 += stumpLeaf(st, sum, tilted, b3, n3);
	}
	sums[0] = t0;
	sums[1] = t1;
	sums[2] = t2;
	sums[3] = t3;
}

bool cpuHasAvx2()
{
#ifdef SEMNAV_HAVE_AVX2_KERNEL
	static const bool has = __builtin_cpu_supports("avx2");
	return has;
#else
	return false;
#endif
}

void stageSums8(
    const FlatStump* stumps, std::size_t n, const int32_t* sum,
    const int32_t* tilted, int32_t base, int step, const float* nf,
    double* sums)
{
#ifdef SEMNAV_HAVE_AVX2_KERNEL
	if (step == 1)
		stageSums8Avx2<1>(stumps, n, sum, tilted, base, nf, sums);
	else
		stageSums8Avx2<2>(stumps, n, sum, tilted, base, nf, sums);
#else
	for (int i = 0; i < 8; i++)
		sums[i] = stageSum(stumps, n, sum, tilted, base + step * i, nf[i]);
#endif
}

}  // namespace semnav::detail

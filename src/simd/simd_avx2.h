/* The SIMD vocabulary on AVX2 + FMA: 8 float lanes, masks are all-ones lanes. */
#ifndef HB_SIMD_AVX2_H
#define HB_SIMD_AVX2_H

#include <immintrin.h>
#include <stdint.h>

#define HB_W 8
#define HB_ISA_LABEL "avx2"

typedef __m256 vf;
typedef __m256i vi;
typedef __m256 vm;

#define HB_ROUND_NEAREST (_MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)

HB_INLINE vf vf_set1(float a) { return _mm256_set1_ps(a); }
HB_INLINE vf vf_loadu(const float *p) { return _mm256_loadu_ps(p); }
HB_INLINE void vf_storeu(float *p, vf a) { _mm256_storeu_ps(p, a); }
HB_INLINE vf vf_add(vf a, vf b) { return _mm256_add_ps(a, b); }
HB_INLINE vf vf_sub(vf a, vf b) { return _mm256_sub_ps(a, b); }
HB_INLINE vf vf_mul(vf a, vf b) { return _mm256_mul_ps(a, b); }
HB_INLINE vf vf_div(vf a, vf b) { return _mm256_div_ps(a, b); }
HB_INLINE vf vf_fma(vf a, vf b, vf c) { return _mm256_fmadd_ps(a, b, c); }
HB_INLINE vf vf_fnma(vf a, vf b, vf c) { return _mm256_fnmadd_ps(a, b, c); }
HB_INLINE vf vf_min(vf a, vf b) { return _mm256_min_ps(a, b); }
HB_INLINE vf vf_max(vf a, vf b) { return _mm256_max_ps(a, b); }
HB_INLINE vf vf_sqrt(vf a) { return _mm256_sqrt_ps(a); }
HB_INLINE vf vf_select(vm m, vf a, vf b) { return _mm256_blendv_ps(b, a, m); }
HB_INLINE vf vf_keep(vm m, vf a) { return _mm256_and_ps(a, m); }
HB_INLINE vf vf_round(vf a) { return _mm256_round_ps(a, HB_ROUND_NEAREST); }

HB_INLINE vm vf_lt(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
HB_INLINE vm vf_le(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
HB_INLINE vm vf_gt(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
HB_INLINE vm vf_ge(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_GE_OQ); }
HB_INLINE vm vf_eq(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_EQ_OQ); }
HB_INLINE vm vf_ne(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_NEQ_UQ); }

HB_INLINE vm vm_and(vm a, vm b) { return _mm256_and_ps(a, b); }
HB_INLINE vm vm_or(vm a, vm b) { return _mm256_or_ps(a, b); }
HB_INLINE vm vm_andnot(vm a, vm b) { return _mm256_andnot_ps(b, a); }
HB_INLINE vm vm_not(vm a) { return _mm256_xor_ps(a, _mm256_castsi256_ps(_mm256_set1_epi32(-1))); }
HB_INLINE unsigned vm_bits(vm a) { return (unsigned)_mm256_movemask_ps(a); }

HB_INLINE vi vf_as_vi(vf a) { return _mm256_castps_si256(a); }
HB_INLINE vf vi_as_vf(vi a) { return _mm256_castsi256_ps(a); }
HB_INLINE vi vi_set1(int32_t a) { return _mm256_set1_epi32(a); }
HB_INLINE vi vi_add(vi a, vi b) { return _mm256_add_epi32(a, b); }
HB_INLINE vi vi_sub(vi a, vi b) { return _mm256_sub_epi32(a, b); }
HB_INLINE vi vi_and(vi a, vi b) { return _mm256_and_si256(a, b); }
HB_INLINE vi vi_or(vi a, vi b) { return _mm256_or_si256(a, b); }
HB_INLINE vi vi_xor(vi a, vi b) { return _mm256_xor_si256(a, b); }
HB_INLINE vi vi_mul(vi a, vi b) { return _mm256_mullo_epi32(a, b); } /* low 32 bits */
HB_INLINE vi vi_shl(vi a, int n) { return _mm256_slli_epi32(a, n); }
HB_INLINE vi vi_shr(vi a, int n) { return _mm256_srli_epi32(a, n); }
HB_INLINE vm vi_eq(vi a, vi b) { return _mm256_castsi256_ps(_mm256_cmpeq_epi32(a, b)); }
HB_INLINE vi vi_from_vf(vf a) { return _mm256_cvttps_epi32(a); }
HB_INLINE vf vf_from_vi(vi a) { return _mm256_cvtepi32_ps(a); }
HB_INLINE vf vf_gather(const float *base, vi idx) { return _mm256_i32gather_ps(base, idx, 4); }

#define HB_PD_T __m256d
#define HB_PD_ADD _mm256_add_pd
#define HB_PD_SUB _mm256_sub_pd
#define HB_PD_MUL _mm256_mul_pd
#define HB_PD_DIV _mm256_div_pd
#define HB_PD_SQRT _mm256_sqrt_pd
#define HB_PD_MIN _mm256_min_pd
#define HB_PD_MAX _mm256_max_pd
#define HB_PD_FMA _mm256_fmadd_pd
#define HB_PD_ROUND(a) _mm256_round_pd(a, HB_ROUND_NEAREST)
#define HB_PD_SET1 _mm256_set1_pd
#include "simd_vdw_pair.h"

HB_INLINE vdw vdw_from_vf(vf a)
{
    vdw r = { _mm256_cvtps_pd(_mm256_castps256_ps128(a)), _mm256_cvtps_pd(_mm256_extractf128_ps(a, 1)) };
    return r;
}
HB_INLINE vf vdw_to_vf(vdw a)
{
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm256_cvtpd_ps(a.lo)), _mm256_cvtpd_ps(a.hi), 1);
}

#endif

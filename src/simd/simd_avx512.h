/* The SIMD vocabulary on AVX-512F: 16 float lanes, masks are k-registers. */
#ifndef HB_SIMD_AVX512_H
#define HB_SIMD_AVX512_H

#include <immintrin.h>
#include <stdint.h>

#include "simd_x86.h"

#define HB_W 16
#define HB_ISA_LABEL "avx512"

typedef __m512 vf;
typedef __m512i vi;
typedef __mmask16 vm;

#define HB_ROUND_NEAREST (_MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)

HB_INLINE vf vf_set1(float a) { return _mm512_set1_ps(a); }
HB_INLINE vf vf_loadu(const float *p) { return _mm512_loadu_ps(p); }
HB_INLINE void vf_storeu(float *p, vf a) { _mm512_storeu_ps(p, a); }
HB_INLINE vf vf_add(vf a, vf b) { return _mm512_add_ps(a, b); }
HB_INLINE vf vf_sub(vf a, vf b) { return _mm512_sub_ps(a, b); }
HB_INLINE vf vf_mul(vf a, vf b) { return _mm512_mul_ps(a, b); }
HB_INLINE vf vf_div(vf a, vf b) { return _mm512_div_ps(a, b); }
HB_INLINE vf vf_fma(vf a, vf b, vf c) { return _mm512_fmadd_ps(a, b, c); }
HB_INLINE vf vf_fnma(vf a, vf b, vf c) { return _mm512_fnmadd_ps(a, b, c); }
HB_INLINE vf vf_min(vf a, vf b) { return _mm512_min_ps(a, b); }
HB_INLINE vf vf_max(vf a, vf b) { return _mm512_max_ps(a, b); }
HB_INLINE vf vf_sqrt(vf a) { return _mm512_sqrt_ps(a); }
HB_INLINE vf vf_select(vm m, vf a, vf b) { return _mm512_mask_blend_ps(m, b, a); }
HB_INLINE vf vf_keep(vm m, vf a) { return _mm512_maskz_mov_ps(m, a); }
HB_INLINE vf vf_round(vf a) { return _mm512_roundscale_ps(a, HB_ROUND_NEAREST); }

HB_INLINE vm vf_lt(vf a, vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_LT_OQ); }
HB_INLINE vm vf_le(vf a, vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ); }
HB_INLINE vm vf_gt(vf a, vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ); }
HB_INLINE vm vf_ge(vf a, vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_GE_OQ); }
HB_INLINE vm vf_eq(vf a, vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_EQ_OQ); }

HB_INLINE vm vm_and(vm a, vm b) { return (vm)(a & b); }
HB_INLINE vm vm_or(vm a, vm b) { return (vm)(a | b); }
HB_INLINE vm vm_andnot(vm a, vm b) { return (vm)(a & ~b); }
HB_INLINE vm vm_not(vm a) { return (vm)~a; }
HB_INLINE unsigned vm_bits(vm a) { return (unsigned)a; }
HB_INLINE float vf_sum_lanes(vf a)
{
    __m256 hi = _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(a), 1));
    __m256 s = _mm256_add_ps(_mm512_castps512_ps256(a), hi);
    __m128 q = _mm_add_ps(_mm256_castps256_ps128(s), _mm256_extractf128_ps(s, 1));
    return HB_SUM4_PS(q);
}

HB_INLINE vi vf_as_vi(vf a) { return _mm512_castps_si512(a); }
HB_INLINE vf vi_as_vf(vi a) { return _mm512_castsi512_ps(a); }
HB_INLINE vi vi_set1(int32_t a) { return _mm512_set1_epi32(a); }
HB_INLINE vi vi_add(vi a, vi b) { return _mm512_add_epi32(a, b); }
HB_INLINE vi vi_sub(vi a, vi b) { return _mm512_sub_epi32(a, b); }
HB_INLINE vi vi_and(vi a, vi b) { return _mm512_and_si512(a, b); }
HB_INLINE vi vi_or(vi a, vi b) { return _mm512_or_si512(a, b); }
HB_INLINE vi vi_xor(vi a, vi b) { return _mm512_xor_si512(a, b); }
HB_INLINE vi vi_mul(vi a, vi b) { return _mm512_mullo_epi32(a, b); } /* low 32 bits */
HB_INLINE vi vi_shl(vi a, int n) { return _mm512_slli_epi32(a, (unsigned)n); }
HB_INLINE vi vi_shr(vi a, int n) { return _mm512_srli_epi32(a, (unsigned)n); }
HB_INLINE vm vi_eq(vi a, vi b) { return _mm512_cmpeq_epi32_mask(a, b); }
HB_INLINE vi vi_from_vf(vf a) { return _mm512_cvttps_epi32(a); }
HB_INLINE vf vf_from_vi(vi a) { return _mm512_cvtepi32_ps(a); }
HB_INLINE vf vf_gather(const float *base, vi idx) { return _mm512_i32gather_ps(idx, base, 4); }
/* out[j], lane l = base[idx_l + j], j < 4: lanes k, k + 4, k + 8, k + 12 fill one register's four
 * 128-bit lanes, transposed in place (simd.h). */
HB_INLINE void vf_gather4(const float *base, vi idx, vf out[4])
{
    int32_t i[16];
    _mm512_storeu_si512(i, idx);
#define HB_LANE_QUAD(k)                                                                                    \
    _mm512_insertf32x4(_mm512_insertf32x4(_mm512_insertf32x4(_mm512_castps128_ps512(_mm_loadu_ps(base + i[k])), \
                                                             _mm_loadu_ps(base + i[k + 4]), 1),                \
                                          _mm_loadu_ps(base + i[k + 8]), 2),                                   \
                       _mm_loadu_ps(base + i[k + 12]), 3)
    HB_TRANSPOSE4_IN_LANES(__m512, _mm512, HB_LANE_QUAD(0), HB_LANE_QUAD(1), HB_LANE_QUAD(2), HB_LANE_QUAD(3), out[0], out[1],
                           out[2], out[3]);
#undef HB_LANE_QUAD
}

#define HB_PD_T __m512d
#define HB_PD_ADD _mm512_add_pd
#define HB_PD_SUB _mm512_sub_pd
#define HB_PD_MUL _mm512_mul_pd
#define HB_PD_DIV _mm512_div_pd
#define HB_PD_SQRT _mm512_sqrt_pd
#define HB_PD_MIN _mm512_min_pd
#define HB_PD_MAX _mm512_max_pd
#define HB_PD_FMA _mm512_fmadd_pd
#define HB_PD_ROUND(a) _mm512_roundscale_pd(a, HB_ROUND_NEAREST)
#define HB_PD_SET1 _mm512_set1_pd
#include "simd_vdw_pair.h"

HB_INLINE vdw vdw_from_vf(vf a)
{
    __m256 hi = _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(a), 1));
    vdw r = { _mm512_cvtps_pd(_mm512_castps512_ps256(a)), _mm512_cvtps_pd(hi) };
    return r;
}
HB_INLINE vf vdw_to_vf(vdw a)
{
    __m512d lo = _mm512_castps_pd(_mm512_castps256_ps512(_mm512_cvtpd_ps(a.lo)));
    return _mm512_castpd_ps(_mm512_insertf64x4(lo, _mm256_castps_pd(_mm512_cvtpd_ps(a.hi)), 1));
}

#endif

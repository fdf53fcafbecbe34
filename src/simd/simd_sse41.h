/* The SIMD vocabulary on SSE4.1: 4 float lanes, masks are all-ones lanes.
 * SSE4.1 has no FMA, so vf_fma rounds twice, as in the scalar kernel. */
#ifndef HB_SIMD_SSE41_H
#define HB_SIMD_SSE41_H

#include <smmintrin.h>
#include <stdint.h>

#include "simd_x86.h"

#define HB_W 4
#define HB_ISA_LABEL "sse4.1"

typedef __m128 vf;
typedef __m128i vi;
typedef __m128 vm;
#define HB_PD_T __m128d
#define HB_PD_ADD _mm_add_pd
#define HB_PD_SUB _mm_sub_pd
#define HB_PD_MUL _mm_mul_pd
#define HB_PD_DIV _mm_div_pd
#define HB_PD_SQRT _mm_sqrt_pd
#define HB_PD_MIN _mm_min_pd
#define HB_PD_MAX _mm_max_pd
#define HB_PD_FMA(a, b, c) _mm_add_pd(_mm_mul_pd(a, b), c)
#define HB_PD_ROUND(a) _mm_round_pd(a, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)
#define HB_PD_SET1 _mm_set1_pd
#include "simd_vdw_pair.h"

HB_INLINE vf vf_set1(float a) { return _mm_set1_ps(a); }
HB_INLINE vf vf_loadu(const float *p) { return _mm_loadu_ps(p); }
HB_INLINE void vf_storeu(float *p, vf a) { _mm_storeu_ps(p, a); }
HB_INLINE vf vf_add(vf a, vf b) { return _mm_add_ps(a, b); }
HB_INLINE vf vf_sub(vf a, vf b) { return _mm_sub_ps(a, b); }
HB_INLINE vf vf_mul(vf a, vf b) { return _mm_mul_ps(a, b); }
HB_INLINE vf vf_div(vf a, vf b) { return _mm_div_ps(a, b); }
HB_INLINE vf vf_fma(vf a, vf b, vf c) { return _mm_add_ps(_mm_mul_ps(a, b), c); }
HB_INLINE vf vf_fnma(vf a, vf b, vf c) { return _mm_sub_ps(c, _mm_mul_ps(a, b)); }
HB_INLINE vf vf_min(vf a, vf b) { return _mm_min_ps(a, b); }
HB_INLINE vf vf_max(vf a, vf b) { return _mm_max_ps(a, b); }
HB_INLINE vf vf_sqrt(vf a) { return _mm_sqrt_ps(a); }
HB_INLINE vf vf_select(vm m, vf a, vf b) { return _mm_blendv_ps(b, a, m); }
HB_INLINE vf vf_keep(vm m, vf a) { return _mm_and_ps(a, m); }
HB_INLINE vf vf_round(vf a) { return _mm_round_ps(a, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC); }

HB_INLINE vm vf_lt(vf a, vf b) { return _mm_cmplt_ps(a, b); }
HB_INLINE vm vf_le(vf a, vf b) { return _mm_cmple_ps(a, b); }
HB_INLINE vm vf_gt(vf a, vf b) { return _mm_cmpgt_ps(a, b); }
HB_INLINE vm vf_ge(vf a, vf b) { return _mm_cmpge_ps(a, b); }
HB_INLINE vm vf_eq(vf a, vf b) { return _mm_cmpeq_ps(a, b); }

HB_INLINE vm vm_and(vm a, vm b) { return _mm_and_ps(a, b); }
HB_INLINE vm vm_or(vm a, vm b) { return _mm_or_ps(a, b); }
HB_INLINE vm vm_andnot(vm a, vm b) { return _mm_andnot_ps(b, a); }
HB_INLINE vm vm_not(vm a) { return _mm_xor_ps(a, _mm_castsi128_ps(_mm_set1_epi32(-1))); }
HB_INLINE unsigned vm_bits(vm a) { return (unsigned)_mm_movemask_ps(a); }
HB_INLINE float vf_sum_lanes(vf a) { return HB_SUM4_PS(a); }

HB_INLINE vi vf_as_vi(vf a) { return _mm_castps_si128(a); }
HB_INLINE vf vi_as_vf(vi a) { return _mm_castsi128_ps(a); }
HB_INLINE vi vi_set1(int32_t a) { return _mm_set1_epi32(a); }
HB_INLINE vi vi_add(vi a, vi b) { return _mm_add_epi32(a, b); }
HB_INLINE vi vi_sub(vi a, vi b) { return _mm_sub_epi32(a, b); }
HB_INLINE vi vi_and(vi a, vi b) { return _mm_and_si128(a, b); }
HB_INLINE vi vi_or(vi a, vi b) { return _mm_or_si128(a, b); }
HB_INLINE vi vi_xor(vi a, vi b) { return _mm_xor_si128(a, b); }
HB_INLINE vi vi_mul(vi a, vi b) { return _mm_mullo_epi32(a, b); } /* low 32 bits */
HB_INLINE vi vi_shl(vi a, int n) { return _mm_slli_epi32(a, n); }
HB_INLINE vi vi_shr(vi a, int n) { return _mm_srli_epi32(a, n); }
HB_INLINE vm vi_eq(vi a, vi b) { return _mm_castsi128_ps(_mm_cmpeq_epi32(a, b)); }
HB_INLINE vi vi_from_vf(vf a) { return _mm_cvttps_epi32(a); }
HB_INLINE vf vf_from_vi(vi a) { return _mm_cvtepi32_ps(a); }
HB_INLINE vf vf_gather(const float *base, vi idx)
{
    int32_t i[4];
    _mm_storeu_si128((__m128i *)i, idx);
    return _mm_setr_ps(base[i[0]], base[i[1]], base[i[2]], base[i[3]]);
}
/* out[j], lane l = base[idx_l + j], j < 4: four loads and a 4 x 4 transpose (simd.h). */
HB_INLINE void vf_gather4(const float *base, vi idx, vf out[4])
{
    int32_t i[4];
    _mm_storeu_si128((__m128i *)i, idx);
    HB_TRANSPOSE4_IN_LANES(__m128, _mm, _mm_loadu_ps(base + i[0]), _mm_loadu_ps(base + i[1]), _mm_loadu_ps(base + i[2]),
                           _mm_loadu_ps(base + i[3]), out[0], out[1], out[2], out[3]);
}

HB_INLINE vdw vdw_from_vf(vf a)
{
    vdw r = { _mm_cvtps_pd(a), _mm_cvtps_pd(_mm_movehl_ps(a, a)) };
    return r;
}
HB_INLINE vf vdw_to_vf(vdw a) { return _mm_movelh_ps(_mm_cvtpd_ps(a.lo), _mm_cvtpd_ps(a.hi)); }
#endif

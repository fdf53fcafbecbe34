/* The SIMD vocabulary on AVX2 + FMA: 16 float lanes held as two 8-lane registers, every
 * operation issued once per half. The kernels are long dependency chains (polynomials,
 * divisions, square roots) that leave most of the pipelines idle on one register; the second
 * half is an independent chain in the same instruction stream, so it fills them (the way
 * AVX-512's 16 lanes do on a core that executes them as two 256-bit halves). Lane by lane the
 * operations are the 8-lane ones, so results are unchanged. Masks are all-ones float lanes. */
#ifndef HB_SIMD_AVX2_H
#define HB_SIMD_AVX2_H

#include <immintrin.h>
#include <stdint.h>

#include "simd_x86.h"

#define HB_W 16
#define HB_ISA_LABEL "avx2"

typedef struct { __m256 lo, hi; } vf;
typedef struct { __m256i lo, hi; } vi;
typedef vf vm;

#define HB_ROUND_NEAREST (_MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)

/* One intrinsic applied to both halves: unary, binary and ternary forms. */
#define HB_HALVES1(T, name, op, A) \
    HB_INLINE T name(A a) { T r = { op(a.lo), op(a.hi) }; return r; }
#define HB_HALVES2(T, name, op, A) \
    HB_INLINE T name(A a, A b) { T r = { op(a.lo, b.lo), op(a.hi, b.hi) }; return r; }
#define HB_HALVES3(T, name, op) \
    HB_INLINE T name(T a, T b, T c) { T r = { op(a.lo, b.lo, c.lo), op(a.hi, b.hi, c.hi) }; return r; }

HB_INLINE vf vf_set1(float a) { vf r = { _mm256_set1_ps(a), _mm256_set1_ps(a) }; return r; }
HB_INLINE vf vf_loadu(const float *p) { vf r = { _mm256_loadu_ps(p), _mm256_loadu_ps(p + 8) }; return r; }
HB_INLINE void vf_storeu(float *p, vf a) { _mm256_storeu_ps(p, a.lo); _mm256_storeu_ps(p + 8, a.hi); }
/* The one-register forms (simd.h): the lower register alone, the upper a copy of it, so that its
 * work is the lower's or dead. */
#define HB_REG_W 8
HB_INLINE vf vf_load_reg(const float *p) { vf r = { _mm256_loadu_ps(p), _mm256_loadu_ps(p) }; return r; }
HB_HALVES2(vf, vf_add, _mm256_add_ps, vf)
HB_HALVES2(vf, vf_sub, _mm256_sub_ps, vf)
HB_HALVES2(vf, vf_mul, _mm256_mul_ps, vf)
HB_HALVES2(vf, vf_div, _mm256_div_ps, vf)
HB_HALVES3(vf, vf_fma, _mm256_fmadd_ps)
HB_HALVES3(vf, vf_fnma, _mm256_fnmadd_ps)
HB_HALVES2(vf, vf_min, _mm256_min_ps, vf)
HB_HALVES2(vf, vf_max, _mm256_max_ps, vf)
HB_HALVES1(vf, vf_sqrt, _mm256_sqrt_ps, vf)
HB_INLINE vf vf_select(vm m, vf a, vf b)
{
    vf r = { _mm256_blendv_ps(b.lo, a.lo, m.lo), _mm256_blendv_ps(b.hi, a.hi, m.hi) };
    return r;
}
HB_HALVES2(vf, vf_keep, _mm256_and_ps, vf)
#define HB_ROUND_HALF(a) _mm256_round_ps(a, HB_ROUND_NEAREST)
HB_HALVES1(vf, vf_round, HB_ROUND_HALF, vf)

#define HB_CMP_LT(a, b) _mm256_cmp_ps(a, b, _CMP_LT_OQ)
#define HB_CMP_LE(a, b) _mm256_cmp_ps(a, b, _CMP_LE_OQ)
#define HB_CMP_GT(a, b) _mm256_cmp_ps(a, b, _CMP_GT_OQ)
#define HB_CMP_GE(a, b) _mm256_cmp_ps(a, b, _CMP_GE_OQ)
#define HB_CMP_EQ(a, b) _mm256_cmp_ps(a, b, _CMP_EQ_OQ)
HB_HALVES2(vm, vf_lt, HB_CMP_LT, vf)
HB_HALVES2(vm, vf_le, HB_CMP_LE, vf)
HB_HALVES2(vm, vf_gt, HB_CMP_GT, vf)
HB_HALVES2(vm, vf_ge, HB_CMP_GE, vf)
HB_HALVES2(vm, vf_eq, HB_CMP_EQ, vf)

HB_HALVES2(vm, vm_and, _mm256_and_ps, vm)
HB_HALVES2(vm, vm_or, _mm256_or_ps, vm)
#define HB_ANDNOT(a, b) _mm256_andnot_ps(b, a)
HB_HALVES2(vm, vm_andnot, HB_ANDNOT, vm)
#define HB_NOT(a) _mm256_xor_ps(a, _mm256_castsi256_ps(_mm256_set1_epi32(-1)))
HB_HALVES1(vm, vm_not, HB_NOT, vm)
HB_INLINE unsigned vm_bits(vm a)
{
    return (unsigned)_mm256_movemask_ps(a.lo) | (unsigned)_mm256_movemask_ps(a.hi) << 8;
}
HB_INLINE float vf_sum_8(__m256 s)
{
    __m128 q = _mm_add_ps(_mm256_castps256_ps128(s), _mm256_extractf128_ps(s, 1));
    return HB_SUM4_PS(q);
}
HB_INLINE float vf_sum_lanes(vf a) { return vf_sum_8(_mm256_add_ps(a.lo, a.hi)); }
HB_INLINE float vf_sum_reg(vf a) { return vf_sum_8(a.lo); }

HB_HALVES1(vi, vf_as_vi, _mm256_castps_si256, vf)
HB_HALVES1(vf, vi_as_vf, _mm256_castsi256_ps, vi)
HB_INLINE vi vi_set1(int32_t a) { vi r = { _mm256_set1_epi32(a), _mm256_set1_epi32(a) }; return r; }
HB_HALVES2(vi, vi_add, _mm256_add_epi32, vi)
HB_HALVES2(vi, vi_sub, _mm256_sub_epi32, vi)
HB_HALVES2(vi, vi_and, _mm256_and_si256, vi)
HB_HALVES2(vi, vi_or, _mm256_or_si256, vi)
HB_HALVES2(vi, vi_xor, _mm256_xor_si256, vi)
HB_HALVES2(vi, vi_mul, _mm256_mullo_epi32, vi) /* low 32 bits */
HB_INLINE vi vi_shl(vi a, int n) { vi r = { _mm256_slli_epi32(a.lo, n), _mm256_slli_epi32(a.hi, n) }; return r; }
HB_INLINE vi vi_shr(vi a, int n) { vi r = { _mm256_srli_epi32(a.lo, n), _mm256_srli_epi32(a.hi, n) }; return r; }
HB_INLINE vm vi_eq(vi a, vi b)
{
    vm r = { _mm256_castsi256_ps(_mm256_cmpeq_epi32(a.lo, b.lo)), _mm256_castsi256_ps(_mm256_cmpeq_epi32(a.hi, b.hi)) };
    return r;
}
HB_HALVES1(vi, vi_from_vf, _mm256_cvttps_epi32, vf)
HB_HALVES1(vf, vf_from_vi, _mm256_cvtepi32_ps, vi)
HB_INLINE vf vf_gather(const float *base, vi idx)
{
    vf r = { _mm256_i32gather_ps(base, idx.lo, 4), _mm256_i32gather_ps(base, idx.hi, 4) };
    return r;
}
/* out[j], lane l = base[idx_l + j], j < 4: 128-bit loads and in-lane transposes, no gather (simd.h).
 * In each half, lanes k and k + 4 share a register's two 128-bit lanes. */
HB_INLINE void vf_gather4(const float *base, vi idx, vf out[4])
{
    int32_t i[16];
    _mm256_storeu_si256((__m256i *)i, idx.lo);
    _mm256_storeu_si256((__m256i *)(i + 8), idx.hi);
#define HB_LANE_PAIR(k) _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(base + i[k])), _mm_loadu_ps(base + i[k + 4]), 1)
    HB_TRANSPOSE4_IN_LANES(__m256, _mm256, HB_LANE_PAIR(0), HB_LANE_PAIR(1), HB_LANE_PAIR(2), HB_LANE_PAIR(3), out[0].lo,
                           out[1].lo, out[2].lo, out[3].lo);
    HB_TRANSPOSE4_IN_LANES(__m256, _mm256, HB_LANE_PAIR(8), HB_LANE_PAIR(9), HB_LANE_PAIR(10), HB_LANE_PAIR(11), out[0].hi,
                           out[1].hi, out[2].hi, out[3].hi);
#undef HB_LANE_PAIR
}

/* Doubles: each float half widens to two __m256d, so vdw is a pair of such pairs. */
typedef struct { __m256d lo, hi; } hb_pd_pair;
HB_HALVES2(hb_pd_pair, hb_pd_pair_add, _mm256_add_pd, hb_pd_pair)
HB_HALVES2(hb_pd_pair, hb_pd_pair_sub, _mm256_sub_pd, hb_pd_pair)
HB_HALVES2(hb_pd_pair, hb_pd_pair_mul, _mm256_mul_pd, hb_pd_pair)
HB_HALVES2(hb_pd_pair, hb_pd_pair_div, _mm256_div_pd, hb_pd_pair)
HB_HALVES2(hb_pd_pair, hb_pd_pair_min, _mm256_min_pd, hb_pd_pair)
HB_HALVES2(hb_pd_pair, hb_pd_pair_max, _mm256_max_pd, hb_pd_pair)
HB_HALVES3(hb_pd_pair, hb_pd_pair_fma, _mm256_fmadd_pd)
HB_HALVES1(hb_pd_pair, hb_pd_pair_sqrt, _mm256_sqrt_pd, hb_pd_pair)
#define HB_ROUND_PD_HALF(a) _mm256_round_pd(a, HB_ROUND_NEAREST)
HB_HALVES1(hb_pd_pair, hb_pd_pair_round, HB_ROUND_PD_HALF, hb_pd_pair)
HB_INLINE hb_pd_pair hb_pd_pair_set1(double a) { hb_pd_pair r = { _mm256_set1_pd(a), _mm256_set1_pd(a) }; return r; }

#define HB_PD_T hb_pd_pair
#define HB_PD_ADD hb_pd_pair_add
#define HB_PD_SUB hb_pd_pair_sub
#define HB_PD_MUL hb_pd_pair_mul
#define HB_PD_DIV hb_pd_pair_div
#define HB_PD_SQRT hb_pd_pair_sqrt
#define HB_PD_MIN hb_pd_pair_min
#define HB_PD_MAX hb_pd_pair_max
#define HB_PD_FMA hb_pd_pair_fma
#define HB_PD_ROUND hb_pd_pair_round
#define HB_PD_SET1 hb_pd_pair_set1
#include "simd_vdw_pair.h"

HB_INLINE hb_pd_pair hb_pd_pair_from_ps(__m256 a)
{
    hb_pd_pair r = { _mm256_cvtps_pd(_mm256_castps256_ps128(a)), _mm256_cvtps_pd(_mm256_extractf128_ps(a, 1)) };
    return r;
}
HB_INLINE __m256 hb_pd_pair_to_ps(hb_pd_pair a)
{
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm256_cvtpd_ps(a.lo)), _mm256_cvtpd_ps(a.hi), 1);
}
HB_INLINE vdw vdw_from_vf(vf a)
{
    vdw r = { hb_pd_pair_from_ps(a.lo), hb_pd_pair_from_ps(a.hi) };
    return r;
}
HB_INLINE vf vdw_to_vf(vdw a)
{
    vf r = { hb_pd_pair_to_ps(a.lo), hb_pd_pair_to_ps(a.hi) };
    return r;
}

#endif

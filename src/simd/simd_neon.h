/* The SIMD vocabulary on AArch64 NEON: 4 float lanes, masks are all-ones lanes. */
#ifndef HB_SIMD_NEON_H
#define HB_SIMD_NEON_H

#include <arm_neon.h>
#include <stdint.h>

#define HB_W 4
#define HB_ISA_LABEL "neon"

typedef float32x4_t vf;
typedef int32x4_t vi;
typedef uint32x4_t vm;

HB_INLINE vf vf_set1(float a) { return vdupq_n_f32(a); }
HB_INLINE vf vf_loadu(const float *p) { return vld1q_f32(p); }
HB_INLINE void vf_storeu(float *p, vf a) { vst1q_f32(p, a); }
HB_INLINE vf vf_add(vf a, vf b) { return vaddq_f32(a, b); }
HB_INLINE vf vf_sub(vf a, vf b) { return vsubq_f32(a, b); }
HB_INLINE vf vf_mul(vf a, vf b) { return vmulq_f32(a, b); }
HB_INLINE vf vf_div(vf a, vf b) { return vdivq_f32(a, b); }
HB_INLINE vf vf_fma(vf a, vf b, vf c) { return vfmaq_f32(c, a, b); }
HB_INLINE vf vf_fnma(vf a, vf b, vf c) { return vfmsq_f32(c, a, b); }
HB_INLINE vf vf_min(vf a, vf b) { return vminq_f32(a, b); }
HB_INLINE vf vf_max(vf a, vf b) { return vmaxq_f32(a, b); }
HB_INLINE vf vf_sqrt(vf a) { return vsqrtq_f32(a); }
HB_INLINE vf vf_select(vm m, vf a, vf b) { return vbslq_f32(m, a, b); }
HB_INLINE vf vf_keep(vm m, vf a) { return vreinterpretq_f32_u32(vandq_u32(vreinterpretq_u32_f32(a), m)); }
HB_INLINE vf vf_round(vf a) { return vrndnq_f32(a); }

HB_INLINE vm vf_lt(vf a, vf b) { return vcltq_f32(a, b); }
HB_INLINE vm vf_le(vf a, vf b) { return vcleq_f32(a, b); }
HB_INLINE vm vf_gt(vf a, vf b) { return vcgtq_f32(a, b); }
HB_INLINE vm vf_ge(vf a, vf b) { return vcgeq_f32(a, b); }
HB_INLINE vm vf_eq(vf a, vf b) { return vceqq_f32(a, b); }

HB_INLINE vm vm_and(vm a, vm b) { return vandq_u32(a, b); }
HB_INLINE vm vm_or(vm a, vm b) { return vorrq_u32(a, b); }
HB_INLINE vm vm_andnot(vm a, vm b) { return vbicq_u32(a, b); }
HB_INLINE vm vm_not(vm a) { return vmvnq_u32(a); }
HB_INLINE float vf_sum_lanes(vf a) { return vaddvq_f32(a); }
HB_INLINE unsigned vm_bits(vm a)
{
    const uint32_t lane_bit[4] = { 1, 2, 4, 8 };
    return vaddvq_u32(vandq_u32(a, vld1q_u32(lane_bit)));
}

HB_INLINE vi vf_as_vi(vf a) { return vreinterpretq_s32_f32(a); }
HB_INLINE vf vi_as_vf(vi a) { return vreinterpretq_f32_s32(a); }
HB_INLINE vi vi_set1(int32_t a) { return vdupq_n_s32(a); }
HB_INLINE vi vi_add(vi a, vi b) { return vaddq_s32(a, b); }
HB_INLINE vi vi_sub(vi a, vi b) { return vsubq_s32(a, b); }
HB_INLINE vi vi_and(vi a, vi b) { return vandq_s32(a, b); }
HB_INLINE vi vi_or(vi a, vi b) { return vorrq_s32(a, b); }
HB_INLINE vi vi_xor(vi a, vi b) { return veorq_s32(a, b); }
HB_INLINE vi vi_mul(vi a, vi b) { return vmulq_s32(a, b); } /* low 32 bits */
HB_INLINE vi vi_shl(vi a, int n) { return vshlq_s32(a, vdupq_n_s32(n)); }
HB_INLINE vi vi_shr(vi a, int n)
{
    return vreinterpretq_s32_u32(vshlq_u32(vreinterpretq_u32_s32(a), vdupq_n_s32(-n)));
}
HB_INLINE vm vi_eq(vi a, vi b) { return vceqq_s32(a, b); }
HB_INLINE vi vi_from_vf(vf a) { return vcvtq_s32_f32(a); }
HB_INLINE vf vf_from_vi(vi a) { return vcvtq_f32_s32(a); }
HB_INLINE vf vf_gather(const float *base, vi idx)
{
    int32_t i[4];
    vst1q_s32(i, idx);
    const float g[4] = { base[i[0]], base[i[1]], base[i[2]], base[i[3]] };
    return vld1q_f32(g);
}
/* out[j], lane l = base[idx_l + j], j < 4: four loads and a 4 x 4 transpose (simd.h). */
HB_INLINE void vf_gather4(const float *base, vi idx, vf out[4])
{
    int32_t i[4];
    vst1q_s32(i, idx);
    float32x4_t a0 = vld1q_f32(base + i[0]), a1 = vld1q_f32(base + i[1]);
    float32x4_t a2 = vld1q_f32(base + i[2]), a3 = vld1q_f32(base + i[3]);
    float32x4_t t0 = vtrn1q_f32(a0, a1), t1 = vtrn2q_f32(a0, a1), t2 = vtrn1q_f32(a2, a3), t3 = vtrn2q_f32(a2, a3);
    out[0] = vreinterpretq_f32_f64(vtrn1q_f64(vreinterpretq_f64_f32(t0), vreinterpretq_f64_f32(t2)));
    out[1] = vreinterpretq_f32_f64(vtrn1q_f64(vreinterpretq_f64_f32(t1), vreinterpretq_f64_f32(t3)));
    out[2] = vreinterpretq_f32_f64(vtrn2q_f64(vreinterpretq_f64_f32(t0), vreinterpretq_f64_f32(t2)));
    out[3] = vreinterpretq_f32_f64(vtrn2q_f64(vreinterpretq_f64_f32(t1), vreinterpretq_f64_f32(t3)));
}

#define HB_PD_T float64x2_t
#define HB_PD_ADD vaddq_f64
#define HB_PD_SUB vsubq_f64
#define HB_PD_MUL vmulq_f64
#define HB_PD_DIV vdivq_f64
#define HB_PD_SQRT vsqrtq_f64
#define HB_PD_MIN vminq_f64
#define HB_PD_MAX vmaxq_f64
#define HB_PD_FMA(a, b, c) vfmaq_f64(c, a, b)
#define HB_PD_ROUND vrndnq_f64
#define HB_PD_SET1 vdupq_n_f64
#include "simd_vdw_pair.h"

HB_INLINE vdw vdw_from_vf(vf a)
{
    vdw r = { vcvt_f64_f32(vget_low_f32(a)), vcvt_high_f64_f32(a) };
    return r;
}
HB_INLINE vf vdw_to_vf(vdw a) { return vcvt_high_f32_f64(vcvt_f32_f64(a.lo), a.hi); }

#endif

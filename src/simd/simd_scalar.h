/* The SIMD vocabulary at width 1: the scalar kernel is the SIMD kernel with W = 1.
 * Only baseline instructions are used (no FMA, no SSE4.1 rounding), so vf_fma
 * rounds twice here; tests state the tolerance this costs. */
#ifndef HB_SIMD_SCALAR_H
#define HB_SIMD_SCALAR_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define HB_W 1
#define HB_ISA_LABEL "scalar"

typedef float vf;
typedef int32_t vi;
typedef uint32_t vm; /* 0 or 1 */
typedef double vdw; /* W doubles */

HB_INLINE vf vf_set1(float a) { return a; }
HB_INLINE vf vf_loadu(const float *p) { return *p; }
HB_INLINE void vf_storeu(float *p, vf a) { *p = a; }
HB_INLINE vf vf_add(vf a, vf b) { return a + b; }
HB_INLINE vf vf_sub(vf a, vf b) { return a - b; }
HB_INLINE vf vf_mul(vf a, vf b) { return a * b; }
HB_INLINE vf vf_div(vf a, vf b) { return a / b; }
HB_INLINE vf vf_fma(vf a, vf b, vf c) { return a * b + c; }
HB_INLINE vf vf_fnma(vf a, vf b, vf c) { return c - a * b; }
HB_INLINE vf vf_min(vf a, vf b) { return a < b ? a : b; }
HB_INLINE vf vf_max(vf a, vf b) { return a > b ? a : b; }
HB_INLINE vf vf_sqrt(vf a) { return sqrtf(a); }
HB_INLINE vf vf_select(vm m, vf a, vf b) { return m ? a : b; }
HB_INLINE vf vf_keep(vm m, vf a) { return m ? a : 0.0f; }

HB_INLINE vm vf_lt(vf a, vf b) { return a < b; }
HB_INLINE vm vf_le(vf a, vf b) { return a <= b; }
HB_INLINE vm vf_gt(vf a, vf b) { return a > b; }
HB_INLINE vm vf_ge(vf a, vf b) { return a >= b; }
HB_INLINE vm vf_eq(vf a, vf b) { return a == b; }

HB_INLINE vm vm_and(vm a, vm b) { return a & b; }
HB_INLINE vm vm_or(vm a, vm b) { return a | b; }
HB_INLINE vm vm_andnot(vm a, vm b) { return a & (b ^ 1u); }
HB_INLINE vm vm_not(vm a) { return a ^ 1u; }
HB_INLINE unsigned vm_bits(vm a) { return a; }
HB_INLINE float vf_sum_lanes(vf a) { return a; }

HB_INLINE vi vf_as_vi(vf a) { vi r; memcpy(&r, &a, sizeof r); return r; }
HB_INLINE vf vi_as_vf(vi a) { vf r; memcpy(&r, &a, sizeof r); return r; }
HB_INLINE vi vi_set1(int32_t a) { return a; }
HB_INLINE vi vi_add(vi a, vi b) { return (vi)((uint32_t)a + (uint32_t)b); }
HB_INLINE vi vi_sub(vi a, vi b) { return (vi)((uint32_t)a - (uint32_t)b); }
HB_INLINE vi vi_and(vi a, vi b) { return a & b; }
HB_INLINE vi vi_or(vi a, vi b) { return a | b; }
HB_INLINE vi vi_xor(vi a, vi b) { return a ^ b; }
HB_INLINE vi vi_mul(vi a, vi b) { return (vi)((uint32_t)a * (uint32_t)b); } /* low 32 bits */
HB_INLINE vi vi_shl(vi a, int n) { return (vi)((uint32_t)a << n); }
HB_INLINE vi vi_shr(vi a, int n) { return (vi)((uint32_t)a >> n); }
HB_INLINE vm vi_eq(vi a, vi b) { return a == b; }
/* a must already be integral and within int32 range. */
HB_INLINE vi vi_from_vf(vf a) { return (vi)a; }
HB_INLINE vf vf_from_vi(vi a) { return (vf)a; }
HB_INLINE vf vf_gather(const float *base, vi idx) { return base[idx]; }
/* out[j] = base[idx + j], j < 4: four consecutive floats per lane as four vectors (simd.h). */
HB_INLINE void vf_gather4(const float *base, vi idx, vf out[4])
{
    out[0] = base[idx], out[1] = base[idx + 1], out[2] = base[idx + 2], out[3] = base[idx + 3];
}

/* Round to nearest even without SSE4.1 or libm: adding 1.5 * 2^23 pushes the
 * fraction out of the mantissa. |a| >= 2^22 is already integral. */
HB_INLINE vf vf_round(vf a)
{
    const float magic = 12582912.0f;
    float r = (a + magic) - magic; /* not folded: we never build with -ffast-math */
    return (a > 4194304.0f || a < -4194304.0f) ? a : r;
}

HB_INLINE vdw vdw_from_vf(vf a) { return (double)a; }
HB_INLINE vf vdw_to_vf(vdw a) { return (float)a; }
HB_INLINE vdw vdw_set1(double a) { return a; }
HB_INLINE vdw vdw_add(vdw a, vdw b) { return a + b; }
HB_INLINE vdw vdw_sub(vdw a, vdw b) { return a - b; }
HB_INLINE vdw vdw_mul(vdw a, vdw b) { return a * b; }
HB_INLINE vdw vdw_div(vdw a, vdw b) { return a / b; }
HB_INLINE vdw vdw_sqrt(vdw a) { return sqrt(a); }
HB_INLINE vdw vdw_fma(vdw a, vdw b, vdw c) { return a * b + c; }
HB_INLINE vdw vdw_min(vdw a, vdw b) { return a < b ? a : b; }
HB_INLINE vdw vdw_max(vdw a, vdw b) { return a > b ? a : b; }
HB_INLINE vdw vdw_round(vdw a)
{
    const double magic = 6755399441055744.0; /* 1.5 * 2^52 */
    double r = (a + magic) - magic;
    return (a > 2251799813685248.0 || a < -2251799813685248.0) ? a : r;
}

#endif

/* The SIMD vocabulary: the seam between the kernels and the instruction sets. This header picks
 * the vocabulary of the ISA this translation unit is compiled for (HB_TARGET_SCALAR, _SSE41, _AVX2,
 * _AVX512 or _NEON, set by the Makefile per src/kernel/isas.h's list) and adds the few operations
 * every ISA derives the same way. The contract every simd_<isa>.h meets:
 *
 * Types and width. HB_W float lanes: scalar 1, SSE4.1 4, AVX2 16 (two 8-lane halves), AVX-512 16,
 * NEON 4 (see each header). vf: HB_W floats; vi: HB_W 32-bit integers; vm: a lane mask (all bits
 * or a bit per lane, opaque to the kernels); vdw: HB_W doubles, for the few steps that need them.
 * HB_ISA_LABEL names the ISA.
 *
 * Every operation works lane by lane, with IEEE single-precision rounding to nearest per step:
 *   vf_set1, vf_loadu, vf_storeu (unaligned, HB_W floats); vf_add, vf_sub, vf_mul, vf_div (correctly
 *   rounded), vf_sqrt (correctly rounded); vf_min, vf_max (a lane with a NaN operand takes either
 *   one: kernels never feed them NaN); vf_fma(a, b, c) = a b + c and vf_fnma(a, b, c) = c - a b,
 *   fused (one rounding) on AVX2, AVX-512 and NEON, two roundings on scalar and SSE4.1;
 *   vf_round (to nearest, ties to even), vf_select(m, a, b) (a where m), vf_keep(m, a) (a where m,
 *   else +0); comparisons vf_lt, vf_le, vf_gt, vf_ge, vf_eq (ordered: false for NaN);
 *   vm_and, vm_or, vm_andnot(a, b) = a and not b, vm_not, vm_bits (bit k: lane k); vf_sum_lanes (the
 *   lanes' sum as one float, added pairwise in a tree of the ISA's order: for one-sample paths);
 *   vf_as_vi, vi_as_vf (bit casts); vi_set1, vi_add, vi_sub, vi_mul (low 32 bits), vi_and, vi_or,
 *   vi_xor, vi_shl, vi_shr (logical), vi_eq; vi_from_vf (the float must be integral and in int32
 *   range), vf_from_vi; vf_gather(base, idx) (one float per lane), vf_gather4 (four consecutive
 *   floats per lane, see below);
 *   vdw_from_vf, vdw_to_vf (rounded to nearest), vdw_set1, vdw_add, vdw_sub, vdw_mul, vdw_div,
 *   vdw_sqrt, vdw_min, vdw_max, vdw_fma (fused where vf_fma is), vdw_round.
 * Derived here for every ISA: vf_abs, vf_neg, vf_copysign, vf_floor, vf_rcp (a division),
 * vf_clamp, vf_lane_index, vf_store_first, vf_sum_first; the one-register forms HB_REG_W, vf_load_reg, vf_sum_reg (AVX2 defines
 * its own); the subnormal mode (hb_flush_subnormals, hb_fp_restore). */
#ifndef HB_SIMD_H
#define HB_SIMD_H

#include "compiler.h"

/* Everything in the vocabulary and the math built on it is forced inline: a kernel
 * is one straight-line body per vector of samples, never a call per operation. Sanitizer builds
 * (HB_SANITIZED) leave inlining to the compiler: the same operations in smaller functions, which
 * the instrumented compile (ASan's passes grow with a function's size) needs to finish in minutes. */
#ifdef HB_SANITIZED
#define HB_INLINE static inline
#else
#define HB_INLINE static HB_ALWAYS_INLINE
#endif
/* A stage that several kernels of one translation unit share (f from the geometry and M_p, the
 * internal paths of a fibre): one out-of-line copy per unit instead of one inlined into every
 * kernel and I0 variant, which is what bounds each unit's compile time and memory. Its vectors
 * cross the call through memory: a few loads and stores per block against hundreds of operations. */
#define HB_STAGE static HB_NOINLINE
/* Unrolls the loop that follows (over lobes, channels, streams) so its arrays of vectors can live
 * in registers; GCC at -O2 keeps a loop with a large body rolled. Clang reads the same pragma.
 * Sanitizer builds (HB_SANITIZED) drop the hint: GCC cannot unroll some instrumented loops and
 * warns that it ignores the annotation. */
#ifdef HB_SANITIZED
#define HB_UNROLL
#else
#define HB_UNROLL HB_PRAGMA_UNROLL
#endif

/* Besides element-wise arithmetic, each vocabulary loads table texels two ways: vf_gather(base, idx),
 * one float per lane, and vf_gather4(base, idx, out), four consecutive floats per lane as four
 * vectors (lane l of out[j] is base[idx_l + j]), by plain loads and a transpose: a texel's values
 * sit side by side, and one gather instruction per value costs far more than its share of a load. */
#if defined(HB_TARGET_SCALAR)
#include "simd_scalar.h"
#elif defined(HB_TARGET_SSE41)
#include "simd_sse41.h"
#elif defined(HB_TARGET_AVX2)
#include "simd_avx2.h"
#elif defined(HB_TARGET_AVX512)
#include "simd_avx512.h"
#elif defined(HB_TARGET_NEON)
#include "simd_neon.h"
#else
#error "define one of HB_TARGET_SCALAR, _SSE41, _AVX2, _AVX512, _NEON"
#endif

/* Batch kernels run with subnormal floats flushed to zero, inputs and results (x86 MXCSR FTZ and
 * DAZ, AArch64 FPCR.FZ), and restore the caller's mode on return: a product that underflows, such as
 * a far-off lobe's M_p times a detector's tail, would otherwise cost a microcode assist each time
 * on x86 (3x the dFH11 kernel's time on the bench's directions). Values below FLT_MIN become 0. */
#if defined(HB_ARCH_X86)
#include <xmmintrin.h>
typedef unsigned hb_fp_mode;
HB_INLINE hb_fp_mode hb_flush_subnormals(void)
{
    hb_fp_mode mode = _mm_getcsr();
    _mm_setcsr(mode | 0x8040u); /* FTZ (bit 15), DAZ (bit 6) */
    return mode;
}
HB_INLINE void hb_fp_restore(hb_fp_mode mode) { _mm_setcsr(mode); }
#elif defined(HB_ARCH_ARM64) && !defined(_MSC_VER)
typedef uint64_t hb_fp_mode;
HB_INLINE hb_fp_mode hb_flush_subnormals(void)
{
    hb_fp_mode mode;
    __asm__ volatile("mrs %0, fpcr" : "=r"(mode));
    __asm__ volatile("msr fpcr, %0" : : "r"(mode | (1ull << 24))); /* FZ */
    return mode;
}
HB_INLINE void hb_fp_restore(hb_fp_mode mode) { __asm__ volatile("msr fpcr, %0" : : "r"(mode)); }
#else
typedef int hb_fp_mode;
HB_INLINE hb_fp_mode hb_flush_subnormals(void) { return 0; }
HB_INLINE void hb_fp_restore(hb_fp_mode mode) { (void)mode; }
#endif

#define HB_SIGN_BIT ((int32_t)0x80000000)

HB_INLINE vf vf_abs(vf a) { return vi_as_vf(vi_and(vf_as_vi(a), vi_set1(0x7fffffff))); }
HB_INLINE vf vf_neg(vf a) { return vi_as_vf(vi_xor(vf_as_vi(a), vi_set1(HB_SIGN_BIT))); }
/* |a| with the sign of s */
HB_INLINE vf vf_copysign(vf a, vf s)
{
    return vi_as_vf(vi_or(vf_as_vi(vf_abs(a)), vi_and(vf_as_vi(s), vi_set1(HB_SIGN_BIT))));
}
HB_INLINE vf vf_floor(vf a)
{
    vf r = vf_round(a);
    return vf_select(vf_gt(r, a), vf_sub(r, vf_set1(1.0f)), r);
}
/* Exact reciprocal (a division): the kernels need it correctly rounded. */
HB_INLINE vf vf_rcp(vf a) { return vf_div(vf_set1(1.0f), a); }
HB_INLINE vf vf_clamp(vf a, float lo, float hi) { return vf_min(vf_max(a, vf_set1(lo)), vf_set1(hi)); }

/* One-register forms, for the one-sample paths whose work fits the lanes of one hardware register
 * (HB_REG_W of them): vf_load_reg(p) loads HB_REG_W floats into the first lanes and vf_sum_reg(a)
 * sums those lanes. On every ISA but AVX2 (two registers, the upper a copy of the lower and its
 * work dead) they are vf_loadu and vf_sum_lanes. */
#ifndef HB_REG_W
#define HB_REG_W HB_W
HB_INLINE vf vf_load_reg(const float *p) { return vf_loadu(p); }
HB_INLINE float vf_sum_reg(vf a) { return vf_sum_lanes(a); }
#endif

/* Lanes 0 .. count - 1 of a (count <= HB_W) into out, and no other lane read: for the one-sample paths
 * whose work sits in the first lanes, so that the work of the others (AVX2's upper register) is dead
 * code the compiler drops. */
HB_INLINE void vf_store_first(float *out, vf a, int count)
{
    float lanes[HB_W];
    vf_storeu(lanes, a);
    for (int k = 0; k < count; k++)
        out[k] = lanes[k];
}

/* Lane k holds k. */
HB_INLINE vf vf_lane_index(void)
{
    static const float index[16] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15 };
    return vf_loadu(index);
}

/* The sum of lanes 0 .. count - 1 of a, in lane order, no other lane read (vf_store_first). */
HB_INLINE float vf_sum_first(vf a, int count)
{
    float lanes[HB_W], total = 0.0f;
    vf_store_first(lanes, a, count);
    for (int k = 0; k < count; k++)
        total += lanes[k];
    return total;
}

#endif

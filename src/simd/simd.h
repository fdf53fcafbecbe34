/* Picks the SIMD vocabulary for the ISA this translation unit is compiled for
 * (HB_TARGET_SCALAR, _SSE41, _AVX2, _AVX512 or _NEON, set by the Makefile) and
 * adds the few operations every ISA derives the same way. */
#ifndef HB_SIMD_H
#define HB_SIMD_H

/* Everything in the vocabulary and the math built on it is forced inline: a kernel
 * is one straight-line body per vector of samples, never a call per operation. Sanitizer builds
 * (HB_SANITIZED) leave inlining to the compiler: the same operations in smaller functions, which
 * the instrumented compile (ASan's passes grow with a function's size) needs to finish in minutes. */
#ifdef HB_SANITIZED
#define HB_INLINE static inline
#else
#define HB_INLINE static inline __attribute__((always_inline))
#endif
/* A stage that several kernels of one translation unit share (f from the geometry and M_p, the
 * internal paths of a fibre): one out-of-line copy per unit instead of one inlined into every
 * kernel and I0 variant, which is what bounds each unit's compile time and memory. Its vectors
 * cross the call through memory: a few loads and stores per block against hundreds of operations. */
#define HB_STAGE static __attribute__((noinline))
/* Unrolls the loop that follows (over lobes, channels, streams) so its arrays of vectors can live
 * in registers; GCC at -O2 keeps a loop with a large body rolled. Clang reads the same pragma.
 * Sanitizer builds (HB_SANITIZED) drop the hint: GCC cannot unroll some instrumented loops and
 * warns that it ignores the annotation. */
#ifdef HB_SANITIZED
#define HB_UNROLL
#else
#define HB_UNROLL _Pragma("GCC unroll 8")
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
#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
typedef unsigned hb_fp_mode;
HB_INLINE hb_fp_mode hb_flush_subnormals(void)
{
    hb_fp_mode mode = _mm_getcsr();
    _mm_setcsr(mode | 0x8040u); /* FTZ (bit 15), DAZ (bit 6) */
    return mode;
}
HB_INLINE void hb_fp_restore(hb_fp_mode mode) { _mm_setcsr(mode); }
#elif defined(__aarch64__)
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
/* False for NaN and +-Inf. */
HB_INLINE vm vf_isfinite(vf a) { return vf_le(vf_abs(a), vf_set1(3.40282347e38f)); }

#endif

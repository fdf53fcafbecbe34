/* What the x86 vocabularies share: one 4 x 4 transpose written once for the SSE, AVX and AVX-512
 * register widths, which apply it in every 128-bit lane. */
#ifndef HB_SIMD_X86_H
#define HB_SIMD_X86_H

/* o0..o3 get element 0..3 of a0..a3 in each 128-bit lane: T is the register type, P the intrinsic
 * prefix (_mm, _mm256, _mm512). Each input is evaluated once; four unpacks and four shuffles. */
#define HB_TRANSPOSE4_IN_LANES(T, P, a0, a1, a2, a3, o0, o1, o2, o3)                              \
    do {                                                                                          \
        T a0_ = (a0), a1_ = (a1), a2_ = (a2), a3_ = (a3);                                         \
        T t0_ = P##_unpacklo_ps(a0_, a1_), t1_ = P##_unpackhi_ps(a0_, a1_);                       \
        T t2_ = P##_unpacklo_ps(a2_, a3_), t3_ = P##_unpackhi_ps(a2_, a3_);                       \
        (o0) = P##_shuffle_ps(t0_, t2_, 0x44);                                                    \
        (o1) = P##_shuffle_ps(t0_, t2_, 0xee);                                                    \
        (o2) = P##_shuffle_ps(t1_, t3_, 0x44);                                                    \
        (o3) = P##_shuffle_ps(t1_, t3_, 0xee);                                                    \
    } while (0)

/* The sum of a 128-bit register's four floats, as (a0 + a2) + (a1 + a3) (SSE3's movehdup). */
#define HB_SUM4_PS(a) _mm_cvtss_f32(hb_sum2_ps_(_mm_add_ps((a), _mm_movehl_ps((a), (a)))))
#define hb_sum2_ps_(s) _mm_add_ss((s), _mm_movehdup_ps(s))

#endif

/* What the x86 vocabularies share: one 4 x 4 transpose written once for the SSE, AVX and AVX-512
 * register widths, which apply it in every 128-bit lane. */
#ifndef HB_SIMD_X86_H
#define HB_SIMD_X86_H

/* out[j] holds element j of a[0..3] in each 128-bit lane: T is the register type, P the intrinsic
 * prefix (_mm, _mm256, _mm512). Four unpacks and four shuffles. */
#define HB_TRANSPOSE4_IN_LANES(T, P, a, out)                                                     \
    do {                                                                                          \
        T t0_ = P##_unpacklo_ps((a)[0], (a)[1]), t1_ = P##_unpackhi_ps((a)[0], (a)[1]);           \
        T t2_ = P##_unpacklo_ps((a)[2], (a)[3]), t3_ = P##_unpackhi_ps((a)[2], (a)[3]);           \
        (out)[0] = P##_shuffle_ps(t0_, t2_, 0x44);                                                \
        (out)[1] = P##_shuffle_ps(t0_, t2_, 0xee);                                                \
        (out)[2] = P##_shuffle_ps(t1_, t3_, 0x44);                                                \
        (out)[3] = P##_shuffle_ps(t1_, t3_, 0xee);                                                \
    } while (0)

#endif

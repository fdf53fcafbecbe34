/* Counter-based uniform numbers for the Monte-Carlo parts of the kernels (HHH22 eqs. 31, 32):
 * a pure function of (plan key, sample index, counter), computed with 32-bit integer lanes, so
 * every ISA and the double reference (reference_internal.c) draw the same bits. */
#ifndef HB_HUANG_RNG_H
#define HB_HUANG_RNG_H

#include "math/vmath.h"

/* A bijective 32-bit mix (two multiply-xorshift rounds, the "lowbias32" constants of
 * C. Wellons' hash prospector). */
HB_INLINE vi rng_mix32(vi x)
{
    x = vi_xor(x, vi_shr(x, 16));
    x = vi_mul(x, vi_set1(0x7feb352d));
    x = vi_xor(x, vi_shr(x, 15));
    x = vi_mul(x, vi_set1((int32_t)0x846ca68bu));
    return vi_xor(x, vi_shr(x, 16));
}

#define HB_RNG_GOLDEN ((int32_t)0x9e3779b9u)

/* The stream of a sample: mix(index ^ key). */
HB_INLINE vi rng_stream(uint32_t key, vi index) { return rng_mix32(vi_xor(index, vi_set1((int32_t)key))); }

/* Number `counter` of a stream, in [0, 1) with 24 bits: mix((stream ^ key2) + counter * golden) >> 8. */
HB_INLINE vf rng_uniform(vi stream, uint32_t key2, int counter)
{
    vi x = vi_add(vi_xor(stream, vi_set1((int32_t)key2)), vi_set1((int32_t)((uint32_t)counter * 0x9e3779b9u)));
    return vf_mul(vf_from_vi(vi_shr(rng_mix32(x), 8)), vf_set1(0x1p-24f));
}

#endif

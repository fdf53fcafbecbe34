/* SplitMix64's finaliser (Steele, Lea and Flood 2014): a bijective 64-bit mix, which keys the
 * uniform numbers of hb_uniforms and HHH22's Monte-Carlo estimator. Internal. */
#ifndef HB_MATH_HASH_H
#define HB_MATH_HASH_H

static inline unsigned long long hb_mix64(unsigned long long x)
{
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

#endif

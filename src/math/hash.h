/* SplitMix64's finaliser (Steele, Lea and Flood 2014): a bijective 64-bit mix, which keys the
 * uniform numbers of hb_uniforms and HHH22's Monte-Carlo estimator; and XXH64, the table file's
 * checksum. Internal. */
#ifndef HB_MATH_HASH_H
#define HB_MATH_HASH_H

#include <stddef.h>

static inline unsigned long long hb_mix64(unsigned long long x)
{
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* XXH64 (Collet, xxHash specification v0.1.1) of n bytes with seed 0: four lanes over 32-byte
 * stripes, so it runs at memory speed; the table file's checksum. */
static inline unsigned long long hb_xxh64_rotl(unsigned long long x, int r) { return x << r | x >> (64 - r); }

static inline unsigned long long hb_xxh64_read(const unsigned char *p, int n)
{
    unsigned long long v = 0;
    for (int k = n - 1; k >= 0; k--)
        v = v << 8 | p[k];
    return v;
}

#define HB_XXH_P1 11400714785074694791ull
#define HB_XXH_P2 14029467366897019727ull
#define HB_XXH_P3 1609587929392839161ull
#define HB_XXH_P4 9650029242287828579ull
#define HB_XXH_P5 2870177450012600261ull

static inline unsigned long long hb_xxh64_round(unsigned long long acc, unsigned long long input)
{
    return hb_xxh64_rotl(acc + input * HB_XXH_P2, 31) * HB_XXH_P1;
}

static inline unsigned long long hb_xxh64(const unsigned char *p, size_t n)
{
    const unsigned char *end = p + n;
    unsigned long long h;
    if (n >= 32) {
        unsigned long long v[4] = { HB_XXH_P1 + HB_XXH_P2, HB_XXH_P2, 0, 0 - HB_XXH_P1 };
        for (; end - p >= 32; p += 32)
            for (int k = 0; k < 4; k++)
                v[k] = hb_xxh64_round(v[k], hb_xxh64_read(p + 8 * k, 8));
        h = hb_xxh64_rotl(v[0], 1) + hb_xxh64_rotl(v[1], 7) + hb_xxh64_rotl(v[2], 12) + hb_xxh64_rotl(v[3], 18);
        for (int k = 0; k < 4; k++)
            h = (h ^ hb_xxh64_round(0, v[k])) * HB_XXH_P1 + HB_XXH_P4;
    } else {
        h = HB_XXH_P5;
    }
    h += n;
    for (; end - p >= 8; p += 8)
        h = hb_xxh64_rotl(h ^ hb_xxh64_round(0, hb_xxh64_read(p, 8)), 27) * HB_XXH_P1 + HB_XXH_P4;
    if (end - p >= 4) {
        h = hb_xxh64_rotl(h ^ hb_xxh64_read(p, 4) * HB_XXH_P1, 23) * HB_XXH_P2 + HB_XXH_P3;
        p += 4;
    }
    for (; p < end; p++)
        h = hb_xxh64_rotl(h ^ *p * HB_XXH_P5, 11) * HB_XXH_P1;
    h = (h ^ h >> 33) * HB_XXH_P2;
    h = (h ^ h >> 29) * HB_XXH_P3;
    return h ^ h >> 32;
}

#endif

/* Vector math written once over the SIMD vocabulary (src/simd/simd.h).
 * Polynomial coefficients are the Cephes single-precision ones (exp, log, sin,
 * cos, asin, atan) and Abramowitz & Stegun 9.8.1 / 9.8.2 (I0). Accuracy is
 * measured by tests/test_vmath.c on every ISA; docs/accuracy.md states the figures.
 * Inputs outside a function's stated domain give unspecified (but not trapping)
 * results: kernels validate their inputs before calling these. */
#ifndef HB_VMATH_H
#define HB_VMATH_H

#include <math.h>

#include "simd/simd.h"

/* pi/2 as float plus the float closest to the rest, for reductions and reflections. */
#define HB_PIO2_F 1.57079637f
#define HB_PIO2_LO -4.37113883e-8f
#define HB_PI_F 3.14159274f
#define HB_PI_LO -8.74227766e-8f
#define HB_PIO2_D 1.5707963267948966
#define HB_TWO_PI_F 6.28318548f
#define HB_TWO_PI_LO -1.74845553e-7f
#define HB_LOG2E_F 1.44269504f

HB_INLINE vf vf_poly2(vf x, float c0, float c1, float c2)
{
    return vf_fma(vf_fma(vf_set1(c2), x, vf_set1(c1)), x, vf_set1(c0));
}

/* y * 2^k for integral k in [-252, 254]: two power-of-two factors, each a normal
 * float, so a result in the denormal range is rounded once. */
HB_INLINE vf vf_ldexp(vf y, vf k)
{
    vf k1 = vf_floor(vf_mul(k, vf_set1(0.5f)));
    vf k2 = vf_sub(k, k1);
    vf s1 = vi_as_vf(vi_shl(vi_add(vi_from_vf(k1), vi_set1(127)), 23));
    vf s2 = vi_as_vf(vi_shl(vi_add(vi_from_vf(k2), vi_set1(127)), 23));
    return vf_mul(vf_mul(y, s1), s2);
}

/* e^r for |r| <= ln(2)/2 (Cephes expf polynomial). */
HB_INLINE vf vf_exp_reduced(vf r)
{
    vf p = vf_set1(1.9875691500e-4f);
    p = vf_fma(p, r, vf_set1(1.3981999507e-3f));
    p = vf_fma(p, r, vf_set1(8.3334519073e-3f));
    p = vf_fma(p, r, vf_set1(4.1665795894e-2f));
    p = vf_fma(p, r, vf_set1(1.6666665459e-1f));
    p = vf_fma(p, r, vf_set1(5.0000001201e-1f));
    return vf_add(vf_fma(p, vf_mul(r, r), r), vf_set1(1.0f));
}

/* e^x: x = k ln2 + r with a two-part ln2 (Cody & Waite), then 2^k * e^r.
 * Underflows to 0 below -103.97 and overflows to +Inf above 88.72. */
HB_INLINE vf vf_exp(vf x)
{
    x = vf_clamp(x, -104.0f, 89.0f);
    vf k = vf_round(vf_mul(x, vf_set1(1.44269504f)));
    vf r = vf_fnma(k, vf_set1(0.693359375f), x);
    r = vf_fnma(k, vf_set1(-2.12194440e-4f), r);
    return vf_ldexp(vf_exp_reduced(r), k);
}

/* e^x for x <= 88 where results below FLT_MIN may be 0 (the kernels' detectors and
 * absorption have x <= 0): one power-of-two scale instead of two, since no denormal is
 * ever formed and 2^k stays finite (k <= 127). Same accuracy as vf_exp above. */
HB_INLINE vf vf_exp_flush(vf x)
{
    vm normal = vf_ge(x, vf_set1(-87.33f));
    x = vf_clamp(x, -87.33f, 88.0f);
    vf k = vf_round(vf_mul(x, vf_set1(1.44269504f)));
    vf r = vf_fnma(k, vf_set1(0.693359375f), x);
    r = vf_fnma(k, vf_set1(-2.12194440e-4f), r);
    vf scale = vi_as_vf(vi_shl(vi_add(vi_from_vf(k), vi_set1(127)), 23));
    return vf_keep(normal, vf_mul(vf_exp_reduced(r), scale));
}

/* 2^-t for t >= 0, exactly 0 from t = 126.5 (2^-127 and below are not formed): the dFH11 kernels'
 * detector Gaussians 2^-(sigma x)^2 and absorptions 2^-(mu' l log2 e), whose exponents the plan
 * scales by log2(e) in advance; the hot path of the node sum. t is clamped to 127 and rounded to k
 * by subtracting it from 1.5 2^23 + 127 (exact for t < 2^22): the difference's low bits then hold
 * 127 - k, the exponent field of 2^-k, one shift away. 2^r for |r| <= 1/2 by a degree-5 minimax
 * polynomial, 7.5e-8 relative before rounding: 2.9 ulp in all (1.3 of them where 2^r < 1 and the
 * ulp is finer). Degree 6 gives 1.2 ulp for 4.5% of the balanced dFH11 kernel's time, digits far
 * below every quality's error target (docs/accuracy.md). */
HB_INLINE vf vf_exp2_neg(vf t)
{
    t = vf_min(t, vf_set1(127.0f));
    vf biased = vf_sub(vf_set1(12583039.0f), t); /* 1.5 2^23 + 127 - t, rounded to an integer */
    vf k = vf_sub(vf_set1(12583039.0f), biased); /* t rounded, exactly */
    vf r = vf_sub(k, t);                         /* in [-1/2, 1/2], exactly (Sterbenz) */
    vf p = vf_set1(1.3276472167819943e-3f);
    p = vf_fma(p, r, vf_set1(9.6755413310213911e-3f));
    p = vf_fma(p, r, vf_set1(5.5507132728753912e-2f));
    p = vf_fma(p, r, vf_set1(2.4022119723969178e-1f));
    p = vf_fma(p, r, vf_set1(6.9314696706526493e-1f));
    p = vf_fma(p, r, vf_set1(1.0000000716546416f));
    return vf_mul(p, vi_as_vf(vi_shl(vf_as_vi(biased), 23)));
}

/* 1 - 2^-t for t >= 0 given p = 2^-t, without the cancellation of 1 - p near t = 0: below t = 1/4
 * the series of -expm1(-x), x = t ln 2, to x^5 (relative error under 3e-8), above it 1 - p (p <= 0.85,
 * so at most 4e-7 relative). Never negative, where 1 - p is an ulp below 0 at t = 0. */
HB_INLINE vf vf_one_minus_exp2_neg(vf t, vf p)
{
    vf x = vf_mul(t, vf_set1(0.693147181f));
    vf series = vf_fnma(x, vf_set1(1.0f / 120.0f), vf_set1(1.0f / 24.0f));
    series = vf_fnma(x, series, vf_set1(1.0f / 6.0f));
    series = vf_fnma(x, series, vf_set1(0.5f));
    series = vf_fnma(x, series, vf_set1(1.0f));
    return vf_select(vf_lt(t, vf_set1(0.25f)), vf_mul(x, series), vf_sub(vf_set1(1.0f), p));
}

/* e^x for an argument carried in double precision: the reduction x - k ln2 is
 * done in double, so a large |x| loses nothing to the float rounding of x. */
HB_INLINE vf vf_exp_dw(vdw x)
{
    x = vdw_min(vdw_max(x, vdw_set1(-110.0)), vdw_set1(100.0));
    vdw k = vdw_round(vdw_mul(x, vdw_set1(1.4426950408889634)));
    vdw r = vdw_fma(k, vdw_set1(-0.69314718055994531), x);
    return vf_ldexp(vf_exp_reduced(vdw_to_vf(r)), vdw_to_vf(k));
}

/* Natural log: x = m 2^e with m in [sqrt(1/2), sqrt(2)), Cephes logf polynomial
 * in m - 1. Denormals are scaled first; log(0) = -Inf, log(x < 0) = NaN. */
HB_INLINE vf vf_log(vf x)
{
    vm tiny = vf_lt(x, vf_set1(1.17549435e-38f));
    vf xs = vf_select(tiny, vf_mul(x, vf_set1(8388608.0f)), x);
    vi bits = vf_as_vi(xs);
    vf e = vf_from_vi(vi_sub(vi_shr(bits, 23), vi_set1(127)));
    e = vf_select(tiny, vf_sub(e, vf_set1(23.0f)), e);
    vf m = vi_as_vf(vi_or(vi_and(bits, vi_set1(0x007fffff)), vi_set1(0x3f800000)));
    vm big = vf_gt(m, vf_set1(1.41421356f));
    m = vf_select(big, vf_mul(m, vf_set1(0.5f)), m);
    e = vf_select(big, vf_add(e, vf_set1(1.0f)), e);
    vf f = vf_sub(m, vf_set1(1.0f));
    vf z = vf_mul(f, f);
    vf p = vf_set1(7.0376836292e-2f);
    p = vf_fma(p, f, vf_set1(-1.1514610310e-1f));
    p = vf_fma(p, f, vf_set1(1.1676998740e-1f));
    p = vf_fma(p, f, vf_set1(-1.2420140846e-1f));
    p = vf_fma(p, f, vf_set1(1.4249322787e-1f));
    p = vf_fma(p, f, vf_set1(-1.6668057665e-1f));
    p = vf_fma(p, f, vf_set1(2.0000714765e-1f));
    p = vf_fma(p, f, vf_set1(-2.4999993993e-1f));
    p = vf_fma(p, f, vf_set1(3.3333331174e-1f));
    vf y = vf_mul(vf_mul(p, f), z);
    y = vf_fma(e, vf_set1(-2.12194440e-4f), y);
    y = vf_fnma(vf_set1(0.5f), z, y);
    vf r = vf_fma(e, vf_set1(0.693359375f), vf_add(f, y));
    r = vf_select(vf_eq(x, vf_set1(0.0f)), vf_set1(-INFINITY), r);
    r = vf_select(vf_eq(x, vf_set1(INFINITY)), x, r);
    return vf_select(vf_lt(x, vf_set1(0.0f)), vf_set1(NAN), r);
}

/* log(1 + u) for u >= -1, exact near u = 0: w = 1 + u is rounded, and the
 * rounding error ((w - 1) - u) is taken back out to first order. */
HB_INLINE vf vf_log1p(vf u)
{
    vf w = vf_add(vf_set1(1.0f), u);
    vf wm1 = vf_sub(w, vf_set1(1.0f));
    vf r = vf_sub(vf_log(w), vf_div(vf_sub(wm1, u), w));
    return vf_select(vf_eq(wm1, vf_set1(0.0f)), u, r);
}

/* sin and cos together: x = q pi/2 + r, |r| <= pi/4, with pi/2 split into three
 * 12-bit floats (so q times each is exact, FMA or not, for |q| < 4096) and a
 * float remainder, so r keeps its relative accuracy next to the zeros of sin and
 * cos. Then the Cephes sin and cos polynomials on r, a quadrant swap and sign
 * flip. Accurate for |x| < 6000. */
HB_INLINE void vf_sincos(vf x, vf *s, vf *c)
{
    vf q = vf_round(vf_mul(x, vf_set1(0.636619772f)));
    vf r = vf_fnma(q, vf_set1(1.57080078125f), x);
    r = vf_fnma(q, vf_set1(-4.453584551811218e-06f), r);
    r = vf_fnma(q, vf_set1(-8.706138032721356e-10f), r);
    r = vf_fnma(q, vf_set1(6.223372171896613e-14f), r);
    vf z = vf_mul(r, r);
    vf sp = vf_poly2(z, -1.6666654611e-1f, 8.3321608736e-3f, -1.9515295891e-4f);
    vf sin_r = vf_fma(vf_mul(sp, z), r, r);
    vf cp = vf_poly2(z, 4.166664568298827e-2f, -1.388731625493765e-3f, 2.443315711809948e-5f);
    vf cos_r = vf_fma(vf_mul(cp, z), z, vf_fnma(vf_set1(0.5f), z, vf_set1(1.0f)));
    vi qi = vi_from_vf(q);
    vm swap = vi_eq(vi_and(qi, vi_set1(1)), vi_set1(1));
    vi sin_flip = vi_shl(vi_and(qi, vi_set1(2)), 30);
    vi cos_flip = vi_shl(vi_and(vi_add(qi, vi_set1(1)), vi_set1(2)), 30);
    *s = vi_as_vf(vi_xor(vf_as_vi(vf_select(swap, cos_r, sin_r)), sin_flip));
    *c = vi_as_vf(vi_xor(vf_as_vi(vf_select(swap, sin_r, cos_r)), cos_flip));
}

HB_INLINE vf vf_sin(vf x) { vf s, c; vf_sincos(x, &s, &c); return s; }
HB_INLINE vf vf_cos(vf x) { vf s, c; vf_sincos(x, &s, &c); return c; }

/* asin of a = |x| in [0, 1] without the final reflection: for a > 1/2 it returns
 * asin(sqrt((1 - a)/2)) and sets *big (Cephes asinf polynomial). */
HB_INLINE vf vf_asin_core(vf a, vm *big)
{
    *big = vf_gt(a, vf_set1(0.5f));
    vf z = vf_select(*big, vf_mul(vf_set1(0.5f), vf_sub(vf_set1(1.0f), a)), vf_mul(a, a));
    vf s = vf_select(*big, vf_sqrt(z), a);
    vf p = vf_set1(4.2163199048e-2f);
    p = vf_fma(p, z, vf_set1(2.4181311049e-2f));
    p = vf_fma(p, z, vf_set1(4.5470025998e-2f));
    p = vf_fma(p, z, vf_set1(7.4953002686e-2f));
    p = vf_fma(p, z, vf_set1(1.6666752422e-1f));
    return vf_fma(vf_mul(p, z), s, s);
}

/* asin(s) for |s| <= 3/4 given z = s^2: s + s z P(z), P of degree 6 fitted (minimax, relative) to
 * (asin(s) - s) / (s z) on that range, 6e-8 relative before rounding; no square root and no
 * reflection. dFH11's refraction angle asin(h / eta') stays in it for eta >= 4/3 (eta' >= eta). */
HB_INLINE vf vf_asin_narrow(vf s, vf z)
{
    vf p = vf_set1(0.158733118466f);
    p = vf_fma(p, z, vf_set1(-0.174444044826f));
    p = vf_fma(p, z, vf_set1(0.131982111211f));
    p = vf_fma(p, z, vf_set1(-0.00172306617339f));
    p = vf_fma(p, z, vf_set1(0.0495011543431f));
    p = vf_fma(p, z, vf_set1(0.0746580618054f));
    p = vf_fma(p, z, vf_set1(0.166674719022f));
    return vf_fma(vf_mul(s, z), p, s);
}

/* asin(s) given c = sqrt(1 - s^2) formed without cancellation (|s| <= 1, c >= 0): the polynomial of
 * vf_asin_narrow at min(|s|, c) <= sqrt(1/2), reflected as pi/2 - asin(c) where |s| > c. Near |s| = 1
 * the error is that of c, where asin(s) of a rounded s has the error of sqrt(1 - s^2): 3e-4 at
 * s = 1 - 6e-8. */
HB_INLINE vf vf_asin_with_cos(vf s, vf c)
{
    vf a = vf_abs(s);
    vm steep = vf_gt(a, c);
    vf x = vf_min(a, c);
    vf g = vf_asin_narrow(x, vf_mul(x, x));
    vf reflected = vf_add(vf_sub(vf_set1(HB_PIO2_F), g), vf_set1(HB_PIO2_LO));
    return vf_copysign(vf_select(steep, reflected, g), s);
}

/* asin(x) for |x| <= 1; for |x| > 1/2, asin(a) = pi/2 - 2 asin(sqrt((1 - a)/2)). */
HB_INLINE vf vf_asin(vf x)
{
    vm big;
    vf p = vf_asin_core(vf_abs(x), &big);
    vf reflected = vf_add(vf_fnma(vf_set1(2.0f), p, vf_set1(HB_PIO2_F)), vf_set1(HB_PIO2_LO));
    return vf_copysign(vf_select(big, reflected, p), x);
}

/* acos(x) for |x| <= 1: pi/2 - asin(x) for |x| <= 1/2, 2 asin(sqrt((1 - x)/2))
 * for x > 1/2 and pi - 2 asin(sqrt((1 + x)/2)) for x < -1/2. */
HB_INLINE vf vf_acos(vf x)
{
    vm big;
    vf p = vf_asin_core(vf_abs(x), &big);
    vf mid = vf_sub(vf_set1(HB_PIO2_F), vf_sub(vf_copysign(p, x), vf_set1(HB_PIO2_LO)));
    vf twice = vf_add(p, p);
    vf far_side = vf_sub(vf_set1(HB_PI_F), vf_sub(twice, vf_set1(HB_PI_LO)));
    vf outer = vf_select(vf_lt(x, vf_set1(0.0f)), far_side, twice);
    return vf_select(big, outer, mid);
}

/* atan2(y, x) in [-pi, pi]: atan of t = min(|x|,|y|)/max(|x|,|y|) in [0, 1]
 * (reduced by pi/4 above tan(pi/8), Cephes atanf polynomial), then reflected
 * into the right octant. The reduced argument (t - 1)/(t + 1) is formed as
 * (min - max)/(min + max), so one division serves both cases (and its rounding
 * is not compounded with t's). atan2(+-0, +-0) follows the C library's signs. */
HB_INLINE vf vf_atan2(vf y, vf x)
{
    vf ay = vf_abs(y), ax = vf_abs(x);
    vf num = vf_min(ay, ax), den = vf_max(ay, ax);
    vm mid = vf_gt(num, vf_mul(den, vf_set1(0.414213562f)));
    vf t = vf_div(vf_select(mid, vf_sub(num, den), num), vf_select(mid, vf_add(num, den), den));
    t = vf_select(vf_eq(den, vf_set1(0.0f)), vf_set1(0.0f), t);
    vf z = vf_mul(t, t);
    vf p = vf_set1(8.05374449538e-2f);
    p = vf_fma(p, z, vf_set1(-1.38776856032e-1f));
    p = vf_fma(p, z, vf_set1(1.99777106478e-1f));
    p = vf_fma(p, z, vf_set1(-3.33329491539e-1f));
    vf a = vf_fma(vf_mul(p, z), t, t);
    a = vf_add(vf_select(mid, vf_set1(0.785398163f), vf_set1(0.0f)), a);
    vf from_y_axis = vf_add(vf_sub(vf_set1(HB_PIO2_F), a), vf_set1(HB_PIO2_LO));
    a = vf_select(vf_gt(ay, ax), from_y_axis, a);
    vm x_negative = vi_eq(vi_and(vf_as_vi(x), vi_set1(HB_SIGN_BIT)), vi_set1(HB_SIGN_BIT));
    vf from_negative_x = vf_add(vf_sub(vf_set1(HB_PI_F), a), vf_set1(HB_PI_LO));
    a = vf_select(x_negative, from_negative_x, a);
    return vf_copysign(a, y);
}

/* A&S 9.8.1 without its leading 1: I0(x) - 1 for |x| <= 3.75, in t = (x/3.75)^2. */
HB_INLINE vf vf_i0_small_minus1(vf x)
{
    vf t = vf_mul(x, vf_set1(1.0f / 3.75f));
    t = vf_mul(t, t);
    vf q = vf_set1(0.0045813f);
    q = vf_fma(q, t, vf_set1(0.0360768f));
    q = vf_fma(q, t, vf_set1(0.2659732f));
    q = vf_fma(q, t, vf_set1(1.2067492f));
    q = vf_fma(q, t, vf_set1(3.0899424f));
    q = vf_fma(q, t, vf_set1(3.5156229f));
    return vf_mul(t, q);
}

/* A&S 9.8.2: sqrt(x) e^-x I0(x) for x >= 3.75, a polynomial in u = 3.75/x. */
HB_INLINE vf vf_i0_large_poly_u(vf u)
{
    vf p = vf_set1(0.00392377f);
    p = vf_fma(p, u, vf_set1(-0.01647633f));
    p = vf_fma(p, u, vf_set1(0.02635537f));
    p = vf_fma(p, u, vf_set1(-0.02057706f));
    p = vf_fma(p, u, vf_set1(0.00916281f));
    p = vf_fma(p, u, vf_set1(-0.00157565f));
    p = vf_fma(p, u, vf_set1(0.00225319f));
    p = vf_fma(p, u, vf_set1(0.01328592f));
    return vf_fma(p, u, vf_set1(0.39894228f));
}

HB_INLINE vf vf_i0_large_poly(vf x) { return vf_i0_large_poly_u(vf_div(vf_set1(3.75f), x)); }

/* e^-x I0(x) for x >= 3.75 (A&S 9.8.2): the polynomial times 1/sqrt(x) = sqrt(u) / sqrt(3.75),
 * one division for both, so the square root runs beside the polynomial rather than after it. */
HB_INLINE vf vf_i0e_large(vf x)
{
    vf u = vf_div(vf_set1(3.75f), x);
    return vf_mul(vf_i0_large_poly_u(u), vf_mul(vf_sqrt(u), vf_set1(0.516397779f)));
}

/* The modified Bessel function I0 (A&S 9.8.1 and 9.8.2); +Inf beyond |x| = 91.9. */
HB_INLINE vf vf_i0(vf x)
{
    vf ax = vf_abs(x);
    vf small = vf_add(vf_set1(1.0f), vf_i0_small_minus1(vf_min(ax, vf_set1(3.75f))));
    vf xl = vf_max(ax, vf_set1(3.75f));
    vf half = vf_exp(vf_mul(vf_set1(0.5f), xl)); /* e^x as a square keeps x up to 2 * 88 */
    vf large = vf_mul(vf_mul(half, vf_i0e_large(xl)), half);
    return vf_select(vf_le(ax, vf_set1(3.75f)), small, large);
}

/* e^-|x| I0(x), finite for every finite x. */
HB_INLINE vf vf_i0e(vf x)
{
    vf ax = vf_abs(x);
    vf xs = vf_min(ax, vf_set1(3.75f));
    vf small = vf_mul(vf_exp(vf_neg(xs)), vf_add(vf_set1(1.0f), vf_i0_small_minus1(xs)));
    vf xl = vf_max(ax, vf_set1(3.75f));
    vf large = vf_i0e_large(xl);
    return vf_select(vf_le(ax, vf_set1(3.75f)), small, large);
}

/* log I0(x): log1p of A&S 9.8.1 below 3.75 (so it stays relative-accurate as
 * x -> 0), x - log(x)/2 + log P(3.75/x) above. */
HB_INLINE vf vf_log_i0(vf x)
{
    vf ax = vf_abs(x);
    vf small = vf_log1p(vf_i0_small_minus1(vf_min(ax, vf_set1(3.75f))));
    vf xl = vf_max(ax, vf_set1(3.75f));
    vf large = vf_add(vf_fnma(vf_set1(0.5f), vf_log(xl), xl), vf_log(vf_i0_large_poly(xl)));
    return vf_select(vf_le(ax, vf_set1(3.75f)), small, large);
}

/* sin(t) in float for |t| <= pi/2: the Taylor series to t^11, whose remainder (below
 * 6e-8 at pi/2) is under half an ulp of sin(t) everywhere there; odd, so sin(-t) = -sin(t) exactly. */
HB_INLINE vf vf_sin_halfpi(vf t)
{
    vf z = vf_mul(t, t);
    vf p = vf_set1(-1.0f / 39916800.0f);   /* -1/11! */
    p = vf_fma(p, z, vf_set1(1.0f / 362880.0f)); /* 1/9! */
    p = vf_fma(p, z, vf_set1(-1.0f / 5040.0f));  /* -1/7! */
    p = vf_fma(p, z, vf_set1(1.0f / 120.0f));    /* 1/5! */
    p = vf_fma(p, z, vf_set1(-1.0f / 6.0f));     /* -1/3! */
    return vf_fma(vf_mul(p, z), t, t);
}

/* The rounding error of s = fl(x + y), exactly: x + y = s + error (Knuth's TwoSum). */
HB_INLINE vf vf_two_sum_error(vf x, vf y, vf s)
{
    vf y_part = vf_sub(s, x), x_part = vf_sub(s, y_part);
    return vf_add(vf_sub(x, x_part), vf_sub(y, y_part));
}

/* sin(t) in double precision for |t| <= pi/2: the Taylor series to t^17, whose
 * remainder is below 5e-14 there. */
HB_INLINE vdw vdw_sin_taylor(vdw t)
{
    vdw z = vdw_mul(t, t);
    vdw p = vdw_set1(1.0 / 355687428096000.0);               /* 1/17! */
    p = vdw_fma(p, z, vdw_set1(-1.0 / 1307674368000.0));     /* -1/15! */
    p = vdw_fma(p, z, vdw_set1(1.0 / 6227020800.0));         /* 1/13! */
    p = vdw_fma(p, z, vdw_set1(-1.0 / 39916800.0));          /* -1/11! */
    p = vdw_fma(p, z, vdw_set1(1.0 / 362880.0));             /* 1/9! */
    p = vdw_fma(p, z, vdw_set1(-1.0 / 5040.0));              /* -1/7! */
    p = vdw_fma(p, z, vdw_set1(1.0 / 120.0));                /* 1/5! */
    p = vdw_fma(p, z, vdw_set1(-1.0 / 6.0));                 /* -1/3! */
    return vdw_fma(vdw_mul(p, z), t, t);
}

/* The standard normal quantile sqrt(2) erfinv(2u - 1) for u in (0, 1), by the single-precision
 * erfinv of M. Giles, "Approximating the erfinv function" (GPU Computing Gems, 2011): a polynomial
 * in w - 2.5 for w = -log(1 - x^2) < 5, else in sqrt(w) - 3. Both are evaluated (fixed cost) and
 * 1 - x^2 is formed as 4u(1 - u), exact in the tails where 1 - x^2 would cancel. u is clamped to
 * [2^-25, 1 - 2^-25], about 5.4 standard deviations. */
HB_INLINE vf vf_normal_quantile(vf u)
{
    static const float central[9] = { 2.81022636e-08f, 3.43273939e-07f, -3.5233877e-06f, -4.39150654e-06f,
                                      0.00021858087f, -0.00125372503f, -0.00417768164f, 0.246640727f,
                                      1.50140941f };
    static const float tail[9] = { -0.000200214257f, 0.000100950558f, 0.00134934322f, -0.00367342844f,
                                   0.00573950773f, -0.0076224613f, 0.00943887047f, 1.00167406f, 2.83297682f };
    u = vf_clamp(u, 2.98023224e-8f, 0.99999997f);
    vf w = vf_neg(vf_log(vf_mul(vf_mul(vf_set1(4.0f), u), vf_sub(vf_set1(1.0f), u))));
    vf wc = vf_sub(w, vf_set1(2.5f)), wt = vf_sub(vf_sqrt(w), vf_set1(3.0f));
    vf pc = vf_set1(central[0]), pt = vf_set1(tail[0]);
    for (int i = 1; i < 9; i++) {
        pc = vf_fma(pc, wc, vf_set1(central[i]));
        pt = vf_fma(pt, wt, vf_set1(tail[i]));
    }
    vf erfinv_over_x = vf_select(vf_lt(w, vf_set1(5.0f)), pc, pt);
    return vf_mul(vf_mul(erfinv_over_x, vf_fnma(vf_set1(-2.0f), u, vf_set1(-1.0f))), vf_set1(1.41421356f));
}

/* The z of a direction's planar part (x, z), with the planar part of a direction along the fibre
 * (x = z = 0) taken as (0, 1): its azimuth is 0, in every entry point (docs/conventions.md). */
HB_INLINE vf planar_z(const vf w[3])
{
    vm pole = vm_and(vf_eq(w[0], vf_set1(0.0f)), vf_eq(w[2], vf_set1(0.0f)));
    return vf_select(pole, vf_set1(1.0f), w[2]);
}

/* phi = phi_o - phi_i of two directions from their planar parts' cross and dot products. */
HB_INLINE vf azimuth_difference(const vf wi[3], const vf wo[3])
{
    vf zi = planar_z(wi), zo = planar_z(wo);
    return vf_atan2(vf_fnma(zo, wi[0], vf_mul(wo[0], zi)), vf_fma(wo[0], wi[0], vf_mul(zo, zi)));
}

/* A sampler's weights f / pdf per channel, 0 where the pdf is 0. */
HB_INLINE void sample_weights_of(vf pdf, const vf *f, vf *weight, int channels)
{
    vm positive = vf_gt(pdf, vf_set1(0.0f));
    vf inv_pdf = vf_div(vf_set1(1.0f), vf_select(positive, pdf, vf_set1(1.0f)));
    for (int k = 0; k < channels; k++)
        weight[k] = vf_keep(positive, vf_mul(f[k], inv_pdf));
}

HB_INLINE void sample_weights(vf pdf, const vf f[3], vf weight[3])
{
    sample_weights_of(pdf, f, weight, 3);
}

/* An azimuth |x| <= HB_PHI_LIMIT past 2 pi reduced to x - 2 pi k in [-pi, pi], the same on every
 * ISA: 2 pi as 6.28125 (8 bits, so k times it and the first difference are exact) plus a float
 * remainder, and no fused operation, so each step rounds alike with and without FMA. At |x| = 1e4
 * the result is within 3e-7 of x mod 2 pi, where the float x itself is spaced 1e-3 apart. Within
 * [-2 pi, 2 pi] x is kept as given: the difference of two azimuths is then exact where it matters
 * (near the forward focus, pi - |phi_o - phi_i| -> 0), and wrap_angle's k is at most 2. */
HB_INLINE vf reduce_angle(vf x)
{
    vf k = vf_round(vf_mul(x, vf_set1(0.159154943f)));
    vf r = vf_sub(vf_sub(x, vf_mul(k, vf_set1(6.28125f))), vf_mul(k, vf_set1(1.9353071693331003e-3f)));
    return vf_select(vf_gt(vf_abs(x), vf_set1(HB_TWO_PI_F)), r, x);
}

/* x - 2 pi k in [-pi, pi] for |x| < 2^24, with 2 pi split in two floats; k = x / 2 pi rounded by
 * adding 1.5 2^23 (as in vf_exp2_neg: two additions instead of a multiply and a rounding). */
HB_INLINE vf wrap_angle(vf x)
{
    vf k = vf_sub(vf_fma(x, vf_set1(0.159154943f), vf_set1(12582912.0f)), vf_set1(12582912.0f));
    return vf_fnma(k, vf_set1(HB_TWO_PI_LO), vf_fnma(k, vf_set1(HB_TWO_PI_F), x));
}

#endif

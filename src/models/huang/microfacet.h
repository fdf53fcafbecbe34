/* HHH22 microsurface over the SIMD vocabulary: the normal distributions and Smith's
 * shadowing-masking. Angles to the mesonormal arrive as x = cos and 1 - x computed
 * without cancellation by the caller, so the peak of a narrow NDF keeps its precision. */
#ifndef HB_HUANG_MICROFACET_H
#define HB_HUANG_MICROFACET_H

#include "math/vmath.h"
#include "constants.h"

#define HB_INV_PI_F 0.318309886f
#define HB_INV_SQRT_PI_F 0.564189584f

/* f's 1 / cos(theta_o) of eq. 10's projected width with cos(theta_o) kept above the plan's floor,
 * times min(1, cos(theta_i) / floor), the same floor for w_i, which keeps S = f / cos(theta_i)
 * reciprocal (docs/huang.md, "At the poles"). 1 / cos(theta_o) away from the poles. */
HB_INLINE vf huang_width_factor_floored(vf cos_ti, vf cos_to, float floor, float inv_floor)
{
    vf incident = vf_min(vf_set1(1.0f), vf_mul(cos_ti, vf_set1(inv_floor)));
    return vf_div(incident, vf_max(cos_to, vf_set1(floor)));
}

HB_INLINE vf huang_width_factor(const hb_huang *h, vf cos_ti, vf cos_to)
{
    return huang_width_factor_floored(cos_ti, cos_to, h->cos_floor, h->inv_cos_floor);
}

/* GGX's D as numerator / denominator, for callers that fold several divisions into one: the
 * denominator ((1 - x^2) + r^2 x^2)^2 lies in [r^4, 1]. */
HB_INLINE void ndf_ggx_ratio(const hb_huang *h, vf one_minus_x, vf *num, vf *den)
{
    vf x = vf_sub(vf_set1(1.0f), one_minus_x);
    vf sin2 = vf_mul(one_minus_x, vf_add(vf_set1(1.0f), x));
    vf r2 = vf_set1(h->roughness2), base = vf_fma(r2, vf_mul(x, x), sin2);
    *num = vf_mul(r2, vf_set1(HB_INV_PI_F));
    *den = vf_mul(base, base);
}

/* D(w_h, w_m) given one_minus_x = 1 - x, x = w_h . w_m: GGX (HHH22 eq. 41) written as
 * r^2 / (pi ((1 - x^2) + r^2 x^2)^2), Beckmann exp(-tan^2 / r^2) / (pi r^2 x^4). Callers only ask
 * inside the visible window, where x >= 0 (both directions see w_m, so their sum does); at its ends
 * x = 0 up to rounding, and both forms are even in x, so there is no cut-off to misplace. */
HB_INLINE vf ndf_huang(const hb_huang *h, vf one_minus_x)
{
    vf num, den;
    if (h->beckmann) {
        vf x = vf_sub(vf_set1(1.0f), one_minus_x);
        vf sin2 = vf_mul(one_minus_x, vf_add(vf_set1(1.0f), x));
        vf x2 = vf_mul(x, x), r2 = vf_set1(h->roughness2);
        vf x4 = vf_max(vf_mul(x2, x2), vf_set1(1e-30f));
        vf tan2 = vf_div(sin2, vf_max(x2, vf_set1(1e-30f)));
        num = vf_exp_flush(vf_max(vf_div(vf_neg(tan2), r2), vf_set1(-100.0f)));
        den = vf_mul(vf_mul(vf_set1(HB_PI_F), r2), x4);
    } else {
        ndf_ggx_ratio(h, one_minus_x, &num, &den);
    }
    return vf_div(num, den);
}

/* erfcx(a) = e^(a^2) erfc(a) for a >= 0 by A&S 7.1.26 (error below 1.5e-7 e^(a^2), i.e. erfc within 1.5e-7). */
HB_INLINE vf erfcx_as(vf a)
{
    vf t = vf_rcp(vf_fma(vf_set1(0.3275911f), a, vf_set1(1.0f)));
    vf p = vf_fma(vf_set1(1.061405429f), t, vf_set1(-1.453152027f));
    p = vf_fma(p, t, vf_set1(1.421413741f));
    p = vf_fma(p, t, vf_set1(-0.284496736f));
    p = vf_fma(p, t, vf_set1(0.254829592f));
    return vf_mul(p, t);
}

/* Smith's Lambda = y / d for a direction at cos c in [0, 1] to the mesonormal (Heitz 2014), the
 * parts kept apart so that c -> 0 (Lambda -> infinity) needs no division by zero.
 * GGX: Lambda = (sqrt(1 + r^2 tan^2) - 1) / 2, y = r^2 (1 - c^2), d = 2 c (sqrt(c^2 + y) + c).
 * Beckmann: Lambda = (e^(-a^2) / (a sqrt(pi)) - erfc(a)) / 2, a = c / (r sqrt(1 - c^2)),
 * y = e^(-a^2) (1/sqrt(pi) - a erfcx(a)), d = 2a (erfcx within 1.5e-7, Lambda within 7.5e-8). */
typedef struct smith_parts {
    vf d, y;
} smith_parts;

HB_INLINE smith_parts smith_lambda_parts(const hb_huang *h, vf c)
{
    smith_parts l;
    vf sin2 = vf_fnma(c, c, vf_set1(1.0f));
    if (h->beckmann) {
        vf a = vf_div(c, vf_mul(vf_set1(h->roughness), vf_sqrt(vf_max(sin2, vf_set1(1e-30f)))));
        a = vf_min(a, vf_set1(1e4f));
        vf tail = vf_max(vf_fnma(a, erfcx_as(a), vf_set1(HB_INV_SQRT_PI_F)), vf_set1(0.0f));
        l.y = vf_mul(vf_exp_flush(vf_max(vf_neg(vf_mul(a, a)), vf_set1(-100.0f))), tail);
        l.d = vf_add(a, a);
    } else {
        l.y = vf_mul(vf_set1(h->roughness2), sin2);
        l.d = vf_mul(vf_add(c, c), vf_add(vf_sqrt(vf_fma(c, c, l.y)), c));
    }
    return l;
}

/* G1 = 1 / (1 + Lambda) = d / (d + y), as that numerator and denominator (the latter >= 1e-30). */
HB_INLINE void smith_g1_ratio(const hb_huang *h, vf c, vf *num, vf *den)
{
    smith_parts l = smith_lambda_parts(h, vf_clamp(c, 0.0f, 1.0f));
    *num = l.d;
    *den = vf_max(vf_add(l.d, l.y), vf_set1(1e-30f));
}

HB_INLINE vf smith_g1_huang(const hb_huang *h, vf c)
{
    vf num, den;
    smith_g1_ratio(h, c, &num, &den);
    return vf_div(num, den);
}

/* G1(c_1) G1(c_2) as numerator / denominator, for callers that fold divisions. */
HB_INLINE void smith_g1_pair_ratio(const hb_huang *h, vf c_1, vf c_2, vf *num, vf *den)
{
    vf num_1, den_1, num_2, den_2;
    smith_g1_ratio(h, c_1, &num_1, &den_1);
    smith_g1_ratio(h, c_2, &num_2, &den_2);
    *num = vf_mul(num_1, num_2);
    *den = vf_mul(den_1, den_2);
}

/* G1 / c, finite as c -> 0 where both vanish (GGX: 2 / r, Beckmann: 2 sqrt(pi) / r): the visible
 * normals' density divides by w . w_m (Heitz 2014, eq. 2 of Heitz 2018). */
HB_INLINE vf smith_g1_over_cos(const hb_huang *h, vf c)
{
    c = vf_clamp(c, 0.0f, 1.0f);
    smith_parts l = smith_lambda_parts(h, c);
    if (h->beckmann) /* d / c = 2 / (r sin), so G1 / c = 2 / (2 c + r sin y) */
        return vf_div(vf_set1(2.0f), vf_fma(vf_mul(vf_set1(h->roughness), vf_sqrt(vf_fnma(c, c, vf_set1(1.0f)))),
                                            l.y, vf_add(c, c)));
    vf d_over_c = vf_mul(vf_set1(2.0f), vf_add(vf_sqrt(vf_fma(c, c, l.y)), c)); /* GGX */
    return vf_div(d_over_c, vf_max(vf_add(l.d, l.y), vf_set1(1e-30f)));
}

#endif

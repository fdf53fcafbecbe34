/* Fresnel reflectance at a smooth dielectric interface, shared by the models. */
#ifndef HB_FRESNEL_H
#define HB_FRESNEL_H

#include "math/vmath.h"
#include "dielectric.h"

/* Unpolarised Fresnel reflectance entering a dielectric of index eta > 1, cos_i in [0, 1], with
 * c = cos_i, eta c_t = sqrt(eta^2 - 1 + c^2) (Snell):
 *     r_s = (c - eta c_t) / (c + eta c_t) = -(eta^2 - 1) / (c + eta c_t)^2,
 *     r_p = (eta c - c_t) / (eta c + c_t) = (eta^2 - 1) ((eta^2 + 1) c^2 - 1) / (eta^2 (eta c + c_t)^2),
 * the differences multiplied out so that nothing cancels as eta -> 1 (the direct form loses
 * log10(1 / (eta - 1)) digits: 1e-3 relative at eta 1.0001). */
typedef struct fresnel_sums {
    vf c2, eta_cos_t, sum_s, sum_p; /* cos_i^2, eta c_t, c + eta c_t, eta c + c_t */
} fresnel_sums;

HB_INLINE fresnel_sums fresnel_sums_of(vf cos_i, const hb_dielectric *ior)
{
    fresnel_sums q;
    q.c2 = vf_mul(cos_i, cos_i);
    q.eta_cos_t = vf_sqrt(vf_add(vf_set1(ior->eta2_minus_1), q.c2));
    vf cos_t = vf_mul(q.eta_cos_t, vf_set1(1.0f / ior->eta));
    q.sum_s = vf_add(cos_i, q.eta_cos_t);
    q.sum_p = vf_fma(vf_set1(ior->eta), cos_i, cos_t);
    return q;
}

/* F from its sums: relative-accurate where F is small (eta -> 1, normal incidence). */
HB_INLINE vf fresnel_of_sums(const fresnel_sums *q, const hb_dielectric *ior)
{
    vf rs = vf_div(vf_set1(ior->eta2_minus_1), vf_mul(q->sum_s, q->sum_s));
    vf brewster = vf_fma(vf_set1(ior->eta2_minus_1 + 2.0f), q->c2, vf_set1(-1.0f)); /* (eta^2 + 1) c^2 - 1 */
    vf rp = vf_div(vf_mul(vf_set1(ior->eta2_minus_1 * ior->inv_eta2), brewster), vf_mul(q->sum_p, q->sum_p));
    /* at grazing incidence both ratios are 1 up to rounding: clamped, 1 - F is never negative */
    return vf_min(vf_mul(vf_set1(0.5f), vf_fma(rs, rs, vf_mul(rp, rp))), vf_set1(1.0f));
}

HB_INLINE vf fresnel_dielectric(vf cos_i, const hb_dielectric *ior)
{
    fresnel_sums q = fresnel_sums_of(cos_i, ior);
    return fresnel_of_sums(&q, ior);
}

/* 1 - F without the cancellation of 1 - fresnel_dielectric near grazing incidence (where F -> 1 and
 * its float rounding, 6e-8, would stand for all of 1 - F): 1 - r_s^2 = 4 c (eta c_t) / (c + eta c_t)^2
 * and 1 - r_p^2 = 4 c (eta c_t) / (eta c + c_t)^2, so
 *     1 - F = 2 c (eta c_t) (1 / (c + eta c_t)^2 + 1 / (eta c + c_t)^2),
 * relative-accurate down to c = 0, where it is 0. */
HB_INLINE vf fresnel_complement_of_sums(const fresnel_sums *q, vf cos_i)
{
    vf s2 = vf_mul(q->sum_s, q->sum_s), p2 = vf_mul(q->sum_p, q->sum_p);
    vf twice_c_eta_cos_t = vf_mul(vf_add(cos_i, cos_i), q->eta_cos_t);
    return vf_min(vf_div(vf_mul(twice_c_eta_cos_t, vf_add(s2, p2)), vf_mul(s2, p2)), vf_set1(1.0f));
}

HB_INLINE vf fresnel_dielectric_complement(vf cos_i, const hb_dielectric *ior)
{
    fresnel_sums q = fresnel_sums_of(cos_i, ior);
    return fresnel_complement_of_sums(&q, cos_i);
}

/* F and 1 - F, each relative-accurate: F where it is small, 1 - F as F -> 1 (dFH11's residual near
 * opposite poles, where the light meets the surface at grazing incidence). */
HB_INLINE vf fresnel_dielectric_pair(vf cos_i, const hb_dielectric *ior, vf *one_minus_f)
{
    fresnel_sums q = fresnel_sums_of(cos_i, ior);
    *one_minus_f = fresnel_complement_of_sums(&q, cos_i);
    return fresnel_of_sums(&q, ior);
}

#endif

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
HB_INLINE vf fresnel_dielectric(vf cos_i, const hb_dielectric *ior)
{
    vf c2 = vf_mul(cos_i, cos_i);
    vf eta_cos_t = vf_sqrt(vf_add(vf_set1(ior->eta2_minus_1), c2));
    vf cos_t = vf_mul(eta_cos_t, vf_set1(1.0f / ior->eta));
    vf sum_s = vf_add(cos_i, eta_cos_t), sum_p = vf_fma(vf_set1(ior->eta), cos_i, cos_t);
    vf rs = vf_div(vf_set1(ior->eta2_minus_1), vf_mul(sum_s, sum_s));
    vf brewster = vf_fma(vf_set1(ior->eta2_minus_1 + 2.0f), c2, vf_set1(-1.0f)); /* (eta^2 + 1) c^2 - 1 */
    vf rp = vf_div(vf_mul(vf_set1(ior->eta2_minus_1 * ior->inv_eta2), brewster), vf_mul(sum_p, sum_p));
    /* at grazing incidence both ratios are 1 up to rounding: clamped, 1 - F is never negative */
    return vf_min(vf_mul(vf_set1(0.5f), vf_fma(rs, rs, vf_mul(rp, rp))), vf_set1(1.0f));
}

#endif

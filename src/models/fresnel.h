/* Fresnel reflectance at a smooth dielectric interface, shared by the models. */
#ifndef HB_FRESNEL_H
#define HB_FRESNEL_H

#include "../math/vmath.h"

/* Unpolarised Fresnel reflectance entering a dielectric of index eta > 1, cos_i in [0, 1]. */
HB_INLINE vf fresnel_dielectric(vf cos_i, float eta, float inv_eta2)
{
    vf sin2_t = vf_mul(vf_fnma(cos_i, cos_i, vf_set1(1.0f)), vf_set1(inv_eta2));
    vf cos_t = vf_sqrt(vf_max(vf_sub(vf_set1(1.0f), sin2_t), vf_set1(0.0f)));
    vf eta_cos_t = vf_mul(vf_set1(eta), cos_t), eta_cos_i = vf_mul(vf_set1(eta), cos_i);
    vf rs = vf_div(vf_sub(cos_i, eta_cos_t), vf_add(cos_i, eta_cos_t));
    vf rp = vf_div(vf_sub(eta_cos_i, cos_t), vf_add(eta_cos_i, cos_t));
    return vf_mul(vf_set1(0.5f), vf_fma(rs, rs, vf_mul(rp, rp)));
}

#endif

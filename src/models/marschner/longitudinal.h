/* MJC03 longitudinal part over the SIMD vocabulary: f = sum_p M_p N_p cos(theta_i) / cos^2(theta_d)
 * (docs/conventions.md), M_p = g(alpha_p, beta_p; theta_h) the unit-area Gaussian (MJC03, the
 * survey's M_p and g). The longitudinal term is T = M_R cos(theta_i) / cos^2(theta_d). */
#ifndef HB_MARSCHNER_LONGITUDINAL_H
#define HB_MARSCHNER_LONGITUDINAL_H

#include "math/vmath.h"
#include "models/common/inclination.h"
#include "constants.h"

/* 1/cos^2(theta_d) diverges (integrably) where theta_i -> -pi/2 and theta_o -> pi/2 together;
 * cos^2(theta_d) is floored so the term stays finite. */
#define HB_MJC_COS2_THETA_D_FLOOR 1e-8f

/* M_p = g(alpha_p, beta_p; theta_h), the unit-area Gaussian (MJC03 sec. 4.2), as norm 2^-(x^2 log2(e) / (2 beta^2)). */
HB_INLINE vf gaussian_marschner(const hb_gaussian_lobe *lobe, vf theta_h)
{
    vf x = vf_sub(theta_h, vf_set1(lobe->mean));
    return vf_mul(vf_exp2_neg(vf_mul(vf_mul(x, x), vf_set1(lobe->log2e_over_two_beta2))), vf_set1(lobe->norm));
}

/* cos(theta_i) / cos^2(theta_d), the factor every lobe shares (docs/conventions.md). */
HB_INLINE vf projection_marschner(vf cos_theta_i, vf cos_theta_d)
{
    vf cos2_d = vf_max(vf_mul(cos_theta_d, cos_theta_d), vf_set1(HB_MJC_COS2_THETA_D_FLOOR));
    return vf_div(vf_max(cos_theta_i, vf_set1(0.0f)), cos2_d);
}

/* g(alpha, beta; theta_h) cos(theta_i) / cos^2(theta_d) from the half and difference angles. */
HB_INLINE vf longitudinal_marschner(const hb_gaussian_lobe *lobe, vf theta_h, vf cos_theta_i, vf cos_theta_d)
{
    return vf_mul(gaussian_marschner(lobe, theta_h), projection_marschner(cos_theta_i, cos_theta_d));
}

HB_INLINE vf longitudinal_marschner_angles(const hb_gaussian_lobe *lobe, vf theta_i, vf theta_o)
{
    vf theta_h = vf_mul(vf_set1(0.5f), vf_add(theta_i, theta_o));
    return longitudinal_marschner(lobe, theta_h, cos_near_pole(theta_i, vf_set1(HB_PIO2_LO)),
                                  cos_half_difference(theta_o, theta_i));
}

/* From unit vectors: the inclinations theta_i, theta_o (atan2 of the tangent component over the
 * planar one) and cos(theta_i), and the planar lengths for the azimuths. */
typedef struct mjc_inclinations {
    vf theta_i, theta_o, cos_theta_i, planar_i, planar_o;
} mjc_inclinations;

HB_INLINE mjc_inclinations inclinations_of_vectors(const vf wi[3], const vf wo[3])
{
    mjc_inclinations n;
    n.planar_i = vf_sqrt(vf_fma(wi[0], wi[0], vf_mul(wi[2], wi[2])));
    n.planar_o = vf_sqrt(vf_fma(wo[0], wo[0], vf_mul(wo[2], wo[2])));
    n.theta_i = vf_atan2(wi[1], n.planar_i);
    n.theta_o = vf_atan2(wo[1], n.planar_o);
    n.cos_theta_i = vf_div(n.planar_i, vf_sqrt(vf_fma(wi[1], wi[1], vf_mul(n.planar_i, n.planar_i))));
    return n;
}

HB_INLINE vf longitudinal_marschner_vectors(const hb_gaussian_lobe *lobe, const vf wi[3], const vf wo[3])
{
    mjc_inclinations n = inclinations_of_vectors(wi, wo);
    return longitudinal_marschner(lobe, vf_mul(vf_set1(0.5f), vf_add(n.theta_i, n.theta_o)), n.cos_theta_i,
                                  cos_half_difference(n.theta_o, n.theta_i));
}

#endif

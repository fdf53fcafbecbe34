/* MJC03 importance sampling and its pdf (docs/sampling.md): a defensive mixture whose density is
 * exact for what it draws. Given w_o and three uniform numbers:
 *  1. u0 picks lobe p with the plan's probability P_p (its attenuation at normal incidence, every
 *     lobe at least a tenth of the largest);
 *  2. u1 draws theta_i from M_p exactly: theta_h ~ g(alpha_p, beta_p) makes theta_i = 2 theta_h -
 *     theta_o a Gaussian of mean 2 alpha_p - theta_o and width 2 beta_p, cut to [-pi/2, pi/2] by the
 *     inverse of its distribution function (mass Z_p(theta_o) inside);
 *  3. u2 picks, with probability 1 - HB_MJC_UNIFORM_SHARE, an offset h uniform in [-1, 1] whose exit
 *     azimuth phi = phi_hat(p, asin h) is the cubic of the survey's N_p at theta_d (the fibre's mean
 *     index), else phi uniform.
 * Drawing h uniformly makes phi's density the unattenuated root sum D_p(phi) = sum over the roots of
 * cos(gamma) / (2 |phi_hat'(gamma)|) (N_p with A = 1), which the caustics' fade and glint and the
 * attenuation then weigh; the uniform share covers the glint's tails beyond the cubic's range. So
 *     pdf = sum_p P_p M_p(theta_h) / (2 Z_p) ((1 - e) D_p(phi) + e / (2 pi)) / cos(theta_i). */
#ifndef HB_MARSCHNER_SAMPLE_H
#define HB_MARSCHNER_SAMPLE_H

#include "azimuthal.h"

#define HB_MJC_UNIFORM_SHARE 0.1f

/* The standard normal distribution function by A&S 7.1.26 (erfc to 1.5e-7 absolute). */
HB_INLINE vf normal_cdf(vf x)
{
    vf z = vf_mul(vf_abs(x), vf_set1(0.707106781f)), t = vf_div(vf_set1(1.0f), vf_fma(z, vf_set1(0.3275911f), vf_set1(1.0f)));
    vf poly = vf_fma(t, vf_set1(1.061405429f), vf_set1(-1.453152027f));
    poly = vf_fma(t, poly, vf_set1(1.421413741f));
    poly = vf_fma(t, poly, vf_set1(-0.284496736f));
    poly = vf_fma(t, poly, vf_set1(0.254829592f));
    vf tail = vf_mul(vf_set1(0.5f), vf_mul(vf_mul(poly, t), vf_exp(vf_neg(vf_mul(z, z))))); /* Phi(-|x|) */
    return vf_select(vf_lt(x, vf_set1(0.0f)), tail, vf_sub(vf_set1(1.0f), tail));
}

/* theta_i's Gaussian for lobe l at theta_o: its mean, width, and the distribution function at the
 * lower pole; returns its mass Z inside [-pi/2, pi/2]. */
HB_INLINE vf theta_window(const hb_gaussian_lobe *l, vf theta_o, vf *mean, vf *width, vf *below)
{
    *mean = vf_fnma(vf_set1(1.0f), theta_o, vf_set1(2.0f * l->mean));
    *width = vf_set1(2.0f * l->beta);
    vf inv = vf_set1(0.5f / l->beta);
    *below = normal_cdf(vf_mul(vf_sub(vf_set1(-HB_PIO2_F), *mean), inv));
    return vf_max(vf_sub(normal_cdf(vf_mul(vf_sub(vf_set1(HB_PIO2_F), *mean), inv)), *below), vf_set1(1e-30f));
}

/* D_p(phi): the density of phi_hat(p, asin h) for h uniform in [-1, 1] (R: |cos(phi / 2)| / 4). */
HB_INLINE vf root_density(const hb_marschner *m, int p, const mjc_index *ix, vf phi)
{
    if (p == 0)
        return vf_mul(vf_abs(vf_cos(vf_mul(phi, vf_set1(0.5f)))), vf_set1(0.25f));
    vf D[3];
    azimuthal_marschner_roots(m, p, m->folds[p], p == 2 ? m->trt_branches : 1, ix, NULL, phi, D);
    return D[0];
}

/* The pdf at given angles (cos(theta_i) floored where theta_i reaches a pole). */
HB_INLINE vf marschner_pdf_angles(const hb_marschner *m, vf theta_i, vf phi_i, vf theta_o, vf phi_o)
{
    vf theta_h = vf_mul(vf_set1(0.5f), vf_add(theta_i, theta_o));
    vf cos_theta_d = cos_half_difference(theta_o, theta_i);
    vf phi = wrap_angle(vf_sub(phi_o, phi_i)), sum = vf_set1(0.0f);
    for (int p = 0; p < 3; p++) {
        if (!(m->lobes >> p & 1u))
            continue;
        vf mean, width, below;
        vf Z = theta_window(&m->lobe[p], theta_o, &mean, &width, &below);
        mjc_index ix = bravais_index(vf_set1(m->eta2_minus_one), cos_theta_d, p);
        vf azimuthal = vf_fma(vf_set1(1.0f - HB_MJC_UNIFORM_SHARE), root_density(m, p, &ix, phi),
                              vf_set1(HB_MJC_UNIFORM_SHARE / HB_TWO_PI_F));
        vf longitudinal = vf_div(gaussian_marschner(&m->lobe[p], theta_h), vf_add(Z, Z));
        sum = vf_fma(vf_set1(m->lobe_probability[p]), vf_mul(longitudinal, azimuthal), sum);
    }
    return vf_div(sum, vf_max(vf_cos(theta_i), vf_set1(1e-7f)));
}

HB_INLINE void marschner_sample(const hb_marschner *m, vf theta_o, vf phi_o, const vf u[3], vf *theta_i, vf *phi_i,
                                vf *pdf, vf weight[3])
{
    /* 1. the lobe: every lobe's window is formed, the chosen one's kept */
    vf cumulative = vf_set1(0.0f), mean = cumulative, width = cumulative, below = cumulative, Z = vf_set1(1.0f);
    vf lobe = vf_set1(0.0f);
    for (int p = 0; p < 3; p++) {
        if (!(m->lobes >> p & 1u))
            continue;
        vm take = vf_ge(u[0], cumulative); /* true at the first lobe */
        vf mp, wp, bp;
        vf zp = theta_window(&m->lobe[p], theta_o, &mp, &wp, &bp);
        mean = vf_select(take, mp, mean), width = vf_select(take, wp, width);
        below = vf_select(take, bp, below), Z = vf_select(take, zp, Z);
        lobe = vf_select(take, vf_set1((float)p), lobe);
        cumulative = vf_add(cumulative, vf_set1(m->lobe_probability[p]));
    }
    /* 2. theta_i by the inverse of the cut Gaussian's distribution function */
    vf q = vf_clamp(vf_fma(u[1], Z, below), 0.0f, 1.0f);
    *theta_i = vf_clamp(vf_fma(width, vf_normal_quantile(q), mean), -HB_PIO2_F, HB_PIO2_F);
    /* 3. phi: the cubic at an offset h, or uniform */
    vf cos_theta_d = cos_half_difference(theta_o, *theta_i);
    vm uniform = vf_lt(u[2], vf_set1(HB_MJC_UNIFORM_SHARE));
    vf rest = vf_div(vf_sub(u[2], vf_set1(HB_MJC_UNIFORM_SHARE)), vf_set1(1.0f - HB_MJC_UNIFORM_SHARE));
    vf gamma = vf_asin(vf_clamp(vf_fma(rest, vf_set1(2.0f), vf_set1(-1.0f)), -1.0f, 1.0f));
    vf phi = vf_mul(gamma, vf_set1(-2.0f)); /* R */
    for (int p = 1; p < 3; p++) {
        if (!(m->lobes >> p & 1u))
            continue;
        mjc_index ix = bravais_index(vf_set1(m->eta2_minus_one), cos_theta_d, p);
        vf cubic = vf_fma(vf_mul(ix.cubic_a, vf_mul(gamma, gamma)), gamma,
                          vf_fma(ix.cubic_b, gamma, vf_set1((float)p * HB_PI_F)));
        phi = vf_select(vf_eq(lobe, vf_set1((float)p)), cubic, phi);
    }
    phi = vf_select(uniform, vf_fma(vf_div(u[2], vf_set1(HB_MJC_UNIFORM_SHARE)), vf_set1(HB_TWO_PI_F), vf_set1(-HB_PI_F)),
                    wrap_angle(phi));
    *phi_i = wrap_angle(vf_sub(phi_o, phi));
    vf f[3];
    marschner_angles(m, *theta_i, *phi_i, theta_o, phi_o, f);
    *pdf = marschner_pdf_angles(m, *theta_i, *phi_i, theta_o, phi_o);
    sample_weights(*pdf, f, weight);
}

#endif

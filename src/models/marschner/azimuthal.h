/* MJC03 azimuthal scattering N_p and the full model f = sum_p M_p N_p cos(theta_i) / cos^2(theta_d)
 * (docs/conventions.md) over the SIMD vocabulary. Equations are numbered by the survey of
 * the paper's published walk-through ("the survey") and the original paper's sections. Every loop count
 * (roots, branches, Newton steps) is fixed by the plan. */
#ifndef HB_MARSCHNER_AZIMUTHAL_H
#define HB_MARSCHNER_AZIMUTHAL_H

#include "cubic.h"
#include "longitudinal.h"

/* |d phi / d gamma| is floored here: it vanishes only exactly at a caustic, where the caustic
 * fade multiplies the term by zero. */
#define HB_MJC_SLOPE_FLOOR 1e-6f
/* cos(theta_d) floor for eta' = sqrt(eta^2 - sin^2 theta_d) / cos(theta_d) at theta_d = +-pi/2. */
#define HB_MJC_COS_THETA_D_FLOOR 1e-6f

/* The survey's corrected Fresnel F = (F_s(n1s, n2s)^2 + F_t(n1p, n2p)^2) / 2 at an angle of
 * incidence with sine s and cosine c (the survey's "Definition of F"; MJC03 sec. 4.1 and its
 * appendix B): eta' for the perpendicular component, eta'' for the parallel one. Written
 * homogeneously, with k = n2 cos(refracted) = sqrt(n2^2 - n1^2 s^2), so no index is divided by:
 *   F_s = (n1 c - k_s) / (n1 c + k_s),   F_t = (n1 k_p - n2^2 c) / (n1 k_p + n2^2 c),
 * and both ratios over one division. Outside the fibre (n1, n2) = (1, eta'), (1, eta''); inside
 * F(1/eta', 1/eta'', gamma_t) is the same ratio with (eta', 1), (eta'', 1). k = 0 is total
 * reflection; where a ratio is 0/0 (grazing and total at once) it is 1. */
HB_INLINE vf fresnel_bravais(vf n1s, vf n2s, vf n1p, vf n2p, vf s, vf c)
{
    vf s2 = vf_mul(s, s);
    vf ks = vf_sqrt(vf_max(vf_fnma(vf_mul(n1s, n1s), s2, vf_mul(n2s, n2s)), vf_set1(0.0f)));
    vf kp = vf_sqrt(vf_max(vf_fnma(vf_mul(n1p, n1p), s2, vf_mul(n2p, n2p)), vf_set1(0.0f)));
    vf xs = vf_mul(n1s, c), ys = ks, xp = vf_mul(n1p, kp), yp = vf_mul(vf_mul(n2p, n2p), c);
    vf one = vf_set1(1.0f);
    xs = vf_select(vf_gt(vf_add(xs, ys), vf_set1(0.0f)), xs, one);
    xp = vf_select(vf_gt(vf_add(xp, yp), vf_set1(0.0f)), xp, one);
    vf ds = vf_add(xs, ys), dp = vf_add(xp, yp), ns = vf_sub(xs, ys), np = vf_sub(xp, yp);
    vf ds2 = vf_mul(ds, ds), dp2 = vf_mul(dp, dp);
    vf num = vf_fma(vf_mul(ns, ns), dp2, vf_mul(vf_mul(np, np), ds2));
    return vf_div(vf_mul(vf_set1(0.5f), num), vf_mul(ds2, dp2));
}

/* The Bravais indices for one fibre index and the cubic phi_hat(p, gamma) = B gamma + A gamma^3 + p pi. */
typedef struct mjc_index {
    vf eta_perp;  /* eta'  = sqrt(eta^2 - sin^2 theta_d) / cos(theta_d)  (the survey's eta') */
    vf inv_eta_perp;
    vf inv_eta_cos_t; /* 1 / (eta cos(theta_t)) = 1 / sqrt(eta^2 - sin^2 theta_d) */
    vf eta_par;   /* eta'' = eta^2 cos(theta_d) / sqrt(eta^2 - sin^2 theta_d) = eta^2 / eta' */
    vf cubic_a;   /* -8 p c / pi^3, c = asin(1 / eta') */
    vf cubic_b;   /* 6 p c / pi - 2 */
} mjc_index;

/* From eta^2 - 1 (given directly, so eta near 1 keeps its digits) and cos(theta_d):
 * eta^2 - sin^2 theta_d = (eta^2 - 1) + cos^2 theta_d, and c = asin(1/eta') = atan2(cos theta_d,
 * sqrt(eta^2 - 1)), which stays well conditioned as eta' -> 1 where asin does not. */
HB_INLINE mjc_index bravais_index(vf eta2_minus_one, vf cos_theta_d, int p)
{
    mjc_index ix;
    vf cos_d = vf_max(cos_theta_d, vf_set1(HB_MJC_COS_THETA_D_FLOOR));
    vf q2 = vf_fma(cos_d, cos_d, eta2_minus_one), q = vf_sqrt(q2);
    vf inv_q_cos_d = vf_div(vf_set1(1.0f), vf_mul(q, cos_d)); /* one division for eta' and 1/eta' */
    ix.eta_perp = vf_mul(q2, inv_q_cos_d);
    ix.inv_eta_perp = vf_mul(vf_mul(cos_d, cos_d), inv_q_cos_d);
    ix.inv_eta_cos_t = vf_mul(cos_d, inv_q_cos_d);
    ix.eta_par = vf_mul(vf_add(eta2_minus_one, vf_set1(1.0f)), ix.inv_eta_perp);
    vf c = vf_atan2(cos_d, vf_sqrt(eta2_minus_one));
    ix.cubic_a = vf_mul(c, vf_set1(-8.0f * (float)p / 31.0062767f));
    ix.cubic_b = vf_fma(c, vf_set1(6.0f * (float)p / 3.14159265f), vf_set1(-2.0f));
    return ix;
}

/* Everything the attenuation of one sample needs besides the root. */
typedef struct mjc_absorption {
    vf mu_log2e[3]; /* mu_a' log2(e), mu_a' = sigma_a / cos(theta_t) (MJC03 sec. 4.2; theta_t the refracted inclination) */
} mjc_absorption;

/* A(p, h) at gamma_i (the survey's "Finding A"): (1 - F(eta', eta'', gamma_i))^2
 * F(1/eta', 1/eta'', gamma_t)^(p - 1) T^p, with T the transmittance of one traversal,
 * exp(-mu_a' 2 cos gamma_t) (docs/conventions.md) or the printed exp(-mu_a' (2 + 2 cos 2 gamma_t)). */
HB_INLINE void attenuation_marschner(const hb_marschner *m, int p, const mjc_index *ix, const mjc_absorption *ab,
                                     vf sin_gi, vf cos_gi, vf out[3])
{
    vf one = vf_set1(1.0f);
    vf fe = fresnel_bravais(one, ix->eta_perp, one, ix->eta_par, sin_gi, cos_gi);
    vf sin_gt = vf_mul(sin_gi, ix->inv_eta_perp);
    vf cos_gt = vf_sqrt(vf_max(vf_fnma(sin_gt, sin_gt, one), vf_set1(0.0f)));
    vf base = vf_mul(vf_sub(one, fe), vf_sub(one, fe));
    if (p == 2)
        base = vf_mul(base, fresnel_bravais(ix->eta_perp, one, ix->eta_par, one, sin_gt, cos_gt));
    vf path = m->absorption_paper ? vf_mul(vf_set1(4.0f), vf_mul(cos_gt, cos_gt)) : vf_add(cos_gt, cos_gt);
    path = vf_mul(path, vf_set1((float)p));
    for (int c = 0; c < 3; c++)
        out[c] = vf_mul(base, vf_exp2_neg(vf_mul(ab->mu_log2e[c], path)));
}

/* N_R = F(eta', eta'', gamma_i) |cos(phi / 2)| / 4 at gamma_i = -phi / 2 (p = 0 of the survey's N_p). */
HB_INLINE vf azimuthal_marschner_r(const mjc_index *ix, vf phi)
{
    vf s, c;
    vf_sincos(vf_mul(phi, vf_set1(-0.5f)), &s, &c);
    vf one = vf_set1(1.0f);
    return vf_mul(fresnel_bravais(one, ix->eta_perp, one, ix->eta_par, s, c), vf_mul(vf_abs(c), vf_set1(0.25f)));
}

/* phi - p pi wrapped to [-pi, pi], for phi in [-pi, pi], so that -phi gives exactly its negative:
 * phi itself for even p, phi -+ pi (pi split in two floats) for odd p. */
HB_INLINE vf centre_on_lobe(vf phi, int p)
{
    if (p % 2 == 0)
        return phi;
    vf hi = vf_copysign(vf_set1(HB_PI_F), phi), lo = vf_copysign(vf_set1(HB_PI_LO), phi);
    return vf_sub(vf_sub(phi, hi), lo);
}

/* sum over the roots gamma_i of phi_hat(p, gamma_i) = phi + 2 pi k of A(p, h) |2 d phi_hat / dh|^-1
 * (the survey's N_p), for the plan's branches k; with ab NULL, A = 1 into N[0] alone. */
HB_INLINE void azimuthal_marschner_roots(const hb_marschner *m, int p, int all_three, int branches,
                                         const mjc_index *ix, const mjc_absorption *ab, vf phi, vf N[3])
{
    vf inv_a = vf_div(vf_set1(1.0f), ix->cubic_a);
    vf P = vf_mul(ix->cubic_b, inv_a);
    vf target = centre_on_lobe(phi, p); /* phi_hat - p pi = target + 2 pi k */
    N[0] = N[1] = N[2] = vf_set1(0.0f);
    for (int k = -(branches / 2); k <= branches / 2; k++) {
        vf Q = vf_mul(vf_neg(vf_add(target, vf_set1(HB_TWO_PI_F * (float)k))), inv_a);
        vf root[3];
        vm real[3];
        cubic_roots(P, Q, all_three, root, real);
        for (int r = 0; r < (all_three ? 3 : 1); r++) {
            vm inside = vm_and(real[r], vf_le(vf_abs(root[r]), vf_set1(HB_PIO2_F + 1e-6f)));
            vf gamma = vf_keep(inside, vf_min(vf_max(root[r], vf_set1(-HB_PIO2_F)), vf_set1(HB_PIO2_F)));
            vf s, c;
            vf_sincos(gamma, &s, &c);
            /* |2 d phi / dh|^-1 = cos(gamma) / (2 |d phi_hat / d gamma|), d phi_hat / d gamma = B + 3 A gamma^2 */
            vf slope = vf_abs(vf_fma(vf_mul(vf_set1(3.0f), ix->cubic_a), vf_mul(gamma, gamma), ix->cubic_b));
            vf weight = vf_div(vf_max(c, vf_set1(0.0f)), vf_mul(vf_set1(2.0f), vf_max(slope, vf_set1(HB_MJC_SLOPE_FLOOR))));
            weight = vf_keep(inside, weight);
            if (!ab) { /* the roots' density alone (sample.h) */
                N[0] = vf_add(N[0], weight);
                continue;
            }
            vf A[3];
            attenuation_marschner(m, p, ix, ab, s, c, A);
            for (int ch = 0; ch < 3; ch++)
                N[ch] = vf_fma(weight, A[ch], N[ch]);
        }
    }
}

/* MJC03's caustic treatment (sec. 4.3; parameters in hb_material): where the cubic folds, at
 * gamma_c with phi_hat'(gamma_c) = 0 and phi_hat(gamma_c) = p pi +- phi_c, N_p is faded out
 * by (1 - t G(phi - phi_c)) (1 - t G(phi + phi_c)), G the Gaussian of width w_c with peak 1,
 * and the glint t k_G A(p, h_c) dh g(w_c; .) is added at both caustics, with
 * dh = min(dh_M, 2 sqrt(2 w_c / |d^2 phi / dh^2 (h_c)|)). Past the fold index
 * eta' = 1 / sin(pi / 3p) (2 for TRT, where 6pc/pi = 2) there is no caustic: h_c = 0, dh = dh_M,
 * and t falls from 1 to 0 over eta' in [2, 2 + Delta eta'] (smoothstep). TT folds only for
 * eta' < 2/sqrt(3) (eta near 1); it gets the same treatment, which MJC03 did not need. */
HB_INLINE void caustic_marschner(const hb_marschner *m, int p, const mjc_index *ix, const mjc_absorption *ab, vf phi,
                                 vf N[3])
{
    vf b = vf_max(ix->cubic_b, vf_set1(0.0f));
    vf gamma_c = vf_sqrt(vf_div(b, vf_mul(vf_set1(-3.0f), ix->cubic_a)));
    vf phi_c = vf_mul(vf_set1(2.0f / 3.0f), vf_mul(b, gamma_c));
    vf s, c;
    vf_sincos(gamma_c, &s, &c);
    /* d^2 phi / dh^2 at the fold = phi_hat''(gamma_c) / cos^2(gamma_c), phi_hat'' = 6 A gamma */
    vf curvature = vf_abs(vf_div(vf_mul(vf_mul(vf_set1(6.0f), ix->cubic_a), gamma_c), vf_mul(c, c)));
    vf dh = vf_sqrt(vf_div(vf_set1(2.0f * m->caustic_width), vf_max(curvature, vf_set1(1e-30f))));
    dh = vf_min(vf_add(dh, dh), vf_set1(m->caustic_limit));
    vf x = vf_mul(vf_sub(ix->eta_perp, vf_set1(m->fold_index[p])), vf_set1(m->inv_caustic_fade));
    x = vf_min(vf_max(x, vf_set1(0.0f)), vf_set1(1.0f));
    vf t = vf_fnma(vf_mul(x, x), vf_fnma(vf_set1(2.0f), x, vf_set1(3.0f)), vf_set1(1.0f)); /* 1 - smoothstep */
    vf centred = centre_on_lobe(phi, p);
    vf d_plus = wrap_angle(vf_sub(centred, phi_c)), d_minus = wrap_angle(vf_add(centred, phi_c));
    vf u_plus = vf_mul(vf_mul(d_plus, d_plus), vf_set1(m->caustic_log2e_over_two_w2));
    vf u_minus = vf_mul(vf_mul(d_minus, d_minus), vf_set1(m->caustic_log2e_over_two_w2));
    vf g_plus = vf_exp2_neg(u_plus), g_minus = vf_exp2_neg(u_minus);
    /* 1 - t G = (1 - t) + t (1 - G): two non-negative terms, 1 - G without cancellation at the caustic */
    vf one_minus_t = vf_sub(vf_set1(1.0f), t);
    vf fade = vf_mul(vf_fma(t, vf_one_minus_exp2_neg(u_plus, g_plus), one_minus_t),
                     vf_fma(t, vf_one_minus_exp2_neg(u_minus, g_minus), one_minus_t));
    vf A[3];
    attenuation_marschner(m, p, ix, ab, s, c, A);
    vf glint = vf_mul(vf_mul(t, vf_set1(m->glint_scale * m->caustic_norm)), vf_mul(dh, vf_add(g_plus, g_minus)));
    for (int ch = 0; ch < 3; ch++)
        N[ch] = vf_fma(glint, A[ch], vf_mul(N[ch], fade));
}

/* Per-sample geometry. */
typedef struct mjc_geometry {
    vf theta_h, cos_theta_i, cos_theta_d;
    vf phi;         /* phi_o - phi_i in [-pi, pi] */
    vf cos_phi_sum; /* cos(phi_i + phi_o) = cos(2 phi_h), for eta* */
    vf absorption[3]; /* sigma_a log2(e) per channel: the plan's, or each sample's (hb_eval_angles_absorption) */
} mjc_geometry;

HB_INLINE void marschner_plan_absorption(const hb_marschner *m, mjc_geometry *g)
{
    for (int c = 0; c < 3; c++)
        g->absorption[c] = vf_set1(m->sigma_a_log2e[c]);
}

/* f = sum_p M_p N_p cos(theta_i) / cos^2(theta_d) for the plan's lobes. */
HB_INLINE void marschner_f(const hb_marschner *m, const mjc_geometry *g, vf out[3])
{
    vf eta2_minus_one = vf_set1(m->eta2_minus_one);
    mjc_index ix = bravais_index(eta2_minus_one, g->cos_theta_d, 1);
    mjc_absorption ab;
    vf inv_cos_theta_t = vf_mul(vf_set1(m->eta), ix.inv_eta_cos_t); /* no cancellation as eta -> 1 */
    for (int c = 0; c < 3; c++)
        ab.mu_log2e[c] = vf_min(vf_mul(g->absorption[c], inv_cos_theta_t), vf_set1(8e37f));
    for (int c = 0; c < 3; c++)
        out[c] = vf_set1(0.0f);
    if (m->lobes & 1u) {
        vf mn = vf_mul(gaussian_marschner(&m->lobe[0], g->theta_h), azimuthal_marschner_r(&ix, g->phi));
        for (int c = 0; c < 3; c++)
            out[c] = mn;
    }
    if (m->lobes & 2u) {
        vf N[3];
        azimuthal_marschner_roots(m, 1, m->folds[1], 1, &ix, &ab, g->phi, N);
        if (m->caustic[1])
            caustic_marschner(m, 1, &ix, &ab, g->phi, N);
        vf M = gaussian_marschner(&m->lobe[1], g->theta_h);
        for (int c = 0; c < 3; c++)
            out[c] = vf_fma(M, N[c], out[c]);
    }
    if (m->lobes & 4u) {
        if (m->eccentric) { /* eta*(phi_h) = (eta1 + eta2)/2 + cos(2 phi_h) (eta1 - eta2)/2 (MJC03 sec. 4.4) */
            vf excess = vf_fma(g->cos_phi_sum, vf_set1(m->eta_star_swing), vf_set1(m->eta_star_excess));
            excess = vf_max(excess, vf_set1(1e-4f)); /* eta* >= 1.0001 */
            ix = bravais_index(vf_mul(excess, vf_add(excess, vf_set1(2.0f))), g->cos_theta_d, 2);
        } else {
            ix = bravais_index(eta2_minus_one, g->cos_theta_d, 2);
        }
        vf N[3];
        azimuthal_marschner_roots(m, 2, m->folds[2], m->trt_branches, &ix, &ab, g->phi, N);
        if (m->caustic[2])
            caustic_marschner(m, 2, &ix, &ab, g->phi, N);
        vf M = gaussian_marschner(&m->lobe[2], g->theta_h);
        for (int c = 0; c < 3; c++)
            out[c] = vf_fma(M, N[c], out[c]);
    }
    vf projection = projection_marschner(g->cos_theta_i, g->cos_theta_d);
    for (int c = 0; c < 3; c++)
        out[c] = vf_mul(out[c], projection);
}

HB_INLINE void marschner_geometry_angles(const hb_marschner *m, vf theta_i, vf phi_i, vf theta_o, vf phi_o,
                                         mjc_geometry *g)
{
    g->theta_h = vf_mul(vf_set1(0.5f), vf_add(theta_i, theta_o));
    g->cos_theta_i = vf_cos(theta_i);
    g->cos_theta_d = cos_half_difference(theta_o, theta_i);
    g->phi = wrap_angle(vf_sub(phi_o, phi_i));
    g->cos_phi_sum = m->eccentric ? vf_cos(wrap_angle(vf_add(phi_i, phi_o))) : vf_set1(1.0f);
    marschner_plan_absorption(m, g);
}

HB_INLINE void marschner_angles(const hb_marschner *m, vf theta_i, vf phi_i, vf theta_o, vf phi_o, vf out[3])
{
    mjc_geometry g;
    marschner_geometry_angles(m, theta_i, phi_i, theta_o, phi_o, &g);
    marschner_f(m, &g, out);
}

HB_INLINE void marschner_vectors(const hb_marschner *m, const vf wi[3], const vf wo[3], vf out[3])
{
    mjc_geometry g;
    mjc_inclinations n = inclinations_of_vectors(wi, wo);
    g.theta_h = vf_mul(vf_set1(0.5f), vf_add(n.theta_i, n.theta_o));
    g.cos_theta_i = n.cos_theta_i;
    g.cos_theta_d = cos_half_difference(n.theta_o, n.theta_i);
    /* phi = phi_o - phi_i and cos(phi_i + phi_o) from the planar components */
    g.phi = azimuth_difference(wi, wo);
    /* a direction along the fibre has azimuth 0 (planar_z): its planar part (0, 1), of length 1 */
    vf zi = planar_z(wi), zo = planar_z(wo);
    vf planar2 = vf_mul(vf_max(n.planar_i, vf_abs(zi)), vf_max(n.planar_o, vf_abs(zo)));
    vf cos_sum = vf_div(vf_fnma(wi[0], wo[0], vf_mul(zi, zo)), vf_max(planar2, vf_set1(1e-30f)));
    g.cos_phi_sum = vf_select(vf_gt(planar2, vf_set1(1e-30f)), cos_sum, vf_set1(1.0f));
    marschner_plan_absorption(m, &g);
    marschner_f(m, &g, out);
}

#endif

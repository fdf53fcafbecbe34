/* dFH11 importance sampling and its pdf over the SIMD vocabulary (docs/sampling.md).
 *
 * Given w_o and five uniform numbers:
 *  1. u0 picks an M_p group g with probability c_g(theta_o) (the plan's table), u1 and u2 draw
 *     theta_i from that M_p exactly: eq. 7 is a von Mises-Fisher distribution of concentration
 *     1/v about the mirror direction averaged over a circle, so theta_i is the inclination of a
 *     vMF sample, 1 - cos(psi) = -v log(u1 + (1 - u1) e^(-2/v)) at azimuth 2 pi u2 about it;
 *  2. u3 picks a quadrature node j with probability weight_j / sum(weight), and, rescaled, a lobe p
 *     with probability proportional to m_p = M_p(theta_i) A(p, h_j) (channel mean), and a side;
 *  3. u4 draws phi from lobe p's Gaussian detector about +-Phi(p, h_j) (a Gaussian, wrapped), or
 *     uniformly for the residual.
 * Its density per solid angle, which hb_pdf_angles returns, is
 *     pdf = (sum_g c_g M_g(theta_i)) sum_j P(j) sum_p m_pj (D_p(phi - Phi_pj) + D_p(-phi - Phi_pj)) / (2 sum_p m_pj),
 * the same node rule as eval, so for a lossless fibre whose lobes share one M_p it equals f / E
 * exactly and every weight f / pdf is the furnace value E(w_o). */
#ifndef HB_DEON_SAMPLE_H
#define HB_DEON_SAMPLE_H

#include "near.h"

/* c_g(theta_o) by linear interpolation of the plan's table in |theta_o|; returns their sum. */
HB_INLINE vf deon_lobe_choice_at(const hb_deon *d, vf theta_o, vf c[HB_MAX_LOBES + 1])
{
    vf x = vf_mul(vf_min(vf_abs(theta_o), vf_set1(HB_PIO2_F)), vf_set1((float)HB_LOBE_CHOICE_STEPS / HB_PIO2_F));
    vf k = vf_min(vf_floor(x), vf_set1((float)HB_LOBE_CHOICE_STEPS));
    vf t = vf_sub(x, k);
    vi index = vi_from_vf(k);
    vf total = vf_set1(0.0f);
    for (int group = 0; group < d->groups; group++) {
        const int p = d->group_leader[group];
        vf lo = vf_gather(d->lobe_choice[p], index), hi = vf_gather(d->lobe_choice[p] + 1, index);
        c[p] = vf_fma(t, vf_sub(hi, lo), lo);
        total = vf_add(total, c[p]);
    }
    return total;
}

/* The density of step 1's theta_i (the mixture sum_g c_g M_g / sum_g c_g) from M of every group. */
HB_INLINE vf deon_theta_density(const hb_deon *d, const vf M[HB_MAX_LOBES + 1], vf theta_o)
{
    vf c[HB_MAX_LOBES + 1];
    vf c_total = deon_lobe_choice_at(d, theta_o, c), mixture = vf_set1(0.0f);
    for (int group = 0; group < d->groups; group++)
        mixture = vf_fma(c[d->group_leader[group]], M[d->group_leader[group]], mixture);
    return vf_div(mixture, c_total);
}

/* M_g(theta_i, theta_o) for every group leader g (the other lobes' entries are not read). */
HB_INLINE void deon_longitudinal_groups(const hb_deon *d, vf theta_i, vf theta_o, hb_i0 i0, vf M[HB_MAX_LOBES + 1])
{
    longitudinal_deon_groups_angles(d, theta_i, theta_o, i0, M);
}

/* Step 1: theta_i from the mixture sum_g c_g M_g (c normalised by their sum); *rest gets u[0]'s
 * remainder within the chosen group's share, a uniform number independent of the choice. */
HB_INLINE vf deon_sample_theta(const hb_deon *d, const vf c[HB_MAX_LOBES + 1], vf c_total, vf theta_o,
                               const vf u[3], vf *rest)
{
    vf target = vf_mul(u[0], c_total), cumulative = vf_set1(0.0f), below = cumulative, share = vf_set1(1.0f);
    vf v = vf_set1(0.0f), e2 = v, cos_shift = v, sin_shift = v;
    for (int group = 0; group < d->groups; group++) {
        const int p = d->group_leader[group];
        const hb_longitudinal *l = &d->longitudinal[p];
        vm take = vf_ge(target, cumulative); /* true at the first group: target >= 0 */
        v = vf_select(take, vf_set1((float)(1.0 / l->inv_v)), v);
        e2 = vf_select(take, vf_set1(d->exp_minus_two_inv_v[p]), e2);
        cos_shift = vf_select(take, vf_set1((float)l->cos_shift), cos_shift);
        sin_shift = vf_select(take, vf_set1((float)l->sin_shift), sin_shift);
        below = vf_select(take, cumulative, below);
        share = vf_select(take, c[p], share);
        cumulative = vf_add(cumulative, c[p]);
    }
    if (rest)
        *rest = vf_clamp(vf_div(vf_sub(target, below), vf_max(share, vf_set1(1e-37f))), 0.0f, 0.99999994f);
    return longitudinal_sample(v, e2, cos_shift, sin_shift, theta_o, u[1], u[2]);
}

/* Step 2 at one node (h = sin gamma_i >= 0): the lobe, in proportion to m_p = M_p A(p, h) (the mean
 * over `channels` channels of g's absorptions; g: cos_theta_d and the absorptions), picked by u in
 * [0, 1); returns u's remainder within the lobe's share, and the lobe's exit azimuth Phi, detector
 * width beta and whether it is the residual. */
HB_INLINE vf deon_pick_lobe_of(const hb_deon *d, const vf M[HB_MAX_LOBES + 1], const deon_geometry *g, int channels,
                               vf h, vf gamma_i, vf cos_gamma_i, vf u, vf *Phi, vf *beta, vm *residual)
{
    deon_medium medium;
    deon_medium_of(d, g, &medium, channels);
    deon_node node;
    deon_node_lobes(d, &medium, h, gamma_i, cos_gamma_i, &node, (deon_shape){ 0, channels, 0 });
    vf mass[HB_MAX_LOBES + 1], total = vf_set1(0.0f);
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        if (!hb_deon_lobe_on(d, p))
            continue;
        mass[p] = vf_mul(M[d->m_group[p]], deon_channel_mean(node.A[p], channels));
        total = vf_add(total, mass[p]);
    }
    vf target = vf_mul(u, total), below = vf_set1(0.0f), cumulative = vf_set1(0.0f), chosen_mass = vf_set1(1.0f);
    *Phi = vf_set1(0.0f);
    *beta = vf_set1(0.0f);
    *residual = vf_lt(total, vf_set1(0.0f)); /* false */
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        if (!hb_deon_lobe_on(d, p))
            continue;
        vm take = vf_ge(target, cumulative);
        below = vf_select(take, cumulative, below);
        chosen_mass = vf_select(take, mass[p], chosen_mass);
        if (p == HB_LOBE_RESIDUAL) {
            *residual = take;
        } else {
            *Phi = vf_select(take, node.paths.Phi[p], *Phi);
            *beta = vf_select(take, vf_set1(d->beta_n[p]), *beta);
            *residual = vm_andnot(*residual, take);
        }
        cumulative = vf_add(cumulative, mass[p]);
    }
    return vf_div(vf_sub(target, below), vf_max(chosen_mass, vf_set1(1e-37f)));
}

/* The same at the plan's own absorption (RGB). */
HB_STAGE vf deon_pick_lobe(const hb_deon *d, const vf M[HB_MAX_LOBES + 1], vf theta_i, vf theta_o, vf h, vf gamma_i,
                           vf cos_gamma_i, vf u, vf *Phi, vf *beta, vm *residual)
{
    deon_geometry g;
    g.cos_theta_d = cos_half_difference(theta_o, theta_i);
    deon_plan_absorption(d, &g);
    return deon_pick_lobe_of(d, M, &g, 3, h, gamma_i, cos_gamma_i, u, Phi, beta, residual);
}

/* Step 3: phi from the lobe's detector about its exit azimuth on the chosen side, D_p(phi - Phi)
 * (or D_p(-phi - Phi) on the negative side: a Gaussian, wrapped), or uniformly for the residual. */
HB_INLINE vf deon_draw_phi(vf Phi, vf beta, vm residual, vm negative_side, vf u)
{
    vf spread = vf_select(residual, vf_mul(vf_fnma(vf_set1(-2.0f), u, vf_set1(-1.0f)), vf_set1(HB_PI_F)),
                          vf_fma(beta, vf_normal_quantile(u), Phi));
    return wrap_angle(vf_select(negative_side, vf_neg(spread), spread));
}

/* Steps 2 and 3 in the far field: phi = phi_o - phi_i given theta_i. u[0] picks the node by the
 * plan's cumulative weights, then, rescaled, the lobe, then, rescaled again, the side. */
HB_STAGE vf deon_sample_phi(const hb_deon *d, const vf M[HB_MAX_LOBES + 1], vf theta_i, vf theta_o, const vf u[2])
{
    vf lo = vf_set1(0.0f), hi = vf_set1(d->node_cdf[0]);
    vf h = vf_set1(d->h[0]), gamma_i = vf_set1(d->gamma_i[0]), cos_gamma_i = vf_set1(d->cos_gamma_i[0]);
    for (int j = 1; j < d->nodes; j++) {
        vm past = vf_ge(u[0], vf_set1(d->node_cdf[j - 1]));
        lo = vf_select(past, vf_set1(d->node_cdf[j - 1]), lo);
        hi = vf_select(past, vf_set1(d->node_cdf[j]), hi);
        h = vf_select(past, vf_set1(d->h[j]), h);
        gamma_i = vf_select(past, vf_set1(d->gamma_i[j]), gamma_i);
        cos_gamma_i = vf_select(past, vf_set1(d->cos_gamma_i[j]), cos_gamma_i);
    }
    vf within = vf_clamp(vf_div(vf_sub(u[0], lo), vf_sub(hi, lo)), 0.0f, 0.99999994f);
    vf Phi, beta;
    vm residual;
    vf side = deon_pick_lobe(d, M, theta_i, theta_o, h, gamma_i, cos_gamma_i, within, &Phi, &beta, &residual);
    return deon_draw_phi(Phi, beta, residual, vf_lt(side, vf_set1(0.5f)), u[1]);
}

/* f (RGB) and the sampling pdf at given angles; M: each group's M_p at these angles. one: a single
 * sample fills the lanes (deon_fused_one, standard plans). */
HB_STAGE vf deon_f_pdf_of(const hb_deon *d, const vf M[HB_MAX_LOBES + 1], const deon_geometry *g, vf theta_o,
                          vf out[3], int one)
{
    deon_pdf_terms terms = { M, vf_set1(0.0f) };
    if (d->standard && one) {
        deon_fused_one(d, g, M, out, &terms);
    } else if (d->standard) { /* f as hb_eval computes it (azimuthal.h, deon_eval), so weight = f / pdf */
        deon_fused(d, g, M, out, &terms);
    } else {
        vf N[HB_MAX_LOBES + 1][3];
        azimuthal_deon(d, g, N, &terms);
        out[0] = out[1] = out[2] = vf_set1(0.0f);
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            if (hb_deon_lobe_on(d, p))
                for (int k = 0; k < 3; k++)
                    out[k] = vf_fma(M[d->m_group[p]], N[p][k], out[k]);
    }
    return vf_mul(deon_theta_density(d, M, theta_o), terms.sum);
}

HB_INLINE vf deon_f_pdf(const hb_deon *d, const vf M[HB_MAX_LOBES + 1], const deon_geometry *g, vf theta_o, vf out[3])
{
    return deon_f_pdf_of(d, M, g, theta_o, out, 0);
}

/* The pdf alone, from angles. */
HB_INLINE vf deon_pdf_angles(const hb_deon *d, vf theta_i, vf phi_i, vf theta_o, vf phi_o, hb_i0 i0)
{
    vf M[HB_MAX_LOBES + 1], f[3];
    deon_longitudinal_groups(d, theta_i, theta_o, i0, M);
    deon_geometry g;
    deon_geometry_angles(d, theta_i, phi_i, theta_o, phi_o, &g);
    return deon_f_pdf(d, M, &g, theta_o, f);
}

/* One sample: theta_i, phi_i, the pdf and the weight f / pdf (0 where the pdf is 0). */
HB_INLINE void deon_sample(const hb_deon *d, vf theta_o, vf phi_o, const vf u[5], hb_i0 i0, vf *theta_i, vf *phi_i,
                           vf *pdf, vf weight[3])
{
    vf c[HB_MAX_LOBES + 1], M[HB_MAX_LOBES + 1], f[3];
    vf c_total = deon_lobe_choice_at(d, theta_o, c);
    *theta_i = deon_sample_theta(d, c, c_total, theta_o, u, NULL);
    deon_longitudinal_groups(d, *theta_i, theta_o, i0, M);
    *phi_i = wrap_angle(vf_sub(phi_o, deon_sample_phi(d, M, *theta_i, theta_o, u + 3)));
    deon_geometry g;
    deon_geometry_angles(d, *theta_i, *phi_i, theta_o, phi_o, &g);
    *pdf = deon_f_pdf(d, M, &g, theta_o, f);
    sample_weights(*pdf, f, weight);
}

/* The near field at offset h (near.h) reads four numbers: u[0] picks the M_p group and theta_i
 * from it with u[1], u[2] as in the far field, u[0]'s remainder picks the lobe in proportion to
 * m_p = M_p A(p, h), and u[3] draws phi from its detector on h's side. Its density is
 *     pdf = (sum_g c_g M_g(theta_i)) sum_p m_p D_p(+-phi - Phi(p, |h|)) / sum_p m_p,
 * which near.h's pdf term forms with f. */
HB_INLINE vf deon_near_f_pdf(const hb_deon *d, const vf M[HB_MAX_LOBES + 1], const deon_geometry *g, vf theta_o,
                             vf h, vf f[3])
{
    vf azimuthal;
    deon_near(d, g, M, h, f, &azimuthal);
    return vf_mul(deon_theta_density(d, M, theta_o), azimuthal);
}

/* The same at a spectral call's k wavelengths, g's absorptions: m_p averages A(p, h) over the k, as
 * pbrt-v4's HairBxDF::Sample_f chooses its lobe (f: k planes, at least three). */
HB_INLINE vf deon_near_f_pdf_spectral(const hb_deon *d, const vf M[HB_MAX_LOBES + 1], const deon_geometry *g,
                                      vf theta_o, vf h, int channels, vf *f)
{
    vf azimuthal;
    deon_near_spectral(d, g, M, h, channels, f, &azimuthal);
    return vf_mul(deon_theta_density(d, M, theta_o), azimuthal);
}

/* One near-field sample: at the plan's absorption (RGB) where absorption is NULL, else at a spectral
 * call's `channels` wavelengths of absorptions sigma_a log2(e), the lobe chosen by their mean
 * attenuation; weight: f / pdf per channel. */
HB_INLINE void deon_sample_near_of(const hb_deon *d, int channels, const vf *absorption, vf theta_o, vf phi_o, vf h,
                                   const vf u[4], hb_i0 i0, vf *theta_i, vf *phi_i, vf *pdf, vf *weight)
{
    vf c[HB_MAX_LOBES + 1], M[HB_MAX_LOBES + 1], f[HB_DEON_CHANNELS], rest, Phi, beta, cos_gamma_i;
    vf c_total = deon_lobe_choice_at(d, theta_o, c);
    *theta_i = deon_sample_theta(d, c, c_total, theta_o, u, &rest);
    deon_longitudinal_groups(d, *theta_i, theta_o, i0, M);
    vf a = near_offset(h, &cos_gamma_i);
    vm residual;
    deon_geometry g;
    if (absorption) {
        g.cos_theta_d = cos_half_difference(theta_o, *theta_i);
        deon_spectral_absorption(&g, channels, absorption);
        deon_pick_lobe_of(d, M, &g, channels, a, vf_asin(a), cos_gamma_i, rest, &Phi, &beta, &residual);
    } else {
        deon_pick_lobe(d, M, *theta_i, theta_o, a, vf_asin(a), cos_gamma_i, rest, &Phi, &beta, &residual);
    }
    vf phi = deon_draw_phi(Phi, beta, residual, vf_lt(h, vf_set1(0.0f)), u[3]);
    *phi_i = wrap_angle(vf_sub(phi_o, phi));
    deon_geometry_angles(d, *theta_i, *phi_i, theta_o, phi_o, &g);
    if (absorption) {
        deon_spectral_absorption(&g, channels, absorption);
        *pdf = deon_near_f_pdf_spectral(d, M, &g, theta_o, h, channels, f);
    } else {
        *pdf = deon_near_f_pdf(d, M, &g, theta_o, h, f);
    }
    sample_weights_of(*pdf, f, weight, channels);
}

HB_INLINE void deon_sample_near(const hb_deon *d, vf theta_o, vf phi_o, vf h, const vf u[4], hb_i0 i0, vf *theta_i,
                                vf *phi_i, vf *pdf, vf weight[3])
{
    deon_sample_near_of(d, 3, NULL, theta_o, phi_o, h, u, i0, theta_i, phi_i, pdf, weight);
}

#endif

/* CBTB16 over the SIMD vocabulary (docs/chiang.md): f = sum_p M_p A_p N_p for R, TT, TRT, plus
 * the residual M_3 A_3 / (2 pi), near-field at the offset h, as pbrt-v4's HairBxDF computes it;
 * and the lobe-choice density of its sampler, which shares every term but A_p. */
#ifndef HB_CHIANG_EVAL_H
#define HB_CHIANG_EVAL_H

#include "constants.h"
#include "models/common/longitudinal.h"
#include "models/common/fresnel.h"

/* The most channels the kernels carry per sample: RGB's three, or a spectral call's wavelengths. */
#define HB_CHIANG_CHANNELS HB_WAVELENGTHS_MAX

/* What the attenuations give at one offset h for w_o, beside A_p per channel (chiang_offset_at): the
 * sampler's lobe probabilities P_p (A_p's mean over the channels and the plan's lobes, normalised, as
 * pbrt-v4's ApPDF averages its wavelengths; with_pdf only) and the exit azimuths Phi(p, h) of the
 * explicit orders. */
typedef struct chiang_offset {
    vf P[HB_CHIANG_TERMS], Phi[HB_CHIANG_ORDERS];
} chiang_offset;

/* The plan's absorption per unit radius times log2(e), per channel, as chiang_offset_at takes it (a
 * sample's own, hb_eval_angles_absorption, comes from load_absorption). */
HB_INLINE void chiang_plan_absorption(const hb_chiang *c, vf absorption[3])
{
    for (int ch = 0; ch < 3; ch++)
        absorption[ch] = vf_set1(c->sigma_a_log2e[ch]);
}

/* A[ch][p] for `channels` channels at absorption[ch] = sigma_a log2(e): dFH11 eqs. 13, 14 at w_o's
 * side, as CBTB16 takes them, and its residual lobe; and o's terms. cos theta_o and sin theta_o carry
 * w_o; h in [-1, 1]. With eta' cos theta_o = sqrt(eta^2 - sin^2
 * theta_o) = sqrt(eta^2 - 1 + cos^2 theta_o) (Bravais' index), sin gamma_t = h / eta'
 * and the path 2 cos gamma_t / cos theta_t (the absorption of HHH22 sec. 3.1.2) need no division by cos theta_o, so w_o at a pole
 * (cos theta_o = 0: gamma_t = 0) is finite. cos gamma_t = sqrt(eta^2 - 1 + cos^2 theta_o cos^2 gamma_o) / (eta' cos theta_o),
 * a sum of two non-negative terms: 1 - sin^2 gamma_t would cancel to 0 as eta -> 1 and |h| -> 1, losing the path inside. */
HB_INLINE void chiang_offset_at(const hb_chiang *c, int channels, const vf *absorption, vf cos_theta_o, vf h,
                                int with_pdf, vf A[][HB_CHIANG_TERMS], chiang_offset *o)
{
    vf cos_o = vf_abs(cos_theta_o); /* |cos theta_o|, as pbrt takes it: the float pi/2 lies beyond the pole */
    vf cos_gamma_o = vf_sqrt(vf_max(vf_mul(vf_sub(vf_set1(1.0f), h), vf_add(vf_set1(1.0f), h)), vf_set1(0.0f)));
    vf cos_o_cos_gamma_o = vf_mul(cos_o, cos_gamma_o);
    vf F = fresnel_dielectric(cos_o_cos_gamma_o, &c->ior); /* dFH11 eq. 14 at cos theta_o cos gamma_o */
    vf eta2_minus_1 = vf_set1(c->ior.eta2_minus_1);
    vf eta_cos_t = vf_sqrt(vf_fma(cos_o, cos_o, eta2_minus_1)); /* eta' cos theta_o = eta cos theta_t */
    vf inv_eta_cos_t = vf_div(vf_set1(1.0f), eta_cos_t);
    vf sin_gamma_t = vf_mul(vf_mul(h, cos_o), inv_eta_cos_t);
    vf cos_gamma_t = vf_mul(vf_sqrt(vf_fma(cos_o_cos_gamma_o, cos_o_cos_gamma_o, eta2_minus_1)), inv_eta_cos_t);
    vf path = vf_mul(vf_mul(vf_set1(2.0f * c->ior.eta), cos_gamma_t), inv_eta_cos_t); /* 2 cos gamma_t / cos theta_t */
    vf one_minus_F = fresnel_dielectric_complement(cos_o_cos_gamma_o, &c->ior); /* exact to 0 at grazing */
    vf mean[HB_CHIANG_TERMS] = { vf_set1(0.0f), vf_set1(0.0f), vf_set1(0.0f), vf_set1(0.0f) };
    /* the residual's denominators, multiplied per three channels for one division per three (each is in
     * [1e-12, 1], so a product of three stays normal); a last group's missing channels count as 1. The
     * loops run to the most channels, each guarded by the count: straight code at a constant count. */
    enum { SLOTS = (HB_CHIANG_CHANNELS + 2) / 3 * 3 };
    vf TF[SLOTS], den[SLOTS], inv_group_den[SLOTS / 3];
    HB_UNROLL
    for (int ch = 0; ch < SLOTS; ch++) {
        TF[ch] = vf_set1(0.0f);
        den[ch] = vf_set1(1.0f);
        if (ch >= channels)
            continue;
        vf t = vf_mul(absorption[ch], path);
        vf T = vf_min(vf_exp2_neg(t), vf_set1(1.0f)); /* T = e^(-sigma_a path); 2^-0 rounds above 1 */
        TF[ch] = vf_mul(T, F);
        A[ch][0] = F;                                        /* dFH11 eq. 13: p = 0 */
        A[ch][1] = vf_mul(vf_mul(one_minus_F, one_minus_F), T); /* p = 1: (1 - F)^2 T */
        A[ch][2] = vf_mul(A[ch][1], TF[ch]);                 /* p = 2: (1 - F)^2 T^2 F */
        /* 1 - T F = (1 - F) + F (1 - T), both terms >= 0 and 1 - T without cancellation, so that
         * (1 - F)^2 / (1 - T F) <= 1 - F however close T F is to 1 (a lossless fibre at grazing
         * incidence); floored where both vanish, and then A_2 = 0 */
        vf one_minus_TF = vf_fma(F, vf_one_minus_exp2_neg(t, T), one_minus_F);
        den[ch] = vf_max(one_minus_TF, vf_set1(1e-12f));
    }
    HB_UNROLL
    for (int g = 0; g < SLOTS / 3; g++)
        inv_group_den[g] = vf_div(vf_set1(1.0f), vf_mul(vf_mul(den[3 * g], den[3 * g + 1]), den[3 * g + 2]));
    /* CBTB16's residual: the orders above TRT summed, A_2 T F / (1 - T F) */
    HB_UNROLL
    for (int ch = 0; ch < SLOTS; ch++) {
        if (ch >= channels)
            continue;
        int first = ch - ch % 3;
        vf others = vf_mul(den[ch == first ? first + 1 : first], den[ch == first + 2 ? first + 1 : first + 2]);
        A[ch][3] = vf_mul(vf_mul(A[ch][2], TF[ch]), vf_mul(others, inv_group_den[ch / 3]));
        HB_UNROLL
        for (int p = 0; p < HB_CHIANG_TERMS; p++) {
            if (!hb_chiang_term_on(c, p))
                A[ch][p] = vf_set1(0.0f);
            mean[p] = vf_add(mean[p], A[ch][p]);
        }
    }
    if (with_pdf) {
        vf total = vf_add(vf_add(mean[0], mean[1]), vf_add(mean[2], mean[3]));
        vf inv_total = vf_div(vf_set1(1.0f), vf_max(total, vf_set1(1e-30f)));
        for (int p = 0; p < HB_CHIANG_TERMS; p++)
            o->P[p] = vf_mul(mean[p], inv_total);
    }
    vf gamma_t = vf_asin_with_cos(sin_gamma_t, cos_gamma_t);
    vf gamma_o = vf_asin(vf_clamp(h, -1.0f, 1.0f));
    for (int p = 0; p < HB_CHIANG_ORDERS; p++) /* dFH11 eq. 8: Phi(p, h) = 2 p gamma_t - 2 gamma_o + p pi */
        o->Phi[p] = vf_fma(vf_set1(2.0f * (float)p), gamma_t, vf_fnma(vf_set1(2.0f), gamma_o, vf_set1((float)p * HB_PI_F)));
}

/* The trimmed logistic N_p(phi) = logistic(phi - Phi_p, s) on [-pi, pi] (CBTB16) of the plan's
 * explicit orders, each difference wrapped once (fixed work): norm e_p / (1 + e_p)^2 with
 * e_p = 2^-(|x_p| log2(e) / s), the three denominators (each in [1, 4]) inverted by one division. */
HB_INLINE void chiang_logistics(const hb_chiang *c, vf phi, const vf Phi[HB_CHIANG_ORDERS], vf N[HB_CHIANG_ORDERS])
{
    vf e[HB_CHIANG_ORDERS], den[HB_CHIANG_ORDERS], product = vf_set1(1.0f);
    for (int p = 0; p < HB_CHIANG_ORDERS; p++) {
        vf x = vf_abs(wrap_angle(vf_sub(phi, Phi[p])));
        e[p] = vf_exp2_neg(vf_mul(x, vf_set1(c->inv_s_log2e)));
        vf one_plus_e = vf_add(vf_set1(1.0f), e[p]);
        den[p] = hb_chiang_term_on(c, p) ? vf_mul(one_plus_e, one_plus_e) : vf_set1(1.0f);
        product = vf_mul(product, den[p]);
    }
    vf inv = vf_div(vf_set1(c->logistic_norm), product);
    N[0] = vf_mul(vf_mul(e[0], vf_mul(den[1], den[2])), inv);
    N[1] = vf_mul(vf_mul(e[1], vf_mul(den[0], den[2])), inv);
    N[2] = vf_mul(vf_mul(e[2], vf_mul(den[0], den[1])), inv);
}

/* The four M_p at one direction pair from angles (the residual's is unshifted). On the float path
 * every lobe's first stage runs before any second stage, so that the four dependent chains overlap
 * (as dFH11's groups do, longitudinal.h). */
HB_INLINE void chiang_longitudinal_angles(const hb_chiang *c, vf theta_i, vf theta_o, vf M[HB_CHIANG_TERMS])
{
    mp_inclinations in = mp_inclinations_of(theta_i, theta_o);
    vf cone[HB_CHIANG_TERMS], x[HB_CHIANG_TERMS];
    for (int p = 0; p < HB_CHIANG_TERMS; p++)
        if (hb_chiang_term_on(c, p) && c->longitudinal[p].single)
            longitudinal_cone_angles(&c->longitudinal[p], &in, &cone[p], &x[p]);
    for (int p = 0; p < HB_CHIANG_TERMS; p++) {
        const hb_longitudinal *l = &c->longitudinal[p];
        M[p] = !hb_chiang_term_on(c, p) ? vf_set1(0.0f)
             : l->single                ? longitudinal_deon_single(l, cone[p], x[p], HB_I0_ABRAMOWITZ)
                                        : longitudinal_deon_inclinations(l, &in, HB_I0_ABRAMOWITZ);
    }
}

HB_INLINE void chiang_longitudinal_vectors(const hb_chiang *c, const vf wi[3], const vf wo[3], vf M[HB_CHIANG_TERMS])
{
    for (int p = 0; p < HB_CHIANG_TERMS; p++)
        M[p] = hb_chiang_term_on(c, p) ? longitudinal_deon_vectors(&c->longitudinal[p], wi, wo, HB_I0_ABRAMOWITZ)
                                       : vf_set1(0.0f);
}

#define HB_INV_TWO_PI_F 0.159154943f

/* Adds weight * sum_p M_p A_p N_p to f (`channels` channels) and weight * sum_p M_p P_p N_p to pdf, at
 * phi = phi_o - phi_i; with `mirrored`, N_p is taken at phi and -phi (the offsets h and -h of the far field). */
HB_INLINE void chiang_accumulate(const hb_chiang *c, int channels, const vf A[][HB_CHIANG_TERMS], const chiang_offset *o,
                                 const vf M[HB_CHIANG_TERMS], vf phi, int mirrored, vf weight, vf *f, vf *pdf)
{
    vf MN[HB_CHIANG_TERMS], N[HB_CHIANG_ORDERS], N_mirror[HB_CHIANG_ORDERS];
    chiang_logistics(c, phi, o->Phi, N);
    if (mirrored)
        chiang_logistics(c, vf_neg(phi), o->Phi, N_mirror);
    for (int p = 0; p < HB_CHIANG_ORDERS; p++)
        MN[p] = vf_mul(vf_mul(M[p], mirrored ? vf_add(N[p], N_mirror[p]) : N[p]), weight);
    /* the residual: N = 1 / (2 pi) (CBTB16), at h and -h alike */
    MN[3] = vf_mul(vf_mul(M[3], vf_set1(mirrored ? 2.0f * HB_INV_TWO_PI_F : HB_INV_TWO_PI_F)), weight);
    for (int p = 0; p < HB_CHIANG_TERMS; p++) {
        if (!hb_chiang_term_on(c, p))
            continue;
        HB_UNROLL
        for (int ch = 0; ch < HB_CHIANG_CHANNELS; ch++)
            if (ch < channels)
                f[ch] = vf_fma(MN[p], A[ch][p], f[ch]);
        if (pdf)
            *pdf = vf_fma(MN[p], o->P[p], *pdf);
    }
}

/* The near field at h: f in `channels` channels at their absorption (as chiang_offset_at takes it),
 * and the sampler's pdf when pdf is not NULL. */
HB_INLINE void chiang_near(const hb_chiang *c, int channels, const vf *absorption, const vf M[HB_CHIANG_TERMS],
                           vf cos_theta_o, vf phi, vf h, vf *f, vf *pdf)
{
    vf A[HB_CHIANG_CHANNELS][HB_CHIANG_TERMS];
    chiang_offset o;
    chiang_offset_at(c, channels, absorption, cos_theta_o, h, pdf != NULL, A, &o);
    for (int ch = 0; ch < channels; ch++)
        f[ch] = vf_set1(0.0f);
    if (pdf)
        *pdf = vf_set1(0.0f);
    chiang_accumulate(c, channels, A, &o, M, phi, 0, vf_set1(1.0f), f, pdf);
}

/* The near field at h of one sample whose values fill every lane, its four terms across the lanes
 * (hb_chiang.lobe_lanes; plans on the float M_p path): A_p and Phi(p, h) once (chiang_offset_at, the
 * same in every lane; `channels` channels at their absorption, as chiang_offset_at takes it), then per
 * lane L its term's A (0 for a term the plan leaves out), N (the trimmed
 * logistic at phi - Phi(L, h), or 1 / (2 pi) in the residual's lane) and M_p (longitudinal_lobe_lanes),
 * and f the sum over the lanes: one pass where chiang_near takes one per term. f comes back in every
 * lane. */
HB_INLINE void chiang_near_lanes(const hb_chiang *c, int channels, const vf *absorption, const mp_inclinations *in,
                                 vf cos_theta_o, vf phi, vf h, vf *f)
{
    vf terms[HB_CHIANG_CHANNELS][HB_CHIANG_TERMS], A[HB_CHIANG_CHANNELS];
    chiang_offset o;
    chiang_offset_at(c, channels, absorption, cos_theta_o, h, 0, terms, &o);
    vf order = vf_lane_index(), Phi = o.Phi[0];
    HB_UNROLL
    for (int ch = 0; ch < HB_CHIANG_CHANNELS; ch++)
        A[ch] = ch < channels ? terms[ch][0] : vf_set1(0.0f);
    vm at;
    HB_UNROLL
    for (int p = 1; p < HB_CHIANG_TERMS; p++) {
        at = vf_ge(order, vf_set1((float)p));
        Phi = p < HB_CHIANG_ORDERS ? vf_select(at, o.Phi[p], Phi) : Phi;
        HB_UNROLL
        for (int ch = 0; ch < HB_CHIANG_CHANNELS; ch++)
            if (ch < channels)
                A[ch] = vf_select(at, terms[ch][p], A[ch]);
    }
    vf e = vf_exp2_neg(vf_mul(vf_abs(wrap_angle(vf_sub(phi, Phi))), vf_set1(c->inv_s_log2e)));
    vf one_plus_e = vf_add(vf_set1(1.0f), e);
    vf logistic = vf_div(vf_mul(vf_set1(c->logistic_norm), e), vf_mul(one_plus_e, one_plus_e));
    vf N = vf_select(at, vf_set1(HB_INV_TWO_PI_F), logistic); /* `at`: the residual's lane and past it */
    vf MN = vf_mul(longitudinal_lobe_lanes(&c->lobe_lanes, 0, in, HB_I0_ABRAMOWITZ), N);
    HB_UNROLL
    for (int ch = 0; ch < HB_CHIANG_CHANNELS; ch++)
        if (ch < channels)
            f[ch] = vf_set1(vf_sum_first(vf_mul(MN, A[ch]), HB_CHIANG_TERMS < HB_W ? HB_CHIANG_TERMS : HB_W));
}

/* The far field: the mean over h in [-1, 1] by the plan's nodes, each pairing h and -h; channels and
 * absorption as chiang_near's. */
HB_INLINE void chiang_far(const hb_chiang *c, int channels, const vf *absorption, const vf M[HB_CHIANG_TERMS],
                          vf cos_theta_o, vf phi, vf *f, vf *pdf)
{
    for (int ch = 0; ch < channels; ch++)
        f[ch] = vf_set1(0.0f);
    if (pdf)
        *pdf = vf_set1(0.0f);
    for (int j = 0; j < c->nodes; j++) {
        vf A[HB_CHIANG_CHANNELS][HB_CHIANG_TERMS];
        chiang_offset o;
        chiang_offset_at(c, channels, absorption, cos_theta_o, vf_set1(c->h[j]), pdf != NULL, A, &o);
        chiang_accumulate(c, channels, A, &o, M, phi, 1, vf_set1(c->weight[j]), f, pdf);
    }
}

#endif

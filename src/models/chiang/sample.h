/* CBTB16's sampler (as pbrt-v4's HairBxDF::Sample_f) over the SIMD vocabulary: the lobe
 * by its probability P_p, theta_i from that lobe's M_p, phi from its trimmed logistic (the residual:
 * uniform); the pdf is the mixture sum_p P_p M_p N_p, exact for these steps (docs/sampling.md). */
#ifndef HB_CHIANG_SAMPLE_H
#define HB_CHIANG_SAMPLE_H

#include "eval.h"

/* A logistic deviate of scale s trimmed to [-pi, pi] by its inverse CDF: with t = tanh(pi / (2 s))
 * (2u - 1), x = s log((1 + t) / (1 - t)) (the trimmed logistic's CDF inverted). |t| is kept an ulp
 * below 1 (tanh rounds to 1 for s below 0.1), where the logarithm would be infinite: the deviates
 * lost lie beyond 17 s, with probability below 1e-7. */
HB_INLINE vf chiang_logistic_deviate(const hb_chiang *c, vf u)
{
    vf t = vf_mul(vf_set1(c->tanh_half_pi_over_s), vf_fma(u, vf_set1(2.0f), vf_set1(-1.0f)));
    t = vf_clamp(t, -0.99999994f, 0.99999994f);
    vf x = vf_mul(vf_set1(c->s), vf_sub(vf_log1p(t), vf_log1p(vf_neg(t))));
    return vf_clamp(x, -HB_PI_F, HB_PI_F);
}

/* One near-field sample at h from u[0..3]: theta_i, phi_i, the pdf and f / pdf in `channels` channels at
 * their absorption (chiang_offset_at), the lobe chosen by the channels' mean attenuations. */
HB_INLINE void chiang_sample_near(const hb_chiang *c, int channels, const vf *absorption, vf theta_o, vf phi_o, vf h,
                                  const vf u[4], vf *theta_i, vf *phi_i, vf *pdf, vf *weight)
{
    vf cos_theta_o = cos_near_pole(theta_o, vf_set1(HB_PIO2_LO));
    vf A[HB_CHIANG_CHANNELS][HB_CHIANG_TERMS];
    chiang_offset o;
    chiang_offset_at(c, channels, absorption, cos_theta_o, h, 1, A, &o);
    /* the lobe: the first p whose cumulative probability passes u[0] */
    vf cumulative = vf_set1(0.0f), Phi = cumulative, cos_shift = vf_set1(1.0f), sin_shift = cumulative;
    vf v = vf_set1(c->v[0]), e2 = vf_set1(c->exp_minus_two_inv_v[0]); /* R's, where no lobe has any mass */
    vm residual = vf_lt(v, v); /* false */
    for (int p = 0; p < HB_CHIANG_TERMS; p++) {
        vm take = vm_and(vf_ge(u[0], cumulative), vf_gt(o.P[p], vf_set1(0.0f)));
        const hb_longitudinal *l = &c->longitudinal[p];
        v = vf_select(take, vf_set1(c->v[p]), v);
        e2 = vf_select(take, vf_set1(c->exp_minus_two_inv_v[p]), e2);
        cos_shift = vf_select(take, vf_set1((float)l->cos_shift), cos_shift);
        sin_shift = vf_select(take, vf_set1((float)l->sin_shift), sin_shift);
        if (p < HB_CHIANG_ORDERS)
            Phi = vf_select(take, o.Phi[p], Phi);
        else
            residual = take;
        cumulative = vf_add(cumulative, o.P[p]);
    }
    *theta_i = longitudinal_sample(v, e2, cos_shift, sin_shift, theta_o, u[1], u[2]);
    /* phi = phi_o - phi_i: Phi(p, h) plus the deviate, or uniform for the residual */
    vf phi = vf_select(residual, vf_mul(vf_fma(u[3], vf_set1(2.0f), vf_set1(-1.0f)), vf_set1(HB_PI_F)),
                       vf_add(Phi, chiang_logistic_deviate(c, u[3])));
    phi = wrap_angle(phi);
    *phi_i = wrap_angle(vf_sub(phi_o, phi));
    vf M[HB_CHIANG_TERMS], f[HB_CHIANG_CHANNELS];
    chiang_longitudinal_angles(c, *theta_i, theta_o, M);
    vf zero = vf_set1(0.0f);
    for (int ch = 0; ch < channels; ch++)
        f[ch] = zero;
    *pdf = zero;
    chiang_accumulate(c, channels, (const vf(*)[HB_CHIANG_TERMS])A, &o, M, vf_sub(phi_o, *phi_i), 0, vf_set1(1.0f), f,
                      pdf);
    vm some = vf_gt(*pdf, zero);
    for (int ch = 0; ch < channels; ch++)
        weight[ch] = vf_keep(some, vf_div(f[ch], vf_select(some, *pdf, vf_set1(1.0f))));
}

/* The far-field sampler: h = 2 u[4] - 1, a near-field sample there, then the far-field f and pdf
 * (the mean of the near-field pdf over h) at the sampled direction. */
HB_INLINE void chiang_sample_far(const hb_chiang *c, vf theta_o, vf phi_o, const vf u[5], vf *theta_i, vf *phi_i,
                                 vf *pdf, vf weight[3])
{
    vf h = vf_fma(u[4], vf_set1(2.0f), vf_set1(-1.0f)), near_weight[3], absorption[3];
    chiang_plan_absorption(c, absorption);
    chiang_sample_near(c, 3, absorption, theta_o, phi_o, h, u, theta_i, phi_i, pdf, near_weight);
    vf M[HB_CHIANG_TERMS], f[3];
    chiang_longitudinal_angles(c, *theta_i, theta_o, M);
    chiang_far(c, 3, absorption, M, cos_near_pole(theta_o, vf_set1(HB_PIO2_LO)), vf_sub(phi_o, *phi_i), f, pdf);
    vf zero = vf_set1(0.0f);
    vm some = vf_gt(*pdf, zero);
    for (int ch = 0; ch < 3; ch++)
        weight[ch] = vf_keep(some, vf_div(f[ch], vf_select(some, *pdf, vf_set1(1.0f))));
}

#endif

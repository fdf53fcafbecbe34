/* White furnace E(w_o) = integral over the sphere of f(w_i, w_o) dw_i (docs/conventions.md):
 * Gauss-Legendre panels in theta_i and the midpoint rule in the periodic phi_i, both fine
 * enough for the plan's narrowest lobe. Evaluated in stack chunks: no allocation. */
#include <math.h>

#include "plan.h"
#include "quadrature.h"
#include "ref/reference.h"

enum { CHUNK = 512, RULE = 8, MC_PASSES = 16 };

hb_status hb_furnace(const hb_plan *plan, double theta_o, double energy[3])
{
    if (!plan || !energy)
        return HB_ERR_NULL;
    if (!(fabs(theta_o) <= M_PI_2))
        return HB_ERR_PARAM;
    /* The longitudinal term T is f / N_p: its energy is the integral of T cos(theta_i) over
     * theta_i alone, as if N_p integrated to 1 (dFH11 eq. 5 and Fig. 3). */
    int longitudinal = plan->options.term == HB_TERM_LONGITUDINAL;
    double beta_m = HUGE_VAL, beta_n = HUGE_VAL;
    int nphi;
    if (plan->options.model == HB_MODEL_MARSCHNER) {
        for (int p = 0; p < 3; p++)
            if (plan->marschner.lobes >> p & 1u || (longitudinal && p == HB_LOBE_R))
                beta_m = fmin(beta_m, plan->marschner_beta[p]);
        /* N_p is not smooth in phi (square-root edges where a root leaves the fibre or total
         * reflection sets in): a fixed fine midpoint rule, error below 1e-4 for the defaults */
        nphi = longitudinal ? 1 : 1440;
    } else if (plan->options.model == HB_MODEL_HUANG) {
        /* HHH22's lobes are about a roughness wide in theta and (TT, the forward focus) in phi */
        beta_m = plan->material.roughness;
        nphi = (int)ceil(3.0 * M_PI / fmin(plan->material.roughness, 1.0)) + 8;
    } else {
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            if (plan->deon.lobes >> p & 1u || (longitudinal && p == HB_LOBE_R)) {
                beta_m = fmin(beta_m, sqrt(plan->v[p]));
                if (p < HB_MAX_LOBES)
                    beta_n = fmin(beta_n, plan->beta_n[p]);
            }
        /* the periodic midpoint rule in phi with steps of beta_n / 1.5 (its error for a Gaussian
         * of width beta and step h is about exp(-2 pi^2 beta^2 / h^2) = 5e-20) */
        nphi = longitudinal ? 1 : (int)ceil(3.0 * M_PI / fmin(beta_n, 1.0)) + 8;
    }
    /* 8-point Gauss-Legendre panels two longitudinal widths wide */
    int panels = (int)ceil(M_PI / (2.0 * fmin(beta_m, 0.5)));
    float ti[CHUNK], pi[CHUNK], to[CHUNK], po[CHUNK], f[3][CHUNK];
    double weight[CHUNK], x[RULE], w[RULE];
    double sum[3] = { 0.0, 0.0, 0.0 };
    int count = 0;
    unsigned long long chunks = 0;
    hb_plan varied = *plan; /* a shallow copy: it shares the plan's tables and is never destroyed */
    /* HHH22's Monte-Carlo TT and TRT: few of the quadrature's points fall inside the narrow TT
     * lobe, so one pass would carry 5-10% of the estimator's noise; MC_PASSES passes with
     * independent numbers bring it to about a quarter of that */
    int internal = plan->options.model == HB_MODEL_HUANG && plan->kernels && !plan->huang.table.values &&
                   (plan->huang.lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT));
    int passes = internal ? MC_PASSES : 1;
    for (int pass = 0; pass < passes; pass++)
    for (int panel = 0; panel < panels; panel++) {
        hb_gauss_legendre(RULE, -M_PI_2 + M_PI * panel / panels, -M_PI_2 + M_PI * (panel + 1) / panels, x, w);
        for (int j = 0; j < RULE; j++)
            for (int q = 0; q < nphi; q++) {
                ti[count] = (float)x[j];
                pi[count] = (float)(-M_PI + 2.0 * M_PI * (q + 0.5) / nphi);
                to[count] = (float)theta_o;
                po[count] = 0.0f;
                weight[count] = w[j] * cos(x[j]) * (longitudinal ? 1.0 : 2.0 * M_PI / nphi); /* dw_i = cos dtheta dphi */
                weight[count] /= passes;
                int last = panel == panels - 1 && j == RULE - 1 && q == nphi - 1;
                if (++count == CHUNK || last) {
                    /* HHH22's Monte-Carlo TT and TRT draw by sample index, which restarts with
                     * every chunk: a key per chunk keeps the chunks' numbers independent */
                    varied.huang.rng_key = plan->huang.rng_key ^ (uint32_t)hb_mix64((unsigned long long)++chunks);
                    hb_eval_angles(&varied, (size_t)count, (hb_angles_soa){ ti, pi, to, po },
                                   (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
                    for (int c = 0; c < 3; c++)
                        for (int k = 0; k < count; k++)
                            sum[c] += weight[k] * f[c][k];
                    count = 0;
                }
            }
    }
    for (int c = 0; c < 3; c++)
        energy[c] = sum[c];
    return HB_OK;
}

hb_status hb_furnace_orders(const hb_plan *plan, double theta, long paths, unsigned long long seed,
                            double energy[HB_ORDER_GROUPS][3], double standard_error[HB_ORDER_GROUPS])
{
    if (!plan || !energy)
        return HB_ERR_NULL;
    if (plan->options.model != HB_MODEL_HUANG || plan->material.eccentricity != 0.0)
        return HB_ERR_UNSUPPORTED;
    if (!(fabs(theta) < M_PI_2) || paths < 1)
        return HB_ERR_PARAM;
    double unused[HB_ORDER_GROUPS];
    hb_ref_huang_orders(plan, theta, paths, seed, energy, standard_error ? standard_error : unused);
    return HB_OK;
}

/* What CBTB16's kernels read from a plan, fixed at plan creation (src/models/chiang/plan.c). */
#ifndef HB_CHIANG_CONSTANTS_H
#define HB_CHIANG_CONSTANTS_H

#include "hairbsdf.h"
#include "models/common/longitudinal_constants.h"
#include "models/common/dielectric.h"

/* The explicit orders R, TT, TRT; every higher order is one residual lobe (CBTB16). */
#define HB_CHIANG_ORDERS 3
#define HB_CHIANG_TERMS (HB_CHIANG_ORDERS + 1) /* index HB_CHIANG_ORDERS: the residual */

/* Uniform numbers a near-field sample reads; the far-field sampler reads one more for h. */
#define HB_CHIANG_NEAR_DIMENSIONS 4

/* The far field's nodes over gamma = asin(h) in [0, pi/2]: Gauss-Legendre over [-pi/2, pi/2]
 * folded by the symmetry A(-h) = A(h), N_p(phi, -h) = N_p(-phi, h). */
#define HB_CHIANG_MAX_NODES ((HB_MAX_QUADRATURE_ORDER + 1) / 2)

typedef struct hb_chiang {
    unsigned lobes; /* bits 0..2 (R, TT, TRT) and HB_LOBE_RESIDUAL */
    hb_dielectric ior;
    float sigma_a_log2e[3]; /* absorption per unit radius times log2(e) */
    /* N_p, the logistic of scale s trimmed to [-pi, pi] (CBTB16): e / (1 + e)^2 times
     * logistic_norm = 1 / (s tanh(pi / (2 s))), e = 2^-(|x| log2(e) / s) */
    float inv_s_log2e, logistic_norm;
    float s, tanh_half_pi_over_s; /* sampling: x = 2 s atanh(tanh(pi/(2 s)) (2u - 1)) */
    /* M_p (dFH11 eq. 7 with CBTB16's v_p) at theta_o - shift_p; index 3 the residual */
    hb_longitudinal longitudinal[HB_CHIANG_TERMS];
    float v[HB_CHIANG_TERMS], exp_minus_two_inv_v[HB_CHIANG_TERMS]; /* sampling M_p */
    /* the terms' float M_p constants side by side for a call of one sample (eval.h, chiang_near_lanes):
     * lane p term p, the lanes past the residual R's; no detector (the terms' N_p are formed per lane) */
    hb_lobe_lanes lobe_lanes;
    /* far field */
    int nodes;
    float h[HB_CHIANG_MAX_NODES], weight[HB_CHIANG_MAX_NODES]; /* weight: of f(h) + f(-h), sum 1/2 */
} hb_chiang;

/* Whether term p (0..2 the orders R, TT, TRT; 3 the residual) is in the plan's sum. */
static inline int hb_chiang_term_on(const hb_chiang *c, int p)
{
    return c->lobes >> (p < HB_CHIANG_ORDERS ? p : HB_LOBE_RESIDUAL) & 1u;
}

#endif

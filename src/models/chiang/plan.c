/* CBTB16's plan: its own option checks, and its constants derived in double from the material
 * (roughness fits, tilt shifts, logistic scale) and the far field's nodes. */
#include <math.h>

#include "chiang.h"
#include "kernel/isas.h"
#include "math/quadrature.h"
#include "models/build/derive.h"
#include "state.h"

/* v_R = (0.726 beta_m + 0.812 beta_m^2 + 3.7 beta_m^20)^2 (CBTB16's fit). */
double hb_chiang_variance_r(double beta_m)
{
    double r = 0.726 * beta_m + 0.812 * beta_m * beta_m + 3.7 * pow(beta_m, 20.0);
    return r * r;
}

/* s = sqrt(pi / 8) (0.265 beta_n + 1.194 beta_n^2 + 5.372 beta_n^22) (CBTB16's fit). */
double hb_chiang_logistic_scale(double beta_n)
{
    return sqrt(M_PI / 8.0) * (0.265 * beta_n + 1.194 * beta_n * beta_n + 5.372 * pow(beta_n, 22.0));
}

hb_status hb_chiang_validate(const hb_material *m, const hb_options *o, hb_error *error)
{
    if (m->eccentricity > 0.0)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "eccentricity = %g: the chiang model is for circular fibres",
                            m->eccentricity);
    for (int p = 0; p < HB_MAX_LOBES; p++)
        if (m->lobe_beta_m[p] != 0.0 || m->lobe_beta_n[p] != 0.0 || (m->lobe_alpha_override >> p & 1u))
            return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "lobe %d has its own roughness or shift: the chiang model "
                                "derives every lobe's from beta_m, beta_n and alpha", p);
    unsigned all = 7u | 1u << HB_LOBE_RESIDUAL;
    if (o->lobes != HB_LOBES_DEFAULT && (o->lobes & ~all))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "lobes = 0x%x: the chiang model has R, TT, TRT and the residual "
                            "(0x%x)", o->lobes, all);
    if (o->term != HB_TERM_FULL)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the longitudinal term is dFH11's and MJC03's; chiang has f only");
    if (o->azimuthal != HB_AZIMUTHAL_QUADRATURE)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the N_p table is dFH11's (model deon); chiang has none");
    if (o->i0 != HB_I0_ABRAMOWITZ)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "i0: dFH11's 10-term series is the deon model's option");
    if (o->absorption != HB_ABSORPTION_CORRECTED)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "absorption: the chiang model's path is 2 cos(gamma_t) / "
                            "cos(theta_t), as CBTB16 and pbrt-v4 have it");
    return HB_OK;
}

/* The far field's rule: Gauss-Legendre in gamma = asin(h) (smooth where h is not, at +-1), nodes at
 * gamma >= 0 paired with -gamma. Two things limit it (docs/chiang.md): N_R, a logistic in Phi = -2 gamma,
 * has poles pi s / 2 off the real gamma axis, so the error falls geometrically at a rate set by s
 * (nodes = ceil(c / s + 1)); and the trimmed logistic has a kink where phi - Phi(p, h) wraps past +-pi,
 * whose size grows as e^(-pi / s) / s, so from s = 0.4 on the error falls only as nodes^-2 (at least
 * kink_nodes). Measured against the reference's integral over h at 64 directions, beta_m 0.05..0.9,
 * beta_n 0.1..1: each quality's target (1e-2, 1e-3, 1e-4) with c = 2.2 / 2.9 / 3.6 and 4 / 13 / 51
 * nodes at s = 1.09; the rule keeps a node or more to spare. */
static const struct {
    double c;
    int min_nodes, kink_nodes;
} far_rules[] = {
    [HB_QUALITY_FAST] = { 2.4, 4, 5 },
    [HB_QUALITY_BALANCED] = { 3.1, 6, 16 },
    [HB_QUALITY_HIGH] = { 3.8, 8, 64 },
    [HB_QUALITY_REFERENCE] = { 3.8, 8, 64 }, /* unused: the reference integrates over h to 1e-10 */
};

static void far_nodes(hb_chiang *c, int order)
{
    double u[HB_MAX_QUADRATURE_ORDER], w[HB_MAX_QUADRATURE_ORDER];
    hb_gauss_legendre(order, -1.0, 1.0, u, w);
    c->nodes = (order + 1) / 2;
    for (int j = 0; j < c->nodes; j++) {
        int k = order / 2 + j, centre = (order & 1) && j == 0;
        double gamma = centre ? 0.0 : M_PI_2 * u[k];
        c->h[j] = (float)sin(gamma);
        /* (1/2) integral over h of f dh = (1/2) integral of f cos(gamma) dgamma, h and -h together */
        c->weight[j] = (float)((centre ? 0.25 : 0.5) * w[k] * M_PI_2 * cos(gamma));
    }
}

static void derive_constants(hb_plan *plan)
{
    const hb_material *m = &plan->material;
    const hb_options *o = &plan->options;
    hb_chiang *c = &hb_chiang_mut(plan)->kernel;
    c->lobes = o->lobes == HB_LOBES_DEFAULT ? 7u | 1u << HB_LOBE_RESIDUAL : o->lobes;
    c->ior = hb_dielectric_of(m->eta);
    for (int ch = 0; ch < 3; ch++)
        c->sigma_a_log2e[ch] = hb_absorption_float(plan->sigma_a[ch] * M_LOG2E);
    double s = hb_chiang_mut(plan)->s = hb_chiang_logistic_scale(m->beta_n);
    c->s = (float)s;
    c->inv_s_log2e = (float)(M_LOG2E / s);
    c->tanh_half_pi_over_s = (float)tanh(M_PI / (2.0 * s));
    c->logistic_norm = (float)(1.0 / (s * tanh(M_PI / (2.0 * s))));
    /* v_TT = v_R / 4, v_TRT = v_residual = 4 v_R; M_p at theta_o - shift: R at theta_o - 2 alpha,
     * TT at theta_o + alpha, TRT at theta_o + 4 alpha, the residual unshifted (pbrt-v4) */
    double v_r = hb_chiang_variance_r(m->beta_m);
    static const double v_ratio[HB_CHIANG_TERMS] = { 1.0, 0.25, 4.0, 4.0 };
    static const double shift_ratio[HB_CHIANG_TERMS] = { 2.0, -1.0, -4.0, 0.0 };
    for (int p = 0; p < HB_CHIANG_TERMS; p++) {
        hb_chiang_mut(plan)->v[p] = v_ratio[p] * v_r;
        hb_longitudinal_derive(&c->longitudinal[p], hb_chiang_of(plan)->v[p], shift_ratio[p] * m->alpha, o->quality);
        c->v[p] = (float)hb_chiang_of(plan)->v[p];
        c->exp_minus_two_inv_v[p] = (float)exp(-2.0 / hb_chiang_of(plan)->v[p]);
    }
    for (int k = 0; k < HB_LANE_ARRAY; k++)
        hb_lobe_lane_set(&c->lobe_lanes, k, &c->longitudinal[k < HB_CHIANG_TERMS ? k : 0], 0.0f, 0.0f);
    double rule = fmax(far_rules[o->quality].c / s + 1.0, far_rules[o->quality].min_nodes);
    if (s >= 0.4)
        rule = fmax(rule, far_rules[o->quality].kink_nodes);
    int nodes = rule > HB_CHIANG_MAX_NODES ? HB_CHIANG_MAX_NODES : (int)ceil(rule - 1e-9);
    hb_chiang_mut(plan)->far_capped = rule > HB_CHIANG_MAX_NODES;
    far_nodes(c, o->quadrature_order > 0 ? o->quadrature_order : 2 * nodes);
}

hb_status hb_chiang_derive(hb_plan *plan, hb_error *error)
{
    (void)error;
    HB_PER_ISA(hb_chiang_kernels, chiang_kernels, kernels_by_isa);
    HB_PLAN_SET_KERNELS(plan, kernels_by_isa, plan->options.quality == HB_QUALITY_REFERENCE);
    derive_constants(plan);
    return HB_OK;
}

/* MJC03's plan: its own option checks, and its lobes, indices and caustic constants derived
 * from the material and options. */
#include <math.h>

#include "kernel/isas.h"
#include "marschner.h"
#include "models/build/derive.h"
#include "state.h"

hb_status hb_marschner_validate(const hb_material *m, const hb_options *o, hb_error *error)
{
    (void)m;
    if (o->term == HB_TERM_FULL && o->lobes != HB_LOBES_DEFAULT && (o->lobes & ~7u))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "lobes = 0x%x: the marschner model has R, TT and TRT only", o->lobes);
    if (o->azimuthal != HB_AZIMUTHAL_QUADRATURE)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the N_p table is dFH11's (model deon); marschner has none");
    return HB_OK;
}

/* The largest |phi_hat(p, gamma) - p pi| over gamma in [-pi/2, pi/2] for index eta': the
 * endpoint |2pc - pi| or, where the cubic folds, the fold value (2/3) B gamma_c. */
static double marschner_cubic_span(int p, double eta_prime)
{
    double c = asin(1.0 / eta_prime), a = -8.0 * p * c / (M_PI * M_PI * M_PI), b = 6.0 * p * c / M_PI - 2.0;
    double span = fabs(2.0 * p * c - M_PI);
    if (b > 0.0) {
        double gamma_c = sqrt(b / (-3.0 * a));
        if (gamma_c < M_PI_2)
            span = fmax(span, 2.0 / 3.0 * b * gamma_c);
    }
    return span;
}

/* The sampler's lobe probabilities (sample.h): each lobe's attenuation at normal incidence and h = 0
 * (R: F(eta, 0); TT: (1 - F)^2 T; TRT: (1 - F)^2 F T^2, T = exp(-2 sigma_a), channel mean), every
 * lobe of the plan at least a tenth of the largest so that no lobe goes unsampled (equal shares where
 * the absorption leaves every lobe 0). */
static void lobe_probabilities(hb_plan *plan)
{
    hb_marschner *k = &hb_marschner_mut(plan)->kernel;
    double eta = plan->material.eta, r = (eta - 1.0) / (eta + 1.0), F = r * r, weight[3] = { 0.0, 0.0, 0.0 };
    for (int c = 0; c < 3; c++) {
        double T = exp(-2.0 * plan->sigma_a[c]);
        weight[0] += F / 3.0;
        weight[1] += (1.0 - F) * (1.0 - F) * T / 3.0;
        weight[2] += (1.0 - F) * (1.0 - F) * F * T * T / 3.0;
    }
    double largest = 0.0, total = 0.0;
    for (int p = 0; p < 3; p++)
        largest = (k->lobes >> p & 1u) ? fmax(largest, weight[p]) : largest;
    for (int p = 0; p < 3; p++) { /* a fibre that absorbs every lobe away (largest 0): equal shares */
        weight[p] = (k->lobes >> p & 1u) ? (largest > 0.0 ? fmax(weight[p], 0.1 * largest) : 1.0) : 0.0;
        total += weight[p];
    }
    for (int p = 0; p < 3; p++)
        k->lobe_probability[p] = (float)(weight[p] / total);
}

/* MJC03 lobes (Table 1 ratios, docs/conventions.md): beta_R = beta_m, beta_TT = beta_R / 2,
 * beta_TRT = 2 beta_R; means alpha_R = -alpha (the R highlight toward the root, as dFH11's),
 * alpha_TT = -alpha_R / 2, alpha_TRT = -3 alpha_R / 2; per-lobe overrides win. */
static void derive_constants(hb_plan *plan)
{
    const hb_material *m = &plan->material;
    hb_marschner *k = &hb_marschner_mut(plan)->kernel;
    static const double beta_ratio[3] = { 1.0, 0.5, 2.0 }, mean_ratio[3] = { -1.0, 0.5, 1.5 };
    for (int p = 0; p < 3; p++) {
        double beta = m->lobe_beta_m[p] > 0.0 ? m->lobe_beta_m[p] : beta_ratio[p] * m->beta_m;
        double mean = (m->lobe_alpha_override >> p & 1u) ? m->lobe_alpha[p] : mean_ratio[p] * m->alpha;
        hb_marschner_mut(plan)->beta[p] = beta;
        hb_marschner_mut(plan)->mean[p] = mean;
        k->lobe[p].mean = (float)mean;
        k->lobe[p].log2e_over_two_beta2 = (float)(M_LOG2E / (2.0 * beta * beta));
        k->lobe[p].norm = (float)(1.0 / (beta * sqrt(2.0 * M_PI)));
        k->lobe[p].beta = (float)beta;
    }
    k->lobes = plan->options.lobes == HB_LOBES_DEFAULT ? 7u : plan->options.lobes;
    k->absorption_paper = plan->options.absorption == HB_ABSORPTION_PAPER;
    k->eta2_minus_one = (float)((m->eta - 1.0) * (m->eta + 1.0));
    k->eta = (float)m->eta;
    for (int c = 0; c < 3; c++)
        k->sigma_a_log2e[c] = hb_absorption_float(plan->sigma_a[c] * M_LOG2E);
    /* eta* (MJC03 sec. 4.4) with the axis ratio a = sqrt(1 - e^2): eta1 = 2(eta - 1) a^2 - eta + 2
     * at phi_h = 0 (both directions along z, the minor axis), eta2 = 2(eta - 1) / a^2 - eta + 2 at
     * phi_h = pi/2; clamped to 1.0001 where a very flat fibre would take it below 1 */
    double a2 = 1.0 - m->eccentricity * m->eccentricity;
    double eta1 = 2.0 * (m->eta - 1.0) * a2 - m->eta + 2.0, eta2 = 2.0 * (m->eta - 1.0) / a2 - m->eta + 2.0;
    k->eccentric = m->eccentricity > 0.0;
    hb_marschner_mut(plan)->eta_star_mean = 0.5 * (eta1 + eta2);
    hb_marschner_mut(plan)->eta_star_swing = 0.5 * (eta1 - eta2);
    k->eta_star_excess = (float)(hb_marschner_of(plan)->eta_star_mean - 1.0); /* its digits near eta = 1 */
    k->eta_star_swing = (float)hb_marschner_of(plan)->eta_star_swing;
    hb_marschner_mut(plan)->eta_star_min = k->eccentric ? fmax(1.0001, fmin(eta1, eta2)) : m->eta;
    /* eta' >= eta, so the smallest index a lobe sees decides which roots and caustics can exist */
    for (int p = 1; p < 3; p++) {
        double smallest = p == 2 ? hb_marschner_of(plan)->eta_star_min : m->eta;
        double fold = 1.0 / sin(M_PI / (3.0 * p));
        k->fold_index[p] = (float)fold;
        k->folds[p] = smallest < fold;
        k->caustic[p] = smallest < fold + m->caustic_fade;
    }
    k->trt_branches = marschner_cubic_span(2, hb_marschner_of(plan)->eta_star_min) > M_PI - 1e-6 ? 3 : 1;
    k->caustic_width = (float)m->caustic_width;
    k->caustic_log2e_over_two_w2 = (float)(M_LOG2E / (2.0 * m->caustic_width * m->caustic_width));
    k->caustic_norm = (float)(1.0 / (m->caustic_width * sqrt(2.0 * M_PI)));
    k->inv_caustic_fade = (float)(1.0 / m->caustic_fade);
    k->caustic_limit = (float)m->caustic_limit;
    k->glint_scale = (float)m->glint_scale;
    lobe_probabilities(plan);
}


hb_status hb_marschner_derive(hb_plan *plan, hb_error *error)
{
    (void)error;
    HB_PER_ISA(hb_marschner_kernels, marschner_kernels, kernels_by_isa);
    HB_PLAN_SET_KERNELS(plan, kernels_by_isa, plan->options.quality == HB_QUALITY_REFERENCE);
    derive_constants(plan);
    return HB_OK;
}

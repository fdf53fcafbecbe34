/* dFH11's plan: its own option checks, and its constants (eqs. 7, 10, 11), sampler and N_p table
 * derived from the material and options in double precision. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "deon.h"
#include "kernel/isas.h"
#include "math/quadrature.h"
#include "models/build/derive.h"
#include "state.h"

/* Each quality level is an error target for f (docs/conventions.md): 1e-2, 1e-3, 1e-4. The quality
 * rules integrate N_p by Gauss-Legendre in a mapped variable (deon_nodes), whose node count the
 * narrowest lobe sets: R's exit azimuth -2 gamma_i moves twice as fast as gamma_i, so its detector
 * is beta_n / 2 wide in gamma_i. Measured against the reference (white, blond, brown and black hair,
 * beta_m 0.05 and 0.3, beta_n 0.02..1, 512 directions), nodes = ceil(c / beta_n + d), at least
 * min_nodes, meets each target with one to four nodes to spare (none for fast at 0.7, balanced at 0.4)
 * (docs/deon.md), nodes being the rule's points with gamma_i >= 0 (order 2 nodes). */
static const struct {
    double c, d; /* nodes = ceil(c / smallest beta_n of the plan's lobes + d) */
    int min_nodes;
    double detector_tolerance;
} quality_levels[] = {
    [HB_QUALITY_FAST] = { 2.25, 1.0, 5, 1e-3 },
    [HB_QUALITY_BALANCED] = { 2.7, 1.0, 8, 1e-4 },
    [HB_QUALITY_HIGH] = { 3.05, 1.5, 10, 1e-6 },
    [HB_QUALITY_REFERENCE] = { 3.05, 1.5, 10, 1e-6 }, /* unused: the reference converges on its own */
};

/* The map of the quality rules' nodes: gamma_i = (pi/2) asin(a u) / asin(a) for Gauss-Legendre
 * points u in [-1, 1] (Kosloff and Tal-Ezer's map, J. Comput. Phys. 104, 1993), which spreads the
 * points that Gauss-Legendre crowds toward h = +-1 over the middle of the fibre, where R's narrow
 * detector moves; a = 0.8 keeps the mapped integrand analytic well beyond [-1, 1] (its branch points
 * at u = +-1.25), so convergence stays geometric. At beta_n 0.3 it needs 8 / 9 / 11 nodes for
 * 1e-2 / 1e-3 / 1e-4 where Gauss-Legendre in gamma_i needs 9 / 11 / 12 (the quality rules above take
 * 9 / 10 / 12, the paper's order 35 is 18); at beta_n 0.02, 110 / 132 / 151 against 128 / 153 / 175. */
#define HB_NODE_MAP 0.8

/* dFH11 sec. 6 shifts: M_p is evaluated at theta_o - alpha_p with alpha_R = -2 alpha
 * (the R highlight moves toward the root for alpha > 0), alpha_TT = alpha, alpha_TRT = 3 alpha
 * (MJC03 Table 1 ratios -alpha_R/2 and -3 alpha_R/2), and no shift above TRT. */
static double lobe_shift(const hb_material *m, int p)
{
    if (p < HB_MAX_LOBES && (m->lobe_alpha_override >> p & 1u))
        return m->lobe_alpha[p];
    static const double ratio[3] = { -2.0, 1.0, 3.0 };
    return p < 3 ? ratio[p] * m->alpha : 0.0;
}

/* The cheaper truncation of the wrapped Gaussian (eq. 11) whose error, relative to its
 * peak, is below tol. Cost model: a direct term is two exponentials (detection at phi
 * and -phi); the Fourier series needs one cosine per node and one multiply-add per term. */
static void derive_detector(hb_detector *d, double beta, double tol)
{
    int k = 0; /* direct: |x| <= pi after wrapping, the first neglected Gaussian is (2k+1) pi away */
    while (k < HB_MAX_DETECTOR_TERMS && 2.0 * exp(-pow((2 * k + 1) * M_PI, 2) / (2 * beta * beta)) > tol)
        k++;
    int n = 1; /* Fourier: the tail after n terms, relative to the peak >= 1/(2 pi) */
    while (n < HB_MAX_DETECTOR_TERMS && 2.0 * exp(-pow(n + 1, 2) * beta * beta / 2) /
                                            (1.0 - exp(-(2.0 * n + 3.0) * beta * beta / 2)) > tol)
        n++;
    int fourier_converged = 2.0 * exp(-pow(n + 1, 2) * beta * beta / 2) /
                                (1.0 - exp(-(2.0 * n + 3.0) * beta * beta / 2)) <= tol;
    double direct_cost = 2.0 * (2 * k + 1) * 18.0, fourier_cost = 28.0 + 4.0 * n;
    memset(d, 0, sizeof *d);
    d->fourier = fourier_converged && fourier_cost < direct_cost;
    d->terms = d->fourier ? n : k;
    d->log2e_over_two_beta2 = (float)(M_LOG2E / (2.0 * beta * beta));
    d->gauss_norm = (float)(1.0 / (beta * sqrt(2.0 * M_PI)));
    d->coeff[0] = (float)(0.5 / M_PI);
    for (int j = 1; j <= HB_MAX_DETECTOR_TERMS; j++)
        d->coeff[j] = (float)(exp(-0.5 * j * j * beta * beta) / M_PI);
}

/* eq. 10's integral over h in [-1, 1] by the order-n Gauss-Legendre rule in gamma_i over
 * [-pi/2, pi/2] (h = sin gamma_i, so the h^(1/2) behaviour of gamma_i at h = +-1 is smooth; the
 * weight carries dh = cos gamma_i dgamma_i and eq. 10's 1/2), or with `mapped` in u of
 * HB_NODE_MAP (the weight then carries dgamma_i / du too). By the symmetry of dFH11 sec. 6
 * (A even in h, Phi odd), nodes +-gamma pair into one node at gamma >= 0 detected at phi and -phi:
 * (n + 1) / 2 nodes are evaluated, the centre (n odd) with half its weight. The paper's
 * "quadrature of order 35" is n = 35 unmapped: 18 nodes. */
static void deon_nodes(hb_deon *d, int n, int mapped)
{
    double gamma[HB_MAX_QUADRATURE_ORDER], w[HB_MAX_QUADRATURE_ORDER];
    hb_gauss_legendre(n, -1.0, 1.0, gamma, w);
    d->order = n;
    d->mapped = mapped;
    d->nodes = (n + 1) / 2;
    const double a = HB_NODE_MAP, asin_a = asin(a);
    for (int j = 0; j < d->nodes; j++) {
        int k = n / 2 + j, centre = (n & 1) && j == 0;
        double u = centre ? 0.0 : gamma[k]; /* the rule's centre is 0 up to rounding */
        double g = mapped ? M_PI_2 * asin(a * u) / asin_a : M_PI_2 * u;
        w[k] *= mapped ? M_PI_2 * a / (asin_a * sqrt(1.0 - a * a * u * u)) : M_PI_2; /* dgamma_i / du */
        d->gamma_i[j] = (float)g;
        d->cos_gamma_i[j] = (float)cos(g);
        d->h[j] = (float)sin(g);
        d->weight[j] = (float)((centre ? 0.25 : 0.5) * w[k] * cos(g));
    }
}

/* The lobes' float M_p and detector constants side by side (models/common/longitudinal_constants.h), after the
 * lobe set and the detectors. */
static void derive_lobe_lanes(hb_deon *d)
{
    for (int k = 0; k < HB_LANE_ARRAY; k++) {
        int lobe = k <= HB_STANDARD_PMAX || k == HB_LOBE_LANES - 1;
        int p = k <= HB_STANDARD_PMAX ? k : k == HB_LOBE_LANES - 1 ? HB_LOBE_RESIDUAL : HB_LOBE_R;
        float on = lobe && hb_deon_lobe_on(d, p) ? 1.0f : 0.0f;
        hb_lobe_lane_set(&d->lobe_lanes, k, &d->longitudinal[p],
                         on * (p == HB_LOBE_RESIDUAL ? HB_RESIDUAL_DETECTOR : d->detector[p].gauss_norm),
                         p == HB_LOBE_RESIDUAL ? 0.0f : d->detector[p].log2e_over_two_beta2);
    }
}

static void derive_constants(hb_plan *plan)
{
    const hb_material *m = &plan->material;
    const hb_options *o = &plan->options;
    hb_deon *d = &hb_deon_mut(plan)->kernel;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        /* the residual lobe takes the roughness of the highest explicit order, and no shift */
        int q = p == HB_LOBE_RESIDUAL ? o->pmax : p;
        double beta = m->lobe_beta_m[q] > 0.0 ? m->lobe_beta_m[q] : m->beta_m;
        hb_deon_mut(plan)->v[p] = beta * beta;
        hb_longitudinal_derive(&d->longitudinal[p], hb_deon_of(plan)->v[p], p == HB_LOBE_RESIDUAL ? 0.0 : lobe_shift(m, p), o->quality);
    }
    double tol = o->detector_tolerance > 0.0 ? o->detector_tolerance : quality_levels[o->quality].detector_tolerance;
    for (int p = 0; p < HB_MAX_LOBES; p++) {
        hb_deon_mut(plan)->beta_n[p] = m->lobe_beta_n[p] > 0.0 ? m->lobe_beta_n[p] : m->beta_n;
        derive_detector(&d->detector[p], hb_deon_of(plan)->beta_n[p], tol);
    }
    unsigned all = ((2u << o->pmax) - 1u) | 1u << HB_LOBE_RESIDUAL;
    d->lobes = o->lobes == HB_LOBES_DEFAULT ? all : o->lobes;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        d->m_group[p] = p;
        for (int q = 0; q < p; q++)
            if ((d->lobes >> q & 1u) && q <= o->pmax && d->m_group[q] == q &&
                d->longitudinal[q].inv_v == d->longitudinal[p].inv_v &&
                d->longitudinal[q].shift == d->longitudinal[p].shift) {
                d->m_group[p] = q;
                break;
            }
    }
    d->pmax = o->pmax;
    d->groups = 0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        if (hb_deon_group_leader(d, p))
            d->group_leader[d->groups++] = p;
    d->fourier_terms = 0;
    for (int p = 0; p <= o->pmax; p++)
        if (d->detector[p].fourier && d->detector[p].terms > d->fourier_terms)
            d->fourier_terms = d->detector[p].terms;
    d->absorption_paper = o->absorption == HB_ABSORPTION_PAPER;
    d->r_fresnel_offset = o->r_fresnel == HB_R_FRESNEL_OFFSET;
    int nearest = 1;
    for (int p = 0; p <= o->pmax; p++)
        nearest = nearest && !d->detector[p].fourier && d->detector[p].terms == 0;
    d->standard = o->pmax == HB_STANDARD_PMAX && nearest && !d->absorption_paper && d->r_fresnel_offset;
    d->ior = hb_dielectric_of(m->eta);
    for (int c = 0; c < 3; c++)
        d->sigma_a_log2e[c] = hb_absorption_float(plan->sigma_a[c] * M_LOG2E);
    d->channels = d->sigma_a_log2e[0] == d->sigma_a_log2e[1] && d->sigma_a_log2e[1] == d->sigma_a_log2e[2] ? 1 : 3;
    double beta_min = HUGE_VAL;
    for (int p = 0; p <= o->pmax; p++)
        beta_min = fmin(beta_min, hb_deon_of(plan)->beta_n[p]);
    double rule = quality_levels[o->quality].c / beta_min + quality_levels[o->quality].d;
    int nodes = rule > HB_MAX_NODES ? HB_MAX_NODES : (int)ceil(rule - 1e-9); /* 1e-9: c / beta is exact only in reals */
    nodes = nodes < quality_levels[o->quality].min_nodes ? quality_levels[o->quality].min_nodes : nodes;
    if (o->quadrature_order > 0)
        deon_nodes(d, o->quadrature_order, 0); /* the paper's rule, of the caller's order */
    else
        deon_nodes(d, 2 * nodes, 1);
    for (int p = 0; p <= HB_STANDARD_PMAX && p <= o->pmax; p++) {
        hb_scaled_detector *s = &d->scaled[p];
        double sigma = sqrt(M_LOG2E / (2.0 * hb_deon_of(plan)->beta_n[p] * hb_deon_of(plan)->beta_n[p])), period = 2.0 * M_PI * sigma;
        s->scale = (float)sigma;
        s->slope = (float)(2.0 * p * sigma);
        s->period_hi = (float)period;
        s->period_lo = (float)(period - (double)s->period_hi);
        s->inv_period = (float)(1.0 / period);
        for (int j = 0; j < d->nodes; j++) /* eq. 8 at gamma_t = 0, p pi - 2 gamma_i, less floor(p / 2) turns */
            s->offset[j] = (float)(sigma * ((p % 2) * M_PI - 2.0 * (double)d->gamma_i[j]));
    }
    d->asin_narrow = m->eta >= 4.0 / 3.0;
    derive_lobe_lanes(d);
}


hb_status hb_deon_validate(const hb_material *m, const hb_options *o, hb_error *error)
{
    if (m->eccentricity > 0.0)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "eccentricity = %g: the deon model is for circular fibres (dFH11 "
                            "sec. 4); marschner and huang have elliptical ones", m->eccentricity);
    if (o->azimuthal != HB_AZIMUTHAL_QUADRATURE) {
        if (o->term != HB_TERM_FULL || o->quality == HB_QUALITY_REFERENCE)
            return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the N_p table is a float fast path of the full model: not with "
                                "the longitudinal term or the reference quality");
        if (o->r_fresnel != HB_R_FRESNEL_OFFSET)
            return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the N_p table needs the offset R Fresnel: eq. 12's half-angle "
                                "factor is not a function of (phi, theta_d)");
    }
    return HB_OK;
}

hb_status hb_deon_derive(hb_plan *plan, hb_error *error)
{
    HB_PER_ISA(hb_deon_kernels, deon_kernels, kernels_by_isa);
    HB_PLAN_SET_KERNELS(plan, kernels_by_isa, plan->options.quality == HB_QUALITY_REFERENCE);
    derive_constants(plan);
    hb_deon_derive_sampling(plan);
    if (plan->options.azimuthal == HB_AZIMUTHAL_COLOUR_TABLE)
        return hb_deon_build_colour_table(plan, error);
    return plan->options.azimuthal == HB_AZIMUTHAL_TABLE ? hb_deon_build_table(plan, error) : HB_OK;
}

void hb_deon_release(hb_plan *plan) { free(hb_deon_of(plan)->table); }

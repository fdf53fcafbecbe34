/* hb_dual_terms_at: a fibre's forward and backward scattering at one inclination of the light
 * (Zinke et al. 2008, eqs. 6 and 12-17; docs/multiple-scattering.md). The hemisphere integrals of
 * f over w_o are Gauss-Legendre panels in theta_o two longitudinal widths wide (the
 * furnace's rule) times Gauss-Legendre panels on each quarter of the azimuths, so that the
 * hemispheres' edge at |phi| = pi/2 is an edge of the rule. For a circular fibre, w_i at phi_i = 0
 * and every model's mirror symmetry, f(phi_o) = f(-phi_o), halves the azimuths: phi_o in [0, pi],
 * counted twice; an elliptical fibre's terms are the mean over its orientations to the light.
 * Evaluated in stack chunks by the plan's own batch call. hb_dual_lobe_energies: the same integrals
 * of each lobe alone, by a plan of that lobe (allocated and freed). */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "math/dual_scattering.h"
#include "math/quadrature.h"
#include "checks.h"
#include "dual_sums.h"
#include "models/build/build_tasks.h"
#include "models/interface/model.h"

enum {
    CHUNK = 512, RULE = 8, QUARTERS = 4, HALF = 2, /* quarters of the azimuths in [0, pi] */
    ORIENTATIONS = 16 /* an elliptical fibre's orientations to the light, averaged by the midpoint rule */
};


typedef struct pending {
    float ti[CHUNK], pi[CHUNK], to[CHUNK], po[CHUNK];
    double weight[CHUNK], theta_h[CHUNK];
    int backward[CHUNK];
    int count;
} pending;

/* The Gauss-Legendre rule (x1, w1) on [0, 1] moved to the panel [start, start + width]. */
static void panel_rule(const double *x1, const double *w1, double start, double width, double *x, double *w)
{
    for (int k = 0; k < RULE; k++)
        x[k] = start + width * x1[k], w[k] = width * w1[k];
}

/* Evaluates the pending directions and adds them to the sums. */
static void flush(const hb_plan *plan, pending *q, hb_dual_sums *s)
{
    float f[3][CHUNK];
    hb_eval_angles(plan, (size_t)q->count, (hb_angles_soa){ q->ti, q->pi, q->to, q->po }, (hb_rgb_soa){ f[0], f[1], f[2] },
                   NULL);
    for (int k = 0; k < q->count; k++)
        for (int c = 0; c < 3; c++) {
            double e = q->weight[k] * f[c][k];
            s->energy[q->backward[k]][c] += e;
            s->first[q->backward[k]][c] += e * q->theta_h[k];
            s->second[q->backward[k]][c] += e * q->theta_h[k] * q->theta_h[k];
        }
    q->count = 0;
}

/* The hemisphere sums of `evaluated` at theta by the rule of `rule`'s plan (its furnace rule): a
 * lobe's own plan integrated on its parent's nodes, so that the lobes' energies sum to the parent's.
 * An elliptical fibre's sums are the mean over its orientations to the light, w_i at phi_i = psi for
 * ORIENTATIONS midpoints psi of [0, pi) (its cross-section repeats after pi), each over both sides
 * phi_o = psi +- x, which the mirror symmetry no longer makes equal. */
static void hemispheres(const hb_plan *rule, const hb_plan *evaluated, double theta, hb_dual_sums *sums)
{
    int orientations = rule->material.eccentricity > 0.0 ? ORIENTATIONS : 1, sides = orientations > 1 ? 2 : 1;
    const hb_model_ops *ops = hb_model_ops_of(rule->options.model);
    double beta_m;
    int azimuths, passes;
    ops->furnace_rule(rule, &beta_m, &azimuths, &passes);
    int theta_panels = (int)ceil(M_PI / (2.0 * fmin(beta_m, 0.5)));
    int phi_panels = (azimuths + QUARTERS * RULE - 1) / (QUARTERS * RULE); /* per quarter */
    double xt[RULE], wt[RULE], xp[RULE], wp[RULE], x1[RULE], w1[RULE];
    hb_gauss_legendre(RULE, 0.0, 1.0, x1, w1); /* the rule on [0, 1], scaled to each panel */
    *sums = (hb_dual_sums){ { { 0 } }, { { 0 } }, { { 0 } } };
    pending q;
    q.count = 0;
    for (int pass = 0; pass < orientations * sides; pass++) {
        int side = pass % sides;
        double psi = orientations > 1 ? M_PI * (pass / sides + 0.5) / orientations : 0.0;
        for (int a = 0; a < theta_panels; a++) {
            panel_rule(x1, w1, -M_PI_2 + M_PI * a / theta_panels, M_PI / theta_panels, xt, wt);
            for (int j = 0; j < RULE; j++) {
                double cos_o = cos(xt[j]);
                for (int b = 0; b < HALF * phi_panels; b++) {
                    panel_rule(x1, w1, M_PI_2 * b / phi_panels, M_PI_2 / phi_panels, xp, wp);
                    for (int l = 0; l < RULE; l++) {
                        q.ti[q.count] = (float)theta, q.pi[q.count] = (float)psi;
                        q.to[q.count] = (float)xt[j], q.po[q.count] = (float)(psi + (side ? -xp[l] : xp[l]));
                        /* eq. 6: f dw_o (f = S cos(theta_i)), dw_o = cos(theta_o) dtheta_o dphi_o */
                        q.weight[q.count] = 2.0 / (sides * orientations) * wt[j] * wp[l] * cos_o;
                        q.theta_h[q.count] = 0.5 * (theta + xt[j]);
                        q.backward[q.count] = xp[l] < M_PI_2;
                        if (++q.count == CHUNK)
                            flush(evaluated, &q, sums);
                    }
                }
            }
        }
    }
    if (q.count)
        flush(evaluated, &q, sums);
}

void hb_dual_terms_of_sums(const hb_dual_sums *sums, double d_b, hb_dual_terms *terms)
{
    for (int c = 0; c < 3; c++) {
        double *energy[2] = { &terms->a_f[c], &terms->a_b[c] }, *mean[2] = { &terms->alpha_f[c], &terms->alpha_b[c] },
               *variance[2] = { &terms->beta_f2[c], &terms->beta_b2[c] };
        for (int h = 0; h < 2; h++) {
            double e = sums->energy[h][c], m = e > 0.0 ? sums->first[h][c] / e : 0.0;
            *energy[h] = e;
            *mean[h] = m;
            *variance[h] = e > 0.0 ? fmax(0.0, sums->second[h][c] / e - m * m) : 0.0;
        }
        terms->A_b[c] = hb_dual_back_energy(terms->a_f[c], terms->a_b[c]);
        terms->delta_b[c] = hb_dual_back_shift(terms->a_f[c], terms->a_b[c], terms->alpha_f[c], terms->alpha_b[c]);
        terms->sigma_b2[c] = hb_dual_back_variance(terms->a_f[c], terms->a_b[c], terms->beta_f2[c], terms->beta_b2[c], d_b);
    }
}

hb_status hb_dual_check_call(const char *call, const hb_plan *plan, double theta, double d_b, const hb_dual_terms *terms)
{
    if (!plan || !terms)
        return hb_fail_null(call, !plan ? "plan" : "terms");
    hb_status st = hb_api_struct_size(call, "terms", terms->struct_size,
                                      offsetof(hb_dual_terms, sigma_b2) + sizeof terms->sigma_b2, sizeof *terms);
    if (st != HB_OK)
        return st;
    if (!(fabs(theta) < M_PI_2))
        return hb_fail(HB_ERR_PARAM, "%s: theta = %g is outside (-pi/2, pi/2)", call, theta);
    if (!(d_b >= 0.0 && d_b <= 1.0))
        return hb_fail(HB_ERR_PARAM, "%s: d_b = %g is outside [0, 1]", call, d_b);
    return HB_OK;
}

hb_status hb_dual_terms_at(const hb_plan *plan, double theta, double d_b, hb_dual_terms *terms)
{
    hb_status st = hb_dual_check_call(__func__, plan, theta, d_b, terms);
    if (st != HB_OK)
        return st;
    size_t size = terms->struct_size;
    hb_dual_terms all = { .struct_size = size };
    hb_dual_sums sums;
    hemispheres(plan, plan, theta, &sums);
    hb_dual_terms_of_sums(&sums, d_b, &all);
    memcpy(terms, &all, size);
    return HB_OK;
}

hb_status hb_dual_lobe_energies(const hb_plan *plan, double theta, double forward[HB_MAX_LOBES + 1][3],
                                double backward[HB_MAX_LOBES + 1][3])
{
    if (!plan || !forward || !backward)
        return hb_fail_null(__func__, !plan ? "plan" : !forward ? "forward" : "backward");
    if (!(fabs(theta) < M_PI_2))
        return hb_fail(HB_ERR_PARAM, "%s: theta = %g is outside (-pi/2, pi/2)", __func__, theta);
    unsigned lobes = hb_model_ops_of(plan->options.model)->lobes(&plan->options);
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        for (int c = 0; c < 3; c++)
            forward[p][c] = backward[p][c] = 0.0;
        if (!(lobes >> p & 1u))
            continue;
        hb_options o = plan->options; /* the plan's own configuration, one lobe of it */
        o.lobes = HB_LOBE_BIT(p), o.tolerance = 0.0, o.budget_ns = 0.0;
        hb_plan *lobe;
        hb_error error;
        hb_status st = hb_plan_create(&plan->material, &o, &lobe, &error);
        if (st != HB_OK)
            return hb_fail(st, "%s: the plan of lobe %s alone: %s", __func__, hb_lobe_name(p), error.message);
        hb_dual_sums sums;
        hemispheres(plan, lobe, theta, &sums);
        hb_plan_destroy(lobe);
        for (int c = 0; c < 3; c++)
            forward[p][c] = sums.energy[0][c], backward[p][c] = sums.energy[1][c];
    }
    return HB_OK;
}

/* One row of hb_dual_terms_grid. */
typedef struct grid_rows {
    const hb_plan *plan;
    int count;
    double d_b;
    unsigned char *terms;
    size_t size;
} grid_rows;

static void grid_row(void *context, int k)
{
    const grid_rows *g = context;
    hb_dual_terms *t = (hb_dual_terms *)(g->terms + (size_t)k * g->size);
    t->struct_size = g->size;
    hb_dual_terms_at(g->plan, -M_PI_2 + M_PI * (k + 0.5) / g->count, g->d_b, t);
}

hb_status hb_dual_terms_grid(const hb_plan *plan, int count, double d_b, hb_dual_terms *terms, hb_progress_fn progress,
                             void *progress_context, hb_parallel_fn parallel, void *parallel_context)
{
    if (!plan || !terms)
        return hb_fail_null(__func__, !plan ? "plan" : "terms");
    if (count < 1)
        return hb_fail(HB_ERR_PARAM, "%s: count = %d; at least 1", __func__, count);
    size_t size = terms->struct_size;
    hb_status st = hb_api_struct_size(__func__, "terms", size, offsetof(hb_dual_terms, sigma_b2) + sizeof terms->sigma_b2,
                                      sizeof *terms);
    if (st == HB_OK && !(d_b >= 0.0 && d_b <= 1.0))
        st = hb_fail(HB_ERR_PARAM, "%s: d_b = %g is outside [0, 1]", __func__, d_b);
    if (st != HB_OK)
        return st;
    hb_options run = { .progress = progress, .progress_context = progress_context, .parallel = parallel,
                       .parallel_context = parallel_context };
    grid_rows rows = { plan, count, d_b, (unsigned char *)terms, size };
    st = hb_build_tasks(&run, count, hb_build_part(count), grid_row, &rows, 0.0, 1.0, NULL);
    return st == HB_OK ? hb_build_finish(&run, NULL) : st;
}

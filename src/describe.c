/* hb_plan_describe: what a plan simulates, what it skipped and why, and what it is expected to cost. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "plan.h"

typedef struct text {
    char *out;
    size_t size, length;
} text;

static void say(text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(t->length < t->size ? t->out + t->length : NULL, t->length < t->size ? t->size - t->length : 0,
                      fmt, ap);
    va_end(ap);
    t->length += n > 0 ? (size_t)n : 0;
}

static const char *const lobe_names[HB_MAX_LOBES + 1] = { "R", "TT", "TRT", "TRRT", "p = 4", "p = 5", "p = 6", "p = 7",
                                                          "residual" };
static const char *const quality_names[] = { "fast", "balanced", "high", "reference" };

static void say_lobes(text *t, unsigned lobes)
{
    int first = 1;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        if (lobes >> p & 1u) {
            say(t, "%s%s", first ? "" : ", ", lobe_names[p]);
            first = 0;
        }
    if (first)
        say(t, "none");
}

static void describe_deon(text *t, const hb_plan *plan)
{
    const hb_deon *d = &plan->deon;
    say(t, "model: d'Eon 2011 (dFH11), f = sum_p M_p N_p, %s; lobes: ",
        d->channels == 1 ? "grey (one channel computed, copied to RGB)" : "RGB");
    say_lobes(t, d->lobes);
    say(t, d->lobes >> HB_LOBE_RESIDUAL & 1u ? " (residual: every order above %d in closed form)\n" : "\n", d->pmax);
    int groups = 0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        groups += hb_deon_group_leader(d, p);
    say(t, "M_p (eq. 7): %s I0; %d distinct M_p per sample (lobes with the same roughness and shift share one%s)\n",
        plan->options.i0 == HB_I0_ABRAMOWITZ ? "A&S 9.8.1/9.8.2" : "the paper's 10-term series for", groups,
        plan->material.alpha == 0.0 ? "; no tilt" : "");
    if (d->np_table)
        say(t, "N_p (eq. 10): bilinear from a %d x %d table per M_p group over sqrt(cos theta_d) x |phi| "
               "(midpoint error %.2g of each group's peak), built with the order-%d Gauss-Legendre rule%s\n",
            d->table_cd, d->table_phi, plan->table_error, d->order, d->mapped ? " (mapped)" : "");
    else
        say(t, "N_p (eq. 10): order-%d Gauss-Legendre rule %s across the fibre, %d nodes per sample "
               "(gamma_i >= 0, detected at +-phi), quality %s\n", d->order,
            d->mapped ? "in u, gamma_i = (pi/2) asin(0.8 u) / asin(0.8)" : "in gamma_i", d->nodes,
            quality_names[plan->options.quality]);
    for (int p = 0; p <= d->pmax && p < HB_MAX_LOBES; p++)
        if (d->lobes >> p & 1u)
            say(t, d->detector[p].fourier ? "  detector %s (eq. 11, beta_n %.3g): Fourier series, %d terms\n"
                                          : "  detector %s (eq. 11, beta_n %.3g): Gaussians at phi - 2 pi k, |k| <= %d\n",
                lobe_names[p], plan->beta_n[p],
                d->detector[p].terms);
}

static void describe_marschner(text *t, const hb_plan *plan)
{
    say(t, "model: Marschner 2003 (MJC03), R + TT + TRT in closed form (the cubic solved per sample), RGB; lobes: ");
    say_lobes(t, plan->marschner.lobes);
    say(t, "\nfibre: %s; TRT caustics: glint %.3g, width %.3g rad\n",
        plan->material.eccentricity > 0.0 ? "elliptical" : "circular", plan->material.glint_scale,
        plan->material.caustic_width);
}

static void describe_huang(text *t, const hb_plan *plan)
{
    const hb_huang *h = &plan->huang;
    say(t, "model: Huang 2022 (HHH22), microfacet %s roughness %.3g, %s, %s fibre%s; lobes: ",
        h->beckmann ? "Beckmann" : "GGX", plan->material.roughness, h->shadowing ? "Smith G" : "no shadowing (G = 1)",
        h->elliptical ? "elliptical" : "circular", h->tilted ? ", tilted scales" : "");
    say_lobes(t, h->lobes);
    say(t, "\n");
    if (h->lobes & 1u) {
        if (h->analytic)
            say(t, "R (eq. 12): App. A's closed form\n");
        else
            say(t, "R (eq. 12): Simpson, %d panels%s\n", h->panels,
                h->step_rule ? " (the paper's uniform steps)" : " in the peak-following variable");
    }
    if (h->lobes & 6u) {
        if (h->table.values)
            say(t, "TT + TRT: interpolated from a table (%d theta_i x %d phi_i x %d x %d)\n", h->table.n_theta_i,
                h->table.n_phi_i, h->table.n_sum, h->table.n_delta);
        else if (plan->kernels)
            say(t, "TT + TRT (eqs. 31, 32): Simpson over %d panels of the entry azimuth, one random internal path per "
                   "node (seed %llu)\n", h->tt_panels, plan->options.seed);
        else
            say(t, "TT + TRT: nested quadrature in double\n");
    }
}

size_t hb_plan_describe(const hb_plan *plan, char *out, size_t size)
{
    text t = { out, size, 0 };
    if (out && size)
        out[0] = '\0';
    if (!plan)
        return 0;
    if (plan->options.model == HB_MODEL_DEON)
        describe_deon(&t, plan);
    else if (plan->options.model == HB_MODEL_MARSCHNER)
        describe_marschner(&t, plan);
    else
        describe_huang(&t, plan);
    say(&t, "evaluation: %s\n", plan->kernels ? hb_isa_name(plan->isa) : "double-precision reference (scalar)");
    const hb_selection *s = &plan->selection;
    if (s->active) {
        if (s->tolerance > 0.0)
            say(&t, "chosen for a tolerance of %.3g of the peak f: %s\n", s->tolerance, s->configuration);
        else
            say(&t, "chosen for a budget of %.4g ns per sample: %s\n", s->budget_ns, s->configuration);
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            if (s->measured >> p & 1u)
                say(&t, "  %s: largest value %.2g of the peak f (measured on a grid of directions) -> %s\n", lobe_names[p],
                    s->share[p], s->dropped >> p & 1u ? "skipped" : "simulated");
        if (s->refused)
            say(&t, "not chosen although calibrated better: %s\n", s->refusal);
        if (s->dropped)
            say(&t, "skipped lobes cost at most %.2g of the peak (twice their measured maxima)\n", s->dropped_bound);
        say(&t, "expected error: %.2g (calibrated max error%s); expected cost: %.4g ns per sample on %s%s (calibration: %s)\n",
            s->expected_error, s->dropped ? " plus the skipped lobes" : "", s->expected_ns,
            s->ranked_by_scalar ? "scalar x86" : hb_isa_name(plan->isa),
            s->ranked_by_scalar ? ", this ISA is not calibrated" : "", s->calibration);
    } else {
        char configuration[32];
        double ns, err;
        if (plan->kernels && hb_plan_expected(plan, configuration, sizeof configuration, &ns, &err))
            say(&t, "calibrated as %s: error %.2g, %.4g ns per sample on %s (built-in calibration)\n", configuration, err,
                ns, hb_isa_name(plan->isa));
        else
            say(&t, "no calibrated figures for this configuration (make bench measures it)\n");
    }
    return t.length;
}

/* hb_plan_describe: what a plan simulates, what it skipped and why, and what it is expected to cost. */
#include <math.h>

#include "dual_sums.h"
#include "math/dual_scattering.h"
#include "plan/creation.h"

enum { DESCRIBED_THETAS = 16 }; /* the inclinations at which a tolerance plan's dual-scattering share is described */

/* What dual scattering adds for this material (docs/multiple-scattering.md): the forward energy a_f
 * at normal incidence (Zinke et al. eq. 6, hb_dual_terms_at) and the fibres n after which the global
 * term's d_f a_f^n falls below the plan's target (its tolerance, or its quality's), where shading
 * behind more fibres can drop the term. Not for a reference plan, whose terms take the double path. */
static void describe_multiple_scattering(hb_text *t, const hb_plan *plan)
{
    hb_dual_terms d = { .struct_size = sizeof d };
    if (!plan->kernels || plan->options.term != HB_TERM_FULL || hb_dual_terms_at(plan, 0.0, HB_DUAL_DENSITY, &d) != HB_OK)
        return;
    double target = plan->selection.active && plan->selection.tolerance > 0.0 ? plan->selection.tolerance
                                                                              : hb_quality_target(plan->options.quality);
    hb_say(t, "multiple scattering (hb_dual_eval): forward energy a_f at theta 0: %.3g %.3g %.3g", d.a_f[0], d.a_f[1],
           d.a_f[2]);
    if (fmax(d.a_f[0], fmax(d.a_f[1], d.a_f[2])) >= 1.0) {
        hb_say(t, "; a_f >= 1, where eqs. 14-15 diverge: no dual scattering (hb_dual_table_create refuses the plan)\n");
        return;
    }
    hb_say(t, "; d_f a_f^n below %.0e after n =", target);
    for (int c = 0; c < 3; c++) {
        double a = d.a_f[c], n = a <= 0.0 ? 0.0 : log(target / HB_DUAL_DENSITY) / log(a);
        hb_say(t, " %.0f", ceil(fmax(n, 0.0)));
    }
    hb_say(t, " fibres (r, g, b)\n");
    if (!plan->selection.active)
        return;
    /* hb_dual_table_create's rule (src/api/dual_table.c) on its own nodes; here at 16 inclinations */
    double share = 0.0, plan_target = hb_dual_drop_target(plan);
    for (int k = 0; k < DESCRIBED_THETAS; k++) {
        if (hb_dual_terms_at(plan, -M_PI_2 + M_PI * (k + 0.5) / DESCRIBED_THETAS, HB_DUAL_DENSITY, &d) != HB_OK)
            return;
        for (int c = 0; c < 3; c++)
            share = fmax(share, hb_dual_share(d.a_f[c], d.a_b[c], d.A_b[c], HB_DUAL_DENSITY, HB_DUAL_DENSITY));
    }
    hb_say(t, "multiple scattering: %s: it adds at most %.2g of the fibre's own energy (at %d inclinations, d_f = d_b = "
              "%.1f), %s the plan's target %.2g\n",
           share < plan_target ? "dropped (hb_dual_table_create makes its terms zero)" : "included", share,
           DESCRIBED_THETAS, HB_DUAL_DENSITY, share < plan_target ? "below" : "not below", plan_target);
}

size_t hb_plan_describe(const hb_plan *plan, char *out, size_t size)
{
    hb_text t = { out, size, 0 };
    if (out && size)
        out[0] = '\0';
    if (!plan)
        return 0;
    hb_model_ops_of(plan->options.model)->describe(&t, plan);
    hb_say(&t, "evaluation: %s\n", plan->kernels ? hb_isa_name(plan->isa) : "double-precision reference (scalar)");
    if (plan->table_file_size)
        hb_say(&t, "table: loaded from a table file of %zu bytes, not built\n", plan->table_file_size);
    describe_multiple_scattering(&t, plan);
    const hb_selection *s = &plan->selection;
    if (s->active) {
        if (s->tolerance > 0.0)
            hb_say(&t, "chosen for a tolerance of %.3g of the peak f: %s\n", s->tolerance, s->configuration);
        else
            hb_say(&t, "chosen for a budget of %.4g ns per sample: %s\n", s->budget_ns, s->configuration);
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            if (s->measured >> p & 1u)
                hb_say(&t, "  %s: largest value %.2g of the peak f (measured on a grid of directions) -> %s\n", hb_lobe_name(p),
                    s->share[p], s->dropped >> p & 1u ? "skipped" : "simulated");
        if (s->refused)
            hb_say(&t, "not chosen although calibrated better: %s\n", s->refusal);
        if (s->dropped)
            hb_say(&t, "skipped lobes cost at most %.2g of the peak (twice their measured maxima)\n", s->dropped_bound);
        hb_say(&t, "expected error: %.2g (calibrated max error%s); expected cost: %.4g ns per sample on %s%s (calibration: %s)\n",
            s->expected_error, s->dropped ? " plus the skipped lobes" : "", s->expected_ns,
            s->ranked_by_scalar ? "scalar x86" : hb_isa_name(plan->isa),
            s->ranked_by_scalar ? ", this ISA is not calibrated" : "", s->calibration);
    } else {
        char configuration[32];
        double ns, err;
        static const char *const levels[] = { "fast", "balanced", "high" };
        if (plan->kernels && hb_plan_expected(plan, configuration, sizeof configuration, &ns, &err)) {
            hb_say(&t, "calibrated as %s: error %.2g, %.4g ns per sample on %s (built-in calibration)\n", configuration, err,
                ns, hb_isa_name(plan->isa));
            int q = (int)plan->options.quality;
            if (q < HB_QUALITY_REFERENCE && err > hb_quality_target(plan->options.quality))
                hb_say(&t, "this configuration does not meet the %s target of %.0e: its calibrated error is %.2g times it\n",
                       levels[q], hb_quality_target(plan->options.quality), err / hb_quality_target(plan->options.quality));
        } else
            hb_say(&t, "no calibrated figures for this configuration (make bench measures it)\n");
    }
    return t.length;
}

/* Plans that choose their own configuration (options.tolerance, options.budget_ns): which lobes a
 * material needs, measured at plan creation, and which named configuration (quality, quadrature
 * order, N_p table) meets the tolerance most cheaply or the budget most accurately, from the
 * calibration that `make bench` measures (calibration.c). docs/engines.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibration.h"
#include "creation.h"

/* The preset the options amount to, for describing any plan; NULL if none. */
static const hb_preset *preset_of(const hb_model_ops *ops, const hb_material *m, const hb_options *o, unsigned lobes)
{
    for (int k = 0; k < ops->preset_count; k++)
        if (ops->preset_applies(&ops->presets[k], m, o, lobes) && ops->preset_is(&ops->presets[k], m, o, lobes))
            return &ops->presets[k];
    return NULL;
}

/* The calibration entry of a preset on the ISA, else on scalar (ranked by scalar timings). */
static const hb_calibration_entry *entry_for(const hb_calibration *c, const hb_model_ops *ops, const hb_preset *p,
                                             hb_isa isa, int *fallback)
{
    const hb_calibration_entry *e = hb_calibration_find(c, ops->name, p->name, hb_isa_name(isa));
    *fallback = !e;
    return e ? e : hb_calibration_find(c, ops->name, p->name, "scalar");
}

enum { PROBE_THETA_I = 17, PROBE_THETA_O = 61, PROBE_CONE = 15, PROBE_PHI = 32 };
#define PROBES (PROBE_THETA_I * (PROBE_THETA_O + PROBE_CONE) * PROBE_PHI)

/* The directions lobes are measured at: theta_i on a grid, theta_o on a grid and on the specular cone
 * -theta_i shifted by multiples of beta_m / 2 and by the tilt's shifts, phi over [0, pi]. */
static void probe_directions(const hb_material *m, float *ti, float *pi, float *to, float *po)
{
    size_t k = 0;
    for (int a = 0; a < PROBE_THETA_I; a++) {
        double theta_i = -1.5 + 3.0 * a / (PROBE_THETA_I - 1);
        for (int b = 0; b < PROBE_THETA_O + PROBE_CONE; b++) {
            double theta_o = b < PROBE_THETA_O ? -1.55 + 3.1 * b / (PROBE_THETA_O - 1)
                           : b < PROBE_THETA_O + 9 ? -theta_i + 0.5 * m->beta_m * (b - PROBE_THETA_O - 4)
                                                   : -theta_i + m->alpha * ((b - PROBE_THETA_O - 9) % 3 + 1) *
                                                                    ((b - PROBE_THETA_O) % 2 ? 1.0 : -1.0);
            theta_o = fmax(-1.5707, fmin(1.5707, theta_o));
            for (int c = 0; c < PROBE_PHI; c++, k++) {
                ti[k] = (float)theta_i, to[k] = (float)theta_o, pi[k] = 0.0f;
                po[k] = (float)(M_PI * c / (PROBE_PHI - 1));
            }
        }
    }
}

/* share[p]: the largest value of lobe p over the probe directions and channels, over the peak of
 * the sum of the lobes there. */
static hb_status measure_lobes(const hb_material *m, const hb_options *base, hb_isa isa, unsigned lobes,
                               double *share, hb_error *error)
{
    float *buffer = malloc((size_t)PROBES * 8 * sizeof *buffer);
    double *sum = calloc((size_t)PROBES * 3, sizeof *sum), *lobe_max = calloc(HB_MAX_LOBES + 1, sizeof *lobe_max);
    hb_status st = buffer && sum && lobe_max ? HB_OK : HB_ERR_NOMEM;
    if (st == HB_OK) {
        float *ti = buffer, *pi = buffer + PROBES, *to = buffer + 2 * PROBES, *po = buffer + 3 * PROBES;
        float *f[3] = { buffer + 4 * PROBES, buffer + 5 * PROBES, buffer + 6 * PROBES };
        probe_directions(m, ti, pi, to, po);
        for (int p = 0; p <= HB_LOBE_RESIDUAL && st == HB_OK; p++) {
            if (!(lobes >> p & 1u))
                continue;
            hb_options o = *base;
            o.lobes = 1u << p;
            hb_plan *plan;
            st = hb_plan_build(m, &o, isa, NULL, &plan, error);
            if (st != HB_OK)
                break;
            size_t invalid;
            hb_model_ops_of(o.model)->eval_angles(plan, PROBES, (hb_angles_soa){ ti, pi, to, po },
                                                  (hb_rgb_soa){ f[0], f[1], f[2] }, &invalid);
            hb_plan_free(plan);
            for (size_t k = 0; k < PROBES; k++)
                for (int c = 0; c < 3; c++) {
                    sum[3 * k + (size_t)c] += f[c][k];
                    lobe_max[p] = fmax(lobe_max[p], f[c][k]);
                }
        }
    }
    double peak = 0.0;
    for (size_t k = 0; st == HB_OK && k < (size_t)PROBES * 3; k++)
        peak = fmax(peak, sum[k]);
    for (int p = 0; p <= HB_LOBE_RESIDUAL && st == HB_OK; p++)
        share[p] = peak > 0.0 ? lobe_max[p] / peak : 0.0;
    free(buffer), free(sum), free(lobe_max);
    if (st == HB_ERR_NOMEM)
        hb_plan_fail(error, st, "could not allocate the lobe probes");
    return st;
}

hb_status hb_plan_select(const hb_material *m, const hb_options *in, hb_isa isa, hb_options *out, hb_selection *sel,
                         hb_error *error)
{
    *out = *in;
    int again = sel->active; /* a later attempt: the lobes are measured, sel->refused presets are out */
    if (!again) {
        memset(sel, 0, sizeof *sel);
        sel->active = 1;
        sel->tolerance = in->tolerance, sel->budget_ns = in->budget_ns;
    }
    const hb_model_ops *ops = hb_model_ops_of(in->model);
    unsigned lobes = ops->lobes(in) & ~sel->dropped;
    hb_calibration calibration;
    hb_status st = hb_calibration_open(in->calibration, &calibration, error);
    if (st != HB_OK)
        return st;
    snprintf(sel->calibration, sizeof sel->calibration, "%s", in->calibration ? in->calibration : "built in");
    double allowed = in->tolerance; /* what the configuration may still spend after dropped lobes */
    if (in->tolerance > 0.0 && ops->drops_lobes && !again) {
        hb_options base = *in;
        base.tolerance = 0.0, base.budget_ns = 0.0, base.quality = HB_QUALITY_BALANCED, base.quadrature_order = 0;
        base.azimuthal = HB_AZIMUTHAL_QUADRATURE, base.isa = isa;
        st = measure_lobes(m, &base, isa, lobes, sel->share, error);
        if (st != HB_OK) {
            hb_calibration_close(&calibration);
            return st;
        }
        sel->measured = lobes;
        /* drop the smallest lobes while twice their summed maxima (a margin for peaks between the
         * probe directions) stays within half the tolerance; keep the largest lobe */
        for (;;) {
            int smallest = -1;
            for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
                if ((lobes >> p & 1u) && (smallest < 0 || sel->share[p] < sel->share[smallest]))
                    smallest = p;
            if (smallest < 0 || (lobes & (lobes - 1u)) == 0 ||
                sel->dropped_bound + 2.0 * sel->share[smallest] > 0.5 * in->tolerance)
                break;
            sel->dropped_bound += 2.0 * sel->share[smallest];
            sel->dropped |= 1u << smallest;
            lobes &= ~(1u << smallest);
        }
    }
    if (in->tolerance > 0.0)
        allowed = in->tolerance - sel->dropped_bound;
    const hb_preset *best = NULL;
    const hb_calibration_entry *best_entry = NULL, *fastest = NULL, *most_accurate = NULL;
    int candidates = 0;
    for (int k = 0; k < ops->preset_count; k++) {
        int fallback;
        const hb_calibration_entry *e;
        if (!ops->preset_applies(&ops->presets[k], m, in, lobes) ||
            !(e = entry_for(&calibration, ops, &ops->presets[k], isa, &fallback)) || (sel->refused >> k & 1u))
            continue;
        candidates++;
        double ns = hb_calibration_ns(&calibration, e);
        fastest = !fastest || ns < hb_calibration_ns(&calibration, fastest) ? e : fastest;
        most_accurate = !most_accurate || e->error < most_accurate->error ? e : most_accurate;
        int fits = in->tolerance > 0.0 ? e->error <= allowed : ns <= in->budget_ns;
        int faster = best_entry && ns < hb_calibration_ns(&calibration, best_entry);
        int better = !best_entry || (in->tolerance > 0.0 ? faster
                                                          : e->error < best_entry->error ||
                                                                (e->error == best_entry->error && faster));
        if (fits && better) {
            best = &ops->presets[k], best_entry = e;
            sel->ranked_by_scalar = fallback;
        }
    }
    /* the message names calibration rows, so it is written before the calibration is closed */
    st = HB_OK;
    if (!candidates)
        st = hb_plan_fail(error, HB_ERR_UNSUPPORTED,
                          "no calibrated configuration of the %s model for these options: tolerance and budget plans "
                          "cover deon, marschner, and huang with R alone or R + TT + TRT", ops->name);
    else if (!best && in->tolerance > 0.0)
        st = hb_plan_fail(error, HB_ERR_LIMIT,
                          "tolerance %g leaves %.3g for the configuration after dropped lobes, below every calibrated "
                          "one (the most accurate, %s, measured %.3g)", in->tolerance, allowed,
                          most_accurate->configuration, most_accurate->error);
    else if (!best)
        st = hb_plan_fail(error, HB_ERR_LIMIT,
                          "budget %g ns: no configuration fits on %s (the fastest, %s, takes %.3g ns)", in->budget_ns,
                          hb_isa_name(isa), fastest->configuration, hb_calibration_ns(&calibration, fastest));
    if (st != HB_OK) {
        hb_calibration_close(&calibration);
        return st;
    }
    snprintf(sel->configuration, sizeof sel->configuration, "%s", best->name);
    sel->preset = (int)(best - ops->presets);
    sel->expected_error = best_entry->error + sel->dropped_bound;
    sel->expected_ns = hb_calibration_ns(&calibration, best_entry);
    out->quality = best->quality;
    out->quadrature_order = best->quadrature_order;
    out->azimuthal = best->azimuthal;
    if (lobes & ~1u) /* a preset's TT/TRT method matters only where a plan has more than R */
        out->tt_trt = best->tt_trt;
    out->table_tolerance = 0.0;
    out->lobes = lobes;
    hb_calibration_close(&calibration);
    return HB_OK;
}

/* The calibrated figures of a plain plan's configuration, for hb_plan_describe. */
int hb_plan_expected(const hb_plan *plan, char *configuration, size_t size, double *ns, double *err)
{
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    unsigned lobes = ops->lobes(&plan->options);
    const hb_preset *p = preset_of(ops, &plan->material, &plan->options, lobes);
    hb_calibration c;
    int fallback = 0, found = 0;
    if (p && hb_calibration_open(NULL, &c, NULL) == HB_OK) {
        const hb_calibration_entry *e = entry_for(&c, ops, p, plan->isa, &fallback);
        if (e && !fallback) {
            snprintf(configuration, size, "%s", p->name);
            *ns = hb_calibration_ns(&c, e), *err = e->error;
            found = 1;
        }
        hb_calibration_close(&c);
    }
    return found;
}

/* Dual scattering's terms in the bench: hb_dual_terms_at over 64 inclinations, one plan per model. */
#include "clock.h"
#include "dual.h"
#include "model_plans.h"

enum { THETAS = 64, RUNS = 3 };

static void dual_line(const hb_plan *plan, const char *name, void *context, FILE *report)
{
    (void)context;
    double best = 1e30;
    for (int r = 0; r < RUNS; r++) {
        double t0 = now_ns();
        for (int j = 0; j < THETAS; j++) {
            hb_dual_terms d = { .struct_size = sizeof d };
            hb_dual_terms_at(plan, -1.5707963267948966 + 3.141592653589793 * (j + 0.5) / THETAS, HB_DUAL_DENSITY, &d);
        }
        double ms = (now_ns() - t0) * 1e-6;
        best = ms < best ? ms : best;
    }
    fprintf(report, "  %s (%s): %.1f ms\n", name, hb_isa_name(hb_plan_isa(plan)), best);
}

void bench_dual(const hb_material *m, FILE *report)
{
    fprintf(report, "Dual scattering's terms (hb_dual_terms_at at %d inclinations, balanced, the bench material):\n", THETAS);
    bench_each_model(m, dual_line, NULL, report);
}

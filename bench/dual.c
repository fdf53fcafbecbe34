/* Dual scattering's terms in the bench: hb_dual_terms_at over 64 inclinations, one plan per model. */
#include "clock.h"
#include "dual.h"

enum { THETAS = 64, RUNS = 3 };

void bench_dual(const hb_material *m, FILE *report)
{
    static const struct { const char *name; hb_model model; } models[] = {
        { "deon", HB_MODEL_DEON }, { "marschner", HB_MODEL_MARSCHNER }, { "huang", HB_MODEL_HUANG },
        { "chiang", HB_MODEL_CHIANG } };
    fprintf(report, "Dual scattering's terms (hb_dual_terms_at at %d inclinations, balanced, the bench material):\n", THETAS);
    for (size_t k = 0; k < sizeof models / sizeof models[0]; k++) {
        hb_options o;
        hb_options_default(&o);
        o.model = models[k].model;
        hb_plan *plan;
        if (hb_plan_create(m, &o, &plan, NULL) != HB_OK)
            continue;
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
        fprintf(report, "  %s (%s): %.1f ms\n", models[k].name, hb_isa_name(hb_plan_isa(plan)), best);
        hb_plan_destroy(plan);
    }
}

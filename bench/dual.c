/* Dual scattering's terms in the bench: hb_dual_terms_at over 64 inclinations, one plan per model. */
#include <math.h>

#include "clock.h"
#include "dual.h"
#include "model_plans.h"

enum { THETAS = 64, RUNS = 3 };

typedef struct measured {
    bench_dual_cost *costs;
    int count;
} measured;

static void dual_line(const hb_plan *plan, const char *name, void *context, FILE *report)
{
    measured *out = context;
    double best = 1e30, ghz = hb_cpu_clock_ghz();
    for (int r = 0; r < RUNS; r++) {
        double t0 = now_ns();
        for (int j = 0; j < THETAS; j++) {
            hb_dual_terms d = { .struct_size = sizeof d };
            hb_dual_terms_at(plan, -1.5707963267948966 + 3.141592653589793 * (j + 0.5) / THETAS, HB_DUAL_DENSITY, &d);
        }
        double ns = now_ns() - t0;
        best = ns < best ? ns : best;
    }
    ghz = fmax(ghz, hb_cpu_clock_ghz()); /* the faster clock: the one the minimum ran at */
    fprintf(report, "  %s (%s): %.1f ms, %.0f million cycles\n", name, hb_isa_name(hb_plan_isa(plan)), best * 1e-6,
            best * ghz * 1e-6);
    if (out->count < BENCH_DUAL_MODELS)
        out->costs[out->count++] = (bench_dual_cost){ name, hb_plan_isa(plan), best, ghz };
}

int bench_dual(const hb_material *m, FILE *report, bench_dual_cost costs[BENCH_DUAL_MODELS])
{
    fprintf(report, "Dual scattering's terms (hb_dual_terms_at at %d inclinations, balanced, the bench material, one core; "
                    "budgets in bench/budgets.txt, term dual-terms):\n", THETAS);
    measured out = { costs, 0 };
    bench_each_model(m, hb_isa_available(HB_ISA_AVX2) ? HB_ISA_AVX2 : HB_ISA_AUTO, dual_line, &out, report);
    return out.count;
}

/* The fibre-assembly reference in the bench: hb_assembly_trace on the default slab, one core. */
#include "assembly.h"
#include "clock.h"
#include "model_plans.h"

enum { PATHS = 20000, RUNS = 3 };

static void assembly_line(const hb_plan *plan, const char *name, void *context, FILE *report)
{
    hb_assembly a = *(const hb_assembly *)context;
    if (hb_plan_pdf_is_estimate(plan)) /* its pdf cannot be divided by: the sampler's weights */
        a.transport = HB_ASSEMBLY_SAMPLER_WEIGHTS;
    double best = 1e30;
    hb_assembly_result r = { .struct_size = sizeof r };
    for (int run = 0; run < RUNS; run++) {
        double t0 = now_ns();
        if (hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) != HB_OK)
            return;
        double ns = now_ns() - t0;
        best = ns < best ? ns : best;
    }
    fprintf(report, "  %s (%s, %s): %.2f million scatterings per second (%.1f per path), %.0f ns each\n", name,
            hb_isa_name(hb_plan_isa(plan)), a.transport == HB_ASSEMBLY_LIGHT_TRANSPORT ? "light's transport" : "sampler's weights",
            (double)r.events / best * 1e3, (double)r.events / (double)a.paths, best / (double)r.events);
}

void bench_assembly(const hb_material *m, FILE *report)
{
    hb_assembly a;
    hb_assembly_default(&a);
    a.paths = PATHS;
    fprintf(report, "Fibre-assembly reference (hb_assembly_trace: %d paths through the default slab, %g layers at packing %g, "
                    "batches of %d paths, one core, balanced, the bench material):\n",
            PATHS, a.layers, a.packing, HB_ASSEMBLY_BATCH);
    bench_each_model(m, HB_ISA_AUTO, assembly_line, &a, report);
}

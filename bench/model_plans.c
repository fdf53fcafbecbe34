/* The four models at balanced quality on the bench material. */
#include "model_plans.h"

void bench_each_model(const hb_material *m, hb_isa isa,
                      void (*line)(const hb_plan *plan, const char *name, void *context, FILE *report), void *context,
                      FILE *report)
{
    static const struct { const char *name; hb_model model; } models[] = {
        { "deon", HB_MODEL_DEON }, { "marschner", HB_MODEL_MARSCHNER }, { "huang", HB_MODEL_HUANG },
        { "chiang", HB_MODEL_CHIANG } };
    for (size_t k = 0; k < sizeof models / sizeof models[0]; k++) {
        hb_options o;
        hb_options_default(&o);
        o.model = models[k].model, o.isa = isa;
        hb_plan *plan;
        if (hb_plan_create(m, &o, &plan, NULL) != HB_OK)
            continue;
        line(plan, models[k].name, context, report);
        hb_plan_destroy(plan);
    }
}

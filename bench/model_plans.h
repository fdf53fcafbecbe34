/* The four models at balanced quality on the bench material, in the order the bench prints them. */
#ifndef HB_BENCH_MODEL_PLANS_H
#define HB_BENCH_MODEL_PLANS_H

#include <stdio.h>

#include "hairbsdf.h"

/* Calls line(plan, name, context, report) for each model's plan at balanced quality in the ISA isa
 * (HB_ISA_AUTO: the best; a model whose plan cannot be made is left out), and destroys the plan after. */
void bench_each_model(const hb_material *m, hb_isa isa,
                      void (*line)(const hb_plan *plan, const char *name, void *context, FILE *report), void *context,
                      FILE *report);

#endif

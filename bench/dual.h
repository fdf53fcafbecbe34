/* What dual scattering's per-fibre terms cost: hb_dual_terms_at at 64 inclinations, per model. */
#ifndef HB_BENCH_DUAL_H
#define HB_BENCH_DUAL_H

#include <stdio.h>

#include "hairbsdf.h"

/* One model's precomputation: the fastest of a few runs over 64 thetas, and the clock beside it. */
typedef struct bench_dual_cost {
    const char *model; /* the budgets' model name */
    hb_isa isa;
    double ns, ghz;
} bench_dual_cost;
#define BENCH_DUAL_MODELS 4

/* One line per model at balanced quality into report, on AVX2 where the CPU has it (the budgets'
 * ISA), and each model's cost into costs; returns how many it measured. */
int bench_dual(const hb_material *m, FILE *report, bench_dual_cost costs[BENCH_DUAL_MODELS]);

#endif

/* What dual scattering's per-fibre terms cost: hb_dual_terms_at at 64 inclinations, per model. */
#ifndef HB_BENCH_DUAL_H
#define HB_BENCH_DUAL_H

#include <stdio.h>

#include "hairbsdf.h"

/* One line per model at balanced quality into report: ms for 64 thetas (the fastest of a few runs). */
void bench_dual(const hb_material *m, FILE *report);

#endif

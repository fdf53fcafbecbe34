/* What the fibre-assembly reference costs: scattering events per second on one core, per model. */
#ifndef HB_BENCH_ASSEMBLY_H
#define HB_BENCH_ASSEMBLY_H

#include <stdio.h>

#include "hairbsdf.h"

/* One line per model into report: the default slab lit at the default angle, traced on one core
 * (no job system), its events per second (the fastest of a few runs) and the batch width. */
void bench_assembly(const hb_material *m, FILE *report);

#endif

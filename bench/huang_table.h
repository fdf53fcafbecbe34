/* How close HHH22's TT/TRT table comes to the model, per quality, beside what it costs to build. */
#ifndef HB_BENCH_HUANG_TABLE_H
#define HB_BENCH_HUANG_TABLE_H

#include <stdio.h>

/* Lines into report: per quality the table's grid, paths per Simpson node, build time, and the
 * relative error of f where f is at least 1% of its peak. */
void bench_huang_table(FILE *report);

#endif

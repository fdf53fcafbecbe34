/* What a table file saves: each table plan's build time against its load from hb_table_save's bytes. */
#ifndef HB_BENCH_TABLE_FILES_H
#define HB_BENCH_TABLE_FILES_H

#include <stdio.h>

#include "hairbsdf.h"

/* One line per table configuration into report: file size, build ms, load ms (the fastest of a few). */
void bench_table_files(const hb_material *m, FILE *report);

#endif

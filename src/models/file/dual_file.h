/* Dual-scattering table files (hb_dual_table_save, hb_dual_table_load; docs/multiple-scattering.md):
 * a material's hb_dual_table with what it was built for. Internal. */
#ifndef HB_MODELS_DUAL_FILE_H
#define HB_MODELS_DUAL_FILE_H

#include "table_file.h"

#define HB_DUAL_FILE_TERMS 27 /* per node: a_f .. sigma_b2 per channel, in hb_dual_terms' order */

/* The file's length (out NULL), or writes it: `fields` is the plan's fields section
 * (hb_table_file_fields_write), `values` thetas x HB_DUAL_FILE_TERMS doubles (may be NULL when out is). */
size_t hb_dual_file_write(hb_model model, int thetas, double d_f, double d_b, const unsigned char *fields,
                          size_t fields_size, const double *values, unsigned char *out);

/* Checks a file against the plan (length, format, checksum, model, every field, the terms finite)
 * and gives its node count, density factors and a pointer to its values (still little-endian bytes
 * inside the caller's file). */
hb_status hb_dual_file_read(const hb_plan *plan, const unsigned char *bytes, size_t size, int *thetas, double *d_f,
                            double *d_b, const unsigned char **values, hb_error *error);

/* Value k of a checked file. */
double hb_dual_file_value(const unsigned char *values, size_t k);

#endif

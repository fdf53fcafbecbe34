/* Dual-scattering table files (docs/multiple-scattering.md): a material's hb_dual_table
 * (hb_dual_table_save, hb_dual_table_load) and an engine-wide hb_dual_engine (hb_dual_engine_save,
 * hb_dual_engine_load), each with what it was built for. Internal. */
#ifndef HB_MODELS_DUAL_FILE_H
#define HB_MODELS_DUAL_FILE_H

#include "table_file.h"

#define HB_DUAL_FILE_TERMS 27  /* per node: a_f .. sigma_b2 per channel, in hb_dual_terms' order */
#define HB_DUAL_ENGINE_TERMS 6 /* per node: a_f, a_b, alpha_f, beta_f2, alpha_b, beta_b2 of one channel */

/* The file's length (out NULL), or writes it: `fields` is the plan's fields section
 * (hb_table_file_fields_write), `values` thetas x HB_DUAL_FILE_TERMS doubles (may be NULL when out is). */
size_t hb_dual_file_write(hb_model model, int thetas, double d_f, double d_b, const unsigned char *fields,
                          size_t fields_size, const double *values, unsigned char *out);

/* Checks a file against the plan (length, format, checksum, model, every field, the terms finite)
 * and gives its node count, density factors and a pointer to its values (still little-endian bytes
 * inside the caller's file). */
hb_status hb_dual_file_read(const hb_plan *plan, const unsigned char *bytes, size_t size, int *thetas, double *d_f,
                            double *d_b, const unsigned char **values, hb_error *error);

/* An engine-wide table's file, as hb_dual_file_write: the base plan's fields, the axes and d_b, and
 * HB_DUAL_ENGINE_TERMS doubles per node in hb_dual_engine_nodes' order. */
size_t hb_dual_engine_file_write(hb_model model, const hb_dual_engine_axes *axes, double d_b,
                                 const unsigned char *fields, size_t fields_size, const double *values,
                                 unsigned char *out);

/* Checks an engine table's file against the base plan as hb_dual_file_read does and gives its axes
 * (struct_size set; their ranges are the caller's to check), d_b and values. */
hb_status hb_dual_engine_file_read(const hb_plan *plan, const unsigned char *bytes, size_t size,
                                   hb_dual_engine_axes *axes, double *d_b, const unsigned char **values,
                                   hb_error *error);

/* Value k of a checked file. */
double hb_dual_file_value(const unsigned char *values, size_t k);

#endif

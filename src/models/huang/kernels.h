/* HHH22's kernels for one ISA: src/models/huang/kernels.c, compiled once per ISA into
 * hb_<isa>_huang_kernels. */
#ifndef HB_HUANG_KERNELS_H
#define HB_HUANG_KERNELS_H

#include <stddef.h>

#include "constants.h"
#include "kernel/streams.h"

typedef void (*hb_huang_angles_fn)(const hb_huang *huang, size_t n, hb_angles_soa in, hb_rgb_soa out,
                                   size_t *invalid);
typedef void (*hb_huang_vectors_fn)(const hb_huang *huang, size_t n, hb_vectors_soa in, hb_rgb_soa out,
                                    size_t *invalid);
typedef void (*hb_huang_sample_fn)(const hb_huang *huang, size_t n, const hb_sample_batch *b, size_t *invalid);
typedef void (*hb_huang_pdf_fn)(const hb_huang *huang, size_t n, const hb_pair_batch *in, float *pdf, size_t *invalid);
/* One table row (theta_i, phi_i): n_sum * n_delta * 3 values. */
typedef void (*hb_huang_table_row_fn)(const hb_huang *huang, float theta_i, float phi_i, const hb_huang_table_build *build,
                                      float *row);

typedef struct hb_huang_kernels {
    hb_huang_angles_fn angles;
    hb_huang_vectors_fn vectors;
    hb_huang_sample_fn sample;
    hb_huang_pdf_fn pdf;
    hb_huang_table_row_fn table_row;
} hb_huang_kernels;

#endif

/* The dual-scattering radiance kernel's per-ISA table (src/dual/kernels.c). Internal. */
#ifndef HB_DUAL_KERNELS_H
#define HB_DUAL_KERNELS_H

#include "constants.h"

/* A batch of hb_dual_eval: directions, fibres and the direct visibility (NULL: the default). */
typedef struct hb_dual_batch {
    hb_angles_soa angles;
    const float *fibres, *direct;
} hb_dual_batch;

typedef struct hb_dual_kernels {
    void (*eval)(const struct hb_dual_table *table, size_t n, const hb_dual_batch *in, hb_rgb_soa out,
                 size_t *invalid);
} hb_dual_kernels;

#endif

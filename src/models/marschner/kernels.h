/* MJC03's kernels for one ISA: src/models/marschner/kernels.c, compiled once per ISA into
 * hb_<isa>_marschner_kernels. */
#ifndef HB_MARSCHNER_KERNELS_H
#define HB_MARSCHNER_KERNELS_H

#include <stddef.h>

#include "constants.h"
#include "kernel/streams.h"

typedef void (*hb_gaussian_angles_fn)(const hb_gaussian_lobe *lobe, size_t n, hb_angles_soa in, float *out,
                                      size_t *invalid);
typedef void (*hb_gaussian_vectors_fn)(const hb_gaussian_lobe *lobe, size_t n, hb_vectors_soa in, float *out,
                                       size_t *invalid);
typedef void (*hb_marschner_angles_fn)(const hb_marschner *mjc, size_t n, hb_angles_soa in, hb_rgb_soa out,
                                       size_t *invalid);
typedef void (*hb_marschner_vectors_fn)(const hb_marschner *mjc, size_t n, hb_vectors_soa in, hb_rgb_soa out,
                                        size_t *invalid);

typedef struct hb_marschner_kernels {
    hb_gaussian_angles_fn longitudinal_angles;
    hb_gaussian_vectors_fn longitudinal_vectors;
    hb_marschner_angles_fn angles;
    hb_marschner_vectors_fn vectors;
    void (*sample)(const hb_marschner *mjc, size_t n, const hb_sample_batch *b, size_t *invalid);
    void (*pdf)(const hb_marschner *mjc, size_t n, const hb_pair_batch *in, float *pdf, size_t *invalid);
    void (*absorbing)(const hb_marschner *mjc, size_t n, const hb_absorbing_batch *in, hb_rgb_soa out,
                      size_t *invalid); /* f at each sample's absorption */
} hb_marschner_kernels;

#endif

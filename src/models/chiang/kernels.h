/* CBTB16's kernels for one ISA: src/models/chiang/kernels.c, compiled once per ISA into
 * hb_<isa>_chiang_kernels. */
#ifndef HB_CHIANG_KERNELS_H
#define HB_CHIANG_KERNELS_H

#include <stddef.h>

#include "constants.h"
#include "kernel/streams.h"

typedef struct hb_chiang_kernels {
    /* far field (the mean over h) */
    void (*angles)(const hb_chiang *c, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid);
    void (*vectors)(const hb_chiang *c, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid);
    void (*sample)(const hb_chiang *c, size_t n, const hb_sample_batch *b, size_t *invalid);
    /* the pdf, and f where out is not NULL, in one pass */
    void (*f_pdf)(const hb_chiang *c, size_t n, const hb_pair_batch *in, const hb_rgb_soa *out, float *pdf,
                  size_t *invalid);
    /* f at each sample's absorption: far field (angles or vectors), near field at h */
    void (*absorbing)(const hb_chiang *c, size_t n, const hb_absorbing_batch *in, hb_rgb_soa out, size_t *invalid);
    void (*near_absorbing)(const hb_chiang *c, size_t n, const hb_absorbing_near *in, hb_rgb_soa out, size_t *invalid);
    /* near field, at each sample's h */
    void (*near)(const hb_chiang *c, size_t n, hb_near_soa in, hb_rgb_soa out, size_t *invalid);
    /* calls of at most near_few_max samples on the float M_p path, each alone (kernels.c) */
    void (*near_few)(const hb_chiang *c, size_t n, hb_near_soa in, hb_rgb_soa out, size_t *invalid);
    int near_few_max;
    void (*sample_near)(const hb_chiang *c, size_t n, hb_sample_streams in, hb_sample_out out, size_t *invalid);
    void (*pdf_near)(const hb_chiang *c, size_t n, hb_near_soa in, float *pdf, size_t *invalid);
    /* k wavelengths per sample: f and the pdf near-field or far, the near-field sampler */
    void (*spectral)(const hb_chiang *c, size_t n, const hb_spectral_batch *b, size_t *invalid);
    /* f alone at h, calls of at most near_few_max samples on the float M_p path (as near_few) */
    void (*spectral_few)(const hb_chiang *c, size_t n, const hb_spectral_batch *b, size_t *invalid);
    void (*sample_spectral)(const hb_chiang *c, size_t n, const hb_spectral_sample_batch *b, size_t *invalid);
} hb_chiang_kernels;

#endif

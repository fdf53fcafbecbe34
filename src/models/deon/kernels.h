/* dFH11's kernels for one ISA: src/models/deon/kernels.c, compiled once per ISA into
 * hb_<isa>_deon_kernels. */
#ifndef HB_DEON_KERNELS_H
#define HB_DEON_KERNELS_H

#include <stddef.h>

#include "constants.h"
#include "kernel/streams.h"

typedef void (*hb_longitudinal_angles_fn)(const hb_longitudinal *lobe, size_t n, hb_angles_soa in,
                                          float *out, size_t *invalid);
typedef void (*hb_longitudinal_vectors_fn)(const hb_longitudinal *lobe, size_t n, hb_vectors_soa in,
                                           float *out, size_t *invalid);

typedef void (*hb_deon_angles_fn)(const hb_deon *deon, size_t n, hb_angles_soa in, hb_rgb_soa out,
                                  size_t *invalid);
typedef void (*hb_deon_vectors_fn)(const hb_deon *deon, size_t n, hb_vectors_soa in, hb_rgb_soa out,
                                   size_t *invalid);
typedef void (*hb_deon_sample_fn)(const hb_deon *deon, size_t n, const hb_sample_batch *b, size_t *invalid);
typedef void (*hb_deon_pdf_fn)(const hb_deon *deon, size_t n, const hb_pair_batch *in, float *pdf, size_t *invalid);
typedef void (*hb_deon_few_fn)(const hb_deon *deon, size_t n, hb_angles_soa in, hb_rgb_soa out, float *pdf,
                               size_t *invalid);
typedef void (*hb_deon_f_pdf_fn)(const hb_deon *deon, size_t n, const hb_pair_batch *in, hb_rgb_soa out,
                                 float *pdf, size_t *invalid);

typedef void (*hb_deon_absorbing_fn)(const hb_deon *deon, size_t n, const hb_absorbing_batch *in, hb_rgb_soa out,
                                     size_t *invalid);
typedef void (*hb_deon_near_absorbing_fn)(const hb_deon *deon, size_t n, const hb_absorbing_near *in, hb_rgb_soa out,
                                          size_t *invalid);
typedef void (*hb_deon_near_fn)(const hb_deon *deon, size_t n, hb_near_soa in, hb_rgb_soa out, size_t *invalid);
typedef void (*hb_deon_spectral_fn)(const hb_deon *deon, size_t n, const hb_spectral_batch *b, size_t *invalid);
typedef void (*hb_deon_pdf_near_fn)(const hb_deon *deon, size_t n, hb_near_soa in, float *pdf, size_t *invalid);
typedef void (*hb_deon_sample_near_fn)(const hb_deon *deon, size_t n, hb_sample_streams in, hb_sample_out out,
                                       size_t *invalid);

typedef void (*hb_deon_sample_spectral_fn)(const hb_deon *deon, size_t n, const hb_spectral_sample_batch *b,
                                           size_t *invalid);

typedef void (*hb_deon_np_row_fn)(const hb_deon *deon, float cos_theta_d, size_t n, const float *phi, float *out);

typedef struct hb_deon_kernels {
    int width;                                          /* samples per block: the ISA's HB_W */
    hb_longitudinal_angles_fn longitudinal_angles[2];   /* indexed by hb_i0 */
    hb_longitudinal_vectors_fn longitudinal_vectors[2]; /* indexed by hb_i0 */
    hb_deon_angles_fn angles[2];                        /* indexed by hb_i0 */
    /* calls (and a batch's partial last block) of at most few_max samples of a standard quadrature
     * plan, each sample alone with the quadrature's nodes across the lanes: f, and the pdf where it
     * is not NULL (kernels.c) */
    hb_deon_few_fn angles_few[2];
    int few_max;
    hb_deon_vectors_fn vectors[2];
    hb_deon_sample_fn sample[2];
    hb_deon_pdf_fn pdf[2];
    hb_deon_f_pdf_fn f_pdf[2]; /* f (quadrature plans) and pdf in one pass */
    hb_deon_absorbing_fn absorbing[2]; /* f (quadrature plans) at each sample's absorption */
    hb_deon_near_fn near[2];   /* at each sample's offset h (near.h) */
    hb_deon_near_fn near_few[2]; /* at most near_few_max samples, each alone with its lobes across the lanes */
    hb_deon_near_absorbing_fn near_absorbing[2]; /* at each sample's h and absorption */
    /* k wavelengths: the near field's f and pdf (every plan), the far field's f (standard quadrature plans) */
    hb_deon_spectral_fn spectral[2];
    int near_few_max;
    hb_deon_pdf_near_fn pdf_near[2];
    hb_deon_sample_near_fn sample_near[2];
    hb_deon_sample_spectral_fn sample_spectral[2]; /* the near-field sampler at k wavelengths */
    hb_deon_np_row_fn np_row; /* one row of the N_p table, out[(k * slots + s) * 3 + c] */
} hb_deon_kernels;


#endif

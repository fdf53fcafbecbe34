/* What the sampling, pdf and fused kernels read and write: the public batches, with directions
 * as angles or as fibre-frame unit vectors (hb_sample_vectors, hb_pdf_vectors, hb_eval_pdf_vectors).
 * A kernel converts vectors to angles as it loads a block and back as it stores one (batch.h), so
 * one kernel serves both forms and the sample index keying a Monte-Carlo estimate is the same in
 * both. Internal. */
#ifndef HB_KERNEL_STREAMS_H
#define HB_KERNEL_STREAMS_H

#include "hairbsdf.h"

/* Direction pairs: vectors when vectors.wi_x is not NULL, else angles. */
typedef struct hb_pair_batch {
    hb_angles_soa angles;
    hb_vectors_soa vectors;
} hb_pair_batch;

/* The near field's angles and h with a per-sample absorption sigma_a[c][k] (hb_eval_near_absorption). */
typedef struct hb_absorbing_near {
    hb_near_soa near;
    const float *sigma_a[3];
} hb_absorbing_near;

/* Direction pairs with a per-sample absorption sigma_a[c][k] (hb_eval_angles_absorption). */
typedef struct hb_absorbing_batch {
    hb_pair_batch pairs;
    const float *sigma_a[3];
} hb_absorbing_batch;

/* A spectral batch (hb_eval_near_spectral, hb_eval_angles_spectral, hb_pdf_near_spectral): the near
 * field's angles and h (h NULL: the far field), the wavelengths' absorptions sigma_a[j][k], and f's
 * planes and the pdf where they are not NULL. */
typedef struct hb_spectral_batch {
    hb_near_soa near;
    int wavelengths;
    const float *const *sigma_a;
    float *const *f;
    float *pdf;
} hb_spectral_batch;

/* A sampling batch: w_o from wo when wo[0] is not NULL, else from in.theta_o and in.phi_o; w_i to
 * wi when wi[0] is not NULL (invalid samples get (0, 0, 0)), else to out.theta_i and out.phi_i. */
/* A sampling batch's input planes as the kernels read them: the caller's, with u copied up to the
 * plan's dimensions (h: the near field's offsets, else NULL). */
typedef struct hb_sample_streams {
    const float *theta_o, *phi_o, *h;
    const float *u[HB_SAMPLE_DIMENSIONS];
} hb_sample_streams;

/* A near-field sampling batch at the wavelengths' absorptions (hb_sample_near_spectral). */
typedef struct hb_spectral_sample_batch {
    hb_sample_streams in;
    int wavelengths;
    const float *const *sigma_a;
    hb_sample_spectral_out out;
} hb_spectral_sample_batch;

typedef struct hb_sample_batch {
    hb_sample_streams in;
    const float *wo[3];
    hb_sample_out out;
    float *wi[3];
} hb_sample_batch;

#endif

/* Helpers of the sampling tests (test_sample.c, test_sample_huang.c): batches of samples for one
 * w_o in static storage, expected cell probabilities from hb_pdf_angles, and a chi-square test. */
#ifndef HB_TEST_SAMPLING_H
#define HB_TEST_SAMPLING_H

#include "test.h"

enum { HB_TEST_MAX_SAMPLES = 200000 };

/* One batch (too large for the stack): inputs, outputs, and scratch for f and a second pdf. */
typedef struct hb_sample_buffers {
    float to[HB_TEST_MAX_SAMPLES], po[HB_TEST_MAX_SAMPLES], u[HB_SAMPLE_DIMENSIONS][HB_TEST_MAX_SAMPLES];
    float ti[HB_TEST_MAX_SAMPLES], pi[HB_TEST_MAX_SAMPLES], pdf[HB_TEST_MAX_SAMPLES], w[3][HB_TEST_MAX_SAMPLES];
    float f[3][HB_TEST_MAX_SAMPLES], pdf2[HB_TEST_MAX_SAMPLES], h[HB_TEST_MAX_SAMPLES];
} hb_sample_buffers;
extern hb_sample_buffers hb_samples;

/* n samples for w_o = (theta_o, phi_o) with hb_uniforms(seed); checks none is reported invalid. */
void hb_test_sample_batch(hb_test_ctx *t, const hb_plan *plan, size_t n, double theta_o, double phi_o,
                          unsigned long long seed);

/* The same at offset h through hb_sample_near (near-field plans). */
void hb_test_sample_batch_near(hb_test_ctx *t, const hb_plan *plan, size_t n, double theta_o, double phi_o, double h,
                               unsigned long long seed);

/* A seed for hb_uniforms drawn from the test's own (printed) seed. */
unsigned long long hb_test_next_seed(hb_test_ctx *t);

/* Cells of equal solid angle: sin(theta_i) in nt strips, phi_i in np sectors (nt * np <= 4096);
 * prob[nt * np] gets each cell's integral of hb_pdf_angles (of_pdf) or of f's first channel, over
 * sub x sub parts of it (2 sub x 2 sub in the two strips at each pole) by gl x gl Gauss-Legendre
 * (gl 6 or 8; np * (2 sub gl)^2 <= HB_TEST_MAX_SAMPLES). Returns the sum. */
double hb_test_cell_integrals(const hb_plan *plan, int of_pdf, double theta_o, double phi_o, int nt, int np, int sub,
                              int gl, double *prob);

/* The same at offset h, of hb_pdf_near or hb_eval_near's first channel. */
double hb_test_cell_integrals_near(const hb_plan *plan, int of_pdf, double theta_o, double phi_o, double h, int nt,
                                   int np, int sub, int gl, double *prob);

/* The absorptions of a spectral sampler's wavelengths, the same for every sample. */
typedef struct hb_test_wavelengths {
    int count;
    float sigma_a[HB_WAVELENGTHS_MAX];
} hb_test_wavelengths;

/* The same of hb_pdf_near_spectral at those absorptions, at offset h. */
double hb_test_cell_integrals_spectral(const hb_plan *plan, const hb_test_wavelengths *spectral, double theta_o,
                                       double phi_o, double h, int nt, int np, int sub_default, int gl, double *prob);

/* For the batch's first n samples, with hb_pdf_angles at the sampled directions in pdf2 and f in f:
 * the pdf is the sampled one bit for bit, weights and pdfs are finite and >= 0, and the weights are
 * f / pdf (their largest relative difference raises *worst_weight). */
void hb_test_check_sampled_weights(hb_test_ctx *t, size_t n, const char *label, double *worst_weight);

/* Chi-square of the batch in hb_samples (n samples) against prob over nt x np equal-area cells
 * (cells expecting fewer than 5 pooled); returns the p-value (Wilson-Hilferty), *chi2 and *cells. */
double hb_test_chi_square(size_t n, const double *prob, double total, int nt, int np, double *chi2, int *cells);

/* The sampler's estimate of f in each of nt x np equal-area cells (the sum of the batch's first-channel
 * weights in the cell over n) against f_cells (hb_test_cell_integrals of f): the largest z-score over
 * the cells with 20 samples or more and at least 1e-3 of f (elsewhere rare large weights make the sample
 * variance an underestimate); *cells gets how many were compared and *uncompared the share of f in the
 * others. Unlike a chi-square against the pdf's cell integrals, it needs
 * no quadrature of the pdf, so it holds where the pdf has integrable singularities (caustics). */
double hb_test_weighted_cells(size_t n, const double *f_cells, int nt, int np, int *cells, double *uncompared);

/* The upper tail of the chi-square distribution with k degrees of freedom (Wilson-Hilferty). */
double hb_test_chi_square_tail(double x, double k);

#endif

/* Helpers of the sampling tests: see sampling.h. */
#include <math.h>
#include <string.h>

#include "sampling.h"

hb_sample_buffers hb_samples;

/* The batch at offset h (near field), or far-field where h is NaN. */
static void sample_batch(hb_test_ctx *t, const hb_plan *plan, size_t n, double theta_o, double phi_o, double h,
                         unsigned long long seed)
{
    hb_sample_buffers *b = &hb_samples;
    float *u[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        u[d] = b->u[d];
    hb_uniforms(seed, 0, n, hb_plan_sample_dimensions(plan), u);
    for (size_t k = 0; k < n; k++) {
        b->to[k] = (float)theta_o;
        b->po[k] = (float)phi_o;
        b->h[k] = (float)h;
    }
    hb_sample_out out = { b->ti, b->pi, b->pdf, { b->w[0], b->w[1], b->w[2] } };
    hb_eval_report report;
    if (isnan(h)) {
        hb_sample_in in = { b->to, b->po, (const float *const[]){ b->u[0], b->u[1], b->u[2], b->u[3], b->u[4], b->u[5], b->u[6], b->u[7] } };
        CHECK(t, hb_sample_angles(plan, n, &in, &out, &report) == HB_OK, "hb_sample_angles failed");
    } else {
        hb_sample_near_in in = { b->to, b->po, b->h,
                                 (const float *const[]){ b->u[0], b->u[1], b->u[2], b->u[3], b->u[4], b->u[5], b->u[6], b->u[7] } };
        CHECK(t, hb_sample_near(plan, n, &in, &out, &report) == HB_OK, "hb_sample_near failed");
    }
    CHECK(t, report.invalid == 0, "%zu samples reported invalid", report.invalid);
}

void hb_test_sample_batch(hb_test_ctx *t, const hb_plan *plan, size_t n, double theta_o, double phi_o,
                          unsigned long long seed)
{
    sample_batch(t, plan, n, theta_o, phi_o, NAN, seed);
}

void hb_test_sample_batch_near(hb_test_ctx *t, const hb_plan *plan, size_t n, double theta_o, double phi_o, double h,
                               unsigned long long seed)
{
    sample_batch(t, plan, n, theta_o, phi_o, h, seed);
}

unsigned long long hb_test_next_seed(hb_test_ctx *t) { return (unsigned long long)(hb_test_uniform(t) * 0x1p53); }

void hb_test_check_sampled_weights(hb_test_ctx *t, size_t n, const char *label, double *worst_weight)
{
    hb_sample_buffers *b = &hb_samples;
    for (size_t i = 0; i < n; i++) {
        CHECK(t, b->pdf2[i] == b->pdf[i], "%s sample %zu: hb_pdf_angles %.9g, sampled pdf %.9g", label, i, b->pdf2[i],
              b->pdf[i]);
        if (b->pdf[i] > 0.0f)
            for (int k = 0; k < 3; k++)
                *worst_weight = fmax(*worst_weight, fabs(b->w[k][i] - b->f[k][i] / b->pdf[i]) / fmax(b->w[k][i], 1e-30));
        CHECK(t, isfinite(b->w[0][i]) && b->w[0][i] >= 0.0f && isfinite(b->pdf[i]) && b->pdf[i] >= 0.0f,
              "%s sample %zu: weight %g pdf %g", label, i, b->w[0][i], b->pdf[i]);
    }
}

/* Gauss-Legendre nodes and weights on [-1, 1] for gl = 6 and 8. */
static void gauss_rule(int gl, const double **x, const double **w)
{
    static const double x6[6] = { -0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                                  0.2386191860831969, 0.6612093864662645, 0.9324695142031521 };
    static const double w6[6] = { 0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                                  0.4679139345726910, 0.3607615730481386, 0.1713244923791704 };
    static const double x8[8] = { -0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                  -0.1834346424956498, 0.1834346424956498, 0.5255324099163290,
                                  0.7966664774136267, 0.9602898564975363 };
    static const double w8[8] = { 0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                  0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                  0.2223810344533745, 0.1012285362903763 };
    *x = gl == 8 ? x8 : x6;
    *w = gl == 8 ? w8 : w6;
}

/* Each cell is integrated in (theta_i, phi_i) with dw = cos(theta) dtheta dphi, which is smooth
 * up to the poles (in sin(theta), a lobe at a pole has a square-root edge), split into sub x sub
 * parts (twice as many each way in the two strips at each pole, where lobes crowd) with a gl x gl
 * rule. One strip of cells at a time through the buffers' scratch. */
/* spectral: NULL, or the absorption of each wavelength (hb_pdf_near_spectral, the same at every node) */
static double cell_integrals(const hb_plan *plan, int of_pdf, double theta_o, double phi_o, double h,
                             const hb_test_wavelengths *spectral, int nt, int np, int sub_default, int gl, double *prob)
{
    hb_sample_buffers *b = &hb_samples;
    const double *x, *w;
    gauss_rule(gl, &x, &w);
    double total = 0.0;
    static double weight[HB_TEST_MAX_SAMPLES];
    for (int a = 0; a < nt; a++) {
        int sub = a < 2 || a >= nt - 2 ? 2 * sub_default : sub_default;
        int per_cell = sub * sub * gl * gl, side = sub * gl;
        double dphi = 2.0 * M_PI / (np * sub);
        double lo = asin(-1.0 + 2.0 * a / nt), dtheta = (asin(fmin(1.0, -1.0 + 2.0 * (a + 1) / nt)) - lo) / sub;
        size_t n = 0;
        for (int c = 0; c < np; c++)
            for (int i = 0; i < side; i++)
                for (int j = 0; j < side; j++, n++) {
                    double theta = lo + (i / gl + 0.5 * (1.0 + x[i % gl])) * dtheta;
                    b->ti[n] = (float)theta;
                    b->pi[n] = (float)(-M_PI + (c * sub + j / gl + 0.5 * (1.0 + x[j % gl])) * dphi);
                    b->to[n] = (float)theta_o;
                    b->po[n] = (float)phi_o;
                    b->h[n] = (float)h;
                    weight[n] = w[i % gl] * w[j % gl] * cos(theta) * dtheta * dphi / 4.0;
                }
        hb_angles_soa far = { b->ti, b->pi, b->to, b->po };
        hb_near_soa near = { b->ti, b->pi, b->to, b->po, b->h };
        hb_rgb_soa f = { b->pdf2, b->f[1], b->f[2] };
        if (spectral) {
            static float sigma[HB_WAVELENGTHS_MAX][HB_TEST_MAX_SAMPLES];
            const float *planes[HB_WAVELENGTHS_MAX];
            for (int j = 0; j < spectral->count; j++) {
                for (size_t k = 0; k < n; k++)
                    sigma[j][k] = spectral->sigma_a[j];
                planes[j] = sigma[j];
            }
            hb_pdf_near_spectral(plan, n, near, (hb_spectral_absorption){ spectral->count, planes }, b->pdf2, NULL);
        } else if (of_pdf)
            isnan(h) ? hb_pdf_angles(plan, n, far, b->pdf2, NULL) : hb_pdf_near(plan, n, near, b->pdf2, NULL);
        else
            isnan(h) ? hb_eval_angles(plan, n, far, f, NULL) : hb_eval_near(plan, n, near, f, NULL);
        n = 0;
        for (int c = 0; c < np; c++) {
            double p = 0.0;
            for (int k = 0; k < per_cell; k++, n++)
                p += weight[n] * b->pdf2[n];
            prob[a * np + c] = p;
            total += p;
        }
    }
    return total;
}

double hb_test_cell_integrals(const hb_plan *plan, int of_pdf, double theta_o, double phi_o, int nt, int np,
                              int sub_default, int gl, double *prob)
{
    return cell_integrals(plan, of_pdf, theta_o, phi_o, NAN, NULL, nt, np, sub_default, gl, prob);
}

double hb_test_cell_integrals_near(const hb_plan *plan, int of_pdf, double theta_o, double phi_o, double h, int nt,
                                   int np, int sub_default, int gl, double *prob)
{
    return cell_integrals(plan, of_pdf, theta_o, phi_o, h, NULL, nt, np, sub_default, gl, prob);
}

double hb_test_cell_integrals_spectral(const hb_plan *plan, const hb_test_wavelengths *spectral, double theta_o,
                                       double phi_o, double h, int nt, int np, int sub_default, int gl, double *prob)
{
    return cell_integrals(plan, 1, theta_o, phi_o, h, spectral, nt, np, sub_default, gl, prob);
}

/* Upper tail of the chi-square distribution with k degrees of freedom (Wilson-Hilferty). */
double hb_test_chi_square_tail(double x, double k)
{
    double z = (cbrt(x / k) - (1.0 - 2.0 / (9.0 * k))) / sqrt(2.0 / (9.0 * k));
    return 0.5 * erfc(z / M_SQRT2);
}

double hb_test_chi_square(size_t n, const double *prob, double total, int nt, int np, double *chi2, int *cells)
{
    static unsigned count[4096];
    hb_sample_buffers *b = &hb_samples;
    memset(count, 0, sizeof count);
    for (size_t i = 0; i < n; i++) {
        int a = (int)floor((sin((double)b->ti[i]) + 1.0) * nt / 2.0), c = (int)floor((b->pi[i] + M_PI) * np / (2.0 * M_PI));
        a = a < 0 ? 0 : a >= nt ? nt - 1 : a;
        c = c < 0 ? 0 : c >= np ? np - 1 : c;
        count[a * np + c]++;
    }
    double pooled_expected = 0.0, pooled_observed = 0.0;
    *chi2 = 0.0;
    *cells = 0;
    for (int k = 0; k < nt * np; k++) {
        double expected = prob[k] / total * (double)n;
        if (expected < 5.0) {
            pooled_expected += expected;
            pooled_observed += count[k];
            continue;
        }
        *chi2 += (count[k] - expected) * (count[k] - expected) / expected;
        (*cells)++;
    }
    if (pooled_expected > 0.0) {
        *chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / fmax(pooled_expected, 5.0);
        (*cells)++;
    }
    return hb_test_chi_square_tail(*chi2, *cells - 1);
}

double hb_test_weighted_cells(size_t n, const double *f_cells, int nt, int np, int *cells, double *uncompared)
{
    static double sum[4096], sum2[4096];
    static unsigned count[4096];
    hb_sample_buffers *b = &hb_samples;
    memset(sum, 0, sizeof sum);
    memset(sum2, 0, sizeof sum2);
    memset(count, 0, sizeof count);
    for (size_t i = 0; i < n; i++) {
        int a = (int)floor((sin((double)b->ti[i]) + 1.0) * nt / 2.0), c = (int)floor((b->pi[i] + M_PI) * np / (2.0 * M_PI));
        a = a < 0 ? 0 : a >= nt ? nt - 1 : a;
        c = c < 0 ? 0 : c >= np ? np - 1 : c;
        sum[a * np + c] += b->w[0][i];
        sum2[a * np + c] += (double)b->w[0][i] * b->w[0][i];
        count[a * np + c]++;
    }
    double total = 0.0, worst = 0.0;
    for (int k = 0; k < nt * np; k++)
        total += f_cells[k];
    *cells = 0;
    *uncompared = 0.0;
    for (int k = 0; k < nt * np; k++) {
        double mean = sum[k] / (double)n, second = sum2[k] / (double)n;
        if (count[k] < 20 || f_cells[k] < 1e-3 * total) { /* too few samples, or too little f, for a variance:
                                                            heavy-tailed weights there make it an underestimate */
            *uncompared += f_cells[k] / total;
            continue;
        }
        double sigma = sqrt(fmax(second - mean * mean, 0.0) / (double)n);
        worst = fmax(worst, fabs(mean - f_cells[k]) / fmax(sigma, 1e-12 * total));
        ++*cells;
    }
    return worst;
}

/* The double-precision reference of the dual-scattering radiance term and the table's terms at an
 * inclination: the header's equations (Zinke et al. 2008 sec. 4, each lobe normalised to its
 * energy), sharing nothing with src/dual/kernels.c. */
#include <math.h>
#include <stddef.h>

#include "constants.h"

#define VARIANCE_MIN 1e-8
#define VARIANCE_MAX 1e8
#define COS_THETA_MIN 2.44140625e-4 /* 2^-12 */

/* The terms' nine per-channel arrays, in the struct's order from a_f to sigma_b2. */
#define TERM_DOUBLES 27
_Static_assert(offsetof(hb_dual_terms, sigma_b2) + 3 * sizeof(double) - offsetof(hb_dual_terms, a_f) ==
                   TERM_DOUBLES * sizeof(double),
               "the terms are 27 doubles without padding");

static double gaussian(double x, double variance)
{
    variance = fmin(fmax(variance, VARIANCE_MIN), VARIANCE_MAX);
    return exp(-x * x / (2.0 * variance)) / sqrt(2.0 * M_PI * variance);
}

void hb_dual_radiance_reference(const hb_dual_terms *terms, double d_f, double d_b, double theta_i, double phi_i,
                                double theta_o, double phi_o, double fibres, double visible, double f[3])
{
    double theta_h = 0.5 * (theta_i + theta_o);
    double abs_phi = fabs(remainder(phi_o - phi_i, 2.0 * M_PI));
    int back = abs_phi < M_PI_2;
    double per_solid_angle = 1.0 / (2.0 * M_PI * fmax(cos(theta_o), COS_THETA_MIN));
    for (int c = 0; c < 3; c++) {
        double spread = fibres * terms->beta_f2[c]; /* sigma_f^2 = n beta_f^2 */
        double global = (1.0 - visible) * d_f * pow(fmax(terms->a_f[c], 0.0), fibres); /* (1 - v) T_f */
        double x_back = theta_h - terms->delta_b[c];
        double back_direct = back ? terms->A_b[c] * gaussian(x_back, terms->sigma_b2[c]) : 0.0;
        double back_spread = back ? terms->A_b[c] * gaussian(x_back, terms->sigma_b2[c] + spread) : 0.0;
        /* f_G: the forward energy's azimuths |phi| / pi^2, the backward's (pi - |phi|) / pi^2 */
        double next = (terms->a_f[c] * abs_phi * gaussian(theta_h - terms->alpha_f[c], terms->beta_f2[c] + spread) +
                       terms->a_b[c] * (M_PI - abs_phi) *
                           gaussian(theta_h - terms->alpha_b[c], terms->beta_b2[c] + spread)) /
                      M_PI;
        f[c] = per_solid_angle * (visible * d_b * back_direct + global * (next + d_b * back_spread));
    }
}

void hb_dual_interpolate(const struct hb_dual_table *table, double theta, hb_dual_terms *terms)
{
    int count = table->thetas;
    double x = fmin(fmax((theta + M_PI_2) * count / M_PI - 0.5, 0.0), count - 1.0);
    int lower = (int)fmin(floor(x), count - 2.0);
    double t = x - lower;
    const double *a = (const double *)((const char *)&table->terms[lower] + offsetof(hb_dual_terms, a_f));
    const double *b = (const double *)((const char *)&table->terms[lower + 1] + offsetof(hb_dual_terms, a_f));
    double *out = (double *)((char *)terms + offsetof(hb_dual_terms, a_f));
    for (int k = 0; k < TERM_DOUBLES; k++)
        out[k] = a[k] + t * (b[k] - a[k]);
}

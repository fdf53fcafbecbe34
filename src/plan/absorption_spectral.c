/* hb_absorption_from_colour_spectral and hb_absorption_spectrum_at (docs/spectral.md): a smooth
 * absorption spectrum for any hair colour, dyed ones included, whose colour as a spectral renderer
 * shows it is that colour. */
#include <math.h>

#include "colour_fit.h"
#include "models/interface/plan.h"
#include "models/text/text.h"
#include "srgb.h"

/* The family: eq. 9's colour per wavelength, C(lambda) = S(z), z = c0 + c1 x + c2 x^2 with
 * x = (lambda - 580) / 200, S(z) = 1/2 + z / (2 sqrt(1 + z^2)): the sigmoid of a quadratic that
 * Jakob and Hanika 2019 use to lift RGB to smooth bounded spectra, so C stays in (0, 1) and
 * sigma_a = (log C / d)^2 is smooth and non-negative at every wavelength. -log C is formed from
 * 1 - S or S without cancellation: 1 - S(z) = 1 / (2 r (r + z)) for z >= 0, S(z) = 1 / (2 r (r - z))
 * for z < 0, r = sqrt(1 + z^2). */
static double minus_log_colour(const double c[3], double wavelength)
{
    double x = (wavelength - 580.0) / 200.0, z = c[0] + x * (c[1] + x * c[2]), r = sqrt(1.0 + z * z);
    return z >= 0.0 ? -log1p(-0.5 / (r * (r + z))) : log(2.0 * r * (r - z));
}

/* log of the linear sRGB of the family's colour (srgb.h's reduction over 41 bands). */
static void log_srgb(const double c[3], double out[3])
{
    double colour[HB_CIE_BANDS], rgb[3];
    for (int b = 0; b < HB_CIE_BANDS; b++)
        colour[b] = exp(-minus_log_colour(c, hb_cie_band(b)));
    hb_srgb_of_spectrum(colour, rgb);
    for (int k = 0; k < 3; k++)
        out[k] = log(fmax(rgb[k], 1e-300));
}

static double cost_of(const double c[3], const double want[3])
{
    double r[3], cost = 0.0;
    log_srgb(c, r);
    for (int k = 0; k < 3; k++)
        cost += (r[k] - want[k]) * (r[k] - want[k]);
    return cost;
}

/* 3x3 solve by Cramer's rule; 0 when singular. */
static int solve3(const double A[3][3], const double g[3], double x[3])
{
    double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                 A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    if (!(fabs(det) > 0.0))
        return 0;
    for (int k = 0; k < 3; k++) {
        double M[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                M[i][j] = j == k ? g[i] : A[i][j];
        x[k] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) /
               det;
    }
    return 1;
}

#define STEPS 200 /* Levenberg-Marquardt steps: a fixed count, enough for the tests' 26 colours */

hb_status hb_absorption_from_colour_spectral(const double rgb[3], double beta_n, hb_absorption_spectrum *spectrum,
                                             hb_error *error)
{
    double sigma[3];
    if (!spectrum)
        return hb_plan_fail(error, HB_ERR_NULL, "spectrum must not be NULL");
    hb_status st = hb_absorption_from_colour(rgb, beta_n, sigma, error); /* the checks */
    if (st != HB_OK)
        return st;
    double want[3], mean = 0.0;
    for (int k = 0; k < 3; k++)
        want[k] = log(rgb[k]), mean += rgb[k] / 3.0;
    /* from a flat spectrum of the colour's mean, the least squares of the log colour over the
     * quadratic's coefficients: damped Gauss-Newton, the Jacobian by central differences */
    double m = fmin(mean, 0.999), c[3] = { (2.0 * m - 1.0) / sqrt(1.0 - (2.0 * m - 1.0) * (2.0 * m - 1.0)), 0.0, 0.0 };
    double damping = 1e-3, cost = cost_of(c, want);
    for (int step = 0; step < STEPS && cost > 1e-28; step++) {
        double r[3], J[3][3];
        log_srgb(c, r);
        for (int k = 0; k < 3; k++)
            r[k] -= want[k];
        for (int p = 0; p < 3; p++) {
            double plus[3] = { c[0], c[1], c[2] }, minus[3] = { c[0], c[1], c[2] }, a[3], b[3], h = 1e-6;
            plus[p] += h;
            minus[p] -= h;
            log_srgb(plus, a);
            log_srgb(minus, b);
            for (int k = 0; k < 3; k++)
                J[k][p] = (a[k] - b[k]) / (2.0 * h);
        }
        double A[3][3] = { { 0 } }, g[3] = { 0 }, delta[3];
        for (int k = 0; k < 3; k++)
            for (int p = 0; p < 3; p++) {
                g[p] += J[k][p] * r[k];
                for (int q = 0; q < 3; q++)
                    A[p][q] += J[k][p] * J[k][q];
            }
        for (int p = 0; p < 3; p++)
            A[p][p] *= 1.0 + damping;
        if (!solve3(A, g, delta)) {
            damping *= 10.0;
            continue;
        }
        double next[3] = { c[0] - delta[0], c[1] - delta[1], c[2] - delta[2] }, trial = cost_of(next, want);
        if (trial <= cost) {
            c[0] = next[0], c[1] = next[1], c[2] = next[2], cost = trial;
            damping = fmax(damping * 0.3, 1e-12);
        } else {
            damping *= 10.0;
        }
    }
    for (int k = 0; k < 3; k++)
        spectrum->shape[k] = c[k];
    spectrum->depth = hb_colour_fit_depth(beta_n);
    return HB_OK;
}

hb_status hb_absorption_spectrum_at(const hb_absorption_spectrum *spectrum, double wavelength, double *sigma_a)
{
    static const char call[] = "hb_absorption_spectrum_at";
    if (!spectrum || !sigma_a)
        return hb_fail_null(call, !spectrum ? "spectrum" : "sigma_a");
    if (!(wavelength >= 300.0 && wavelength <= 1000.0))
        return hb_fail(HB_ERR_PARAM, "%s: wavelength = %g nm is outside [300, 1000]", call, wavelength);
    if (!(spectrum->depth > 0.0 && isfinite(spectrum->shape[0] + spectrum->shape[1] + spectrum->shape[2])))
        return hb_fail(HB_ERR_PARAM, "%s: the spectrum (depth %g) is not one hb_absorption_from_colour_spectral made",
                       call, spectrum->depth);
    double s = minus_log_colour(spectrum->shape, wavelength) / spectrum->depth; /* eq. 9 inverted */
    *sigma_a = s * s;
    return HB_OK;
}

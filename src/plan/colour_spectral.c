/* hb_melanin_from_colour_spectral (docs/spectral.md): the melanin concentrations whose colour, as a
 * spectral renderer shows it, comes closest to a hair colour. */
#include <math.h>

#include "colour_fit.h"
#include "models/interface/plan.h"
#include "models/text/text.h"
#include "srgb.h"

/* log of the linear sRGB of eq. 9's colour at every band's melanin absorption. */
static void log_colour(double eumelanin, double pheomelanin, double depth, double out[3])
{
    double c[HB_CIE_BANDS], rgb[3];
    for (int b = 0; b < HB_CIE_BANDS; b++) {
        double sigma_a;
        hb_melanin_absorption_spectral(eumelanin, pheomelanin, hb_cie_band(b), &sigma_a);
        c[b] = exp(-depth * sqrt(sigma_a));
    }
    hb_srgb_of_spectrum(c, rgb);
    for (int k = 0; k < 3; k++)
        out[k] = log(fmax(rgb[k], 1e-300));
}

#define STEPS 40 /* Gauss-Newton steps: converged to 1e-12 in the round trips (tests/test_spectral.c) */

hb_status hb_melanin_from_colour_spectral(const double rgb[3], double beta_n, double *eumelanin, double *pheomelanin,
                                          hb_error *error)
{
    double x[2];
    hb_status st = hb_melanin_from_colour(rgb, beta_n, &x[0], &x[1], error); /* the start, and the checks */
    if (st != HB_OK)
        return st;
    double depth = hb_colour_fit_depth(beta_n), want[3];
    for (int k = 0; k < 3; k++)
        want[k] = log(rgb[k]);
    /* least squares of the log colour over (eumelanin, pheomelanin) >= 0: damped Gauss-Newton, the
     * Jacobian by central differences, each step projected onto the quadrant */
    double damping = 1e-3;
    for (int step = 0; step < STEPS; step++) {
        double r[3], J[3][2], cost = 0.0;
        log_colour(x[0], x[1], depth, r);
        for (int k = 0; k < 3; k++)
            r[k] -= want[k], cost += r[k] * r[k];
        for (int p = 0; p < 2; p++) {
            double hx = 1e-6 * fmax(x[p], 1e-3), plus[2] = { x[0], x[1] }, minus[2] = { x[0], x[1] }, a[3], b[3];
            plus[p] += hx;
            minus[p] = fmax(minus[p] - hx, 0.0);
            log_colour(plus[0], plus[1], depth, a);
            log_colour(minus[0], minus[1], depth, b);
            for (int k = 0; k < 3; k++)
                J[k][p] = (a[k] - b[k]) / (plus[p] - minus[p]);
        }
        double A[2][2] = { { 0 } }, g[2] = { 0 };
        for (int k = 0; k < 3; k++)
            for (int p = 0; p < 2; p++) {
                g[p] += J[k][p] * r[k];
                for (int q = 0; q < 2; q++)
                    A[p][q] += J[k][p] * J[k][q];
            }
        double a00 = A[0][0] * (1.0 + damping), a11 = A[1][1] * (1.0 + damping), det = a00 * a11 - A[0][1] * A[1][0];
        if (!(det > 0.0))
            break;
        double next[2] = { fmax(x[0] - (a11 * g[0] - A[0][1] * g[1]) / det, 0.0),
                           fmax(x[1] - (a00 * g[1] - A[1][0] * g[0]) / det, 0.0) };
        double trial[3], trial_cost = 0.0;
        log_colour(next[0], next[1], depth, trial);
        for (int k = 0; k < 3; k++)
            trial_cost += (trial[k] - want[k]) * (trial[k] - want[k]);
        if (trial_cost <= cost) {
            x[0] = next[0], x[1] = next[1];
            damping = fmax(damping * 0.3, 1e-9);
        } else {
            damping *= 10.0;
        }
    }
    *eumelanin = x[0];
    *pheomelanin = x[1];
    return HB_OK;
}

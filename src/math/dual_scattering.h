/* Zinke, Yuksel, Weber and Keyser 2008's multiple back-scattering from a fibre's forward and backward
 * energies and moments (their eqs. 14-17), in double, per channel. Model-free: any scattering
 * model's hemisphere integrals feed it (src/api/dual.c). Internal. */
#ifndef HB_MATH_DUAL_SCATTERING_H
#define HB_MATH_DUAL_SCATTERING_H

#include <math.h>

/* Eqs. 14, 15: A_b = A_1 + A_3, the light that returns after one (A_1) or three (A_3) backward
 * scatterings between any number of forward ones, A_1 = a_b a_f^2 / (1 - a_f^2) and
 * A_3 = a_b^3 a_f^2 / (1 - a_f^2)^2. */
static inline double hb_dual_back_energy(double a_f, double a_b)
{
    double f2 = a_f * a_f, rest = 1.0 - f2;
    return a_b * f2 / rest + a_b * a_b * a_b * f2 / (rest * rest);
}

/* Eq. 16: the shift of multiple back-scattering, alpha_b (1 - 2 a_b^2 / (1 - a_f^2)^2) +
 * alpha_f (2 (1 - a_f^2)^2 + 4 a_f^2 a_b^2) / (1 - a_f^2)^3. */
static inline double hb_dual_back_shift(double a_f, double a_b, double alpha_f, double alpha_b)
{
    double f2 = a_f * a_f, b2 = a_b * a_b, rest = 1.0 - f2;
    return alpha_b * (1.0 - 2.0 * b2 / (rest * rest)) + alpha_f * (2.0 * rest * rest + 4.0 * f2 * b2) / (rest * rest * rest);
}

/* Eq. 17: its standard deviation, (1 + d_b a_f^2) (a_b sqrt(2 beta_f^2 + beta_b^2) + a_b^3
 * sqrt(2 beta_f^2 + 3 beta_b^2)) / (a_b + a_b^3 (2 beta_f + 3 beta_b)); returned squared. */
static inline double hb_dual_back_variance(double a_f, double a_b, double beta_f2, double beta_b2, double d_b)
{
    double b3 = a_b * a_b * a_b, denominator = a_b + b3 * (2.0 * sqrt(beta_f2) + 3.0 * sqrt(beta_b2));
    if (!(denominator > 0.0))
        return 0.0;
    double sigma = (1.0 + d_b * a_f * a_f) *
                   (a_b * sqrt(2.0 * beta_f2 + beta_b2) + b3 * sqrt(2.0 * beta_f2 + 3.0 * beta_b2)) / denominator;
    return sigma * sigma;
}

/* What dual scattering adds to a fibre's own scattering, as a share of its energy a_f + a_b: the
 * larger of the local back-scattering d_b A_b (fully lit) and the global term at one fibre,
 * d_f a_f (a_f + a_b + d_b A_b), the largest over n >= 1 of d_f a_f^n (its energies), since a_f < 1. */
static inline double hb_dual_share(double a_f, double a_b, double A_b, double d_f, double d_b)
{
    double own = a_f + a_b;
    if (!(own > 0.0))
        return 0.0;
    return fmax(d_b * A_b, d_f * a_f * (own + d_b * A_b)) / own;
}

#endif

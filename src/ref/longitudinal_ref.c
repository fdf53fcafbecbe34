/* dFH11's M_p (eq. 7) in double, with its own Bessel function: the longitudinal term dFH11 and
 * CBTB16 share. */
#include <math.h>

#include "reference.h"

/* I0(x) - 1 = sum_{k>=1} (x^2/4)^k / (k!)^2: positive terms, no cancellation. */
static double i0_series_minus1(double x)
{
    double u = 0.25 * x * x, term = 1.0, sum = 0.0;
    for (int k = 1; k == 1 || term > 1e-18 * sum; k++) {
        term *= u / ((double)k * k);
        sum += term;
    }
    return sum;
}

/* sqrt(2 pi x) e^-x I0(x) ~ sum_k ((2k-1)!!)^2 / (k! (8x)^k); past x = 30 the terms
 * fall below 1e-17 long before they start to grow again. */
static double i0_asymptotic_sum(double x)
{
    double term = 1.0, sum = 1.0;
    for (int k = 1; k < 60 && term > 1e-18 * sum; k++) {
        term *= (2.0 * k - 1.0) * (2.0 * k - 1.0) / (8.0 * k * x);
        sum += term;
    }
    return sum;
}

double hb_ref_bessel_i0e(double x)
{
    x = fabs(x);
    if (x <= 30.0)
        return (1.0 + i0_series_minus1(x)) * exp(-x);
    return i0_asymptotic_sum(x) / sqrt(2.0 * M_PI * x);
}

double hb_ref_log_bessel_i0(double x)
{
    x = fabs(x);
    if (x <= 30.0)
        return log1p(i0_series_minus1(x));
    return x + log(i0_asymptotic_sum(x)) - 0.5 * log(2.0 * M_PI * x);
}

/* log of dFH11 eq. 15, sum_{i<=10} (x^2/4)^i / (i!)^2. */
static double log_i0_series_paper_ref(double x)
{
    double u = 0.25 * x * x, term = 1.0, sum = 1.0;
    for (int i = 1; i <= 10; i++) {
        term *= u / ((double)i * i);
        sum += term;
    }
    return log(sum);
}

double hb_ref_longitudinal(double v, double theta_i, double theta_o, hb_i0 i0)
{
    /* eq. 7 with csch(1/v)/(2v) = e^(-1/v) / (v (1 - e^(-2/v))) and
     * -(1 + sin_i sin_o)/v = -(1 - cos(theta_i + theta_o))/v - x. */
    double x = cos(theta_i) * cos(theta_o) / v, ax = fabs(x);
    double half = sin(0.5 * (theta_i + theta_o));
    double log_norm = -log(v) - log(-expm1(-2.0 / v));
    double exponent = log_norm - 2.0 * half * half / v - x;
    if (i0 == HB_I0_PAPER)
        return exp(exponent + log_i0_series_paper_ref(ax));
    return exp(exponent + ax) * hb_ref_bessel_i0e(ax);
}

/* dFH11 eq. 7 is a von Mises-Fisher lobe of concentration 1/v about the mirror direction, projected
 * on the fibre axis: 1 - cos psi = -v log(u1 + (1 - u1) e^(-2/v)), azimuth 2 pi u2. theta_i is the
 * atan2 of the direction's axial and across-axis parts, so it keeps its digits at the poles, where
 * asin of the axial part alone loses half of them. */
double hb_ref_longitudinal_sample(double v, double t, double u1, double u2)
{
    double sin_o = sin(t), cos_o = fabs(cos(t)), zeta = 2.0 * M_PI * u2;
    double one_minus_cos_psi = fmin(-v * log(u1 + (1.0 - u1) * exp(-2.0 / v)), 2.0);
    double cos_psi = 1.0 - one_minus_cos_psi, sin_psi = sqrt(fmax(one_minus_cos_psi * (2.0 - one_minus_cos_psi), 0.0));
    double axial = sin_psi * cos(zeta) * cos_o - cos_psi * sin_o;   /* the mirror is at -t */
    double across = cos_psi * cos_o + sin_psi * cos(zeta) * sin_o;  /* in the plane of the axis and the mirror */
    double aside = sin_psi * sin(zeta);                             /* out of that plane */
    return atan2(axial, hypot(across, aside));
}

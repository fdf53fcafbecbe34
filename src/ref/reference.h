/* Double-precision references. They share only the equations with the SIMD
 * kernels: their own Bessel function, libm trigonometry, no float anywhere. Internal. */
#ifndef HB_REFERENCE_H
#define HB_REFERENCE_H

#include <stddef.h>
#include "hairbsdf.h"

/* e^-|x| I0(x) to double precision (power series below |x| = 30, asymptotic expansion above). */
double hb_ref_bessel_i0e(double x);
/* log I0(x), relative-accurate also as x -> 0 (where it is x^2/4). */
double hb_ref_log_bessel_i0(double x);

/* dFH11 eq. 7, M_p(v, theta_i, theta_o); with HB_I0_PAPER, I0 is the series of eq. 15. */
double hb_ref_deon_longitudinal(double v, double theta_i, double theta_o, hb_i0 i0);

/* MJC03's longitudinal term g(mean, beta; theta_h) cos(theta_i) / cos^2(theta_d), with
 * cos^2(theta_d) floored at 1e-8 as in the kernels. */
double hb_ref_marschner_longitudinal(double beta, double mean, double theta_i, double theta_o);

/* Unpolarised Fresnel reflectance of a dielectric of relative index eta at incidence cos_i. */
double hb_ref_fresnel(double eta, double cos_i);

/* dFH11 eq. 11: the wrapped Gaussian of standard deviation beta, by its direct series
 * (Gaussians at x - 2 pi k, |k| <= terms), its Fourier series (n <= terms), or converged. */
double hb_ref_detector_direct(double beta, double x, int terms);
double hb_ref_detector_fourier(double beta, double x, int terms);
double hb_ref_detector(double beta, double x);

/* dFH11 f = sum_p M_p N_p (eqs. 7, 10-14) for the plan's lobes, N_p converged to 1e-10. */
void hb_ref_deon(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3]);

/* Reference batch evaluation of a plan's term: writes f and returns the invalid count. */
size_t hb_ref_eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out);
size_t hb_ref_eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out);

#endif

/* MJC03's double-precision reference (reference*.c of this folder): the paper's equations in
 * double, sharing nothing with the kernels but the equations; reached through hb_ref_marschner_ops.
 * Internal. */
#ifndef HB_MARSCHNER_REFERENCE_H
#define HB_MARSCHNER_REFERENCE_H

#include "models/interface/plan.h"
#include "ref/reference.h"

extern const hb_reference_ops hb_ref_marschner_ops;

/* MJC03's longitudinal term g(mean, beta; theta_h) cos(theta_i) / cos^2(theta_d), with
 * cos^2(theta_d) floored at 1e-8 as in the kernels. */
double hb_ref_marschner_longitudinal(double beta, double mean, double theta_i, double theta_o);

/* MJC03 full model f = sum_p M_p N_p cos(theta_i) / cos^2(theta_d) for the plan's lobes. */
void hb_ref_marschner(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3]);
#define HB_REF_MARSCHNER_CHANNELS HB_WAVELENGTHS_MAX /* RGB's three, or a spectral call's wavelengths */

/* N_p of MJC03 (caustic treatment included) at theta_d and phi for k channels of absorptions sigma_a;
 * cos_phi_sum = cos(phi_i + phi_o) for eta*. */
void hb_ref_marschner_azimuthal(const hb_plan *plan, int p, int k, const double *sigma_a, double theta_d, double phi,
                                double cos_phi_sum, double *N);
/* The survey's corrected Fresnel F(eta', eta'', angle): eta' for the perpendicular, eta'' for the
 * parallel component; F(1/eta', 1/eta'', gamma_t) inside the fibre. */
double hb_ref_marschner_fresnel(double eta_perp, double eta_par, double angle);
/* Roots gamma_i in [-pi/2, pi/2] of phi(p, gamma_i) = phi (mod 2 pi) for index eta', by scanning
 * and bisection: of the survey's cubic phi_hat, or (exact = 1) of 2 p gamma_t - 2 gamma_i + p pi. */
#define HB_REF_MAX_ROOTS 8
int hb_ref_marschner_roots(int p, double eta_prime, double phi, int exact, double roots[HB_REF_MAX_ROOTS]);

#endif

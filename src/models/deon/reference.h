/* dFH11's double-precision reference (reference*.c of this folder): the paper's equations in
 * double, sharing nothing with the kernels but the equations; reached through hb_ref_deon_ops.
 * Internal. */
#ifndef HB_DEON_REFERENCE_H
#define HB_DEON_REFERENCE_H

#include "models/interface/plan.h"
#include "ref/reference.h"

extern const hb_reference_ops hb_ref_deon_ops;

/* dFH11 eq. 11: the wrapped Gaussian of standard deviation beta, by its direct series
 * (Gaussians at x - 2 pi k, |k| <= terms), its Fourier series (n <= terms), or converged. */
double hb_ref_detector_direct(double beta, double x, int terms);
double hb_ref_detector_fourier(double beta, double x, int terms);
double hb_ref_detector(double beta, double x);

#define HB_REF_DEON_CHANNELS HB_WAVELENGTHS_MAX /* RGB's three, or a spectral call's wavelengths */

/* dFH11 attenuation A(p, h) (eqs. 12-14, at k channels of absorptions sigma_a; A[R] = 1 under eq.
 * 12's half-angle Fresnel, which the caller applies) and exit azimuth Phi(p, h) (eq. 8) at
 * h = sin(gamma_i) for every order up to pmax; A[HB_LOBE_RESIDUAL] is the sum over the orders above pmax. */
void hb_ref_deon_node(const hb_plan *plan, int k, const double *sigma_a, double sin2_theta_d, double gamma_i,
                      double A[HB_MAX_LOBES + 1][HB_REF_DEON_CHANNELS], double Phi[HB_MAX_LOBES]);

/* dFH11 f = sum_p M_p N_p (eqs. 7, 10-14) for the plan's lobes, N_p converged to 1e-10. */
void hb_ref_deon(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3]);

/* dFH11 sampling (docs/sampling.md): the kernels' procedure in double, from five uniform
 * numbers, and its solid-angle pdf. */
void hb_ref_deon_sample(const hb_plan *plan, double theta_o, double phi_o, const double u[5], double *theta_i,
                        double *phi_i);
double hb_ref_deon_pdf(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o);

/* dFH11 at offset h (the near field, src/models/deon/near.h): f, the sampler from four numbers and
 * its pdf, in double. */
void hb_ref_deon_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                      double f[3]);
void hb_ref_deon_sample_near(const hb_plan *plan, double theta_o, double phi_o, double h, const double u[4],
                             double *theta_i, double *phi_i);
double hb_ref_deon_pdf_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h);

/* f at k wavelengths of absorptions sigma_a (hb_*_spectral on a reference plan): the near field at h,
 * or the far field where h is NaN; *pdf (may be NULL) the near-field sampler's, 0 for the far field. */
void hb_ref_deon_spectral(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                          int k, const double *sigma_a, double *f, double *pdf);

/* The near-field sampler at k wavelengths and its pdf: the lobe by A(p, h) averaged over the k. */
void hb_ref_deon_sample_spectral(const hb_plan *plan, double theta_o, double phi_o, double h, const double *u, int k,
                                 const double *sigma_a, double *theta_i, double *phi_i);
double hb_ref_deon_pdf_spectral(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                                double h, int k, const double *sigma_a);

#endif

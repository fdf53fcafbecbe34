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

/* dFH11 attenuation A(p, h) (eqs. 12-14, RGB; A[R] = 1 under eq. 12's half-angle Fresnel, which the
 * caller applies) and exit azimuth Phi(p, h) (eq. 8) at h = sin(gamma_i) for every order up to
 * pmax; A[HB_LOBE_RESIDUAL] is the sum over the orders above pmax. */
void hb_ref_deon_node(const hb_plan *plan, double sin2_theta_d, double gamma_i, double A[HB_MAX_LOBES + 1][3],
                      double Phi[HB_MAX_LOBES]);

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

#endif

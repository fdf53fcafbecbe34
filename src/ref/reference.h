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
/* theta_i drawn from eq. 7's M_p(v, theta_i, t) cos(theta_i) by the vMF inverse CDF (u1 the polar
 * angle, u2 its azimuth about the mirror direction -t), t = theta_o - shift in [-pi/2, pi/2]. */
double hb_ref_longitudinal_sample(double v, double t, double u1, double u2);

/* MJC03's longitudinal term g(mean, beta; theta_h) cos(theta_i) / cos^2(theta_d), with
 * cos^2(theta_d) floored at 1e-8 as in the kernels. */
double hb_ref_marschner_longitudinal(double beta, double mean, double theta_i, double theta_o);

/* MJC03 full model f = sum_p M_p N_p cos(theta_i) / cos^2(theta_d) for the plan's lobes. */
void hb_ref_marschner(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3]);
/* N_p of MJC03 (caustic treatment included) at theta_d and phi; cos_phi_sum = cos(phi_i + phi_o) for eta*. */
void hb_ref_marschner_azimuthal(const hb_plan *plan, int p, double theta_d, double phi, double cos_phi_sum,
                                double N[3]);
/* The survey's corrected Fresnel F(eta', eta'', angle): eta' for the perpendicular, eta'' for the
 * parallel component; F(1/eta', 1/eta'', gamma_t) inside the fibre. */
double hb_ref_marschner_fresnel(double eta_perp, double eta_par, double angle);
/* Roots gamma_i in [-pi/2, pi/2] of phi(p, gamma_i) = phi (mod 2 pi) for index eta', by scanning
 * and bisection: of the survey's cubic phi_hat, or (exact = 1) of 2 p gamma_t - 2 gamma_i + p pi. */
#define HB_REF_MAX_ROOTS 8
int hb_ref_marschner_roots(int p, double eta_prime, double phi, int exact, double roots[HB_REF_MAX_ROOTS]);

/* Unpolarised Fresnel reflectance of a dielectric of relative index eta at incidence cos_i. */
double hb_ref_fresnel(double eta, double cos_i);
/* The refraction into a fibre of index eta at inclination cos_theta (>= 0) and offset angle gamma_i
 * (sin and cos given): sin and cos of gamma_t with sin gamma_t = sin gamma_i / eta' (Bravais' eta'),
 * cos gamma_t as sqrt(eta^2 - 1 + cos^2 theta cos^2 gamma_i) / sqrt(eta^2 - sin^2 theta), free of the
 * cancellation of 1 - sin^2 gamma_t as eta -> 1 and |h| -> 1; gamma_t itself from both. */
double hb_ref_refraction(double eta, double cos_theta, double sin_gamma_i, double cos_gamma_i, double *sin_gamma_t,
                         double *cos_gamma_t);

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

/* HHH22 microsurface: D(w_h, w_m) at cos_m = w_h . w_m (eq. 41 for GGX, Beckmann) and
 * Smith's Lambda for a direction at cos_w to the mesonormal (Heitz 2014). */
double hb_ref_huang_ndf(hb_ndf ndf, double roughness, double cos_m);
double hb_ref_huang_lambda(hb_ndf ndf, double roughness, double cos_w);
/* The R lobe's integral of D G rho over the visible window (eq. 12; eq. 28 over gamma for elliptical
 * fibres), by adaptive Gauss-Legendre to 1e-12 relative; G = 1 unless shadowing. */
double hb_ref_huang_r_integral(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                               int shadowing);
/* The same without G for GGX and a circular fibre from App. A, eq. 43 as printed. */
double hb_ref_huang_r_integral_analytic(const hb_plan *plan, double theta_i, double phi_i, double theta_o,
                                        double phi_o);
/* Eq. 10's 1 / cos(theta_o), with cos(theta_o) kept above a floor (half the larger of the scales'
 * pi |sin tau| and, without G, the rough surface's grazing width; at least 1e-8), times
 * min(1, cos(theta_i) / floor) for reciprocity (docs/huang.md, "At the poles"). */
double hb_ref_huang_width(const hb_plan *plan, double theta_i, double theta_o);
/* HHH22 f = S_R cos(theta_i) (eqs. 12, 28) with the plan's NDF, shadowing and fibre, integrated
 * numerically. */
void hb_ref_huang(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3]);

/* HHH22 R lobe sampling (docs/sampling.md): the mesonormal azimuths w_o sees, phi_o +- *half,
 * and the projected offsets of their ends across w_o's view (0 when w_o sees none); the kernels'
 * procedure in double from three uniform numbers; its pdf by adaptive quadrature. */
int hb_ref_huang_o_window(const hb_plan *plan, double theta_o, double phi_o, double *half, double *lo, double *hi);
void hb_ref_huang_sample(const hb_plan *plan, double theta_o, double phi_o, const double u[3], double *theta_i,
                         double *phi_i);
double hb_ref_huang_pdf(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o);

/* Half the width of the mesonormal azimuths (around a direction's own) from which a direction of
 * inclination theta sees both the macronormal and the mesonormal tilted by tau (eq. 40), or -1. */
double hb_ref_huang_half_width(double theta, double tilt);

/* A visible normal (Heitz and d'Eon 2014) of the direction o (o[2] > 0, in the mesonormal's frame)
 * from two uniform numbers: the kernels' mapping (GGX: Dupuy and Benyoub 2023; Beckmann: the visible
 * slope's CDF inverted by bisection). */
void hb_ref_huang_visible_normal(const hb_plan *plan, const double o[3], double u1, double u2, double m[3]);

/* HHH22 TT and TRT (docs/huang.md). The kernels' counter-based numbers: number
 * `counter` of sample `index` under the plan's keys. */
float hb_ref_huang_uniform(const hb_plan *plan, unsigned index, unsigned counter);
/* The kernels' estimator (eqs. 31, 32) in double with the same numbers: f_TT and f_TRT per channel. */
/* HHH22 Fig. 16: energy leaving a circular fibre lit along (theta, 0) by scattering order (R, TT,
 * TRT, beyond), by a random walk of `paths` paths; standard errors of the channel mean. */
void hb_ref_huang_orders(const hb_plan *plan, double theta, long paths, unsigned long long seed,
                         double energy[HB_ORDER_GROUPS][3], double standard_error[HB_ORDER_GROUPS]);
void hb_ref_huang_internal_mc(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                              unsigned index, double tt[3], double trt[3]);
/* The same integrals by nested quadrature: over the entry azimuth phi_m1 either Simpson on the plan's
 * nodes (simpson = 1: what the estimator's mean is) or composite Gauss-Legendre with phi_points
 * points (simpson = 0); over each visible-normal pair (the estimator's numbers) composite
 * Gauss-Legendre with tt_points (TT) or trt_points (TRT) points per dimension (TT's in a variable
 * that crowds them at the ends of [0, 1], Sidi's sin^2 transformation). */
void hb_ref_huang_internal(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                           int simpson, int phi_points, int tt_points, int trt_points, double tt[3], double trt[3]);
/* The points the reference quality uses (docs/huang.md: their convergence). */
#define HB_REF_HUANG_PHI_POINTS 192
#define HB_REF_HUANG_TT_POINTS 32
#define HB_REF_HUANG_TRT_POINTS 12

/* CBTB16 (chiang_ref.c): f near-field at h and the far field (the mean over h, adaptive), each
 * with its sampler's pdf (pdf may be NULL); the kernels' sampler in double at h from four numbers. */
void hb_ref_chiang_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                        double f[3], double *pdf);
void hb_ref_chiang_far(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                       double f[3], double *pdf);
void hb_ref_chiang_sample_near(const hb_plan *plan, double theta_o, double phi_o, double h, const double u[4],
                               double *theta_i, double *phi_i);

/* A model's double-precision procedures, as its model.c names them (hb_model_ops.reference) and
 * the plan carries them (hb_plan.reference): f of the plan's term, the sampler and its pdf, and at
 * an offset h for a near-field model, the furnace by order. NULL where the model has none. */
typedef struct hb_reference_ops {
    void (*eval)(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3]);
    void (*eval_near)(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                      double f[3]);
    void (*sample)(const hb_plan *plan, double theta_o, double phi_o, const double *u, double *theta_i,
                   double *phi_i);
    double (*pdf)(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o);
    void (*sample_near)(const hb_plan *plan, double theta_o, double phi_o, double h, const double *u,
                        double *theta_i, double *phi_i);
    double (*pdf_near)(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h);
    /* The white furnace by scattering order, from a random walk through a circular fibre (hb_furnace_orders). */
    void (*orders)(const hb_plan *plan, double theta, long paths, unsigned long long seed,
                   double energy[HB_ORDER_GROUPS][3], double standard_error[HB_ORDER_GROUPS]);
} hb_reference_ops;

extern const hb_reference_ops hb_ref_deon_ops, hb_ref_marschner_ops, hb_ref_huang_ops, hb_ref_chiang_ops;

/* theta and phi of a fibre-frame vector (atan2 of its parts, in double); 0 when it is not a unit
 * vector within HB_UNIT_TOLERANCE or not finite. */
int hb_ref_direction(float x, float y, float z, double *theta, double *phi);

/* The plan's term at one direction pair, in double (three channels; src/ref/reference.c). */
void hb_ref_eval_pair(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3]);

/* Reference batch evaluation of a plan's term: writes f and returns the invalid count. */
size_t hb_ref_eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out);
size_t hb_ref_eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out);

/* Near-field models (CBTB16) at offset h: f, the sampler and its pdf, in double. */
void hb_ref_eval_near_pair(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                           double f[3]);
void hb_ref_sample_near(const hb_plan *plan, double theta_o, double phi_o, double h, const double *u,
                        double *theta_i, double *phi_i);
double hb_ref_pdf_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h);

/* The plan's sampler and pdf in double (the models that have one: dFH11, HHH22's R lobe, CBTB16). */
void hb_ref_sample(const hb_plan *plan, double theta_o, double phi_o, const double *u, double *theta_i,
                   double *phi_i);
double hb_ref_pdf(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o);

#endif

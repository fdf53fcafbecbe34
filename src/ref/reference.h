/* Double-precision references: what every model's reference shares (the Bessel function, the
 * spherical-Gaussian M_p and its sampler, the dielectric's optics), the operations through which a
 * plan reaches its model's reference, and the batch entry points over them. They share only the
 * equations with the SIMD kernels: their own Bessel function, libm trigonometry, no float anywhere.
 * Each model's own procedures are declared in src/models/<model>/reference.h. Internal. */
#ifndef HB_REFERENCE_H
#define HB_REFERENCE_H

#include <stddef.h>
#include "hairbsdf.h"

/* e^-|x| I0(x) to double precision (power series below |x| = 30, asymptotic expansion above). */
double hb_ref_bessel_i0e(double x);
/* log I0(x), relative-accurate also as x -> 0 (where it is x^2/4). */
double hb_ref_log_bessel_i0(double x);

/* The spherical-Gaussian M_p of dFH11 eq. 7 (CBTB16's too), M_p(v, theta_i, theta_o); with
 * HB_I0_PAPER, I0 is the series of dFH11 eq. 15. */
double hb_ref_longitudinal(double v, double theta_i, double theta_o, hb_i0 i0);
/* theta_i drawn from eq. 7's M_p(v, theta_i, t) cos(theta_i) by the vMF inverse CDF (u1 the polar
 * angle, u2 its azimuth about the mirror direction -t), t = theta_o - shift in [-pi/2, pi/2]. */
double hb_ref_longitudinal_sample(double v, double t, double u1, double u2);

/* Unpolarised Fresnel reflectance of a dielectric of relative index eta at incidence cos_i. */
double hb_ref_fresnel(double eta, double cos_i);
/* The refraction into a fibre of index eta at inclination cos_theta (>= 0) and offset angle gamma_i
 * (sin and cos given): sin and cos of gamma_t with sin gamma_t = sin gamma_i / eta' (Bravais' eta'),
 * cos gamma_t as sqrt(eta^2 - 1 + cos^2 theta cos^2 gamma_i) / sqrt(eta^2 - sin^2 theta), free of the
 * cancellation of 1 - sin^2 gamma_t as eta -> 1 and |h| -> 1; gamma_t itself from both. */
double hb_ref_refraction(double eta, double cos_theta, double sin_gamma_i, double cos_gamma_i, double *sin_gamma_t,
                         double *cos_gamma_t);

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
    /* k wavelengths at absorptions sigma_a[0..k) per unit radius (hb_*_spectral): f and the pdf (pdf may
     * be NULL) near-field at h, or the far field where h is NaN; the near-field sampler at h, its lobe
     * chosen by the wavelengths' mean attenuations. */
    void (*spectral)(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                     int k, const double *sigma_a, double *f, double *pdf);
    void (*sample_spectral)(const hb_plan *plan, double theta_o, double phi_o, double h, const double *u, int k,
                            const double *sigma_a, double *theta_i, double *phi_i);
    /* The white furnace by scattering order, from a random walk through a circular fibre (hb_furnace_orders). */
    void (*orders)(const hb_plan *plan, double theta, long paths, unsigned long long seed,
                   double energy[HB_ORDER_GROUPS][3], double standard_error[HB_ORDER_GROUPS]);
} hb_reference_ops;

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

/* HHH22's double-precision reference (reference*.c of this folder): the paper's equations in
 * double, sharing nothing with the kernels but the equations; reached through hb_ref_huang_ops.
 * Internal. */
#ifndef HB_HUANG_REFERENCE_H
#define HB_HUANG_REFERENCE_H

#include "models/interface/plan.h"
#include "ref/reference.h"

extern const hb_reference_ops hb_ref_huang_ops;

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

#endif

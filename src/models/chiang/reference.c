/* CBTB16 in double precision (docs/chiang.md): near-field f at h, its sampler and pdf, and the
 * far field as an adaptive integral over h. M_p is dFH11 eq. 7 with this reference's own Bessel
 * function (src/ref/longitudinal_ref.c), exact to double precision at every argument (no switch between forms
 * with different errors). */
#include <math.h>

#include "math/quadrature.h"
#include "models/interface/plan.h"
#include "reference.h"
#include "state.h"

/* theta_o - shift reflected across a pole into [-pi/2, pi/2] (eq. 7 is unchanged by theta -> pi - theta). */
static double shifted(double theta_o, double shift)
{
    double t = theta_o - shift;
    return t > M_PI_2 ? M_PI - t : t < -M_PI_2 ? -M_PI - t : t;
}

static const double shift_ratio[HB_CHIANG_TERMS] = { 2.0, -1.0, -4.0, 0.0 };

#define CHANNELS HB_WAVELENGTHS_MAX /* RGB's three, or a spectral call's wavelengths */

/* A_p in k channels at absorptions sigma_a[0..k), the lobe probabilities P_p (A_p's channel mean,
 * normalised) and Phi(p, h) at h for w_o (as eval.h, in double). */
static void offset_terms(const hb_plan *plan, int k, const double *sigma_a, double theta_o, double h,
                         double A[HB_CHIANG_TERMS][CHANNELS], double P[HB_CHIANG_TERMS], double Phi[HB_CHIANG_ORDERS])
{
    double eta = plan->material.eta, cos_o = fabs(cos(theta_o)), sin_o = sin(theta_o); /* pbrt: sqrt(1 - sin^2) */
    double gamma_o = asin(h), F = hb_ref_fresnel(eta, cos_o * cos(gamma_o));
    double sin_gamma_t, cos_gamma_t; /* sin gamma_t = h / eta', Bravais' index */
    double gamma_t = hb_ref_refraction(eta, cos_o, h, sqrt((1.0 - h) * (1.0 + h)), &sin_gamma_t, &cos_gamma_t);
    double cos_theta_t = sqrt(1.0 - sin_o * sin_o / (eta * eta));
    double mean[HB_CHIANG_TERMS] = { 0.0 }, total = 0.0;
    for (int c = 0; c < k; c++) {
        double mu = sigma_a[c] * 2.0 * cos_gamma_t / cos_theta_t, T = exp(-mu);
        double one_minus_TF = (1.0 - F) - F * expm1(-mu); /* (1 - F) + F (1 - T), no cancellation */
        A[0][c] = F;
        A[1][c] = (1.0 - F) * (1.0 - F) * T;
        A[2][c] = A[1][c] * T * F;
        A[3][c] = one_minus_TF > 0.0 ? A[2][c] * T * F / one_minus_TF : 0.0;
        for (int p = 0; p < HB_CHIANG_TERMS; p++) {
            if (!hb_chiang_term_on(&hb_chiang_of(plan)->kernel, p))
                A[p][c] = 0.0;
            mean[p] += A[p][c];
        }
    }
    for (int p = 0; p < HB_CHIANG_TERMS; p++)
        total += mean[p];
    for (int p = 0; p < HB_CHIANG_TERMS; p++)
        P[p] = total > 0.0 ? mean[p] / total : 0.0;
    for (int p = 0; p < HB_CHIANG_ORDERS; p++)
        Phi[p] = 2.0 * p * gamma_t - 2.0 * gamma_o + p * M_PI;
}

/* The trimmed logistic at phi - Phi, wrapped into [-pi, pi]. */
static double logistic(double s, double x)
{
    x = fabs(remainder(x, 2.0 * M_PI));
    double e = exp(-x / s);
    return e / (s * (1.0 + e) * (1.0 + e)) / tanh(M_PI / (2.0 * s));
}

static void longitudinal(const hb_plan *plan, double theta_i, double theta_o, double M[HB_CHIANG_TERMS])
{
    for (int p = 0; p < HB_CHIANG_TERMS; p++)
        M[p] = hb_ref_longitudinal(hb_chiang_of(plan)->v[p], theta_i,
                                        shifted(theta_o, shift_ratio[p] * plan->material.alpha), HB_I0_ABRAMOWITZ);
}

/* f at h (k channels at absorptions sigma_a) and the sampler's pdf there. */
static void near_terms(const hb_plan *plan, int k, const double *sigma_a, const double M[HB_CHIANG_TERMS],
                       double theta_o, double phi, double h, double *f, double *pdf)
{
    double A[HB_CHIANG_TERMS][CHANNELS], P[HB_CHIANG_TERMS], Phi[HB_CHIANG_ORDERS], MN[HB_CHIANG_TERMS];
    offset_terms(plan, k, sigma_a, theta_o, h, A, P, Phi);
    for (int p = 0; p < HB_CHIANG_ORDERS; p++)
        MN[p] = M[p] * logistic(hb_chiang_of(plan)->s, phi - Phi[p]);
    MN[3] = M[3] / (2.0 * M_PI);
    for (int c = 0; c < k; c++)
        f[c] = 0.0;
    *pdf = 0.0;
    for (int p = 0; p < HB_CHIANG_TERMS; p++) {
        for (int c = 0; c < k; c++)
            f[c] += MN[p] * A[p][c];
        *pdf += MN[p] * P[p];
    }
}

/* f near-field at h in k channels and its pdf. */
static void near_field(const hb_plan *plan, int k, const double *sigma_a, double theta_i, double phi_i,
                       double theta_o, double phi_o, double h, double *f, double *pdf)
{
    double M[HB_CHIANG_TERMS], p;
    longitudinal(plan, theta_i, theta_o, M);
    near_terms(plan, k, sigma_a, M, theta_o, phi_o - phi_i, h, f, pdf ? pdf : &p);
}

void hb_ref_chiang_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                        double f[3], double *pdf)
{
    near_field(plan, 3, plan->sigma_a, theta_i, phi_i, theta_o, phi_o, h, f, pdf);
}

/* The far field, (1/2) integral of f over h, as an integral over gamma = asin(h) (the integrand's
 * square-root ends at h = +-1 become smooth) by 8-point Gauss-Legendre panels no wider than s / 4,
 * where the narrowest N_p moves at most twice as fast as gamma: converged to 1e-10 (tests). */
static void far_field(const hb_plan *plan, int k, const double *sigma_a, double theta_i, double phi_i,
                      double theta_o, double phi_o, double *f, double *pdf)
{
    double M[HB_CHIANG_TERMS], x[8], w[8], sum_pdf = 0.0;
    longitudinal(plan, theta_i, theta_o, M);
    hb_gauss_legendre(8, 0.0, 1.0, x, w);
    int panels = (int)ceil(M_PI / (0.25 * hb_chiang_of(plan)->s));
    double width = M_PI / panels;
    for (int c = 0; c < k; c++)
        f[c] = 0.0;
    for (int panel = 0; panel < panels; panel++)
        for (int j = 0; j < 8; j++) {
            double gamma = -M_PI_2 + (panel + x[j]) * width, g[CHANNELS], q;
            near_terms(plan, k, sigma_a, M, theta_o, phi_o - phi_i, sin(gamma), g, &q);
            double weight = 0.5 * w[j] * width * cos(gamma);
            for (int c = 0; c < k; c++)
                f[c] += weight * g[c];
            sum_pdf += weight * q;
        }
    if (pdf)
        *pdf = sum_pdf;
}

void hb_ref_chiang_far(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                       double f[3], double *pdf)
{
    far_field(plan, 3, plan->sigma_a, theta_i, phi_i, theta_o, phi_o, f, pdf);
}

/* The spectral calls: near-field at h, or the far field where h is NaN. */
static void chiang_spectral(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                            int k, const double *sigma_a, double *f, double *pdf)
{
    if (isnan(h))
        far_field(plan, k, sigma_a, theta_i, phi_i, theta_o, phi_o, f, pdf);
    else
        near_field(plan, k, sigma_a, theta_i, phi_i, theta_o, phi_o, h, f, pdf);
}

/* The kernels' sampling procedure (sample.h) in double, near-field at h from u[0..3], the lobe chosen
 * by the mean attenuations of k channels at absorptions sigma_a. */
static void sample_at(const hb_plan *plan, double theta_o, double phi_o, double h, const double *u, int k,
                      const double *sigma_a, double *theta_i, double *phi_i)
{
    double A[HB_CHIANG_TERMS][CHANNELS], P[HB_CHIANG_TERMS], Phi[HB_CHIANG_ORDERS], cumulative = 0.0;
    offset_terms(plan, k, sigma_a, theta_o, h, A, P, Phi);
    int chosen = 0;
    for (int p = 0; p < HB_CHIANG_TERMS; p++) {
        if (u[0] >= cumulative && P[p] > 0.0)
            chosen = p;
        cumulative += P[p];
    }
    double v = hb_chiang_of(plan)->v[chosen], t = shifted(theta_o, shift_ratio[chosen] * plan->material.alpha);
    *theta_i = hb_ref_longitudinal_sample(v, t, u[1], u[2]);
    double s = hb_chiang_of(plan)->s, phi;
    if (chosen == HB_CHIANG_ORDERS) {
        phi = (2.0 * u[3] - 1.0) * M_PI;
    } else {
        double q = fmax(-0.99999994, fmin(0.99999994, tanh(M_PI / (2.0 * s)) * (2.0 * u[3] - 1.0))); /* as the kernels */
        phi = Phi[chosen] + fmax(-M_PI, fmin(M_PI, s * (log1p(q) - log1p(-q))));
    }
    *phi_i = remainder(phi_o - phi, 2.0 * M_PI);
}

void hb_ref_chiang_sample_near(const hb_plan *plan, double theta_o, double phi_o, double h, const double u[4],
                               double *theta_i, double *phi_i)
{
    sample_at(plan, theta_o, phi_o, h, u, 3, plan->sigma_a, theta_i, phi_i);
}

static void chiang_eval_far(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                            double f[3])
{
    hb_ref_chiang_far(plan, theta_i, phi_i, theta_o, phi_o, f, NULL);
}

static void chiang_eval_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                             double h, double f[3])
{
    hb_ref_chiang_near(plan, theta_i, phi_i, theta_o, phi_o, h, f, NULL);
}

/* The far-field sampler draws h uniformly from the number after the near field's. */
static void chiang_sample_far(const hb_plan *plan, double theta_o, double phi_o, const double *u, double *theta_i,
                              double *phi_i)
{
    hb_ref_chiang_sample_near(plan, theta_o, phi_o, 2.0 * u[HB_CHIANG_NEAR_DIMENSIONS] - 1.0, u, theta_i, phi_i);
}

static double chiang_pdf_far(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o)
{
    double f[3], pdf;
    hb_ref_chiang_far(plan, theta_i, phi_i, theta_o, phi_o, f, &pdf);
    return pdf;
}

static double chiang_pdf_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h)
{
    double f[3], pdf;
    hb_ref_chiang_near(plan, theta_i, phi_i, theta_o, phi_o, h, f, &pdf);
    return pdf;
}

const hb_reference_ops hb_ref_chiang_ops = {
    .eval = chiang_eval_far, .eval_near = chiang_eval_near, .sample = chiang_sample_far, .pdf = chiang_pdf_far,
    .sample_near = hb_ref_chiang_sample_near, .pdf_near = chiang_pdf_near,
    .spectral = chiang_spectral, .sample_spectral = sample_at,
};

/* dFH11 references in double precision. */
#include <math.h>
#include <string.h>

#include "reference.h"
#include "models/interface/plan.h"
#include "math/quadrature.h"
#include "state.h"

double hb_ref_detector_direct(double beta, double x, int terms)
{
    x = remainder(x, 2.0 * M_PI);
    double sum = 0.0;
    for (int k = -terms; k <= terms; k++) {
        double d = x - 2.0 * M_PI * k;
        sum += exp(-d * d / (2.0 * beta * beta));
    }
    return sum / (beta * sqrt(2.0 * M_PI));
}

double hb_ref_detector_fourier(double beta, double x, int terms)
{
    double sum = 1.0;
    for (int n = 1; n <= terms; n++)
        sum += 2.0 * exp(-0.5 * n * n * beta * beta) * cos(n * x);
    return sum / (2.0 * M_PI);
}

/* eq. 11 to double precision: Gaussians out to 40 standard deviations, or the Fourier
 * series until its terms are below 1e-300. */
double hb_ref_detector(double beta, double x)
{
    if (beta < 1.0)
        return hb_ref_detector_direct(beta, x, (int)ceil((40.0 * beta + M_PI) / (2.0 * M_PI)));
    return hb_ref_detector_fourier(beta, x, (int)ceil(38.0 / beta));
}

/* The geometry dFH11's azimuthal part needs. */
typedef struct deon_geometry {
    double phi, sin2_theta_d, cos_half_io; /* cos of half the angle between w_i and w_o */
} deon_geometry;

void hb_ref_deon_node(const hb_plan *plan, int k, const double *sigma_a, double sin2_theta_d, double gamma_i,
                      double A[HB_MAX_LOBES + 1][HB_REF_DEON_CHANNELS], double Phi[HB_MAX_LOBES])
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    double eta = plan->material.eta, cos_theta_d = sqrt(1.0 - sin2_theta_d);
    double cos_theta_t = sqrt(1.0 - sin2_theta_d / (eta * eta));
    double sin_gamma_t, cos_gamma_t; /* sin gamma_t = h / eta' (sec. 5) */
    double gamma_t = hb_ref_refraction(eta, cos_theta_d, sin(gamma_i), cos(gamma_i), &sin_gamma_t, &cos_gamma_t);
    double f = hb_ref_fresnel(eta, cos_theta_d * cos(gamma_i)); /* eq. 14 */
    double T[HB_REF_DEON_CHANNELS];
    for (int c = 0; c < k; c++) {
        double mu = sigma_a[c] / cos_theta_t; /* mu_a' = mu_a / cos(theta_t) */
        T[c] = d->absorption_paper ? exp(-2.0 * mu * (1.0 + cos(2.0 * gamma_t))) : exp(-2.0 * mu * cos_gamma_t);
    }
    for (int p = 0; p <= d->pmax; p++) {
        Phi[p] = 2.0 * p * gamma_t - 2.0 * gamma_i + p * M_PI; /* eq. 8 */
        for (int c = 0; c < k; c++)
            A[p][c] = p > 0 ? (1 - f) * (1 - f) * pow(f, p - 1) * pow(T[c], p) /* eq. 13 */
                            : d->r_fresnel_offset ? f : 1.0;                   /* eq. 14, or eq. 12 later */
    }
    for (int c = 0; c < k; c++) { /* every order above pmax; 1 - f T as (1 - f) + f (1 - T), and the limit 0 at f = 1 */
        double series = (1.0 - f) + f * (1.0 - T[c]);
        A[HB_LOBE_RESIDUAL][c] = series > 0.0 ? (1 - f) * (1 - f) * pow(f, d->pmax) * pow(T[c], d->pmax + 1) / series : 0.0;
    }
}

/* eqs. 10, 12-14 for every order of the plan at one geometry, with n_panels panels of a
 * 16-point Gauss-Legendre rule over gamma_i in [0, pi/2]. N[HB_LOBE_RESIDUAL] is the residual,
 * spread uniformly in phi. */
static void azimuthal_ref(const hb_plan *plan, int k, const double *sigma_a, const deon_geometry *g, int n_panels,
                          double N[HB_MAX_LOBES + 1][HB_REF_DEON_CHANNELS])
{
    enum { RULE = 16 };
    double x[RULE], w[RULE];
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    double fresnel_r = d->r_fresnel_offset ? 1.0 : hb_ref_fresnel(plan->material.eta, g->cos_half_io); /* eq. 12 */
    memset(N, 0, sizeof(double) * (HB_MAX_LOBES + 1) * HB_REF_DEON_CHANNELS);
    for (int panel = 0; panel < n_panels; panel++) {
        hb_gauss_legendre(RULE, M_PI_2 * panel / n_panels, M_PI_2 * (panel + 1) / n_panels, x, w);
        for (int j = 0; j < RULE; j++) {
            double weight = 0.5 * w[j] * cos(x[j]), A[HB_MAX_LOBES + 1][HB_REF_DEON_CHANNELS], Phi[HB_MAX_LOBES];
            hb_ref_deon_node(plan, k, sigma_a, g->sin2_theta_d, x[j], A, Phi);
            for (int p = 0; p <= d->pmax; p++) {
                double beta = hb_deon_of(plan)->beta_n[p];
                double detect = hb_ref_detector(beta, g->phi - Phi[p]) + hb_ref_detector(beta, -g->phi - Phi[p]);
                for (int c = 0; c < k; c++)
                    N[p][c] += weight * A[p][c] * detect * (p == 0 ? fresnel_r : 1.0);
            }
            for (int c = 0; c < k; c++)
                N[HB_LOBE_RESIDUAL][c] += weight * A[HB_LOBE_RESIDUAL][c] / M_PI;
        }
    }
}

/* f at k channels of absorptions sigma_a: the far field, N_p converged to 1e-10. */
static void far_field(const hb_plan *plan, int k, const double *sigma_a, double theta_i, double phi_i, double theta_o,
                      double phi_o, double *f)
{
    double phi = remainder(phi_o - phi_i, 2.0 * M_PI);
    double theta_d = 0.5 * (theta_o - theta_i);
    double dot = cos(theta_i) * cos(theta_o) * cos(phi) + sin(theta_i) * sin(theta_o);
    deon_geometry g = { phi, sin(theta_d) * sin(theta_d), sqrt(fmax(0.0, 0.5 * (1.0 + dot))) };
    /* panels: start where a panel is narrower than the narrowest detector, double until converged */
    double beta_min = hb_deon_of(plan)->beta_n[0];
    for (int p = 1; p <= hb_deon_of(plan)->kernel.pmax; p++)
        beta_min = fmin(beta_min, hb_deon_of(plan)->beta_n[p]);
    int panels = (int)fmax(4.0, ceil(M_PI_2 / beta_min));
    double N[HB_MAX_LOBES + 1][HB_REF_DEON_CHANNELS], previous[HB_MAX_LOBES + 1][HB_REF_DEON_CHANNELS];
    azimuthal_ref(plan, k, sigma_a, &g, panels, previous);
    for (int round = 0; round < 6; round++) {
        panels *= 2;
        azimuthal_ref(plan, k, sigma_a, &g, panels, N);
        double change = 0.0;
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            for (int c = 0; c < k; c++)
                change = fmax(change, fabs(N[p][c] - previous[p][c]) / fmax(1.0, fabs(N[p][c])));
        if (change < 1e-10)
            break;
        memcpy(previous, N, sizeof N);
    }
    for (int c = 0; c < k; c++)
        f[c] = 0.0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        if (!hb_deon_lobe_on(&hb_deon_of(plan)->kernel, p))
            continue;
        double M = hb_ref_longitudinal(hb_deon_of(plan)->v[p], theta_i, theta_o - hb_deon_of(plan)->kernel.longitudinal[p].shift,
                                            plan->options.i0);
        for (int c = 0; c < k; c++)
            f[c] += M * N[p][c];
    }
}

void hb_ref_deon(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3])
{
    far_field(plan, 3, plan->sigma_a, theta_i, phi_i, theta_o, phi_o, f);
}

/* The near field at offset h (src/models/deon/near.h): eq. 10's integrand at h per lobe,
 * A(p, |h|) D_p(+-phi - Phi(p, |h|)) with phi's sign that of h, times M_p; the residual spread
 * uniformly, 1 / (2 pi). */
static void near_field(const hb_plan *plan, int k, const double *sigma_a, double theta_i, double phi_i, double theta_o,
                       double phi_o, double h, double *f)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    double phi = remainder(phi_o - phi_i, 2.0 * M_PI), theta_d = 0.5 * (theta_o - theta_i);
    double dot = cos(theta_i) * cos(theta_o) * cos(phi) + sin(theta_i) * sin(theta_o);
    double fresnel_r = d->r_fresnel_offset ? 1.0 : hb_ref_fresnel(plan->material.eta, sqrt(fmax(0.0, 0.5 * (1.0 + dot))));
    double A[HB_MAX_LOBES + 1][HB_REF_DEON_CHANNELS], Phi[HB_MAX_LOBES], side = h < 0.0 ? -phi : phi;
    hb_ref_deon_node(plan, k, sigma_a, sin(theta_d) * sin(theta_d), asin(fmin(fabs(h), 1.0)), A, Phi);
    for (int c = 0; c < k; c++)
        f[c] = 0.0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        if (!hb_deon_lobe_on(d, p))
            continue;
        double M = hb_ref_longitudinal(hb_deon_of(plan)->v[p], theta_i, theta_o - d->longitudinal[p].shift, plan->options.i0);
        double D = p == HB_LOBE_RESIDUAL ? 0.5 / M_PI : hb_ref_detector(hb_deon_of(plan)->beta_n[p], side - Phi[p]);
        for (int c = 0; c < k; c++)
            f[c] += M * A[p][c] * D * (p == 0 ? fresnel_r : 1.0);
    }
}

void hb_ref_deon_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                      double f[3])
{
    near_field(plan, 3, plan->sigma_a, theta_i, phi_i, theta_o, phi_o, h, f);
}

void hb_ref_deon_spectral(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                          int k, const double *sigma_a, double *f, double *pdf)
{
    if (isnan(h))
        far_field(plan, k, sigma_a, theta_i, phi_i, theta_o, phi_o, f);
    else
        near_field(plan, k, sigma_a, theta_i, phi_i, theta_o, phi_o, h, f);
    if (pdf) /* the spectral sampler is the near field's */
        *pdf = isnan(h) ? 0.0 : hb_ref_deon_pdf_spectral(plan, theta_i, phi_i, theta_o, phi_o, h, k, sigma_a);
}

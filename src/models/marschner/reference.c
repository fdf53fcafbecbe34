/* MJC03 references in double precision. The roots of phi(p, gamma) = phi are found by
 * scanning gamma in [-pi/2, pi/2] for sign changes of the wrapped residual and bisecting,
 * not by the kernels' closed form, so the two paths share only the equations. */
#include <math.h>

#include "reference.h"
#include "models/interface/plan.h"
#include "state.h"

double hb_ref_marschner_longitudinal(double beta, double mean, double theta_i, double theta_o)
{
    double theta_h = 0.5 * (theta_i + theta_o), cos_d = cos(0.5 * (theta_o - theta_i));
    double g = exp(-(theta_h - mean) * (theta_h - mean) / (2.0 * beta * beta)) / (beta * sqrt(2.0 * M_PI));
    return g * fmax(cos(theta_i), 0.0) / fmax(cos_d * cos_d, 1e-8);
}

/* One component of the survey's Fresnel equations for indices (n1, n2) at angle phi:
 * F_s = (n1 cos phi - n2 cos phi') / (n1 cos phi + n2 cos phi'), sin phi' = n1 sin phi / n2, and
 * F_t = (n1 cos phi' - n2 cos phi) / (n1 cos phi' + n2 cos phi); total reflection gives 1. */
static double fresnel_s(double n1, double n2, double phi)
{
    double sin_t = n1 * sin(phi) / n2;
    if (fabs(sin_t) >= 1.0 || n2 <= 0.0)
        return 1.0;
    double cos_t = sqrt(1.0 - sin_t * sin_t), num = n1 * cos(phi) - n2 * cos_t, den = n1 * cos(phi) + n2 * cos_t;
    return den > 0.0 ? num / den : 1.0;
}

static double fresnel_t(double n1, double n2, double phi)
{
    double sin_t = n1 * sin(phi) / n2;
    if (fabs(sin_t) >= 1.0 || n2 <= 0.0)
        return 1.0;
    double cos_t = sqrt(1.0 - sin_t * sin_t), num = n1 * cos_t - n2 * cos(phi), den = n1 * cos_t + n2 * cos(phi);
    return den > 0.0 ? num / den : 1.0;
}

double hb_ref_marschner_fresnel(double eta_perp, double eta_par, double angle)
{
    double fs = fresnel_s(1.0, eta_perp, angle), ft = fresnel_t(1.0, eta_par, angle);
    return 0.5 * (fs * fs + ft * ft);
}

/* phi(p, gamma): the survey's cubic phi_hat, or the exact 2 p gamma_t - 2 gamma_i + p pi. */
static double exit_azimuth(int p, double eta_prime, double gamma, int exact)
{
    double c = asin(1.0 / eta_prime);
    if (exact)
        return 2.0 * p * asin(sin(gamma) / eta_prime) - 2.0 * gamma + p * M_PI;
    return (6.0 * p * c / M_PI - 2.0) * gamma - 8.0 * p * c / (M_PI * M_PI * M_PI) * gamma * gamma * gamma + p * M_PI;
}

static double exit_slope(int p, double eta_prime, double gamma, int exact)
{
    double c = asin(1.0 / eta_prime);
    if (exact) {
        double s = sin(gamma) / eta_prime;
        return 2.0 * p * cos(gamma) / (eta_prime * sqrt(fmax(1.0 - s * s, 1e-300))) - 2.0;
    }
    return 6.0 * p * c / M_PI - 2.0 - 24.0 * p * c / (M_PI * M_PI * M_PI) * gamma * gamma;
}

int hb_ref_marschner_roots(int p, double eta_prime, double phi, int exact, double roots[HB_REF_MAX_ROOTS])
{
    enum { SCAN = 4096 };
    int count = 0;
    double a = -M_PI_2, ra = remainder(exit_azimuth(p, eta_prime, a, exact) - phi, 2.0 * M_PI);
    for (int j = 1; j <= SCAN && count < HB_REF_MAX_ROOTS; j++) {
        double b = -M_PI_2 + M_PI * j / SCAN, rb = remainder(exit_azimuth(p, eta_prime, b, exact) - phi, 2.0 * M_PI);
        if (ra == 0.0) {
            roots[count++] = a;
        } else if (ra * rb < 0.0 && fabs(ra - rb) < M_PI) { /* a sign change, not the wrap at +-pi */
            double lo = a, hi = b, rlo = ra;
            for (int it = 0; it < 200 && hi - lo > 1e-16; it++) {
                double mid = 0.5 * (lo + hi), rm = remainder(exit_azimuth(p, eta_prime, mid, exact) - phi, 2.0 * M_PI);
                if ((rm < 0.0) == (rlo < 0.0))
                    lo = mid, rlo = rm;
                else
                    hi = mid;
            }
            roots[count++] = 0.5 * (lo + hi);
        }
        if (j == SCAN && rb == 0.0 && count < HB_REF_MAX_ROOTS)
            roots[count++] = b;
        a = b, ra = rb;
    }
    return count;
}

typedef struct ref_index {
    double eta_perp, eta_par, cubic_a, cubic_b;
} ref_index;

static ref_index index_of(double eta, double theta_d, int p)
{
    ref_index ix;
    double cos_d = fmax(cos(theta_d), 1e-6), excess = (eta - 1.0) * (eta + 1.0); /* eta^2 - 1 */
    ix.eta_perp = sqrt(excess + cos_d * cos_d) / cos_d;
    ix.eta_par = eta * eta / ix.eta_perp;
    double c = atan2(cos_d, sqrt(excess)); /* asin(1 / eta') */
    ix.cubic_a = -8.0 * p * c / (M_PI * M_PI * M_PI);
    ix.cubic_b = 6.0 * p * c / M_PI - 2.0;
    return ix;
}

/* A(p, h) at gamma_i (the survey's "Finding A"), with the plan's absorption variant. */
static void attenuation(const hb_plan *plan, int p, const ref_index *ix, int k, const double *mu, double gamma_i,
                        double *A)
{
    double fe = hb_ref_marschner_fresnel(ix->eta_perp, ix->eta_par, gamma_i);
    double gamma_t = asin(sin(gamma_i) / ix->eta_perp);
    double base = (1.0 - fe) * (1.0 - fe);
    if (p == 2) /* F(1/eta', 1/eta'', gamma_t) */
        base *= hb_ref_marschner_fresnel(1.0 / ix->eta_perp, 1.0 / ix->eta_par, gamma_t);
    double path = plan->options.absorption == HB_ABSORPTION_PAPER ? 2.0 * (1.0 + cos(2.0 * gamma_t))
                                                                  : 2.0 * cos(gamma_t);
    for (int c = 0; c < k; c++)
        A[c] = base * exp(-p * mu[c] * path);
}

/* MJC03 sec. 4.3 caustic fade and glint, the same formulas as the kernels' caustic_marschner. */
static void caustic(const hb_plan *plan, int p, const ref_index *ix, int k, const double *mu, double phi, double *N)
{
    const hb_material *m = &plan->material;
    double b = fmax(ix->cubic_b, 0.0), gamma_c = sqrt(b / (-3.0 * ix->cubic_a));
    double phi_c = 2.0 / 3.0 * b * gamma_c;
    double curvature = fabs(6.0 * ix->cubic_a * gamma_c / (cos(gamma_c) * cos(gamma_c)));
    double dh = fmin(2.0 * sqrt(2.0 * m->caustic_width / fmax(curvature, 1e-300)), m->caustic_limit);
    double fold = 1.0 / sin(M_PI / (3.0 * p));
    double x = fmin(fmax((ix->eta_perp - fold) / m->caustic_fade, 0.0), 1.0);
    double t = 1.0 - x * x * (3.0 - 2.0 * x);
    double centred = remainder(phi - p * M_PI, 2.0 * M_PI);
    double d_plus = remainder(centred - phi_c, 2.0 * M_PI), d_minus = remainder(centred + phi_c, 2.0 * M_PI);
    double w2 = 2.0 * m->caustic_width * m->caustic_width;
    double g_plus = exp(-d_plus * d_plus / w2), g_minus = exp(-d_minus * d_minus / w2);
    double A[HB_REF_MARSCHNER_CHANNELS];
    attenuation(plan, p, ix, k, mu, gamma_c, A);
    double glint = t * m->glint_scale * dh * (g_plus + g_minus) / (m->caustic_width * sqrt(2.0 * M_PI));
    for (int c = 0; c < k; c++)
        N[c] = N[c] * (1.0 - t * g_plus) * (1.0 - t * g_minus) + glint * A[c];
}

void hb_ref_marschner_azimuthal(const hb_plan *plan, int p, int k, const double *sigma_a, double theta_d, double phi,
                                double cos_phi_sum, double *N)
{
    double eta = plan->material.eta;
    if (p == 2 && hb_marschner_of(plan)->kernel.eccentric) {
        eta = fmax(hb_marschner_of(plan)->eta_star_mean + hb_marschner_of(plan)->eta_star_swing * cos_phi_sum, 1.0001);
    }
    ref_index ix = index_of(eta, theta_d, p);
    double cos_theta_t = sqrt(1.0 - sin(theta_d) * sin(theta_d) / (plan->material.eta * plan->material.eta));
    double mu[HB_REF_MARSCHNER_CHANNELS];
    for (int c = 0; c < k; c++)
        mu[c] = sigma_a[c] / cos_theta_t, N[c] = 0.0;
    double roots[HB_REF_MAX_ROOTS];
    int n = p == 0 ? 1 : hb_ref_marschner_roots(p, ix.eta_perp, phi, 0, roots);
    if (p == 0) /* gamma_i = -phi / 2 */
        roots[0] = -0.5 * remainder(phi, 2.0 * M_PI);
    for (int r = 0; r < n; r++) {
        double weight = cos(roots[r]) / (2.0 * fmax(fabs(exit_slope(p, ix.eta_perp, roots[r], 0)), 1e-6));
        double A[HB_REF_MARSCHNER_CHANNELS];
        if (p == 0)
            for (int c = 0; c < k; c++)
                A[c] = hb_ref_marschner_fresnel(ix.eta_perp, ix.eta_par, roots[r]);
        else
            attenuation(plan, p, &ix, k, mu, roots[r], A);
        for (int c = 0; c < k; c++)
            N[c] += weight * A[c];
    }
    if (p > 0)
        caustic(plan, p, &ix, k, mu, phi, N);
}

/* f at k channels of absorptions sigma_a. */
static void full(const hb_plan *plan, int k, const double *sigma_a, double theta_i, double phi_i, double theta_o,
                 double phi_o, double *f)
{
    unsigned lobes = hb_marschner_of(plan)->kernel.lobes;
    double theta_d = 0.5 * (theta_o - theta_i), theta_h = 0.5 * (theta_i + theta_o);
    double phi = remainder(phi_o - phi_i, 2.0 * M_PI), cos_phi_sum = cos(phi_i + phi_o);
    for (int c = 0; c < k; c++)
        f[c] = 0.0;
    for (int p = 0; p < 3; p++) {
        if (!(lobes >> p & 1u))
            continue;
        double N[HB_REF_MARSCHNER_CHANNELS], beta = hb_marschner_of(plan)->beta[p], x = theta_h - hb_marschner_of(plan)->mean[p];
        double M = exp(-x * x / (2.0 * beta * beta)) / (beta * sqrt(2.0 * M_PI)); /* M_p = g(alpha_p, beta_p; theta_h) */
        hb_ref_marschner_azimuthal(plan, p, k, sigma_a, theta_d, phi, cos_phi_sum, N);
        for (int c = 0; c < k; c++)
            f[c] += M * N[c];
    }
    double cos_d = cos(theta_d), projection = fmax(cos(theta_i), 0.0) / fmax(cos_d * cos_d, 1e-8);
    for (int c = 0; c < k; c++)
        f[c] *= projection;
}

void hb_ref_marschner(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3])
{
    full(plan, 3, plan->sigma_a, theta_i, phi_i, theta_o, phi_o, f);
}

/* The spectral calls on a reference plan: the far field (MJC03 has no near field: h is NaN) at k
 * wavelengths; no spectral sampler, so *pdf is 0. */
static void marschner_spectral(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                               int k, const double *sigma_a, double *f, double *pdf)
{
    (void)h;
    full(plan, k, sigma_a, theta_i, phi_i, theta_o, phi_o, f);
    if (pdf)
        *pdf = 0.0;
}

/* The plan's term: the R lobe's longitudinal term alone (HB_TERM_LONGITUDINAL), or the whole of f.
 * MJC03 has no double-precision sampler: a reference plan cannot sample. */
static void marschner_eval(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                           double f[3])
{
    if (plan->options.term == HB_TERM_LONGITUDINAL)
        f[0] = f[1] = f[2] = hb_ref_marschner_longitudinal(hb_marschner_of(plan)->beta[HB_LOBE_R],
                                                           hb_marschner_of(plan)->mean[HB_LOBE_R], theta_i, theta_o);
    else
        hb_ref_marschner(plan, theta_i, phi_i, theta_o, phi_o, f);
}

const hb_reference_ops hb_ref_marschner_ops = { .eval = marschner_eval, .spectral = marschner_spectral };

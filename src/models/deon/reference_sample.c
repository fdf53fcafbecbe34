/* dFH11 sampling and pdf in double precision (the procedure of src/models/deon/sample.h with
 * libm, the converged detector and the reference M_p; docs/sampling.md). The plan's tables
 * (node and lobe-choice weights) define the procedure and are shared. Internal. */
#include <math.h>

#include "models/interface/plan.h"
#include "reference.h"
#include "state.h"

/* c_g(theta_o) from the plan's table, as the kernels interpolate it; returns their sum. */
static double lobe_choice(const hb_deon *d, double theta_o, double c[HB_MAX_LOBES + 1])
{
    double x = fmin(fabs(theta_o), M_PI_2) * HB_LOBE_CHOICE_STEPS / M_PI_2;
    int k = (int)fmin(floor(x), HB_LOBE_CHOICE_STEPS);
    double t = x - k, total = 0.0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        c[p] = hb_deon_group_leader(d, p) ? d->lobe_choice[p][k] + t * (d->lobe_choice[p][k + 1] - d->lobe_choice[p][k]) : 0.0;
        total += c[p];
    }
    return total;
}

static void longitudinal_groups(const hb_plan *plan, double theta_i, double theta_o, double M[HB_MAX_LOBES + 1])
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        M[p] = hb_deon_group_leader(d, p) ? hb_ref_longitudinal(hb_deon_of(plan)->v[p], theta_i, theta_o - d->longitudinal[p].shift,
                                                             plan->options.i0)
                                  : 0.0;
}

/* The channels a sampler weighs its lobes by: the plan's RGB, or a spectral call's k wavelengths. */
typedef struct channels {
    int k;
    const double *sigma_a;
} channels;

static channels rgb_of(const hb_plan *plan) { return (channels){ 3, plan->sigma_a }; }

/* m_p = M_p A(p, h) (the mean over the channels) at h = sin(gamma_i); returns their sum. */
static double lobe_masses(const hb_plan *plan, channels ch, const double M[HB_MAX_LOBES + 1], double sin2_theta_d,
                          double gamma_i, double mass[HB_MAX_LOBES + 1], double Phi[HB_MAX_LOBES])
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    double A[HB_MAX_LOBES + 1][HB_REF_DEON_CHANNELS], total = 0.0;
    hb_ref_deon_node(plan, ch.k, ch.sigma_a, sin2_theta_d, gamma_i, A, Phi);
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        double sum = 0.0;
        for (int c = 0; c < ch.k; c++)
            sum += A[p][c];
        mass[p] = hb_deon_lobe_on(d, p) ? M[d->m_group[p]] * sum / ch.k : 0.0;
        total += mass[p];
    }
    return total;
}

double hb_ref_deon_pdf(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    double phi = remainder(phi_o - phi_i, 2.0 * M_PI), sin_td = sin(0.5 * (theta_o - theta_i));
    double M[HB_MAX_LOBES + 1], c[HB_MAX_LOBES + 1];
    longitudinal_groups(plan, theta_i, theta_o, M);
    double c_total = lobe_choice(d, theta_o, c), mixture = 0.0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        mixture += c[p] * M[p];
    double weight_total = 0.0, sum = 0.0;
    for (int j = 0; j < d->nodes; j++)
        weight_total += d->weight[j];
    for (int j = 0; j < d->nodes; j++) {
        double mass[HB_MAX_LOBES + 1], Phi[HB_MAX_LOBES], detected = 0.0;
        double total = lobe_masses(plan, rgb_of(plan), M, sin_td * sin_td, d->gamma_i[j], mass, Phi);
        if (total <= 0.0)
            continue;
        for (int p = 0; p <= d->pmax; p++)
            if (mass[p] > 0.0)
                detected += mass[p] * (hb_ref_detector(hb_deon_of(plan)->beta_n[p], phi - Phi[p]) +
                                       hb_ref_detector(hb_deon_of(plan)->beta_n[p], -phi - Phi[p]));
        detected += mass[HB_LOBE_RESIDUAL] / M_PI;
        sum += 0.5 * d->weight[j] / weight_total * detected / total;
    }
    return mixture / c_total * sum;
}

/* The standard normal quantile, by bisection on erfc to double precision, u clamped to
 * [2^-25, 1 - 2^-25] (5.4 standard deviations) as the kernels' vf_normal_quantile does: the
 * procedure is the same on both paths, and a u of 1e-44 cannot draw a 14-sigma azimuth whose
 * density (1e-42) makes the weight f / pdf overflow a float. */
static double normal_quantile(double u)
{
    u = fmin(fmax(u, 0x1p-25), 1.0 - 0x1p-25);
    double lo = -40.0, hi = 40.0;
    for (int k = 0; k < 200 && hi - lo > 1e-15; k++) {
        double mid = 0.5 * (lo + hi);
        if (0.5 * erfc(-mid / M_SQRT2) < u)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* Step 1: theta_i from the longitudinal mixture by u[0..2]; *rest (may be NULL) gets u[0]'s remainder
 * within the chosen group's share. */
static double sample_theta(const hb_plan *plan, double theta_o, const double *u, double *rest)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    double c[HB_MAX_LOBES + 1];
    double target = u[0] * lobe_choice(d, theta_o, c), cumulative = 0.0, below = 0.0;
    int g = -1;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        if (hb_deon_group_leader(d, p)) {
            if (g < 0 || target >= cumulative) {
                g = p;
                below = cumulative;
            }
            cumulative += c[p];
        }
    if (rest)
        *rest = fmin(fmax((target - below) / fmax(c[g], 1e-300), 0.0), 1.0 - 0x1p-24);
    double v = hb_deon_of(plan)->v[g], shift = d->longitudinal[g].shift;
    return hb_ref_longitudinal_sample(v, theta_o - shift, u[1], u[2]);
}

void hb_ref_deon_sample(const hb_plan *plan, double theta_o, double phi_o, const double u[5], double *theta_i,
                        double *phi_i)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    *theta_i = sample_theta(plan, theta_o, u, NULL);
    /* 2. the node, then the lobe in proportion to M_p A(p, h), then the side */
    int j = 0;
    while (j < d->nodes - 1 && u[3] >= d->node_cdf[j])
        j++;
    double lo = j > 0 ? d->node_cdf[j - 1] : 0.0, within = (u[3] - lo) / (d->node_cdf[j] - lo);
    double M[HB_MAX_LOBES + 1], mass[HB_MAX_LOBES + 1], Phi[HB_MAX_LOBES];
    longitudinal_groups(plan, *theta_i, theta_o, M);
    double sin_td = sin(0.5 * (theta_o - *theta_i));
    double total = lobe_masses(plan, rgb_of(plan), M, sin_td * sin_td, d->gamma_i[j], mass, Phi);
    double target = within * total;
    double cumulative = 0.0;
    int lobe = -1;
    double below = 0.0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        if (hb_deon_lobe_on(d, p)) {
            if (lobe < 0 || target >= cumulative) {
                lobe = p;
                below = cumulative;
            }
            cumulative += mass[p];
        }
    int negative_side = (target - below) / fmax(mass[lobe], 1e-300) < 0.5;
    /* 3. phi about the exit azimuth */
    double spread = lobe == HB_LOBE_RESIDUAL ? M_PI * (2.0 * u[4] - 1.0)
                                             : Phi[lobe] + hb_deon_of(plan)->beta_n[lobe] * normal_quantile(u[4]);
    double phi = remainder(negative_side ? -spread : spread, 2.0 * M_PI);
    *phi_i = remainder(phi_o - phi, 2.0 * M_PI);
}

/* The near field at offset h (src/models/deon/sample.h, deon_sample_near_of): theta_i as in the far
 * field, u[0]'s remainder picks the lobe by M_p A(p, |h|) averaged over the channels, u[3] draws phi
 * on h's side. */
static void sample_near(const hb_plan *plan, channels ch, double theta_o, double phi_o, double h, const double *u,
                        double *theta_i, double *phi_i)
{
    double rest, M[HB_MAX_LOBES + 1], mass[HB_MAX_LOBES + 1], Phi[HB_MAX_LOBES];
    *theta_i = sample_theta(plan, theta_o, u, &rest);
    longitudinal_groups(plan, *theta_i, theta_o, M);
    double sin_td = sin(0.5 * (theta_o - *theta_i));
    double target = rest * lobe_masses(plan, ch, M, sin_td * sin_td, asin(fmin(fabs(h), 1.0)), mass, Phi);
    double cumulative = 0.0;
    int lobe = -1;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        if (hb_deon_lobe_on(&hb_deon_of(plan)->kernel, p)) {
            if (lobe < 0 || target >= cumulative)
                lobe = p;
            cumulative += mass[p];
        }
    double spread = lobe == HB_LOBE_RESIDUAL ? M_PI * (2.0 * u[3] - 1.0)
                                             : Phi[lobe] + hb_deon_of(plan)->beta_n[lobe] * normal_quantile(u[3]);
    *phi_i = remainder(phi_o - remainder(h < 0.0 ? -spread : spread, 2.0 * M_PI), 2.0 * M_PI);
}

static double pdf_near(const hb_plan *plan, channels ch, double theta_i, double phi_i, double theta_o, double phi_o,
                       double h)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    double phi = remainder(phi_o - phi_i, 2.0 * M_PI), sin_td = sin(0.5 * (theta_o - theta_i));
    double M[HB_MAX_LOBES + 1], c[HB_MAX_LOBES + 1], mass[HB_MAX_LOBES + 1], Phi[HB_MAX_LOBES];
    longitudinal_groups(plan, theta_i, theta_o, M);
    double c_total = lobe_choice(d, theta_o, c), mixture = 0.0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        mixture += c[p] * M[p];
    double total = lobe_masses(plan, ch, M, sin_td * sin_td, asin(fmin(fabs(h), 1.0)), mass, Phi), detected = 0.0;
    if (total <= 0.0)
        return 0.0;
    double side = h < 0.0 ? -phi : phi;
    for (int p = 0; p <= d->pmax; p++)
        if (mass[p] > 0.0)
            detected += mass[p] * hb_ref_detector(hb_deon_of(plan)->beta_n[p], side - Phi[p]);
    detected += mass[HB_LOBE_RESIDUAL] * 0.5 / M_PI;
    return mixture / c_total * detected / total;
}

void hb_ref_deon_sample_near(const hb_plan *plan, double theta_o, double phi_o, double h, const double u[4],
                             double *theta_i, double *phi_i)
{
    sample_near(plan, rgb_of(plan), theta_o, phi_o, h, u, theta_i, phi_i);
}

double hb_ref_deon_pdf_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h)
{
    return pdf_near(plan, rgb_of(plan), theta_i, phi_i, theta_o, phi_o, h);
}

void hb_ref_deon_sample_spectral(const hb_plan *plan, double theta_o, double phi_o, double h, const double *u, int k,
                                 const double *sigma_a, double *theta_i, double *phi_i)
{
    sample_near(plan, (channels){ k, sigma_a }, theta_o, phi_o, h, u, theta_i, phi_i);
}

double hb_ref_deon_pdf_spectral(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                                double h, int k, const double *sigma_a)
{
    return pdf_near(plan, (channels){ k, sigma_a }, theta_i, phi_i, theta_o, phi_o, h);
}

/* The plan's term: eq. 7 of the R lobe alone (HB_TERM_LONGITUDINAL), or the whole of f. */
static void deon_eval(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3])
{
    if (plan->options.term == HB_TERM_LONGITUDINAL)
        f[0] = f[1] = f[2] = hb_ref_longitudinal(hb_deon_of(plan)->v[HB_LOBE_R], theta_i,
                                                      theta_o - hb_deon_of(plan)->kernel.longitudinal[HB_LOBE_R].shift,
                                                      plan->options.i0);
    else
        hb_ref_deon(plan, theta_i, phi_i, theta_o, phi_o, f);
}

const hb_reference_ops hb_ref_deon_ops = {
    .eval = deon_eval, .eval_near = hb_ref_deon_near, .sample = hb_ref_deon_sample, .pdf = hb_ref_deon_pdf,
    .sample_near = hb_ref_deon_sample_near, .pdf_near = hb_ref_deon_pdf_near, .spectral = hb_ref_deon_spectral,
    .sample_spectral = hb_ref_deon_sample_spectral,
};

/* The constants dFH11's sampler reads (docs/sampling.md), fixed at plan creation. */
#include <math.h>

#include "deon.h"
#include "state.h"

/* Fresnel reflectance of an unpolarised beam entering at cos_i (dFH11 eq. 14's F). */
static double fresnel(double eta, double cos_i)
{
    double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0)
        return 1.0;
    double cos_t = sqrt(1.0 - sin2_t);
    double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t), rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

/* The channel mean of each lobe's attenuation A(p, h) at node gamma_i (eqs. 13, 14; the residual,
 * every order above pmax, summed in closed form), with sin^2(theta_d) = sin2_theta_d. */
static void node_attenuation(const hb_plan *plan, double sin2_theta_d, double gamma_i, double A[HB_MAX_LOBES + 1])
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    double eta = plan->material.eta, cos_theta_d = sqrt(1.0 - sin2_theta_d);
    double inv_eta_prime = cos_theta_d / sqrt(eta * eta - sin2_theta_d); /* 1 / eta' (sec. 5) */
    double cos_theta_t = sqrt(1.0 - sin2_theta_d / (eta * eta));
    double sin_gamma_t = sin(gamma_i) * inv_eta_prime, gamma_t = asin(sin_gamma_t);
    double f = fresnel(eta, cos_theta_d * cos(gamma_i));
    double chord = d->absorption_paper ? 2.0 * (1.0 + cos(2.0 * gamma_t)) : 2.0 * cos(gamma_t);
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        A[p] = 0.0;
    for (int c = 0; c < 3; c++) {
        double T = exp(-plan->sigma_a[c] / cos_theta_t * chord);
        A[0] += d->r_fresnel_offset ? f : 1.0;
        for (int p = 1; p <= d->pmax; p++)
            A[p] += (1.0 - f) * (1.0 - f) * pow(f, p - 1) * pow(T, p);
        A[HB_LOBE_RESIDUAL] += (1.0 - f) * (1.0 - f) * pow(f, d->pmax) * pow(T, d->pmax + 1) / (1.0 - f * T);
    }
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        A[p] /= 3.0;
}

/* c_g(theta_o): the share of each M_p group in the longitudinal mixture theta_i is drawn from,
 * the lobes' energy sum_j 2 w_j A(p, h_j) (channel mean) at theta_d = theta_o, where the
 * specular theta_i = -theta_o puts it. 1% is spread evenly over the groups, so that every lobe
 * keeps some probability however dark the fibre. */
static void deon_lobe_choice(const hb_plan *plan, hb_deon *d)
{
    const int groups = d->groups;
    for (int k = 0; k <= HB_LOBE_CHOICE_STEPS; k++) {
        double theta = M_PI_2 * k / HB_LOBE_CHOICE_STEPS, s = sin(theta);
        double energy[HB_MAX_LOBES + 1] = { 0 }, total = 0.0;
        for (int j = 0; j < d->nodes; j++) {
            double A[HB_MAX_LOBES + 1];
            node_attenuation(plan, s * s, d->gamma_i[j], A);
            for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
                if (hb_deon_lobe_on(d, p)) {
                    double e = 2.0 * d->weight[j] * A[p];
                    energy[d->m_group[p]] += e;
                    total += e;
                }
        }
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
            double c = 0.0;
            if (hb_deon_group_leader(d, p))
                c = total > 0.0 ? 0.99 * energy[p] / total + 0.01 / groups : 1.0 / groups;
            d->lobe_choice[p][k] = (float)c;
            if (k == HB_LOBE_CHOICE_STEPS)
                d->lobe_choice[p][k + 1] = (float)c;
        }
    }
}

void hb_deon_derive_sampling(hb_plan *plan)
{
    hb_deon *d = &hb_deon_mut(plan)->kernel;
    double total = 0.0, cumulative = 0.0;
    for (int j = 0; j < d->nodes; j++)
        total += d->weight[j];
    for (int j = 0; j < d->nodes; j++) {
        cumulative += d->weight[j];
        d->node_cdf[j] = j == d->nodes - 1 ? 1.0f : (float)(cumulative / total);
        d->node_half_probability[j] = (float)(0.5 * d->weight[j] / total);
    }
    for (int p = 0; p < HB_MAX_LOBES; p++)
        d->beta_n[p] = (float)hb_deon_of(plan)->beta_n[p];
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        d->exp_minus_two_inv_v[p] = (float)exp(-2.0 / hb_deon_of(plan)->v[p]);
    deon_lobe_choice(plan, d);
}

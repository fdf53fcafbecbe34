/* The constants a plan's sampler reads (docs/sampling.md), fixed at plan creation. Internal. */
#include <math.h>

#include "plan.h"
#include "ref/reference.h"

/* c_g(theta_o): the share of each M_p group in the longitudinal mixture theta_i is drawn from,
 * the lobes' energy sum_j 2 w_j A(p, h_j) (channel mean) at theta_d = theta_o, where the
 * specular theta_i = -theta_o puts it. 1% is spread evenly over the groups, so that every lobe
 * keeps some probability however dark the fibre. */
static void deon_lobe_choice(const hb_plan *plan, hb_deon *d)
{
    int groups = 0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        groups += hb_deon_group_leader(d, p);
    for (int k = 0; k <= HB_LOBE_CHOICE_STEPS; k++) {
        double theta = M_PI_2 * k / HB_LOBE_CHOICE_STEPS, s = sin(theta);
        double energy[HB_MAX_LOBES + 1] = { 0 }, total = 0.0;
        for (int j = 0; j < d->nodes; j++) {
            double A[HB_MAX_LOBES + 1][3], Phi[HB_MAX_LOBES];
            hb_ref_deon_node(plan, s * s, d->gamma_i[j], A, Phi);
            for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
                if (hb_deon_lobe_on(d, p)) {
                    double e = 2.0 * d->weight[j] * (A[p][0] + A[p][1] + A[p][2]) / 3.0;
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

void hb_plan_derive_sampling(hb_plan *plan)
{
    hb_deon *d = &plan->deon;
    double total = 0.0, cumulative = 0.0;
    for (int j = 0; j < d->nodes; j++)
        total += d->weight[j];
    for (int j = 0; j < d->nodes; j++) {
        cumulative += d->weight[j];
        d->node_cdf[j] = j == d->nodes - 1 ? 1.0f : (float)(cumulative / total);
        d->node_half_probability[j] = (float)(0.5 * d->weight[j] / total);
    }
    for (int p = 0; p < HB_MAX_LOBES; p++)
        d->beta_n[p] = (float)plan->beta_n[p];
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        d->exp_minus_two_inv_v[p] = (float)exp(-2.0 / plan->v[p]);
    deon_lobe_choice(plan, d);
}

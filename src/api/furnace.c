/* White furnace E(w_o) = integral over the sphere of f(w_i, w_o) dw_i (docs/conventions.md):
 * Gauss-Legendre panels in theta_i and the midpoint rule in the periodic phi_i, both fine
 * enough for the plan's narrowest lobe (its model's furnace rule). Evaluated in stack chunks; a
 * model whose estimator is re-keyed per chunk gets one copy of the plan, freed at the end. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "math/quadrature.h"
#include "models/interface/model.h"
#include "ref/reference.h"

enum { CHUNK = 512, RULE = 8 };

hb_status hb_furnace(const hb_plan *plan, double theta_o, double energy[3])
{
    if (!plan || !energy)
        return hb_fail_null(__func__, !plan ? "plan" : "energy");
    if (!(fabs(theta_o) <= M_PI_2))
        return hb_fail(HB_ERR_PARAM, "%s: theta_o = %g is outside [-pi/2, pi/2]", __func__, theta_o);
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    int longitudinal = plan->options.term == HB_TERM_LONGITUDINAL, nphi, passes;
    double beta_m;
    ops->furnace_rule(plan, &beta_m, &nphi, &passes);
    /* 8-point Gauss-Legendre panels two longitudinal widths wide */
    int panels = (int)ceil(M_PI / (2.0 * fmin(beta_m, 0.5)));
    float ti[CHUNK], pi[CHUNK], to[CHUNK], po[CHUNK], f[3][CHUNK];
    double weight[CHUNK], x[RULE], w[RULE];
    double sum[3] = { 0.0, 0.0, 0.0 };
    int count = 0;
    unsigned long long chunks = 0;
    /* a shallow copy, head and state: it shares the plan's tables, and only it is freed */
    size_t bytes = sizeof *plan + plan->state_size;
    hb_plan *varied = ops->rekey ? malloc(bytes) : NULL;
    if (ops->rekey && !varied)
        return hb_fail(HB_ERR_NOMEM, "%s: the plan's copy (%zu bytes) could not be allocated", __func__, bytes);
    if (varied)
        memcpy(varied, plan, bytes);
    const hb_plan *evaluated = varied ? varied : plan;
    for (int pass = 0; pass < passes; pass++)
        for (int panel = 0; panel < panels; panel++) {
            hb_gauss_legendre(RULE, -M_PI_2 + M_PI * panel / panels, -M_PI_2 + M_PI * (panel + 1) / panels, x, w);
            for (int j = 0; j < RULE; j++)
                for (int q = 0; q < nphi; q++) {
                    ti[count] = (float)x[j];
                    pi[count] = (float)(-M_PI + 2.0 * M_PI * (q + 0.5) / nphi);
                    to[count] = (float)theta_o;
                    po[count] = 0.0f;
                    /* dw_i = cos dtheta dphi; the longitudinal term integrates over theta_i alone */
                    weight[count] = w[j] * cos(x[j]) * (longitudinal ? 1.0 : 2.0 * M_PI / nphi) / passes;
                    int last = panel == panels - 1 && j == RULE - 1 && q == nphi - 1;
                    if (++count == CHUNK || last) {
                        hb_angles_soa in = { ti, pi, to, po };
                        hb_rgb_soa out = { f[0], f[1], f[2] };
                        size_t invalid = 0;
                        if (varied)
                            ops->rekey(varied, plan, ++chunks);
                        if (plan->kernels)
                            ops->eval_angles(evaluated, (size_t)count, in, out, &invalid);
                        else
                            hb_ref_eval_angles(evaluated, (size_t)count, in, out);
                        for (int c = 0; c < 3; c++)
                            for (int k = 0; k < count; k++)
                                sum[c] += weight[k] * f[c][k];
                        count = 0;
                    }
                }
        }
    free(varied);
    for (int c = 0; c < 3; c++)
        energy[c] = sum[c];
    return HB_OK;
}

/* By scattering order: a random walk through a circular fibre, where the model's reference has one
 * (HHH22's). */
hb_status hb_furnace_orders(const hb_plan *plan, double theta, long paths, unsigned long long seed,
                            double energy[HB_ORDER_GROUPS][3], double standard_error[HB_ORDER_GROUPS])
{
    if (!plan || !energy)
        return hb_fail_null(__func__, !plan ? "plan" : "energy");
    if (!plan->reference->orders || plan->material.eccentricity != 0.0)
        return hb_api_unsupported(__func__, plan, "walk by scattering order (HHH22, circular fibres)");
    if (!(fabs(theta) < M_PI_2))
        return hb_fail(HB_ERR_PARAM, "%s: theta = %g is outside (-pi/2, pi/2)", __func__, theta);
    if (paths < 1)
        return hb_fail(HB_ERR_PARAM, "%s: paths = %ld; at least 1", __func__, paths);
    double unused[HB_ORDER_GROUPS];
    plan->reference->orders(plan, theta, paths, seed, energy, standard_error ? standard_error : unused);
    return HB_OK;
}

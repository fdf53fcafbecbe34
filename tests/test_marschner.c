/* MJC03, so far its longitudinal term T = g(alpha_R, beta_R; theta_h) cos(theta_i) / cos^2(theta_d). */
#include <stdlib.h>

#include "test.h"
#include "ref/reference.h"
#include "models/marschner/reference.h"

static hb_plan *marschner_plan(hb_test_ctx *t, double beta, double alpha, hb_quality quality)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.beta_m = beta;
    m.alpha = alpha;
    o.model = HB_MODEL_MARSCHNER;
    o.term = HB_TERM_LONGITUDINAL;
    o.quality = quality;
    o.isa = t->isa == HB_ISA_AUTO ? hb_isa_best() : t->isa;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "plan: %s", err.message);
    return plan;
}

/* Float kernels (angles and vectors) against the double reference, including the corner
 * theta_i = -pi/2, theta_o = pi/2 where 1/cos^2(theta_d) is floored. */
static void test_matches_reference(hb_test_ctx *t)
{
    enum { N = 512 };
    static float ti[N], pi[N], to[N], po[N], f[3][N], ref[3][N], w[6][N];
    const double betas[] = { 0.01, 0.1, 0.5, 1.5 };
    for (int b = 0; b < 4; b++) {
        for (int k = 0; k < N; k++) {
            ti[k] = (float)asin(hb_test_range(t, -1, 1));
            to[k] = k % 2 ? -ti[k] - 0.07f + (float)(betas[b] * hb_test_range(t, -3, 3)) : (float)asin(hb_test_range(t, -1, 1));
            to[k] = fmaxf(-1.57079637f, fminf(1.57079637f, to[k]));
            pi[k] = (float)hb_test_range(t, -M_PI, M_PI), po[k] = (float)hb_test_range(t, -M_PI, M_PI);
            if (k < 4)
                ti[k] = k % 2 ? 1.57079637f : -1.57079637f, to[k] = -ti[k];
            hb_test_vectors_of(ti[k], pi[k], to[k], po[k], (float *const[6]){ w[0], w[1], w[2], w[3], w[4], w[5] },
                           (size_t)k);
        }
        hb_plan *plan = marschner_plan(t, betas[b], 0.035, HB_QUALITY_BALANCED);
        hb_plan *ref_plan = marschner_plan(t, betas[b], 0.035, HB_QUALITY_REFERENCE);
        for (int entry = 0; entry < 2; entry++) {
            hb_rgb_soa out = { f[0], f[1], f[2] }, rout = { ref[0], ref[1], ref[2] };
            if (entry == 0) {
                hb_angles_soa in = { ti, pi, to, po };
                hb_eval_angles(plan, N, in, out, NULL);
                hb_eval_angles(ref_plan, N, in, rout, NULL);
            } else {
                hb_vectors_soa in = { w[0], w[1], w[2], w[3], w[4], w[5] };
                hb_eval_vectors(plan, N, in, out, NULL);
                hb_eval_vectors(ref_plan, N, in, rout, NULL);
            }
            for (int k = 0; k < N; k++)
                CHECK(t, isfinite(f[0][k]) && f[0][k] >= 0.0f, "beta %g: T(%g, %g) = %g", betas[b], ti[k], to[k],
                      f[0][k]);
            double err = hb_test_spec_error((float *const[3]){ f[0], f[1], f[2] },
                                            (float *const[3]){ ref[0], ref[1], ref[2] }, N, NULL);
            /* angles: float exp and cos; vectors: also the float atan2 of each inclination */
            CHECK(t, err <= (entry ? 1e-4 : 2e-5), "beta %g, %s: error %.3g", betas[b], entry ? "vectors" : "angles",
                  err);
        }
        hb_plan_destroy(plan);
        hb_plan_destroy(ref_plan);
    }
}

/* dFH11 Fig. 3 / eq. 5: the energy of MJC03's Gaussian, by hb_furnace on the library's term and
 * by an independent midpoint sum over theta_r here, must agree; it is near 2 at small roughness
 * (the doubling dFH11 points out) and above it at grazing angles. */
static void test_fig3_energy(hb_test_ctx *t)
{
    const double betas[] = { 0.1, 0.3 }, thetas[] = { -1.5, 0.0, 0.5, 1.5 };
    for (int b = 0; b < 2; b++) {
        hb_plan *plan = marschner_plan(t, betas[b], 0.0, HB_QUALITY_BALANCED);
        for (int k = 0; k < 4; k++) {
            double e[3], sum = 0.0;
            CHECK(t, hb_furnace(plan, thetas[k], e) == HB_OK, "furnace");
            enum { M = 20000 };
            for (int j = 0; j < M; j++) {
                double tr = -M_PI_2 + M_PI * (j + 0.5) / M;
                sum += hb_ref_marschner_longitudinal(betas[b], 0.0, tr, thetas[k]) * cos(tr);
            }
            sum *= M_PI / M;
            CHECK(t, fabs(e[0] - sum) < 1e-4 * sum, "beta %g theta %g: furnace %.6f, direct sum %.6f", betas[b],
                  thetas[k], e[0], sum);
            if (b == 0 && fabs(thetas[k]) < 1.0)
                CHECK(t, e[0] > 1.85 && e[0] < 2.0, "beta 0.1 theta %g: energy %.4f is not near 2", thetas[k], e[0]);
        }
        double edge[3], mid[3];
        hb_furnace(plan, 1.5, edge);
        hb_furnace(plan, 0.0, mid);
        CHECK(t, edge[0] > mid[0], "beta %g: no extra energy at grazing (%.4f vs %.4f)", betas[b], edge[0], mid[0]);
        hb_plan_destroy(plan);
    }
}

const hb_test hb_tests_marschner[] = {
    { "marschner_longitudinal_matches_reference", test_matches_reference, 1 },
    { "marschner_fig3_energy", test_fig3_energy, 0 },
    { NULL, NULL, 0 },
};

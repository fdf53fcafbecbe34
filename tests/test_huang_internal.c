/* HHH22 TT and TRT (docs/huang.md): the kernels' Monte-Carlo/Simpson estimator
 * (eqs. 31, 32) equals the same estimator in double path by path on every ISA, its mean over
 * sample indices converges to the nested-quadrature integral, the integral is reciprocal, the
 * numbers are a pure function of (seed, index), and hard cases stay finite and non-negative. */
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "models/interface/plan.h"
#include "ref/reference.h"
#include "models/huang/reference.h"

typedef struct internal_case {
    hb_ndf ndf;
    double roughness, alpha_deg, eccentricity;
    int shadowing;
    double sigma_a; /* red; green and blue are 2x and 4x */
    double theta_i, phi_i, theta_o, phi_o;
} internal_case;

static hb_plan *internal_plan(hb_test_ctx *t, const internal_case *c, unsigned lobes, hb_isa isa,
                              unsigned long long seed)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.ndf = c->ndf;
    m.roughness = c->roughness;
    m.alpha = c->alpha_deg * M_PI / 180.0;
    m.eccentricity = c->eccentricity;
    for (int k = 0; k < 3; k++)
        m.sigma_a[k] = c->sigma_a * (1 << k);
    o.model = HB_MODEL_HUANG;
    o.tt_trt = HB_TT_TRT_MC; /* the estimator itself */
    o.lobes = lobes;
    o.shadowing = c->shadowing ? HB_SHADOWING_SMITH : HB_SHADOWING_NONE;
    o.isa = isa;
    o.seed = seed;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "plan: %s", err.message);
    return plan;
}

enum { TT_TRT = 1u << HB_LOBE_TT | 1u << HB_LOBE_TRT };

/* Both NDFs, with and without G, tilts, elliptical fibres, absorption. */
static const internal_case materials[] = {
    { HB_NDF_GGX, 0.1, 0.0, 0.0, 1, 0.0, 0, 0, 0, 0 },      { HB_NDF_GGX, 0.05, 2.0, 0.0, 0, 0.3, 0, 0, 0, 0 },
    { HB_NDF_BECKMANN, 0.2, -3.0, 0.0, 1, 0.0, 0, 0, 0, 0 }, { HB_NDF_BECKMANN, 0.1, 0.0, 0.8, 0, 1.0, 0, 0, 0, 0 },
    { HB_NDF_GGX, 0.3, 4.0, 0.8, 1, 0.1, 0, 0, 0, 0 },       { HB_NDF_GGX, 0.4, -2.0, 0.5, 1, 2.0, 0, 0, 0, 0 },
};
enum { MATERIALS = sizeof materials / sizeof materials[0], PAIRS = 48 };

/* Per ISA: every lane's estimate equals the double estimator with the same numbers. A path whose
 * float and double versions fall on two sides of a condition (a total internal reflection, a
 * visibility edge) differs by its whole contribution: such flips are counted, not hidden. */
static void test_internal_matches_double(hb_test_ctx *t)
{
    float ti[PAIRS], pi[PAIRS], to[PAIRS], po[PAIRS], f[3][PAIRS];
    double worst = 0.0, worst_ndf[2] = { 0.0, 0.0 };
    int flips = 0, total = 0, worst_material = -1;
    for (int k = 0; k < MATERIALS; k++) {
        hb_plan *plan = internal_plan(t, &materials[k], TT_TRT, t->isa, 11u + (unsigned)k);
        if (!plan)
            return;
        for (int j = 0; j < PAIRS; j++) {
            ti[j] = (float)hb_test_range(t, -1.5, 1.5);
            pi[j] = (float)hb_test_range(t, -M_PI, M_PI);
            to[j] = (float)hb_test_range(t, -1.5, 1.5);
            /* half the pairs near the forward (TT) direction, the others anywhere */
            po[j] = (float)(j % 2 ? hb_test_range(t, -M_PI, M_PI) : pi[j] + M_PI + hb_test_range(t, -0.6, 0.6));
        }
        hb_eval_report report;
        hb_eval_angles(plan, PAIRS, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, &report);
        CHECK(t, report.invalid == 0, "material %d: %zu invalid", k, report.invalid);
        double want[PAIRS][3], peak = 0.0;
        for (int j = 0; j < PAIRS; j++) {
            double tt[3], trt[3];
            hb_ref_huang_internal_mc(plan, ti[j], pi[j], to[j], po[j], (unsigned)j, tt, trt);
            for (int c = 0; c < 3; c++) {
                want[j][c] = tt[c] + trt[c];
                peak = fmax(peak, want[j][c]);
            }
        }
        for (int j = 0; j < PAIRS; j++)
            for (int c = 0; c < 3; c++) {
                double err = fabs(f[c][j] - want[j][c]) / fmax(want[j][c], 1e-3 * peak);
                CHECK(t, isfinite(f[c][j]) && f[c][j] >= 0.0f, "material %d pair %d: f = %g", k, j, f[c][j]);
                total++;
                if (err > 1e-2)
                    flips++;
                else if ((worst_ndf[materials[k].ndf] = fmax(worst_ndf[materials[k].ndf], err)) > worst) {
                    worst = err;
                    worst_material = k;
                }
            }
        hb_plan_destroy(plan);
    }
    hb_test_note(t, "%d of %d values differ by a flipped path condition; the rest within %.1e (GGX) and %.1e "
                 "(Beckmann, material %d) of the double estimator", flips, total, worst_ndf[0], worst_ndf[1], worst_material);
    /* GGX's visible normal is closed-form in both; Beckmann's float slope comes from 5 Newton steps on
     * Giles' erfinv (2.8e-6 rad from the double's bisection, test_sample_huang), which a narrow exit
     * lobe two interfaces later magnifies */
    CHECK(t, worst_ndf[0] <= 2e-3 && worst_ndf[1] <= 5e-3, "float vs double estimator: %.2e, %.2e", worst_ndf[0],
          worst_ndf[1]);
    CHECK(t, flips * 100 <= total, "%d of %d flips", flips, total);
}

/* The estimator's mean over many sample indices (independent numbers) converges to
 * the nested quadrature of the same Simpson sum in phi_m1, within 4 standard errors plus the
 * quadrature's own error (estimated by the difference from half the points per dimension). The
 * quadrature over phi_m1 itself (Simpson vs converged Gauss-Legendre) is reported: it is the
 * quality setting's bias. Roughness 0.05..0.4, theta_i in {0, +-0.7, +-1.3}, circular and e = 0.8. */
static const internal_case convergence_cases[] = {
    { HB_NDF_GGX, 0.05, 0.0, 0.0, 1, 0.0, 0.0, 0.0, -0.05, 2.9 },
    { HB_NDF_GGX, 0.1, 2.0, 0.0, 1, 0.0, 0.7, 0.3, -0.75, 0.8 },
    { HB_NDF_BECKMANN, 0.2, -2.0, 0.8, 1, 0.2, -0.7, -1.0, 0.6, 2.2 },
    { HB_NDF_GGX, 0.4, 0.0, 0.0, 0, 0.0, 1.3, 0.0, -1.2, 2.5 },
    { HB_NDF_GGX, 0.2, 4.0, 0.8, 1, 0.5, -1.3, 0.5, 1.3, -0.1 },
    { HB_NDF_BECKMANN, 0.05, 0.0, 0.8, 1, 0.0, 0.7, 1.2, -0.7, 1.2 },
};
enum { CONVERGENCE = sizeof convergence_cases / sizeof convergence_cases[0], DRAWS = 8192 };

static void test_internal_unbiased(hb_test_ctx *t)
{
    static float ti[DRAWS], pi[DRAWS], to[DRAWS], po[DRAWS], f[3][DRAWS];
    for (int k = 0; k < CONVERGENCE; k++) {
        if (t->quick && k % 3)
            continue;
        const internal_case *c = &convergence_cases[k];
        hb_plan *plan = internal_plan(t, c, TT_TRT, HB_ISA_AUTO, 7u);
        if (!plan)
            return;
        for (int j = 0; j < DRAWS; j++) {
            ti[j] = (float)c->theta_i;
            pi[j] = (float)c->phi_i;
            to[j] = (float)c->theta_o;
            po[j] = (float)c->phi_o;
        }
        hb_eval_angles(plan, DRAWS, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        double tt[3], trt[3], tt_half[3], trt_half[3], tt_gl[3], trt_gl[3];
        hb_ref_huang_internal(plan, ti[0], pi[0], to[0], po[0], 1, 0, 32, 12, tt, trt);
        hb_ref_huang_internal(plan, ti[0], pi[0], to[0], po[0], 1, 0, 16, 8, tt_half, trt_half);
        hb_ref_huang_internal(plan, ti[0], pi[0], to[0], po[0], 0, 384, 32, 8, tt_gl, trt_gl);
        for (int ch = 0; ch < 3; ch += 2) {
            double sum = 0.0, sum2 = 0.0;
            for (int j = 0; j < DRAWS; j++) {
                sum += f[ch][j];
                sum2 += (double)f[ch][j] * f[ch][j];
            }
            double mean = sum / DRAWS, error = sqrt(fmax(sum2 / DRAWS - mean * mean, 0.0) / DRAWS);
            double want = tt[ch] + trt[ch], quadrature = fabs(want - tt_half[ch] - trt_half[ch]);
            double simpson = fabs(tt[ch] + trt_half[ch] - tt_gl[ch] - trt_gl[ch]) / fmax(want, 1e-300);
            hb_test_note(t, "case %d ch %d: mean %.6g +- %.2g (%d draws), quadrature %.6g +- %.2g (TT %.4g TRT %.4g); "
                         "Simpson's own error %.1e",
                         k, ch, mean, error, DRAWS, want, quadrature, tt[ch], trt[ch], simpson);
            CHECK(t, fabs(mean - want) <= 4.0 * error + quadrature + 1e-7 * want,
                  "case %d channel %d: mean %.6g vs %.6g (%.1f standard errors)", k, ch, mean, want,
                  fabs(mean - want) / fmax(error, 1e-300));
            CHECK(t, want > 0.0 && error < 0.1 * want, "case %d: the case must test something (%.3g +- %.2g)", k, want,
                  error);
        }
        hb_plan_destroy(plan);
    }
}

/* S_TT and S_TRT of a circular fibre without tilt are reciprocal: f(w_i, w_o) / cos(theta_i) =
 * f(w_o, w_i) / cos(theta_o). The nested quadrature of the derivation's integrand shows it, which
 * checks the 1 / (2 cos(theta_o)) normalisation and every Jacobian (eqs. 21-24). */
static void test_internal_reciprocal(hb_test_ctx *t)
{
    /* TT pairs near the forward direction, TRT pairs on the back side, where each lobe is bright */
    static const double pairs[2][3][4] = { { { 0.3, 0.0, -0.5, 2.8 }, { 0.6, 0.2, -0.3, -2.7 }, { -0.9, 0.0, 0.7, 3.0 } },
                                           { { 0.3, 0.0, -0.4, 0.5 }, { -0.5, 0.1, 0.4, -0.8 }, { 0.0, 0.0, 0.1, 0.2 } } };
    static const internal_case fibres[] = { { HB_NDF_GGX, 0.2, 0.0, 0.0, 1, 0.0, 0, 0, 0, 0 },
                                            { HB_NDF_BECKMANN, 0.3, 0.0, 0.0, 0, 0.5, 0, 0, 0, 0 } };
    double worst = 0.0;
    for (int k = 0; k < 2; k++) {
        for (unsigned lobe = HB_LOBE_TT; lobe <= HB_LOBE_TRT; lobe++) {
            hb_plan *plan = internal_plan(t, &fibres[k], 1u << lobe, HB_ISA_AUTO, 0);
            if (!plan)
                return;
            int points = lobe == HB_LOBE_TT ? 48 : 12, which = lobe == HB_LOBE_TRT;
            for (int j = 0; j < 3; j++) {
                if ((t->quick && j % 2) || (which && k > 0)) /* TRT's 5D quadrature: one fibre */
                    continue;
                const double *q = pairs[which][j];
                double a[2][3], b[2][3];
                hb_ref_huang_internal(plan, q[0], q[1], q[2], q[3], 0, 128, points, points, a[0], a[1]);
                hb_ref_huang_internal(plan, q[2], q[3], q[0], q[1], 0, 128, points, points, b[0], b[1]);
                double forward = a[which][0] / cos(q[0]), backward = b[which][0] / cos(q[2]);
                double err = fabs(forward - backward) / fmax(fabs(backward), 1e-300);
                worst = fmax(worst, err);
                CHECK(t, forward > 0.0 && err <= (lobe == HB_LOBE_TT ? 2e-3 : 2e-2),
                      "fibre %d lobe %u pair %d: S %.6g vs swapped %.6g", k, lobe, j, forward, backward);
            }
            hb_plan_destroy(plan);
        }
    }
    hb_test_note(t, "S(w_i, w_o) vs S(w_o, w_i): within %.1e (TT 48, TRT 12 points per visible-normal dimension)",
                 worst);
}

/* The numbers are a pure function of (seed, index): a sample's value does not depend on the batch
 * around it beyond its index, a second call repeats it, and another seed changes it. */
static void test_internal_seed(hb_test_ctx *t)
{
    enum { N = 37 };
    float ti[N], pi[N], to[N], po[N], a[3][N], b[3][N], c[3][N];
    for (int j = 0; j < N; j++) {
        ti[j] = 0.2f;
        pi[j] = 0.1f;
        to[j] = -0.3f;
        po[j] = 2.9f;
    }
    hb_plan *one = internal_plan(t, &materials[0], TT_TRT, t->isa, 5), *two = internal_plan(t, &materials[0], TT_TRT, t->isa, 6);
    if (!one || !two)
        return;
    hb_angles_soa in = { ti, pi, to, po };
    hb_eval_angles(one, N, in, (hb_rgb_soa){ a[0], a[1], a[2] }, NULL);
    hb_eval_angles(one, N, in, (hb_rgb_soa){ b[0], b[1], b[2] }, NULL);
    hb_eval_angles(two, N, in, (hb_rgb_soa){ c[0], c[1], c[2] }, NULL);
    int same_seed = memcmp(a, b, sizeof a) == 0, differ = 0, distinct = 0;
    for (int j = 0; j < N; j++) {
        differ += a[0][j] != c[0][j];
        distinct += j > 0 && a[0][j] != a[0][j - 1];
        double tt[3], trt[3];
        hb_ref_huang_internal_mc(one, ti[j], pi[j], to[j], po[j], (unsigned)j, tt, trt);
        CHECK(t, fabs(a[0][j] - (tt[0] + trt[0])) <= 2e-3 * fmax(tt[0] + trt[0], 1e-3), "index %d: %g vs %g", j,
              a[0][j], tt[0] + trt[0]);
    }
    CHECK(t, same_seed, "the same seed repeats every value");
    CHECK(t, differ >= N - 1 && distinct >= N - 2, "another seed / index changes the value (%d, %d of %d)", differ,
          distinct, N);
    hb_plan_destroy(one);
    hb_plan_destroy(two);
}

/* Hard cases: grazing and reversed directions, phi at +-pi, tiny and huge roughness, eta near 1
 * (almost no total internal reflection) and large, huge absorption, an eccentric fibre: every value
 * finite and non-negative, and a black fibre (sigma_a = 1e3) gives TT = TRT = 0 exactly. */
static void test_internal_hard_cases(hb_test_ctx *t)
{
    static const float angles[][4] = {
        { 1.57079637f, 0.0f, -1.57079637f, 3.14159274f }, { -1.5707963f, 1.0f, 1.5707963f, -2.0f },
        { 0.0f, 0.0f, 0.0f, 3.14159274f },                 { 0.0f, 3.14159274f, 0.0f, -3.14159274f },
        { 1.2f, -3.14159274f, -1.2f, 0.0f },               { 0.5f, 0.0f, -0.5f, 1e-7f },
        { -0.7f, 2.0f, 0.7f, -1.14159274f },               { 1e-38f, -0.0f, -1e-38f, 3.1415925f },
    };
    enum { N = sizeof angles / sizeof angles[0] };
    static const struct {
        hb_ndf ndf;
        double roughness, eta, eccentricity, sigma_a, alpha;
        int shadowing;
    } hard[] = {
        { HB_NDF_GGX, 0.01, 1.55, 0.0, 0.0, 0.035, 1 },     { HB_NDF_BECKMANN, 0.01, 1.55, 0.0, 0.0, 0.0, 0 },
        { HB_NDF_GGX, 1.0, 1.55, 0.0, 0.0, 0.1, 1 },        { HB_NDF_BECKMANN, 1.0, 1.0001, 0.0, 0.0, -0.1, 0 },
        { HB_NDF_GGX, 0.1, 2.5, 0.95, 0.0, 0.035, 1 },      { HB_NDF_GGX, 0.1, 1.55, 0.0, 1e3, 0.035, 1 },
        { HB_NDF_BECKMANN, 0.05, 1.0001, 0.95, 0.0, 0.0, 1 },
    };
    float ti[N], pi[N], to[N], po[N], f[3][N];
    for (int j = 0; j < N; j++) {
        ti[j] = angles[j][0];
        pi[j] = angles[j][1];
        to[j] = angles[j][2];
        po[j] = angles[j][3];
    }
    for (size_t k = 0; k < sizeof hard / sizeof hard[0]; k++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        m.ndf = hard[k].ndf;
        m.roughness = hard[k].roughness;
        m.eta = hard[k].eta;
        m.eccentricity = hard[k].eccentricity;
        m.alpha = hard[k].alpha;
        m.sigma_a[0] = m.sigma_a[1] = m.sigma_a[2] = hard[k].sigma_a;
        o.model = HB_MODEL_HUANG;
        o.isa = t->isa;
        o.shadowing = hard[k].shadowing ? HB_SHADOWING_SMITH : HB_SHADOWING_NONE;
        o.lobes = TT_TRT;
        o.tt_trt = HB_TT_TRT_MC;
        o.tt_panels = 64; /* the hard cases are about the path, not the node count */
        hb_plan *plan = NULL;
        hb_error err;
        CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "case %zu: %s", k, err.message);
        if (!plan)
            continue;
        hb_eval_report report;
        hb_eval_angles(plan, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, &report);
        CHECK(t, report.invalid == 0, "case %zu: %zu invalid", k, report.invalid);
        for (int j = 0; j < N; j++)
            for (int c = 0; c < 3; c++) {
                CHECK(t, isfinite(f[c][j]) && f[c][j] >= 0.0f, "case %zu pair %d: f = %g", k, j, f[c][j]);
                if (hard[k].sigma_a >= 1e3)
                    CHECK(t, f[c][j] == 0.0f, "case %zu pair %d: a black fibre transmits %g", k, j, f[c][j]);
            }
        hb_plan_destroy(plan);
    }
}

/* Without G in the plan, TT and TRT keep G at their interfaces: every sample's estimate is bounded.
 * With G = 1 inside, one sample of this direction (the default tilt) weighed 1e25 (1 / G1 of a grazing
 * internal path). */
static void test_internal_no_g_bounded(hb_test_ctx *t)
{
    internal_case c = { HB_NDF_GGX, 0.1, 0.035 * 180.0 / M_PI, 0.0, 0, 0.0, -0.81, 0.0, 0.5, 2.21 };
    hb_plan *plan = internal_plan(t, &c, TT_TRT, t->isa, 0);
    if (!plan)
        return;
    enum { N = 1024 };
    static float ti[N], pi[N], to[N], po[N], f[3][N];
    for (int k = 0; k < N; k++)
        ti[k] = (float)c.theta_i, pi[k] = (float)c.phi_i, to[k] = (float)c.theta_o, po[k] = (float)c.phi_o;
    hb_eval_angles(plan, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    double most = 0.0, mean = 0.0;
    for (int k = 0; k < N; k++) {
        CHECK(t, isfinite(f[0][k]) && f[0][k] >= 0.0f, "sample %d: f = %g", k, f[0][k]);
        most = fmax(most, f[0][k]);
        mean += f[0][k] / N;
    }
    CHECK(t, most <= 100.0 * mean + 1.0, "largest estimate %g against the mean %g", most, mean);
    hb_test_note(t, "no G: the largest of %d estimates %.3g, their mean %.3g", N, most, mean);
    hb_plan_destroy(plan);
}

/* HHH22 Fig. 16's random walk (hb_furnace_orders): its R, TT and TRT agree with hb_furnace of each
 * lobe (quadrature of the table's f over w_i, alpha = 0 so the model is reciprocal) within 4 of the
 * walk's standard errors plus 3% (the table's error integrated: docs/huang.md); a lossless fibre
 * sends at most all the light back out and some of it beyond TRT; a black fibre nothing beyond;
 * elliptical fibres and other models are refused. */
static void test_internal_orders(hb_test_ctx *t)
{
    long paths = t->quick ? 20000 : 100000;
    const internal_case absorbing = { HB_NDF_GGX, 0.3, 0.0, 0.0, 1, 0.1, 0, 0, 0, 0 };
    static const double thetas[] = { 0.0, 0.8 };
    for (int k = 0; k < 2; k++) {
        hb_plan *plan = internal_plan(t, &absorbing, 1u << HB_LOBE_R | TT_TRT, HB_ISA_AUTO, 0);
        if (!plan)
            return;
        double e[HB_ORDER_GROUPS][3], se[HB_ORDER_GROUPS];
        CHECK(t, hb_furnace_orders(plan, thetas[k], paths, 7, e, se) == HB_OK, "hb_furnace_orders failed");
        hb_plan_destroy(plan);
        for (int lobe = 0; lobe < 3; lobe++) {
            /* the furnace of the table: deterministic (the estimator's furnace carries ~1.5% noise) */
            hb_material m;
            hb_options o;
            hb_material_default(&m);
            hb_options_default(&o);
            m.roughness = absorbing.roughness;
            m.alpha = 0.0;
            for (int c = 0; c < 3; c++)
                m.sigma_a[c] = absorbing.sigma_a * (1 << c);
            o.model = HB_MODEL_HUANG;
            o.lobes = 1u << lobe; /* tt_trt auto: the table at this roughness */
            hb_plan *one = NULL;
            CHECK(t, hb_plan_create(&m, &o, &one, NULL) == HB_OK, "table plan");
            double f[3] = { 0.0, 0.0, 0.0 };
            hb_furnace(one, thetas[k], f);
            hb_plan_destroy(one);
            double walk = (e[lobe][0] + e[lobe][1] + e[lobe][2]) / 3.0, furnace = (f[0] + f[1] + f[2]) / 3.0;
            hb_test_note(t, "theta %.1f lobe %d: walk %.5f +- %.5f, furnace %.5f", thetas[k], lobe, walk, se[lobe], furnace);
            CHECK(t, fabs(walk - furnace) <= 4.0 * se[lobe] + 0.03 * furnace, "theta %.1f lobe %d: walk %.5f, furnace %.5f",
                  thetas[k], lobe, walk, furnace);
        }
    }
    const internal_case lossless = { HB_NDF_BECKMANN, 0.15, 2.0, 0.0, 1, 0.0, 0, 0, 0, 0 };
    const internal_case black = { HB_NDF_BECKMANN, 0.15, 2.0, 0.0, 1, 30.0, 0, 0, 0, 0 };
    hb_plan *clear = internal_plan(t, &lossless, TT_TRT, HB_ISA_AUTO, 0), *dark = internal_plan(t, &black, TT_TRT, HB_ISA_AUTO, 0);
    if (!clear || !dark)
        return;
    double e[HB_ORDER_GROUPS][3], se[HB_ORDER_GROUPS], d[HB_ORDER_GROUPS][3];
    hb_furnace_orders(clear, 1.2, paths / 10, 3, e, se);
    hb_furnace_orders(dark, 1.2, paths / 10, 3, d, NULL);
    double total = 0.0, spread = 0.0;
    for (int g = 0; g < HB_ORDER_GROUPS; g++) {
        total += e[g][0];
        spread += se[g];
    }
    CHECK(t, total <= 1.0 + 4.0 * spread && total > 0.8, "lossless: %.5f leaves the fibre", total);
    CHECK(t, e[3][0] > 0.05, "lossless at theta 1.2: only %.5f beyond TRT", e[3][0]);
    CHECK(t, d[3][0] < 1e-6 && d[1][0] < 1e-6, "black: TT %.3g, beyond %.3g", d[1][0], d[3][0]);
    CHECK(t, hb_furnace_orders(clear, M_PI_2, 10, 0, e, NULL) == HB_ERR_PARAM, "theta = pi/2 accepted");
    hb_plan_destroy(clear);
    hb_plan_destroy(dark);
    const internal_case ellipse = { HB_NDF_GGX, 0.3, 0.0, 0.8, 1, 0.0, 0, 0, 0, 0 };
    hb_plan *oval = internal_plan(t, &ellipse, TT_TRT, HB_ISA_AUTO, 0);
    CHECK(t, hb_furnace_orders(oval, 0.0, 10, 0, e, NULL) == HB_ERR_UNSUPPORTED, "elliptical fibre accepted");
    hb_plan_destroy(oval);
}

/* HHH22 Fig. 16 by the CLI (`hairbsdf furnace --model huang --fig16`, 20000 paths per row): the
 * share beyond TRT falls with melanin at every theta (lossless, blond, brown, black) and a black
 * fibre's is under 1e-3; what the lossless fibre sends out is at most 1 within four standard errors.
 * Long tier only: it takes the walk 20 s. Its rows are docs/huang.md's table. */
static void test_internal_fig16(hb_test_ctx *t)
{
    if (t->quick) {
        hb_test_skip(t, "the long tier's");
        return;
    }
    hb_tool_run r;
    if (!hb_test_run_tool(t, "furnace --model huang --fig16 --theta-o -1.2,-0.6,0,0.6,1.2", NULL, 0, &r))
        return;
    CHECK(t, r.status == 0, "furnace --fig16: status %d, %s", r.status, r.err);
    enum { THETAS = 5, FIBRES = 4 };
    double share[FIBRES][THETAS];
    int rows = 0;
    char *header_end = strchr(r.out, '\n');
    if (header_end)
        hb_test_note(t, "%.*s", (int)(header_end - r.out), r.out);
    for (char *line = header_end; line && line[1]; line = strchr(line + 1, '\n')) {
        char fibre[16];
        double theta, e_r, e_tt, e_trt, beyond, se, part;
        if (sscanf(line + 1, "%15[^,],%lf,%lf,%lf,%lf,%lf,%lf,%lf", fibre, &theta, &e_r, &e_tt, &e_trt, &beyond, &se,
                   &part) != 8 || rows >= FIBRES * THETAS)
            break;
        share[rows / THETAS][rows % THETAS] = part;
        if (rows < THETAS)
            CHECK(t, e_r + e_tt + e_trt + beyond <= 1.0 + 4.0 * se, "lossless at theta %g: %.5f leaves", theta,
                  e_r + e_tt + e_trt + beyond);
        rows++;
        char *end = strchr(line + 1, '\n');
        hb_test_note(t, "%.*s", end ? (int)(end - line - 1) : (int)strlen(line + 1), line + 1);
    }
    CHECK(t, rows == FIBRES * THETAS, "furnace --fig16 printed %d rows", rows);
    for (int k = 0; rows == FIBRES * THETAS && k < THETAS; k++) {
        for (int f = 1; f < FIBRES; f++)
            CHECK(t, share[f][k] < share[f - 1][k], "theta %d: fibre %d's share beyond TRT %.4f, fibre %d's %.4f", k, f,
                  share[f][k], f - 1, share[f - 1][k]);
        CHECK(t, share[FIBRES - 1][k] < 1e-3, "theta %d: the black fibre's share beyond TRT %.4f", k, share[FIBRES - 1][k]);
    }
}

const hb_test hb_tests_huang_internal[] = {
    { "huang_internal_matches_double", test_internal_matches_double, 1 },
    { "huang_internal_unbiased", test_internal_unbiased, 0 },
    { "huang_internal_reciprocal", test_internal_reciprocal, 0 },
    { "huang_internal_orders", test_internal_orders, 0 },
    { "huang_internal_fig16", test_internal_fig16, 0 },
    { "huang_internal_seed", test_internal_seed, 1 },
    { "huang_internal_hard_cases", test_internal_hard_cases, 1 },
    { "huang_internal_no_g_bounded", test_internal_no_g_bounded, 1 },
    { 0 },
};

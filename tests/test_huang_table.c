/* HHH22 TT/TRT table (HB_TT_TRT_TABLE, docs/huang.md): on every ISA the table tt_trt auto builds at
 * balanced (at these roughnesses the second grid, which builds within about a second) agrees with
 * the Monte-Carlo/Simpson estimator's mean (high quality, 256 sample indices, 64 under emulation)
 * within the error docs/huang.md states for it, and with the nested-quadrature reference at each
 * material's brightest pair; lookups are finite and non-negative at the hard directions. */
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "ref/reference.h"
#include "models/huang/reference.h"

typedef struct table_case {
    hb_ndf ndf;
    double roughness, alpha_deg, eccentricity, sigma_a;
} table_case;

static const table_case table_cases[] = {
    { HB_NDF_GGX, 0.3, 2.0, 0.0, 0.1 },
    { HB_NDF_BECKMANN, 0.2, -3.0, 0.0, 0.0 },
    { HB_NDF_GGX, 0.1, 2.0, 0.0, 0.3 },
    { HB_NDF_GGX, 0.3, 4.0, 0.8, 0.1 },
};
enum { CASES = sizeof table_cases / sizeof table_cases[0] };

/* theta_i in {0, +-0.7, +-1.3}; theta_o from the mirror -theta_i in steps of 1.5 roughness; 9 azimuths. */
enum { THETAS = 5, OFFSETS = 7, AZIMUTHS = 9, PAIRS = THETAS * OFFSETS * AZIMUTHS, DRAWS = 256 };

static hb_plan *table_plan(hb_test_ctx *t, const table_case *c, hb_tt_trt method, hb_quality quality, hb_isa isa)
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
    o.lobes = 1u << HB_LOBE_TT | 1u << HB_LOBE_TRT;
    o.tt_trt = method;
    o.quality = quality;
    o.isa = isa;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "plan: %s", err.message);
    return plan;
}

static void pair_of(const table_case *c, int k, float q[4])
{
    static const float thetas[THETAS] = { 0.0f, 0.7f, -0.7f, 1.3f, -1.3f };
    int a = k / (OFFSETS * AZIMUTHS), b = k / AZIMUTHS % OFFSETS, z = k % AZIMUTHS;
    q[0] = thetas[a];
    q[1] = c->eccentricity > 0.0 ? 0.4f : 0.0f;
    q[2] = fminf(fmaxf(-thetas[a] + (float)((b - 3) * 1.5 * c->roughness), -1.5f), 1.5f);
    q[3] = q[1] + 0.3f + 0.35f * (float)z;
}

static void test_table_matches_estimator(hb_test_ctx *t)
{
    static float ti[PAIRS * DRAWS], pi[PAIRS * DRAWS], to[PAIRS * DRAWS], po[PAIRS * DRAWS], f[3][PAIRS * DRAWS];
    static double mean[PAIRS], standard[PAIRS];
    int draws = t->quick ? DRAWS / 4 : DRAWS, built = 0;
    for (int k = 0; k < CASES; k++) {
        const table_case *c = &table_cases[k];
        if ((t->quick || t->isa == HB_ISA_SCALAR) && (c->roughness < 0.2 || c->eccentricity > 0.0))
            continue; /* the two costly builds: the SIMD ISAs on x86 run them */
        if (t->emulated && built++) /* under qemu a table build takes minutes: one case */
            continue;
        hb_plan *mc = table_plan(t, c, HB_TT_TRT_MC, HB_QUALITY_HIGH, t->isa);
        hb_plan *table = table_plan(t, c, HB_TT_TRT_AUTO, HB_QUALITY_BALANCED, t->isa);
        if (!mc || !table)
            return;
        for (int j = 0; j < PAIRS * draws; j++) {
            float q[4];
            pair_of(c, j / draws, q);
            ti[j] = q[0];
            pi[j] = q[1];
            to[j] = q[2];
            po[j] = q[3];
        }
        hb_angles_soa in = { ti, pi, to, po };
        hb_eval_angles(mc, (size_t)(PAIRS * draws), in, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        double peak = 0.0;
        for (int j = 0; j < PAIRS; j++) {
            double sum = 0.0, sum2 = 0.0;
            for (int d = 0; d < draws; d++) {
                sum += f[0][j * draws + d];
                sum2 += (double)f[0][j * draws + d] * f[0][j * draws + d];
            }
            mean[j] = sum / draws;
            standard[j] = sqrt(fmax(sum2 / draws - mean[j] * mean[j], 0.0) / draws);
            peak = fmax(peak, mean[j]);
        }
        hb_eval_report report;
        hb_eval_angles(table, (size_t)(PAIRS * draws), in, (hb_rgb_soa){ f[0], f[1], f[2] }, &report);
        CHECK(t, report.invalid == 0, "case %d: %zu invalid", k, report.invalid);
        double total = 0.0, worst = 0.0;
        int worst_pair = 0;
        for (int j = 0; j < PAIRS; j++) {
            double error = fabs(f[0][j * draws] - mean[j]);
            total += error;
            if (error - 4.0 * standard[j] > worst) {
                worst = error - 4.0 * standard[j];
                worst_pair = j;
            }
        }
        float q[4];
        pair_of(c, worst_pair, q);
        hb_test_note(t, "case %d: mean |table - estimator| %.2e of the peak %.3g, worst %.2e beyond 4 standard errors "
                     "(theta_i %g theta_o %g phi_o %g: %.4g vs %.4g)",
                     k, total / PAIRS / peak, peak, worst / peak, q[0], q[2], q[3], f[0][worst_pair * draws],
                     mean[worst_pair]);
        CHECK(t, total / PAIRS <= 0.005 * peak, "case %d: mean error %.3g of the peak", k, total / PAIRS / peak);
        CHECK(t, worst <= 0.04 * peak, "case %d: error %.3g of the peak at theta_i %g theta_o %g phi_o %g", k,
              worst / peak, q[0], q[2], q[3]);
        hb_plan_destroy(mc);
        hb_plan_destroy(table);
    }
}

/* At each material's brightest forward pair auto's balanced table is within 2.5% of the nested quadrature. */
static void test_table_matches_reference(hb_test_ctx *t)
{
    for (int k = 0; k < CASES; k++) {
        const table_case *c = &table_cases[k];
        if (t->quick && (c->roughness < 0.2 || c->eccentricity > 0.0))
            continue;
        hb_plan *table = table_plan(t, c, HB_TT_TRT_AUTO, HB_QUALITY_BALANCED, HB_ISA_AUTO);
        if (!table)
            return;
        float ti = 0.3f, pi = (float)(c->eccentricity > 0.0 ? 0.4 : 0.0), to = -0.3f, po = pi + 3.0f, f[3];
        hb_eval_angles(table, 1, (hb_angles_soa){ &ti, &pi, &to, &po }, (hb_rgb_soa){ f, f + 1, f + 2 }, NULL);
        double tt[3], trt[3];
        hb_ref_huang_internal(table, ti, pi, to, po, 0, 192, 24, 8, tt, trt);
        for (int ch = 0; ch < 3; ch++) {
            double want = tt[ch] + trt[ch];
            hb_test_note(t, "case %d channel %d: table %.5g, nested quadrature %.5g (%.2e)", k, ch, f[ch], want,
                         fabs(f[ch] - want) / want);
            CHECK(t, fabs(f[ch] - want) <= 0.025 * want, "case %d channel %d: table %.5g vs %.5g", k, ch, f[ch], want);
        }
        hb_plan_destroy(table);
    }
}

/* Grazing, poles, phi at +-pi, and the table's clamped edges: finite and non-negative. */
static void test_table_hard_directions(hb_test_ctx *t)
{
    static const float angles[] = { -1.5707964f, -1.5707963f, -1.3f, 0.0f, 1e-30f, 1.5707963f, 1.5707964f };
    static const float azimuths[] = { -3.1415927f, -3.1415925f, -1e-30f, 0.0f, 1.0f, 3.1415925f, 3.1415927f, 1e4f };
    enum { A = sizeof angles / sizeof angles[0], Z = sizeof azimuths / sizeof azimuths[0], N = A * A * Z * 2 };
    float ti[N], pi[N], to[N], po[N], f[3][N];
    for (int j = 0; j < N; j++) {
        ti[j] = angles[j % A];
        to[j] = angles[j / A % A];
        po[j] = azimuths[j / (A * A) % Z];
        pi[j] = j >= N / 2 ? 0.7f : 0.0f;
    }
    static const table_case hard[] = { { HB_NDF_GGX, 0.3, 2.0, 0.0, 0.0 }, { HB_NDF_BECKMANN, 0.3, -2.0, 0.9, 1e4 } };
    for (size_t k = 0; k < sizeof hard / sizeof hard[0]; k++) {
        hb_plan *table = table_plan(t, &hard[k], HB_TT_TRT_TABLE, HB_QUALITY_FAST, t->isa);
        if (!table)
            return;
        hb_eval_report report;
        hb_eval_angles(table, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, &report);
        CHECK(t, report.invalid == 0, "case %zu: %zu invalid", k, report.invalid);
        for (int j = 0; j < N; j++)
            for (int c = 0; c < 3; c++) {
                CHECK(t, isfinite(f[c][j]) && f[c][j] >= 0.0f, "case %zu: f = %g at %g %g %g %g", k, f[c][j], ti[j],
                      pi[j], to[j], po[j]);
                if (hard[k].sigma_a >= 1e3)
                    CHECK(t, f[c][j] == 0.0f, "case %zu: a black fibre transmits %g", k, f[c][j]);
            }
        hb_plan_destroy(table);
    }
}

/* Past the tilted mesonormal's closing windows (theta beyond tau +- pi/2, tau = -alpha: no point of the
 * fibre shows w a visible mesosurface) TT and TRT are 0 in the model; the table, whose grid steps
 * cross the closure, gives exactly 0 there too, for w_i and for w_o. */
static void test_table_closed_windows(hb_test_ctx *t)
{
    static const table_case tilted[] = { { HB_NDF_GGX, 0.3, 2.0, 0.0, 0.1 }, { HB_NDF_BECKMANN, 0.3, -3.0, 0.0, 0.0 } };
    static const float others[] = { -1.2f, -0.5f, 0.0f, 0.5f, 1.2f }, azimuths[] = { 0.0f, 1.0f, 2.0f, 3.0f };
    enum { O = sizeof others / sizeof others[0], Z = sizeof azimuths / sizeof azimuths[0], N = 2 * O * Z };
    for (size_t k = 0; k < sizeof tilted / sizeof tilted[0]; k++) {
        float alpha = (float)(tilted[k].alpha_deg * M_PI / 180.0);
        float past = copysignf(1.5707964f - 0.5f * fabsf(alpha), alpha); /* halfway from the closure to the pole */
        float ti[N], pi[N], to[N], po[N], f[3][N], g[3][N];
        for (int j = 0; j < N; j++) {
            int o = j / Z % O, z = j % Z, as_input = j < N / 2;
            ti[j] = as_input ? past : others[o];
            to[j] = as_input ? others[o] : past;
            pi[j] = 0.0f;
            po[j] = azimuths[z];
        }
        hb_plan *table = table_plan(t, &tilted[k], HB_TT_TRT_TABLE, HB_QUALITY_FAST, t->isa);
        hb_plan *mc = table_plan(t, &tilted[k], HB_TT_TRT_MC, HB_QUALITY_FAST, t->isa);
        if (!table || !mc)
            return;
        hb_eval_angles(table, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        hb_eval_angles(mc, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ g[0], g[1], g[2] }, NULL);
        for (int j = 0; j < N; j++)
            for (int c = 0; c < 3; c++)
                CHECK(t, f[c][j] == 0.0f && g[c][j] == 0.0f, "case %zu: theta_i %g theta_o %g phi_o %g: table %g, "
                      "estimator %g", k, ti[j], to[j], po[j], f[c][j], g[c][j]);
        hb_plan_destroy(table);
        hb_plan_destroy(mc);
    }
}

/* Without tilt f_TT + f_TRT keeps a finite limit at a pole (f 2 cos(theta_o) falls as cos(theta_o) and
 * the projected width's floor is 1e-8), and the table follows it to within 0.003 rad of the pole:
 * the fast table within a factor 1.5 of the nested quadrature at the brighter pairs there (measured
 * 0.77-1.20; the quadrature's own resolution moves these values by up to 18%); a lookup whose
 * cos(theta_o) were floored at half a theta_i step would read 58 times low. The quadrature runs once,
 * for every ISA. */
static void test_table_untilted_pole(hb_test_ctx *t)
{
    static const table_case untilted = { HB_NDF_GGX, 0.3, 0.0, 0.0, 0.1 };
    static const float ti[] = { -1.3f, -0.7f, -1.3f, 0.7f }, to[] = { 1.5678f, 1.5678f, 1.5678f, -1.5678f };
    static const float po[] = { 1.5f, 1.5f, 3.0f, 1.0f }, pi[] = { 0.0f, 0.0f, 0.0f, 0.0f };
    enum { N = sizeof ti / sizeof ti[0] };
    static double want[N][3];
    static int have_want;
    hb_plan *table = table_plan(t, &untilted, HB_TT_TRT_TABLE, HB_QUALITY_FAST, t->isa);
    if (!table)
        return;
    float f[3][N];
    hb_eval_angles(table, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    for (int j = 0; j < N; j++) {
        double tt[3], trt[3];
        if (!have_want) {
            hb_ref_huang_internal(table, ti[j], pi[j], to[j], po[j], 0, 192, 24, 8, tt, trt);
            for (int c = 0; c < 3; c++)
                want[j][c] = tt[c] + trt[c];
        }
        for (int c = 0; c < 3; c++) {
            double ratio = f[c][j] / want[j][c];
            hb_test_note(t, "theta_i %g theta_o %g phi_o %g channel %d: table %.5g, nested quadrature %.5g (%.3f)", ti[j],
                         to[j], po[j], c, f[c][j], want[j][c], ratio);
            CHECK(t, ratio >= 1.0 / 1.5 && ratio <= 1.5, "theta_i %g theta_o %g phi_o %g channel %d: table %.5g vs %.5g",
                  ti[j], to[j], po[j], c, f[c][j], want[j][c]);
        }
    }
    have_want = 1;
    hb_plan_destroy(table);
}

/* A table too costly to build, or asked of the double reference quality, fails at plan creation. */
static void test_table_refusals(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = HB_MODEL_HUANG;
    o.tt_trt = HB_TT_TRT_TABLE;
    m.roughness = 0.01;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_ERR_LIMIT && !plan && strstr(err.message, "tt_trt = mc"),
          "roughness 0.01 balanced: %s", err.message);
    m.roughness = 0.3;
    o.quality = HB_QUALITY_REFERENCE;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_ERR_UNSUPPORTED && !plan, "reference quality: %s", err.message);
}

/* hb_options_default's HB_TT_TRT_AUTO: the table on the finest grid that builds in about a second
 * (the default material's own at balanced), so a direction gives the same f in every call and at
 * every position of a batch (to float rounding between the scalar and SIMD kernels); high quality at roughness 0.1 takes a coarser grid, roughness 0.01 the
 * estimator, and the description says which and why. */
static void test_default_deterministic(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = HB_MODEL_HUANG;
    hb_plan *plan = NULL;
    hb_error e;
    CHECK(t, o.tt_trt == HB_TT_TRT_AUTO, "hb_options_default's tt_trt is %d", (int)o.tt_trt);
    CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "default plan: %s", e.message);
    if (!plan)
        return;
    char text[4096];
    hb_plan_describe(plan, text, sizeof text);
    CHECK(t, strstr(text, "interpolated from a table") != NULL, "the default at balanced is the table:\n%s", text);
    enum { N = 19 };
    float ti[N], pi[N], to[N], po[N], f[3][N], again[3][N], first = 0.0f;
    for (int k = 0; k < N; k++)
        ti[k] = 0.4f, pi[k] = 0.0f, to[k] = -0.45f, po[k] = 3.0f;
    static const size_t counts[] = { 1, 5, 19 };
    for (int call = 0; call < 3; call++) {
        hb_eval_angles(plan, counts[call], (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        hb_eval_angles(plan, counts[call], (hb_angles_soa){ ti, pi, to, po },
                       (hb_rgb_soa){ again[0], again[1], again[2] }, NULL);
        if (call == 0)
            first = f[0][0];
        for (size_t k = 0; k < counts[call]; k++) {
            /* bit for bit in a call and between calls of a size; a call of one sample runs the scalar
             * kernel, which rounds differently from the SIMD ones (docs/huang.md) */
            CHECK(t, f[0][k] == again[0][k] && f[0][k] == f[0][0] && f[0][k] > 0.0f,
                  "call %d, position %zu: %.9g, again %.9g, position 0 %.9g", call, k, f[0][k], again[0][k], f[0][0]);
            CHECK(t, fabsf(f[0][k] - first) <= 1e-6f * first, "call %d, position %zu: %.9g against %.9g", call, k,
                  f[0][k], first);
        }
    }
    hb_plan_destroy(plan);
    static const struct {
        hb_quality quality;
        double roughness;
        const char *says;
    } costly[] = { { HB_QUALITY_HIGH, 0.1, "a coarser grid than the quality's" },
                   { HB_QUALITY_BALANCED, 0.01, "even the fast table would take more than a second" } };
    for (int k = 0; k < 2; k++) {
        o.quality = costly[k].quality, m.roughness = costly[k].roughness;
        CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "quality %d, roughness %g: %s", (int)o.quality,
              m.roughness, e.message);
        if (!plan)
            continue;
        hb_plan_describe(plan, text, sizeof text);
        CHECK(t, strstr(text, costly[k].says) != NULL, "quality %d, roughness %g: '%s' missing from\n%s",
              (int)o.quality, m.roughness, costly[k].says, text);
        hb_plan_destroy(plan);
    }
}

const hb_test hb_tests_huang_table[] = {
    { "huang_default_deterministic", test_default_deterministic, 0 },
    { "huang_table_refusals", test_table_refusals, 0 },
    { "huang_table_matches_estimator", test_table_matches_estimator, 1 },
    { "huang_table_matches_reference", test_table_matches_reference, 0 },
    { "huang_table_hard_directions", test_table_hard_directions, 1 },
    { "huang_table_closed_windows", test_table_closed_windows, 1 },
    { "huang_table_untilted_pole", test_table_untilted_pole, 1 },
    { 0 },
};

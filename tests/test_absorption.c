/* Per-sample absorption (hb_eval_angles_absorption, hb_eval_vectors_absorption, and at h
 * hb_eval_near_absorption): a batch whose samples each carry their strand's sigma_a gives, sample for
 * sample, what a plan of that strand's material gives (dFH11 quadrature in its standard and general
 * shapes, MJC03, CBTB16; the near field of dFH11 and CBTB16), over eumelanin 0..8 and pheomelanin
 * 0..4; bad absorptions are counted; the plans that cannot take it say so. */
#include <math.h>
#include <string.h>

#include "test.h"

enum { STRANDS = 8, PER_STRAND = 96, N = STRANDS * PER_STRAND };

typedef struct absorption_case {
    const char *name;
    hb_model model;
    int pmax;     /* dFH11: 3 is the standard shape, 5 the general one */
    double beta_m, beta_n, eta;
    int near; /* at each sample's h (hb_eval_near_absorption) */
} absorption_case;

static void case_plan_options(const absorption_case *c, hb_material *m, hb_options *o, hb_isa isa)
{
    hb_material_default(m);
    hb_options_default(o);
    o->model = c->model, o->isa = isa, o->pmax = c->pmax;
    m->beta_m = c->beta_m, m->beta_n = c->beta_n, m->eta = c->eta;
}

static void test_matches_per_material_plans(hb_test_ctx *t)
{
    static const absorption_case cases[] = {
        { "deon balanced", HB_MODEL_DEON, 3, 0.1, 0.3, 1.55, 0 },
        { "deon pmax 5, rough", HB_MODEL_DEON, 5, 0.3, 0.6, 1.3, 0 },
        { "deon smooth, eta 1.9", HB_MODEL_DEON, 3, 0.05, 0.15, 1.9, 0 },
        { "marschner", HB_MODEL_MARSCHNER, 3, 0.1, 0.3, 1.55, 0 },
        { "chiang", HB_MODEL_CHIANG, 3, 0.3, 0.3, 1.55, 0 },
        { "deon near", HB_MODEL_DEON, 3, 0.1, 0.3, 1.55, 1 },
        { "deon near pmax 5", HB_MODEL_DEON, 5, 0.3, 0.6, 1.3, 1 },
        { "chiang near", HB_MODEL_CHIANG, 3, 0.3, 0.3, 1.55, 1 },
    };
    static float ti[N], pi[N], to[N], po[N], h[N], sr[N], sg[N], sb[N], f[3][N], ref[3][N];
    for (size_t ci = 0; ci < sizeof cases / sizeof cases[0]; ci++) {
        const absorption_case *c = &cases[ci];
        hb_material m;
        hb_options o;
        case_plan_options(c, &m, &o, t->isa);
        double strand_sigma[STRANDS][3];
        for (int s = 0; s < STRANDS; s++) { /* melanins over 0..8 and 0..4; strand 0 white, strand 1 grey */
            double eu = s == 0 ? 0.0 : hb_test_range(t, 0.0, 8.0), pheo = s < 2 ? 0.0 : hb_test_range(t, 0.0, 4.0);
            hb_melanin_absorption(eu, pheo, strand_sigma[s]);
            if (s == 1)
                strand_sigma[s][1] = strand_sigma[s][2] = strand_sigma[s][0];
            for (int ch = 0; ch < 3; ch++) /* the floats a caller passes */
                strand_sigma[s][ch] = (float)strand_sigma[s][ch];
        }
        for (int k = 0; k < N; k++) { /* strands interleaved, so every block mixes them */
            int s = k % STRANDS;
            ti[k] = (float)hb_test_range(t, -1.5, 1.5), to[k] = (float)hb_test_range(t, -1.5, 1.5);
            pi[k] = (float)hb_test_range(t, -M_PI, M_PI), po[k] = (float)hb_test_range(t, -M_PI, M_PI);
            h[k] = (float)hb_test_range(t, -1.0, 1.0);
            sr[k] = (float)strand_sigma[s][0], sg[k] = (float)strand_sigma[s][1], sb[k] = (float)strand_sigma[s][2];
        }
        hb_plan *plan;
        CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "%s: plan", c->name);
        hb_eval_report report = { 99 };
        hb_absorption_soa sigma = { sr, sg, sb };
        hb_rgb_soa out = { f[0], f[1], f[2] };
        hb_status st = c->near ? hb_eval_near_absorption(plan, N, (hb_near_soa){ ti, pi, to, po, h }, sigma, out, &report)
                               : hb_eval_angles_absorption(plan, N, (hb_angles_soa){ ti, pi, to, po }, sigma, out, &report);
        CHECK(t, st == HB_OK && report.invalid == 0, "%s: status %d, %zu invalid", c->name, (int)st, report.invalid);
        hb_plan_destroy(plan);
        double worst = 0.0, peak = 0.0;
        for (int s = 0; s < STRANDS; s++) { /* the strand's own plan over the same samples */
            hb_material strand = m;
            memcpy(strand.sigma_a, strand_sigma[s], sizeof strand.sigma_a);
            CHECK(t, hb_plan_create(&strand, &o, &plan, NULL) == HB_OK, "%s: strand plan", c->name);
            hb_rgb_soa strand_f = { ref[0], ref[1], ref[2] };
            if (c->near)
                hb_eval_near(plan, N, (hb_near_soa){ ti, pi, to, po, h }, strand_f, NULL);
            else
                hb_eval_angles(plan, N, (hb_angles_soa){ ti, pi, to, po }, strand_f, NULL);
            hb_plan_destroy(plan);
            for (int k = s; k < N; k += STRANDS)
                for (int ch = 0; ch < 3; ch++) {
                    peak = fmax(peak, ref[ch][k]);
                    worst = fmax(worst, fabs(f[ch][k] - ref[ch][k]) / fmax(fabs(ref[ch][k]), 1e-30));
                }
        }
        CHECK(t, worst <= 1e-6, "%s: per-sample absorption differs from the strand's plan by %.3g relative", c->name,
              worst);
        hb_test_note(t, "%s: largest relative difference %.2g (peak f %.3g)", c->name, worst, peak);
    }
}

static void test_vectors_and_invalid(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.isa = t->isa;
    hb_plan *plan;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "plan");
    enum { M = 64 };
    float ti[M], pi[M], to[M], po[M], s[3][M], f[3][M], g[3][M];
    float wx[2][M], wy[2][M], wz[2][M];
    for (int k = 0; k < M; k++) {
        ti[k] = (float)hb_test_range(t, -1.2, 1.2), to[k] = (float)hb_test_range(t, -1.2, 1.2);
        pi[k] = (float)hb_test_range(t, -M_PI, M_PI), po[k] = (float)hb_test_range(t, -M_PI, M_PI);
        const float theta[2] = { ti[k], to[k] }, phi[2] = { pi[k], po[k] };
        for (int d = 0; d < 2; d++) /* docs/conventions.md: x = cos(theta) sin(phi), y = sin(theta), z = cos(theta) cos(phi) */
            wx[d][k] = cosf(theta[d]) * sinf(phi[d]), wy[d][k] = sinf(theta[d]), wz[d][k] = cosf(theta[d]) * cosf(phi[d]);
        for (int ch = 0; ch < 3; ch++)
            s[ch][k] = (float)hb_test_range(t, 0.0, 3.0);
    }
    s[0][3] = NAN, s[1][5] = -1.0f, s[2][7] = INFINITY, ti[7] = NAN; /* 7: both bad, counted once */
    s[0][9] = 1e35f; /* huge but valid: black */
    hb_eval_report report;
    hb_absorption_soa sigma = { s[0], s[1], s[2] };
    CHECK(t, hb_eval_angles_absorption(plan, M, (hb_angles_soa){ ti, pi, to, po }, sigma, (hb_rgb_soa){ f[0], f[1], f[2] },
                                       &report) == HB_OK && report.invalid == 3,
          "three invalid samples, %zu counted", report.invalid);
    for (int ch = 0; ch < 3; ch++)
        CHECK(t, f[ch][3] == 0.0f && f[ch][5] == 0.0f && f[ch][7] == 0.0f && f[ch][9] >= 0.0f && isfinite(f[ch][9]),
              "invalid samples give 0, a huge absorption a finite value");
    hb_vectors_soa vin = { wx[0], wy[0], wz[0], wx[1], wy[1], wz[1] };
    CHECK(t, hb_eval_vectors_absorption(plan, M, vin, sigma, (hb_rgb_soa){ g[0], g[1], g[2] }, &report) == HB_OK &&
                 report.invalid == 3, "vectors: the same three invalid (by absorption alone), %zu counted", report.invalid);
    double worst = 0.0;
    for (int k = 0; k < M; k++)
        for (int ch = 0; ch < 3; ch++)
            if (k != 3 && k != 5 && k != 7)
                worst = fmax(worst, fabs(f[ch][k] - g[ch][k]) / fmax(fabs(f[ch][k]), 1e-3));
    CHECK(t, worst <= 2e-4, "vectors against angles: %.3g relative", worst);
    CHECK(t, hb_eval_angles_absorption(plan, M, (hb_angles_soa){ ti, pi, to, po }, (hb_absorption_soa){ s[0], NULL, s[2] },
                                       (hb_rgb_soa){ f[0], f[1], f[2] }, NULL) == HB_ERR_NULL, "a NULL channel");
    hb_plan_destroy(plan);
    double melanin[3], material[3];
    hb_melanin_absorption(1.3, 0.4, melanin);
    m.eumelanin = 1.3, m.pheomelanin = 0.4;
    hb_material_absorption(&m, material);
    CHECK(t, memcmp(melanin, material, sizeof melanin) == 0, "hb_melanin_absorption is the material's melanin part");
}

static void test_unsupported(hb_test_ctx *t)
{
    static const struct {
        const char *what;
        hb_model model;
        hb_quality quality;
        hb_azimuthal azimuthal;
        hb_term term;
    } plans[] = {
        { "deon N_p table", HB_MODEL_DEON, HB_QUALITY_FAST, HB_AZIMUTHAL_TABLE, HB_TERM_FULL },
        { "deon reference", HB_MODEL_DEON, HB_QUALITY_REFERENCE, HB_AZIMUTHAL_QUADRATURE, HB_TERM_FULL },
        { "deon longitudinal", HB_MODEL_DEON, HB_QUALITY_BALANCED, HB_AZIMUTHAL_QUADRATURE, HB_TERM_LONGITUDINAL },
        { "huang", HB_MODEL_HUANG, HB_QUALITY_FAST, HB_AZIMUTHAL_QUADRATURE, HB_TERM_FULL },
        { "chiang reference", HB_MODEL_CHIANG, HB_QUALITY_REFERENCE, HB_AZIMUTHAL_QUADRATURE, HB_TERM_FULL },
    };
    float x[1] = { 0.1f }, f[3][1];
    for (size_t k = 0; k < sizeof plans / sizeof plans[0]; k++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        o.model = plans[k].model, o.quality = plans[k].quality, o.azimuthal = plans[k].azimuthal, o.term = plans[k].term;
        if (o.term == HB_TERM_LONGITUDINAL)
            o.lobes = 1u << HB_LOBE_R;
        hb_plan *plan;
        hb_error error;
        CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_OK, "%s: %s", plans[k].what, error.message);
        hb_status st = hb_eval_angles_absorption(plan, 1, (hb_angles_soa){ x, x, x, x }, (hb_absorption_soa){ x, x, x },
                                                 (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        CHECK(t, st == HB_ERR_UNSUPPORTED, "%s: status %d", plans[k].what, (int)st);
        st = hb_eval_near_absorption(plan, 1, (hb_near_soa){ x, x, x, x, x }, (hb_absorption_soa){ x, x, x },
                                     (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        int near_field = plans[k].model == HB_MODEL_DEON && plans[k].term == HB_TERM_FULL &&
                         plans[k].quality != HB_QUALITY_REFERENCE;
        CHECK(t, st == (near_field ? HB_OK : HB_ERR_UNSUPPORTED), "%s: near-field status %d", plans[k].what, (int)st);
        hb_plan_destroy(plan);
    }
}

const hb_test hb_tests_absorption[] = {
    { "absorption_matches_per_material_plans", test_matches_per_material_plans, 1 },
    { "absorption_vectors_and_invalid", test_vectors_and_invalid, 1 },
    { "absorption_unsupported", test_unsupported, 0 },
    { NULL, NULL, 0 },
};

/* Runs tests/data/hard_cases.csv (or $HB_TEST_DATA/hard_cases.csv) through every model and term
 * that exists, on the test's ISA and at every quality. */
#include <stdlib.h>
#include <string.h>

#include "test.h"

typedef struct corpus_row {
    double eta, sigma_a, beta_m, beta_n, alpha;
    float theta_i, phi_i, theta_o, phi_o;
    char expect[16];
    double tolerance;
    int line;
} corpus_row;

static int load_corpus(hb_test_ctx *t, corpus_row *rows, int cap)
{
    const char *dir = getenv("HB_TEST_DATA");
    char path[512], line[512];
    snprintf(path, sizeof path, "%s/hard_cases.csv", dir && *dir ? dir : "tests/data");
    FILE *f = fopen(path, "r");
    CHECK(t, f != NULL, "cannot open %s", path);
    int n = 0, lineno = 0;
    while (f && fgets(line, sizeof line, f) && n < cap) {
        lineno++;
        if (line[0] == '#' || line[0] == '\n')
            continue;
        corpus_row *r = &rows[n];
        double v[9];
        char *p = line, *end;
        int ok = 1;
        for (int c = 0; c < 9 && ok; c++) {
            v[c] = strtod(p, &end);
            ok = end != p && *end == ',';
            p = end + 1;
        }
        r->tolerance = 0.0;
        ok = ok && sscanf(p, "%15s %lf", r->expect, &r->tolerance) >= 1;
        CHECK(t, ok, "%s:%d: malformed row", path, lineno);
        if (!ok)
            continue;
        r->eta = v[0], r->sigma_a = v[1], r->beta_m = v[2], r->beta_n = v[3], r->alpha = v[4];
        r->theta_i = (float)v[5], r->phi_i = (float)v[6], r->theta_o = (float)v[7], r->phi_o = (float)v[8];
        r->line = lineno;
        n++;
    }
    if (f)
        fclose(f);
    return n;
}

/* HHH22 rows use beta_m as the microfacet roughness (capped at its range, 1) and the R lobe;
 * term LONGITUDINAL stands for its closed form (GGX without G), FULL for Simpson with Smith G. */
static int eval_row(const corpus_row *r, hb_model model, hb_term term, hb_quality quality, hb_isa isa, float f[3])
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eta = r->eta;
    m.sigma_a[0] = m.sigma_a[1] = m.sigma_a[2] = r->sigma_a;
    m.beta_m = r->beta_m, m.beta_n = r->beta_n, m.alpha = r->alpha;
    o.model = model, o.term = term, o.quality = quality, o.isa = isa;
    if (model == HB_MODEL_HUANG) {
        m.roughness = fmin(r->beta_m, 1.0);
        o.lobes = 1u << HB_LOBE_R;
        o.term = HB_TERM_FULL;
        o.shadowing = term == HB_TERM_LONGITUDINAL ? HB_SHADOWING_NONE : HB_SHADOWING_SMITH;
    }
    hb_plan *plan;
    if (hb_plan_create(&m, &o, &plan, NULL) != HB_OK)
        return -1;
    hb_eval_report rep;
    hb_eval_angles(plan, 1, (hb_angles_soa){ &r->theta_i, &r->phi_i, &r->theta_o, &r->phi_o },
                   (hb_rgb_soa){ &f[0], &f[1], &f[2] }, &rep);
    hb_plan_destroy(plan);
    return (int)rep.invalid;
}

static void test_hard_case_corpus(hb_test_ctx *t)
{
    static corpus_row rows[256];
    int n = load_corpus(t, rows, 256);
    CHECK(t, n > 20, "corpus has %d rows", n);
    const struct { hb_model model; hb_term term; const char *name; } terms[] = {
        { HB_MODEL_DEON, HB_TERM_FULL, "deon" },
        { HB_MODEL_DEON, HB_TERM_LONGITUDINAL, "deon longitudinal" },
        { HB_MODEL_MARSCHNER, HB_TERM_FULL, "marschner" },
        { HB_MODEL_MARSCHNER, HB_TERM_LONGITUDINAL, "marschner longitudinal" },
        { HB_MODEL_HUANG, HB_TERM_FULL, "huang R" },
        { HB_MODEL_HUANG, HB_TERM_LONGITUDINAL, "huang R analytic" },
    };
    for (size_t k = 0; k < sizeof terms / sizeof terms[0]; k++)
        for (int q = HB_QUALITY_FAST; q <= HB_QUALITY_HIGH; q++) {
            float prev[3] = { 0, 0, 0 };
            for (int i = 0; i < n; i++) {
                const corpus_row *r = &rows[i];
                float f[3], ref[3];
                int invalid = eval_row(r, terms[k].model, terms[k].term, (hb_quality)q, t->isa, f);
                CHECK(t, invalid >= 0, "line %d: plan refused", r->line);
                if (!strcmp(r->expect, "invalid")) {
                    CHECK(t, invalid == 1 && f[0] == 0 && f[1] == 0 && f[2] == 0, "line %d (%s q%d): invalid %d, f %g",
                          r->line, terms[k].name, q, invalid, f[0]);
                    continue;
                }
                for (int c = 0; c < 3; c++)
                    CHECK(t, invalid == 0 && isfinite(f[c]) && f[c] >= 0.0f, "line %d (%s q%d): f = %g, invalid %d",
                          r->line, terms[k].name, q, f[c], invalid);
                if (!strcmp(r->expect, "ref") && q == HB_QUALITY_HIGH) {
                    eval_row(r, terms[k].model, terms[k].term, HB_QUALITY_REFERENCE, t->isa, ref);
                    for (int c = 0; c < 3; c++)
                        CHECK(t, fabs(f[c] - ref[c]) <= r->tolerance * fmax(ref[c], 1e-4),
                              "line %d (%s): %.9g vs reference %.9g", r->line, terms[k].name, f[c], ref[c]);
                }
                if (!strcmp(r->expect, "prev"))
                    for (int c = 0; c < 3; c++)
                        CHECK(t, fabs(f[c] - prev[c]) <= r->tolerance * fmax(fabs(prev[c]), 1e-6),
                              "line %d (%s q%d): %.9g, previous row %.9g", r->line, terms[k].name, q, f[c], prev[c]);
                memcpy(prev, f, sizeof prev);
            }
        }
}

const hb_test hb_tests_corpus[] = {
    { "hard_case_corpus", test_hard_case_corpus, 1 },
    { NULL, NULL, 0 },
};

/* Runs tests/data/hard_cases.csv (or $HB_TEST_DATA/hard_cases.csv) through every model and term
 * that exists, on the test's ISA and at every quality. HHH22's TT and TRT come from the
 * Monte-Carlo/Simpson estimator; their "ref" is the same estimator in double with the same random
 * numbers (hb_ref_huang_internal_mc), plus the R lobe's own reference. */
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "ref/reference.h"
#include "models/huang/reference.h"

typedef struct corpus_row {
    double eta, sigma_a, beta_m, beta_n, alpha, eccentricity;
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
        double v[10];
        char *p = line, *end;
        int ok = 1;
        for (int c = 0; c < 10 && ok; c++) {
            v[c] = strtod(p, &end);
            ok = end != p && *end == ',';
            p = end + 1;
        }
        r->tolerance = 0.0;
        ok = ok && sscanf(p, "%15s %lf", r->expect, &r->tolerance) >= 1;
        CHECK(t, ok, "%s:%d: malformed row", path, lineno);
        if (!ok)
            continue;
        r->eta = v[0], r->sigma_a = v[1], r->beta_m = v[2], r->beta_n = v[3], r->alpha = v[4], r->eccentricity = v[5];
        r->theta_i = (float)v[6], r->phi_i = (float)v[7], r->theta_o = (float)v[8], r->phi_o = (float)v[9];
        r->line = lineno;
        n++;
    }
    if (f)
        fclose(f);
    return n;
}

/* What a corpus row runs through. HHH22 terms read beta_m as the microfacet roughness (capped at its
 * range, 1); analytic is App. A's closed form (GGX, no G, circular fibres only). */
typedef struct corpus_term {
    const char *name;
    hb_model model;
    hb_term term;
    unsigned lobes;
    hb_ndf ndf;
    hb_shadowing shadowing;
    int analytic;
    double tolerance; /* the path's own stated float tolerance, when above a row's */
    float h;          /* CBTB16: the near field at this offset */
} corpus_term;

enum { R_ONLY = 1u << HB_LOBE_R, R_TT_TRT = 7u };

static const corpus_term terms[] = {
    { "deon", HB_MODEL_DEON, HB_TERM_FULL, HB_LOBES_DEFAULT, HB_NDF_GGX, HB_SHADOWING_SMITH, 0, 0.0, 0.0f },
    { "deon longitudinal", HB_MODEL_DEON, HB_TERM_LONGITUDINAL, HB_LOBES_DEFAULT, HB_NDF_GGX, HB_SHADOWING_SMITH, 0, 0.0, 0.0f },
    { "marschner", HB_MODEL_MARSCHNER, HB_TERM_FULL, HB_LOBES_DEFAULT, HB_NDF_GGX, HB_SHADOWING_SMITH, 0, 0.0, 0.0f },
    { "marschner longitudinal", HB_MODEL_MARSCHNER, HB_TERM_LONGITUDINAL, HB_LOBES_DEFAULT, HB_NDF_GGX,
      HB_SHADOWING_SMITH, 0, 0.0, 0.0f },
    { "huang R", HB_MODEL_HUANG, HB_TERM_FULL, R_ONLY, HB_NDF_GGX, HB_SHADOWING_SMITH, 0, 0.0, 0.0f },
    { "huang R beckmann", HB_MODEL_HUANG, HB_TERM_FULL, R_ONLY, HB_NDF_BECKMANN, HB_SHADOWING_SMITH, 0, 0.0, 0.0f },
    { "huang R analytic", HB_MODEL_HUANG, HB_TERM_FULL, R_ONLY, HB_NDF_GGX, HB_SHADOWING_NONE, 1, 0.0, 0.0f },
    /* Beckmann's float visible normal (Newton on Giles' erfinv) is 5e-3 from the double's after two
     * interfaces (test_huang_internal) */
    { "huang R+TT+TRT", HB_MODEL_HUANG, HB_TERM_FULL, R_TT_TRT, HB_NDF_GGX, HB_SHADOWING_SMITH, 0, 0.0, 0.0f },
    { "huang R+TT+TRT beckmann", HB_MODEL_HUANG, HB_TERM_FULL, R_TT_TRT, HB_NDF_BECKMANN, HB_SHADOWING_SMITH, 0, 5e-3, 0.0f },
    /* CBTB16's near field at the fibre's edge and inside; its float azimuth limits it to 3e-5
     * (docs/chiang.md) */
    { "chiang near h 1", HB_MODEL_CHIANG, HB_TERM_FULL, HB_LOBES_DEFAULT, HB_NDF_GGX, HB_SHADOWING_SMITH, 0, 3e-5, 1.0f },
    { "chiang near h -0.3", HB_MODEL_CHIANG, HB_TERM_FULL, HB_LOBES_DEFAULT, HB_NDF_GGX, HB_SHADOWING_SMITH, 0, 3e-5,
      -0.3f },
};

static int circular_only(const corpus_term *term)
{
    return term->model == HB_MODEL_DEON || term->model == HB_MODEL_CHIANG || term->analytic;
}

/* The row's plan for a term; NULL when the term does not apply (an ellipse for dFH11 or for App. A). */
static hb_plan *row_plan(const corpus_row *r, const corpus_term *term, unsigned lobes, hb_quality quality, hb_isa isa)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eta = r->eta;
    m.sigma_a[0] = m.sigma_a[1] = m.sigma_a[2] = r->sigma_a;
    m.beta_m = r->beta_m, m.beta_n = r->beta_n, m.alpha = r->alpha, m.eccentricity = r->eccentricity;
    o.model = term->model, o.term = term->term, o.quality = quality, o.isa = isa, o.lobes = lobes;
    if (term->model == HB_MODEL_CHIANG) { /* its roughnesses in [0, 1], beta_m from 0.0028 (v_TT >= 1e-6) */
        m.beta_m = fmax(0.0028, fmin(r->beta_m, 1.0));
        m.beta_n = fmin(r->beta_n, 1.0);
    }
    if (term->model == HB_MODEL_HUANG) {
        m.roughness = fmin(r->beta_m, 1.0);
        m.ndf = term->ndf;
        o.shadowing = term->shadowing;
        o.r_integration = term->analytic ? HB_R_INTEGRATION_ANALYTIC : HB_R_INTEGRATION_AUTO;
        o.tt_trt = HB_TT_TRT_MC; /* the estimator's hard cases (the table's: test_huang_table.c) */
        o.pole_floor = HB_POLE_FLOOR_BOUNDED; /* the kernels' pole choice at the reference too */
    }
    if (r->eccentricity > 0.0 && circular_only(term))
        return NULL;
    hb_plan *plan = NULL;
    hb_plan_create(&m, &o, &plan, NULL);
    return plan;
}

/* f of the row's single sample (near-field terms at their h); returns the number of invalid samples,
 * -1 if the plan was refused. */
static int eval_row(const corpus_row *r, const corpus_term *term, const hb_plan *plan, float f[3])
{
    if (!plan)
        return -1;
    hb_eval_report rep;
    hb_rgb_soa out = { &f[0], &f[1], &f[2] };
    if (term->model == HB_MODEL_CHIANG)
        hb_eval_near(plan, 1, (hb_near_soa){ &r->theta_i, &r->phi_i, &r->theta_o, &r->phi_o, &term->h }, out, &rep);
    else
        hb_eval_angles(plan, 1, (hb_angles_soa){ &r->theta_i, &r->phi_i, &r->theta_o, &r->phi_o }, out, &rep);
    return (int)rep.invalid;
}

/* The double reference of what `plan` evaluates: the reference quality's plan, and for HHH22's
 * TT and TRT the double estimator with the numbers of the sample at index 0 of `plan`. */
static void reference_row(const corpus_row *r, const corpus_term *term, const hb_plan *plan, double ref[3])
{
    int internal = term->model == HB_MODEL_HUANG && term->lobes != R_ONLY;
    hb_plan *reference = row_plan(r, term, internal ? R_ONLY : term->lobes, HB_QUALITY_REFERENCE, HB_ISA_SCALAR);
    float f[3] = { 0, 0, 0 };
    eval_row(r, term, reference, f);
    hb_plan_destroy(reference);
    double tt[3] = { 0, 0, 0 }, trt[3] = { 0, 0, 0 };
    if (internal)
        hb_ref_huang_internal_mc(plan, r->theta_i, r->phi_i, r->theta_o, r->phi_o, 0, tt, trt);
    for (int c = 0; c < 3; c++)
        ref[c] = (double)f[c] + tt[c] + trt[c];
}

static void test_hard_case_corpus(hb_test_ctx *t)
{
    static corpus_row rows[256];
    int n = load_corpus(t, rows, 256);
    CHECK(t, n > 20, "corpus has %d rows", n);
    for (size_t k = 0; k < sizeof terms / sizeof terms[0]; k++) {
        double worst = 0.0; /* |f - ref| / max(ref, 1e-4) over the ref rows, reported */
        int worst_line = 0;
        for (int q = HB_QUALITY_FAST; q <= HB_QUALITY_HIGH; q++) {
            float prev[3] = { 0, 0, 0 };
            for (int i = 0; i < n; i++) {
                const corpus_row *r = &rows[i];
                float f[3];
                hb_plan *plan = row_plan(r, &terms[k], terms[k].lobes, (hb_quality)q, t->isa);
                if (!plan && r->eccentricity > 0.0 && circular_only(&terms[k]))
                    continue; /* not this term's fibre */
                int invalid = eval_row(r, &terms[k], plan, f);
                CHECK(t, invalid >= 0, "line %d (%s): plan refused", r->line, terms[k].name);
                if (!strcmp(r->expect, "invalid")) {
                    CHECK(t, invalid == 1 && f[0] == 0 && f[1] == 0 && f[2] == 0, "line %d (%s q%d): invalid %d, f %g",
                          r->line, terms[k].name, q, invalid, f[0]);
                    hb_plan_destroy(plan);
                    continue;
                }
                for (int c = 0; c < 3; c++)
                    CHECK(t, invalid == 0 && isfinite(f[c]) && f[c] >= 0.0f, "line %d (%s q%d): f = %g, invalid %d",
                          r->line, terms[k].name, q, f[c], invalid);
                if (!strcmp(r->expect, "ref") && q == HB_QUALITY_HIGH && plan) {
                    double ref[3], tolerance = fmax(r->tolerance, terms[k].tolerance);
                    reference_row(r, &terms[k], plan, ref);
                    for (int c = 0; c < 3; c++) {
                        double err = fabs(f[c] - ref[c]) / fmax(ref[c], 1e-4);
                        CHECK(t, err <= tolerance, "line %d (%s): %.9g vs reference %.9g", r->line, terms[k].name,
                              f[c], ref[c]);
                        if (err > worst)
                            worst = err, worst_line = r->line;
                    }
                }
                if (!strcmp(r->expect, "prev"))
                    for (int c = 0; c < 3; c++)
                        CHECK(t, fabs(f[c] - prev[c]) <= r->tolerance * fmax(fabs(prev[c]), 1e-6),
                              "line %d (%s q%d): %.9g, previous row %.9g", r->line, terms[k].name, q, f[c], prev[c]);
                memcpy(prev, f, sizeof prev);
                hb_plan_destroy(plan);
            }
        }
        hb_test_note(t, "%s: worst %.1e of the reference (line %d)", terms[k].name, worst, worst_line);
    }
}

const hb_test hb_tests_corpus[] = {
    { "hard_case_corpus", test_hard_case_corpus, 1 },
    { NULL, NULL, 0 },
};

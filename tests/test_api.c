/* Public API contract: defaults, validation with messages that name the parameter,
 * NULL handling, unsupported combinations, ISA selection and HB_ISA. */
#include <stdlib.h>
#include <string.h>

#include "portable.h"
#include "test.h"

static hb_status create(hb_material *m, hb_options *o, hb_error *err)
{
    hb_plan *plan = (hb_plan *)&plan; /* must be reset to NULL on failure */
    hb_status st = hb_plan_create(m, o, &plan, err);
    if (st == HB_OK)
        hb_plan_destroy(plan);
    else if (plan != NULL)
        return (hb_status)-1;
    return st;
}

static void test_defaults(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    CHECK(t, m.eta == 1.55 && m.beta_m == 0.1 && m.beta_n == 0.3 && m.alpha == 0.035 && m.roughness == 0.1,
          "docs/conventions.md defaults");
    CHECK(t, m.sigma_a[0] == 0 && m.eccentricity == 0 && m.ndf == HB_NDF_GGX, "zero absorption, circular, GGX");
    CHECK(t, o.model == HB_MODEL_DEON && o.quality == HB_QUALITY_BALANCED && o.isa == HB_ISA_AUTO, "options");
    m.sigma_a[1] = 0.5;
    m.eumelanin = 2.0;
    m.pheomelanin = 1.0;
    double s[3];
    hb_material_absorption(&m, s);
    CHECK(t, fabs(s[0] - (2 * 0.419 + 0.187)) < 1e-15 && fabs(s[1] - (0.5 + 2 * 0.697 + 0.4)) < 1e-15 &&
                 fabs(s[2] - (2 * 1.37 + 1.05)) < 1e-15,
          "melanin absorption (dFH11 sec. 6.1) adds to sigma_a: %g %g %g", s[0], s[1], s[2]);
}

/* Every out-of-range parameter fails at plan creation with a message naming it. */
static void test_validation(hb_test_ctx *t)
{
    struct {
        const char *name;
        size_t offset;
        double value;
    } cases[] = {
        { "eta", offsetof(hb_material, eta), 1.0 },
        { "eta", offsetof(hb_material, eta), NAN },
        { "sigma_a.r", offsetof(hb_material, sigma_a), -0.1 },
        { "sigma_a.r", offsetof(hb_material, sigma_a), NAN },
        { "sigma_a.g", offsetof(hb_material, sigma_a) + sizeof(double), INFINITY },
        { "eumelanin", offsetof(hb_material, eumelanin), -1.0 },
        { "pheomelanin", offsetof(hb_material, pheomelanin), NAN },
        { "beta_m", offsetof(hb_material, beta_m), 0.0009 },
        { "beta_m", offsetof(hb_material, beta_m), -0.1 },
        { "beta_m", offsetof(hb_material, beta_m), 4.0 },
        { "beta_m", offsetof(hb_material, beta_m), NAN },
        { "beta_n", offsetof(hb_material, beta_n), 0.0 },
        { "alpha", offsetof(hb_material, alpha), 0.5 },
        { "roughness", offsetof(hb_material, roughness), -1.0 },
        { "eccentricity", offsetof(hb_material, eccentricity), 1.0 },
        { "lobe_beta_m[2]", offsetof(hb_material, lobe_beta_m) + 2 * sizeof(double), 9.0 },
        { "lobe_beta_n[1]", offsetof(hb_material, lobe_beta_n) + 1 * sizeof(double), 0.001 },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        hb_material m;
        hb_options o;
        hb_test_longitudinal_setup(t, &m, &o);
        memcpy((char *)&m + cases[k].offset, &cases[k].value, sizeof(double));
        hb_error err;
        hb_status st = create(&m, &o, &err);
        CHECK(t, st == HB_ERR_PARAM && err.status == HB_ERR_PARAM, "%s = %g: status %d", cases[k].name,
              cases[k].value, (int)st);
        CHECK(t, strstr(err.message, cases[k].name) != NULL, "%s = %g: message '%s' does not name it",
              cases[k].name, cases[k].value, err.message);
    }
    hb_material m;
    hb_options o;
    hb_test_longitudinal_setup(t, &m, &o);
    m.eta = 1.0001; /* eta near 1 is valid */
    m.beta_m = 0.01;
    m.sigma_a[0] = 1e3;
    CHECK(t, create(&m, &o, NULL) == HB_OK, "hard but valid material refused");
    m.struct_size = 8;
    CHECK(t, create(&m, &o, NULL) == HB_ERR_VERSION, "struct_size 8 accepted");
    m.struct_size = sizeof m + 8; /* a newer header's */
    hb_error newer;
    CHECK(t, create(&m, &o, &newer) == HB_ERR_VERSION && strstr(newer.message, "newer hairbsdf.h"),
          "a larger struct_size: '%s'", newer.message);

    /* per-lobe tilt: the printed range [-0.6, 0.6] exactly, not the double 3 * 0.2 */
    static const double lobe_alphas[] = { 0.6000000000000001, -0.6000000000000001, 0.6, -0.6 };
    for (size_t k = 0; k < sizeof lobe_alphas / sizeof lobe_alphas[0]; k++) {
        hb_material_default(&m);
        hb_options_default(&o);
        o.isa = HB_ISA_SCALAR;
        m.lobe_alpha_override = 1u << HB_LOBE_TT;
        m.lobe_alpha[HB_LOBE_TT] = lobe_alphas[k];
        hb_error err;
        hb_status st = create(&m, &o, &err);
        int inside = fabs(lobe_alphas[k]) <= 0.6;
        CHECK(t, inside ? st == HB_OK : (st == HB_ERR_PARAM && strstr(err.message, "lobe_alpha[1]")),
              "lobe_alpha = %.17g: status %d '%s'", lobe_alphas[k], (int)st, st ? err.message : "");
    }
    /* HHH22's TT/TRT options are checked for every model, and each model names its own lobes */
    for (int model = HB_MODEL_DEON; model <= HB_MODEL_HUANG; model++) {
        const struct { int tt_trt, tt_panels; const char *name; } bad[] = { { 7, 0, "tt_trt" }, { -1, 0, "tt_trt" },
                                                                             { 0, 3, "tt_panels" }, { 0, -2, "tt_panels" } };
        for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
            hb_material_default(&m);
            hb_options_default(&o);
            o.model = (hb_model)model;
            o.isa = HB_ISA_SCALAR;
            o.tt_trt = (hb_tt_trt)bad[k].tt_trt;
            o.tt_panels = bad[k].tt_panels;
            hb_error err;
            hb_status st = create(&m, &o, &err);
            CHECK(t, st == HB_ERR_PARAM && strstr(err.message, bad[k].name), "model %d %s = %d/%d: status %d '%s'", model,
                  bad[k].name, bad[k].tt_trt, bad[k].tt_panels, (int)st, st ? err.message : "");
        }
    }
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = HB_MODEL_HUANG;
    o.lobes = 1u << HB_LOBE_TRRT;
    hb_error err;
    CHECK(t, create(&m, &o, &err) == HB_ERR_UNSUPPORTED && strstr(err.message, "huang"),
          "huang with TRRT: '%s' does not name the huang model's lobes", err.message);
}

static void test_unsupported_and_null(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_error err;
    hb_test_longitudinal_setup(t, &m, &o);
    o.model = HB_MODEL_HUANG;
    CHECK(t, create(&m, &o, &err) == HB_ERR_UNSUPPORTED && strstr(err.message, "huang"), "huang: %s", err.message);
    o.model = HB_MODEL_MARSCHNER;
    o.term = HB_TERM_FULL;
    CHECK(t, create(&m, &o, &err) == HB_OK, "full marschner: %s", err.message);
    o.lobes = 1u << HB_LOBE_TRRT;
    CHECK(t, create(&m, &o, &err) == HB_ERR_UNSUPPORTED && strstr(err.message, "marschner"), "marschner TRRT: %s",
          err.message);
    o.lobes = HB_LOBES_DEFAULT;
    o.term = HB_TERM_LONGITUDINAL;
    CHECK(t, create(&m, &o, &err) == HB_OK, "marschner longitudinal: %s", err.message);
    o.model = HB_MODEL_DEON;
    o.term = HB_TERM_FULL;
    CHECK(t, create(&m, &o, &err) == HB_OK, "full deon: %s", err.message);
    o.pmax = 2;
    o.lobes = 1u << HB_LOBE_TRRT;
    CHECK(t, create(&m, &o, &err) == HB_ERR_UNSUPPORTED && strstr(err.message, "pmax"), "TRRT above pmax 2: %s",
          err.message);
    o.pmax = 8;
    o.lobes = HB_LOBES_DEFAULT;
    CHECK(t, create(&m, &o, &err) == HB_ERR_PARAM && strstr(err.message, "pmax"), "pmax 8: %s", err.message);
    o.pmax = 3;
    m.eccentricity = 0.5; /* valid for marschner and huang; dFH11 has no elliptical fibre */
    CHECK(t, create(&m, &o, &err) == HB_ERR_UNSUPPORTED && strstr(err.message, "eccentricity"), "deon ellipse: %s",
          err.message);
    m.eccentricity = 0.0;
    o.quadrature_order = HB_MAX_QUADRATURE_ORDER + 1;
    CHECK(t, create(&m, &o, &err) == HB_ERR_PARAM && strstr(err.message, "quadrature_order"), "nodes: %s",
          err.message);
    o.quadrature_order = 0;
    o.detector_tolerance = 0.5;
    CHECK(t, create(&m, &o, &err) == HB_ERR_PARAM && strstr(err.message, "detector_tolerance"), "tol: %s",
          err.message);
    o.detector_tolerance = 0.0;
    o.term = HB_TERM_LONGITUDINAL;
    o.lobes = 1u << HB_LOBE_TT;
    CHECK(t, create(&m, &o, &err) == HB_ERR_UNSUPPORTED, "longitudinal term of TT");
    o.lobes = HB_LOBES_DEFAULT;
    o.quality = (hb_quality)17;
    CHECK(t, create(&m, &o, &err) == HB_ERR_PARAM && strstr(err.message, "quality"), "bad quality: %s",
          err.message);
    o.quality = HB_QUALITY_BALANCED;
    CHECK(t, hb_plan_create(NULL, &o, NULL, NULL) == HB_ERR_NULL, "NULL output pointer");
    hb_plan *plan = NULL;
    CHECK(t, hb_plan_create(NULL, &o, &plan, &err) == HB_ERR_NULL && plan == NULL, "NULL material");
    CHECK(t, create(&m, &o, NULL) == HB_OK, "NULL error pointer is allowed");

    hb_plan_create(&m, &o, &plan, NULL);
    float x = 0.1f, r, g, b;
    hb_angles_soa in = { &x, &x, &x, &x };
    CHECK(t, hb_eval_angles(NULL, 1, in, (hb_rgb_soa){ &r, &g, &b }, NULL) == HB_ERR_NULL, "NULL plan");
    CHECK(t, hb_eval_angles(plan, 1, in, (hb_rgb_soa){ &r, NULL, &b }, NULL) == HB_ERR_NULL, "NULL output");
    in.phi_o = NULL;
    CHECK(t, hb_eval_angles(plan, 1, in, (hb_rgb_soa){ &r, &g, &b }, NULL) == HB_ERR_NULL, "NULL input");
    hb_eval_report rep = { 99 };
    CHECK(t, hb_eval_angles(plan, 0, in, (hb_rgb_soa){ NULL, NULL, NULL }, &rep) == HB_OK && rep.invalid == 0,
          "empty batch");
    hb_plan_destroy(plan);
    hb_plan_destroy(NULL);
    for (int s = HB_OK; s <= HB_ERR_NOMEM; s++)
        CHECK(t, strlen(hb_status_string((hb_status)s)) > 0, "status %d has no string", s);
}

static void test_isa_selection(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_error err;
    hb_test_longitudinal_setup(t, &m, &o);
    CHECK(t, hb_isa_available(HB_ISA_SCALAR) && !hb_isa_available(HB_ISA_AUTO), "scalar always, auto never");
    for (int i = HB_ISA_SCALAR; i < HB_ISA_COUNT; i++) {
        CHECK(t, hb_isa_from_name(hb_isa_name((hb_isa)i)) == (hb_isa)i, "name round trip %d", i);
        o.isa = (hb_isa)i;
        hb_plan *plan = NULL;
        hb_status st = hb_plan_create(&m, &o, &plan, &err);
        if (hb_isa_available((hb_isa)i))
            CHECK(t, st == HB_OK && hb_plan_isa(plan) == (hb_isa)i, "%s: %s", hb_isa_name((hb_isa)i), err.message);
        else
            CHECK(t, st == HB_ERR_ISA && strstr(err.message, hb_isa_name((hb_isa)i)), "%s unavailable: %s",
                  hb_isa_name((hb_isa)i), err.message);
        hb_plan_destroy(plan);
    }
    CHECK(t, hb_isa_from_name("mmx") == HB_ISA_COUNT, "unknown name");

    /* HB_ISA steers HB_ISA_AUTO; a bad value is a clear error. */
    const char *saved = getenv("HB_ISA");
    char *copy = saved ? strdup(saved) : NULL;
    o.isa = HB_ISA_AUTO;
    setenv("HB_ISA", "scalar", 1);
    hb_plan *plan = NULL;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK && hb_plan_isa(plan) == HB_ISA_SCALAR, "HB_ISA=scalar");
    hb_plan_destroy(plan);
    setenv("HB_ISA", "bogus", 1);
    CHECK(t, create(&m, &o, &err) == HB_ERR_ISA && strstr(err.message, "HB_ISA=bogus"), "HB_ISA=bogus: %s",
          err.message);
    if (copy) {
        setenv("HB_ISA", copy, 1);
        free(copy);
    } else {
        unsetenv("HB_ISA");
    }
    if (!copy) {
        hb_plan_create(&m, &o, &plan, NULL);
        CHECK(t, hb_plan_isa(plan) == hb_isa_best(), "auto picks the best ISA");
        hb_plan_destroy(plan);
    }
}

/* A program built against an older header passes a smaller struct_size: the fields it lacks take
 * their defaults, whatever follows its struct in memory. Here the older hb_material ends before the
 * MJC03 caustic fields and the older hb_options before the tolerance/budget fields; the plan equals
 * one made from defaults for them, value for value. */
static void test_older_structs(hb_test_ctx *t)
{
    hb_material full_m, old_m;
    hb_options full_o, old_o;
    hb_material_default(&full_m);
    hb_options_default(&full_o);
    full_m.eta = 1.6;
    full_m.beta_m = 0.2;
    full_o.model = HB_MODEL_MARSCHNER;
    full_o.isa = HB_ISA_SCALAR;
    old_m = full_m;
    old_o = full_o;
    old_m.struct_size = offsetof(hb_material, glint_scale);
    old_o.struct_size = offsetof(hb_options, tolerance);
    old_m.glint_scale = old_m.caustic_width = old_m.caustic_fade = old_m.caustic_limit = -7.0; /* past the old end */
    old_o.tolerance = old_o.budget_ns = -7.0;
    hb_plan *full = NULL, *old = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&full_m, &full_o, &full, NULL) == HB_OK, "full-size structs refused");
    CHECK(t, hb_plan_create(&old_m, &old_o, &old, &err) == HB_OK, "older structs refused: %s", err.message);
    CHECK(t, old_m.struct_size == offsetof(hb_material, glint_scale), "the caller's struct was written");
    if (full && old) {
        enum { N = 64 };
        float ti[N], pi[N], to[N], po[N], a[3][N], b[3][N];
        for (int k = 0; k < N; k++) {
            ti[k] = -1.4f + 2.8f * (float)k / N;
            pi[k] = 0.1f * (float)k - 3.0f;
            to[k] = 0.3f;
            po[k] = 0.2f;
        }
        hb_eval_angles(full, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ a[0], a[1], a[2] }, NULL);
        hb_eval_angles(old, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ b[0], b[1], b[2] }, NULL);
        int differ = 0;
        for (int k = 0; k < N; k++)
            differ += memcmp(&a[0][k], &b[0][k], sizeof(float)) != 0;
        CHECK(t, differ == 0, "%d of %d values differ from the plan with defaults", differ, N);
    }
    hb_plan_destroy(full);
    hb_plan_destroy(old);
    int major = -1, minor = -1, patch = -1;
    const char *version = hb_version(&major, &minor, &patch);
    char expected[32];
    snprintf(expected, sizeof expected, "%d.%d.%d", HB_VERSION_MAJOR, HB_VERSION_MINOR, HB_VERSION_PATCH);
    CHECK(t, major == HB_VERSION_MAJOR && minor == HB_VERSION_MINOR && patch == HB_VERSION_PATCH,
          "hb_version gives %d.%d.%d", major, minor, patch);
    CHECK(t, strcmp(version, expected) == 0 && strcmp(version, HB_VERSION_STRING) == 0, "hb_version() = %s", version);
}

const hb_test hb_tests_api[] = {
    { "api_defaults", test_defaults, 0 },
    { "api_validation", test_validation, 0 },
    { "api_unsupported_and_null", test_unsupported_and_null, 0 },
    { "api_isa_selection", test_isa_selection, 0 },
    { "api_older_structs", test_older_structs, 0 },
    { NULL, NULL, 0 },
};

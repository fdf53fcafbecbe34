/* docs/api.md's table of which call works with which model, against the library's own answers: for
 * every row and model the test builds the plan the row names, makes the call, and reads "yes" where
 * it returns HB_OK and "no" where it refuses with HB_ERR_UNSUPPORTED; the page's cell must say the
 * same (its first word). Any other status fails the test. */
#include <stdlib.h>
#include <string.h>

#include "test.h"

static const hb_model models[] = { HB_MODEL_DEON, HB_MODEL_MARSCHNER, HB_MODEL_HUANG, HB_MODEL_CHIANG };
static const char *const model_names[] = { "dFH11", "MJC03", "HHH22", "CBTB16" };
enum { MODELS = sizeof models / sizeof models[0] };

/* One direction pair, valid for every model, and the buffers a call of one sample needs. */
typedef struct one_sample {
    float ti, pi, to, po, h, u[HB_SAMPLE_DIMENSIONS], f[3], pdf, wi[3], sigma[3];
} one_sample;

static one_sample sample_of(void)
{
    one_sample s = { 0.3f, 0.2f, -0.4f, 2.5f, 0.25f, { 0.2f, 0.7f, 0.4f, 0.9f, 0.1f, 0.6f, 0.3f, 0.8f }, { 0 }, 0,
                     { 0 }, { 0.2f, 0.3f, 0.5f } };
    return s;
}

/* The plan a row asks for: the model's defaults (fast quality: only whether the call works matters),
 * changed by the row's configure; NULL (with *st the refusal) when plan creation refuses. */
typedef void (*configure_fn)(hb_model model, hb_material *m, hb_options *o);

static hb_plan *plan_for(hb_model model, configure_fn configure, hb_status *st)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = model;
    o.quality = HB_QUALITY_FAST;
    if (model == HB_MODEL_HUANG)
        o.tt_trt = HB_TT_TRT_TABLE;
    if (configure)
        configure(model, &m, &o);
    hb_plan *plan = NULL;
    *st = hb_plan_create(&m, &o, &plan, NULL);
    return plan;
}

static void table_plan(hb_model model, hb_material *m, hb_options *o)
{
    (void)m;
    if (model == HB_MODEL_DEON)
        o->azimuthal = HB_AZIMUTHAL_TABLE;
}

static void shader_plan(hb_model model, hb_material *m, hb_options *o)
{
    table_plan(model, m, o);
    o->shadowing = HB_SHADOWING_NONE;
}

static void tolerance_plan(hb_model model, hb_material *m, hb_options *o)
{
    (void)model, (void)m;
    o->tolerance = 1e-2;
    o->tt_trt = HB_TT_TRT_AUTO;
}

static void budget_plan(hb_model model, hb_material *m, hb_options *o)
{
    (void)model, (void)m;
    o->budget_ns = 2000.0;
    o->tt_trt = HB_TT_TRT_AUTO;
}

static void longitudinal_plan(hb_model model, hb_material *m, hb_options *o)
{
    (void)model, (void)m;
    o->term = HB_TERM_LONGITUDINAL;
}

static void elliptical_plan(hb_model model, hb_material *m, hb_options *o)
{
    (void)model, (void)o;
    m->eccentricity = 0.5;
}

static void reference_plan(hb_model model, hb_material *m, hb_options *o)
{
    (void)m;
    o->quality = HB_QUALITY_REFERENCE;
    if (model == HB_MODEL_HUANG)
        o->lobes = 1u << HB_LOBE_R, o->tt_trt = HB_TT_TRT_AUTO;
}

/* A call on a plan; its status. */
typedef hb_status (*call_fn)(const hb_plan *plan);

static hb_status call_eval(const hb_plan *p)
{
    one_sample s = sample_of();
    hb_status a = hb_eval_angles(p, 1, (hb_angles_soa){ &s.ti, &s.pi, &s.to, &s.po },
                                 (hb_rgb_soa){ &s.f[0], &s.f[1], &s.f[2] }, NULL);
    float wi[3] = { 0.0f, 1.0f, 0.0f }, wo[3] = { 0.6f, 0.0f, 0.8f };
    hb_status v = hb_eval_vectors(p, 1, (hb_vectors_soa){ &wi[0], &wi[1], &wi[2], &wo[0], &wo[1], &wo[2] },
                                  (hb_rgb_soa){ &s.f[0], &s.f[1], &s.f[2] }, NULL);
    return a != HB_OK ? a : v;
}

static hb_status call_absorption(const hb_plan *p)
{
    one_sample s = sample_of();
    return hb_eval_angles_absorption(p, 1, (hb_angles_soa){ &s.ti, &s.pi, &s.to, &s.po },
                                     (hb_absorption_soa){ &s.sigma[0], &s.sigma[1], &s.sigma[2] },
                                     (hb_rgb_soa){ &s.f[0], &s.f[1], &s.f[2] }, NULL);
}

static hb_status call_near_absorption(const hb_plan *p)
{
    one_sample s = sample_of();
    return hb_eval_near_absorption(p, 1, (hb_near_soa){ &s.ti, &s.pi, &s.to, &s.po, &s.h },
                                   (hb_absorption_soa){ &s.sigma[0], &s.sigma[1], &s.sigma[2] },
                                   (hb_rgb_soa){ &s.f[0], &s.f[1], &s.f[2] }, NULL);
}

/* The near field, sampled and evaluated, and one hit by the per-hit calls at h. */
static hb_status call_near(const hb_plan *p)
{
    one_sample s = sample_of();
    hb_near_soa in = { &s.ti, &s.pi, &s.to, &s.po, &s.h };
    hb_status e = hb_eval_near(p, 1, in, (hb_rgb_soa){ &s.f[0], &s.f[1], &s.f[2] }, NULL);
    hb_sample_near_in sin = { &s.to, &s.po, &s.h, (const float *const[]){ &s.u[0], &s.u[1], &s.u[2], &s.u[3], &s.u[4], &s.u[5], &s.u[6], &s.u[7] } };
    float ti, pi;
    hb_status d = hb_sample_near(p, 1, &sin, &(hb_sample_out){ &ti, &pi, &s.pdf, { &s.f[0], &s.f[1], &s.f[2] } }, NULL);
    hb_status q = hb_pdf_near(p, 1, in, &s.pdf, NULL);
    float wi[3] = { 0.0f, 1.0f, 0.0f }, wo[3] = { 0.6f, 0.0f, 0.8f };
    hb_status v = hb_eval_pdf_near_vectors(p, 1, (hb_near_vectors_soa){ &wi[0], &wi[1], &wi[2], &wo[0], &wo[1], &wo[2], &s.h },
                                           (hb_rgb_soa){ &s.f[0], &s.f[1], &s.f[2] }, &s.pdf, NULL);
    float hwi[3], hpdf, hweight[3];
    hb_status h = hb_hit_sample(p, wo, &s.h, s.u, hwi, &hpdf, hweight);
    return e != HB_OK ? e : d != HB_OK ? d : q != HB_OK ? q : v != HB_OK ? v : h;
}

/* Four wavelengths' absorptions and f, for the spectral calls. */
typedef struct four_wavelengths {
    float f[4];
    const float *sigma[4];
    float *out[4];
} four_wavelengths;

static hb_spectral_absorption four_of(one_sample *s, four_wavelengths *w)
{
    for (int j = 0; j < 4; j++)
        w->sigma[j] = &s->sigma[j % 3], w->out[j] = &w->f[j];
    return (hb_spectral_absorption){ 4, w->sigma };
}

static hb_status call_spectral_far(const hb_plan *p)
{
    one_sample s = sample_of();
    four_wavelengths w;
    hb_spectral_absorption a = four_of(&s, &w);
    return hb_eval_angles_spectral(p, 1, (hb_angles_soa){ &s.ti, &s.pi, &s.to, &s.po }, a, w.out, NULL);
}

static hb_status call_spectral_near(const hb_plan *p)
{
    one_sample s = sample_of();
    four_wavelengths w;
    hb_spectral_absorption a = four_of(&s, &w);
    return hb_eval_near_spectral(p, 1, (hb_near_soa){ &s.ti, &s.pi, &s.to, &s.po, &s.h }, a, w.out, NULL);
}

/* The sampler and pdf at four wavelengths, and pbrt-v4's per-hit call. */
static hb_status call_spectral_sampling(const hb_plan *p)
{
    one_sample s = sample_of();
    four_wavelengths w;
    hb_spectral_absorption a = four_of(&s, &w);
    float ti, pi, wo[3] = { 0.6f, 0.0f, 0.8f }, wi[3];
    hb_status q = hb_pdf_near_spectral(p, 1, (hb_near_soa){ &s.ti, &s.pi, &s.to, &s.po, &s.h }, a, &s.pdf, NULL);
    hb_sample_near_in in = { &s.to, &s.po, &s.h, (const float *const[]){ &s.u[0], &s.u[1], &s.u[2], &s.u[3] } };
    hb_status d = hb_sample_near_spectral(p, 1, &in, a, &(hb_sample_spectral_out){ &ti, &pi, &s.pdf, w.out }, NULL);
    float sigma[4] = { s.sigma[0], s.sigma[1], s.sigma[2], s.sigma[0] };
    hb_status b = hb_pbrt_sample_f(p, wo, s.h, s.u, 4, sigma, wi, w.f, &s.pdf);
    return q != HB_OK ? q : d != HB_OK ? d : b;
}

static hb_status call_sample(const hb_plan *p)
{
    one_sample s = sample_of();
    hb_sample_in in = { &s.to, &s.po, (const float *const[]){ &s.u[0], &s.u[1], &s.u[2], &s.u[3], &s.u[4], &s.u[5], &s.u[6], &s.u[7] } };
    float ti, pi;
    hb_status d = hb_sample_angles(p, 1, &in, &(hb_sample_out){ &ti, &pi, &s.pdf, { &s.f[0], &s.f[1], &s.f[2] } }, NULL);
    hb_status q = hb_pdf_angles(p, 1, (hb_angles_soa){ &s.ti, &s.pi, &s.to, &s.po }, &s.pdf, NULL);
    return d != HB_OK ? d : q;
}

static hb_status call_eval_pdf(const hb_plan *p)
{
    one_sample s = sample_of();
    return hb_eval_pdf_angles(p, 1, (hb_angles_soa){ &s.ti, &s.pi, &s.to, &s.po },
                              (hb_rgb_soa){ &s.f[0], &s.f[1], &s.f[2] }, &s.pdf, NULL);
}

static hb_status call_table(const hb_plan *p)
{
    hb_table_view view = { .struct_size = sizeof view };
    size_t size = 0;
    hb_status t = hb_plan_table(p, &view);
    hb_status s = hb_table_save(p, NULL, 0, &size);
    return t != HB_OK ? t : s;
}

static hb_status call_shader(const hb_plan *p)
{
    float constants[HB_SHADER_CONSTANTS];
    return hb_plan_shader_constants(p, constants);
}

static hb_status call_furnace(const hb_plan *p)
{
    double e[3];
    return hb_furnace(p, 0.3, e);
}

static hb_status call_orders(const hb_plan *p)
{
    double e[HB_ORDER_GROUPS][3];
    return hb_furnace_orders(p, 0.3, 16, 1, e, NULL);
}

static hb_status call_dual(const hb_plan *p)
{
    hb_dual_terms d = { .struct_size = sizeof d };
    return hb_dual_terms_at(p, 0.3, HB_DUAL_DENSITY, &d);
}

static hb_status call_none(const hb_plan *p)
{
    (void)p;
    return HB_OK;
}

static const struct row {
    const char *key; /* how the row's first cell in docs/api.md starts */
    configure_fn configure;
    call_fn call;
} rows[] = {
    { "`hb_eval_angles`", NULL, call_eval },
    { "`hb_eval_angles_absorption`", NULL, call_absorption },
    { "`hb_eval_near`", NULL, call_near },
    { "`hb_eval_near_absorption`", NULL, call_near_absorption },
    { "`hb_eval_angles_spectral`", NULL, call_spectral_far },
    { "`hb_eval_near_spectral`", NULL, call_spectral_near },
    { "`hb_sample_near_spectral`", NULL, call_spectral_sampling },
    { "`HB_QUALITY_REFERENCE`: spectral f", reference_plan, call_spectral_far },
    { "`HB_QUALITY_REFERENCE`: spectral sampling", reference_plan, call_spectral_sampling },
    { "`hb_sample_angles`", NULL, call_sample },
    { "`hb_eval_pdf_angles`", NULL, call_eval_pdf },
    { "`hb_plan_table`", table_plan, call_table },
    { "`hb_plan_shader_constants`", shader_plan, call_shader },
    { "`hb_furnace`", NULL, call_furnace },
    { "`hb_furnace_orders`", NULL, call_orders },
    { "`hb_dual_terms_at`", NULL, call_dual },
    { "`options.tolerance", tolerance_plan, call_none },
    { "`options.budget_ns", budget_plan, call_none },
    { "`HB_TERM_LONGITUDINAL`", longitudinal_plan, call_none },
    { "`eccentricity", elliptical_plan, call_none },
    { "`HB_QUALITY_REFERENCE`: f", reference_plan, call_eval },
    { "`HB_QUALITY_REFERENCE`: sampling", reference_plan, call_sample },
};

/* The library's answer: 1 yes, 0 no; -1 (the test fails) for any other status. */
static int answer(hb_test_ctx *t, const struct row *r, int k)
{
    hb_model model = models[k];
    hb_status st;
    hb_plan *plan = plan_for(model, r->configure, &st);
    if (plan)
        st = r->call(plan);
    hb_plan_destroy(plan);
    /* HB_ERR_LIMIT: the model has the call but not at the row's setting (a tolerance none of its
     * configurations reaches), which is "no" for that row */
    int no = st == HB_ERR_UNSUPPORTED || st == HB_ERR_LIMIT;
    CHECK(t, st == HB_OK || no, "%s, %s: status %s", r->key, model_names[k], hb_status_string(st));
    return st == HB_OK ? 1 : no ? 0 : -1;
}

/* The page's row whose first cell starts with key: its cells after the first, each's first word
 * ("yes", "no") in word[k]; the number of cells. */
static int page_row(const char *page, const char *key, char word[MODELS][8])
{
    char start[96];
    snprintf(start, sizeof start, "\n| %s", key);
    const char *p = strstr(page, start);
    if (!p)
        return 0;
    const char *end = strchr(p + 1, '\n');
    int cells = 0;
    for (const char *c = strchr(p + 2, '|'); c && c < end && cells < MODELS; c = strchr(c + 1, '|')) {
        const char *w = c + 1;
        while (*w == ' ')
            w++;
        if (w >= end)
            break;
        snprintf(word[cells], sizeof word[cells], "%.*s", (int)strcspn(w, " |,;("), w);
        cells++;
    }
    return cells;
}

static void test_support_matrix(hb_test_ctx *t)
{
    char *page = hb_test_read_file("docs/api.md", NULL);
    CHECK(t, page != NULL, "cannot read docs/api.md");
    if (!page)
        return;
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; r++) {
        char word[MODELS][8];
        int cells = page_row(page, rows[r].key, word);
        CHECK(t, cells == MODELS, "docs/api.md: the row of %s has %d model cells", rows[r].key, cells);
        char line[128] = "";
        for (int k = 0; k < MODELS; k++) {
            int yes = answer(t, &rows[r], k);
            const char *says = yes ? "yes" : "no";
            size_t used = strlen(line);
            snprintf(line + used, sizeof line - used, " %s", says);
            CHECK(t, k >= cells || yes < 0 || !strcmp(word[k], says), "docs/api.md: %s for %s says '%s', the library '%s'",
                  rows[r].key, model_names[k], k < cells ? word[k] : "", says);
        }
        hb_test_note(t, "%-34s%s", rows[r].key, line);
    }
    free(page);
}

const hb_test hb_tests_api_matrix[] = {
    { "api_support_matrix", test_support_matrix, 0 },
    { NULL, NULL, 0 },
};

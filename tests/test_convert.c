/* hb_material_convert keeps the look across models: the R lobe's width at half maximum and its peak,
 * measured on each model's own f, and a conversion there and back returns the parameters. Also the
 * failures every entry point words (hb_last_error). */
#include <math.h>
#include <string.h>

#include "test.h"

enum { N = 3001 };

/* The R lobe at theta_i = 0.3, phi = 0 over theta_o: its peak and its half-maximum width as a
 * Gaussian's deviation (the full width over 2 sqrt(2 ln 2)). */
static int r_lobe(hb_test_ctx *t, hb_model model, const hb_material *m, double *peak, double *deviation)
{
    hb_options o;
    hb_options_default(&o);
    o.model = model, o.lobes = HB_LOBE_BIT(HB_LOBE_R), o.isa = t->isa;
    hb_plan *plan;
    hb_error e;
    if (hb_plan_create(m, &o, &plan, &e) != HB_OK) {
        CHECK(t, 0, "model %d: %s", (int)model, e.message);
        return 0;
    }
    static float ti[N], pi[N], to[N], po[N], f[3][N];
    for (int k = 0; k < N; k++)
        ti[k] = 0.3f, pi[k] = 0.0f, to[k] = (float)(-1.5 + 3.0 * k / (N - 1)), po[k] = 0.0f;
    hb_eval_angles(plan, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    hb_plan_destroy(plan);
    int top = 0;
    for (int k = 0; k < N; k++)
        top = f[0][k] > f[0][top] ? k : top;
    double half = 0.5 * f[0][top];
    int l = top, r = top;
    while (l > 0 && f[0][l] > half)
        l--;
    while (r < N - 1 && f[0][r] > half)
        r++;
    double left = to[l] + (half - f[0][l]) / (f[0][l + 1] - f[0][l]) * (to[l + 1] - to[l]);
    double right = to[r - 1] + (half - f[0][r - 1]) / (f[0][r] - f[0][r - 1]) * (to[r] - to[r - 1]);
    *peak = to[top];
    *deviation = (right - left) / (2.0 * sqrt(2.0 * M_LN2));
    return 1;
}

static void test_convert_look(hb_test_ctx *t)
{
    static const hb_model models[] = { HB_MODEL_DEON, HB_MODEL_MARSCHNER, HB_MODEL_CHIANG, HB_MODEL_HUANG };
    static const char *const names[] = { "deon", "marschner", "chiang", "huang" };
    static const double betas[] = { 0.03, 0.1 };
    double worst[4] = { 0 }, worst_peak[4] = { 0 };
    for (int b = 0; b < 2; b++) {
        hb_material m;
        hb_material_default(&m);
        m.beta_m = betas[b], m.beta_n = 0.3, m.alpha = 0.035;
        for (int k = 0; k < 4; k++) {
            hb_material c;
            hb_error e;
            CHECK(t, hb_material_convert(&m, HB_MODEL_DEON, models[k], &c, &e) == HB_OK, "to %s: %s", names[k], e.message);
            double peak, deviation;
            if (!r_lobe(t, models[k], &c, &peak, &deviation))
                continue;
            /* the look's deviation (the beta_m asked) and peak (theta_o = -theta_i - 2 alpha) */
            worst[k] = fmax(worst[k], fabs(deviation / betas[b] - 1.0));
            worst_peak[k] = fmax(worst_peak[k], fabs(peak - (-0.3 - 2.0 * m.alpha)));
            hb_material back;
            CHECK(t, hb_material_convert(&c, models[k], HB_MODEL_DEON, &back, &e) == HB_OK &&
                         fabs(back.beta_m - m.beta_m) < 1e-12 && fabs(back.beta_n - m.beta_n) < 1e-12 &&
                         fabs(back.alpha - m.alpha) < 1e-15,
                  "%s and back: beta_m %.17g beta_n %.17g alpha %.17g", names[k], back.beta_m, back.beta_n, back.alpha);
        }
    }
    /* HHH22's GGX lobe widens faster than its small-roughness limit as the roughness grows */
    static const double bound[] = { 1e-2, 1e-2, 1e-2, 2.5e-2 };
    for (int k = 0; k < 4; k++) {
        hb_test_note(t, "%s: the R lobe's half-maximum deviation within %.2g of the asked one, the peak within %.2g rad",
                     names[k], worst[k], worst_peak[k]);
        CHECK(t, worst[k] < bound[k], "%s: width off by %.3g", names[k], worst[k]);
        CHECK(t, worst_peak[k] < 5e-3, "%s: peak off by %.3g rad", names[k], worst_peak[k]);
    }
}

static void test_convert_refusals(hb_test_ctx *t)
{
    hb_material m, c;
    hb_material_default(&m);
    m.beta_m = 6.0; /* beyond CBTB16's beta_m = 1, whose R deviation is 5.23 */
    CHECK(t, hb_material_convert(&m, HB_MODEL_DEON, HB_MODEL_CHIANG, &c, NULL) == HB_ERR_PARAM &&
                 strstr(hb_last_error()->message, "CBTB16"),
          "a look beyond CBTB16's range: %s", hb_last_error()->message);
    hb_material_default(&m);
    m.lobe_beta_m[HB_LOBE_TT] = 0.05;
    CHECK(t, hb_material_convert(&m, HB_MODEL_DEON, HB_MODEL_MARSCHNER, &c, NULL) == HB_ERR_UNSUPPORTED &&
                 hb_material_convert(&m, HB_MODEL_DEON, HB_MODEL_DEON, &c, NULL) == HB_OK,
          "per-lobe overrides convert only to their own model");
    CHECK(t, hb_material_convert(&m, (hb_model)9, HB_MODEL_DEON, &c, NULL) == HB_ERR_PARAM &&
                 hb_material_convert(NULL, HB_MODEL_DEON, HB_MODEL_DEON, &c, NULL) == HB_ERR_NULL,
          "bad arguments accepted");
}

/* A failed call's status and the calling thread's last error, read right after it. */
static void expect(hb_test_ctx *t, hb_status got, hb_status want, const char *words)
{
    const hb_error *e = hb_last_error();
    CHECK(t, got == want && e->status == want && strstr(e->message, words), "want %s with \"%s\"; got %s, \"%s\"",
          hb_status_string(want), words, hb_status_string(got), e->message);
}

/* Every fallible call words its failure: the status, and a message naming the call and the argument. */
static void test_last_error(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = HB_MODEL_HUANG;
    hb_plan *plan;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "huang plan");
    float x[1] = { 0.3f }, y[1] = { 0.0f }, out[3][1], pdf[1];
    hb_rgb_soa rgb = { out[0], out[1], out[2] };
    expect(t, hb_eval_angles(plan, 1, (hb_angles_soa){ x, y, NULL, y }, rgb, NULL), HB_ERR_NULL,
           "hb_eval_angles: in.theta_o is NULL");
    expect(t, hb_eval_near(plan, 1, (hb_near_soa){ x, y, x, y, y }, rgb, NULL), HB_ERR_UNSUPPORTED,
           "hb_eval_near: this huang plan");
    expect(t, hb_pdf_angles(NULL, 1, (hb_angles_soa){ x, y, x, y }, pdf, NULL), HB_ERR_NULL, "hb_pdf_angles: plan is NULL");
    expect(t, hb_eval_pdf_vectors(plan, 1, (hb_vectors_soa){ x, y, x, x, y, NULL }, rgb, pdf, NULL), HB_ERR_NULL,
           "hb_eval_pdf_vectors: in.wo_z is NULL");
    hb_table_view v = { .struct_size = 8 };
    expect(t, hb_plan_table(plan, &v), HB_ERR_VERSION, "view->struct_size is 8");
    expect(t, hb_furnace(plan, 2.0, (double[3]){ 0 }), HB_ERR_PARAM, "theta_o = 2 is outside");
    expect(t, hb_frame_from_tangent((float[3]){ 0, 0, 0 }, NULL, &(hb_frame){ .x = { 0 } }), HB_ERR_PARAM, "has no direction");
    hb_sample_in in = { x, y, NULL };
    hb_sample_out so = { out[0], out[1], pdf, rgb };
    expect(t, hb_sample_angles(plan, 1, &in, &so, NULL), HB_ERR_NULL, "hb_sample_angles: in->u is NULL");
    expect(t, hb_plan_shader_constants(plan, (float[HB_SHADER_CONSTANTS]){ 0 }), HB_ERR_UNSUPPORTED,
           "offers no shader constants");
    hb_dual_terms d = { .struct_size = sizeof d };
    expect(t, hb_dual_terms_at(plan, 0.2, 1.5, &d), HB_ERR_PARAM, "d_b = 1.5 is outside [0, 1]");
    hb_plan_destroy(plan);
    o.model = HB_MODEL_DEON, o.tolerance = 1e-6;
    expect(t, hb_plan_create(&m, &o, &plan, NULL), HB_ERR_LIMIT, "below every calibrated");
}

const hb_test hb_tests_convert[] = {
    { "convert_look", test_convert_look, 0 },
    { "convert_refusals", test_convert_refusals, 0 },
    { "last_error", test_last_error, 0 },
    { NULL, NULL, 0 },
};

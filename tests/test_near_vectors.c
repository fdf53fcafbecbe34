/* The near field from fibre-frame vectors (hb_eval_near_vectors, hb_pdf_near_vectors,
 * hb_eval_pdf_near_vectors, hb_sample_near_vectors) and the fused hb_eval_pdf_near: each equals,
 * bit for bit, the angle call on the vectors' angles (in double, rounded to float), for dFH11 and
 * CBTB16 on every ISA and for dFH11's reference; a non-unit vector and |h| > 1 are counted invalid
 * and give zeros, (0, 0, 0) for a sampled w_i; a far-field-only model refuses. */
#include <math.h>
#include <string.h>

#include "test.h"
#include "ref/reference.h"

enum { N = 300 }; /* more than one of the calls' stack chunks */

static hb_plan *near_plan(hb_test_ctx *t, hb_model model, hb_quality quality)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = 0.4, m.beta_m = 0.2;
    o.model = model, o.quality = quality;
    o.isa = quality == HB_QUALITY_REFERENCE ? HB_ISA_AUTO : t->isa;
    hb_plan *plan = NULL;
    hb_error e;
    CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "plan: %s", e.message);
    return plan;
}

static int same(const float *a, const float *b, size_t n)
{
    return memcmp(a, b, n * sizeof *a) == 0;
}

static void check_plan(hb_test_ctx *t, const hb_plan *plan, const char *name)
{
    static float w[6][N], h[N], ti[N], pi[N], to[N], po[N], u[HB_SAMPLE_DIMENSIONS][N];
    static float f[3][N], g[3][N], pdf[N], pdf2[N], fused[3][N], fused_pdf[N], wi[3][N], sti[N], spi[N], weight[3][N],
        weight2[3][N], spdf[N], spdf2[N];
    float *wp[6] = { w[0], w[1], w[2], w[3], w[4], w[5] };
    float *us[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        us[d] = u[d];
    hb_uniforms(hb_test_uniform(t) * 1e9, 0, N, HB_SAMPLE_DIMENSIONS, us);
    for (int k = 0; k < N; k++) {
        hb_test_vectors_of((float)hb_test_range(t, -1.5, 1.5), (float)hb_test_range(t, -M_PI, M_PI),
                           (float)hb_test_range(t, -1.5, 1.5), (float)hb_test_range(t, -M_PI, M_PI), wp, (size_t)k);
        h[k] = (float)hb_test_range(t, -1.0, 1.0);
    }
    w[0][7] *= 1.5f, w[1][7] *= 1.5f, w[2][7] *= 1.5f; /* a non-unit w_i */
    w[3][8] = NAN;   /* a NaN w_o */
    h[9] = 1.5f;     /* an offset off the fibre */
    for (int k = 0; k < N; k++) {
        double a, b;
        int ok = hb_ref_direction(w[0][k], w[1][k], w[2][k], &a, &b);
        ti[k] = ok ? (float)a : NAN, pi[k] = ok ? (float)b : NAN;
        ok = hb_ref_direction(w[3][k], w[4][k], w[5][k], &a, &b);
        to[k] = ok ? (float)a : NAN, po[k] = ok ? (float)b : NAN;
    }
    hb_near_soa angles = { ti, pi, to, po, h };
    hb_near_vectors_soa vectors = { w[0], w[1], w[2], w[3], w[4], w[5], h };
    hb_eval_report ra, rv;
    CHECK(t, hb_eval_near(plan, N, angles, (hb_rgb_soa){ f[0], f[1], f[2] }, &ra) == HB_OK &&
                 hb_eval_near_vectors(plan, N, vectors, (hb_rgb_soa){ g[0], g[1], g[2] }, &rv) == HB_OK,
          "%s: eval_near", name);
    CHECK(t, same(f[0], g[0], N) && same(f[1], g[1], N) && same(f[2], g[2], N), "%s: f from vectors differs", name);
    CHECK(t, ra.invalid == 3 && rv.invalid == 3 && g[0][7] == 0.0f && g[0][8] == 0.0f && g[0][9] == 0.0f,
          "%s: invalid %zu and %zu, f %g %g %g", name, ra.invalid, rv.invalid, g[0][7], g[0][8], g[0][9]);
    CHECK(t, hb_pdf_near(plan, N, angles, pdf, NULL) == HB_OK && hb_pdf_near_vectors(plan, N, vectors, pdf2, NULL) == HB_OK &&
                 same(pdf, pdf2, N),
          "%s: pdf from vectors differs", name);
    CHECK(t, hb_eval_pdf_near_vectors(plan, N, vectors, (hb_rgb_soa){ fused[0], fused[1], fused[2] }, fused_pdf, NULL) == HB_OK &&
                 same(fused[0], f[0], N) && same(fused[2], f[2], N) && same(fused_pdf, pdf, N),
          "%s: fused f and pdf from vectors differ", name);
    CHECK(t, hb_eval_pdf_near(plan, N, angles, (hb_rgb_soa){ fused[0], fused[1], fused[2] }, fused_pdf, NULL) == HB_OK &&
                 same(fused[1], f[1], N) && same(fused_pdf, pdf, N),
          "%s: fused f and pdf differ", name);
    const float *const *planes = (const float *const *)us;
    hb_sample_near_in sa = { to, po, h, planes };
    hb_sample_near_vectors_in sv = { w[3], w[4], w[5], h, planes };
    CHECK(t, hb_sample_near(plan, N, &sa, &(hb_sample_out){ sti, spi, spdf, { weight[0], weight[1], weight[2] } }, &ra) == HB_OK &&
                 hb_sample_near_vectors(plan, N, &sv,
                                        &(hb_sample_vectors_out){ wi[0], wi[1], wi[2], spdf2, { weight2[0], weight2[1], weight2[2] } },
                                        &rv) == HB_OK,
          "%s: sample_near", name);
    CHECK(t, same(spdf, spdf2, N) && same(weight[0], weight2[0], N) && ra.invalid == rv.invalid && rv.invalid == 2,
          "%s: sampled pdf or weight from vectors differ (invalid %zu, %zu)", name, ra.invalid, rv.invalid);
    int wrong = 0;
    for (int k = 0; k < N; k++) {
        int invalid = k == 8 || k == 9;
        double ct = cos(sti[k]);
        float want[3] = { invalid ? 0.0f : (float)(sin(spi[k]) * ct), invalid ? 0.0f : (float)sin(sti[k]),
                          invalid ? 0.0f : (float)(cos(spi[k]) * ct) };
        wrong += wi[0][k] != want[0] || wi[1][k] != want[1] || wi[2][k] != want[2];
    }
    CHECK(t, wrong == 0, "%s: %d sampled w_i differ from the angle sampler's", name, wrong);
}

static void test_near_vectors(hb_test_ctx *t)
{
    static const hb_model models[] = { HB_MODEL_DEON, HB_MODEL_CHIANG };
    for (int m = 0; m < 2; m++) {
        hb_plan *plan = near_plan(t, models[m], HB_QUALITY_BALANCED);
        if (plan)
            check_plan(t, plan, m ? "CBTB16" : "dFH11");
        hb_plan_destroy(plan);
    }
    if (t->isa == HB_ISA_SCALAR) {
        hb_plan *plan = near_plan(t, HB_MODEL_DEON, HB_QUALITY_REFERENCE);
        if (plan)
            check_plan(t, plan, "dFH11 reference");
        hb_plan_destroy(plan);
    }
    hb_plan *far = near_plan(t, HB_MODEL_MARSCHNER, HB_QUALITY_BALANCED);
    float x = 0.0f, y = 1.0f, z = 0.0f, hh = 0.0f, f[3], p;
    hb_near_vectors_soa one = { &x, &y, &z, &x, &y, &z, &hh };
    CHECK(t, far && hb_eval_near_vectors(far, 1, one, (hb_rgb_soa){ &f[0], &f[1], &f[2] }, NULL) == HB_ERR_UNSUPPORTED &&
                 hb_pdf_near_vectors(far, 1, one, &p, NULL) == HB_ERR_UNSUPPORTED,
          "MJC03 accepts a near-field call");
    hb_plan_destroy(far);
}

/* hb_hit_sample and hb_hit_eval_pdf give, bit for bit, the vector calls' one-sample results: far
 * field for every model, near field at h for dFH11 and CBTB16. */
static void test_hit_calls(hb_test_ctx *t)
{
    static const hb_model models[] = { HB_MODEL_DEON, HB_MODEL_CHIANG, HB_MODEL_MARSCHNER, HB_MODEL_HUANG };
    for (int k = 0; k < 4; k++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        o.model = models[k], o.isa = t->isa;
        o.lobes = models[k] == HB_MODEL_HUANG ? HB_LOBE_BIT(HB_LOBE_R) : HB_LOBES_DEFAULT; /* no TT/TRT table build */
        hb_plan *plan = NULL;
        CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "model %d", (int)models[k]);
        if (!plan)
            continue;
        int near_field = k < 2, wrong = 0;
        for (int s = 0; s < 64; s++) {
            float u[HB_SAMPLE_DIMENSIONS], *planes[HB_SAMPLE_DIMENSIONS];
            for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
                planes[d] = &u[d];
            hb_uniforms(77, (unsigned long long)s, 1, HB_SAMPLE_DIMENSIONS, planes);
            double a = 6.283185307179586 * u[0], c = 2.0 * u[1] - 1.0, r = sqrt(1.0 - c * c);
            float wo[3] = { (float)(r * cos(a)), (float)c, (float)(r * sin(a)) }, wl[3] = { wo[2], wo[0], wo[1] };
            float h = 2.0f * u[2] - 1.0f;
            for (int near = 0; near <= near_field; near++) {
                const float *hp = near ? &h : NULL;
                float wi[3], pdf, weight[3], bwi[3], bpdf, bweight[3], f[3], fpdf, bf[3], bfpdf;
                hb_status st = hb_hit_sample(plan, wo, hp, u, wi, &pdf, weight);
                hb_sample_vectors_out out = { &bwi[0], &bwi[1], &bwi[2], &bpdf, { &bweight[0], &bweight[1], &bweight[2] } };
                const float *const *up = (const float *const *)planes;
                hb_status bst = near ? hb_sample_near_vectors(plan, 1,
                                                              &(hb_sample_near_vectors_in){ &wo[0], &wo[1], &wo[2], &h, up },
                                                              &out, NULL)
                                     : hb_sample_vectors(plan, 1, &(hb_sample_vectors_in){ &wo[0], &wo[1], &wo[2], up },
                                                         &out, NULL);
                hb_status est = hb_hit_eval_pdf(plan, wl, wo, hp, f, &fpdf);
                hb_rgb_soa rgb = { &bf[0], &bf[1], &bf[2] };
                hb_status best = near ? hb_eval_pdf_near_vectors(plan, 1,
                                                                 (hb_near_vectors_soa){ &wl[0], &wl[1], &wl[2], &wo[0],
                                                                                        &wo[1], &wo[2], &h },
                                                                 rgb, &bfpdf, NULL)
                                      : hb_eval_pdf_vectors(plan, 1,
                                                            (hb_vectors_soa){ &wl[0], &wl[1], &wl[2], &wo[0], &wo[1], &wo[2] },
                                                            rgb, &bfpdf, NULL);
                wrong += st != HB_OK || bst != HB_OK || est != HB_OK || best != HB_OK || !same(wi, bwi, 3) ||
                         !same(&pdf, &bpdf, 1) || !same(weight, bweight, 3) || !same(f, bf, 3) || !same(&fpdf, &bfpdf, 1);
            }
        }
        CHECK(t, wrong == 0, "model %d: %d hits differ from the vector calls", (int)models[k], wrong);
        hb_plan_destroy(plan);
    }
}

const hb_test hb_tests_near_vectors[] = {
    { "near_vectors", test_near_vectors, 1 },
    { "hit_calls", test_hit_calls, 1 },
    { NULL, NULL, 0 },
};

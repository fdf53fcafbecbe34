/* The calls a path tracer makes per hit (docs/sampling.md): sampling and pdf with fibre-frame unit
 * vectors, f and the pdf in one call, and the frame from a world-space tangent. Each is checked
 * against the angle calls it stands for. */
#include <stdlib.h>
#include <string.h>

#include "test.h"

enum { N = 512 };

typedef struct plan_case {
    const char *label;
    hb_model model;
    hb_quality quality;
    unsigned lobes;
    hb_azimuthal azimuthal;
} plan_case;

/* Every sampler and every way a fused call is formed: dFH11 quadrature (one pass) and table (two),
 * HHH22 R (exact sampler) and R+TT+TRT (traced paths keyed by the sample index), CBTB16, and the
 * double-precision reference. */
static const plan_case cases[] = {
    { "deon balanced", HB_MODEL_DEON, HB_QUALITY_BALANCED, HB_LOBES_DEFAULT, HB_AZIMUTHAL_QUADRATURE },
    { "deon table", HB_MODEL_DEON, HB_QUALITY_FAST, HB_LOBES_DEFAULT, HB_AZIMUTHAL_TABLE },
    { "huang R", HB_MODEL_HUANG, HB_QUALITY_BALANCED, 1u << HB_LOBE_R, HB_AZIMUTHAL_QUADRATURE },
    { "huang R+TT+TRT", HB_MODEL_HUANG, HB_QUALITY_FAST, HB_LOBES_DEFAULT, HB_AZIMUTHAL_QUADRATURE },
    { "chiang", HB_MODEL_CHIANG, HB_QUALITY_BALANCED, HB_LOBES_DEFAULT, HB_AZIMUTHAL_QUADRATURE },
    { "deon reference", HB_MODEL_DEON, HB_QUALITY_REFERENCE, HB_LOBES_DEFAULT, HB_AZIMUTHAL_QUADRATURE },
};

static hb_plan *case_plan(hb_test_ctx *t, const plan_case *c)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.sigma_a[0] = 0.2, m.sigma_a[1] = 0.5, m.sigma_a[2] = 1.0;
    m.beta_m = 0.2, m.beta_n = 0.3;
    if (c->model == HB_MODEL_CHIANG)
        m.beta_m = 0.3, m.beta_n = 0.3;
    o.model = c->model;
    o.quality = c->quality;
    o.lobes = c->lobes;
    o.azimuthal = c->azimuthal;
    o.tt_trt = HB_TT_TRT_MC; /* HHH22's estimated pdf */
    o.isa = c->quality == HB_QUALITY_REFERENCE ? HB_ISA_AUTO : t->isa;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s plan: %s", c->label, err.message);
    return plan;
}

static struct {
    float angles[4][N];          /* theta_i, phi_i, theta_o, phi_o */
    float w[6][N];               /* their unit vectors */
    float u[HB_SAMPLE_DIMENSIONS][N];
    float ti[N], pi[N], pdf[N], weight[3][N];
    float wi[3][N], pdf_v[N], weight_v[3][N];
    float f[3][N], f2[3][N], pdf2[N];
} buf;

/* N direction pairs away from the poles, as angles and as the unit vectors the angles give. */
static void fill_pairs(hb_test_ctx *t)
{
    for (int k = 0; k < N; k++) {
        buf.angles[0][k] = (float)hb_test_range(t, -1.45, 1.45);
        buf.angles[1][k] = (float)hb_test_range(t, -3.1, 3.1);
        buf.angles[2][k] = (float)hb_test_range(t, -1.45, 1.45);
        buf.angles[3][k] = (float)hb_test_range(t, -3.1, 3.1);
    }
    float *w[6] = { buf.w[0], buf.w[1], buf.w[2], buf.w[3], buf.w[4], buf.w[5] };
    for (int k = 0; k < N; k++) {
        hb_test_vectors_of(buf.angles[0][k], buf.angles[1][k], buf.angles[2][k], buf.angles[3][k], w, k);
        /* the angles of the rounded vectors, so that both calls see the same directions */
        for (int d = 0; d < 2; d++) {
            double x = w[3 * d][k], y = w[3 * d + 1][k], z = w[3 * d + 2][k];
            buf.angles[2 * d][k] = (float)atan2(y, hypot(x, z));
            buf.angles[2 * d + 1][k] = (float)atan2(x, z);
        }
    }
}

/* HHH22's TT/TRT pdf is eq. 33 estimated by traced paths: a function of the directions with jumps
 * where a path changes branch, so a rounding's change of a direction can move it by a few per cent. */
static int estimated_pdf(const plan_case *c) { return c->model == HB_MODEL_HUANG && c->lobes != 1u << HB_LOBE_R; }

static double relative(double a, double b) { return fabs(a - b) / fmax(fmax(fabs(a), fabs(b)), 1e-30); }

/* hb_sample_vectors gives hb_sample_angles' samples as vectors (same numbers, same sample index):
 * directions within 2e-5, pdf and weights within 1e-4 relative (measured 1e-6: the float atan2 of
 * w_o against the double one of the test); HHH22's estimated TT/TRT pdf moves by up to 5% at 2% of
 * the samples (measured), so there 95% of the pdfs must agree. */
static void sample_vectors_case(hb_test_ctx *t, const plan_case *c)
{
    hb_plan *plan = case_plan(t, c);
    if (!plan)
        return;
    int dims = hb_plan_sample_dimensions(plan);
    float *u[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        u[d] = buf.u[d];
    hb_uniforms(hb_test_uniform(t) * 1e9, 0, N, dims, u);
    hb_sample_in in = { buf.angles[2], buf.angles[3], (const float *const *)u };
    hb_sample_vectors_in vin = { buf.w[3], buf.w[4], buf.w[5], (const float *const *)u };
    hb_sample_out out = { buf.ti, buf.pi, buf.pdf, { buf.weight[0], buf.weight[1], buf.weight[2] } };
    hb_sample_vectors_out vout = { buf.wi[0], buf.wi[1], buf.wi[2], buf.pdf_v, { buf.weight_v[0], buf.weight_v[1], buf.weight_v[2] } };
    hb_eval_report ra = { 99 }, rv = { 99 };
    CHECK(t, hb_sample_angles(plan, N, &in, &out, &ra) == HB_OK, "%s: sample angles", c->label);
    CHECK(t, hb_sample_vectors(plan, N, &vin, &vout, &rv) == HB_OK, "%s: sample vectors", c->label);
    CHECK(t, ra.invalid == 0 && rv.invalid == 0, "%s: invalid %zu %zu", c->label, ra.invalid, rv.invalid);
    double worst_dir = 0.0, worst_pdf = 0.0, worst_weight = 0.0;
    size_t differ = 0, pdf_differ = 0;
    for (int k = 0; k < N; k++) {
        double ct = cos(buf.ti[k]);
        double want[3] = { sin(buf.pi[k]) * ct, sin(buf.ti[k]), cos(buf.pi[k]) * ct }, dir = 0.0, norm = 0.0;
        for (int a = 0; a < 3; a++) {
            dir = fmax(dir, fabs(buf.wi[a][k] - want[a]));
            norm += (double)buf.wi[a][k] * buf.wi[a][k];
        }
        double dp = relative(buf.pdf[k], buf.pdf_v[k]), dw = 0.0;
        for (int ch = 0; ch < 3; ch++)
            dw = fmax(dw, relative(buf.weight[ch][k], buf.weight_v[ch][k]));
        CHECK(t, fabs(norm - 1.0) < 1e-5, "%s: sample %d has |w_i|^2 = %.8f", c->label, k, norm);
        differ += dir > 2e-5 || dw > 1e-4;
        pdf_differ += dp > 1e-4;
        worst_dir = fmax(worst_dir, dir), worst_pdf = fmax(worst_pdf, dp), worst_weight = fmax(worst_weight, dw);
    }
    CHECK(t, differ == 0, "%s: %zu of %d samples differ between the angle and vector calls", c->label, differ, N);
    CHECK(t, pdf_differ <= (estimated_pdf(c) ? N / 20 : 0), "%s: %zu of %d pdfs differ", c->label, pdf_differ, N);
    hb_test_note(t, "%s: vectors vs angles: direction %.2g, pdf %.2g, weight %.2g", c->label, worst_dir, worst_pdf,
                 worst_weight);
    hb_plan_destroy(plan);
}

/* The double reference is the same on every ISA: it runs with the scalar kernels' pass alone. */
static int case_runs_here(const hb_test_ctx *t, const plan_case *c)
{
    return c->quality != HB_QUALITY_REFERENCE || t->isa == HB_ISA_SCALAR;
}

static void test_sample_vectors(hb_test_ctx *t)
{
    fill_pairs(t);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
        if (case_runs_here(t, &cases[c]))
            sample_vectors_case(t, &cases[c]);
}

/* hb_eval_pdf_* return what the separate calls return: f as hb_eval_angles / hb_eval_vectors and
 * the pdf as hb_pdf_angles / hb_pdf_vectors, within 1e-6 relative (a fused pass computes the same
 * arithmetic); hb_pdf_vectors within 1e-4 of hb_pdf_angles of the same directions (95% of them for
 * HHH22's estimated pdf). */
static void eval_pdf_case(hb_test_ctx *t, const plan_case *c)
{
    hb_plan *plan = case_plan(t, c);
    if (!plan)
        return;
    hb_angles_soa in = { buf.angles[0], buf.angles[1], buf.angles[2], buf.angles[3] };
    hb_vectors_soa vin = { buf.w[0], buf.w[1], buf.w[2], buf.w[3], buf.w[4], buf.w[5] };
    hb_rgb_soa f = { buf.f[0], buf.f[1], buf.f[2] }, f2 = { buf.f2[0], buf.f2[1], buf.f2[2] };
    hb_eval_report r1 = { 99 }, r2 = { 99 };
    for (int form = 0; form < 2; form++) {
        const char *name = form ? "vectors" : "angles";
        hb_status s1 = form ? hb_eval_pdf_vectors(plan, N, vin, f, buf.pdf, &r1) : hb_eval_pdf_angles(plan, N, in, f, buf.pdf, &r1);
        hb_status s2 = form ? hb_eval_vectors(plan, N, vin, f2, NULL) : hb_eval_angles(plan, N, in, f2, NULL);
        hb_status s3 = form ? hb_pdf_vectors(plan, N, vin, buf.pdf2, &r2) : hb_pdf_angles(plan, N, in, buf.pdf2, &r2);
        CHECK(t, s1 == HB_OK && s2 == HB_OK && s3 == HB_OK, "%s %s: %d %d %d", c->label, name, s1, s2, s3);
        CHECK(t, r1.invalid == 0 && r2.invalid == 0, "%s %s: invalid %zu %zu", c->label, name, r1.invalid, r2.invalid);
        double worst_f = 0.0, worst_pdf = 0.0;
        for (int k = 0; k < N; k++) {
            worst_pdf = fmax(worst_pdf, relative(buf.pdf[k], buf.pdf2[k]));
            for (int ch = 0; ch < 3; ch++)
                worst_f = fmax(worst_f, relative(buf.f[ch][k], buf.f2[ch][k]) * (fabs(buf.f2[ch][k]) > 1e-30));
        }
        /* f from vectors: hb_eval_vectors forms the geometry from dot products, the fused call from
         * the vectors' angles, as the sampler does; they agree as vectors and angles do (2e-4 of the peak) */
        float *got[3] = { buf.f[0], buf.f[1], buf.f[2] }, *want[3] = { buf.f2[0], buf.f2[1], buf.f2[2] };
        double f_error = form ? hb_test_spec_error(got, want, N, NULL) : worst_f;
        CHECK(t, f_error <= (form ? 2e-4 : 1e-6), "%s %s: fused f differs by %.3g", c->label, name, f_error);
        CHECK(t, worst_pdf <= 1e-6, "%s %s: fused pdf differs by %.3g", c->label, name, worst_pdf);
        hb_test_note(t, "%s %s: fused vs separate: f %.2g, pdf %.2g", c->label, name, f_error, worst_pdf);
    }
    /* along the fibre (x = z = 0, zeros of either sign) a direction's azimuth is 0 in every vector call:
     * f alone and f with its pdf agree there as everywhere */
    enum { POLE = 16 };
    static float pw[6][POLE], pf[3][POLE], pg[3][POLE], ppdf[POLE];
    for (int k = 0; k < POLE; k++) {
        float a = 0.4f * (float)k - 3.0f, b = 0.17f * (float)k - 1.3f; /* the other direction: azimuth a, inclination b */
        float other[3] = { sinf(a) * cosf(b), sinf(b), cosf(a) * cosf(b) };
        float pole[3] = { k & 4 ? -0.0f : 0.0f, k & 1 ? -1.0f : 1.0f, k & 8 ? -0.0f : 0.0f };
        for (int d = 0; d < 3; d++) {
            pw[d][k] = k & 2 ? other[d] : pole[d];     /* w_i */
            pw[3 + d][k] = k & 2 ? pole[d] : other[d]; /* w_o */
        }
    }
    hb_vectors_soa pin = { pw[0], pw[1], pw[2], pw[3], pw[4], pw[5] };
    CHECK(t, hb_eval_vectors(plan, POLE, pin, (hb_rgb_soa){ pf[0], pf[1], pf[2] }, NULL) == HB_OK &&
                 hb_eval_pdf_vectors(plan, POLE, pin, (hb_rgb_soa){ pg[0], pg[1], pg[2] }, ppdf, NULL) == HB_OK,
          "%s: the poles' calls", c->label);
    double pole_error = hb_test_spec_error((float *const[3]){ pf[0], pf[1], pf[2] }, (float *const[3]){ pg[0], pg[1], pg[2] },
                                           POLE, NULL);
    CHECK(t, pole_error <= 2e-4, "%s: at the poles f from hb_eval_vectors and hb_eval_pdf_vectors differ by %.3g of the peak",
          c->label, pole_error);
    /* the pdf from vectors against the pdf from the angles (buf.pdf2 holds the vectors' now) */
    CHECK(t, hb_pdf_angles(plan, N, in, buf.pdf, NULL) == HB_OK, "%s: pdf", c->label);
    size_t differ = 0;
    for (int k = 0; k < N; k++)
        differ += relative(buf.pdf[k], buf.pdf2[k]) > 1e-4;
    CHECK(t, differ <= (estimated_pdf(c) ? N / 20 : 0), "%s: %zu of %d pdfs from vectors differ from the angles'",
          c->label, differ, N);
    hb_plan_destroy(plan);
}

static void test_eval_pdf(hb_test_ctx *t)
{
    fill_pairs(t);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
        if (case_runs_here(t, &cases[c]))
            eval_pdf_case(t, &cases[c]);
}

/* f and the pdf of the M samples by calls of the sizes `sizes` cycles through (the fused call for
 * every third, eval then pdf for the others), into buf.f2 and buf.pdf2. */
static void calls_of_sizes(const hb_plan *plan, int M, const int *sizes, int count)
{
    float *a[4] = { buf.angles[0], buf.angles[1], buf.angles[2], buf.angles[3] };
    for (int k = 0, call = 0; k < M; call++) {
        int n = sizes[call % count] <= M - k ? sizes[call % count] : M - k;
        hb_angles_soa in = { a[0] + k, a[1] + k, a[2] + k, a[3] + k };
        hb_rgb_soa f = { buf.f2[0] + k, buf.f2[1] + k, buf.f2[2] + k };
        if (call % 3 == 0) {
            hb_eval_pdf_angles(plan, (size_t)n, in, f, buf.pdf2 + k, NULL);
        } else {
            hb_eval_angles(plan, (size_t)n, in, f, NULL);
            hb_pdf_angles(plan, (size_t)n, in, buf.pdf2 + k, NULL);
        }
        k += n;
    }
}

/* Calls of one to five samples (a path tracer's per hit: dFH11's standard plans sum the quadrature's
 * nodes across the lanes, a call of one sample elsewhere runs on the scalar kernels), and batches
 * whose last block is partial (37, 50 and 9 samples: dFH11's standard plans take a last block of a
 * few samples one sample at a time), give what one batch call gives, f and the fused pdf, within the
 * stated bound between ISAs (3e-5 of the peak; dFH11 measured 3e-7, the sum in another order).
 * HHH22's Monte-Carlo TT/TRT keys its numbers by the index within the call, so its values differ by
 * design and it is left out. */
static void test_per_hit_calls(hb_test_ctx *t)
{
    static const int one_to_five[] = { 1, 2, 3, 4, 5 }, tails[] = { 37, 50, 9 };
    static const struct {
        const int *sizes;
        int count;
        const char *what;
    } patterns[] = { { one_to_five, 5, "calls of 1 to 5 samples" }, { tails, 3, "batches of 37, 50 and 9" } };
    fill_pairs(t);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        if (estimated_pdf(&cases[c]) || !case_runs_here(t, &cases[c]))
            continue;
        hb_plan *plan = case_plan(t, &cases[c]);
        if (!plan)
            return;
        enum { M = 96 };
        float *a[4] = { buf.angles[0], buf.angles[1], buf.angles[2], buf.angles[3] };
        hb_eval_pdf_angles(plan, M, (hb_angles_soa){ a[0], a[1], a[2], a[3] }, (hb_rgb_soa){ buf.f[0], buf.f[1], buf.f[2] },
                           buf.pdf, NULL);
        for (size_t p = 0; p < sizeof patterns / sizeof patterns[0]; p++) {
            calls_of_sizes(plan, M, patterns[p].sizes, patterns[p].count);
            float *got[3] = { buf.f2[0], buf.f2[1], buf.f2[2] }, *want[3] = { buf.f[0], buf.f[1], buf.f[2] };
            float *pdf_got[3] = { buf.pdf2, buf.pdf2, buf.pdf2 }, *pdf_want[3] = { buf.pdf, buf.pdf, buf.pdf };
            double ef = hb_test_spec_error(got, want, M, NULL), ep = hb_test_spec_error(pdf_got, pdf_want, M, NULL);
            CHECK(t, ef <= 3e-5 && ep <= 3e-5, "%s: %s differ from the batch by %.3g (f), %.3g (pdf)", cases[c].label,
                  patterns[p].what, ef, ep);
            hb_test_note(t, "%s: %s within %.2g (f), %.2g (pdf) of the batch", cases[c].label, patterns[p].what, ef, ep);
        }
        hb_plan_destroy(plan);
    }
}

/* Invalid samples: a vector of length 2 and a NaN one are counted, get w_i = (0, 0, 0), pdf 0 and
 * weight 0; missing streams are refused; a plan without a sampler refuses every call. */
static void test_renderer_calls_api(hb_test_ctx *t)
{
    hb_plan *plan = case_plan(t, &cases[0]);
    if (!plan)
        return;
    float wo[3][3] = { { 0.0f, 2.0f, NAN }, { 0.0f, 0.0f, 0.0f }, { 1.0f, 0.0f, 1.0f } };
    float u[5][3], wi[3][3], pdf[3], w[3][3];
    for (int d = 0; d < 5; d++)
        u[d][0] = u[d][1] = u[d][2] = 0.3f;
    hb_sample_vectors_in in = { wo[0], wo[1], wo[2], (const float *const[]){ u[0], u[1], u[2], u[3], u[4] } };
    hb_sample_vectors_out out = { wi[0], wi[1], wi[2], pdf, { w[0], w[1], w[2] } };
    hb_eval_report report;
    CHECK(t, hb_sample_vectors(plan, 3, &in, &out, &report) == HB_OK, "sample vectors");
    CHECK(t, report.invalid == 2, "invalid count %zu, want 2", report.invalid);
    CHECK(t, pdf[0] > 0.0f && w[0][0] > 0.0f, "the valid sample: pdf %g weight %g", pdf[0], w[0][0]);
    for (int k = 1; k < 3; k++)
        CHECK(t, wi[0][k] == 0.0f && wi[1][k] == 0.0f && wi[2][k] == 0.0f && pdf[k] == 0.0f && w[1][k] == 0.0f,
              "invalid sample %d: (%g, %g, %g) pdf %g", k, wi[0][k], wi[1][k], wi[2][k], pdf[k]);
    hb_sample_vectors_out missing = out;
    missing.wi_y = NULL;
    CHECK(t, hb_sample_vectors(plan, 3, &in, &missing, NULL) == HB_ERR_NULL, "a missing w_i stream is refused");
    float f[3][3];
    hb_vectors_soa pairs = { wo[0], wo[1], wo[2], wo[0], wo[1], wo[2] };
    CHECK(t, hb_eval_pdf_vectors(plan, 3, pairs, (hb_rgb_soa){ f[0], f[1], f[2] }, pdf, &report) == HB_OK &&
                 report.invalid == 2 && f[0][1] == 0.0f && pdf[2] == 0.0f,
          "fused call on invalid vectors: invalid %zu", report.invalid);
    CHECK(t, hb_eval_pdf_angles(plan, 3, (hb_angles_soa){ 0 }, (hb_rgb_soa){ f[0], f[1], f[2] }, pdf, NULL) ==
                 HB_ERR_NULL, "missing angles are refused");
    CHECK(t, hb_pdf_vectors(plan, 0, (hb_vectors_soa){ 0 }, NULL, NULL) == HB_OK, "an empty batch is fine");
    hb_plan_destroy(plan);

    static const plan_case marschner = { "marschner", HB_MODEL_MARSCHNER, HB_QUALITY_REFERENCE, HB_LOBES_DEFAULT,
                                         HB_AZIMUTHAL_QUADRATURE }; /* MJC03 samples on its kernels only */
    if (!(plan = case_plan(t, &marschner)))
        return;
    CHECK(t, hb_sample_vectors(plan, 3, &in, &out, NULL) == HB_ERR_UNSUPPORTED &&
                 hb_pdf_vectors(plan, 3, pairs, pdf, NULL) == HB_ERR_UNSUPPORTED &&
                 hb_eval_pdf_vectors(plan, 3, pairs, (hb_rgb_soa){ f[0], f[1], f[2] }, pdf, NULL) == HB_ERR_UNSUPPORTED,
          "a plan without a sampler refuses the sampling calls");
    hb_plan_destroy(plan);
}

static void random_unit(hb_test_ctx *t, float v[3])
{
    double z = hb_test_range(t, -1.0, 1.0), a = hb_test_range(t, 0.0, 2.0 * M_PI), r = sqrt(1.0 - z * z);
    v[0] = (float)(r * cos(a)), v[1] = (float)(r * sin(a)), v[2] = (float)z;
}

static double dot3(const float a[3], const float b[3]) { return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2]; }

/* hb_frame_from_tangent: orthonormal and right-handed to 1e-6, y along the tangent, z along the
 * normal's perpendicular part; to_local and to_world invert each other; a circular fibre's f does not
 * depend on the normal; zero, NaN and parallel inputs handled as the header says. */
static void test_frame_from_tangent(hb_test_ctx *t)
{
    double worst = 0.0;
    for (int trial = 0; trial < 2000; trial++) {
        float tangent[3], normal[3];
        random_unit(t, tangent);
        random_unit(t, normal);
        double scale = hb_test_range(t, 1e-3, 1e3);
        for (int k = 0; k < 3; k++)
            tangent[k] *= (float)scale;
        if (trial % 4 == 0) /* exact axes, both signs */
            for (int k = 0; k < 3; k++)
                tangent[k] = (float)(k == trial / 4 % 3) * (trial / 12 % 2 ? -1.0f : 1.0f);
        hb_frame fr;
        CHECK(t, hb_frame_from_tangent(tangent, trial % 3 ? normal : NULL, &fr) == HB_OK, "frame %d", trial);
        double e = fmax(fmax(fabs(dot3(fr.x, fr.x) - 1.0), fabs(dot3(fr.y, fr.y) - 1.0)), fabs(dot3(fr.z, fr.z) - 1.0));
        e = fmax(e, fmax(fmax(fabs(dot3(fr.x, fr.y)), fabs(dot3(fr.y, fr.z))), fabs(dot3(fr.x, fr.z))));
        double cross_z = (double)fr.x[0] * fr.y[1] - (double)fr.x[1] * fr.y[0]; /* (x cross y) . e_z = z . e_z */
        e = fmax(e, fabs(cross_z - fr.z[2]));
        e = fmax(e, fabs(dot3(fr.y, tangent) / sqrt(dot3(tangent, tangent)) - 1.0));
        if (trial % 3) { /* z lies in the plane of y and the normal, on the normal's side */
            float n_perp[3];
            double along = dot3(normal, fr.y);
            for (int k = 0; k < 3; k++)
                n_perp[k] = (float)(normal[k] - along * fr.y[k]);
            double len = sqrt(dot3(n_perp, n_perp));
            if (len > 1e-3)
                e = fmax(e, fabs(dot3(fr.z, n_perp) / len - 1.0));
        }
        float v[3], local[3], back[3];
        random_unit(t, v);
        hb_frame_to_local(&fr, v, local);
        hb_frame_to_world(&fr, local, back);
        for (int k = 0; k < 3; k++)
            e = fmax(e, fabs(back[k] - v[k]));
        worst = fmax(worst, e);
    }
    CHECK(t, worst <= 1e-6, "frame error %.3g", worst);
    hb_test_note(t, "frame: orthonormality, tangent, normal and round trip within %.2g", worst);

    hb_frame fr;
    float zero[3] = { 0.0f, 0.0f, 0.0f }, nan3[3] = { NAN, 0.0f, 1.0f }, y[3] = { 0.0f, 3.0f, 0.0f };
    CHECK(t, hb_frame_from_tangent(zero, NULL, &fr) == HB_ERR_PARAM, "a zero tangent is refused");
    CHECK(t, hb_frame_from_tangent(nan3, NULL, &fr) == HB_ERR_PARAM, "a NaN tangent is refused");
    CHECK(t, hb_frame_from_tangent(NULL, NULL, &fr) == HB_ERR_NULL, "a NULL tangent is refused");
    const float *normals[3] = { y, zero, nan3 }; /* parallel, zero, NaN: as NULL */
    for (int k = 0; k < 3; k++) {
        CHECK(t, hb_frame_from_tangent(y, normals[k], &fr) == HB_OK, "normal %d", k);
        CHECK(t, fabs(dot3(fr.z, fr.z) - 1.0) < 1e-6 && fabs(dot3(fr.z, fr.y)) < 1e-6 && fr.y[1] == 1.0f,
              "normal %d: z = (%g, %g, %g)", k, fr.z[0], fr.z[1], fr.z[2]);
    }

    /* world directions through two frames that differ only in the normal: the same f */
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    hb_plan *plan = NULL;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "plan");
    if (!plan)
        return;
    enum { M = 64 };
    float w[2][6][M], f[2][3][M];
    float tangent[3] = { 0.3f, -0.8f, 0.5f }, n1[3] = { 1.0f, 0.0f, 0.0f }, n2[3] = { 0.0f, 0.2f, 1.0f };
    hb_frame frames[2];
    hb_frame_from_tangent(tangent, n1, &frames[0]);
    hb_frame_from_tangent(tangent, n2, &frames[1]);
    for (int k = 0; k < M; k++) {
        float wi[3], wo[3];
        random_unit(t, wi);
        random_unit(t, wo);
        for (int s = 0; s < 2; s++) {
            float li[3], lo[3];
            hb_frame_to_local(&frames[s], wi, li);
            hb_frame_to_local(&frames[s], wo, lo);
            for (int a = 0; a < 3; a++)
                w[s][a][k] = li[a], w[s][3 + a][k] = lo[a];
        }
    }
    for (int s = 0; s < 2; s++)
        hb_eval_vectors(plan, M, (hb_vectors_soa){ w[s][0], w[s][1], w[s][2], w[s][3], w[s][4], w[s][5] },
                        (hb_rgb_soa){ f[s][0], f[s][1], f[s][2] }, NULL);
    float *a[3] = { f[0][0], f[0][1], f[0][2] }, *b2[3] = { f[1][0], f[1][1], f[1][2] };
    double e = hb_test_spec_error(a, b2, M, NULL);
    CHECK(t, e <= 2e-4, "f depends on the frame's normal by %.3g", e);
    hb_plan_destroy(plan);
}

const hb_test hb_tests_renderer_calls[] = {
    { "sample_vectors", test_sample_vectors, 1 },
    { "eval_pdf_fused", test_eval_pdf, 1 },
    { "per_hit_calls", test_per_hit_calls, 1 },
    { "renderer_calls_api", test_renderer_calls_api, 0 },
    { "frame_from_tangent", test_frame_from_tangent, 0 },
    { 0 },
};

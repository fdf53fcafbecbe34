/* dFH11 at the hit's offset h (the near field, src/models/deon/near.h; docs/deon.md): its mean over h
 * is the far field, the kernels agree with the double reference on every ISA, h's sign is CBTB16's,
 * and its sampler draws its own pdf. */
#include <string.h>

#include "sampling.h"
#include "ref/reference.h"
#include "models/deon/reference.h"

typedef struct near_material {
    const char *name;
    double beta_m, beta_n, alpha, sigma_a, eta;
    int pmax;
    hb_r_fresnel r_fresnel;
} near_material;

static const near_material materials[] = {
    { "default", 0.1, 0.3, 0.035, 0.0, 1.55, 3, HB_R_FRESNEL_OFFSET },
    { "brown", 0.2, 0.3, 0.035, 0.6, 1.55, 3, HB_R_FRESNEL_OFFSET },
    { "narrow", 0.05, 0.05, -0.05, 0.1, 1.55, 3, HB_R_FRESNEL_OFFSET },
    { "wide (Fourier)", 0.5, 1.5, 0.0, 0.2, 1.3, 3, HB_R_FRESNEL_OFFSET },
    { "pmax 5, half-angle R", 0.15, 0.4, 0.035, 0.3, 1.55, 5, HB_R_FRESNEL_HALF_ANGLE },
    { "eta near 1", 0.2, 0.3, 0.035, 0.0, 1.0001, 3, HB_R_FRESNEL_OFFSET },
};
enum { MATERIALS = sizeof materials / sizeof materials[0] };

/* detector_tolerance 0: the quality's; the arithmetic tests ask for 1e-7, so that the plan's truncation
 * of a detector (up to the quality's target: 2e-4 of the peak for beta_n 1.5 at balanced) stays out of them. */
static hb_plan *near_plan_lobes(hb_test_ctx *t, const near_material *nm, hb_quality quality, hb_isa isa,
                                double detector_tolerance, unsigned lobes)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.beta_m = nm->beta_m, m.beta_n = nm->beta_n, m.alpha = nm->alpha, m.eta = nm->eta;
    m.sigma_a[0] = nm->sigma_a, m.sigma_a[1] = 2.0 * nm->sigma_a, m.sigma_a[2] = 3.0 * nm->sigma_a;
    o.pmax = nm->pmax;
    o.r_fresnel = nm->r_fresnel;
    o.quality = quality;
    o.isa = isa;
    o.detector_tolerance = detector_tolerance;
    o.lobes = lobes;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s: %s", nm->name, err.message);
    return plan;
}

static hb_plan *near_plan(hb_test_ctx *t, const near_material *nm, hb_quality quality, hb_isa isa,
                          double detector_tolerance)
{
    return near_plan_lobes(t, nm, quality, isa, detector_tolerance, HB_LOBES_DEFAULT);
}

enum { H = 4000 };
static float ti[H], pi[H], to[H], po[H], hh[H], f[3][H];

/* (1/2) integral over h in [-1, 1] of the kernels' near field, by the midpoint rule in gamma = asin h
 * (dh = cos(gamma) dgamma; H nodes resolve a detector of beta_n 0.05 to 1e-6), against the double
 * far-field reference: within 2e-5 of the peak (measured 1e-5: the float near field's own error). */
static void test_deon_near_mean_is_far(hb_test_ctx *t)
{
    static const double dirs[][4] = { { 0.3, 0.0, -0.2, 0.5 }, { 0.3, 0.0, -0.3, 2.9 }, { -0.5, 1.0, 0.4, -2.0 },
                                      { 1.2, 0.0, -1.0, 0.1 }, { -1.4, 0.2, 1.45, 3.1 }, { 0.0, 0.0, 0.0, 0.0 } };
    enum { DIRS = sizeof dirs / sizeof dirs[0] };
    for (int mc = 0; mc < MATERIALS; mc++) {
        hb_plan *plan = near_plan(t, &materials[mc], HB_QUALITY_BALANCED, HB_ISA_AUTO, 0.0);
        hb_plan *reference = near_plan(t, &materials[mc], HB_QUALITY_REFERENCE, HB_ISA_AUTO, 0.0);
        if (!plan || !reference)
            return;
        double mean[DIRS][3], far[DIRS][3], peak = 0.0, worst = 0.0;
        for (int d = 0; d < DIRS; d++) {
            for (int k = 0; k < H; k++) {
                ti[k] = (float)dirs[d][0], pi[k] = (float)dirs[d][1], to[k] = (float)dirs[d][2], po[k] = (float)dirs[d][3];
                hh[k] = (float)sin(-M_PI_2 + (k + 0.5) * M_PI / H);
            }
            hb_eval_near(plan, H, (hb_near_soa){ ti, pi, to, po, hh }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
            for (int c = 0; c < 3; c++) {
                mean[d][c] = 0.0;
                for (int k = 0; k < H; k++)
                    mean[d][c] += 0.5 * f[c][k] * cos(-M_PI_2 + (k + 0.5) * M_PI / H) * M_PI / H;
            }
            hb_ref_eval_pair(reference, ti[0], pi[0], to[0], po[0], far[d]);
            for (int c = 0; c < 3; c++)
                peak = fmax(peak, far[d][c]);
        }
        for (int d = 0; d < DIRS; d++)
            for (int c = 0; c < 3; c++) {
                double e = fabs(mean[d][c] - far[d][c]) / peak;
                worst = fmax(worst, e);
                CHECK(t, e <= 2e-5, "%s direction %d channel %d: mean near %.8g, far %.8g (peak %.4g)",
                      materials[mc].name, d, c, mean[d][c], far[d][c], peak);
            }
        hb_test_note(t, "%-20s: mean of the near field over h within %.2g of the far field's peak", materials[mc].name,
                     worst);
        hb_plan_destroy(plan);
        hb_plan_destroy(reference);
    }
}

/* The kernels' near field against the double reference at random directions and offsets (a
 * tenth at h = -1, 0, 1 and grazing theta): within 3e-5 of the peak (conventions.md's metric) on
 * every ISA, detectors untruncated. */
static void test_deon_near_reference(hb_test_ctx *t)
{
    enum { N = 600 };
    static float rf[3][N];
    for (int mc = 0; mc < MATERIALS; mc++) {
        hb_plan *plan = near_plan(t, &materials[mc], HB_QUALITY_BALANCED, t->isa, 1e-7);
        hb_plan *reference = near_plan(t, &materials[mc], HB_QUALITY_REFERENCE, HB_ISA_AUTO, 0.0);
        if (!plan || !reference)
            return;
        for (int k = 0; k < N; k++) {
            ti[k] = (float)hb_test_range(t, -1.5707963, 1.5707963);
            to[k] = k % 10 == 3 ? 1.5707963f : (float)hb_test_range(t, -1.5707963, 1.5707963);
            pi[k] = (float)hb_test_range(t, -M_PI, M_PI);
            po[k] = (float)hb_test_range(t, -M_PI, M_PI);
            hh[k] = k % 10 == 0 ? -1.0f : k % 10 == 1 ? 1.0f : k % 10 == 2 ? 0.0f : (float)hb_test_range(t, -1.0, 1.0);
        }
        hb_near_soa in = { ti, pi, to, po, hh };
        hb_eval_report report = { 99 };
        CHECK(t, hb_eval_near(plan, N, in, (hb_rgb_soa){ f[0], f[1], f[2] }, &report) == HB_OK && report.invalid == 0,
              "%s: eval_near (invalid %zu)", materials[mc].name, report.invalid);
        hb_eval_near(reference, N, in, (hb_rgb_soa){ rf[0], rf[1], rf[2] }, NULL);
        float *got[3] = { f[0], f[1], f[2] }, *want[3] = { rf[0], rf[1], rf[2] };
        size_t worst_k = 0;
        double e = hb_test_spec_error(got, want, N, &worst_k);
        CHECK(t, e <= 3e-5, "%s: near field %.3g from the reference (sample %zu: %.9g vs %.9g)", materials[mc].name, e,
              worst_k, f[0][worst_k], rf[0][worst_k]);
        hb_test_note(t, "%-20s: near field within %.2g of the reference", materials[mc].name, e);
        hb_plan_destroy(plan);
        hb_plan_destroy(reference);
    }
}

double hb_test_near_per_hit(hb_test_ctx *t, const hb_plan *plan, const char *name, int pairs)
{
    enum { N = 300 };
    static float one[3][N];
    for (int k = 0; k < N; k++) {
        ti[k] = k % 10 == 4 ? -1.5707964f : (float)hb_test_range(t, -1.5707963, 1.5707963);
        to[k] = k % 10 == 3 ? 1.5707964f : (float)hb_test_range(t, -1.5707963, 1.5707963);
        pi[k] = (float)hb_test_range(t, -M_PI, M_PI);
        po[k] = k % 10 == 5 ? pi[k] - 2.0f * asinf(0.3f) : (float)hb_test_range(t, -M_PI, M_PI);
        hh[k] = k % 10 == 0 ? -1.0f : k % 10 == 1 ? 1.0f : k % 10 == 2 ? 0.0f : (float)hb_test_range(t, -1.0, 1.0);
    }
    hb_eval_near(plan, N, (hb_near_soa){ ti, pi, to, po, hh }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    for (int k = 0; k < N;) {
        int n = pairs && k % 3 == 1 && k + 2 <= N ? 2 : 1;
        hb_eval_near(plan, (size_t)n, (hb_near_soa){ ti + k, pi + k, to + k, po + k, hh + k },
                     (hb_rgb_soa){ one[0] + k, one[1] + k, one[2] + k }, NULL);
        k += n;
    }
    float *got[3] = { one[0], one[1], one[2] }, *want[3] = { f[0], f[1], f[2] };
    size_t at = 0;
    double e = hb_test_spec_error(got, want, N, &at);
    CHECK(t, e <= 3e-5, "%s: calls of one sample differ from the batch by %.3g (sample %zu: %.9g vs %.9g)", name, e,
          at, one[0][at], f[0][at]);
    float bad_h = NAN, out[3] = { 1.0f, 1.0f, 1.0f };
    hb_eval_report report = { 0 };
    hb_eval_near(plan, 1, (hb_near_soa){ ti, pi, to, po, &bad_h }, (hb_rgb_soa){ out, out + 1, out + 2 }, &report);
    CHECK(t, report.invalid == 1 && out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f,
          "%s: a NaN offset in a call of one: %zu invalid, f %g", name, report.invalid, out[0]);
    return e;
}

/* Calls of one and two samples, as a path tracer makes them per hit (standard plans below high quality
 * put one sample's lobes across the lanes, near.h; the others run on the scalar kernels), give what one
 * batch call gives: within 3e-5 of the peak (the stated bound between ISAs; measured 1.6e-6, from the
 * scalar kernels without FMA) for every material, lobe set and quality, at the poles and h = -1, 0, 1
 * too (hb_test_near_per_hit). */
static void test_deon_near_per_hit(hb_test_ctx *t)
{
    static const unsigned lobe_sets[] = { HB_LOBES_DEFAULT, 1u << HB_LOBE_R | 1u << HB_LOBE_TT,
                                          1u << HB_LOBE_TT | 1u << HB_LOBE_TRRT | 1u << HB_LOBE_RESIDUAL };
    double worst = 0.0;
    for (int mc = 0; mc < MATERIALS; mc++)
        for (int q = HB_QUALITY_FAST; q <= HB_QUALITY_HIGH; q++)
            for (size_t l = 0; l < sizeof lobe_sets / sizeof lobe_sets[0]; l++) {
                if (l && (materials[mc].pmax != 3 || q != HB_QUALITY_BALANCED))
                    continue;
                hb_plan *plan = near_plan_lobes(t, &materials[mc], (hb_quality)q, t->isa, 0.0, lobe_sets[l]);
                if (!plan)
                    return;
                char name[96];
                snprintf(name, sizeof name, "%s, quality %d, lobes %#x", materials[mc].name, q, lobe_sets[l]);
                worst = fmax(worst, hb_test_near_per_hit(t, plan, name, 1));
                hb_plan_destroy(plan);
            }
    hb_test_note(t, "calls of one and two samples within %.2g of the batch", worst);
}

/* The exit azimuth of R at h is Phi(0, h) = -2 asin(h) in both near-field models (dFH11 eq. 8 and
 * CBTB16 in its h convention, docs/chiang.md): for an R-only fibre with a narrow azimuthal lobe and
 * no tilt, f over phi peaks there for both, within the scan's step. */
static void test_deon_near_sign(hb_test_ctx *t)
{
    enum { S = 3600 };
    static const double offsets[] = { 0.5, -0.8, 0.1 };
    for (int model = 0; model < 2; model++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        o.model = model ? HB_MODEL_CHIANG : HB_MODEL_DEON;
        o.lobes = 1u << HB_LOBE_R;
        m.alpha = 0.0;
        m.beta_m = 0.2;
        m.beta_n = model ? 0.1 : 0.05;
        hb_plan *plan = NULL;
        CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "R-only plan, model %d", model);
        if (!plan)
            return;
        for (int c = 0; c < 3; c++) {
            for (int k = 0; k < S; k++) {
                ti[k] = -0.3f, to[k] = 0.3f, pi[k] = 0.0f, hh[k] = (float)offsets[c];
                po[k] = (float)(-M_PI + (k + 0.5) * 2.0 * M_PI / S);
            }
            hb_eval_near(plan, S, (hb_near_soa){ ti, pi, to, po, hh }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
            int best = 0;
            for (int k = 1; k < S; k++)
                best = f[0][k] > f[0][best] ? k : best;
            double want = -2.0 * asin(offsets[c]);
            CHECK(t, fabs(remainder(po[best] - want, 2.0 * M_PI)) <= 2.0 * M_PI / S,
                  "model %s, h %g: R peaks at phi %.4f, eq. 8 says %.4f", model ? "chiang" : "deon", offsets[c],
                  po[best], want);
        }
        hb_plan_destroy(plan);
    }
}

enum { NT = 24, NP = 48, GL = 6 };

/* The near-field sampler draws its pdf (chi-square over equal-area cells, p >= 1e-3; the pdf
 * integrates to 1 within 2e-3), and every sample's weight is f / pdf with hb_pdf_near at the sample
 * equal to the sampled pdf bit for bit. */
static void test_deon_near_chi_square(hb_test_ctx *t)
{
    static const struct { int material; double theta_o, h; } cases[] = {
        { 0, 0.5, 0.2 }, { 1, -0.7, -0.9 }, { 2, 0.3, 0.6 }, { 3, 1.3, -0.4 }, { 4, 0.0, 1.0 }, { 5, -1.2, 0.0 },
    };
    static double prob[NT * NP];
    size_t n = t->quick ? 20000 : HB_TEST_MAX_SAMPLES;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        if (t->quick && c % 2)
            continue;
        near_material sampled = materials[cases[c].material];
        sampled.r_fresnel = HB_R_FRESNEL_OFFSET; /* eq. 12's half-angle Fresnel has no sampler */
        const near_material *nm = &sampled;
        hb_plan *plan = near_plan(t, nm, HB_QUALITY_BALANCED, HB_ISA_AUTO, 0.0);
        if (!plan)
            return;
        CHECK(t, hb_plan_sample_dimensions(plan) - 1 == 4, "%s: the near sampler reads 4 numbers", nm->name);
        double integral = hb_test_cell_integrals_near(plan, 1, cases[c].theta_o, 0.3, cases[c].h, NT, NP, 1, GL, prob);
        unsigned long long seed = hb_test_next_seed(t);
        hb_test_sample_batch_near(t, plan, n, cases[c].theta_o, 0.3, cases[c].h, seed);
        double chi2, worst_weight = 0.0;
        int cells;
        double p_value = hb_test_chi_square(n, prob, integral, NT, NP, &chi2, &cells);
        hb_sample_buffers *b = &hb_samples;
        hb_near_soa at = { b->ti, b->pi, b->to, b->po, b->h };
        hb_pdf_near(plan, n, at, b->pdf2, NULL);
        hb_eval_near(plan, n, at, (hb_rgb_soa){ b->f[0], b->f[1], b->f[2] }, NULL);
        hb_test_check_sampled_weights(t, n, nm->name, &worst_weight);
        hb_test_note(t, "%-20s theta_o %5.2f h %5.2f (seed %llu): pdf integral %.6f, chi2 %.1f over %d cells, p = %.3f, "
                        "weights f / pdf to %.1e", nm->name, cases[c].theta_o, cases[c].h, seed, integral, chi2, cells,
                     p_value, worst_weight);
        CHECK(t, fabs(integral - 1.0) <= 2e-3, "%s: pdf integrates to %.6f", nm->name, integral);
        CHECK(t, p_value >= 1e-3, "%s: chi-square p-value %.2e below the 1e-3 significance", nm->name, p_value);
        CHECK(t, worst_weight <= 1e-5, "%s: weight differs from f / pdf by %.3g", nm->name, worst_weight);
        hb_plan_destroy(plan);
    }
}

/* The sampler on every ISA against the double procedure (hb_ref_deon_sample_near) from the same
 * numbers: directions within 1e-4 rad but for lobe choices that flip on float rounding (at most 1%),
 * and the reference plan's own sampled pdf against the kernels' pdf at its samples within 1e-4. */
static void test_deon_near_sample_reference(hb_test_ctx *t)
{
    enum { S = 2048 };
    static float u[HB_SAMPLE_DIMENSIONS][S], pdf[S], w[3][S], rti[S], rpi[S], rpdf[S], pdf2[S];
    for (int mc = 1; mc < 4; mc++) {
        hb_plan *plan = near_plan(t, &materials[mc], HB_QUALITY_BALANCED, t->isa, 1e-7);
        hb_plan *reference = near_plan(t, &materials[mc], HB_QUALITY_REFERENCE, HB_ISA_AUTO, 0.0);
        if (!plan || !reference)
            return;
        float *streams[HB_SAMPLE_DIMENSIONS];
        for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
            streams[d] = u[d];
        hb_uniforms(hb_test_next_seed(t), 0, S, 4, streams);
        for (int k = 0; k < S; k++) {
            to[k] = (float)hb_test_range(t, -1.5, 1.5);
            po[k] = (float)hb_test_range(t, -M_PI, M_PI);
            hh[k] = (float)hb_test_range(t, -1.0, 1.0);
        }
        hb_sample_near_in in = { to, po, hh, (const float *const[]){ u[0], u[1], u[2], u[3] } };
        hb_sample_near(plan, S, &in, &(hb_sample_out){ ti, pi, pdf, { w[0], w[1], w[2] } }, NULL);
        hb_sample_near(reference, S, &in, &(hb_sample_out){ rti, rpi, rpdf, { w[0], w[1], w[2] } }, NULL);
        hb_pdf_near(plan, S, (hb_near_soa){ rti, rpi, to, po, hh }, pdf2, NULL);
        int flips = 0;
        double worst_angle = 0.0, worst_pdf = 0.0;
        for (int k = 0; k < S; k++) {
            double d = fmax(fabs(rti[k] - ti[k]), fabs(remainder(rpi[k] - pi[k], 2.0 * M_PI)));
            if (d > 1e-4)
                flips++;
            else
                worst_angle = fmax(worst_angle, d);
            if (rpdf[k] > 1e-3f)
                worst_pdf = fmax(worst_pdf, fabs(pdf2[k] / rpdf[k] - 1.0));
        }
        hb_test_note(t, "%-20s: directions within %.2e rad of the double procedure, %d flips; pdf within %.2e",
                     materials[mc].name, worst_angle, flips, worst_pdf);
        CHECK(t, flips <= S / 100, "%s: %d of %d samples off the double procedure", materials[mc].name, flips, S);
        CHECK(t, worst_pdf <= 1e-4, "%s: kernel pdf %.3g from the reference's", materials[mc].name, worst_pdf);
        hb_plan_destroy(plan);
        hb_plan_destroy(reference);
    }
}

/* Invalid offsets (NaN, beyond +-1) are counted and give 0; the longitudinal term has no near field. */
static void test_deon_near_api(hb_test_ctx *t)
{
    hb_plan *plan = near_plan(t, &materials[0], HB_QUALITY_FAST, HB_ISA_AUTO, 0.0);
    if (!plan)
        return;
    float a[4] = { 0.3f, 0.3f, 0.3f, 0.3f }, b0[4] = { 0.0f, 0.0f, 0.0f, 0.0f }, c[4] = { -0.2f, -0.2f, -0.2f, -0.2f };
    float h4[4] = { 0.5f, NAN, 1.0000001f, -1.0f }, out[3][4];
    hb_eval_report report;
    CHECK(t, hb_eval_near(plan, 4, (hb_near_soa){ a, b0, c, b0, h4 }, (hb_rgb_soa){ out[0], out[1], out[2] }, &report) ==
                     HB_OK && report.invalid == 2 && out[0][1] == 0.0f && out[0][2] == 0.0f && out[0][0] > 0.0f &&
                 out[0][3] > 0.0f,
          "invalid offsets: %zu counted, f %g %g %g %g", report.invalid, out[0][0], out[0][1], out[0][2], out[0][3]);
    hb_plan_destroy(plan);
    hb_material m;
    hb_options o;
    hb_test_longitudinal_setup(t, &m, &o);
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "longitudinal plan");
    CHECK(t, hb_eval_near(plan, 4, (hb_near_soa){ a, b0, c, b0, h4 }, (hb_rgb_soa){ out[0], out[1], out[2] }, NULL) ==
                 HB_ERR_UNSUPPORTED, "the longitudinal term has no near field");
    hb_plan_destroy(plan);
}

const hb_test hb_tests_deon_near[] = {
    { "deon_near_mean_is_far", test_deon_near_mean_is_far, 0 },
    { "deon_near_reference", test_deon_near_reference, 1 },
    { "deon_near_per_hit", test_deon_near_per_hit, 1 },
    { "deon_near_sign", test_deon_near_sign, 0 },
    { "deon_near_chi_square", test_deon_near_chi_square, 0 },
    { "deon_near_sample_reference", test_deon_near_sample_reference, 1 },
    { "deon_near_api", test_deon_near_api, 0 },
    { 0 },
};

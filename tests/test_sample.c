/* Sampling and pdf (docs/sampling.md): the tests renderers run on hair, and stricter
 * ones. Random numbers come from hb_uniforms with a seed drawn from the test's seed (printed by
 * the runner), so every failure reproduces with --seed. */
#include <stdlib.h>
#include <string.h>

#include "sampling.h"
#include "models/interface/plan.h"
#include "ref/reference.h"
#include "models/deon/reference.h"

#define MAX_SAMPLES HB_TEST_MAX_SAMPLES

static hb_sample_buffers *const buf = &hb_samples;

static hb_plan *deon_plan(hb_test_ctx *t, double beta_m, double beta_n, double alpha, double sigma_a,
                          hb_quality quality, hb_isa isa)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.beta_m = beta_m;
    m.beta_n = beta_n;
    m.alpha = alpha;
    m.sigma_a[0] = m.sigma_a[1] = m.sigma_a[2] = sigma_a;
    o.quality = quality;
    o.isa = isa;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "plan: %s", err.message);
    return plan;
}

/* Items 1 and 2: for sigma_a = 0 the mean weight is the albedo E(w_o), and with lobes sharing
 * one M_p (alpha = 0) every single weight is E(w_o), within 1e-3 (measured: 3e-7). With the
 * default tilt the lobes' M_p differ, weights spread (about +-15%) and their mean is still E. */
static void test_sample_furnace(hb_test_ctx *t)
{
    static const double betas[] = { 0.1, 0.3, 0.5, 0.7, 0.9 }, thetas[] = { 0.0, -0.7, 1.3 };
    size_t n = t->quick ? 5000 : 100000;
    double worst_mean = 0.0, worst_single = 0.0, worst_tilted = 0.0;
    for (int a = 0; a < 5; a++)
        for (int b = 0; b < 5; b++) {
            if (t->quick && (a + b) % 4)
                continue;
            for (int tilted = 0; tilted < 2; tilted++) {
                if (tilted && (a + b) % 2) /* the tilted case on half of the pairs */
                    continue;
                hb_plan *plan = deon_plan(t, betas[a], betas[b], tilted ? 0.035 : 0.0, 0.0, HB_QUALITY_BALANCED,
                                          HB_ISA_AUTO);
                if (!plan)
                    return;
                for (int k = 0; k < 3; k++) {
                    double energy[3], mean = 0.0;
                    hb_furnace(plan, thetas[k], energy);
                    hb_test_sample_batch(t, plan, n, thetas[k], 0.3, hb_test_next_seed(t));
                    for (size_t i = 0; i < n; i++) {
                        mean += buf->w[0][i];
                        if (!tilted)
                            worst_single = fmax(worst_single, fabs(buf->w[0][i] - energy[0]));
                    }
                    mean /= (double)n;
                    if (tilted)
                        worst_tilted = fmax(worst_tilted, fabs(mean - energy[0]));
                    else
                        worst_mean = fmax(worst_mean, fabs(mean - 1.0));
                }
                hb_plan_destroy(plan);
            }
        }
    hb_test_note(t, "alpha 0: |mean weight - 1| <= %.1e, |weight - E| <= %.1e; alpha 0.035: |mean - E| <= %.1e",
                 worst_mean, worst_single, worst_tilted);
    CHECK(t, worst_mean <= 1e-2, "mean weight off 1 by %.3e", worst_mean);
    CHECK(t, worst_single <= 1e-3, "a single weight off the albedo by %.3e", worst_single);
    CHECK(t, worst_tilted <= 1e-2, "tilted: mean weight off E by %.3e", worst_tilted);
}

/* Item 3: with sigma_a = 0.25 and L(w) = w_z^2, the importance-sampled estimate of L_o and the
 * uniform-sphere estimate agree within 5%. */
static void test_sample_consistency(hb_test_ctx *t)
{
    static const double pairs[][2] = { { 0.2, 0.3 }, { 0.3, 0.5 }, { 0.5, 0.9 }, { 0.15, 0.7 } };
    static const double thetas[] = { 0.2, -0.9 };
    size_t n_sampled = t->quick ? 20000 : 100000, n_uniform = t->quick ? 40000 : MAX_SAMPLES;
    double worst = 0.0;
    for (int c = 0; c < 4; c++) {
        if (t->quick && c % 2)
            continue;
        hb_plan *plan = deon_plan(t, pairs[c][0], pairs[c][1], 0.035, 0.25, HB_QUALITY_BALANCED, HB_ISA_AUTO);
        if (!plan)
            return;
        for (int k = 0; k < 2; k++) {
            double sampled = 0.0, uniform = 0.0, uniform2 = 0.0;
            hb_test_sample_batch(t, plan, n_sampled, thetas[k], 0.0, hb_test_next_seed(t));
            for (size_t i = 0; i < n_sampled; i++) {
                double wz = cos(buf->pi[i]) * cos(buf->ti[i]);
                sampled += buf->w[0][i] * wz * wz;
            }
            sampled /= (double)n_sampled;
            /* uniform directions: sin(theta) = 2 u - 1, phi = 2 pi u' - pi; pdf 1 / (4 pi) */
            int reps = t->quick ? 3 : 5;
            for (int rep = 0; rep < reps; rep++) {
                float *u[2] = { buf->u[0], buf->u[1] };
                hb_uniforms(hb_test_next_seed(t), 0, n_uniform, 2, u);
                for (size_t i = 0; i < n_uniform; i++) {
                    buf->ti[i] = (float)asin(2.0 * buf->u[0][i] - 1.0);
                    buf->pi[i] = (float)(2.0 * M_PI * buf->u[1][i] - M_PI);
                    buf->to[i] = (float)thetas[k];
                    buf->po[i] = 0.0f;
                }
                hb_eval_angles(plan, n_uniform, (hb_angles_soa){ buf->ti, buf->pi, buf->to, buf->po },
                               (hb_rgb_soa){ buf->f[0], buf->f[1], buf->f[2] }, NULL);
                for (size_t i = 0; i < n_uniform; i++) {
                    double wz = cos(buf->pi[i]) * cos(buf->ti[i]), x = 4.0 * M_PI * buf->f[0][i] * wz * wz;
                    uniform += x;
                    uniform2 += x * x;
                }
            }
            size_t total = (size_t)reps * n_uniform;
            uniform /= (double)total;
            double sigma = sqrt(fmax(uniform2 / (double)total - uniform * uniform, 0.0) / (double)total);
            double diff = fabs(sampled - uniform) / uniform;
            worst = fmax(worst, diff);
            if (diff > 0.05)
                hb_test_note(t, "beta %g/%g theta_o %g: sampled %.5f uniform %.5f (+-%.5f)", pairs[c][0], pairs[c][1],
                             thetas[k], sampled, uniform, sigma);
        }
        hb_plan_destroy(plan);
    }
    hb_test_note(t, "importance-sampled vs uniform estimates of L_o: worst relative difference %.2e", worst);
    CHECK(t, worst <= 0.05, "estimates differ by %.3e", worst);
}

enum { NT = 24, NP = 48, GL = 6 };

/* Items 4 and 5: sampled directions follow the pdf (chi-square on NT x NP equal-area cells,
 * cells expecting fewer than 5 pooled, significance 1e-3), and the pdf integrates to 1. */
static void test_sample_chi_square(hb_test_ctx *t)
{
    static const struct { double beta_m, beta_n, alpha, sigma_a, theta_o, phi_o; } cases[] = {
        { 0.3, 0.3, 0.035, 0.0, 0.5, 0.3 },  { 0.1, 0.2, 0.035, 0.5, -0.7, 1.0 },
        { 0.5, 0.9, 0.0, 0.2, 1.3, -2.0 },   { 0.2, 0.5, 0.035, 2.0, 0.0, 3.1 },
        { 0.15, 0.15, -0.05, 0.05, 1.45, 0.0 },
    };
    static double prob[NT * NP];
    size_t n = t->quick ? 20000 : MAX_SAMPLES;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        hb_plan *plan = deon_plan(t, cases[c].beta_m, cases[c].beta_n, cases[c].alpha, cases[c].sigma_a,
                                  HB_QUALITY_BALANCED, HB_ISA_AUTO);
        if (!plan)
            return;
        double integral = hb_test_cell_integrals(plan, 1, cases[c].theta_o, cases[c].phi_o, NT, NP, 1, GL, prob);
        unsigned long long seed = hb_test_next_seed(t);
        hb_test_sample_batch(t, plan, n, cases[c].theta_o, cases[c].phi_o, seed);
        double chi2;
        int cells;
        double p_value = hb_test_chi_square(n, prob, integral, NT, NP, &chi2, &cells);
        hb_test_note(t, "case %zu (seed %llu): integral of pdf %.6f, chi2 %.1f over %d cells, p = %.3f", c, seed,
                     integral, chi2, cells, p_value);
        CHECK(t, fabs(integral - 1.0) <= 2e-3, "case %zu: pdf integrates to %.6f", c, integral);
        CHECK(t, p_value >= 1e-3, "case %zu: chi-square p-value %.2e below the 1e-3 significance", c, p_value);
        hb_plan_destroy(plan);
    }
}

/* Item 5 on every ISA, hard cases included (v = 1e-4 with beta_n 0.02 at grazing theta_o, huge
 * absorption): the same uniform numbers give the double reference's direction (up to
 * the few samples whose discrete choice, of lobe, node or side, flips on float rounding), the
 * pdf at a sampled direction agrees with the double procedure's pdf there, hb_pdf_angles
 * returns the sampled pdf bit for bit, and weights are f / pdf. */
static void test_sample_reference(hb_test_ctx *t)
{
    static const struct { double beta_m, beta_n, alpha, sigma_a, theta_o; } cases[] = {
        { 0.3, 0.3, 0.035, 0.0, 0.5 }, { 0.1, 0.2, 0.035, 0.5, -1.2 }, { 0.02, 0.05, 0.0, 0.1, 0.3 },
        { 0.9, 1.5, -0.1, 3.0, 1.5 }, { 0.01, 0.02, 0.035, 0.0, 1.5707963 }, { 0.01, 0.3, 0.0, 1e3, -0.3 },
        { 0.005, 0.02, 0.035, 0.0, 1.5707963 }, { 0.001, 0.3, 0.0, 1e3, -0.3 },
    };
    size_t n = t->quick ? 100 : 400;
    double worst_direction = 0.0, worst_pdf = 0.0, worst_weight = 0.0;
    size_t flips = 0, total = 0;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        hb_plan *plan = deon_plan(t, cases[c].beta_m, cases[c].beta_n, cases[c].alpha, cases[c].sigma_a,
                                  HB_QUALITY_HIGH, t->isa);
        if (!plan)
            return;
        hb_test_sample_batch(t, plan, n, cases[c].theta_o, 0.7, hb_test_next_seed(t));
        hb_pdf_angles(plan, n, (hb_angles_soa){ buf->ti, buf->pi, buf->to, buf->po }, buf->pdf2, NULL);
        double peak = 0.0, ref_pdf[400];
        for (size_t i = 0; i < n; i++) {
            ref_pdf[i] = hb_ref_deon_pdf(plan, buf->ti[i], buf->pi[i], buf->to[i], buf->po[i]);
            peak = fmax(peak, ref_pdf[i]);
        }
        hb_eval_angles(plan, n, (hb_angles_soa){ buf->ti, buf->pi, buf->to, buf->po }, (hb_rgb_soa){ buf->f[0], buf->f[1], buf->f[2] }, NULL);
        for (size_t i = 0; i < n; i++) {
            double u[5], ti, pi;
            for (int d = 0; d < 5; d++)
                u[d] = buf->u[d][i];
            hb_ref_deon_sample(plan, buf->to[i], buf->po[i], u, &ti, &pi);
            double dphi = fabs(remainder(pi - buf->pi[i], 2.0 * M_PI)), d = fmax(fabs(ti - buf->ti[i]), dphi);
            if (d > 1e-3)
                flips++;
            else
                worst_direction = fmax(worst_direction, d);
            total++;
            worst_pdf = fmax(worst_pdf, fabs(buf->pdf[i] - ref_pdf[i]) / fmax(ref_pdf[i], 1e-3 * peak));
        }
        char label[32];
        snprintf(label, sizeof label, "case %zu", c);
        hb_test_check_sampled_weights(t, n, label, &worst_weight);
        hb_plan_destroy(plan);
    }
    hb_test_note(t, "directions: %zu of %zu flip a discrete choice, the rest within %.1e rad; pdf within %.1e; weight = f/pdf to %.1e",
                 flips, total, worst_direction, worst_pdf, worst_weight);
    CHECK(t, flips * 100 <= total, "%zu of %zu samples differ from the reference's", flips, total);
    CHECK(t, worst_direction <= 1e-5, "sampled direction off the reference by %.2e rad", worst_direction);
    CHECK(t, worst_pdf <= 2e-4, "pdf off the reference by %.2e", worst_pdf);
    CHECK(t, worst_weight <= 1e-6, "weight differs from f / pdf by %.2e", worst_weight);
}

/* The reference quality samples with the double procedure: its weights are f_ref / pdf_ref. */
static void test_sample_reference_quality(hb_test_ctx *t)
{
    hb_plan *plan = deon_plan(t, 0.3, 0.3, 0.0, 0.0, HB_QUALITY_REFERENCE, HB_ISA_AUTO);
    if (!plan)
        return;
    size_t n = t->quick ? 50 : 300;
    hb_test_sample_batch(t, plan, n, 0.4, 0.0, hb_test_next_seed(t));
    double worst = 0.0;
    for (size_t i = 0; i < n; i++)
        worst = fmax(worst, fabs(buf->w[0][i] - 1.0));
    hb_test_note(t, "reference quality, lossless, alpha 0: every weight within %.1e of 1", worst);
    CHECK(t, worst <= 1e-3, "reference weights off 1 by %.2e", worst);
    hb_plan_destroy(plan);
}

/* Refusals and invalid samples: documented outputs and counts, never a crash. */
static void test_sample_api(hb_test_ctx *t)
{
    hb_plan *plan = deon_plan(t, 0.3, 0.3, 0.035, 0.1, HB_QUALITY_FAST, HB_ISA_AUTO);
    if (!plan)
        return;
    CHECK(t, hb_plan_sample_dimensions(plan) == 5, "d'Eon reads %d numbers", hb_plan_sample_dimensions(plan));
    float to[4] = { 0.3f, NAN, 0.3f, 2.0f }, po[4] = { 0.0f, 0.0f, 0.0f, 0.0f }, u[5][4];
    for (int d = 0; d < 5; d++)
        for (int k = 0; k < 4; k++)
            u[d][k] = 0.25f;
    u[3][2] = 1.5f;
    float ti[4], pi[4], pdf[4], w[3][4];
    const float *planes[5] = { u[0], u[1], u[2], u[3], u[4] };
    hb_sample_in in = { to, po, planes };
    hb_sample_out out = { ti, pi, pdf, { w[0], w[1], w[2] } };
    hb_eval_report report;
    CHECK(t, hb_sample_angles(plan, 4, &in, &out, &report) == HB_OK, "sample");
    CHECK(t, report.invalid == 3, "invalid count %zu, want 3", report.invalid);
    CHECK(t, pdf[0] > 0.0f && w[0][0] > 0.0f, "valid sample: pdf %g weight %g", pdf[0], w[0][0]);
    for (int k = 1; k < 4; k++)
        CHECK(t, ti[k] == 0.0f && pi[k] == 0.0f && pdf[k] == 0.0f && w[0][k] == 0.0f && w[2][k] == 0.0f,
              "invalid sample %d: %g %g %g %g", k, ti[k], pi[k], pdf[k], w[0][k]);
    planes[4] = NULL;
    CHECK(t, hb_sample_angles(plan, 4, &in, &out, NULL) == HB_ERR_NULL, "a missing u stream is refused");
    hb_plan_destroy(plan);

    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = HB_MODEL_MARSCHNER;
    o.quality = HB_QUALITY_REFERENCE;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "marschner plan");
    CHECK(t, hb_plan_sample_dimensions(plan) == 0, "MJC03 has no double-precision sampler");
    CHECK(t, hb_sample_angles(plan, 0, &in, &out, NULL) == HB_ERR_UNSUPPORTED, "MJC03 reference sampling is refused");
    hb_plan_destroy(plan);
    o.model = HB_MODEL_DEON;
    o.quality = HB_QUALITY_BALANCED;
    o.r_fresnel = HB_R_FRESNEL_HALF_ANGLE;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "half-angle plan");
    CHECK(t, hb_pdf_angles(plan, 0, (hb_angles_soa){ 0 }, NULL, NULL) == HB_ERR_UNSUPPORTED,
          "the half-angle Fresnel variant has no sampler");
    hb_plan_destroy(plan);

    /* hb_uniforms: a pure function of (seed, index, dimension), uniform */
    static float a[2][4096], b[2][4096];
    float *pa[2] = { a[0], a[1] }, *pb[2] = { b[0], b[1] };
    hb_uniforms(7, 0, 4096, 2, pa);
    hb_uniforms(7, 1000, 10, 2, pb);
    CHECK(t, memcmp(a[1] + 1000, b[1], 10 * sizeof(float)) == 0, "hb_uniforms depends on the batch split");
    double mean = 0.0;
    for (int k = 0; k < 4096; k++) {
        mean += a[0][k];
        CHECK(t, a[0][k] >= 0.0f && a[0][k] < 1.0f, "u = %g", a[0][k]);
    }
    mean /= 4096.0;
    CHECK(t, fabs(mean - 0.5) < 0.02, "mean of hb_uniforms %.4f", mean);
}

/* Uniform numbers at the ends of [0, 1] and at subnormals: every sampler, float and reference, counts
 * the same samples invalid (a subnormal u is read as a zero of its sign, as the kernels flush it, so
 * -1e-45 is valid), and gives weight 0 wherever it gives pdf 0 (a balance heuristic divides by it). */
static void test_sample_extreme_u(hb_test_ctx *t)
{
    enum { K = 512 };
    static float to[K], po[K], h[K], u[HB_SAMPLE_DIMENSIONS][K], ti[K], pi[K], pdf[K], w[3][K];
    static const float ends[] = { 0.0f, 1.0f, -1e-45f, 1e-45f, -0.0f, 0.5f, 0.99999994f, -1e-38f };
    static const struct { const char *name; hb_model model; unsigned lobes; int near; } cases[] = {
        { "deon", HB_MODEL_DEON, HB_LOBES_DEFAULT, 0 },    { "deon near", HB_MODEL_DEON, HB_LOBES_DEFAULT, 1 },
        { "chiang", HB_MODEL_CHIANG, HB_LOBES_DEFAULT, 0 }, { "chiang near", HB_MODEL_CHIANG, HB_LOBES_DEFAULT, 1 },
        { "huang R", HB_MODEL_HUANG, 1u << HB_LOBE_R, 0 },
    };
    const float *planes[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        planes[d] = u[d];
    for (int k = 0; k < K; k++) {
        to[k] = (float)hb_test_range(t, -1.5, 1.5), po[k] = (float)hb_test_range(t, -3, 3);
        h[k] = (float)hb_test_range(t, -1, 1);
        for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
            u[d][k] = hb_test_uniform(t) < 0.7 ? ends[(k + 3 * d) % 8] : (float)hb_test_uniform(t);
    }
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        size_t invalid[2] = { 0, 0 };
        for (int reference = 0; reference < 2; reference++) {
            hb_material m;
            hb_options o;
            hb_material_default(&m);
            hb_options_default(&o);
            o.model = cases[c].model, o.lobes = cases[c].lobes;
            o.quality = reference ? HB_QUALITY_REFERENCE : HB_QUALITY_BALANCED;
            o.isa = t->isa;
            hb_plan *plan;
            hb_error err;
            CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s: %s", cases[c].name, err.message);
            if (!plan)
                continue;
            hb_sample_out out = { ti, pi, pdf, { w[0], w[1], w[2] } };
            hb_eval_report report = { 0 };
            hb_status st;
            if (cases[c].near) {
                hb_sample_near_in in = { to, po, h, planes };
                st = hb_sample_near(plan, K, &in, &out, &report);
            } else {
                hb_sample_in in = { to, po, planes };
                st = hb_sample_angles(plan, K, &in, &out, &report);
            }
            CHECK(t, st == HB_OK, "%s: status %d", cases[c].name, (int)st);
            invalid[reference] = report.invalid;
            int zero_pdf_weighted = 0, not_finite = 0;
            for (int k = 0; k < K; k++)
                for (int ch = 0; ch < 3; ch++) {
                    zero_pdf_weighted += pdf[k] == 0.0f && w[ch][k] != 0.0f;
                    not_finite += !(isfinite(w[ch][k]) && w[ch][k] >= 0.0f && isfinite(pdf[k]) && pdf[k] >= 0.0f);
                }
            CHECK(t, zero_pdf_weighted == 0 && not_finite == 0, "%s %s: %d weights > 0 with pdf 0, %d not finite or < 0",
                  cases[c].name, reference ? "reference" : "balanced", zero_pdf_weighted, not_finite);
            hb_plan_destroy(plan);
        }
        CHECK(t, invalid[0] == invalid[1], "%s: %zu invalid samples in the kernels, %zu in the reference", cases[c].name,
              invalid[0], invalid[1]);
    }
}

const hb_test hb_tests_sample[] = {
    { "sample_extreme_u", test_sample_extreme_u, 1 },
    { "sample_api", test_sample_api, 0 },
    { "deon_sample_furnace", test_sample_furnace, 0 },
    { "deon_sample_consistency", test_sample_consistency, 0 },
    { "deon_sample_chi_square", test_sample_chi_square, 0 },
    { "deon_sample_reference", test_sample_reference, 1 },
    { "deon_sample_reference_quality", test_sample_reference_quality, 0 },
    { 0 },
};

/* Spectral evaluation (docs/spectral.md): CBTB16 at k wavelengths per sample against the RGB
 * kernels at the same absorptions (bit for bit), against the double reference at 16 wavelengths on
 * every ISA, its sampler's pdf, weights and unbiasedness, and the calls' refusals and invalid samples. */
#include <string.h>

#include "sampling.h"

enum { N = 512, K = HB_WAVELENGTHS_MAX };

static float ti[N], pi[N], to[N], po[N], h[N], sigma[2 * K][N], f[K][N], g[K][N], pdf[N], pdf2[N];

/* A plan of the model (CBTB16 or dFH11) of the melanin (or, with eumelanin 0, of a grey sigma_a grey). */
static hb_plan *model_plan(hb_test_ctx *t, hb_model model, double eumelanin, double grey, double beta_n,
                           hb_quality quality, hb_isa isa)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = model;
    o.quality = quality;
    o.isa = isa;
    m.beta_m = 0.3;
    m.beta_n = beta_n;
    m.alpha = 0.035;
    m.eumelanin = eumelanin;
    m.sigma_a[0] = m.sigma_a[1] = m.sigma_a[2] = grey;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "plan: %s", err.message);
    return plan;
}

static hb_plan *absorbing_plan(hb_test_ctx *t, double eumelanin, double grey, double beta_n, hb_quality quality,
                               hb_isa isa)
{
    return model_plan(t, HB_MODEL_CHIANG, eumelanin, grey, beta_n, quality, isa);
}

static hb_plan *spectral_plan(hb_test_ctx *t, double eumelanin, double beta_n, hb_quality quality, hb_isa isa)
{
    return absorbing_plan(t, eumelanin, 0.0, beta_n, quality, isa);
}

static const char *model_name(hb_model model) { return model == HB_MODEL_DEON ? "dFH11" : "CBTB16"; }

/* A plan of the model's default material with absorption sigma_a alone, on the test's ISA. */
static hb_plan *default_plan(hb_test_ctx *t, hb_model model, const double sigma_a[3], hb_quality quality)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = model, o.isa = t->isa, o.quality = quality;
    m.eumelanin = 0.0;
    memcpy(m.sigma_a, sigma_a, sizeof m.sigma_a);
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s", err.message);
    return plan;
}

static void random_directions(hb_test_ctx *t)
{
    for (int k = 0; k < N; k++) {
        ti[k] = (float)hb_test_range(t, -1.5707, 1.5707), to[k] = (float)hb_test_range(t, -1.5707, 1.5707);
        pi[k] = (float)hb_test_range(t, -M_PI, M_PI), po[k] = (float)hb_test_range(t, -M_PI, M_PI);
        h[k] = (float)hb_test_range(t, -1.0, 1.0);
        if (k % 16 == 0) /* the poles and the fibre's edges */
            ti[k] = 1.5707964f, to[k] = -1.5707964f, h[k] = k % 32 ? 1.0f : -1.0f;
    }
}

/* The largest |f - ref| / peak over k planes of n samples: the difference as a share of the peak. */
static double peak_share(float (*got)[N], float (*want)[N], int k, int n)
{
    double peak = 0.0, worst = 0.0;
    for (int j = 0; j < k; j++)
        for (int s = 0; s < n; s++)
            peak = fmax(peak, fabs(want[j][s])), worst = fmax(worst, fabs(got[j][s] - want[j][s]));
    return worst / peak;
}

/* The largest |f - ref| / max(|ref|, 1e-3 peak) over k planes of n samples (docs/conventions.md). */
static double planes_error(float (*got)[N], float (*want)[N], int k, int n)
{
    double peak = 0.0, worst = 0.0;
    for (int j = 0; j < k; j++)
        for (int s = 0; s < n; s++)
            peak = fmax(peak, fabs(want[j][s]));
    for (int j = 0; j < k; j++)
        for (int s = 0; s < n; s++)
            worst = fmax(worst, fabs(got[j][s] - want[j][s]) / fmax(fabs(want[j][s]), 1e-3 * peak));
    return worst;
}

static float *const *planes(float (*p)[N], float **out, int k)
{
    for (int j = 0; j < k; j++)
        out[j] = p[j];
    return out;
}

/* Three wavelengths at the plan's own RGB absorptions (floats exactly) give what the RGB calls give, bit for bit, and
 * six (RGB twice) give it twice: the residual's shared division runs per three channels; calls of one
 * sample too; and dFH11's three wavelengths its RGB f. */
static void test_spectral_rgb_bits(hb_test_ctx *t)
{
    static const double rgb[3] = { 0.375, 0.75, 1.5 }; /* floats exactly, as a plan's sigma_a is double */
    hb_plan *plan = default_plan(t, HB_MODEL_CHIANG, rgb, HB_QUALITY_BALANCED);
    if (!plan)
        return;
    random_directions(t);
    for (int j = 0; j < 6; j++)
        for (int s = 0; s < N; s++)
            sigma[j][s] = (float)rgb[j % 3];
    float *fp[K], *sp[2 * K];
    hb_spectral_absorption six = { 6, (const float *const *)planes(sigma, sp, 6) };
    hb_spectral_absorption three = { 3, six.sigma_a };
    hb_near_soa near = { ti, pi, to, po, h };
    hb_angles_soa angles = { ti, pi, to, po };
    hb_rgb_soa out = { g[0], g[1], g[2] };
    int mismatched = 0;
    for (int pass = 0; pass < 2; pass++) { /* near field, far field */
        if (pass == 0) {
            hb_eval_near(plan, N, near, out, NULL);
            CHECK(t, hb_eval_near_spectral(plan, N, near, six, planes(f, fp, 6), NULL) == HB_OK, "%s",
                  hb_last_error()->message);
        } else {
            hb_eval_angles(plan, N, angles, out, NULL);
            CHECK(t, hb_eval_angles_spectral(plan, N, angles, six, planes(f, fp, 6), NULL) == HB_OK, "%s",
                  hb_last_error()->message);
        }
        for (int j = 0; j < 6; j++)
            mismatched += memcmp(f[j], g[j % 3], sizeof f[j]) != 0;
    }
    hb_pdf_near(plan, N, near, pdf, NULL);
    hb_pdf_near_spectral(plan, N, near, three, pdf2, NULL);
    mismatched += memcmp(pdf, pdf2, sizeof pdf) != 0;
    /* calls of one sample, a path tracer's per hit (their own path: the terms across the lanes) */
    for (int k = 0; k < 64; k++) {
        float one[3], spectral[3];
        hb_near_soa at = { ti + k, pi + k, to + k, po + k, h + k };
        hb_eval_near(plan, 1, at, (hb_rgb_soa){ &one[0], &one[1], &one[2] }, NULL);
        hb_spectral_absorption a = { 3, (const float *const[]){ sigma[0] + k, sigma[1] + k, sigma[2] + k } };
        hb_eval_near_spectral(plan, 1, at, a, (float *const[]){ &spectral[0], &spectral[1], &spectral[2] }, NULL);
        mismatched += memcmp(one, spectral, sizeof one) != 0;
    }
    CHECK(t, mismatched == 0, "%d planes differ from the RGB calls' bits", mismatched);
    hb_plan_destroy(plan);
    /* dFH11's spectral kernels: the fused sum of its RGB f */
    plan = default_plan(t, HB_MODEL_DEON, rgb, HB_QUALITY_BALANCED);
    if (!plan)
        return;
    hb_eval_angles(plan, N, angles, out, NULL);
    CHECK(t, hb_eval_angles_spectral(plan, N, angles, three, planes(f, fp, 3), NULL) == HB_OK, "%s",
          hb_last_error()->message);
    int deon_mismatched = 0;
    for (int j = 0; j < 3; j++)
        deon_mismatched += memcmp(f[j], g[j], sizeof f[j]) != 0;
    CHECK(t, deon_mismatched == 0, "dFH11: %d planes differ from the RGB call's bits", deon_mismatched);
    hb_plan_destroy(plan);
}

/* 16 wavelengths from 380 to 780 nm (two calls of 8) of a blond and a brown fibre at melanin's
 * spectral absorption, CBTB16 and dFH11: the kernels against the reference plan's double path, near
 * field and pdf within 1e-5 in the accuracy metric (measured: 5e-6, float M_p and the float azimuth's
 * rounding, as for RGB), the near field's largest difference within 2.5e-6 of the peak itself
 * (measured: 1.7e-6 CBTB16 brown, 8.2e-7 blond, 4.3e-7 dFH11), and far field within the quality's target; 4 and 1
 * wavelengths agree with 8. */
static void test_spectral_reference(hb_test_ctx *t)
{
    static const struct { hb_model model; double eumelanin; } cases[] = {
        { HB_MODEL_CHIANG, 0.3 }, { HB_MODEL_CHIANG, 1.3 }, { HB_MODEL_DEON, 0.3 }, { HB_MODEL_DEON, 1.3 } };
    int n = t->quick ? N / 4 : N;
    for (int mc = 0; mc < 4; mc++) {
        hb_model model = cases[mc].model;
        int n_far = model == HB_MODEL_DEON ? 16 : t->quick ? 64 : N; /* dFH11's reference converges N_p per sample */
        hb_plan *plan = model_plan(t, model, cases[mc].eumelanin, 0.0, 0.3, HB_QUALITY_BALANCED, t->isa);
        hb_plan *reference = model_plan(t, model, cases[mc].eumelanin, 0.0, 0.3, HB_QUALITY_REFERENCE, HB_ISA_AUTO);
        if (!plan || !reference)
            return;
        random_directions(t);
        double near = 0.0, far = 0.0, pdf_error = 0.0, narrow = 0.0, share = 0.0;
        for (int half = 0; half < 2; half++) {
            for (int j = 0; j < K; j++) {
                double lambda = 380.0 + 400.0 * (half * K + j) / 15.0, s;
                hb_melanin_absorption_spectral(cases[mc].eumelanin, 0.0, lambda, &s);
                for (int k = 0; k < N; k++)
                    sigma[j][k] = (float)(s * (1.0 + 0.2 * (k % 5))); /* per-strand variation */
            }
            float *fp[K], *gp[K], *sp[K];
            hb_spectral_absorption a = { K, (const float *const *)planes(sigma, sp, K) };
            hb_near_soa in = { ti, pi, to, po, h };
            hb_eval_report report;
            CHECK(t, hb_eval_near_spectral(plan, (size_t)n, in, a, planes(f, fp, K), &report) == HB_OK && !report.invalid,
                  "near: %s", hb_last_error()->message);
            CHECK(t, hb_eval_near_spectral(reference, (size_t)n, in, a, planes(g, gp, K), NULL) == HB_OK, "%s",
                  hb_last_error()->message);
            near = fmax(near, planes_error(f, g, K, n));
            share = fmax(share, peak_share(f, g, K, n));
            hb_pdf_near_spectral(plan, (size_t)n, in, a, pdf, NULL);
            hb_pdf_near_spectral(reference, (size_t)n, in, a, pdf2, NULL);
            pdf_error = fmax(pdf_error, planes_error(&pdf, &pdf2, 1, n));
            /* fewer wavelengths: the unrolled four and one alone, against the first planes of eight */
            static float f4[K][N];
            hb_eval_near_spectral(plan, (size_t)n, in, (hb_spectral_absorption){ 4, a.sigma_a }, planes(f4, fp, 4), NULL);
            narrow = fmax(narrow, planes_error(f4, f, 4, n));
            hb_eval_near_spectral(plan, (size_t)n, in, (hb_spectral_absorption){ 1, a.sigma_a + 5 }, planes(f4, fp, 1), NULL);
            narrow = fmax(narrow, planes_error(f4, f + 5, 1, n));
            hb_angles_soa angles = { ti, pi, to, po };
            hb_eval_angles_spectral(plan, (size_t)n_far, angles, a, planes(f, fp, K), NULL);
            hb_eval_angles_spectral(reference, (size_t)n_far, angles, a, planes(g, gp, K), NULL);
            far = fmax(far, planes_error(f, g, K, n_far));
        }
        hb_test_note(t, "%s, eumelanin %.1f, 16 wavelengths: near field %.2e (%.2e of the peak itself), its pdf %.2e, "
                        "far field %.2e; 4 and 1 wavelengths against 8: %.2e",
                     model_name(model), cases[mc].eumelanin, near, share, pdf_error, far, narrow);
        CHECK(t, near <= 1e-5, "%s: near field off the reference by %.3g", model_name(model), near);
        CHECK(t, share <= 2.5e-6, "%s: near field off the reference by %.3g of the peak", model_name(model), share);
        CHECK(t, pdf_error <= 1e-5, "%s: pdf off the reference by %.3g", model_name(model), pdf_error);
        CHECK(t, far <= 1e-3, "%s: far field off the reference by %.3g (balanced: 1e-3)", model_name(model), far);
        CHECK(t, narrow <= 1e-6, "%s: fewer wavelengths differ by %.3g", model_name(model), narrow);
        hb_plan_destroy(plan);
        hb_plan_destroy(reference);
    }
}

/* The sampler at 4 wavelengths, CBTB16's and dFH11's: the sampled pdf is hb_pdf_near_spectral's at the
 * sampled direction bit for bit, the weights are f / pdf; with grey absorption the pdf is the RGB
 * sampler's; and each wavelength's mean weight (the fibre's albedo at w_o and h) equals the RGB
 * sampler's for a plan of that absorption within 4 standard errors of the difference. */
static void spectral_sampling_of(hb_test_ctx *t, hb_model model)
{
    enum { S = 4096, M = 40000 };
    int m_samples = t->quick ? M / 4 : M;
    static float so[S], sph[S], sh[S], u[HB_SAMPLE_DIMENSIONS][S], sti[S], spi[S], sw[K][S], sf[K][S], p2[S];
    hb_plan *plan = model_plan(t, model, 0.3, 0.0, 0.3, HB_QUALITY_BALANCED, t->isa);
    if (!plan)
        return;
    float *streams[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        streams[d] = u[d];
    hb_uniforms(hb_test_next_seed(t), 0, S, 4, streams);
    static const double lambda[4] = { 450.0, 550.0, 650.0, 700.0 };
    static float sa[4][S];
    for (int j = 0; j < 4; j++) {
        double s;
        hb_melanin_absorption_spectral(0.3, 0.0, lambda[j], &s);
        for (int k = 0; k < S; k++)
            sa[j][k] = (float)s;
    }
    for (int k = 0; k < S; k++) {
        so[k] = (float)hb_test_range(t, -1.5707, 1.5707), sph[k] = (float)hb_test_range(t, -M_PI, M_PI);
        sh[k] = (float)hb_test_range(t, -1.0, 1.0);
    }
    hb_spectral_absorption a = { 4, (const float *const[]){ sa[0], sa[1], sa[2], sa[3] } };
    hb_sample_near_in in = { so, sph, sh, (const float *const[]){ u[0], u[1], u[2], u[3] } };
    hb_sample_spectral_out out = { sti, spi, p2, (float *const[]){ sw[0], sw[1], sw[2], sw[3] } };
    hb_eval_report report;
    CHECK(t, hb_sample_near_spectral(plan, S, &in, a, &out, &report) == HB_OK && !report.invalid, "%s",
          hb_last_error()->message);
    hb_near_soa at = { sti, spi, so, sph, sh };
    static float pdf_at[S];
    hb_pdf_near_spectral(plan, S, at, a, pdf_at, NULL);
    hb_eval_near_spectral(plan, S, at, a, (float *const[]){ sf[0], sf[1], sf[2], sf[3] }, NULL);
    int pdf_differs = 0, bad = 0;
    double worst_weight = 0.0;
    for (int k = 0; k < S; k++) {
        pdf_differs += pdf_at[k] != p2[k];
        for (int j = 0; j < 4; j++) {
            bad += !(isfinite(sw[j][k]) && sw[j][k] >= 0.0f);
            if (p2[k] > 0.0f)
                worst_weight = fmax(worst_weight, fabs(sw[j][k] - sf[j][k] / p2[k]) / fmax(sw[j][k], 1e-30f));
        }
    }
    CHECK(t, pdf_differs == 0 && bad == 0, "%s: %d pdfs off hb_pdf_near_spectral, %d weights not finite",
          model_name(model), pdf_differs, bad);
    CHECK(t, worst_weight <= 1e-5, "%s: weights differ from f / pdf by %.3g", model_name(model), worst_weight);
    /* grey absorption: the lobe probabilities are the RGB sampler's */
    hb_plan *grey = model_plan(t, model, 0.0, 0.4, 0.3, HB_QUALITY_BALANCED, t->isa);
    if (!grey)
        return;
    for (int k = 0; k < S; k++)
        sa[0][k] = sa[1][k] = sa[2][k] = sa[3][k] = 0.4f;
    hb_pdf_near(grey, S, at, pdf_at, NULL);
    hb_pdf_near_spectral(grey, S, at, a, p2, NULL);
    double grey_pdf = 0.0;
    for (int k = 0; k < S; k++)
        grey_pdf = fmax(grey_pdf, fabs(p2[k] - pdf_at[k]) / fmax(pdf_at[k], 1e-30f));
    CHECK(t, grey_pdf <= 1e-6, "%s, grey absorption: pdf %.3g off the RGB sampler's", model_name(model), grey_pdf);
    hb_plan_destroy(grey);
    /* unbiasedness at one w_o and h, each wavelength against an RGB plan of its absorption */
    static float mo[M], mp[M], mh[M], mu[4][M], mti[M], mpi[M], mpdf[M], mw[4][M], rw[3][M];
    double s_of[4];
    for (int j = 0; j < 4; j++)
        hb_melanin_absorption_spectral(0.3, 0.0, lambda[j], &s_of[j]);
    static float ma[4][M];
    for (int k = 0; k < M; k++) {
        mo[k] = 0.4f, mp[k] = 0.3f, mh[k] = 0.35f;
        for (int j = 0; j < 4; j++)
            ma[j][k] = (float)s_of[j];
    }
    float *mstreams[4] = { mu[0], mu[1], mu[2], mu[3] };
    hb_uniforms(hb_test_next_seed(t), 0, (size_t)m_samples, 4, mstreams);
    hb_sample_near_in min = { mo, mp, mh, (const float *const *)mstreams };
    hb_sample_near_spectral(plan, (size_t)m_samples, &min, (hb_spectral_absorption){ 4, (const float *const[]){ ma[0], ma[1], ma[2], ma[3] } },
                            &(hb_sample_spectral_out){ mti, mpi, mpdf, (float *const[]){ mw[0], mw[1], mw[2], mw[3] } },
                            NULL);
    double worst_z = 0.0;
    for (int j = 0; j < 4; j++) {
        hb_plan *rgb = model_plan(t, model, 0.0, s_of[j], 0.3, HB_QUALITY_BALANCED, t->isa);
        if (!rgb)
            break;
        float *rstreams[4] = { mu[0], mu[1], mu[2], mu[3] };
        hb_uniforms(hb_test_next_seed(t), 0, (size_t)m_samples, 4, rstreams); /* independent numbers */
        hb_sample_near(rgb, (size_t)m_samples, &(hb_sample_near_in){ mo, mp, mh, (const float *const *)rstreams },
                       &(hb_sample_out){ mti, mpi, mpdf, { rw[0], rw[1], rw[2] } }, NULL);
        double sum[2] = { 0.0 }, sum2[2] = { 0.0 };
        for (int k = 0; k < m_samples; k++) {
            sum[0] += mw[j][k], sum2[0] += (double)mw[j][k] * mw[j][k];
            sum[1] += rw[0][k], sum2[1] += (double)rw[0][k] * rw[0][k];
        }
        double mean[2], var[2];
        for (int e = 0; e < 2; e++)
            mean[e] = sum[e] / m_samples, var[e] = (sum2[e] / m_samples - mean[e] * mean[e]) / (m_samples - 1);
        double z = fabs(mean[0] - mean[1]) / sqrt(var[0] + var[1]);
        worst_z = fmax(worst_z, z);
        hb_test_note(t, "%s, %.0f nm: spectral sampler's mean weight %.5f, RGB sampler's %.5f (z %.2f)",
                     model_name(model), lambda[j], mean[0], mean[1], z);
        hb_plan_destroy(rgb);
    }
    CHECK(t, worst_z <= 4.0, "%s: a wavelength's mean weight is %.2f standard errors off", model_name(model), worst_z);
    hb_plan_destroy(plan);
}

static void test_spectral_sampling(hb_test_ctx *t)
{
    spectral_sampling_of(t, HB_MODEL_CHIANG);
    spectral_sampling_of(t, HB_MODEL_DEON);
}

/* The samplers of CBTB16 and dFH11 at 4 wavelengths (a blond fibre's melanin at 450, 550, 650 and 700
 * nm) by chi-square against hb_pdf_near_spectral's integrals over equal-area cells, which sum to 1
 * within 2e-3. */
static void spectral_chi_square_of(hb_test_ctx *t, hb_model model)
{
    enum { NT = 24, NP = 48, GL = 6 };
    static const struct { double theta_o, h; } cases[] = { { 0.5, 0.2 }, { -1.2, -0.9 }, { 0.1, 0.95 } };
    static double prob[NT * NP];
    static const double lambda[4] = { 450.0, 550.0, 650.0, 700.0 };
    hb_test_wavelengths w = { 4, { 0 } };
    for (int j = 0; j < 4; j++) {
        double s;
        hb_melanin_absorption_spectral(0.3, 0.1, lambda[j], &s);
        w.sigma_a[j] = (float)s;
    }
    hb_plan *plan = model_plan(t, model, 0.3, 0.0, 0.3, HB_QUALITY_BALANCED, HB_ISA_AUTO);
    if (!plan)
        return;
    size_t n = t->quick ? 20000 : HB_TEST_MAX_SAMPLES;
    hb_sample_buffers *b = &hb_samples;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        if (t->quick && c == 2)
            break;
        double integral = hb_test_cell_integrals_spectral(plan, &w, cases[c].theta_o, 0.3, cases[c].h, NT, NP, 1, GL, prob);
        unsigned long long seed = hb_test_next_seed(t);
        float *u[4] = { b->u[0], b->u[1], b->u[2], b->u[3] };
        hb_uniforms(seed, 0, n, 4, u);
        static float sa[4][HB_TEST_MAX_SAMPLES], weight[4][HB_TEST_MAX_SAMPLES];
        for (size_t k = 0; k < n; k++) {
            b->to[k] = (float)cases[c].theta_o, b->po[k] = 0.3f, b->h[k] = (float)cases[c].h;
            for (int j = 0; j < 4; j++)
                sa[j][k] = w.sigma_a[j];
        }
        hb_eval_report report;
        hb_sample_near_in in = { b->to, b->po, b->h, (const float *const *)u };
        hb_spectral_absorption a = { 4, (const float *const[]){ sa[0], sa[1], sa[2], sa[3] } };
        hb_sample_spectral_out out = { b->ti, b->pi, b->pdf, (float *const[]){ weight[0], weight[1], weight[2], weight[3] } };
        CHECK(t, hb_sample_near_spectral(plan, n, &in, a, &out, &report) == HB_OK && !report.invalid, "%s",
              hb_last_error()->message);
        double chi2;
        int cells;
        double p_value = hb_test_chi_square(n, prob, integral, NT, NP, &chi2, &cells);
        hb_test_note(t, "%s, theta_o %g, h %g (seed %llu): integral of pdf %.6f, chi2 %.1f over %d cells, p = %.3f",
                     model_name(model), cases[c].theta_o, cases[c].h, seed, integral, chi2, cells, p_value);
        CHECK(t, fabs(integral - 1.0) <= 2e-3, "%s, case %zu: pdf integrates to %.6f", model_name(model), c, integral);
        CHECK(t, p_value >= 1e-3, "%s, case %zu: chi-square p-value %.2e below the 1e-3 significance",
              model_name(model), c, p_value);
    }
    hb_plan_destroy(plan);
}

static void test_spectral_chi_square(hb_test_ctx *t)
{
    spectral_chi_square_of(t, HB_MODEL_CHIANG);
    spectral_chi_square_of(t, HB_MODEL_DEON);
}

/* dFH11's far field (its spectral kernels), its near field and MJC03's far field (their per-sample
 * absorption calls, three wavelengths a call): f at 16 wavelengths (k = 8, then 5 and 3, whose last
 * groups of three are partial; the quick tier 5 and 3) against a reference plan of each wavelength's
 * absorption in every channel, within the balanced quality's target 1e-3 of the peak. */
static void test_spectral_other_models(hb_test_ctx *t)
{
    static const hb_model models[] = { HB_MODEL_DEON, HB_MODEL_DEON, HB_MODEL_MARSCHNER };
    static const int near_field[] = { 0, 1, 0 };
    static const int counts[] = { 8, 5, 3 }; /* the quick tier: the last two, 8 wavelengths */
    int n = t->quick ? 32 : 128, total = t->quick ? 8 : 16;
    for (int mc = 0; mc < 3; mc++) {
        static const double none[3] = { 0.0, 0.0, 0.0 };
        hb_plan *plan = default_plan(t, models[mc], none, HB_QUALITY_BALANCED);
        if (!plan)
            return;
        random_directions(t);
        double worst = 0.0;
        for (int first = 0, call = t->quick; first < total; first += counts[call++]) {
            int k = counts[call];
            float *fp[K], *sp[K];
            for (int j = 0; j < k; j++) {
                double s;
                hb_melanin_absorption_spectral(0.6, 0.1, 380.0 + 400.0 * (first + j) / 15.0, &s);
                for (int q = 0; q < n; q++)
                    sigma[j][q] = (float)s;
                double grey[3] = { sigma[j][0], sigma[j][0], sigma[j][0] };
                hb_plan *reference = default_plan(t, models[mc], grey, HB_QUALITY_REFERENCE);
                if (!reference)
                    return;
                hb_rgb_soa rgb = { g[j], g[K - 1], g[K - 1] };
                if (near_field[mc])
                    hb_eval_near(reference, (size_t)n, (hb_near_soa){ ti, pi, to, po, h }, rgb, NULL);
                else
                    hb_eval_angles(reference, (size_t)n, (hb_angles_soa){ ti, pi, to, po }, rgb, NULL);
                hb_plan_destroy(reference);
            }
            hb_spectral_absorption a = { k, (const float *const *)planes(sigma, sp, k) };
            hb_eval_report report;
            hb_status st = near_field[mc]
                               ? hb_eval_near_spectral(plan, (size_t)n, (hb_near_soa){ ti, pi, to, po, h }, a,
                                                       planes(f, fp, k), &report)
                               : hb_eval_angles_spectral(plan, (size_t)n, (hb_angles_soa){ ti, pi, to, po }, a,
                                                         planes(f, fp, k), &report);
            CHECK(t, st == HB_OK && report.invalid == 0, "%s", hb_last_error()->message);
            worst = fmax(worst, planes_error(f, g, k, n));
        }
        hb_test_note(t, "%s %s: %d wavelengths against reference plans: %.2e of the peak",
                     models[mc] == HB_MODEL_DEON ? "dFH11" : "MJC03", near_field[mc] ? "near field" : "far field",
                     total, worst);
        CHECK(t, worst <= 1e-3, "off the reference by %.3g", worst);
        hb_plan_destroy(plan);
    }
}

/* A reference plan's spectral f (its reference at k absorptions) is its RGB reference at each
 * wavelength's absorption: dFH11 far and near field, MJC03 far field; 8 wavelengths against a
 * reference plan of each wavelength's absorption in every channel, float for float. */
static void test_spectral_reference_plans(hb_test_ctx *t)
{
    static const double none[3] = { 0.0, 0.0, 0.0 };
    static const struct { hb_model model; int near; const char *name; } cases[] = {
        { HB_MODEL_DEON, 0, "dFH11 far" }, { HB_MODEL_DEON, 1, "dFH11 near" }, { HB_MODEL_MARSCHNER, 0, "MJC03 far" } };
    int n = t->quick ? 8 : 32;
    random_directions(t);
    for (int c = 0; c < 3; c++) {
        hb_plan *plan = default_plan(t, cases[c].model, none, HB_QUALITY_REFERENCE);
        if (!plan)
            return;
        int near = cases[c].near;
        float *fp[K], *sp[K];
        long differ = 0;
        for (int j = 0; j < K; j++) {
            double s;
            hb_melanin_absorption_spectral(0.6, 0.1, 380.0 + 400.0 * j / (K - 1), &s);
            for (int q = 0; q < n; q++)
                sigma[j][q] = (float)s;
            double grey[3] = { sigma[j][0], sigma[j][0], sigma[j][0] };
            hb_plan *reference = default_plan(t, cases[c].model, grey, HB_QUALITY_REFERENCE);
            if (!reference)
                return;
            hb_rgb_soa rgb = { g[j], g[K - 1], g[K - 1] };
            if (near)
                hb_eval_near(reference, (size_t)n, (hb_near_soa){ ti, pi, to, po, h }, rgb, NULL);
            else
                hb_eval_angles(reference, (size_t)n, (hb_angles_soa){ ti, pi, to, po }, rgb, NULL);
            hb_plan_destroy(reference);
        }
        hb_spectral_absorption a = { K, (const float *const *)planes(sigma, sp, K) };
        hb_status st = near ? hb_eval_near_spectral(plan, (size_t)n, (hb_near_soa){ ti, pi, to, po, h }, a,
                                                    planes(f, fp, K), NULL)
                            : hb_eval_angles_spectral(plan, (size_t)n, (hb_angles_soa){ ti, pi, to, po }, a,
                                                      planes(f, fp, K), NULL);
        CHECK(t, st == HB_OK, "%s", hb_last_error()->message);
        for (int j = 0; j < K; j++) /* grey: plane K - 1 held every reference's g and b, and is the last's */
            for (int q = 0; q < n; q++)
                differ += f[j][q] != g[j][q];
        CHECK(t, differ == 0, "%s: %ld values differ from the RGB reference's", cases[c].name, differ);
        hb_plan_destroy(plan);
    }
}

/* The reference plans' spectral samplers (double) against the kernels', CBTB16's and dFH11's, from the
 * same numbers at 4 wavelengths of a brown fibre: the same direction within 1e-4 radians but where a
 * number falls on a lobe's edge (at most 1% of the samples), and there the same weights within 1e-5
 * (measured: 4.8e-6, as the near field's f and pdf against the reference). */
static void test_spectral_reference_sampler(hb_test_ctx *t)
{
    enum { S = 512 };
    static float so[S], sph[S], sh[S], u[4][S], sa[4][S], ti2[2][S], pi2[2][S], p2[2][S], w2[2][4][S];
    static const hb_model models[] = { HB_MODEL_CHIANG, HB_MODEL_DEON };
    for (int k = 0; k < S; k++) {
        so[k] = (float)hb_test_range(t, -1.5, 1.5), sph[k] = (float)hb_test_range(t, -M_PI, M_PI);
        sh[k] = (float)hb_test_range(t, -1.0, 1.0);
        for (int j = 0; j < 4; j++) {
            double s;
            hb_melanin_absorption_spectral(1.3, 0.2, 450.0 + 80.0 * j, &s);
            sa[j][k] = (float)s;
        }
    }
    float *streams[4] = { u[0], u[1], u[2], u[3] };
    hb_uniforms(hb_test_next_seed(t), 0, S, 4, streams);
    for (int mc = 0; mc < 2; mc++) {
        for (int r = 0; r < 2; r++) {
            hb_plan *plan = model_plan(t, models[mc], 1.3, 0.0, 0.3, r ? HB_QUALITY_REFERENCE : HB_QUALITY_BALANCED,
                                       t->isa);
            if (!plan)
                return;
            hb_sample_near_in in = { so, sph, sh, (const float *const *)streams };
            hb_spectral_absorption a = { 4, (const float *const[]){ sa[0], sa[1], sa[2], sa[3] } };
            hb_sample_spectral_out out = { ti2[r], pi2[r], p2[r], (float *const[]){ w2[r][0], w2[r][1], w2[r][2], w2[r][3] } };
            hb_eval_report report;
            CHECK(t, hb_sample_near_spectral(plan, S, &in, a, &out, &report) == HB_OK && !report.invalid, "%s",
                  hb_last_error()->message);
            hb_plan_destroy(plan);
        }
        int apart = 0;
        double weight = 0.0;
        for (int k = 0; k < S; k++) {
            double d = fmax(fabs(ti2[0][k] - ti2[1][k]), fabs(remainder(pi2[0][k] - pi2[1][k], 2.0 * M_PI)));
            if (d > 1e-4) {
                apart++;
                continue;
            }
            for (int j = 0; j < 4; j++)
                weight = fmax(weight, fabs(w2[0][j][k] - w2[1][j][k]) / fmax(fabs(w2[1][j][k]), 1e-3));
        }
        hb_test_note(t, "%s: %d of %d directions apart from the reference sampler's, weights within %.2e",
                     model_name(models[mc]), apart, S, weight);
        CHECK(t, apart <= S / 100, "%s: %d directions apart from the reference sampler's", model_name(models[mc]),
              apart);
        CHECK(t, weight <= 1e-5, "%s: weights off the reference sampler's by %.3g", model_name(models[mc]), weight);
    }
}

/* Hard cases at 8 wavelengths, CBTB16 and dFH11, on every ISA: the smoothest and roughest fibres, eta
 * near 1 and 10, poles, h = +-1, u at 0 and just below 1, absorptions 0, 1e-30, 1e4 and 1e30 among the
 * wavelengths: the sampler's directions, pdfs and weights and f at the sampled directions finite and
 * >= 0, and the same samples invalid as for the RGB sampler. */
static void test_spectral_hard_cases(hb_test_ctx *t)
{
    enum { S = 64 };
    static const double roughness[] = { 0.02, 0.3, 1.0 }, eta[] = { 1.0001, 1.55, 10.0 };
    static const float absorption[] = { 0.0f, 1e-30f, 1e4f, 1e30f, 0.5f };
    static const hb_model models[] = { HB_MODEL_CHIANG, HB_MODEL_DEON };
    static float so[S], sph[S], sh[S], u[4][S], sa[K][S], sti[S], spi[S], p2[S], w2[K][S], sf[K][S], rw[3][S];
    for (int k = 0; k < S; k++) {
        so[k] = k % 4 == 0 ? 1.5707964f : k % 4 == 1 ? -1.5707964f : (float)(0.05 * k - 1.5);
        sph[k] = (float)(0.3 * k - 3.0), sh[k] = k % 3 == 0 ? 1.0f : k % 3 == 1 ? -1.0f : (float)(0.03 * k - 0.9);
        for (int d = 0; d < 4; d++)
            u[d][k] = k % 5 == 0 ? 0.0f : k % 5 == 1 ? 0.99999994f : (float)((7 * k + 13 * d) % 97) / 97.0f;
        for (int j = 0; j < K; j++)
            sa[j][k] = absorption[(k + j) % 5];
    }
    const float *sp[K];
    float *wp[K], *fp[K];
    for (int j = 0; j < K; j++)
        sp[j] = sa[j], wp[j] = w2[j], fp[j] = sf[j];
    int bad = 0, counts_differ = 0;
    for (int mc = 0; mc < 2; mc++)
        for (int r = 0; r < 3; r++)
            for (int e = 0; e < 3; e++) {
                hb_material m;
                hb_options o;
                hb_material_default(&m);
                hb_options_default(&o);
                o.model = models[mc], o.isa = t->isa;
                m.beta_m = m.beta_n = roughness[r], m.eta = eta[e];
                hb_plan *plan = NULL;
                hb_error err;
                CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s", err.message);
                if (!plan)
                    return;
                hb_sample_near_in in = { so, sph, sh, (const float *const[]){ u[0], u[1], u[2], u[3] } };
                hb_eval_report spectral, rgb;
                hb_sample_near_spectral(plan, S, &in, (hb_spectral_absorption){ K, sp },
                                        &(hb_sample_spectral_out){ sti, spi, p2, wp }, &spectral);
                hb_eval_near_spectral(plan, S, (hb_near_soa){ sti, spi, so, sph, sh }, (hb_spectral_absorption){ K, sp },
                                      fp, NULL);
                for (int k = 0; k < S; k++) {
                    int ok = isfinite(sti[k]) && isfinite(spi[k]) && isfinite(p2[k]) && p2[k] >= 0.0f;
                    for (int j = 0; j < K; j++)
                        ok = ok && isfinite(w2[j][k]) && w2[j][k] >= 0.0f && isfinite(sf[j][k]) && sf[j][k] >= 0.0f;
                    bad += !ok;
                }
                hb_sample_near(plan, S, &in, &(hb_sample_out){ sti, spi, p2, { rw[0], rw[1], rw[2] } }, &rgb);
                counts_differ += spectral.invalid != rgb.invalid;
                hb_plan_destroy(plan);
            }
    CHECK(t, bad == 0, "%d samples not finite and >= 0", bad);
    CHECK(t, counts_differ == 0, "%d plans count other invalid samples than their RGB sampler", counts_differ);
}

/* Refusals name the problem; an invalid absorption makes an invalid sample with zeros. */
static void test_spectral_api(hb_test_ctx *t)
{
    hb_plan *plan = spectral_plan(t, 1.3, 0.3, HB_QUALITY_FAST, HB_ISA_AUTO);
    if (!plan)
        return;
    float x[4] = { 0.3f, 0.2f, -0.1f, 0.5f }, hh[4] = { 0.1f, 0.2f, 0.3f, 0.4f };
    float s0[4] = { 0.5f, NAN, -1.0f, INFINITY }, out0[4] = { 7.0f, 7.0f, 7.0f, 7.0f };
    hb_near_soa in = { x, x, x, x, hh };
    float *fo[1] = { out0 };
    hb_eval_report report;
    CHECK(t, hb_eval_near_spectral(plan, 4, in, (hb_spectral_absorption){ 1, (const float *const[]){ s0 } }, fo,
                                   &report) == HB_OK && report.invalid == 3 && out0[0] > 0.0f && out0[1] == 0.0f &&
                 out0[2] == 0.0f && out0[3] == 0.0f,
          "invalid absorptions: %zu counted, f %g %g %g %g", report.invalid, out0[0], out0[1], out0[2], out0[3]);
    CHECK(t, hb_eval_near_spectral(plan, 4, in, (hb_spectral_absorption){ 0, (const float *const[]){ s0 } }, fo,
                                   NULL) == HB_ERR_PARAM && strstr(hb_last_error()->message, "wavelengths"),
          "k = 0: %s", hb_last_error()->message);
    CHECK(t, hb_eval_near_spectral(plan, 4, in, (hb_spectral_absorption){ 9, (const float *const[]){ s0 } }, fo,
                                   NULL) == HB_ERR_PARAM,
          "k = 9: %s", hb_last_error()->message);
    CHECK(t, hb_eval_near_spectral(plan, 4, in, (hb_spectral_absorption){ 2, (const float *const[]){ s0, NULL } },
                                   (float *const[]){ out0, out0 }, NULL) == HB_ERR_NULL &&
                 strstr(hb_last_error()->message, "sigma_a[1]"),
          "a NULL plane: %s", hb_last_error()->message);
    hb_plan_destroy(plan);
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s", err.message);
    o.model = HB_MODEL_HUANG;
    hb_plan *huang = NULL;
    CHECK(t, hb_plan_create(&m, &o, &huang, &err) == HB_OK, "%s", err.message);
    CHECK(t, hb_eval_angles_spectral(huang, 4, (hb_angles_soa){ x, x, x, x },
                                     (hb_spectral_absorption){ 1, (const float *const[]){ s0 } }, fo, NULL) ==
                     HB_ERR_UNSUPPORTED &&
                 strstr(hb_last_error()->message, "spectral"),
          "HHH22's f: %s", hb_last_error()->message);
    hb_plan_destroy(huang);
    o.model = HB_MODEL_DEON;
    CHECK(t, hb_pdf_near_spectral(plan, 4, in, (hb_spectral_absorption){ 1, (const float *const[]){ s0 } }, out0,
                                  &report) == HB_OK && report.invalid == 3 && out0[0] > 0.0f && out0[3] == 0.0f,
          "dFH11's pdf, invalid absorptions: %zu counted, %s", report.invalid, hb_last_error()->message);
    hb_plan_destroy(plan);
    /* a plan whose path has no per-sample absorption answers so for an empty batch too */
    o.azimuthal = HB_AZIMUTHAL_TABLE;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s", err.message);
    hb_angles_soa none = { NULL, NULL, NULL, NULL };
    CHECK(t, hb_eval_angles_spectral(plan, 0, none, (hb_spectral_absorption){ 1, NULL }, NULL, NULL) ==
                 HB_ERR_UNSUPPORTED &&
             hb_eval_angles_spectral(plan, 4, (hb_angles_soa){ x, x, x, x },
                                     (hb_spectral_absorption){ 1, (const float *const[]){ s0 } }, fo, NULL) ==
                 HB_ERR_UNSUPPORTED,
          "a dFH11 table plan: %s", hb_last_error()->message);
    o.azimuthal = HB_AZIMUTHAL_QUADRATURE;
    hb_plan_destroy(plan);
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s", err.message);
    CHECK(t, hb_eval_near_spectral(plan, 4, in, (hb_spectral_absorption){ 1, (const float *const[]){ s0 } }, fo,
                                   &report) == HB_OK && report.invalid == 3 && out0[0] > 0.0f && out0[1] == 0.0f,
          "dFH11, invalid absorptions: %zu counted", report.invalid);
    hb_plan_destroy(plan);
}

const hb_test hb_tests_spectral_eval[] = {
    { "spectral_reference_plans", test_spectral_reference_plans, 0 },
    { "spectral_rgb_bits", test_spectral_rgb_bits, 1 },
    { "spectral_reference", test_spectral_reference, 1 },
    { "spectral_sampling", test_spectral_sampling, 1 },
    { "spectral_chi_square", test_spectral_chi_square, 0 },
    { "spectral_reference_sampler", test_spectral_reference_sampler, 1 },
    { "spectral_hard_cases", test_spectral_hard_cases, 1 },
    { "spectral_other_models", test_spectral_other_models, 1 },
    { "spectral_api", test_spectral_api, 0 },
    { NULL, NULL, 0 },
};

/* libFuzzer: arbitrary bytes as material, options and directions. Plan creation either refuses
 * with a message or succeeds, and every valid sample's f must be finite and >= 0; where the plan
 * samples, sampled directions are in range and pdfs and weights finite and >= 0; where it has a
 * near field, the same at offsets h from the bytes (many outside [-1, 1], which must be counted). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hairbsdf.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { MAX_SAMPLES = 16 };

static size_t take(const uint8_t **data, size_t *size, void *out, size_t n)
{
    size_t k = *size < n ? *size : n;
    memset(out, 0, n);
    memcpy(out, *data, k);
    *data += k, *size -= k;
    return k;
}

/* Every valid sample's f finite and >= 0. */
static void check_rgb(float f[3][MAX_SAMPLES], size_t n)
{
    for (int c = 0; c < 3; c++)
        for (size_t k = 0; k < n; k++)
            if (!(isfinite(f[c][k]) && f[c][k] >= 0.0f))
                abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    double params[13];
    uint8_t opts[12];
    uint64_t seed;
    take(&data, &size, params, sizeof params);
    take(&data, &size, opts, sizeof opts);
    take(&data, &size, &seed, sizeof seed);
    m.eta = params[0], m.sigma_a[0] = params[1], m.sigma_a[1] = fabs(params[1]), m.sigma_a[2] = params[2];
    m.beta_m = params[3], m.beta_n = params[4], m.alpha = params[5], m.eumelanin = params[6];
    m.lobe_beta_n[opts[7] & 7] = params[7];
    m.eccentricity = params[8], m.glint_scale = params[9], m.caustic_width = params[10], m.caustic_fade = params[11];
    m.roughness = params[12], m.ndf = (hb_ndf)(opts[8] % 3); /* HHH22; 2 is no NDF and must be refused */
    o.model = (hb_model)(opts[0] % 4);
    o.term = (hb_term)(opts[1] % 3);
    o.quality = (hb_quality)(opts[2] % 5);
    o.i0 = (hb_i0)(opts[3] % 3);
    o.pmax = opts[4] % 9;
    o.lobes = opts[5] & 1 ? 0u : (unsigned)opts[5] << 1;
    o.quadrature_order = opts[6] % 70;
    o.absorption = (hb_absorption)(opts[7] >> 6 & 1);
    o.r_fresnel = (hb_r_fresnel)(opts[7] >> 7);
    o.shadowing = (hb_shadowing)(opts[9] % 3);
    o.r_integration = (hb_r_integration)(opts[10] % 4);
    o.r_panels = opts[10] >> 4 & 1 ? opts[10] >> 2 : 0;
    o.tt_trt = (hb_tt_trt)(opts[11] % 3);
    o.tt_panels = opts[11] >> 2;
    o.seed = seed;
    hb_plan *plan;
    hb_error error;
    if (hb_plan_create(&m, &o, &plan, &error) != HB_OK) {
        if (!error.message[0])
            abort(); /* every refusal must say why */
        return 0;
    }
    float a[4][MAX_SAMPLES], f[3][MAX_SAMPLES];
    size_t n = size / 16 < MAX_SAMPLES ? size / 16 : MAX_SAMPLES;
    if (o.quality == HB_QUALITY_REFERENCE && n > 1)
        n = 1; /* the reference is slow */
    unsigned internal = 1u << HB_LOBE_TT | 1u << HB_LOBE_TRT;
    if (o.model == HB_MODEL_HUANG && (o.quality == HB_QUALITY_REFERENCE || o.tt_trt == HB_TT_TRT_REFERENCE) &&
        (o.lobes == HB_LOBES_DEFAULT || (o.lobes & internal)))
        n = 0; /* HHH22's TT/TRT quadrature takes 2 s a sample: the tests' corpus covers it, not the fuzzer */
    for (size_t k = 0; k < n; k++)
        for (int c = 0; c < 4; c++)
            take(&data, &size, &a[c][k], sizeof(float));
    for (int entry = 0; entry < 2; entry++) {
        hb_eval_report rep;
        if (entry == 0) {
            hb_eval_angles(plan, n, (hb_angles_soa){ a[0], a[1], a[2], a[3] }, (hb_rgb_soa){ f[0], f[1], f[2] }, &rep);
        } else { /* the same numbers as vectors: most are not unit length, which must be counted */
            float z[MAX_SAMPLES];
            for (size_t k = 0; k < n; k++)
                z[k] = a[3][k] * a[0][k];
            hb_eval_vectors(plan, n, (hb_vectors_soa){ a[0], a[1], a[2], a[3], a[1], z }, (hb_rgb_soa){ f[0], f[1], f[2] },
                            &rep);
        }
        if (rep.invalid > n)
            abort();
        check_rgb(f, n);
    }
    if (hb_plan_sample_dimensions(plan) > 0) { /* u from the first two streams (some outside [0, 1]) */
        float u[3][MAX_SAMPLES], ti[MAX_SAMPLES], pi[MAX_SAMPLES], pdf[MAX_SAMPLES];
        for (size_t k = 0; k < n; k++) {
            u[0][k] = a[0][k] - floorf(a[0][k]);
            u[1][k] = a[1][k] - floorf(a[1][k]);
            u[2][k] = a[0][k] * 0.25f;
        }
        hb_eval_report rep;
        /* every dimension a sampler may read (HHH22 with TT/TRT reads 8) */
        hb_sample_in in = { a[2], a[3], (const float *const[]){ u[0], u[1], u[2], a[0], a[1], u[1], u[2], u[0] } };
        if (hb_sample_angles(plan, n, &in, &(hb_sample_out){ ti, pi, pdf, { f[0], f[1], f[2] } }, &rep) != HB_OK)
            abort();
        if (rep.invalid > n)
            abort();
        for (size_t k = 0; k < n; k++) {
            if (!(fabsf(ti[k]) <= 1.5707964f && fabsf(pi[k]) <= 3.1415927f && isfinite(pdf[k]) && pdf[k] >= 0.0f))
                abort();
            for (int c = 0; c < 3; c++)
                if (!(isfinite(f[c][k]) && f[c][k] >= 0.0f))
                    abort();
        }
        hb_pdf_angles(plan, n, (hb_angles_soa){ a[0], a[1], a[2], a[3] }, pdf, &rep);
        for (size_t k = 0; k < n; k++)
            if (!(isfinite(pdf[k]) && pdf[k] >= 0.0f))
                abort();
        /* the vector forms, on the same numbers as vectors (most not unit length: counted) */
        float wi[3][MAX_SAMPLES];
        hb_sample_vectors_in vin = { a[1], a[2], a[3], (const float *const[]){ u[0], u[1], u[2], a[0], a[1], u[1], u[2], u[0] } };
        if (hb_sample_vectors(plan, n, &vin, &(hb_sample_vectors_out){ wi[0], wi[1], wi[2], pdf, { f[0], f[1], f[2] } },
                              &rep) != HB_OK || rep.invalid > n)
            abort();
        for (size_t k = 0; k < n; k++)
            if (!(isfinite(pdf[k]) && pdf[k] >= 0.0f && fabsf(wi[0][k]) <= 1.0f && fabsf(wi[1][k]) <= 1.0f &&
                  fabsf(wi[2][k]) <= 1.0f))
                abort();
        hb_vectors_soa pairs = { a[0], a[1], a[2], a[3], a[1], a[2] };
        if (hb_eval_pdf_vectors(plan, n, pairs, (hb_rgb_soa){ f[0], f[1], f[2] }, pdf, &rep) != HB_OK || rep.invalid > n)
            abort();
        check_rgb(f, n);
        if (hb_eval_pdf_angles(plan, n, (hb_angles_soa){ a[0], a[1], a[2], a[3] }, (hb_rgb_soa){ f[0], f[1], f[2] }, pdf,
                               &rep) != HB_OK || rep.invalid > n)
            abort();
        check_rgb(f, n);
        for (size_t k = 0; k < n; k++)
            if (!(isfinite(pdf[k]) && pdf[k] >= 0.0f))
                abort();
    }
    float h[MAX_SAMPLES], pdf[MAX_SAMPLES], ti[MAX_SAMPLES], pi[MAX_SAMPLES];
    for (size_t k = 0; k < n; k++)
        h[k] = a[1][k] * a[2][k];
    hb_eval_report rep;
    if (hb_eval_near(plan, n, (hb_near_soa){ a[0], a[1], a[2], a[3], h }, (hb_rgb_soa){ f[0], f[1], f[2] }, &rep) ==
        HB_OK) {
        if (rep.invalid > n)
            abort();
        check_rgb(f, n);
        float u[MAX_SAMPLES];
        for (size_t k = 0; k < n; k++)
            u[k] = a[0][k] - floorf(a[0][k]);
        hb_sample_near_in in = { a[2], a[3], h, (const float *const[]){ u, a[1], u, a[0], u, u, u, u } };
        hb_status sampled = hb_sample_near(plan, n, &in, &(hb_sample_out){ ti, pi, pdf, { f[0], f[1], f[2] } }, &rep);
        if (sampled == HB_ERR_UNSUPPORTED && hb_plan_sample_dimensions(plan) == 0) { /* a near field without a sampler */
            hb_plan_destroy(plan);
            return 0;
        }
        if (sampled != HB_OK || rep.invalid > n)
            abort();
        for (size_t k = 0; k < n; k++)
            if (!(fabsf(ti[k]) <= 1.5707964f && fabsf(pi[k]) <= 3.1415927f && isfinite(pdf[k]) && pdf[k] >= 0.0f &&
                  isfinite(f[0][k]) && f[0][k] >= 0.0f))
                abort();
        hb_pdf_near(plan, n, (hb_near_soa){ a[0], a[1], a[2], a[3], h }, pdf, &rep);
        for (size_t k = 0; k < n; k++)
            if (!(isfinite(pdf[k]) && pdf[k] >= 0.0f))
                abort();
    }
    hb_plan_destroy(plan);
    return 0;
}

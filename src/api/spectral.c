/* Public spectral entry points (docs/spectral.md): k wavelengths per sample, each at its own
 * absorption. Argument checks, then the plan's spectral kernels or, for a reference plan, the model's
 * double-precision procedure one sample at a time; for the models without spectral kernels, f by
 * their per-sample absorption calls, three wavelengths at a time. No allocation. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "checks.h"
#include "math/valid.h"
#include "models/interface/model.h"
#include "ref/reference.h"

static void report_invalid(hb_eval_report *report, size_t invalid)
{
    if (report)
        report->invalid = invalid;
}

static int absorbing(const hb_model_ops *ops, int near)
{
    return near ? ops->eval_near_absorption != NULL : ops->eval_absorption != NULL;
}

/* Whether the plan takes the spectral sampler's calls (its pdf): a model with a spectral sampler, in
 * its kernels or, for a reference plan, its reference. */
static int samples_spectral(const hb_plan *plan, const hb_model_ops *ops)
{
    return ops->sample_spectral && (plan->kernels ? ops->spectral != NULL : ops->reference->sample_spectral != NULL);
}

/* Whether the plan takes a spectral f: its spectral kernels where its path has them, else its
 * per-sample absorption calls three wavelengths at a time; for a reference plan, its reference. */
static int evaluates_spectral(const hb_plan *plan, const hb_model_ops *ops, int near)
{
    return plan->kernels ? ops->spectral || absorbing(ops, near)
                         : ops->reference->spectral && (!near || ops->reference->eval_near);
}

/* The plan takes this spectral call (f_only: an evaluation of f, far field or near field by `near`) and
 * k is in range; the absorption planes and `outputs` output planes (named `what`) are there. */
static hb_status spectral_checks(const char *call, const hb_plan *plan, size_t n, hb_spectral_absorption sigma_a,
                                 int f_only, int near, const char *what, int outputs, float *const *out)
{
    if (!plan)
        return hb_fail_null(call, "plan");
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    int takes = f_only ? evaluates_spectral(plan, ops, near) : samples_spectral(plan, ops);
    if (!takes || plan->options.term != HB_TERM_FULL)
        return hb_api_unsupported(call, plan, f_only ? "spectral evaluation" : "spectral sampling");
    if (sigma_a.wavelengths < 1 || sigma_a.wavelengths > HB_WAVELENGTHS_MAX)
        return hb_fail(HB_ERR_PARAM, "%s: sigma_a.wavelengths is %d, not in [1, %d]", call, sigma_a.wavelengths,
                       HB_WAVELENGTHS_MAX);
    if (!n)
        return HB_OK;
    if (!sigma_a.sigma_a)
        return hb_fail_null(call, "sigma_a.sigma_a");
    if (outputs && !out)
        return hb_fail_null(call, what);
    for (int j = 0; j < sigma_a.wavelengths; j++) {
        if (!sigma_a.sigma_a[j])
            return hb_fail(HB_ERR_NULL, "%s: sigma_a.sigma_a[%d] is NULL (%d wavelengths)", call, j,
                           sigma_a.wavelengths);
        if (outputs && !out[j])
            return hb_fail(HB_ERR_NULL, "%s: %s[%d] is NULL (%d wavelengths)", call, what, j, sigma_a.wavelengths);
    }
    return HB_OK;
}

/* Sample k's absorptions in double; 0 when one is NaN, negative or infinite. */
static int absorptions_at(hb_spectral_absorption sigma_a, size_t k, double *out)
{
    int ok = 1;
    for (int j = 0; j < sigma_a.wavelengths; j++) {
        float s = sigma_a.sigma_a[j][k];
        ok = ok && s >= 0.0f && s <= FLT_MAX;
        out[j] = ok ? s : 0.0;
    }
    return ok;
}

/* The reference, one sample at a time: f and the pdf where b asks for them. */
static size_t spectral_ref(const hb_plan *plan, size_t n, const hb_spectral_batch *b, hb_spectral_absorption sigma_a)
{
    size_t invalid = 0;
    for (size_t k = 0; k < n; k++) {
        const hb_near_soa *in = &b->near;
        double absorption[HB_WAVELENGTHS_MAX], f[HB_WAVELENGTHS_MAX] = { 0.0 }, pdf = 0.0;
        double h = in->h ? in->h[k] : NAN;
        int ok = hb_theta_valid(in->theta_i[k]) && hb_theta_valid(in->theta_o[k]) && hb_phi_valid(in->phi_i[k]) &&
                 hb_phi_valid(in->phi_o[k]) && (!in->h || hb_offset_valid(in->h[k]));
        ok = absorptions_at(sigma_a, k, absorption) && ok;
        if (ok)
            plan->reference->spectral(plan, in->theta_i[k], in->phi_i[k], in->theta_o[k], in->phi_o[k], h,
                                      sigma_a.wavelengths, absorption, f, &pdf);
        else
            invalid++;
        for (int j = 0; b->f && j < sigma_a.wavelengths; j++)
            b->f[j][k] = (float)f[j];
        if (b->pdf)
            b->pdf[k] = (float)pdf;
    }
    return invalid;
}

/* f at k wavelengths by a model's per-sample absorption call, the wavelengths three at a time as
 * the RGB channels (a last group of one or two repeats its last wavelength), in chunks of samples
 * whose results pass through the stack; then every plane 0 at each invalid sample, counted once. */
enum { CHUNK = 256 };
static hb_status spectral_by_channels(const hb_plan *plan, size_t n, const hb_near_soa *in,
                                      hb_spectral_absorption sigma_a, float *const *f, size_t *invalid)
{
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    const int k = sigma_a.wavelengths;
    if (!n) { /* the path's own answer for an empty batch: whether it takes a per-sample absorption */
        size_t none;
        hb_absorbing_near near = { *in, { NULL, NULL, NULL } };
        hb_absorbing_batch far = { { .angles = { in->theta_i, in->phi_i, in->theta_o, in->phi_o } }, { NULL, NULL, NULL } };
        *invalid = 0;
        return in->h ? ops->eval_near_absorption(plan, 0, &near, (hb_rgb_soa){ NULL, NULL, NULL }, &none)
                     : ops->eval_absorption(plan, 0, &far, (hb_rgb_soa){ NULL, NULL, NULL }, &none);
    }
    for (size_t first = 0; first < n; first += CHUNK) {
        size_t m = n - first < CHUNK ? n - first : CHUNK, bad;
        hb_near_soa part = { in->theta_i + first, in->phi_i + first, in->theta_o + first, in->phi_o + first,
                             in->h ? in->h + first : NULL };
        for (int group = 0; group < k; group += 3) {
            float out[3][CHUNK];
            const float *s[3];
            for (int c = 0; c < 3; c++)
                s[c] = sigma_a.sigma_a[group + c < k ? group + c : k - 1] + first;
            hb_rgb_soa rgb = { out[0], out[1], out[2] };
            hb_status st;
            if (in->h) {
                hb_absorbing_near b = { part, { s[0], s[1], s[2] } };
                st = ops->eval_near_absorption(plan, m, &b, rgb, &bad);
            } else {
                hb_absorbing_batch b = { { .angles = { part.theta_i, part.phi_i, part.theta_o, part.phi_o } },
                                         { s[0], s[1], s[2] } };
                st = ops->eval_absorption(plan, m, &b, rgb, &bad);
            }
            if (st != HB_OK)
                return st;
            for (int c = 0; c < 3 && group + c < k; c++)
                memcpy(f[group + c] + first, out[c], m * sizeof(float));
        }
    }
    *invalid = 0;
    for (size_t s = 0; s < n; s++) {
        double absorption[HB_WAVELENGTHS_MAX];
        int ok = hb_theta_valid(in->theta_i[s]) && hb_theta_valid(in->theta_o[s]) && hb_phi_valid(in->phi_i[s]) &&
                 hb_phi_valid(in->phi_o[s]) && (!in->h || hb_offset_valid(in->h[s]));
        if (absorptions_at(sigma_a, s, absorption) && ok)
            continue;
        ++*invalid;
        for (int j = 0; j < k; j++)
            f[j][s] = 0.0f;
    }
    return HB_OK;
}

static hb_status spectral_batch(const char *call, const hb_plan *plan, size_t n, hb_near_soa in,
                                hb_spectral_absorption sigma_a, float *const *f, float *pdf, hb_eval_report *report)
{
    hb_status st = spectral_checks(call, plan, n, sigma_a, !pdf, in.h != NULL, "f", f != NULL || !pdf, f);
    if (st == HB_OK && in.h)
        st = hb_api_near_present(call, n, &in);
    if (st == HB_OK && !in.h) {
        hb_angles_soa angles = { in.theta_i, in.phi_i, in.theta_o, in.phi_o };
        st = hb_api_angles_present(call, n, &angles);
    }
    if (st == HB_OK && n && !f && !pdf)
        st = hb_fail_null(call, "pdf");
    if (st != HB_OK)
        return st;
    hb_spectral_batch b = { in, sigma_a.wavelengths, sigma_a.sigma_a, f, pdf };
    size_t invalid = 0;
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    if (!plan->kernels) {
        invalid = spectral_ref(plan, n, &b, sigma_a);
    } else {
        st = ops->spectral ? ops->spectral(plan, n, &b, &invalid) : HB_ERR_UNSUPPORTED;
        if (st == HB_ERR_UNSUPPORTED && !pdf && absorbing(ops, in.h != NULL))
            st = spectral_by_channels(plan, n, &in, sigma_a, f, &invalid);
        if (st != HB_OK)
            return hb_api_unsupported(call, plan, "spectral evaluation on this path");
    }
    report_invalid(report, invalid);
    return HB_OK;
}

hb_status hb_eval_angles_spectral(const hb_plan *plan, size_t n, hb_angles_soa in, hb_spectral_absorption sigma_a,
                                  float *const *f, hb_eval_report *report)
{
    hb_near_soa far = { in.theta_i, in.phi_i, in.theta_o, in.phi_o, NULL };
    return spectral_batch(__func__, plan, n, far, sigma_a, f, NULL, report);
}

hb_status hb_eval_near_spectral(const hb_plan *plan, size_t n, hb_near_soa in, hb_spectral_absorption sigma_a,
                                float *const *f, hb_eval_report *report)
{
    if (n && !in.h)
        return hb_fail_null(__func__, "in.h");
    return spectral_batch(__func__, plan, n, in, sigma_a, f, NULL, report);
}

hb_status hb_pdf_near_spectral(const hb_plan *plan, size_t n, hb_near_soa in, hb_spectral_absorption sigma_a,
                               float *pdf, hb_eval_report *report)
{
    if (n && !in.h)
        return hb_fail_null(__func__, "in.h");
    if (n && !pdf)
        return hb_fail_null(__func__, "pdf");
    return spectral_batch(__func__, plan, n, in, sigma_a, NULL, pdf, report);
}

/* x with a subnormal flushed to a zero of its sign, as the kernels read and write floats (simd.h). */
static float flushed(float x)
{
    return fabsf(x) < FLT_MIN ? copysignf(0.0f, x) : x;
}

/* The reference sampler, one sample at a time: the direction at the rounded numbers, then f and the
 * pdf there. */
static size_t sample_ref(const hb_plan *plan, int dims, size_t n, const hb_spectral_sample_batch *b,
                         hb_spectral_absorption sigma_a)
{
    size_t invalid = 0;
    for (size_t k = 0; k < n; k++) {
        double u[HB_SAMPLE_DIMENSIONS], absorption[HB_WAVELENGTHS_MAX], f[HB_WAVELENGTHS_MAX] = { 0.0 };
        double theta_o = b->in.theta_o[k], phi_o = b->in.phi_o[k], h = b->in.h[k], theta_i = 0.0, phi_i = 0.0,
               pdf = 0.0;
        int ok = hb_theta_valid(theta_o) && hb_phi_valid(phi_o) && hb_offset_valid(b->in.h[k]);
        for (int d = 0; d < dims; d++) {
            u[d] = flushed(b->in.u[d][k]);
            ok = ok && u[d] >= 0.0 && u[d] <= 1.0;
        }
        ok = absorptions_at(sigma_a, k, absorption) && ok;
        if (ok) {
            plan->reference->sample_spectral(plan, theta_o, phi_o, h, u, sigma_a.wavelengths, absorption, &theta_i,
                                             &phi_i);
            theta_i = (float)theta_i; /* f and pdf where the caller will see the sample */
            phi_i = (float)phi_i;
            plan->reference->spectral(plan, theta_i, phi_i, theta_o, phi_o, h, sigma_a.wavelengths, absorption, f,
                                      &pdf);
        } else {
            invalid++;
        }
        float pdf_out = flushed((float)pdf);
        b->out.theta_i[k] = (float)theta_i;
        b->out.phi_i[k] = (float)phi_i;
        b->out.pdf[k] = pdf_out;
        for (int j = 0; j < sigma_a.wavelengths; j++)
            b->out.weight[j][k] = pdf_out > 0.0f ? flushed((float)(f[j] / pdf)) : 0.0f;
    }
    return invalid;
}

hb_status hb_sample_near_spectral(const hb_plan *plan, size_t n, const hb_sample_near_in *in,
                                  hb_spectral_absorption sigma_a, const hb_sample_spectral_out *out,
                                  hb_eval_report *report)
{
    if (!plan || !in || !out)
        return hb_fail_null(__func__, !plan ? "plan" : !in ? "in" : "out");
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    int dims = ops->sample_spectral ? hb_plan_sample_dimensions(plan) - 1 : 0;
    if (dims <= 0)
        return hb_api_unsupported(__func__, plan, "spectral near-field sampler");
    hb_status st = spectral_checks(__func__, plan, n, sigma_a, 0, 1, "out->weight", 1, out->weight);
    if (st != HB_OK || !n)
        return st;
    const void *planes[] = { in->theta_o, in->phi_o, in->h, in->u, out->theta_i, out->phi_i, out->pdf };
    static const char *const names[] = { "in->theta_o", "in->phi_o", "in->h", "in->u", "out->theta_i",
                                         "out->phi_i", "out->pdf" };
    st = hb_api_present(__func__, n, (int)(sizeof planes / sizeof planes[0]), planes, names);
    if (st != HB_OK)
        return st;
    hb_spectral_sample_batch b = { .in = { in->theta_o, in->phi_o, in->h, { NULL } },
                                   .wavelengths = sigma_a.wavelengths, .sigma_a = sigma_a.sigma_a, .out = *out };
    for (int d = 0; d < dims; d++) {
        if (!in->u[d])
            return hb_fail(HB_ERR_NULL, "%s: in->u[%d] is NULL (this plan reads %d planes)", __func__, d, dims);
        b.in.u[d] = in->u[d];
    }
    size_t invalid = 0;
    if (plan->kernels)
        ops->sample_spectral(plan, n, &b, &invalid);
    else
        invalid = sample_ref(plan, dims, n, &b, sigma_a);
    report_invalid(report, invalid);
    return HB_OK;
}

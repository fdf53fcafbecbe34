/* Public sampling entry points (docs/sampling.md): argument checks, then the plan's kernel
 * or, for HB_QUALITY_REFERENCE, the double-precision procedure. No allocation. */
#include <math.h>

#include "math/hash.h"
#include "models/model.h"
#include "ref/reference.h"

int hb_plan_sample_dimensions(const hb_plan *plan)
{
    if (!plan || plan->options.term != HB_TERM_FULL)
        return 0;
    return hb_model_ops_of(plan->options.model)->sample_dimensions(plan);
}

static int angles_valid(float theta, float phi)
{
    return fabsf(theta) <= 1.57079637f && fabsf(phi) <= HB_PHI_LIMIT; /* false for NaN */
}

/* The reference path, one sample at a time; h: each sample's offset (near field), or NULL. */
static size_t sample_ref(const hb_plan *plan, int dims, size_t n, const float *theta_o, const float *phi_o,
                         const float *h, const float *const *uniforms, hb_sample_out out)
{
    size_t invalid = 0;
    for (size_t k = 0; k < n; k++) {
        double u[HB_SAMPLE_DIMENSIONS], theta_i = 0.0, phi_i = 0.0, f[3] = { 0.0, 0.0, 0.0 }, pdf = 0.0;
        int ok = angles_valid(theta_o[k], phi_o[k]) && (!h || fabsf(h[k]) <= 1.0f);
        for (int d = 0; d < dims; d++) {
            u[d] = uniforms[d][k];
            ok = ok && u[d] >= 0.0 && u[d] <= 1.0;
        }
        if (ok) {
            if (h)
                hb_ref_sample_near(plan, theta_o[k], phi_o[k], h[k], u, &theta_i, &phi_i);
            else
                hb_ref_sample(plan, theta_o[k], phi_o[k], u, &theta_i, &phi_i);
            float ti = (float)theta_i, pi = (float)phi_i; /* f and pdf where the caller will see the sample */
            theta_i = ti;
            phi_i = pi;
            if (h) {
                pdf = hb_ref_pdf_near(plan, theta_i, phi_i, theta_o[k], phi_o[k], h[k]);
                hb_ref_eval_near_pair(plan, theta_i, phi_i, theta_o[k], phi_o[k], h[k], f);
            } else {
                pdf = hb_ref_pdf(plan, theta_i, phi_i, theta_o[k], phi_o[k]);
                hb_ref_eval_pair(plan, theta_i, phi_i, theta_o[k], phi_o[k], f);
            }
        } else {
            invalid++;
        }
        out.theta_i[k] = (float)theta_i;
        out.phi_i[k] = (float)phi_i;
        out.pdf[k] = (float)pdf;
        float *weight[3] = { out.weight.r, out.weight.g, out.weight.b };
        for (int c = 0; c < 3; c++)
            weight[c][k] = pdf > 0.0 ? (float)(f[c] / pdf) : 0.0f;
    }
    return invalid;
}

/* The pointers a sampling call of n > 0 samples reads and writes (h: the near field's, or NULL). */
static hb_status sample_arguments(size_t n, const float *theta_o, const float *phi_o, int near, const float *h,
                                  const float *const *u, int dims, hb_sample_out out)
{
    if (!n)
        return HB_OK;
    if (!theta_o || !phi_o || (near && !h) || !out.theta_i || !out.phi_i || !out.pdf || !out.weight.r ||
        !out.weight.g || !out.weight.b)
        return HB_ERR_NULL;
    for (int d = 0; d < dims; d++)
        if (!u[d])
            return HB_ERR_NULL;
    return HB_OK;
}

static void report_invalid(hb_eval_report *report, size_t invalid)
{
    if (report)
        report->invalid = invalid;
}

/* The reference pdf, one sample at a time; h: each sample's offset (near field), or NULL. */
static size_t pdf_ref(const hb_plan *plan, size_t n, const float *theta_i, const float *phi_i, const float *theta_o,
                      const float *phi_o, const float *h, float *pdf)
{
    size_t invalid = 0;
    for (size_t k = 0; k < n; k++) {
        int ok = angles_valid(theta_i[k], phi_i[k]) && angles_valid(theta_o[k], phi_o[k]) && (!h || fabsf(h[k]) <= 1.0f);
        double p = !ok ? 0.0
                 : h   ? hb_ref_pdf_near(plan, theta_i[k], phi_i[k], theta_o[k], phi_o[k], h[k])
                       : hb_ref_pdf(plan, theta_i[k], phi_i[k], theta_o[k], phi_o[k]);
        pdf[k] = (float)p;
        invalid += !ok;
    }
    return invalid;
}

hb_status hb_sample_angles(const hb_plan *plan, size_t n, hb_sample_in in, hb_sample_out out, hb_eval_report *report)
{
    if (!plan)
        return HB_ERR_NULL;
    int dims = hb_plan_sample_dimensions(plan);
    if (dims == 0)
        return HB_ERR_UNSUPPORTED;
    hb_status st = sample_arguments(n, in.theta_o, in.phi_o, 0, NULL, in.u, dims, out);
    if (st != HB_OK)
        return st;
    size_t invalid = 0;
    if (!plan->kernels)
        invalid = sample_ref(plan, dims, n, in.theta_o, in.phi_o, NULL, in.u, out);
    else
        hb_model_ops_of(plan->options.model)->sample(plan, n, in, out, &invalid);
    report_invalid(report, invalid);
    return HB_OK;
}

hb_status hb_pdf_angles(const hb_plan *plan, size_t n, hb_angles_soa in, float *pdf, hb_eval_report *report)
{
    if (!plan)
        return HB_ERR_NULL;
    if (hb_plan_sample_dimensions(plan) == 0)
        return HB_ERR_UNSUPPORTED;
    if (n && (!in.theta_i || !in.phi_i || !in.theta_o || !in.phi_o || !pdf))
        return HB_ERR_NULL;
    size_t invalid = 0;
    if (!plan->kernels)
        invalid = pdf_ref(plan, n, in.theta_i, in.phi_i, in.theta_o, in.phi_o, NULL, pdf);
    else
        hb_model_ops_of(plan->options.model)->pdf(plan, n, in, pdf, &invalid);
    report_invalid(report, invalid);
    return HB_OK;
}

/* The near field's number count: the far-field sampler's less the one it turns into h. */
static int near_dimensions(const hb_plan *plan)
{
    return plan && hb_model_ops_of(plan->options.model)->sample_near ? hb_plan_sample_dimensions(plan) - 1 : 0;
}

hb_status hb_sample_near(const hb_plan *plan, size_t n, hb_sample_near_in in, hb_sample_out out,
                         hb_eval_report *report)
{
    if (!plan)
        return HB_ERR_NULL;
    int dims = near_dimensions(plan);
    if (dims <= 0)
        return HB_ERR_UNSUPPORTED;
    hb_status st = sample_arguments(n, in.theta_o, in.phi_o, 1, in.h, in.u, dims, out);
    if (st != HB_OK)
        return st;
    size_t invalid = 0;
    if (!plan->kernels)
        invalid = sample_ref(plan, dims, n, in.theta_o, in.phi_o, in.h, in.u, out);
    else
        hb_model_ops_of(plan->options.model)->sample_near(plan, n, in, out, &invalid);
    report_invalid(report, invalid);
    return HB_OK;
}

hb_status hb_pdf_near(const hb_plan *plan, size_t n, hb_near_soa in, float *pdf, hb_eval_report *report)
{
    if (!plan)
        return HB_ERR_NULL;
    if (near_dimensions(plan) <= 0)
        return HB_ERR_UNSUPPORTED;
    if (n && (!in.theta_i || !in.phi_i || !in.theta_o || !in.phi_o || !in.h || !pdf))
        return HB_ERR_NULL;
    size_t invalid = 0;
    if (!plan->kernels)
        invalid = pdf_ref(plan, n, in.theta_i, in.phi_i, in.theta_o, in.phi_o, in.h, pdf);
    else
        hb_model_ops_of(plan->options.model)->pdf_near(plan, n, in, pdf, &invalid);
    report_invalid(report, invalid);
    return HB_OK;
}

void hb_uniforms(unsigned long long seed, unsigned long long first, size_t n, int dimensions, float *const *u)
{
    unsigned long long key = hb_mix64(seed + 0x9e3779b97f4a7c15ull);
    for (int d = 0; d < dimensions; d++)
        for (size_t k = 0; k < n; k++) {
            unsigned long long index = (first + k) * HB_SAMPLE_DIMENSIONS + (unsigned long long)d;
            u[d][k] = (float)(hb_mix64(key ^ hb_mix64(index)) >> 40) * 0x1p-24f;
        }
}

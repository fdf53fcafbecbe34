/* Public sampling, pdf and fused entry points (docs/sampling.md): argument checks, then the plan's
 * kernels or, for HB_QUALITY_REFERENCE, the double-precision procedure. Directions come as angles
 * or as fibre-frame unit vectors (kernel/streams.h). No allocation. */
#include <float.h>
#include <math.h>

#include "checks.h"
#include "math/hash.h"
#include "math/valid.h"
#include "models/interface/model.h"
#include "ref/reference.h"

int hb_plan_sample_dimensions(const hb_plan *plan)
{
    if (!plan || plan->options.term != HB_TERM_FULL)
        return 0;
    return hb_model_ops_of(plan->options.model)->sample_dimensions(plan);
}

static int angles_valid(double theta, double phi)
{
    return hb_theta_valid(theta) && hb_phi_valid(phi);
}

/* Direction k of three streams (unit vectors, x, y, z) or two (theta, phi) as angles; 0 if invalid. */
static int direction_at(const float *const *s, int vectors, size_t k, double *theta, double *phi)
{
    if (vectors)
        return hb_ref_direction(s[0][k], s[1][k], s[2][k], theta, phi);
    *theta = s[0][k];
    *phi = s[1][k];
    return angles_valid(*theta, *phi);
}

static void report_invalid(hb_eval_report *report, size_t invalid)
{
    if (report)
        report->invalid = invalid;
}

int hb_plan_pdf_is_estimate(const hb_plan *plan)
{
    if (!hb_plan_sample_dimensions(plan))
        return 0;
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    return ops->pdf_is_estimate ? ops->pdf_is_estimate(plan) : 0;
}

/* x with a subnormal flushed to a zero of its sign, as the kernels read and write floats (simd.h). */
static float flushed(float x)
{
    return fabsf(x) < FLT_MIN ? copysignf(0.0f, x) : x;
}

/* The reference sampler, one sample at a time; h: each sample's offset (near field), or NULL. */
static size_t sample_ref(const hb_plan *plan, int dims, size_t n, const hb_sample_batch *b, const float *h)
{
    const float *wo[3] = { b->in.theta_o, b->in.phi_o, NULL };
    int vectors = b->wo[0] != NULL;
    if (vectors)
        wo[0] = b->wo[0], wo[1] = b->wo[1], wo[2] = b->wo[2];
    size_t invalid = 0;
    for (size_t k = 0; k < n; k++) {
        double u[HB_SAMPLE_DIMENSIONS], theta_o = 0.0, phi_o = 0.0, theta_i = 0.0, phi_i = 0.0, pdf = 0.0;
        double f[3] = { 0.0, 0.0, 0.0 };
        int ok = direction_at(wo, vectors, k, &theta_o, &phi_o) && (!h || fabsf(h[k]) <= 1.0f);
        for (int d = 0; d < dims; d++) {
            u[d] = flushed(b->in.u[d][k]);
            ok = ok && u[d] >= 0.0 && u[d] <= 1.0;
        }
        if (ok) {
            if (h)
                hb_ref_sample_near(plan, theta_o, phi_o, h[k], u, &theta_i, &phi_i);
            else
                hb_ref_sample(plan, theta_o, phi_o, u, &theta_i, &phi_i);
            theta_i = (float)theta_i; /* f and pdf where the caller will see the sample */
            phi_i = (float)phi_i;
            if (h) {
                pdf = hb_ref_pdf_near(plan, theta_i, phi_i, theta_o, phi_o, h[k]);
                hb_ref_eval_near_pair(plan, theta_i, phi_i, theta_o, phi_o, h[k], f);
            } else {
                pdf = hb_ref_pdf(plan, theta_i, phi_i, theta_o, phi_o);
                hb_ref_eval_pair(plan, theta_i, phi_i, theta_o, phi_o, f);
            }
        } else {
            invalid++;
        }
        if (b->wi[0]) {
            double c = ok ? cos(theta_i) : 0.0;
            b->wi[0][k] = (float)(sin(phi_i) * c);
            b->wi[1][k] = ok ? (float)sin(theta_i) : 0.0f;
            b->wi[2][k] = (float)(cos(phi_i) * c);
        } else {
            b->out.theta_i[k] = (float)theta_i;
            b->out.phi_i[k] = (float)phi_i;
        }
        /* the weight is 0 where the pdf the caller sees is 0, as in the kernels (a balance heuristic
         * divides by it): a pdf below FLT_MIN at an extreme u is flushed as the kernels flush it */
        float pdf_out = flushed((float)pdf);
        b->out.pdf[k] = pdf_out;
        float *weight[3] = { b->out.weight.r, b->out.weight.g, b->out.weight.b };
        for (int c = 0; c < 3; c++)
            weight[c][k] = pdf_out > 0.0f ? flushed((float)(f[c] / pdf)) : 0.0f;
    }
    return invalid;
}

/* HB_ERR_NULL naming the first pointer a sampling batch of n > 0 samples reads or writes that is
 * NULL (u: the caller's array of planes, which holds dims of them), else HB_OK; b's u gets the planes. */
static hb_status sample_pointers(const char *call, size_t n, hb_sample_batch *b, const float *const *u, int dims,
                                 int near)
{
    if (!n)
        return HB_OK;
    const void *planes[12];
    const char *names[12];
    int count = 0;
#define HB_PLANE(plane, name) (planes[count] = (plane), names[count++] = (name))
    if (b->wo[0])
        HB_PLANE(b->wo[0], "in->wo_x"), HB_PLANE(b->wo[1], "in->wo_y"), HB_PLANE(b->wo[2], "in->wo_z");
    else
        HB_PLANE(b->in.theta_o, "in->theta_o"), HB_PLANE(b->in.phi_o, "in->phi_o");
    if (near)
        HB_PLANE(b->in.h, "in->h");
    if (b->wi[0])
        HB_PLANE(b->wi[0], "out->wi_x"), HB_PLANE(b->wi[1], "out->wi_y"), HB_PLANE(b->wi[2], "out->wi_z");
    else
        HB_PLANE(b->out.theta_i, "out->theta_i"), HB_PLANE(b->out.phi_i, "out->phi_i");
    HB_PLANE(b->out.pdf, "out->pdf"), HB_PLANE(b->out.weight.r, "out->weight.r");
    HB_PLANE(b->out.weight.g, "out->weight.g"), HB_PLANE(b->out.weight.b, "out->weight.b"), HB_PLANE(u, "in->u");
#undef HB_PLANE
    hb_status st = hb_api_present(call, n, count, planes, names);
    for (int d = 0; st == HB_OK && d < dims; d++) {
        b->in.u[d] = u[d];
        if (!u[d])
            st = hb_fail(HB_ERR_NULL, "%s: in->u[%d] is NULL (this plan reads %d planes)", call, d, dims);
    }
    return st;
}

static hb_status sample_batch(const char *call, const hb_plan *plan, size_t n, hb_sample_batch *b,
                              const float *const *u, hb_eval_report *report)
{
    if (!plan)
        return hb_fail_null(call, "plan");
    int dims = hb_plan_sample_dimensions(plan);
    if (dims == 0)
        return hb_api_unsupported(call, plan, "sampler");
    hb_status st = sample_pointers(call, n, b, u, dims, 0);
    if (st != HB_OK)
        return st;
    size_t invalid = 0;
    if (!plan->kernels)
        invalid = sample_ref(plan, dims, n, b, NULL);
    else
        hb_model_ops_of(plan->options.model)->sample(plan, n, b, &invalid);
    report_invalid(report, invalid);
    return HB_OK;
}

hb_status hb_sample_angles(const hb_plan *plan, size_t n, const hb_sample_in *in, const hb_sample_out *out,
                           hb_eval_report *report)
{
    if (!in || !out)
        return hb_fail_null(__func__, !in ? "in" : "out");
    hb_sample_batch b = { .in = { .theta_o = in->theta_o, .phi_o = in->phi_o }, .out = *out };
    return sample_batch(__func__, plan, n, &b, in->u, report);
}

hb_status hb_sample_vectors(const hb_plan *plan, size_t n, const hb_sample_vectors_in *in,
                            const hb_sample_vectors_out *out, hb_eval_report *report)
{
    if (!in || !out)
        return hb_fail_null(__func__, !in ? "in" : "out");
    hb_sample_batch b = { .wo = { in->wo_x, in->wo_y, in->wo_z }, .wi = { out->wi_x, out->wi_y, out->wi_z } };
    b.out.pdf = out->pdf;
    b.out.weight = out->weight;
    if (n && (!in->wo_x || !out->wi_x)) /* a batch without wo[0] or wi[0] would read or write angles */
        return hb_fail_null(__func__, !in->wo_x ? "in->wo_x" : "out->wi_x");
    return sample_batch(__func__, plan, n, &b, in->u, report);
}

/* The reference pdf (and f where f is not NULL), one sample at a time; h: offsets, or NULL. */
static size_t pdf_ref(const hb_plan *plan, size_t n, const hb_pair_batch *in, const float *h, float *pdf,
                      const hb_rgb_soa *f)
{
    int vectors = in->vectors.wi_x != NULL;
    const float *wi[3] = { in->angles.theta_i, in->angles.phi_i, NULL };
    const float *wo[3] = { in->angles.theta_o, in->angles.phi_o, NULL };
    if (vectors) {
        const hb_vectors_soa *v = &in->vectors;
        wi[0] = v->wi_x, wi[1] = v->wi_y, wi[2] = v->wi_z, wo[0] = v->wo_x, wo[1] = v->wo_y, wo[2] = v->wo_z;
    }
    size_t invalid = 0;
    for (size_t k = 0; k < n; k++) {
        double ti, pi, to, po, p = 0.0, value[3] = { 0.0, 0.0, 0.0 };
        int ok = direction_at(wi, vectors, k, &ti, &pi) && direction_at(wo, vectors, k, &to, &po) &&
                 (!h || fabsf(h[k]) <= 1.0f);
        if (ok && h)
            p = hb_ref_pdf_near(plan, ti, pi, to, po, h[k]);
        else if (ok)
            p = hb_ref_pdf(plan, ti, pi, to, po);
        if (ok && f)
            hb_ref_eval_pair(plan, ti, pi, to, po, value);
        pdf[k] = flushed((float)p); /* as the sampler writes it */
        if (f)
            f->r[k] = (float)value[0], f->g[k] = (float)value[1], f->b[k] = (float)value[2];
        invalid += !ok;
    }
    return invalid;
}

/* pdf, and f where f is not NULL, of direction pairs. */
static hb_status pdf_batch(const char *call, const hb_plan *plan, size_t n, const hb_pair_batch *in, int vectors,
                           const hb_rgb_soa *f, float *pdf, hb_eval_report *report)
{
    if (!plan)
        return hb_fail_null(call, "plan");
    if (hb_plan_sample_dimensions(plan) == 0)
        return hb_api_unsupported(call, plan, "sampler, so no pdf");
    hb_status st = vectors ? hb_api_vectors_present(call, n, &in->vectors) : hb_api_angles_present(call, n, &in->angles);
    if (st == HB_OK && f)
        st = hb_api_rgb_present(call, n, "f", f);
    if (st == HB_OK && n && !pdf)
        st = hb_fail_null(call, "pdf");
    if (st != HB_OK)
        return st;
    size_t invalid = 0;
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    if (!plan->kernels)
        invalid = pdf_ref(plan, n, in, NULL, pdf, f);
    else if (f)
        ops->eval_pdf(plan, n, in, *f, pdf, &invalid);
    else
        ops->pdf(plan, n, in, pdf, &invalid);
    report_invalid(report, invalid);
    return HB_OK;
}

hb_status hb_pdf_angles(const hb_plan *plan, size_t n, hb_angles_soa in, float *pdf, hb_eval_report *report)
{
    hb_pair_batch pairs = { .angles = in };
    return pdf_batch(__func__, plan, n, &pairs, 0, NULL, pdf, report);
}

hb_status hb_pdf_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, float *pdf, hb_eval_report *report)
{
    hb_pair_batch pairs = { .vectors = in };
    return pdf_batch(__func__, plan, n, &pairs, 1, NULL, pdf, report);
}

hb_status hb_eval_pdf_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa f, float *pdf,
                             hb_eval_report *report)
{
    hb_pair_batch pairs = { .angles = in };
    return pdf_batch(__func__, plan, n, &pairs, 0, &f, pdf, report);
}

hb_status hb_eval_pdf_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa f, float *pdf,
                              hb_eval_report *report)
{
    hb_pair_batch pairs = { .vectors = in };
    return pdf_batch(__func__, plan, n, &pairs, 1, &f, pdf, report);
}

/* The near field's number count: the far-field sampler's less the one it turns into h. */
static int near_dimensions(const hb_plan *plan)
{
    return plan && hb_model_ops_of(plan->options.model)->sample_near ? hb_plan_sample_dimensions(plan) - 1 : 0;
}

hb_status hb_sample_near(const hb_plan *plan, size_t n, const hb_sample_near_in *in, const hb_sample_out *out,
                         hb_eval_report *report)
{
    if (!plan || !in || !out)
        return hb_fail_null(__func__, !plan ? "plan" : !in ? "in" : "out");
    int dims = near_dimensions(plan);
    if (dims <= 0)
        return hb_api_unsupported(__func__, plan, "near-field sampler");
    hb_sample_batch b = { .in = { .theta_o = in->theta_o, .phi_o = in->phi_o, .h = in->h }, .out = *out };
    hb_status st = sample_pointers(__func__, n, &b, in->u, dims, 1);
    if (st != HB_OK)
        return st;
    size_t invalid = 0;
    if (!plan->kernels)
        invalid = sample_ref(plan, dims, n, &b, in->h);
    else
        hb_model_ops_of(plan->options.model)->sample_near(plan, n, b.in, *out, &invalid);
    report_invalid(report, invalid);
    return HB_OK;
}

hb_status hb_pdf_near(const hb_plan *plan, size_t n, hb_near_soa in, float *pdf, hb_eval_report *report)
{
    if (!plan)
        return hb_fail_null(__func__, "plan");
    if (near_dimensions(plan) <= 0)
        return hb_api_unsupported(__func__, plan, "near-field sampler, so no pdf");
    hb_status st = hb_api_near_present(__func__, n, &in);
    if (st == HB_OK && n && !pdf)
        st = hb_fail_null(__func__, "pdf");
    if (st != HB_OK)
        return st;
    size_t invalid = 0;
    if (!plan->kernels) {
        hb_pair_batch pairs = { .angles = { in.theta_i, in.phi_i, in.theta_o, in.phi_o } };
        invalid = pdf_ref(plan, n, &pairs, in.h, pdf, NULL);
    } else {
        hb_model_ops_of(plan->options.model)->pdf_near(plan, n, in, pdf, &invalid);
    }
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

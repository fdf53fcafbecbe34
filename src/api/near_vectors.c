/* The near field from fibre-frame unit vectors (hb_eval_near_vectors and its kin): the vectors become
 * angles in double (hb_ref_direction, the one rule of a valid vector), in chunks on the stack, and
 * the angle entry points run on them; the sampler's w_i goes back to a vector. */
#include <math.h>

#include "checks.h"
#include "ref/reference.h"

enum { CHUNK = 256 };

/* One chunk's angles and offsets; a sample with an invalid vector gets a NaN angle, which the angle
 * calls count as invalid and answer with zeros. */
typedef struct near_chunk {
    float ti[CHUNK], pi[CHUNK], to[CHUNK], po[CHUNK], h[CHUNK];
} near_chunk;

static void to_angles(const float *x, const float *y, const float *z, size_t k, float *theta, float *phi)
{
    double t, p;
    int ok = hb_ref_direction(x[k], y[k], z[k], &t, &p);
    *theta = ok ? (float)t : NAN;
    *phi = ok ? (float)p : NAN;
}

static size_t fill(near_chunk *c, const hb_near_vectors_soa *in, size_t first, size_t n)
{
    size_t m = n - first < CHUNK ? n - first : CHUNK;
    for (size_t k = 0; k < m; k++) {
        to_angles(in->wi_x, in->wi_y, in->wi_z, first + k, &c->ti[k], &c->pi[k]);
        to_angles(in->wo_x, in->wo_y, in->wo_z, first + k, &c->to[k], &c->po[k]);
        c->h[k] = in->h[first + k];
    }
    return m;
}

/* f (f != NULL) and the pdf (pdf != NULL) of the pairs, chunk by chunk. */
static hb_status near_pairs(const char *call, const hb_plan *plan, size_t n, const hb_near_vectors_soa *in,
                            const hb_rgb_soa *f, float *pdf, hb_eval_report *report)
{
    if (!plan)
        return hb_fail_null(call, "plan");
    const void *planes[] = { in->wi_x, in->wi_y, in->wi_z, in->wo_x, in->wo_y, in->wo_z, in->h };
    static const char *const names[] = { "in.wi_x", "in.wi_y", "in.wi_z", "in.wo_x", "in.wo_y", "in.wo_z", "in.h" };
    hb_status st = hb_api_present(call, n, 7, planes, names);
    if (st == HB_OK && f)
        st = hb_api_rgb_present(call, n, "f", f);
    if (st != HB_OK)
        return st;
    size_t invalid = 0;
    near_chunk c;
    for (size_t first = 0; first < n || first == 0; first += CHUNK) {
        size_t m = n ? fill(&c, in, first, n) : 0;
        hb_near_soa angles = { c.ti, c.pi, c.to, c.po, c.h };
        hb_eval_report r = { 0 }, q = { 0 };
        if (f)
            st = hb_eval_near(plan, m, angles, (hb_rgb_soa){ f->r + first, f->g + first, f->b + first }, &r);
        if (st == HB_OK && pdf)
            st = hb_pdf_near(plan, m, angles, pdf + first, &q);
        if (st != HB_OK)
            return st;
        invalid += f ? r.invalid : q.invalid;
        if (!n)
            break;
    }
    if (report)
        report->invalid = invalid;
    return HB_OK;
}

hb_status hb_eval_near_vectors(const hb_plan *plan, size_t n, hb_near_vectors_soa in, hb_rgb_soa out,
                               hb_eval_report *report)
{
    return near_pairs(__func__, plan, n, &in, &out, NULL, report);
}

hb_status hb_pdf_near_vectors(const hb_plan *plan, size_t n, hb_near_vectors_soa in, float *pdf, hb_eval_report *report)
{
    if (n && !pdf)
        return hb_fail_null(__func__, "pdf");
    return near_pairs(__func__, plan, n, &in, NULL, pdf, report);
}

hb_status hb_eval_pdf_near_vectors(const hb_plan *plan, size_t n, hb_near_vectors_soa in, hb_rgb_soa f, float *pdf,
                                   hb_eval_report *report)
{
    if (n && !pdf)
        return hb_fail_null(__func__, "pdf");
    return near_pairs(__func__, plan, n, &in, &f, pdf, report);
}

hb_status hb_eval_pdf_near(const hb_plan *plan, size_t n, hb_near_soa in, hb_rgb_soa f, float *pdf,
                           hb_eval_report *report)
{
    if (n && !pdf)
        return hb_fail_null(__func__, "pdf");
    hb_status st = hb_eval_near(plan, n, in, f, report);
    return st == HB_OK ? hb_pdf_near(plan, n, in, pdf, NULL) : st;
}

hb_status hb_sample_near_vectors(const hb_plan *plan, size_t n, const hb_sample_near_vectors_in *in,
                                 const hb_sample_vectors_out *out, hb_eval_report *report)
{
    if (!plan || !in || !out)
        return hb_fail_null(__func__, !plan ? "plan" : !in ? "in" : "out");
    const void *planes[] = { in->wo_x, in->wo_y, in->wo_z, in->h, in->u, out->wi_x, out->wi_y, out->wi_z };
    static const char *const names[] = { "in->wo_x", "in->wo_y", "in->wo_z", "in->h", "in->u", "out->wi_x", "out->wi_y",
                                         "out->wi_z" };
    hb_status st = hb_api_present(__func__, n, 8, planes, names);
    if (st != HB_OK)
        return st;
    int dims = hb_plan_sample_dimensions(plan); /* the near sampler reads one fewer; u has at least that many */
    size_t invalid = 0;
    near_chunk c;
    for (size_t first = 0; first < n || first == 0; first += CHUNK) {
        size_t m = n - first < CHUNK ? n - first : CHUNK;
        for (size_t k = 0; k < m; k++) {
            to_angles(in->wo_x, in->wo_y, in->wo_z, first + k, &c.to[k], &c.po[k]);
            c.h[k] = in->h[first + k];
        }
        const float *u[HB_SAMPLE_DIMENSIONS] = { NULL };
        for (int d = 0; n && d + 1 < dims; d++)
            u[d] = in->u[d] ? in->u[d] + first : NULL;
        hb_sample_near_in angles = { c.to, c.po, c.h, u };
        hb_sample_out sampled = { c.ti, c.pi, out->pdf ? out->pdf + first : NULL,
                                  { out->weight.r ? out->weight.r + first : NULL,
                                    out->weight.g ? out->weight.g + first : NULL,
                                    out->weight.b ? out->weight.b + first : NULL } };
        hb_eval_report r = { 0 };
        st = hb_sample_near(plan, m, &angles, &sampled, &r);
        if (st != HB_OK)
            return st;
        for (size_t k = 0; k < m; k++) {
            int ok = 1; /* where the chunk has invalid samples, each sample's own call says which */
            if (r.invalid) {
                hb_eval_report one = { 0 };
                const float *u_k[HB_SAMPLE_DIMENSIONS] = { NULL };
                for (int d = 0; d + 1 < dims; d++)
                    u_k[d] = u[d] + k;
                hb_sample_near_in at = { c.to + k, c.po + k, c.h + k, u_k };
                float ti, pi, pdf, w[3];
                hb_sample_near(plan, 1, &at, &(hb_sample_out){ &ti, &pi, &pdf, { &w[0], &w[1], &w[2] } }, &one);
                ok = one.invalid == 0;
            }
            double ct = cos(c.ti[k]);
            out->wi_x[first + k] = ok ? (float)(sin(c.pi[k]) * ct) : 0.0f;
            out->wi_y[first + k] = ok ? (float)sin(c.ti[k]) : 0.0f;
            out->wi_z[first + k] = ok ? (float)(cos(c.pi[k]) * ct) : 0.0f;
        }
        invalid += r.invalid;
        if (!n)
            break;
    }
    if (report)
        report->invalid = invalid;
    return HB_OK;
}

/* pbrt-v4's HairBxDF at one hit, in pbrt's own terms (docs/spectral.md): its hair frame (the tangent
 * on x) and its offset h mapped to the library's (docs/chiang.md), the spectral calls at its sampled
 * wavelengths, and f returned as pbrt's f is, divided by |cos| to its shading normal. */
#include <math.h>

#include "models/interface/plan.h"
#include "ref/reference.h"

/* A pbrt hair-frame vector (a, b, c) is (c, a, b) here: its angles in double; 0 when not a unit vector. */
static int pbrt_direction(const float w[3], float *theta, float *phi)
{
    double t, p;
    int ok = hb_ref_direction(w[2], w[0], w[1], &t, &p);
    *theta = (float)t, *phi = (float)p;
    return ok;
}

/* pbrt's f is the library's divided by |w_i.z| in its frame (HairBxDF::f), where that is not 0. */
static float pbrt_f(float f, const float wi[3])
{
    return wi[2] != 0.0f ? f / fabsf(wi[2]) : f;
}

hb_status hb_pbrt_f(const hb_plan *plan, const float wo[3], const float wi[3], float h, int wavelengths,
                    const float *sigma_a, float *f, float *pdf)
{
    if (!wo || !wi || !sigma_a || !f || !pdf)
        return hb_fail_null(__func__, !wo ? "wo" : !wi ? "wi" : !sigma_a ? "sigma_a" : !f ? "f" : "pdf");
    float ti, pi, to, po, offset = -h;
    int valid = pbrt_direction(wi, &ti, &pi) & pbrt_direction(wo, &to, &po);
    if (!valid)
        ti = to = NAN; /* an invalid sample: zeros, as the batch calls give */
    const float *planes[HB_WAVELENGTHS_MAX];
    float *out[HB_WAVELENGTHS_MAX];
    for (int j = 0; j < wavelengths && j < HB_WAVELENGTHS_MAX; j++)
        planes[j] = sigma_a + j, out[j] = f + j;
    hb_near_soa in = { &ti, &pi, &to, &po, &offset };
    hb_spectral_absorption a = { wavelengths, planes };
    hb_status st = hb_eval_near_spectral(plan, 1, in, a, out, NULL);
    if (st == HB_OK)
        st = hb_pdf_near_spectral(plan, 1, in, a, pdf, NULL);
    for (int j = 0; st == HB_OK && j < wavelengths; j++)
        f[j] = pbrt_f(f[j], wi);
    return st;
}

hb_status hb_pbrt_sample_f(const hb_plan *plan, const float wo[3], float h, const float u[4], int wavelengths,
                           const float *sigma_a, float wi[3], float *f, float *pdf)
{
    if (!wo || !u || !sigma_a || !wi || !f || !pdf)
        return hb_fail_null(__func__, !wo ? "wo" : !u ? "u" : !sigma_a ? "sigma_a" : !wi ? "wi" : !f ? "f" : "pdf");
    float to, po, offset = -h, ti, pi;
    if (!pbrt_direction(wo, &to, &po))
        to = NAN;
    const float *planes[HB_WAVELENGTHS_MAX], *numbers[4] = { u, u + 1, u + 2, u + 3 };
    float *weight[HB_WAVELENGTHS_MAX];
    for (int j = 0; j < wavelengths && j < HB_WAVELENGTHS_MAX; j++)
        planes[j] = sigma_a + j, weight[j] = f + j;
    hb_sample_near_in in = { &to, &po, &offset, numbers };
    hb_sample_spectral_out out = { &ti, &pi, pdf, weight };
    hb_status st = hb_sample_near_spectral(plan, 1, &in, (hb_spectral_absorption){ wavelengths, planes }, &out, NULL);
    if (st != HB_OK)
        return st;
    double c = cos(ti); /* the library's (x, y, z) is pbrt's (y, z, x) */
    wi[0] = (float)sin(ti), wi[1] = (float)(cos(pi) * c), wi[2] = (float)(sin(pi) * c);
    if (*pdf == 0.0f)
        wi[0] = wi[1] = wi[2] = 0.0f;
    for (int j = 0; j < wavelengths; j++)
        f[j] = pbrt_f(f[j] * *pdf, wi);
    return HB_OK;
}

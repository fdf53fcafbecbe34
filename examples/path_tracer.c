/* A path tracer's direct lighting at hair hits, in the style of pbrt-v4's integrator, with vectors
 * only: at each hit the fibre frame from the hair's tangent, then one BSDF sample (hb_hit_sample) and
 * one light sample (f and pdf by hb_hit_eval_pdf) combined by multiple importance sampling (the power
 * heuristic); make bench times this step per hit (the per-hit path-step rows). The light is a white
 * environment of radiance 1 sampled uniformly over the sphere, so the estimate at a hit is the
 * fibre's white furnace E(w_o) (docs/conventions.md): every hit here sees w_o at the same
 * inclination to its fibre, and the mean over the hits converges to hb_furnace at that
 * inclination, which the example prints beside it. */
#include <math.h>
#include <stdio.h>

#include "hairbsdf.h"

enum { HITS = 20000 };

static const double pi = 3.14159265358979323846;

/* A unit vector from two uniform numbers, uniform over the sphere. */
static void uniform_sphere(float u1, float u2, float w[3])
{
    float z = 1.0f - 2.0f * u1, r = sqrtf(fmaxf(0.0f, 1.0f - z * z)), a = (float)(2.0 * pi) * u2;
    w[0] = r * cosf(a), w[1] = r * sinf(a), w[2] = z;
}

static float power_heuristic(float a, float b) { return a * a / (a * a + b * b); }

int main(void)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = HB_MODEL_DEON;
    hb_plan *plan;
    hb_error error;
    if (hb_plan_create(&m, &o, &plan, &error) != HB_OK) {
        fprintf(stderr, "%s\n", error.message);
        return 1;
    }
    const double theta_o = 0.4; /* w_o's inclination to the fibre at every hit */
    const float light_pdf = (float)(1.0 / (4.0 * pi));
    int dimensions = hb_plan_sample_dimensions(plan);
    double sum = 0.0, sum2 = 0.0;
    for (int hit = 0; hit < HITS; hit++) {
        /* the scene's part: a hit on a strand of random direction, seen from a random azimuth */
        float r[5], *rs[5] = { &r[0], &r[1], &r[2], &r[3], &r[4] }, tangent[3], around[3];
        hb_uniforms(1, (unsigned long long)hit, 1, 5, rs);
        uniform_sphere(r[0], r[1], tangent);
        hb_frame frame;
        hb_frame_from_tangent(tangent, NULL, &frame);
        float local_o[3] = { (float)(cos(theta_o) * cos(2.0 * pi * r[2])), (float)sin(theta_o),
                             (float)(cos(theta_o) * sin(2.0 * pi * r[2])) };
        float to_eye[3];
        hb_frame_to_world(&frame, local_o, to_eye);

        /* the integrator's part, in the fibre frame */
        float wo[3];
        hb_frame_to_local(&frame, to_eye, wo);
        float u[HB_SAMPLE_DIMENSIONS], *us[HB_SAMPLE_DIMENSIONS];
        for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
            us[d] = &u[d];
        hb_uniforms(2, (unsigned long long)hit, 1, dimensions, us);
        float wi[3], pdf, weight[3];
        hb_hit_sample(plan, wo, NULL, u, wi, &pdf, weight);
        double estimate = pdf > 0.0f ? weight[0] * power_heuristic(pdf, light_pdf) : 0.0;

        uniform_sphere(r[3], r[4], around); /* the light sample, and what the BSDF says of it */
        float wl[3], f[3], bsdf_pdf;
        hb_frame_to_local(&frame, around, wl);
        hb_hit_eval_pdf(plan, wl, wo, NULL, f, &bsdf_pdf);
        estimate += f[0] / light_pdf * power_heuristic(light_pdf, bsdf_pdf);
        sum += estimate, sum2 += estimate * estimate;
    }
    double mean = sum / HITS, error_of_mean = sqrt(fmax(0.0, sum2 / HITS - mean * mean) / HITS), furnace[3];
    hb_furnace(plan, theta_o, furnace);
    printf("direct light from a white sky over %d hits: %.4f +- %.4f; hb_furnace at theta_o %.1f: %.4f\n", HITS,
           mean, error_of_mean, theta_o, furnace[0]);
    hb_plan_destroy(plan);
    return fabs(mean - furnace[0]) <= 4.0 * error_of_mean + 1e-3 ? 0 : 1;
}

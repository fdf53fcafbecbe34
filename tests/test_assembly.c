/* hb_assembly_trace (docs/multiple-scattering.md): light traced through explicit fibres. A slab of
 * one fibre gives back what that fibre sends, bin by bin, within the estimator's standard errors
 * (this checks the hits' h and the light's footprint), under both transports; a lossless assembly absorbs nothing; the numbers are the same bit for bit
 * on any job system; the near-field sampler reflects R about the normal at phi_o + asin(h), the
 * convention the hits' h follows; invalid assemblies are refused by name. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/fibres.h"
#include "test.h"

static hb_plan *assembly_plan(hb_test_ctx *t, hb_model model, double eumelanin, double pheomelanin, double alpha)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = eumelanin, m.pheomelanin = pheomelanin, m.alpha = alpha;
    o.model = model, o.isa = t->isa;
    hb_plan *plan = NULL;
    hb_error e;
    CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "%s", e.message);
    return plan;
}

enum { THETA_BINS = 6, PHI_BINS = 12, SIDES = 2 };

/* The integral over bin (i, j) of w, by the midpoint rule on n x n nodes, of the far-field f(w, w_light), what the
 * paths draw, or (transposed) of S(w_light, w) cos(theta_w), what light from w_light sends into w:
 * the two are equal for a reciprocal S. */
static void bin_integral(const hb_plan *plan, const hb_assembly *a, int i, int j, int transposed, int n, double out[3])
{
    enum { MOST = 24 };
    static float ti[MOST * MOST], pi[MOST * MOST], to[MOST * MOST], po[MOST * MOST], f[3][MOST * MOST];
    const int N = n < MOST ? n : MOST;
    double t0 = -M_PI_2 + M_PI * i / THETA_BINS, p0 = -M_PI + 2.0 * M_PI * j / PHI_BINS;
    double dt = M_PI / THETA_BINS / N, dp = 2.0 * M_PI / PHI_BINS / N;
    for (int k = 0; k < N * N; k++) {
        ti[k] = (float)(t0 + dt * (k / N + 0.5)), pi[k] = (float)(p0 + dp * (k % N + 0.5));
        to[k] = (float)a->theta_light, po[k] = (float)a->phi_light;
    }
    hb_angles_soa drawn = { ti, pi, to, po }, sent = { to, po, ti, pi };
    hb_eval_angles(plan, (size_t)(N * N), transposed ? sent : drawn, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    double weight[MOST]; /* per row of nodes: the measure cos(theta) dtheta dphi, and the transposed S's cosines */
    for (int row = 0; row < N; row++) {
        double c = cos((double)ti[row * N]);
        weight[row] = c * (transposed ? c / cos(a->theta_light) : 1.0) * dt * dp;
    }
    for (int c = 0; c < 3; c++) {
        out[c] = 0.0;
        for (int k = 0; k < N * N; k++)
            out[c] += f[c][k] * weight[k / N];
    }
}

/* One fibre in a slab of period 64 gives back what that fibre sends, bin by bin: S(w_light, w)
 * cos(theta_w) under the light's transport (the far field), and the sampler's f(w, w_light) under
 * its own weights (the near field at the hits' offsets, which average to the far field). */
static void test_one_fibre(hb_test_ctx *t)
{
    static const struct {
        const char *name;
        hb_model model;
        hb_assembly_transport transport;
    } cases[] = { { "dFH11 blond,  light's transport", HB_MODEL_DEON, HB_ASSEMBLY_LIGHT_TRANSPORT },
                  { "CBTB16 blond, light's transport", HB_MODEL_CHIANG, HB_ASSEMBLY_LIGHT_TRANSPORT },
                  { "MJC03 blond,  light's transport", HB_MODEL_MARSCHNER, HB_ASSEMBLY_LIGHT_TRANSPORT },
                  { "dFH11 blond,  sampler's weights", HB_MODEL_DEON, HB_ASSEMBLY_SAMPLER_WEIGHTS },
                  { "CBTB16 blond, sampler's weights", HB_MODEL_CHIANG, HB_ASSEMBLY_SAMPLER_WEIGHTS } };
    for (size_t m = 0; m < sizeof cases / sizeof cases[0]; m++) {
        hb_plan *plan = assembly_plan(t, cases[m].model, 0.3, 0.0, 0.035);
        if (!plan)
            return;
        int sampler = cases[m].transport == HB_ASSEMBLY_SAMPLER_WEIGHTS;
        hb_assembly a;
        hb_assembly_default(&a);
        a.layers = 1.0, a.period = 64, a.packing = M_PI / (2.0 * 128.0), a.theta_light = 0.3, a.phi_light = 0.4;
        /* under qemu the quick tier traces a quarter of the paths and integrates each bin on
         * 12 x 12 nodes instead of 24 x 24, the evaluations being most of the time */
        a.paths = (t->quick ? (t->emulated ? 25000 : 100000) : 4000000) / (sampler ? 2 : 1);
        int nodes = t->quick && t->emulated ? 12 : 24;
        a.theta_bins = THETA_BINS, a.phi_bins = PHI_BINS;
        a.seed = 7, a.transport = cases[m].transport;
        static double radiance[SIDES * THETA_BINS * PHI_BINS * 3], se[SIDES * THETA_BINS * PHI_BINS * 3];
        hb_assembly_result r = { .struct_size = sizeof r, .radiance = radiance, .radiance_se = se };
        CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_OK, "%s", hb_last_error()->message);
        CHECK(t, r.fibres == 1, "%s: %ld fibres", cases[m].name, r.fibres);
        /* the share of the light that meets the fibre: its shadow's width 2 / cos(phi_light) of the period */
        double met = 2.0 / cos(a.phi_light) / (2.0 * a.period), worst = 0.0, worst_abs = 0.0, transposed = 0.0, largest = 0.0;
        for (int side = 0; side < SIDES; side++)
            for (int i = 0; i < THETA_BINS; i++)
                for (int j = 0; j < PHI_BINS; j++) {
                    /* bins along the slab's faces (phi near +-pi/2) also take light that meets the
                     * fibre's copy a period away: left out; light sent along the faces may still
                     * scatter off a copy into the other bins, which a period of 64 keeps below the
                     * noise (at 16 it shows in MJC03's bins as 5 standard errors) */
                    if (j == 2 || j == 3 || j == 8 || j == 9)
                        continue;
                    double phi = -M_PI + 2.0 * M_PI * (j + 0.5) / PHI_BINS;
                    if ((cos(phi) > 0.0) != (side == 0))
                        continue; /* leaving through the other face: empty */
                    double drawn[3], sent[3], solid = (sin(-M_PI_2 + M_PI * (i + 1) / THETA_BINS) - sin(-M_PI_2 + M_PI * i / THETA_BINS)) *
                                                2.0 * M_PI / PHI_BINS;
                    bin_integral(plan, &a, i, j, 0, nodes, drawn);
                    bin_integral(plan, &a, i, j, 1, nodes, sent);
                    const double *want = sampler ? drawn : sent;
                    for (int c = 0; c < 3; c++) {
                        size_t k = (size_t)((side * THETA_BINS + i) * PHI_BINS + j) * 3 + (size_t)c;
                        /* a bin's standard error, at least that of its expected count's Poisson noise
                         * (an empty bin's estimate is 0) with weights up to 1 */
                        double got = radiance[k] * solid / met,
                               err = fmax(se[k] * solid / met, sqrt(want[c] / (met * (double)a.paths)));
                        double z = fabs(got - want[c]) / fmax(err, 1e-12);
                        if (fabs(got - want[c]) > 1e-5)
                            worst = fmax(worst, z);
                        worst_abs = fmax(worst_abs, fabs(got - want[c]));
                        transposed = fmax(transposed, fabs(sent[c] - drawn[c]));
                        largest = fmax(largest, sent[c]);
                        CHECK(t, fabs(got - want[c]) <= 4.5 * err + 1e-5, "%s: bin (%d, %d, %d) channel %d: %.5g, f gives %.5g (se %.2g)",
                              cases[m].name, side, i, j, c, got, want[c], err);
                    }
                }
        hb_test_note(t, "%s, %lld paths: binned exits within %.2f standard errors of the bins' integrals (largest difference %.1e)",
                     cases[m].name, a.paths, worst, worst_abs);
        if (!sampler)
            hb_test_note(t, "%s: what the sampler draws, f(w, w_light), differs from what the fibre sends by %.2f%% of the largest bin",
                         cases[m].name, 100.0 * transposed / largest);
        hb_plan_destroy(plan);
    }
}

/* Lossless untilted fibres under the sampler's weights absorb nothing: each weight's mean is the
 * white furnace, 1. Under the light's transport the mean is the integral of S(w_from, w_next)
 * cos(theta_next) over w_next, 1 only for a reciprocal S: what a lossless slab then absorbs, with
 * and without tilt, is noted. */
static void test_lossless(hb_test_ctx *t)
{
    static const struct {
        const char *name;
        hb_model model;
        hb_assembly_shape shape;
        hb_assembly_transport transport;
        double alpha;
    } cases[] = { { "dFH11 slab,    sampler's weights", HB_MODEL_DEON, HB_ASSEMBLY_SLAB, HB_ASSEMBLY_SAMPLER_WEIGHTS, 0.0 },
                  { "CBTB16 slab,   sampler's weights", HB_MODEL_CHIANG, HB_ASSEMBLY_SLAB, HB_ASSEMBLY_SAMPLER_WEIGHTS, 0.0 },
                  { "CBTB16 bundle, sampler's weights", HB_MODEL_CHIANG, HB_ASSEMBLY_BUNDLE, HB_ASSEMBLY_SAMPLER_WEIGHTS, 0.0 },
                  { "dFH11 slab,    light's transport", HB_MODEL_DEON, HB_ASSEMBLY_SLAB, HB_ASSEMBLY_LIGHT_TRANSPORT, 0.0 },
                  { "CBTB16 slab,   light's transport", HB_MODEL_CHIANG, HB_ASSEMBLY_SLAB, HB_ASSEMBLY_LIGHT_TRANSPORT, 0.0 },
                  { "dFH11 slab,    light's transport, tilt 0.035", HB_MODEL_DEON, HB_ASSEMBLY_SLAB, HB_ASSEMBLY_LIGHT_TRANSPORT, 0.035 },
                  { "CBTB16 slab,   light's transport, tilt 0.035", HB_MODEL_CHIANG, HB_ASSEMBLY_SLAB, HB_ASSEMBLY_LIGHT_TRANSPORT,
                    0.035 } };
    for (size_t m = 0; m < sizeof cases / sizeof cases[0]; m++) {
        hb_plan *plan = assembly_plan(t, cases[m].model, 0.0, 0.0, cases[m].alpha);
        if (!plan)
            return;
        hb_assembly a;
        hb_assembly_default(&a);
        a.shape = cases[m].shape, a.layers = 4.0, a.packing = 0.3, a.paths = t->quick ? 4000 : 40000;
        a.transport = cases[m].transport;
        hb_assembly_result r = { .struct_size = sizeof r };
        CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_OK, "%s", hb_last_error()->message);
        for (int c = 0; c < 3; c++) {
            double total = r.reflected[c] + r.transmitted[c] + r.absorbed[c] + r.unfinished[c];
            CHECK(t, fabs(total - 1.0) < 1e-9, "%s: the shares sum to %.12g", cases[m].name, total);
            if (cases[m].transport == HB_ASSEMBLY_SAMPLER_WEIGHTS)
                CHECK(t, fabs(r.absorbed[c]) <= 3.0 * r.absorbed_se[c] + 1e-5, "%s: lossless fibres absorbed %.3g (se %.2g)",
                      cases[m].name, r.absorbed[c], r.absorbed_se[c]);
        }
        hb_test_note(t, "%s, lossless, 4 layers, packing %.3f: reflected %.4f +- %.4f, transmitted %.4f, absorbed %.1e +- %.1e, "
                        "%.1f scatterings per path",
                     cases[m].name, r.packing, r.reflected[1], r.reflected_se[1], r.transmitted[1], r.absorbed[1],
                     r.absorbed_se[1], (double)r.events / (double)a.paths);
        hb_plan_destroy(plan);
    }
}

/* A job system that runs a part's tasks last to first on two threads. */
typedef struct reversed {
    int count, parity;
    hb_task_fn task;
    void *context;
} reversed;

static void *run_reversed(void *arg)
{
    reversed *p = arg;
    for (int k = p->count - 1; k >= 0; k--)
        if (k % 2 == p->parity)
            p->task(p->context, k);
    return NULL;
}

static void reversed_on_two_threads(void *context, int count, hb_task_fn task, void *task_context)
{
    (void)context;
    reversed odd = { count, 1, task, task_context }, even = { count, 0, task, task_context };
    pthread_t thread;
    int started = pthread_create(&thread, NULL, run_reversed, &odd) == 0;
    run_reversed(&even);
    if (started)
        pthread_join(thread, NULL);
    else
        run_reversed(&odd);
}

static void test_same_on_any_job_system(hb_test_ctx *t)
{
    hb_plan *plan = assembly_plan(t, HB_MODEL_CHIANG, 0.3, 0.0, 0.035);
    if (!plan)
        return;
    hb_assembly a;
    hb_assembly_default(&a);
    a.paths = 20000, a.theta_bins = 4, a.phi_bins = 8, a.depth_bins = 4;
    static double rad[2][2 * 4 * 8 * 3], se[2][2 * 4 * 8 * 3], depth[2][4 * 9];
    hb_assembly_result r[2];
    for (int k = 0; k < 2; k++) {
        r[k] = (hb_assembly_result){ .struct_size = sizeof r[k], .radiance = rad[k], .radiance_se = se[k], .depth = depth[k] };
        CHECK(t, hb_assembly_trace(plan, &a, &r[k], NULL, NULL, k ? reversed_on_two_threads : NULL, NULL) == HB_OK, "%s",
              hb_last_error()->message);
    }
    r[1].radiance = r[0].radiance, r[1].radiance_se = r[0].radiance_se, r[1].depth = r[0].depth;
    CHECK(t, memcmp(&r[0], &r[1], sizeof r[0]) == 0, "the job system changed the sums");
    CHECK(t, memcmp(rad[0], rad[1], sizeof rad[0]) == 0 && memcmp(se[0], se[1], sizeof se[0]) == 0 &&
                 memcmp(depth[0], depth[1], sizeof depth[0]) == 0,
          "the job system changed the bins");
    double arrived = 0.0;
    for (int k = 0; k < 4 * 3; k++)
        arrived += depth[0][k * 3 + 1];
    CHECK(t, arrived > 0.5, "the light arriving at the fibres sums to %g", arrived);
    hb_plan_destroy(plan);
}

/* CBTB16's R alone, narrow in phi: the sampled w_i is w_o mirrored about the normal at azimuth
 * phi_o + asin(h), so phi_i = phi_o + 2 asin(h). */
static void test_h_convention(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.beta_m = m.beta_n = 0.05, m.alpha = 0.0;
    o.model = HB_MODEL_CHIANG, o.lobes = HB_LOBE_BIT(HB_LOBE_R);
    hb_plan *plan;
    hb_error e;
    CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "%s", e.message);
    if (t->failures)
        return;
    enum { N = 64 };
    float to[N], po[N], h[N], planes[HB_SAMPLE_DIMENSIONS][N], ti[N], pi[N], pdf[N], w[3][N];
    const float *u[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        for (int k = 0; k < N; k++)
            planes[d][k] = 0.5f, u[d] = planes[d];
    for (int k = 0; k < N; k++)
        to[k] = 0.2f, po[k] = 0.3f, h[k] = -0.9f + 1.8f * (float)k / (N - 1);
    hb_sample_near_in in = { to, po, h, u };
    hb_sample_out out = { ti, pi, pdf, { w[0], w[1], w[2] } };
    CHECK(t, hb_sample_near(plan, N, &in, &out, NULL) == HB_OK, "%s", hb_last_error()->message);
    double worst = 0.0;
    for (int k = 0; k < N; k++) {
        double want = po[k] + 2.0 * asin((double)h[k]), d = remainder((double)pi[k] - want, 2.0 * M_PI);
        worst = fmax(worst, fabs(d));
    }
    CHECK(t, worst < 0.05, "phi_i is %.3g from phi_o + 2 asin(h)", worst);
    hb_plan_destroy(plan);
}

static void test_refusals(hb_test_ctx *t)
{
    hb_plan *plan = assembly_plan(t, HB_MODEL_CHIANG, 0.3, 0.0, 0.035);
    if (!plan)
        return;
    hb_assembly a;
    hb_assembly_result r = { .struct_size = sizeof r };
    hb_assembly_default(&a);
    a.packing = 0.6;
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_ERR_PARAM &&
                 strstr(hb_last_error()->message, "assembly.packing"),
          "packing 0.6: %s", hb_last_error()->message);
    hb_assembly_default(&a);
    a.phi_light = 2.0;
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_ERR_PARAM &&
                 strstr(hb_last_error()->message, "phi_light"),
          "a slab lit from below: %s", hb_last_error()->message);
    hb_assembly_default(&a);
    a.layers = 2.0, a.packing = 0.5;
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_ERR_LIMIT &&
                 strstr(hb_last_error()->message, "reached packing"),
          "two layers at packing 0.5: %s", hb_last_error()->message);
    hb_assembly_default(&a);
    a.transport = (hb_assembly_transport)7;
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_ERR_PARAM &&
                 strstr(hb_last_error()->message, "assembly.transport"),
          "transport 7: %s", hb_last_error()->message);
    hb_assembly_default(&a);
    a.struct_size = 8;
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_ERR_VERSION, "struct_size 8 accepted");
    hb_plan_destroy(plan);
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = HB_MODEL_HUANG, o.quality = HB_QUALITY_FAST; /* TT and TRT by one traced path: the pdf is an estimate */
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK && hb_plan_pdf_is_estimate(plan), "HHH22 plan");
    hb_assembly_default(&a);
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_ERR_UNSUPPORTED &&
                 strstr(hb_last_error()->message, "HB_ASSEMBLY_SAMPLER_WEIGHTS"),
          "HHH22 under the light's transport: %s", hb_last_error()->message);
    a.transport = HB_ASSEMBLY_SAMPLER_WEIGHTS, a.paths = 512;
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_OK, "HHH22 under its sampler's weights: %s",
          hb_last_error()->message);
    hb_plan_destroy(plan);
    m.eccentricity = 0.5, o.model = HB_MODEL_MARSCHNER, o.quality = HB_QUALITY_BALANCED;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "MJC03 elliptical plan");
    hb_assembly_default(&a);
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_ERR_UNSUPPORTED &&
                 strstr(hb_last_error()->message, "elliptical"),
          "elliptical: %s", hb_last_error()->message);
    hb_plan_destroy(plan);
}

/* The reflected light of orders first .. HB_ASSEMBLY_ORDERS - 1 in channel c, and its standard error. */
static double reflected_orders(const hb_assembly_result *r, long long paths, int first, int c, double *se)
{
    double sum = 0.0, square = 0.0;
    for (int k = first; k < HB_ASSEMBLY_ORDERS; k++)
        sum += r->by_order[0][k][c], square += r->by_order_square[0][k][c];
    *se = sqrt(fmax(square - sum * sum, 0.0) / (double)(paths - 1));
    return sum;
}

/* What single scattering alone misses: CBTB16 slabs of 8 layers of five fibres at two packings and
 * two light inclinations (from straight above the slab), the reflected light, the part of it that
 * scattered more than once, with standard errors, under the light's transport. The orders' sums
 * agree with the reflected total and its standard error. The quick tier traces one cell with fewer
 * paths. */
static void test_single_scattering_share(hb_test_ctx *t)
{
    static const struct {
        const char *name;
        double eumelanin, pheomelanin;
    } fibres[] = { { "lossless", 0.0, 0.0 }, { "blond", 0.3, 0.0 }, { "brown", 1.3, 0.0 }, { "black", 8.0, 0.0 },
                   { "red", 0.0, 2.0 } };
    static const double packings[] = { 0.1, 0.3 }, thetas[] = { 0.0, 0.6 };
    long long paths = t->quick ? 2000 : 100000;
    hb_test_note(t, "CBTB16, slab of 8 layers lit from above (phi 0), green channel, %lld paths per cell:", paths);
    hb_test_note(t, "fibre     packing theta  reflected          scattered more than once       transmitted  absorbed  scatterings");
    for (size_t m = (size_t)t->quick; m < (t->quick ? 2 : sizeof fibres / sizeof fibres[0]); m++) {
        hb_material mat;
        hb_material_default(&mat);
        hb_plan *plan = assembly_plan(t, HB_MODEL_CHIANG, fibres[m].eumelanin, fibres[m].pheomelanin, mat.alpha);
        if (!plan)
            return;
        for (size_t p = (size_t)t->quick; p < sizeof packings / sizeof packings[0]; p++)
            for (size_t l = (size_t)t->quick; l < sizeof thetas / sizeof thetas[0]; l++) {
                hb_assembly a;
                hb_assembly_default(&a);
                a.packing = packings[p], a.theta_light = thetas[l], a.paths = paths;
                hb_assembly_result r = { .struct_size = sizeof r };
                CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_OK, "%s", hb_last_error()->message);
                double all_se, multiple_se, all = reflected_orders(&r, paths, 0, 1, &all_se);
                double multiple = reflected_orders(&r, paths, 2, 1, &multiple_se);
                CHECK(t, fabs(all - r.reflected[1]) < 1e-12 && fabs(all_se - r.reflected_se[1]) < 1e-9,
                      "%s: the orders sum to %.12g +- %.3g, reflected %.12g +- %.3g", fibres[m].name, all, all_se,
                      r.reflected[1], r.reflected_se[1]);
                CHECK(t, r.unfinished[1] < 1e-3, "%s: unfinished %.2g", fibres[m].name, r.unfinished[1]);
                hb_test_note(t, "%-9s %7.2f %5.1f  %.5f +- %.5f  %.5f +- %.5f (%4.1f%%)  %.4f       %.4f    %6.1f",
                             fibres[m].name, r.packing, a.theta_light, r.reflected[1], r.reflected_se[1], multiple, multiple_se,
                             r.reflected[1] > 0.0 ? 100.0 * multiple / r.reflected[1] : 0.0, r.transmitted[1], r.absorbed[1],
                             (double)r.events / (double)a.paths);
            }
        hb_plan_destroy(plan);
    }
}

/* A ray along a slab's face, in the gap below every fibre, ends after a fixed number of cells
 * (hb_fibres_hit: -1, the path unfinished) instead of walking the period for ever; the same ray
 * tilted into the slab leaves through the face or meets a fibre. */
static void test_ray_along_faces(hb_test_ctx *t)
{
    hb_assembly a;
    hb_assembly_default(&a);
    a.layers = 2.0, a.packing = 0.02, a.period = 16;
    hb_fibres f;
    CHECK(t, hb_fibres_place(&a, &f) == HB_OK, "%s", hb_last_error()->message);
    if (t->failures)
        return;
    double lowest = INFINITY, dist, cx, cz;
    for (long k = 0; k < f.count; k++)
        lowest = fmin(lowest, f.centre[2 * k + 1]);
    hb_ray2 along = { 0.0, 0.5 * (lowest - 1.0), 1.0, 0.0 }, down = { 0.0, 0.5 * (lowest - 1.0), 0.999, -0.0447 };
    CHECK(t, lowest > 1.0 + 1e-3, "%ld fibres, the lowest at z = %.6f", f.count, lowest);
    CHECK(t, hb_fibres_hit(&f, &along, NAN, NAN, &dist, &cx, &cz) == -1, "a ray along the face below every fibre");
    int hit = hb_fibres_hit(&f, &down, NAN, NAN, &dist, &cx, &cz);
    CHECK(t, hit == 0 && fabs(dist - hb_fibres_exit(&f, &down)) < 1e-12, "tilted out of the slab: %d at %g", hit, dist);
    hb_fibres_free(&f);
}

const hb_test hb_tests_assembly[] = {
    { "assembly_one_fibre", test_one_fibre, 1 },
    { "assembly_lossless", test_lossless, 0 },
    { "assembly_same_on_any_job_system", test_same_on_any_job_system, 0 },
    { "assembly_h_convention", test_h_convention, 0 },
    { "assembly_refusals", test_refusals, 0 },
    { "assembly_ray_along_faces", test_ray_along_faces, 0 },
    { "assembly_single_scattering_share", test_single_scattering_share, 0 },
    { NULL, NULL, 0 },
};

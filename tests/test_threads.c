/* Plans are immutable and shared between threads: four threads evaluating, sampling and taking
 * pdfs with the same plans, each over its own share of one batch, give bit for bit what one
 * thread gives. `make tsan` runs this test under ThreadSanitizer, kernels instrumented. */
#include <pthread.h>
#include <string.h>

#include "test.h"

enum { N = 2048, THREADS = 4, PLANS = 4 };

typedef struct shared_work {
    const hb_plan *plans[PLANS];
    const float *ti, *pi, *to, *po, *u[HB_SAMPLE_DIMENSIONS];
    float (*f)[3][N];       /* per plan: f */
    float (*sampled)[4][N]; /* per plan: theta_i, phi_i, pdf, weight (red) */
    int first, count;       /* this thread's share of the batch */
} shared_work;

static void run_share(const shared_work *w)
{
    size_t n = (size_t)w->count, k0 = (size_t)w->first;
    for (int p = 0; p < PLANS; p++) {
        float *f = w->f[p][0] + k0, *g = w->f[p][1] + k0, *b = w->f[p][2] + k0;
        hb_eval_angles(w->plans[p], n, (hb_angles_soa){ w->ti + k0, w->pi + k0, w->to + k0, w->po + k0 },
                       (hb_rgb_soa){ f, g, b }, NULL);
        /* HHH22's path sampler keys its numbers by the index within the call: a share draws others */
        if (hb_plan_sample_dimensions(w->plans[p]) == 0 || p == 3)
            continue;
        float *s[4] = { w->sampled[p][0] + k0, w->sampled[p][1] + k0, w->sampled[p][2] + k0, w->sampled[p][3] + k0 };
        const float *u[HB_SAMPLE_DIMENSIONS];
        for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
            u[d] = w->u[d] + k0;
        hb_sample_in in = { w->to + k0, w->po + k0, u };
        static float sink[2][THREADS * N];
        hb_sample_angles(w->plans[p], n, &in, &(hb_sample_out){ s[0], s[1], s[2], { s[3], sink[0] + k0, sink[1] + k0 } },
                         NULL);
    }
}

static void *thread_main(void *arg)
{
    run_share(arg);
    return NULL;
}

static void test_threads_share_plans(hb_test_ctx *t)
{
    static float ti[N], pi[N], to[N], po[N], u[HB_SAMPLE_DIMENSIONS][N];
    static float one_f[PLANS][3][N], many_f[PLANS][3][N], one_s[PLANS][4][N], many_s[PLANS][4][N];
    for (int k = 0; k < N; k++) {
        ti[k] = (float)(hb_test_uniform(t) * 3.1 - 1.55);
        to[k] = (float)(hb_test_uniform(t) * 3.1 - 1.55);
        pi[k] = (float)(hb_test_uniform(t) * 6.2 - 3.1);
        po[k] = (float)(hb_test_uniform(t) * 6.2 - 3.1);
    }
    float *planes[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        planes[d] = u[d];
    hb_uniforms(7, 0, N, HB_SAMPLE_DIMENSIONS, planes);
    hb_plan *plans[PLANS] = { NULL };
    static const hb_model models[PLANS] = { HB_MODEL_DEON, HB_MODEL_MARSCHNER, HB_MODEL_HUANG, HB_MODEL_HUANG };
    for (int p = 0; p < PLANS; p++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        m.eumelanin = 0.4;
        o.model = models[p];
        o.isa = t->isa;
        if (p == 0)
            o.azimuthal = HB_AZIMUTHAL_TABLE, o.quality = HB_QUALITY_FAST;
        if (p == 2)
            o.lobes = 1u << HB_LOBE_R; /* sampled exactly */
        if (p == 3)
            o.tt_trt = HB_TT_TRT_TABLE, o.quality = HB_QUALITY_FAST, m.roughness = 0.3;
        hb_error err;
        CHECK(t, hb_plan_create(&m, &o, &plans[p], &err) == HB_OK, "plan %d: %s", p, err.message);
    }
    for (int p = 0; p < PLANS; p++)
        if (!plans[p])
            goto done;
    shared_work one = { .ti = ti, .pi = pi, .to = to, .po = po, .f = one_f, .sampled = one_s, .first = 0, .count = N };
    memcpy(one.plans, plans, sizeof one.plans);
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        one.u[d] = u[d];
    run_share(&one);
    shared_work shares[THREADS];
    pthread_t threads[THREADS];
    int started = 0;
    for (int k = 0; k < THREADS; k++) {
        shares[k] = one;
        shares[k].f = many_f, shares[k].sampled = many_s;
        shares[k].first = k * (N / THREADS), shares[k].count = N / THREADS;
        started += pthread_create(&threads[k], NULL, thread_main, &shares[k]) == 0;
    }
    for (int k = 0; k < started; k++)
        pthread_join(threads[k], NULL);
    CHECK(t, started == THREADS, "started %d of %d threads", started, THREADS);
    CHECK(t, memcmp(one_f, many_f, sizeof one_f) == 0, "threads' f differ from one thread's");
    CHECK(t, memcmp(one_s, many_s, sizeof one_s) == 0, "threads' samples differ from one thread's");
done:
    for (int p = 0; p < PLANS; p++)
        hb_plan_destroy(plans[p]);
}

const hb_test hb_tests_threads[] = {
    { "threads_share_plans", test_threads_share_plans, 1 },
    { NULL, NULL, 0 },
};

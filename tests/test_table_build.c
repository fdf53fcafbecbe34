/* Long table builds: progress is reported non-decreasing up to 1 and can cancel, and a build run
 * through a job system (hb_options.parallel, its tasks in any order and on several threads) gives
 * the same table bit for bit as one thread. */
#include <pthread.h>
#include <string.h>

#include "test.h"

enum { MAX_REPORTS = 256, MAX_TASKS = 1024 };

typedef struct progress_log {
    int reports, cancel_at; /* cancel_at: return nonzero at that report (0: never) */
    double fraction[MAX_REPORTS];
} progress_log;

static int log_progress(void *context, double fraction)
{
    progress_log *log = context;
    if (log->reports < MAX_REPORTS)
        log->fraction[log->reports] = fraction;
    return ++log->reports == log->cancel_at;
}

/* A job system that runs a part's tasks last to first, on two threads (odd and even indices). */
typedef struct reversed_part {
    int count, parity;
    hb_task_fn task;
    void *task_context;
    int *calls;
} reversed_part;

static void *run_parity(void *arg)
{
    reversed_part *p = arg;
    for (int k = p->count - 1; k >= 0; k--)
        if (k % 2 == p->parity) {
            p->task(p->task_context, k);
            p->calls[k]++; /* k is this thread's alone */
        }
    return NULL;
}

static void reversed_on_two_threads(void *context, int count, hb_task_fn task, void *task_context)
{
    int *calls = context; /* calls[k]: how often task k ran, over the whole build's parts */
    static int part_calls[MAX_TASKS];
    if (count > MAX_TASKS)
        return;
    memset(part_calls, 0, sizeof part_calls);
    reversed_part odd = { count, 1, task, task_context, part_calls }, even = { count, 0, task, task_context, part_calls };
    pthread_t thread;
    int started = pthread_create(&thread, NULL, run_parity, &odd) == 0;
    run_parity(&even);
    if (started)
        pthread_join(thread, NULL);
    else
        run_parity(&odd);
    for (int k = 0; k < count; k++)
        calls[part_calls[k] == 1 ? 0 : 1]++; /* calls[0] counts tasks run once, calls[1] any other */
}

static void table_plan_options(int huang, hb_material *m, hb_options *o, hb_isa isa)
{
    hb_material_default(m);
    hb_options_default(o);
    o->isa = isa;
    if (huang)
        o->model = HB_MODEL_HUANG, o->tt_trt = HB_TT_TRT_TABLE, o->quality = HB_QUALITY_FAST, m->roughness = 0.3;
    else
        o->azimuthal = HB_AZIMUTHAL_TABLE; /* balanced: a few refinements */
}

static void test_progress_and_cancel(hb_test_ctx *t)
{
    for (int huang = 0; huang < 2; huang++) {
        hb_material m;
        hb_options o;
        table_plan_options(huang, &m, &o, t->isa);
        progress_log log = { 0, 0, { 0 } };
        o.progress = log_progress, o.progress_context = &log;
        hb_plan *plan;
        hb_error error;
        CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_OK, "%s", error.message);
        hb_plan_destroy(plan);
        int monotone = log.reports >= 2 && log.reports <= MAX_REPORTS && log.fraction[0] >= 0.0;
        for (int k = 1; monotone && k < log.reports; k++)
            monotone = log.fraction[k] >= log.fraction[k - 1];
        CHECK(t, monotone && log.fraction[log.reports - 1] == 1.0, "%s: %d reports, non-decreasing to 1 (last %g)",
              huang ? "huang" : "deon", log.reports, log.reports ? log.fraction[log.reports - 1] : -1.0);
        hb_test_note(t, "%s: %d progress reports", huang ? "huang" : "deon", log.reports);
        for (int at = 1; at <= log.reports && at <= MAX_REPORTS; at += log.reports / 3 + 1) {
            progress_log cancel = { 0, at, { 0 } };
            o.progress_context = &cancel;
            hb_status st = hb_plan_create(&m, &o, &plan, &error);
            CHECK(t, st == HB_ERR_CANCELLED && !plan && strstr(error.message, "cancelled") && cancel.reports == at,
                  "%s: cancel at report %d gave status %d after %d reports: %s", huang ? "huang" : "deon", at, (int)st,
                  cancel.reports, error.message);
            hb_plan_destroy(plan);
        }
    }
    /* a plan without a table never calls back */
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    progress_log log = { 0, 1, { 0 } };
    o.progress = log_progress, o.progress_context = &log;
    hb_plan *plan;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK && log.reports == 0, "quadrature plan: %d reports", log.reports);
    hb_plan_destroy(plan);
}

static void test_parallel_same_table(hb_test_ctx *t)
{
    for (int huang = 0; huang < 2; huang++) {
        hb_material m;
        hb_options o;
        table_plan_options(huang, &m, &o, t->isa);
        hb_plan *serial, *parallel;
        hb_error error;
        CHECK(t, hb_plan_create(&m, &o, &serial, &error) == HB_OK, "%s", error.message);
        int calls[2] = { 0, 0 };
        o.parallel = reversed_on_two_threads, o.parallel_context = calls;
        CHECK(t, hb_plan_create(&m, &o, &parallel, &error) == HB_OK, "%s", error.message);
        hb_table_view a = { .struct_size = sizeof a }, b = { .struct_size = sizeof b };
        CHECK(t, hb_plan_table(serial, &a) == HB_OK && hb_plan_table(parallel, &b) == HB_OK && a.count == b.count &&
                     memcmp(a.values, b.values, a.count * sizeof *a.values) == 0,
              "%s: the table built through the job system differs from one thread's", huang ? "huang" : "deon");
        CHECK(t, calls[0] > 0 && calls[1] == 0, "%s: %d tasks ran once, %d did not", huang ? "huang" : "deon", calls[0],
              calls[1]);
        hb_plan_destroy(serial), hb_plan_destroy(parallel);
    }
}

/* hb_dual_terms_grid: the rows through the job system equal one thread's and hb_dual_terms_at's, bit
 * for bit; progress rises to 1 and cancels. */
static void test_dual_grid(hb_test_ctx *t)
{
    enum { COUNT = 24 };
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = 0.3, o.quality = HB_QUALITY_FAST, o.isa = t->isa;
    hb_plan *plan;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "dFH11 plan");
    if (!plan)
        return;
    static hb_dual_terms serial[COUNT], parallel[COUNT], one;
    serial[0].struct_size = parallel[0].struct_size = one.struct_size = sizeof one;
    progress_log log = { 0, 0, { 0 } };
    int calls[2] = { 0, 0 };
    CHECK(t, hb_dual_terms_grid(plan, COUNT, HB_DUAL_DENSITY, serial, log_progress, &log, NULL, NULL) == HB_OK &&
                 hb_dual_terms_grid(plan, COUNT, HB_DUAL_DENSITY, parallel, NULL, NULL, reversed_on_two_threads, calls) ==
                     HB_OK,
          "grid: %s", hb_last_error()->message);
    int differ = memcmp(serial, parallel, sizeof serial) != 0;
    for (int k = 0; k < COUNT; k++) {
        hb_dual_terms_at(plan, -M_PI_2 + M_PI * (k + 0.5) / COUNT, HB_DUAL_DENSITY, &one);
        differ += memcmp(&one, &serial[k], sizeof one) != 0;
    }
    CHECK(t, differ == 0 && calls[0] == COUNT && calls[1] == 0, "%d rows differ; %d tasks ran once, %d not", differ,
          calls[0], calls[1]);
    int rising = log.reports > 1 && log.fraction[log.reports - 1] == 1.0;
    for (int k = 1; k < log.reports && k < MAX_REPORTS; k++)
        rising = rising && log.fraction[k] >= log.fraction[k - 1];
    CHECK(t, rising, "%d progress reports, last %g", log.reports, log.reports ? log.fraction[log.reports - 1] : 0.0);
    progress_log cancel = { 0, 2, { 0 } };
    CHECK(t, hb_dual_terms_grid(plan, COUNT, HB_DUAL_DENSITY, serial, log_progress, &cancel, NULL, NULL) ==
                 HB_ERR_CANCELLED && cancel.reports == 2,
          "cancel at the second report: %d reports", cancel.reports);
    hb_plan_destroy(plan);
}

const hb_test hb_tests_table_build[] = {
    { "dual_grid_tasks", test_dual_grid, 1 },
    { "table_build_progress_and_cancel", test_progress_and_cancel, 0 },
    { "table_build_parallel_same_table", test_parallel_same_table, 1 },
    { NULL, NULL, 0 },
};

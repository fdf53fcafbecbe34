/* hb_build_tasks: a table build's rows through the caller's job system and progress callback. */
#include "build_tasks.h"

typedef struct part_run {
    hb_task_fn task;
    void *context;
    int first;
} part_run;

static void run_in_part(void *run, int k)
{
    const part_run *r = run;
    r->task(r->context, r->first + k);
}

static hb_status report(const hb_options *o, double fraction, hb_error *error)
{
    if (o->progress && o->progress(o->progress_context, fraction))
        return hb_plan_fail(error, HB_ERR_CANCELLED, "cancelled by the progress callback at %.0f%%", 100.0 * fraction);
    return HB_OK;
}

hb_status hb_build_finish(const hb_options *o, hb_error *error) { return report(o, 1.0, error); }

hb_status hb_build_tasks(const hb_options *o, int count, int part, hb_task_fn task, void *context, double from,
                         double to, hb_error *error)
{
    for (int first = 0; first < count; first += part) {
        int n = count - first < part ? count - first : part;
        part_run run = { task, context, first };
        if (o->parallel)
            o->parallel(o->parallel_context, n, run_in_part, &run);
        else
            for (int k = 0; k < n; k++)
                run_in_part(&run, k);
        hb_status st = report(o, from + (to - from) * (double)(first + n) / (double)count, error);
        if (st != HB_OK)
            return st;
    }
    return HB_OK;
}

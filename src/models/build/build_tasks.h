/* Table builds as tasks: rows run in parts, each part's rows as parallel tasks where the caller's
 * options give a job system, with progress reported and cancellation honoured between parts. Internal. */
#ifndef HB_MODELS_BUILD_TASKS_H
#define HB_MODELS_BUILD_TASKS_H

#include "models/interface/plan.h"

#define HB_BUILD_PARTS 8 /* a build reports progress (and may be cancelled) about this often; a part's tasks run in parallel */

/* Runs task(context, k) for every k in [0, count), in parts of `part` tasks (k % part is a task's
 * slot within its part, for per-slot scratch); after each part reports from + (to - from) times the
 * share done to options->progress. HB_ERR_CANCELLED (with a message) when progress asks. */
hb_status hb_build_tasks(const hb_options *options, int count, int part, hb_task_fn task, void *context, double from,
                         double to, hb_error *error);

/* Reports the end of a build (fraction 1); HB_ERR_CANCELLED when progress asks even then. */
hb_status hb_build_finish(const hb_options *options, hb_error *error);

/* The part size for count tasks: about count / HB_BUILD_PARTS, at least 1. */
static inline int hb_build_part(int count) { return count / HB_BUILD_PARTS > 1 ? count / HB_BUILD_PARTS : 1; }

#endif

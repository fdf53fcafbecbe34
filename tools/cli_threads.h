/* The CLI's job system for long plan creations (hb_options.parallel) and its progress line. */
#ifndef HB_CLI_THREADS_H
#define HB_CLI_THREADS_H

#include "hairbsdf.h"

/* hb_parallel_fn over *(int *)context threads (each call starts them and joins them). */
void cli_parallel(void *context, int count, hb_task_fn task, void *task_context);

/* hb_progress_fn printing "building the table: N%" to stderr; never cancels. */
int cli_progress(void *context, double fraction);

/* hb_progress_fn printing "tracing: N%" to stderr, for the assembly's paths; never cancels. */
int cli_tracing_progress(void *context, double fraction);

#endif

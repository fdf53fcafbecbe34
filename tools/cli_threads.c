/* cli_parallel: a part's tasks shared by a few POSIX threads, each taking the next index. */
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>

#include "cli_threads.h"

enum { MAX_THREADS = 64 };

typedef struct shared_part {
    hb_task_fn task;
    void *context;
    int count;
    atomic_int next;
} shared_part;

static void *worker(void *arg)
{
    shared_part *p = arg;
    for (int k; (k = atomic_fetch_add(&p->next, 1)) < p->count;)
        p->task(p->context, k);
    return NULL;
}

void cli_parallel(void *context, int count, hb_task_fn task, void *task_context)
{
    int threads = *(const int *)context;
    threads = threads > count ? count : threads > MAX_THREADS ? MAX_THREADS : threads;
    shared_part part = { task, task_context, count, 0 };
    pthread_t started[MAX_THREADS];
    int n = 0;
    while (n + 1 < threads && pthread_create(&started[n], NULL, worker, &part) == 0)
        n++;
    worker(&part); /* this thread works too, and alone if no thread could start */
    for (int k = 0; k < n; k++)
        pthread_join(started[k], NULL);
}

int cli_progress(void *context, double fraction)
{
    (void)context;
    fprintf(stderr, "building the table: %.0f%%\n", 100.0 * fraction);
    return 0;
}

int cli_tracing_progress(void *context, double fraction)
{
    (void)context;
    fprintf(stderr, "tracing: %.0f%%\n", 100.0 * fraction);
    return 0;
}

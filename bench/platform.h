/* What the bench needs of the operating system, on Linux and on Windows (MinGW-w64): the core
 * count, pinning to a core, threads started on a core, and text collected in memory. */
#ifndef HB_BENCH_PLATFORM_H
#define HB_BENCH_PLATFORM_H

#include <pthread.h>
#include <stdio.h>

long bench_cores(void);

/* Pins the calling thread to `core`; 0 on success. */
int bench_pin_self(int core);

/* Starts run(arg) on a thread that runs on `core` from its start; 0 on success. */
int bench_thread_start(pthread_t *thread, int core, void *(*run)(void *), void *arg);

/* A stream whose text bench_text_close returns (malloc'd, NUL-terminated; NULL if it failed). */
FILE *bench_text_open(void);
char *bench_text_close(FILE *f);

#endif

/* bench/platform.h on Linux (sched and pthread affinity, sysconf) and Windows (thread affinity
 * masks, GetSystemInfo); text in a temporary file, read back, on both. */
#include "platform.h"

#include <stdlib.h>

#ifdef _WIN32
#include <windows.h>

long bench_cores(void)
{
    SYSTEM_INFO info;
    GetSystemInfo(&info);
    return (long)info.dwNumberOfProcessors;
}

int bench_pin_self(int core)
{
    return SetThreadAffinityMask(GetCurrentThread(), (DWORD_PTR)1 << core) ? 0 : -1;
}

typedef struct pinned_start {
    int core;
    void *(*run)(void *);
    void *arg;
} pinned_start;

static void *run_pinned(void *start)
{
    pinned_start s = *(pinned_start *)start;
    free(start);
    bench_pin_self(s.core);
    return s.run(s.arg);
}

int bench_thread_start(pthread_t *thread, int core, void *(*run)(void *), void *arg)
{
    pinned_start *s = malloc(sizeof *s);
    if (!s)
        return -1;
    *s = (pinned_start){ core, run, arg };
    if (pthread_create(thread, NULL, run_pinned, s) == 0)
        return 0;
    free(s);
    return -1;
}

#else
#include <sched.h>
#include <unistd.h>

long bench_cores(void) { return sysconf(_SC_NPROCESSORS_ONLN); }

int bench_pin_self(int core)
{
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(core, &set);
    return sched_setaffinity(0, sizeof set, &set);
}

/* Pinned in its attributes, not by itself, which it could only do once the core it was started on
 * let it run. */
int bench_thread_start(pthread_t *thread, int core, void *(*run)(void *), void *arg)
{
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(core, &set);
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    pthread_attr_setaffinity_np(&attr, sizeof set, &set);
    int st = pthread_create(thread, &attr, run, arg);
    pthread_attr_destroy(&attr);
    return st == 0 ? 0 : -1;
}
#endif

FILE *bench_text_open(void) { return tmpfile(); }

char *bench_text_close(FILE *f)
{
    if (!f)
        return NULL;
    long n = ftell(f);
    char *text = n >= 0 ? malloc((size_t)n + 1) : NULL;
    rewind(f);
    if (text && fread(text, 1, (size_t)n, f) == (size_t)n)
        text[n] = '\0';
    else
        free(text), text = NULL;
    fclose(f);
    return text;
}

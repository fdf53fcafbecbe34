/* The calling core's clock, measured: a dependent chain of register-to-register integer additions
 * runs one addition per cycle on every x86-64 and AArch64 core, so additions per nanosecond are
 * cycles per nanosecond, at whatever frequency the core runs now. The addend is a register, not an
 * immediate: cores from Intel's Golden Cove on fold chains of immediate additions at rename, several
 * a cycle, which would read as several times the core's clock. The bench writes costs in cycles with it, and
 * budget plans convert a calibration's cycles to this machine's nanoseconds with it. */
#include "isas.h"

#define ADD8(op) op op op op op op op op
#define ADDS_PER_STEP 64

#if defined(__GNUC__) && defined(__x86_64__)
#define CHAIN_STEP(x, one) __asm__ volatile(ADD8(ADD8("add %1, %0\n\t")) : "+r"(x) : "r"(one))
#elif defined(__GNUC__) && defined(__aarch64__)
#define CHAIN_STEP(x, one) __asm__ volatile(ADD8(ADD8("add %0, %0, %1\n\t")) : "+r"(x) : "r"(one))
#endif

#ifdef CHAIN_STEP
#if defined(_WIN32)
#include <windows.h>

static double now_ns(void)
{
    LARGE_INTEGER count, frequency;
    QueryPerformanceCounter(&count);
    QueryPerformanceFrequency(&frequency);
    return (double)count.QuadPart * (1e9 / (double)frequency.QuadPart);
}
#else
#include <time.h>

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}
#endif

enum { STEPS = 8192, TRIALS = 8 };

/* ns for STEPS chain steps; the loop's own counter runs beside the chain, off its critical path. */
static double chain_ns(unsigned long long *sink)
{
    unsigned long long x = *sink, one = 1;
    double t0 = now_ns();
    for (int k = 0; k < STEPS; k++)
        CHAIN_STEP(x, one);
    double t = now_ns() - t0;
    *sink = x;
    return t;
}

double hb_cpu_clock_ghz(void)
{
    unsigned long long sink = 0;
    double best = chain_ns(&sink); /* the first trial wakes the core's clock up */
    for (int k = 0; k < TRIALS; k++) {
        double t = chain_ns(&sink);
        best = t < best ? t : best;
    }
    return best > 0.0 && sink == (unsigned long long)(TRIALS + 1) * STEPS * ADDS_PER_STEP
               ? (double)STEPS * ADDS_PER_STEP / best
               : 0.0;
}
#else
double hb_cpu_clock_ghz(void)
{
    return 0.0;
}
#endif

/* Runs every test: ISA-independent ones once, the others once per ISA this CPU has (or those
 * listed in $HB_TEST_ISAS, comma-separated, else $HB_ISA), one line per test. Under emulation
 * ($HB_TEST_EMULATED, qemu) the quick tier runs the tests that depend on the ISA: the others check
 * the same C code that the native run checks, at twenty times the cost. Options: --long (the long tier: every test's full case set; the
 * default is the quick tier's subset of cases), --verbose (each test's measurements), --filter
 * SUBSTRING, --seed N, --list, --figures (writes the measurements into the pages' blocks, figures.h). */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "figures.h"
#include "test.h"

/* A failing check prints this many lines per test and ISA, then a count of the rest. */
#define MAX_REPORTED_FAILURES 20

static int verbose;

void hb_test_fail(hb_test_ctx *t, const char *file, int line, const char *fmt, ...)
{
    if (t->failures++ < MAX_REPORTED_FAILURES) {
        va_list ap;
        va_start(ap, fmt);
        printf("    FAIL [%s] %s:%d: ", t->isa == HB_ISA_AUTO ? "-" : hb_isa_name(t->isa), file, line);
        vprintf(fmt, ap);
        printf("\n");
        va_end(ap);
    }
}

/* Prints a note with --verbose; a measurement (keep) is also kept for --figures. */
static void report(hb_test_ctx *t, int keep, const char *fmt, va_list ap)
{
    char line[1024];
    vsnprintf(line, sizeof line, fmt, ap);
    if (verbose)
        printf("    %s [%s]: %s\n", t->name, t->isa == HB_ISA_AUTO ? "-" : hb_isa_name(t->isa), line);
    if (keep && hb_figures_enabled())
        hb_figures_record(t->name, t->isa, line);
}

void hb_test_note(hb_test_ctx *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report(t, 1, fmt, ap);
    va_end(ap);
}

void hb_test_detail(hb_test_ctx *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report(t, 0, fmt, ap);
    va_end(ap);
}

void hb_test_skip(hb_test_ctx *t, const char *reason)
{
    t->skipped = 1;
    snprintf(t->skip_reason, sizeof t->skip_reason, "%s", reason);
}

const char *hb_test_tool(hb_test_ctx *t)
{
    const char *tool = getenv("HB_TOOL");
    if (tool && *tool)
        return tool;
    CHECK(t, 0, "HB_TOOL is not set (make test sets it)");
    return NULL;
}

char *hb_test_read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long length = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = length >= 0 ? malloc((size_t)length + 1) : NULL;
    size_t got = text ? fread(text, 1, (size_t)length, f) : 0;
    fclose(f);
    if (text)
        text[got] = '\0';
    if (size)
        *size = got;
    return text;
}

double hb_test_uniform(hb_test_ctx *t)
{
    uint64_t z = (t->rng += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1p-53;
}

void hb_test_vectors_of(float theta_i, float phi_i, float theta_o, float phi_o, float *const w[6], size_t k)
{
    const double dirs[2][2] = { { theta_i, phi_i }, { theta_o, phi_o } };
    for (int d = 0; d < 2; d++) {
        w[3 * d][k] = (float)(sin(dirs[d][1]) * cos(dirs[d][0]));
        w[3 * d + 1][k] = (float)sin(dirs[d][0]);
        w[3 * d + 2][k] = (float)(cos(dirs[d][1]) * cos(dirs[d][0]));
    }
}

double hb_test_spec_error(float *const f[3], float *const ref[3], size_t n, size_t *worst_sample)
{
    double peak = 0.0, worst = 0.0;
    for (int c = 0; c < 3; c++)
        for (size_t k = 0; k < n; k++)
            peak = fmax(peak, ref[c][k]);
    for (int c = 0; c < 3; c++)
        for (size_t k = 0; k < n; k++) {
            double e = fabs((double)f[c][k] - ref[c][k]) / fmax(ref[c][k], 1e-3 * peak);
            if (!(e <= worst)) { /* NaN counts as the worst */
                worst = isnan(e) ? INFINITY : e;
                if (worst_sample)
                    *worst_sample = k;
            }
        }
    return worst;
}

double hb_test_ulp_error(float got, double want)
{
    if (isnan(want) || isnan(got))
        return isnan(want) && isnan(got) ? 0.0 : INFINITY;
    if (isinf(want) || isinf(got))
        return (double)got == want ? 0.0 : INFINITY;
    int e;
    frexp(want, &e);                         /* |want| in [2^(e-1), 2^e) */
    double ulp = ldexp(1.0, (e - 1 < -126 ? -126 : e - 1) - 23);
    return fabs((double)got - want) / ulp;
}

void hb_test_longitudinal_setup(const hb_test_ctx *t, hb_material *m, hb_options *o)
{
    hb_material_default(m);
    hb_options_default(o);
    o->term = HB_TERM_LONGITUDINAL;
    o->isa = t->isa == HB_ISA_AUTO ? HB_ISA_SCALAR : t->isa;
}

static const hb_test *const suites[] = { hb_tests_api, hb_tests_vmath, hb_tests_longitudinal, hb_tests_deon,
                                          hb_tests_marschner, hb_tests_marschner_full, hb_tests_huang, hb_tests_huang_paper, hb_tests_sample, hb_tests_sample_huang, hb_tests_huang_internal, hb_tests_huang_table, hb_tests_properties, hb_tests_corpus, hb_tests_cli, hb_tests_images, hb_tests_deon_table, hb_tests_table_file, hb_tests_table_build, hb_tests_absorption, hb_tests_shaders, hb_tests_colour_table, hb_tests_plan_select, hb_tests_threads, hb_tests_chiang, hb_tests_renderer_calls, hb_tests_colour, hb_tests_deon_near, hb_tests_marschner_sample, hb_tests_docs, hb_tests_api_matrix, hb_tests_dual, hb_tests_near_vectors, hb_tests_convert, hb_tests_assembly, hb_tests_dual_eval, hb_tests_dual_engine, hb_tests_assembly_dual, hb_tests_spectral, hb_tests_spectral_eval };

const hb_test *hb_test_find(const char *name)
{
    size_t n = strlen(name);
    int prefix = n && name[n - 1] == '*';
    for (size_t s = 0; s < sizeof suites / sizeof suites[0]; s++)
        for (const hb_test *test = suites[s]; test->name; test++)
            if (prefix ? !strncmp(test->name, name, n - 1) : !strcmp(test->name, name))
                return test;
    return NULL;
}

/* The line under each block `make figures` writes: the date, the compiler, the tier and seed. */
static void figures_run(char *run, size_t capacity, uint64_t seed)
{
    char date[16];
    time_t now = time(NULL);
    strftime(date, sizeof date, "%Y-%m-%d", gmtime(&now));
#ifdef __clang__
    const char *compiler = "clang";
#else
    const char *compiler = "gcc";
#endif
    snprintf(run, capacity, "`make figures`, %s, %s %s, long tier, seed %llu", date, compiler, __VERSION__,
             (unsigned long long)seed);
}

static uint64_t name_hash(const char *s)
{
    uint64_t h = 1469598103934665603ull;
    while (*s)
        h = (h ^ (unsigned char)*s++) * 1099511628211ull;
    return h;
}

/* Whether the comma-separated list names isa. */
static int isa_listed(const char *list, hb_isa isa)
{
    const char *name = hb_isa_name(isa);
    size_t length = strlen(name);
    for (const char *p = list; *p; p += strcspn(p, ","), p += *p == ',')
        if (strncmp(p, name, length) == 0 && (p[length] == ',' || p[length] == '\0'))
            return 1;
    return 0;
}

static double seconds_now(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec + (double)now.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    const char *filter = NULL;
    uint64_t seed = 20261124;
    int list = 0, long_tier = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--filter") == 0 && i + 1 < argc)
            filter = argv[++i];
        else if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc)
            seed = strtoull(argv[++i], NULL, 0);
        else if (strcmp(argv[i], "--list") == 0)
            list = 1;
        else if (strcmp(argv[i], "--long") == 0)
            long_tier = 1;
        else if (strcmp(argv[i], "--verbose") == 0 || strcmp(argv[i], "-v") == 0)
            verbose = 1;
        else if (strcmp(argv[i], "--figures") == 0)
            hb_figures_enable();
        else {
            fprintf(stderr, "usage: %s [--long] [--verbose] [--filter SUBSTRING] [--seed N] [--list] [--figures]\n",
                    argv[0]);
            return 2;
        }
    }
    const char *emulation = getenv("HB_TEST_EMULATED");
    int emulated = emulation && *emulation && strcmp(emulation, "0") != 0;
    hb_isa isas[HB_ISA_COUNT];
    int nisa = 0;
    const char *env = getenv("HB_TEST_ISAS");
    if (!env || !*env)
        env = getenv("HB_ISA");
    int isa_named = env && *env;
    for (int i = HB_ISA_SCALAR; i < HB_ISA_COUNT; i++)
        if (hb_isa_available((hb_isa)i) && (!env || !*env || isa_listed(env, (hb_isa)i)))
            isas[nisa++] = (hb_isa)i;
    printf("%s tier, seed %llu (rerun with --seed %llu)%s; ISAs:", long_tier ? "long" : "quick",
           (unsigned long long)seed, (unsigned long long)seed,
           !emulated ? "" : long_tier || isa_named ? ", emulated" : ", emulated (per-ISA tests on the vector ISAs)");
    for (int i = 0; i < nisa; i++)
        printf(" %s", hb_isa_name(isas[i]));
    printf("\n");

    unsigned passed = 0, failed = 0, skipped = 0;
    double start = seconds_now();
    for (size_t s = 0; s < sizeof suites / sizeof suites[0]; s++) {
        for (const hb_test *test = suites[s]; test->name; test++) {
            if (filter && !strstr(test->name, filter))
                continue;
            if (list) {
                printf("%s [%s]\n", test->name, test->per_isa ? "every ISA" : "-");
                continue;
            }
            if (emulated && !long_tier && !test->per_isa) { /* the same source's native run has it */
                skipped++;
                continue;
            }
            int runs = test->per_isa ? nisa : 1;
            /* emulated quick tier: the per-ISA tests on the vector ISAs, the scalar one being the native
             * runs' source (the vector plans still reach it for their calls of one sample) */
            int first = emulated && !long_tier && test->per_isa && !isa_named && nisa > 1 && isas[0] == HB_ISA_SCALAR;
            char failing[64] = "";
            int skipped_runs = 0;
            char skip_reason[160] = "";
            double t0 = seconds_now();
            for (int r = first; r < runs; r++) {
                hb_test_ctx t = { test->name, test->per_isa ? isas[r] : HB_ISA_AUTO, NULL,
                                  seed ^ name_hash(test->name), 0, !long_tier, emulated, 0, "" };
                t.hooks = test->per_isa ? hb_kernel_hooks_for(t.isa) : NULL;
                test->run(&t);
                fflush(stdout);
                if (t.failures > MAX_REPORTED_FAILURES)
                    printf("    ... and %u more failed checks\n", t.failures - MAX_REPORTED_FAILURES);
                if (t.skipped && !t.failures) {
                    skipped++, skipped_runs++;
                    snprintf(skip_reason, sizeof skip_reason, "%s", t.skip_reason);
                    continue;
                }
                if (t.failures) {
                    failed++;
                    size_t used = strlen(failing);
                    snprintf(failing + used, sizeof failing - used, " %s", test->per_isa ? hb_isa_name(t.isa) : "-");
                } else {
                    passed++;
                }
            }
            double ms = (seconds_now() - t0) * 1e3;
            if (*failing)
                printf("FAIL %s [%s ] %.0f ms\n", test->name, failing, ms);
            else if (skipped_runs == runs - first)
                printf("skip %s: %s\n", test->name, skip_reason);
            else
                printf("ok   %s%s %.0f ms\n", test->name, test->per_isa ? " [every ISA]" : "", ms);
            fflush(stdout);
        }
    }
    if (list)
        return 0;
    printf("%.1f s\n", seconds_now() - start);
    if (hb_figures_enabled()) {
        char run[256];
        figures_run(run, sizeof run, seed);
        if (hb_figures_write(run))
            failed++;
    }
    if (skipped)
        printf("%u passed, %u failed, %u skipped\n", passed, failed, skipped);
    else
        printf("%u passed, %u failed\n", passed, failed);
    return failed ? 1 : 0;
}

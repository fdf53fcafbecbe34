/* Runs every test: ISA-independent ones once, the others once per ISA this CPU has
 * (or only $HB_ISA). Options: --filter SUBSTRING, --seed N, --list. */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "test.h"

#define MAX_REPORTED_FAILURES 6

void hb_test_fail(hb_test_ctx *t, const char *file, int line, const char *fmt, ...)
{
    if (t->failures++ < MAX_REPORTED_FAILURES) {
        va_list ap;
        va_start(ap, fmt);
        printf("    FAIL %s:%d: ", file, line);
        vprintf(fmt, ap);
        printf("\n");
        va_end(ap);
    }
}

void hb_test_note(hb_test_ctx *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    printf("    %s: ", t->name);
    vprintf(fmt, ap);
    printf("\n");
    va_end(ap);
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
                                          hb_tests_marschner, hb_tests_marschner_full, hb_tests_huang, hb_tests_sample, hb_tests_sample_huang, hb_tests_huang_internal, hb_tests_huang_table, hb_tests_properties, hb_tests_corpus, hb_tests_cli, hb_tests_images, hb_tests_deon_table, hb_tests_plan_select };

static uint64_t name_hash(const char *s)
{
    uint64_t h = 1469598103934665603ull;
    while (*s)
        h = (h ^ (unsigned char)*s++) * 1099511628211ull;
    return h;
}

int main(int argc, char **argv)
{
    const char *filter = NULL;
    uint64_t seed = 20261124;
    int list = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--filter") == 0 && i + 1 < argc)
            filter = argv[++i];
        else if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc)
            seed = strtoull(argv[++i], NULL, 0);
        else if (strcmp(argv[i], "--list") == 0)
            list = 1;
        else {
            fprintf(stderr, "usage: %s [--filter SUBSTRING] [--seed N] [--list]\n", argv[0]);
            return 2;
        }
    }
    const char *emulation = getenv("HB_TEST_EMULATED");
    int emulated = emulation && *emulation && strcmp(emulation, "0") != 0;
    hb_isa isas[HB_ISA_COUNT];
    int nisa = 0;
    const char *env = getenv("HB_ISA");
    for (int i = HB_ISA_SCALAR; i < HB_ISA_COUNT; i++)
        if (hb_isa_available((hb_isa)i) && (!env || !*env || hb_isa_from_name(env) == (hb_isa)i))
            isas[nisa++] = (hb_isa)i;
    printf("seed %llu (rerun with --seed %llu)%s; ISAs:", (unsigned long long)seed, (unsigned long long)seed,
           emulated ? ", emulated: heavy model tests run fewer cases" : "");
    for (int i = 0; i < nisa; i++)
        printf(" %s", hb_isa_name(isas[i]));
    printf("\n");

    unsigned passed = 0, failed = 0;
    for (size_t s = 0; s < sizeof suites / sizeof suites[0]; s++) {
        for (const hb_test *test = suites[s]; test->name; test++) {
            if (filter && !strstr(test->name, filter))
                continue;
            int runs = test->per_isa ? nisa : 1;
            for (int r = 0; r < runs; r++) {
                hb_test_ctx t = { test->name, test->per_isa ? isas[r] : HB_ISA_AUTO, NULL,
                                  seed ^ name_hash(test->name), 0, emulated };
                t.kernels = test->per_isa ? hb_kernels_for(t.isa) : NULL;
                if (list) {
                    printf("%s [%s]\n", test->name, test->per_isa ? hb_isa_name(t.isa) : "-");
                    continue;
                }
                struct timespec t0, t1;
                clock_gettime(CLOCK_MONOTONIC, &t0);
                test->run(&t);
                clock_gettime(CLOCK_MONOTONIC, &t1);
                double ms = (t1.tv_sec - t0.tv_sec) * 1e3 + (t1.tv_nsec - t0.tv_nsec) / 1e6;
                printf("%s %s [%s] %.0f ms\n", t.failures ? "FAIL" : "ok  ", test->name,
                       test->per_isa ? hb_isa_name(t.isa) : "-", ms);
                fflush(stdout);
                if (t.failures)
                    failed++;
                else
                    passed++;
            }
        }
    }
    printf("%u passed, %u failed\n", passed, failed);
    return failed ? 1 : 0;
}

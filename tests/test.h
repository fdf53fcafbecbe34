/* A plain C test runner: named tests, some run once per available ISA, seedable random cases,
 * two tiers (quick: a subset of the heavy tests' cases; long: all of them). The last line of
 * output is "N passed, N failed", counting each test once per ISA it ran on. */
#ifndef HB_TEST_H
#define HB_TEST_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hairbsdf.h"
#include "simd/compiler.h"
#include "kernel_hooks.h"

typedef struct hb_test_ctx {
    const char *name;
    hb_isa isa;                /* HB_ISA_AUTO for tests that do not depend on the ISA */
    const hb_kernel_hooks *hooks; /* the ISA's kernel internals, NULL for ISA-independent tests */
    uint64_t rng;              /* seeded per test from the run's seed */
    unsigned failures;
    int quick;    /* the quick tier (make test): heavy tests run a subset of their cases; 0: the long tier */
    int emulated; /* running under qemu ($HB_TEST_EMULATED): nothing that needs the native machine (valgrind) */
    int skipped;  /* set by hb_test_skip: the test could not run here and is counted as skipped */
    char skip_reason[160];
} hb_test_ctx;

typedef struct hb_test {
    const char *name;
    void (*run)(hb_test_ctx *t);
    int per_isa;
} hb_test;

void hb_test_fail(hb_test_ctx *t, const char *file, int line, const char *fmt, ...) HB_PRINTF_FORMAT(4, 5);
/* A measurement, printed with --verbose and kept for the pages' blocks by --figures (figures.h). */
void hb_test_note(hb_test_ctx *t, const char *fmt, ...) HB_PRINTF_FORMAT(2, 3);
/* A diagnostic (where a worst case lies), printed with --verbose only. */
void hb_test_detail(hb_test_ctx *t, const char *fmt, ...) HB_PRINTF_FORMAT(2, 3);

#define CHECK(t, cond, ...)                                         \
    do {                                                            \
        if (!(cond))                                                \
            hb_test_fail((t), __FILE__, __LINE__, __VA_ARGS__);     \
    } while (0)

/* The test of that name (the first whose name starts with it, for a name ending in '*'), NULL when
 * there is none. */
const hb_test *hb_test_find(const char *name);

/* Marks the test as skipped here, for the reason the runner prints. */
void hb_test_skip(hb_test_ctx *t, const char *reason);

/* The hairbsdf tool's command ($HB_TOOL, which make test sets; under qemu it starts with the
 * emulator); a missing HB_TOOL fails the test and gives NULL. */
const char *hb_test_tool(hb_test_ctx *t);

/* The system's temporary directory ($TMPDIR, Windows' own, else /tmp), without a final separator. */
const char *hb_test_temp_dir(void);

/* Creates a new empty file named hb_XXXXXX<suffix> in it; 0 with its path, or -1. */
int hb_test_temp_file(char *path, size_t capacity, const char *suffix);

/* What a run of the tool printed (text, truncated to the buffers) and its exit status. */
typedef struct hb_tool_run {
    int status;
    char out[16384], err[4096];
} hb_tool_run;

/* Runs the tool with `args` (quoted with double quotes only) and `input_size` bytes on stdin;
 * 0 when it could not be run (the test has failed). */
int hb_test_run_tool(hb_test_ctx *t, const char *args, const void *input, size_t input_size, hb_tool_run *r);

/* A whole file, NUL-terminated (its size without the NUL in *size, which may be NULL); malloc'd,
 * NULL when it cannot be read. */
char *hb_test_read_file(const char *path, size_t *size);

/* At most capacity - 1 bytes of a text file, NUL-terminated (empty when it cannot be read);
 * Windows' CRLF read back as LF. */
void hb_test_read_text(const char *path, char *text, size_t capacity);

/* Uniform double in [0, 1) and in [lo, hi) (splitmix64). */
double hb_test_uniform(hb_test_ctx *t);
static inline double hb_test_range(hb_test_ctx *t, double lo, double hi) { return lo + (hi - lo) * hb_test_uniform(t); }

/* docs/conventions.md: max over the n samples of 3 channels of |f - ref| / max(|ref|, 1e-3 peak),
 * peak being the largest reference value. */
double hb_test_spec_error(float *const f[3], float *const ref[3], size_t n, size_t *worst_sample);

/* Unit vectors of sample k's angle pair (docs/conventions.md): w[0..2] = w_i, w[3..5] = w_o. */
void hb_test_vectors_of(float theta_i, float phi_i, float theta_o, float phi_o, float *const w[6], size_t k);

/* A near-field plan's calls of one sample (and of two, with pairs) against one batch call
 * (tests/test_deon_near.c): random directions and offsets, every tenth at a pole or h = -1, 0, 1;
 * checks them within 3e-5 of the peak and that a NaN offset in a call of one is counted and gives 0;
 * returns the error. */
double hb_test_near_per_hit(hb_test_ctx *t, const hb_plan *plan, const char *name, int pairs);

/* Error of a float result in units of the float spacing at the double reference. */
double hb_test_ulp_error(float got, double want);

/* Default material and options for a deon longitudinal plan on the test's ISA. */
void hb_test_longitudinal_setup(const hb_test_ctx *t, hb_material *m, hb_options *o);

/* Test tables of each file, terminated by a zero entry. */
extern const hb_test hb_tests_vmath[];
extern const hb_test hb_tests_longitudinal[];
extern const hb_test hb_tests_deon[];
extern const hb_test hb_tests_marschner[];
extern const hb_test hb_tests_marschner_full[];
extern const hb_test hb_tests_huang[];
extern const hb_test hb_tests_huang_paper[];
extern const hb_test hb_tests_properties[];
extern const hb_test hb_tests_api[];
extern const hb_test hb_tests_cli[];
extern const hb_test hb_tests_images[];
extern const hb_test hb_tests_deon_table[];
extern const hb_test hb_tests_table_file[];
extern const hb_test hb_tests_table_build[];
extern const hb_test hb_tests_absorption[];
extern const hb_test hb_tests_shaders[];
extern const hb_test hb_tests_colour_table[];
extern const hb_test hb_tests_plan_select[];
extern const hb_test hb_tests_corpus[];
extern const hb_test hb_tests_sample[];
extern const hb_test hb_tests_sample_huang[];
extern const hb_test hb_tests_huang_internal[];
extern const hb_test hb_tests_huang_table[];
extern const hb_test hb_tests_threads[];
extern const hb_test hb_tests_chiang[];
extern const hb_test hb_tests_renderer_calls[];
extern const hb_test hb_tests_colour[];
extern const hb_test hb_tests_deon_near[];
extern const hb_test hb_tests_marschner_sample[];
extern const hb_test hb_tests_docs[];
extern const hb_test hb_tests_api_matrix[];
extern const hb_test hb_tests_dual[];
extern const hb_test hb_tests_assembly[];
extern const hb_test hb_tests_dual_eval[];
extern const hb_test hb_tests_dual_engine[];
/* The engine-wide dual-scattering table of the default material's family at these axes, d_b 0.7
 * (test_dual_engine.c); NULL after a failed check. */
hb_dual_engine *hb_test_dual_engine(hb_test_ctx *t, const hb_dual_engine_axes *axes);
extern const hb_test hb_tests_assembly_dual[];
extern const hb_test hb_tests_spectral[];
extern const hb_test hb_tests_spectral_eval[];
extern const hb_test hb_tests_convert[];
extern const hb_test hb_tests_near_vectors[];

#endif

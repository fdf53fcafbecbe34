/* Accuracy of src/math/vmath.h on each ISA: maximum error in ULP against libm in
 * double (relative error for the Bessel functions, against the double reference),
 * over dense grids, random points and edge cases. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "ref/reference.h"

enum { DENSE = 1 << 20 };

typedef struct input_set {
    float *a, *b;
    size_t n, cap;
} input_set;

static void push(input_set *s, float a, float b)
{
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 4096;
        s->a = realloc(s->a, s->cap * sizeof(float));
        s->b = realloc(s->b, s->cap * sizeof(float));
    }
    s->a[s->n] = a;
    s->b[s->n++] = b;
}

static void push_grid(input_set *s, double lo, double hi, size_t n)
{
    for (size_t k = 0; k < n; k++)
        push(s, (float)(lo + (hi - lo) * (double)k / (double)(n - 1)), 1.0f);
}

/* The 2 * count + 1 floats around x. */
static void push_neighbourhood(input_set *s, float x, int count)
{
    float lo = x, hi = x;
    push(s, x, 1.0f);
    for (int k = 0; k < count; k++) {
        lo = nextafterf(lo, -INFINITY);
        hi = nextafterf(hi, INFINITY);
        push(s, lo, 1.0f);
        push(s, hi, 1.0f);
    }
}

typedef double (*ref_fn)(double a, double b);
typedef enum { ERR_ULP, ERR_RELATIVE } err_kind;

/* Runs fn over the set and returns the worst error; *where gets its input. */
static double worst_error(hb_test_ctx *t, hb_math_fn fn, ref_fn ref, const input_set *s, err_kind kind,
                          float *where_a, float *where_b)
{
    float *out = malloc(s->n * sizeof(float));
    t->hooks->math_map(fn, s->n, s->a, s->b, out);
    double worst = 0.0;
    for (size_t k = 0; k < s->n; k++) {
        double want = ref(s->a[k], s->b[k]);
        double err = kind == ERR_ULP ? hb_test_ulp_error(out[k], want)
                                     : fabs((double)out[k] - want) / fmax(fabs(want), DBL_MIN);
        if (!(err <= worst)) { /* NaN counts as the worst */
            worst = isnan(err) ? INFINITY : err;
            *where_a = s->a[k];
            *where_b = s->b[k];
        }
    }
    free(out);
    return worst;
}

static void check_function(hb_test_ctx *t, const char *label, hb_math_fn fn, ref_fn ref, input_set *s,
                           err_kind kind, double bound)
{
    float wa = 0.0f, wb = 0.0f;
    double worst = worst_error(t, fn, ref, s, kind, &wa, &wb);
    if (kind == ERR_ULP)
        hb_test_note(t, "%-6s max %.2f ulp over %zu inputs (worst at %.9g, %.9g)", label, worst, s->n, wa, wb);
    else
        hb_test_note(t, "%-6s max relative error %.2e over %zu inputs (worst at %.9g)", label, worst, s->n, wa);
    CHECK(t, worst <= bound, "%s: %.3g exceeds %.3g at a = %.9g, b = %.9g", label, worst, bound, wa, wb);
    free(s->a);
    free(s->b);
    memset(s, 0, sizeof *s);
}

static double ref_exp(double a, double b) { (void)b; return exp(a); }
static double ref_log(double a, double b) { (void)b; return log(a); }
static double ref_log1p(double a, double b) { (void)b; return log1p(a); }
static double ref_sin(double a, double b) { (void)b; return sin(a); }
static double ref_cos(double a, double b) { (void)b; return cos(a); }
static double ref_asin(double a, double b) { (void)b; return asin(a); }
static double ref_acos(double a, double b) { (void)b; return acos(a); }
static double ref_atan2(double a, double b) { return atan2(a, b); }
static double ref_sqrt(double a, double b) { (void)b; return sqrt(a); }
static double ref_i0(double a, double b) { (void)b; return hb_ref_bessel_i0e(a) * exp(fabs(a)); }
static double ref_i0e(double a, double b) { (void)b; return hb_ref_bessel_i0e(a); }
static double ref_log_i0(double a, double b) { (void)b; return hb_ref_log_bessel_i0(a); }

static void test_exp(hb_test_ctx *t)
{
    input_set s = { 0 };
    push_grid(&s, -103.9, 88.7, DENSE);
    push_grid(&s, -1e-3, 1e-3, 4096);
    const float edges[] = { 0.0f, -0.0f, 1e-30f, -1e-30f, 1e-40f, -87.3f, -88.0f, 88.72f, 0.34657359f, -0.34657359f };
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++)
        push_neighbourhood(&s, edges[k], 64);
    check_function(t, "exp", HB_FN_EXP, ref_exp, &s, ERR_ULP, 2.0);
}

/* exp with results below FLT_MIN flushed to 0, for x <= 88: 2 ulp where the result is normal, 0 below. */
static double ref_exp_flush(double a, double b) { (void)b; return a < -87.33 ? 0.0 : exp(a); }

static void test_exp_flush(hb_test_ctx *t)
{
    input_set s = { 0 };
    push_grid(&s, -87.33, 88.0, DENSE);
    push_grid(&s, -200.0, -87.34, 4096);
    const float edges[] = { 0.0f, -0.0f, 1e-30f, -87.3f, -87.33f, 87.99f, 0.34657359f, -0.34657359f };
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++)
        push_neighbourhood(&s, edges[k], 64);
    check_function(t, "exp_flush", HB_FN_EXP_FLUSH, ref_exp_flush, &s, ERR_ULP, 2.0);
}

/* 2^-t for t >= 0, exactly 0 from t = 126.5 on (rounded to k = 127): its degree-5 polynomial's 7.5e-8
 * is up to 1.3 ulp where 2^r < 1, plus the evaluation's rounding, so 3 ulp where the result is
 * normal, and in [126, 126.5), where it is denormal, within the denormal's own spacing. */
static double ref_exp2_neg(double a, double b) { (void)b; return a >= 126.5 ? 0.0 : exp2(-a); }

static void test_exp2_neg(hb_test_ctx *t)
{
    input_set s = { 0 };
    push_grid(&s, 0.0, 126.0, DENSE);
    push_grid(&s, 126.5, 1000.0, 4096);
    push_grid(&s, 0.0, 1e-3, 4096);
    const float edges[] = { 0.0f, 1e-30f, 0.5f, 1.5f, 2.5f, 125.5f, 126.0f, 126.5f, 127.0f, 3e38f };
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++)
        push_neighbourhood(&s, edges[k], 64);
    for (size_t k = 0; k < s.n; k++) /* the neighbourhood of 0 stepped below it */
        s.a[k] = fmaxf(s.a[k], 0.0f);
    check_function(t, "exp2_neg", HB_FN_EXP2_NEG, ref_exp2_neg, &s, ERR_ULP, 3.0);
}

static void test_log(hb_test_ctx *t)
{
    input_set s = { 0 };
    for (size_t k = 0; k < DENSE; k++) { /* every binade, denormals included */
        uint32_t bits = (uint32_t)(hb_test_uniform(t) * 2139095040.0) + 1u;
        float x;
        memcpy(&x, &bits, sizeof x);
        push(&s, x, 1.0f);
    }
    push_grid(&s, 0.5, 2.0, DENSE / 4);
    const float edges[] = { 1.0f, 0.70710678f, 1.41421356f, 2.0f, 0.5f, FLT_MIN, FLT_MAX };
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++)
        push_neighbourhood(&s, edges[k], 256);
    check_function(t, "log", HB_FN_LOG, ref_log, &s, ERR_ULP, 2.0);
}

static void test_log1p(hb_test_ctx *t)
{
    input_set s = { 0 };
    push_grid(&s, -0.5, 1000.0, DENSE / 4);
    push_grid(&s, -1e-3, 1e-3, DENSE / 4);
    const float edges[] = { 0.0f, 1e-8f, 1e-20f, 3e-8f, 6e-8f, 1.0f };
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++)
        push_neighbourhood(&s, edges[k], 256);
    check_function(t, "log1p", HB_FN_LOG1P, ref_log1p, &s, ERR_ULP, 2.0);
}

/* sin and cos on [-2 pi, 2 pi], the widest range any model feeds them, with every
 * float near the multiples of pi/2 where the reduction is hardest. */
static void trig_inputs(input_set *s)
{
    push_grid(s, -2.0 * M_PI, 2.0 * M_PI, DENSE);
    for (int q = -4; q <= 4; q++)
        push_neighbourhood(s, (float)(q * M_PI_2), 512);
    push_neighbourhood(s, 0.78539816f, 64);
    push_neighbourhood(s, 1e-20f, 8);
}

static void test_sin(hb_test_ctx *t)
{
    input_set s = { 0 };
    trig_inputs(&s);
    check_function(t, "sin", HB_FN_SIN, ref_sin, &s, ERR_ULP, 4.0);
}

static void test_cos(hb_test_ctx *t)
{
    input_set s = { 0 };
    trig_inputs(&s);
    check_function(t, "cos", HB_FN_COS, ref_cos, &s, ERR_ULP, 4.0);
}

static void inverse_trig_inputs(input_set *s)
{
    push_grid(s, -1.0, 1.0, DENSE);
    const float edges[] = { 1.0f, -1.0f, 0.5f, -0.5f, 0.0f, 1e-20f };
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++)
        push_neighbourhood(s, edges[k], 512);
    for (size_t k = 0; k < s->n; k++) /* the neighbourhoods of +-1 stepped outside */
        s->a[k] = fminf(fmaxf(s->a[k], -1.0f), 1.0f);
}

static void test_asin(hb_test_ctx *t)
{
    input_set s = { 0 };
    inverse_trig_inputs(&s);
    check_function(t, "asin", HB_FN_ASIN, ref_asin, &s, ERR_ULP, 4.0);
}

/* asin on [-3/4, 3/4] by the one polynomial of vf_asin_narrow (dFH11's refraction angles for eta >= 4/3). */
static void test_asin_narrow(hb_test_ctx *t)
{
    input_set s = { 0 };
    push_grid(&s, -0.75, 0.75, DENSE);
    const float edges[] = { 0.75f, -0.75f, 0.5f, -0.5f, 0.0f, 1e-20f, 0.64516129f };
    for (size_t k = 0; k < sizeof edges / sizeof edges[0]; k++)
        push_neighbourhood(&s, edges[k], 512);
    for (size_t k = 0; k < s.n; k++) /* the neighbourhoods of +-3/4 stepped outside */
        s.a[k] = fminf(fmaxf(s.a[k], -0.75f), 0.75f);
    check_function(t, "asin_narrow", HB_FN_ASIN_NARROW, ref_asin, &s, ERR_ULP, 4.0);
}

static void test_acos(hb_test_ctx *t)
{
    input_set s = { 0 };
    inverse_trig_inputs(&s);
    check_function(t, "acos", HB_FN_ACOS, ref_acos, &s, ERR_ULP, 4.0);
}

static void test_atan2(hb_test_ctx *t)
{
    input_set s = { 0 };
    for (size_t k = 0; k < DENSE; k++) { /* directions all round, lengths over many scales */
        double angle = hb_test_range(t, -M_PI, M_PI), r = exp(hb_test_range(t, -20.0, 20.0));
        push(&s, (float)(r * sin(angle)), (float)(r * cos(angle)));
    }
    const float axes[][2] = { { 0, 1 }, { 1, 0 }, { 0, -1 }, { -1, 0 }, { 0.0f, 0.0f }, { -0.0f, 0.0f },
                              { 0.0f, -0.0f }, { -0.0f, -0.0f }, { 1, 1 }, { -1, -1 }, { 1e-30f, -1 },
                              { -1e-30f, -1 }, { 0.41421356f, 1 }, { 1, 0.41421356f } };
    for (size_t k = 0; k < sizeof axes / sizeof axes[0]; k++)
        push(&s, axes[k][0], axes[k][1]);
    check_function(t, "atan2", HB_FN_ATAN2, ref_atan2, &s, ERR_ULP, 4.0);
}

static void test_sqrt(hb_test_ctx *t)
{
    input_set s = { 0 };
    push_grid(&s, 0.0, 4.0, DENSE / 4);
    push_neighbourhood(&s, 1.0f, 256);
    push_neighbourhood(&s, FLT_MIN, 256);
    check_function(t, "sqrt", HB_FN_SQRT, ref_sqrt, &s, ERR_ULP, 0.5); /* correctly rounded */
}

/* A&S 9.8.1 is good to ~1.6e-7 relative and 9.8.2 to ~5e-7; float adds a few ulp. */
static void test_i0(hb_test_ctx *t)
{
    input_set s = { 0 };
    push_grid(&s, -88.0, 88.0, DENSE / 2);
    push_neighbourhood(&s, 3.75f, 256);
    push_neighbourhood(&s, -3.75f, 256);
    push_neighbourhood(&s, 0.0f, 64);
    check_function(t, "I0", HB_FN_I0, ref_i0, &s, ERR_RELATIVE, 1e-6);
}

static void test_i0e(hb_test_ctx *t)
{
    input_set s = { 0 };
    push_grid(&s, -20.0, 20.0, DENSE / 4);
    push_grid(&s, 0.0, 1e4, DENSE / 4);
    push_neighbourhood(&s, 3.75f, 256);
    check_function(t, "I0e", HB_FN_I0E, ref_i0e, &s, ERR_RELATIVE, 1e-6);
}

static void test_log_i0(hb_test_ctx *t)
{
    input_set s = { 0 };
    push_grid(&s, -20.0, 20.0, DENSE / 4);
    push_grid(&s, 0.0, 1e4, DENSE / 4);
    push_grid(&s, -1e-3, 1e-3, 4096); /* log I0 ~ x^2/4: relative accuracy needs log1p */
    push_neighbourhood(&s, 3.75f, 256);
    check_function(t, "logI0", HB_FN_LOG_I0, ref_log_i0, &s, ERR_RELATIVE, 1e-6);
}

/* The reference Bessel function itself, against tabulated values (A&S table 9.8 and
 * DLMF). Its series and asymptotic branches must also meet at x = 30. */
static void test_reference_i0(hb_test_ctx *t)
{
    static const double table[][2] = {
        { 0.0, 1.0 },
        { 1.0, 1.2660658777520082 },
        { 2.0, 2.2795853023360673 },
        { 5.0, 27.239871823604442 },
        { 10.0, 2815.7166284662544 },
    };
    for (size_t k = 0; k < sizeof table / sizeof table[0]; k++) {
        double got = hb_ref_bessel_i0e(table[k][0]) * exp(table[k][0]);
        CHECK(t, fabs(got / table[k][1] - 1.0) < 1e-14, "I0(%g) = %.17g, table %.17g", table[k][0], got,
              table[k][1]);
    }
    double below = hb_ref_bessel_i0e(nextafter(30.0, 0.0)), above = hb_ref_bessel_i0e(nextafter(30.0, 31.0));
    CHECK(t, fabs(below / above - 1.0) < 1e-14, "branches disagree at 30: %.17g vs %.17g", below, above);
    /* Large x: e^-x I0(x) -> 1/sqrt(2 pi x) (1 + 1/(8x) + 9/(128 x^2) + ...). */
    double x = 1e4, lead = 1.0 / sqrt(2.0 * M_PI * x) * (1.0 + 1.0 / (8 * x) + 9.0 / (128 * x * x));
    CHECK(t, fabs(hb_ref_bessel_i0e(x) / lead - 1.0) < 1e-12, "asymptotic branch off at x = 1e4");
}

const hb_test hb_tests_vmath[] = {
    { "vmath_exp", test_exp, 1 },
    { "vmath_exp_flush", test_exp_flush, 1 },
    { "vmath_exp2_neg", test_exp2_neg, 1 },
    { "vmath_log", test_log, 1 },
    { "vmath_log1p", test_log1p, 1 },
    { "vmath_sin", test_sin, 1 },
    { "vmath_cos", test_cos, 1 },
    { "vmath_asin", test_asin, 1 },
    { "vmath_asin_narrow", test_asin_narrow, 1 },
    { "vmath_acos", test_acos, 1 },
    { "vmath_atan2", test_atan2, 1 },
    { "vmath_sqrt", test_sqrt, 1 },
    { "vmath_i0", test_i0, 1 },
    { "vmath_i0e", test_i0e, 1 },
    { "vmath_log_i0", test_log_i0, 1 },
    { "reference_i0", test_reference_i0, 0 },
    { NULL, NULL, 0 },
};

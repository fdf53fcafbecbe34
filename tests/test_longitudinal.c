/* dFH11 M_p (eq. 7): float kernels against the double reference, unit integral,
 * reciprocity, peak position, the eq. 15 series' failure, vector vs angle entry
 * points, invalid samples and batch tails. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "ref/reference.h"

static const char *const quality_names[] = { "fast", "balanced", "high", "reference" };
static const double roughness_v[] = { 1e-6, 1e-5, 1e-4, 3e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0 };
#define N_V (sizeof roughness_v / sizeof roughness_v[0])

static hb_plan *make_plan(hb_test_ctx *t, double v, double alpha, hb_i0 i0, hb_quality quality)
{
    hb_material m;
    hb_options o;
    hb_test_longitudinal_setup(t, &m, &o);
    m.beta_m = sqrt(v);
    m.alpha = alpha;
    o.i0 = i0;
    o.quality = quality;
    hb_plan *plan = NULL;
    hb_error err;
    hb_status st = hb_plan_create(&m, &o, &plan, &err);
    CHECK(t, st == HB_OK, "plan for v = %g: %s", v, err.message);
    return plan;
}

/* M_p for n angle pairs (phi = 0) into out; returns the invalid count. */
static size_t eval_mp(const hb_plan *plan, size_t n, const float *ti, const float *to, float *out)
{
    float *zero = calloc(n ? n : 1, sizeof(float));
    float *g = malloc((n ? n : 1) * sizeof(float)), *b = malloc((n ? n : 1) * sizeof(float));
    hb_angles_soa in = { ti, zero, to, zero };
    hb_rgb_soa rgb = { out, g, b };
    hb_eval_report report = { 0 };
    hb_eval_angles(plan, n, in, rgb, &report);
    free(zero);
    free(g);
    free(b);
    return report.invalid;
}

/* Inclinations that include the grazing limits (pi/2 as a float) and their neighbours. */
static size_t theta_grid(float *out, size_t cap)
{
    size_t n = 0;
    for (int k = -40; k <= 40 && n < cap; k++)
        out[n++] = (float)(k * (M_PI / 80.0));
    const float edges[] = { 1.57079637f, -1.57079637f, 1.57079625f, -1.57079625f, 1.5707e0f, 1e-30f, -0.0f };
    for (size_t k = 0; k < sizeof edges / sizeof edges[0] && n < cap; k++)
        out[n++] = edges[k];
    return n;
}

/* dFH11 eq. 7's cone exponent (1 - cos(theta_i + theta_o')) / v at theta_o' = theta_o - shift,
 * reflected across a pole: what the float path's error grows with. */
static double cone_exponent(double v, double ti, double to_shifted)
{
    if (fabs(to_shifted) > M_PI_2)
        to_shifted = copysign(M_PI, to_shifted) - to_shifted;
    double s = sin(0.5 * (ti + to_shifted));
    return 2.0 * s * s / v;
}

/* The relative error M_p may have (docs/deon.md): 1e-6 from HB_QUALITY_HIGH up (double
 * arithmetic); below, float arithmetic: the cone exponent carries up to 4 ulps (sin a, its square,
 * the scaling by 1/v), the normalisation log(1/v) about 2 (its rounding and the sum's), the
 * exponential and I0 a few more: 5e-7 (2 + exponent) + 2e-7 |log v|. From
 * unit vectors the float path also carries the vectors' own rounding, about 2.4e-7 in angle,
 * which the exponent amplifies by 2 sqrt(2 exponent / v): 7e-7 sqrt(exponent / v) more. */
static double mp_error_bound(hb_quality quality, double exponent, double v, int from_vectors)
{
    if (quality >= HB_QUALITY_HIGH)
        return 1e-6;
    return 5e-7 * (2.0 + exponent) + 2e-7 * fabs(log(v)) + (from_vectors ? 7e-7 * sqrt(exponent / v) : 0.0);
}

/* The bound: M_p within 1e-6 relative of the double reference wherever M_p > 1e-30, for v
 * from 1e-6 to 10 and every theta, with and without a tilt shift, at HB_QUALITY_HIGH; below it,
 * the float path within mp_error_bound. */
static void test_matches_reference(hb_test_ctx *t)
{
    float grid[128];
    size_t ng = theta_grid(grid, 128);
    enum { RANDOM = 4096 };
    size_t n = ng * ng + RANDOM;
    float *ti = malloc(n * sizeof(float)), *to = malloc(n * sizeof(float)), *out = malloc(n * sizeof(float));
    for (size_t a = 0; a < ng; a++)
        for (size_t b = 0; b < ng; b++) {
            ti[a * ng + b] = grid[a];
            to[a * ng + b] = grid[b];
        }
    const double alphas[] = { 0.0, 0.035, -0.2 };
    const hb_quality qualities[] = { HB_QUALITY_HIGH, HB_QUALITY_BALANCED };
    for (size_t iq = 0; iq < 2; iq++) {
    double worst_all = 0.0, worst_ratio = 0.0;
    for (size_t iv = 0; iv < N_V; iv++) {
        for (size_t ia = 0; ia < 3; ia++) {
            double v = roughness_v[iv], alpha = alphas[ia], shift = -2.0 * alpha;
            /* random pairs concentrated near the specular cone theta_o = -theta_i + shift */
            for (size_t k = ng * ng; k < n; k++) {
                double x = hb_test_range(t, -M_PI_2, M_PI_2);
                double y = -x + shift + sqrt(v) * hb_test_range(t, -12.0, 12.0);
                ti[k] = (float)x;
                to[k] = (float)fmax(-M_PI_2, fmin(M_PI_2, y));
            }
            hb_plan *plan = make_plan(t, v, alpha, HB_I0_ABRAMOWITZ, qualities[iq]);
            CHECK(t, eval_mp(plan, n, ti, to, out) == 0, "valid grid reported invalid");
            double worst = 0.0, worst_err = 0.0;
            size_t worst_k = 0;
            for (size_t k = 0; k < n; k++) {
                double want = hb_ref_longitudinal(v, ti[k], (double)to[k] - shift, HB_I0_ABRAMOWITZ);
                CHECK(t, isfinite(out[k]) && out[k] >= 0.0f, "M_p(%g, %g, %g) = %g", v, ti[k], to[k], out[k]);
                if (want > 1e-30) {
                    double err = fabs(out[k] / want - 1.0);
                    double ratio = err / mp_error_bound(qualities[iq], cone_exponent(v, ti[k], (double)to[k] - shift), v, 0);
                    worst_err = fmax(worst_err, err);
                    if (!(ratio <= worst)) {
                        worst = ratio;
                        worst_k = k;
                    }
                } else {
                    CHECK(t, out[k] <= 2e-30, "M_p(%g, %g, %g) = %g where the reference is %g", v, ti[k],
                          to[k], out[k], want);
                }
            }
            CHECK(t, worst <= 1.0, "%s v = %g alpha = %g: error %.3g of its bound at theta_i = %.9g theta_o = %.9g",
                  quality_names[qualities[iq]], v, alpha, worst, ti[worst_k], to[worst_k]);
            worst_all = fmax(worst_all, worst_err);
            worst_ratio = fmax(worst_ratio, worst);
            hb_plan_destroy(plan);
        }
    }
    hb_test_note(t, "%s: max relative error vs double reference %.2e, %.2f of the bound (M_p > 1e-30, v in [1e-6, 10])",
                 quality_names[qualities[iq]], worst_all, worst_ratio);
    }
    free(ti);
    free(to);
    free(out);
}

/* Integral of M_p cos(theta_i) over theta_i in [-pi/2, pi/2] is 1 (dFH11 sec. 4.2), by composite
 * Simpson for the float kernel and the reference: 13334 intervals on each of three pieces, the middle
 * one the lobe's +-30 sqrt(v) around its peak theta_i = -theta_o, so v = 1e-6 is resolved too. */
static void test_unit_integral(hb_test_ctx *t)
{
    enum { PIECES = 3, INTERVALS = 13334, PER_PIECE = INTERVALS + 1 };
    size_t n = PIECES * PER_PIECE;
    float *ti = malloc(n * sizeof(float)), *to = malloc(n * sizeof(float)), *out = malloc(n * sizeof(float));
    double *x = malloc(n * sizeof(double)), *w = malloc(n * sizeof(double));
    const double theta_o[] = { 0.0, 0.4, -0.9, 1.3, 1.55, 1.5707963 };
    double worst = 0.0, worst_ref = 0.0;
    for (size_t iv = 0; iv < N_V; iv++) {
        double v = roughness_v[iv];
        hb_plan *plan = make_plan(t, v, 0.0, HB_I0_ABRAMOWITZ, HB_QUALITY_BALANCED);
        for (size_t io = 0; io < sizeof theta_o / sizeof theta_o[0]; io++) {
            double half = 30.0 * sqrt(v);
            double ends[PIECES + 1] = { -M_PI_2, fmax(-M_PI_2, -theta_o[io] - half), fmin(M_PI_2, -theta_o[io] + half),
                                        M_PI_2 };
            for (size_t p = 0; p < PIECES; p++) {
                double h = (ends[p + 1] - ends[p]) / INTERVALS;
                for (size_t k = 0; k < PER_PIECE; k++) {
                    size_t i = p * PER_PIECE + k;
                    x[i] = ends[p] + h * (double)k;
                    w[i] = h / 3.0 * ((k == 0 || k == INTERVALS) ? 1.0 : (k % 2 ? 4.0 : 2.0));
                    ti[i] = (float)x[i];
                    to[i] = (float)theta_o[io];
                }
            }
            eval_mp(plan, n, ti, to, out);
            double sum = 0.0, sum_ref = 0.0;
            for (size_t i = 0; i < n; i++) {
                sum += w[i] * out[i] * cos((double)ti[i]);
                sum_ref += w[i] * hb_ref_longitudinal(v, x[i], to[i], HB_I0_ABRAMOWITZ) * cos(x[i]);
            }
            worst = fmax(worst, fabs(sum - 1.0));
            worst_ref = fmax(worst_ref, fabs(sum_ref - 1.0));
            CHECK(t, fabs(sum - 1.0) < 2e-6, "v = %g theta_o = %g: integral %.9f", v, theta_o[io], sum);
            CHECK(t, fabs(sum_ref - 1.0) < 1e-9, "reference v = %g theta_o = %g: integral %.12f", v,
                  theta_o[io], sum_ref);
        }
        hb_plan_destroy(plan);
    }
    hb_test_note(t, "|integral - 1| max %.2e (float kernel), %.2e (double reference)", worst, worst_ref);
    free(ti);
    free(to);
    free(out);
    free(x);
    free(w);
}

/* M_p(theta_i, theta_o) = M_p(theta_o, theta_i) without tilt, bit for bit. */
static void test_reciprocity(hb_test_ctx *t)
{
    enum { N = 2000 };
    float a[N], b[N], fab[N], fba[N];
    for (size_t iv = 0; iv < N_V; iv++) {
        hb_plan *plan = make_plan(t, roughness_v[iv], 0.0, HB_I0_ABRAMOWITZ, HB_QUALITY_BALANCED);
        for (int k = 0; k < N; k++) {
            a[k] = (float)hb_test_range(t, -M_PI_2, M_PI_2);
            b[k] = (float)hb_test_range(t, -M_PI_2, M_PI_2);
        }
        eval_mp(plan, N, a, b, fab);
        eval_mp(plan, N, b, a, fba);
        for (int k = 0; k < N; k++)
            CHECK(t, fab[k] == fba[k], "v = %g: M(%g, %g) = %.9g but M(%g, %g) = %.9g", roughness_v[iv], a[k],
                  b[k], fab[k], b[k], a[k], fba[k]);
        hb_plan_destroy(plan);
    }
}

/* At normal incidence the lobe is symmetric about the tilted specular direction
 * theta_o = -2 alpha; off normal the float peak is where the reference's is. */
static void test_peak(hb_test_ctx *t)
{
    enum { N = 20001 };
    float *ti = malloc(N * sizeof(float)), *to = malloc(N * sizeof(float)), *out = malloc(N * sizeof(float));
    const double alpha = 0.05, incidences[] = { 0.0, -1.0, -1.3, 0.7 };
    for (size_t ii = 0; ii < 4; ii++) {
        hb_plan *plan = make_plan(t, 0.02, alpha, HB_I0_ABRAMOWITZ, HB_QUALITY_BALANCED);
        for (int k = 0; k < N; k++) {
            ti[k] = (float)incidences[ii];
            to[k] = (float)(-M_PI_2 + M_PI * k / (N - 1));
        }
        eval_mp(plan, N, ti, to, out);
        int best = 0, best_ref = 0;
        double best_ref_value = -1.0;
        for (int k = 0; k < N; k++) {
            if (out[k] > out[best])
                best = k;
            double r = hb_ref_longitudinal(0.02, ti[k], (double)to[k] + 2.0 * alpha, HB_I0_ABRAMOWITZ);
            if (r > best_ref_value) {
                best_ref_value = r;
                best_ref = k;
            }
        }
        CHECK(t, abs(best - best_ref) <= 1, "theta_i = %g: float peak at %g, reference at %g", incidences[ii],
              to[best], to[best_ref]);
        if (incidences[ii] == 0.0)
            CHECK(t, fabs(to[best] + 2.0 * alpha) <= M_PI / (N - 1), "peak at %g, expected %g", to[best],
                  -2.0 * alpha);
        hb_plan_destroy(plan);
    }
    free(ti);
    free(to);
    free(out);
}

/* Integral over theta_i of M_p cos(theta_i) by Simpson, for one plan. */
static double integral_over_theta_i(const hb_plan *plan, double theta_o)
{
    enum { INTERVALS = 20000 };
    size_t n = INTERVALS + 1;
    float *ti = malloc(n * sizeof(float)), *to = malloc(n * sizeof(float)), *out = malloc(n * sizeof(float));
    for (size_t k = 0; k < n; k++) {
        ti[k] = (float)(-M_PI_2 + M_PI * (double)k / INTERVALS);
        to[k] = (float)theta_o;
    }
    eval_mp(plan, n, ti, to, out);
    double sum = 0.0;
    for (size_t k = 0; k < n; k++)
        sum += ((k == 0 || k == n - 1) ? 1.0 : (k % 2 ? 4.0 : 2.0)) * out[k] * cos((double)ti[k]);
    free(ti);
    free(to);
    free(out);
    return sum * M_PI / INTERVALS / 3.0;
}

/* dFH11 eq. 15 keeps 10 terms of the I0 series: right for small arguments (large v),
 * badly low for large ones (small v), where M_p loses most of its energy. */
static void test_paper_series_failure(hb_test_ctx *t)
{
    const double v_values[] = { 1.0, 0.3, 0.1, 0.03, 0.01 };
    for (size_t iv = 0; iv < 5; iv++) {
        double v = v_values[iv];
        hb_plan *paper = make_plan(t, v, 0.0, HB_I0_PAPER, HB_QUALITY_BALANCED);
        double energy = integral_over_theta_i(paper, 0.2);
        hb_test_note(t, "eq. 15 series, v = %-5g: integral of M_p cos = %.6f (eq. 7 gives 1)", v, energy);
        if (v >= 0.3)
            CHECK(t, fabs(energy - 1.0) < 1e-5, "series should be exact for v = %g: %.9f", v, energy);
        if (v <= 0.03)
            CHECK(t, energy < 0.5, "series should lose energy at v = %g: %.9f", v, energy);
        /* float paper variant against its double reference at the specular peak */
        float ti = 0.3f, to = -0.3f, out;
        eval_mp(paper, 1, &ti, &to, &out);
        double want = hb_ref_longitudinal(v, ti, to, HB_I0_PAPER);
        CHECK(t, fabs(out / want - 1.0) < 1e-5, "paper variant v = %g: %g vs reference %g", v, out, want);
        hb_plan_destroy(paper);
    }
}

/* The rewritten reference against eq. 7 as printed, in long double, where it does not overflow. */
static void test_reference_matches_eq7(hb_test_ctx *t)
{
    const double v_values[] = { 0.05, 0.1, 0.5, 2.0, 10.0 };
    for (size_t iv = 0; iv < 5; iv++) {
        long double v = v_values[iv];
        for (int k = 0; k < 200; k++) {
            double ti = hb_test_range(t, -M_PI_2, M_PI_2), to = hb_test_range(t, -M_PI_2, M_PI_2);
            long double x = cosl(ti) * cosl(to) / v, u = x * x / 4, term = 1, i0 = 1;
            for (int j = 1; j < 400; j++) {
                term *= u / ((long double)j * j);
                i0 += term;
            }
            long double csch = 2.0L / (expl(1.0L / v) - expl(-1.0L / v));
            long double literal = csch / (2 * v) * expl(-sinl(ti) * sinl(to) / v) * i0;
            double ref = hb_ref_longitudinal((double)v, ti, to, HB_I0_ABRAMOWITZ);
            CHECK(t, fabsl(ref / literal - 1) < 1e-12, "v = %g (%g, %g): %.17g vs eq. 7 %.17Lg", (double)v, ti,
                  to, ref, literal);
        }
    }
}

/* The vector entry point against the double reference of the same float vectors. */
static void test_vectors_match_reference(hb_test_ctx *t)
{
    enum { N = 3000 };
    static float w[6][N];
    float out[N], g[N], b[N], ref[N];
    for (size_t iv = 0; iv < N_V; iv++) {
        double v = roughness_v[iv];
        for (int k = 0; k < N; k++) {
            double ti = hb_test_range(t, -M_PI_2, M_PI_2), pi = hb_test_range(t, -M_PI, M_PI);
            double to = -ti + sqrt(v) * hb_test_range(t, -8.0, 8.0), po = hb_test_range(t, -M_PI, M_PI);
            to = fmax(-M_PI_2, fmin(M_PI_2, to));
            if (k < 8) /* exact grazing and axis directions */
                ti = k % 2 ? M_PI_2 : -M_PI_2, to = k < 4 ? 0.0 : M_PI_2;
            w[0][k] = (float)(sin(pi) * cos(ti));
            w[1][k] = (float)sin(ti);
            w[2][k] = (float)(cos(pi) * cos(ti));
            w[3][k] = (float)(sin(po) * cos(to));
            w[4][k] = (float)sin(to);
            w[5][k] = (float)(cos(po) * cos(to));
        }
        hb_vectors_soa in = { w[0], w[1], w[2], w[3], w[4], w[5] };
        hb_plan *ref_plan = make_plan(t, v, 0.035, HB_I0_ABRAMOWITZ, HB_QUALITY_REFERENCE);
        hb_eval_report r2;
        hb_eval_vectors(ref_plan, N, in, (hb_rgb_soa){ ref, g, b }, &r2);
        for (hb_quality quality = HB_QUALITY_BALANCED; quality <= HB_QUALITY_HIGH; quality++) {
            hb_plan *plan = make_plan(t, v, 0.035, HB_I0_ABRAMOWITZ, quality);
            hb_eval_report r1;
            hb_eval_vectors(plan, N, in, (hb_rgb_soa){ out, g, b }, &r1);
            CHECK(t, r1.invalid == 0 && r2.invalid == 0, "unit vectors reported invalid: %zu, %zu", r1.invalid,
                  r2.invalid);
            double worst = 0.0;
            for (int k = 0; k < N; k++) {
                if (!(ref[k] > 1e-30f))
                    continue;
                double ti = asin(fmax(-1.0, fmin(1.0, w[1][k] / sqrt((double)w[0][k] * w[0][k] + (double)w[1][k] * w[1][k] + (double)w[2][k] * w[2][k]))));
                double to = asin(fmax(-1.0, fmin(1.0, w[4][k] / sqrt((double)w[3][k] * w[3][k] + (double)w[4][k] * w[4][k] + (double)w[5][k] * w[5][k]))));
                double bound = mp_error_bound(quality, cone_exponent(v, ti, to + 0.07), v, 1);
                worst = fmax(worst, fabs((double)out[k] / ref[k] - 1.0) / bound);
            }
            CHECK(t, worst <= 1.0, "%s v = %g: vector path error %.3g of its bound", quality_names[quality], v, worst);
            hb_plan_destroy(plan);
        }
        hb_plan_destroy(ref_plan);
    }
}

/* NaN, Inf and |theta| > pi/2 give 0 and are counted; denormal and signed-zero angles are valid;
 * every batch length (all tails) gives the same values as the sample alone in a block. */
static void test_invalid_and_tails(hb_test_ctx *t)
{
    hb_plan *plan = make_plan(t, 0.01, 0.0, HB_I0_ABRAMOWITZ, HB_QUALITY_BALANCED);
    const float bad_theta[] = { NAN, INFINITY, -INFINITY, 1.5707965f, -1.6f, 3.0f };
    for (size_t k = 0; k < sizeof bad_theta / sizeof bad_theta[0]; k++) {
        float ti[2] = { 0.3f, bad_theta[k] }, to[2] = { bad_theta[k], -0.3f }, out[2];
        CHECK(t, eval_mp(plan, 2, ti, to, out) == 2, "theta %g not counted", bad_theta[k]);
        CHECK(t, out[0] == 0.0f && out[1] == 0.0f, "theta %g gives %g, %g", bad_theta[k], out[0], out[1]);
    }
    float zero = 0.0f, phi_bad[3] = { NAN, INFINITY, -INFINITY };
    for (int k = 0; k < 3; k++) {
        float ti = 0.1f, to = -0.1f, r, g, b;
        hb_angles_soa in = { &ti, &phi_bad[k], &to, &zero };
        hb_eval_report rep;
        hb_eval_angles(plan, 1, in, (hb_rgb_soa){ &r, &g, &b }, &rep);
        CHECK(t, rep.invalid == 1 && r == 0.0f && g == 0.0f && b == 0.0f, "phi %g: invalid %zu, f %g", phi_bad[k],
              rep.invalid, r);
    }
    float odd_ti[4] = { 1e-40f, -0.0f, 0.0f, -1e-45f }, odd_to[4] = { -0.0f, 1e-40f, -1e-45f, 0.0f }, odd_out[4];
    CHECK(t, eval_mp(plan, 4, odd_ti, odd_to, odd_out) == 0, "denormal / signed zero angles counted invalid");
    for (int k = 0; k < 4; k++)
        CHECK(t, isfinite(odd_out[k]) && fabsf(odd_out[k] / odd_out[0] - 1.0f) < 1e-6f, "odd angle %d: %g", k,
              odd_out[k]);

    /* non-unit vectors */
    float x[3] = { 0.0f, 0.0f, NAN }, y[3] = { 1.1f, 0.0f, 0.0f }, z[3] = { 0.0f, 0.0f, 1.0f };
    float one[3] = { 1.0f, 1.0f, 1.0f }, zeros[3] = { 0.0f, 0.0f, 0.0f }, r[3], g[3], b[3];
    hb_vectors_soa vin = { x, y, z, zeros, zeros, one };
    hb_eval_report rep;
    hb_eval_vectors(plan, 3, vin, (hb_rgb_soa){ r, g, b }, &rep);
    CHECK(t, rep.invalid == 3 && r[0] == 0.0f && r[1] == 0.0f && r[2] == 0.0f,
          "non-unit vectors: invalid %zu, f = %g %g %g", rep.invalid, r[0], r[1], r[2]);

    enum { MAXN = 37 };
    float ti[MAXN], to[MAXN], batch[MAXN], single[2];
    for (int k = 0; k < MAXN; k++) {
        ti[k] = (float)hb_test_range(t, -1.5, 1.5);
        to[k] = k % 5 == 4 ? NAN : (float)(-ti[k] + hb_test_range(t, -0.05, 0.05));
    }
    for (int n = 0; n <= MAXN; n++) {
        size_t invalid = eval_mp(plan, (size_t)n, ti, to, batch);
        CHECK(t, invalid == (size_t)(n / 5), "n = %d: %zu invalid, expected %d", n, invalid, n / 5);
        for (int k = 0; k < n; k++) { /* the sample alone in a block (a call of one runs on the scalar kernels) */
            float pair_ti[2] = { ti[k], ti[k] }, pair_to[2] = { to[k], to[k] };
            eval_mp(plan, 2, pair_ti, pair_to, single);
            CHECK(t, batch[k] == single[0], "n = %d lane %d: batch %g, alone %g", n, k, batch[k], single[0]);
        }
    }
    hb_plan_destroy(plan);
}

/* Every ISA gives the same results as the scalar kernel within the float budget. */
static void test_matches_scalar(hb_test_ctx *t)
{
    enum { N = 4096 };
    float ti[N], to[N], out[N], scalar[N];
    hb_test_ctx scalar_ctx = *t;
    scalar_ctx.isa = HB_ISA_SCALAR;
    for (size_t iv = 0; iv < N_V; iv++) {
        for (int k = 0; k < N; k++) {
            ti[k] = (float)hb_test_range(t, -M_PI_2, M_PI_2);
            to[k] = (float)(-ti[k] + sqrt(roughness_v[iv]) * hb_test_range(t, -6.0, 6.0));
            to[k] = fmaxf(-1.5707963f, fminf(1.5707963f, to[k]));
        }
        for (hb_quality quality = HB_QUALITY_BALANCED; quality <= HB_QUALITY_HIGH; quality++) {
            hb_plan *plan = make_plan(t, roughness_v[iv], 0.035, HB_I0_ABRAMOWITZ, quality);
            hb_plan *ref = make_plan(&scalar_ctx, roughness_v[iv], 0.035, HB_I0_ABRAMOWITZ, quality);
            eval_mp(plan, N, ti, to, out);
            eval_mp(ref, N, ti, to, scalar);
            for (int k = 0; k < N; k++) {
                /* both within the bound of the reference (FMA or not), so within twice it of each other */
                double bound = 2.0 * mp_error_bound(quality, cone_exponent(roughness_v[iv], ti[k], to[k] + 0.07),
                                                    roughness_v[iv], 0);
                if (scalar[k] > 1e-30f)
                    CHECK(t, fabs((double)out[k] / scalar[k] - 1.0) <= bound, "%s v = %g: %s %.9g vs scalar %.9g",
                          quality_names[quality], roughness_v[iv], hb_isa_name(t->isa), out[k], scalar[k]);
            }
            hb_plan_destroy(plan);
            hb_plan_destroy(ref);
        }
    }
}

const hb_test hb_tests_longitudinal[] = {
    { "mp_matches_reference", test_matches_reference, 1 },
    { "mp_unit_integral", test_unit_integral, 1 },
    { "mp_reciprocity", test_reciprocity, 1 },
    { "mp_peak", test_peak, 1 },
    { "mp_paper_series_failure", test_paper_series_failure, 1 },
    { "mp_vectors_match_reference", test_vectors_match_reference, 1 },
    { "mp_invalid_and_tails", test_invalid_and_tails, 1 },
    { "mp_matches_scalar", test_matches_scalar, 1 },
    { "mp_reference_matches_eq7", test_reference_matches_eq7, 0 },
    { NULL, NULL, 0 },
};

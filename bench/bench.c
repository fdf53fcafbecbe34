/* hairbsdf_bench: ns/sample of each kernel on each ISA, the accuracy it buys against
 * the double reference, and a check against the latency budgets in bench/budgets.txt.
 * Batches are SoA, warm in cache, timed many times on one pinned core; the minimum
 * is what the budget applies to, the median is printed beside it. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hairbsdf.h"
#include "plot.h"
#include "clock.h"
#include "platform.h"
#include "readme.h"
#include "assembly.h"
#include "dual.h"
#include "table_files.h"
#include "huang_table.h"

enum { BATCH = 4096, REPEATS = 200, NREF = 256 };

#if defined(__clang__)
#define HB_COMPILER "clang " __clang_version__
#elif defined(__GNUC__)
#define HB_COMPILER "gcc " __VERSION__
#else
#define HB_COMPILER "an unnamed compiler"
#endif
#if defined(__x86_64__)
#define HB_ARCH_NAME "an x86-64 CPU"
#elif defined(__aarch64__)
#define HB_ARCH_NAME "an AArch64 CPU"
#else
#define HB_ARCH_NAME "a CPU"
#endif

/* What a row times: hb_eval_angles, hb_sample_angles or hb_pdf_angles, or their near-field forms
 * (hb_eval_near, hb_sample_near, hb_pdf_near) at each sample's h, or f and the pdf in one call
 * (hb_eval_pdf_angles; its error is f's), or a path tracer's step at one hit from vectors
 * (hb_hit_sample, then hb_hit_eval_pdf of the light's direction; far field, or near at h; its error
 * is the light direction's f), or the dual-scattering term f_DS from the plan's 64-node table
 * (hb_dual_eval at each sample's fibre count; its error against hb_dual_radiance of the same table), or
 * the near field or the far field at pbrt-v4's four wavelengths, 450, 550, 650 and 700 nm, each at the
 * material's melanin absorption there (hb_eval_near_spectral, hb_eval_angles_spectral; its error over
 * the four planes, the far field's against a reference plan of each wavelength's absorption). */
typedef enum bench_op {
    OP_EVAL, OP_SAMPLE, OP_PDF, OP_EVAL_NEAR, OP_SAMPLE_NEAR, OP_PDF_NEAR, OP_EVAL_PDF, OP_EVAL_ABSORPTION, OP_HIT, OP_HIT_NEAR,
    OP_DUAL, OP_SPECTRAL_NEAR, OP_SPECTRAL
} bench_op;

enum { WAVELENGTHS = 4 };
static const double wavelengths[WAVELENGTHS] = { 450.0, 550.0, 650.0, 700.0 };

/* The planes a row's result has: four wavelengths, or RGB. */
static int planes_of(bench_op op) { return op == OP_SPECTRAL_NEAR || op == OP_SPECTRAL ? WAVELENGTHS : 3; }

static int op_is(bench_op op, bench_op far) { return op == far || op == far + OP_EVAL_NEAR; }

typedef struct row {
    const char *model, *term, *variant;
    int config; /* index in configs[] */
    hb_isa isa;
    double min_ns, median_ns, max_rel_err;
    double ghz; /* the core's clock measured beside the timing (hb_cpu_clock_ghz) */
} row;

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static float theta_i[BATCH], phi_i[BATCH], theta_o[BATCH], phi_o[BATCH], offset_h[BATCH];
static float out[WAVELENGTHS][BATCH], ref[WAVELENGTHS][BATCH];
static float spectral_absorption[WAVELENGTHS][BATCH]; /* per sample and wavelength (OP_SPECTRAL_NEAR) */
static float absorption[3][BATCH]; /* per sample (OP_EVAL_ABSORPTION): the blond material's sigma_a */
static float uniforms[HB_SAMPLE_DIMENSIONS][BATCH], sampled_theta[BATCH], sampled_phi[BATCH], sampled_pdf[BATCH];
static float w_i[BATCH][3], w_o[BATCH][3]; /* the directions as fibre-frame vectors (OP_HIT) */
static float fibres[BATCH];                 /* the fibres toward the light (OP_DUAL) */
static hb_dual_table *dual_table;           /* the plan's table while an OP_DUAL row runs */

/* A path tracer's step at hit k: a sample from w_o, then f and the pdf of the light's direction w_i. */
static void run_hit(const hb_plan *plan, size_t k, const float *h)
{
    float u[HB_SAMPLE_DIMENSIONS], wi[3], pdf, weight[3], f[3];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        u[d] = uniforms[d][k];
    hb_hit_sample(plan, w_o[k], h, u, wi, &pdf, weight);
    hb_hit_eval_pdf(plan, w_i[k], w_o[k], h, f, &sampled_pdf[k]);
    for (int c = 0; c < 3; c++)
        out[c][k] = f[c];
}

/* The configuration's operation on samples [first, first + n) of the batch. For sampling, out holds
 * the weights; for the pdf, out[0..2] all hold the pdf. */
static void run_part(const hb_plan *plan, bench_op op, size_t first, size_t n)
{
    size_t k = first;
    hb_angles_soa in = { theta_i + k, phi_i + k, theta_o + k, phi_o + k };
    hb_near_soa near = { theta_i + k, phi_i + k, theta_o + k, phi_o + k, offset_h + k };
    hb_rgb_soa f = { out[0] + k, out[1] + k, out[2] + k };
    hb_sample_out sampled = { sampled_theta + k, sampled_phi + k, sampled_pdf + k, f };
    const float *u[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        u[d] = uniforms[d] + k;
    if (op == OP_HIT || op == OP_HIT_NEAR) {
        for (size_t j = k; j < k + n; j++)
            run_hit(plan, j, op == OP_HIT_NEAR ? &offset_h[j] : NULL);
    } else if (op == OP_EVAL) {
        hb_eval_angles(plan, n, in, f, NULL);
    } else if (op == OP_EVAL_NEAR) {
        hb_eval_near(plan, n, near, f, NULL);
    } else if (op == OP_SPECTRAL_NEAR || op == OP_SPECTRAL) {
        const float *sigma_a[WAVELENGTHS];
        float *f_planes[WAVELENGTHS];
        for (int j = 0; j < WAVELENGTHS; j++)
            sigma_a[j] = spectral_absorption[j] + k, f_planes[j] = out[j] + k;
        hb_spectral_absorption a = { WAVELENGTHS, sigma_a };
        if (op == OP_SPECTRAL)
            hb_eval_angles_spectral(plan, n, in, a, f_planes, NULL);
        else
            hb_eval_near_spectral(plan, n, near, a, f_planes, NULL);
    } else if (op == OP_DUAL) {
        hb_dual_eval(dual_table, n, in, fibres + k, NULL, f, NULL);
    } else if (op == OP_EVAL_PDF) {
        hb_eval_pdf_angles(plan, n, in, f, sampled_pdf + k, NULL);
    } else if (op == OP_EVAL_ABSORPTION) {
        hb_eval_angles_absorption(plan, n, in, (hb_absorption_soa){ absorption[0] + k, absorption[1] + k, absorption[2] + k },
                                  f, NULL);
    } else if (op == OP_SAMPLE) {
        hb_sample_in sample_in = { theta_o + k, phi_o + k, u };
        hb_sample_angles(plan, n, &sample_in, &sampled, NULL);
    } else if (op == OP_SAMPLE_NEAR) {
        hb_sample_near_in sample_in = { theta_o + k, phi_o + k, offset_h + k, u };
        hb_sample_near(plan, n, &sample_in, &sampled, NULL);
    } else {
        if (op == OP_PDF_NEAR)
            hb_pdf_near(plan, n, near, out[0] + k, NULL);
        else
            hb_pdf_angles(plan, n, in, out[0] + k, NULL);
        memcpy(out[1] + k, out[0] + k, n * sizeof(float));
        memcpy(out[2] + k, out[0] + k, n * sizeof(float));
    }
}

/* One timed pass: the whole batch in one call, or (per_hit) one call per sample, as a path tracer
 * calls at each ray hit. */
static void run_op(const hb_plan *plan, bench_op op, int per_hit)
{
    if (!per_hit)
        run_part(plan, op, 0, BATCH);
    else
        for (size_t k = 0; k < BATCH; k++)
            run_part(plan, op, k, 1);
}

/* Directions spread over the sphere, half of them near the specular cone where M_p is large. */
static void make_inputs(const hb_material *m)
{
    double v = m->beta_m * m->beta_m, sigma_a[3];
    hb_material_absorption(m, sigma_a);
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < BATCH; k++)
            absorption[c][k] = (float)sigma_a[c];
    for (int j = 0; j < WAVELENGTHS; j++) {
        double s;
        hb_melanin_absorption_spectral(m->eumelanin, m->pheomelanin, wavelengths[j], &s);
        for (int k = 0; k < BATCH; k++)
            spectral_absorption[j][k] = (float)s;
    }
    srand(12345);
    for (int k = 0; k < BATCH; k++) {
        double u = rand() / (double)RAND_MAX, w = rand() / (double)RAND_MAX;
        theta_i[k] = (float)(asin(2 * u - 1));
        theta_o[k] = k % 2 ? (float)asin(2 * w - 1) : (float)fmax(-1.5707, fmin(1.5707, -theta_i[k] + sqrt(v) * (4 * w - 2)));
        phi_i[k] = (float)(2 * M_PI * u - M_PI);
        phi_o[k] = (float)(2 * M_PI * w - M_PI);
        offset_h[k] = (float)(2.0 * rand() / RAND_MAX - 1.0);
        fibres[k] = k % 4 ? (float)(16.0 * rand() / RAND_MAX) : 0.0f;
        const float *angles[2][2] = { { &theta_i[k], &phi_i[k] }, { &theta_o[k], &phi_o[k] } };
        float *vector[2] = { w_i[k], w_o[k] };
        for (int s = 0; s < 2; s++) { /* w(theta, phi) of docs/conventions.md */
            double t = *angles[s][0], p = *angles[s][1];
            vector[s][0] = (float)(sin(p) * cos(t));
            vector[s][1] = (float)sin(t);
            vector[s][2] = (float)(cos(p) * cos(t));
        }
    }
}

/* An OP_DUAL row's table (dual_table, the plan's of `thetas` nodes): 1, or 0 with the failure printed.
 * --once builds one of ONCE_DUAL_THETAS nodes: hb_dual_eval's work per sample does not depend on the
 * table's size, and callgrind runs the build too, at fifty times its cost. */
enum { ONCE_DUAL_THETAS = 4 };
static int make_dual_table(const hb_plan *plan, bench_op op, int thetas)
{
    if (op != OP_DUAL || hb_dual_table_create(plan, thetas, HB_DUAL_DENSITY, HB_DUAL_DENSITY, NULL, NULL, NULL, NULL,
                                              &dual_table) == HB_OK)
        return 1;
    fprintf(stderr, "bench: %s\n", hb_last_error()->message);
    return 0;
}

static int time_plan(const hb_material *m, const hb_options *o, bench_op op, int per_hit, row *r)
{
    hb_plan *plan = NULL;
    hb_error err;
    if (hb_plan_create(m, o, &plan, &err) != HB_OK) {
        fprintf(stderr, "bench: %s\n", err.message);
        return 0;
    }
    int repeats = o->term == HB_TERM_FULL ? REPEATS / 10 : REPEATS;
    double t[REPEATS];
    if (!make_dual_table(plan, op, 64)) {
        hb_plan_destroy(plan);
        return 0;
    }
    run_op(plan, op, per_hit); /* warm up */
    double ghz_before = hb_cpu_clock_ghz();
    for (int k = 0; k < repeats; k++) {
        double t0 = now_ns();
        run_op(plan, op, per_hit);
        t[k] = (now_ns() - t0) / BATCH;
    }
    qsort(t, (size_t)repeats, sizeof t[0], compare_double);
    /* HHH22 path weights and eq. 33's pdf are estimates themselves: no reference */
    int traced = o->model == HB_MODEL_HUANG && (o->lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT)) && op != OP_EVAL;
    if (op_is(op, OP_SAMPLE) && !traced) { /* the weight's error: f_ref / pdf at the sampled directions */
        hb_options ro = *o;
        ro.quality = HB_QUALITY_REFERENCE;
        ro.pole_floor = HB_POLE_FLOOR_BOUNDED; /* HHH22: the kernels' pole choice, so the error is the float path's */
        hb_plan *reference;
        hb_plan_create(m, &ro, &reference, NULL);
        hb_rgb_soa f_ref = { ref[0], ref[1], ref[2] };
        if (op == OP_SAMPLE_NEAR)
            hb_eval_near(reference, NREF, (hb_near_soa){ sampled_theta, sampled_phi, theta_o, phi_o, offset_h }, f_ref,
                         NULL);
        else
            hb_eval_angles(reference, NREF, (hb_angles_soa){ sampled_theta, sampled_phi, theta_o, phi_o }, f_ref, NULL);
        hb_plan_destroy(reference);
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < NREF; k++)
                ref[c][k] = sampled_pdf[k] > 0.0f ? ref[c][k] / sampled_pdf[k] : 0.0f;
    }
    for (int k = 0; op == OP_DUAL && k < NREF; k++) { /* the double reference of the same table */
        hb_dual_terms d = { .struct_size = sizeof d };
        double f[3];
        hb_dual_table_terms(dual_table, theta_i[k], &d);
        hb_dual_radiance(&d, HB_DUAL_DENSITY, HB_DUAL_DENSITY, theta_i[k], phi_i[k], theta_o[k], phi_o[k], fibres[k], -1.0, f);
        for (int c = 0; c < 3; c++)
            ref[c][k] = (float)f[c];
    }
    hb_dual_table_destroy(dual_table);
    dual_table = NULL;
    r->min_ns = t[0];
    r->median_ns = t[repeats / 2];
    r->ghz = fmax(ghz_before, hb_cpu_clock_ghz()); /* the faster clock: the one the minimum ran at */
    r->isa = hb_plan_isa(plan);
    double peak = 0.0, worst = 0.0; /* docs/conventions.md, over the samples with a reference */
    for (int c = 0; c < planes_of(op); c++)
        for (int k = 0; k < NREF; k++)
            peak = fmax(peak, ref[c][k]);
    for (int c = 0; c < planes_of(op); c++)
        for (int k = 0; k < NREF; k++)
            worst = fmax(worst, fabs((double)out[c][k] - ref[c][k]) / fmax(ref[c][k], 1e-3 * peak));
    r->max_rel_err = traced ? NAN : worst;
    hb_plan_destroy(plan);
    return 1;
}

/* Budget lines: model term variant isa cycles. Writes a verdict per row to verdicts, cycles with the
 * ns at the measured clock beside them, and returns the number of rows over budget. */
static int check_budgets(const char *path, const row *rows, int nrows, FILE *verdicts)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "bench: cannot read budget file %s\n", path);
        return 1;
    }
    char line[256];
    int over = 0, checked = 0;
    while (fgets(line, sizeof line, f)) {
        char model[32], term[32], variant[32], isa[32];
        double budget;
        if (line[0] == '#' || sscanf(line, "%31s %31s %31s %31s %lf", model, term, variant, isa, &budget) != 5)
            continue;
        for (int k = 0; k < nrows; k++) {
            const row *r = &rows[k];
            if (strcmp(r->model, model) || strcmp(r->term, term) || strcmp(r->variant, variant) ||
                strcmp(hb_isa_name(r->isa), isa))
                continue;
            checked++;
            double cycles = r->min_ns * r->ghz;
            int fits = r->ghz > 0.0 && cycles <= budget;
            over += !fits;
            int long_run = r->min_ns >= 1e5; /* a precomputation row: its time in ms */
            fprintf(verdicts, "%s: %s %s %s on %s: %.0f cycles %s %.0f (%.2f %s at %.2f GHz)\n",
                    fits ? "budget ok" : "OVER BUDGET", model, term, variant, isa, cycles, fits ? "<=" : ">", budget,
                    long_run ? r->min_ns * 1e-6 : r->min_ns, long_run ? "ms" : "ns", r->ghz);
        }
    }
    fclose(f);
    if (!checked)
        fprintf(verdicts, "no budget row matched the ISAs this CPU has\n");
    return over;
}

#define HB_LOBES_HUANG (1u << HB_LOBE_R | 1u << HB_LOBE_TT | 1u << HB_LOBE_TRT)

typedef struct config {
    const char *model, *term, *variant;
    hb_model model_enum;
    hb_term term_enum;
    hb_quality quality;
    int quadrature_order;
    hb_i0 i0;
    hb_shadowing shadowing;         /* HHH22 */
    hb_r_integration r_integration; /* HHH22 */
    double r_step;                  /* HHH22: the paper's Simpson rule */
    bench_op op;
    unsigned lobes; /* HHH22: 0 for R alone */
    hb_tt_trt tt_trt;
    hb_azimuthal azimuthal; /* dFH11: N_p by quadrature or from the plan's table */
    int untilted;           /* the effect rows: alpha = 0 (dFH11: one M_p for lobes of equal roughness) */
    double eccentricity;    /* an elliptical fibre (MJC03, HHH22) */
    const char *label;      /* what the row measures, in the tables of docs/benchmarks.md and the README */
    int per_hit;            /* one call per sample (ns per call), as a path tracer calls at each hit */
} config;

/* What each row measures: dFH11's M_p alone and its full model (R..TRRT + residual, RGB) per
 * quality, at the paper's quadrature order 35 (float M_p, and double M_p as at high), and with N_p
 * from the plan's table (docs/engines.md); MJC03's longitudinal term and its full model (R + TT + TRT, RGB: one closed-form
 * kernel for every quality); HHH22's R lobe (GGX 0.1): App. A's closed form without G, Simpson
 * with Smith G in the peak-following variable per quality, and the paper's rule (steps of 0.7
 * roughness in phi_m); sampling of dFH11 and of HHH22's R lobe with G (direction, pdf and weight;
 * its error is the weight's against f_ref / pdf at the sampled directions) and their pdf alone
 * (against the reference quality's pdf: dFH11's procedure with the high-quality node set, HHH22's
 * by adaptive quadrature). */
static const config configs[] = {
    { "deon", "longitudinal", "abramowitz", HB_MODEL_DEON, HB_TERM_LONGITUDINAL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 M_p alone (eq. 7, A&S I0), float (fast, balanced)", 0 },
    { "deon", "longitudinal", "abramowitz-high", HB_MODEL_DEON, HB_TERM_LONGITUDINAL, HB_QUALITY_HIGH, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 M_p alone, double where it matters (high, reference)", 0 },
    { "deon", "longitudinal", "paper", HB_MODEL_DEON, HB_TERM_LONGITUDINAL, HB_QUALITY_BALANCED, 0, HB_I0_PAPER, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 M_p alone with eq. 15's series (error against the series in double)", 0 },
    { "deon", "full", "fast", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_FAST, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 full, R..TRRT + residual, RGB: fast", 0 },
    { "deon", "full", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 full: balanced", 0 },
    { "deon", "full", "absorption-balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_ABSORPTION, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 full: balanced, absorption per sample (hb_eval_angles_absorption)", 0 },
    { "deon", "full", "high", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_HIGH, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 full: high", 0 },
    { "deon", "full", "order35", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 35, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 full: the paper's order 35 (18 nodes), float M_p", 0 },
    { "deon", "full", "order35-high", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_HIGH, 35, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 full: order 35, double M_p (as at high)", 0 },
    { "deon", "full", "table-fast", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_FAST, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_TABLE, 0, 0.0,
      "dFH11 full, N_p from the table: fast", 0 },
    { "deon", "full", "table-balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_TABLE, 0, 0.0,
      "dFH11 full, N_p from the table: balanced", 0 },
    { "deon", "full", "table-high", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_HIGH, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_TABLE, 0, 0.0,
      "dFH11 full, N_p from the table: high", 0 },
    { "deon", "full", "colour-table-fast", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_FAST, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_ABSORPTION, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_COLOUR_TABLE, 0, 0.0,
      "dFH11 full, N_p from the colour table at each sample's absorption: fast", 0 },
    { "deon", "dual", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_DUAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 balanced: the dual-scattering term f_DS alone (hb_dual_eval, 64-node table, 0..16 fibres)", 0 },
    { "chiang", "dual", "balanced", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_DUAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "CBTB16 balanced: the dual-scattering term f_DS alone (hb_dual_eval, 64-node table)", 0 },
    { "marschner", "longitudinal", "gaussian", HB_MODEL_MARSCHNER, HB_TERM_LONGITUDINAL, HB_QUALITY_BALANCED, 0,
      HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "MJC03 longitudinal term alone", 0 },
    { "marschner", "full", "closed-form", HB_MODEL_MARSCHNER, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "MJC03 full, R + TT + TRT with caustics, RGB", 0 },
    { "marschner", "full", "absorption", HB_MODEL_MARSCHNER, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_ABSORPTION, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "MJC03 full, absorption per sample (hb_eval_angles_absorption)", 0 },
    { "huang", "R", "analytic", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_NONE, HB_R_INTEGRATION_ANALYTIC, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R, GGX 0.1, App. A closed form (no G)", 0 },
    { "huang", "R", "G-fast", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_FAST, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R with Smith G, Simpson (peak-following): fast (16 panels)", 0 },
    { "huang", "R", "G-balanced", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R with G: balanced (32 panels)", 0 },
    { "huang", "R", "G-high", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_HIGH, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R with G: high (64 panels)", 0 },
    { "huang", "R", "G-paper-step", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_NUMERIC, 0.7, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R with G, the paper's rule (steps of 0.7 roughness)", 0 },
    { "deon", "sample", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_SAMPLE, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 sampling: w_i, pdf and weight f/pdf (error: the weight's), balanced", 0 },
    { "deon", "pdf", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_PDF, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 sampling pdf alone (error: against the reference quality's pdf), balanced", 0 },
    { "huang", "sample", "G-balanced", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_SAMPLE, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R sampling with G: w_i, pdf and weight (error: the weight's), balanced", 0 },
    { "huang", "pdf", "G-balanced", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_PDF, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R sampling pdf alone (error: against adaptive quadrature), balanced", 0 },
    { "huang", "all", "mc-fast", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_FAST, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH,
      HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, HB_LOBES_HUANG, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R + TT + TRT, Monte-Carlo TT/TRT: fast (error: one estimate's noise)", 0 },
    { "huang", "all", "mc-balanced", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, HB_LOBES_HUANG, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R + TT + TRT, Monte-Carlo TT/TRT: balanced", 0 },
    { "huang", "all", "table-fast", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_FAST, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, HB_LOBES_HUANG, HB_TT_TRT_TABLE, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R + TT + TRT, TT/TRT from the table: fast (error: where f is under 1% of the peak)", 0 },
    { "huang", "all", "table-balanced", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, HB_LOBES_HUANG, HB_TT_TRT_AUTO, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 R + TT + TRT, TT/TRT from the table tt_trt auto builds: balanced", 0 },
    { "huang", "TT+TRT", "table-balanced", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, HB_LOBES_HUANG & ~1u, HB_TT_TRT_AUTO, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 TT + TRT table lookup alone, tt_trt auto, balanced", 0 },
    { "huang", "sample-all", "balanced", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_SAMPLE, HB_LOBES_HUANG, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 sampling with TT and TRT (one traced path; no reference), balanced", 0 },
    { "huang", "pdf-all", "balanced", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_PDF, HB_LOBES_HUANG, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "HHH22 sampling pdf with TT and TRT, balanced", 0 },
    /* CBTB16 (pbrt-v4's hair): near-field f at each sample's h per quality (the float and the double
     * M_p), its sampler and pdf, the far field (the mean over h) per quality, and R alone */
    { "chiang", "near", "balanced", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "CBTB16 near field at h, balanced (float M_p)", 0 },
    { "chiang", "near", "high", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_HIGH, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "CBTB16 near field at h, high (double M_p)", 0 },
    { "chiang", "near-spectral4", "balanced", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_SPECTRAL_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "CBTB16 near field at h at pbrt-v4's 4 wavelengths, balanced", 0 },
    { "deon", "full-spectral4", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_SPECTRAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 full at pbrt-v4's 4 wavelengths, balanced", 0 },
    { "chiang", "sample-near", "balanced", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_SAMPLE_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "CBTB16 sampling at h (direction, pdf and f / pdf), balanced", 0 },
    { "chiang", "pdf-near", "balanced", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_PDF_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "CBTB16 sampling pdf at h, balanced", 0 },
    { "chiang", "far", "fast", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_FAST, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "CBTB16 far field (mean over h), fast", 0 },
    { "chiang", "far", "balanced", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "CBTB16 far field (mean over h), balanced", 0 },
    { "chiang", "far", "high", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_HIGH, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "CBTB16 far field (mean over h), high", 0 },
    { "chiang", "effects", "R", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_NEAR, 1u, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "effect: CBTB16 near field, R only", 0 },
    /* dFH11 at the hit's h (near.h): f, its sampler and pdf; f and the pdf in one call (far field) */
    { "deon", "near", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 near field at h, balanced", 0 },
    { "deon", "near-spectral4", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_SPECTRAL_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 near field at h at pbrt-v4's 4 wavelengths, balanced", 0 },
    { "deon", "sample-near", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_SAMPLE_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 sampling at h (direction, pdf and f / pdf), balanced", 0 },
    { "deon", "pdf-near", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_PDF_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 sampling pdf at h, balanced", 0 },
    { "deon", "eval-pdf", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_PDF, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "dFH11 f and pdf in one call (hb_eval_pdf_angles), balanced", 0 },
    /* per hit: one call of one sample, ns per call (the batch rows above are ns per sample) */
    { "deon", "per-hit", "balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "per hit (ns per call of n = 1): dFH11 far field, balanced", 1 },
    { "deon", "per-hit", "near-balanced", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "per hit: dFH11 near field at h, balanced", 1 },
    { "deon", "per-hit", "eval-pdf", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_PDF, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "per hit: dFH11 f and pdf in one call, balanced", 1 },
    { "marschner", "per-hit", "closed-form", HB_MODEL_MARSCHNER, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "per hit: MJC03 full", 1 },
    { "huang", "per-hit", "R-analytic", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_NONE, HB_R_INTEGRATION_ANALYTIC, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "per hit: HHH22 R, App. A closed form", 1 },
    { "chiang", "per-hit", "near-balanced", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "per hit: CBTB16 near field at h, balanced", 1 },
    { "chiang", "per-hit", "near-spectral4", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_SPECTRAL_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "per hit: CBTB16 near field at h at pbrt-v4's 4 wavelengths, balanced", 1 },
    /* a path tracer's step at one hit, from vectors (examples/path_tracer.c): sample, then f and pdf */
    { "deon", "per-hit", "path-step", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_HIT, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "per hit: a path tracer's step from vectors (hb_hit_sample, hb_hit_eval_pdf), dFH11 balanced", 1 },
    { "chiang", "per-hit", "path-step-near", HB_MODEL_CHIANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_HIT_NEAR, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "per hit: a path tracer's step from vectors at h, CBTB16 balanced", 1 },
    /* what each effect costs: the balanced dFH11 row without TRT and above (dark hair), without the tilt,
     * R alone; MJC03 R alone and R + TT; HHH22's R lobe on an elliptical fibre */
    { "deon", "effects", "R+TT", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH,
      HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 3u, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "effect: dFH11 balanced, R + TT only (dark hair)", 0 },
    { "deon", "effects", "untilted", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 1, 0.0,
      "effect: dFH11 balanced, alpha = 0 (one M_p for every lobe)", 0 },
    { "deon", "effects", "R+TT-untilted", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 3u, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 1, 0.0,
      "effect: dFH11 balanced, R + TT, alpha = 0", 0 },
    { "deon", "effects", "R", HB_MODEL_DEON, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ, HB_SHADOWING_SMITH,
      HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 1u, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "effect: dFH11 balanced, R only (black hair)", 0 },
    { "marschner", "effects", "R", HB_MODEL_MARSCHNER, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 1u, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "effect: MJC03, R only", 0 },
    { "marschner", "effects", "R+TT", HB_MODEL_MARSCHNER, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 3u, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.0,
      "effect: MJC03, R + TT", 0 },
    { "marschner", "effects", "elliptical", HB_MODEL_MARSCHNER, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.5,
      "effect: MJC03, elliptical fibre (e 0.5)", 0 },
    { "huang", "effects", "G-balanced-elliptical", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 0, 0.5,
      "effect: HHH22 R with G, balanced, elliptical fibre (e 0.5)", 0 },
    { "huang", "effects", "G-balanced-untilted", HB_MODEL_HUANG, HB_TERM_FULL, HB_QUALITY_BALANCED, 0, HB_I0_ABRAMOWITZ,
      HB_SHADOWING_SMITH, HB_R_INTEGRATION_AUTO, 0.0, OP_EVAL, 0, HB_TT_TRT_MC, HB_AZIMUTHAL_QUADRATURE, 1, 0.0,
      "effect: HHH22 R with G, balanced, no tilt", 0 },
};

/* The options of a configuration (quality and ISA left to the caller where they differ). */
static void options_of(const config *c, hb_options *o)
{
    hb_options_default(o);
    o->model = c->model_enum;
    o->term = c->term_enum;
    o->quality = c->quality;
    o->quadrature_order = c->quadrature_order;
    o->i0 = c->i0;
    o->shadowing = c->shadowing;
    o->r_integration = c->r_integration;
    o->r_step = c->r_step;
    o->azimuthal = c->azimuthal;
    if (c->model_enum == HB_MODEL_HUANG) {
        o->lobes = c->lobes ? c->lobes : 1u << HB_LOBE_R;
        o->tt_trt = c->tt_trt;
    } else if (c->lobes) {
        o->lobes = c->lobes;
    }
}

/* The bench's material, blond hair, with the configuration's effect changes. */
static void material_of(const config *c, hb_material *m)
{
    hb_material_default(m);
    m->sigma_a[0] = 0.1, m->sigma_a[1] = 0.25, m->sigma_a[2] = 0.6;
    if (c->untilted)
        m->alpha = 0.0;
    m->eccentricity = c->eccentricity;
}
#define N_CONFIGS (sizeof configs / sizeof configs[0])

enum { REFERENCE_SEEDS = 1024 };


/* HHH22 with TT and TRT: the nested-quadrature reference takes seconds per pair, so the reference is
 * the mean of the high-quality estimator over REFERENCE_SEEDS seeds (its own noise about 1.5% of a
 * value), made once per lobe set. */
static void internal_reference(const hb_material *m, const config *c)
{
    static unsigned made = 0;
    static float cache[2][3][NREF];
    int slot = c->lobes >> HB_LOBE_R & 1u;
    if (!(made >> slot & 1u)) {
        static double sum[3][NREF];
        memset(sum, 0, sizeof sum);
        for (int s = 0; s < REFERENCE_SEEDS; s++) {
            hb_options o;
            options_of(c, &o);
            o.quality = HB_QUALITY_HIGH;
            o.tt_trt = HB_TT_TRT_MC;
            o.seed = (unsigned long long)s;
            hb_plan *plan;
            hb_plan_create(m, &o, &plan, NULL);
            hb_eval_angles(plan, NREF, (hb_angles_soa){ theta_i, phi_i, theta_o, phi_o },
                           (hb_rgb_soa){ out[0], out[1], out[2] }, NULL);
            hb_plan_destroy(plan);
            for (int ch = 0; ch < 3; ch++)
                for (int k = 0; k < NREF; k++)
                    sum[ch][k] += out[ch][k];
        }
        for (int ch = 0; ch < 3; ch++)
            for (int k = 0; k < NREF; k++)
                cache[slot][ch][k] = (float)(sum[ch][k] / REFERENCE_SEEDS);
        made |= 1u << slot;
    }
    for (int ch = 0; ch < 3; ch++)
        memcpy(ref[ch], cache[slot][ch], sizeof cache[slot][ch]);
}

/* The double reference of the plan's term for the first NREF samples (it is slow). */
static void reference_of(const hb_material *m, const config *c)
{
    if (c->model_enum == HB_MODEL_HUANG && (c->lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT))) {
        if (c->op == OP_EVAL)
            internal_reference(m, c);
        return;
    }
    hb_options o;
    options_of(c, &o);
    o.quality = HB_QUALITY_REFERENCE;
    o.pole_floor = HB_POLE_FLOOR_BOUNDED; /* HHH22: the kernels' pole choice, so the error is the float path's */
    o.azimuthal = HB_AZIMUTHAL_QUADRATURE;
    o.r_integration = HB_R_INTEGRATION_AUTO;
    o.r_step = 0.0;
    hb_plan *plan;
    hb_plan_create(m, &o, &plan, NULL);
    /* (a sampling row's reference is made per ISA at its sampled directions, in time_plan) */
    hb_angles_soa in = { theta_i, phi_i, theta_o, phi_o };
    hb_near_soa near = { theta_i, phi_i, theta_o, phi_o, offset_h };
    if (op_is(c->op, OP_PDF)) {
        if (c->op == OP_PDF_NEAR)
            hb_pdf_near(plan, NREF, near, ref[0], NULL);
        else
            hb_pdf_angles(plan, NREF, in, ref[0], NULL);
        memcpy(ref[1], ref[0], sizeof ref[0]);
        memcpy(ref[2], ref[0], sizeof ref[0]);
    } else if (c->op == OP_EVAL || c->op == OP_EVAL_PDF || c->op == OP_EVAL_ABSORPTION || c->op == OP_HIT) {
        hb_eval_angles(plan, NREF, in, (hb_rgb_soa){ ref[0], ref[1], ref[2] }, NULL);
    } else if (c->op == OP_EVAL_NEAR || c->op == OP_HIT_NEAR) {
        hb_eval_near(plan, NREF, near, (hb_rgb_soa){ ref[0], ref[1], ref[2] }, NULL);
    } else if (c->op == OP_SPECTRAL_NEAR) {
        const float *sigma_a[WAVELENGTHS] = { spectral_absorption[0], spectral_absorption[1], spectral_absorption[2],
                                              spectral_absorption[3] };
        hb_eval_near_spectral(plan, NREF, near, (hb_spectral_absorption){ WAVELENGTHS, sigma_a },
                              (float *const[]){ ref[0], ref[1], ref[2], ref[3] }, NULL);
    } else if (c->op == OP_SPECTRAL) { /* a reference plan of each wavelength's absorption in every channel */
        for (int j = 0; j < WAVELENGTHS; j++) {
            static float other[2][NREF];
            hb_material grey = *m;
            grey.eumelanin = grey.pheomelanin = 0.0;
            grey.sigma_a[0] = grey.sigma_a[1] = grey.sigma_a[2] = spectral_absorption[j][0];
            hb_plan *at = NULL;
            hb_plan_create(&grey, &o, &at, NULL);
            hb_eval_angles(at, NREF, in, (hb_rgb_soa){ ref[j], other[0], other[1] }, NULL);
            hb_plan_destroy(at);
        }
    }
    hb_plan_destroy(plan);
}

/* ns per sample with three significant digits, as the tables print them. */
static void put_ns(FILE *f, double ns)
{
    fprintf(f, ns < 10.0 ? " %.2f |" : ns < 100.0 ? " %.1f |" : " %.0f |", ns);
}

/* "model name" of /proc/cpuinfo, or what the compiler knows of the architecture. */
static void cpu_name(char *name, size_t size)
{
    snprintf(name, size, "%s", HB_ARCH_NAME);
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    while (f && fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) == 0 && colon) {
            snprintf(name, size, "%s", colon + 2);
            name[strcspn(name, "\n")] = '\0';
            break;
        }
    }
    if (f)
        fclose(f);
}

/* A marked region's text being written: the run's date and CPU, the text in memory (readme.h). */
typedef struct region {
    FILE *f;
    char *text;
    char cpu[256], date[32];
} region;

static int region_open(region *r)
{
    cpu_name(r->cpu, sizeof r->cpu);
    time_t now = time(NULL);
    strftime(r->date, sizeof r->date, "%Y-%m-%d", gmtime(&now));
    r->text = NULL;
    r->f = bench_text_open();
    return r->f != NULL;
}

/* Closes the text and writes it between the marker lines begin and end of the file at path. */
static void region_write(region *r, const char *path, const char *begin, const char *end)
{
    r->text = bench_text_close(r->f);
    if (r->text && !bench_update_region(path, begin, end, r->text))
        printf("wrote %s ... %s of %s\n", begin, end, path);
    free(r->text);
}

/* docs/benchmarks.md's bench region (readme.h): what ran where, one line per configuration with its ns/sample
 * on each ISA (the budgets' AVX2 first), the error and speed-up over scalar of the first ISA there,
 * then the multi-core line and the budgets' verdicts. */
static void write_report(const char *path, const row *rows, int nrows, const char *scaling_text,
                         const char *budget_text)
{
    static const hb_isa columns[] = { HB_ISA_AVX2, HB_ISA_AVX512, HB_ISA_NEON, HB_ISA_SSE41, HB_ISA_SCALAR };
    enum { NCOLUMNS = sizeof columns / sizeof columns[0] };
    int present[NCOLUMNS] = { 0 };
    for (int k = 0; k < nrows; k++)
        for (int c = 0; c < NCOLUMNS; c++)
            present[c] |= rows[k].isa == columns[c];
    region r;
    if (!region_open(&r))
        return;
    FILE *f = r.f;
    const char *cpu = r.cpu, *date = r.date;
    fprintf(f, "`make bench`, %s, %s (%ld cores), %s -O2; one pinned core, batches of %d directions (half near\n"
               "the specular cone), blond hair (sigma_a = 0.1/0.25/0.6, beta_m 0.1, beta_n 0.3, alpha 0.035). ns per\n"
               "sample: the minimum over repeated batches. Error: max over %d samples and 3 channels of\n"
               "|f - f_ref| / max(|f_ref|, 1e-3 peak) against the double reference of the same configuration\n"
               "([conventions.md](conventions.md)), on the first ISA shown; speed-up: that ISA against scalar. Written by\n"
               "`make bench` itself.\n\n| what |",
            date, cpu, bench_cores(), HB_COMPILER, BATCH, NREF);
    for (int c = 0; c < NCOLUMNS; c++)
        if (present[c])
            fprintf(f, " ns/sample %s |", hb_isa_name(columns[c]));
    fprintf(f, " max error | speed-up |\n|---|");
    for (int c = 0; c < NCOLUMNS; c++)
        if (present[c])
            fprintf(f, "---|");
    fprintf(f, "---|---|\n");
    for (size_t ci = 0; ci < N_CONFIGS; ci++) {
        const row *by_isa[NCOLUMNS] = { NULL }, *first = NULL, *scalar = NULL;
        for (int k = 0; k < nrows; k++)
            for (int c = 0; c < NCOLUMNS; c++)
                if (rows[k].config == (int)ci && rows[k].isa == columns[c])
                    by_isa[c] = &rows[k];
        for (int c = 0; c < NCOLUMNS; c++)
            first = first ? first : by_isa[c];
        scalar = by_isa[NCOLUMNS - 1];
        if (!first)
            continue;
        fprintf(f, "| %s |", configs[ci].label);
        for (int c = 0; c < NCOLUMNS; c++)
            if (present[c]) {
                if (by_isa[c])
                    put_ns(f, by_isa[c]->min_ns);
                else
                    fprintf(f, " - |");
            }
        if (isnan(first->max_rel_err))
            fprintf(f, " - |");
        else
            fprintf(f, " %.1e |", first->max_rel_err);
        if (scalar)
            fprintf(f, " %.1fx |\n", scalar->min_ns / first->min_ns);
        else
            fprintf(f, " - |\n");
    }
    fprintf(f, "\n```\n%s%s```\n", scaling_text, budget_text);
    region_write(&r, path, HB_REPORT_BEGIN, HB_REPORT_END);
}

/* The row of configuration key MODEL/TERM/VARIANT on isa, or NULL. */
static const row *find_row(const row *rows, int nrows, const char *key, hb_isa isa)
{
    for (int k = 0; k < nrows; k++) {
        char label[64];
        snprintf(label, sizeof label, "%s/%s/%s", rows[k].model, rows[k].term, rows[k].variant);
        if (rows[k].isa == isa && strcmp(label, key) == 0)
            return &rows[k];
    }
    return NULL;
}

/* docs/benchmarks.md's effects region: what turning one effect off saves, each pair of rows of
 * the run on AVX2 (the budgets' ISA). */
static void write_effects(const char *path, const row *rows, int nrows)
{
    static const struct {
        const char *what, *with, *without;
    } effects[] = {
        { "dFH11 balanced: TRT, TRRT and residual (dark hair: R + TT)", "deon/full/balanced", "deon/effects/R+TT" },
        { "dFH11 balanced: the tilt (alpha = 0: one M_p for every lobe)", "deon/full/balanced", "deon/effects/untilted" },
        { "dFH11 balanced: both (dark hair, untilted)", "deon/full/balanced", "deon/effects/R+TT-untilted" },
        { "dFH11 balanced: everything but R (black hair)", "deon/full/balanced", "deon/effects/R" },
        { "dFH11: N_p by quadrature vs from the table (balanced)", "deon/full/balanced", "deon/full/table-balanced" },
        { "MJC03: TT and TRT (R alone)", "marschner/full/closed-form", "marschner/effects/R" },
        { "MJC03: TRT (R + TT)", "marschner/full/closed-form", "marschner/effects/R+TT" },
        { "MJC03: the elliptical fibre (e 0.5 vs circular)", "marschner/effects/elliptical", "marschner/full/closed-form" },
        { "HHH22 R, balanced: Smith G (App. A closed form without it)", "huang/R/G-balanced", "huang/R/analytic" },
        { "HHH22 R, balanced: the elliptical fibre (e 0.5)", "huang/effects/G-balanced-elliptical", "huang/R/G-balanced" },
        { "HHH22 R, balanced: the tilt", "huang/R/G-balanced", "huang/effects/G-balanced-untilted" },
        { "CBTB16 near field, balanced: TT, TRT and the residual (R alone)", "chiang/near/balanced", "chiang/effects/R" },
        { "CBTB16 near field, balanced: pbrt-v4's 4 wavelengths (RGB)", "chiang/near-spectral4/balanced", "chiang/near/balanced" },
        { "dFH11 balanced: pbrt-v4's 4 wavelengths (RGB)", "deon/full-spectral4/balanced", "deon/full/balanced" },
        { "dFH11 near field, balanced: pbrt-v4's 4 wavelengths (RGB)", "deon/near-spectral4/balanced", "deon/near/balanced" },
        { "CBTB16 per hit: pbrt-v4's 4 wavelengths (RGB)", "chiang/per-hit/near-spectral4", "chiang/per-hit/near-balanced" },
    };
    region r;
    if (!region_open(&r))
        return;
    FILE *f = r.f;
    fprintf(f, "| effect | ns/sample with it (avx2) | without it | saving |\n|---|---|---|---|\n");
    for (size_t k = 0; k < sizeof effects / sizeof effects[0]; k++) {
        const row *with = find_row(rows, nrows, effects[k].with, HB_ISA_AVX2);
        const row *without = find_row(rows, nrows, effects[k].without, HB_ISA_AVX2);
        if (!with || !without)
            continue;
        fprintf(f, "| %s |", effects[k].what);
        put_ns(f, with->min_ns);
        put_ns(f, without->min_ns);
        fprintf(f, " %.0f%% |\n", 100.0 * (1.0 - without->min_ns / with->min_ns));
    }
    fprintf(f, "\n`make bench`, %s, %s, the same run as the table above.\n", r.date, r.cpu);
    region_write(&r, path, HB_EFFECTS_BEGIN, HB_EFFECTS_END);
}

static int is_demo_row(const char *label);

/* The README's summary region: the demo rows on the best ISA of the run, ns per sample and error. */
static void write_summary(const char *path, const row *rows, int nrows)
{
    hb_isa best = hb_isa_best();
    region r;
    if (!region_open(&r))
        return;
    FILE *f = r.f;
    static const double aims[] = { [HB_QUALITY_FAST] = 1e-2, [HB_QUALITY_BALANCED] = 1e-3, [HB_QUALITY_HIGH] = 1e-4 };
    fprintf(f, "| model and quality | ns/sample (%s) | max error | the level's aim |\n|---|---|---|---|\n",
            hb_isa_name(best));
    for (int k = 0; k < nrows; k++) {
        char label[64];
        snprintf(label, sizeof label, "%s/%s/%s", rows[k].model, rows[k].term, rows[k].variant);
        if (rows[k].isa != best || !is_demo_row(label))
            continue;
        const config *c = &configs[rows[k].config];
        fprintf(f, "| %s |", c->label);
        put_ns(f, rows[k].min_ns);
        double aim = c->quality < HB_QUALITY_REFERENCE ? aims[c->quality] : 0.0;
        if (aim > 0.0)
            fprintf(f, " %.1e | %.0e%s |\n", rows[k].max_rel_err, aim, rows[k].max_rel_err <= aim ? "" : ", missed");
        else
            fprintf(f, " %.1e | - |\n", rows[k].max_rel_err);
    }
    fprintf(f, "\n`make bench`, %s, %s, one core, batches of %d; every row on every ISA in "
               "[docs/benchmarks.md](docs/benchmarks.md).\n", r.date, r.cpu, BATCH);
    region_write(&r, path, HB_SUMMARY_BEGIN, HB_SUMMARY_END);
}

/* --once CONFIG: evaluate one batch of CONFIG on $HB_ISA `repeats` times (default once) and exit,
 * for callgrind (make bench-instr counts the instructions inside hb_eval_angles) or, repeated,
 * for a sampling profiler such as perf record. */
static int run_once(const char *name, long repeats)
{
    for (size_t ci = 0; ci < N_CONFIGS; ci++) {
        char label[64];
        snprintf(label, sizeof label, "%s/%s/%s", configs[ci].model, configs[ci].term, configs[ci].variant);
        if (strcmp(label, name) != 0)
            continue;
        hb_material m;
        material_of(&configs[ci], &m);
        make_inputs(&m);
        hb_options o;
        options_of(&configs[ci], &o);
        hb_plan *plan;
        hb_error err;
        if (hb_plan_create(&m, &o, &plan, &err) != HB_OK) {
            fprintf(stderr, "bench: %s\n", err.message);
            return 2;
        }
        float *streams[HB_SAMPLE_DIMENSIONS];
        for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
            streams[d] = uniforms[d];
        hb_uniforms(1, 0, BATCH, HB_SAMPLE_DIMENSIONS, streams);
        if (!make_dual_table(plan, configs[ci].op, ONCE_DUAL_THETAS)) {
            hb_plan_destroy(plan);
            return 2;
        }
        for (long r = 0; r < repeats; r++)
            run_op(plan, configs[ci].op, configs[ci].per_hit);
        hb_dual_table_destroy(dual_table);
        dual_table = NULL;
        hb_plan_destroy(plan);
        return 0;
    }
    fprintf(stderr, "bench: no configuration '%s'\n", name);
    return 2;
}

/* Multi-core scaling: threads in the bench only (the library never starts any), each pinned to its
 * core, evaluating the same immutable plan into its own output. */
enum { SCALING_REPEATS = 200, MAX_THREADS = 64 };

static void *worker_run(void *arg)
{
    const hb_plan *plan = arg;
    float *planes = malloc(3 * BATCH * sizeof *planes);
    for (int r = 0; planes && r < SCALING_REPEATS; r++)
        hb_eval_angles(plan, BATCH, (hb_angles_soa){ theta_i, phi_i, theta_o, phi_o },
                       (hb_rgb_soa){ planes, planes + BATCH, planes + 2 * BATCH }, NULL);
    free(planes);
    return NULL;
}

/* Samples per second of the balanced dFH11 plan on 1..cores threads, written to report. */
static void scaling(const hb_material *m, FILE *report)
{
    hb_options o;
    hb_options_default(&o);
    hb_plan *plan;
    if (hb_plan_create(m, &o, &plan, NULL) != HB_OK)
        return;
    long cores = bench_cores();
    cores = cores < 1 ? 1 : cores > MAX_THREADS ? MAX_THREADS : cores;
    double one = 0.0;
    fprintf(report, "Multi-core scaling (dFH11 full model, balanced, %s, %d batches of %d per thread):\n",
            hb_isa_name(hb_plan_isa(plan)), SCALING_REPEATS, BATCH);
    for (long n = 1; n <= cores; n++) {
        pthread_t threads[MAX_THREADS];
        double t0 = now_ns();
        long started = 0;
        while (started < n && bench_thread_start(&threads[started], (int)started, worker_run, plan) == 0)
            started++;
        for (long k = 0; k < started; k++)
            pthread_join(threads[k], NULL);
        double rate = (double)n * SCALING_REPEATS * BATCH / ((now_ns() - t0) * 1e-9) / 1e6;
        one = n == 1 ? rate : one;
        fprintf(report, "  %ld thread%s: %.2f Msamples/s (%.2fx one thread)\n", n, n > 1 ? "s" : "", rate, rate / one);
    }
    hb_plan_destroy(plan);
}

/* --demo (make demo): a handful of rows, each model's real-time and budgeted configurations, on
 * the best ISA alone. */
static int is_demo_row(const char *label)
{
    static const char *const demo_rows[] = { "deon/full/fast", "deon/full/balanced", "deon/full/high",
                                             "deon/full/table-balanced", "marschner/full/closed-form",
                                             "huang/R/analytic", "huang/R/G-balanced", "huang/TT+TRT/table-balanced" };
    for (size_t k = 0; k < sizeof demo_rows / sizeof demo_rows[0]; k++)
        if (!strcmp(label, demo_rows[k]))
            return 1;
    return 0;
}

int main(int argc, char **argv)
{
    const char *budgets = NULL, *results_dir = NULL, *only = "", *only_isa = NULL, *once = NULL, *report = NULL,
               *summary = NULL;
    long repeats = 1;
    int demo = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--budgets") == 0 && i + 1 < argc)
            budgets = argv[++i];
        else if (strcmp(argv[i], "--results") == 0 && i + 1 < argc)
            results_dir = argv[++i];
        else if (strcmp(argv[i], "--report") == 0 && i + 1 < argc)
            report = argv[++i];
        else if (strcmp(argv[i], "--summary") == 0 && i + 1 < argc)
            summary = argv[++i];
        else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc)
            only = argv[++i];
        else if (strcmp(argv[i], "--isa") == 0 && i + 1 < argc)
            only_isa = argv[++i];
        else if (strcmp(argv[i], "--demo") == 0)
            demo = 1;
        else if (strcmp(argv[i], "--once") == 0 && i + 1 < argc)
            once = argv[++i];
        else if (strcmp(argv[i], "--repeat") == 0 && i + 1 < argc && atol(argv[i + 1]) > 0)
            repeats = atol(argv[++i]);
        else if (strcmp(argv[i], "--list") == 0) {
            for (size_t ci = 0; ci < N_CONFIGS; ci++)
                printf("%s/%s/%s\n", configs[ci].model, configs[ci].term, configs[ci].variant);
            return 0;
        } else {
            fprintf(stderr,
                    "usage: %s [--budgets FILE] [--results DIR] [--report docs/benchmarks.md] [--summary README.md] [--only PREFIX] "
                    "[--isa NAME] [--demo] | "
                    "--list | --once MODEL/TERM/VARIANT [--repeat N]\n",
                    argv[0]);
            return 2;
        }
    }
    if (once)
        return run_once(once, repeats);
    if (bench_pin_self(0) != 0)
        fprintf(stderr, "bench: could not pin to core 0; timings may be noisier\n");

    hb_material m;
    material_of(&configs[0], &m); /* blond */
    make_inputs(&m);
    float *streams[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        streams[d] = uniforms[d];
    hb_uniforms(1, 0, BATCH, HB_SAMPLE_DIMENSIONS, streams);

    static row rows[N_CONFIGS * HB_ISA_COUNT + N_CONFIGS + BENCH_DUAL_MODELS]; /* + the dual-terms rows */
    int nrows = 0;
    for (size_t ci = 0; ci < N_CONFIGS; ci++) {
        const config *c = &configs[ci];
        char label[64];
        snprintf(label, sizeof label, "%s/%s/%s", c->model, c->term, c->variant);
        if (strncmp(label, only, strlen(only)) != 0 || (demo && !is_demo_row(label)))
            continue;
        hb_material mc;
        material_of(c, &mc);
        reference_of(&mc, c);
        for (int isa = HB_ISA_SCALAR; isa < HB_ISA_COUNT; isa++) {
            if (!hb_isa_available((hb_isa)isa) || (only_isa && strcmp(only_isa, hb_isa_name((hb_isa)isa))) ||
                (demo && isa != (int)hb_isa_best()))
                continue;
            hb_options o;
            options_of(c, &o);
            o.isa = (hb_isa)isa;
            row r = { c->model, c->term, c->variant, (int)ci, HB_ISA_SCALAR, 0, 0, 0, 0 };
            if (time_plan(&mc, &o, c->op, c->per_hit, &r))
                rows[nrows++] = r;
        }
    }
    printf("Blond hair (sigma_a 0.1/0.25/0.6, beta_m %.2g, beta_n %.2g, alpha %.3g), batch %d, one core\n", m.beta_m,
           m.beta_n, m.alpha, BATCH);
    printf("| model | term | variant | ISA | ns/sample (min) | ns/sample (median) | Msamples/s | max error | speed-up vs scalar |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < nrows; k++) {
        double scalar = 0.0;
        for (int j = 0; j < nrows; j++)
            if (rows[j].isa == HB_ISA_SCALAR && !strcmp(rows[j].variant, rows[k].variant) &&
                !strcmp(rows[j].term, rows[k].term) && !strcmp(rows[j].model, rows[k].model))
                scalar = rows[j].min_ns;
        char speedup[16] = "-"; /* no scalar row in a partial run */
        if (scalar > 0.0)
            snprintf(speedup, sizeof speedup, "%.1fx", scalar / rows[k].min_ns);
        printf("| %s | %s | %s | %s | %.2f | %.2f | %.1f | %.1e | %s |\n", rows[k].model, rows[k].term, rows[k].variant,
               hb_isa_name(rows[k].isa), rows[k].min_ns, rows[k].median_ns, 1e3 / rows[k].min_ns,
               rows[k].max_rel_err, speedup);
    }
    /* per model: a CSV of every row and an SVG of the full model's error against time */
    static const char *const models[][2] = { { "deon", "d'Eon 2011 full model" },
                                             { "marschner", "Marschner 2003 full model and lobe subsets" },
                                             { "huang", "Huang 2022 R lobe" } };
    int partial = *only || only_isa || demo; /* a partial run leaves the results of the last full run alone */
    for (int mi = 0; mi < 3 && results_dir && !partial; mi++) {
        static bench_point points[N_CONFIGS * HB_ISA_COUNT], full[N_CONFIGS * HB_ISA_COUNT];
        static char labels[N_CONFIGS * HB_ISA_COUNT][48];
        int npoints = 0, nfull = 0;
        for (int k = 0; k < nrows; k++) {
            if (strcmp(rows[k].model, models[mi][0]))
                continue;
            snprintf(labels[npoints], sizeof labels[0], "%s/%s", rows[k].term, rows[k].variant);
            points[npoints] = (bench_point){ labels[npoints], hb_isa_name(rows[k].isa), rows[k].min_ns,
                                             rows[k].max_rel_err };
            /* M_p alone and sampling measure other quantities; MJC03 has one quality, so its plot shows
             * the lobe subsets and the elliptical fibre (the effect rows) beside the full model */
            if (!strcmp(rows[k].term, "full") || !strcmp(rows[k].term, "R") ||
                (mi == 1 && !strcmp(rows[k].term, "effects")))
                full[nfull++] = points[npoints];
            npoints++;
        }
        char csv[512], svg[512], title[128];
        snprintf(csv, sizeof csv, "%s/%s.csv", results_dir, models[mi][0]);
        snprintf(svg, sizeof svg, "%s/%s.svg", results_dir, models[mi][0]);
        snprintf(title, sizeof title, "%s: error against time per sample, Pareto front per ISA", models[mi][1]);
        if (bench_write_csv(csv, points, npoints) || bench_write_svg(svg, title, full, nfull))
            fprintf(stderr, "bench: cannot write %s or %s\n", csv, svg);
        else
            printf("wrote %s and %s\n", csv, svg);
    }
    FILE *scaling_out = bench_text_open();
    if (!partial && scaling_out)
        scaling(&m, scaling_out);
    if ((!partial || !strcmp(only, "table-files")) && scaling_out)
        bench_table_files(&m, scaling_out);
    if ((!partial || !strcmp(only, "huang-table")) && scaling_out)
        bench_huang_table(scaling_out);
    bench_dual_cost dual_costs[BENCH_DUAL_MODELS];
    int ndual = 0;
    if ((!partial || !strcmp(only, "dual")) && scaling_out)
        ndual = bench_dual(&m, scaling_out, dual_costs);
    if ((!partial || !strcmp(only, "assembly")) && scaling_out)
        bench_assembly(&m, scaling_out);
    char *scaling_text = bench_text_close(scaling_out);
    printf("%s", scaling_text ? scaling_text : "");
    if (results_dir && !partial) { /* what tolerance and budget plans choose from (options.calibration) */
        char path[512];
        snprintf(path, sizeof path, "%s/calibration.csv", results_dir);
        FILE *f = fopen(path, "w");
        if (f) {
            fprintf(f, "model,configuration,isa,ns_per_sample,max_error,ghz\n");
            for (int k = 0; k < nrows; k++)
                fprintf(f, "%s,%s/%s,%s,%.3f,%.3e,%.3f\n", rows[k].model, rows[k].term, rows[k].variant,
                        hb_isa_name(rows[k].isa), rows[k].min_ns, rows[k].max_rel_err, rows[k].ghz);
        }
        if (!f || fclose(f) != 0)
            fprintf(stderr, "bench: cannot write %s\n", path);
        else
            printf("wrote %s\n", path);
    }
    /* the precomputation per material is budgeted as a row of its own, its ns per material */
    for (int k = 0; k < ndual; k++)
        rows[nrows++] = (row){ dual_costs[k].model, "dual-terms", "balanced", -1, dual_costs[k].isa, dual_costs[k].ns,
                               dual_costs[k].ns, 0.0, dual_costs[k].ghz };
    FILE *budget_out = bench_text_open();
    int over = budgets && budget_out ? check_budgets(budgets, rows, nrows, budget_out) : 0;
    nrows -= ndual; /* the report's tables and the summary hold the per-sample rows alone */
    char *budget_text = bench_text_close(budget_out);
    printf("%s", budget_text ? budget_text : "");
    if (report && !partial)
        write_report(report, rows, nrows, scaling_text ? scaling_text : "", budget_text ? budget_text : "");
    if (summary && !partial)
        write_summary(summary, rows, nrows);
    if (report && !partial)
        write_effects(report, rows, nrows);
    free(scaling_text);
    free(budget_text);
    return over ? 1 : 0;
}

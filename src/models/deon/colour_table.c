/* dFH11's colour table (HB_AZIMUTHAL_COLOUR_TABLE): N per M_p group for one channel over
 * (sqrt(cos(theta_d)), |phi|, w(sigma_a)), sigma_a from 0 to HB_COLOUR_TABLE_SIGMA_MAX. A channel's N
 * depends on its own absorption alone (eq. 13's attenuation T = exp(-2 mu_a' cos(gamma_t))), so one
 * table serves every melanin mix and every channel. Built with the plan's kernel three absorptions at a time (as its three
 * channels), refined like the material's table (table_build.c) with the error relative to each slot's
 * peak over every absorption, or loaded from a table file; and its view. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "models/build/build_tasks.h"
#include "models/build/derive.h"
#include "models/file/table_file.h"
#include "table.h"
#include "state.h"

#define MAX_X 257

/* The absorption axis w = log(1 + sigma_a / knee) / log(1 + SIGMA_MAX / knee), uniform in [0, 1]: nodes
 * spaced evenly in sigma_a below the knee and in proportion to sigma_a above. Near sigma_a = 0 at
 * grazing theta_d the residual's geometric series 1 / (1 - f T) (f -> 1) is a pole just beyond the
 * axis, which needs the dense end; far above, N falls as e^(-a sigma_a), which needs steps relative to
 * sigma_a. Measured (balanced, blond defaults): the absorption axis' midpoint error converges 4x per
 * halving with the knee at 0.001, 2x with it at 0.02 (a uniform axis in exp(-sigma_a / 2) stalls at
 * 0.017 of the residual's peak). */
#define SIGMA_KNEE 0.001

static double axis_length(void) { return log1p(HB_COLOUR_TABLE_SIGMA_MAX / SIGMA_KNEE); }

static double sigma_at(double w) { return SIGMA_KNEE * expm1(w * axis_length()); }

/* One grid of the build: N at cd[j] x phi[k] x x[l], out[((j n_phi + k) n_x + l) slots + s]. */
typedef struct colour_grid {
    const hb_plan *plan;
    const double *cd, *x; /* x: the absorption axis' coordinates w */
    const float *phi;
    int n_phi, n_x, part;
    float *out, *scratch; /* scratch: n_phi x slots x 3 floats per task of a part */
} colour_grid;

static void build_colour_row(void *grid, int j)
{
    const colour_grid *g = grid;
    hb_deon d = hb_deon_of(g->plan)->kernel; /* three absorptions at a time, as its channels */
    d.channels = 3;
    const int slots = d.groups;
    float *row = g->scratch + (size_t)(j % g->part) * (size_t)g->n_phi * (size_t)slots * 3;
    for (int l0 = 0; l0 < g->n_x; l0 += 3) {
        for (int c = 0; c < 3; c++) {
            int l = l0 + c < g->n_x ? l0 + c : g->n_x - 1;
            d.sigma_a_log2e[c] = hb_absorption_float(sigma_at(g->x[l]) * M_LOG2E);
        }
        ((const hb_deon_kernels *)g->plan->kernels)->np_row(&d, (float)g->cd[j], (size_t)g->n_phi, g->phi, row);
        for (int k = 0; k < g->n_phi; k++)
            for (int c = 0; c < 3 && l0 + c < g->n_x; c++)
                for (int s = 0; s < slots; s++)
                    g->out[(((size_t)j * (size_t)g->n_phi + (size_t)k) * (size_t)g->n_x + (size_t)(l0 + c)) * (size_t)slots +
                           (size_t)s] = row[((size_t)k * (size_t)slots + (size_t)s) * 3 + (size_t)c];
    }
}

static void layout(const hb_plan *plan, int n_cd, int n_phi, int n_x, hb_table_view *v)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    *v = (hb_table_view){ .model = HB_MODEL_DEON, .axes = 3, .size = { n_cd, n_phi, n_x },
                          .lo = { 0.0, 0.0, 0.0 }, .hi = { 1.0, M_PI, 1.0 },
                          .axis = { "sqrt(cos(theta_d)), theta_d = (theta_o - theta_i) / 2", "|phi_o - phi_i| wrapped to [0, pi]",
                                    "log(1 + sigma_a / 0.02) / log(1 + 16 / 0.02), sigma_a of the channel" },
                          .slots = d->groups };
    hb_deon_slot_lobes(d, v);
    v->count = hb_table_count(v, 1);
}

static void install(hb_plan *plan, float *values, int n_cd, int n_phi, int n_x, double error)
{
    hb_deon *d = &hb_deon_mut(plan)->kernel;
    hb_deon_mut(plan)->table = values;
    d->np_table = values;
    d->table_cd = n_cd, d->table_phi = n_phi, d->table_absorption = n_x;
    d->table_sigma_scale = (float)(M_LN2 / SIGMA_KNEE);
    d->table_w_scale = (float)((n_x - 1) / axis_length());
    hb_deon_mut(plan)->table_error = error;
}

static hb_status load_colour_table(hb_plan *plan, double tol, hb_error *error)
{
    hb_table_file file;
    hb_status st = hb_table_file_read(plan, &file, error);
    if (st != HB_OK)
        return st;
    int n_cd = file.layout.size[0], n_phi = file.layout.size[1], n_x = file.layout.size[2];
    if (file.layout.axes != 3 || n_cd < 2 || n_cd > HB_DEON_TABLE_MAX_CD || n_phi < 2 ||
        n_phi > HB_DEON_TABLE_MAX_PHI || n_x < 2 || n_x > MAX_X || !(file.layout.error <= tol))
        return hb_plan_fail(error, HB_ERR_FILE,
                            "table file: %d axes of %d x %d x %d nodes with midpoint error %.3g, where this plan's colour "
                            "table has 3 of at most %d x %d x %d and error at most %g", file.layout.axes, n_cd, n_phi, n_x,
                            file.layout.error, HB_DEON_TABLE_MAX_CD, HB_DEON_TABLE_MAX_PHI, MAX_X, tol);
    hb_table_view expected;
    layout(plan, n_cd, n_phi, n_x, &expected);
    float *values = calloc(expected.count + HB_TABLE_READ_PAD, sizeof *values);
    if (!values)
        return hb_plan_fail(error, HB_ERR_NOMEM, "could not allocate the deon colour table");
    st = hb_table_file_values(&file, &expected, 1, values, error);
    if (st != HB_OK) {
        free(values);
        return st;
    }
    install(plan, values, n_cd, n_phi, n_x, file.layout.error);
    return HB_OK;
}

/* One build attempt's nodes and midpoints, and the grids of N there. */
typedef struct attempt {
    int n_cd, n_phi, n_x, slots;
    double *cd, *x, *angle; /* nodes, then midpoints */
    float *phi;            /* nodes, then midpoints */
    float *values, *mid[3]; /* mid[0]: cd midpoints, [1]: phi, [2]: x */
    float *scratch;
} attempt;

static void attempt_free(attempt *a)
{
    free(a->cd), free(a->x), free(a->angle), free(a->phi), free(a->values), free(a->mid[0]), free(a->mid[1]), free(a->mid[2]);
    free(a->scratch);
}

static int attempt_alloc(attempt *a, int part)
{
    size_t nodes = (size_t)a->n_cd * (size_t)a->n_phi * (size_t)a->n_x * (size_t)a->slots;
    a->cd = malloc(2 * (size_t)a->n_cd * sizeof *a->cd);
    a->x = malloc(2 * (size_t)a->n_x * sizeof *a->x);
    a->phi = malloc(2 * (size_t)a->n_phi * sizeof *a->phi);
    a->angle = malloc(2 * (size_t)a->n_phi * sizeof *a->angle);
    a->values = calloc(nodes + HB_TABLE_READ_PAD, sizeof *a->values);
    for (int k = 0; k < 3; k++)
        a->mid[k] = malloc(nodes * sizeof *a->mid[k]);
    a->scratch = malloc((size_t)part * (size_t)a->n_phi * (size_t)a->slots * 3 * sizeof *a->scratch);
    return a->cd && a->x && a->angle && a->phi && a->values && a->mid[0] && a->mid[1] && a->mid[2] && a->scratch;
}

/* The grid at cd[0..n_cd) x phi[0..n_phi) x x[0..n_x) into out, as tasks reporting from..to. */
static hb_status build_grid(const hb_plan *plan, attempt *a, const double *cd, int n_cd, const float *phi, int n_phi,
                            const double *x, int n_x, float *out, int part, double from, double to, hb_error *error)
{
    colour_grid g = { plan, cd, x, phi, n_phi, n_x, part, out, a->scratch };
    return hb_build_tasks(&plan->options, n_cd, part, build_colour_row, &g, from, to, error);
}

hb_status hb_deon_build_colour_table(hb_plan *plan, hb_error *error)
{
    hb_deon *d = &hb_deon_mut(plan)->kernel;
    double tol = hb_deon_table_tolerance(plan);
    if (plan->options.table_file)
        return load_colour_table(plan, tol, error);
    attempt a = { .n_cd = 9, .n_phi = 33, .n_x = 9, .slots = d->groups };
    double done = 0.0;
    for (;;) {
        double work = 4.0 * a.n_cd * a.n_phi * a.n_x / 3.0 * d->nodes;
        if (work > 4.0 * HB_DEON_TABLE_MAX_WORK)
            return hb_plan_fail(error, HB_ERR_LIMIT,
                                "table_tolerance %g needs a finer colour table than %.3g node evaluations allow (this "
                                "beta_n and quality): loosen it or use the quadrature", tol, work);
        int part = hb_build_part(a.n_cd);
        if (!attempt_alloc(&a, part)) {
            attempt_free(&a);
            return hb_plan_fail(error, HB_ERR_NOMEM, "could not allocate the deon colour table (%d x %d x %d nodes)",
                                a.n_cd, a.n_phi, a.n_x);
        }
        /* sqrt(cos(theta_d)) and |phi| as the material's table has them; w uniform in [0, 1] */
        hb_deon_axis_nodes(a.n_cd, 0.0, 1.0, 0, a.cd);
        hb_deon_axis_nodes(a.n_cd, 0.0, 1.0, 1, a.cd + a.n_cd);
        for (int k = 0; k < 2 * a.n_cd - 1; k++)
            a.cd[k] *= a.cd[k];
        hb_deon_axis_nodes(a.n_phi, 0.0, M_PI, 0, a.angle);
        hb_deon_axis_nodes(a.n_phi, 0.0, M_PI, 1, a.angle + a.n_phi);
        for (int k = 0; k < 2 * a.n_phi - 1; k++)
            a.phi[k] = (float)a.angle[k];
        hb_deon_axis_nodes(a.n_x, 0.0, 1.0, 0, a.x);
        hb_deon_axis_nodes(a.n_x, 0.0, 1.0, 1, a.x + a.n_x);
        double span = (1.0 - done) / 2.0, step = span / 4.0; /* each attempt at least doubles the work */
        hb_status st = build_grid(plan, &a, a.cd, a.n_cd, a.phi, a.n_phi, a.x, a.n_x, a.values, part, done, done + step, error);
        if (st == HB_OK)
            st = build_grid(plan, &a, a.cd + a.n_cd, a.n_cd - 1, a.phi, a.n_phi, a.x, a.n_x, a.mid[0], part, done + step,
                            done + 2 * step, error);
        if (st == HB_OK)
            st = build_grid(plan, &a, a.cd, a.n_cd, a.phi + a.n_phi, a.n_phi - 1, a.x, a.n_x, a.mid[1], part,
                            done + 2 * step, done + 3 * step, error);
        if (st == HB_OK)
            st = build_grid(plan, &a, a.cd, a.n_cd, a.phi, a.n_phi, a.x + a.n_x, a.n_x - 1, a.mid[2], part, done + 3 * step,
                            done + span, error);
        done += span;
        if (st != HB_OK) {
            attempt_free(&a);
            return st;
        }
        const int slots = a.slots;
        double peak[HB_MAX_LOBES + 1] = { 0.0 };
        size_t nodes = (size_t)a.n_cd * (size_t)a.n_phi * (size_t)a.n_x;
        for (size_t k = 0; k < nodes; k++)
            for (int s = 0; s < slots; s++)
                peak[s] = fmax(peak[s], a.values[k * (size_t)slots + (size_t)s]);
        size_t x_line = (size_t)a.n_x * (size_t)slots, row = (size_t)a.n_phi * x_line;
        double error_cd = hb_deon_midpoint_error(a.values, a.mid[0], a.n_cd - 1, a.n_phi, row, row, row, (int)x_line, peak,
                                                 slots);
        double error_phi = hb_deon_midpoint_error(a.values, a.mid[1], a.n_cd, a.n_phi - 1, row, x_line,
                                                  (size_t)(a.n_phi - 1) * x_line, (int)x_line, peak, slots);
        double error_x = hb_deon_midpoint_error(a.values, a.mid[2], a.n_cd * a.n_phi, a.n_x - 1, x_line, (size_t)slots,
                                                (size_t)(a.n_x - 1) * (size_t)slots, slots, peak, slots);
        double total = error_cd + error_phi + error_x; /* trilinear error at a cell's centre: about the sum */

        if (total <= tol) {
            float *values = a.values;
            a.values = NULL;
            attempt_free(&a);
            install(plan, values, a.n_cd, a.n_phi, a.n_x, total);
            return hb_build_finish(&plan->options, error);
        }
        attempt_free(&a);
        a.cd = a.x = a.angle = NULL, a.phi = a.values = a.mid[0] = a.mid[1] = a.mid[2] = a.scratch = NULL;
        int *axis = error_cd >= error_phi && error_cd >= error_x ? &a.n_cd : error_phi >= error_x ? &a.n_phi : &a.n_x;
        int most = axis == &a.n_cd ? HB_DEON_TABLE_MAX_CD : axis == &a.n_phi ? HB_DEON_TABLE_MAX_PHI : MAX_X;
        if (*axis >= most)
            return hb_plan_fail(error, HB_ERR_LIMIT,
                                "table_tolerance %g is not reached by the largest colour table (midpoint error %.2g): "
                                "loosen it or use the quadrature", tol, total);
        *axis = 2 * *axis - 1;
    }
}

hb_status hb_deon_colour_table_view(const hb_plan *plan, hb_table_view *v, int *channels)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    *channels = 1;
    layout(plan, d->table_cd, d->table_phi, d->table_absorption, v);
    v->values = hb_deon_of(plan)->table;
    v->error = hb_deon_of(plan)->table_error;
    return HB_OK;
}

/* dFH11 N_p table (HB_AZIMUTHAL_TABLE): its resolution refined from the tolerance, rows built by
 * the plan's kernel (src/models/deon/azimuthal.h), or loaded from a table file; and its view for
 * hb_plan_table, which engines bake. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "models/build/build_tasks.h"
#include "models/file/table_file.h"
#include "table.h"
#include "state.h"

#define MAX_PHI HB_DEON_TABLE_MAX_PHI
#define MAX_CD HB_DEON_TABLE_MAX_CD
#define MAX_WORK HB_DEON_TABLE_MAX_WORK

double hb_deon_table_tolerance(const hb_plan *plan)
{
    return plan->options.table_tolerance > 0.0 ? plan->options.table_tolerance : hb_quality_target(plan->options.quality);
}

void hb_deon_slot_lobes(const hb_deon *d, hb_table_view *v)
{
    for (int s = 0; s < d->groups; s++)
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            if (hb_deon_lobe_on(d, p) && d->m_group[p] == d->group_leader[s])
                v->slot_lobes[s] |= 1u << p;
}

/* The rows of one grid: N at cos(theta_d) = cd[j] for the azimuths phi[0..n_phi), row j at out + j * row. */
typedef struct row_grid {
    const hb_plan *plan;
    const double *cd;
    int n_phi;
    const float *phi;
    float *out;
} row_grid;

static void build_row(void *grid, int j)
{
    const row_grid *g = grid;
    size_t row = (size_t)g->n_phi * (size_t)hb_deon_of(g->plan)->kernel.groups * 3;
    ((const hb_deon_kernels *)g->plan->kernels)->np_row(&hb_deon_of(g->plan)->kernel, (float)g->cd[j], (size_t)g->n_phi, g->phi,
                                                        g->out + (size_t)j * row);
}

/* n_cd rows as tasks (build_tasks.h), reporting progress from `from` to `to`. */
static hb_status build_rows(const hb_plan *plan, int n_cd, const double *cd, int n_phi, const float *phi, float *out,
                            double from, double to, hb_error *error)
{
    row_grid grid = { plan, cd, n_phi, phi, out };
    return hb_build_tasks(&plan->options, n_cd, hb_build_part(n_cd), build_row, &grid, from, to, error);
}

void hb_deon_axis_nodes(int n, double lo, double hi, int half, double *nodes)
{
    for (int k = 0; k < n - half; k++)
        nodes[k] = lo + (hi - lo) * (k + 0.5 * half) / (n - 1);
}

double hb_deon_midpoint_error(const float *values, const float *mid, int lines, int mids, size_t line_stride,
                              size_t step, size_t mid_line_stride, int texel, const double *peak, int peaks)
{
    double worst = 0.0;
    for (int a = 0; a < lines; a++)
        for (int b = 0; b < mids; b++)
            for (int v = 0; v < texel; v++) {
                const float *node = values + (size_t)a * line_stride + (size_t)b * (size_t)texel + (size_t)v;
                double interpolated = 0.5 * ((double)node[0] + (double)node[step]);
                double direct = mid[(size_t)a * mid_line_stride + (size_t)b * (size_t)texel + (size_t)v];
                double e = fabs(interpolated - direct) / fmax(peak[v % peaks], 1e-30);
                worst = fmax(worst, e);
            }
    return worst;
}

/* The table's layout for a resolution (the view without values and error). */
static void layout(const hb_plan *plan, int n_cd, int n_phi, hb_table_view *v)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    *v = (hb_table_view){ .model = HB_MODEL_DEON, .axes = 2, .size = { n_cd, n_phi },
                          .lo = { 0.0, 0.0 }, .hi = { 1.0, M_PI },
                          .axis = { "sqrt(cos(theta_d)), theta_d = (theta_o - theta_i) / 2", "|phi_o - phi_i| wrapped to [0, pi]" },
                          .slots = d->groups };
    hb_deon_slot_lobes(d, v);
    v->count = hb_table_count(v, 3);
}

static void install(hb_plan *plan, float *values, int n_cd, int n_phi, double error)
{
    hb_deon_mut(plan)->table = values;
    hb_deon_mut(plan)->kernel.np_table = values;
    hb_deon_mut(plan)->kernel.table_cd = n_cd, hb_deon_mut(plan)->kernel.table_phi = n_phi;
    hb_deon_mut(plan)->table_error = error;
}

/* The table of options.table_file, whose resolution it gives and whose measured error must meet tol. */
static hb_status load_table(hb_plan *plan, double tol, hb_error *error)
{
    hb_table_file file;
    hb_status st = hb_table_file_read(plan, &file, error);
    if (st != HB_OK)
        return st;
    int n_cd = file.layout.size[0], n_phi = file.layout.size[1];
    if (n_cd < 2 || n_cd > MAX_CD || n_phi < 2 || n_phi > MAX_PHI || !(file.layout.error <= tol))
        return hb_plan_fail(error, HB_ERR_FILE,
                            "table file: %d x %d nodes with midpoint error %.3g, where this plan's table has at most "
                            "%d x %d and error at most %g", n_cd, n_phi, file.layout.error, MAX_CD, MAX_PHI, tol);
    hb_table_view expected;
    layout(plan, n_cd, n_phi, &expected);
    float *values = calloc(expected.count + HB_TABLE_READ_PAD, sizeof *values);
    if (!values)
        return hb_plan_fail(error, HB_ERR_NOMEM, "could not allocate the deon N_p table (%d x %d nodes)", n_cd, n_phi);
    st = hb_table_file_values(&file, &expected, 3, values, error);
    if (st != HB_OK) {
        free(values);
        return st;
    }
    install(plan, values, n_cd, n_phi, file.layout.error);
    return HB_OK;
}

hb_status hb_deon_build_table(hb_plan *plan, hb_error *error)
{
    hb_deon *d = &hb_deon_mut(plan)->kernel;
    double tol = hb_deon_table_tolerance(plan);
    if (plan->options.table_file)
        return load_table(plan, tol, error);
    int texel = 3 * d->groups, n_phi = 33, n_cd = 9;
    double done = 0.0; /* the progress reported */
    for (;;) {
        double work = 3.0 * n_phi * n_cd * d->nodes;
        if (work > MAX_WORK)
            return hb_plan_fail(error, HB_ERR_LIMIT,
                              "table_tolerance %g needs a finer N_p table than %.3g node evaluations allow (this "
                              "beta_n and quality): loosen it or use the quadrature", tol, work);
        size_t nodes = (size_t)n_phi * (size_t)n_cd;
        /* 4 floats of padding: the kernels read a row's two corners 4 floats at a time (azimuthal.h) */
        float *values = calloc(nodes * (size_t)texel + HB_TABLE_READ_PAD, sizeof *values);
        float *mid_phi = malloc((size_t)n_cd * (size_t)n_phi * (size_t)texel * sizeof *mid_phi);
        float *mid_cd = malloc((size_t)n_cd * (size_t)n_phi * (size_t)texel * sizeof *mid_cd);
        float *phi = malloc(2 * (size_t)n_phi * sizeof *phi);
        double *cd = malloc(2 * (size_t)n_cd * sizeof *cd), *angle = malloc((size_t)n_phi * sizeof *angle);
        double *peak = calloc((size_t)texel, sizeof *peak);
        if (!values || !mid_phi || !mid_cd || !phi || !cd || !angle || !peak) {
            free(values), free(mid_phi), free(mid_cd), free(phi), free(cd), free(angle), free(peak);
            return hb_plan_fail(error, HB_ERR_NOMEM, "could not allocate the deon N_p table (%d x %d nodes)", n_cd,
                              n_phi);
        }
        hb_deon_axis_nodes(n_cd, 0.0, 1.0, 0, cd);
        hb_deon_axis_nodes(n_cd, 0.0, 1.0, 1, cd + n_cd);
        /* nodes uniform in sqrt(cos(theta_d)): near theta_d = pi/2 the Fresnel factors rise like
         * cos^2(theta_d) over a narrow range (measured: 4x less error per halving, against 2x in cos) */
        for (int k = 0; k < 2 * n_cd - 1; k++)
            cd[k] *= cd[k];
        hb_deon_axis_nodes(n_phi, 0.0, M_PI, 0, angle);
        for (int k = 0; k < n_phi; k++)
            phi[k] = (float)angle[k];
        hb_deon_axis_nodes(n_phi, 0.0, M_PI, 1, angle);
        for (int k = 0; k + 1 < n_phi; k++)
            phi[n_phi + k] = (float)angle[k];
        /* each attempt at least doubles the work: it takes half of what is left of the progress */
        double span = (1.0 - done) / 2.0;
        hb_status st = build_rows(plan, n_cd, cd, n_phi, phi, values, done, done + span / 3.0, error);
        if (st == HB_OK)
            st = build_rows(plan, n_cd, cd, n_phi - 1, phi + n_phi, mid_phi, done + span / 3.0, done + 2.0 * span / 3.0,
                            error);
        if (st == HB_OK)
            st = build_rows(plan, n_cd - 1, cd + n_cd, n_phi, phi, mid_cd, done + 2.0 * span / 3.0, done + span, error);
        done += span;
        if (st != HB_OK) {
            free(values), free(mid_phi), free(mid_cd), free(phi), free(cd), free(angle), free(peak);
            return st;
        }
        for (size_t k = 0; k < nodes; k++)
            for (int v = 0; v < texel; v++)
                peak[v] = fmax(peak[v], values[k * (size_t)texel + (size_t)v]);
        size_t row = (size_t)n_phi * (size_t)texel;
        double error_phi = hb_deon_midpoint_error(values, mid_phi, n_cd, n_phi - 1, row, (size_t)texel,
                                                  (size_t)(n_phi - 1) * (size_t)texel, texel, peak, texel);
        double error_cd = hb_deon_midpoint_error(values, mid_cd, n_cd - 1, n_phi, row, row, row, texel, peak, texel);
        free(mid_phi), free(mid_cd), free(phi), free(cd), free(angle), free(peak);
        /* bilinear error at a cell's centre is about the sum of the two axes' midpoint errors */
        if (error_phi + error_cd <= tol) {
            install(plan, values, n_cd, n_phi, error_phi + error_cd);
            return hb_build_finish(&plan->options, error); /* a refusal here frees the plan and its table */
        }
        free(values);
        int refine_phi = error_phi >= error_cd ? n_phi < MAX_PHI : n_cd >= MAX_CD;
        if (refine_phi ? n_phi >= MAX_PHI : n_cd >= MAX_CD)
            return hb_plan_fail(error, HB_ERR_LIMIT,
                              "table_tolerance %g is not reached by the largest N_p table (midpoint error %.2g): "
                              "loosen it or use the quadrature", tol, error_phi + error_cd);
        if (refine_phi)
            n_phi = 2 * n_phi - 1;
        else
            n_cd = 2 * n_cd - 1;
    }
}

hb_status hb_deon_table_view(const hb_plan *plan, hb_table_view *v, int *channels)
{
    if (!hb_deon_of(plan)->table)
        return HB_ERR_UNSUPPORTED;
    if (hb_deon_of(plan)->kernel.table_absorption)
        return hb_deon_colour_table_view(plan, v, channels);
    *channels = 3;
    layout(plan, hb_deon_of(plan)->kernel.table_cd, hb_deon_of(plan)->kernel.table_phi, v);
    v->values = hb_deon_of(plan)->table;
    v->error = hb_deon_of(plan)->table_error;
    return HB_OK;
}

/* shaders/hairbsdf_deon_body.inc reads the table's grid and each slot's M_p constants (eq. 7). */
hb_status hb_deon_shader_constants(const hb_plan *plan, float *k)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    if (!hb_deon_of(plan)->table)
        return HB_ERR_UNSUPPORTED;
    k[0] = (float)d->table_cd, k[1] = (float)d->table_phi, k[2] = (float)d->groups;
    if (d->table_absorption) { /* the colour table's axis, for sigma_a itself (the plan keeps sigma_a log2(e)) */
        k[3] = (float)d->table_absorption;
        k[40] = (float)(d->table_sigma_scale / M_LN2), k[41] = d->table_w_scale;
    }
    for (int s = 0; s < d->groups; s++) {
        const hb_longitudinal *l = &d->longitudinal[d->group_leader[s]];
        k[4 + 4 * s] = l->inv_v_f, k[5 + 4 * s] = l->inv_v_log2e_f, k[6 + 4 * s] = l->log2_norm_f;
        k[7 + 4 * s] = (float)l->shift;
    }
    return HB_OK;
}

/* HHH22 TT/TRT table (HB_TT_TRT_TABLE): its grid, chosen from quality and roughness, and its
 * rows, each built by the plan's kernel (src/models/huang/table.h) or loaded from a table file; and
 * its view for hb_plan_table. docs/huang.md has the measured error and build time per quality. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "huang.h"
#include "models/build/build_tasks.h"
#include "models/file/table_file.h"
#include "state.h"

/* Rank-1 lattices of internal paths per Simpson node: N points, N a Fibonacci number, whose first
 * two coordinates (the entry's visible normal, all TT needs) are the Fibonacci lattice and whose
 * last two (the bounce's) are the same lattice at point k l, k minimising the P2 discrepancy of the
 * four together. */
typedef struct path_lattice {
    int points, generator[4];
} path_lattice;

/* The grids, coarsest first: nodes in theta_i and in phi_i (elliptical), the delta step and the step
 * of u = asinh(s / roughness) (near s = 0 that is the step in s over the roughness), the quality
 * whose Simpson step over the entry azimuth the rows take, and the paths per Simpson node. A
 * quality's own grid (hb_huang_table_grid_of) is the coarsest whose error on the bench material
 * (GGX 0.2, where f is at least 1% of its peak) is within the quality's bound: 3% at balanced, 1% at
 * high (docs/huang.md). HB_TT_TRT_AUTO takes the finest grid up to the quality's own that builds in
 * about a second. The Simpson step is half the estimator's at fast (the paper's 0.7 roughness puts
 * a TT peak 3% off on a circle and on an ellipse of e = 0.8). */
typedef struct table_grid {
    int theta_i, phi_i;
    double delta_step, u_step;
    hb_quality simpson;
    path_lattice lattice;
} table_grid;

static const table_grid grids[] = {
    { 17, 5, 1.0, 0.5, HB_QUALITY_BALANCED, { 13, { 1, 8, 2, 3 } } },
    { 33, 9, 0.5, 0.25, HB_QUALITY_HIGH, { 21, { 1, 13, 16, 19 } } },
    { 49, 13, 0.35, 0.12, HB_QUALITY_HIGH, { 377, { 1, 233, 354, 296 } } },
    { 49, 13, 0.25, 0.09, HB_QUALITY_HIGH, { 1597, { 1, 987, 1173, 1523 } } },
};

int hb_huang_table_grid_of(hb_quality quality)
{
    return quality == HB_QUALITY_FAST ? 0 : quality == HB_QUALITY_BALANCED ? 2 : 3;
}

/* The most exit-to-node connections a build may make: a few minutes on one AVX2 core (the cost per
 * connection is `make bench --only huang-table`'s; threads divide it). A circular fibre needs 4.7e9
 * at roughness 0.2 and 2.2e10 at 0.1 on the balanced grid (refused below about 0.05), 3.7e10 at 0.2
 * on the high grid (refused below about 0.13). */
#define MAX_CONNECTIONS 1e11

static int nodes_for(double range, double step, int least, int most)
{
    int n = (int)ceil(range / step) + 1;
    return n < least ? least : n > most ? most : n;
}

static hb_status out_of_memory(hb_error *error, void *a, void *b, void *c)
{
    free(a);
    free(b);
    free(c);
    return hb_plan_fail(error, HB_ERR_NOMEM, "could not allocate the huang TT/TRT table");
}

/* Exit-to-node connections a build of the plan's grid makes with `paths` per node: its cost. */
static double connections_with(const hb_huang_table *t, int paths)
{
    double rows = (double)t->n_theta_i * t->n_phi_i, nodes = (double)t->n_sum * t->n_delta;
    return rows * 2.0 * paths * (t->panels + 1) * nodes;
}

/* The grid of hb_huang_of(plan)->kernel.table, from its grid's row and the roughness. */
static void choose_grid(hb_plan *plan)
{
    hb_huang *h = &hb_huang_mut(plan)->kernel;
    hb_huang_table *t = &h->table;
    const table_grid *g = &grids[h->table_grid];
    double r = plan->material.roughness;
    t->n_theta_i = g->theta_i;
    t->n_phi_i = h->elliptical ? g->phi_i : 1;
    double delta_range = h->elliptical ? 2.0 * M_PI : M_PI;
    t->n_delta = nodes_for(delta_range, g->delta_step * r, 9, 257);
    t->delta_lo = h->elliptical ? (float)-M_PI : 0.0f;
    t->delta_scale = (float)((t->n_delta - 1) / delta_range);
    t->sum_centre = 0.0f;
    t->inv_sum_width = (float)(1.0 / r);
    double u_lo = asinh(-M_PI / r), u_hi = asinh(M_PI / r);
    t->n_sum = nodes_for(u_hi - u_lo, g->u_step, 9, 513);
    t->u_lo = (float)u_lo;
    t->u_scale = (float)((t->n_sum - 1) / (u_hi - u_lo));
    t->panels = hb_huang_tt_panels(&plan->options, g->simpson, r);
    t->paths = g->lattice.points;
}

/* The table's layout from its grid (the view without values). */
static void layout(const hb_plan *plan, hb_table_view *v)
{
    *v = (hb_table_view){ .model = HB_MODEL_HUANG };
    const hb_huang_table *t = &hb_huang_of(plan)->kernel.table;
    int k = 0;
    v->size[k] = t->n_theta_i, v->lo[k] = -M_PI_2, v->hi[k] = M_PI_2, v->axis[k++] = "theta_i";
    if (t->n_phi_i > 1)
        v->size[k] = t->n_phi_i, v->lo[k] = 0.0, v->hi[k] = M_PI_2,
        v->axis[k++] = "phi_i folded into [0, pi/2] by the fibre's symmetries (delta's sign follows)";
    v->size[k] = t->n_sum, v->lo[k] = t->u_lo, v->hi[k] = t->u_lo + (t->n_sum - 1) / t->u_scale,
    v->axis[k++] = "asinh((theta_i + theta_o) / roughness)";
    v->size[k] = t->n_delta, v->lo[k] = t->delta_lo, v->hi[k] = t->delta_lo + (t->n_delta - 1) / t->delta_scale,
    v->axis[k++] = t->n_phi_i > 1 ? "phi_o - phi_i in [-pi, pi]" : "|phi_o - phi_i| in [0, pi]";
    v->axes = k;
    v->slots = 1;
    v->slot_lobes[0] = hb_huang_of(plan)->kernel.lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT);
    v->error = NAN;
    v->count = hb_table_count(v, 3);
}

/* The table of options.table_file, on the grid this plan would build. */
static hb_status load_table(hb_plan *plan, hb_error *error)
{
    hb_table_file file;
    hb_status st = hb_table_file_read(plan, &file, error);
    if (st != HB_OK)
        return st;
    hb_table_view expected;
    layout(plan, &expected);
    float *values = malloc(expected.count * sizeof *values);
    if (!values)
        return out_of_memory(error, NULL, NULL, NULL);
    st = hb_table_file_values(&file, &expected, 3, values, error);
    if (st != HB_OK) {
        free(values);
        return st;
    }
    hb_huang_mut(plan)->table = values;
    hb_huang_mut(plan)->kernel.table.values = values;
    return HB_OK;
}

/* The table's rows as tasks (build_tasks.h): row k is theta_i node k / n_phi_i and phi_i node k % n_phi_i;
 * a task uses the scratch of its slot in the part. */
typedef struct table_rows {
    const hb_plan *plan;
    hb_huang_table_build build; /* its scratch set per task */
    float *scratch;
    size_t scratch_floats;
    int part;
    float *values;
    size_t row;
} table_rows;

static void build_row(void *rows, int k)
{
    const table_rows *r = rows;
    const hb_huang_table *t = &hb_huang_of(r->plan)->kernel.table;
    int i = k / t->n_phi_i, m = k % t->n_phi_i;
    double theta_i = -M_PI_2 + M_PI * i / (t->n_theta_i - 1);
    double phi_i = t->n_phi_i > 1 ? M_PI_2 * m / (t->n_phi_i - 1) : 0.0;
    hb_huang_table_build build = r->build;
    build.scratch = r->scratch + (size_t)(k % r->part) * r->scratch_floats;
    build.row = k;
    ((const hb_huang_kernels *)r->plan->kernels)->table_row(&hb_huang_of(r->plan)->kernel, (float)theta_i, (float)phi_i, &build,
                                                             r->values + (size_t)k * r->row);
}

/* The plan's grid and the connections its build makes (what tt_trt auto and the refusal judge by). */
static double table_connections(hb_plan *plan)
{
    choose_grid(plan);
    return connections_with(&hb_huang_of(plan)->kernel.table, hb_huang_of(plan)->kernel.table.paths);
}

/* HB_TT_TRT_AUTO builds the table where it takes about a second on one core at most (on the second
 * grid circular fibres down to roughness 0.1; elliptical ones of e = 0.8 from about 0.3). */
#define AUTO_CONNECTIONS 5e8

int hb_huang_table_fits(hb_plan *plan) { return table_connections(plan) <= AUTO_CONNECTIONS; }

hb_status hb_huang_build_table(hb_plan *plan, hb_error *error)
{
    double connections = table_connections(plan);
    if (plan->options.table_file)
        return load_table(plan, error);
    hb_huang *h = &hb_huang_mut(plan)->kernel;
    hb_huang_table *t = &h->table;
    const path_lattice *lattice = &grids[h->table_grid].lattice;
    double r = plan->material.roughness;
    double delta_range = h->elliptical ? 2.0 * M_PI : M_PI;
    double u_lo = asinh(-M_PI / r), u_hi = asinh(M_PI / r);
    size_t row = (size_t)t->n_sum * (size_t)t->n_delta * 3;
    size_t rows = (size_t)t->n_theta_i * (size_t)t->n_phi_i;
    size_t exits = 2 * (size_t)lattice->points * (size_t)(t->panels + 1);
    if (connections > MAX_CONNECTIONS)
        return hb_plan_fail(error, HB_ERR_LIMIT,
                            "the TT/TRT table at roughness %g and this quality needs %.2g path connections (about %.0f s "
                            "to build; the limit is %.0g): use a coarser quality, tt_trt = mc, or fewer tt_panels", r,
                            connections, connections * 2.1e-9, MAX_CONNECTIONS);
    int count = (int)rows, part = hb_build_part(count);
    size_t scratch_floats = exits * HB_HUANG_EXIT_FLOATS;
    float *values = malloc(rows * row * sizeof *values);
    float *grid = malloc(((size_t)t->n_sum + (size_t)t->n_delta) * sizeof *grid);
    float *scratch = malloc((size_t)part * scratch_floats * sizeof *scratch); /* one per task of a part */
    if (!values || !grid || !scratch)
        return out_of_memory(error, values, grid, scratch);
    for (int k = 0; k < t->n_sum; k++)
        grid[k] = (float)(r * sinh(u_lo + k * (u_hi - u_lo) / (t->n_sum - 1)));
    for (int l = 0; l < t->n_delta; l++)
        grid[t->n_sum + l] = (float)(t->delta_lo + l * delta_range / (t->n_delta - 1));
    table_rows rows_run = { plan, { grid, grid + t->n_sum, lattice->points, { 0 }, 0, NULL }, scratch, scratch_floats, part, values, row };
    for (int k = 0; k < 4; k++)
        rows_run.build.generator[k] = lattice->generator[k];
    hb_status st = hb_build_tasks(&plan->options, count, part, build_row, &rows_run, 0.0, 1.0, error);
    free(grid);
    free(scratch);
    if (st != HB_OK) {
        free(values);
        return st;
    }
    hb_huang_mut(plan)->table = values;
    t->values = values;
    return HB_OK;
}

hb_status hb_huang_table_view(const hb_plan *plan, hb_table_view *v, int *channels)
{
    if (!hb_huang_of(plan)->table)
        return HB_ERR_UNSUPPORTED;
    *channels = 3;
    layout(plan, v);
    v->values = hb_huang_of(plan)->table;
    return HB_OK;
}

/* shaders/hairbsdf_huang_body.inc reads the R lobe's App. A constants, eta, the tilt and the TT/TRT
 * table's grid: circular fibres whose R lobe is analytic (or absent) and whose TT and TRT come from
 * the table (or are absent). */
hb_status hb_huang_shader_constants(const hb_plan *plan, float *k)
{
    const hb_huang *h = &hb_huang_of(plan)->kernel;
    int r = h->lobes >> HB_LOBE_R & 1u, internal = (h->lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT)) != 0;
    if (h->elliptical || (r && !h->analytic) || (internal && !h->table.values) || !plan->kernels)
        return HB_ERR_UNSUPPORTED;
    const hb_huang_table *t = &h->table;
    k[0] = (float)r, k[1] = (float)internal, k[2] = h->ior.eta, k[3] = h->ior.eta2_minus_1;
    k[4] = h->ior.inv_eta2, k[5] = h->c_rough, k[6] = h->one_minus_c, k[7] = h->roughness2 * 0.25f * (float)M_1_PI;
    k[8] = h->cos_tilt, k[9] = h->sin_tilt, k[10] = (float)h->tilted, k[11] = h->cos_floor;
    if (internal) {
        k[12] = (float)t->n_theta_i, k[13] = (float)t->n_sum, k[14] = (float)t->n_delta;
        k[16] = t->u_lo, k[17] = t->u_scale, k[18] = t->delta_lo, k[19] = t->delta_scale;
        k[20] = t->sum_centre, k[21] = t->inv_sum_width;
    }
    return HB_OK;
}

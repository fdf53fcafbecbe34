/* An assembly's fibres: random sequential addition without overlap, a grid of cells one diameter
 * wide, and the nearest fibre along a ray by walking the grid's cells in the ray's order. */
#include <math.h>
#include <stdlib.h>

#include "assembly/fibres.h"
#include "math/hash.h"
#include "models/interface/plan.h"

#define CELL 2.0          /* a cell's side: one fibre diameter */
#define TRIES 10000       /* random positions tried for one fibre before placement gives up */
#define MOST_CELLS (1 << 20) /* cells one ray may cross: a slab's ray nearly along its faces */

static double uniform01(unsigned long long key, unsigned long long index)
{
    return (double)(hb_mix64(key ^ hb_mix64(index)) >> 11) * 0x1p-53;
}

/* The cell of coordinate v on an axis of n cells from v0 (unclamped). */
static int cell_of(double v, double v0) { return (int)floor((v - v0) / CELL); }

/* The squared distance between two centres, across the slab's period along x. */
static double distance2(const hb_fibres *f, double ax, double az, double bx, double bz)
{
    double dx = fabs(ax - bx), dz = az - bz;
    if (f->shape == HB_ASSEMBLY_SLAB && dx > 0.5 * f->width)
        dx = f->width - dx;
    return dx * dx + dz * dz;
}

/* Whether a fibre at (x, z) overlaps one already placed, from the cells about it (the grid's lists
 * are built afterwards, so placement keeps its own lists: `cell_head` and `next`). */
static int overlaps(const hb_fibres *f, const int *cell_head, const long *next, double x, double z)
{
    int cx = cell_of(x, f->x0), cz = cell_of(z, f->z0);
    for (int j = cz - 1; j <= cz + 1; j++) {
        if (j < 0 || j >= f->nz)
            continue;
        for (int i = cx - 1; i <= cx + 1; i++) {
            int w = i;
            if (f->shape == HB_ASSEMBLY_SLAB)
                w = (i % f->nx + f->nx) % f->nx;
            else if (i < 0 || i >= f->nx)
                continue;
            for (long k = cell_head[j * f->nx + w]; k >= 0; k = next[k])
                if (distance2(f, x, z, f->centre[2 * k], f->centre[2 * k + 1]) < 4.0)
                    return 1;
        }
    }
    return 0;
}

/* Lists each fibre in every cell its circle reaches (the slab's across its period). */
static hb_status build_cells(hb_fibres *f)
{
    int cells = f->nx * f->nz;
    f->first = calloc((size_t)cells + 1, sizeof *f->first);
    f->entry = malloc((size_t)(f->count ? f->count : 1) * 9 * sizeof *f->entry);
    if (!f->first || !f->entry)
        return hb_fail(HB_ERR_NOMEM, "hb_assembly_trace: no memory for the cells of %ld fibres", f->count);
    for (int pass = 0; pass < 2; pass++) { /* count, then fill */
        int *fill = pass ? calloc((size_t)cells, sizeof *fill) : NULL;
        if (pass && !fill)
            return hb_fail(HB_ERR_NOMEM, "hb_assembly_trace: no memory for the cells of %ld fibres", f->count);
        for (long k = 0; k < f->count; k++) {
            double x = f->centre[2 * k], z = f->centre[2 * k + 1];
            for (int j = cell_of(z - 1.0, f->z0); j <= cell_of(z + 1.0, f->z0); j++)
                for (int i = cell_of(x - 1.0, f->x0); i <= cell_of(x + 1.0, f->x0); i++) {
                    if (j < 0 || j >= f->nz)
                        continue;
                    int w = i;
                    double shift = 0.0;
                    if (f->shape == HB_ASSEMBLY_SLAB) {
                        w = (i % f->nx + f->nx) % f->nx;
                        shift = (double)(w - i) * CELL; /* the copy of the fibre in cell w's period */
                    } else if (i < 0 || i >= f->nx) {
                        continue;
                    }
                    int c = j * f->nx + w;
                    if (!pass)
                        f->first[c + 1]++;
                    else
                        f->entry[f->first[c] + fill[c]++] = (hb_cell_fibre){ x + shift, z };
                }
        }
        if (!pass)
            for (int c = 0; c < cells; c++)
                f->first[c + 1] += f->first[c];
        free(fill);
    }
    return HB_OK;
}

hb_status hb_fibres_place(const hb_assembly *a, hb_fibres *f)
{
    *f = (hb_fibres){ .shape = a->shape };
    double area;
    if (a->shape == HB_ASSEMBLY_SLAB) {
        f->height = 2.0 * a->layers, f->width = 2.0 * a->period;
        f->nx = a->period, f->nz = (int)ceil(a->layers);
        area = f->height * f->width;
    } else {
        f->height = 2.0 * a->layers, f->width = 2.0 * f->height;
        f->nx = f->nz = (int)ceil(f->width / CELL);
        f->x0 = f->z0 = -f->height;
        area = M_PI * f->height * f->height;
    }
    long want = lround(a->packing * area / M_PI);
    int cells = f->nx * f->nz;
    f->centre = malloc((size_t)(want ? want : 1) * 2 * sizeof *f->centre);
    int *cell_head = malloc((size_t)cells * sizeof *cell_head);
    long *next = malloc((size_t)(want ? want : 1) * sizeof *next);
    hb_status st = HB_OK;
    if (!f->centre || !cell_head || !next)
        st = hb_fail(HB_ERR_NOMEM, "hb_assembly_trace: no memory for %ld fibres", want);
    for (int c = 0; st == HB_OK && c < cells; c++)
        cell_head[c] = -1;
    unsigned long long key = hb_mix64(a->seed ^ 0x6a09e667f3bcc909ull), draw = 0;
    while (st == HB_OK && f->count < want) {
        int placed = 0;
        for (int tries = 0; tries < TRIES && !placed; tries++) {
            double x, z;
            if (a->shape == HB_ASSEMBLY_SLAB) { /* centres at least a radius inside both faces */
                x = f->width * uniform01(key, draw++);
                z = 1.0 + (f->height - 2.0) * uniform01(key, draw++);
            } else { /* uniform over the disc of centres, radius height - 1 */
                double r = (f->height - 1.0) * sqrt(uniform01(key, draw++)), angle = 2.0 * M_PI * uniform01(key, draw++);
                x = r * sin(angle), z = r * cos(angle);
            }
            if (overlaps(f, cell_head, next, x, z))
                continue;
            long k = f->count++;
            f->centre[2 * k] = x, f->centre[2 * k + 1] = z;
            int c = cell_of(z, f->z0) * f->nx + cell_of(x, f->x0);
            next[k] = cell_head[c], cell_head[c] = (int)k;
            placed = 1;
        }
        if (!placed)
            st = hb_fail(HB_ERR_LIMIT,
                         "hb_assembly_trace: random placement reached packing %.3f (%ld fibres) of the %.3f asked; "
                         "random sequential addition of discs jams near 0.55, less in a thin slab",
                         (double)f->count * M_PI / area, f->count, a->packing);
    }
    free(cell_head);
    free(next);
    if (st == HB_OK)
        st = build_cells(f);
    if (st != HB_OK)
        hb_fibres_free(f);
    return st;
}

void hb_fibres_free(hb_fibres *f)
{
    free(f->centre);
    free(f->first);
    free(f->entry);
    f->centre = NULL, f->first = NULL, f->entry = NULL;
}

double hb_fibres_exit(const hb_fibres *f, const hb_ray2 *r)
{
    if (f->shape == HB_ASSEMBLY_SLAB)
        return r->uz > 0.0 ? (f->height - r->z) / r->uz : r->uz < 0.0 ? -r->z / r->uz : INFINITY;
    double b = r->x * r->ux + r->z * r->uz, c = r->x * r->x + r->z * r->z - f->height * f->height;
    return -b + sqrt(fmax(b * b - c, 0.0)); /* the far root of |origin + t u| = radius */
}

int hb_fibres_hit(const hb_fibres *f, const hb_ray2 *r, double skip_x, double skip_z, double *t, double *cx, double *cz)
{
    double t_exit = hb_fibres_exit(f, r), best = t_exit;
    /* The grid walk (Amanatides and Woo 1987): the cell of the origin, then each next cell across
     * the nearer of its x and z boundaries. */
    int i = cell_of(r->x, f->x0), j = cell_of(r->z, f->z0);
    if (j >= f->nz && r->uz < 0.0)
        j = f->nz - 1;
    if (j < 0 && r->uz > 0.0)
        j = 0;
    int step_i = r->ux > 0.0 ? 1 : -1, step_j = r->uz > 0.0 ? 1 : -1;
    double next_x = f->x0 + CELL * (i + (step_i > 0)), next_z = f->z0 + CELL * (j + (step_j > 0));
    double t_x = r->ux != 0.0 ? (next_x - r->x) / r->ux : INFINITY, t_z = r->uz != 0.0 ? (next_z - r->z) / r->uz : INFINITY;
    double dt_x = r->ux != 0.0 ? CELL / fabs(r->ux) : INFINITY, dt_z = r->uz != 0.0 ? CELL / fabs(r->uz) : INFINITY;
    double t_cell = 0.0; /* where the walk entered the cell */
    int found = 0;
    for (int cells = 0; t_cell < best; cells++) {
        if (cells == MOST_CELLS)
            return -1;
        if (j < 0 || j >= f->nz)
            break;
        int w = i;
        double shift = 0.0;
        if (f->shape == HB_ASSEMBLY_SLAB) {
            w = (i % f->nx + f->nx) % f->nx;
            shift = (double)(i - w) * CELL;
        } else if (i < 0 || i >= f->nx) {
            break;
        }
        int c = j * f->nx + w;
        for (int k = f->first[c]; k < f->first[c + 1]; k++) {
            double x = f->entry[k].x + shift, z = f->entry[k].z;
            double ox = r->x - x, oz = r->z - z, b = ox * r->ux + oz * r->uz, q = ox * ox + oz * oz - 1.0;
            double disc = b * b - q;
            if (disc < 0.0 || b > 0.0) /* missed, or the circle lies behind the origin */
                continue;
            double s = -b - sqrt(disc);
            if (s < 0.0 || s >= best)
                continue;
            if (fabs(x - skip_x) < 1e-6 && fabs(z - skip_z) < 1e-6)
                continue;
            best = s, *cx = x, *cz = z, found = 1;
        }
        if (t_x < t_z)
            t_cell = t_x, t_x += dt_x, i += step_i;
        else
            t_cell = t_z, t_z += dt_z, j += step_j;
    }
    *t = best;
    return found;
}

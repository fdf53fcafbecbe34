/* The fibres of an assembly in their cross-section (the frame's x-z plane; the fibres run along y):
 * random placement without overlap, a uniform grid of cells one fibre diameter wide, and the nearest
 * fibre a ray meets. In double precision. Internal. */
#ifndef HB_ASSEMBLY_FIBRES_H
#define HB_ASSEMBLY_FIBRES_H

#include "hairbsdf.h"

/* A fibre as one cell lists it: its centre in the frame of the cell's period (a slab's fibre near
 * x = 0 or x = width is listed a second time, shifted by the period, in the cells across the edge). */
typedef struct hb_cell_fibre {
    double x, z;
} hb_cell_fibre;

typedef struct hb_fibres {
    hb_assembly_shape shape;
    double height;   /* slab: its thickness, 2 layers; bundle: its radius */
    double width;    /* slab: the period along x; bundle: the grid's side, 2 radius */
    double x0, z0;   /* the grid's corner */
    int nx, nz;      /* cells of side 2 */
    long count;      /* fibres placed */
    double *centre;  /* 2 count: x, z */
    int *first;      /* nx nz + 1: cell c lists entries first[c] .. first[c + 1] - 1 */
    hb_cell_fibre *entry;
} hb_fibres;

/* Places round(packing area / pi) fibres of radius 1 without overlap by random sequential addition
 * from seed; HB_ERR_LIMIT when a fibre finds no place in 10^4 tries per fibre placed (the message
 * gives the packing reached), HB_ERR_NOMEM when memory runs out. */
hb_status hb_fibres_place(const hb_assembly *a, hb_fibres *f);
void hb_fibres_free(hb_fibres *f);

/* A ray from (x, z) along the unit (ux, uz) in the cross-section. */
typedef struct hb_ray2 {
    double x, z, ux, uz;
} hb_ray2;

/* The nearest fibre the ray meets before leaving the assembly, ignoring the fibre centred within
 * 1e-6 of (skip_x, skip_z) (the one it leaves; NaN for none): 1 with the distance along the ray and
 * the centre met (in the ray's own unwrapped x), 0 when it leaves first, -1 when it crosses 2^20
 * cells before either (a ray in a slab nearly along its faces). */
int hb_fibres_hit(const hb_fibres *f, const hb_ray2 *ray, double skip_x, double skip_z, double *t, double *cx,
                  double *cz);

/* HB_ERR_PARAM naming the first field of the assembly outside its range, HB_ERR_VERSION for its
 * struct_size (src/assembly/trace.c). */
hb_status hb_assembly_check(const char *call, const hb_assembly *a);

/* Where a ray from inside leaves the assembly (the slab's faces, the bundle's circle), along it. */
double hb_fibres_exit(const hb_fibres *f, const hb_ray2 *ray);

/* hb_assembly_trace that also tallies hb_assembly_render's traced picture (image NULL: none;
 * src/assembly/trace.c), and the dual-scattering picture (src/assembly/dual_view.c). */
hb_status hb_assembly_trace_image(const hb_plan *plan, const hb_assembly *a, hb_assembly_result *result,
                                  const hb_assembly_image *image, hb_progress_fn progress, void *progress_context,
                                  hb_parallel_fn parallel, void *parallel_context);
hb_status hb_assembly_dual_image(const hb_plan *plan, const hb_dual_table *table, const hb_assembly *a,
                                 const hb_assembly_image *image);

#endif

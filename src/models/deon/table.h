/* What dFH11's two N_p tables share (table_build.c): a material's own over (sqrt(cos(theta_d)), |phi|)
 * and the colour table with the absorption as a third axis (colour_table.c): their slots, tolerance,
 * limits, node coordinates and midpoint error. Internal. */
#ifndef HB_DEON_TABLE_H
#define HB_DEON_TABLE_H

#include "deon.h"

/* The largest table: 4097 azimuths x 513 values of cos(theta_d) (a beta_n near 0.01 at 1e-4), and the
 * most quadrature-node evaluations one build attempt may make (its grids of nodes x quadrature nodes):
 * a fraction of a second on one core. */
#define HB_DEON_TABLE_MAX_PHI 4097
#define HB_DEON_TABLE_MAX_CD 513
#define HB_DEON_TABLE_MAX_WORK 1e8
/* 4 floats of padding: the kernels read a row's corners 4 floats at a time (azimuthal.h) */
#define HB_TABLE_READ_PAD 4

/* options.table_tolerance, or the quality's (1e-2, 1e-3, 1e-4). */
double hb_deon_table_tolerance(const hb_plan *plan);

/* Uniform node coordinates in [lo, hi]; with `half`, the n - 1 midpoints. */
void hb_deon_axis_nodes(int n, double lo, double hi, int half, double *nodes);

/* The largest |interpolated - direct| / peak over the midpoints of one axis: mid[a][b] holds `texel`
 * direct values at `lines` x `mids` midpoints (line a of `values`, `line_stride` floats long, node b);
 * the interpolant there is the mean of node (a, b) and the node `step` floats after it. Value v of a
 * texel is measured against peak[v % peaks]. */
double hb_deon_midpoint_error(const float *values, const float *mid, int lines, int mids, size_t line_stride,
                              size_t step, size_t mid_line_stride, int texel, const double *peak, int peaks);

/* The slot lobes of a table view, from the plan's groups. */
void hb_deon_slot_lobes(const hb_deon *d, hb_table_view *v);

#endif

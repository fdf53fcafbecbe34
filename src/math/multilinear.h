/* Multilinear interpolation in tables of texels (dFH11 N_p, HHH22 TT + TRT): the cell a sample
 * falls in and its corners' weights and offsets, which the models then gather per value. */
#ifndef HB_MULTILINEAR_H
#define HB_MULTILINEAR_H

#include "vmath.h"

/* Node coordinate x of a table axis with n >= 2 nodes, clamped to the table: the lower node's
 * index and the fraction toward the next. */
HB_INLINE vi table_cell(vf x, int n, vf *fraction)
{
    x = vf_clamp(x, 0.0f, (float)(n - 1));
    vf lower = vf_min(vf_from_vi(vi_from_vf(x)), vf_set1((float)(n - 2)));
    *fraction = vf_sub(x, lower);
    return vi_from_vf(lower);
}

/* The 2^axes corners of the cells whose lower nodes are cell[a] on axes of stride[a] floats: the
 * index of the lower corner (returned), and per corner k (the upper node on axis a where bit a of
 * k is set) its offset in floats and its weight, the product over the axes of frac or 1 - frac.
 * With a constant `axes` the loops unroll and 2^(axes+1) - 2 products make every weight. */
HB_INLINE vi cell_corners(int axes, const vi cell[], const vf frac[], const int stride[], vf weight[],
                          int offset[])
{
    vi base = vi_mul(cell[0], vi_set1(stride[0]));
    weight[0] = vf_sub(vf_set1(1.0f), frac[0]);
    weight[1] = frac[0];
    offset[0] = 0;
    offset[1] = stride[0];
    HB_UNROLL
    for (int a = 1; a < axes; a++) {
        base = vi_add(base, vi_mul(cell[a], vi_set1(stride[a])));
        int half = 1 << a;
        HB_UNROLL
        for (int k = 0; k < half; k++) {
            weight[k + half] = vf_mul(weight[k], frac[a]);
            weight[k] = vf_fnma(weight[k], frac[a], weight[k]); /* w (1 - f), rounded once */
            offset[k + half] = offset[k] + stride[a];
        }
    }
    return base;
}

#endif

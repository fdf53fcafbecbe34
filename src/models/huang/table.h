/* HHH22 TT and TRT from a table built at plan creation (HHH22 sec. 3.4.2 suggests "precomputing
 * them and storing the result in a 3D table (4D for elliptical cross-sections)"; docs/huang.md).
 * The builder integrates eqs. 31, 32 deterministically: Simpson over the entry azimuth phi_m1 on
 * the table's panels, and at each node `lattice` internal paths whose visible normals are the
 * points of a rank-1 lattice (randomly shifted per node and row) instead of one random path; every
 * path is traced once per row and connected to every w_o of the row. The nodes hold square roots
 * of f over the tilted windows' closing factor; lookup interpolates them multilinearly, squares the
 * result and multiplies the factor back. */
#ifndef HB_HUANG_TABLE_H
#define HB_HUANG_TABLE_H

#include <float.h>

#include "internal.h"
#include "math/multilinear.h"

/* asinh(x) = sign(x) log(|x| + sqrt(x^2 + 1)): the warp of s (monotone and continuous, which is
 * all the grid needs; its absolute error is a few float ulps of the index). */
HB_INLINE vf table_asinh(vf x)
{
    vf a = vf_abs(x);
    return vf_copysign(vf_log(vf_add(a, vf_sqrt(vf_fma(a, a, vf_set1(1.0f))))), x);
}

/* Where the nodes are evaluated: theta in [lo, hi], HB_TABLE_NODE_GAP (0.01 rad) inside the poles
 * and the windows' closures tau +- pi/2. At a pole the macronormal sees nothing and past a closure
 * the window is empty, so f is 0 exactly there, while the node stands for the limit beside it. */
#define HB_TABLE_NODE_GAP 0.01f

/* One direction's c / cos(theta) of the closing factor, with cos(theta) floored at the node gap
 * where c exceeds it (a tilted fibre's pole, where c stays near |sin tau|) and at c itself below it
 * (an untilted pole, where c = cos(theta) and the ratio is 1 down to the pole itself). */
HB_INLINE vf closing_ratio(vf c, vf cos_theta)
{
    vf floor = vf_max(vf_min(c, vf_set1(HB_TABLE_NODE_GAP)), vf_set1(FLT_MIN));
    return vf_div(c, vf_max(cos_theta, floor));
}

/* The closing factor C(theta_i) C(theta_o), C = c sqrt(c / cos(theta)) with c = cos(theta - tau)
 * floored at 0, tau the mesonormal's tilt (closing_ratio floors cos(theta)): w's visible window
 * (r_lobe.h, visible_cut) closes where c reaches 0, at theta = tau +- pi/2. f_TT + f_TRT times
 * cos(theta_o) falls there as c^1.5 (at the bench material's theta_i = -1.246, f 2 cos(theta_o) /
 * c^1.5 is 0.476, 0.467 and 0.445 at theta_o = 1.46, 1.48 and 1.50, as c falls from 0.076 to 0.036),
 * and without tilt, at a pole, as cos(theta) = c. The table holds the rest, which stays smooth. */
HB_INLINE vf table_closing(const hb_huang *h, vf cos_ti, vf sin_ti, vf cos_to, vf sin_to)
{
    vf zero = vf_set1(0.0f), cos_tilt = vf_set1(h->cos_tilt), sin_tilt = vf_set1(h->sin_tilt);
    vf c_i = vf_max(vf_fma(cos_ti, cos_tilt, vf_mul(sin_ti, sin_tilt)), zero);
    vf c_o = vf_max(vf_fma(cos_to, cos_tilt, vf_mul(sin_to, sin_tilt)), zero);
    vf c = vf_mul(c_i, c_o);
    return vf_mul(c, vf_sqrt(vf_mul(closing_ratio(c_i, cos_ti), closing_ratio(c_o, cos_to))));
}

typedef struct table_node_range {
    float lo, hi;
} table_node_range;

HB_INLINE table_node_range table_node_range_of(const hb_huang *h)
{
    float tau = atan2f(h->sin_tilt, h->cos_tilt);
    table_node_range r = { fmaxf(-HB_PIO2_F, tau - HB_PIO2_F) + HB_TABLE_NODE_GAP,
                           fminf(HB_PIO2_F, tau + HB_PIO2_F) - HB_TABLE_NODE_GAP };
    return r;
}

HB_INLINE float table_node_inclination(const table_node_range *r, float theta)
{
    return fminf(fmaxf(theta, r->lo), r->hi);
}

/* The angles a lookup reads: theta_i, theta_o, and phi = phi_o - phi_i and phi_i in [-pi, pi]. */
typedef struct huang_table_angles {
    vf theta_i, theta_o, phi, phi_i;
} huang_table_angles;

HB_INLINE huang_table_angles huang_table_angles_from(vf theta_i, vf phi_i, vf theta_o, vf phi_o)
{
    return (huang_table_angles){ theta_i, theta_o, wrap_angle(vf_sub(phi_o, phi_i)), wrap_angle(phi_i) };
}

/* The angles back from the directions (for callers that have vectors). */
HB_INLINE huang_table_angles huang_table_angles_of(const hb_huang *h, const huang_directions *d)
{
    huang_table_angles a;
    a.theta_i = vf_atan2(d->sin_ti, d->cos_ti);
    a.theta_o = vf_atan2(d->sin_to, d->cos_to);
    a.phi = d->phi;
    a.phi_i = h->elliptical ? vf_atan2(d->sin_phi_i, d->cos_phi_i) : vf_set1(0.0f);
    return a;
}

/* f_TT + f_TRT per channel from the table: the square of its square roots multilinear over `axes`
 * axes (theta_i, phi_i on an elliptical fibre, the warped sum theta_i + theta_o and the azimuth
 * difference) times the closing factor; the angles' cosines and sines for that factor and for eqs.
 * 31, 32's 1 / (2 a cos(theta_o)) with sin^2(phi_o) (elliptical only), cos(theta_i) for its floor. */
HB_INLINE void huang_table_shaped(const hb_huang *h, const huang_table_angles *a, vf cos_ti, vf sin_ti, vf cos_to,
                                  vf sin_to, vf sin2_phi_o, vf out[3], int axes)
{
    const hb_huang_table *t = &h->table;
    vf delta = a->phi, phi_i = a->phi_i;
    if (axes == 4) { /* x -> -x and z -> -z map the fibre onto itself: phi_i into [0, pi/2] */
        vm flip = vf_lt(phi_i, vf_set1(0.0f));
        phi_i = vf_abs(phi_i);
        delta = vf_select(flip, vf_neg(delta), delta);
        flip = vf_gt(phi_i, vf_set1(HB_PIO2_F));
        phi_i = vf_select(flip, vf_sub(vf_set1(HB_PI_F), phi_i), phi_i);
        delta = vf_select(flip, vf_neg(delta), delta);
    } else {
        delta = vf_abs(delta);
    }
    vf u = table_asinh(vf_mul(vf_sub(vf_add(a->theta_i, a->theta_o), vf_set1(t->sum_centre)), vf_set1(t->inv_sum_width)));
    vf frac[4], weight[16];
    vi cell[4];
    int stride[4], offset[16], k = 0;
    cell[k] = table_cell(vf_mul(vf_add(a->theta_i, vf_set1(HB_PIO2_F)), vf_set1((float)(t->n_theta_i - 1) / HB_PI_F)),
                         t->n_theta_i, &frac[k]);
    stride[k++] = 3 * t->n_delta * t->n_sum * t->n_phi_i;
    if (axes == 4) {
        cell[k] = table_cell(vf_mul(phi_i, vf_set1((float)(t->n_phi_i - 1) / HB_PIO2_F)), t->n_phi_i, &frac[k]);
        stride[k++] = 3 * t->n_delta * t->n_sum;
    }
    cell[k] = table_cell(vf_mul(vf_sub(u, vf_set1(t->u_lo)), vf_set1(t->u_scale)), t->n_sum, &frac[k]);
    stride[k++] = 3 * t->n_delta;
    cell[k] = table_cell(vf_mul(vf_sub(delta, vf_set1(t->delta_lo)), vf_set1(t->delta_scale)), t->n_delta, &frac[k]);
    stride[k] = 3;
    vi base = cell_corners(axes, cell, frac, stride, weight, offset);
    vf zero = vf_set1(0.0f), sum[3] = { zero, zero, zero };
    HB_UNROLL
    for (int corner = 0; corner < 1 << axes; corner++) {
        vi index = vi_add(base, vi_set1(offset[corner]));
        HB_UNROLL
        for (int c = 0; c < 3; c++)
            sum[c] = vf_fma(weight[corner], vf_gather(t->values + c, index), sum[c]);
    }
    vf den = vf_set1(2.0f);
    if (axes == 4)
        den = vf_mul(den, vf_sqrt(vf_fnma(vf_set1(h->e2), sin2_phi_o, vf_set1(1.0f))));
    vf scale = vf_div(vf_mul(huang_width_factor(h, cos_ti, cos_to),
                             table_closing(h, cos_ti, sin_ti, cos_to, sin_to)),
                      den);
    for (int c = 0; c < 3; c++) /* the nodes hold square roots */
        out[c] = vf_mul(vf_mul(sum[c], sum[c]), scale);
}

HB_INLINE void huang_table_lookup(const hb_huang *h, const huang_table_angles *a, vf cos_ti, vf sin_ti, vf cos_to,
                                  vf sin_to, vf sin2_phi_o, vf out[3])
{
    if (h->elliptical)
        huang_table_shaped(h, a, cos_ti, sin_ti, cos_to, sin_to, sin2_phi_o, out, 4);
    else
        huang_table_shaped(h, a, cos_ti, sin_ti, cos_to, sin_to, sin2_phi_o, out, 3);
}

/* The fractional part of x, in [0, 1]. */
HB_INLINE vf unit_fraction(vf x)
{
    vf f = vf_sub(x, vf_round(x));
    return vf_select(vf_lt(f, vf_set1(0.0f)), vf_add(f, vf_set1(1.0f)), f);
}

/* The entry normal's second number warped toward the visible normals' rim, u -> 1 - (1 - u)^1.5,
 * with its Jacobian 1.5 sqrt(1 - u) (the path's weight): the lattice's points spread further into
 * the NDF's tail, which TT's tails read (noise between seeds at balanced, GGX 0.2: 2.6% rms, 3.9%
 * without the warp). */
HB_INLINE vf rim_warp(vf u, vf *jacobian)
{
    vf rest = vf_max(vf_sub(vf_set1(1.0f), u), vf_set1(0.0f)), root = vf_sqrt(rest);
    *jacobian = vf_mul(vf_set1(1.5f), root);
    return vf_fnma(rest, root, vf_set1(1.0f));
}

/* Traces the row's internal paths and stores their exits with weight (Simpson weight times rho
 * times step / 3 / lattice, times the path's own weight): HB_HUANG_EXIT_FLOATS floats each,
 * those of zero weight left out. Returns how many. */
HB_INLINE int table_row_exits(const hb_huang *h, float theta_i, float phi_i, const hb_huang_table_build *b,
                              float *store)
{
    int lattice = b->lattice, panels = h->table.panels, count = 0;
    vf sin_ti, cos_ti, sin_pi, cos_pi;
    vf_sincos(vf_set1(theta_i), &sin_ti, &cos_ti);
    vf_sincos(vf_set1(phi_i), &sin_pi, &cos_pi);
    entry_rule e = entry_rule_of(h, vf_max(cos_ti, vf_set1(0.0f)), sin_ti, cos_pi, sin_pi, panels);
    float lane_of[HB_W];
    for (int k = 0; k < HB_W; k++)
        lane_of[k] = (float)k;
    vf scale = vf_div(e.step, vf_set1(3.0f * (float)lattice));
    for (int j = 0; j <= panels; j++) {
        vf weight;
        fibre_point p = entry_node(h, &e, j, panels, &weight);
        weight = vf_keep(e.seen, vf_mul(weight, scale));
        vi stream = rng_stream(h->rng_key, vi_set1(j + (panels + 1) * b->row)); /* the node's shift of the lattice */
        for (int first = 0; first < lattice; first += HB_W) {
            vf index = vf_add(vf_set1((float)first), vf_loadu(lane_of)), u[4];
            for (int k = 0; k < 4; k++) /* point l: frac(l z_k / N + shift_k) */
                u[k] = unit_fraction(vf_fma(index, vf_set1((float)b->generator[k] / (float)lattice),
                                            rng_uniform(stream, h->rng_key2, k)));
            vf jacobian, path_weight;
            u[1] = rim_warp(u[1], &jacobian);
            path_weight = vf_mul(weight, jacobian);
            internal_exit exits[2];
            internal_exits(h, &p, e.wi, u, exits, h->lobes >> HB_LOBE_TRT & 1u, NULL, NULL);
            for (int l = 0; l < 2; l++) {
                if (!(h->lobes >> (HB_LOBE_TT + l) & 1u))
                    continue;
                const internal_exit *x = &exits[l];
                vf fields[HB_HUANG_EXIT_FLOATS] = { x->q.macro.x, x->q.macro.z, x->q.meso.x, x->q.meso.y, x->q.meso.z,
                                                    x->w.x,       x->w.y,       x->w.z };
                for (int c = 0; c < 3; c++)
                    fields[8 + c] = vf_mul(path_weight, x->weight[c]);
                float lanes[HB_HUANG_EXIT_FLOATS][HB_W];
                for (int f = 0; f < HB_HUANG_EXIT_FLOATS; f++)
                    vf_storeu(lanes[f], fields[f]);
                for (int k = 0; k < HB_W && first + k < lattice; k++) {
                    if (lanes[8][k] + lanes[9][k] + lanes[10][k] <= 0.0f)
                        continue;
                    for (int f = 0; f < HB_HUANG_EXIT_FLOATS; f++)
                        store[HB_HUANG_EXIT_FLOATS * count + f] = lanes[f][k];
                    count++;
                }
            }
        }
    }
    return count;
}

/* One row of the table: for every (s, delta) node, the square root of the sum over the row's exits
 * of their weight times the exit interface's value toward w_o (eqs. 31, 32 without
 * 1 / (2 a cos(theta_o))) over the closing factor, both inclinations taken at their nodes'
 * (table_node_inclination). Interpolating square roots and squaring the result halves the linear
 * interpolant's relative error on an exponential tail and still reaches zero where f does. */
HB_INLINE void huang_table_row(const hb_huang *h, float theta_i, float phi_i, const hb_huang_table_build *b, float *row)
{
    const hb_huang_table *t = &h->table;
    table_node_range range = table_node_range_of(h);
    float node_theta_i = table_node_inclination(&range, theta_i);
    int exits = table_row_exits(h, node_theta_i, phi_i, b, b->scratch);
    vf zero = vf_set1(0.0f), sin_ti, cos_ti;
    vf_sincos(vf_set1(node_theta_i), &sin_ti, &cos_ti);
    for (int k = 0; k < t->n_sum; k++)
        for (int first = 0; first < t->n_delta; first += HB_W) {
            float theta_o[HB_W], phi_o[HB_W];
            for (int l = 0; l < HB_W; l++) {
                theta_o[l] = table_node_inclination(&range, b->sums[k] - theta_i);
                phi_o[l] = phi_i + b->deltas[first + l < t->n_delta ? first + l : t->n_delta - 1];
            }
            vf st, ct, sp, cp;
            vf_sincos(vf_loadu(theta_o), &st, &ct);
            vf_sincos(vf_loadu(phi_o), &sp, &cp);
            ct = vf_max(ct, zero);
            v3 wo = { vf_mul(sp, ct), st, vf_mul(cp, ct) };
            vf sum[3] = { zero, zero, zero };
            for (int x = 0; x < exits; x++) {
                const float *f = b->scratch + HB_HUANG_EXIT_FLOATS * x;
                fibre_point q;
                q.px = q.pz = zero;
                q.macro = (v3){ vf_set1(f[0]), zero, vf_set1(f[1]) };
                q.meso = (v3){ vf_set1(f[2]), vf_set1(f[3]), vf_set1(f[4]) };
                q.t1 = q.t2 = q.meso; /* unused by exit_value */
                v3 w = { vf_set1(f[5]), vf_set1(f[6]), vf_set1(f[7]) };
                vf value = exit_value(h, &q, w, wo);
                for (int c = 0; c < 3; c++)
                    sum[c] = vf_fma(value, vf_set1(f[8 + c]), sum[c]);
            }
            vf inv_closing = vf_div(vf_set1(1.0f), table_closing(h, cos_ti, sin_ti, ct, st));
            float lanes[3][HB_W];
            for (int c = 0; c < 3; c++)
                vf_storeu(lanes[c], vf_sqrt(vf_mul(vf_max(sum[c], zero), inv_closing)));
            for (int l = 0; l < HB_W && first + l < t->n_delta; l++)
                for (int c = 0; c < 3; c++)
                    row[3 * (k * t->n_delta + first + l) + c] = lanes[c][l];
        }
}

#endif

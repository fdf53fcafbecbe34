/* The dual-scattering radiance term (hb_dual_eval) for one ISA: the Makefile compiles this file once
 * per instruction set into hb_<isa>_dual_kernels. The terms at theta_i are the table's linear
 * interpolation; the equations are the header's (Zinke et al. 2008 sec. 4, in the library's
 * normalisation: each lobe integrates over w_o to its energy). */
#include "kernel/batch.h"
#include "math/multilinear.h"
#include "kernels.h"

#define INV_SQRT_2PI 0.398942280f
#define VARIANCE_MIN 1e-8f /* a lobe no narrower than 1e-4 rad: a zero variance has zero energy */
#define VARIANCE_MAX 1e8f  /* wider, a lobe is 0 within float rounding (n beyond 1e10 fibres) */
#define COS_THETA_MIN 2.44140625e-4f /* 2^-12: the lobes' 1 / cos(theta_o) stays finite at the poles */

/* The unit Gaussians g(x[k], variance[k]) of one channel's four lobes, each variance held in
 * [VARIANCE_MIN, VARIANCE_MAX]: four square roots and one division, 1 / s_k = (the other three s)
 * / (s_0 s_1 s_2 s_3), the product within 1e-16..1e16. */
HB_INLINE void gaussians(const vf x[4], const vf variance[4], vf g[4])
{
    vf root[4];
    HB_UNROLL
    for (int k = 0; k < 4; k++)
        root[k] = vf_sqrt(vf_clamp(variance[k], VARIANCE_MIN, VARIANCE_MAX));
    vf low = vf_mul(root[0], root[1]), high = vf_mul(root[2], root[3]);
    vf all = vf_div(vf_set1(1.0f), vf_mul(low, high));
    vf inverse[4] = { vf_mul(vf_mul(root[1], high), all), vf_mul(vf_mul(root[0], high), all),
                      vf_mul(vf_mul(root[3], low), all), vf_mul(vf_mul(root[2], low), all) };
    HB_UNROLL
    for (int k = 0; k < 4; k++) { /* e^(-z^2 / 2) = 2^-(z sqrt(log2(e) / 2))^2 */
        vf z = vf_mul(vf_mul(x[k], inverse[k]), vf_set1(0.849321800f));
        g[k] = vf_mul(vf_exp2_neg(vf_mul(z, z)), vf_mul(vf_set1(INV_SQRT_2PI), inverse[k]));
    }
}

/* Lane block i: the four angles, n and v; invalid lanes (hb_eval_angles' rule, n NaN, negative or
 * infinite, v outside [0, 1]) get zeros. Without a direct plane v = max(0, 1 - n). */
HB_INLINE vm load_dual(const hb_dual_batch *b, size_t i, size_t lanes, vf a[6])
{
    vm valid = load_angles(b->angles, i, lanes, a);
    const float *extra[2] = { b->fibres, b->direct };
    a[5] = vf_set1(0.0f);
    load_block(extra, b->direct ? 2 : 1, i, lanes, 0.0f, a + 4);
    valid = vm_and(valid, vm_and(vf_ge(a[4], vf_set1(0.0f)), vf_le(a[4], vf_set1(FLT_MAX))));
    if (b->direct)
        valid = vm_and(valid, vm_and(vf_ge(a[5], vf_set1(0.0f)), vf_le(a[5], vf_set1(1.0f))));
    else
        a[5] = vf_max(vf_sub(vf_set1(1.0f), a[4]), vf_set1(0.0f));
    HB_UNROLL
    for (int k = 0; k < 6; k++)
        a[k] = vf_keep(valid, a[k]);
    return valid;
}

/* One channel's terms at theta_i: the lower node's three gathers of four and the upper node's. */
HB_INLINE void channel_terms(const float *nodes, vi base, vf fraction, vf term[HB_DUAL_PER_CHANNEL])
{
    HB_UNROLL
    for (int q = 0; q < HB_DUAL_PER_CHANNEL; q += 4) {
        vf lower[4], upper[4];
        vf_gather4(nodes + q, base, lower);
        vf_gather4(nodes + q + HB_DUAL_PER_NODE, base, upper);
        HB_UNROLL
        for (int k = 0; k < 4; k++)
            term[q + k] = vf_fma(fraction, vf_sub(upper[k], lower[k]), lower[k]);
    }
}

HB_INLINE void dual_radiance(const struct hb_dual_table *t, const vf a[6], vf f[3])
{
    vf theta_h = vf_mul(vf_set1(0.5f), vf_add(a[0], a[2]));
    vf abs_phi = vf_abs(wrap_angle(vf_sub(a[3], a[1])));
    vm back = vf_lt(abs_phi, vf_set1(1.57079633f));
    /* 1 / (2 pi cos theta_o): a density in theta_h over 2 cos theta_o dtheta_h dphi_o */
    vf per_solid_angle = vf_div(vf_set1(0.159154943f), vf_max(vf_cos(a[2]), vf_set1(COS_THETA_MIN)));
    vf fibres = a[4], visible = a[5];
    vf fraction;
    vi cell = table_cell(vf_fma(a[0], vf_set1((float)t->thetas * 0.318309886f), vf_set1(0.5f * (float)t->thetas - 0.5f)),
                         t->thetas, &fraction);
    vi base = vi_mul(cell, vi_set1(HB_DUAL_PER_NODE));
    vf local = vf_mul(visible, vf_set1((float)t->d_b));
    vf unlit = vf_mul(vf_sub(vf_set1(1.0f), visible), vf_set1((float)t->d_f));
    HB_UNROLL
    for (int c = 0; c < 3; c++) {
        vf m[HB_DUAL_PER_CHANNEL];
        channel_terms(t->nodes + c * HB_DUAL_PER_CHANNEL, base, fraction, m);
        vf spread = vf_mul(fibres, m[HB_DUAL_BETA_F2]); /* sigma_f^2 = n beta_f^2 */
        vf log2_forward = vf_mul(vf_log(vf_max(m[HB_DUAL_A_F], vf_set1(FLT_MIN))), vf_set1(1.44269504f));
        vf global = vf_mul(unlit, vf_exp2_neg(vf_mul(vf_neg(fibres), log2_forward))); /* (1 - v) d_f a_f^n */
        vf x_back = vf_sub(theta_h, m[HB_DUAL_DELTA_B]);
        const vf x[4] = { x_back, x_back, vf_sub(theta_h, m[HB_DUAL_ALPHA_F]), vf_sub(theta_h, m[HB_DUAL_ALPHA_B]) };
        const vf variance[4] = { m[HB_DUAL_SIGMA_B2], vf_add(m[HB_DUAL_SIGMA_B2], spread), vf_add(m[HB_DUAL_BETA_F2], spread),
                                 vf_add(m[HB_DUAL_BETA_B2], spread) };
        vf g[4];
        gaussians(x, variance, g);
        vf back_direct = vf_keep(back, vf_mul(m[HB_DUAL_A_BACK], g[0]));
        vf back_spread = vf_keep(back, vf_mul(m[HB_DUAL_A_BACK], g[1]));
        /* f_G: the forward energy's azimuths |phi| / pi^2, the backward's (pi - |phi|) / pi^2 */
        vf forward = vf_mul(vf_mul(m[HB_DUAL_A_F], abs_phi), g[2]);
        vf backward = vf_mul(vf_mul(m[HB_DUAL_A_B], vf_sub(vf_set1(3.14159265f), abs_phi)), g[3]);
        vf scattered = vf_fma(vf_add(forward, backward), vf_set1(0.318309886f),
                              vf_mul(vf_set1((float)t->d_b), back_spread));
        f[c] = vf_mul(per_solid_angle, vf_fma(local, back_direct, vf_mul(global, scattered)));
    }
}

static void eval_kernel(const struct hb_dual_table *table, size_t n, const hb_dual_batch *in, hb_rgb_soa out,
                        size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_dual, 6, in, n, invalid, (dual_radiance(table, a, f), store_rgb(out, i, lanes, valid, f)));
}

const hb_dual_kernels HB_ISA_SYMBOL(dual_kernels) = { .eval = eval_kernel };

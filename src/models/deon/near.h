/* dFH11 at one offset h across the fibre (the near field, as CBTB16 evaluates its model): the
 * integrand of eq. 10 at h instead of its integral, N_p(phi; h) = A(p, h) D_p(phi - Phi(p, h)), with
 * M_p, the tilt, every order and the residual as in the far field, so that the mean of the near
 * field over h in [-1, 1] is the far field. h's sign is CBTB16's (docs/chiang.md): Phi(p, h) = 2 p
 * gamma_t - 2 gamma_i + p pi with gamma_i = asin(h). */
#ifndef HB_DEON_NEAR_H
#define HB_DEON_NEAR_H

#include "azimuthal.h"

/* D_p(x) of eq. 11 alone: the plan's Gaussians at x - 2 pi k, |k| <= terms (the nearest alone for
 * the standard shape), or its Fourier series coeff_0 + sum_n coeff_n cos(n x). */
HB_INLINE vf detector_single(const hb_detector *det, vf x, deon_shape shape)
{
    x = wrap_angle(x);
    if (!shape.standard && det->fourier) {
        vf cos_x = vf_cos(x), previous = vf_set1(1.0f), current = cos_x, sum = vf_set1(det->coeff[0]);
        for (int n = 1; n <= det->terms; n++) {
            sum = vf_fma(vf_set1(det->coeff[n]), current, sum);
            vf next = vf_fnma(previous, vf_set1(1.0f), vf_mul(vf_add(cos_x, cos_x), current));
            previous = current;
            current = next;
        }
        return sum;
    }
    vf sum = vf_set1(0.0f), exponent = vf_set1(det->log2e_over_two_beta2);
    int terms = shape.standard ? 0 : det->terms;
    for (int k = -terms; k <= terms; k++) {
        vf dx = vf_sub(x, vf_set1(HB_TWO_PI_F * (float)k));
        sum = vf_add(sum, vf_exp2_neg(vf_mul(vf_mul(dx, dx), exponent)));
    }
    return vf_mul(sum, vf_set1(det->gauss_norm));
}

/* The lobes at offset |h|: A(p, h) is even in h and Phi(p, h) odd, so the node at gamma_i = asin|h|
 * serves both signs, detected at phi for h >= 0 and at -phi for h < 0 (D_p is even). */
HB_INLINE vf near_offset(vf h, vf *cos_gamma_i)
{
    vf a = vf_min(vf_abs(h), vf_set1(1.0f));
    *cos_gamma_i = vf_sqrt(vf_mul(vf_sub(vf_set1(1.0f), a), vf_add(vf_set1(1.0f), a)));
    return a;
}

HB_INLINE void deon_near_node(const hb_deon *d, const deon_medium *medium, vf h, deon_node *node, deon_shape shape)
{
    vf cos_gamma_i, a = near_offset(h, &cos_gamma_i);
    deon_node_lobes(d, medium, a, vf_asin(a), cos_gamma_i, node, shape);
}

/* f at h (eq. 10's integrand per lobe, times M_p) in the shape's channels (out: at least three);
 * with pdf, the sampler's azimuthal density at h, sum_p m_p D_p / sum_p m_p with m_p = M_p A(p, h)
 * averaged over the channels (sample.h). */
HB_INLINE void deon_near_shaped(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1], vf h,
                                vf *out, vf *pdf, deon_shape shape)
{
    deon_medium medium;
    deon_medium_of(d, g, &medium, shape.channels);
    deon_node node;
    deon_near_node(d, &medium, h, &node, shape);
    vf phi = vf_select(vf_lt(h, vf_set1(0.0f)), vf_neg(g->phi), g->phi);
    vf fresnel_r = d->r_fresnel_offset ? vf_set1(1.0f) : fresnel_dielectric(g->cos_half_io, &d->ior); /* eq. 12 */
    vf mass = vf_set1(0.0f), detected = vf_set1(0.0f);
    HB_UNROLL
    for (int c = 0; c < HB_DEON_CHANNELS; c++)
        if (c < 3 || c < shape.channels)
            out[c] = vf_set1(0.0f);
    HB_UNROLL
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        if (!deon_lobe_on(d, p, shape))
            continue;
        vf D = p == HB_LOBE_RESIDUAL ? vf_set1(HB_RESIDUAL_DETECTOR)
                                     : detector_single(&d->detector[p], vf_sub(phi, node.paths.Phi[p]), shape);
        vf MD = vf_mul(M[d->m_group[p]], p == 0 ? vf_mul(D, fresnel_r) : D);
        HB_UNROLL
        for (int c = 0; c < shape.channels; c++)
            out[c] = vf_fma(MD, node.A[p][c], out[c]);
        if (pdf) {
            vf m = vf_mul(M[d->m_group[p]], deon_channel_mean(node.A[p], shape.channels));
            mass = vf_add(mass, m);
            detected = vf_fma(m, D, detected);
        }
    }
    if (shape.channels == 1)
        out[1] = out[2] = out[0];
    if (pdf)
        *pdf = vf_div(detected, vf_max(mass, vf_set1(1e-37f)));
}

/* The near field of one sample whose values fill every lane, with its lobes across the lanes (constants.h,
 * hb_lobe_lanes; standard plans, whose R takes the offset Fresnel, on the float M_p path): the paths at
 * |h| once (deon_node_paths, the same in every lane), then per lane L its lobe's A(p, h) = A_f[L] T^L
 * (eq. 13; the residual's lane, L = pmax + 1, times 1 / (1 - f T)), Phi(p, h) (eq. 8), detector (eq. 11)
 * and M_p (longitudinal_lobe_lanes), and f the sum over the lanes: a pass for up to HB_W lobes where
 * deon_near takes one per lobe. f comes back in every lane. */
HB_INLINE void deon_near_lanes(const hb_deon *d, const deon_geometry *g, const mp_inclinations *in, vf h, hb_i0 i0,
                               vf out[3])
{
    const deon_shape shape = { 1, 3, 0 };
    const hb_lobe_lanes *lanes = &d->lobe_lanes;
    deon_medium medium;
    deon_medium_of(d, g, &medium, 3);
    vf cos_gamma_i, a = near_offset(h, &cos_gamma_i);
    deon_paths paths;
    deon_node_paths(d, &medium, a, vf_asin(a), cos_gamma_i, &paths, shape);
    vf phi = vf_select(vf_lt(h, vf_set1(0.0f)), vf_neg(g->phi), g->phi);
    vf one = vf_set1(1.0f), series[3], sum[3];
    HB_UNROLL
    for (int c = 0; c < 3; c++) {
        series[c] = residual_series(paths.f, paths.one_minus_f, paths.T[c]);
        sum[c] = vf_set1(0.0f);
    }
    for (int first = 0; first < HB_LOBE_LANES; first += HB_W) {
        vf order = vf_add(vf_set1((float)first), vf_lane_index()), A_f = paths.A_f[0], Phi = paths.Phi[0];
        vf T_lane[3] = { one, one, one };
        vm at;
        HB_UNROLL /* lanes past the residual's take its values, and a detector of 0 */
        for (int p = 1; p <= HB_STANDARD_PMAX + 1; p++) {
            at = vf_ge(order, vf_set1((float)p));
            A_f = vf_select(at, paths.A_f[p], A_f);
            Phi = p <= HB_STANDARD_PMAX ? vf_select(at, paths.Phi[p], Phi) : Phi;
            HB_UNROLL
            for (int c = 0; c < 3; c++) /* T^p as deon_node_lobes forms it */
                T_lane[c] = vf_mul(T_lane[c], vf_select(at, paths.T[c], one));
        }
        HB_UNROLL
        for (int c = 0; c < 3; c++)
            T_lane[c] = vf_mul(T_lane[c], vf_select(at, series[c], one));
        vf x = wrap_angle(vf_sub(phi, Phi));
        vf D = vf_mul(vf_loadu(lanes->detector_norm + first),
                      vf_exp2_neg(vf_mul(vf_mul(x, x), vf_loadu(lanes->detector_exponent + first))));
        vf MDA = vf_mul(vf_mul(longitudinal_lobe_lanes(lanes, first, in, i0), D), A_f);
        for (int c = 0; c < 3; c++)
            sum[c] = vf_fma(MDA, T_lane[c], sum[c]);
    }
    for (int c = 0; c < 3; c++) /* the lanes past the lobes hold 0: not read */
        out[c] = vf_set1(vf_sum_first(sum[c], HB_LOBE_LANES < HB_W ? HB_LOBE_LANES : HB_W));
}

HB_INLINE void deon_near(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1], vf h, vf out[3],
                         vf *pdf)
{
    if (d->standard && g->grey)
        deon_near_shaped(d, g, M, h, out, pdf, (deon_shape){ 1, 1, 0 });
    else if (d->standard)
        deon_near_shaped(d, g, M, h, out, pdf, (deon_shape){ 1, 3, 0 });
    else
        deon_near_shaped(d, g, M, h, out, pdf, (deon_shape){ 0, 3, 0 });
}

/* The same at a spectral call's k wavelengths, g's absorptions (out: k planes, at least three). */
HB_INLINE void deon_near_spectral(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1], vf h,
                                  int channels, vf *out, vf *pdf)
{
    if (d->standard)
        deon_near_shaped(d, g, M, h, out, pdf, (deon_shape){ 1, channels, 0 });
    else
        deon_near_shaped(d, g, M, h, out, pdf, (deon_shape){ 0, channels, 0 });
}

#endif

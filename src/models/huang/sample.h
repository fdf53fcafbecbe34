/* HHH22 R lobe importance sampling and its pdf over the SIMD vocabulary (HHH22 sec. 3.4.1 and
 * eq. 33 for the R lobe alone; docs/sampling.md).
 *
 * Given w_o and three uniform numbers:
 *  1. u0 picks the offset h uniformly across the part of the fibre's projected width (seen from w_o)
 *     whose mesonormal faces w_o (eq. 40's window for w_o alone), so the density of the mesonormal
 *     azimuth phi_m is cos(phi_m - phi_o) rho(phi_m) / W, W that part's projected width (2 cos(cut)
 *     for a circle; an ellipse is the affine image of a circle, so h is drawn on that circle);
 *  2. u1, u2 draw a micronormal w_h from the visible normals of w_o on the mesosurface (Heitz 2014):
 *     GGX exactly, by Dupuy and Benyoub's spherical caps (2023); Beckmann by inverting the visible
 *     slope CDF with five safeguarded Newton steps on sqrt(1 - CDF), which converge quadratically
 *     also where the density vanishes linearly at the top, 1 - CDF computed without cancellation;
 *  3. w_i is w_o reflected about w_h.
 * Its density per solid angle, which hb_pdf_angles returns, is
 *     pdf(w_i) = 1 / (4 W) * integral over phi_m of cos(phi_m - phi_o) rho G1(w_o) D(w_h, w_m) / (w_o . w_m)
 * over the phi_m that w_o sees with w_h . w_m > 0: one arc, or two when w_h is steep; taken by the
 * peak-following Simpson rule of eval in two pieces (the halves of the one arc, or the two arcs). */
#ifndef HB_HUANG_SAMPLE_H
#define HB_HUANG_SAMPLE_H

#include "r_lobe.h"

/* The mesonormal azimuths w_o sees, phi_o +- half, and their projected width W. */
typedef struct huang_o_window {
    vf half, projected;
    vf sin_half;     /* sin(half) = cos(cut) */
    vf lo_projected; /* elliptical: signed projected offset of the window's low end */
    vm seen;
} huang_o_window;

/* For an ellipse (point (sin g, b cos g), normal azimuth phi_m with tan(phi_m) = b tan(g)), the
 * projection of the point whose normal has azimuth phi_o + x on the direction across w_o's view,
 * (e^2 sin(phi_o) cos(phi_o) cos(x) + a^2 sin(x)) / sqrt(1 - e^2 cos^2(phi_o + x)), a^2 = 1 - e^2 sin^2(phi_o). */
HB_INLINE vf ellipse_offset(const hb_huang *h, vf cos_po, vf sin_po, vf a2, vf sin_x, vf cos_x)
{
    vf cos_end = vf_fnma(sin_po, sin_x, vf_mul(cos_po, cos_x));
    vf num = vf_fma(vf_mul(vf_set1(h->e2), vf_mul(sin_po, cos_po)), cos_x, vf_mul(a2, sin_x));
    vf norm2 = vf_fnma(vf_set1(h->e2), vf_mul(cos_end, cos_end), vf_set1(1.0f));
    return vf_div(num, vf_sqrt(norm2));
}

HB_INLINE huang_o_window huang_o_window_of(const hb_huang *h, vf cos_to, vf sin_to, vf phi_o)
{
    huang_o_window w;
    vf cut = visible_cut(h, cos_to, sin_to, &w.seen), cos_half;
    w.half = vf_keep(w.seen, vf_sub(vf_set1(HB_PIO2_F), cut));
    vf_sincos(w.half, &w.sin_half, &cos_half);
    w.projected = vf_add(w.sin_half, w.sin_half);
    w.lo_projected = vf_neg(w.sin_half);
    if (h->elliptical) {
        vf sin_po, cos_po;
        vf_sincos(wrap_angle(phi_o), &sin_po, &cos_po);
        vf a2 = vf_fnma(vf_set1(h->e2), vf_mul(sin_po, sin_po), vf_set1(1.0f));
        vf hi = ellipse_offset(h, cos_po, sin_po, a2, w.sin_half, cos_half);
        w.lo_projected = ellipse_offset(h, cos_po, sin_po, a2, vf_neg(w.sin_half), cos_half);
        w.projected = vf_sub(hi, w.lo_projected);
    }
    return w;
}

/* pdf at a direction pair (in the frame phi_i = 0). */
HB_STAGE vf huang_pdf(const hb_huang *h, const huang_directions *d, const huang_r_geometry *g, const huang_o_window *w)
{
    vf pi = vf_set1(HB_PI_F), two_pi = vf_set1(HB_TWO_PI_F), zero = vf_set1(0.0f);
    /* w_o's window in delta = phi_h - phi_m: centre phi_h - phi_o, half width w->half; w_h . w_m > 0
     * for |delta| < beta, cos(beta) = -sin_h_tilt / cos_h_tilt */
    vf centre = wrap_angle(vf_sub(g->phi_h, g->phi)), lo = vf_sub(centre, w->half), hi = vf_add(centre, w->half);
    vf cos_beta = vf_div(vf_neg(g->sin_h_tilt), vf_max(g->cos_h_tilt, vf_set1(1e-30f)));
    vf beta = vf_acos(vf_clamp(cos_beta, -1.0f, 1.0f));
    vf lo1 = vf_max(lo, vf_neg(beta)), hi1 = vf_min(hi, beta);
    /* the part of the window past +-pi, wrapped, inside |delta| < beta */
    vm over = vf_gt(hi, pi), under = vf_lt(lo, vf_neg(pi));
    vf lo2 = vf_select(over, vf_neg(beta), vf_add(lo, two_pi));
    vf hi2 = vf_select(over, vf_sub(hi, two_pi), beta);
    vf half1 = vf_max(vf_mul(vf_set1(0.5f), vf_sub(hi1, lo1)), zero);
    vf half2 = vf_select(vm_or(over, under), vf_max(vf_mul(vf_set1(0.5f), vf_sub(hi2, lo2)), zero), zero);
    huang_t_piece t1 = t_piece_of(g, vf_mul(vf_set1(0.5f), vf_add(lo1, hi1)), half1);
    huang_t_piece t2 = t_piece_of(g, vf_mul(vf_set1(0.5f), vf_add(lo2, hi2)), half2);
    /* one arc: its two halves in t */
    vm one_arc = vf_le(half2, zero);
    vf half_span = vf_mul(vf_set1(0.5f), t1.half_span);
    t2.half_lo = vf_select(one_arc, vf_add(t1.half_lo, half_span), t2.half_lo);
    t2.half_span = vf_select(one_arc, half_span, t2.half_span);
    t1.half_span = vf_select(one_arc, half_span, t1.half_span);
    int panels = h->pdf_panels / 2;
    vf integral = vf_add(mapped_simpson(h, d, g, t1, panels, 1), mapped_simpson(h, d, g, t2, panels, 1));
    vf pdf = vf_div(vf_max(integral, zero), vf_mul(vf_set1(4.0f), vf_max(w->projected, vf_set1(1e-30f))));
    vm some = vm_and(w->seen, vm_or(vf_gt(half1, zero), vf_gt(half2, zero)));
    return vf_select(vm_and(some, vf_gt(w->projected, zero)), pdf, zero);
}

HB_INLINE vf huang_pdf_angles(const hb_huang *h, vf theta_i, vf phi_i, vf theta_o, vf phi_o)
{
    huang_directions d = huang_directions_of_angles(h, theta_i, phi_i, theta_o, phi_o);
    huang_r_geometry g = huang_r_geometry_of(h, &d);
    huang_o_window w = huang_o_window_of(h, d.cos_to, d.sin_to, phi_o);
    return huang_pdf(h, &d, &g, &w);
}

/* A GGX visible normal of the direction o (o_z > 0) in the frame of the mesonormal (Dupuy and
 * Benyoub 2023): in the configuration stretched to roughness 1, the visible normals are o' plus a
 * point drawn uniformly on the spherical cap z >= -o'_z; unstretched and normalised. */
HB_INLINE void ggx_visible_normal(const hb_huang *h, const vf o[3], vf u1, vf u2, vf m[3])
{
    vf r = vf_set1(h->roughness), one = vf_set1(1.0f);
    vf sx = vf_mul(r, o[0]), sy = vf_mul(r, o[1]), sz = o[2];
    vf inv = vf_div(one, vf_sqrt(vf_fma(sx, sx, vf_fma(sy, sy, vf_mul(sz, sz)))));
    sx = vf_mul(sx, inv);
    sy = vf_mul(sy, inv);
    sz = vf_mul(sz, inv);
    /* z = (1 - u2)(1 + s_z) - s_z; 1 - z = u2 (1 + s_z) and 1 + z = (1 - s_z) + (1 - u2)(1 + s_z), without cancellation */
    vf one_plus_sz = vf_add(one, sz), upper = vf_mul(vf_sub(one, u2), one_plus_sz);
    vf z = vf_sub(upper, sz);
    vf sin2 = vf_mul(vf_mul(u2, one_plus_sz), vf_add(vf_sub(one, sz), upper));
    vf sin_t = vf_sqrt(vf_max(sin2, vf_set1(0.0f))), sp, cp;
    vf_sincos(vf_mul(vf_set1(HB_TWO_PI_F), u1), &sp, &cp);
    vf hx = vf_mul(r, vf_fma(sin_t, cp, sx)), hy = vf_mul(r, vf_fma(sin_t, sp, sy)), hz = vf_add(z, sz);
    vf norm = vf_div(one, vf_sqrt(vf_max(vf_fma(hx, hx, vf_fma(hy, hy, vf_mul(hz, hz))), vf_set1(1e-30f))));
    m[0] = vf_mul(hx, norm);
    m[1] = vf_mul(hy, norm);
    m[2] = vf_mul(hz, norm);
}

#define HB_BECKMANN_NEWTON_STEPS 5

/* A Beckmann visible normal of o (o_z > 0) in the mesonormal's frame (Heitz and d'Eon 2014): in
 * the configuration stretched to roughness 1, o' at inclination t, the slope along o's azimuth has
 * density proportional to e^(-x^2) (cos t - x sin t) for x <= c = cot t, whose CDF in q = (1 + erf x) / 2
 * is F(q) = (2 q cos t + sin t e^(-x^2) / sqrt(pi)) / (2 q_max cos t + sin t e^(-c^2) / sqrt(pi)),
 * and the slope across it is normal with variance 1/2. F(q) = u1 is solved by Newton steps on
 * sqrt(1 - F) (F's slope vanishes at q_max, sqrt(1 - F)'s does not), kept inside a bracket.
 * 1 - F is computed as such, never as 1 minus a rounded F: with d = c - x,
 *     (1 - F) total = (2 / sqrt(pi)) sin t I(d),  I(d) = integral over [0, d] of v e^(-(c - v)^2) dv,
 * by three-point Gauss-Legendre below d = 1/2 (relative error under 1e-6 there) and as
 * 2 (q_max - q) cos t - sin t (e^(-x^2) - e^(-c^2)) / sqrt(pi) above it. Newton starts at u1 q_max,
 * or nearer the top where sqrt(1 - F) ~ k (q_max - q), k^2 = sqrt(pi) e^(c^2) sin t / total. */
HB_INLINE vf beckmann_one_minus_cdf(vf q, vf x, vf cot, vf sin_t, vf q_max, vf cos_t, vf gauss_top, vf inv_total)
{
    vf zero = vf_set1(0.0f), d = vf_max(vf_sub(cot, x), zero), h = vf_mul(vf_set1(0.5f), d);
    vf a = vf_mul(vf_set1(0.774596669f), h), mid = vf_sub(cot, h); /* nodes h, h -+ a; their c - v */
    vf lo = vf_add(mid, a), hi = vf_sub(mid, a);
    vf sum = vf_mul(vf_set1(8.0f / 9.0f), vf_mul(h, vf_exp_flush(vf_max(vf_neg(vf_mul(mid, mid)), vf_set1(-100.0f)))));
    vf sides = vf_mul(vf_sub(h, a), vf_exp_flush(vf_max(vf_neg(vf_mul(lo, lo)), vf_set1(-100.0f))));
    sides = vf_fma(vf_add(h, a), vf_exp_flush(vf_max(vf_neg(vf_mul(hi, hi)), vf_set1(-100.0f))), sides);
    vf near = vf_mul(vf_mul(h, vf_fma(vf_set1(5.0f / 9.0f), sides, sum)), vf_mul(vf_set1(2.0f * HB_INV_SQRT_PI_F), sin_t));
    vf gauss_x = vf_exp_flush(vf_max(vf_neg(vf_mul(x, x)), vf_set1(-100.0f)));
    vf far = vf_fnma(vf_mul(sin_t, vf_set1(HB_INV_SQRT_PI_F)), vf_sub(gauss_x, gauss_top),
                     vf_mul(vf_mul(vf_set1(2.0f), vf_sub(q_max, q)), cos_t));
    return vf_max(vf_mul(vf_select(vf_lt(d, vf_set1(0.5f)), near, far), inv_total), zero);
}

HB_INLINE void beckmann_visible_normal(const hb_huang *h, const vf o[3], vf u1, vf u2, vf m[3])
{
    vf r = vf_set1(h->roughness), one = vf_set1(1.0f), zero = vf_set1(0.0f), inv_sqrt2 = vf_set1(0.707106781f);
    vf sx = vf_mul(r, o[0]), sy = vf_mul(r, o[1]);
    vf planar = vf_sqrt(vf_fma(sx, sx, vf_mul(sy, sy)));
    vf inv = vf_div(one, vf_sqrt(vf_fma(planar, planar, vf_mul(o[2], o[2]))));
    vf cos_t = vf_mul(o[2], inv), sin_t = vf_mul(planar, inv);
    vm has_azimuth = vf_gt(planar, vf_set1(1e-30f));
    vf inv_planar = vf_div(one, vf_max(planar, vf_set1(1e-30f)));
    vf cos_a = vf_select(has_azimuth, vf_mul(sx, inv_planar), one), sin_a = vf_select(has_azimuth, vf_mul(sy, inv_planar), zero);
    vf cot = vf_min(vf_div(cos_t, vf_max(sin_t, vf_set1(1e-30f))), vf_set1(1e4f));
    vf cot2 = vf_mul(cot, cot);
    vf gauss_top = vf_exp_flush(vf_max(vf_neg(cot2), vf_set1(-100.0f))); /* e^(-c^2) */
    vf tail = vf_mul(vf_mul(sin_t, vf_set1(HB_INV_SQRT_PI_F)), gauss_top);
    vf q_max = vf_fnma(vf_set1(0.5f), vf_mul(gauss_top, erfcx_as(cot)), one); /* 1 - erfc(c) / 2 */
    vf inv_total = vf_div(one, vf_fma(vf_add(q_max, q_max), cos_t, tail));
    vf target = vf_sqrt(vf_max(vf_sub(one, u1), zero));
    vf k = vf_sqrt(vf_mul(vf_mul(sin_t, inv_total), vf_mul(vf_set1(1.77245385f), vf_exp(vf_min(cot2, vf_set1(80.0f))))));
    vf lo = zero, hi = q_max, q = vf_mul(u1, q_max), x;
    q = vf_max(vf_min(q, vf_sub(q_max, vf_div(target, vf_max(k, vf_set1(1e-30f))))), vf_mul(vf_set1(0.5f), q));
    for (int step = 0; step < HB_BECKMANN_NEWTON_STEPS; step++) {
        x = vf_mul(vf_normal_quantile(q), inv_sqrt2);
        vf root = vf_sqrt(beckmann_one_minus_cdf(q, x, cot, sin_t, q_max, cos_t, gauss_top, inv_total));
        vm above = vf_lt(root, target); /* F(q) > u1 */
        hi = vf_select(above, q, hi);
        lo = vf_select(above, lo, q);
        vf slope = vf_mul(vf_mul(vf_set1(2.0f), vf_mul(sin_t, vf_sub(cot, x))), inv_total); /* dF/dq */
        vf next = vf_add(q, vf_div(vf_mul(vf_add(root, root), vf_sub(root, target)), vf_max(slope, vf_set1(1e-30f))));
        vm inside = vm_and(vf_ge(next, lo), vf_le(next, hi));
        q = vf_select(inside, next, vf_mul(vf_set1(0.5f), vf_add(lo, hi)));
    }
    x = vf_mul(vf_normal_quantile(q), inv_sqrt2);
    vf y = vf_mul(vf_normal_quantile(u2), inv_sqrt2);
    /* slopes turned to o's azimuth and unstretched; m = (-slope_x, -slope_y, 1) normalised */
    vf px = vf_mul(r, vf_fnma(sin_a, y, vf_mul(cos_a, x))), py = vf_mul(r, vf_fma(cos_a, y, vf_mul(sin_a, x)));
    vf norm = vf_div(one, vf_sqrt(vf_fma(px, px, vf_fma(py, py, one))));
    m[0] = vf_neg(vf_mul(px, norm));
    m[1] = vf_neg(vf_mul(py, norm));
    m[2] = norm;
}

/* Step 1: the azimuth psi = phi_m - phi_o of the mesonormal at an offset drawn uniformly (u0)
 * across the part of the projected width that w_o's window w covers. */
HB_INLINE void huang_sample_offset(const hb_huang *h, const huang_o_window *w, vf phi_o, vf u0, vf *sin_psi, vf *cos_psi)
{
    vf one = vf_set1(1.0f);
    if (h->elliptical) {
        /* on the circle the ellipse is the image of, the point of projected offset s sits at
         * gamma = chi + asin(s / a), chi the view's azimuth there; its normal is (b sin g, cos g) */
        vf sin_po, cos_po;
        vf_sincos(wrap_angle(phi_o), &sin_po, &cos_po);
        vf b = vf_set1(h->b);
        vf a = vf_sqrt(vf_fnma(vf_set1(h->e2), vf_mul(sin_po, sin_po), one));
        vf sin_d = vf_clamp(vf_div(vf_fma(u0, w->projected, w->lo_projected), a), -1.0f, 1.0f);
        vf cos_d = vf_sqrt(vf_fnma(sin_d, sin_d, one));
        vf cos_chi = vf_div(cos_po, a), sin_chi = vf_div(vf_mul(b, sin_po), a);
        vf sin_g = vf_fma(sin_chi, cos_d, vf_mul(cos_chi, sin_d)), cos_g = vf_fnma(sin_chi, sin_d, vf_mul(cos_chi, cos_d));
        vf nx = vf_mul(b, sin_g), nz = cos_g, inv = vf_div(one, vf_sqrt(vf_fma(nx, nx, vf_mul(nz, nz))));
        nx = vf_mul(nx, inv);
        nz = vf_mul(nz, inv);
        *sin_psi = vf_fnma(nz, sin_po, vf_mul(nx, cos_po));
        *cos_psi = vf_fma(nz, cos_po, vf_mul(nx, sin_po));
    } else {
        *sin_psi = vf_mul(vf_fma(vf_set1(2.0f), u0, vf_set1(-1.0f)), w->sin_half);
        *cos_psi = vf_sqrt(vf_max(vf_fnma(*sin_psi, *sin_psi, one), vf_set1(0.0f)));
    }
}

/* Steps 1-3: the direction w_i = (theta_i, phi_i) for w_o and u[0..2]. */
HB_INLINE void huang_sample_direction(const hb_huang *h, vf theta_o, vf phi_o, const vf u[3], vf *theta_i, vf *phi_i)
{
    vf sin_to, cos_to, sin_psi, cos_psi;
    vf_sincos(theta_o, &sin_to, &cos_to);
    cos_to = vf_max(cos_to, vf_set1(0.0f));
    huang_o_window w = huang_o_window_of(h, cos_to, sin_to, phi_o);
    huang_sample_offset(h, &w, phi_o, u[0], &sin_psi, &cos_psi);
    /* the mesonormal frame in the frame of w_o (phi_o = 0): w_m = (ct sin psi, st, ct cos psi),
     * t1 = (cos psi, 0, -sin psi), t2 = (-st sin psi, ct, -st cos psi) (eq. 39) */
    vf ct = vf_set1(h->cos_tilt), st = vf_set1(h->sin_tilt);
    vf o[3], m[3];
    o[0] = vf_neg(vf_mul(sin_psi, cos_to));
    o[1] = vf_fnma(st, vf_mul(cos_psi, cos_to), vf_mul(ct, sin_to));
    o[2] = vf_fma(ct, vf_mul(cos_psi, cos_to), vf_mul(st, sin_to));
    o[2] = vf_max(o[2], vf_set1(1e-30f));
    if (h->beckmann)
        beckmann_visible_normal(h, o, u[1], u[2], m);
    else
        ggx_visible_normal(h, o, u[1], u[2], m);
    /* step 3: reflect, then back to the frame of w_o */
    vf dot2 = vf_mul(vf_set1(2.0f), vf_fma(o[0], m[0], vf_fma(o[1], m[1], vf_mul(o[2], m[2]))));
    vf ix = vf_fma(dot2, m[0], vf_neg(o[0])), iy = vf_fma(dot2, m[1], vf_neg(o[1])), iz = vf_fma(dot2, m[2], vf_neg(o[2]));
    vf x = vf_fma(iz, vf_mul(ct, sin_psi), vf_fnma(iy, vf_mul(st, sin_psi), vf_mul(ix, cos_psi)));
    vf y = vf_fma(iy, ct, vf_mul(iz, st));
    vf z = vf_fma(iz, vf_mul(ct, cos_psi), vf_fnma(iy, vf_mul(st, cos_psi), vf_neg(vf_mul(ix, sin_psi))));
    vf planar = vf_sqrt(vf_fma(x, x, vf_mul(z, z)));
    *theta_i = vf_atan2(y, planar);
    *phi_i = wrap_angle(vf_add(phi_o, vf_atan2(x, z)));
}

/* Sampling with the pdf and the weight f / pdf at the (float) direction returned, by the same code
 * as hb_eval_angles and hb_pdf_angles. */
HB_INLINE void huang_sample(const hb_huang *h, vf theta_o, vf phi_o, const vf u[3], vf *theta_i, vf *phi_i, vf *pdf,
                            vf weight[3])
{
    huang_sample_direction(h, theta_o, phi_o, u, theta_i, phi_i);
    *pdf = huang_pdf_angles(h, *theta_i, *phi_i, theta_o, phi_o);
    huang_directions d = huang_directions_of_angles(h, *theta_i, *phi_i, theta_o, phi_o);
    vf f = huang_r(h, &d); /* the plan samples R-only plans */
    vm positive = vf_gt(*pdf, vf_set1(0.0f));
    vf inv = vf_div(vf_set1(1.0f), vf_select(positive, *pdf, vf_set1(1.0f)));
    for (int c = 0; c < 3; c++)
        weight[c] = vf_keep(positive, vf_mul(f, inv));
}

#endif

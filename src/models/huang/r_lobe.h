/* HHH22 R lobe over the SIMD vocabulary: f_R = S_R cos(theta_i) with S_R from eq. 12
 * (eq. 28 for elliptical fibres), the integral over the azimuth phi_m of the macro/mesonormal
 * taken over the part of the fibre both directions see, either in closed form (App. A) or by
 * composite Simpson with a node count the plan fixes. Everything is computed in the frame
 * turned about the fibre so that phi_i = 0; delta = phi_h - phi_m is the azimuth of the
 * mesonormal seen from the half vector's. docs/huang.md, has the derivations. */
#ifndef HB_HUANG_R_LOBE_H
#define HB_HUANG_R_LOBE_H

#include "microfacet.h"
#include "models/common/fresnel.h"

/* The two directions: inclinations and the azimuth between them, and for elliptical fibres
 * their absolute azimuths (the fibre's orientation). cos(theta) >= 0. */
typedef struct huang_directions {
    vf cos_ti, sin_ti, cos_to, sin_to;
    vf phi;                  /* phi_o - phi_i in [-pi, pi] */
    vf cos_phi, sin_phi;
    vf forward_gap;          /* pi - |phi|, to float accuracy also where it is tiny (the window's width there) */
    vf cos_phi_i, sin_phi_i; /* elliptical only */
    vf sin2_phi_o;           /* elliptical only */
    vf hx, hy, hz;           /* w_i + w_o, to float accuracy also where it nearly vanishes */
} huang_directions;

/* What the R integrand needs of a direction pair. */
typedef struct huang_r_geometry {
    vf cos_half;              /* w_i . w_h = w_o . w_h, |w_i + w_o| / 2 */
    vf cos_h_tilt, sin_h_tilt; /* cos(theta_h) cos(tau), sin(theta_h) sin(tau): x = w_h . w_m = cos_h_tilt cos(delta) + sin_h_tilt */
    vf one_minus_cos_minus;   /* 1 - cos(theta_h - tau), so 1 - x = this + 2 cos_h_tilt sin^2(delta / 2) */
    vf p_minus, p_plus;       /* App. A with A, B: 1 - A - B = 1 - C cos(theta_h - tau), 1 - B + A = 1 + C cos(theta_h + tau) */
    vf q_minus, q_plus;       /* 1 + B - A = 1 - C cos(theta_h + tau), 1 + B + A = 1 + C cos(theta_h - tau) */
    vf cos_phi_h, sin_phi_h;  /* azimuth of w_h (phi_i = 0) */
    vf phi_h, phi;            /* azimuths of w_h and of w_o (phi_i = 0) */
    vf delta_centre;          /* delta at the middle of the visible window (|delta| <= pi/2 inside it) */
    vf half_width;            /* half the window's width in phi_m (and delta), 0 where nothing is visible */
    vm visible;               /* the window is not empty */
} huang_r_geometry;

/* Half-angles of the window's ends delta_lo, delta_hi = centre -+ half width, from the centre and
 * the half width (so a narrow window keeps its width's digits). */
typedef struct huang_window_ends {
    vf cos_hi, sin_hi, cos_lo, sin_lo; /* of delta_hi / 2 and delta_lo / 2 */
    vf cc, ss;                         /* cos_hi cos_lo and sin_hi sin_lo */
    vf sin_width;                      /* sin((delta_hi - delta_lo) / 2) = sin(half width) */
} huang_window_ends;

HB_INLINE huang_window_ends window_ends(vf delta_centre, vf half_width)
{
    huang_window_ends e;
    vf cm, sm, cw, sw;
    vf_sincos(vf_mul(vf_set1(0.5f), delta_centre), &sm, &cm);
    vf_sincos(vf_mul(vf_set1(0.5f), half_width), &sw, &cw);
    vf a = vf_mul(cm, cw), b = vf_mul(sm, sw), c = vf_mul(sm, cw), d = vf_mul(cm, sw);
    e.cos_hi = vf_sub(a, b);
    e.cos_lo = vf_add(a, b);
    e.sin_hi = vf_add(c, d);
    e.sin_lo = vf_sub(c, d);
    e.cc = vf_fnma(b, b, vf_mul(a, a));
    e.ss = vf_fnma(d, d, vf_mul(c, c));
    e.sin_width = vf_mul(vf_set1(2.0f), vf_mul(sw, cw));
    return e;
}

/* 1 - cos(x) from sin(x) and cos(x) without cancellation: sin^2 / (1 + cos) for cos > 0. */
HB_INLINE vf one_minus_cos(vf s, vf c)
{
    vf one = vf_set1(1.0f);
    return vf_select(vf_gt(c, vf_set1(0.0f)), vf_div(vf_mul(s, s), vf_add(one, c)), vf_sub(one, c));
}

/* The azimuths phi_m (around the direction's own) from which a direction of inclination theta sees
 * both the macronormal (cos(phi - phi_m) >= 0) and the mesonormal (cos(phi - phi_m) >= -tan(theta)
 * tan(tau)), HHH22 sec. 3.2 and eq. 40, are |phi - phi_m| <= pi/2 - cut; this returns cut =
 * asin(max(0, -tan(theta) tan(tau))) (so pi/2 itself never enters a sum), *seen false where no phi_m
 * qualifies. */
HB_INLINE vf visible_cut(const hb_huang *h, vf cos_t, vf sin_t, vm *seen)
{
    if (!h->tilted) {
        *seen = vf_eq(cos_t, cos_t); /* every lane (cos_t is never NaN) */
        return vf_set1(0.0f);
    }
    vf bound = vf_mul(vf_neg(sin_t), vf_set1(h->sin_tilt)), scale = vf_mul(cos_t, vf_set1(h->cos_tilt));
    *seen = vf_le(bound, scale);
    vf ratio = vf_div(vf_max(bound, vf_set1(0.0f)), vf_max(scale, vf_set1(1e-30f)));
    return vf_asin(vf_min(ratio, vf_set1(1.0f)));
}

HB_INLINE huang_r_geometry huang_r_geometry_of(const hb_huang *h, const huang_directions *d)
{
    huang_r_geometry g;
    vf one = vf_set1(1.0f), zero = vf_set1(0.0f);
    vf hx = d->hx, hy = d->hy, hz = d->hz;
    vf planar = vf_sqrt(vf_fma(hx, hx, vf_mul(hz, hz)));
    vf norm = vf_sqrt(vf_fma(hy, hy, vf_mul(planar, planar)));
    g.cos_half = vf_mul(vf_set1(0.5f), norm);
    vf inv_norm = vf_div(one, vf_max(norm, vf_set1(1e-30f)));
    vf cos_h = vf_mul(planar, inv_norm), sin_h = vf_mul(hy, inv_norm);
    vm has_azimuth = vf_gt(planar, vf_set1(1e-30f));
    vf inv_planar = vf_div(one, vf_max(planar, vf_set1(1e-30f)));
    g.cos_phi_h = vf_select(has_azimuth, vf_mul(hz, inv_planar), one);
    g.sin_phi_h = vf_select(has_azimuth, vf_mul(hx, inv_planar), zero);
    g.phi_h = vf_atan2(hx, hz);
    /* theta_h -+ tau, and the App. A factors in cancellation-free form (1 - A - B =
     * r^2 / (1 + C) + C (1 - cos(theta_h - tau)), which cancels at small roughness) */
    vf ct = vf_set1(h->cos_tilt), st = vf_set1(h->sin_tilt);
    g.cos_h_tilt = vf_mul(cos_h, ct);
    g.sin_h_tilt = vf_mul(sin_h, st);
    vf cos_minus = vf_add(g.cos_h_tilt, g.sin_h_tilt), sin_minus = vf_fnma(cos_h, st, vf_mul(sin_h, ct));
    vf cos_plus = vf_sub(g.cos_h_tilt, g.sin_h_tilt), sin_plus = vf_fma(cos_h, st, vf_mul(sin_h, ct));
    g.one_minus_cos_minus = one_minus_cos(sin_minus, cos_minus);
    vf one_minus_cos_plus = one_minus_cos(sin_plus, cos_plus);
    vf c_rough = vf_set1(h->c_rough), one_minus_c = vf_set1(h->one_minus_c);
    g.p_minus = vf_fma(c_rough, g.one_minus_cos_minus, one_minus_c);
    g.q_minus = vf_fma(c_rough, one_minus_cos_plus, one_minus_c);
    g.p_plus = vf_fma(c_rough, cos_plus, one);
    g.q_plus = vf_fma(c_rough, cos_minus, one);
    /* the window: the arcs |phi_m| <= pi/2 - cut_i and |phi_m - phi| <= pi/2 - cut_o overlap over
     * min(pi - 2 cut_i, pi - 2 cut_o, (pi - |phi|) - cut_i - cut_o), the last term accurate where
     * the directions nearly oppose each other (the forward focus of sec. 4.1.1) */
    vm seen_i, seen_o;
    vf cut_i = visible_cut(h, d->cos_ti, d->sin_ti, &seen_i), cut_o = visible_cut(h, d->cos_to, d->sin_to, &seen_o);
    vf width = vf_min(vf_sub(vf_set1(HB_PI_F), vf_add(vf_max(cut_i, cut_o), vf_max(cut_i, cut_o))),
                      vf_sub(d->forward_gap, vf_add(cut_i, cut_o)));
    g.visible = vm_and(vm_and(seen_i, seen_o), vf_gt(width, vf_set1(0.0f)));
    g.half_width = vf_keep(g.visible, vf_mul(vf_set1(0.5f), width));
    g.phi = d->phi;
    vf phi = g.phi, half_i = vf_sub(vf_set1(HB_PIO2_F), cut_i);
    vf half_o = vf_sub(vf_set1(HB_PIO2_F), cut_o);
    vf lo = vf_max(vf_neg(half_i), vf_sub(phi, half_o)), hi = vf_min(half_i, vf_add(phi, half_o));
    g.delta_centre = wrap_angle(vf_sub(g.phi_h, vf_mul(vf_set1(0.5f), vf_add(lo, hi))));
    return g;
}

/* integral of D(w_h, w_m) d phi_m over the window for GGX without G (HHH22 App. A, eq. 43), in a
 * form without branch cuts or cancellation. With p = 1 - B - A cos(delta), q = 1 + B + A cos(delta),
 * p + q = 2, the integrand r^2 / (pi p^2 q^2) = r^2 / (4 pi) (1/p^2 + 1/q^2 + 1/p + 1/q), and
 *   int 1/p   = 2 / sqrt(P- P+) atan(sqrt(P+ / P-) tan(delta / 2)),   P-+ = 1 - B -+ A,
 *   int 1/p^2 = (1 - B) / (P- P+) int 1/p + A sin(delta) / (P- P+ p),
 * (q likewise with A -> -A). Differences of the arctangents between delta_lo and delta_hi are one
 * atan2 (so there is no branch of tan(delta / 2) to cross), and differences of sin(delta) / p are
 * written over a common denominator from half-angle products. */
/* For u = a - A cos(delta) = near cos^2(delta/2) + far sin^2(delta/2) (near = a - A, far = a + A):
 * the integral of 1/u over the window, 2 / sqrt(near far) times one atan2, and the difference of
 * sin(delta) / u between its ends, over a common denominator. */
HB_INLINE void reciprocal_terms(const huang_window_ends *e, vf near, vf far, vf *integral, vf *sin_over)
{
    vf root = vf_sqrt(vf_mul(near, far));
    vf arc = vf_atan2(vf_mul(root, e->sin_width), vf_fma(near, e->cc, vf_mul(far, e->ss)));
    *integral = vf_div(vf_add(arc, arc), root);
    vf at_hi = vf_fma(near, vf_mul(e->cos_hi, e->cos_hi), vf_mul(far, vf_mul(e->sin_hi, e->sin_hi)));
    vf at_lo = vf_fma(near, vf_mul(e->cos_lo, e->cos_lo), vf_mul(far, vf_mul(e->sin_lo, e->sin_lo)));
    *sin_over = vf_div(vf_mul(vf_add(e->sin_width, e->sin_width), vf_fnma(far, e->ss, vf_mul(near, e->cc))),
                       vf_mul(at_hi, at_lo));
}

HB_INLINE vf r_integral_ggx_analytic(const hb_huang *h, const huang_r_geometry *g)
{
    vf one = vf_set1(1.0f), int_p, sin_over_p, int_q, sin_over_q;
    huang_window_ends e = window_ends(g->delta_centre, g->half_width);
    vf a_coef = vf_mul(g->cos_h_tilt, vf_set1(h->c_rough)), b_coef = vf_mul(g->sin_h_tilt, vf_set1(h->c_rough));
    reciprocal_terms(&e, g->p_minus, g->p_plus, &int_p, &sin_over_p); /* p = (1 - B) - A cos(delta) */
    reciprocal_terms(&e, g->q_plus, g->q_minus, &int_q, &sin_over_q); /* q = (1 + B) + A cos(delta) */
    /* 1 / (P- P+) and 1 / (Q- Q+) from one division: each factor lies in [1 - c, 2], 1 - c about
     * roughness^2 / 2 >= 5e-7, so the product of all four stays within [6e-26, 16] */
    vf pp = vf_mul(g->p_minus, g->p_plus), qq = vf_mul(g->q_minus, g->q_plus);
    vf inv_ppqq = vf_div(one, vf_mul(pp, qq));
    vf inv_pp = vf_mul(qq, inv_ppqq), inv_qq = vf_mul(pp, inv_ppqq);
    vf sum_p = vf_fma(vf_fma(vf_sub(one, b_coef), inv_pp, one), int_p, vf_mul(vf_mul(a_coef, inv_pp), sin_over_p));
    vf sum_q = vf_fnma(vf_mul(a_coef, inv_qq), sin_over_q, vf_mul(vf_fma(vf_add(one, b_coef), inv_qq, one), int_q));
    return vf_mul(vf_set1(h->roughness2 * 0.25f * HB_INV_PI_F), vf_add(sum_p, sum_q));
}

/* The arc length per unit phi_m of an elliptical fibre, rho = b^2 / (1 - e^2 cos^2 phi_m)^(3/2)
 * (eq. 26 after the change of variable gamma -> phi_m, tan(phi_m) = b tan(gamma)), at the mesonormal
 * azimuth (cos_m, sin_m) in the frame phi_i = 0. */
HB_INLINE vf arc_length_rho(const hb_huang *h, const huang_directions *d, vf cos_m, vf sin_m)
{
    vf cos_abs = vf_fnma(d->sin_phi_i, sin_m, vf_mul(d->cos_phi_i, cos_m));
    vf q = vf_fnma(vf_set1(h->e2), vf_mul(cos_abs, cos_abs), vf_set1(1.0f));
    return vf_div(vf_set1(h->b2), vf_mul(q, vf_sqrt(q)));
}

/* D G rho at one phi_m = phi_h - delta of the window, given sin^2(delta / 2), cos(delta), sin(delta):
 * the NDF at the mesonormal, Smith G1(w_i) G1(w_o) against it (eq. 12), and for elliptical fibres
 * the arc length rho. GGX's D and the two G1 are one fraction, one division: its denominator is at
 * least r^4 (d_i + y_i)(d_o + y_o) >= r^8 > 1e-24 (microfacet.h); Beckmann's D, whose denominator
 * reaches 1e-36, is divided alone. */
HB_INLINE vf r_integrand(const hb_huang *h, const huang_directions *d, const huang_r_geometry *g, vf sin2_half,
                         vf cos_delta, vf sin_delta)
{
    vf one_minus_x = vf_fma(vf_add(g->cos_h_tilt, g->cos_h_tilt), sin2_half, g->one_minus_cos_minus);
    if (!h->shadowing && !h->elliptical)
        return ndf_huang(h, one_minus_x);
    vf num = vf_set1(1.0f), den = vf_set1(1.0f);
    if (h->beckmann)
        num = ndf_huang(h, one_minus_x);
    else
        ndf_ggx_ratio(h, one_minus_x, &num, &den);
    vf cos_m = vf_fma(g->cos_phi_h, cos_delta, vf_mul(g->sin_phi_h, sin_delta));
    vf sin_m = vf_fnma(g->cos_phi_h, sin_delta, vf_mul(g->sin_phi_h, cos_delta));
    if (h->shadowing) {
        vf ct = vf_set1(h->cos_tilt), st = vf_set1(h->sin_tilt), g_num, g_den;
        vf macro_i = vf_mul(d->cos_ti, cos_m);
        vf macro_o = vf_mul(d->cos_to, vf_fma(d->cos_phi, cos_m, vf_mul(d->sin_phi, sin_m)));
        vf meso_i = vf_fma(ct, macro_i, vf_mul(st, d->sin_ti)), meso_o = vf_fma(ct, macro_o, vf_mul(st, d->sin_to));
        smith_g1_pair_ratio(h, meso_i, meso_o, &g_num, &g_den);
        num = vf_mul(num, g_num);
        den = vf_mul(den, g_den);
    }
    vf value = vf_div(num, den);
    if (h->elliptical)
        value = vf_mul(value, arc_length_rho(h, d, cos_m, sin_m));
    return value;
}

/* The sampling density's integrand at phi_m = phi_h - delta (docs/sampling.md): the density
 * of phi_m, cos(phi_m - phi_o) rho over the window's projected width (applied by the caller),
 * times the visible normals' density mapped to w_i, G1(w_o) D / (4 w_o . w_m) (Heitz 2014; the 4 is
 * applied by the caller). G1 / (w_o . w_m) stays finite at the window's ends. The window keeps
 * w_h . w_m >= 0, where D is the NDF. */
HB_INLINE vf pdf_integrand(const hb_huang *h, const huang_directions *d, const huang_r_geometry *g, vf sin2_half,
                           vf cos_delta, vf sin_delta)
{
    vf one_minus_x = vf_fma(vf_add(g->cos_h_tilt, g->cos_h_tilt), sin2_half, g->one_minus_cos_minus);
    vf cos_m = vf_fma(g->cos_phi_h, cos_delta, vf_mul(g->sin_phi_h, sin_delta));
    vf sin_m = vf_fnma(g->cos_phi_h, sin_delta, vf_mul(g->sin_phi_h, cos_delta));
    vf cos_psi = vf_max(vf_fma(d->cos_phi, cos_m, vf_mul(d->sin_phi, sin_m)), vf_set1(0.0f)); /* phi_m - phi_o */
    vf meso_o = vf_fma(vf_set1(h->cos_tilt), vf_mul(d->cos_to, cos_psi), vf_mul(vf_set1(h->sin_tilt), d->sin_to));
    vf value = vf_mul(vf_mul(ndf_huang(h, one_minus_x), cos_psi), smith_g1_over_cos(h, meso_o));
    if (h->elliptical)
        value = vf_mul(value, arc_length_rho(h, d, cos_m, sin_m));
    return value;
}

/* The peak-following variable t, tan(t / 2) = sqrt(P+ / P-) tan(delta / 2): the substitution that
 * turns GGX's 1/p^2 peak into a bounded, smooth integrand (d delta / dt = sqrt(P- P+) / (P+ cos^2(t/2) +
 * P- sin^2(t/2))), so a fixed number of panels serves every roughness and every window. A window
 * [delta_lo, delta_hi] becomes half-angles t_lo / 2 and (t_hi - t_lo) / 2, the latter one atan2 (App.
 * A's arctangent difference), so that narrow windows keep their width's digits. */
typedef struct huang_t_piece {
    vf half_lo, half_span;
} huang_t_piece;

HB_INLINE huang_t_piece t_piece_of(const huang_r_geometry *g, vf delta_centre, vf half_width)
{
    huang_t_piece t;
    huang_window_ends e = window_ends(delta_centre, half_width);
    vf root_m = vf_sqrt(g->p_minus), root_p = vf_sqrt(g->p_plus);
    t.half_lo = vf_atan2(vf_mul(root_p, e.sin_lo), vf_mul(root_m, e.cos_lo));
    t.half_span = vf_atan2(vf_mul(vf_mul(root_m, root_p), e.sin_width), vf_fma(g->p_minus, e.cc, vf_mul(g->p_plus, e.ss)));
    return t;
}

/* Composite Simpson with `panels` panels over a piece of t, of eval's integrand (r_integrand) or
 * the sampling pdf's (pdf_integrand). The half-angles of the nodes come from a rotation
 * recurrence, one sincos per piece. */
HB_INLINE vf mapped_simpson(const hb_huang *h, const huang_directions *d, const huang_r_geometry *g, huang_t_piece t,
                            int panels, int pdf)
{
    vf one = vf_set1(1.0f), root_mp = vf_sqrt(vf_mul(g->p_minus, g->p_plus));
    vf half_step = vf_div(t.half_span, vf_set1((float)panels));
    vf c, s, cr, sr;
    vf_sincos(t.half_lo, &s, &c);
    vf_sincos(half_step, &sr, &cr);
    vf sum = vf_set1(0.0f);
    for (int j = 0; j <= panels; j++) {
        float w = (j == 0 || j == panels) ? 1.0f : (j & 1) ? 4.0f : 2.0f;
        vf pc2 = vf_mul(g->p_plus, vf_mul(c, c)), ms2 = vf_mul(g->p_minus, vf_mul(s, s));
        vf inv_den = vf_div(one, vf_add(pc2, ms2));
        vf sin2_half = vf_mul(ms2, inv_den);
        vf cos_delta = vf_mul(vf_sub(pc2, ms2), inv_den);
        vf sin_delta = vf_mul(vf_mul(vf_set1(2.0f), vf_mul(root_mp, vf_mul(c, s))), inv_den);
        vf jacobian = vf_mul(root_mp, inv_den);
        vf value = pdf ? pdf_integrand(h, d, g, sin2_half, cos_delta, sin_delta)
                       : r_integrand(h, d, g, sin2_half, cos_delta, sin_delta);
        sum = vf_fma(vf_set1(w), vf_mul(value, jacobian), sum);
        vf c_next = vf_fnma(s, sr, vf_mul(c, cr));
        s = vf_fma(c, sr, vf_mul(s, cr));
        c = c_next;
    }
    /* dt = 2 d(t/2), Simpson's h / 3 */
    return vf_mul(sum, vf_mul(half_step, vf_set1(2.0f / 3.0f)));
}

HB_STAGE vf r_integral_mapped(const hb_huang *h, const huang_directions *d, const huang_r_geometry *g)
{
    return mapped_simpson(h, d, g, t_piece_of(g, g->delta_centre, g->half_width), h->panels, 0);
}

/* The paper's rule (HHH22 sec. 3.4.2): Simpson in phi_m with an even number of panels n per
 * sample, the fewest with steps <= step. Every sample runs the plan's panel count (the most
 * any window needs) with the nodes past its own n weighted 0, so the cost is fixed. */
HB_STAGE vf r_integral_steps(const hb_huang *h, const huang_directions *d, const huang_r_geometry *g)
{
    vf width = vf_add(g->half_width, g->half_width), delta_lo = vf_sub(g->delta_centre, g->half_width);
    vf n = vf_mul(vf_set1(-2.0f), vf_floor(vf_div(width, vf_set1(-2.0f * h->step)))); /* 2 ceil(width / 2 step) */
    n = vf_clamp(n, 2.0f, (float)h->panels);
    vf step = vf_div(width, n), sum = vf_set1(0.0f);
    for (int j = 0; j <= h->panels; j++) {
        vf jf = vf_set1((float)j);
        vf w = vf_select(vf_eq(jf, n), vf_set1(1.0f), vf_set1(j == 0 ? 1.0f : (j & 1) ? 4.0f : 2.0f));
        w = vf_select(vf_gt(jf, n), vf_set1(0.0f), w);
        vf s, c;
        vf_sincos(vf_mul(vf_set1(0.5f), vf_fma(jf, step, delta_lo)), &s, &c);
        vf sin2_half = vf_mul(s, s);
        vf cos_delta = vf_fnma(vf_set1(2.0f), sin2_half, vf_set1(1.0f));
        vf sin_delta = vf_mul(vf_set1(2.0f), vf_mul(s, c));
        sum = vf_fma(w, r_integrand(h, d, g, sin2_half, cos_delta, sin_delta), sum);
    }
    return vf_mul(sum, vf_mul(step, vf_set1(1.0f / 3.0f)));
}

/* f_R = F(w_o . w_h) / (8 cos(theta_o) a) * integral, a = sqrt(1 - e^2 sin^2 phi_o) the fibre's
 * projected half width (eqs. 12, 27, 28; f = S cos(theta_i)). */
HB_INLINE vf huang_r(const hb_huang *h, const huang_directions *d)
{
    huang_r_geometry g = huang_r_geometry_of(h, d);
    vf integral = h->analytic ? r_integral_ggx_analytic(h, &g)
                  : h->step_rule ? r_integral_steps(h, d, &g) : r_integral_mapped(h, d, &g);
    vf fresnel = fresnel_dielectric(vf_min(g.cos_half, vf_set1(1.0f)), &h->ior);
    vf den = vf_set1(8.0f);
    if (h->elliptical)
        den = vf_mul(den, vf_sqrt(vf_fnma(vf_set1(h->e2), d->sin2_phi_o, vf_set1(1.0f))));
    vf width = huang_width_factor(h, d->cos_ti, d->cos_to);
    vf f = vf_div(vf_mul(vf_mul(fresnel, vf_max(integral, vf_set1(0.0f))), width), den);
    return vf_keep(g.visible, f);
}

/* The directions of an angle pair. */
HB_INLINE huang_directions huang_directions_of_angles(const hb_huang *h, vf theta_i, vf phi_i, vf theta_o, vf phi_o)
{
    huang_directions d;
    vf_sincos(theta_i, &d.sin_ti, &d.cos_ti);
    vf_sincos(theta_o, &d.sin_to, &d.cos_to);
    d.cos_ti = vf_max(d.cos_ti, vf_set1(0.0f));
    d.cos_to = vf_max(d.cos_to, vf_set1(0.0f));
    /* phi = phi_o - phi_i with its rounding error (two-sum), wrapped: exact for |phi_i|, |phi_o| <= pi,
     * so pi - |phi| keeps its digits near the forward direction */
    vf diff = vf_sub(phi_o, phi_i), back = vf_sub(diff, phi_o);
    vf rounding = vf_sub(vf_sub(phi_o, vf_sub(diff, back)), vf_add(phi_i, back));
    vf turns = vf_round(vf_mul(diff, vf_set1(0.159154943f)));
    vf phi = vf_fnma(turns, vf_set1(HB_TWO_PI_F), diff), phi_low = vf_fnma(turns, vf_set1(HB_TWO_PI_LO), rounding);
    d.forward_gap = vf_add(vf_sub(vf_set1(HB_PI_F), vf_abs(phi)), vf_fnma(vf_copysign(vf_set1(1.0f), phi), phi_low,
                                                                          vf_set1(HB_PI_LO)));
    d.phi = vf_add(phi, phi_low);
    vf_sincos(d.phi, &d.sin_phi, &d.cos_phi);
    /* w_i = (0, sin theta_i, cos theta_i), w_o = (sin phi cos theta_o, sin theta_o, cos phi cos theta_o) */
    d.hx = vf_mul(d.sin_phi, d.cos_to);
    d.hy = vf_add(d.sin_ti, d.sin_to);
    d.hz = vf_fma(d.cos_phi, d.cos_to, d.cos_ti);
    d.cos_phi_i = vf_set1(1.0f);
    d.sin_phi_i = d.sin2_phi_o = vf_set1(0.0f);
    if (h->elliptical) {
        vf s, c;
        vf_sincos(wrap_angle(phi_i), &d.sin_phi_i, &d.cos_phi_i);
        vf_sincos(wrap_angle(phi_o), &s, &c);
        d.sin2_phi_o = vf_mul(s, s);
    }
    return d;
}

/* From unit vectors (within HB_UNIT_TOLERANCE). The sum w_i + w_o, normalised and turned to the
 * frame phi_i = 0, and pi - |phi| are formed in double: products of floats are exact there, so both
 * keep their digits where w_o is nearly -w_i (the forward focus), which float rounding of the
 * normalisation alone would blur by 6e-8. */
HB_INLINE huang_directions huang_directions_of_vectors(const vf wi[3], const vf wo[3])
{
    huang_directions d;
    vf one = vf_set1(1.0f), zero = vf_set1(0.0f), tiny = vf_set1(1e-30f);
    vdw i[3], o[3];
    for (int k = 0; k < 3; k++) {
        i[k] = vdw_from_vf(wi[k]);
        o[k] = vdw_from_vf(wo[k]);
    }
    vdw planar2_i = vdw_fma(i[0], i[0], vdw_mul(i[2], i[2])), planar2_o = vdw_fma(o[0], o[0], vdw_mul(o[2], o[2]));
    vdw inv_i = vdw_div(vdw_set1(1.0), vdw_sqrt(vdw_fma(i[1], i[1], planar2_i)));
    vdw inv_o = vdw_div(vdw_set1(1.0), vdw_sqrt(vdw_fma(o[1], o[1], planar2_o)));
    vdw planar_i = vdw_sqrt(planar2_i);
    /* the azimuth of w_i: (sin, cos) = (x, z) / planar, (0, 1) on the axis */
    vdw inv_planar_i = vdw_div(vdw_set1(1.0), vdw_max(planar_i, vdw_set1(1e-300)));
    vm azimuth_i = vf_gt(vdw_to_vf(planar_i), tiny);
    vdw cos_pi = vdw_mul(i[2], inv_planar_i), sin_pi = vdw_mul(i[0], inv_planar_i);
    d.cos_phi_i = vf_select(azimuth_i, vdw_to_vf(cos_pi), one);
    d.sin_phi_i = vf_select(azimuth_i, vdw_to_vf(sin_pi), zero);
    cos_pi = vdw_from_vf(d.cos_phi_i);
    sin_pi = vdw_from_vf(d.sin_phi_i);
    vdw hx = vdw_fma(i[0], inv_i, vdw_mul(o[0], inv_o)), hz = vdw_fma(i[2], inv_i, vdw_mul(o[2], inv_o));
    d.hy = vdw_to_vf(vdw_fma(i[1], inv_i, vdw_mul(o[1], inv_o)));
    d.hx = vdw_to_vf(vdw_sub(vdw_mul(hx, cos_pi), vdw_mul(hz, sin_pi))); /* turned by -phi_i */
    d.hz = vdw_to_vf(vdw_fma(hx, sin_pi, vdw_mul(hz, cos_pi)));
    d.cos_ti = vdw_to_vf(vdw_mul(planar_i, inv_i));
    d.sin_ti = vdw_to_vf(vdw_mul(i[1], inv_i));
    vf planar_o = vdw_to_vf(vdw_sqrt(planar2_o));
    d.cos_to = vdw_to_vf(vdw_mul(vdw_sqrt(planar2_o), inv_o));
    d.sin_to = vdw_to_vf(vdw_mul(o[1], inv_o));
    vm azimuth_o = vf_gt(planar_o, tiny);
    vf inv_po = vf_div(one, vf_max(planar_o, tiny));
    vf cos_phi_o = vf_select(azimuth_o, vf_mul(wo[2], inv_po), one);
    vf sin_phi_o = vf_select(azimuth_o, vf_mul(wo[0], inv_po), zero);
    d.cos_phi = vf_fma(cos_phi_o, d.cos_phi_i, vf_mul(sin_phi_o, d.sin_phi_i));
    d.sin_phi = vf_fnma(cos_phi_o, d.sin_phi_i, vf_mul(sin_phi_o, d.cos_phi_i));
    d.sin2_phi_o = vf_mul(sin_phi_o, sin_phi_o);
    d.phi = vf_atan2(d.sin_phi, d.cos_phi);
    /* pi - |phi| = atan2(|P_i x P_o|, -P_i . P_o) of the planar parts */
    vf cross = vdw_to_vf(vdw_sub(vdw_mul(i[2], o[0]), vdw_mul(i[0], o[2])));
    vf dot = vdw_to_vf(vdw_fma(i[0], o[0], vdw_mul(i[2], o[2])));
    d.forward_gap = vf_select(vm_and(azimuth_i, azimuth_o), vf_atan2(vf_abs(cross), vf_neg(dot)),
                              vf_sub(vf_set1(HB_PI_F), vf_abs(d.phi)));
    return d;
}

#endif

/* HHH22 TT and TRT lobes over the SIMD vocabulary, by the paper's combined Monte-Carlo/Simpson
 * estimator (eqs. 31, 32; eqs. 29, 30 for elliptical fibres): composite Simpson over the azimuth
 * phi_m1 of the entry point's mesonormal, and at each node one internal path drawn with visible
 * normals (Heitz and d'Eon 2014) from the counter-based generator, connected to w_o through the
 * exit microfacet's generalised half vector. Worked in the fibre frame (absolute azimuths), the
 * chords of the cross-section x = sin g, z = b cos g (b = 1: a circle) traced exactly. docs/huang.md
 * "Huang 2022 TT and TRT" has the derivation; reference_internal.c is the same path in double. */
#ifndef HB_HUANG_INTERNAL_H
#define HB_HUANG_INTERNAL_H

#include "sample.h"
#include "rng.h"

typedef struct v3 {
    vf x, y, z;
} v3;

HB_INLINE vf v3_dot(v3 a, v3 b) { return vf_fma(a.x, b.x, vf_fma(a.y, b.y, vf_mul(a.z, b.z))); }
HB_INLINE v3 v3_axpy(vf s, v3 a, v3 b) /* s a + b */
{
    v3 r = { vf_fma(s, a.x, b.x), vf_fma(s, a.y, b.y), vf_fma(s, a.z, b.z) };
    return r;
}
HB_INLINE v3 v3_scale(vf s, v3 a)
{
    v3 r = { vf_mul(s, a.x), vf_mul(s, a.y), vf_mul(s, a.z) };
    return r;
}
/* 1 - a . b = |a - b|^2 / 2 for unit a, b: no cancellation near a narrow NDF's peak. */
HB_INLINE vf v3_one_minus_dot(v3 a, v3 b)
{
    vf dx = vf_sub(a.x, b.x), dy = vf_sub(a.y, b.y), dz = vf_sub(a.z, b.z);
    return vf_mul(vf_set1(0.5f), vf_fma(dx, dx, vf_fma(dy, dy, vf_mul(dz, dz))));
}

/* A point of the fibre's surface: where it is (x, z) and its normals, given the azimuth of its
 * macronormal: the macronormal (sin phi_m, 0, cos phi_m), the mesonormal tilted by tau (eq. 39) and
 * a tangent pair completing the mesonormal's frame. */
typedef struct fibre_point {
    vf px, pz;
    v3 macro, meso, t1, t2;
} fibre_point;

HB_INLINE fibre_point fibre_point_of_normal(const hb_huang *h, vf cos_m, vf sin_m, vf px, vf pz)
{
    vf ct = vf_set1(h->cos_tilt), st = vf_set1(h->sin_tilt), zero = vf_set1(0.0f);
    fibre_point p;
    p.px = px;
    p.pz = pz;
    p.macro = (v3){ sin_m, zero, cos_m };
    p.meso = (v3){ vf_mul(ct, sin_m), st, vf_mul(ct, cos_m) };
    p.t1 = (v3){ cos_m, zero, vf_neg(sin_m) };
    p.t2 = (v3){ vf_neg(vf_mul(st, sin_m)), ct, vf_neg(vf_mul(st, cos_m)) };
    return p;
}

/* The point of x = sin g, z = b cos g whose normal has azimuth phi_m: (sin, b^2 cos) / k,
 * k = sqrt(sin^2 + b^2 cos^2). */
HB_INLINE fibre_point entry_point(const hb_huang *h, vf cos_m, vf sin_m)
{
    vf b2 = vf_set1(h->b2);
    vf inv_k = vf_div(vf_set1(1.0f), vf_sqrt(vf_fma(b2, vf_mul(cos_m, cos_m), vf_mul(sin_m, sin_m))));
    return fibre_point_of_normal(h, cos_m, sin_m, vf_mul(sin_m, inv_k), vf_mul(vf_mul(b2, cos_m), inv_k));
}

/* The chord from p along the internal direction w: the exit point (in the coordinates where the
 * cross-section is the unit circle, z / b, the chord parameter is -2 P'.d' / |d'|^2), its outward
 * normal (x, z / b^2) normalised, and the path length inside, planar length / cos(theta_t). */
HB_INLINE fibre_point chord_exit(const hb_huang *h, const fibre_point *p, v3 w, vf *length)
{
    vf one = vf_set1(1.0f), tiny = vf_set1(1e-30f), inv_b2 = vf_set1(1.0f / h->b2);
    vf planar = vf_sqrt(vf_fma(w.x, w.x, vf_mul(w.z, w.z)));
    vf inv_planar = vf_div(one, vf_max(planar, tiny));
    vf dx = vf_mul(w.x, inv_planar), dz = vf_mul(w.z, inv_planar);
    vf num = vf_fma(p->px, dx, vf_mul(vf_mul(p->pz, dz), inv_b2));
    vf den = vf_fma(dx, dx, vf_mul(vf_mul(dz, dz), inv_b2));
    vf s = vf_max(vf_div(vf_mul(vf_set1(-2.0f), num), den), vf_set1(0.0f));
    vf qx = vf_fma(s, dx, p->px), qz = vf_fma(s, dz, p->pz);
    vf nx = qx, nz = vf_mul(qz, inv_b2);
    vf inv_n = vf_div(one, vf_max(vf_sqrt(vf_fma(nx, nx, vf_mul(nz, nz))), tiny));
    *length = vf_div(s, vf_max(planar, tiny));
    return fibre_point_of_normal(h, vf_mul(nz, inv_n), vf_mul(nx, inv_n), qx, qz);
}

/* A visible normal of the direction `toward` (pointing away from the side the normal faces) at
 * a point, on the outer side (side = 1) or the inner side (side = -1) of the mesosurface. */
HB_INLINE v3 visible_micronormal(const hb_huang *h, const fibre_point *p, v3 toward, float side, vf u1, vf u2)
{
    vf o[3], m[3], s = vf_set1(side);
    o[0] = vf_mul(s, v3_dot(toward, p->t1));
    o[1] = v3_dot(toward, p->t2);
    o[2] = vf_max(vf_mul(s, v3_dot(toward, p->meso)), vf_set1(1e-30f));
    if (h->beckmann)
        beckmann_visible_normal(h, o, u1, u2, m);
    else
        ggx_visible_normal(h, o, u1, u2, m);
    v3 r = v3_scale(vf_mul(s, m[0]), p->t1);
    r = v3_axpy(m[1], p->t2, r);
    return v3_axpy(vf_mul(s, m[2]), p->meso, r);
}

/* 1 - F entering at cos_i (<= 1), never below 0 where rounding puts F a hair above 1 at grazing. */
HB_INLINE vf fresnel_transmittance(const hb_huang *h, vf cos_i)
{
    vf f = fresnel_dielectric(vf_min(cos_i, vf_set1(1.0f)), &h->ior);
    return vf_max(vf_sub(vf_set1(1.0f), f), vf_set1(0.0f));
}

/* Reflectance at a smooth interface met from inside the fibre at cos_in: 1 past the critical
 * angle (total internal reflection), else Fresnel at the outside angle (F is the same both ways). */
HB_INLINE vf fresnel_from_inside(const hb_huang *h, vf cos_in)
{
    vf sin2_out = vf_mul(vf_set1(h->ior.eta * h->ior.eta), vf_fnma(cos_in, cos_in, vf_set1(1.0f)));
    vf cos_out = vf_sqrt(vf_max(vf_sub(vf_set1(1.0f), sin2_out), vf_set1(0.0f)));
    return vf_select(vf_ge(sin2_out, vf_set1(1.0f)), vf_set1(1.0f), fresnel_dielectric(cos_out, &h->ior));
}

/* The weight of a visible-normal sample through an interface: what its BSDF times the outgoing
 * cosine over the sample's density leaves besides the Fresnel factor (Heitz 2014): G1 of the
 * outgoing direction with shadowing, 1 / G1 of the incoming one without. TT and TRT keep G at every
 * interface (docs/huang.md): with G = 1 their integrals diverge as a path grazes the mesosurface,
 * so this serves the R reflection; the internal interfaces use G1 of the outgoing direction. */
HB_INLINE vf sampled_shadowing(const hb_huang *h, vf cos_in, vf cos_out)
{
    if (h->shadowing)
        return smith_g1_huang(h, cos_out);
    return vf_div(vf_set1(1.0f), vf_max(smith_g1_huang(h, cos_in), vf_set1(1e-30f)));
}

/* The outward micronormal at an exit that refracts w (inside) into d (outside): the generalised
 * half vector (eta w - d) / |eta w - d| (Walter et al. 2007), with |eta w - d|^2 in *len2. */
HB_INLINE v3 exit_half_vector(const hb_huang *h, v3 w, v3 d, vf *len2)
{
    v3 half = v3_axpy(vf_set1(h->ior.eta), w, v3_scale(vf_set1(-1.0f), d));
    *len2 = vf_max(v3_dot(half, half), vf_set1(1e-30f));
    return v3_scale(vf_div(vf_set1(1.0f), vf_sqrt(*len2)), half);
}

/* Leaving through the exit point q along w (inside) toward w_o: f_t |w_o . w_m| of the rough
 * interface (Walter et al. 2007) with the generalised half vector w_h = (eta w - w_o) / |.|,
 * T D G |w . w_h| |w_o . w_h| / (|w . w_m| |eta w - w_o|^2) (HHH22 eqs. 21, 31), zero unless w_o
 * sees the point's macronormal and mesonormal and w_h faces out of it. */
HB_INLINE vf exit_value(const hb_huang *h, const fibre_point *q, v3 w, v3 wo)
{
    vf zero = vf_set1(0.0f), len2;
    v3 wh = exit_half_vector(h, w, wo, &len2);
    vf cos_in = v3_dot(w, wh), cos_out = v3_dot(wo, wh);
    vf w_m = v3_dot(w, q->meso), wo_m = v3_dot(wo, q->meso);
    vm ok = vm_and(vf_gt(cos_out, zero), vf_gt(cos_in, zero));
    ok = vm_and(ok, vm_and(vf_gt(v3_dot(wo, q->macro), zero), vf_gt(wo_m, zero)));
    ok = vm_and(ok, vm_and(vf_gt(w_m, zero), vf_gt(v3_dot(wh, q->meso), zero)));
    vf value = vf_mul(fresnel_transmittance(h, cos_out), ndf_huang(h, v3_one_minus_dot(wh, q->meso)));
    value = vf_mul(value, vf_mul(smith_g1_huang(h, w_m), smith_g1_huang(h, wo_m)));
    value = vf_div(vf_mul(value, vf_mul(cos_in, cos_out)), vf_max(vf_mul(w_m, len2), vf_set1(1e-30f)));
    return vf_select(ok, value, zero);
}

/* e^(-sigma_a length) per channel. */
HB_INLINE void absorption(const hb_huang *h, vf length, vf a[3])
{
    for (int c = 0; c < 3; c++)
        a[c] = vf_exp_flush(vf_max(vf_mul(vf_set1(-h->sigma_a[c]), length), vf_set1(-100.0f)));
}

/* Where an internal path leaves the fibre: the exit point, the direction inside, the micronormal
 * that sent the path along it (entry: outer side; bounce: inner side), and the path's weight up to
 * the exit interface per channel (entry and bounce factors and absorption). */
typedef struct internal_exit {
    fibre_point q;
    v3 w;
    v3 normal;
    vf weight[3];
} internal_exit;

/* One internal path from the entry point p, u[0..3] the visible normals' numbers at interfaces 1
 * and 2: its TT exit (exits[0]) and TRT exit (exits[1], traced only when `bounce` is set), the
 * entry factor |w_i . w_m1| of eqs. 31, 32 included. The pdf of eq. 33 fixes one micronormal
 * instead of drawing it: entry_normal (u[0], u[1] unused), or the bounce normal as the one whose
 * exit refracts w_t into *tt_exit (u[2], u[3] unused); NULL draws them. */
HB_INLINE void internal_exits(const hb_huang *h, const fibre_point *p, v3 wi, const vf u[4], internal_exit exits[2],
                              int bounce, const v3 *entry_normal, const v3 *tt_exit)
{
    vf zero = vf_set1(0.0f), one = vf_set1(1.0f), inv_eta = vf_set1(1.0f / h->ior.eta);
    /* interface 1: refraction into the fibre through a visible normal of w_i */
    v3 h1 = entry_normal ? *entry_normal : visible_micronormal(h, p, wi, 1.0f, u[0], u[1]);
    vf c1 = vf_max(v3_dot(wi, h1), zero);
    vf cos_t = vf_sqrt(vf_max(vf_fnma(vf_mul(inv_eta, inv_eta), vf_fnma(c1, c1, one), one), zero));
    v3 wt = v3_axpy(vf_fnma(vf_set1(h->ior.eta), cos_t, c1), v3_scale(inv_eta, h1), v3_scale(vf_neg(inv_eta), wi));
    vf wi_m = vf_max(v3_dot(wi, p->meso), zero), wt_m = vf_neg(v3_dot(wt, p->meso)); /* >= 0 up to rounding at the window's ends */
    vm inside = vm_and(vf_gt(wt_m, zero), vf_lt(v3_dot(wt, p->macro), zero));
    vf entry = vf_mul(fresnel_transmittance(h, c1), vf_mul(wi_m, smith_g1_huang(h, wt_m)));
    entry = vf_select(inside, entry, zero);
    vf length, a[3];
    exits[0].q = chord_exit(h, p, wt, &length);
    exits[0].w = wt;
    exits[0].normal = h1;
    absorption(h, length, a);
    for (int c = 0; c < 3; c++)
        exits[0].weight[c] = vf_mul(entry, a[c]);
    if (!bounce)
        return; /* exits[1] is left unset: callers skip the lobes the plan leaves out */
    /* interface 2: internal reflection off a visible normal (inner side) of -w_t */
    const fibre_point *q = &exits[0].q;
    v3 h2;
    if (tt_exit) {
        vf len2;
        h2 = v3_scale(vf_set1(-1.0f), exit_half_vector(h, wt, *tt_exit, &len2));
    } else {
        h2 = visible_micronormal(h, q, v3_scale(vf_set1(-1.0f), wt), -1.0f, u[2], u[3]);
    }
    vf c2 = vf_max(vf_neg(v3_dot(wt, h2)), zero);
    v3 wtr = v3_axpy(vf_add(c2, c2), h2, wt);
    vf wtr_m2 = vf_neg(v3_dot(wtr, q->meso));
    vm back = vm_and(vf_gt(wtr_m2, zero), vf_lt(v3_dot(wtr, q->macro), zero));
    vf bounce_factor = vf_mul(fresnel_from_inside(h, c2), smith_g1_huang(h, wtr_m2));
    bounce_factor = vf_select(back, vf_mul(entry, bounce_factor), zero);
    vf length2, a2[3];
    exits[1].q = chord_exit(h, q, wtr, &length2);
    exits[1].w = wtr;
    exits[1].normal = h2;
    absorption(h, length2, a2);
    for (int c = 0; c < 3; c++)
        exits[1].weight[c] = vf_mul(bounce_factor, vf_mul(a[c], a2[c]));
}

/* The entry window of w_i, |phi_m1 - phi_i| <= pi/2 - cut_i, and composite Simpson over it with
 * `panels` panels (eqs. 31, 32 integrate over phi_m1). */
typedef struct entry_rule {
    vf half, step;
    vf cos_phi_i, sin_phi_i;
    vm seen;
    v3 wi;
} entry_rule;

HB_INLINE entry_rule entry_rule_of(const hb_huang *h, vf cos_ti, vf sin_ti, vf cos_phi_i, vf sin_phi_i, int panels)
{
    entry_rule e;
    vf cut = visible_cut(h, cos_ti, sin_ti, &e.seen);
    e.half = vf_keep(e.seen, vf_sub(vf_set1(HB_PIO2_F), cut));
    e.step = vf_div(vf_add(e.half, e.half), vf_set1((float)panels));
    e.cos_phi_i = cos_phi_i;
    e.sin_phi_i = sin_phi_i;
    e.wi = (v3){ vf_mul(sin_phi_i, cos_ti), sin_ti, vf_mul(cos_phi_i, cos_ti) };
    return e;
}

/* Node j of the rule: the entry point, and its weight, Simpson's 1-4-2-...-4-1 times rho(phi_m1)
 * (eq. 26 in phi_m for an ellipse: rho = b^2 / k^3, k^2 = sin^2 + b^2 cos^2 = 1 - e^2 cos^2). */
HB_INLINE fibre_point entry_node(const hb_huang *h, const entry_rule *e, int j, int panels, vf *weight)
{
    vf s, c;
    vf_sincos(vf_fma(vf_set1((float)j), e->step, vf_neg(e->half)), &s, &c);
    vf cos_m = vf_fnma(s, e->sin_phi_i, vf_mul(c, e->cos_phi_i)), sin_m = vf_fma(s, e->cos_phi_i, vf_mul(c, e->sin_phi_i));
    *weight = vf_set1((j == 0 || j == panels) ? 1.0f : (j & 1) ? 4.0f : 2.0f);
    if (h->elliptical) {
        vf k2 = vf_fma(vf_set1(h->b2), vf_mul(cos_m, cos_m), vf_mul(sin_m, sin_m));
        *weight = vf_mul(*weight, vf_div(vf_set1(h->b2), vf_mul(k2, vf_sqrt(k2))));
    }
    return entry_point(h, cos_m, sin_m);
}

/* f_TT + f_TRT (eqs. 29-32; f = S cos(theta_i)) per channel: 1 / (2 a cos(theta_o)) times Simpson
 * over the entry window of rho(phi_m1) times one internal path per node, a = sqrt(1 - e^2 sin^2 phi_o)
 * the fibre's projected half width. Node j of sample `index` draws numbers 4j..4j+3 of the
 * sample's stream. */
HB_STAGE void huang_internal(const hb_huang *h, const huang_directions *d, vi index, vf out[3])
{
    vf zero = vf_set1(0.0f);
    int panels = h->tt_panels;
    entry_rule e = entry_rule_of(h, d->cos_ti, d->sin_ti, d->cos_phi_i, d->sin_phi_i, panels);
    /* w_o in the fibre frame, turned from the frame phi_i = 0 */
    vf ox = vf_mul(d->sin_phi, d->cos_to), oz = vf_mul(d->cos_phi, d->cos_to);
    v3 wo = { vf_fma(ox, d->cos_phi_i, vf_mul(oz, d->sin_phi_i)), d->sin_to, vf_fnma(ox, d->sin_phi_i, vf_mul(oz, d->cos_phi_i)) };
    vi stream = rng_stream(h->rng_key, index);
    vf sum[3] = { zero, zero, zero };
    for (int j = 0; j <= panels; j++) {
        vf weight, u[4];
        fibre_point p = entry_node(h, &e, j, panels, &weight);
        for (int k = 0; k < 4; k++)
            u[k] = rng_uniform(stream, h->rng_key2, 4 * j + k);
        internal_exit exits[2];
        internal_exits(h, &p, e.wi, u, exits, h->lobes >> HB_LOBE_TRT & 1u, NULL, NULL);
        for (int l = 0; l < 2; l++) {
            if (!(h->lobes >> (HB_LOBE_TT + l) & 1u))
                continue;
            vf leave = vf_mul(weight, exit_value(h, &exits[l].q, exits[l].w, wo));
            for (int c = 0; c < 3; c++)
                sum[c] = vf_fma(leave, exits[l].weight[c], sum[c]);
        }
    }
    vf den = vf_set1(2.0f);
    if (h->elliptical)
        den = vf_mul(den, vf_sqrt(vf_fnma(vf_set1(h->e2), d->sin2_phi_o, vf_set1(1.0f))));
    vf width = huang_width_factor(h, d->cos_ti, d->cos_to);
    vf scale = vf_select(e.seen, vf_div(vf_mul(vf_mul(e.step, vf_set1(1.0f / 3.0f)), width), den), zero);
    for (int c = 0; c < 3; c++)
        out[c] = vf_mul(sum[c], scale);
}

#endif

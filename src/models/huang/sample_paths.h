/* HHH22 importance sampling with TT and TRT (sec. 3.4.1, 8 random numbers) and its pdf (eq. 33),
 * over the SIMD vocabulary; docs/sampling.md.
 *
 * Sampling traces one path from the known direction w_o (by reciprocity; the model's f(w_i, w_o)
 * is what the weight estimates): u0 the entry offset (as the R sampler), u1 u2 the entry
 * micronormal h1, u3 u4 the bounce micronormal h2, u5 u6 the TRT exit micronormal h3, u7 the lobe.
 * Each lobe L in {R, TT, TRT} has a throughput w_L (Fresnel, visible-normal shadowing factors,
 * absorption; zero where its direction leaves through the fibre), and L is chosen with probability
 * mean(w_L) / sum mean(w_L): the paper's attenuation-proportional choice, with the shadowing
 * included so that the choice carries no variance for grey fibres. The weight w_L / P(L) times
 * W / (2 a cos(theta_o) cos(psi)) (the entry point's density against the eval's measure, eqs. 29-32)
 * and the reversal factor of trace_path is an unbiased estimate of f / pdf: its mean times L_i
 * estimates L_o.
 *
 * The pdf is eq. 33 made exact in expectation: Simpson over the entry azimuth of the density of the
 * entry point times, for each lobe, the density of its last micronormal given the ones before it
 * (drawn, one path per node) times E[P(L)], P(L) taken on a path whose lobe-L micronormal is the
 * one that sends it to w_i and whose other micronormals are drawn. Numbers come from the sample's
 * stream (seed, index), so hb_pdf_angles at a sample's index returns the sampled pdf bit for bit. */
#ifndef HB_HUANG_SAMPLE_PATHS_H
#define HB_HUANG_SAMPLE_PATHS_H

#include "internal.h"

enum { PATH_R, PATH_TT, PATH_TRT, PATH_LOBES, PATH_DRAWN = PATH_LOBES };

/* One traced path: each lobe's direction out of the fibre and throughput per channel. */
typedef struct huang_path {
    v3 dir[PATH_LOBES];
    vf weight[PATH_LOBES][3];
} huang_path;

/* Reflection of w_a off the entry micronormal h1 into d: F w_a.w_m G-factor (eq. 12's integrand
 * against the visible normals of w_a), zero unless d sees the entry point. */
HB_INLINE vf reflect_factor(const hb_huang *h, const fibre_point *p, v3 wa, v3 h1, v3 d)
{
    vf zero = vf_set1(0.0f);
    vf c1 = v3_dot(wa, h1), wa_m = v3_dot(wa, p->meso), d_m = v3_dot(d, p->meso);
    vm ok = vm_and(vm_and(vf_gt(c1, zero), vf_gt(wa_m, zero)), vm_and(vf_gt(d_m, zero), vf_gt(v3_dot(d, p->macro), zero)));
    vf value = vf_mul(fresnel_dielectric(vf_min(c1, vf_set1(1.0f)), &h->ior), vf_mul(wa_m, sampled_shadowing(h, wa_m, d_m)));
    return vf_select(ok, value, zero);
}

/* w (inside, at the exit point q) refracted out through the outward micronormal n; *cos_in = w . n. */
HB_INLINE v3 refract_out(const hb_huang *h, v3 w, v3 n, vf *cos_in, vf *sin2_out)
{
    vf eta = vf_set1(h->ior.eta);
    *cos_in = v3_dot(w, n);
    *sin2_out = vf_mul(vf_mul(eta, eta), vf_fnma(*cos_in, *cos_in, vf_set1(1.0f)));
    vf cos_out = vf_sqrt(vf_max(vf_sub(vf_set1(1.0f), *sin2_out), vf_set1(0.0f)));
    return v3_axpy(vf_fnma(eta, *cos_in, cos_out), n, v3_scale(eta, w)); /* eta w + (cos_out - eta cos_in) n */
}

/* Transmission of w out through the outward micronormal n into d: T times the G-factor, zero unless
 * the refraction exists and d sees the exit point (exit_value's conditions). */
HB_INLINE vf exit_factor(const hb_huang *h, const fibre_point *q, v3 w, v3 n, v3 d, vf cos_in, vf sin2_out)
{
    vf zero = vf_set1(0.0f), cos_out = v3_dot(d, n);
    vf w_m = v3_dot(w, q->meso), d_m = v3_dot(d, q->meso);
    vm ok = vm_and(vm_and(vf_gt(cos_in, zero), vf_lt(sin2_out, vf_set1(1.0f))), vm_and(vf_gt(cos_out, zero), vf_gt(w_m, zero)));
    ok = vm_and(ok, vm_and(vm_and(vf_gt(d_m, zero), vf_gt(v3_dot(d, q->macro), zero)), vf_gt(v3_dot(n, q->meso), zero)));
    return vf_select(ok, vf_mul(fresnel_transmittance(h, cos_out), smith_g1_huang(h, d_m)), zero);
}

/* Leaving an exit toward the fixed direction d: the factor, and the density of d given the path
 * so far, D G1(w) |w . n| |d . n| / (|w . w_m| |eta w - d|^2) (the visible normals of -w at the
 * inner side, and the refraction's Jacobian; eq. 33's TT and TRT terms). */
HB_INLINE vf exit_toward(const hb_huang *h, const internal_exit *x, v3 d, vf *density)
{
    vf len2, cos_in, sin2_out;
    v3 n = exit_half_vector(h, x->w, d, &len2);
    refract_out(h, x->w, n, &cos_in, &sin2_out);
    vf factor = exit_factor(h, &x->q, x->w, n, d, cos_in, sin2_out);
    vf w_m = v3_dot(x->w, x->q.meso);
    vf shape = vf_mul(ndf_huang(h, v3_one_minus_dot(n, x->q.meso)), smith_g1_over_cos(h, w_m));
    *density = vf_keep(vf_gt(factor, vf_set1(0.0f)), vf_div(vf_mul(shape, vf_mul(cos_in, v3_dot(d, n))), len2));
    return factor;
}

/* Leaving an exit through a drawn micronormal n (outward): the direction and the factor. */
HB_INLINE vf exit_drawn(const hb_huang *h, const internal_exit *x, v3 n, v3 *d)
{
    vf cos_in, sin2_out;
    *d = refract_out(h, x->w, n, &cos_in, &sin2_out);
    return exit_factor(h, &x->q, x->w, n, *d, cos_in, sin2_out);
}

/* The path from the entry point p for the known direction wa, u[0..5] the micronormals' numbers.
 * fixed (a compile-time constant after inlining) names the lobe whose last micronormal sends the
 * path to d instead of being drawn (PATH_DRAWN: none); *density is then d's density given the rest. */
HB_INLINE void trace_path(const hb_huang *h, const fibre_point *p, v3 wa, const vf u[6], int fixed, v3 d,
                          huang_path *path, vf *density)
{
    vf zero = vf_set1(0.0f);
    internal_exit exits[2];
    v3 entry_normal;
    if (fixed == PATH_R) { /* h1 = (w_a + d) / |w_a + d|: D G1(w_a) / (4 w_a . w_m) (eq. 33's R term) */
        v3 sum = { vf_add(wa.x, d.x), vf_add(wa.y, d.y), vf_add(wa.z, d.z) };
        entry_normal = v3_scale(vf_div(vf_set1(1.0f), vf_sqrt(vf_max(v3_dot(sum, sum), vf_set1(1e-30f)))), sum);
    }
    internal_exits(h, p, wa, u, exits, 1, fixed == PATH_R ? &entry_normal : NULL, fixed == PATH_TT ? &d : NULL);
    v3 h1 = exits[0].normal;
    *density = zero;
    /* R: reflection off h1 */
    path->dir[PATH_R] = fixed == PATH_R ? d : v3_axpy(vf_mul(vf_set1(2.0f), v3_dot(wa, h1)), h1, v3_scale(vf_set1(-1.0f), wa));
    vf r = reflect_factor(h, p, wa, h1, path->dir[PATH_R]);
    if (fixed == PATH_R) {
        vf wa_m = v3_dot(wa, p->meso);
        vf shape = vf_mul(ndf_huang(h, v3_one_minus_dot(h1, p->meso)), smith_g1_over_cos(h, wa_m));
        vm faces = vm_and(vf_gt(r, zero), vf_gt(v3_dot(h1, p->meso), zero));
        *density = vf_select(faces, vf_mul(vf_set1(0.25f), shape), zero);
    }
    /* TT: out through the bounce normal h2 (exits[1].normal faces inward) */
    vf tt, tt_density;
    if (fixed == PATH_TT) {
        path->dir[PATH_TT] = d;
        tt = exit_toward(h, &exits[0], d, &tt_density);
        *density = tt_density;
    } else {
        tt = exit_drawn(h, &exits[0], v3_scale(vf_set1(-1.0f), exits[1].normal), &path->dir[PATH_TT]);
    }
    /* TRT: out through h3, a visible normal (inner side) of -w_tr */
    vf trt, trt_density;
    if (fixed == PATH_TRT) {
        path->dir[PATH_TRT] = d;
        trt = exit_toward(h, &exits[1], d, &trt_density);
        *density = trt_density;
    } else {
        v3 h3 = visible_micronormal(h, &exits[1].q, v3_scale(vf_set1(-1.0f), exits[1].w), -1.0f, u[4], u[5]);
        trt = exit_drawn(h, &exits[1], v3_scale(vf_set1(-1.0f), h3), &path->dir[PATH_TRT]);
    }
    /* The path runs from w_o, but f(w_i, w_o) weighs it from w_i's side: eqs. 23-32 take each
     * interface's cosines against the tilted mesonormal w_m while a chord's entry and exit points
     * correspond through the macronormal n (ds_q |w.n_q| = ds_p |w.n_p|), so reversing a segment
     * p -> q scales its weight by (|w.w_m,q| / |w.n_q|) / (|w.w_m,p| / |w.n_p|): exactly 1 without
     * tilt, and with it what makes the mean weight f(w_i, w_o)'s albedo (docs/sampling.md). */
    vf tiny = vf_set1(1e-30f);
    const fibre_point *q2 = &exits[0].q, *q3 = &exits[1].q;
    v3 wt = exits[0].w, wtr = exits[1].w;
    vf reverse_tt = vf_div(vf_mul(vf_max(v3_dot(wt, q2->meso), tiny), vf_max(vf_neg(v3_dot(wt, p->macro)), tiny)),
                           vf_mul(vf_max(v3_dot(wt, q2->macro), tiny), vf_max(vf_neg(v3_dot(wt, p->meso)), tiny)));
    vf reverse_bounce = vf_div(vf_mul(vf_max(v3_dot(wtr, q3->meso), tiny), vf_max(vf_neg(v3_dot(wtr, q2->macro)), tiny)),
                               vf_mul(vf_max(v3_dot(wtr, q3->macro), tiny), vf_max(vf_neg(v3_dot(wtr, q2->meso)), tiny)));
    tt = vf_mul(tt, reverse_tt);
    trt = vf_mul(trt, vf_mul(reverse_tt, reverse_bounce));
    vf lobe[PATH_LOBES] = { r, tt, trt };
    for (int l = 0; l < PATH_LOBES; l++) {
        if (!(h->lobes >> l & 1u))
            lobe[l] = zero;
        for (int c = 0; c < 3; c++)
            path->weight[l][c] = l == PATH_R ? lobe[l] : vf_mul(lobe[l], exits[l - 1].weight[c]);
    }
}

/* mean(w_L) per lobe and their sum. */
HB_INLINE vf path_choice(const huang_path *path, vf mean[PATH_LOBES])
{
    vf total = vf_set1(0.0f);
    for (int l = 0; l < PATH_LOBES; l++) {
        mean[l] = vf_mul(vf_set1(1.0f / 3.0f), vf_add(path->weight[l][0], vf_add(path->weight[l][1], path->weight[l][2])));
        total = vf_add(total, mean[l]);
    }
    return total;
}

/* w_o in the fibre frame. */
HB_INLINE v3 fibre_direction(vf cos_t, vf sin_t, vf cos_p, vf sin_p)
{
    v3 w = { vf_mul(sin_p, cos_t), sin_t, vf_mul(cos_p, cos_t) };
    return w;
}

/* The pdf of w_i (eq. 33 in expectation) for w_o, keyed by the sample's index. */
HB_STAGE vf huang_path_pdf(const hb_huang *h, vf theta_i, vf phi_i, vf theta_o, vf phi_o, vi index)
{
    vf zero = vf_set1(0.0f), sti, cti, sto, cto, spi, cpi, spo, cpo;
    vf_sincos(theta_i, &sti, &cti);
    vf_sincos(theta_o, &sto, &cto);
    vf_sincos(wrap_angle(phi_i), &spi, &cpi);
    vf_sincos(wrap_angle(phi_o), &spo, &cpo);
    cti = vf_max(cti, zero);
    cto = vf_max(cto, zero);
    v3 wi = fibre_direction(cti, sti, cpi, spi);
    int panels = h->tt_panels;
    entry_rule e = entry_rule_of(h, cto, sto, cpo, spo, panels);
    huang_o_window w = huang_o_window_of(h, cto, sto, phi_o);
    vi stream = rng_stream(h->rng_key, index);
    uint32_t key2 = h->rng_key2 ^ 0x5bd1e995u; /* apart from eval's numbers */
    vf sum = zero;
    for (int j = 0; j <= panels; j++) {
        vf weight;
        fibre_point p = entry_node(h, &e, j, panels, &weight);
        vf cos_psi = vf_cos(vf_fma(vf_set1((float)j), e.step, vf_neg(e.half)));
        vf node = zero;
        for (int l = 0; l < PATH_LOBES; l++) {
            if (!(h->lobes >> l & 1u))
                continue;
            vf u[6], density, mean[PATH_LOBES];
            for (int k = 0; k < 6; k++)
                u[k] = rng_uniform(stream, key2, 18 * j + 6 * l + k);
            huang_path path;
            trace_path(h, &p, e.wi, u, l, wi, &path, &density);
            vf total = path_choice(&path, mean);
            vm some = vf_gt(total, zero);
            node = vf_fma(vf_select(some, vf_div(mean[l], vf_select(some, total, vf_set1(1.0f))), zero), density, node);
        }
        sum = vf_fma(vf_mul(weight, cos_psi), node, sum);
    }
    vf pdf = vf_div(vf_mul(sum, vf_mul(e.step, vf_set1(1.0f / 3.0f))), vf_max(w.projected, vf_set1(1e-30f)));
    return vf_select(vm_and(e.seen, vf_gt(w.projected, zero)), vf_max(pdf, zero), zero);
}

/* Sampling: w_i, its pdf (the code of hb_pdf_angles at the returned float angles) and the weight. */
HB_INLINE void huang_path_sample(const hb_huang *h, vf theta_o, vf phi_o, const vf u[HB_HUANG_PATH_DIMENSIONS], vi index,
                                 vf *theta_i, vf *phi_i, vf *pdf, vf weight[3])
{
    vf zero = vf_set1(0.0f), one = vf_set1(1.0f), sto, cto, spo, cpo, sin_psi, cos_psi;
    vf_sincos(theta_o, &sto, &cto);
    cto = vf_max(cto, zero);
    vf_sincos(wrap_angle(phi_o), &spo, &cpo);
    huang_o_window w = huang_o_window_of(h, cto, sto, phi_o);
    huang_sample_offset(h, &w, phi_o, u[0], &sin_psi, &cos_psi);
    /* the entry point: mesonormal azimuth phi_o + psi */
    fibre_point p = entry_point(h, vf_fnma(spo, sin_psi, vf_mul(cpo, cos_psi)), vf_fma(spo, cos_psi, vf_mul(cpo, sin_psi)));
    v3 wo = fibre_direction(cto, sto, cpo, spo);
    huang_path path;
    vf density, mean[PATH_LOBES];
    trace_path(h, &p, wo, u + 1, PATH_DRAWN, wo, &path, &density);
    vf total = path_choice(&path, mean);
    /* the lobe: R below mean_R, TT below mean_R + mean_TT, else TRT */
    vf pick = vf_mul(u[7], total);
    vm is_r = vf_lt(pick, mean[PATH_R]), is_tt = vm_andnot(vf_lt(pick, vf_add(mean[PATH_R], mean[PATH_TT])), is_r);
    vm is_trt = vm_andnot(vf_gt(total, zero), vm_or(is_r, is_tt));
    v3 d = path.dir[PATH_TRT];
    d.x = vf_select(is_tt, path.dir[PATH_TT].x, vf_select(is_r, path.dir[PATH_R].x, d.x));
    d.y = vf_select(is_tt, path.dir[PATH_TT].y, vf_select(is_r, path.dir[PATH_R].y, d.y));
    d.z = vf_select(is_tt, path.dir[PATH_TT].z, vf_select(is_r, path.dir[PATH_R].z, d.z));
    vf chosen = vf_select(is_r, mean[PATH_R], vf_select(is_tt, mean[PATH_TT], mean[PATH_TRT]));
    /* W / (2 a cos(theta_o) cos(psi)): the entry point's density against the eval's measure */
    vf planar = vf_sqrt(vf_fma(d.x, d.x, vf_mul(d.z, d.z))); /* cos(theta_i) */
    vf den = vf_mul(vf_set1(2.0f), vf_max(cos_psi, vf_set1(1e-6f)));
    if (h->elliptical)
        den = vf_mul(den, vf_sqrt(vf_fnma(vf_set1(h->e2), vf_mul(spo, spo), one)));
    /* every lobe's throughput carries w_o . w_m1, which vanishes with cos(psi) without tilt; at the
     * window's very ends (probability ~1e-12) the ratio is rounding, and the sample is dropped */
    vf scale = vf_mul(vf_div(total, vf_max(chosen, vf_set1(1e-30f))),
                      vf_div(vf_mul(w.projected, huang_width_factor(h, planar, cto)), den));
    vm some = vm_and(vm_and(w.seen, vf_gt(total, zero)), vm_or(is_r, vm_or(is_tt, is_trt)));
    some = vm_and(some, vf_ge(cos_psi, vf_set1(1e-6f)));
    for (int c = 0; c < 3; c++) {
        vf lobe = vf_select(is_r, path.weight[PATH_R][c], vf_select(is_tt, path.weight[PATH_TT][c], path.weight[PATH_TRT][c]));
        weight[c] = vf_select(some, vf_mul(lobe, scale), zero);
    }
    *theta_i = vf_select(some, vf_atan2(d.y, planar), zero);
    *phi_i = vf_select(some, wrap_angle(vf_atan2(d.x, d.z)), zero);
    *pdf = vf_select(some, huang_path_pdf(h, *theta_i, *phi_i, theta_o, phi_o, index), zero);
}

#endif

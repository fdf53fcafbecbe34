/* dFH11 azimuthal scattering N_p (eqs. 8, 10-14) and the full model f = sum_p M_p N_p,
 * over the SIMD vocabulary. Loop counts (nodes, orders, detector terms) come from the
 * plan, never from the samples. */
#ifndef HB_DEON_AZIMUTHAL_H
#define HB_DEON_AZIMUTHAL_H

#include "longitudinal_groups.h"
#include "models/common/fresnel.h"
#include "math/multilinear.h"

/* cos(n phi) for n = 1..terms by the Chebyshev recurrence, for the Fourier detectors. */
HB_INLINE void cos_multiples(vf cos_phi, int terms, vf *out)
{
    vf previous = vf_set1(1.0f), current = cos_phi;
    for (int n = 1; n <= terms; n++) {
        out[n] = current;
        vf next = vf_fnma(previous, vf_set1(1.0f), vf_mul(vf_add(cos_phi, cos_phi), current));
        previous = current;
        current = next;
    }
}

/* The plan's shape as constants, so that each kernel's loops over lobes and detector terms unroll:
 * standard = explicit orders up to TRRT (any subset of them and the residual), every detector the
 * nearest Gaussian alone, the default absorption and R Fresnel (hb_deon.standard); all_lobes: the
 * standard shape with every one of those lobes; channels 3, or 1 for a grey fibre. */
typedef struct deon_shape {
    int standard, channels, all_lobes;
} deon_shape;

/* The most channels a sample carries: RGB's three, or a spectral call's wavelengths (the standard
 * shape's fused sum, deon_fused_shaped). */
#define HB_DEON_CHANNELS HB_WAVELENGTHS_MAX

#define HB_STANDARD_LOBES (((2u << HB_STANDARD_PMAX) - 1u) | 1u << HB_LOBE_RESIDUAL)

HB_INLINE int deon_pmax(const hb_deon *d, deon_shape shape) { return shape.standard ? HB_STANDARD_PMAX : d->pmax; }

/* hb_deon_lobe_on with the shape's pmax, a constant for the standard shape */
HB_INLINE int deon_lobe_on(const hb_deon *d, int p, deon_shape shape)
{
    unsigned lobes = shape.all_lobes ? HB_STANDARD_LOBES : d->lobes;
    return (lobes >> p & 1u) && (p <= deon_pmax(d, shape) || p == HB_LOBE_RESIDUAL);
}

/* D_p(phi - Phi) + D_p(-phi - Phi), eq. 11: detection at phi and -phi covers h < 0.
 * Fourier form: cos(n(phi - Phi)) + cos(n(-phi - Phi)) = 2 cos(n phi) cos(n Phi). */
HB_INLINE vf detector_pair(const hb_detector *d, vf phi, vf Phi, const vf *cos_n_phi, deon_shape shape)
{
    if (!shape.standard && d->fourier) {
        vf cos_Phi = vf_cos(Phi);
        vf previous = vf_set1(1.0f), current = cos_Phi;
        vf sum = vf_set1(2.0f * d->coeff[0]);
        for (int n = 1; n <= d->terms; n++) {
            sum = vf_fma(vf_set1(2.0f * d->coeff[n]), vf_mul(cos_n_phi[n], current), sum);
            vf next = vf_fnma(previous, vf_set1(1.0f), vf_mul(vf_add(cos_Phi, cos_Phi), current));
            previous = current;
            current = next;
        }
        return sum;
    }
    vf x1 = wrap_angle(vf_sub(phi, Phi)), x2 = wrap_angle(vf_neg(vf_add(phi, Phi)));
    vf sum = vf_set1(0.0f), exponent = vf_set1(d->log2e_over_two_beta2);
    int terms = shape.standard ? 0 : d->terms;
    for (int k = -terms; k <= terms; k++) {
        vf d1 = vf_sub(x1, vf_set1(HB_TWO_PI_F * (float)k)), d2 = vf_sub(x2, vf_set1(HB_TWO_PI_F * (float)k));
        sum = vf_add(sum, vf_exp2_neg(vf_mul(vf_mul(d1, d1), exponent)));
        sum = vf_add(sum, vf_exp2_neg(vf_mul(vf_mul(d2, d2), exponent)));
    }
    return vf_mul(sum, vf_set1(d->gauss_norm));
}

HB_INLINE vf channel_mean(const vf rgb[3])
{
    return vf_mul(vf_add(vf_add(rgb[0], rgb[1]), rgb[2]), vf_set1(1.0f / 3.0f));
}

/* The mean over a shape's channels: RGB's three (a grey fibre's copies among them), or a spectral
 * call's k wavelengths. */
HB_INLINE vf deon_channel_mean(const vf *A, int channels)
{
    if (channels == 1 || channels == 3)
        return channel_mean(A);
    vf sum = A[0];
    HB_UNROLL
    for (int c = 1; c < HB_DEON_CHANNELS; c++)
        sum = c < channels ? vf_add(sum, A[c]) : sum;
    return vf_mul(sum, vf_set1(1.0f / (float)channels));
}

/* Per-sample geometry the azimuthal part needs. */
typedef struct deon_geometry {
    vf phi;          /* phi_o - phi_i in [-pi, pi] */
    vf cos_phi;
    vf cos_theta_d;  /* theta_d = (theta_o - theta_i)/2 */
    vf cos_half_io;  /* cos of half the angle between w_i and w_o (eq. 12's Fresnel; 1 where unused) */
    vf absorption[HB_DEON_CHANNELS]; /* sigma_a log2(e) per channel: the plan's, or each sample's (hb_eval_angles_absorption, a spectral call's) */
    int grey;         /* the same absorption in every channel: one channel computed, copied */
} deon_geometry;

/* The plan's absorption into a sample's geometry. */
HB_INLINE void deon_plan_absorption(const hb_deon *d, deon_geometry *g)
{
    for (int c = 0; c < 3; c++)
        g->absorption[c] = vf_set1(d->sigma_a_log2e[c]);
    g->grey = d->channels == 1;
}

/* A spectral call's absorptions (sigma_a log2(e) per wavelength) into a sample's geometry. */
HB_INLINE void deon_spectral_absorption(deon_geometry *g, int channels, const vf *absorption)
{
    HB_UNROLL
    for (int c = 0; c < HB_DEON_CHANNELS; c++)
        g->absorption[c] = c < channels ? absorption[c] : vf_set1(0.0f);
    g->grey = 0;
}

/* What every node of the h quadrature needs from a sample: eta' (sec. 5) and mu_a' (sec. 6). */
typedef struct deon_medium {
    vf cos_theta_d;
    vf inv_eta_cos_t; /* 1 / (eta' cos(theta_d)) = 1 / sqrt(eta^2 - sin^2(theta_d)) */
    vf inv_eta_prime; /* 1 / eta' = cos(theta_d) / sqrt(eta^2 - sin^2(theta_d)) */
    vf mu_log2e[HB_DEON_CHANNELS]; /* mu_a' log2(e), mu_a' = mu_a / cos(theta_t), per channel */
} deon_medium;

HB_INLINE void deon_medium_of(const hb_deon *d, const deon_geometry *g, deon_medium *m, const int channels)
{
    m->cos_theta_d = g->cos_theta_d;
    /* eta^2 - sin^2(theta_d) as (eta^2 - 1) + cos^2(theta_d): positive for every eta > 1, where the
     * float eta^2 is 1 for eta below 1 + 6e-8 and the difference would be 0 (0 / 0 at the pole) */
    vf eta_cos_t = vf_sqrt(vf_fma(g->cos_theta_d, g->cos_theta_d, vf_set1(d->ior.eta2_minus_1)));
    m->inv_eta_cos_t = vf_div(vf_set1(1.0f), eta_cos_t);
    m->inv_eta_prime = vf_mul(g->cos_theta_d, m->inv_eta_cos_t); /* sec. 5 */
    vf inv_cos_theta_t = vf_mul(vf_set1(d->ior.eta), m->inv_eta_cos_t);
    HB_UNROLL /* to the most channels, each guarded by the count: straight code at a constant count */
    for (int c = 0; c < HB_DEON_CHANNELS; c++) /* at most FLT_MAX / 4, so that twice it times a cosine stays finite */
        m->mu_log2e[c] = c < channels ? vf_min(vf_mul(g->absorption[c], inv_cos_theta_t), vf_set1(8e37f)) : vf_set1(0.0f);
}

/* What the paths through one offset h = sin(gamma_i) share across channels: the Fresnel factor f
 * (eq. 14), the per-traversal transmittance T (per channel), the exit azimuths Phi(p, h) (eq. 8) and the
 * channel-free part of A(p, h) (eq. 13): A_f[0] = f, A_f[p] = (1 - f)^2 f^(p-1) up to p = pmax + 1
 * (the residual's first order); A(p, h) = A_f[p] T^p. */
typedef struct deon_paths {
    vf f, one_minus_f, T[HB_DEON_CHANNELS];
    vf A_f[HB_MAX_LOBES + 1];
    vf Phi[HB_MAX_LOBES];
} deon_paths;

HB_INLINE void deon_node_paths(const hb_deon *d, const deon_medium *m, vf h, vf gamma_i, vf cos_gamma_i,
                               deon_paths *out, deon_shape shape)
{
    const int pmax = deon_pmax(d, shape);
    vf cos_d_cos_gamma_i = vf_mul(m->cos_theta_d, cos_gamma_i);
    vf sin_gamma_t = vf_mul(h, m->inv_eta_prime);
    /* cos^2(gamma_t) = (eta^2 - 1 + cos^2(theta_d) cos^2(gamma_i)) / (eta^2 - sin^2(theta_d)), two terms
     * >= 0: 1 - sin^2(gamma_t) cancels to 0 as eta -> 1 and |h| -> 1, losing the path inside */
    vf cos_gamma_t = vf_mul(vf_sqrt(vf_fma(cos_d_cos_gamma_i, cos_d_cos_gamma_i, vf_set1(d->ior.eta2_minus_1))),
                            m->inv_eta_cos_t);
    vf gamma_t = vf_asin_with_cos(sin_gamma_t, cos_gamma_t);
    /* eq. 14, with 1 - f formed on its own: it keeps its digits as f -> 1 at grazing incidence */
    vf one_minus_f, f = out->f = fresnel_dielectric_pair(cos_d_cos_gamma_i, &d->ior, &one_minus_f);
    /* path length per traversal: 2 cos(gamma_t), or the printed 2 (1 + cos 2 gamma_t) (docs/conventions.md) */
    vf path = !shape.standard && d->absorption_paper ? vf_mul(vf_set1(4.0f), vf_mul(cos_gamma_t, cos_gamma_t))
                                                     : vf_add(cos_gamma_t, cos_gamma_t);
    HB_UNROLL /* to the most channels, each guarded by the count, as deon_medium_of's */
    for (int c = 0; c < HB_DEON_CHANNELS; c++)
        out->T[c] = c < shape.channels ? vf_exp2_neg(vf_mul(m->mu_log2e[c], path)) : vf_set1(1.0f);
    out->Phi[0] = vf_mul(vf_set1(-2.0f), gamma_i); /* eq. 8, p = 0 */
    out->A_f[0] = f;
    out->one_minus_f = one_minus_f;
    out->A_f[1] = vf_mul(one_minus_f, one_minus_f); /* (1 - f)^2 f^(p-1), eq. 13 */
    HB_UNROLL
    for (int p = 1; p <= pmax && p < HB_MAX_LOBES; p++) {
        out->Phi[p] = vf_fma(vf_set1(2.0f * (float)p), gamma_t,
                             vf_fnma(vf_set1(2.0f), gamma_i, vf_set1((float)p * 3.14159265f))); /* eq. 8 */
        out->A_f[p + 1] = vf_mul(out->A_f[p], f);
    }
}

/* 1 / (1 - f T), the geometric series of the orders above pmax. 1 - f T is formed as
 * (1 - f) + f (1 - T), two non-negative terms (T clamped to 1: 2^-0 rounds an ulp above it), so the
 * residual (1 - f)^2 f^pmax T^(pmax+1) / (1 - f T) stays below 1 - f as f -> 1 at grazing angles; a
 * direct 1 - f T rounds to 0 or below there for a lossless fibre. one_minus_f is 1 - f formed on
 * its own (fresnel_dielectric_pair). */
HB_INLINE vf residual_series(vf f, vf one_minus_f, vf T)
{
    vf one = vf_set1(1.0f);
    vf denominator = vf_fma(f, vf_sub(one, vf_min(T, one)), one_minus_f);
    return vf_div(one, vf_max(denominator, vf_set1(1e-30f)));
}

/* Attenuation A(p, h) (eqs. 12-14, per channel) and exit azimuth Phi(p, h) (eq. 8) of every lobe of the
 * plan at one offset h = sin(gamma_i). A[HB_LOBE_RESIDUAL] = sum_{p > pmax} A(p, h). Without
 * the offset Fresnel option, A[R] = 1 and eq. 12's factor is applied by the caller. */
typedef struct deon_node {
    deon_paths paths; /* Phi among them */
    vf A[HB_MAX_LOBES + 1][HB_DEON_CHANNELS];
} deon_node;

HB_INLINE void deon_node_lobes(const hb_deon *d, const deon_medium *m, vf h, vf gamma_i, vf cos_gamma_i,
                               deon_node *node, deon_shape shape)
{
    const int channels = shape.channels, r_fresnel_offset = shape.standard || d->r_fresnel_offset;
    const int pmax = deon_pmax(d, shape);
    const deon_paths *paths = &node->paths;
    deon_node_paths(d, m, h, gamma_i, cos_gamma_i, &node->paths, shape);
    vf T_power[HB_DEON_CHANNELS];
    HB_UNROLL
    for (int c = 0; c < HB_DEON_CHANNELS; c++)
        T_power[c] = paths->T[c];
    if (deon_lobe_on(d, 0, shape))
        HB_UNROLL
        for (int c = 0; c < HB_DEON_CHANNELS; c++)
            if (c < 3 || c < channels)
                node->A[0][c] = r_fresnel_offset ? paths->f : vf_set1(1.0f);
    HB_UNROLL
    for (int p = 1; p <= pmax; p++) {
        if (deon_lobe_on(d, p, shape)) {
            HB_UNROLL
            for (int c = 0; c < channels; c++)
                node->A[p][c] = vf_mul(paths->A_f[p], T_power[c]);
        }
        HB_UNROLL
        for (int c = 0; c < channels; c++)
            T_power[c] = vf_mul(T_power[c], paths->T[c]);
    }
    if (deon_lobe_on(d, HB_LOBE_RESIDUAL, shape)) /* sum_{p > pmax} A(p, h) = A(pmax+1, h) / (1 - f T) */
        HB_UNROLL
        for (int c = 0; c < channels; c++)
            node->A[HB_LOBE_RESIDUAL][c] = vf_mul(vf_mul(paths->A_f[pmax + 1], T_power[c]), residual_series(paths->f, paths->one_minus_f, paths->T[c]));
    if (channels == 1) /* a grey fibre: the other channels are copies (register moves) */
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            if (deon_lobe_on(d, p, shape))
                node->A[p][1] = node->A[p][2] = node->A[p][0];
}

/* The residual lobe's pair of detectors: uniform in phi, 2 / (2 pi). */
#define HB_RESIDUAL_DETECTOR_PAIR 0.318309886f

/* For the sampling density (docs/sampling.md): M_p at the sample per lobe (NULL when only f is
 * wanted) and the accumulated sum over nodes of P(node) sum_p m_p D_p / (2 sum_p m_p), where
 * m_p = M_p times A(p, h) averaged over the channels. */
typedef struct deon_pdf_terms {
    const vf *M;
    vf sum;
} deon_pdf_terms;

/* N_p of eq. 10 for every lobe of the plan, by the plan's Gauss-Legendre rule in gamma_i:
 * N_p = sum_j weight_j A(p, h_j) [D_p(phi - Phi(p, h_j)) + D_p(-phi - Phi(p, h_j))].
 * N[HB_LOBE_RESIDUAL] holds all orders above pmax, spread uniformly in phi. A grey fibre (the same
 * absorption in every channel, hb_deon.channels = 1) computes channel 0 alone and copies it: bit for bit
 * what three channels give. */
HB_INLINE void azimuthal_deon_shaped(const hb_deon *d, const deon_geometry *g, vf N[HB_MAX_LOBES + 1][3],
                                     deon_pdf_terms *pdf, deon_shape shape)
{
    const int channels = shape.channels;
    deon_medium medium;
    deon_medium_of(d, g, &medium, channels);
    vf cos_n_phi[HB_MAX_DETECTOR_TERMS + 1];
    cos_multiples(g->cos_phi, d->fourier_terms, cos_n_phi);
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        N[p][0] = N[p][1] = N[p][2] = vf_set1(0.0f);
    if (pdf)
        pdf->sum = vf_set1(0.0f);

    for (int j = 0; j < d->nodes; j++) {
        vf weight = vf_set1(d->weight[j]);
        deon_node node;
        deon_node_lobes(d, &medium, vf_set1(d->h[j]), vf_set1(d->gamma_i[j]), vf_set1(d->cos_gamma_i[j]), &node,
                        shape);
        vf mass = vf_set1(0.0f), detected = vf_set1(0.0f);
        HB_UNROLL
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
            if (!deon_lobe_on(d, p, shape))
                continue;
            vf pair = p == HB_LOBE_RESIDUAL ? vf_set1(HB_RESIDUAL_DETECTOR_PAIR)
                                            : detector_pair(&d->detector[p], g->phi, node.paths.Phi[p], cos_n_phi, shape);
            vf wd = vf_mul(weight, pair);
            for (int c = 0; c < channels; c++)
                N[p][c] = vf_fma(wd, node.A[p][c], N[p][c]);
            if (pdf) {
                vf m = vf_mul(pdf->M[d->m_group[p]], channel_mean(node.A[p]));
                mass = vf_add(mass, m);
                detected = vf_fma(m, pair, detected);
            }
        }
        if (pdf) /* (P(node) / 2) detected / mass, 0 where no lobe carries mass */
            pdf->sum = vf_fma(vf_set1(d->node_half_probability[j]),
                              vf_div(detected, vf_max(mass, vf_set1(1e-37f))), pdf->sum);
    }
    vf fresnel_r = d->r_fresnel_offset ? vf_set1(1.0f) : fresnel_dielectric(g->cos_half_io, &d->ior); /* eq. 12 */
    for (int c = 0; c < 3; c++)
        N[0][c] = vf_mul(N[0][c], fresnel_r);
    if (channels == 1)
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            N[p][1] = N[p][2] = N[p][0];
}

HB_INLINE void azimuthal_deon(const hb_deon *d, const deon_geometry *g, vf N[HB_MAX_LOBES + 1][3],
                              deon_pdf_terms *pdf)
{
    if (d->standard && g->grey)
        azimuthal_deon_shaped(d, g, N, pdf, (deon_shape){ 1, 1, 0 });
    else if (d->standard)
        azimuthal_deon_shaped(d, g, N, pdf, (deon_shape){ 1, 3, 0 });
    else if (g->grey)
        azimuthal_deon_shaped(d, g, N, pdf, (deon_shape){ 0, 1, 0 });
    else
        azimuthal_deon_shaped(d, g, N, pdf, (deon_shape){ 0, 3, 0 });
}

/* N_p from a table (HB_AZIMUTHAL_TABLE; dFH11 sec. 6 suggests tabulating N_p per lobe over
 * (phi, theta_d)): for circular fibres N_p depends on the directions only through |phi| and
 * theta_d (eta' of sec. 5, mu_a' of sec. 6, Fresnel at cos(theta_d) cos(gamma_i)), and smoothly
 * in sqrt(cos(theta_d)), the table's other axis. One slot per group of lobes sharing an M_p;
 * lookup is bilinear. */
/* One table row: N summed per M_p group at one cos(theta_d) and n azimuths phi,
 * out[(k * slots + s) * 3 + c]. */
HB_INLINE void deon_np_row(const hb_deon *d, float cos_theta_d, size_t n, const float *phi, float *out)
{
    for (size_t first = 0; first < n; first += HB_W) {
        float lane_phi[HB_W];
        for (size_t l = 0; l < HB_W; l++)
            lane_phi[l] = phi[first + l < n ? first + l : n - 1];
        deon_geometry g;
        g.phi = vf_loadu(lane_phi);
        g.cos_phi = vf_cos(g.phi);
        g.cos_theta_d = vf_set1(cos_theta_d);
        g.cos_half_io = vf_set1(1.0f); /* eq. 12's factor: the table is for the offset Fresnel only */
        deon_plan_absorption(d, &g);
        vf N[HB_MAX_LOBES + 1][3];
        azimuthal_deon(d, &g, N, NULL);
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) /* non-leaders into their group's leader */
            if (hb_deon_lobe_on(d, p) && d->m_group[p] != p)
                for (int c = 0; c < 3; c++)
                    N[d->m_group[p]][c] = vf_add(N[d->m_group[p]][c], N[p][c]);
        for (int s = 0; s < d->groups; s++)
            for (int c = 0; c < 3; c++) {
                float lanes[HB_W];
                vf_storeu(lanes, N[d->group_leader[s]][c]);
                for (size_t l = 0; l < HB_W && first + l < n; l++)
                    out[((first + l) * (size_t)d->groups + (size_t)s) * 3 + (size_t)c] = lanes[l];
            }
    }
}

/* f = sum over the M_p groups of M_group N_group, N bilinear in (|phi|, sqrt(cos(theta_d))) from the
 * plan's table (slot s holds group leader group_leader[s]); M is per group leader. A cell's two
 * azimuth corners are 2 texels side by side in a row, 6 floats per slot, so each of the cell's two
 * rows is read with vf_gather4 four floats at a time (the table has 4 floats of padding for the last
 * group), and f takes one fused multiply-add per value with the weight times M of its corner and slot.
 * `slots` is a constant at each call, so the loops unroll and every value's place is known. */
HB_INLINE void deon_table_shaped(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1], vf out[3],
                                 const int channels, const int slots)
{
    vf frac[2], weight[4];
    vi cell[2];
    cell[0] = table_cell(vf_mul(vf_abs(g->phi), vf_set1((float)(d->table_phi - 1) / HB_PI_F)), d->table_phi, &frac[0]);
    cell[1] = table_cell(vf_mul(vf_sqrt(g->cos_theta_d), vf_set1((float)(d->table_cd - 1))), d->table_cd, &frac[1]);
    const int texel = 3 * slots, pair = 2 * texel;
    int stride[2] = { texel, texel * d->table_phi }, offset[4];
    vi base = cell_corners(2, cell, frac, stride, weight, offset);
    vf coef[4][HB_MAX_LOBES + 1]; /* corner k (bit 0: the next azimuth, bit 1: the next row) times M of slot s */
    HB_UNROLL
    for (int k = 0; k < 4; k++)
        HB_UNROLL
        for (int s = 0; s < slots; s++)
            coef[k][s] = vf_mul(weight[k], M[d->group_leader[s]]);
    for (int c = 0; c < 3; c++)
        out[c] = vf_set1(0.0f);
    HB_UNROLL
    for (int row = 0; row < 2; row++) {
        HB_UNROLL
        for (int first = 0; first < pair; first += 4) {
            vf value[4];
            vf_gather4(d->np_table + offset[2 * row] + first, base, value);
            HB_UNROLL
            for (int j = 0; j < 4; j++) {
                int v = first + j, c = v % 3;
                if (v < pair && c < channels)
                    out[c] = vf_fma(coef[2 * row + v / texel][v % texel / 3], value[j], out[c]);
            }
        }
    }
    if (channels == 1) /* a grey fibre: the table's channels are equal */
        out[1] = out[2] = out[0];
}

/* The colour table (HB_AZIMUTHAL_COLOUR_TABLE): per channel c, N trilinear in (w = log(1 + sigma_a,c /
 * knee) scaled, |phi|, sqrt(cos(theta_d))) at the channel's absorption (the plan's, or the sample's),
 * one value per slot. A cell's two corners along w are 2 slots side by side, read four floats at a
 * time as the material's table reads its rows. */
HB_INLINE void deon_colour_table_shaped(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1],
                                        vf out[3], const int slots)
{
    vf frac[3], weight[8], m[HB_MAX_LOBES + 1];
    vi cell[3];
    cell[1] = table_cell(vf_mul(vf_abs(g->phi), vf_set1((float)(d->table_phi - 1) / HB_PI_F)), d->table_phi, &frac[1]);
    cell[2] = table_cell(vf_mul(vf_sqrt(g->cos_theta_d), vf_set1((float)(d->table_cd - 1))), d->table_cd, &frac[2]);
    int stride[3] = { slots, slots * d->table_absorption, slots * d->table_absorption * d->table_phi }, offset[8];
    HB_UNROLL
    for (int s = 0; s < slots; s++)
        m[s] = M[d->group_leader[s]];
    const int channels = g->grey ? 1 : 3;
    for (int c = 0; c < channels; c++) {
        vf w = vf_log(vf_fma(g->absorption[c], vf_set1(d->table_sigma_scale), vf_set1(1.0f))); /* log(1 + sigma_a / knee) */
        cell[0] = table_cell(vf_mul(w, vf_set1(d->table_w_scale)), d->table_absorption, &frac[0]);
        vi base = cell_corners(3, cell, frac, stride, weight, offset);
        out[c] = vf_set1(0.0f);
        HB_UNROLL
        for (int k = 0; k < 8; k += 2) { /* corners k and k + 1 differ along x alone */
            HB_UNROLL
            for (int first = 0; first < 2 * slots; first += 4) {
                vf value[4];
                vf_gather4(d->np_table + offset[k] + first, base, value);
                HB_UNROLL
                for (int j = 0; j < 4; j++) {
                    int v = first + j;
                    if (v < 2 * slots)
                        out[c] = vf_fma(vf_mul(weight[k + v / slots], m[v % slots]), value[j], out[c]);
                }
            }
        }
    }
    if (channels == 1)
        out[1] = out[2] = out[0];
}

/* The slot counts of the standard shape as constants (R, TT, TRT, TRRT and the residual in up to five
 * M_p groups); more slots take the same body with a run-time count. */
HB_INLINE void deon_table(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1], vf out[3])
{
    if (d->table_absorption) {
        switch (d->groups) {
        case 1: deon_colour_table_shaped(d, g, M, out, 1); return;
        case 2: deon_colour_table_shaped(d, g, M, out, 2); return;
        case 3: deon_colour_table_shaped(d, g, M, out, 3); return;
        case 4: deon_colour_table_shaped(d, g, M, out, 4); return;
        default: deon_colour_table_shaped(d, g, M, out, d->groups); return;
        }
    }
    int channels = d->channels;
#define HB_TABLE_SLOTS(n)                                                                             \
    case n:                                                                                           \
        if (channels == 1)                                                                            \
            deon_table_shaped(d, g, M, out, 1, n);                                                    \
        else                                                                                          \
            deon_table_shaped(d, g, M, out, 3, n);                                                    \
        return;
    switch (d->groups) {
    HB_TABLE_SLOTS(1)
    HB_TABLE_SLOTS(2)
    HB_TABLE_SLOTS(3)
    HB_TABLE_SLOTS(4)
    HB_TABLE_SLOTS(5)
    default:
        deon_table_shaped(d, g, M, out, 3, d->groups);
    }
#undef HB_TABLE_SLOTS
}

/* u less whole periods P = 2 pi sigma, into [-P/2, P/2] (wrap_angle in a detector's units). */
HB_INLINE vf wrap_scaled(const hb_scaled_detector *s, vf u)
{
    vf k = vf_sub(vf_fma(u, vf_set1(s->inv_period), vf_set1(12582912.0f)), vf_set1(12582912.0f));
    return vf_fnma(k, vf_set1(s->period_lo), vf_fnma(k, vf_set1(s->period_hi), u));
}

/* The distance min(u, P - u) of u in [0, P] to the nearest whole period: |wrap_scaled(u)|. */
HB_INLINE vf fold_scaled(const hb_scaled_detector *s, vf u)
{
    return vf_min(u, vf_add(vf_sub(vf_set1(s->period_hi), u), vf_set1(s->period_lo)));
}

/* The standard shape's detector pair of lobe p at node j, D_p(phi - Phi) + D_p(-phi - Phi) of eq. 11
 * without its factor 1 / (beta sqrt(2 pi)): 2^-w1^2 + 2^-w2^2 with w1, w2 = sigma (|phi| -+ Phi(p, h))
 * wrapped, in the detector's units (hb_scaled_detector; sigma |phi| is in [0, P/2]). At a node
 * 0 <= gamma_t <= gamma_i <= pi/2, so R's sigma Phi_0 = -2 sigma gamma_i lies in [-P/2, 0] and TT's
 * sigma Phi_1 in [0, P/2]: one of each pair needs no wrap, the other only a fold from [0, P]. */
HB_INLINE vf detector_pair_scaled(const hb_scaled_detector *s, int p, vf offset, vf scaled_phi, vf gamma_t)
{
    vf w1, w2;
    if (p == 0) {
        w1 = fold_scaled(s, vf_sub(scaled_phi, offset)); /* sigma (|phi| + 2 gamma_i) */
        w2 = vf_add(scaled_phi, offset);                 /* sigma (|phi| - 2 gamma_i) */
    } else {
        vf Phi = vf_fma(vf_set1(s->slope), gamma_t, offset); /* sigma Phi(p, h), eq. 8, less whole turns */
        w1 = vf_sub(scaled_phi, Phi);
        w2 = vf_add(scaled_phi, Phi);
        w1 = p == 1 ? w1 : wrap_scaled(s, w1);
        w2 = p == 1 ? fold_scaled(s, w2) : wrap_scaled(s, w2);
    }
    return vf_add(vf_exp2_neg(vf_mul(w1, w1)), vf_exp2_neg(vf_mul(w2, w2)));
}

/* f = sum_p M_p N_p for the standard shape with M_p folded into the sum over nodes, so that three
 * accumulators replace one N per lobe and channel. Per node j, with the weighted attenuations
 * a_p = weight_j A_f[p] (eq. 13 without T), pairs of eq. 11 and M'_p = M_p / (beta_p sqrt(2 pi)),
 * s_p = a_p M'_p pair_p (0 for a lobe the plan leaves out) and the residual's q = a_4 M_res / pi,
 * the channel's sum over p of A(p, h) M_p D_p (eqs. 10, 13) is
 * s_0 + T (s_1 + T (s_2 + T (s_3 + T q / (1 - f T)))). The node's f (eq. 14), T (sec. 6, with
 * 2 cos(gamma_t) per traversal, docs/conventions.md) and gamma_t are formed once for every lobe. M is per M_p
 * group (the group leader's index); with pdf, the sampling density's node sum as
 * azimuthal_deon_shaped forms it. */

/* What every node of the fused sum reads from the sample, formed once per sample. */
typedef struct deon_fused_sample {
    deon_medium medium;
    vf mu2[HB_DEON_CHANNELS], M_scaled[HB_STANDARD_PMAX + 1], scaled_phi[HB_STANDARD_PMAX + 1], M_residual;
    const vf *M;
} deon_fused_sample;

/* Node constants as vectors: one node in every lane (a batch of samples), or a block of nodes
 * across the lanes (one sample; unused lanes have weight 0). */
typedef struct deon_fused_nodes {
    vf h, cos_gamma_i, weight, half_probability, offset[HB_STANDARD_PMAX + 1];
} deon_fused_nodes;

/* The running sums of the node loop: R's (the same in every channel), the channels', the pdf's. */
typedef struct deon_fused_sums {
    vf R, rgb[HB_DEON_CHANNELS], pdf;
} deon_fused_sums;

HB_INLINE void deon_fused_prepare(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1],
                                  deon_fused_sample *s, deon_fused_sums *sums, deon_shape shape)
{
    deon_medium_of(d, g, &s->medium, shape.channels);
    vf abs_phi = vf_abs(g->phi);
    HB_UNROLL
    for (int c = 0; c < HB_DEON_CHANNELS; c++) /* two cos(gamma_t) per traversal */
        s->mu2[c] = c < shape.channels ? vf_add(s->medium.mu_log2e[c], s->medium.mu_log2e[c]) : vf_set1(0.0f);
    HB_UNROLL
    for (int p = 0; p <= HB_STANDARD_PMAX; p++) {
        s->M_scaled[p] = deon_lobe_on(d, p, shape) ? vf_mul(M[d->m_group[p]], vf_set1(d->detector[p].gauss_norm))
                                                   : vf_set1(0.0f);
        s->scaled_phi[p] = vf_mul(abs_phi, vf_set1(d->scaled[p].scale));
    }
    s->M_residual = deon_lobe_on(d, HB_LOBE_RESIDUAL, shape)
                        ? vf_mul(M[d->m_group[HB_LOBE_RESIDUAL]], vf_set1(HB_RESIDUAL_DETECTOR_PAIR))
                        : vf_set1(0.0f);
    s->M = M;
    sums->R = sums->pdf = vf_set1(0.0f);
    HB_UNROLL
    for (int c = 0; c < HB_DEON_CHANNELS; c++)
        sums->rgb[c] = vf_set1(0.0f);
}

HB_INLINE void deon_fused_node(const hb_deon *d, const deon_fused_sample *s, const deon_fused_nodes *node,
                               deon_fused_sums *sums, int with_pdf, deon_shape shape)
{
    const int channels = shape.channels;
    vf sin_gamma_t = vf_mul(node->h, s->medium.inv_eta_prime);
    vf cos_gamma_t = vf_sqrt(vf_fnma(sin_gamma_t, sin_gamma_t, vf_set1(1.0f)));
    vf gamma_t = d->asin_narrow ? vf_asin_narrow(sin_gamma_t, vf_mul(sin_gamma_t, sin_gamma_t)) : vf_asin(sin_gamma_t);
    /* eq. 14, with 1 - f formed on its own: it keeps its digits as f -> 1 at grazing incidence */
    vf one_minus_f, f = fresnel_dielectric_pair(vf_mul(s->medium.cos_theta_d, node->cos_gamma_i), &d->ior, &one_minus_f);
    vf a[HB_STANDARD_PMAX + 2];
    a[0] = vf_mul(node->weight, f);
    a[1] = vf_mul(vf_mul(one_minus_f, one_minus_f), node->weight); /* (1 - f)^2 f^(p-1), eq. 13 */
    HB_UNROLL
    for (int p = 2; p <= HB_STANDARD_PMAX + 1; p++)
        a[p] = vf_mul(a[p - 1], f);
    vf T[HB_DEON_CHANNELS], pair[HB_STANDARD_PMAX + 1], sp[HB_STANDARD_PMAX + 1];
    HB_UNROLL
    for (int c = 0; c < HB_DEON_CHANNELS; c++)
        T[c] = c < channels ? vf_exp2_neg(vf_mul(s->mu2[c], cos_gamma_t)) : vf_set1(0.0f);
    HB_UNROLL
    for (int p = 0; p <= HB_STANDARD_PMAX; p++) {
        pair[p] = deon_lobe_on(d, p, shape)
                      ? detector_pair_scaled(&d->scaled[p], p, node->offset[p], s->scaled_phi[p], gamma_t)
                      : vf_set1(0.0f);
        sp[p] = vf_mul(a[p], vf_mul(s->M_scaled[p], pair[p]));
    }
    vf q = vf_mul(a[HB_STANDARD_PMAX + 1], s->M_residual);
    sums->R = vf_add(sums->R, sp[0]);
    vf series[HB_DEON_CHANNELS];
    HB_UNROLL
    for (int c = 0; c < HB_DEON_CHANNELS; c++) {
        if (c >= channels)
            continue;
        series[c] = residual_series(f, one_minus_f, T[c]);
        vf inner = vf_fma(T[c], vf_mul(q, series[c]), sp[3]);
        inner = vf_fma(T[c], inner, sp[2]);
        inner = vf_fma(T[c], inner, sp[1]);
        sums->rgb[c] = vf_fma(T[c], inner, sums->rgb[c]);
    }
    if (with_pdf) { /* m_p = M_p times A(p, h) averaged over the channels (the node's weight cancels) */
        vf A[3], T_power[3], mass = vf_set1(0.0f), detected = vf_set1(0.0f);
        HB_UNROLL
        for (int c = 0; c < 3; c++)
            T_power[c] = vf_set1(1.0f);
        HB_UNROLL
        for (int p = 0; p <= HB_STANDARD_PMAX + 1; p++) { /* the last: the residual's orders */
            HB_UNROLL
            for (int c = 0; c < 3; c++) {
                int k = channels == 1 ? 0 : c;
                vf series_k = p == HB_STANDARD_PMAX + 1 ? series[k] : vf_set1(1.0f);
                A[c] = vf_mul(vf_mul(a[p], T_power[c]), series_k);
                T_power[c] = vf_mul(T_power[c], T[k]);
            }
            int lobe = p == HB_STANDARD_PMAX + 1 ? HB_LOBE_RESIDUAL : p;
            vf m = deon_lobe_on(d, lobe, shape) ? vf_mul(s->M[d->m_group[lobe]], channel_mean(A)) : vf_set1(0.0f);
            vf detector = lobe == HB_LOBE_RESIDUAL ? vf_set1(HB_RESIDUAL_DETECTOR_PAIR)
                                                   : vf_mul(pair[lobe], vf_set1(d->detector[lobe].gauss_norm));
            mass = vf_add(mass, m);
            detected = vf_fma(m, detector, detected);
        }
        sums->pdf = vf_fma(node->half_probability, vf_div(detected, vf_max(mass, vf_set1(1e-37f))), sums->pdf);
    }
}

HB_INLINE void deon_fused_shaped(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1],
                                 vf *out, deon_pdf_terms *pdf, deon_shape shape)
{
    deon_fused_sample s;
    deon_fused_sums sums;
    deon_fused_prepare(d, g, M, &s, &sums, shape);
    for (int j = 0; j < d->nodes; j++) {
        deon_fused_nodes node = { vf_set1(d->h[j]), vf_set1(d->cos_gamma_i[j]), vf_set1(d->weight[j]),
                                  vf_set1(d->node_half_probability[j]), { vf_set1(0.0f) } };
        HB_UNROLL
        for (int p = 0; p <= HB_STANDARD_PMAX; p++)
            node.offset[p] = vf_set1(d->scaled[p].offset[j]);
        deon_fused_node(d, &s, &node, &sums, pdf != NULL, shape);
    }
    if (pdf)
        pdf->sum = sums.pdf;
    HB_UNROLL /* a grey fibre's one channel copied to three; else every channel its own */
    for (int c = 0; c < HB_DEON_CHANNELS; c++)
        if (c < (shape.channels == 1 ? 3 : shape.channels))
            out[c] = vf_add(sums.rgb[shape.channels == 1 ? 0 : c], sums.R);
}

/* The same for one sample whose value fills every lane of g and M, with the nodes across the lanes
 * of one register (HB_REG_W at a time, the plan's node arrays zero past its count): one register's
 * work for up to HB_REG_W nodes instead of a block per node, for a path tracer's call of a few
 * samples (on AVX2, two 8-lane steps for 10 nodes keep half the values live that one 16-lane step
 * does: 1368 instructions per call against 1458, most of the difference spills). f and the pdf's sum
 * come back in every lane; the sum over nodes runs in another order than deon_fused_shaped's, which
 * moves the result by a rounding. */
HB_INLINE void deon_fused_one_shaped(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1],
                                     vf out[3], deon_pdf_terms *pdf, deon_shape shape)
{
    deon_fused_sample s;
    deon_fused_sums sums;
    deon_fused_prepare(d, g, M, &s, &sums, shape);
    for (int j = 0; j < d->nodes; j += HB_REG_W) {
        deon_fused_nodes node = { vf_load_reg(d->h + j), vf_load_reg(d->cos_gamma_i + j), vf_load_reg(d->weight + j),
                                  vf_load_reg(d->node_half_probability + j), { vf_set1(0.0f) } };
        HB_UNROLL
        for (int p = 0; p <= HB_STANDARD_PMAX; p++)
            node.offset[p] = vf_load_reg(d->scaled[p].offset + j);
        deon_fused_node(d, &s, &node, &sums, pdf != NULL, shape);
    }
    if (pdf)
        pdf->sum = vf_set1(vf_sum_reg(sums.pdf));
    for (int c = 0; c < 3; c++)
        out[c] = vf_set1(vf_sum_reg(vf_add(sums.rgb[shape.channels == 1 ? 0 : c], sums.R)));
}

HB_INLINE void deon_fused(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1], vf out[3],
                          deon_pdf_terms *pdf)
{
    int all = d->lobes == HB_STANDARD_LOBES;
    if (all && g->grey)
        deon_fused_shaped(d, g, M, out, pdf, (deon_shape){ 1, 1, 1 });
    else if (all)
        deon_fused_shaped(d, g, M, out, pdf, (deon_shape){ 1, 3, 1 });
    else if (g->grey)
        deon_fused_shaped(d, g, M, out, pdf, (deon_shape){ 1, 1, 0 });
    else
        deon_fused_shaped(d, g, M, out, pdf, (deon_shape){ 1, 3, 0 });
}

/* deon_fused for one sample, its value in every lane, the nodes across the lanes: two shapes serve
 * every standard plan, all of its lobes or a lobe set read at run time (three channels even for a
 * grey fibre). */
HB_INLINE void deon_fused_one(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1], vf out[3],
                              deon_pdf_terms *pdf)
{
    if (d->lobes == HB_STANDARD_LOBES)
        deon_fused_one_shaped(d, g, M, out, pdf, (deon_shape){ 1, 3, 1 });
    else
        deon_fused_one_shaped(d, g, M, out, pdf, (deon_shape){ 1, 3, 0 });
}

/* f by quadrature from M per group leader (longitudinal_deon_groups_*): the standard shape folds M_p
 * into the node sum (above), any other sums N_p per lobe first and adds the lobes of equal M_p before
 * multiplying, so each distinct M_p is evaluated once. */
HB_STAGE void deon_quadrature_general(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1],
                                      vf out[3])
{
    vf N[HB_MAX_LOBES + 1][3];
    azimuthal_deon(d, g, N, NULL);
    out[0] = out[1] = out[2] = vf_set1(0.0f);
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        int group = d->m_group[p];
        if (group == p || !hb_deon_lobe_on(d, p))
            continue;
        for (int c = 0; c < 3; c++)
            N[group][c] = vf_add(N[group][c], N[p][c]);
    }
    for (int group = 0; group < d->groups; group++) {
        const int p = d->group_leader[group];
        for (int c = 0; c < 3; c++)
            out[c] = vf_fma(M[p], N[p][c], out[c]);
    }
}

/* The standard shape's fused sum, or the general node loop as its own stage (its per-node lobes
 * would crowd the fused loop's registers in one function). */
HB_STAGE void deon_quadrature(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1], vf out[3])
{
    if (d->standard)
        deon_fused(d, g, M, out, NULL);
    else
        deon_quadrature_general(d, g, M, out);
}

/* f for the plan's shape: a table plan looks N up per M_p group (inline: a few dozen operations), the
 * quadrature is one stage that the angle and vector kernels and both I0 variants share. */
HB_INLINE void deon_eval(const hb_deon *d, const deon_geometry *g, const vf M[HB_MAX_LOBES + 1], vf out[3])
{
    if (d->np_table)
        deon_table(d, g, M, out);
    else
        deon_quadrature(d, g, M, out);
}

/* deon_geometry from angles. */
HB_INLINE void deon_geometry_angles(const hb_deon *d, vf theta_i, vf phi_i, vf theta_o, vf phi_o, deon_geometry *g)
{
    g->phi = wrap_angle(vf_sub(phi_o, phi_i));
    /* read by Fourier detectors and eq. 12 only (a table reads |phi|, the standard shape sigma |phi|) */
    g->cos_phi = !d->np_table && (d->fourier_terms > 0 || !d->r_fresnel_offset) ? vf_cos(g->phi) : vf_set1(1.0f);
    /* |theta_d| <= pi/2: one sine polynomial, no reduction, relative-accurate near the pole */
    g->cos_theta_d = cos_half_difference(theta_o, theta_i);
    g->cos_half_io = vf_set1(1.0f);
    deon_plan_absorption(d, g);
    if (!d->r_fresnel_offset) { /* two more sine-cosine pairs only for eq. 12 */
        vf si, ci, so, co;
        vf_sincos(theta_i, &si, &ci);
        vf_sincos(theta_o, &so, &co);
        vf dot = vf_fma(vf_mul(ci, co), g->cos_phi, vf_mul(si, so));
        g->cos_half_io = vf_sqrt(vf_max(vf_fma(dot, vf_set1(0.5f), vf_set1(0.5f)), vf_set1(0.0f)));
    }
}

/* f from angles. */
HB_INLINE void deon_angles(const hb_deon *d, vf theta_i, vf phi_i, vf theta_o, vf phi_o, hb_i0 i0, vf out[3])
{
    deon_geometry g;
    deon_geometry_angles(d, theta_i, phi_i, theta_o, phi_o, &g);
    vf M[HB_MAX_LOBES + 1];
    longitudinal_deon_groups_angles(d, theta_i, theta_o, i0, M);
    deon_eval(d, &g, M, out);
}

/* f from unit vectors: the geometry comes from dot products, no trigonometry but one atan2. */
HB_INLINE void deon_vectors(const hb_deon *d, const vf wi[3], const vf wo[3], hb_i0 i0, vf out[3])
{
    deon_geometry g;
    vf inv_i = vf_div(vf_set1(1.0f), vf_sqrt(vf_fma(wi[0], wi[0], vf_fma(wi[1], wi[1], vf_mul(wi[2], wi[2])))));
    vf inv_o = vf_div(vf_set1(1.0f), vf_sqrt(vf_fma(wo[0], wo[0], vf_fma(wo[1], wo[1], vf_mul(wo[2], wo[2])))));
    vf si = vf_mul(wi[1], inv_i), so = vf_mul(wo[1], inv_o);
    vf ci = vf_mul(vf_sqrt(vf_fma(wi[0], wi[0], vf_mul(wi[2], wi[2]))), inv_i);
    vf co = vf_mul(vf_sqrt(vf_fma(wo[0], wo[0], vf_mul(wo[2], wo[2]))), inv_o);
    g.phi = azimuth_difference(wi, wo); /* from the planar components (scale drops out of atan2) */
    g.cos_phi = !d->np_table && d->fourier_terms > 0 ? vf_cos(g.phi) : vf_set1(1.0f); /* Fourier detectors only */
    /* cos(theta_d) = |(cos theta_i + cos theta_o, sin theta_i + sin theta_o)| / 2: both sums are small
     * and exact to their operands' rounding near opposite poles, where sqrt((1 + cos(2 theta_d)) / 2)
     * cancels */
    vf cs = vf_add(ci, co), ss = vf_add(si, so);
    g.cos_theta_d = vf_mul(vf_set1(0.5f), vf_sqrt(vf_fma(cs, cs, vf_mul(ss, ss))));
    vf dot = vf_mul(vf_mul(inv_i, inv_o), vf_fma(wi[0], wo[0], vf_fma(wi[1], wo[1], vf_mul(wi[2], wo[2]))));
    g.cos_half_io = vf_sqrt(vf_max(vf_fma(dot, vf_set1(0.5f), vf_set1(0.5f)), vf_set1(0.0f)));
    deon_plan_absorption(d, &g);
    vf M[HB_MAX_LOBES + 1];
    longitudinal_deon_groups_vectors(d, wi, wo, i0, M);
    deon_eval(d, &g, M, out);
}

#endif

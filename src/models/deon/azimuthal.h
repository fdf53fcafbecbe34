/* dFH11 azimuthal scattering N_p (eqs. 8, 10-14) and the full model f = sum_p M_p N_p,
 * over the SIMD vocabulary. Loop counts (nodes, orders, detector terms) come from the
 * plan, never from the samples. */
#ifndef HB_DEON_AZIMUTHAL_H
#define HB_DEON_AZIMUTHAL_H

#include "longitudinal.h"
#include "../fresnel.h"

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

/* D_p(phi - Phi) + D_p(-phi - Phi), eq. 11: detection at phi and -phi covers h < 0.
 * Fourier form: cos(n(phi - Phi)) + cos(n(-phi - Phi)) = 2 cos(n phi) cos(n Phi). */
HB_INLINE vf detector_pair(const hb_detector *d, vf phi, vf Phi, const vf *cos_n_phi)
{
    if (d->fourier) {
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
    vf sum = vf_set1(0.0f);
    for (int k = -d->terms; k <= d->terms; k++) {
        vf d1 = vf_sub(x1, vf_set1(HB_TWO_PI_F * (float)k)), d2 = vf_sub(x2, vf_set1(HB_TWO_PI_F * (float)k));
        sum = vf_add(sum, vf_exp_flush(vf_mul(vf_mul(d1, d1), vf_set1(-d->inv_two_beta2))));
        sum = vf_add(sum, vf_exp_flush(vf_mul(vf_mul(d2, d2), vf_set1(-d->inv_two_beta2))));
    }
    return vf_mul(sum, vf_set1(d->gauss_norm));
}

HB_INLINE vf channel_mean(const vf rgb[3])
{
    return vf_mul(vf_add(vf_add(rgb[0], rgb[1]), rgb[2]), vf_set1(1.0f / 3.0f));
}

/* Per-sample geometry the azimuthal part needs. */
typedef struct deon_geometry {
    vf phi;          /* phi_o - phi_i in [-pi, pi] */
    vf cos_phi;
    vf sin2_theta_d; /* theta_d = (theta_o - theta_i)/2 */
    vf cos_theta_d;
    vf cos_half_io;  /* cos of half the angle between w_i and w_o */
} deon_geometry;

/* What every node of the h quadrature needs from a sample: eta' (sec. 5) and mu_a' (sec. 6). */
typedef struct deon_medium {
    vf cos_theta_d;
    vf inv_eta_prime; /* 1 / eta' = cos(theta_d) / sqrt(eta^2 - sin^2(theta_d)) */
    vf mu[3];         /* mu_a' = mu_a / cos(theta_t), per channel */
} deon_medium;

/* channels: 3, or 1 for a grey fibre (a constant at every call, so the loops unroll) */
HB_INLINE void deon_medium_of(const hb_deon *d, const deon_geometry *g, deon_medium *m, const int channels)
{
    m->cos_theta_d = g->cos_theta_d;
    m->inv_eta_prime = vf_div(g->cos_theta_d, vf_sqrt(vf_sub(vf_set1(d->ior.eta * d->ior.eta), g->sin2_theta_d))); /* sec. 5 */
    vf cos_theta_t = vf_sqrt(vf_fnma(g->sin2_theta_d, vf_set1(d->ior.inv_eta2), vf_set1(1.0f)));
    for (int c = 0; c < channels; c++)
        m->mu[c] = vf_div(vf_set1(d->sigma_a[c]), cos_theta_t);
}

/* Attenuation A(p, h) (eqs. 12-14, RGB) and exit azimuth Phi(p, h) (eq. 8) of every lobe of the
 * plan at one offset h = sin(gamma_i). A[HB_LOBE_RESIDUAL] = sum_{p > pmax} A(p, h). Without
 * the offset Fresnel option, A[R] = 1 and eq. 12's factor is applied by the caller. */
typedef struct deon_node {
    vf A[HB_MAX_LOBES + 1][3];
    vf Phi[HB_MAX_LOBES];
} deon_node;

HB_INLINE void deon_node_lobes(const hb_deon *d, const deon_medium *m, vf h, vf gamma_i, vf cos_gamma_i,
                               deon_node *node, const int channels)
{
    vf sin_gamma_t = vf_mul(h, m->inv_eta_prime);
    vf cos_gamma_t = vf_sqrt(vf_fnma(sin_gamma_t, sin_gamma_t, vf_set1(1.0f)));
    vf gamma_t = vf_asin(sin_gamma_t);
    vf f = fresnel_dielectric(vf_mul(m->cos_theta_d, cos_gamma_i), &d->ior); /* eq. 14 */
    /* path length per traversal: 2 cos(gamma_t), or the printed 2 (1 + cos 2 gamma_t) (SPEC.md 4) */
    vf path = d->absorption_paper ? vf_mul(vf_set1(4.0f), vf_mul(cos_gamma_t, cos_gamma_t))
                                  : vf_add(cos_gamma_t, cos_gamma_t);
    vf T[3], T_power[3];
    for (int c = 0; c < channels; c++)
        T_power[c] = T[c] = vf_exp_flush(vf_neg(vf_mul(m->mu[c], path)));
    if (d->lobes & 1u) {
        node->Phi[0] = vf_mul(vf_set1(-2.0f), gamma_i); /* eq. 8, p = 0 */
        node->A[0][0] = node->A[0][1] = node->A[0][2] = d->r_fresnel_offset ? f : vf_set1(1.0f);
    }
    vf A = vf_mul(vf_sub(vf_set1(1.0f), f), vf_sub(vf_set1(1.0f), f)); /* (1 - f)^2 f^(p-1), eq. 13 */
    for (int p = 1; p <= d->pmax; p++) {
        if (d->lobes >> p & 1u) {
            node->Phi[p] = vf_fma(vf_set1(2.0f * (float)p), gamma_t,
                                  vf_fnma(vf_set1(2.0f), gamma_i, vf_set1((float)p * 3.14159265f))); /* eq. 8 */
            for (int c = 0; c < channels; c++)
                node->A[p][c] = vf_mul(A, T_power[c]);
        }
        A = vf_mul(A, f);
        for (int c = 0; c < channels; c++)
            T_power[c] = vf_mul(T_power[c], T[c]);
    }
    if (d->lobes >> HB_LOBE_RESIDUAL & 1u) { /* sum_{p > pmax} A(p, h) = A(pmax+1, h) / (1 - f T) */
        for (int c = 0; c < channels; c++) {
            vf geometric = vf_max(vf_fnma(f, T[c], vf_set1(1.0f)), vf_set1(1e-30f));
            node->A[HB_LOBE_RESIDUAL][c] = vf_div(vf_mul(A, T_power[c]), geometric);
        }
    }
    if (channels == 1) /* a grey fibre: the other channels are copies (register moves) */
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            if (hb_deon_lobe_on(d, p))
                node->A[p][1] = node->A[p][2] = node->A[p][0];
}

/* The residual lobe's pair of detectors: uniform in phi, 2 / (2 pi). */
#define HB_RESIDUAL_DETECTOR_PAIR 0.318309886f

/* For the sampling density (README, "Sampling"): M_p at the sample per lobe (NULL when only f is
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
HB_INLINE void azimuthal_deon_channels(const hb_deon *d, const deon_geometry *g, vf N[HB_MAX_LOBES + 1][3],
                                       deon_pdf_terms *pdf, const int channels)
{
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
                        channels);
        vf mass = vf_set1(0.0f), detected = vf_set1(0.0f);
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
            if (!hb_deon_lobe_on(d, p))
                continue;
            vf pair = p == HB_LOBE_RESIDUAL ? vf_set1(HB_RESIDUAL_DETECTOR_PAIR)
                                            : detector_pair(&d->detector[p], g->phi, node.Phi[p], cos_n_phi);
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
    if (d->channels == 1)
        azimuthal_deon_channels(d, g, N, pdf, 1);
    else
        azimuthal_deon_channels(d, g, N, pdf, 3);
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
        g.sin2_theta_d = vf_set1(1.0f - cos_theta_d * cos_theta_d);
        g.cos_half_io = vf_set1(1.0f); /* eq. 12's factor: the table is for the offset Fresnel only */
        vf N[HB_MAX_LOBES + 1][3];
        azimuthal_deon(d, &g, N, NULL);
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) /* non-leaders into their group's leader */
            if (hb_deon_lobe_on(d, p) && d->m_group[p] != p)
                for (int c = 0; c < 3; c++)
                    N[d->m_group[p]][c] = vf_add(N[d->m_group[p]][c], N[p][c]);
        for (int s = 0; s < d->table_slots; s++)
            for (int c = 0; c < 3; c++) {
                float lanes[HB_W];
                vf_storeu(lanes, N[d->table_leader[s]][c]);
                for (size_t l = 0; l < HB_W && first + l < n; l++)
                    out[((first + l) * (size_t)d->table_slots + (size_t)s) * 3 + (size_t)c] = lanes[l];
            }
    }
}

/* N per M_p group leader, bilinear in (sqrt(cos(theta_d)), |phi|); every other N is 0, so
 * HB_DEON_SUM adds nothing for the non-leaders. */
HB_INLINE void azimuthal_deon_table(const hb_deon *d, const deon_geometry *g, vf N[HB_MAX_LOBES + 1][3])
{
    vf zero = vf_set1(0.0f), one = vf_set1(1.0f);
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        N[p][0] = N[p][1] = N[p][2] = zero;
    vf x = vf_clamp(vf_mul(vf_sqrt(g->cos_theta_d), vf_set1((float)(d->table_cd - 1))), 0.0f, (float)(d->table_cd - 1));
    vf y = vf_clamp(vf_mul(vf_abs(g->phi), vf_set1((float)(d->table_phi - 1) / HB_PI_F)), 0.0f,
                    (float)(d->table_phi - 1));
    vf row = vf_min(vf_from_vi(vi_from_vf(x)), vf_set1((float)(d->table_cd - 2)));
    vf column = vf_min(vf_from_vi(vi_from_vf(y)), vf_set1((float)(d->table_phi - 2)));
    vf fx = vf_sub(x, row), fy = vf_sub(y, column);
    int texel = 3 * d->table_slots, row_stride = texel * d->table_phi;
    vi base = vi_add(vi_mul(vi_from_vf(row), vi_set1(row_stride)), vi_mul(vi_from_vf(column), vi_set1(texel)));
    vf weight[4] = { vf_mul(vf_sub(one, fx), vf_sub(one, fy)), vf_mul(vf_sub(one, fx), fy),
                     vf_mul(fx, vf_sub(one, fy)), vf_mul(fx, fy) };
    int offset[4] = { 0, texel, row_stride, row_stride + texel };
    for (int corner = 0; corner < 4; corner++) {
        vi index = vi_add(base, vi_set1(offset[corner]));
        for (int s = 0; s < d->table_slots; s++)
            for (int c = 0; c < d->channels; c++)
                N[d->table_leader[s]][c] =
                    vf_fma(weight[corner], vf_gather(d->np_table + 3 * s + c, index), N[d->table_leader[s]][c]);
    }
    if (d->channels == 1) /* a grey fibre: one gather per corner and slot, copied */
        for (int s = 0; s < d->table_slots; s++)
            N[d->table_leader[s]][1] = N[d->table_leader[s]][2] = N[d->table_leader[s]][0];
}

/* f = sum_p M_p N_p over the plan's lobes, with lobes of equal M_p summed first so each
 * distinct M_p is evaluated once; M_p from a caller-supplied evaluator so the angle and
 * vector entry points share everything else. */
#define HB_DEON_SUM(d, N, out, longitudinal_of_lobe)                                    \
    do {                                                                                \
        (out)[0] = (out)[1] = (out)[2] = vf_set1(0.0f);                                 \
        for (int p_ = 0; p_ <= HB_LOBE_RESIDUAL; p_++) {                                \
            int g_ = (d)->m_group[p_];                                                  \
            if (g_ == p_ || !hb_deon_lobe_on((d), p_))                                  \
                continue;                                                               \
            for (int c_ = 0; c_ < 3; c_++)                                              \
                (N)[g_][c_] = vf_add((N)[g_][c_], (N)[p_][c_]);                         \
        }                                                                               \
        for (int p_ = 0; p_ <= HB_LOBE_RESIDUAL; p_++) {                                \
            if (!hb_deon_group_leader((d), p_))                                         \
                continue;                                                               \
            vf m_ = longitudinal_of_lobe(&(d)->longitudinal[p_]);                       \
            for (int c_ = 0; c_ < 3; c_++)                                              \
                (out)[c_] = vf_fma(m_, (N)[p_][c_], (out)[c_]);                         \
        }                                                                               \
    } while (0)

/* deon_geometry from angles. */
HB_INLINE void deon_geometry_angles(vf theta_i, vf phi_i, vf theta_o, vf phi_o, deon_geometry *g)
{
    vf si, ci, so, co, sin_phi, sin_td, cos_td;
    g->phi = wrap_angle(vf_sub(phi_o, phi_i));
    vf_sincos(theta_i, &si, &ci);
    vf_sincos(theta_o, &so, &co);
    vf_sincos(g->phi, &sin_phi, &g->cos_phi);
    vf_sincos(vf_mul(vf_set1(0.5f), vf_sub(theta_o, theta_i)), &sin_td, &cos_td);
    g->sin2_theta_d = vf_mul(sin_td, sin_td);
    g->cos_theta_d = vf_max(cos_td, vf_set1(0.0f));
    vf dot = vf_fma(vf_mul(ci, co), g->cos_phi, vf_mul(si, so));
    g->cos_half_io = vf_sqrt(vf_max(vf_fma(dot, vf_set1(0.5f), vf_set1(0.5f)), vf_set1(0.0f)));
}

/* f from angles. */
HB_INLINE void deon_angles(const hb_deon *d, vf theta_i, vf phi_i, vf theta_o, vf phi_o, hb_i0 i0, vf out[3])
{
    deon_geometry g;
    deon_geometry_angles(theta_i, phi_i, theta_o, phi_o, &g);
    vf N[HB_MAX_LOBES + 1][3];
    if (d->np_table)
        azimuthal_deon_table(d, &g, N);
    else
        azimuthal_deon(d, &g, N, NULL);
#define HB_M_ANGLES(lobe) longitudinal_deon_angles((lobe), theta_i, theta_o, i0)
    HB_DEON_SUM(d, N, out, HB_M_ANGLES);
#undef HB_M_ANGLES
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
    /* phi = phi_o - phi_i from the planar components (scale drops out of atan2) */
    vf sin_part = vf_fnma(wo[2], wi[0], vf_mul(wo[0], wi[2]));
    vf cos_part = vf_fma(wo[0], wi[0], vf_mul(wo[2], wi[2]));
    g.phi = vf_atan2(sin_part, cos_part);
    g.cos_phi = vf_cos(g.phi);
    vf cos_diff = vf_fma(ci, co, vf_mul(si, so)); /* cos(theta_o - theta_i) = cos(2 theta_d) */
    g.cos_theta_d = vf_sqrt(vf_max(vf_fma(cos_diff, vf_set1(0.5f), vf_set1(0.5f)), vf_set1(0.0f)));
    g.sin2_theta_d = vf_max(vf_fnma(cos_diff, vf_set1(0.5f), vf_set1(0.5f)), vf_set1(0.0f));
    vf dot = vf_mul(vf_mul(inv_i, inv_o), vf_fma(wi[0], wo[0], vf_fma(wi[1], wo[1], vf_mul(wi[2], wo[2]))));
    g.cos_half_io = vf_sqrt(vf_max(vf_fma(dot, vf_set1(0.5f), vf_set1(0.5f)), vf_set1(0.0f)));
    vf N[HB_MAX_LOBES + 1][3];
    if (d->np_table)
        azimuthal_deon_table(d, &g, N);
    else
        azimuthal_deon(d, &g, N, NULL);
#define HB_M_VECTORS(lobe) longitudinal_deon_vectors((lobe), wi, wo, i0)
    HB_DEON_SUM(d, N, out, HB_M_VECTORS);
#undef HB_M_VECTORS
}

#endif

/* dFH11's batch kernels for one ISA: the Makefile compiles this file once per instruction
 * set (-DHB_TARGET_<NAME> and that ISA's flags) into hb_<isa>_deon_kernels. */
#include "kernel/batch.h"
#include "kernels.h"
#include "sample.h"

HB_INLINE vm load_deon_sample(const hb_sample_batch *b, size_t i, size_t lanes, vf *a)
{
    return load_sample(b, HB_DEON_SAMPLE_DIMENSIONS, i, lanes, a);
}

HB_INLINE vm load_deon_sample_near(hb_sample_near_in in, size_t i, size_t lanes, vf *a)
{
    return load_sample_near(in, HB_DEON_NEAR_DIMENSIONS, i, lanes, a);
}

/* The near field at a[4] = h: f, and the pdf where pdf is not NULL. */
HB_INLINE void deon_near_angles(const hb_deon *d, const vf a[5], hb_i0 i0, vf f[3], vf *pdf)
{
    vf M[HB_MAX_LOBES + 1];
    deon_longitudinal_groups(d, a[0], a[2], i0, M);
    deon_geometry g;
    deon_geometry_angles(d, a[0], a[1], a[2], a[3], &g);
    if (pdf)
        *pdf = deon_near_f_pdf(d, M, &g, a[2], a[4], f);
    else
        deon_near(d, &g, M, a[4], f, NULL);
}

/* f and the pdf in one pass (quadrature plans: deon_f_pdf's f is deon_eval's). */
HB_INLINE vf deon_f_pdf_angles(const hb_deon *d, const vf a[4], hb_i0 i0, vf f[3])
{
    vf M[HB_MAX_LOBES + 1];
    deon_longitudinal_groups(d, a[0], a[2], i0, M);
    deon_geometry g;
    deon_geometry_angles(d, a[0], a[1], a[2], a[3], &g);
    return deon_f_pdf(d, M, &g, a[2], f);
}

/* f at each sample's absorption a[4..6] (load_absorbing), by the quadrature or the colour table: the
 * plan's geometry with the sample's sigma_a in every channel, three channels computed. */
HB_INLINE void deon_absorbing_angles(const hb_deon *d, const vf a[7], hb_i0 i0, vf f[3])
{
    vf M[HB_MAX_LOBES + 1];
    deon_longitudinal_groups(d, a[0], a[2], i0, M);
    deon_geometry g;
    deon_geometry_angles(d, a[0], a[1], a[2], a[3], &g);
    for (int c = 0; c < 3; c++)
        g.absorption[c] = a[4 + c];
    g.grey = 0;
    deon_eval(d, &g, M, f);
}

/* Calls of fewer than HB_DEON_ONE_MAX samples on a standard quadrature plan take each sample alone
 * with the quadrature's nodes across the lanes (azimuthal.h, deon_fused_one): a path tracer's call at
 * a hit costs one sample's work instead of a block of HB_W lanes. Measured (make bench, balanced, 10
 * nodes): one sample alone 299 ns on AVX2, 239 on AVX-512, 329 on SSE4.1, a block 899, 518 and 671
 * ns, so from three samples on the block is as cheap. */
#define HB_DEON_ONE_MAX 3

HB_INLINE int deon_one_by_one(const hb_deon *d, size_t n) { return HB_W > 1 && d->standard && !d->np_table && n < HB_DEON_ONE_MAX; }

/* f, and the pdf where pdf is not NULL, sample by sample. */
HB_INLINE void deon_one_by_one_angles(const hb_deon *d, size_t n, hb_angles_soa in, hb_rgb_soa out, float *pdf,
                                      hb_i0 i0, size_t *invalid)
{
    hb_fp_mode mode = hb_flush_subnormals();
    size_t bad = 0;
    for (size_t k = 0; k < n; k++) {
        vf a[4], M[HB_MAX_LOBES + 1], f[3];
        vm valid = load_angles_one(in, k, a);
        deon_longitudinal_groups(d, a[0], a[2], i0, M);
        deon_geometry g;
        deon_geometry_angles(d, a[0], a[1], a[2], a[3], &g);
        if (pdf)
            store_one(pdf, k, valid, deon_f_pdf_of(d, M, &g, a[2], f, 1));
        else
            deon_fused_one(d, &g, M, f, NULL);
        store_one(out.r, k, valid, f[0]);
        store_one(out.g, k, valid, f[1]);
        store_one(out.b, k, valid, f[2]);
        bad += !(vm_bits(valid) & 1u);
    }
    *invalid = bad;
    hb_fp_restore(mode);
}

/* One specialised kernel per I0 variant: the variant is a constant inside each. */
#define HB_DEON_KERNELS(suffix, i0)                                                                       \
    static void longitudinal_angles_##suffix(const hb_longitudinal *lobe, size_t n, hb_angles_soa in,     \
                                             float *out, size_t *invalid)                                \
    {                                                                                                     \
        HB_BATCH(load_angles, 4, in, n, invalid,                                                          \
                 store_block(out, i, lanes,                                                               \
                             vf_keep(valid, longitudinal_deon_angles(lobe, a[0], a[2], i0))));             \
    }                                                                                                     \
    static void longitudinal_vectors_##suffix(const hb_longitudinal *lobe, size_t n, hb_vectors_soa in,   \
                                              float *out, size_t *invalid)                               \
    {                                                                                                     \
        HB_BATCH(load_vectors, 6, in, n, invalid,                                                         \
                 store_block(out, i, lanes,                                                               \
                             vf_keep(valid, longitudinal_deon_vectors(lobe, a, a + 3, i0))));              \
    }                                                                                                     \
    static void deon_angles_##suffix(const hb_deon *deon, size_t n, hb_angles_soa in, hb_rgb_soa out,     \
                                     size_t *invalid)                                                    \
    {                                                                                                     \
        vf f[3];                                                                                          \
        if (deon_one_by_one(deon, n)) {                                                                   \
            deon_one_by_one_angles(deon, n, in, out, NULL, i0, invalid);                                  \
            return;                                                                                       \
        }                                                                                                 \
        HB_BATCH(load_angles, 4, in, n, invalid,                                                          \
                 (deon_angles(deon, a[0], a[1], a[2], a[3], i0, f), store_rgb(out, i, lanes, valid, f))); \
    }                                                                                                     \
    static void deon_sample_##suffix(const hb_deon *deon, size_t n, const hb_sample_batch *b,              \
                                     size_t *invalid)                                                    \
    {                                                                                                     \
        vf theta_i, phi_i, pdf, weight[3];                                                                \
        HB_BATCH(load_deon_sample, 2 + HB_DEON_SAMPLE_DIMENSIONS, b, n, invalid,                          \
                 (deon_sample(deon, a[0], a[1], a + 2, i0, &theta_i, &phi_i, &pdf, weight),                \
                  store_sampled(b, i, lanes, valid, theta_i, phi_i, pdf, weight)));                       \
    }                                                                                                     \
    static void deon_pdf_##suffix(const hb_deon *deon, size_t n, const hb_pair_batch *in, float *pdf,     \
                                  size_t *invalid)                                                       \
    {                                                                                                     \
        HB_BATCH(load_pairs, 4, in, n, invalid,                                                           \
                 store_block(pdf, i, lanes,                                                               \
                             vf_keep(valid, deon_pdf_angles(deon, a[0], a[1], a[2], a[3], i0))));          \
    }                                                                                                     \
    static void deon_f_pdf_##suffix(const hb_deon *deon, size_t n, const hb_pair_batch *in, hb_rgb_soa out, \
                                    float *pdf, size_t *invalid)                                         \
    {                                                                                                     \
        vf f[3];                                                                                          \
        if (!in->vectors.wi_x && deon_one_by_one(deon, n)) {                                              \
            deon_one_by_one_angles(deon, n, in->angles, out, pdf, i0, invalid);                           \
            return;                                                                                       \
        }                                                                                                 \
        HB_BATCH(load_pairs, 4, in, n, invalid,                                                           \
                 (store_block(pdf, i, lanes, vf_keep(valid, deon_f_pdf_angles(deon, a, i0, f))),          \
                  store_rgb(out, i, lanes, valid, f)));                                                   \
    }                                                                                                     \
    static void deon_absorbing_##suffix(const hb_deon *deon, size_t n, const hb_absorbing_batch *in,      \
                                        hb_rgb_soa out, size_t *invalid)                                 \
    {                                                                                                     \
        vf f[3];                                                                                          \
        HB_BATCH(load_absorbing, 7, in, n, invalid,                                                       \
                 (deon_absorbing_angles(deon, a, i0, f), store_rgb(out, i, lanes, valid, f)));            \
    }                                                                                                     \
    static void deon_near_##suffix(const hb_deon *deon, size_t n, hb_near_soa in, hb_rgb_soa out,         \
                                   size_t *invalid)                                                      \
    {                                                                                                     \
        vf f[3];                                                                                          \
        HB_BATCH(load_near, 5, in, n, invalid,                                                            \
                 (deon_near_angles(deon, a, i0, f, NULL), store_rgb(out, i, lanes, valid, f)));           \
    }                                                                                                     \
    static void deon_pdf_near_##suffix(const hb_deon *deon, size_t n, hb_near_soa in, float *pdf,         \
                                       size_t *invalid)                                                  \
    {                                                                                                     \
        vf f[3], p;                                                                                       \
        HB_BATCH(load_near, 5, in, n, invalid,                                                            \
                 (deon_near_angles(deon, a, i0, f, &p), store_block(pdf, i, lanes, vf_keep(valid, p))));  \
    }                                                                                                     \
    static void deon_sample_near_##suffix(const hb_deon *deon, size_t n, hb_sample_near_in in,            \
                                          hb_sample_out out, size_t *invalid)                            \
    {                                                                                                     \
        vf theta_i, phi_i, pdf, weight[3];                                                                \
        HB_BATCH(load_deon_sample_near, 3 + HB_DEON_NEAR_DIMENSIONS, in, n, invalid,                      \
                 (deon_sample_near(deon, a[0], a[1], a[2 + HB_DEON_NEAR_DIMENSIONS], a + 2, i0, &theta_i,  \
                                   &phi_i, &pdf, weight),                                                 \
                  store_sample(out, i, lanes, valid, theta_i, phi_i, pdf, weight)));                      \
    }                                                                                                     \
    static void deon_vectors_##suffix(const hb_deon *deon, size_t n, hb_vectors_soa in, hb_rgb_soa out,   \
                                      size_t *invalid)                                                   \
    {                                                                                                     \
        vf f[3];                                                                                          \
        HB_BATCH(load_vectors, 6, in, n, invalid,                                                         \
                 (deon_vectors(deon, a, a + 3, i0, f), store_rgb(out, i, lanes, valid, f)));              \
    }
HB_DEON_KERNELS(abramowitz, HB_I0_ABRAMOWITZ)
HB_DEON_KERNELS(paper, HB_I0_PAPER)
#undef HB_DEON_KERNELS

static void np_row(const hb_deon *deon, float cos_theta_d, size_t n, const float *phi, float *out)
{
    deon_np_row(deon, cos_theta_d, n, phi, out);
}

const hb_deon_kernels HB_ISA_SYMBOL(deon_kernels) = {
    .longitudinal_angles = { longitudinal_angles_abramowitz, longitudinal_angles_paper },
    .longitudinal_vectors = { longitudinal_vectors_abramowitz, longitudinal_vectors_paper },
    .angles = { deon_angles_abramowitz, deon_angles_paper },
    .vectors = { deon_vectors_abramowitz, deon_vectors_paper },
    .sample = { deon_sample_abramowitz, deon_sample_paper },
    .pdf = { deon_pdf_abramowitz, deon_pdf_paper },
    .f_pdf = { deon_f_pdf_abramowitz, deon_f_pdf_paper },
    .absorbing = { deon_absorbing_abramowitz, deon_absorbing_paper },
    .near = { deon_near_abramowitz, deon_near_paper },
    .pdf_near = { deon_pdf_near_abramowitz, deon_pdf_near_paper },
    .sample_near = { deon_sample_near_abramowitz, deon_sample_near_paper },
    .np_row = np_row,
};

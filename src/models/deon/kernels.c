/* dFH11's batch kernels for one ISA: the Makefile compiles this file once per instruction
 * set (-DHB_TARGET_<NAME> and that ISA's flags) into hb_<isa>_deon_kernels. */
#include "kernel/batch.h"
#include "kernels.h"
#include "sample.h"

HB_INLINE vm load_deon_sample(const hb_sample_batch *b, size_t i, size_t lanes, vf *a)
{
    return load_sample(b, HB_DEON_SAMPLE_DIMENSIONS, i, lanes, a);
}

HB_INLINE vm load_deon_sample_near(hb_sample_streams in, size_t i, size_t lanes, vf *a)
{
    return load_sample_near(in, HB_DEON_NEAR_DIMENSIONS, i, lanes, a);
}

HB_INLINE vm load_deon_sample_spectral(const hb_spectral_sample_batch *b, size_t i, size_t lanes, vf *a)
{
    return load_sample_near_spectral(b, HB_DEON_NEAR_DIMENSIONS, i, lanes, a);
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

/* M and the geometry of a sample that carries its own absorption (sigma_a log2(e) per channel): the
 * plan's geometry with that absorption in every channel, three channels computed. */
HB_INLINE void deon_absorbing_setup(const hb_deon *d, const vf a[4], const vf absorption[3], hb_i0 i0,
                                    vf M[HB_MAX_LOBES + 1], deon_geometry *g)
{
    deon_longitudinal_groups(d, a[0], a[2], i0, M);
    deon_geometry_angles(d, a[0], a[1], a[2], a[3], g);
    for (int c = 0; c < 3; c++)
        g->absorption[c] = absorption[c];
    g->grey = 0;
}

/* f at each sample's absorption a[4..6] (load_absorbing), by the quadrature or the colour table. */
HB_INLINE void deon_absorbing_angles(const hb_deon *d, const vf a[7], hb_i0 i0, vf f[3])
{
    vf M[HB_MAX_LOBES + 1];
    deon_geometry g;
    deon_absorbing_setup(d, a, a + 4, i0, M, &g);
    deon_eval(d, &g, M, f);
}

/* The near field at each sample's h (a[4]) and absorption a[5..7] (load_near_absorbing). */
HB_INLINE void deon_near_absorbing_angles(const hb_deon *d, const vf a[8], hb_i0 i0, vf f[3])
{
    vf M[HB_MAX_LOBES + 1];
    deon_geometry g;
    deon_absorbing_setup(d, a, a + 5, i0, M, &g);
    deon_near(d, &g, M, a[4], f, NULL);
}

/* M and the geometry of a spectral sample a[0..3] at its absorptions a[5..5 + k) (load_spectral). */
HB_INLINE void deon_spectral_setup(const hb_deon *d, int channels, const vf *a, hb_i0 i0, vf M[HB_MAX_LOBES + 1],
                                   deon_geometry *g)
{
    deon_longitudinal_groups(d, a[0], a[2], i0, M);
    deon_geometry_angles(d, a[0], a[1], a[2], a[3], g);
    deon_spectral_absorption(g, channels, a + 5);
}

/* f at k wavelengths (the far field): the standard shape's fused sum, whose node work is shared but
 * for each wavelength's transmittance and residual series. */
HB_INLINE void deon_spectral_angles(const hb_deon *d, int channels, const vf *a, hb_i0 i0, vf *f)
{
    vf M[HB_MAX_LOBES + 1];
    deon_geometry g;
    deon_spectral_setup(d, channels, a, i0, M, &g);
    if (d->lobes == HB_STANDARD_LOBES)
        deon_fused_shaped(d, &g, M, f, NULL, (deon_shape){ 1, channels, 1 });
    else
        deon_fused_shaped(d, &g, M, f, NULL, (deon_shape){ 1, channels, 0 });
}

/* The near field at k wavelengths and each sample's h a[4]: f, and the sampler's pdf (the lobes
 * weighted by their attenuations' mean over the k) where pdf is not NULL. */
HB_INLINE void deon_near_spectral_angles(const hb_deon *d, int channels, const vf *a, hb_i0 i0, vf *f, vf *pdf)
{
    vf M[HB_MAX_LOBES + 1];
    deon_geometry g;
    deon_spectral_setup(d, channels, a, i0, M, &g);
    if (pdf)
        *pdf = deon_near_f_pdf_spectral(d, M, &g, a[2], a[4], channels, f);
    else
        deon_near_spectral(d, &g, M, a[4], channels, f, NULL);
}

/* How many samples a call may have for the kernels to take them one at a time, the far field's
 * quadrature nodes or the near field's lobes across the lanes (model.c dispatches such calls of a
 * standard quadrature plan to angles_few and near_few): a path tracer's call at a hit costs one
 * sample's work instead of a block of HB_W lanes. Up to where that is cheaper, measured per ISA
 * (balanced, ns per call): far field, five samples one at a time against a block, AVX2 598 against
 * 764, AVX-512 577 against 619 (six: 720 against 730, 678 against 572); one sample, SSE4.1 245
 * against 552; near field, one sample, 127 against 256, 152 against 168, 166 against 173 (NEON
 * taken as SSE4.1). */
#if defined(HB_TARGET_AVX2)
#define HB_DEON_FEW_MAX 5
#define HB_DEON_NEAR_FEW_MAX 2
#elif defined(HB_TARGET_AVX512)
#define HB_DEON_FEW_MAX 5
#define HB_DEON_NEAR_FEW_MAX 1
#else
#define HB_DEON_FEW_MAX (HB_W > 1)
#define HB_DEON_NEAR_FEW_MAX (HB_W > 1)
#endif

/* M per lobe of one sample in every lane: the lobes across the lanes on the float path. */
HB_INLINE void deon_one_M(const hb_deon *d, const vf a[4], hb_i0 i0, vf M[HB_MAX_LOBES + 1])
{
    if (d->longitudinal[HB_LOBE_R].single)
        longitudinal_deon_lobes_one(d, a[0], a[2], i0, M);
    else
        deon_longitudinal_groups(d, a[0], a[2], i0, M);
}

/* f, and the pdf where pdf is not NULL, of one sample in every lane. */
HB_INLINE void deon_one_angles(const hb_deon *d, const vf a[4], hb_i0 i0, vf f[3], vf *pdf)
{
    vf M[HB_MAX_LOBES + 1];
    deon_one_M(d, a, i0, M);
    deon_geometry g;
    deon_geometry_angles(d, a[0], a[1], a[2], a[3], &g);
    if (pdf)
        *pdf = deon_f_pdf_of(d, M, &g, a[2], f, 1);
    else
        deon_fused_one(d, &g, M, f, NULL);
}

/* The near field of one sample in every lane, its lobes across the lanes (near.h; the float M_p path). */
HB_INLINE void deon_near_one_sample(const hb_deon *d, const vf a[5], hb_i0 i0, vf f[3])
{
    deon_geometry g;
    deon_geometry_angles(d, a[0], a[1], a[2], a[3], &g);
    mp_inclinations in = mp_inclinations_of(a[0], a[2]);
    deon_near_lanes(d, &g, &in, a[4], i0, f);
}

/* One specialised set of entry kernels per I0 variant (kernels_variant.h). */
#define HB_DEON_SUFFIX abramowitz
#define HB_DEON_I0 HB_I0_ABRAMOWITZ
#include "kernels_variant.h"
#define HB_DEON_SUFFIX paper
#define HB_DEON_I0 HB_I0_PAPER
#include "kernels_variant.h"

static void np_row(const hb_deon *deon, float cos_theta_d, size_t n, const float *phi, float *out)
{
    deon_np_row(deon, cos_theta_d, n, phi, out);
}

const hb_deon_kernels HB_ISA_SYMBOL(deon_kernels) = {
    .width = HB_W,
    .longitudinal_angles = { longitudinal_angles_abramowitz, longitudinal_angles_paper },
    .longitudinal_vectors = { longitudinal_vectors_abramowitz, longitudinal_vectors_paper },
    .angles = { deon_angles_abramowitz, deon_angles_paper },
    .angles_few = { deon_angles_few_abramowitz, deon_angles_few_paper },
    .few_max = HB_DEON_FEW_MAX,
    .vectors = { deon_vectors_abramowitz, deon_vectors_paper },
    .sample = { deon_sample_abramowitz, deon_sample_paper },
    .pdf = { deon_pdf_abramowitz, deon_pdf_paper },
    .f_pdf = { deon_f_pdf_abramowitz, deon_f_pdf_paper },
    .absorbing = { deon_absorbing_abramowitz, deon_absorbing_paper },
    .near = { deon_near_abramowitz, deon_near_paper },
    .near_few = { deon_near_few_abramowitz, deon_near_few_paper },
    .near_absorbing = { deon_near_absorbing_abramowitz, deon_near_absorbing_paper },
    .spectral = { deon_spectral_abramowitz, deon_spectral_paper },
    .near_few_max = HB_DEON_NEAR_FEW_MAX,
    .pdf_near = { deon_pdf_near_abramowitz, deon_pdf_near_paper },
    .sample_near = { deon_sample_near_abramowitz, deon_sample_near_paper },
    .sample_spectral = { deon_sample_spectral_abramowitz, deon_sample_spectral_paper },
    .np_row = np_row,
};

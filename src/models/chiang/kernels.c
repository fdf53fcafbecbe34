/* CBTB16's batch kernels for one ISA: the Makefile compiles this file once per instruction set
 * (-DHB_TARGET_<NAME> and that ISA's flags) into hb_<isa>_chiang_kernels. */
#include "kernel/batch.h"
#include "kernels.h"
#include "sample.h"

HB_INLINE vm load_chiang_sample_near(hb_sample_streams in, size_t i, size_t lanes, vf *a)
{
    return load_sample_near(in, HB_CHIANG_NEAR_DIMENSIONS, i, lanes, a);
}

HB_INLINE vm load_sample_far(const hb_sample_batch *b, size_t i, size_t lanes, vf *a)
{
    return load_sample(b, HB_CHIANG_NEAR_DIMENSIONS + 1, i, lanes, a);
}

HB_INLINE vf cos_theta_of(vf theta) { return cos_near_pole(theta, vf_set1(HB_PIO2_LO)); }

static void angles_kernel(const hb_chiang *c, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf M[HB_CHIANG_TERMS], f[3], absorption[3];
    chiang_plan_absorption(c, absorption);
    HB_BATCH(load_angles, 4, in, n, invalid,
             (chiang_longitudinal_angles(c, a[0], a[2], M),
              chiang_far(c, 3, absorption, M, cos_theta_of(a[2]), vf_sub(a[3], a[1]), f, NULL),
              store_rgb(out, i, lanes, valid, f)));
}

/* f at each sample's absorption a[4..6] (load_absorbing): the far field, from angles or vectors. */
static void absorbing_kernel(const hb_chiang *c, size_t n, const hb_absorbing_batch *in, hb_rgb_soa out,
                             size_t *invalid)
{
    vf M[HB_CHIANG_TERMS], f[3];
    HB_BATCH(load_absorbing, 7, in, n, invalid,
             (chiang_longitudinal_angles(c, a[0], a[2], M),
              chiang_far(c, 3, a + 4, M, cos_theta_of(a[2]), vf_sub(a[3], a[1]), f, NULL),
              store_rgb(out, i, lanes, valid, f)));
}

/* The near field at each sample's h (a[4]) and absorption a[5..7] (load_near_absorbing). */
static void near_absorbing_kernel(const hb_chiang *c, size_t n, const hb_absorbing_near *in, hb_rgb_soa out,
                                  size_t *invalid)
{
    vf M[HB_CHIANG_TERMS], f[3];
    HB_BATCH(load_near_absorbing, 8, in, n, invalid,
             (chiang_longitudinal_angles(c, a[0], a[2], M),
              chiang_near(c, 3, a + 5, M, cos_theta_of(a[2]), vf_sub(a[3], a[1]), a[4], f, NULL),
              store_rgb(out, i, lanes, valid, f)));
}

/* theta_o's cosine and phi = phi_o - phi_i from unit vectors: cos phi and sin phi are
 * proportional to the planar parts' dot and cross products (docs/conventions.md's frame). */
HB_INLINE void chiang_vectors_far(const hb_chiang *c, const vf wi[3], const vf wo[3], vf f[3])
{
    vf M[HB_CHIANG_TERMS], sin_o, cos_o, absorption[3];
    chiang_longitudinal_vectors(c, wi, wo, M);
    inclination(wo[0], wo[1], wo[2], &sin_o, &cos_o);
    vf phi = azimuth_difference(wi, wo);
    chiang_plan_absorption(c, absorption);
    chiang_far(c, 3, absorption, M, cos_o, phi, f, NULL);
}

static void vectors_kernel(const hb_chiang *c, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_vectors, 6, in, n, invalid, (chiang_vectors_far(c, a, a + 3, f), store_rgb(out, i, lanes, valid, f)));
}

static void sample_kernel(const hb_chiang *c, size_t n, const hb_sample_batch *b, size_t *invalid)
{
    vf theta_i, phi_i, pdf, weight[3];
    HB_BATCH(load_sample_far, 3 + HB_CHIANG_NEAR_DIMENSIONS, b, n, invalid,
             (chiang_sample_far(c, a[0], a[1], a + 2, &theta_i, &phi_i, &pdf, weight),
              store_sampled(b, i, lanes, valid, theta_i, phi_i, pdf, weight)));
}

/* The far field's pdf; f too where out is not NULL (one pass: chiang_far forms both). */
static void f_pdf_kernel(const hb_chiang *c, size_t n, const hb_pair_batch *in, const hb_rgb_soa *out, float *pdf,
                         size_t *invalid)
{
    vf M[HB_CHIANG_TERMS], f[3], p, absorption[3];
    chiang_plan_absorption(c, absorption);
    HB_BATCH(load_pairs, 4, in, n, invalid,
             (chiang_longitudinal_angles(c, a[0], a[2], M),
              chiang_far(c, 3, absorption, M, cos_theta_of(a[2]), vf_sub(a[3], a[1]), f, &p),
              store_block(pdf, i, lanes, vf_keep(valid, p)), out ? store_rgb(*out, i, lanes, valid, f) : (void)0));
}

static void near_kernel(const hb_chiang *c, size_t n, hb_near_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf M[HB_CHIANG_TERMS], f[3], absorption[3];
    chiang_plan_absorption(c, absorption);
    HB_BATCH(load_near, 5, in, n, invalid,
             (chiang_longitudinal_angles(c, a[0], a[2], M),
              chiang_near(c, 3, absorption, M, cos_theta_of(a[2]), vf_sub(a[3], a[1]), a[4], f, NULL),
              store_rgb(out, i, lanes, valid, f)));
}

/* A call of a few samples of the near field (a path tracer's call per hit), each alone with its
 * terms across the lanes (eval.h, chiang_near_lanes): model.c sends such calls of a plan on the float
 * M_p path here, up to near_few_max samples. One sample costs less so than on the scalar kernels,
 * two more than a whole block (make bench, the per-hit and near rows). */
static void near_few_kernel(const hb_chiang *c, size_t n, hb_near_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3], absorption[3];
    chiang_plan_absorption(c, absorption);
    HB_ONE_BY_ONE(load_near_one, 5, in, n, invalid,
                  (chiang_near_lanes(c, 3, absorption, &(mp_inclinations){ a[0], a[2], cos_theta_of(a[0]) },
                                     cos_theta_of(a[2]), vf_sub(a[3], a[1]), a[4], f),
                   store_rgb_one(out, k, valid, f)));
}

/* The same at k wavelengths (a spectral call of f alone, at h): each sample's absorptions a[5..5 + k). */
HB_INLINE void spectral_few_samples(const hb_chiang *c, int channels, size_t n, const hb_spectral_batch *b,
                                    size_t *invalid)
{
    vf f[HB_CHIANG_CHANNELS];
    HB_ONE_BY_ONE(load_spectral_one, 5 + HB_CHIANG_CHANNELS, b, n, invalid,
                  (chiang_near_lanes(c, channels, a + 5, &(mp_inclinations){ a[0], a[2], cos_theta_of(a[0]) },
                                     cos_theta_of(a[2]), vf_sub(a[3], a[1]), a[4], f),
                   store_planes_one(b->f, channels, k, valid, f)));
}

static void spectral_few_kernel(const hb_chiang *c, size_t n, const hb_spectral_batch *b, size_t *invalid)
{
    if (b->wavelengths == 4)
        spectral_few_samples(c, 4, n, b, invalid);
    else
        spectral_few_samples(c, b->wavelengths, n, b, invalid);
}

static void sample_near_kernel(const hb_chiang *c, size_t n, hb_sample_streams in, hb_sample_out out,
                               size_t *invalid)
{
    vf theta_i, phi_i, pdf, weight[3], absorption[3];
    chiang_plan_absorption(c, absorption);
    HB_BATCH(load_chiang_sample_near, 3 + HB_CHIANG_NEAR_DIMENSIONS, in, n, invalid,
             (chiang_sample_near(c, 3, absorption, a[0], a[1], a[2 + HB_CHIANG_NEAR_DIMENSIONS], a + 2, &theta_i,
                                 &phi_i, &pdf, weight),
              store_sample(out, i, lanes, valid, theta_i, phi_i, pdf, weight)));
}

static void pdf_near_kernel(const hb_chiang *c, size_t n, hb_near_soa in, float *pdf, size_t *invalid)
{
    vf M[HB_CHIANG_TERMS], f[3], p, absorption[3];
    chiang_plan_absorption(c, absorption);
    HB_BATCH(load_near, 5, in, n, invalid,
             (chiang_longitudinal_angles(c, a[0], a[2], M),
              chiang_near(c, 3, absorption, M, cos_theta_of(a[2]), vf_sub(a[3], a[1]), a[4], f, &p),
              store_block(pdf, i, lanes, vf_keep(valid, p))));
}

/* k wavelengths at each sample's absorptions a[5..5 + k) (load_spectral): f and the pdf where the batch
 * asks, near-field at h (a[4]) or the far field; M_p, Fresnel, the paths and N_p once for the k. */
HB_INLINE void spectral_blocks(const hb_chiang *c, int k, size_t n, const hb_spectral_batch *b, size_t *invalid)
{
    vf M[HB_CHIANG_TERMS], f[HB_CHIANG_CHANNELS], p, *pdf = b->pdf ? &p : NULL;
    HB_BATCH(load_spectral, 5 + HB_CHIANG_CHANNELS, b, n, invalid,
             (chiang_longitudinal_angles(c, a[0], a[2], M),
              b->near.h ? chiang_near(c, k, a + 5, M, cos_theta_of(a[2]), vf_sub(a[3], a[1]), a[4], f, pdf)
                        : chiang_far(c, k, a + 5, M, cos_theta_of(a[2]), vf_sub(a[3], a[1]), f, pdf),
              b->f ? store_planes(b->f, k, i, lanes, valid, f) : (void)0,
              pdf ? store_block(b->pdf, i, lanes, vf_keep(valid, p)) : (void)0));
}

/* pbrt-v4's four wavelengths with their channel loops unrolled, any other count as it comes. */
static void spectral_kernel(const hb_chiang *c, size_t n, const hb_spectral_batch *b, size_t *invalid)
{
    if (b->wavelengths == 4)
        spectral_blocks(c, 4, n, b, invalid);
    else
        spectral_blocks(c, b->wavelengths, n, b, invalid);
}

HB_INLINE vm load_spectral_sample(const hb_spectral_sample_batch *b, size_t i, size_t lanes, vf *a)
{
    return load_sample_near_spectral(b, HB_CHIANG_NEAR_DIMENSIONS, i, lanes, a);
}

HB_INLINE void spectral_sample_blocks(const hb_chiang *c, int k, size_t n, const hb_spectral_sample_batch *b,
                                      size_t *invalid)
{
    vf theta_i, phi_i, pdf, weight[HB_CHIANG_CHANNELS];
    HB_BATCH(load_spectral_sample, 3 + HB_CHIANG_NEAR_DIMENSIONS + HB_CHIANG_CHANNELS, b, n, invalid,
             (chiang_sample_near(c, k, a + 3 + HB_CHIANG_NEAR_DIMENSIONS, a[0], a[1], a[2 + HB_CHIANG_NEAR_DIMENSIONS],
                                 a + 2, &theta_i, &phi_i, &pdf, weight),
              store_sample_spectral(&b->out, k, i, lanes, valid, theta_i, phi_i, pdf, weight)));
}

static void sample_spectral_kernel(const hb_chiang *c, size_t n, const hb_spectral_sample_batch *b, size_t *invalid)
{
    if (b->wavelengths == 4)
        spectral_sample_blocks(c, 4, n, b, invalid);
    else
        spectral_sample_blocks(c, b->wavelengths, n, b, invalid);
}

const hb_chiang_kernels HB_ISA_SYMBOL(chiang_kernels) = {
    .angles = angles_kernel,
    .vectors = vectors_kernel,
    .sample = sample_kernel,
    .f_pdf = f_pdf_kernel,
    .near = near_kernel,
    .absorbing = absorbing_kernel,
    .near_absorbing = near_absorbing_kernel,
    .near_few = near_few_kernel,
    .near_few_max = HB_W > 1,
    .sample_near = sample_near_kernel,
    .pdf_near = pdf_near_kernel,
    .spectral = spectral_kernel,
    .spectral_few = spectral_few_kernel,
    .sample_spectral = sample_spectral_kernel,
};

/* MJC03's batch kernels for one ISA: the Makefile compiles this file once per instruction
 * set (-DHB_TARGET_<NAME> and that ISA's flags) into hb_<isa>_marschner_kernels. */
#include "kernel/batch.h"
#include "kernels.h"
#include "sample.h"

static void longitudinal_angles(const hb_gaussian_lobe *lobe, size_t n, hb_angles_soa in, float *out,
                                size_t *invalid)
{
    HB_BATCH(load_angles, 4, in, n, invalid,
             store_block(out, i, lanes,
                         vf_keep(valid, longitudinal_marschner_angles(lobe, a[0], a[2]))));
}

static void longitudinal_vectors(const hb_gaussian_lobe *lobe, size_t n, hb_vectors_soa in, float *out,
                                 size_t *invalid)
{
    HB_BATCH(load_vectors, 6, in, n, invalid,
             store_block(out, i, lanes,
                         vf_keep(valid, longitudinal_marschner_vectors(lobe, a, a + 3))));
}

static void angles_kernel(const hb_marschner *mjc, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_angles, 4, in, n, invalid,
             (marschner_angles(mjc, a[0], a[1], a[2], a[3], f), store_rgb(out, i, lanes, valid, f)));
}

static void vectors_kernel(const hb_marschner *mjc, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_vectors, 6, in, n, invalid, (marschner_vectors(mjc, a, a + 3, f), store_rgb(out, i, lanes, valid, f)));
}

/* f at each sample's absorption a[4..6] (load_absorbing). */
static void absorbing_kernel(const hb_marschner *mjc, size_t n, const hb_absorbing_batch *in, hb_rgb_soa out,
                             size_t *invalid)
{
    vf f[3];
    mjc_geometry g;
    HB_BATCH(load_absorbing, 7, in, n, invalid,
             (marschner_geometry_angles(mjc, a[0], a[1], a[2], a[3], &g), g.absorption[0] = a[4],
              g.absorption[1] = a[5], g.absorption[2] = a[6], marschner_f(mjc, &g, f),
              store_rgb(out, i, lanes, valid, f)));
}

HB_INLINE vm load_marschner_sample(const hb_sample_batch *b, size_t i, size_t lanes, vf *a)
{
    return load_sample(b, HB_MARSCHNER_SAMPLE_DIMENSIONS, i, lanes, a);
}

static void sample_kernel(const hb_marschner *mjc, size_t n, const hb_sample_batch *b, size_t *invalid)
{
    vf theta_i, phi_i, pdf, weight[3];
    HB_BATCH(load_marschner_sample, 2 + HB_MARSCHNER_SAMPLE_DIMENSIONS, b, n, invalid,
             (marschner_sample(mjc, a[0], a[1], a + 2, &theta_i, &phi_i, &pdf, weight),
              store_sampled(b, i, lanes, valid, theta_i, phi_i, pdf, weight)));
}

static void pdf_kernel(const hb_marschner *mjc, size_t n, const hb_pair_batch *in, float *pdf, size_t *invalid)
{
    HB_BATCH(load_pairs, 4, in, n, invalid,
             store_block(pdf, i, lanes, vf_keep(valid, marschner_pdf_angles(mjc, a[0], a[1], a[2], a[3]))));
}

const hb_marschner_kernels HB_ISA_SYMBOL(marschner_kernels) = {
    .longitudinal_angles = longitudinal_angles,
    .longitudinal_vectors = longitudinal_vectors,
    .angles = angles_kernel,
    .vectors = vectors_kernel,
    .sample = sample_kernel,
    .pdf = pdf_kernel,
    .absorbing = absorbing_kernel,
};

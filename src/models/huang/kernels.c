/* HHH22's batch kernels for one ISA: the Makefile compiles this file once per instruction
 * set (-DHB_TARGET_<NAME> and that ISA's flags) into hb_<isa>_huang_kernels. */
#include "kernel/batch.h"
#include "eval.h"
#include "kernels.h"
#include "sample_paths.h"

HB_INLINE vm load_huang_sample(const hb_sample_batch *b, size_t i, size_t lanes, vf *a)
{
    return load_sample(b, HB_HUANG_SAMPLE_DIMENSIONS, i, lanes, a);
}

HB_INLINE vm load_huang_path_sample(const hb_sample_batch *b, size_t i, size_t lanes, vf *a)
{
    return load_sample(b, HB_HUANG_PATH_DIMENSIONS, i, lanes, a);
}

/* The sample indices first + lane of a block (mod 2^32), which key the Monte-Carlo numbers. */
HB_INLINE vi lane_indices(size_t first)
{
    float lane[HB_W];
    for (int k = 0; k < HB_W; k++)
        lane[k] = (float)k;
    return vi_add(vi_set1((int32_t)(uint32_t)first), vi_from_vf(vf_loadu(lane)));
}

static void angles_kernel(const hb_huang *h, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_angles, 4, in, n, invalid,
             (huang_angles(h, a[0], a[1], a[2], a[3], lane_indices(i), f), store_rgb(out, i, lanes, valid, f)));
}

static void vectors_kernel(const hb_huang *h, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_vectors, 6, in, n, invalid,
             (huang_vectors(h, a, a + 3, lane_indices(i), f), store_rgb(out, i, lanes, valid, f)));
}

/* R-only plans sample exactly (weight = f / pdf); with TT or TRT, by traced paths (sample_paths.h). */
static void sample_kernel(const hb_huang *h, size_t n, const hb_sample_batch *b, size_t *invalid)
{
    vf theta_i, phi_i, pdf, weight[3];
    if (h->lobes == 1u << HB_LOBE_R)
        HB_BATCH(load_huang_sample, 2 + HB_HUANG_SAMPLE_DIMENSIONS, b, n, invalid,
                 (huang_sample(h, a[0], a[1], a + 2, &theta_i, &phi_i, &pdf, weight),
                  store_sampled(b, i, lanes, valid, theta_i, phi_i, pdf, weight)));
    else
        HB_BATCH(load_huang_path_sample, 2 + HB_HUANG_PATH_DIMENSIONS, b, n, invalid,
                 (huang_path_sample(h, a[0], a[1], a + 2, lane_indices(i), &theta_i, &phi_i, &pdf, weight),
                  store_sampled(b, i, lanes, valid, theta_i, phi_i, pdf, weight)));
}

static void pdf_kernel(const hb_huang *h, size_t n, const hb_pair_batch *in, float *pdf, size_t *invalid)
{
    if (h->lobes == 1u << HB_LOBE_R)
        HB_BATCH(load_pairs, 4, in, n, invalid,
                 store_block(pdf, i, lanes,
                             vf_keep(valid, huang_pdf_angles(h, a[0], a[1], a[2], a[3]))));
    else
        HB_BATCH(load_pairs, 4, in, n, invalid,
                 store_block(pdf, i, lanes,
                             vf_keep(valid, huang_path_pdf(h, a[0], a[1], a[2], a[3], lane_indices(i)))));
}

static void table_row(const hb_huang *h, float theta_i, float phi_i, const hb_huang_table_build *build, float *row)
{
    huang_table_row(h, theta_i, phi_i, build, row);
}

const hb_huang_kernels HB_ISA_SYMBOL(huang_kernels) = {
    .angles = angles_kernel,
    .vectors = vectors_kernel,
    .sample = sample_kernel,
    .pdf = pdf_kernel,
    .table_row = table_row,
};

/* One translation unit per ISA: the Makefile compiles this file once for each
 * instruction set with -DHB_TARGET_<NAME> and that ISA's flags, and each copy exports
 * its table of kernels as hb_kernels_<name>. Nothing in here is ISA specific. */
#include <string.h>

#include "simd/simd.h"
#include "math/vmath.h"
#include "models/deon/sample.h"
#include "models/marschner/azimuthal.h"
#include "models/huang/eval.h"
#include "models/huang/sample_paths.h"
#include "kernels.h"

#if defined(HB_TARGET_SCALAR)
#define HB_TABLE hb_kernels_scalar
#define HB_TABLE_ISA HB_ISA_SCALAR
#elif defined(HB_TARGET_SSE41)
#define HB_TABLE hb_kernels_sse41
#define HB_TABLE_ISA HB_ISA_SSE41
#elif defined(HB_TARGET_AVX2)
#define HB_TABLE hb_kernels_avx2
#define HB_TABLE_ISA HB_ISA_AVX2
#elif defined(HB_TARGET_AVX512)
#define HB_TABLE hb_kernels_avx512
#define HB_TABLE_ISA HB_ISA_AVX512
#elif defined(HB_TARGET_NEON)
#define HB_TABLE hb_kernels_neon
#define HB_TABLE_ISA HB_ISA_NEON
#endif

/* Loads lane block [i, i + lanes) of each stream; a short tail is padded with pad. One load per
 * stream either way (from the stream, or from the padded copy), so the vectors stay in registers. */
HB_INLINE void load_block(const float *const *src, int streams, size_t i, size_t lanes, float pad, vf *dst)
{
    float padded[2 + HB_SAMPLE_DIMENSIONS][HB_W]; /* the most streams a kernel loads */
    if (lanes != HB_W)
        for (int s = 0; s < streams; s++)
            for (size_t k = 0; k < HB_W; k++)
                padded[s][k] = k < lanes ? src[s][i + k] : pad;
    HB_UNROLL
    for (int s = 0; s < streams; s++)
        dst[s] = vf_loadu(lanes == HB_W ? src[s] + i : padded[s]);
}

HB_INLINE void store_block(float *dst, size_t i, size_t lanes, vf value)
{
    if (lanes == HB_W) {
        vf_storeu(dst + i, value);
    } else {
        float buf[HB_W];
        vf_storeu(buf, value);
        memcpy(dst + i, buf, lanes * sizeof(float));
    }
}

HB_INLINE size_t count_invalid(vm valid, size_t lanes)
{
    unsigned live = lanes >= 32 ? ~0u : (1u << lanes) - 1u;
    return (size_t)__builtin_popcount(~vm_bits(valid) & live);
}

/* theta in [-pi/2, pi/2] (as floats), |phi| <= HB_PHI_LIMIT; false for NaN and Inf. */
HB_INLINE vm angle_pair_valid(vf theta, vf phi)
{
    return vm_and(vf_le(vf_abs(theta), vf_set1(HB_PIO2_F)), vf_le(vf_abs(phi), vf_set1(HB_PHI_LIMIT)));
}

HB_INLINE vm unit_vector_valid(const vf w[3])
{
    vf norm2 = vf_fma(w[0], w[0], vf_fma(w[1], w[1], vf_mul(w[2], w[2])));
    return vf_le(vf_abs(vf_sub(norm2, vf_set1(1.0f))), vf_set1(HB_UNIT_TOLERANCE));
}

/* Loads lane block i of an angle batch; returns which lanes are valid samples. */
/* Loads lane block i of an angle batch; returns which lanes are valid samples. Invalid lanes
 * are replaced by a benign direction, so no NaN or huge value reaches the math (a float-to-int
 * conversion of one is undefined behaviour); their output is 0 anyway. */
HB_INLINE vm load_angles(hb_angles_soa in, size_t i, size_t lanes, vf a[4])
{
    const float *src[4] = { in.theta_i, in.phi_i, in.theta_o, in.phi_o };
    load_block(src, 4, i, lanes, 0.0f, a);
    vm valid = vm_and(angle_pair_valid(a[0], a[1]), angle_pair_valid(a[2], a[3]));
HB_UNROLL
    for (int k = 0; k < 4; k++)
        a[k] = vf_keep(valid, a[k]);
    return valid;
}

HB_INLINE vm load_vectors(hb_vectors_soa in, size_t i, size_t lanes, vf a[6])
{
    const float *src[6] = { in.wi_x, in.wi_y, in.wi_z, in.wo_x, in.wo_y, in.wo_z };
    load_block(src, 6, i, lanes, 0.0f, a);
    vm valid = vm_and(unit_vector_valid(a), unit_vector_valid(a + 3));
    for (int k = 0; k < 6; k++)
        a[k] = vf_select(valid, a[k], vf_set1(k % 3 == 2 ? 1.0f : 0.0f)); /* w = (0, 0, 1) */
    return valid;
}

/* Loads lane block i of a sampling batch: theta_o, phi_o, then `dims` uniform numbers. Valid
 * lanes have a valid direction and every u in [0, 1]; the others get (0, 0) and u = 1/2. */
HB_INLINE vm load_sample(hb_sample_in in, int dims, size_t i, size_t lanes, vf *a)
{
    const float *src[2 + HB_SAMPLE_DIMENSIONS] = { in.theta_o, in.phi_o };
    for (int k = 0; k < dims; k++)
        src[2 + k] = in.u[k];
    load_block(src, 2 + dims, i, lanes, 0.0f, a);
    vm valid = angle_pair_valid(a[0], a[1]);
    for (int k = 2; k < 2 + dims; k++)
        valid = vm_and(valid, vm_and(vf_ge(a[k], vf_set1(0.0f)), vf_le(a[k], vf_set1(1.0f))));
    for (int k = 0; k < 2 + dims; k++)
        a[k] = vf_select(valid, a[k], vf_set1(k < 2 ? 0.0f : 0.5f));
    return valid;
}

#define HB_DEON_SAMPLE_DIMENSIONS 5
HB_INLINE vm load_deon_sample(hb_sample_in in, size_t i, size_t lanes, vf *a)
{
    return load_sample(in, HB_DEON_SAMPLE_DIMENSIONS, i, lanes, a);
}

#define HB_HUANG_SAMPLE_DIMENSIONS 3
HB_INLINE vm load_huang_sample(hb_sample_in in, size_t i, size_t lanes, vf *a)
{
    return load_sample(in, HB_HUANG_SAMPLE_DIMENSIONS, i, lanes, a);
}

HB_INLINE vm load_huang_path_sample(hb_sample_in in, size_t i, size_t lanes, vf *a)
{
    return load_sample(in, HB_HUANG_PATH_DIMENSIONS, i, lanes, a);
}

/* Invalid lanes get 0 in every plane. */
HB_INLINE void store_rgb(hb_rgb_soa out, size_t i, size_t lanes, vm valid, const vf f[3])
{
    float *planes[3] = { out.r, out.g, out.b };
    for (int c = 0; c < 3; c++)
        store_block(planes[c], i, lanes, vf_keep(valid, f[c]));
}

/* A sampled direction, its pdf and weight; invalid lanes get 0 everywhere. */
HB_INLINE void store_sample(hb_sample_out out, size_t i, size_t lanes, vm valid, vf theta_i, vf phi_i, vf pdf,
                            const vf weight[3])
{
    store_block(out.theta_i, i, lanes, vf_keep(valid, theta_i));
    store_block(out.phi_i, i, lanes, vf_keep(valid, phi_i));
    store_block(out.pdf, i, lanes, vf_keep(valid, pdf));
    store_rgb(out.weight, i, lanes, valid, weight);
}

/* The loop every entry point shares: blocks of W lanes (a padded tail last), `compute`
 * turning the loaded lanes `a` (valid where `valid`) into stored results, and the count of
 * invalid samples; subnormals flushed meanwhile (simd.h). */
#define HB_BATCH(load, streams, in, n, invalid, compute)              \
    do {                                                              \
        hb_fp_mode mode_ = hb_flush_subnormals();                     \
        size_t bad_ = 0;                                              \
        for (size_t i = 0; i < (n); i += HB_W) {                      \
            size_t lanes = (n) - i < HB_W ? (n) - i : HB_W;           \
            vf a[streams];                                            \
            vm valid = load((in), i, lanes, a);                       \
            compute;                                                  \
            bad_ += count_invalid(valid, lanes);                      \
        }                                                             \
        *(invalid) = bad_;                                            \
        hb_fp_restore(mode_);                                         \
    } while (0)

/* One specialised kernel per I0 variant: the variant is a constant inside each. */
#define HB_KERNEL_VARIANTS(suffix, i0)                                                                    \
    static void longitudinal_angles_##suffix(const hb_longitudinal *lobe, size_t n, hb_angles_soa in,     \
                                             float *out, size_t *invalid)                                \
    {                                                                                                     \
        HB_BATCH(load_angles, 4, in, n, invalid,                                                          \
                 store_block(out, i, lanes,                                                               \
                             vf_keep(valid, longitudinal_deon_angles(lobe, a[0], a[2], i0)))); \
    }                                                                                                     \
    static void longitudinal_vectors_##suffix(const hb_longitudinal *lobe, size_t n, hb_vectors_soa in,   \
                                              float *out, size_t *invalid)                               \
    {                                                                                                     \
        HB_BATCH(load_vectors, 6, in, n, invalid,                                                         \
                 store_block(out, i, lanes,                                                               \
                             vf_keep(valid, longitudinal_deon_vectors(lobe, a, a + 3, i0)))); \
    }                                                                                                     \
    static void deon_angles_##suffix(const hb_deon *deon, size_t n, hb_angles_soa in, hb_rgb_soa out,     \
                                     size_t *invalid)                                                    \
    {                                                                                                     \
        vf f[3];                                                                                          \
        HB_BATCH(load_angles, 4, in, n, invalid,                                                          \
                 (deon_angles(deon, a[0], a[1], a[2], a[3], i0, f), store_rgb(out, i, lanes, valid, f))); \
    }                                                                                                     \
    static void deon_sample_##suffix(const hb_deon *deon, size_t n, hb_sample_in in, hb_sample_out out,   \
                                     size_t *invalid)                                                    \
    {                                                                                                     \
        vf theta_i, phi_i, pdf, weight[3];                                                                \
        HB_BATCH(load_deon_sample, 2 + HB_DEON_SAMPLE_DIMENSIONS, in, n, invalid,                         \
                 (deon_sample(deon, a[0], a[1], a + 2, i0, &theta_i, &phi_i, &pdf, weight),                \
                  store_sample(out, i, lanes, valid, theta_i, phi_i, pdf, weight)));                      \
    }                                                                                                     \
    static void deon_pdf_##suffix(const hb_deon *deon, size_t n, hb_angles_soa in, float *pdf,            \
                                  size_t *invalid)                                                       \
    {                                                                                                     \
        HB_BATCH(load_angles, 4, in, n, invalid,                                                          \
                 store_block(pdf, i, lanes,                                                               \
                             vf_keep(valid, deon_pdf_angles(deon, a[0], a[1], a[2], a[3], i0)))); \
    }                                                                                                     \
    static void deon_vectors_##suffix(const hb_deon *deon, size_t n, hb_vectors_soa in, hb_rgb_soa out,   \
                                      size_t *invalid)                                                   \
    {                                                                                                     \
        vf f[3];                                                                                          \
        HB_BATCH(load_vectors, 6, in, n, invalid,                                                         \
                 (deon_vectors(deon, a, a + 3, i0, f), store_rgb(out, i, lanes, valid, f)));              \
    }
static void marschner_longitudinal_angles(const hb_gaussian_lobe *lobe, size_t n, hb_angles_soa in, float *out,
                                          size_t *invalid)
{
    HB_BATCH(load_angles, 4, in, n, invalid,
             store_block(out, i, lanes,
                         vf_keep(valid, longitudinal_marschner_angles(lobe, a[0], a[2]))));
}

static void marschner_longitudinal_vectors(const hb_gaussian_lobe *lobe, size_t n, hb_vectors_soa in, float *out,
                                           size_t *invalid)
{
    HB_BATCH(load_vectors, 6, in, n, invalid,
             store_block(out, i, lanes,
                         vf_keep(valid, longitudinal_marschner_vectors(lobe, a, a + 3))));
}

static void marschner_angles_kernel(const hb_marschner *mjc, size_t n, hb_angles_soa in, hb_rgb_soa out,
                                    size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_angles, 4, in, n, invalid,
             (marschner_angles(mjc, a[0], a[1], a[2], a[3], f), store_rgb(out, i, lanes, valid, f)));
}

static void marschner_vectors_kernel(const hb_marschner *mjc, size_t n, hb_vectors_soa in, hb_rgb_soa out,
                                     size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_vectors, 6, in, n, invalid, (marschner_vectors(mjc, a, a + 3, f), store_rgb(out, i, lanes, valid, f)));
}

/* The sample indices first + lane of a block (mod 2^32), which key the Monte-Carlo numbers. */
HB_INLINE vi lane_indices(size_t first)
{
    float lane[HB_W];
    for (int k = 0; k < HB_W; k++)
        lane[k] = (float)k;
    return vi_add(vi_set1((int32_t)(uint32_t)first), vi_from_vf(vf_loadu(lane)));
}

static void huang_angles_kernel(const hb_huang *h, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_angles, 4, in, n, invalid,
             (huang_angles(h, a[0], a[1], a[2], a[3], lane_indices(i), f), store_rgb(out, i, lanes, valid, f)));
}

static void huang_vectors_kernel(const hb_huang *h, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_vectors, 6, in, n, invalid,
             (huang_vectors(h, a, a + 3, lane_indices(i), f), store_rgb(out, i, lanes, valid, f)));
}

/* R-only plans sample exactly (weight = f / pdf); with TT or TRT, by traced paths (sample_paths.h). */
static void huang_sample_kernel(const hb_huang *h, size_t n, hb_sample_in in, hb_sample_out out, size_t *invalid)
{
    vf theta_i, phi_i, pdf, weight[3];
    if (h->lobes == 1u << HB_LOBE_R)
        HB_BATCH(load_huang_sample, 2 + HB_HUANG_SAMPLE_DIMENSIONS, in, n, invalid,
                 (huang_sample(h, a[0], a[1], a + 2, &theta_i, &phi_i, &pdf, weight),
                  store_sample(out, i, lanes, valid, theta_i, phi_i, pdf, weight)));
    else
        HB_BATCH(load_huang_path_sample, 2 + HB_HUANG_PATH_DIMENSIONS, in, n, invalid,
                 (huang_path_sample(h, a[0], a[1], a + 2, lane_indices(i), &theta_i, &phi_i, &pdf, weight),
                  store_sample(out, i, lanes, valid, theta_i, phi_i, pdf, weight)));
}

static void huang_pdf_kernel(const hb_huang *h, size_t n, hb_angles_soa in, float *pdf, size_t *invalid)
{
    if (h->lobes == 1u << HB_LOBE_R)
        HB_BATCH(load_angles, 4, in, n, invalid,
                 store_block(pdf, i, lanes,
                             vf_keep(valid, huang_pdf_angles(h, a[0], a[1], a[2], a[3]))));
    else
        HB_BATCH(load_angles, 4, in, n, invalid,
                 store_block(pdf, i, lanes,
                             vf_keep(valid, huang_path_pdf(h, a[0], a[1], a[2], a[3], lane_indices(i)))));
}

HB_KERNEL_VARIANTS(abramowitz, HB_I0_ABRAMOWITZ)
HB_KERNEL_VARIANTS(paper, HB_I0_PAPER)
#undef HB_KERNEL_VARIANTS
#undef HB_BATCH

HB_INLINE vf math_apply(hb_math_fn fn, vf a, vf b)
{
    switch (fn) {
    case HB_FN_EXP: return vf_exp(a);
    case HB_FN_EXP_FLUSH: return vf_exp_flush(a);
    case HB_FN_EXP2_NEG: return vf_exp2_neg(a);
    case HB_FN_LOG: return vf_log(a);
    case HB_FN_LOG1P: return vf_log1p(a);
    case HB_FN_SIN: return vf_sin(a);
    case HB_FN_COS: return vf_cos(a);
    case HB_FN_ASIN: return vf_asin(a);
    case HB_FN_ASIN_NARROW: return vf_asin_narrow(a, vf_mul(a, a));
    case HB_FN_ACOS: return vf_acos(a);
    case HB_FN_ATAN2: return vf_atan2(a, b);
    case HB_FN_SQRT: return vf_sqrt(a);
    case HB_FN_I0: return vf_i0(a);
    case HB_FN_I0E: return vf_i0e(a);
    case HB_FN_LOG_I0: return vf_log_i0(a);
    case HB_FN_COUNT: break;
    }
    return a;
}

/* Applies one vector math function to arrays (b is the second operand of atan2 and may be NULL otherwise). */
static void math_map(hb_math_fn fn, size_t n, const float *a, const float *b, float *out)
{
    const float *src[2] = { a, b ? b : a };
    for (size_t i = 0; i < n; i += HB_W) {
        size_t lanes = n - i < HB_W ? n - i : HB_W;
        vf v[2];
        load_block(src, 2, i, lanes, 1.0f, v);
        store_block(out, i, lanes, math_apply(fn, v[0], v[1]));
    }
}

/* D_p(x) = (D_p(x - 0) + D_p(-x - 0)) / 2, D_p being even: the kernel's detector, for the tests. */
static void detector_map(const hb_detector *d, size_t n, const float *x, float *out)
{
    for (size_t i = 0; i < n; i += HB_W) {
        size_t lanes = n - i < HB_W ? n - i : HB_W;
        vf phi, cos_n_phi[HB_MAX_DETECTOR_TERMS + 1];
        load_block(&x, 1, i, lanes, 0.0f, &phi);
        cos_multiples(vf_cos(phi), d->fourier ? d->terms : 0, cos_n_phi);
        vf pair = detector_pair(d, phi, vf_set1(0.0f), cos_n_phi, (deon_shape){ 0, 1, 0 });
        store_block(out, i, lanes, vf_mul(pair, vf_set1(0.5f)));
    }
}

/* The cubic solver on arrays, all three roots (NaN where a root is not real), for the tests. */
static void cubic_map(size_t n, const float *P, const float *Q, float *roots)
{
    const float *src[2] = { P, Q };
    for (size_t i = 0; i < n; i += HB_W) {
        size_t lanes = n - i < HB_W ? n - i : HB_W;
        vf pq[2], root[3];
        vm real[3];
        load_block(src, 2, i, lanes, 1.0f, pq);
        cubic_roots(pq[0], pq[1], 1, root, real);
        for (int k = 0; k < 3; k++) {
            float buf[HB_W];
            vf_storeu(buf, vf_select(real[k], root[k], vf_set1(__builtin_nanf(""))));
            for (size_t j = 0; j < lanes; j++)
                roots[3 * (i + j) + (size_t)k] = buf[j];
        }
    }
}

const hb_kernels HB_TABLE = {
    .isa = HB_TABLE_ISA,
    .width = HB_W,
    .longitudinal_angles = { longitudinal_angles_abramowitz, longitudinal_angles_paper },
    .longitudinal_vectors = { longitudinal_vectors_abramowitz, longitudinal_vectors_paper },
    .deon_angles = { deon_angles_abramowitz, deon_angles_paper },
    .deon_vectors = { deon_vectors_abramowitz, deon_vectors_paper },
    .deon_sample = { deon_sample_abramowitz, deon_sample_paper },
    .deon_pdf = { deon_pdf_abramowitz, deon_pdf_paper },
    .marschner_longitudinal_angles = marschner_longitudinal_angles,
    .marschner_longitudinal_vectors = marschner_longitudinal_vectors,
    .marschner_angles = marschner_angles_kernel,
    .marschner_vectors = marschner_vectors_kernel,
    .huang_angles = huang_angles_kernel,
    .huang_vectors = huang_vectors_kernel,
    .huang_sample = huang_sample_kernel,
    .huang_pdf = huang_pdf_kernel,
    .huang_table_row = huang_table_row,
    .deon_np_row = deon_np_row,
    .cubic_map = cubic_map,
    .math_map = math_map,
    .detector_map = detector_map,
};

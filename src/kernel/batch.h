/* The batch loop every kernel entry point shares, for the ISA this translation unit is
 * compiled for: lane blocks loaded from caller-owned SoA streams (a padded tail last),
 * invalid samples replaced by benign ones and counted, results stored back. A model's
 * kernels.c includes this, its model headers, and defines its table under HB_ISA_SYMBOL. */
#ifndef HB_ISA_BATCH_H
#define HB_ISA_BATCH_H

#include <float.h>
#include <string.h>

#include "simd/simd.h"
#include "math/valid.h"
#include "math/vmath.h"
#include "streams.h"

/* hb_<isa>_<name>: the per-ISA name of a model's table (internal to the library). */
#if defined(HB_TARGET_SCALAR)
#define HB_ISA_SYMBOL(name) hb_scalar_##name
#define HB_THIS_ISA HB_ISA_SCALAR
#elif defined(HB_TARGET_SSE41)
#define HB_ISA_SYMBOL(name) hb_sse41_##name
#define HB_THIS_ISA HB_ISA_SSE41
#elif defined(HB_TARGET_AVX2)
#define HB_ISA_SYMBOL(name) hb_avx2_##name
#define HB_THIS_ISA HB_ISA_AVX2
#elif defined(HB_TARGET_AVX512)
#define HB_ISA_SYMBOL(name) hb_avx512_##name
#define HB_THIS_ISA HB_ISA_AVX512
#elif defined(HB_TARGET_NEON)
#define HB_ISA_SYMBOL(name) hb_neon_##name
#define HB_THIS_ISA HB_ISA_NEON
#endif

/* Loads lane block [i, i + lanes) of each stream; a short tail is padded with pad. One load per
 * stream either way (from the stream, or from the padded copy), so the vectors stay in registers. */
HB_INLINE void load_block(const float *const *src, int streams, size_t i, size_t lanes, float pad, vf *dst)
{
    float padded[3 + HB_SAMPLE_DIMENSIONS][HB_W]; /* the most streams a kernel loads */
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
    return (size_t)hb_popcount32(~vm_bits(valid) & live);
}

/* theta in [-pi/2, pi/2] (as floats), |phi| <= HB_PHI_LIMIT; false for NaN and Inf. */
HB_INLINE vm angle_pair_valid(vf theta, vf phi)
{
    return vm_and(vf_le(vf_abs(theta), vf_set1(HB_THETA_LIMIT)), vf_le(vf_abs(phi), vf_set1(HB_PHI_LIMIT)));
}

HB_INLINE vm unit_vector_valid(const vf w[3])
{
    vf norm2 = vf_fma(w[0], w[0], vf_fma(w[1], w[1], vf_mul(w[2], w[2])));
    return vf_le(vf_abs(vf_sub(norm2, vf_set1(1.0f))), vf_set1(HB_UNIT_TOLERANCE));
}

/* Loads lane block i of an angle batch; returns which lanes are valid samples. Invalid lanes
 * are replaced by a benign direction, so no NaN or huge value reaches the math (a float-to-int
 * conversion of one is undefined behaviour); their output is 0 anyway. Azimuths are reduced to
 * [-pi, pi] alike on every ISA (vmath.h, reduce_angle). */
HB_INLINE vm valid_angles(vf a[4])
{
    vm valid = vm_and(angle_pair_valid(a[0], a[1]), angle_pair_valid(a[2], a[3]));
    HB_UNROLL
    for (int k = 0; k < 4; k++)
        a[k] = vf_keep(valid, k % 2 ? reduce_angle(a[k]) : a[k]);
    return valid;
}

HB_INLINE vm load_angles(hb_angles_soa in, size_t i, size_t lanes, vf a[4])
{
    const float *src[4] = { in.theta_i, in.phi_i, in.theta_o, in.phi_o };
    load_block(src, 4, i, lanes, 0.0f, a);
    return valid_angles(a);
}

/* Sample k of an angle batch in every lane (the one-sample paths), as load_angles checks it. */
HB_INLINE vm load_angles_one(hb_angles_soa in, size_t k, vf a[4])
{
    a[0] = vf_set1(in.theta_i[k]), a[1] = vf_set1(in.phi_i[k]), a[2] = vf_set1(in.theta_o[k]), a[3] = vf_set1(in.phi_o[k]);
    return valid_angles(a);
}

/* Lane 0 of v into dst[k], 0 where invalid (the one-sample paths). */
HB_INLINE void store_one(float *dst, size_t k, vm valid, vf v)
{
    float lanes[HB_W];
    vf_storeu(lanes, vf_keep(valid, v));
    dst[k] = lanes[0];
}

HB_INLINE void store_rgb_one(hb_rgb_soa out, size_t k, vm valid, const vf f[3])
{
    store_one(out.r, k, valid, f[0]);
    store_one(out.g, k, valid, f[1]);
    store_one(out.b, k, valid, f[2]);
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

/* theta and phi of unit vectors w (docs/conventions.md): theta = atan2(y, |(x, z)|), phi = atan2(x, z),
 * 0 along the fibre (planar_z). */
HB_INLINE void direction_angles(const vf w[3], vf *theta, vf *phi)
{
    *theta = vf_atan2(w[1], vf_sqrt(vf_fma(w[0], w[0], vf_mul(w[2], w[2]))));
    *phi = vf_atan2(w[0], planar_z(w));
}

/* Loads lane block i of direction pairs as angles (theta_i, phi_i, theta_o, phi_o), vectors
 * validated as hb_eval_vectors does and converted. */
HB_INLINE vm load_pairs(const hb_pair_batch *in, size_t i, size_t lanes, vf a[4])
{
    if (!in->vectors.wi_x)
        return load_angles(in->angles, i, lanes, a);
    vf w[6];
    vm valid = load_vectors(in->vectors, i, lanes, w);
    direction_angles(w, &a[0], &a[1]);
    direction_angles(w + 3, &a[2], &a[3]);
    return valid;
}

/* Loads lane block i of a sampling batch: theta_o, phi_o (from w_o's vector where the batch gives
 * one), then `dims` uniform numbers. Valid lanes have a valid direction and every u in [0, 1]; the
 * others get (0, 0) and u = 1/2. */
HB_INLINE vm load_sample(const hb_sample_batch *b, int dims, size_t i, size_t lanes, vf *a)
{
    int vectors = b->wo[0] != NULL, first = vectors ? 3 : 2;
    const float *src[3 + HB_SAMPLE_DIMENSIONS] = { b->in.theta_o, b->in.phi_o };
    if (vectors)
        for (int k = 0; k < 3; k++)
            src[k] = b->wo[k];
    for (int k = 0; k < dims; k++)
        src[first + k] = b->in.u[k];
    vf raw[3 + HB_SAMPLE_DIMENSIONS];
    load_block(src, first + dims, i, lanes, 0.0f, raw);
    vm valid;
    if (vectors) {
        valid = unit_vector_valid(raw);
        for (int k = 0; k < 3; k++)
            raw[k] = vf_select(valid, raw[k], vf_set1(k == 2 ? 1.0f : 0.0f));
        direction_angles(raw, &a[0], &a[1]);
    } else {
        valid = angle_pair_valid(raw[0], raw[1]);
        a[0] = raw[0], a[1] = raw[1];
    }
    for (int k = 0; k < dims; k++) {
        a[2 + k] = raw[first + k];
        valid = vm_and(valid, vm_and(vf_ge(a[2 + k], vf_set1(0.0f)), vf_le(a[2 + k], vf_set1(1.0f))));
    }
    for (int k = 0; k < 2 + dims; k++)
        a[k] = vf_select(valid, a[k], vf_set1(k < 2 ? 0.0f : 0.5f));
    a[1] = reduce_angle(a[1]);
    return valid;
}

/* h in [-1, 1]; false for NaN. */
HB_INLINE vm offset_valid(vf h) { return vf_le(vf_abs(h), vf_set1(1.0f)); }

/* `channels` absorption streams (3, or a spectral call's wavelengths) into a[0..channels) = sigma_a
 * log2(e) per channel, each rounded from its product in double and capped at 1e30 as a plan's constant
 * is (src/models/build/derive.h), so that a sample's absorption gives what a plan of that material
 * gives; valid less the lanes whose absorption is NaN, negative or infinite. */
HB_INLINE vm load_absorption(const float *const *sigma_a, int channels, size_t i, size_t lanes, vm valid, vf *a)
{
    load_block(sigma_a, channels, i, lanes, 0.0f, a);
    HB_UNROLL
    for (int c = 0; c < channels; c++) {
        valid = vm_and(valid, vm_and(vf_ge(a[c], vf_set1(0.0f)), vf_le(a[c], vf_set1(FLT_MAX))));
        a[c] = vdw_to_vf(vdw_min(vdw_mul(vdw_from_vf(a[c]), vdw_set1(1.4426950408889634)), vdw_set1(1e30)));
    }
    return valid;
}

/* Direction pairs and three absorption streams (a[4..6], load_absorption); invalid lanes get zeros. */
HB_INLINE vm load_absorbing(const hb_absorbing_batch *b, size_t i, size_t lanes, vf a[7])
{
    vm valid = load_absorption(b->sigma_a, 3, i, lanes, load_pairs(&b->pairs, i, lanes, a), a + 4);
    HB_UNROLL
    for (int k = 0; k < 7; k++)
        a[k] = vf_keep(valid, a[k]);
    return valid;
}

/* An angle batch with h as a fifth stream; invalid lanes get h = 0. */
HB_INLINE vm load_near(hb_near_soa in, size_t i, size_t lanes, vf a[5])
{
    hb_angles_soa angles = { in.theta_i, in.phi_i, in.theta_o, in.phi_o };
    vm valid = load_angles(angles, i, lanes, a);
    const float *h = in.h;
    load_block(&h, 1, i, lanes, 0.0f, a + 4);
    valid = vm_and(valid, offset_valid(a[4]));
    HB_UNROLL
    for (int k = 0; k < 4; k++)
        a[k] = vf_keep(valid, a[k]);
    a[4] = vf_keep(valid, a[4]);
    return valid;
}

/* The near field's five streams and three absorption streams (a[5..7], load_absorption). */
HB_INLINE vm load_near_absorbing(const hb_absorbing_near *b, size_t i, size_t lanes, vf a[8])
{
    vm valid = load_absorption(b->sigma_a, 3, i, lanes, load_near(b->near, i, lanes, a), a + 5);
    HB_UNROLL
    for (int k = 0; k < 8; k++)
        a[k] = vf_keep(valid, a[k]);
    return valid;
}

/* A spectral batch's lane block: the angles a[0..3], h a[4] (0 for the far field) and the wavelengths'
 * absorptions a[5..5 + wavelengths) (load_absorption); invalid lanes get zeros. */
HB_INLINE vm load_spectral(const hb_spectral_batch *b, size_t i, size_t lanes, vf *a)
{
    hb_angles_soa angles = { b->near.theta_i, b->near.phi_i, b->near.theta_o, b->near.phi_o };
    vm valid = b->near.h ? load_near(b->near, i, lanes, a) : load_angles(angles, i, lanes, a);
    if (!b->near.h)
        a[4] = vf_set1(0.0f);
    valid = load_absorption(b->sigma_a, b->wavelengths, i, lanes, valid, a + 5);
    for (int k = 0; k < 5 + b->wavelengths; k++)
        a[k] = vf_keep(valid, a[k]);
    return valid;
}

/* Sample k of a near-field batch in every lane (the one-sample paths), as load_near checks it. */
HB_INLINE vm load_near_one(hb_near_soa in, size_t k, vf a[5])
{
    hb_angles_soa angles = { in.theta_i, in.phi_i, in.theta_o, in.phi_o };
    vm valid = vm_and(load_angles_one(angles, k, a), offset_valid(vf_set1(in.h[k])));
    for (int s = 0; s < 4; s++)
        a[s] = vf_keep(valid, a[s]);
    a[4] = vf_keep(valid, vf_set1(in.h[k]));
    return valid;
}

/* Sample k of a spectral near-field batch in every lane (the one-sample paths), as load_spectral
 * checks it: the angles a[0..3], h a[4], the absorptions a[5..5 + wavelengths) as load_absorption
 * converts them. */
HB_INLINE vm load_spectral_one(const hb_spectral_batch *b, size_t k, vf *a)
{
    vm valid = load_near_one(b->near, k, a);
    int ok = 1;
    for (int j = 0; j < b->wavelengths; j++) {
        float s = b->sigma_a[j][k];
        ok = ok && s >= 0.0f && s <= FLT_MAX;
        a[5 + j] = vf_set1(ok ? (float)fmin((double)s * 1.4426950408889634, 1e30) : 0.0f);
    }
    if (!ok)
        valid = vf_lt(a[5], a[5]); /* false in every lane */
    for (int j = 0; j < 5 + b->wavelengths; j++)
        a[j] = vf_keep(valid, a[j]);
    return valid;
}

/* `planes` planes of one sample from lane 0 (the one-sample paths); 0 where invalid. */
HB_INLINE void store_planes_one(float *const *out, int planes, size_t k, vm valid, const vf *f)
{
    for (int c = 0; c < planes; c++)
        store_one(out[c], k, valid, f[c]);
}

/* A near-field sampling batch: theta_o, phi_o, the `dims` uniform numbers, then h last. */
HB_INLINE vm load_sample_near(hb_sample_streams in, int dims, size_t i, size_t lanes, vf *a)
{
    hb_sample_batch far = { .in = in }; /* load_sample reads theta_o, phi_o and u */
    vm valid = load_sample(&far, dims, i, lanes, a);
    vf *h = a + 2 + dims;
    load_block(&in.h, 1, i, lanes, 0.0f, h);
    vm h_valid = offset_valid(*h);
    for (int k = 0; k < 2 + dims; k++)
        a[k] = vf_select(h_valid, a[k], vf_set1(k < 2 ? 0.0f : 0.5f));
    *h = vf_keep(vm_and(valid, h_valid), *h);
    return vm_and(valid, h_valid);
}

/* A spectral near-field sampling batch: load_sample_near's streams, then the wavelengths'
 * absorptions after h (load_absorption); invalid lanes get zero absorptions. */
HB_INLINE vm load_sample_near_spectral(const hb_spectral_sample_batch *b, int dims, size_t i, size_t lanes, vf *a)
{
    vm valid = load_sample_near(b->in, dims, i, lanes, a);
    vf *absorption = a + 3 + dims;
    valid = load_absorption(b->sigma_a, b->wavelengths, i, lanes, valid, absorption);
    for (int k = 0; k < b->wavelengths; k++)
        absorption[k] = vf_keep(valid, absorption[k]);
    return valid;
}

/* `planes` planes of a spectral result; invalid lanes get 0. */
HB_INLINE void store_planes(float *const *out, int planes, size_t i, size_t lanes, vm valid, const vf *f)
{
    for (int c = 0; c < planes; c++)
        store_block(out[c], i, lanes, vf_keep(valid, f[c]));
}

/* Invalid lanes get 0 in every plane. */
HB_INLINE void store_rgb(hb_rgb_soa out, size_t i, size_t lanes, vm valid, const vf f[3])
{
    float *planes[3] = { out.r, out.g, out.b };
    HB_UNROLL
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

/* A sampled direction, its pdf and `planes` weights of a spectral sampler; invalid lanes get 0. */
HB_INLINE void store_sample_spectral(const hb_sample_spectral_out *out, int planes, size_t i, size_t lanes, vm valid,
                                     vf theta_i, vf phi_i, vf pdf, const vf *weight)
{
    store_block(out->theta_i, i, lanes, vf_keep(valid, theta_i));
    store_block(out->phi_i, i, lanes, vf_keep(valid, phi_i));
    store_block(out->pdf, i, lanes, vf_keep(valid, pdf));
    store_planes(out->weight, planes, i, lanes, valid, weight);
}

/* The same into a sampling batch, w_i as a unit vector where the batch asks for one. */
HB_INLINE void store_sampled(const hb_sample_batch *b, size_t i, size_t lanes, vm valid, vf theta_i, vf phi_i,
                             vf pdf, const vf weight[3])
{
    if (!b->wi[0]) {
        store_sample(b->out, i, lanes, valid, theta_i, phi_i, pdf, weight);
        return;
    }
    vf sin_t, cos_t, sin_p, cos_p;
    vf_sincos(theta_i, &sin_t, &cos_t);
    vf_sincos(phi_i, &sin_p, &cos_p);
    vf w[3] = { vf_mul(sin_p, cos_t), sin_t, vf_mul(cos_p, cos_t) };
    for (int k = 0; k < 3; k++)
        store_block(b->wi[k], i, lanes, vf_keep(valid, w[k]));
    store_block(b->out.pdf, i, lanes, vf_keep(valid, pdf));
    store_rgb(b->out.weight, i, lanes, valid, weight);
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

/* HB_BATCH for a call of a few samples taken one at a time, sample k in every lane of `a` (load_one),
 * `compute` storing lane 0 (store_one). */
#define HB_ONE_BY_ONE(load_one, streams, in, n, invalid, compute)     \
    do {                                                              \
        hb_fp_mode mode_ = hb_flush_subnormals();                     \
        size_t bad_ = 0;                                              \
        for (size_t k = 0; k < (n); k++) {                            \
            vf a[streams];                                            \
            vm valid = load_one((in), k, a);                          \
            compute;                                                  \
            bad_ += !(vm_bits(valid) & 1u);                           \
        }                                                             \
        *(invalid) = bad_;                                            \
        hb_fp_restore(mode_);                                         \
    } while (0)

#endif

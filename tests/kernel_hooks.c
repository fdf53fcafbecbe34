/* The kernel internals the tests read (kernel_hooks.h), compiled once per ISA like the library's
 * kernel units: the vector math, dFH11's detector and MJC03's cubic solver over arrays. */
#include "kernel/batch.h"
#include "kernel_hooks.h"
#include "models/deon/azimuthal.h"
#include "models/marschner/cubic.h"

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

const hb_kernel_hooks HB_ISA_SYMBOL(kernel_hooks) = {
    .math_map = math_map,
    .detector_map = detector_map,
    .cubic_map = cubic_map,
};

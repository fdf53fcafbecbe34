/* One ISA's table of kernels, hb_<isa>_kernels: the Makefile compiles this file once per
 * instruction set, beside each model's kernels.c of the same ISA, whose tables it points to.
 * It also holds the vector math on arrays that the accuracy tests read. */
#include "batch.h"

extern const hb_deon_kernels HB_ISA_SYMBOL(deon_kernels);
extern const hb_marschner_kernels HB_ISA_SYMBOL(marschner_kernels);
extern const hb_huang_kernels HB_ISA_SYMBOL(huang_kernels);

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

const hb_kernels HB_ISA_SYMBOL(kernels) = {
    .isa = HB_THIS_ISA,
    .width = HB_W,
    .deon = &HB_ISA_SYMBOL(deon_kernels),
    .marschner = &HB_ISA_SYMBOL(marschner_kernels),
    .huang = &HB_ISA_SYMBOL(huang_kernels),
    .math_map = math_map,
};

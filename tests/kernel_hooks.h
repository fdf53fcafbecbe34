/* Kernel internals the accuracy tests read, compiled once per ISA from tests/kernel_hooks.c
 * (the library itself carries none of them). */
#ifndef HB_TEST_KERNEL_HOOKS_H
#define HB_TEST_KERNEL_HOOKS_H

#include <stddef.h>

#include "models/deon/constants.h"

/* Functions of src/math/vmath.h the tests map over arrays. */
typedef enum hb_math_fn {
    HB_FN_EXP, HB_FN_EXP_FLUSH, HB_FN_EXP2_NEG, HB_FN_LOG, HB_FN_LOG1P, HB_FN_SIN, HB_FN_COS, HB_FN_ASIN, HB_FN_ASIN_NARROW, HB_FN_ACOS,
    HB_FN_ATAN2, HB_FN_SQRT, HB_FN_I0, HB_FN_I0E, HB_FN_LOG_I0, HB_FN_COUNT
} hb_math_fn;

typedef struct hb_kernel_hooks {
    /* one vector math function on arrays (b: atan2's second operand, else NULL) */
    void (*math_map)(hb_math_fn fn, size_t n, const float *a, const float *b, float *out);
    /* dFH11's detector D_p(x) as the kernel evaluates it */
    void (*detector_map)(const hb_detector *d, size_t n, const float *x, float *out);
    /* MJC03's cubic solver: roots[3 * i + k], NaN where root k is not real */
    void (*cubic_map)(size_t n, const float *P, const float *Q, float *roots);
} hb_kernel_hooks;

/* The hooks of an ISA this CPU runs; NULL otherwise. */
const hb_kernel_hooks *hb_kernel_hooks_for(hb_isa isa);

#endif

/* The table of kernels one ISA translation unit (src/kernel.c) exports, and the
 * plain constants those kernels read from a plan. Internal. */
#ifndef HB_KERNELS_H
#define HB_KERNELS_H

#include <stddef.h>
#include "hairbsdf.h"

/* Constants of one lobe's longitudinal function, fixed at plan creation. */
typedef struct hb_longitudinal {
    double inv_v;     /* 1 / v, v = beta_m^2 */
    double log_norm;  /* log(1 / (v (1 - e^(-2/v)))), the csch factor of dFH11 eq. 7 without e^(-1/v) */
    double shift;     /* alpha_p: M_p is evaluated at theta_o - shift (dFH11 sec. 6) */
    double cos_shift, sin_shift;
} hb_longitudinal;

/* Functions of src/math/vmath.h exported for the accuracy tests. */
typedef enum hb_math_fn {
    HB_FN_EXP, HB_FN_LOG, HB_FN_LOG1P, HB_FN_SIN, HB_FN_COS, HB_FN_ASIN, HB_FN_ACOS,
    HB_FN_ATAN2, HB_FN_SQRT, HB_FN_I0, HB_FN_I0E, HB_FN_LOG_I0, HB_FN_COUNT
} hb_math_fn;

typedef void (*hb_longitudinal_angles_fn)(const hb_longitudinal *lobe, size_t n, hb_angles_soa in,
                                          float *out, size_t *invalid);
typedef void (*hb_longitudinal_vectors_fn)(const hb_longitudinal *lobe, size_t n, hb_vectors_soa in,
                                           float *out, size_t *invalid);

typedef struct hb_kernels {
    hb_isa isa;
    int width; /* float lanes */
    hb_longitudinal_angles_fn longitudinal_angles[2];   /* indexed by hb_i0 */
    hb_longitudinal_vectors_fn longitudinal_vectors[2]; /* indexed by hb_i0 */
    void (*math_map)(hb_math_fn fn, size_t n, const float *a, const float *b, float *out);
} hb_kernels;

/* NULL when the ISA is not compiled in or not supported by this CPU. */
const hb_kernels *hb_kernels_for(hb_isa isa);

#endif

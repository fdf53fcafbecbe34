/* dFH11's M_p (eq. 7) as a plan holds it, for every model that evaluates it (dFH11, CBTB16):
 * one lobe's constants, and lobes side by side one per lane. Fixed at plan creation. */
#ifndef HB_COMMON_LONGITUDINAL_CONSTANTS_H
#define HB_COMMON_LONGITUDINAL_CONSTANTS_H

#include "hairbsdf.h"

/* Constants of one lobe's longitudinal function, fixed at plan creation. */
typedef struct hb_longitudinal {
    double inv_v;     /* 1 / v, v = beta_m^2 */
    double log_norm;  /* log(1 / (v (1 - e^(-2/v)))), the csch factor of dFH11 eq. 7 without e^(-1/v) */
    double shift;     /* alpha_p: M_p is evaluated at theta_o - shift (dFH11 sec. 6) */
    double cos_shift, sin_shift;
    /* Below HB_QUALITY_HIGH M_p is formed in float (docs/deon.md): the same
     * constants rounded, and the shift c of theta_o'' = sign * theta_o - c as a float pair
     * c_hi + c_lo for the three cases of the pole reflection (none, above pi/2, below -pi/2). */
    int single;
    float inv_v_f, cos_shift_f, sin_shift_f;
    float inv_v_log2e_f, log2_norm_f; /* log2(e) / v and log2(norm), for the float path's 2^-t */
    float shift_hi[3], shift_lo[3];
} hb_longitudinal;

/* The standard shape's lobes side by side, one lobe per lane, for a call of one sample: lane p holds
 * order p up to HB_STANDARD_PMAX, lane HB_LOBE_LANES - 1 the residual, and the lanes past them repeat
 * R's M_p constants with a detector of 0. M_p's float path (longitudinal.h, longitudinal_lobe_lanes)
 * and the nearest Gaussian of eq. 11, D = norm 2^-(x^2 exponent), times 0 for a lobe the plan leaves
 * out; the residual's is uniform (exponent 0, norm 1 / (2 pi)). */
#define HB_LOBE_LANES 5
#define HB_RESIDUAL_DETECTOR 0.159154943f /* the residual's detector: uniform in phi, 1 / (2 pi) */
#define HB_LANE_ARRAY 16 /* the widest vector */
typedef struct hb_lobe_lanes {
    float inv_v_f[HB_LANE_ARRAY], inv_v_log2e_f[HB_LANE_ARRAY], log2_norm_f[HB_LANE_ARRAY];
    float shift_hi[3][HB_LANE_ARRAY], shift_lo[3][HB_LANE_ARRAY];
    float detector_norm[HB_LANE_ARRAY], detector_exponent[HB_LANE_ARRAY];
} hb_lobe_lanes;

/* Lane k of `lanes`: the float M_p constants of l and a detector (longitudinal.c). */
void hb_lobe_lane_set(hb_lobe_lanes *lanes, int k, const hb_longitudinal *l, float detector_norm,
                      float detector_exponent);

/* dFH11 eq. 7's constants for variance v and shift, in double, and rounded for the float path below
 * HB_QUALITY_HIGH (longitudinal.c). */
void hb_longitudinal_derive(hb_longitudinal *l, double v, double shift, hb_quality quality);

#endif

/* The plan-time constants of dFH11's M_p (eq. 7) for every model that evaluates it. */
#include <math.h>

#include "longitudinal_constants.h"

void hb_longitudinal_derive(hb_longitudinal *l, double v, double shift, hb_quality quality)
{
    l->inv_v = 1.0 / v;
    l->log_norm = -log(v) - log(-expm1(-2.0 / v));
    l->shift = shift;
    l->cos_shift = cos(shift);
    l->sin_shift = sin(shift);
    l->single = quality < HB_QUALITY_HIGH;
    l->inv_v_f = (float)l->inv_v;
    l->inv_v_log2e_f = (float)(l->inv_v * M_LOG2E);
    l->log2_norm_f = (float)(l->log_norm * M_LOG2E);
    l->cos_shift_f = (float)l->cos_shift;
    l->sin_shift_f = (float)l->sin_shift;
    /* theta_o - shift reflected across a pole: pi - (theta_o - shift) = -theta_o - (-shift - pi),
     * -pi - (theta_o - shift) = -theta_o - (pi - shift) */
    const double c[3] = { shift, -shift - M_PI, M_PI - shift };
    for (int k = 0; k < 3; k++) {
        l->shift_hi[k] = (float)c[k];
        l->shift_lo[k] = (float)(c[k] - (double)l->shift_hi[k]);
    }
}

void hb_lobe_lane_set(hb_lobe_lanes *lanes, int k, const hb_longitudinal *l, float detector_norm,
                      float detector_exponent)
{
    lanes->detector_norm[k] = detector_norm;
    lanes->detector_exponent[k] = detector_exponent;
    lanes->inv_v_f[k] = l->inv_v_f;
    lanes->inv_v_log2e_f[k] = l->inv_v_log2e_f;
    lanes->log2_norm_f[k] = l->log2_norm_f;
    for (int c = 0; c < 3; c++) {
        lanes->shift_hi[c][k] = l->shift_hi[c];
        lanes->shift_lo[c][k] = l->shift_lo[c];
    }
}

/* Cosines of inclinations near the poles, where a float angle has lost the digits of pi/2 - |t|
 * that its cosine is: dFH11's and CBTB16's M_p, and cos(theta_d) of every separable model. */
#ifndef HB_MODELS_INCLINATION_H
#define HB_MODELS_INCLINATION_H

#include "math/vmath.h"

/* cos(t) = sin(pi/2 - |t| + low) for |t| up to just beyond pi/2 (the float pi/2 lies beyond it,
 * where the cosine is negative, as eq. 7 has it), relative-accurate near the poles: pi/2 - |t| is
 * exact there (Sterbenz) before low, pi/2's low part and any of t's own, is added. */
HB_INLINE vf cos_near_pole(vf t, vf low)
{
    return vf_sin_halfpi(vf_add(vf_sub(vf_set1(HB_PIO2_F), vf_abs(t)), low));
}

/* The low part for t = t_hi + t_lo: pi/2's low part less t_lo with t_hi's sign. */
HB_INLINE vf pole_distance_low(vf t_hi, vf t_lo)
{
    return vf_fnma(t_lo, vf_copysign(vf_set1(1.0f), t_hi), vf_set1(HB_PIO2_LO));
}

/* cos(theta_d), theta_d = (theta_o - theta_i) / 2 (dFH11 sec. 5), from the difference as a float pair
 * (hi + lo exactly, TwoSum): near opposite poles theta_d -> pi/2, where the float difference alone
 * rounds away the digits of pi/2 - |theta_d| that cos(theta_d) is. */
HB_INLINE vf cos_half_difference(vf theta_o, vf theta_i)
{
    vf minus_i = vf_neg(theta_i), d = vf_add(theta_o, minus_i);
    vf hi = vf_mul(vf_set1(0.5f), d), lo = vf_mul(vf_set1(0.5f), vf_two_sum_error(theta_o, minus_i, d));
    return vf_max(cos_near_pole(hi, pole_distance_low(hi, lo)), vf_set1(0.0f));
}

#endif

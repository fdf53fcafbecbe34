/* Double-precision references. They share only the equations with the SIMD
 * kernels: their own Bessel function, libm trigonometry, no float anywhere. Internal. */
#ifndef HB_REFERENCE_H
#define HB_REFERENCE_H

#include <stddef.h>
#include "hairbsdf.h"

/* e^-|x| I0(x) to double precision (power series below |x| = 30, asymptotic expansion above). */
double hb_ref_bessel_i0e(double x);
/* log I0(x), relative-accurate also as x -> 0 (where it is x^2/4). */
double hb_ref_log_bessel_i0(double x);

/* dFH11 eq. 7, M_p(v, theta_i, theta_o); with HB_I0_PAPER, I0 is the series of eq. 15. */
double hb_ref_deon_longitudinal(double v, double theta_i, double theta_o, hb_i0 i0);

/* Reference batch evaluation of a plan's term: writes f (one channel) and returns the invalid count. */
size_t hb_ref_eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, float *out);
size_t hb_ref_eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, float *out);

#endif

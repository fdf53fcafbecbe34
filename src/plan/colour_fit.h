/* CBTB16 eq. 9's fit of a fibre's multiply-scattered colour under its azimuthal roughness beta_n:
 * C = exp(-d(beta_n) sqrt(sigma_a)). Internal. */
#ifndef HB_PLAN_COLOUR_FIT_H
#define HB_PLAN_COLOUR_FIT_H

/* d(beta_n) = 5.969 - 0.215 b + 2.532 b^2 - 10.73 b^3 + 5.574 b^4 + 0.245 b^5 */
double hb_colour_fit_depth(double beta_n);

#endif

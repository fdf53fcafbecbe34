/* The real roots of a depressed cubic gamma^3 + P gamma + Q = 0, in closed form and
 * branch-free over the SIMD vocabulary (MJC03 solves phi_hat(p, gamma_i) = phi, a cubic
 * without a quadratic term, for the entry offset). With r = sqrt(|P| / 3) and
 * z = Q / (2 r^3), the trigonometric / hyperbolic forms of Cardano's solution are
 *   P > 0:           one root   -2 r sinh(asinh(z) / 3)
 *   P < 0, |z| > 1:  one root   -2 sign(z) r cosh(acosh(|z|) / 3)
 *   P < 0, |z| <= 1: three      2 r cos(acos(-z) / 3 - 2 pi k / 3), k = 0, 1, 2.
 * None of them cancels: as P grows (a thin lobe of the cubic, eta' -> infinity at grazing
 * angles) the root tends to -Q / P smoothly, and at P -> 0 to the cube root of -Q. The roots
 * are within 4e-7 of the double reference's (tests/test_marschner_full.c); a Newton step
 * after them was measured to change f by nothing visible at 1e-5, so there is none. */
#ifndef HB_MARSCHNER_CUBIC_H
#define HB_MARSCHNER_CUBIC_H

#include "math/vmath.h"

/* |P| below this is treated as this (with its sign): the roots are continuous there, and
 * it keeps z = Q / (2 r^3) below 1e17 for every cubic of the model, so z^2 cannot overflow. */
#define HB_CUBIC_P_FLOOR 1e-6f

/* The root that always exists (the only one unless P < 0 and |z| <= 1), and whether all three
 * are real. Writes r and z for the trigonometric roots. */
HB_INLINE vf cubic_first_root(vf P, vf Q, vf *r_out, vf *z_out, vm *three)
{
    vf abs_p = vf_max(vf_abs(P), vf_set1(HB_CUBIC_P_FLOOR));
    vf r = vf_sqrt(vf_mul(abs_p, vf_set1(1.0f / 3.0f)));
    vf z = vf_div(Q, vf_mul(vf_set1(2.0f), vf_mul(r, vf_mul(r, r))));
    vf az = vf_abs(z), z2 = vf_mul(z, z);
    vm hyperbolic_cos = vf_lt(P, vf_set1(0.0f));
    *three = vm_and(hyperbolic_cos, vf_le(az, vf_set1(1.0f)));
    /* asinh|z| = log1p(|z| + z^2 / (sqrt(z^2 + 1) + 1)) and acosh|z| = log1p(|z| - 1 + sqrt(z^2 - 1)),
     * both without cancellation (acosh is only used for |z| > 1) */
    vf root_term = vf_sqrt(vf_max(vf_add(z2, vf_select(hyperbolic_cos, vf_set1(-1.0f), vf_set1(1.0f))), vf_set1(0.0f)));
    vf excess = vf_select(hyperbolic_cos, vf_sub(root_term, vf_set1(1.0f)),
                          vf_div(z2, vf_add(root_term, vf_set1(1.0f))));
    vf y = vf_mul(vf_log1p(vf_add(az, excess)), vf_set1(1.0f / 3.0f));
    /* sinh(y) or cosh(y) from one exponential; sinh by its series where e - 1/e would cancel */
    vf e = vf_exp(y), inv_e = vf_div(vf_set1(1.0f), e);
    vf y2 = vf_mul(y, y); /* y (1 + y^2/6 + y^4/120 + y^6/5040): relative error < 3e-9 for y < 0.5 */
    vf sinh_series = vf_mul(y, vf_fma(y2, vf_fma(y2, vf_fma(y2, vf_set1(1.0f / 5040.0f), vf_set1(1.0f / 120.0f)),
                                                 vf_set1(1.0f / 6.0f)),
                                      vf_set1(1.0f)));
    vf sinh_y = vf_select(vf_lt(y, vf_set1(0.5f)), sinh_series, vf_mul(vf_set1(0.5f), vf_sub(e, inv_e)));
    vf hyper = vf_select(hyperbolic_cos, vf_mul(vf_set1(0.5f), vf_add(e, inv_e)), sinh_y);
    vf sign_z = vf_select(vf_lt(z, vf_set1(0.0f)), vf_set1(-1.0f), vf_set1(1.0f));
    *r_out = r;
    *z_out = z;
    return vf_mul(vf_mul(vf_set1(-2.0f), sign_z), vf_mul(r, hyper));
}

/* All real roots: root[k] with real[k] its existence. With all_three 0 the plan knows the
 * cubic is monotonic (P > 0 for every sample) and only root 0 is computed. */
HB_INLINE void cubic_roots(vf P, vf Q, int all_three, vf root[3], vm real[3])
{
    vf r, z;
    vm three;
    vf first = cubic_first_root(P, Q, &r, &z, &three);
    real[0] = vf_eq(P, P);
    real[1] = real[2] = vm_not(real[0]);
    root[1] = root[2] = vf_set1(0.0f);
    if (all_three) {
        /* 2 r cos(t - 2 pi k / 3), t = acos(-z) / 3, from one sincos. Computed for -|z| and the
         * set negated for z > 0 (the roots of Q and -Q are negatives), so phi and -phi give
         * roots that are exact negatives, as they are for the hyperbolic root. */
        vf t = vf_mul(vf_acos(vf_min(vf_abs(z), vf_set1(1.0f))), vf_set1(1.0f / 3.0f));
        vf st, ct;
        vf_sincos(t, &st, &ct);
        vf sign_z = vf_select(vf_lt(z, vf_set1(0.0f)), vf_set1(-1.0f), vf_set1(1.0f));
        vf two_r = vf_mul(vf_mul(vf_set1(-2.0f), sign_z), r);
        vf half = vf_mul(vf_set1(-0.5f), ct), root3_half = vf_mul(vf_set1(0.866025404f), st);
        first = vf_select(three, vf_mul(two_r, ct), first);
        root[1] = vf_mul(two_r, vf_add(half, root3_half)); /* k = 1: cos(t - 2 pi / 3) */
        root[2] = vf_mul(two_r, vf_sub(half, root3_half)); /* k = 2: cos(t + 2 pi / 3) */
        real[1] = real[2] = three;
    }
    root[0] = first;
}

#endif

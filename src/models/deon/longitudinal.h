/* dFH11 longitudinal scattering M_p (eq. 7) over the SIMD vocabulary.
 *
 * eq. 7:  M_p = csch(1/v) / (2v) * exp(-sin(theta_i) sin(theta_o) / v) * I0(cos(theta_i) cos(theta_o) / v).
 * With csch(1/v)/(2v) = e^(-1/v) / (v (1 - e^(-2/v))) and
 * -(1 + sin sin)/v = -(1 - cos(theta_i + theta_o))/v - x, x = cos cos / v, it becomes
 *     M_p = exp(log_norm - (1 - cos(theta_i + theta_o))/v - x + |x|) * e^(-|x|) I0(|x|),
 * which never overflows, and whose large exponent (up to 2/v) is formed in double
 * precision, so M_p keeps float accuracy for v down to 1e-4. */
#ifndef HB_DEON_LONGITUDINAL_H
#define HB_DEON_LONGITUDINAL_H

#include "../../math/vmath.h"
#include "../../kernels.h"

/* log of dFH11 eq. 15, the 10-term series S(x) = sum_{i<=10} (x^2/4)^i / (i!)^2. For
 * u = x^2/4 > 1 it is evaluated as u^10 R(1/u) so that no power overflows. */
static inline vf log_i0_series_paper(vf ax)
{
    static const float inv_factorial_sq[11] = {
        1.0f, 1.0f, 1.0f / 4.0f, 1.0f / 36.0f, 1.0f / 576.0f, 1.0f / 14400.0f, 1.0f / 518400.0f,
        1.0f / 25401600.0f, 1.0f / 1625702400.0f, 1.0f / 131681894400.0f, 1.0f / 13168189440000.0f,
    };
    vf u = vf_mul(vf_mul(ax, ax), vf_set1(0.25f));
    vf us = vf_min(u, vf_set1(1.0f));
    vf w = vf_rcp(vf_max(u, vf_set1(1.0f)));
    vf s = vf_set1(inv_factorial_sq[10]), r = vf_set1(inv_factorial_sq[0]);
    for (int i = 9; i >= 0; i--) {
        s = vf_fma(s, us, vf_set1(inv_factorial_sq[i]));
        r = vf_fma(r, w, vf_set1(inv_factorial_sq[10 - i]));
    }
    vf log_large = vf_fma(vf_set1(10.0f), vf_neg(vf_log(w)), vf_log(r));
    return vf_select(vf_le(u, vf_set1(1.0f)), vf_log(s), log_large);
}

/* dFH11 eq. 7 from 1 - cos(theta_i + theta_o - shift) (double) and x = cos cos' / v. */
static inline vf longitudinal_deon(const hb_longitudinal *lobe, vdw one_minus_cos_sum, vf x, hb_i0 i0)
{
    vf ax = vf_abs(x);
    vf exponent = vf_add(vf_min(x, vf_set1(0.0f)), vf_min(x, vf_set1(0.0f))); /* -x + |x| */
    vf factor;
    if (i0 == HB_I0_PAPER) {
        exponent = vf_add(vf_sub(exponent, ax), log_i0_series_paper(ax)); /* e^-|x| S(|x|) */
        factor = vf_set1(1.0f);
    } else {
        vm small = vf_le(ax, vf_set1(3.75f));
        vf xs = vf_min(ax, vf_set1(3.75f)), xl = vf_max(ax, vf_set1(3.75f));
        exponent = vf_sub(exponent, vf_select(small, ax, vf_set1(0.0f)));
        vf i0_small = vf_add(vf_set1(1.0f), vf_i0_small_minus1(xs));        /* A&S 9.8.1 */
        vf i0e_large = vf_div(vf_i0_large_poly(xl), vf_sqrt(xl));          /* A&S 9.8.2 */
        factor = vf_select(small, i0_small, i0e_large);
    }
    vdw e = vdw_fma(one_minus_cos_sum, vdw_set1(-lobe->inv_v), vdw_set1(lobe->log_norm));
    return vf_mul(vf_exp_dw(vdw_add(e, vdw_from_vf(exponent))), factor);
}

/* M_p(v, theta_i, theta_o - shift) from angles. theta_o - shift is carried as a
 * float pair (hi + lo) so cos(theta_o - shift) keeps relative accuracy near pi/2. */
static inline vf longitudinal_deon_angles(const hb_longitudinal *lobe, vf theta_i, vf theta_o, hb_i0 i0)
{
    vdw ti = vdw_from_vf(theta_i);
    vdw to = vdw_sub(vdw_from_vf(theta_o), vdw_set1(lobe->shift));
    vdw s = vdw_sin_taylor(vdw_mul(vdw_add(ti, to), vdw_set1(0.5)));
    vdw one_minus_cos_sum = vdw_mul(vdw_add(s, s), s); /* 1 - cos(a) = 2 sin^2(a/2) */
    vf to_hi = vdw_to_vf(to);
    vf to_lo = vdw_to_vf(vdw_sub(to, vdw_from_vf(to_hi)));
    vf sin_hi, cos_hi;
    vf_sincos(to_hi, &sin_hi, &cos_hi);
    vf cos_o = vf_fnma(sin_hi, to_lo, cos_hi);
    vf x = vf_mul(vf_mul(vf_cos(theta_i), cos_o), vf_set1((float)lobe->inv_v));
    return longitudinal_deon(lobe, one_minus_cos_sum, x, i0);
}

/* sin and cos of the inclination of w = (x, y, z), in double: y / |w| and |(x, z)| / |w|. */
static inline void inclination_dw(vf x, vf y, vf z, vdw *sin_theta, vdw *cos_theta)
{
    vdw xd = vdw_from_vf(x), yd = vdw_from_vf(y), zd = vdw_from_vf(z);
    vdw planar2 = vdw_fma(xd, xd, vdw_mul(zd, zd));
    vdw inv_norm = vdw_div(vdw_set1(1.0), vdw_sqrt(vdw_fma(yd, yd, planar2)));
    *sin_theta = vdw_mul(yd, inv_norm);
    *cos_theta = vdw_mul(vdw_sqrt(planar2), inv_norm);
}

/* M_p(v, theta_i, theta_o - shift) from unit vectors, all in double up to x. */
static inline vf longitudinal_deon_vectors(const hb_longitudinal *lobe, const vf wi[3], const vf wo[3], hb_i0 i0)
{
    vdw si, ci, so, co;
    inclination_dw(wi[0], wi[1], wi[2], &si, &ci);
    inclination_dw(wo[0], wo[1], wo[2], &so, &co);
    vdw cs = vdw_set1(lobe->cos_shift), ss = vdw_set1(lobe->sin_shift);
    vdw co_shifted = vdw_fma(co, cs, vdw_mul(so, ss)); /* cos(theta_o - shift) */
    vdw so_shifted = vdw_sub(vdw_mul(so, cs), vdw_mul(co, ss));
    vdw cos_sum = vdw_sub(vdw_mul(ci, co_shifted), vdw_mul(si, so_shifted));
    vdw one_minus_cos_sum = vdw_max(vdw_sub(vdw_set1(1.0), cos_sum), vdw_set1(0.0));
    vf x = vdw_to_vf(vdw_mul(vdw_mul(ci, co_shifted), vdw_set1(lobe->inv_v)));
    return longitudinal_deon(lobe, one_minus_cos_sum, x, i0);
}

#endif

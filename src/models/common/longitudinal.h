/* dFH11 longitudinal scattering M_p (eq. 7) over the SIMD vocabulary, for every model that uses it.
 *
 * eq. 7:  M_p = csch(1/v) / (2v) * exp(-sin(theta_i) sin(theta_o) / v) * I0(cos(theta_i) cos(theta_o) / v).
 * With csch(1/v)/(2v) = e^(-1/v) / (v (1 - e^(-2/v))) and
 * -(1 + sin sin)/v = -(1 - cos(theta_i + theta_o))/v - x, x = cos cos / v, it becomes
 *     M_p = exp(log_norm - (1 - cos(theta_i + theta_o))/v - x) * I0(x),
 *         = exp(log_norm - (1 - cos(theta_i + theta_o))/v) * e^-x I0(x)   for x >= 0,
 * which never overflows, and whose large exponent (up to 2/v) is formed in double
 * precision, so M_p keeps float accuracy for v down to 1e-6.
 * A tilt shift can push theta_o - alpha_p past a pole, where cos < 0 and the
 * exponent would be a cancellation of two large terms. eq. 7 is unchanged by the
 * reflection theta -> +-pi - theta (sin kept, cos negated, I0 even), so the shifted
 * angle is reflected back into [-pi/2, pi/2] first and x >= 0 always. */
#ifndef HB_COMMON_LONGITUDINAL_H
#define HB_COMMON_LONGITUDINAL_H

#include "math/vmath.h"
#include "inclination.h"
#include "longitudinal_constants.h"

/* log of dFH11 eq. 15, the 10-term series S(x) = sum_{i<=10} (x^2/4)^i / (i!)^2. For
 * u = x^2/4 > 1 it is evaluated as u^10 R(1/u) so that no power overflows. */
HB_INLINE vf log_i0_series_paper(vf ax)
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

#define HB_MP_EXPONENT_FLOOR -80.0

/* e^-x I0(x) as e^exponent * factor for x >= -3.75 (negative only by a cosine just beyond a
 * pole): A&S 9.8.1 (exponent -x) below |x| = 3.75 and 9.8.2 (exponent 0) above, or dFH11
 * eq. 15's series as a log. */
HB_INLINE void i0_scaled(vf x, hb_i0 i0, vf *exponent, vf *factor)
{
    vf ax = vf_abs(x);
    if (i0 == HB_I0_PAPER) {
        *exponent = vf_sub(log_i0_series_paper(ax), x); /* e^-x S(x), eq. 15 */
        *factor = vf_set1(1.0f);
    } else {
        vm small = vf_le(ax, vf_set1(3.75f));
        vf xs = vf_min(ax, vf_set1(3.75f)), xl = vf_max(ax, vf_set1(3.75f));
        *exponent = vf_keep(small, vf_neg(x));
        vf i0_small = vf_add(vf_set1(1.0f), vf_i0_small_minus1(xs)); /* A&S 9.8.1 */
        vf i0e_large = vf_i0e_large(xl);                             /* A&S 9.8.2 */
        *factor = vf_select(small, i0_small, i0e_large);
    }
}

/* dFH11 eq. 7 from 1 - cos(theta_i + theta_o') (double) and x = cos(theta_i) cos(theta_o') / v >= 0. */
HB_INLINE vf longitudinal_deon(const hb_longitudinal *lobe, vdw one_minus_cos_sum, vf x, hb_i0 i0)
{
    vf exponent, factor;
    i0_scaled(vf_abs(x), i0, &exponent, &factor); /* x >= 0 up to the rounding of a cosine at pi/2 */
    vdw e = vdw_add(vdw_fma(one_minus_cos_sum, vdw_set1(-lobe->inv_v), vdw_set1(lobe->log_norm)),
                    vdw_from_vf(exponent));
    /* Below e^-80 the result (factor >= 0.004) is under 1e-34: return 0 rather than
     * form a denormal, whose multiply costs a microcode assist on x86. */
    vdw e_clamped = vdw_max(e, vdw_set1(HB_MP_EXPONENT_FLOOR));
    vm significant = vf_ge(vdw_to_vf(e), vf_set1((float)HB_MP_EXPONENT_FLOOR));
    return vf_keep(significant, vf_mul(vf_exp_dw(e_clamped), factor));
}

/* The float path of dFH11 eq. 7 (plans below HB_QUALITY_HIGH), from the cone exponent in bits,
 * (1 - cos(theta_i + theta_o')) log2(e) / v, and x, both in float:
 * M_p = 2^-t factor, t = cone - log2(norm) - exponent log2(e), by vf_exp2_neg (the plan scales
 * 1/v and the norm by log2(e) in advance, so this costs no multiply; |exponent| <= 3.75 keeps the
 * rounding of log2(e) itself below 1e-7 in t). The exponent carries about two ulps of relative
 * error, so M_p's relative error grows as 1e-7 (1 + that exponent): within 1e-6 on the lobe and
 * 2e-5 at M_p = 1e-30 of the peak (docs/deon.md). log2_norm: the lobe's log2(norm) per lane. */
HB_INLINE vf longitudinal_deon_single_norm(vf log2_norm, vf cone_bits, vf x, hb_i0 i0)
{
    vf exponent, factor;
    i0_scaled(x, i0, &exponent, &factor);
    vf t = vf_fnma(exponent, vf_set1(HB_LOG2E_F), vf_sub(cone_bits, log2_norm));
    vm significant = vf_le(t, vf_set1((float)(-HB_MP_EXPONENT_FLOOR * 1.4426950408889634)));
    return vf_keep(significant, vf_mul(vf_exp2_neg(t), factor));
}

HB_INLINE vf longitudinal_deon_single(const hb_longitudinal *lobe, vf cone_bits, vf x, hb_i0 i0)
{
    return longitudinal_deon_single_norm(vf_set1(lobe->log2_norm_f), cone_bits, x, i0);
}

/* What the M_p of one sample's groups share: its two inclinations and cos(theta_i), which the
 * float path forms once per sample rather than once per group. */
typedef struct mp_inclinations {
    vf theta_i, theta_o, cos_theta_i;
} mp_inclinations;

HB_INLINE mp_inclinations mp_inclinations_of(vf theta_i, vf theta_o)
{
    mp_inclinations in = { theta_i, theta_o, cos_near_pole(theta_i, vf_set1(HB_PIO2_LO)) };
    return in;
}

/* Where the float path reads its constants of M_p: one lobe's (hb_longitudinal) broadcast to every lane,
 * or a lobe per lane (longitudinal_constants.h, hb_lobe_lanes, from lane `first` on). */
typedef struct longitudinal_consts {
    const float *inv_v, *inv_v_log2e, *log2_norm, *shift_hi[3], *shift_lo[3];
    int per_lane;
} longitudinal_consts;

HB_INLINE vf longitudinal_const(const longitudinal_consts *k, const float *value)
{
    return k->per_lane ? vf_loadu(value) : vf_set1(*value);
}

HB_INLINE longitudinal_consts longitudinal_consts_of(const hb_longitudinal *l)
{
    longitudinal_consts k = { &l->inv_v_f, &l->inv_v_log2e_f, &l->log2_norm_f,
                              { &l->shift_hi[0], &l->shift_hi[1], &l->shift_hi[2] },
                              { &l->shift_lo[0], &l->shift_lo[1], &l->shift_lo[2] }, 0 };
    return k;
}

HB_INLINE longitudinal_consts longitudinal_consts_lanes(const hb_lobe_lanes *l, int first)
{
    longitudinal_consts k = { l->inv_v_f + first, l->inv_v_log2e_f + first, l->log2_norm_f + first,
                              { l->shift_hi[0] + first, l->shift_hi[1] + first, l->shift_hi[2] + first },
                              { l->shift_lo[0] + first, l->shift_lo[1] + first, l->shift_lo[2] + first }, 1 };
    return k;
}

/* The float path's first stage from angles: the cone exponent (1 - cos(theta_i + theta_o'')) log2(e) / v and
 * x = cos(theta_i) cos(theta_o'') / v of M_p(v, theta_i, theta_o - shift). theta_o'' = theta_o - shift, reflected
 * across a pole when it passes one, is s theta_o - c with s = +-1 and c = c_hi + c_lo per case;
 * a = (theta_i + theta_o'')/2 and theta_o'' itself come from exact TwoSums, so their errors
 * stay relative near the cone (a -> 0) and pi/2 - |theta_o''| near a pole. Then
 *     1 - cos(theta_i + theta_o'') = 2 sin^2 a,  x = cos(theta_i) cos(theta_o'') / v. */
HB_INLINE void longitudinal_cone_consts(const longitudinal_consts *k, const mp_inclinations *in, vf *cone_bits,
                                        vf *x)
{
    vf theta_i = in->theta_i, theta_o = in->theta_o;
    vf t = vf_sub(theta_o, longitudinal_const(k, k->shift_hi[0]));
    vm over = vf_gt(t, vf_set1(HB_PIO2_F)), under = vf_lt(t, vf_set1(-HB_PIO2_F));
    vf signed_o = vf_select(vm_or(over, under), vf_neg(theta_o), theta_o);
    vf c_hi = vf_select(over, longitudinal_const(k, k->shift_hi[1]),
                        vf_select(under, longitudinal_const(k, k->shift_hi[2]), longitudinal_const(k, k->shift_hi[0])));
    vf c_lo = vf_select(over, longitudinal_const(k, k->shift_lo[1]),
                        vf_select(under, longitudinal_const(k, k->shift_lo[2]), longitudinal_const(k, k->shift_lo[0])));
    vf sum = vf_add(theta_i, signed_o);
    vf sum_error = vf_two_sum_error(theta_i, signed_o, sum);
    vf sin_a = vf_sin_halfpi(vf_mul(vf_add(vf_sub(sum, c_hi), vf_sub(sum_error, c_lo)), vf_set1(0.5f)));
    vf theta_o_hi = vf_sub(signed_o, c_hi);
    vf theta_o_lo = vf_sub(vf_two_sum_error(signed_o, vf_neg(c_hi), theta_o_hi), c_lo);
    vf cos_product = vf_mul(in->cos_theta_i, cos_near_pole(theta_o_hi, pole_distance_low(theta_o_hi, theta_o_lo)));
    *cone_bits = vf_mul(vf_mul(vf_add(sin_a, sin_a), sin_a), longitudinal_const(k, k->inv_v_log2e));
    *x = vf_mul(cos_product, longitudinal_const(k, k->inv_v));
}

HB_INLINE void longitudinal_cone_angles(const hb_longitudinal *lobe, const mp_inclinations *in, vf *cone_bits,
                                        vf *x)
{
    longitudinal_consts k = longitudinal_consts_of(lobe);
    longitudinal_cone_consts(&k, in, cone_bits, x);
}

HB_INLINE vf longitudinal_deon_angles_single(const hb_longitudinal *lobe, const mp_inclinations *in, hb_i0 i0)
{
    vf cone_bits, x;
    longitudinal_cone_angles(lobe, in, &cone_bits, &x);
    return longitudinal_deon_single(lobe, cone_bits, x, i0);
}

/* M_p of one sample (its angles in every lane) for the lobes in lanes first .. first + HB_W - 1 of
 * hb_lobe_lanes: one pass of the float path for up to HB_W lobes, bit for bit each lobe's own. */
HB_INLINE vf longitudinal_lobe_lanes(const hb_lobe_lanes *lanes, int first, const mp_inclinations *in,
                                     hb_i0 i0)
{
    longitudinal_consts k = longitudinal_consts_lanes(lanes, first);
    vf cone_bits, x;
    longitudinal_cone_consts(&k, in, &cone_bits, &x);
    return longitudinal_deon_single_norm(longitudinal_const(&k, k.log2_norm), cone_bits, x, i0);
}

/* theta - shift in double, reflected across a pole into [-pi/2, pi/2]: pi - t above
 * pi/2, -pi - t below -pi/2. */
HB_INLINE vdw inclination_reflected(vf theta, double shift)
{
    vdw t = vdw_sub(vdw_from_vf(theta), vdw_set1(shift));
    vdw over = vdw_max(vdw_sub(t, vdw_set1(HB_PIO2_D)), vdw_set1(0.0));
    vdw under = vdw_min(vdw_add(t, vdw_set1(HB_PIO2_D)), vdw_set1(0.0));
    return vdw_fma(vdw_add(over, under), vdw_set1(-2.0), t);
}

/* M_p(v, theta_i, theta_o - shift) from angles, all in double up to x, with
 * a = (theta_i + theta_o')/2 and b = (theta_i - theta_o')/2:
 *     1 - cos(theta_i + theta_o') = 2 sin^2 a,  cos(theta_i) cos(theta_o') = 1 - sin^2 a - sin^2 b.
 * theta_i and theta_o take the same path, so without a shift M_p(a, b) == M_p(b, a) bit for bit. */
HB_INLINE vf longitudinal_deon_inclinations(const hb_longitudinal *lobe, const mp_inclinations *in, hb_i0 i0)
{
    if (lobe->single)
        return longitudinal_deon_angles_single(lobe, in, i0);
    vdw ti = inclination_reflected(in->theta_i, 0.0);
    vdw to = inclination_reflected(in->theta_o, lobe->shift);
    vdw sin_a = vdw_sin_taylor(vdw_mul(vdw_add(ti, to), vdw_set1(0.5)));
    vdw sin_b = vdw_sin_taylor(vdw_mul(vdw_sub(ti, to), vdw_set1(0.5)));
    vdw sin2_a = vdw_mul(sin_a, sin_a), sin2_b = vdw_mul(sin_b, sin_b);
    vdw one_minus_cos_sum = vdw_add(sin2_a, sin2_a);
    vdw cos_product = vdw_sub(vdw_sub(vdw_set1(1.0), sin2_a), sin2_b);
    vf x = vdw_to_vf(vdw_mul(cos_product, vdw_set1(lobe->inv_v)));
    return longitudinal_deon(lobe, one_minus_cos_sum, x, i0);
}

/* M_p of one lobe from angles. */
HB_INLINE vf longitudinal_deon_angles(const hb_longitudinal *lobe, vf theta_i, vf theta_o, hb_i0 i0)
{
    mp_inclinations in = mp_inclinations_of(theta_i, theta_o);
    return longitudinal_deon_inclinations(lobe, &in, i0);
}

/* sin and cos of the inclination of w = (x, y, z), in double: y / |w| and |(x, z)| / |w|. */
HB_INLINE void inclination_dw(vf x, vf y, vf z, vdw *sin_theta, vdw *cos_theta)
{
    vdw xd = vdw_from_vf(x), yd = vdw_from_vf(y), zd = vdw_from_vf(z);
    vdw planar2 = vdw_fma(xd, xd, vdw_mul(zd, zd));
    vdw inv_norm = vdw_div(vdw_set1(1.0), vdw_sqrt(vdw_fma(yd, yd, planar2)));
    *sin_theta = vdw_mul(yd, inv_norm);
    *cos_theta = vdw_mul(vdw_sqrt(planar2), inv_norm);
}

/* sin and cos of the inclination of w = (x, y, z), in float. */
HB_INLINE void inclination(vf x, vf y, vf z, vf *sin_theta, vf *cos_theta)
{
    vf planar2 = vf_fma(x, x, vf_mul(z, z));
    vf inv_norm = vf_div(vf_set1(1.0f), vf_sqrt(vf_fma(y, y, planar2)));
    *sin_theta = vf_mul(y, inv_norm);
    *cos_theta = vf_mul(vf_sqrt(planar2), inv_norm);
}

/* The float path's first stage from unit vectors: 1 - cos(theta_i + theta_o') = ((cos theta_i - cos theta_o')^2 +
 * (sin theta_i + sin theta_o')^2) / 2, a sum of squares that cannot cancel; its terms carry the
 * float rounding of the sines and cosines (about 1e-7 in angle), so the exponent's error near
 * the cone grows as sqrt(exponent / v) 1e-7 (docs/deon.md). The exponent is in bits, as
 * longitudinal_deon_single takes it. */
HB_INLINE void longitudinal_cone_vectors(const hb_longitudinal *lobe, const vf wi[3], const vf wo[3], vf *cone_bits,
                                         vf *x)
{
    vf si, ci, so, co;
    inclination(wi[0], wi[1], wi[2], &si, &ci);
    inclination(wo[0], wo[1], wo[2], &so, &co);
    vf cs = vf_set1(lobe->cos_shift_f), ss = vf_set1(lobe->sin_shift_f);
    vf co_shifted = vf_abs(vf_fma(co, cs, vf_mul(so, ss))); /* cos(theta_o - shift), reflected to >= 0 */
    vf so_shifted = vf_fnma(co, ss, vf_mul(so, cs));
    vf dc = vf_sub(ci, co_shifted), ds = vf_add(si, so_shifted);
    *cone_bits = vf_mul(vf_fma(dc, dc, vf_mul(ds, ds)), vf_set1(0.5f * lobe->inv_v_log2e_f));
    *x = vf_mul(vf_mul(ci, co_shifted), vf_set1(lobe->inv_v_f));
}

HB_INLINE vf longitudinal_deon_vectors_single(const hb_longitudinal *lobe, const vf wi[3], const vf wo[3], hb_i0 i0)
{
    vf cone_bits, x;
    longitudinal_cone_vectors(lobe, wi, wo, &cone_bits, &x);
    return longitudinal_deon_single(lobe, cone_bits, x, i0);
}

/* M_p(v, theta_i, theta_o - shift) from unit vectors, all in double up to x. The
 * reflection across a pole is |cos(theta_o - shift)| with sin(theta_o - shift) kept. */
HB_INLINE vf longitudinal_deon_vectors(const hb_longitudinal *lobe, const vf wi[3], const vf wo[3], hb_i0 i0)
{
    if (lobe->single)
        return longitudinal_deon_vectors_single(lobe, wi, wo, i0);
    vdw si, ci, so, co;
    inclination_dw(wi[0], wi[1], wi[2], &si, &ci);
    inclination_dw(wo[0], wo[1], wo[2], &so, &co);
    vdw cs = vdw_set1(lobe->cos_shift), ss = vdw_set1(lobe->sin_shift);
    vdw co_shifted = vdw_fma(co, cs, vdw_mul(so, ss)); /* cos(theta_o - shift), reflected to >= 0 */
    co_shifted = vdw_max(co_shifted, vdw_sub(vdw_set1(0.0), co_shifted));
    vdw so_shifted = vdw_sub(vdw_mul(so, cs), vdw_mul(co, ss));
    vdw cos_sum = vdw_sub(vdw_mul(ci, co_shifted), vdw_mul(si, so_shifted));
    vdw one_minus_cos_sum = vdw_max(vdw_sub(vdw_set1(1.0), cos_sum), vdw_set1(0.0));
    vf x = vdw_to_vf(vdw_mul(vdw_mul(ci, co_shifted), vdw_set1(lobe->inv_v)));
    return longitudinal_deon(lobe, one_minus_cos_sum, x, i0);
}

/* theta_i drawn from M_p(v, theta_i, theta_o - shift) cos(theta_i) (dFH11 eq. 7 is the projection
 * of a von Mises-Fisher lobe about the mirror direction; d'Eon et al. 2013): the lobe's polar angle
 * psi by its inverse CDF, 1 - cos psi = -v log(u1 + (1 - u1) e^(-2/v)) (e2 = e^(-2/v), stable as
 * v -> 0), its azimuth 2 pi u2. theta_i comes from the direction's axial part and its across-axis
 * length together, which keeps its digits at the poles (asin of the axial part alone is off by up
 * to sqrt(2 eps) = 3.5e-4 rad there). */
HB_INLINE vf longitudinal_sample(vf v, vf e2, vf cos_shift, vf sin_shift, vf theta_o, vf u1, vf u2)
{
    vf so, co;
    vf_sincos(theta_o, &so, &co);
    vf sin_o = vf_fnma(co, sin_shift, vf_mul(so, cos_shift));      /* sin(theta_o - shift) */
    vf cos_o = vf_abs(vf_fma(co, cos_shift, vf_mul(so, sin_shift))); /* |cos(theta_o - shift)| */
    vf inner = vf_fma(vf_sub(vf_set1(1.0f), u1), e2, u1);
    vf one_minus_cos_psi = vf_min(vf_mul(vf_neg(v), vf_log(inner)), vf_set1(2.0f));
    vf sin_psi = vf_sqrt(vf_max(vf_mul(one_minus_cos_psi, vf_sub(vf_set1(2.0f), one_minus_cos_psi)), vf_set1(0.0f)));
    vf cos_psi = vf_sub(vf_set1(1.0f), one_minus_cos_psi), sin_azimuth, cos_azimuth;
    vf_sincos(vf_mul(u2, vf_set1(HB_TWO_PI_F)), &sin_azimuth, &cos_azimuth);
    vf tilt = vf_mul(sin_psi, cos_azimuth);
    vf axial = vf_fnma(cos_psi, sin_o, vf_mul(tilt, cos_o)); /* the mirror direction is at -(theta_o - shift) */
    vf across = vf_fma(cos_psi, cos_o, vf_mul(tilt, sin_o));
    vf aside = vf_mul(sin_psi, sin_azimuth);
    vf cos_i = vf_sqrt(vf_fma(across, across, vf_mul(aside, aside))); /* a unit vector's parts to 1e-7 */
    return vf_asin_with_cos(axial, cos_i);
}

#endif

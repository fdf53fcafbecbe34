/* dFH11's M_p for the plan's lobe groups at one sample (eq. 7 per group leader; lobes of equal
 * roughness and shift share it), over the shared M_p of src/models/common/longitudinal.h. */
#ifndef HB_DEON_LONGITUDINAL_GROUPS_H
#define HB_DEON_LONGITUDINAL_GROUPS_H

#include "constants.h"
#include "models/common/longitudinal.h"

/* M[p] for every group leader p of plan d at one sample. Each M_p is a chain of some forty dependent
 * operations and the kernels are bound by its latency, not by throughput: the float path's first
 * stage runs for every group before any second stage (I0 and the exponential), so the groups'
 * chains lie side by side in the instruction stream and overlap. cone_of_lobe(lobe, &cone_bits, &x)
 * is that first stage at the sample, longitudinal_of_lobe(lobe) the whole of M_p (the double path). */
#define HB_DEON_GROUPS_M(d, M, i0, cone_of_lobe, longitudinal_of_lobe)                                 \
    do {                                                                                              \
        vf cone_[HB_MAX_LOBES + 1], x_[HB_MAX_LOBES + 1];                                             \
        for (int g_ = 0; g_ < (d)->groups; g_++) {                                                    \
            const hb_longitudinal *lobe_ = &(d)->longitudinal[(d)->group_leader[g_]];                 \
            if (lobe_->single)                                                                        \
                cone_of_lobe(lobe_, &cone_[g_], &x_[g_]);                                             \
        }                                                                                             \
        for (int g_ = 0; g_ < (d)->groups; g_++) {                                                    \
            const hb_longitudinal *lobe_ = &(d)->longitudinal[(d)->group_leader[g_]];                 \
            (M)[(d)->group_leader[g_]] = lobe_->single ? longitudinal_deon_single(lobe_, cone_[g_], x_[g_], (i0)) \
                                                       : longitudinal_of_lobe(lobe_);                 \
        }                                                                                             \
    } while (0)

/* HB_DEON_GROUPS_M from angles; M of the other lobes is left as it is. */
HB_INLINE void longitudinal_deon_groups_angles(const hb_deon *d, vf theta_i, vf theta_o, hb_i0 i0,
                                               vf M[HB_MAX_LOBES + 1])
{
    mp_inclinations in = mp_inclinations_of(theta_i, theta_o);
#define HB_CONE_ANGLES(lobe, cone_bits, x) longitudinal_cone_angles((lobe), &in, (cone_bits), (x))
#define HB_M_ANGLES(lobe) longitudinal_deon_inclinations((lobe), &in, i0)
    HB_DEON_GROUPS_M(d, M, i0, HB_CONE_ANGLES, HB_M_ANGLES);
#undef HB_M_ANGLES
#undef HB_CONE_ANGLES
}

/* M[p] for every lobe of the standard shape at one sample whose angles fill every lane, the lobes across
 * the lanes (longitudinal_lobe_lanes) instead of a pass per group; the float path only (plans below
 * HB_QUALITY_HIGH). Each lobe's M equals its group leader's bit for bit (the same constants). */
HB_INLINE void longitudinal_deon_lobes_one(const hb_deon *d, vf theta_i, vf theta_o, hb_i0 i0,
                                           vf M[HB_MAX_LOBES + 1])
{
    mp_inclinations in = mp_inclinations_of(theta_i, theta_o);
    float m[HB_LOBE_LANES];
    for (int first = 0; first < HB_LOBE_LANES; first += HB_W)
        vf_store_first(m + first, longitudinal_lobe_lanes(&d->lobe_lanes, first, &in, i0),
                       HB_LOBE_LANES - first < HB_W ? HB_LOBE_LANES - first : HB_W);
    HB_UNROLL
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        M[p] = vf_set1(p <= HB_STANDARD_PMAX ? m[p] : p == HB_LOBE_RESIDUAL ? m[HB_LOBE_LANES - 1] : 0.0f);
}

/* HB_DEON_GROUPS_M from unit vectors. */
HB_INLINE void longitudinal_deon_groups_vectors(const hb_deon *d, const vf wi[3], const vf wo[3], hb_i0 i0,
                                                vf M[HB_MAX_LOBES + 1])
{
#define HB_CONE_VECTORS(lobe, cone_bits, x) longitudinal_cone_vectors((lobe), wi, wo, (cone_bits), (x))
#define HB_M_VECTORS(lobe) longitudinal_deon_vectors((lobe), wi, wo, i0)
    HB_DEON_GROUPS_M(d, M, i0, HB_CONE_VECTORS, HB_M_VECTORS);
#undef HB_M_VECTORS
#undef HB_CONE_VECTORS
}

#endif

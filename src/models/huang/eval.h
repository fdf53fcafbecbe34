/* HHH22 f = (S_R + S_TT + S_TRT) cos(theta_i) (eq. 3) for the plan's lobes, from angles or vectors. */
#ifndef HB_HUANG_EVAL_H
#define HB_HUANG_EVAL_H

#include "table.h"

/* index: each lane's sample index, which keys the Monte-Carlo numbers of TT and TRT (unused when
 * the plan has their table); angles: theta_i, phi_i, theta_o, phi_o where the caller has them, else NULL. */
HB_INLINE void huang_eval(const hb_huang *h, const huang_directions *d, const vf *angles, vi index, vf out[3])
{
    vf r = vf_set1(0.0f);
    if (h->lobes >> HB_LOBE_R & 1u)
        r = huang_r(h, d);
    for (int c = 0; c < 3; c++)
        out[c] = r;
    if (!(h->lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT)))
        return;
    vf internal[3];
    if (h->table.values) {
        huang_table_angles a = angles ? huang_table_angles_from(angles[0], angles[1], angles[2], angles[3])
                                      : huang_table_angles_of(h, d);
        huang_table_lookup(h, &a, d->cos_ti, d->sin_ti, d->cos_to, d->sin_to, d->sin2_phi_o, internal);
    } else {
        huang_internal(h, d, index, internal);
    }
    for (int c = 0; c < 3; c++)
        out[c] = vf_add(out[c], internal[c]);
}

HB_INLINE void huang_angles(const hb_huang *h, vf theta_i, vf phi_i, vf theta_o, vf phi_o, vi index, vf out[3])
{
    if (h->table.values && !(h->lobes >> HB_LOBE_R & 1u)) { /* the table alone reads no directions */
        huang_table_angles a = huang_table_angles_from(theta_i, phi_i, theta_o, phi_o);
        vf sin_po = h->elliptical ? vf_sin(wrap_angle(phi_o)) : vf_set1(0.0f);
        vf cos_ti, sin_ti, cos_to, sin_to;
        vf_sincos(theta_i, &sin_ti, &cos_ti);
        vf_sincos(theta_o, &sin_to, &cos_to);
        cos_ti = vf_max(cos_ti, vf_set1(0.0f));
        cos_to = vf_max(cos_to, vf_set1(0.0f));
        huang_table_lookup(h, &a, cos_ti, sin_ti, cos_to, sin_to, vf_mul(sin_po, sin_po), out);
        return;
    }
    huang_directions d = huang_directions_of_angles(h, theta_i, phi_i, theta_o, phi_o);
    vf angles[4] = { theta_i, phi_i, theta_o, phi_o };
    huang_eval(h, &d, angles, index, out);
}

HB_INLINE void huang_vectors(const hb_huang *h, const vf wi[3], const vf wo[3], vi index, vf out[3])
{
    huang_directions d = huang_directions_of_vectors(wi, wo);
    huang_eval(h, &d, NULL, index, out);
}

#endif

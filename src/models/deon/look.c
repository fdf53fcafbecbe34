/* dFH11's parameters are the shared look itself: v_R = beta_m^2 (eq. 7's M_p is near a Gaussian in
 * theta_o of standard deviation beta_m), the detector's Gaussian beta_n (eq. 9), alpha_R = -2 alpha. */
#include "deon.h"

void hb_deon_look(const hb_material *m, hb_look *look) { *look = (hb_look){ m->beta_m, m->beta_n, m->alpha }; }

hb_status hb_deon_set_look(const hb_look *look, hb_material *m, hb_error *error)
{
    (void)error;
    m->beta_m = look->longitudinal, m->beta_n = look->azimuthal, m->alpha = look->tilt;
    return HB_OK;
}

/* MJC03's M_R is a Gaussian in theta_h = (theta_i + theta_o) / 2 of width beta_R = beta_m (Table 1),
 * so in theta_o its standard deviation is 2 beta_m; its mean -alpha in theta_h puts the peak where
 * dFH11's alpha does. beta_n is not read by MJC03 and carries the look's azimuthal spread through. */
#include "marschner.h"

void hb_marschner_look(const hb_material *m, hb_look *look)
{
    *look = (hb_look){ 2.0 * m->beta_m, m->beta_n, m->alpha };
}

hb_status hb_marschner_set_look(const hb_look *look, hb_material *m, hb_error *error)
{
    (void)error;
    m->beta_m = 0.5 * look->longitudinal, m->beta_n = look->azimuthal, m->alpha = look->tilt;
    return HB_OK;
}

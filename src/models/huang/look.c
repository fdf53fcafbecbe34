/* HHH22's R lobe takes its width from the microfacet roughness a, not from beta_m. For small a a
 * reflected direction turns by twice the microfacet's slope, whose marginal in one dimension is
 * (1 + x^2 / a^2)^(-3/2) for GGX (half maximum at x = a sqrt(2^(2/3) - 1)) and a Gaussian of
 * deviation a / sqrt(2) for Beckmann: the look's deviation is the Gaussian with the same half-maximum
 * width, 1.3019 a (GGX) or sqrt(2) a (Beckmann). docs/conventions.md gives the measured widths. The
 * mesonormal tilt is tau = -alpha, which puts R where dFH11's alpha does. HHH22 reads no beta_m or
 * beta_n: they carry the look through unchanged. */
#include <math.h>

#include "huang.h"

static double width_per_roughness(hb_ndf ndf)
{
    return ndf == HB_NDF_GGX ? 2.0 * sqrt(cbrt(4.0) - 1.0) / sqrt(2.0 * M_LN2) : M_SQRT2;
}

void hb_huang_look(const hb_material *m, hb_look *look)
{
    *look = (hb_look){ width_per_roughness(m->ndf) * m->roughness, m->beta_n, m->alpha };
}

hb_status hb_huang_set_look(const hb_look *look, hb_material *m, hb_error *error)
{
    (void)error;
    m->roughness = look->longitudinal / width_per_roughness(m->ndf);
    m->beta_n = look->azimuthal, m->alpha = look->tilt;
    return HB_OK;
}

/* A dielectric cylinder's optics in double: Fresnel reflectance and refraction into the fibre,
 * for every model's reference. */
#include <math.h>

#include "reference.h"

double hb_ref_fresnel(double eta, double cos_i)
{
    cos_i = fmin(fabs(cos_i), 1.0);
    double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0)
        return 1.0;
    double cos_t = sqrt(1.0 - sin2_t);
    double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

double hb_ref_refraction(double eta, double cos_theta, double sin_gamma_i, double cos_gamma_i, double *sin_gamma_t,
                         double *cos_gamma_t)
{
    double eta2_minus_1 = (eta - 1.0) * (eta + 1.0);
    double eta_cos_t = sqrt(eta2_minus_1 + cos_theta * cos_theta); /* eta' cos theta = sqrt(eta^2 - sin^2 theta) */
    double c = cos_theta * cos_gamma_i;
    *sin_gamma_t = sin_gamma_i * cos_theta / eta_cos_t;
    *cos_gamma_t = sqrt(eta2_minus_1 + c * c) / eta_cos_t;
    return atan2(*sin_gamma_t, *cos_gamma_t);
}

/* MJC03 references in double precision. */
#include <math.h>

#include "reference.h"

double hb_ref_marschner_longitudinal(double beta, double mean, double theta_i, double theta_o)
{
    double theta_h = 0.5 * (theta_i + theta_o), cos_d = cos(0.5 * (theta_o - theta_i));
    double g = exp(-(theta_h - mean) * (theta_h - mean) / (2.0 * beta * beta)) / (beta * sqrt(2.0 * M_PI));
    return g * fmax(cos(theta_i), 0.0) / fmax(cos_d * cos_d, 1e-8);
}

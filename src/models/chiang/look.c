/* CBTB16's roughness scales and tilt in the shared look: the R lobe's standard deviation is
 * sqrt(v_R(beta_m)) (its M_p is dFH11's eq. 7 at that variance), the logistic N_p of scale
 * s(beta_n) has the standard deviation pi s / sqrt(3), and pbrt-v4's tilt moves R by +2 alpha where
 * dFH11's moves it by -2 alpha. The fits are increasing on [0, 1]: bisection inverts them. */
#include <math.h>

#include "chiang.h"

static double logistic_deviation(double beta_n) { return M_PI / sqrt(3.0) * hb_chiang_logistic_scale(beta_n); }

static double r_deviation(double beta_m) { return sqrt(hb_chiang_variance_r(beta_m)); }

void hb_chiang_look(const hb_material *m, hb_look *look)
{
    *look = (hb_look){ r_deviation(m->beta_m), logistic_deviation(m->beta_n), -m->alpha };
}

/* The scale in [lo, 1] where the increasing fit reaches target (64 halvings: to the double's resolution). */
static double invert(double (*fit)(double), double target, double lo)
{
    double hi = 1.0;
    for (int k = 0; k < 64; k++) {
        double mid = 0.5 * (lo + hi);
        if (fit(mid) < target)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

hb_status hb_chiang_set_look(const hb_look *look, hb_material *m, hb_error *error)
{
    double lo_m = r_deviation(HB_CHIANG_BETA_M_MIN), hi_m = r_deviation(1.0);
    double lo_n = logistic_deviation(0.02), hi_n = logistic_deviation(1.0);
    if (!(look->longitudinal >= lo_m && look->longitudinal <= hi_m))
        return hb_plan_fail(error, HB_ERR_PARAM, "a longitudinal deviation of %g rad is outside CBTB16's [%.6g, %.6g] "
                            "(beta_m in [%g, 1])", look->longitudinal, lo_m, hi_m, HB_CHIANG_BETA_M_MIN);
    if (!(look->azimuthal >= lo_n && look->azimuthal <= hi_n))
        return hb_plan_fail(error, HB_ERR_PARAM, "an azimuthal deviation of %g rad is outside CBTB16's [%.6g, %.6g] "
                            "(beta_n in [0.02, 1])", look->azimuthal, lo_n, hi_n);
    m->beta_m = invert(r_deviation, look->longitudinal, HB_CHIANG_BETA_M_MIN);
    m->beta_n = invert(logistic_deviation, look->azimuthal, 0.02);
    m->alpha = -look->tilt;
    return HB_OK;
}

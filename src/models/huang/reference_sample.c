/* HHH22 R lobe sampling in double (docs/sampling.md): the kernels' procedure with libm
 * and vectors, the offset drawn on the ellipse itself, and the Beckmann visible slope found by
 * bisection on its CDF (the kernels use Newton steps on its square root). */
#include <math.h>

#include "reference.h"
#include "models/interface/plan.h"
#include "state.h"

/* x with (1 + erf(x)) / 2 = u, by bisection. */
static double normal_half_quantile(double u)
{
    double lo = -30.0, hi = 30.0;
    while (hi - lo > 1e-13) { /* 60 halvings */
        double mid = 0.5 * (lo + hi);
        if (0.5 * erfc(-mid) > u)
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

/* Heitz and d'Eon 2014: the visible slope along o's azimuth (stretched inclination t) has CDF
 * (cos t erfc(-x) + sin t e^(-x^2) / sqrt(pi)) / (cos t erfc(-cot t) + sin t e^(-cot^2 t) / sqrt(pi)). */
static double beckmann_slope(double cos_t, double sin_t, double u)
{
    double top = sin_t > 0.0 ? cos_t / sin_t : 30.0, lo = -30.0, hi = fmin(top, 30.0);
    double total = cos_t * erfc(-hi) + sin_t * exp(-hi * hi) / sqrt(M_PI);
    while (hi - lo > 1e-13) {
        double mid = 0.5 * (lo + hi);
        if ((cos_t * erfc(-mid) + sin_t * exp(-mid * mid) / sqrt(M_PI)) / total > u)
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

void hb_ref_huang_visible_normal(const hb_plan *plan, const double o[3], double u1, double u2, double m[3])
{
    double r = plan->material.roughness;
    double s[3] = { r * o[0], r * o[1], o[2] }, norm = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]), h[3];
    for (int k = 0; k < 3; k++)
        s[k] /= norm;
    if (plan->material.ndf == HB_NDF_BECKMANN) {
        double planar = hypot(s[0], s[1]), ca = planar > 0.0 ? s[0] / planar : 1.0, sa = planar > 0.0 ? s[1] / planar : 0.0;
        double x = beckmann_slope(s[2], planar, u1), y = normal_half_quantile(u2);
        h[0] = -r * (ca * x - sa * y);
        h[1] = -r * (sa * x + ca * y);
        h[2] = 1.0;
    } else { /* Dupuy and Benyoub 2023: o' plus a uniform point of the cap z >= -o'_z */
        double z = (1.0 - u2) * (1.0 + s[2]) - s[2], sin_t = sqrt(fmax(0.0, 1.0 - z * z)), p = 2.0 * M_PI * u1;
        h[0] = r * (sin_t * cos(p) + s[0]);
        h[1] = r * (sin_t * sin(p) + s[1]);
        h[2] = z + s[2];
    }
    norm = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    for (int k = 0; k < 3; k++)
        m[k] = h[k] / norm;
}

void hb_ref_huang_sample(const hb_plan *plan, double theta_o, double phi_o, const double u[3], double *theta_i,
                         double *phi_i)
{
    double half, lo, hi, e = plan->material.eccentricity, b = sqrt(1.0 - e * e), tau = hb_huang_of(plan)->tilt;
    if (!hb_ref_huang_o_window(plan, theta_o, phi_o, &half, &lo, &hi))
        half = lo = hi = 0.0;
    /* the point at projected offset lo + u0 (hi - lo) across the view: (sin g, b cos g) . (cos phi_o,
     * -sin phi_o) = a sin(g - chi) */
    double chi = atan2(b * sin(phi_o), cos(phi_o)), a = hypot(cos(phi_o), b * sin(phi_o));
    double g = chi + asin(fmax(-1.0, fmin(1.0, (lo + u[0] * (hi - lo)) / a)));
    double psi = atan2(b * sin(g), cos(g)) - phi_o;
    /* w_o, the mesonormal (eq. 39) and its tangents, in the frame phi_o = 0 */
    double wo[3] = { 0.0, sin(theta_o), fmax(cos(theta_o), 0.0) };
    double wm[3] = { cos(tau) * sin(psi), sin(tau), cos(tau) * cos(psi) }, t1[3] = { cos(psi), 0.0, -sin(psi) };
    double t2[3] = { -sin(tau) * sin(psi), cos(tau), -sin(tau) * cos(psi) };
    double o[3] = { 0.0, 0.0, 0.0 }, m[3], wi[3];
    for (int k = 0; k < 3; k++) {
        o[0] += wo[k] * t1[k];
        o[1] += wo[k] * t2[k];
        o[2] += wo[k] * wm[k];
    }
    o[2] = fmax(o[2], 1e-300);
    hb_ref_huang_visible_normal(plan, o, u[1], u[2], m);
    double dot = o[0] * m[0] + o[1] * m[1] + o[2] * m[2];
    for (int k = 0; k < 3; k++)
        wi[k] = (2.0 * dot * m[0] - o[0]) * t1[k] + (2.0 * dot * m[1] - o[1]) * t2[k] + (2.0 * dot * m[2] - o[2]) * wm[k];
    *theta_i = atan2(wi[1], hypot(wi[0], wi[2]));
    *phi_i = remainder(phi_o + atan2(wi[0], wi[2]), 2.0 * M_PI);
}

const hb_reference_ops hb_ref_huang_ops = {
    .eval = hb_ref_huang, .sample = hb_ref_huang_sample, .pdf = hb_ref_huang_pdf, .orders = hb_ref_huang_orders,
};

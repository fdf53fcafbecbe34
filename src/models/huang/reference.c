/* HHH22 references in double precision. The R lobe integral is taken by adaptive
 * Gauss-Legendre directly in the variables of the paper: phi_m for circular fibres (eq. 12)
 * and the ellipse parameter gamma for elliptical ones (eq. 28), with vectors and dot
 * products rather than the kernels' half-angle algebra, libm's erfc for Beckmann's Smith
 * Lambda, and App. A's eq. 43 as printed for the closed form. */
#include <math.h>

#include "reference.h"
#include "models/interface/plan.h"
#include "math/quadrature.h"
#include "state.h"

enum { RULE = 15, MAX_PIECES = 1000 };

typedef struct ref_r_setup {
    const hb_plan *plan;
    double wi[3], wo[3], wh[3];
    double tilt, b;  /* mesonormal inclination tau; minor semi-axis */
    int shadowing;
    int in_gamma;    /* integrate over the ellipse parameter gamma (eq. 28) */
    int pdf;         /* the sampling pdf's integrand (docs/sampling.md) instead of eval's */
    double phi_o;
    double gl_x[RULE], gl_w[RULE]; /* Gauss-Legendre on [-1, 1] */
} ref_r_setup;

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* cos(theta) >= 0 also for the float nearest pi/2 (which is slightly above it), as in the kernels. */
static void unit_direction(double theta, double phi, double w[3])
{
    w[0] = sin(phi) * fmax(cos(theta), 0.0);
    w[1] = sin(theta);
    w[2] = cos(phi) * fmax(cos(theta), 0.0);
}

/* D at cos_m = w_h . w_m with sin2_m = |w_h x w_m|^2 given separately (near the peak 1 - cos^2
 * would lose the digits the NDF's narrow peak needs). */
static double ndf(hb_ndf kind, double r, double cos_m, double sin2_m)
{
    if (cos_m <= 0.0)
        return 0.0;
    double c2 = cos_m * cos_m;
    if (kind == HB_NDF_BECKMANN)
        return exp(-sin2_m / (c2 * r * r)) / (M_PI * r * r * c2 * c2);
    double den = sin2_m + r * r * c2; /* eq. 41: 1 + (r^2 - 1) cos^2 */
    return r * r / (M_PI * den * den);
}

double hb_ref_huang_ndf(hb_ndf kind, double r, double cos_m) { return ndf(kind, r, cos_m, 1.0 - cos_m * cos_m); }

double hb_ref_huang_lambda(hb_ndf ndf, double r, double cos_w)
{
    if (cos_w >= 1.0)
        return 0.0;
    double tan_w = sqrt(1.0 - cos_w * cos_w) / cos_w;
    if (ndf == HB_NDF_BECKMANN) {
        double a = 1.0 / (r * tan_w);
        return 0.5 * (exp(-a * a) / (a * sqrt(M_PI)) - erfc(a));
    }
    return 0.5 * (sqrt(1.0 + r * r * tan_w * tan_w) - 1.0);
}

/* Eq. 10's 1 / (2 cos(theta_o)) as f carries it, bounded at the poles where options.pole_floor asks
 * (docs/huang.md, "At the poles"): the paper's form at the reference unless the caller asks. */
double hb_ref_huang_width(const hb_plan *plan, double theta_i, double theta_o)
{
    const hb_material *m = &plan->material;
    if (plan->options.pole_floor != HB_POLE_FLOOR_BOUNDED &&
        (plan->options.pole_floor == HB_POLE_FLOOR_PAPER || plan->options.quality == HB_QUALITY_REFERENCE))
        return fmin(1.0, fmax(cos(theta_i), 0.0) / 1e-8) / fmax(cos(theta_o), 1e-8);
    double scales = M_PI * fabs(sin(hb_huang_of(plan)->tilt)) / 2.0;
    double grazing_width = m->ndf == HB_NDF_BECKMANN ? m->roughness / (2.0 * sqrt(M_PI)) : m->roughness / 2.0;
    double rough = plan->options.shadowing == HB_SHADOWING_SMITH ? 0.0 : M_PI * grazing_width / 2.0;
    double floor = fmax(1e-8, fmax(scales, rough));
    return fmin(1.0, fmax(cos(theta_i), 0.0) / floor) / fmax(cos(theta_o), floor);
}

static double smith_g1(hb_ndf ndf, double r, double cos_w)
{
    return cos_w > 0.0 ? 1.0 / (1.0 + hb_ref_huang_lambda(ndf, r, cos_w)) : 0.0;
}

/* D G rho at the macronormal azimuth phi_m (or at ellipse parameter gamma): zero unless both
 * directions see the macronormal and the mesonormal (eq. 40). */
static double r_integrand(const ref_r_setup *s, double t)
{
    const hb_material *m = &s->plan->material;
    double phi_m = t, weight = 1.0;
    if (s->in_gamma) { /* normal (b sin g, cos g) of the point (sin g, b cos g); da = sqrt(1 - e^2 sin^2 g) dg */
        phi_m = atan2(s->b * sin(t), cos(t));
        weight = sqrt(1.0 - m->eccentricity * m->eccentricity * sin(t) * sin(t));
    }
    double macro[3] = { sin(phi_m), 0.0, cos(phi_m) };
    double meso[3] = { sin(phi_m) * cos(s->tilt), sin(s->tilt), cos(phi_m) * cos(s->tilt) }; /* eq. 39 */
    double mi = dot3(s->wi, meso), mo = dot3(s->wo, meso);
    double cross[3] = { s->wh[1] * meso[2] - s->wh[2] * meso[1], s->wh[2] * meso[0] - s->wh[0] * meso[2],
                        s->wh[0] * meso[1] - s->wh[1] * meso[0] };
    if (s->pdf) { /* density of phi_m cos(phi_m - phi_o) rho, times G1(w_o) D / (w_o . w_m) */
        if (dot3(s->wo, macro) < 0.0 || mo <= 0.0)
            return 0.0;
        return ndf(m->ndf, m->roughness, dot3(s->wh, meso), dot3(cross, cross)) * weight * cos(phi_m - s->phi_o) *
               smith_g1(m->ndf, m->roughness, mo) / mo;
    }
    if (dot3(s->wi, macro) < 0.0 || dot3(s->wo, macro) < 0.0 || mi < 0.0 || mo < 0.0)
        return 0.0;
    double value = ndf(m->ndf, m->roughness, dot3(s->wh, meso), dot3(cross, cross)) * weight;
    if (s->shadowing)
        value *= smith_g1(m->ndf, m->roughness, mi) * smith_g1(m->ndf, m->roughness, mo);
    return value;
}

static double gauss_legendre(const ref_r_setup *s, double a, double b)
{
    double mid = 0.5 * (a + b), half = 0.5 * (b - a), sum = 0.0;
    for (int k = 0; k < RULE; k++)
        sum += s->gl_w[k] * r_integrand(s, mid + half * s->gl_x[k]);
    return sum * half;
}

/* A piece of the integration range: its integral as the sum of the rule on both halves, and the
 * difference from the rule on the whole as its error estimate. */
typedef struct piece {
    double a, b, value, error;
} piece;

static piece estimate(const ref_r_setup *s, double a, double b, double whole)
{
    double mid = 0.5 * (a + b), left = gauss_legendre(s, a, mid), right = gauss_legendre(s, mid, b);
    double error = fabs(left + right - whole);
    piece p = { a, b, left + right, error <= 1e-14 * (fabs(left) + fabs(right)) ? 0.0 : error }; /* rounding */
    return p;
}

/* Globally adaptive: split the piece with the largest error until the total error is below
 * 1e-12 of the integral (or the rounding of the integrand), with a bounded number of pieces. */
static double adaptive(const ref_r_setup *s, const double *cuts, int ncuts)
{
    piece p[MAX_PIECES];
    int n = 0;
    for (int k = 0; k + 1 < ncuts; k++)
        p[n++] = estimate(s, cuts[k], cuts[k + 1], gauss_legendre(s, cuts[k], cuts[k + 1]));
    for (;;) {
        double total = 0.0, error = 0.0;
        int worst = 0;
        for (int k = 0; k < n; k++) {
            total += p[k].value;
            error += p[k].error;
            if (p[k].error > p[worst].error)
                worst = k;
        }
        if (error <= 1e-12 * fabs(total) || n == MAX_PIECES)
            return total;
        piece split = p[worst];
        double mid = 0.5 * (split.a + split.b);
        p[worst] = estimate(s, split.a, mid, gauss_legendre(s, split.a, mid));
        p[n++] = estimate(s, mid, split.b, gauss_legendre(s, mid, split.b));
    }
}

double hb_ref_huang_half_width(double theta, double tilt)
{
    double num = -sin(theta) * sin(tilt), den = fmax(cos(theta), 0.0) * cos(tilt);
    if (num > den)
        return -1.0;
    return num <= 0.0 ? M_PI_2 : acos(num / den);
}

/* The visible window [lo, hi] in phi_m around phi_i; returns 0 when it is empty. */
static int window(const ref_r_setup *s, double theta_i, double phi_i, double theta_o, double phi_o, double *lo,
                  double *hi)
{
    double half_i = hb_ref_huang_half_width(theta_i, s->tilt), half_o = hb_ref_huang_half_width(theta_o, s->tilt);
    double phi = remainder(phi_o - phi_i, 2.0 * M_PI);
    *lo = phi_i + fmax(-half_i, phi - half_o);
    *hi = phi_i + fmin(half_i, phi + half_o);
    return half_i >= 0.0 && half_o >= 0.0 && *lo < *hi;
}

static int setup(ref_r_setup *s, const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                 int shadowing)
{
    s->plan = plan;
    s->tilt = hb_huang_of(plan)->tilt;
    s->b = sqrt(1.0 - plan->material.eccentricity * plan->material.eccentricity);
    s->shadowing = shadowing;
    s->pdf = 0;
    s->phi_o = phi_o;
    s->in_gamma = plan->material.eccentricity > 0.0;
    hb_gauss_legendre(RULE, -1.0, 1.0, s->gl_x, s->gl_w);
    unit_direction(theta_i, phi_i, s->wi);
    unit_direction(theta_o, phi_o, s->wo);
    double norm = 0.0;
    for (int k = 0; k < 3; k++) {
        s->wh[k] = s->wi[k] + s->wo[k];
        norm += s->wh[k] * s->wh[k];
    }
    norm = sqrt(norm);
    if (!(norm > 0.0))
        return 0;
    for (int k = 0; k < 3; k++)
        s->wh[k] /= norm;
    return 1;
}

/* The ellipse parameter of the point whose normal has azimuth phi_m, continuous around phi_ref. */
static double gamma_of(double b, double phi_m, double phi_ref)
{
    double g = atan2(sin(phi_m), b * cos(phi_m));
    return g + 2.0 * M_PI * round((phi_ref - g) / (2.0 * M_PI));
}

double hb_ref_huang_r_integral(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                               int shadowing)
{
    ref_r_setup s;
    double lo, hi;
    if (!setup(&s, plan, theta_i, phi_i, theta_o, phi_o, shadowing) ||
        !window(&s, theta_i, phi_i, theta_o, phi_o, &lo, &hi))
        return 0.0;
    /* split at the NDF's peak, phi_m = phi_h, where it falls inside */
    double phi_h = atan2(s.wh[0], s.wh[2]), mid = 0.5 * (lo + hi);
    phi_h += 2.0 * M_PI * round((mid - phi_h) / (2.0 * M_PI));
    double cuts[3] = { lo, phi_h, hi };
    int ncuts = phi_h > lo && phi_h < hi ? 3 : 0;
    if (!ncuts) {
        cuts[1] = hi;
        ncuts = 2;
    }
    if (s.in_gamma)
        for (int k = 0; k < ncuts; k++)
            cuts[k] = gamma_of(s.b, cuts[k], gamma_of(s.b, mid, 0.0));
    return adaptive(&s, cuts, ncuts);
}

/* HHH22 App. A, eq. 43 exactly as printed: the antiderivative in phi_m of GGX's D over the
 * mesonormal, A = cos(theta_h) cos(alpha) sqrt(1 - r^2), B = sin(theta_h) sin(alpha) sqrt(1 - r^2),
 * evaluated at the window's ends (circular fibres, no G). */
static double eq43(double r, double A, double B, double x)
{
    double pm = (B - 1.0) * (B - 1.0) - A * A, pp = (B + 1.0) * (B + 1.0) - A * A, t = tan(0.5 * x);
    double sum = 2.0 * (A * A - B * B + 3.0 * B - 2.0) / pow(pm, 1.5) * atan((A - B + 1.0) * t / sqrt(pm)) +
                 2.0 * (A * A - B * B - 3.0 * B - 2.0) / pow(pp, 1.5) * atan((B - A + 1.0) * t / sqrt(pp)) +
                 A * sin(x) / (pm * (A * cos(x) + B - 1.0)) + A * sin(x) / (pp * (A * cos(x) + B + 1.0));
    return r * r / (4.0 * M_PI) * sum;
}

double hb_ref_huang_r_integral_analytic(const hb_plan *plan, double theta_i, double phi_i, double theta_o,
                                        double phi_o)
{
    ref_r_setup s;
    double lo, hi;
    if (!setup(&s, plan, theta_i, phi_i, theta_o, phi_o, 0) || !window(&s, theta_i, phi_i, theta_o, phi_o, &lo, &hi))
        return 0.0;
    double r = plan->material.roughness, c = sqrt(1.0 - r * r);
    double theta_h = asin(fmax(-1.0, fmin(1.0, s.wh[1]))), phi_h = atan2(s.wh[0], s.wh[2]);
    phi_h += 2.0 * M_PI * round((0.5 * (lo + hi) - phi_h) / (2.0 * M_PI));
    double A = cos(theta_h) * cos(s.tilt) * c, B = sin(theta_h) * sin(s.tilt) * c;
    return eq43(r, A, B, phi_h - hi) - eq43(r, A, B, phi_h - lo);
}

/* The mesonormal azimuths w_o sees, phi_o +- *half, and the projected offsets *lo, *hi of their
 * ends across w_o's view: for the point (sin g, b cos g) with normal azimuth phi_m, its dot product
 * with (cos phi_o, -sin phi_o). Returns 0 when w_o sees no mesonormal. */
int hb_ref_huang_o_window(const hb_plan *plan, double theta_o, double phi_o, double *half, double *lo, double *hi)
{
    double b = sqrt(1.0 - plan->material.eccentricity * plan->material.eccentricity);
    *half = hb_ref_huang_half_width(theta_o, hb_huang_of(plan)->tilt);
    if (*half < 0.0)
        return 0;
    double ends[2];
    for (int k = 0; k < 2; k++) {
        double phi_m = phi_o + (k ? *half : -*half), g = atan2(sin(phi_m), b * cos(phi_m));
        ends[k] = sin(g) * cos(phi_o) - b * cos(g) * sin(phi_o);
    }
    *lo = ends[0];
    *hi = ends[1];
    return 1;
}

double hb_ref_huang_pdf(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o)
{
    ref_r_setup s;
    double half, lo_offset, hi_offset;
    if (!hb_ref_huang_o_window(plan, theta_o, phi_o, &half, &lo_offset, &hi_offset) ||
        !setup(&s, plan, theta_i, phi_i, theta_o, phi_o, 0) || !(hi_offset > lo_offset))
        return 0.0;
    s.pdf = 1;
    /* cuts: the window's ends, the NDF's peak phi_h and where w_h . w_m = 0, phi_h +- beta */
    double lo = phi_o - half, hi = phi_o + half, mid = phi_o;
    double phi_h = atan2(s.wh[0], s.wh[2]), theta_h = asin(fmax(-1.0, fmin(1.0, s.wh[1])));
    phi_h += 2.0 * M_PI * round((mid - phi_h) / (2.0 * M_PI));
    double cos_beta = -sin(theta_h) * sin(s.tilt) / fmax(cos(theta_h) * cos(s.tilt), 1e-300);
    double beta = acos(fmax(-1.0, fmin(1.0, cos_beta)));
    double cuts[8] = { lo, hi }, candidates[5] = { phi_h, phi_h - beta, phi_h + beta, phi_h - beta + 2.0 * M_PI,
                                                   phi_h + beta - 2.0 * M_PI };
    int ncuts = 2;
    for (int k = 0; k < 5; k++)
        if (candidates[k] > lo && candidates[k] < hi)
            cuts[ncuts++] = candidates[k];
    for (int a = 1; a < ncuts; a++) /* insertion sort */
        for (int b = a; b > 0 && cuts[b] < cuts[b - 1]; b--) {
            double t = cuts[b];
            cuts[b] = cuts[b - 1];
            cuts[b - 1] = t;
        }
    if (s.in_gamma)
        for (int k = 0; k < ncuts; k++)
            cuts[k] = gamma_of(s.b, cuts[k], gamma_of(s.b, mid, 0.0));
    return adaptive(&s, cuts, ncuts) / (4.0 * (hi_offset - lo_offset));
}

void hb_ref_huang(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3])
{
    const hb_material *m = &plan->material;
    double tt[3] = { 0.0, 0.0, 0.0 }, trt[3] = { 0.0, 0.0, 0.0 };
    if (hb_huang_of(plan)->kernel.lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT))
        hb_ref_huang_internal(plan, theta_i, phi_i, theta_o, phi_o, 0, HB_REF_HUANG_PHI_POINTS, HB_REF_HUANG_TT_POINTS,
                              HB_REF_HUANG_TRT_POINTS, tt, trt);
    for (int c = 0; c < 3; c++)
        f[c] = tt[c] + trt[c];
    if (!(hb_huang_of(plan)->kernel.lobes >> HB_LOBE_R & 1u))
        return;
    double integral = hb_ref_huang_r_integral(plan, theta_i, phi_i, theta_o, phi_o,
                                              plan->options.shadowing == HB_SHADOWING_SMITH);
    double wi[3], wo[3];
    unit_direction(theta_i, phi_i, wi);
    unit_direction(theta_o, phi_o, wo);
    double cos_half = sqrt(fmax(0.0, 0.5 * (1.0 + dot3(wi, wo)))); /* w_o . w_h */
    double fresnel = hb_ref_fresnel(m->eta, cos_half);
    double projected = sqrt(1.0 - m->eccentricity * m->eccentricity * sin(phi_o) * sin(phi_o)); /* eq. 27 */
    double value = fresnel * integral * hb_ref_huang_width(plan, theta_i, theta_o) / (8.0 * projected); /* eqs. 12, 28 */
    for (int c = 0; c < 3; c++)
        f[c] += value;
}

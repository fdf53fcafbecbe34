/* HHH22 TT and TRT lobes in double (docs/huang.md): one internal path as a function
 * of the entry azimuth phi_m1 and the four numbers that pick the visible normals at interfaces 1
 * and 2, written with vectors and libm; the kernels' estimator (eqs. 31, 32) with the kernels'
 * counter-based numbers; and the integrals by nested quadrature over the same variables. */
#include <math.h>
#include <stdint.h>

#include "reference.h"
#include "models/interface/plan.h"
#include "math/hash.h"
#include "math/quadrature.h"
#include "state.h"

enum { U_RULE = 4, PHI_RULE = 4, MAX_POINTS = 1024 };

typedef struct point {
    double p[2];                          /* (x, z) */
    double macro[3], meso[3], t1[3], t2[3];
} point;

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void point_of_normal(const hb_plan *plan, double phi_m, double x, double z, point *q)
{
    double tau = hb_huang_of(plan)->tilt, s = sin(phi_m), c = cos(phi_m);
    q->p[0] = x;
    q->p[1] = z;
    double macro[3] = { s, 0.0, c }, meso[3] = { cos(tau) * s, sin(tau), cos(tau) * c }; /* eq. 39 */
    double t1[3] = { c, 0.0, -s }, t2[3] = { -sin(tau) * s, cos(tau), -sin(tau) * c };
    for (int k = 0; k < 3; k++) {
        q->macro[k] = macro[k];
        q->meso[k] = meso[k];
        q->t1[k] = t1[k];
        q->t2[k] = t2[k];
    }
}

static double minor_axis(const hb_plan *plan)
{
    return sqrt(1.0 - plan->material.eccentricity * plan->material.eccentricity);
}

/* The point of x = sin g, z = b cos g whose normal (b sin g, cos g) has azimuth phi_m. */
static void entry_point(const hb_plan *plan, double phi_m, point *q)
{
    double b = minor_axis(plan), g = atan2(sin(phi_m), b * cos(phi_m));
    point_of_normal(plan, phi_m, sin(g), b * cos(g), q);
}

/* The chord from q along w: solve |(x + s dx, (z + s dz) / b)| = 1 for the far root s. */
static void chord_exit(const hb_plan *plan, const point *q, const double w[3], point *out, double *length)
{
    double b = minor_axis(plan), planar = hypot(w[0], w[2]);
    double d[2] = { w[0] / planar, w[2] / planar };
    double a2 = d[0] * d[0] + d[1] * d[1] / (b * b), a1 = q->p[0] * d[0] + q->p[1] * d[1] / (b * b);
    double s = fmax(-2.0 * a1 / a2, 0.0);
    double x = q->p[0] + s * d[0], z = q->p[1] + s * d[1];
    *length = s / planar;
    point_of_normal(plan, atan2(x, z / (b * b)), x, z, out);
}

static double g1(const hb_plan *plan, double c)
{
    return c > 0.0 ? 1.0 / (1.0 + hb_ref_huang_lambda(plan->material.ndf, plan->material.roughness, fmin(c, 1.0)))
                   : 0.0;
}

/* A visible normal of `toward` on the outer (side 1) or inner (side -1) side at q. */
static void micronormal(const hb_plan *plan, const point *q, const double toward[3], double side, double u1, double u2,
                        double h[3])
{
    double o[3] = { side * dot3(toward, q->t1), dot3(toward, q->t2), fmax(side * dot3(toward, q->meso), 1e-300) }, m[3];
    hb_ref_huang_visible_normal(plan, o, u1, u2, m);
    for (int k = 0; k < 3; k++)
        h[k] = side * m[0] * q->t1[k] + m[1] * q->t2[k] + side * m[2] * q->meso[k];
}

/* Leaving through q along w toward w_o (Walter et al. 2007; HHH22 eqs. 21, 31). */
static double exit_value(const hb_plan *plan, const point *q, const double w[3], const double wo[3])
{
    const hb_material *m = &plan->material;
    double half[3], len2 = 0.0;
    for (int k = 0; k < 3; k++) {
        half[k] = m->eta * w[k] - wo[k];
        len2 += half[k] * half[k];
    }
    double len = sqrt(len2), wh[3] = { half[0] / len, half[1] / len, half[2] / len };
    double cos_in = dot3(w, wh), cos_out = dot3(wo, wh), w_m = dot3(w, q->meso), wo_m = dot3(wo, q->meso);
    double h_m = dot3(wh, q->meso);
    if (!(cos_in > 0.0 && cos_out > 0.0 && dot3(wo, q->macro) > 0.0 && wo_m > 0.0 && w_m > 0.0 && h_m > 0.0))
        return 0.0;
    double value = (1.0 - hb_ref_fresnel(m->eta, fmin(cos_out, 1.0))) * hb_ref_huang_ndf(m->ndf, m->roughness, h_m);
    value *= g1(plan, w_m) * g1(plan, wo_m); /* G at every interface of TT and TRT, also without G for R */
    return value * cos_in * cos_out / (w_m * len2);
}

/* Reflectance met from inside at cos_in: 1 under total internal reflection. */
static double fresnel_inside(double eta, double cos_in)
{
    double sin2_out = eta * eta * (1.0 - cos_in * cos_in);
    return sin2_out >= 1.0 ? 1.0 : hb_ref_fresnel(eta, sqrt(1.0 - sin2_out));
}

/* One internal path from the entry azimuth phi_m1: the TT and TRT integrands of eqs. 31, 32 (rho
 * excluded) per channel. */
static void internal_path(const hb_plan *plan, unsigned lobes, double phi_m1, const double wi[3], const double wo[3],
                          const double u[4], double tt[3], double trt[3])
{
    const hb_material *m = &plan->material;
    double eta = m->eta, h1[3], wt[3], length;
    for (int c = 0; c < 3; c++)
        tt[c] = trt[c] = 0.0;
    point p, q, r;
    entry_point(plan, phi_m1, &p);
    micronormal(plan, &p, wi, 1.0, u[0], u[1], h1);
    double c1 = fmax(dot3(wi, h1), 0.0), cos_t = sqrt(fmax(1.0 - (1.0 - c1 * c1) / (eta * eta), 0.0));
    for (int k = 0; k < 3; k++)
        wt[k] = (c1 / eta - cos_t) * h1[k] - wi[k] / eta;
    double wi_m = fmax(dot3(wi, p.meso), 0.0), wt_m = -dot3(wt, p.meso); /* >= 0 up to rounding */
    if (!(wt_m > 0.0 && dot3(wt, p.macro) < 0.0))
        return;
    double entry = (1.0 - hb_ref_fresnel(eta, fmin(c1, 1.0))) * wi_m * g1(plan, wt_m);
    chord_exit(plan, &p, wt, &q, &length);
    double a[3];
    for (int c = 0; c < 3; c++)
        a[c] = exp(-plan->sigma_a[c] * length);
    if (lobes >> HB_LOBE_TT & 1u) {
        double leave = entry * exit_value(plan, &q, wt, wo);
        for (int c = 0; c < 3; c++)
            tt[c] = leave * a[c];
    }
    if (!(lobes >> HB_LOBE_TRT & 1u))
        return;
    double minus_wt[3] = { -wt[0], -wt[1], -wt[2] }, h2[3], wtr[3], length2;
    micronormal(plan, &q, minus_wt, -1.0, u[2], u[3], h2);
    double c2 = fmax(-dot3(wt, h2), 0.0);
    for (int k = 0; k < 3; k++)
        wtr[k] = wt[k] + 2.0 * c2 * h2[k];
    double wtr_m2 = -dot3(wtr, q.meso);
    if (!(wtr_m2 > 0.0 && dot3(wtr, q.macro) < 0.0))
        return;
    double bounce = fresnel_inside(eta, c2) * g1(plan, wtr_m2);
    chord_exit(plan, &q, wtr, &r, &length2);
    double leave = entry * bounce * exit_value(plan, &r, wtr, wo);
    for (int c = 0; c < 3; c++)
        trt[c] = leave * a[c] * exp(-plan->sigma_a[c] * length2);
}

/* rho = b^2 / (1 - e^2 cos^2 phi_m)^(3/2), the arc length per unit phi_m (eq. 26). */
static double arc_length(const hb_plan *plan, double phi_m)
{
    double e2 = plan->material.eccentricity * plan->material.eccentricity, q = 1.0 - e2 * cos(phi_m) * cos(phi_m);
    return (1.0 - e2) / (q * sqrt(q));
}

typedef struct setup {
    double wi[3], wo[3];
    double half, scale; /* the entry window phi_i +- half; 1 / (2 a cos(theta_o)) */
} setup;

static int setup_of(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, setup *s)
{
    double ct_i = fmax(cos(theta_i), 0.0), ct_o = fmax(cos(theta_o), 0.0), e = plan->material.eccentricity;
    double wi[3] = { sin(phi_i) * ct_i, sin(theta_i), cos(phi_i) * ct_i };
    double wo[3] = { sin(phi_o) * ct_o, sin(theta_o), cos(phi_o) * ct_o };
    for (int k = 0; k < 3; k++) {
        s->wi[k] = wi[k];
        s->wo[k] = wo[k];
    }
    s->half = hb_ref_huang_half_width(theta_i, hb_huang_of(plan)->tilt);
    s->scale = hb_ref_huang_width(plan, theta_i, theta_o) / (2.0 * sqrt(1.0 - e * e * sin(phi_o) * sin(phi_o)));
    return s->half > 0.0;
}

/* The 32-bit mix of src/models/huang/rng.h. */
static uint32_t mix32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    return x ^ (x >> 16);
}

float hb_ref_huang_uniform(const hb_plan *plan, unsigned index, unsigned counter)
{
    uint32_t stream = mix32((uint32_t)index ^ hb_huang_of(plan)->kernel.rng_key);
    return (float)(mix32((stream ^ hb_huang_of(plan)->kernel.rng_key2) + (uint32_t)counter * 0x9e3779b9u) >> 8) * 0x1p-24f;
}

static double simpson_weight(int j, int panels) { return (j == 0 || j == panels) ? 1.0 : (j & 1) ? 4.0 : 2.0; }

void hb_ref_huang_internal_mc(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                              unsigned index, double tt[3], double trt[3])
{
    setup s;
    for (int c = 0; c < 3; c++)
        tt[c] = trt[c] = 0.0;
    if (!setup_of(plan, theta_i, phi_i, theta_o, phi_o, &s))
        return;
    int panels = hb_huang_of(plan)->kernel.tt_panels;
    double step = 2.0 * s.half / panels;
    for (int j = 0; j <= panels; j++) {
        double phi_m = phi_i - s.half + j * step, u[4], path_tt[3], path_trt[3];
        for (int k = 0; k < 4; k++)
            u[k] = hb_ref_huang_uniform(plan, index, (unsigned)(4 * j + k));
        internal_path(plan, hb_huang_of(plan)->kernel.lobes, phi_m, s.wi, s.wo, u, path_tt, path_trt);
        double w = simpson_weight(j, panels) * arc_length(plan, phi_m) * step / 3.0 * s.scale;
        for (int c = 0; c < 3; c++) {
            tt[c] += w * path_tt[c];
            trt[c] += w * path_trt[c];
        }
    }
}

/* Composite Gauss-Legendre with n points (a multiple of rule) on [a, b]. */
static int composite_rule(int n, int rule, double a, double b, double *x, double *w)
{
    int panels = n / rule < 1 ? 1 : n / rule;
    if (panels * rule > MAX_POINTS)
        panels = MAX_POINTS / rule;
    double width = (b - a) / panels;
    for (int k = 0; k < panels; k++)
        hb_gauss_legendre(rule, a + k * width, a + (k + 1) * width, x + k * rule, w + k * rule);
    return panels * rule;
}

/* A visible normal's number u maps the NDF's tail to a thin layer at an end of [0, 1] (GGX: the
 * spherical cap's rim at u2 -> 1), where an evenly spread rule put 4 of 32 points on the whole tail
 * (TT 8% low at f 2% of its peak). Gauss-Legendre in t with u = t - sin(2 pi t) / (2 pi),
 * du = (1 - cos(2 pi t)) dt (Sidi's sin^2 transformation) crowds the points at both ends. TT's
 * two numbers take it; TRT's four keep the even spread, whose 12 points per number the
 * transformation would thin where TRT's integrand lies (its reciprocity check off by 3.6e-2
 * instead of 1.2e-2). */
static int visible_number_rule(int n, double *u, double *w)
{
    int count = composite_rule(n, U_RULE, 0.0, 1.0, u, w);
    for (int k = 0; k < count; k++) {
        double t = u[k];
        w[k] *= 1.0 - cos(2.0 * M_PI * t);
        u[k] = t - sin(2.0 * M_PI * t) / (2.0 * M_PI);
    }
    return count;
}

/* The integral of one lobe's path over the entry nodes and `pairs` visible-normal pairs of numbers. */
static void nested(const hb_plan *plan, unsigned lobe, const setup *s, int n_phi, const double *phi_x,
                   const double *phi_w, int u_points, double out[3])
{
    double ux[MAX_POINTS], uw[MAX_POINTS];
    int n_u = lobe == HB_LOBE_TT ? visible_number_rule(u_points, ux, uw)
                                 : composite_rule(u_points, U_RULE, 0.0, 1.0, ux, uw),
        n_v = lobe == HB_LOBE_TRT ? n_u : 1;
    const double *vx = n_v > 1 ? ux : (const double[]){ 0.5 }, *vw = n_v > 1 ? uw : (const double[]){ 1.0 };
    for (int c = 0; c < 3; c++)
        out[c] = 0.0;
    for (int j = 0; j < n_phi; j++) {
        double wj = phi_w[j] * arc_length(plan, phi_x[j]) * s->scale;
        for (int a = 0; a < n_u; a++)
            for (int b = 0; b < n_u; b++)
                for (int c3 = 0; c3 < n_v; c3++)
                    for (int d4 = 0; d4 < n_v; d4++) {
                        double u[4] = { ux[a], ux[b], vx[c3], vx[d4] }, path[2][3];
                        double w = wj * uw[a] * uw[b] * vw[c3] * vw[d4];
                        internal_path(plan, 1u << lobe, phi_x[j], s->wi, s->wo, u, path[0], path[1]);
                        for (int c = 0; c < 3; c++)
                            out[c] += w * path[lobe == HB_LOBE_TRT][c];
                    }
    }
}

void hb_ref_huang_internal(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                           int simpson, int phi_points, int tt_points, int trt_points, double tt[3], double trt[3])
{
    setup s;
    for (int c = 0; c < 3; c++)
        tt[c] = trt[c] = 0.0;
    if (!setup_of(plan, theta_i, phi_i, theta_o, phi_o, &s))
        return;
    double phi_x[MAX_POINTS + 1], phi_w[MAX_POINTS + 1];
    int n_phi;
    if (simpson) {
        int panels = hb_huang_of(plan)->kernel.tt_panels;
        double step = 2.0 * s.half / panels;
        n_phi = panels + 1;
        for (int j = 0; j <= panels; j++) {
            phi_x[j] = phi_i - s.half + j * step;
            phi_w[j] = simpson_weight(j, panels) * step / 3.0;
        }
    } else {
        n_phi = composite_rule(phi_points, PHI_RULE, phi_i - s.half, phi_i + s.half, phi_x, phi_w);
    }
    if (hb_huang_of(plan)->kernel.lobes >> HB_LOBE_TT & 1u)
        nested(plan, HB_LOBE_TT, &s, n_phi, phi_x, phi_w, tt_points, tt);
    if (hb_huang_of(plan)->kernel.lobes >> HB_LOBE_TRT & 1u)
        nested(plan, HB_LOBE_TRT, &s, n_phi, phi_x, phi_w, trt_points, trt);
}

/* The visible-normal sample's weight through an interface besides Fresnel (Heitz 2014): G1 of
 * the outgoing direction with shadowing, 1 / G1 of the incoming one without. The R reflection's;
 * the internal interfaces keep G (g1 of the outgoing direction), as in internal_path. */
static double sampled_shadowing(const hb_plan *plan, double cos_in, double cos_out)
{
    if (plan->options.shadowing == HB_SHADOWING_SMITH)
        return g1(plan, cos_out);
    return 1.0 / fmax(g1(plan, cos_in), 1e-300);
}

static double walk_uniform(unsigned long long *state)
{
    *state += 0x9e3779b97f4a7c15ull;
    return (double)(hb_mix64(*state) >> 11) * 0x1p-53;
}

enum { WALK_ORDERS = 64 };

/* HHH22 Fig. 16 by a random walk through the rough circular fibre, light arriving along
 * w = (theta, phi = 0): the entry offset uniform across the part of the projected width whose
 * mesonormal faces w (weight W w.w_m1 / (2 cos(theta) cos(psi)), as in the kernels' sampler), a
 * visible normal at every interface, and at each internal hit the transmitted part leaving as order
 * p (splitting) and the reflected part going on; energy[p][c] per order p = 0 (R), 1 (TT), 2 (TRT),
 * 3 (everything beyond), the mean over `paths` walks, *standard_error[p] that of the channel mean. */
void hb_ref_huang_orders(const hb_plan *plan, double theta, long paths, unsigned long long seed,
                         double energy[HB_ORDER_GROUPS][3], double standard_error[HB_ORDER_GROUPS])
{
    const hb_material *m = &plan->material;
    double sum[HB_ORDER_GROUPS][3] = { { 0.0 } }, sum2[HB_ORDER_GROUPS] = { 0.0 };
    double half, lo, hi, eta = m->eta, wa[3] = { 0.0, sin(theta), cos(theta) };
    int seen = hb_ref_huang_o_window(plan, theta, 0.0, &half, &lo, &hi);
    unsigned long long state = hb_mix64(seed ^ 0x243f6a8885a308d3ull);
    for (long n = 0; seen && n < paths; n++) {
        double path[HB_ORDER_GROUPS][3] = { { 0.0 } };
        double sin_psi = (2.0 * walk_uniform(&state) - 1.0) * sin(half), cos_psi = sqrt(1.0 - sin_psi * sin_psi);
        point p, q;
        entry_point(plan, atan2(sin_psi, cos_psi), &p);
        double h1[3], wt[3], d[3];
        double u1 = walk_uniform(&state), u2 = walk_uniform(&state);
        micronormal(plan, &p, wa, 1.0, u1, u2, h1);
        double c1 = dot3(wa, h1), wa_m = dot3(wa, p.meso);
        double weight0 = 2.0 * sin(half) * wa_m / (2.0 * cos(theta) * fmax(cos_psi, 1e-300));
        if (!(c1 > 0.0 && wa_m > 0.0 && cos_psi > 1e-9))
            continue;
        /* R: reflection off h1 */
        for (int k = 0; k < 3; k++)
            d[k] = 2.0 * c1 * h1[k] - wa[k];
        double f1 = hb_ref_fresnel(eta, fmin(c1, 1.0)), d_m = dot3(d, p.meso);
        if (d_m > 0.0 && dot3(d, p.macro) > 0.0)
            for (int c = 0; c < 3; c++)
                path[0][c] = weight0 * f1 * sampled_shadowing(plan, wa_m, d_m);
        /* into the fibre */
        double cos_t = sqrt(fmax(1.0 - (1.0 - c1 * c1) / (eta * eta), 0.0));
        for (int k = 0; k < 3; k++)
            wt[k] = (c1 / eta - cos_t) * h1[k] - wa[k] / eta;
        double wt_m = -dot3(wt, p.meso), weight[3];
        if (wt_m > 0.0 && dot3(wt, p.macro) < 0.0) {
            for (int c = 0; c < 3; c++)
                weight[c] = weight0 * (1.0 - f1) * g1(plan, wt_m);
            for (int order = 1; order < WALK_ORDERS; order++) {
                double length, h[3], minus_w[3] = { -wt[0], -wt[1], -wt[2] };
                chord_exit(plan, &p, wt, &q, &length);
                for (int c = 0; c < 3; c++)
                    weight[c] *= exp(-plan->sigma_a[c] * length);
                u1 = walk_uniform(&state);
                u2 = walk_uniform(&state);
                micronormal(plan, &q, minus_w, -1.0, u1, u2, h); /* inner side: faces inward */
                double c_in = -dot3(wt, h), w_m = dot3(wt, q.meso), sin2 = eta * eta * (1.0 - c_in * c_in);
                if (sin2 < 1.0 && c_in > 0.0 && w_m > 0.0 && -dot3(h, q.meso) > 0.0) { /* out through -h */
                    double cos_out = sqrt(1.0 - sin2);
                    for (int k = 0; k < 3; k++)
                        d[k] = eta * wt[k] - (cos_out - eta * c_in) * h[k];
                    d_m = dot3(d, q.meso);
                    if (d_m > 0.0 && dot3(d, q.macro) > 0.0) {
                        double leave = (1.0 - hb_ref_fresnel(eta, fmin(cos_out, 1.0))) * g1(plan, d_m);
                        int group = order < HB_ORDER_GROUPS - 1 ? order : HB_ORDER_GROUPS - 1;
                        for (int c = 0; c < 3; c++)
                            path[group][c] += weight[c] * leave;
                    }
                }
                /* the reflected part goes on */
                for (int k = 0; k < 3; k++)
                    wt[k] += 2.0 * c_in * h[k];
                double back_m = -dot3(wt, q.meso);
                if (!(c_in > 0.0 && back_m > 0.0 && dot3(wt, q.macro) < 0.0))
                    break;
                double bounce = fresnel_inside(eta, c_in) * g1(plan, back_m), largest = 0.0;
                for (int c = 0; c < 3; c++) {
                    weight[c] *= bounce;
                    largest = fmax(largest, weight[c]);
                }
                if (largest < 1e-9)
                    break;
                p = q;
            }
        }
        for (int g = 0; g < HB_ORDER_GROUPS; g++) {
            double mean = (path[g][0] + path[g][1] + path[g][2]) / 3.0;
            sum2[g] += mean * mean;
            for (int c = 0; c < 3; c++)
                sum[g][c] += path[g][c];
        }
    }
    for (int g = 0; g < HB_ORDER_GROUPS; g++) {
        double mean = (sum[g][0] + sum[g][1] + sum[g][2]) / (3.0 * (double)paths);
        standard_error[g] = paths > 1 ? sqrt(fmax(sum2[g] / (double)paths - mean * mean, 0.0) / (double)(paths - 1)) : 0.0;
        for (int c = 0; c < 3; c++)
            energy[g][c] = seen && paths > 0 ? sum[g][c] / (double)paths : 0.0;
    }
}

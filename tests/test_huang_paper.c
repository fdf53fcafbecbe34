/* HHH22's R lobe at grazing w_o is the paper's eq. 12 at the reference: f = F(w_o . w_h) / (8
 * cos(theta_o)) times the integral over the macronormal azimuth of D G, integrated here on its own
 * (the window both directions see, found in closed form, and a composite Simpson rule on it), for
 * an untilted circular fibre, GGX and Beckmann, with and without G. The energy bound at the poles
 * (pole_floor = bounded) is a departure from it whose size the test prints. */
#include <math.h>

#include "test.h"

typedef struct r_case {
    hb_ndf ndf;
    double roughness;
    int shadowing;
} r_case;

static void direction(double theta, double phi, double w[3])
{
    w[0] = sin(phi) * cos(theta), w[1] = sin(theta), w[2] = cos(phi) * cos(theta);
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The microfacet distribution at cos(theta_m) = c from the macronormal: GGX (eq. 41) or Beckmann. */
static double distribution(const r_case *k, double c)
{
    if (c <= 0.0)
        return 0.0;
    double r2 = k->roughness * k->roughness, t2 = (1.0 - c * c) / (c * c);
    if (k->ndf == HB_NDF_BECKMANN)
        return exp(-t2 / r2) / (M_PI * r2 * c * c * c * c);
    return r2 / (M_PI * c * c * c * c * (r2 + t2) * (r2 + t2));
}

/* Smith's masking of one direction at cos c to the macronormal, 1 / (1 + Lambda). */
static double masking(const r_case *k, double c)
{
    double tan_w = sqrt(fmax(1.0 - c * c, 0.0)) / c, r = k->roughness, lambda;
    if (k->ndf == HB_NDF_BECKMANN) {
        double a = 1.0 / (r * tan_w);
        lambda = 0.5 * (erf(a) - 1.0) + exp(-a * a) / (2.0 * a * sqrt(M_PI));
    } else {
        lambda = 0.5 * (sqrt(1.0 + r * r * tan_w * tan_w) - 1.0);
    }
    return 1.0 / (1.0 + lambda);
}

/* Unpolarised dielectric Fresnel reflectance at incidence cosine c from outside. */
static double fresnel(double eta, double c)
{
    double s2 = (1.0 - c * c) / (eta * eta);
    if (s2 >= 1.0)
        return 1.0;
    double ct = sqrt(1.0 - s2), rs = (c - eta * ct) / (c + eta * ct), rp = (eta * c - ct) / (eta * c + ct);
    return 0.5 * (rs * rs + rp * rp);
}

static double integrand(const r_case *k, const double wi[3], const double wo[3], const double wh[3], double phi_m)
{
    double wm[3] = { sin(phi_m), 0.0, cos(phi_m) };
    double ci = dot(wi, wm), co = dot(wo, wm);
    if (ci <= 0.0 || co <= 0.0)
        return 0.0;
    double value = distribution(k, dot(wh, wm));
    return k->shadowing ? value * masking(k, ci) * masking(k, co) : value;
}

/* Eq. 12 times cos(theta_i): the macronormals both directions see are phi_m within pi/2 of phi_i
 * and of phi_o (their planar parts point there), an interval; Simpson with 20000 panels on it. */
static double eq12(const r_case *k, double eta, double ti, double pi, double to, double po)
{
    double wi[3], wo[3], wh[3];
    direction(ti, pi, wi);
    direction(to, po, wo);
    double len = sqrt((wi[0] + wo[0]) * (wi[0] + wo[0]) + (wi[1] + wo[1]) * (wi[1] + wo[1]) + (wi[2] + wo[2]) * (wi[2] + wo[2]));
    for (int c = 0; c < 3; c++)
        wh[c] = (wi[c] + wo[c]) / len;
    double d = remainder(po - pi, 2.0 * M_PI), lo = fmax(pi, pi + d) - M_PI_2, hi = fmin(pi, pi + d) + M_PI_2;
    if (!(hi > lo))
        return 0.0;
    enum { PANELS = 20000 };
    double h = (hi - lo) / PANELS, sum = integrand(k, wi, wo, wh, lo) + integrand(k, wi, wo, wh, hi);
    for (int j = 1; j < PANELS; j++)
        sum += (j % 2 ? 4.0 : 2.0) * integrand(k, wi, wo, wh, lo + j * h);
    return fresnel(eta, dot(wo, wh)) * sum * h / 3.0 / (8.0 * cos(to));
}

static double eval_at(hb_test_ctx *t, const r_case *k, hb_pole_floor pole, double ti, double pi, double to, double po)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.ndf = k->ndf, m.roughness = k->roughness, m.alpha = 0.0;
    o.model = HB_MODEL_HUANG, o.lobes = 1u << HB_LOBE_R, o.quality = HB_QUALITY_REFERENCE, o.pole_floor = pole;
    o.shadowing = k->shadowing ? HB_SHADOWING_SMITH : HB_SHADOWING_NONE;
    hb_plan *plan;
    hb_error e;
    if (hb_plan_create(&m, &o, &plan, &e) != HB_OK) {
        CHECK(t, 0, "plan: %s", e.message);
        return NAN;
    }
    float a[4] = { (float)ti, (float)pi, (float)to, (float)po }, f[3];
    hb_eval_angles(plan, 1, (hb_angles_soa){ &a[0], &a[1], &a[2], &a[3] }, (hb_rgb_soa){ &f[0], &f[1], &f[2] }, NULL);
    hb_plan_destroy(plan);
    return f[0];
}

static void reference_is_eq12(hb_test_ctx *t)
{
    static const r_case cases[] = {
        { HB_NDF_GGX, 0.3, 0 }, { HB_NDF_GGX, 0.3, 1 }, { HB_NDF_BECKMANN, 0.3, 0 },
        { HB_NDF_BECKMANN, 0.3, 1 }, { HB_NDF_GGX, 0.1, 0 }, { HB_NDF_BECKMANN, 0.1, 1 },
    };
    static const double degrees[] = { 76.0, 80.0, 85.0, 88.0, 89.0, 89.9 };
    static const double phis[] = { 0.3, 1.4510765, 2.5 };
    double eta;
    {
        hb_material m;
        hb_material_default(&m);
        eta = m.eta;
    }
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const r_case *k = &cases[c];
        double worst = 0.0, departure = 0.0;
        for (size_t d = 0; d < sizeof degrees / sizeof degrees[0]; d++)
            for (size_t p = 0; p < sizeof phis / sizeof phis[0]; p++)
                for (int side = 0; side < 2; side++) {
                    /* w_o grazing on either side, w_i near its specular cone and away from it */
                    double to = (side ? 1.0 : -1.0) * degrees[d] * M_PI / 180.0, ti = side ? -1.3 : 1.3;
                    /* the float angles the library is given, so both sides integrate the same directions */
                    ti = (float)ti, to = (float)to;
                    double po = (float)phis[p], truth = eq12(k, eta, ti, 0.0, to, po);
                    double f = eval_at(t, k, HB_POLE_FLOOR_AUTO, ti, 0.0, to, po);
                    double bounded = eval_at(t, k, HB_POLE_FLOOR_BOUNDED, ti, 0.0, to, po);
                    double err = fabs(f - truth) / fmax(truth, 1e-6);
                    CHECK(t, err <= 2e-4, "%s %.2g %s: f(%.7g, 0, %.7g, %.7g) = %.9g, eq. 12 %.9g (%.2e)",
                          k->ndf == HB_NDF_GGX ? "GGX" : "Beckmann", k->roughness, k->shadowing ? "G" : "no G", ti, to,
                          po, f, truth, err);
                    worst = fmax(worst, err);
                    departure = fmax(departure, fabs(bounded - truth) / fmax(truth, 1e-6));
                }
        hb_test_note(t, "%s %.2g %s: reference against eq. 12 %.1e; pole_floor = bounded departs by up to %.3g",
                     k->ndf == HB_NDF_GGX ? "GGX" : "Beckmann", k->roughness, k->shadowing ? "with G" : "without G",
                     worst, departure);
    }
}

/* The repro of the paper's value at theta_o = -1.5 (86 degrees), GGX 0.3 without G. */
static void paper_value_without_g(hb_test_ctx *t)
{
    r_case k = { HB_NDF_GGX, 0.3, 0 };
    double f = eval_at(t, &k, HB_POLE_FLOOR_AUTO, 1.3, 0.0, -1.5, 1.4510765);
    double bounded = eval_at(t, &k, HB_POLE_FLOOR_BOUNDED, 1.3, 0.0, -1.5, 1.4510765);
    CHECK(t, fabs(f - 1.1065) <= 2e-4, "f = %.9g, the paper's is 1.1065", f);
    CHECK(t, bounded < 0.5 * f, "bounded f = %.9g, not below the paper's %.9g", bounded, f);
    hb_test_note(t, "reference %.6f (eq. 12), bounded %.6f", f, bounded);
}

const hb_test hb_tests_huang_paper[] = {
    { "huang_reference_is_eq12", reference_is_eq12, 0 },
    { "huang_paper_value_without_g", paper_value_without_g, 0 },
    { NULL, NULL, 0 },
};

/* From a hair colour to absorption (docs/conventions.md, colour): CBTB16's fit and its inverse by
 * melanin concentrations (dFH11 sec. 6.1), and what the fibre they give reflects (hb_furnace). */
#include <string.h>

#include "test.h"

static const double eumelanin_rgb[3] = { 0.419, 0.697, 1.37 }, pheomelanin_rgb[3] = { 0.187, 0.4, 1.05 };

/* CBTB16 eq. 9's colour of absorption sigma under azimuthal roughness b: C = exp(-d(b) sqrt(sigma)). */
static double colour_of(double sigma, double b)
{
    double d = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * pow(b, 3) + 5.574 * pow(b, 4) + 0.245 * pow(b, 5);
    return exp(-d * sqrt(sigma));
}

/* A colour made by melanins comes back as the same concentrations (to 1e-9 relative: the weighted
 * least squares has no residual there), for every mix from blonde to black and every beta_n. */
static void test_melanin_round_trip(hb_test_ctx *t)
{
    double worst = 0.0;
    for (int trial = 0; trial < 400; trial++) {
        double eu = trial % 5 == 0 ? 0.0 : hb_test_range(t, 0.0, 8.0);
        double pheo = trial % 7 == 0 ? 0.0 : hb_test_range(t, 0.0, 3.0), b = hb_test_range(t, 0.0, 1.0);
        if (eu + pheo < 1e-3)
            eu = 0.5;
        double rgb[3], got_eu, got_pheo;
        for (int c = 0; c < 3; c++)
            rgb[c] = colour_of(eu * eumelanin_rgb[c] + pheo * pheomelanin_rgb[c], b);
        hb_error err;
        CHECK(t, hb_melanin_from_colour(rgb, b, &got_eu, &got_pheo, &err) == HB_OK, "trial %d: %s", trial, err.message);
        double e = fmax(fabs(got_eu - eu), fabs(got_pheo - pheo)) / (eu + pheo);
        worst = fmax(worst, e);
        CHECK(t, e <= 1e-9, "trial %d: eumelanin %.9g pheomelanin %.9g came back as %.9g %.9g", trial, eu, pheo, got_eu,
              got_pheo);
    }
    hb_test_note(t, "melanin colours come back as their concentrations within %.2g", worst);
}

/* Colours melanins cannot make (a blue, a neutral grey, a neutral black) get non-negative
 * concentrations whose colour is the nearest in log colour: no other non-negative mix on a grid
 * comes closer. Refusals name the problem. */
static void test_melanin_out_of_gamut(hb_test_ctx *t)
{
    static const double colours[][3] = { { 0.2, 0.4, 0.8 }, { 0.5, 0.5, 0.5 }, { 0.02, 0.015, 0.01 }, { 1.0, 1.0, 1.0 } };
    const double b = 0.3;
    for (int k = 0; k < 4; k++) {
        double eu, pheo, sigma[3];
        hb_error err;
        CHECK(t, hb_melanin_from_colour(colours[k], b, &eu, &pheo, &err) == HB_OK, "colour %d: %s", k, err.message);
        CHECK(t, eu >= 0.0 && pheo >= 0.0 && isfinite(eu + pheo), "colour %d: %g %g", k, eu, pheo);
        hb_absorption_from_colour(colours[k], b, sigma, NULL);
        /* the objective: sum_c (sigma_mix - sigma)^2 / sigma */
        double best = INFINITY, at_fit = 0.0;
        for (int c = 0; c < 3; c++) {
            double mix = eu * eumelanin_rgb[c] + pheo * pheomelanin_rgb[c];
            at_fit += (mix - sigma[c]) * (mix - sigma[c]) / fmax(sigma[c], 1e-6);
        }
        for (int i = 0; i <= 200; i++)
            for (int j = 0; j <= 200; j++) {
                double e2 = 0.0, ge = 0.01 * i * fmax(eu, 0.01) * 2.0, gp = 0.01 * j * fmax(pheo, 0.01) * 2.0;
                for (int c = 0; c < 3; c++) {
                    double mix = ge * eumelanin_rgb[c] + gp * pheomelanin_rgb[c];
                    e2 += (mix - sigma[c]) * (mix - sigma[c]) / fmax(sigma[c], 1e-6);
                }
                best = fmin(best, e2);
            }
        CHECK(t, at_fit <= best * (1.0 + 1e-9) + 1e-15, "colour %d: the fit's objective %.6g, a grid point's %.6g", k,
              at_fit, best);
        double got[3];
        for (int c = 0; c < 3; c++)
            got[c] = colour_of(eu * eumelanin_rgb[c] + pheo * pheomelanin_rgb[c], b);
        hb_test_note(t, "colour (%.3g, %.3g, %.3g): eumelanin %.4g pheomelanin %.4g give (%.3g, %.3g, %.3g)",
                     colours[k][0], colours[k][1], colours[k][2], eu, pheo, got[0], got[1], got[2]);
    }
    double eu, pheo;
    hb_error err;
    CHECK(t, hb_melanin_from_colour((double[3]){ 0.5, 0.0, 0.5 }, b, &eu, &pheo, &err) == HB_ERR_PARAM &&
                 strstr(err.message, "rgb.g"), "a zero channel: %s", err.message);
    CHECK(t, hb_melanin_from_colour((double[3]){ 0.5, 0.5, 0.5 }, b, NULL, &pheo, &err) == HB_ERR_NULL, "NULL output");
}

/* What a fibre of the fitted absorption reflects: CBTB16's fit gives the colour of a hair volume
 * after multiple scattering, so one fibre's albedo (hb_furnace, the mean over theta_o in (0, 1.4))
 * is brighter than the colour asked, by more the darker it is; measured, and held to the order of
 * the colours (darker asked, darker fibre, in every channel). */
static void test_colour_albedo(hb_test_ctx *t)
{
    static const double colours[][3] = { { 0.9, 0.7, 0.5 }, { 0.6, 0.4, 0.25 }, { 0.3, 0.18, 0.1 },
                                         { 0.1, 0.06, 0.03 }, { 0.02, 0.015, 0.01 } };
    double last[3] = { 2.0, 2.0, 2.0 };
    for (int k = 0; k < 5; k++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        o.model = HB_MODEL_CHIANG;
        m.beta_m = 0.3, m.beta_n = 0.3;
        hb_absorption_from_colour(colours[k], m.beta_n, m.sigma_a, NULL);
        hb_plan *plan = NULL;
        hb_error err;
        CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "colour %d: %s", k, err.message);
        if (!plan)
            return;
        double albedo[3] = { 0.0, 0.0, 0.0 };
        for (int j = 0; j < 8; j++) {
            double e[3];
            hb_furnace(plan, (j + 0.5) / 8.0 * 1.4, e);
            for (int c = 0; c < 3; c++)
                albedo[c] += e[c] / 8.0;
        }
        for (int c = 0; c < 3; c++) {
            CHECK(t, albedo[c] < last[c] && albedo[c] > colours[k][c] && albedo[c] <= 1.0,
                  "colour %d channel %d: albedo %.4f (asked %.3g, the brighter colour's %.4f)", k, c, albedo[c],
                  colours[k][c], last[c]);
            last[c] = albedo[c];
        }
        hb_test_note(t, "asked (%.3g, %.3g, %.3g): sigma_a (%.3g, %.3g, %.3g), one fibre's albedo (%.3f, %.3f, %.3f)",
                     colours[k][0], colours[k][1], colours[k][2], m.sigma_a[0], m.sigma_a[1], m.sigma_a[2], albedo[0],
                     albedo[1], albedo[2]);
        hb_plan_destroy(plan);
    }
}

const hb_test hb_tests_colour[] = {
    { "melanin_round_trip", test_melanin_round_trip, 0 },
    { "melanin_out_of_gamut", test_melanin_out_of_gamut, 0 },
    { "colour_albedo", test_colour_albedo, 0 },
    { 0 },
};

/* hb_melanin_absorption_spectral (docs/spectral.md): Donner and Jensen 2006's power laws, scaled to
 * dFH11 sec. 6.1's units by the sRGB reduction of a fibre's spectral transmittance. The reduction:
 * the transmittance exp(-d sigma_a(lambda)) through a thickness d, times D65, against the CIE 1931
 * colour-matching functions over 41 bands (tests/cie_1931.h), to XYZ (Y = 1 for white) and to linear
 * sRGB (IEC 61966-2-1's matrix), each channel over its white; the RGB cross-section of a channel is
 * the least-squares slope of -log(channel) against d over 32 thicknesses up to where the first
 * channel falls to 5%. The library's scales are the ones whose RGB cross-sections come closest to
 * dFH11's in relative least squares, and the residual per channel is printed. */
#include <string.h>

#include "cie_1931.h"
#include "test.h"

/* Linear sRGB of the spectral transmittance of thickness d of a pigment, each channel over white. */
static void reduce(double eumelanin, double pheomelanin, double d, double rgb[3])
{
    static const double to_srgb[3][3] = { { 3.2404542, -1.5371385, -0.4985314 },
                                          { -0.9692660, 1.8760108, 0.0415560 },
                                          { 0.0556434, -0.2040259, 1.0572252 } };
    double xyz[2][3] = { { 0 } }, norm = 0.0;
    for (int b = 0; b < CIE_BANDS; b++) {
        const double *row = cie_1931_d65[b];
        double sigma_a;
        hb_melanin_absorption_spectral(eumelanin, pheomelanin, row[0], &sigma_a);
        double t = exp(-d * sigma_a);
        for (int k = 0; k < 3; k++)
            xyz[0][k] += t * row[4] * row[1 + k], xyz[1][k] += row[4] * row[1 + k];
        norm += row[4] * row[2];
    }
    for (int c = 0; c < 3; c++) {
        double lit = 0.0, white = 0.0;
        for (int k = 0; k < 3; k++)
            lit += to_srgb[c][k] * xyz[0][k] / norm, white += to_srgb[c][k] * xyz[1][k] / norm;
        rgb[c] = lit / white;
    }
}

static double least_channel(double eumelanin, double pheomelanin, double d)
{
    double rgb[3];
    reduce(eumelanin, pheomelanin, d, rgb);
    return fmin(rgb[0], fmin(rgb[1], rgb[2]));
}

/* The RGB cross-sections of a pigment mix per unit concentration. */
static void rgb_cross_sections(double eumelanin, double pheomelanin, double out[3])
{
    double lo = 0.0, hi = 1.0;
    while (least_channel(eumelanin, pheomelanin, hi) > 0.05)
        hi *= 2.0;
    for (int k = 0; k < 100; k++) {
        double mid = 0.5 * (lo + hi);
        *(least_channel(eumelanin, pheomelanin, mid) > 0.05 ? &lo : &hi) = mid;
    }
    double num[3] = { 0 }, den = 0.0;
    for (int k = 1; k <= 32; k++) {
        double d = 0.5 * (lo + hi) * k / 32.0, rgb[3];
        reduce(eumelanin, pheomelanin, d, rgb);
        for (int c = 0; c < 3; c++)
            num[c] -= d * log(rgb[c]);
        den += d * d;
    }
    for (int c = 0; c < 3; c++)
        out[c] = num[c] / den;
}

static void test_srgb_reduction(hb_test_ctx *t)
{
    static const struct {
        const char *name;
        double eumelanin, pheomelanin, rgb[3];
    } pigments[] = { { "eumelanin", 1.0, 0.0, { 0.419, 0.697, 1.37 } }, { "pheomelanin", 0.0, 1.0, { 0.187, 0.4, 1.05 } } };
    for (int p = 0; p < 2; p++) {
        double s[3], rgb[3];
        rgb_cross_sections(pigments[p].eumelanin, pigments[p].pheomelanin, s);
        hb_melanin_absorption(pigments[p].eumelanin, pigments[p].pheomelanin, rgb);
        /* the scale k minimising sum ((k s_c - rgb_c) / rgb_c)^2: 1 for the library's own */
        double num = 0.0, den = 0.0;
        for (int c = 0; c < 3; c++)
            num += s[c] / rgb[c], den += (s[c] / rgb[c]) * (s[c] / rgb[c]);
        CHECK(t, fabs(num / den - 1.0) < 1e-9, "%s: the closest scale is %.12f of the library's", pigments[p].name, num / den);
        CHECK(t, memcmp(rgb, pigments[p].rgb, sizeof rgb) == 0, "%s: the RGB default is dFH11's", pigments[p].name);
        hb_test_note(t, "%-11s RGB cross-sections from the spectrum %.3f %.3f %.3f, dFH11's %.3f %.3f %.3f: residual %+.1f%% "
                        "%+.1f%% %+.1f%%",
                     pigments[p].name, s[0], s[1], s[2], rgb[0], rgb[1], rgb[2], 100.0 * (s[0] / rgb[0] - 1.0),
                     100.0 * (s[1] / rgb[1] - 1.0), 100.0 * (s[2] / rgb[2] - 1.0));
    }
}

/* The power laws and the mix: sigma_a(450) / sigma_a(650) is (450 / 650)^-3.33 for eumelanin and
 * ^-4.75 for pheomelanin, concentrations add, and the refusals name what is wrong. */
static void test_power_laws(hb_test_ctx *t)
{
    double e450, e650, p450, p650, mix, e, p;
    hb_melanin_absorption_spectral(1.0, 0.0, 450.0, &e450), hb_melanin_absorption_spectral(1.0, 0.0, 650.0, &e650);
    hb_melanin_absorption_spectral(0.0, 1.0, 450.0, &p450), hb_melanin_absorption_spectral(0.0, 1.0, 650.0, &p650);
    CHECK(t, fabs(e450 / e650 / pow(450.0 / 650.0, -3.33) - 1.0) < 1e-14, "eumelanin's exponent");
    CHECK(t, fabs(p450 / p650 / pow(450.0 / 650.0, -4.75) - 1.0) < 1e-14, "pheomelanin's exponent");
    hb_melanin_absorption_spectral(0.3, 0.2, 520.0, &mix);
    hb_melanin_absorption_spectral(1.0, 0.0, 520.0, &e), hb_melanin_absorption_spectral(0.0, 1.0, 520.0, &p);
    CHECK(t, fabs(mix - (0.3 * e + 0.2 * p)) < 1e-15, "concentrations add");
    CHECK(t, hb_melanin_absorption_spectral(1.0, 0.0, 250.0, &e) == HB_ERR_PARAM && strstr(hb_last_error()->message, "250"),
          "250 nm: %s", hb_last_error()->message);
    CHECK(t, hb_melanin_absorption_spectral(-1.0, 0.0, 500.0, &e) == HB_ERR_PARAM, "a negative concentration");
    CHECK(t, hb_melanin_absorption_spectral(1.0, NAN, 500.0, &e) == HB_ERR_PARAM, "NaN");
    CHECK(t, hb_melanin_absorption_spectral(1.0, 0.0, 500.0, NULL) == HB_ERR_NULL, "NULL");
}

const hb_test hb_tests_spectral[] = {
    { "spectral_srgb_reduction", test_srgb_reduction, 0 },
    { "spectral_power_laws", test_power_laws, 0 },
    { NULL, NULL, 0 },
};

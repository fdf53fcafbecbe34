/* hb_melanin_absorption_spectral (docs/spectral.md): Donner and Jensen 2006's power laws, scaled to
 * dFH11 sec. 6.1's units by the sRGB reduction of a fibre's spectral transmittance. The reduction:
 * the transmittance exp(-d sigma_a(lambda)) through a thickness d, times D65, against the CIE 1931
 * colour-matching functions over 41 bands (src/plan/cie_1931.c), to XYZ (Y = 1 for white) and to linear
 * sRGB (IEC 61966-2-1's matrix), each channel over its white; the RGB cross-section of a channel is
 * the least-squares slope of -log(channel) against d over 32 thicknesses up to where the first
 * channel falls to 5%. The library's scales are the ones whose RGB cross-sections come closest to
 * dFH11's in relative least squares, and the residual per channel is printed. */
#include <string.h>

#include "plan/srgb.h"
#include "test.h"

/* Linear sRGB of the spectral transmittance of thickness d of a pigment, each channel over white
 * (the library's reduction, src/plan/srgb.h). */
static void reduce(double eumelanin, double pheomelanin, double d, double rgb[3])
{
    double t[HB_CIE_BANDS];
    for (int b = 0; b < HB_CIE_BANDS; b++) {
        double sigma_a;
        hb_melanin_absorption_spectral(eumelanin, pheomelanin, hb_cie_band(b), &sigma_a);
        t[b] = exp(-d * sigma_a);
    }
    hb_srgb_of_spectrum(t, rgb);
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

/* The colour a spectral renderer shows for concentrations under CBTB16's roughness beta_n: eq. 9's
 * exp(-d sqrt(sigma_a)) per band, d = 1 / sqrt(hb_absorption_from_colour's sigma_a for e^-1), reduced
 * to linear sRGB. */
static void spectral_colour(double eumelanin, double pheomelanin, double beta_n, double rgb[3])
{
    double e1[3] = { exp(-1.0), exp(-1.0), exp(-1.0) }, sigma[3], t[HB_CIE_BANDS];
    hb_absorption_from_colour(e1, beta_n, sigma, NULL);
    for (int b = 0; b < HB_CIE_BANDS; b++) {
        double sigma_a;
        hb_melanin_absorption_spectral(eumelanin, pheomelanin, hb_cie_band(b), &sigma_a);
        t[b] = exp(-sqrt(sigma_a / sigma[0]));
    }
    hb_srgb_of_spectrum(t, rgb);
}

/* The same through dFH11's RGB cross-sections, as an RGB renderer shows it. */
static void rgb_colour(double eumelanin, double pheomelanin, double beta_n, double rgb[3])
{
    double e1[3] = { exp(-1.0), exp(-1.0), exp(-1.0) }, sigma[3], s[3];
    hb_absorption_from_colour(e1, beta_n, sigma, NULL);
    hb_melanin_absorption(eumelanin, pheomelanin, s);
    for (int c = 0; c < 3; c++)
        rgb[c] = exp(-sqrt(s[c] / sigma[0]));
}

static double colour_error(const double got[3], const double want[3])
{
    double worst = 0.0;
    for (int c = 0; c < 3; c++)
        worst = fmax(worst, fabs(got[c] / want[c] - 1.0));
    return worst;
}

/* The two colour modes (docs/spectral.md). Round trips: concentrations' spectral colour gives them back
 * through hb_melanin_from_colour_spectral. Over 20 colours an RGB pipeline shows for melanins: each
 * mode's concentrations as an RGB and as a spectral renderer shows them, against the asked colour; the
 * spectral mode is never further than the RGB mode from it, as a spectral renderer shows it. */
static void test_colour_modes(hb_test_ctx *t)
{
    /* blond to dark brown, red, and one pigment alone: colours whose channels are all positive (a darker
     * eumelanin's blue falls below sRGB's gamut) */
    static const double trips[][2] = { { 0.05, 0.0 }, { 0.2, 0.0 }, { 0.1, 0.1 }, { 0.02, 0.15 }, { 0.4, 0.05 },
                                       { 0.6, 0.0 }, { 0.0, 0.3 } };
    double worst_trip = 0.0;
    for (size_t k = 0; k < sizeof trips / sizeof trips[0]; k++) {
        double rgb[3], eu = -1.0, pheo = -1.0;
        hb_error err;
        spectral_colour(trips[k][0], trips[k][1], 0.3, rgb);
        CHECK(t, hb_melanin_from_colour_spectral(rgb, 0.3, &eu, &pheo, &err) == HB_OK, "%s", err.message);
        worst_trip = fmax(worst_trip, fmax(fabs(eu - trips[k][0]), fabs(pheo - trips[k][1])) / fmax(trips[k][0], 0.1));
    }
    hb_test_note(t, "round trips of 7 concentrations through their spectral colour: within %.1e", worst_trip);
    CHECK(t, worst_trip <= 1e-6, "a round trip is off by %.3g", worst_trip);
    /* 20 colours an RGB pipeline shows for melanins from light blond to near-black and red (eumelanin
     * 0.01 to 0.8, pheomelanin 0 to 0.4) */
    double sum[3] = { 0.0 }, worst[3] = { 0.0 };
    int closer = 0;
    for (int k = 0; k < 20; k++) {
        double colour[3], eu, pheo, seu, spheo, shown[3][3];
        rgb_colour(0.01 * pow(80.0, (k % 10) / 9.0), k < 10 ? 0.0 : 0.04 * (k - 9) * (k % 2 ? 0.5 : 1.0), 0.3, colour);
        hb_melanin_from_colour(colour, 0.3, &eu, &pheo, NULL);
        hb_melanin_from_colour_spectral(colour, 0.3, &seu, &spheo, NULL);
        rgb_colour(eu, pheo, 0.3, shown[0]);       /* RGB mode, RGB renderer */
        spectral_colour(eu, pheo, 0.3, shown[1]);  /* RGB mode, spectral renderer */
        spectral_colour(seu, spheo, 0.3, shown[2]); /* spectral mode, spectral renderer */
        double log_error[2] = { 0.0, 0.0 };
        for (int c = 0; c < 3; c++) {
            log_error[0] += pow(log(shown[1][c] / colour[c]), 2.0);
            log_error[1] += pow(log(shown[2][c] / colour[c]), 2.0);
        }
        closer += log_error[1] <= log_error[0] + 1e-15;
        for (int m = 0; m < 3; m++) {
            double e = colour_error(shown[m], colour);
            sum[m] += e / 20.0, worst[m] = fmax(worst[m], e);
        }
    }
    hb_test_note(t, "20 melanin colours, the largest channel's relative error, mean / largest: RGB mode in an RGB "
                    "renderer %.1e / %.1e, in a spectral renderer %.1f%% / %.1f%%; spectral mode in a spectral renderer "
                    "%.1f%% / %.1f%%", sum[0], worst[0], 100 * sum[1], 100 * worst[1], 100 * sum[2], 100 * worst[2]);
    CHECK(t, closer == 20, "the spectral mode is closer in log colour for %d of 20 colours", closer);
}

/* The colour of an absorption spectrum in a spectral renderer: eq. 9's colour per band at its
 * absorption, reduced to linear sRGB (as spectral_colour). */
static void spectrum_colour(const hb_absorption_spectrum *spectrum, double beta_n, double rgb[3])
{
    double e1[3] = { exp(-1.0), exp(-1.0), exp(-1.0) }, sigma[3], t[HB_CIE_BANDS];
    hb_absorption_from_colour(e1, beta_n, sigma, NULL);
    for (int b = 0; b < HB_CIE_BANDS; b++) {
        double sigma_a;
        hb_absorption_spectrum_at(spectrum, hb_cie_band(b), &sigma_a);
        t[b] = exp(-sqrt(sigma_a / sigma[0]));
    }
    hb_srgb_of_spectrum(t, rgb);
}

/* hb_absorption_from_colour_spectral over the same 20 melanin colours and 11 dyed ones (blue, green,
 * violet, grey, a near-white blond, a saturated red, the three primaries at 0.99 against 0.01, white,
 * near-black and an orange with red at 1): the asked colour as a spectral renderer shows the
 * spectrum, within 1e-12 but white, which the family's colours (each below 1) approach from below
 * (measured 4.4e-8); every spectrum finite and non-negative from 300 to 1000 nm; refusals. */
static void test_absorption_modes(hb_test_ctx *t)
{
    static const double dyed[][3] = { { 0.05, 0.12, 0.45 }, { 0.08, 0.3, 0.1 }, { 0.25, 0.06, 0.35 },
                                      { 0.3, 0.3, 0.3 },    { 0.95, 0.9, 0.75 }, { 0.6, 0.02, 0.01 },
                                      { 0.99, 0.01, 0.01 }, { 0.01, 0.99, 0.01 }, { 0.01, 0.01, 0.99 },
                                      { 1.0, 1.0, 1.0 },    { 0.001, 0.001, 0.001 }, { 1.0, 0.5, 0.2 } };
    enum { DYED = sizeof dyed / sizeof dyed[0] };
    double sum[2] = { 0.0 }, worst[2] = { 0.0 }, white = 0.0;
    int bad = 0;
    for (int k = 0; k < 20 + DYED; k++) {
        double colour[3], shown[3];
        if (k < 20)
            rgb_colour(0.01 * pow(80.0, (k % 10) / 9.0), k < 10 ? 0.0 : 0.04 * (k - 9) * (k % 2 ? 0.5 : 1.0), 0.3, colour);
        else
            memcpy(colour, dyed[k - 20], sizeof colour);
        hb_absorption_spectrum spectrum;
        hb_error err;
        CHECK(t, hb_absorption_from_colour_spectral(colour, 0.3, &spectrum, &err) == HB_OK, "%s", err.message);
        spectrum_colour(&spectrum, 0.3, shown);
        double e = colour_error(shown, colour);
        if (colour[0] == 1.0 && colour[1] == 1.0 && colour[2] == 1.0) { /* the family's colours are below 1 */
            white = e;
            continue;
        }
        sum[k >= 20] += e / (k < 20 ? 20.0 : DYED - 1), worst[k >= 20] = fmax(worst[k >= 20], e);
        for (double lambda = 300.0; lambda <= 1000.0; lambda += 10.0) {
            double s = -1.0;
            bad += hb_absorption_spectrum_at(&spectrum, lambda, &s) != HB_OK || !(s >= 0.0 && isfinite(s));
        }
    }
    hb_test_note(t, "absorption spectra of 20 melanin colours in a spectral renderer, the largest channel's relative "
                    "error, mean / largest: %.1e / %.1e; of %d dyed colours: %.1e / %.1e; white %.1e",
                 sum[0], worst[0], DYED - 1, sum[1], worst[1], white);
    CHECK(t, bad == 0, "%d absorptions not finite and >= 0", bad);
    CHECK(t, white <= 1e-7, "white is off by %.3g", white);
    CHECK(t, worst[0] <= 1e-12, "a melanin colour is off by %.3g", worst[0]);
    CHECK(t, worst[1] <= 1e-12, "a dyed colour is off by %.3g", worst[1]);
    hb_absorption_spectrum spectrum;
    double s;
    CHECK(t, hb_absorption_from_colour_spectral((double[3]){ 0.5, 0.0, 0.5 }, 0.3, &spectrum, NULL) == HB_ERR_PARAM &&
                 strstr(hb_last_error()->message, "rgb.g"),
          "a channel of 0: %s", hb_last_error()->message);
    hb_absorption_from_colour_spectral((double[3]){ 0.5, 0.4, 0.3 }, 0.3, &spectrum, NULL);
    CHECK(t, hb_absorption_spectrum_at(&spectrum, 200.0, &s) == HB_ERR_PARAM, "200 nm: %s", hb_last_error()->message);
    CHECK(t, hb_absorption_spectrum_at(&spectrum, 500.0, NULL) == HB_ERR_NULL, "NULL");
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
    { "spectral_colour_modes", test_colour_modes, 0 },
    { "spectral_absorption_modes", test_absorption_modes, 0 },
    { "spectral_srgb_reduction", test_srgb_reduction, 0 },
    { "spectral_power_laws", test_power_laws, 0 },
    { NULL, NULL, 0 },
};

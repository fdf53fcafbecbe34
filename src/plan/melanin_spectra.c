/* The melanins' absorption at a wavelength (hb_melanin_absorption_spectral; docs/spectral.md):
 * Donner and Jensen 2006's power laws in wavelength, in dFH11 sec. 6.1's units. */
#include <math.h>

#include "models/interface/plan.h"

/* DJ06: eumelanin's cross-section goes as lambda^-3.33 and pheomelanin's as lambda^-4.75. Each
 * scale is its cross-section at 550 nm per unit radius and concentration: the one whose fibre,
 * reduced to sRGB over 41 bands (CIE 1931, D65), comes closest to dFH11 sec. 6.1's RGB
 * cross-sections in the least squares of their relative differences (tests/test_spectral.c
 * recomputes both). */
#define EUMELANIN_EXPONENT 3.33
#define PHEOMELANIN_EXPONENT 4.75
#define EUMELANIN_AT_550 0.67680607509429
#define PHEOMELANIN_AT_550 0.38525626446453
#define LAMBDA_MIN 300.0
#define LAMBDA_MAX 1000.0

hb_status hb_melanin_absorption_spectral(double eumelanin, double pheomelanin, double wavelength, double *sigma_a)
{
    static const char call[] = "hb_melanin_absorption_spectral";
    if (!sigma_a)
        return hb_fail_null(call, "sigma_a");
    if (!(wavelength >= LAMBDA_MIN && wavelength <= LAMBDA_MAX))
        return hb_fail(HB_ERR_PARAM, "%s: wavelength = %g nm is outside [300, 1000]", call, wavelength);
    if (!(eumelanin >= 0.0 && eumelanin <= 1e30 && pheomelanin >= 0.0 && pheomelanin <= 1e30))
        return hb_fail(HB_ERR_PARAM, "%s: the concentrations (%g, %g) must be finite and >= 0", call, eumelanin,
                       pheomelanin);
    double x = wavelength / 550.0;
    *sigma_a = eumelanin * EUMELANIN_AT_550 * pow(x, -EUMELANIN_EXPONENT) +
               pheomelanin * PHEOMELANIN_AT_550 * pow(x, -PHEOMELANIN_EXPONENT);
    return HB_OK;
}

/* A spectrum seen in linear sRGB (docs/spectral.md): a transmittance or reflectance per 10 nm band
 * from 380 to 780 nm, lit by D65, against the CIE 1931 colour-matching functions, each sRGB channel
 * over white's. Internal. */
#ifndef HB_PLAN_SRGB_H
#define HB_PLAN_SRGB_H

#define HB_CIE_BANDS 41 /* 380, 390, ..., 780 nm */

/* Band b's wavelength in nm. */
double hb_cie_band(int band);

/* Linear sRGB of a spectrum given per band, each channel over that of 1 in every band. */
void hb_srgb_of_spectrum(const double transmittance[HB_CIE_BANDS], double rgb[3]);

#endif

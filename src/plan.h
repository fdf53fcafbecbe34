/* The immutable plan: validated inputs, derived constants and the chosen kernels. Internal. */
#ifndef HB_PLAN_H
#define HB_PLAN_H

#include "hairbsdf.h"
#include "kernels.h"

struct hb_plan {
    hb_material material;
    hb_options options;
    const hb_kernels *kernels; /* NULL for HB_QUALITY_REFERENCE */
    hb_isa isa;
    double v[HB_MAX_LOBES + 1];      /* dFH11 roughness variance per lobe, v = beta_m^2 */
    double beta_n[HB_MAX_LOBES];     /* dFH11 azimuthal roughness per lobe */
    double sigma_a[3];               /* sigma_a plus melanin */
    hb_deon deon;                    /* float constants of the SIMD kernels */
    double marschner_mean_r, marschner_beta_r; /* MJC03 M_R = g(mean, beta; theta_h) */
    hb_gaussian_lobe marschner_r;
};

#endif

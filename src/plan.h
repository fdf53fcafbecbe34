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
    double v[HB_MAX_LOBES];    /* dFH11 roughness variance per lobe, v = beta_m^2 */
    hb_longitudinal longitudinal[HB_MAX_LOBES];
};

#endif

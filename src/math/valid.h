/* The one rule for a valid sample's angles and offset (include/hairbsdf.h, docs/conventions.md):
 * |theta| up to the float nearest pi/2 (4.4e-8 past it, so that float is a pole, not an error),
 * |phi| <= HB_PHI_LIMIT, |h| <= 1; each false for NaN. The kernels' vector form is in
 * src/kernel/batch.h, the scalar form here serves the entry points and the reference. */
#ifndef HB_MATH_VALID_H
#define HB_MATH_VALID_H

#include <math.h>

#include "hairbsdf.h"

#define HB_THETA_LIMIT 1.57079637f

static inline int hb_theta_valid(double theta) { return fabs(theta) <= HB_THETA_LIMIT; }
static inline int hb_phi_valid(double phi) { return fabs(phi) <= HB_PHI_LIMIT; }
static inline int hb_offset_valid(double h) { return fabs(h) <= 1.0; }

#endif

/* Plan-time helpers every model's derivation shares. Internal. */
#ifndef HB_MODELS_DERIVE_H
#define HB_MODELS_DERIVE_H

#include <math.h>

#include "models/common/dielectric.h"

/* An absorption coefficient as the kernels' float: any finite double is valid, but one above
 * FLT_MAX would become +Inf and Inf * 0 (a zero path length) NaN; past 1e30 per radius every
 * path but a zero-length one is absorbed entirely, so 1e30 stands for all of them. */
static inline float hb_absorption_float(double sigma_a) { return (float)fmin(sigma_a, 1e30); }

/* eta and its derived terms, eta^2 - 1 formed in double. */
static inline hb_dielectric hb_dielectric_of(double eta)
{
    return (hb_dielectric){ (float)eta, (float)(1.0 / (eta * eta)), (float)((eta - 1.0) * (eta + 1.0)) };
}

#endif

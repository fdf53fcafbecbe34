/* A fibre's hemisphere integrals at one inclination, as the dual-scattering terms are made of them:
 * shared by the converged quadrature (dual.c) and the engines' estimate (dual_sampled.c). Internal. */
#ifndef HB_API_DUAL_SUMS_H
#define HB_API_DUAL_SUMS_H

#include "hairbsdf.h"

/* Per hemisphere (0 forward, 1 backward) and channel: the energy and its first two moments in theta_h. */
typedef struct hb_dual_sums {
    double energy[2][3], first[2][3], second[2][3];
} hb_dual_sums;

/* The terms from the sums: eq. 6's energies, the moments' mean and variance, then eqs. 14-17 with
 * d_b. Fills terms->a_f to sigma_b2, not struct_size. */
void hb_dual_terms_of_sums(const hb_dual_sums *sums, double d_b, hb_dual_terms *terms);

/* The checks hb_dual_terms_at and hb_dual_terms_sampled share: plan and terms present, terms'
 * struct_size known, theta in (-pi/2, pi/2), d_b in [0, 1]; words a failure for `call`. */
hb_status hb_dual_check_call(const char *call, const hb_plan *plan, double theta, double d_b, const hb_dual_terms *terms);

/* The share below which a tolerance or budget plan drops dual scattering (its tolerance, or the error
 * its budget accepts); 0 for other plans, which keep it (src/api/dual_table.c). */
double hb_dual_drop_target(const hb_plan *plan);

#endif

/* dFH11's part of a plan: what its derive (plan.c, sample_plan.c and the table builds) computes from the material and
 * options, in the plan's allocation after its head (models/interface/plan.h). Derive writes it through
 * hb_deon_mut; evaluation, the reference and the description read it through hb_deon_of. Internal. */
#ifndef HB_DEON_STATE_H
#define HB_DEON_STATE_H

#include "models/interface/plan.h"
#include "constants.h"

typedef struct hb_deon_state {
    double v[HB_MAX_LOBES + 1];  /* roughness variance per lobe, v = beta_m^2 */
    double beta_n[HB_MAX_LOBES]; /* azimuthal roughness per lobe */
    hb_deon kernel;              /* float constants of the SIMD kernels */
    float *table;                /* owns kernel.np_table (HB_AZIMUTHAL_TABLE) */
    double table_error;          /* the N_p table's measured midpoint error */
} hb_deon_state;

static inline const hb_deon_state *hb_deon_of(const hb_plan *plan) { return (const hb_deon_state *)(const void *)plan->state; }
static inline hb_deon_state *hb_deon_mut(hb_plan *plan) { return (hb_deon_state *)(void *)plan->state; }

#endif

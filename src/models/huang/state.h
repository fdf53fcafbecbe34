/* HHH22's part of a plan: what its derive (plan.c and table_build.c) computes from the material and
 * options, in the plan's allocation after its head (models/interface/plan.h). Derive writes it through
 * hb_huang_mut; evaluation, the reference and the description read it through hb_huang_of. Internal. */
#ifndef HB_HUANG_STATE_H
#define HB_HUANG_STATE_H

#include "models/interface/plan.h"
#include "constants.h"

typedef struct hb_huang_state {
    double tilt;     /* the mesonormal inclination tau (eq. 39) */
    hb_huang kernel; /* float constants of the SIMD kernels */
    float *table;    /* owns kernel.table.values (HB_TT_TRT_TABLE) */
} hb_huang_state;

static inline const hb_huang_state *hb_huang_of(const hb_plan *plan) { return (const hb_huang_state *)(const void *)plan->state; }
static inline hb_huang_state *hb_huang_mut(hb_plan *plan) { return (hb_huang_state *)(void *)plan->state; }

#endif

/* CBTB16's part of a plan: what its derive (plan.c) computes from the material and
 * options, in the plan's allocation after its head (models/interface/plan.h). Derive writes it through
 * hb_chiang_mut; evaluation, the reference and the description read it through hb_chiang_of. Internal. */
#ifndef HB_CHIANG_STATE_H
#define HB_CHIANG_STATE_H

#include "models/interface/plan.h"
#include "constants.h"

typedef struct hb_chiang_state {
    double v[HB_CHIANG_TERMS]; /* M_p's variance: R, TT, TRT, residual */
    double s;                  /* the logistic scale of N_p */
    int far_capped;            /* the far field's rule asked for more than HB_CHIANG_MAX_NODES */
    hb_chiang kernel;          /* float constants of the SIMD kernels */
} hb_chiang_state;

static inline const hb_chiang_state *hb_chiang_of(const hb_plan *plan) { return (const hb_chiang_state *)(const void *)plan->state; }
static inline hb_chiang_state *hb_chiang_mut(hb_plan *plan) { return (hb_chiang_state *)(void *)plan->state; }

#endif

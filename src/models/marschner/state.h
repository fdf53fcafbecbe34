/* MJC03's part of a plan: what its derive (plan.c) computes from the material and
 * options, in the plan's allocation after its head (models/interface/plan.h). Derive writes it through
 * hb_marschner_mut; evaluation, the reference and the description read it through hb_marschner_of. Internal. */
#ifndef HB_MARSCHNER_STATE_H
#define HB_MARSCHNER_STATE_H

#include "models/interface/plan.h"
#include "constants.h"

typedef struct hb_marschner_state {
    double mean[3], beta[3];                 /* M_p = g(mean_p, beta_p; theta_h) */
    double eta_star_mean, eta_star_swing;    /* eta*(phi_h) = mean + swing cos(2 phi_h) */
    double eta_star_min;                     /* the smallest eta* of the fibre (eta if circular) */
    hb_marschner kernel;                     /* float constants of the SIMD kernels */
} hb_marschner_state;

static inline const hb_marschner_state *hb_marschner_of(const hb_plan *plan) { return (const hb_marschner_state *)(const void *)plan->state; }
static inline hb_marschner_state *hb_marschner_mut(hb_plan *plan) { return (hb_marschner_state *)(void *)plan->state; }

#endif

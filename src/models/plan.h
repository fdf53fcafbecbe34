/* The plan's data (struct hb_plan): the validated inputs, every model's constants and what a
 * tolerance or budget plan chose. Written once at plan creation (src/plan/create.c and the
 * model's derive), read by every evaluation; also hb_plan_fail, which words a refusal. Internal. */
#ifndef HB_MODELS_PLAN_H
#define HB_MODELS_PLAN_H

#include "hairbsdf.h"
#include "models/chiang/constants.h"
#include "models/deon/constants.h"
#include "models/huang/constants.h"
#include "models/marschner/constants.h"
#include "simd/compiler.h"

/* What a tolerance or budget plan chose and why (src/plan/select.c), for hb_plan_describe. */
typedef struct hb_selection {
    int active;
    double tolerance, budget_ns;
    unsigned measured, dropped;         /* lobes measured at creation, lobes dropped */
    double share[HB_MAX_LOBES + 1];     /* each measured lobe's largest value over the peak of f */
    double dropped_bound;               /* twice the dropped lobes' summed shares */
    char configuration[32];             /* the chosen preset, as the bench names it */
    int preset;                         /* its index; bit k of refused: preset k failed to build */
    unsigned refused;
    char refusal[160];                  /* why the last refused preset failed */
    double expected_error, expected_ns; /* calibrated error plus dropped_bound; ns on the plan's ISA */
    int ranked_by_scalar;               /* the ISA has no calibration: figures are scalar x86's */
    char calibration[128];              /* "built in" or the file */
} hb_selection;

struct hb_plan {
    hb_material material;
    hb_options options;
    const void *kernels; /* the model's kernel table for the plan's ISA; NULL: the double reference */
    const void *narrow_kernels; /* the scalar ISA's table where the plan's ISA is wider, else NULL (model.h) */
    const struct hb_reference_ops *reference; /* the model's double-precision procedures (src/ref/reference.h) */
    hb_isa isa;
    double sigma_a[3];   /* sigma_a plus melanin */
    /* dFH11 (src/models/deon/plan.c) */
    double v[HB_MAX_LOBES + 1];  /* roughness variance per lobe, v = beta_m^2 */
    double beta_n[HB_MAX_LOBES]; /* azimuthal roughness per lobe */
    hb_deon deon;                /* float constants of the SIMD kernels */
    float *deon_table;           /* owns deon.np_table (HB_AZIMUTHAL_TABLE) */
    double table_error;          /* the N_p table's measured midpoint error */
    /* MJC03 (src/models/marschner/plan.c) */
    double marschner_mean[3], marschner_beta[3]; /* M_p = g(mean_p, beta_p; theta_h) */
    double eta_star_mean, eta_star_swing;        /* eta*(phi_h) = mean + swing cos(2 phi_h) */
    double eta_star_min;                         /* the smallest eta* of the fibre (eta if circular) */
    hb_marschner marschner;
    /* HHH22 (src/models/huang/plan.c) */
    double huang_tilt;  /* the mesonormal inclination tau (eq. 39) */
    hb_huang huang;
    float *huang_table; /* owns huang.table.values (HB_TT_TRT_TABLE) */
    /* CBTB16 (src/models/chiang/plan.c) */
    double chiang_v[HB_CHIANG_TERMS]; /* M_p's variance: R, TT, TRT, residual */
    double chiang_s;                  /* the logistic scale of N_p */
    int chiang_far_capped;            /* the far field's rule asked for more than HB_CHIANG_MAX_NODES */
    hb_chiang chiang;
    hb_selection selection; /* tolerance and budget plans */
    size_t table_file_size; /* the table file the table was loaded from (0: built); options.table_file is NULL */
};

/* Fills error (if not NULL) with status and the formatted message; returns status (src/models/fail.c). */
hb_status hb_plan_fail(hb_error *error, hb_status status, const char *fmt, ...) HB_PRINTF_FORMAT(3, 4);

#endif

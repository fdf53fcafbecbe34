/* The immutable plan: validated inputs, derived constants and the chosen kernels. Internal. */
#ifndef HB_PLAN_H
#define HB_PLAN_H

#include "hairbsdf.h"
#include "kernels.h"

/* What a tolerance or budget plan chose and why (src/plan_select.c), for hb_plan_describe. */
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
    const hb_kernels *kernels; /* NULL for HB_QUALITY_REFERENCE */
    hb_isa isa;
    double v[HB_MAX_LOBES + 1];      /* dFH11 roughness variance per lobe, v = beta_m^2 */
    double beta_n[HB_MAX_LOBES];     /* dFH11 azimuthal roughness per lobe */
    double sigma_a[3];               /* sigma_a plus melanin */
    hb_deon deon;                    /* float constants of the SIMD kernels */
    double marschner_mean[3], marschner_beta[3]; /* MJC03 M_p = g(mean_p, beta_p; theta_h) */
    double eta_star_mean, eta_star_swing;        /* MJC03 eta*(phi_h) = mean + swing cos(2 phi_h) */
    double eta_star_min;                         /* MJC03: the smallest eta* of the fibre (eta if circular) */
    hb_marschner marschner;                      /* float constants of the SIMD kernels */
    double huang_tilt;                           /* HHH22 mesonormal inclination tau (eq. 39) */
    hb_huang huang;                              /* float constants of the SIMD kernels */
    float *huang_table;                          /* owns huang.table.values (HB_TT_TRT_TABLE) */
    float *deon_table;                           /* owns deon.np_table (HB_AZIMUTHAL_TABLE) */
    double table_error;                          /* the N_p table's measured midpoint error */
    hb_selection selection;                      /* tolerance and budget plans */
};

/* Fills error (if not NULL) with status and the formatted message; returns status (src/plan.c). */
hb_status hb_plan_fail(hb_error *error, hb_status status, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* SplitMix64's finaliser: a bijective 64-bit mix (src/sample.c). */
unsigned long long hb_mix64(unsigned long long x);

/* HHH22's TT/TRT table for HB_TT_TRT_TABLE (src/huang_table.c). */
hb_status hb_plan_build_huang_table(hb_plan *plan, hb_error *error);

/* dFH11's N_p table for HB_AZIMUTHAL_TABLE (src/deon_table.c). */
hb_status hb_plan_build_deon_table(hb_plan *plan, hb_error *error);

/* A tolerance or budget plan's options (src/plan_select.c); the calibrated figures of any plan's
 * configuration (0 when it has none). */
hb_status hb_plan_select(const hb_material *m, const hb_options *in, hb_isa isa, hb_options *out, hb_selection *sel,
                         hb_error *error);
int hb_plan_expected(const hb_plan *plan, char *configuration, size_t size, double *ns, double *err);

/* The sampler's constants (src/sample_plan.c). */
void hb_plan_derive_sampling(hb_plan *plan);

#endif

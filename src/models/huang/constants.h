/* What HHH22's kernels read from a plan, fixed at plan creation (src/models/huang/plan.c). */
#ifndef HB_HUANG_CONSTANTS_H
#define HB_HUANG_CONSTANTS_H

#include <stdint.h>

#include "hairbsdf.h"
#include "models/common/dielectric.h"

/* HHH22's f_TT + f_TRT tabulated at plan creation (docs/huang.md): values
 * times 2 a cos(theta_o) (bounded where f has its 1 / cos(theta_o)) on a grid over theta_i,
 * phi_i (elliptical fibres only; reduced to [0, pi/2] by the cross-section's two mirror
 * symmetries), s = theta_i + theta_o warped as u = asinh((s - sum_centre) / sum_width) so that the
 * nodes crowd where the lobes are narrow, and delta = phi_o - phi_i (|delta| in [0, pi] for a
 * circle, [-pi, pi] for an ellipse). Node order: theta_i, phi_i, u, delta, channel. */
typedef struct hb_huang_table {
    const float *values;
    int n_theta_i, n_phi_i, n_sum, n_delta;
    float sum_centre, inv_sum_width, u_lo, u_scale; /* u node k at u_lo + k / u_scale */
    float delta_lo, delta_scale;                    /* delta node l at delta_lo + l / delta_scale */
    int panels; /* the builder's Simpson panels over the entry window */
    int paths;  /* the builder's internal paths per Simpson node */
} hb_huang_table;

/* What the table builder needs besides the plan's constants: the grid of one row (s and delta at
 * every node), the rank-1 lattice of internal paths per Simpson node (its point count and
 * generating vector), and scratch for the row's internal paths. */
typedef struct hb_huang_table_build {
    const float *sums, *deltas;
    int lattice;
    int generator[4];
    int row; /* the row's index: it keys the lattice's shifts */
    float *scratch; /* HB_HUANG_EXIT_FLOATS * 2 * lattice * (table panels + 1) floats */
} hb_huang_table_build;
#define HB_HUANG_EXIT_FLOATS 11

/* Uniform numbers an HHH22 sample of the R lobe alone reads (sec. 3.4.1). */
#define HB_HUANG_SAMPLE_DIMENSIONS 3

/* Numbers HHH22 sampling with TT or TRT reads per sample (sec. 3.4.1; src/models/huang/sample_paths.h). */
#define HB_HUANG_PATH_DIMENSIONS 8

/* Everything the HHH22 kernel reads, fixed at plan creation (docs/huang.md). The flags are
 * the same for every sample of a batch, so branching on them never depends on the data. */
typedef struct hb_huang {
    unsigned lobes;      /* bits R, TT, TRT */
    int beckmann;        /* NDF: 0 GGX (eq. 41), 1 Beckmann */
    int shadowing;       /* separable Smith G1(w_i) G1(w_o) against the mesonormal */
    int analytic;        /* R: App. A, eq. 43 (GGX, no G, circular); else Simpson */
    int step_rule;       /* R Simpson: 1 the paper's uniform steps in phi_m, 0 the peak-following variable */
    int panels;          /* R Simpson panels (even); for the step rule the most any window needs */
    int pdf_panels;      /* sampling pdf: Simpson panels in the peak-following variable (a multiple of 4) */
    int elliptical;      /* eqs. 26-28 */
    int tilted;          /* tau != 0: the mesonormal adds visibility conditions (eq. 40) */
    float step;          /* step rule: the largest phi_m step, r_step * roughness */
    float roughness, roughness2; /* r and r^2 */
    float c_rough;       /* C = sqrt(1 - r^2) of App. A */
    float one_minus_c;   /* 1 - C = r^2 / (1 + C) */
    float cos_tilt, sin_tilt; /* the mesonormal's inclination tau (sec. 3.2, eq. 39) */
    float cos_floor, inv_cos_floor; /* the least cos(theta) in eq. 10's projected width 2 cos(theta) (docs/huang.md) */
    hb_dielectric ior;
    float e2, b, b2;     /* eccentricity^2, the minor semi-axis b = sqrt(1 - e^2) and b^2 */
    /* TT and TRT by eqs. 31, 32: Simpson panels over the entry window, the counter-based
     * generator's keys (from the seed), absorption per unit radius */
    int tt_panels;
    uint32_t rng_key, rng_key2;
    float sigma_a[3];
    hb_huang_table table; /* values == NULL: TT and TRT by eqs. 31, 32 at every evaluation */
    int table_grid; /* the grid (table_build.c): the plan's quality's, or for HB_TT_TRT_AUTO the finest up to it that
                       builds in about a second */
    int table_too_costly; /* HB_TT_TRT_AUTO chose eqs. 31, 32: even the fast grid would take more than that */
} hb_huang;

#endif

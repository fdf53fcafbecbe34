/* The dual-scattering table (hb_dual_table): the terms of hb_dual_terms_grid at its theta nodes, in
 * double for the reference and as floats laid out for the kernels' gathers. Internal. */
#ifndef HB_DUAL_CONSTANTS_H
#define HB_DUAL_CONSTANTS_H

#include "hairbsdf.h"

/* A node's floats: per channel c the nine terms at c * HB_DUAL_PER_CHANNEL + term, then three of
 * padding, so that the kernels load one channel in three gathers of four (a channel at a time keeps
 * AVX2's sixteen registers from spilling). */
enum {
    HB_DUAL_A_F, HB_DUAL_A_B, HB_DUAL_ALPHA_F, HB_DUAL_BETA_F2, HB_DUAL_ALPHA_B, HB_DUAL_BETA_B2,
    HB_DUAL_A_BACK, HB_DUAL_DELTA_B, HB_DUAL_SIGMA_B2,
    HB_DUAL_PER_CHANNEL = 12,
    HB_DUAL_PER_NODE = 3 * HB_DUAL_PER_CHANNEL
};
_Static_assert(HB_DUAL_PER_NODE == HB_DUAL_NODE_FLOATS, "the shaders' layout is the kernels'");

struct hb_dual_kernels;

struct hb_dual_table {
    const struct hb_dual_kernels *kernels; /* the plan's ISA */
    hb_isa isa;
    int thetas;
    double d_f, d_b;
    hb_dual_terms *terms; /* thetas of them, at the midpoints -pi/2 + pi (k + 1/2) / thetas */
    float *nodes;         /* thetas x HB_DUAL_PER_NODE */
    hb_model model;       /* the plan's, and the fields section of its table files: what a saved */
    unsigned char *fields; /* table is checked against when it is loaded */
    size_t fields_size;
    int included;  /* 0: a tolerance or budget plan dropped the term, and the terms are zeros */
    double share;  /* the term's largest share of the fibre's energy (hb_dual_table_included) */
};

/* The table's terms at theta, the kernels' linear interpolation in double (src/dual/reference.c). */
void hb_dual_interpolate(const struct hb_dual_table *table, double theta, hb_dual_terms *terms);

/* f_DS in double from the terms at theta_i (src/dual/reference.c); visible: v. */
void hb_dual_radiance_reference(const hb_dual_terms *terms, double d_f, double d_b, double theta_i, double phi_i,
                                double theta_o, double phi_o, double fibres, double visible, double f[3]);

#endif

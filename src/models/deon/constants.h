/* What dFH11's kernels read from a plan, fixed at plan creation (src/models/deon/plan.c). */
#ifndef HB_DEON_CONSTANTS_H
#define HB_DEON_CONSTANTS_H

#include "hairbsdf.h"
#include "models/common/dielectric.h"
#include "models/common/longitudinal_constants.h"

/* dFH11 quadrature nodes a plan evaluates: gamma_i >= 0 of the largest order */
#define HB_MAX_NODES ((HB_MAX_QUADRATURE_ORDER + 1) / 2)

/* Uniform numbers a dFH11 sample reads (docs/sampling.md), and a near-field sample at a given h. */
#define HB_DEON_SAMPLE_DIMENSIONS 5
#define HB_DEON_NEAR_DIMENSIONS 4

/* dFH11's Gaussian detector D_p (eq. 11), a wrapped Gaussian (a Jacobi theta function),
 * truncated at plan creation to the cheaper of its two series for the tolerance. */
typedef struct hb_detector {
    int fourier;         /* 1: (1/2pi)(1 + 2 sum_{n<=terms} e^(-n^2 beta^2/2) cos(n x)); 0: Gaussians at x - 2 pi k, |k| <= terms */
    int terms;
    float log2e_over_two_beta2; /* direct series: log2(e) / (2 beta^2), the Gaussian as a power of 2 */
    float gauss_norm;    /* direct series: 1 / (beta sqrt(2 pi)) */
    float coeff[HB_MAX_DETECTOR_TERMS + 1]; /* Fourier series: coeff[0] = 1/(2 pi), coeff[n] = e^(-n^2 beta^2/2) / pi */
} hb_detector;

#define HB_LOBE_CHOICE_STEPS 32

/* The highest explicit order of dFH11's standard shape (azimuthal.h, deon_shape). */
#define HB_STANDARD_PMAX 3

/* A standard-shape detector in units of its own width (azimuthal.h, deon_fused_shaped): with
 * sigma = sqrt(log2(e) / (2 beta_n^2)), D_p(x) = gauss_norm 2^-(sigma x)^2, so the node sum works
 * with sigma |phi| and sigma Phi(p, h) = slope gamma_t + offset[j] (eq. 8 less whole turns). */
typedef struct hb_scaled_detector {
    float scale;                        /* sigma */
    float slope;                        /* 2 p sigma */
    float period_hi, period_lo, inv_period; /* 2 pi sigma as two floats, and 1 / (2 pi sigma) */
    float offset[HB_MAX_NODES];         /* sigma ((p mod 2) pi - 2 gamma_i) at node j */
} hb_scaled_detector;

/* Everything the dFH11 kernel reads, fixed at plan creation. */
typedef struct hb_deon {
    unsigned lobes; /* bits p <= pmax, and HB_LOBE_RESIDUAL */
    int pmax;
    int channels;   /* 3, or 1 for a grey fibre (sigma_a the same in every channel: one computed, copied) */
    int order; /* the Gauss-Legendre order across the fibre: in gamma_i over [-pi/2, pi/2], or mapped */
    int mapped; /* the quality rules' nodes, mapped (plan.c, HB_NODE_MAP); 0: the paper's rule in gamma_i */
    int standard; /* the default shape: pmax 3 (any lobe subset), every detector the nearest Gaussian
                   * alone, corrected absorption, R Fresnel per offset (azimuthal.h, deon_shape) */
    int nodes; /* its nodes with gamma_i >= 0: (order + 1) / 2 */
    int absorption_paper;
    int r_fresnel_offset; /* R uses eq. 14 per node instead of eq. 12 */
    hb_dielectric ior;
    float sigma_a_log2e[3]; /* sigma_a log2(e): absorption as a power of 2 */
    /* the rule's nodes with gamma_i >= 0 (h = sin gamma_i), each detected at phi and -phi; weights
     * include eq. 10's 1/2 and dh/dgamma (plan.c, deon_nodes) */
    float gamma_i[HB_MAX_NODES], cos_gamma_i[HB_MAX_NODES], h[HB_MAX_NODES], weight[HB_MAX_NODES];
    hb_detector detector[HB_MAX_LOBES];
    hb_scaled_detector scaled[HB_STANDARD_PMAX + 1]; /* the standard shape's detectors, per node */
    int asin_narrow; /* eta >= 4/3: gamma_t = asin(h / eta') by vf_asin_narrow (|h / eta'| <= 3/4) */
    int fourier_terms; /* the most Fourier terms any lobe's detector uses (cos(n phi) to precompute) */
    hb_longitudinal longitudinal[HB_MAX_LOBES + 1]; /* index HB_LOBE_RESIDUAL: the residual lobe */
    hb_lobe_lanes lobe_lanes; /* the standard shape's float M_p constants, a lobe per lane */
    /* lobes whose M_p is the same function (same v and shift) share one evaluation: m_group[p]
     * is the first included lobe with p's constants, and M_p is evaluated for it alone */
    int m_group[HB_MAX_LOBES + 1];
    /* sampling (docs/sampling.md): a node is picked with probability weight_j / sum(weight), by
     * its cumulative node_cdf; node_half_probability[j] is half that probability */
    float node_cdf[HB_MAX_NODES], node_half_probability[HB_MAX_NODES];
    float beta_n[HB_MAX_LOBES]; /* the detector's standard deviation per lobe */
    /* the lobe-choice weights c_p(theta_o) of the longitudinal mixture, per M_p group (zero for
     * lobes that are not group leaders), tabulated at |theta_o| = k pi / (2 HB_LOBE_CHOICE_STEPS) */
    float lobe_choice[HB_MAX_LOBES + 1][HB_LOBE_CHOICE_STEPS + 2];
    float exp_minus_two_inv_v[HB_MAX_LOBES + 1]; /* e^(-2/v) per lobe, for sampling M_p */
    /* the M_p groups' leaders in increasing order: group_leader[0 .. groups) */
    int groups, group_leader[HB_MAX_LOBES + 1];
    /* HB_AZIMUTHAL_TABLE (src/models/deon/table_build.c): N of each M_p group, [sqrt(cos(theta_d)) node][|phi| node][slot][rgb],
     * NULL for the quadrature; slot s holds group leader group_leader[s] */
    const float *np_table;
    int table_cd, table_phi;
    /* HB_AZIMUTHAL_COLOUR_TABLE (src/models/deon/colour_table.c): one channel per slot over a third axis,
     * w = log(1 + sigma_a / knee) / log(1 + sigma_max / knee) in [0, 1] in table_absorption nodes,
     * [cd][phi][w][slot]; 0 nodes for a material's own table */
    int table_absorption;
    float table_sigma_scale; /* ln(2) / knee: times sigma_a log2(e), sigma_a / knee */
    float table_w_scale;     /* (nodes - 1) / log(1 + sigma_max / knee): the node coordinate per unit of the log */
} hb_deon;

/* Whether lobe p (an order up to pmax, or the residual) is in the plan's dFH11 sum, and whether it
 * is the first lobe of its M_p group (the one whose M_p is evaluated). */
static inline int hb_deon_lobe_on(const hb_deon *d, int p)
{
    return (d->lobes >> p & 1u) && (p <= d->pmax || p == HB_LOBE_RESIDUAL);
}
static inline int hb_deon_group_leader(const hb_deon *d, int p) { return hb_deon_lobe_on(d, p) && d->m_group[p] == p; }

#endif

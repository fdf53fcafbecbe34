/* The tables of kernels each ISA's translation units export (src/isa/kernels.c and each
 * model's kernels.c), and the plain constants those kernels read from a plan. Internal. */
#ifndef HB_KERNELS_H
#define HB_KERNELS_H

#include <stddef.h>
#include <stdint.h>
#include "hairbsdf.h"

/* dFH11 quadrature nodes a plan evaluates: gamma_i >= 0 of the largest order */
#define HB_MAX_NODES ((HB_MAX_QUADRATURE_ORDER + 1) / 2)

/* Constants of one lobe's longitudinal function, fixed at plan creation. */
typedef struct hb_longitudinal {
    double inv_v;     /* 1 / v, v = beta_m^2 */
    double log_norm;  /* log(1 / (v (1 - e^(-2/v)))), the csch factor of dFH11 eq. 7 without e^(-1/v) */
    double shift;     /* alpha_p: M_p is evaluated at theta_o - shift (dFH11 sec. 6) */
    double cos_shift, sin_shift;
    /* Below HB_QUALITY_HIGH M_p is formed in float (docs/deon.md): the same
     * constants rounded, and the shift c of theta_o'' = sign * theta_o - c as a float pair
     * c_hi + c_lo for the three cases of the pole reflection (none, above pi/2, below -pi/2). */
    int single;
    float inv_v_f, cos_shift_f, sin_shift_f;
    float inv_v_log2e_f, log2_norm_f; /* log2(e) / v and log2(norm), for the float path's 2^-t */
    float shift_hi[3], shift_lo[3];
} hb_longitudinal;

/* MJC03's unit-area Gaussian M_p = g(mean, beta; theta_h). */
typedef struct hb_gaussian_lobe {
    float mean;          /* alpha_p, the shift of the lobe in theta_h */
    float log2e_over_two_beta2; /* log2(e) / (2 beta^2): g = norm 2^-(x^2 log2e_over_two_beta2) */
    float norm;          /* 1 / (beta sqrt(2 pi)) */
} hb_gaussian_lobe;

/* Everything the MJC03 kernel reads, fixed at plan creation (docs/marschner.md). */
typedef struct hb_marschner {
    unsigned lobes;       /* bits R, TT, TRT */
    int absorption_paper;
    /* per lobe p (TT, TRT), from the smallest eta' the plan can see (eta, or min eta*):
     * folds[p]: the cubic can have three real roots (eta' < fold_index[p] = 1 / sin(pi / 3p));
     * caustic[p]: the caustic treatment can be non-zero (eta' < fold_index[p] + caustic_fade) */
    int folds[3], caustic[3];
    float fold_index[3];
    int trt_branches;     /* 1, or 3 when TRT's cubic spans more than 2 pi (eta* near 1): phi + 2 pi k, |k| <= 1 */
    int eccentric;        /* TRT sees eta*(phi_h) (MJC03), not eta */
    float eta, eta2_minus_one; /* eta and eta^2 - 1 (formed in double) */
    float eta_star_excess, eta_star_swing; /* eta* - 1 = excess + swing cos(2 phi_h) = excess + swing cos(phi_i + phi_o), excess = mean - 1 in double */
    float sigma_a_log2e[3]; /* sigma_a log2(e), for the transmittances 2^-(mu' log2 e l) */
    hb_gaussian_lobe lobe[3];
    float caustic_log2e_over_two_w2, caustic_norm, caustic_width; /* the fade and glint Gaussian g(w_c; x) */
    float inv_caustic_fade, caustic_limit, glint_scale;
} hb_marschner;

/* A dielectric interface of index eta > 1, with eta^2 - 1 formed in double so that Fresnel keeps
 * its relative accuracy as eta -> 1 (the float eta alone holds eta - 1 to 1.7e-4 at eta 1.0001). */
typedef struct hb_dielectric {
    float eta, inv_eta2, eta2_minus_1;
} hb_dielectric;

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
} hb_huang_table;

/* What the table builder needs besides the plan's constants: the grid of one row (s and delta at
 * every node), the lattice points per Simpson node, and scratch for the row's internal paths. */
typedef struct hb_huang_table_build {
    const float *sums, *deltas;
    int lattice;
    float *scratch; /* HB_HUANG_EXIT_FLOATS * 2 * lattice * (tt_panels + 1) floats */
} hb_huang_table_build;
#define HB_HUANG_EXIT_FLOATS 11

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
    hb_dielectric ior;
    float e2, b, b2;     /* eccentricity^2, the minor semi-axis b = sqrt(1 - e^2) and b^2 */
    /* TT and TRT by eqs. 31, 32: Simpson panels over the entry window, the counter-based
     * generator's keys (from the seed), absorption per unit radius */
    int tt_panels;
    uint32_t rng_key, rng_key2;
    float sigma_a[3];
    hb_huang_table table; /* values == NULL: TT and TRT by eqs. 31, 32 at every evaluation */
} hb_huang;

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
    /* HB_AZIMUTHAL_TABLE (src/deon_table.c): N of each M_p group, [sqrt(cos(theta_d)) node][|phi| node][slot][rgb],
     * NULL for the quadrature; slot s holds group leader table_leader[s] */
    const float *np_table;
    int table_cd, table_phi, table_slots;
    int table_leader[HB_MAX_LOBES + 1];
} hb_deon;

/* Whether lobe p (an order up to pmax, or the residual) is in the plan's dFH11 sum, and whether it
 * is the first lobe of its M_p group (the one whose M_p is evaluated). */
static inline int hb_deon_lobe_on(const hb_deon *d, int p)
{
    return (d->lobes >> p & 1u) && (p <= d->pmax || p == HB_LOBE_RESIDUAL);
}
static inline int hb_deon_group_leader(const hb_deon *d, int p) { return hb_deon_lobe_on(d, p) && d->m_group[p] == p; }

/* Functions of src/math/vmath.h exported for the accuracy tests. */
typedef enum hb_math_fn {
    HB_FN_EXP, HB_FN_EXP_FLUSH, HB_FN_EXP2_NEG, HB_FN_LOG, HB_FN_LOG1P, HB_FN_SIN, HB_FN_COS, HB_FN_ASIN, HB_FN_ASIN_NARROW, HB_FN_ACOS,
    HB_FN_ATAN2, HB_FN_SQRT, HB_FN_I0, HB_FN_I0E, HB_FN_LOG_I0, HB_FN_COUNT
} hb_math_fn;

typedef void (*hb_longitudinal_angles_fn)(const hb_longitudinal *lobe, size_t n, hb_angles_soa in,
                                          float *out, size_t *invalid);
typedef void (*hb_longitudinal_vectors_fn)(const hb_longitudinal *lobe, size_t n, hb_vectors_soa in,
                                           float *out, size_t *invalid);

typedef void (*hb_gaussian_angles_fn)(const hb_gaussian_lobe *lobe, size_t n, hb_angles_soa in, float *out,
                                      size_t *invalid);
typedef void (*hb_gaussian_vectors_fn)(const hb_gaussian_lobe *lobe, size_t n, hb_vectors_soa in, float *out,
                                       size_t *invalid);
typedef void (*hb_marschner_angles_fn)(const hb_marschner *mjc, size_t n, hb_angles_soa in, hb_rgb_soa out,
                                       size_t *invalid);
typedef void (*hb_marschner_vectors_fn)(const hb_marschner *mjc, size_t n, hb_vectors_soa in, hb_rgb_soa out,
                                        size_t *invalid);
typedef void (*hb_deon_angles_fn)(const hb_deon *deon, size_t n, hb_angles_soa in, hb_rgb_soa out,
                                  size_t *invalid);
typedef void (*hb_deon_vectors_fn)(const hb_deon *deon, size_t n, hb_vectors_soa in, hb_rgb_soa out,
                                   size_t *invalid);
typedef void (*hb_deon_sample_fn)(const hb_deon *deon, size_t n, hb_sample_in in, hb_sample_out out,
                                  size_t *invalid);
typedef void (*hb_deon_pdf_fn)(const hb_deon *deon, size_t n, hb_angles_soa in, float *pdf, size_t *invalid);

typedef void (*hb_huang_angles_fn)(const hb_huang *huang, size_t n, hb_angles_soa in, hb_rgb_soa out,
                                   size_t *invalid);
typedef void (*hb_huang_vectors_fn)(const hb_huang *huang, size_t n, hb_vectors_soa in, hb_rgb_soa out,
                                    size_t *invalid);
typedef void (*hb_huang_sample_fn)(const hb_huang *huang, size_t n, hb_sample_in in, hb_sample_out out,
                                   size_t *invalid);
typedef void (*hb_huang_pdf_fn)(const hb_huang *huang, size_t n, hb_angles_soa in, float *pdf, size_t *invalid);
/* One table row (theta_i, phi_i): n_sum * n_delta * 3 values. */
typedef void (*hb_huang_table_row_fn)(const hb_huang *huang, float theta_i, float phi_i, const hb_huang_table_build *build,
                                      float *row);

typedef void (*hb_deon_np_row_fn)(const hb_deon *deon, float cos_theta_d, size_t n, const float *phi, float *out);

/* Each model's kernels for one ISA (src/models/<model>/kernels.c, compiled once per ISA). */
typedef struct hb_deon_kernels {
    hb_longitudinal_angles_fn longitudinal_angles[2];   /* indexed by hb_i0 */
    hb_longitudinal_vectors_fn longitudinal_vectors[2]; /* indexed by hb_i0 */
    hb_deon_angles_fn angles[2];                        /* indexed by hb_i0 */
    hb_deon_vectors_fn vectors[2];
    hb_deon_sample_fn sample[2];
    hb_deon_pdf_fn pdf[2];
    hb_deon_np_row_fn np_row; /* one row of the N_p table, out[(k * slots + s) * 3 + c] */
    void (*detector_map)(const hb_detector *d, size_t n, const float *x, float *out); /* D_p(x), for tests */
} hb_deon_kernels;

typedef struct hb_marschner_kernels {
    hb_gaussian_angles_fn longitudinal_angles;
    hb_gaussian_vectors_fn longitudinal_vectors;
    hb_marschner_angles_fn angles;
    hb_marschner_vectors_fn vectors;
    /* the real roots of gamma^3 + P gamma + Q = 0 the kernels find, for tests: roots[3 * i + k],
     * NaN where root k does not exist */
    void (*cubic_map)(size_t n, const float *P, const float *Q, float *roots);
} hb_marschner_kernels;

typedef struct hb_huang_kernels {
    hb_huang_angles_fn angles;
    hb_huang_vectors_fn vectors;
    hb_huang_sample_fn sample;
    hb_huang_pdf_fn pdf;
    hb_huang_table_row_fn table_row;
} hb_huang_kernels;

/* One ISA's kernels (src/isa/kernels.c). */
typedef struct hb_kernels {
    hb_isa isa;
    int width; /* float lanes */
    const hb_deon_kernels *deon;
    const hb_marschner_kernels *marschner;
    const hb_huang_kernels *huang;
    void (*math_map)(hb_math_fn fn, size_t n, const float *a, const float *b, float *out);
} hb_kernels;

/* NULL when the ISA is not compiled in or not supported by this CPU. */
const hb_kernels *hb_kernels_for(hb_isa isa);

#endif

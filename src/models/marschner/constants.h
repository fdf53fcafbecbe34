/* What MJC03's kernels read from a plan, fixed at plan creation (src/models/marschner/plan.c). */
#ifndef HB_MARSCHNER_CONSTANTS_H
#define HB_MARSCHNER_CONSTANTS_H

#include "hairbsdf.h"

/* MJC03's unit-area Gaussian M_p = g(mean, beta; theta_h). */
typedef struct hb_gaussian_lobe {
    float mean;          /* alpha_p, the shift of the lobe in theta_h */
    float log2e_over_two_beta2; /* log2(e) / (2 beta^2): g = norm 2^-(x^2 log2e_over_two_beta2) */
    float norm;          /* 1 / (beta sqrt(2 pi)) */
    float beta;          /* the width: theta_i = 2 theta_h - theta_o has mean 2 mean - theta_o and width 2 beta */
} hb_gaussian_lobe;

/* Uniform numbers an MJC03 sample reads (docs/sampling.md). */
#define HB_MARSCHNER_SAMPLE_DIMENSIONS 3

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
    float lobe_probability[3]; /* sampling (sample.h): lobe p is drawn with this probability */
} hb_marschner;

#endif

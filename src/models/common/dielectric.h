/* The smooth interface the dFH11 and HHH22 kernels share (fresnel.h evaluates it). */
#ifndef HB_MODELS_DIELECTRIC_H
#define HB_MODELS_DIELECTRIC_H


/* A dielectric interface of index eta > 1, with eta^2 - 1 formed in double so that Fresnel keeps
 * its relative accuracy as eta -> 1 (the float eta alone holds eta - 1 to 1.7e-4 at eta 1.0001). */
typedef struct hb_dielectric {
    float eta, inv_eta2, eta2_minus_1;
} hb_dielectric;

#endif

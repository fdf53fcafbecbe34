/* CBTB16's double-precision reference (reference*.c of this folder): the paper's equations in
 * double, sharing nothing with the kernels but the equations; reached through hb_ref_chiang_ops.
 * Internal. */
#ifndef HB_CHIANG_REFERENCE_H
#define HB_CHIANG_REFERENCE_H

#include "models/interface/plan.h"
#include "ref/reference.h"

extern const hb_reference_ops hb_ref_chiang_ops;

/* CBTB16: f near-field at h and the far field (the mean over h, adaptive), each
 * with its sampler's pdf (pdf may be NULL); the kernels' sampler in double at h from four numbers. */
void hb_ref_chiang_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                        double f[3], double *pdf);
void hb_ref_chiang_far(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o,
                       double f[3], double *pdf);
void hb_ref_chiang_sample_near(const hb_plan *plan, double theta_o, double phi_o, double h, const double u[4],
                               double *theta_i, double *phi_i);

#endif

/* CBTB16's operations (model.c) and the parts they call across the model's folder. Internal. */
#ifndef HB_CHIANG_CHIANG_H
#define HB_CHIANG_CHIANG_H

#include "kernels.h"
#include "models/interface/model.h"

hb_status hb_chiang_validate(const hb_material *m, const hb_options *o, hb_error *error); /* plan.c */
hb_status hb_chiang_derive(hb_plan *plan, hb_error *error);
/* The least beta_m, rounded up to 5 digits, whose TT lobe has v_TT = v_R / 4 >= 1e-6, the least variance
 * where M_p's accuracy is tested (test_chiang checks the rounding). */
#define HB_CHIANG_BETA_M_MIN 0.0027464

/* CBTB16's roughness fits (pbrt-v4's HairBxDF): the R lobe's variance v_R from beta_m and the
 * logistic scale s from beta_n, both in [0, 1]. */
double hb_chiang_variance_r(double beta_m);
double hb_chiang_logistic_scale(double beta_n);
void hb_chiang_look(const hb_material *m, hb_look *look); /* look.c */
hb_status hb_chiang_set_look(const hb_look *look, hb_material *m, hb_error *error);

#endif

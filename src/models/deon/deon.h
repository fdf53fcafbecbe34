/* dFH11's operations (model.c) and the parts they call across the model's folder. Internal. */
#ifndef HB_DEON_DEON_H
#define HB_DEON_DEON_H

#include "kernels.h"
#include "models/interface/model.h"

hb_status hb_deon_validate(const hb_material *m, const hb_options *o, hb_error *error); /* plan.c */
hb_status hb_deon_derive(hb_plan *plan, hb_error *error);
void hb_deon_release(hb_plan *plan);
void hb_deon_derive_sampling(hb_plan *plan);                       /* sample_plan.c */
hb_status hb_deon_build_table(hb_plan *plan, hb_error *error);    /* table_build.c */
hb_status hb_deon_table_view(const hb_plan *plan, hb_table_view *view, int *channels); /* table_build.c */
hb_status hb_deon_build_colour_table(hb_plan *plan, hb_error *error);                  /* colour_table.c */
hb_status hb_deon_colour_table_view(const hb_plan *plan, hb_table_view *view, int *channels);
hb_status hb_deon_shader_constants(const hb_plan *plan, float *constants); /* table_build.c */
void hb_deon_look(const hb_material *m, hb_look *look); /* look.c */
hb_status hb_deon_set_look(const hb_look *look, hb_material *m, hb_error *error);

#endif

/* HHH22's operations (model.c) and the parts they call across the model's folder. Internal. */
#ifndef HB_HUANG_HUANG_H
#define HB_HUANG_HUANG_H

#include "kernels.h"
#include "models/interface/model.h"

hb_status hb_huang_validate(const hb_material *m, const hb_options *o, hb_error *error); /* plan.c */
hb_status hb_huang_derive(hb_plan *plan, hb_error *error);
/* Simpson panels over TT and TRT's entry window at a quality's step (options.tt_panels if set). */
int hb_huang_tt_panels(const hb_options *o, hb_quality quality, double roughness);
void hb_huang_release(hb_plan *plan);
hb_status hb_huang_build_table(hb_plan *plan, hb_error *error);    /* table_build.c */
int hb_huang_table_fits(hb_plan *plan);                           /* its build takes about a second at most */
int hb_huang_table_grid_of(hb_quality quality);                   /* a quality's own table grid */
hb_status hb_huang_table_view(const hb_plan *plan, hb_table_view *view, int *channels);
hb_status hb_huang_shader_constants(const hb_plan *plan, float *constants); /* table_build.c */
void hb_huang_look(const hb_material *m, hb_look *look); /* look.c */
hb_status hb_huang_set_look(const hb_look *look, hb_material *m, hb_error *error);

#endif

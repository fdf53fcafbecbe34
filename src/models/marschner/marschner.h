/* MJC03's operations (model.c) and the parts they call across the model's folder. Internal. */
#ifndef HB_MARSCHNER_MARSCHNER_H
#define HB_MARSCHNER_MARSCHNER_H

#include "kernels.h"
#include "models/interface/model.h"

hb_status hb_marschner_validate(const hb_material *m, const hb_options *o, hb_error *error); /* plan.c */
hb_status hb_marschner_derive(hb_plan *plan, hb_error *error);
void hb_marschner_look(const hb_material *m, hb_look *look); /* look.c */
hb_status hb_marschner_set_look(const hb_look *look, hb_material *m, hb_error *error);

#endif

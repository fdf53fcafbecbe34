/* Plan creation (src/plan/): the checks every model shares, the plan built through its model's
 * operations, and the configuration a tolerance or budget plan chooses. Internal. */
#ifndef HB_PLAN_CREATION_H
#define HB_PLAN_CREATION_H

#include "models/interface/model.h"

/* A plan for the caller's structs (of this header's or an older one's size): validated, its ISA
 * resolved, its configuration chosen for a tolerance or budget, built (create.c). */
hb_status hb_plan_make(const hb_material *material, const hb_options *options, hb_plan **out, hb_error *error);

/* The caller's material (of this header's or an older one's size) at this header's size (create.c). */
hb_status hb_material_upgrade(const hb_material *material, hb_material *out, hb_error *error);

/* The plan of validated, concrete options on an ISA; selection (NULL for a plain plan) is what
 * chose them (create.c). hb_plan_free releases one. */
hb_status hb_plan_build(const hb_material *material, const hb_options *options, hb_isa isa,
                        const hb_selection *selection, hb_plan **out, hb_error *error);
void hb_plan_free(hb_plan *plan);

/* The material's and options' ranges, then the model's own checks (validate.c). */
hb_status hb_plan_validate(const hb_material *m, const hb_options *o, hb_error *error);

/* A tolerance or budget plan's options (select.c); the calibrated figures of any plan's
 * configuration (0 when it has none). */
hb_status hb_plan_select(const hb_material *m, const hb_options *in, hb_isa isa, hb_options *out, hb_selection *sel,
                         hb_error *error);
int hb_plan_expected(const hb_plan *plan, char *configuration, size_t size, double *ns, double *err);

#endif

/* Public plan entry points: argument checks, then plan creation (src/plan/). */
#include "plan/creation.h"

hb_status hb_plan_create(const hb_material *material, const hb_options *options, hb_plan **out, hb_error *error)
{
    if (error) {
        error->status = HB_OK;
        error->message[0] = '\0';
    }
    if (!out)
        return hb_plan_fail(error, HB_ERR_NULL, "plan output pointer is NULL");
    *out = NULL;
    if (!material || !options)
        return hb_plan_fail(error, HB_ERR_NULL, "%s is NULL", material ? "options" : "material");
    return hb_plan_make(material, options, out, error);
}

void hb_plan_destroy(hb_plan *plan) { hb_plan_free(plan); }

hb_isa hb_plan_isa(const hb_plan *plan) { return plan ? plan->isa : HB_ISA_SCALAR; }

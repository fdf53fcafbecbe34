/* hb_plan_table: the view of a plan's table that engines bake, from its model. */
#include "models/model.h"

hb_status hb_plan_table(const hb_plan *plan, hb_table_view *v)
{
    if (!plan || !v)
        return HB_ERR_NULL;
    *v = (hb_table_view){ .model = plan->options.model };
    hb_status st = hb_model_ops_of(plan->options.model)->table(plan, v);
    if (st != HB_OK)
        return st;
    v->count = (size_t)v->slots * 3;
    for (int k = 0; k < v->axes; k++)
        v->count *= (size_t)v->size[k];
    return HB_OK;
}

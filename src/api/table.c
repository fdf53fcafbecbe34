/* hb_plan_table: the view of a plan's table that engines bake, from its model; hb_table_save: that
 * table as a table file (src/models/file/table_file.c); hb_plan_shader_constants: what the shaders read
 * beside it. */
#include "models/interface/model.h"
#include "models/file/table_file.h"

hb_status hb_plan_table(const hb_plan *plan, hb_table_view *v)
{
    if (!plan || !v)
        return HB_ERR_NULL;
    *v = (hb_table_view){ .model = plan->options.model };
    int channels;
    hb_status st = hb_model_ops_of(plan->options.model)->table(plan, v, &channels);
    if (st != HB_OK)
        return st;
    v->count = hb_table_count(v, channels);
    return HB_OK;
}

int hb_plan_table_channels(const hb_plan *plan)
{
    hb_table_view v;
    int channels = 0;
    return plan && hb_model_ops_of(plan->options.model)->table(plan, &v, &channels) == HB_OK ? channels : 0;
}

hb_status hb_table_save(const hb_plan *plan, void *bytes, size_t capacity, size_t *size)
{
    if (!plan || !size)
        return HB_ERR_NULL;
    hb_table_view v;
    hb_status st = hb_plan_table(plan, &v);
    if (st != HB_OK)
        return st;
    int channels = hb_plan_table_channels(plan);
    *size = hb_table_file_write(plan, &v, channels, NULL);
    if (!bytes)
        return HB_OK;
    if (capacity < *size)
        return HB_ERR_PARAM;
    hb_table_file_write(plan, &v, channels, bytes);
    return HB_OK;
}

hb_status hb_plan_shader_constants(const hb_plan *plan, float constants[HB_SHADER_CONSTANTS])
{
    if (!plan || !constants)
        return HB_ERR_NULL;
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    if (!ops->shader_constants)
        return HB_ERR_UNSUPPORTED;
    for (int k = 0; k < HB_SHADER_CONSTANTS; k++)
        constants[k] = 0.0f;
    return ops->shader_constants(plan, constants);
}

/* hb_plan_table: the view of a plan's table that engines bake, from its model; hb_table_save: that
 * table as a table file (src/models/file/table_file.c); hb_plan_shader_constants: what the shaders read
 * beside it. */
#include <stddef.h>
#include <string.h>

#include "checks.h"
#include "models/interface/model.h"
#include "models/file/table_file.h"

/* The plan's table, whole: HB_ERR_UNSUPPORTED (with its message) when it has none. */
static hb_status table_of(const char *call, const hb_plan *plan, hb_table_view *v, int *channels)
{
    *v = (hb_table_view){ .struct_size = sizeof *v, .model = plan->options.model };
    hb_status st = hb_model_ops_of(plan->options.model)->table(plan, v, channels);
    if (st != HB_OK)
        return hb_api_unsupported(call, plan, "table (dFH11 and HHH22 plans with one, docs/engines.md)");
    v->count = hb_table_count(v, *channels);
    return HB_OK;
}

hb_status hb_plan_table(const hb_plan *plan, hb_table_view *view)
{
    if (!plan || !view)
        return hb_fail_null(__func__, !plan ? "plan" : "view");
    size_t size = view->struct_size;
    hb_status st = hb_api_struct_size(__func__, "view", size, offsetof(hb_table_view, error) + sizeof view->error,
                                      sizeof *view);
    if (st != HB_OK)
        return st;
    hb_table_view v;
    int channels;
    st = table_of(__func__, plan, &v, &channels);
    if (st == HB_OK)
        memcpy(view, &v, size);
    return st;
}

int hb_plan_table_channels(const hb_plan *plan)
{
    hb_table_view v = { .struct_size = sizeof v };
    int channels = 0;
    return plan && hb_model_ops_of(plan->options.model)->table(plan, &v, &channels) == HB_OK ? channels : 0;
}

hb_status hb_table_save(const hb_plan *plan, void *bytes, size_t capacity, size_t *size)
{
    if (!plan || !size)
        return hb_fail_null(__func__, !plan ? "plan" : "size");
    hb_table_view v;
    int channels;
    hb_status st = table_of(__func__, plan, &v, &channels);
    if (st != HB_OK)
        return st;
    *size = hb_table_file_write(plan, &v, channels, NULL);
    if (!bytes)
        return HB_OK;
    if (capacity < *size)
        return hb_fail(HB_ERR_BUFFER, "%s: the table file takes %zu bytes, capacity is %zu (*size has the length)",
                       __func__, *size, capacity);
    hb_table_file_write(plan, &v, channels, bytes);
    return HB_OK;
}

hb_status hb_plan_shader_constants(const hb_plan *plan, float constants[HB_SHADER_CONSTANTS])
{
    if (!plan || !constants)
        return hb_fail_null(__func__, !plan ? "plan" : "constants");
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    for (int k = 0; k < HB_SHADER_CONSTANTS; k++)
        constants[k] = 0.0f;
    hb_status st = ops->shader_constants ? ops->shader_constants(plan, constants) : HB_ERR_UNSUPPORTED;
    if (st != HB_OK)
        return hb_api_unsupported(__func__, plan, "shader constants (dFH11 table plans, HHH22 with the analytic GGX R "
                                  "lobe without G; docs/engines.md)");
    return HB_OK;
}

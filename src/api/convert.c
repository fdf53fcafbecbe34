/* hb_material_convert: a material's look carried from one model's parameters to another's through
 * each model's look (models/interface/model.h). */
#include "models/interface/model.h"
#include "plan/creation.h"

static int has_overrides(const hb_material *m)
{
    for (int p = 0; p < HB_MAX_LOBES; p++)
        if (m->lobe_beta_m[p] != 0.0 || m->lobe_beta_n[p] != 0.0)
            return 1;
    return m->lobe_alpha_override != 0u;
}

hb_status hb_material_convert(const hb_material *material, hb_model from, hb_model to, hb_material *converted,
                              hb_error *error)
{
    if (!material || !converted)
        return hb_plan_fail(error, HB_ERR_NULL, "%s: %s is NULL", __func__, !material ? "material" : "converted");
    const hb_model_ops *source = hb_model_ops_of(from), *target = hb_model_ops_of(to);
    if (!source || !target)
        return hb_plan_fail(error, HB_ERR_PARAM, "%s: model %d is not an hb_model", __func__, !source ? (int)from : (int)to);
    hb_material m;
    hb_status st = hb_material_upgrade(material, &m, error);
    if (st != HB_OK)
        return st;
    if (from != to && has_overrides(&m))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "%s: per-lobe overrides (lobe_beta_m, lobe_beta_n, "
                            "lobe_alpha_override) are in the %s model's own terms; convert them by hand", __func__,
                            source->name);
    hb_look look;
    source->look(&m, &look);
    st = target->set_look(&look, &m, error);
    if (st == HB_OK)
        *converted = m;
    return st;
}

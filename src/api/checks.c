/* Refusals of the entry points, worded for hb_last_error. */
#include "checks.h"
#include "models/interface/model.h"

hb_status hb_api_unsupported(const char *call, const hb_plan *plan, const char *what)
{
    return hb_fail(HB_ERR_UNSUPPORTED, "%s: this %s plan (term %s, quality %s) offers no %s; docs/api.md's matrix lists "
                   "which plans do", call, hb_model_ops_of(plan->options.model)->name,
                   plan->options.term == HB_TERM_FULL ? "full" : "longitudinal", hb_quality_name(plan->options.quality),
                   what);
}

hb_status hb_api_present(const char *call, size_t n, int count, const void *const *planes, const char *const *names)
{
    for (int k = 0; n && k < count; k++)
        if (!planes[k])
            return hb_fail_null(call, names[k]);
    return HB_OK;
}

hb_status hb_api_angles_missing(const char *call, const hb_angles_soa *in)
{
    const void *planes[] = { in->theta_i, in->phi_i, in->theta_o, in->phi_o };
    static const char *const names[] = { "in.theta_i", "in.phi_i", "in.theta_o", "in.phi_o" };
    return hb_api_present(call, 1, 4, planes, names);
}

hb_status hb_api_vectors_missing(const char *call, const hb_vectors_soa *in)
{
    const void *planes[] = { in->wi_x, in->wi_y, in->wi_z, in->wo_x, in->wo_y, in->wo_z };
    static const char *const names[] = { "in.wi_x", "in.wi_y", "in.wi_z", "in.wo_x", "in.wo_y", "in.wo_z" };
    return hb_api_present(call, 1, 6, planes, names);
}

hb_status hb_api_near_missing(const char *call, const hb_near_soa *in)
{
    const void *planes[] = { in->theta_i, in->phi_i, in->theta_o, in->phi_o, in->h };
    static const char *const names[] = { "in.theta_i", "in.phi_i", "in.theta_o", "in.phi_o", "in.h" };
    return hb_api_present(call, 1, 5, planes, names);
}

hb_status hb_api_rgb_missing(const char *call, const char *name, const hb_rgb_soa *rgb)
{
    return hb_fail(HB_ERR_NULL, "%s: %s.%c is NULL", call, name, !rgb->r ? 'r' : !rgb->g ? 'g' : 'b');
}

hb_status hb_api_struct_size(const char *call, const char *name, size_t size, size_t least, size_t own)
{
    if (size >= least && size <= own)
        return HB_OK;
    return hb_fail(HB_ERR_VERSION, "%s: %s->struct_size is %zu; this library's has %zu bytes (set it to sizeof)", call,
                   name, size, own);
}

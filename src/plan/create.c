/* Plan creation: the caller's structs brought to this header's size, validated, the ISA resolved,
 * a tolerance or budget plan's configuration chosen, and the plan built by its model's derive.
 * Everything that depends only on the material is computed here, once, in double precision. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "creation.h"

/* A struct from an older header is a prefix of this one (releases only append fields): its
 * struct_size bytes go over `out`, which holds the defaults. A larger size comes from a newer
 * header, whose fields this library cannot honour. */
static hb_status upgrade_struct(const char *name, const void *in, size_t size, void *out, size_t own_size,
                                size_t alignment, hb_error *error)
{
    if (size > own_size)
        return hb_plan_fail(error, HB_ERR_VERSION,
                            "%s.struct_size is %zu, larger than this library's %zu: the program was built against a "
                            "newer hairbsdf.h (this library is " HB_VERSION_STRING ")", name, size, own_size);
    if (size < 2 * sizeof(size_t) || size % alignment)
        return hb_plan_fail(error, HB_ERR_VERSION, "%s.struct_size is %zu, which no release had (%s_default sets it)",
                            name, size, name);
    memcpy(out, in, size);
    return HB_OK;
}

hb_status hb_material_upgrade(const hb_material *material, hb_material *m, hb_error *error)
{
    hb_material_default(m);
    hb_status st = upgrade_struct("hb_material", material, material->struct_size, m, sizeof *m, _Alignof(hb_material), error);
    m->struct_size = sizeof *m;
    return st;
}

static hb_status upgrade_structs(const hb_material *material, const hb_options *options, hb_material *m,
                                 hb_options *o, hb_error *error)
{
    hb_options_default(o);
    hb_status st = hb_material_upgrade(material, m, error);
    if (st == HB_OK)
        st = upgrade_struct("hb_options", options, options->struct_size, o, sizeof *o, _Alignof(hb_options), error);
    o->struct_size = sizeof *o;
    return st;
}

/* HB_ISA_AUTO resolves to $HB_ISA if set, else the best available. */
static hb_status resolve_isa(hb_isa requested, hb_isa *isa, hb_error *error)
{
    const char *env = getenv("HB_ISA");
    if (requested == HB_ISA_AUTO && env && *env) {
        requested = hb_isa_from_name(env);
        if (requested == HB_ISA_COUNT || requested == HB_ISA_AUTO)
            return hb_plan_fail(error, HB_ERR_ISA, "HB_ISA=%s is not one of scalar, sse4.1, avx2, avx512, neon", env);
    }
    if (requested == HB_ISA_AUTO)
        requested = hb_isa_best();
    if (!hb_isa_available(requested))
        return hb_plan_fail(error, HB_ERR_ISA, "instruction set %s is not available on this CPU or build",
                    hb_isa_name(requested));
    *isa = requested;
    return HB_OK;
}

hb_status hb_plan_make(const hb_material *given_material, const hb_options *given_options, hb_plan **out,
                       hb_error *error)
{
    hb_material material_copy;
    hb_options options_copy;
    hb_status st = upgrade_structs(given_material, given_options, &material_copy, &options_copy, error);
    if (st != HB_OK)
        return st;
    const hb_material *material = &material_copy;
    const hb_options *options = &options_copy;
    st = hb_plan_validate(material, options, error);
    hb_isa isa = HB_ISA_SCALAR;
    if (st == HB_OK && options->quality != HB_QUALITY_REFERENCE)
        st = resolve_isa(options->isa, &isa, error);
    if (st != HB_OK)
        return st;
    if (options->tolerance == 0.0 && options->budget_ns == 0.0)
        return hb_plan_build(material, options, isa, NULL, out, error);
    /* a tolerance or budget plan: the best configuration, or the next when its table cannot be built */
    hb_selection selection = { 0 };
    for (;;) {
        hb_options chosen;
        st = hb_plan_select(material, options, isa, &chosen, &selection, error);
        if (st != HB_OK)
            return st;
        st = hb_plan_build(material, &chosen, isa, &selection, out, error);
        if (st == HB_OK && error) /* an earlier attempt's message is not this call's */
            error->status = HB_OK, error->message[0] = '\0';
        if ((st != HB_ERR_UNSUPPORTED && st != HB_ERR_LIMIT) || selection.preset >= 32)
            return st;
        selection.refused |= 1u << selection.preset;
        snprintf(selection.refusal, sizeof selection.refusal, "%s: %.120s", selection.configuration,
                 error ? error->message : "could not be built");
    }
}

hb_status hb_plan_build(const hb_material *material, const hb_options *options, hb_isa isa,
                        const hb_selection *selection, hb_plan **out, hb_error *error)
{
    const hb_model_ops *ops = hb_model_ops_of(options->model);
    hb_plan *plan = calloc(1, sizeof *plan + ops->state_size);
    if (!plan)
        return hb_plan_fail(error, HB_ERR_NOMEM, "could not allocate a plan");
    plan->state_size = ops->state_size;
    plan->material = *material;
    plan->options = *options;
    if (selection)
        plan->selection = *selection;
    plan->isa = isa;
    hb_material_absorption(material, plan->sigma_a);
    plan->reference = ops->reference;
    hb_status st = ops->derive(plan, error);
    hb_table_view view;
    int channels;
    if (st == HB_OK && options->table_file && ops->table(plan, &view, &channels) != HB_OK)
        st = hb_plan_fail(error, HB_ERR_UNSUPPORTED, "a table file is given but this plan has no table to load (dFH11: "
                          "azimuthal = table; HHH22: tt_trt = table)");
    /* the caller's bytes may be freed: the plan keeps only their length */
    plan->table_file_size = options->table_file_size;
    plan->options.table_file = NULL;
    plan->options.table_file_size = 0;
    if (st != HB_OK) {
        hb_plan_free(plan);
        return st;
    }
    *out = plan;
    return HB_OK;
}

void hb_plan_free(hb_plan *plan)
{
    if (plan) {
        const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
        if (ops->release)
            ops->release(plan);
    }
    free(plan);
}

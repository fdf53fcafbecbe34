/* MJC03 behind the model interface (models/interface/model.h): its kernels through the plan, its
 * sampler (sample.h), description, furnace rule and named configuration. It has no table. */
#include <math.h>

#include "marschner.h"
#include "state.h"

static unsigned lobes(const hb_options *o) { return o->lobes == HB_LOBES_DEFAULT ? 7u : o->lobes; }

static void eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid)
{
    const hb_marschner_kernels *k = hb_kernels_for(plan, n);
    if (plan->options.term == HB_TERM_LONGITUDINAL) {
        k->longitudinal_angles(&hb_marschner_of(plan)->kernel.lobe[HB_LOBE_R], n, in, out.r, invalid);
        hb_spread_channels(n, out);
    } else {
        k->angles(&hb_marschner_of(plan)->kernel, n, in, out, invalid);
    }
}

static void eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid)
{
    const hb_marschner_kernels *k = hb_kernels_for(plan, n);
    if (plan->options.term == HB_TERM_LONGITUDINAL) {
        k->longitudinal_vectors(&hb_marschner_of(plan)->kernel.lobe[HB_LOBE_R], n, in, out.r, invalid);
        hb_spread_channels(n, out);
    } else {
        k->vectors(&hb_marschner_of(plan)->kernel, n, in, out, invalid);
    }
}

/* The sampler runs on the kernels (no double-precision procedure: a reference plan cannot sample). */
static int sample_dimensions(const hb_plan *plan)
{
    return plan->kernels && plan->options.term == HB_TERM_FULL ? HB_MARSCHNER_SAMPLE_DIMENSIONS : 0;
}

static void sample(const hb_plan *plan, size_t n, const hb_sample_batch *b, size_t *invalid)
{
    ((const hb_marschner_kernels *)hb_kernels_for(plan, n))->sample(&hb_marschner_of(plan)->kernel, n, b, invalid);
}

static void pdf(const hb_plan *plan, size_t n, const hb_pair_batch *in, float *out, size_t *invalid)
{
    ((const hb_marschner_kernels *)hb_kernels_for(plan, n))->pdf(&hb_marschner_of(plan)->kernel, n, in, out, invalid);
}

/* f (the caustics' fade and glint, the attenuation) and the pdf share only the geometry: two passes. */
static void eval_pdf(const hb_plan *plan, size_t n, const hb_pair_batch *in, hb_rgb_soa out, float *pdf_out,
                     size_t *invalid)
{
    hb_eval_then_pdf(plan, n, in, out, pdf_out, invalid);
}

static hb_status eval_absorption(const hb_plan *plan, size_t n, const hb_absorbing_batch *in, hb_rgb_soa out,
                                 size_t *invalid)
{
    if (plan->options.term != HB_TERM_FULL)
        return HB_ERR_UNSUPPORTED;
    ((const hb_marschner_kernels *)hb_kernels_for(plan, n))->absorbing(&hb_marschner_of(plan)->kernel, n, in, out, invalid);
    return HB_OK;
}

static hb_status table(const hb_plan *plan, hb_table_view *view, int *channels)
{
    (void)plan, (void)view, (void)channels;
    return HB_ERR_UNSUPPORTED;
}

static void describe(hb_text *t, const hb_plan *plan)
{
    hb_say(t, "model: Marschner 2003 (MJC03), R + TT + TRT in closed form (the cubic solved per sample), RGB; lobes: ");
    hb_say_lobes(t, hb_marschner_of(plan)->kernel.lobes);
    hb_say(t, "\nfibre: %s; TRT caustics: glint %.3g, width %.3g rad\n",
        plan->material.eccentricity > 0.0 ? "elliptical" : "circular", plan->material.glint_scale,
        plan->material.caustic_width);
}

/* N_p is not smooth in phi (square-root edges where a root leaves the fibre or total reflection
 * sets in): a fixed fine midpoint rule, error below 1e-4 for the defaults. */
static void furnace_rule(const hb_plan *plan, double *beta_m, int *azimuths, int *passes)
{
    int longitudinal = plan->options.term == HB_TERM_LONGITUDINAL;
    *beta_m = HUGE_VAL;
    for (int p = 0; p < 3; p++)
        if (hb_marschner_of(plan)->kernel.lobes >> p & 1u || (longitudinal && p == HB_LOBE_R))
            *beta_m = fmin(*beta_m, hb_marschner_of(plan)->beta[p]);
    *azimuths = longitudinal ? 1 : 1440;
    *passes = 1;
}

static const hb_preset presets[] = {
    { "full/closed-form", HB_QUALITY_BALANCED, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
};

/* Its one configuration is every plan's: the closed form has no quality knob. */
static int any_preset(const hb_preset *p, const hb_material *m, const hb_options *o, unsigned lobe_mask)
{
    (void)p, (void)m, (void)o, (void)lobe_mask;
    return 1;
}

/* its double-precision procedures (reference.h; the fast path includes none of it) */
extern const struct hb_reference_ops hb_ref_marschner_ops;

const hb_model_ops hb_marschner_model = {
    .name = "marschner",
    .reference = &hb_ref_marschner_ops,
    .state_size = sizeof(hb_marschner_state),
    .table_version = 1,
    .lobes = lobes,
    .validate = hb_marschner_validate,
    .derive = hb_marschner_derive,
    .eval_angles = eval_angles,
    .eval_vectors = eval_vectors,
    .sample_dimensions = sample_dimensions,
    .sample = sample,
    .pdf = pdf,
    .eval_absorption = eval_absorption,
    .eval_pdf = eval_pdf,
    .table = table,
    .look = hb_marschner_look,
    .set_look = hb_marschner_set_look,
    .describe = describe,
    .furnace_rule = furnace_rule,
    .presets = presets,
    .preset_count = sizeof presets / sizeof presets[0],
    .preset_applies = any_preset,
    .preset_is = any_preset,
    .drops_lobes = 1,
};

/* HHH22 behind the model interface (models/interface/model.h): its kernels through the plan, its
 * description, furnace rule and named configurations. */
#include <math.h>
#include <string.h>

#include "huang.h"
#include "math/hash.h"
#include "state.h"

static unsigned lobes(const hb_options *o) { return o->lobes == HB_LOBES_DEFAULT ? 7u : o->lobes; }

static void eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid)
{
    ((const hb_huang_kernels *)hb_kernels_for(plan, n))->angles(&hb_huang_of(plan)->kernel, n, in, out, invalid);
}

static void eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid)
{
    ((const hb_huang_kernels *)hb_kernels_for(plan, n))->vectors(&hb_huang_of(plan)->kernel, n, in, out, invalid);
}

/* R alone is sampled exactly, with TT and TRT by traced paths; the double path has no TT/TRT sampler. */
static int sample_dimensions(const hb_plan *plan)
{
    if (hb_huang_of(plan)->kernel.lobes == 1u << HB_LOBE_R)
        return HB_HUANG_SAMPLE_DIMENSIONS;
    return plan->kernels ? HB_HUANG_PATH_DIMENSIONS : 0;
}

/* The traced paths' pdf is eq. 33 estimated (sample_paths.h); R alone has its exact pdf. */
static int pdf_is_estimate(const hb_plan *plan)
{
    return sample_dimensions(plan) == HB_HUANG_PATH_DIMENSIONS;
}

static void sample(const hb_plan *plan, size_t n, const hb_sample_batch *b, size_t *invalid)
{
    ((const hb_huang_kernels *)hb_kernels_for(plan, n))->sample(&hb_huang_of(plan)->kernel, n, b, invalid);
}

static void pdf(const hb_plan *plan, size_t n, const hb_pair_batch *in, float *out, size_t *invalid)
{
    ((const hb_huang_kernels *)hb_kernels_for(plan, n))->pdf(&hb_huang_of(plan)->kernel, n, in, out, invalid);
}

/* f and its pdf share no stage (the pdf is eq. 33's, f eqs. 12, 23 and 24): two passes. */
static void eval_pdf(const hb_plan *plan, size_t n, const hb_pair_batch *in, hb_rgb_soa out, float *pdf,
                     size_t *invalid)
{
    hb_eval_then_pdf(plan, n, in, out, pdf, invalid);
}

static void describe(hb_text *t, const hb_plan *plan)
{
    const hb_huang *h = &hb_huang_of(plan)->kernel;
    hb_say(t, "model: Huang 2022 (HHH22), microfacet %s roughness %.3g, %s, %s fibre%s; lobes: ",
        h->beckmann ? "Beckmann" : "GGX", plan->material.roughness, h->shadowing ? "Smith G" : "no shadowing (G = 1)",
        h->elliptical ? "elliptical" : "circular", h->tilted ? ", tilted scales" : "");
    hb_say_lobes(t, h->lobes);
    hb_say(t, "\n");
    if (h->lobes & 1u) {
        if (h->analytic)
            hb_say(t, "R (eq. 12): App. A's closed form\n");
        else
            hb_say(t, "R (eq. 12): Simpson, %d panels%s\n", h->panels,
                h->step_rule ? " (the paper's uniform steps)" : " in the peak-following variable");
    }
    if (h->lobes & 6u) {
        if (h->table.values)
            hb_say(t, "TT + TRT: interpolated from a table (%d theta_i x %d phi_i x %d x %d, built with Simpson over "
                   "%d panels, %d paths per node)%s\n", h->table.n_theta_i, h->table.n_phi_i, h->table.n_sum, h->table.n_delta,
                   h->table.panels, h->table.paths,
                   h->table_grid < hb_huang_table_grid_of(plan->options.quality)
                       ? "; tt_trt auto: a coarser grid than the quality's, whose build would take more than a second"
                       : "");
        else if (plan->kernels)
            hb_say(t, "TT + TRT (eqs. 31, 32): Simpson over %d panels of the entry azimuth, one random internal path per "
                   "node (seed %llu)%s\n", h->tt_panels, plan->options.seed,
                   h->table_too_costly ? "; tt_trt auto: even the fast table would take more than a second to "
                                         "build (tt_trt = table builds it)" : "");
        else
            hb_say(t, "TT + TRT: nested quadrature in double\n");
    }
    if (h->cos_floor > 1e-8f)
        hb_say(t, "poles: cos(theta) in eq. 10's width kept above %.3g, f bounded from |theta| = %.4g on (pole_floor; "
               "the paper's f is pole_floor = paper)\n", h->cos_floor, acos(h->cos_floor));
    else
        hb_say(t, "poles: the paper's 1 / cos(theta_o) up to the pole itself (pole_floor)\n");
}

/* HHH22's lobes are about a roughness wide in theta and (TT, the forward focus) in phi. Its
 * Monte-Carlo TT and TRT put few points inside the narrow TT lobe, so one pass would carry 5-10% of
 * the estimator's noise; 16 passes with independent numbers bring it to about a quarter of that. */
static void furnace_rule(const hb_plan *plan, double *beta_m, int *azimuths, int *passes)
{
    *beta_m = plan->material.roughness;
    *azimuths = (int)ceil(3.0 * M_PI / fmin(plan->material.roughness, 1.0)) + 8;
    int monte_carlo = plan->kernels && !hb_huang_of(plan)->kernel.table.values &&
                      (hb_huang_of(plan)->kernel.lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT));
    *passes = monte_carlo ? 16 : 1;
}

/* The Monte-Carlo numbers are drawn by sample index, which restarts with every furnace chunk: a
 * key per chunk keeps the chunks' numbers independent. */
static void rekey(hb_plan *copy, const hb_plan *plan, unsigned long long chunk)
{
    hb_huang_mut(copy)->kernel.rng_key = hb_huang_of(plan)->kernel.rng_key ^ (uint32_t)hb_mix64(chunk);
}

static const hb_preset presets[] = {
    { "R/analytic", HB_QUALITY_BALANCED, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "R/G-fast", HB_QUALITY_FAST, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "R/G-balanced", HB_QUALITY_BALANCED, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "R/G-high", HB_QUALITY_HIGH, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "all/mc-fast", HB_QUALITY_FAST, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "all/mc-balanced", HB_QUALITY_BALANCED, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "all/table-fast", HB_QUALITY_FAST, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_TABLE },
    { "all/table-balanced", HB_QUALITY_BALANCED, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_AUTO }, /* the bench row's */
};

/* App. A's closed form covers GGX without shadowing on circular fibres. */
static int analytic(const hb_material *m, const hb_options *o)
{
    return m->ndf == HB_NDF_GGX && o->shadowing == HB_SHADOWING_NONE && m->eccentricity == 0.0 &&
           o->r_integration != HB_R_INTEGRATION_NUMERIC;
}

/* The bench times R alone ("R/...") and R + TT + TRT ("all/..."). */
static int preset_applies(const hb_preset *p, const hb_material *m, const hb_options *o, unsigned lobe_mask)
{
    if (strncmp(p->name, "all/", 4) == 0)
        return lobe_mask == 7u;
    return lobe_mask == 1u << HB_LOBE_R && (strcmp(p->name, "R/analytic") == 0) == analytic(m, o);
}

/* tt_trt auto is a table (on a grid no finer than the quality's) wherever the bench times it. */
static hb_tt_trt table_if_auto(hb_tt_trt tt_trt) { return tt_trt == HB_TT_TRT_AUTO ? HB_TT_TRT_TABLE : tt_trt; }

static int preset_is(const hb_preset *p, const hb_material *m, const hb_options *o, unsigned lobe_mask)
{
    if (lobe_mask == 1u && analytic(m, o))
        return 1;
    return p->quality == o->quality && p->quadrature_order == o->quadrature_order && p->azimuthal == o->azimuthal &&
           (lobe_mask == 1u || table_if_auto(p->tt_trt) == table_if_auto(o->tt_trt));
}

/* its double-precision procedures (reference.h; the fast path includes none of it) */
extern const struct hb_reference_ops hb_ref_huang_ops;

const hb_model_ops hb_huang_model = {
    .name = "huang",
    .reference = &hb_ref_huang_ops,
    .state_size = sizeof(hb_huang_state),
    .table_version = 1,
    .lobes = lobes,
    .validate = hb_huang_validate,
    .derive = hb_huang_derive,
    .release = hb_huang_release,
    .eval_angles = eval_angles,
    .eval_vectors = eval_vectors,
    .sample_dimensions = sample_dimensions,
    .pdf_is_estimate = pdf_is_estimate,
    .sample = sample,
    .pdf = pdf,
    .eval_pdf = eval_pdf,
    .table = hb_huang_table_view,
    .shader_constants = hb_huang_shader_constants,
    .look = hb_huang_look,
    .set_look = hb_huang_set_look,
    .describe = describe,
    .furnace_rule = furnace_rule,
    .rekey = rekey,
    .presets = presets,
    .preset_count = sizeof presets / sizeof presets[0],
    .preset_applies = preset_applies,
    .preset_is = preset_is,
    .drops_lobes = 0,
};

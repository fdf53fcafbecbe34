/* CBTB16 behind the model interface (models/interface/model.h): near-field kernels at each sample's h, the
 * far field (the mean over h) through the angle and vector entry points, its sampler, description,
 * furnace rule and named configurations. */
#include <math.h>

#include "chiang.h"
#include "state.h"

static unsigned lobes(const hb_options *o) { return o->lobes == HB_LOBES_DEFAULT ? 7u | 1u << HB_LOBE_RESIDUAL : o->lobes; }

static const hb_chiang_kernels *kernels_of(const hb_plan *plan, size_t n) { return hb_kernels_for(plan, n); }

static void eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid)
{
    kernels_of(plan, n)->angles(&hb_chiang_of(plan)->kernel, n, in, out, invalid);
}

static void eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid)
{
    kernels_of(plan, n)->vectors(&hb_chiang_of(plan)->kernel, n, in, out, invalid);
}

/* The far-field sampler reads one number more than the near field's: h. */
static int sample_dimensions(const hb_plan *plan)
{
    (void)plan;
    return HB_CHIANG_NEAR_DIMENSIONS + 1;
}

static void sample(const hb_plan *plan, size_t n, const hb_sample_batch *b, size_t *invalid)
{
    kernels_of(plan, n)->sample(&hb_chiang_of(plan)->kernel, n, b, invalid);
}

static void pdf(const hb_plan *plan, size_t n, const hb_pair_batch *in, float *out, size_t *invalid)
{
    kernels_of(plan, n)->f_pdf(&hb_chiang_of(plan)->kernel, n, in, NULL, out, invalid);
}

static void eval_pdf(const hb_plan *plan, size_t n, const hb_pair_batch *in, hb_rgb_soa out, float *pdf,
                     size_t *invalid)
{
    kernels_of(plan, n)->f_pdf(&hb_chiang_of(plan)->kernel, n, in, &out, pdf, invalid);
}

static void eval_near(const hb_plan *plan, size_t n, hb_near_soa in, hb_rgb_soa out, size_t *invalid)
{
    const hb_chiang_kernels *wide = plan->kernels;
    if (n <= (size_t)wide->near_few_max && hb_chiang_of(plan)->kernel.longitudinal[0].single)
        wide->near_few(&hb_chiang_of(plan)->kernel, n, in, out, invalid);
    else
        kernels_of(plan, n)->near(&hb_chiang_of(plan)->kernel, n, in, out, invalid);
}

static hb_status eval_absorption(const hb_plan *plan, size_t n, const hb_absorbing_batch *in, hb_rgb_soa out,
                                 size_t *invalid)
{
    kernels_of(plan, n)->absorbing(&hb_chiang_of(plan)->kernel, n, in, out, invalid);
    return HB_OK;
}

static hb_status eval_near_absorption(const hb_plan *plan, size_t n, const hb_absorbing_near *in, hb_rgb_soa out,
                                      size_t *invalid)
{
    kernels_of(plan, n)->near_absorbing(&hb_chiang_of(plan)->kernel, n, in, out, invalid);
    return HB_OK;
}

static void sample_near(const hb_plan *plan, size_t n, hb_sample_streams in, hb_sample_out out, size_t *invalid)
{
    kernels_of(plan, n)->sample_near(&hb_chiang_of(plan)->kernel, n, in, out, invalid);
}

static void pdf_near(const hb_plan *plan, size_t n, hb_near_soa in, float *out, size_t *invalid)
{
    kernels_of(plan, n)->pdf_near(&hb_chiang_of(plan)->kernel, n, in, out, invalid);
}

/* As eval_near, a call of a few samples of f at h goes to the wide kernels' one-sample path. */
static hb_status spectral(const hb_plan *plan, size_t n, const hb_spectral_batch *b, size_t *invalid)
{
    const hb_chiang_kernels *wide = plan->kernels;
    if (b->near.h && !b->pdf && n <= (size_t)wide->near_few_max && hb_chiang_of(plan)->kernel.longitudinal[0].single)
        wide->spectral_few(&hb_chiang_of(plan)->kernel, n, b, invalid);
    else
        kernels_of(plan, n)->spectral(&hb_chiang_of(plan)->kernel, n, b, invalid);
    return HB_OK;
}
static void sample_spectral(const hb_plan *plan, size_t n, const hb_spectral_sample_batch *b, size_t *invalid)
{
    kernels_of(plan, n)->sample_spectral(&hb_chiang_of(plan)->kernel, n, b, invalid);
}

static hb_status table(const hb_plan *plan, hb_table_view *view, int *channels)
{
    (void)plan, (void)view, (void)channels;
    return HB_ERR_UNSUPPORTED;
}

static void describe(hb_text *t, const hb_plan *plan)
{
    const hb_chiang *c = &hb_chiang_of(plan)->kernel;
    hb_say(t, "model: Chiang et al. 2016 (CBTB16, pbrt-v4's HairBxDF), f = sum_p M_p A_p N_p near-field at h, RGB; "
              "lobes: ");
    hb_say_lobes(t, c->lobes);
    hb_say(t, "\nM_p (dFH11 eq. 7, %s): v_R %.4g, v_TT %.4g, v_TRT and residual %.4g; N_p: trimmed logistic, "
              "s %.4g\nfar field (hb_eval_angles): order-%d Gauss-Legendre rule in asin(h), %d nodes per sample "
              "(h >= 0, paired with -h), quality %s\n",
           c->longitudinal[0].single ? "float" : "double where it matters", hb_chiang_of(plan)->v[0], hb_chiang_of(plan)->v[1],
           hb_chiang_of(plan)->v[2], hb_chiang_of(plan)->s, 2 * c->nodes, c->nodes, hb_quality_name(plan->options.quality));
    if (hb_chiang_of(plan)->far_capped)
        hb_say(t, "far field: the quality's rule asks for more nodes than %d (s below 0.012): its error is above "
                  "the quality's target\n", HB_CHIANG_MAX_NODES);
}

/* The narrowest M_p (TT's, v_R / 4) and the periodic midpoint rule in phi at steps of s / 2 (the
 * logistic's poles lie pi s off the real axis: the rule's error is about e^(-2 pi^2 s / step)). */
static void furnace_rule(const hb_plan *plan, double *beta_m, int *azimuths, int *passes)
{
    *beta_m = HUGE_VAL;
    for (int p = 0; p < HB_CHIANG_TERMS; p++)
        if (hb_chiang_term_on(&hb_chiang_of(plan)->kernel, p))
            *beta_m = fmin(*beta_m, sqrt(hb_chiang_of(plan)->v[p]));
    *azimuths = (int)ceil(4.0 * M_PI / hb_chiang_of(plan)->s) + 8;
    *passes = 1;
}

static const hb_preset presets[] = {
    { "far/fast", HB_QUALITY_FAST, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "far/balanced", HB_QUALITY_BALANCED, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "far/high", HB_QUALITY_HIGH, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
};

static int any_preset(const hb_preset *p, const hb_material *m, const hb_options *o, unsigned lobe_mask)
{
    (void)p, (void)m, (void)o, (void)lobe_mask;
    return 1;
}

static int preset_is(const hb_preset *p, const hb_material *m, const hb_options *o, unsigned lobe_mask)
{
    (void)m, (void)lobe_mask;
    return p->quality == o->quality && o->quadrature_order == 0;
}

/* its double-precision procedures (reference.h; the fast path includes none of it) */
extern const struct hb_reference_ops hb_ref_chiang_ops;

const hb_model_ops hb_chiang_model = {
    .name = "chiang",
    .reference = &hb_ref_chiang_ops,
    .state_size = sizeof(hb_chiang_state),
    .beta_max = 1.0, /* pbrt-v4's [0, 1] scale (docs/chiang.md) */
    .beta_m_min = HB_CHIANG_BETA_M_MIN,
    .table_version = 1,
    .lobes = lobes,
    .validate = hb_chiang_validate,
    .derive = hb_chiang_derive,
    .eval_angles = eval_angles,
    .eval_vectors = eval_vectors,
    .sample_dimensions = sample_dimensions,
    .sample = sample,
    .pdf = pdf,
    .eval_pdf = eval_pdf,
    .table = table,
    .eval_near = eval_near,
    .sample_near = sample_near,
    .eval_absorption = eval_absorption,
    .eval_near_absorption = eval_near_absorption,
    .pdf_near = pdf_near,
    .spectral = spectral,
    .sample_spectral = sample_spectral,
    .look = hb_chiang_look,
    .set_look = hb_chiang_set_look,
    .describe = describe,
    .furnace_rule = furnace_rule,
    .presets = presets,
    .preset_count = sizeof presets / sizeof presets[0],
    .preset_applies = any_preset,
    .preset_is = preset_is,
    .drops_lobes = 1,
};

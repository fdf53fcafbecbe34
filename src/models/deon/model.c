/* dFH11 behind the model interface (models/interface/model.h): its kernels through the plan, its
 * description, furnace rule and named configurations. */
#include <math.h>

#include "deon.h"
#include "state.h"

/* Whether the plan's kernels take a call of n samples one sample at a time, the lanes carrying the
 * far field's quadrature nodes or the near field's lobes instead of samples (kernels.c): standard
 * quadrature plans of the full model, up to the count measured for the ISA. */
static int few(const hb_plan *plan, size_t n, int most)
{
    return n <= (size_t)most && hb_deon_of(plan)->kernel.standard && !hb_deon_of(plan)->kernel.np_table && plan->options.term == HB_TERM_FULL;
}

/* How many samples at the end of a batch of n the few-sample kernels take: the partial last block
 * (n mod the block's width) when it has at most `most` samples, else none. A partial block costs a
 * whole one, more than its samples' one-sample calls (make bench, the per-hit rows). */
static size_t few_tail(const hb_plan *plan, size_t n, int most)
{
    const hb_deon_kernels *wide = plan->kernels;
    size_t tail = n % (size_t)wide->width;
    return n > tail && few(plan, tail, most) ? tail : 0;
}

static hb_angles_soa angles_from(hb_angles_soa a, size_t k)
{
    return (hb_angles_soa){ a.theta_i + k, a.phi_i + k, a.theta_o + k, a.phi_o + k };
}

static hb_rgb_soa rgb_from(hb_rgb_soa out, size_t k) { return (hb_rgb_soa){ out.r + k, out.g + k, out.b + k }; }

/* The few-sample kernel over samples first.. of a batch, its invalid samples added to *invalid. */
static void few_from(const hb_plan *plan, size_t first, size_t n, hb_angles_soa in, hb_rgb_soa out, float *pdf,
                     size_t *invalid)
{
    const hb_deon_kernels *wide = plan->kernels;
    size_t bad = 0;
    if (n)
        wide->angles_few[plan->options.i0](&hb_deon_of(plan)->kernel, n, angles_from(in, first), rgb_from(out, first),
                                            pdf ? pdf + first : NULL, &bad);
    *invalid += bad;
}

/* hb_kernels_for, typed. */
static const hb_deon_kernels *deon_kernels_for(const hb_plan *plan, size_t n) { return hb_kernels_for(plan, n); }

static unsigned lobes(const hb_options *o)
{
    return o->lobes == HB_LOBES_DEFAULT ? ((2u << o->pmax) - 1u) | 1u << HB_LOBE_RESIDUAL : o->lobes;
}

static void eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid)
{
    const hb_deon_kernels *wide = plan->kernels;
    if (few(plan, n, wide->few_max)) {
        wide->angles_few[plan->options.i0](&hb_deon_of(plan)->kernel, n, in, out, NULL, invalid);
        return;
    }
    const hb_deon_kernels *k = deon_kernels_for(plan, n);
    if (plan->options.term == HB_TERM_LONGITUDINAL) {
        k->longitudinal_angles[plan->options.i0](&hb_deon_of(plan)->kernel.longitudinal[HB_LOBE_R], n, in, out.r, invalid);
        hb_spread_channels(n, out);
    } else {
        size_t tail = few_tail(plan, n, wide->few_max);
        k->angles[plan->options.i0](&hb_deon_of(plan)->kernel, n - tail, in, out, invalid);
        few_from(plan, n - tail, tail, in, out, NULL, invalid);
    }
}

static void eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid)
{
    const hb_deon_kernels *k = deon_kernels_for(plan, n);
    if (plan->options.term == HB_TERM_LONGITUDINAL) {
        k->longitudinal_vectors[plan->options.i0](&hb_deon_of(plan)->kernel.longitudinal[HB_LOBE_R], n, in, out.r, invalid);
        hb_spread_channels(n, out);
    } else {
        k->vectors[plan->options.i0](&hb_deon_of(plan)->kernel, n, in, out, invalid);
    }
}

/* The sampler draws eq. 14's per-offset R Fresnel; eq. 12's half-angle factor has no sampler. */
static int sample_dimensions(const hb_plan *plan)
{
    return plan->options.term == HB_TERM_FULL && plan->options.r_fresnel == HB_R_FRESNEL_OFFSET
               ? HB_DEON_SAMPLE_DIMENSIONS : 0;
}

static void sample(const hb_plan *plan, size_t n, const hb_sample_batch *b, size_t *invalid)
{
    deon_kernels_for(plan, n)->sample[plan->options.i0](&hb_deon_of(plan)->kernel, n, b, invalid);
}

static void pdf(const hb_plan *plan, size_t n, const hb_pair_batch *in, float *out, size_t *invalid)
{
    deon_kernels_for(plan, n)->pdf[plan->options.i0](&hb_deon_of(plan)->kernel, n, in, out, invalid);
}

/* The quadrature forms f and the pdf's terms together (sample.h, deon_f_pdf); a table plan's f
 * comes from its table, so it takes two passes. */
static void eval_pdf(const hb_plan *plan, size_t n, const hb_pair_batch *in, hb_rgb_soa out, float *pdf,
                     size_t *invalid)
{
    const hb_deon_kernels *wide = plan->kernels;
    if (hb_deon_of(plan)->kernel.np_table)
        hb_eval_then_pdf(plan, n, in, out, pdf, invalid);
    else if (!in->vectors.wi_x && few(plan, n, wide->few_max))
        wide->angles_few[plan->options.i0](&hb_deon_of(plan)->kernel, n, in->angles, out, pdf, invalid);
    else {
        size_t tail = in->vectors.wi_x ? 0 : few_tail(plan, n, wide->few_max);
        deon_kernels_for(plan, n)->f_pdf[plan->options.i0](&hb_deon_of(plan)->kernel, n - tail, in, out, pdf, invalid);
        few_from(plan, n - tail, tail, in->angles, out, pdf, invalid);
    }
}

/* Per-sample absorption by the quadrature or the colour table: a material's own table holds N_p of
 * its own absorption. */
static hb_status eval_absorption(const hb_plan *plan, size_t n, const hb_absorbing_batch *in, hb_rgb_soa out,
                                 size_t *invalid)
{
    if ((hb_deon_of(plan)->kernel.np_table && !hb_deon_of(plan)->kernel.table_absorption) || plan->options.term != HB_TERM_FULL)
        return HB_ERR_UNSUPPORTED;
    deon_kernels_for(plan, n)->absorbing[plan->options.i0](&hb_deon_of(plan)->kernel, n, in, out, invalid);
    return HB_OK;
}

/* The near field at each sample's h (near.h): f by the plan's kernels, HB_TERM_FULL only (the
 * longitudinal term has no h). */
static void eval_near(const hb_plan *plan, size_t n, hb_near_soa in, hb_rgb_soa out, size_t *invalid)
{
    const hb_deon_kernels *wide = plan->kernels;
    if (few(plan, n, wide->near_few_max) && hb_deon_of(plan)->kernel.longitudinal[HB_LOBE_R].single) /* the float M_p lanes */
        wide->near_few[plan->options.i0](&hb_deon_of(plan)->kernel, n, in, out, invalid);
    else
        deon_kernels_for(plan, n)->near[plan->options.i0](&hb_deon_of(plan)->kernel, n, in, out, invalid);
}

static hb_status eval_near_absorption(const hb_plan *plan, size_t n, const hb_absorbing_near *in, hb_rgb_soa out,
                                      size_t *invalid)
{
    deon_kernels_for(plan, n)->near_absorbing[plan->options.i0](&hb_deon_of(plan)->kernel, n, in, out, invalid);
    return HB_OK;
}

/* k wavelengths: the near field's f and pdf for every plan, the far field's f by the standard
 * quadrature's fused sum; HB_ERR_UNSUPPORTED for the other far fields, which the spectral calls then
 * evaluate through eval_absorption three wavelengths a call. */
static hb_status spectral(const hb_plan *plan, size_t n, const hb_spectral_batch *b, size_t *invalid)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    if (plan->options.term != HB_TERM_FULL || (!b->near.h && (b->pdf || !d->standard || d->np_table)))
        return HB_ERR_UNSUPPORTED;
    deon_kernels_for(plan, n)->spectral[plan->options.i0](d, n, b, invalid);
    return HB_OK;
}

static void sample_spectral(const hb_plan *plan, size_t n, const hb_spectral_sample_batch *b, size_t *invalid)
{
    deon_kernels_for(plan, n)->sample_spectral[plan->options.i0](&hb_deon_of(plan)->kernel, n, b, invalid);
}

static void sample_near(const hb_plan *plan, size_t n, hb_sample_streams in, hb_sample_out out, size_t *invalid)
{
    deon_kernels_for(plan, n)->sample_near[plan->options.i0](&hb_deon_of(plan)->kernel, n, in, out, invalid);
}

static void pdf_near(const hb_plan *plan, size_t n, hb_near_soa in, float *out, size_t *invalid)
{
    deon_kernels_for(plan, n)->pdf_near[plan->options.i0](&hb_deon_of(plan)->kernel, n, in, out, invalid);
}

static void describe(hb_text *t, const hb_plan *plan)
{
    const hb_deon *d = &hb_deon_of(plan)->kernel;
    hb_say(t, "model: d'Eon 2011 (dFH11), f = sum_p M_p N_p, %s; lobes: ",
        d->channels == 1 ? "grey (one channel computed, copied to RGB)" : "RGB");
    hb_say_lobes(t, d->lobes);
    hb_say(t, d->lobes >> HB_LOBE_RESIDUAL & 1u ? " (residual: every order above %d in closed form)\n" : "\n", d->pmax);
    hb_say(t, "M_p (eq. 7): %s I0; %d distinct M_p per sample (lobes with the same roughness and shift share one%s)\n",
        plan->options.i0 == HB_I0_ABRAMOWITZ ? "A&S 9.8.1/9.8.2" : "the paper's 10-term series for", d->groups,
        plan->material.alpha == 0.0 ? "; no tilt" : "");
    if (d->table_absorption)
        hb_say(t, "N_p (eq. 10): per channel, trilinear from one colour table, %d x %d x %d per M_p group over "
               "sqrt(cos theta_d) x |phi| x log(1 + sigma_a / 0.001) for every absorption up to %g (midpoint error "
               "%.2g of each group's peak), built with the order-%d Gauss-Legendre rule%s\n", d->table_cd,
               d->table_phi, d->table_absorption, HB_COLOUR_TABLE_SIGMA_MAX, hb_deon_of(plan)->table_error, d->order,
               d->mapped ? " (mapped)" : "");
    else if (d->np_table)
        hb_say(t, "N_p (eq. 10): bilinear from a %d x %d table per M_p group over sqrt(cos theta_d) x |phi| "
               "(midpoint error %.2g of each group's peak), built with the order-%d Gauss-Legendre rule%s\n",
            d->table_cd, d->table_phi, hb_deon_of(plan)->table_error, d->order, d->mapped ? " (mapped)" : "");
    else
        hb_say(t, "N_p (eq. 10): order-%d Gauss-Legendre rule %s across the fibre, %d nodes per sample "
               "(gamma_i >= 0, detected at +-phi), quality %s\n", d->order,
            d->mapped ? "in u, gamma_i = (pi/2) asin(0.8 u) / asin(0.8)" : "in gamma_i", d->nodes,
            hb_quality_name(plan->options.quality));
    for (int p = 0; p <= d->pmax && p < HB_MAX_LOBES; p++)
        if (d->lobes >> p & 1u)
            hb_say(t, d->detector[p].fourier ? "  detector %s (eq. 11, beta_n %.3g): Fourier series, %d terms\n"
                                          : "  detector %s (eq. 11, beta_n %.3g): Gaussians at phi - 2 pi k, |k| <= %d\n",
                hb_lobe_name(p), hb_deon_of(plan)->beta_n[p],
                d->detector[p].terms);
}

/* The longitudinal term T is f / N_p: its energy is the integral of T cos(theta_i) over theta_i
 * alone, as if N_p integrated to 1 (dFH11 eq. 5 and Fig. 3). Otherwise the periodic midpoint rule
 * in phi with steps of beta_n / 1.5 (its error for a Gaussian of width beta and step h is about
 * exp(-2 pi^2 beta^2 / h^2) = 5e-20). */
static void furnace_rule(const hb_plan *plan, double *beta_m, int *azimuths, int *passes)
{
    int longitudinal = plan->options.term == HB_TERM_LONGITUDINAL;
    double beta_n = HUGE_VAL;
    *beta_m = HUGE_VAL;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        if (hb_deon_of(plan)->kernel.lobes >> p & 1u || (longitudinal && p == HB_LOBE_R)) {
            *beta_m = fmin(*beta_m, sqrt(hb_deon_of(plan)->v[p]));
            if (p < HB_MAX_LOBES)
                beta_n = fmin(beta_n, hb_deon_of(plan)->beta_n[p]);
        }
    *azimuths = longitudinal ? 1 : (int)ceil(3.0 * M_PI / fmin(beta_n, 1.0)) + 8;
    *passes = 1;
}

static const hb_preset presets[] = {
    { "full/fast", HB_QUALITY_FAST, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "full/balanced", HB_QUALITY_BALANCED, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "full/high", HB_QUALITY_HIGH, 0, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "full/order35", HB_QUALITY_BALANCED, 35, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "full/order35-high", HB_QUALITY_HIGH, 35, HB_AZIMUTHAL_QUADRATURE, HB_TT_TRT_MC },
    { "full/table-fast", HB_QUALITY_FAST, 0, HB_AZIMUTHAL_TABLE, HB_TT_TRT_MC },
    { "full/table-balanced", HB_QUALITY_BALANCED, 0, HB_AZIMUTHAL_TABLE, HB_TT_TRT_MC },
    { "full/table-high", HB_QUALITY_HIGH, 0, HB_AZIMUTHAL_TABLE, HB_TT_TRT_MC },
};

/* The N_p table needs the offset R Fresnel. */
static int preset_applies(const hb_preset *p, const hb_material *m, const hb_options *o, unsigned lobe_mask)
{
    (void)m, (void)lobe_mask;
    return p->azimuthal != HB_AZIMUTHAL_TABLE || o->r_fresnel == HB_R_FRESNEL_OFFSET;
}

static int preset_is(const hb_preset *p, const hb_material *m, const hb_options *o, unsigned lobe_mask)
{
    (void)m, (void)lobe_mask;
    return p->quality == o->quality && p->quadrature_order == o->quadrature_order && p->azimuthal == o->azimuthal;
}

/* its double-precision procedures (reference.h; the fast path includes none of it) */
extern const struct hb_reference_ops hb_ref_deon_ops;

const hb_model_ops hb_deon_model = {
    .name = "deon",
    .reference = &hb_ref_deon_ops,
    .state_size = sizeof(hb_deon_state),
    .table_version = 1,
    .lobes = lobes,
    .validate = hb_deon_validate,
    .derive = hb_deon_derive,
    .release = hb_deon_release,
    .eval_angles = eval_angles,
    .eval_vectors = eval_vectors,
    .sample_dimensions = sample_dimensions,
    .sample = sample,
    .pdf = pdf,
    .eval_pdf = eval_pdf,
    .eval_absorption = eval_absorption,
    .eval_near = eval_near,
    .sample_near = sample_near,
    .eval_near_absorption = eval_near_absorption,
    .spectral = spectral,
    .sample_spectral = sample_spectral,
    .pdf_near = pdf_near,
    .table = hb_deon_table_view,
    .shader_constants = hb_deon_shader_constants,
    .look = hb_deon_look,
    .set_look = hb_deon_set_look,
    .describe = describe,
    .furnace_rule = furnace_rule,
    .presets = presets,
    .preset_count = sizeof presets / sizeof presets[0],
    .preset_applies = preset_applies,
    .preset_is = preset_is,
    .drops_lobes = 1,
};

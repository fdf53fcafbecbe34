/* The interface every scattering model implements (docs/architecture.md). Plan creation asks a
 * model to validate its own options and to derive its constants and tables; the public entry points
 * evaluate, sample and describe through it; tolerance and budget plans choose among its named
 * configurations. A model defines one hb_model_ops in src/models/<model>/model.c, and
 * src/models/models.c lists them. Internal. */
#ifndef HB_MODELS_MODEL_H
#define HB_MODELS_MODEL_H

#include <string.h>

#include "kernel/streams.h"
#include "plan.h"
#include "models/text/text.h"

/* The error a quality level below reference aims at, relative to the peak f (docs/conventions.md). */
static inline double hb_quality_target(hb_quality q)
{
    static const double targets[] = { 1e-2, 1e-3, 1e-4 };
    return targets[q];
}

/* A named configuration, as the bench names its rows and the calibration its entries. */
typedef struct hb_preset {
    const char *name;
    hb_quality quality;
    int quadrature_order;
    hb_azimuthal azimuthal;
    hb_tt_trt tt_trt;
} hb_preset;

/* A material's look in terms every model converts through (hb_material_convert), in radians: the
 * R lobe's longitudinal standard deviation in theta_o, the azimuthal spread as a Gaussian's
 * standard deviation, and the tilt that puts the R peak at theta_o = -theta_i - 2 tilt. */
typedef struct hb_look {
    double longitudinal, azimuthal, tilt;
} hb_look;

typedef struct hb_model_ops {
    const char *name; /* "deon": as the CLI, the bench and the calibration name the model */
    const struct hb_reference_ops *reference; /* its double-precision procedures (its reference.h) */
    double beta_max; /* beta_m and beta_n at most this on the model's own scale (CBTB16: 1); 0: radians, the shared ranges */
    double beta_m_min; /* beta_m at least this on the model's own scale; 0: the shared range */
    size_t state_size; /* sizeof its state (src/models/<model>/state.h), allocated after the plan's head */

    /* Plan creation, after the checks every model shares (src/plan/validate.c). */
    unsigned (*lobes)(const hb_options *o); /* the lobe mask the options ask for (resolving HB_LOBES_DEFAULT) */
    hb_status (*validate)(const hb_material *m, const hb_options *o, hb_error *error);
    /* The plan's constants for plan->material, options and isa; sets plan->kernels to the ISA's
     * table, or NULL where the plan evaluates with the double reference; builds tables. */
    hb_status (*derive)(hb_plan *plan, hb_error *error);
    void (*release)(hb_plan *plan); /* frees what derive allocated */

    /* Evaluation by the plan's kernels (plan->kernels != NULL); invalid samples are counted. */
    void (*eval_angles)(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid);
    void (*eval_vectors)(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid);
    int (*sample_dimensions)(const hb_plan *plan); /* 0: the plan cannot sample */
    int (*pdf_is_estimate)(const hb_plan *plan); /* 1 where the pdf is a Monte-Carlo estimate; NULL: never */
    void (*sample)(const hb_plan *plan, size_t n, const hb_sample_batch *b, size_t *invalid);
    void (*pdf)(const hb_plan *plan, size_t n, const hb_pair_batch *in, float *pdf, size_t *invalid);
    /* f as eval_angles or eval_vectors gives it and the pdf, in one pass where the model's kernels
     * form both together, else in two (hb_eval_then_pdf). */
    void (*eval_pdf)(const hb_plan *plan, size_t n, const hb_pair_batch *in, hb_rgb_soa out, float *pdf,
                     size_t *invalid);
    /* f at each sample's absorption (hb_eval_angles_absorption), by the plan's kernels; NULL when the
     * model has none, HB_ERR_UNSUPPORTED for plans whose path cannot take it. */
    hb_status (*eval_absorption)(const hb_plan *plan, size_t n, const hb_absorbing_batch *in, hb_rgb_soa out,
                                 size_t *invalid);
    /* The version of the parameterisation of its tables' values, written into table files: a change
     * that alters what a table of the same layout holds bumps it, so that older files are refused. */
    int table_version;
    /* HB_ERR_UNSUPPORTED: no table; channels gets its floats per node and slot */
    hb_status (*table)(const hb_plan *plan, hb_table_view *view, int *channels);
    /* hb_plan_shader_constants: HB_SHADER_CONSTANTS floats; NULL when the model has no shader. */
    hb_status (*shader_constants)(const hb_plan *plan, float *constants);
    /* Near-field models: the same at each sample's offset h (plan->kernels != NULL); NULL when the
     * model has no near field. */
    void (*eval_near)(const hb_plan *plan, size_t n, hb_near_soa in, hb_rgb_soa out, size_t *invalid);
    void (*sample_near)(const hb_plan *plan, size_t n, hb_sample_streams in, hb_sample_out out, size_t *invalid);
    /* f at each sample's h and absorption (hb_eval_near_absorption); HB_ERR_UNSUPPORTED for plans
     * whose path cannot take it. */
    hb_status (*eval_near_absorption)(const hb_plan *plan, size_t n, const hb_absorbing_near *in, hb_rgb_soa out,
                                      size_t *invalid);
    void (*pdf_near)(const hb_plan *plan, size_t n, hb_near_soa in, float *pdf, size_t *invalid);
    /* k wavelengths per sample at their absorptions (hb_*_spectral), by the plan's kernels: f and the pdf
     * near-field or far (hb_spectral_batch), the near-field sampler; NULL when the model has none.
     * spectral returns HB_ERR_UNSUPPORTED for a batch the plan's path cannot take (f is then evaluated
     * through eval_absorption or eval_near_absorption, three wavelengths a call). */
    hb_status (*spectral)(const hb_plan *plan, size_t n, const hb_spectral_batch *b, size_t *invalid);
    void (*sample_spectral)(const hb_plan *plan, size_t n, const hb_spectral_sample_batch *b, size_t *invalid);

    /* The look of a material's roughness and tilt, and the parameters that give a look (the
     * material's others untouched); HB_ERR_PARAM when the look is beyond the model's range. */
    void (*look)(const hb_material *m, hb_look *look);
    hb_status (*set_look)(const hb_look *look, hb_material *m, hb_error *error);

    /* hb_plan_describe's model paragraph. */
    void (*describe)(hb_text *t, const hb_plan *plan);
    /* hb_furnace's rule: the narrowest longitudinal width and the azimuths the midpoint rule needs;
     * passes > 1 re-keys a Monte-Carlo estimator (rekey, on a copy of the plan) for each chunk. */
    void (*furnace_rule)(const hb_plan *plan, double *beta_m, int *azimuths, int *passes);
    void (*rekey)(hb_plan *copy, const hb_plan *plan, unsigned long long chunk);

    /* Tolerance and budget plans (src/plan/select.c): the named configurations; which compute the
     * options' model (only accuracy and cost differ) for a lobe set; which one plain options are;
     * whether a tolerance plan may drop lobes it measures as negligible. */
    const hb_preset *presets;
    int preset_count;
    int (*preset_applies)(const hb_preset *p, const hb_material *m, const hb_options *o, unsigned lobes);
    int (*preset_is)(const hb_preset *p, const hb_material *m, const hb_options *o, unsigned lobes);
    int drops_lobes;
} hb_model_ops;

/* A separable model's longitudinal term is one value per sample: copied to the other channels. */
static inline void hb_spread_channels(size_t n, hb_rgb_soa out)
{
    if (out.g != out.r)
        memcpy(out.g, out.r, n * sizeof(float));
    if (out.b != out.r)
        memcpy(out.b, out.r, n * sizeof(float));
}

/* A model's derive sets the plan's kernel tables from its per-ISA table (HB_PER_ISA): the plan's ISA's,
 * NULL for the double reference, and the scalar ISA's as the narrow one where the plan's is wider. */
#define HB_PLAN_SET_KERNELS(plan, table, reference)                                                    \
    do {                                                                                               \
        (plan)->kernels = (reference) ? NULL : (const void *)(table)[(plan)->isa];                     \
        (plan)->narrow_kernels = (plan)->kernels && (plan)->isa != HB_ISA_SCALAR                       \
                                     ? (const void *)(table)[HB_ISA_SCALAR] : NULL;                     \
    } while (0)

/* The kernels for a call of n samples: a call of one sample runs on the scalar kernels where the plan's
 * ISA is wider, since a vector block costs as much for one sample as for all its lanes (make bench,
 * the per-hit rows). Results agree with the wide kernels' within the ISAs' stated bound. */
static inline const void *hb_kernels_for(const hb_plan *plan, size_t n)
{
    return n == 1 && plan->narrow_kernels ? plan->narrow_kernels : plan->kernels;
}

/* The model of an hb_model value; NULL if there is none (src/models/models.c). */
const hb_model_ops *hb_model_ops_of(hb_model model);

/* eval_pdf in two passes over the batch: eval (as the batch's form asks), then pdf. */
static inline void hb_eval_then_pdf(const hb_plan *plan, size_t n, const hb_pair_batch *in, hb_rgb_soa out, float *pdf,
                                    size_t *invalid)
{
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    if (in->vectors.wi_x)
        ops->eval_vectors(plan, n, in->vectors, out, invalid);
    else
        ops->eval_angles(plan, n, in->angles, out, invalid);
    ops->pdf(plan, n, in, pdf, invalid);
}

#endif

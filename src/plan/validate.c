/* The checks every plan passes before its model's own (hb_model_ops.validate): each material
 * parameter and option in its range, and the option combinations no model has. */
#include <math.h>

#include "creation.h"

/* Valid ranges. v = beta_m^2 in [1e-6, 10] is where M_p's accuracy is tested. */
#define BETA_M_MIN 0.001
#define BETA_M_MAX 3.1622776601683795
#define BETA_N_MIN 0.02
#define BETA_N_MAX 3.0
#define ALPHA_MAX 0.2
#define LOBE_ALPHA_MAX 0.6 /* three times ALPHA_MAX, written out: 3 * 0.2 rounds above 0.6 */
#define ETA_MAX 10.0
#define ROUGHNESS_MIN 1e-3
#define ROUGHNESS_MAX 1.0
#define ECCENTRICITY_MAX 0.99

static int in_range(double x, double lo, double hi) { return x >= lo && x <= hi; } /* false for NaN */

/* beta_m and beta_n against their ranges: radians, or the model's own scale where it has one (CBTB16's [0, 1]). */
static hb_status validate_roughnesses(const hb_material *m, const hb_model_ops *ops, hb_error *error)
{
    double beta_m_min = ops->beta_m_min > 0.0 ? ops->beta_m_min : BETA_M_MIN;
    double beta_m_max = ops->beta_max > 0.0 ? ops->beta_max : BETA_M_MAX;
    double beta_n_max = ops->beta_max > 0.0 ? ops->beta_max : BETA_N_MAX;
    if (!in_range(m->beta_m, beta_m_min, beta_m_max))
        return hb_plan_fail(error, HB_ERR_PARAM, "beta_m = %s must be in [%s, %s] for the %s model (a lobe's v >= 1e-6)",
                            HB_NUM(m->beta_m), HB_NUM(beta_m_min), HB_NUM(beta_m_max), ops->name);
    for (int p = 0; p < HB_MAX_LOBES; p++)
        if (m->lobe_beta_m[p] != 0.0 && !in_range(m->lobe_beta_m[p], BETA_M_MIN, beta_m_max))
            return hb_plan_fail(error, HB_ERR_PARAM, "lobe_beta_m[%d] = %s must be 0 (derived) or in [%s, %s]", p,
                                HB_NUM(m->lobe_beta_m[p]), HB_NUM(BETA_M_MIN), HB_NUM(beta_m_max));
    if (!in_range(m->beta_n, BETA_N_MIN, beta_n_max))
        return hb_plan_fail(error, HB_ERR_PARAM, "beta_n = %s must be in [%s, %s] for the %s model", HB_NUM(m->beta_n),
                            HB_NUM(BETA_N_MIN), HB_NUM(beta_n_max), ops->name);
    for (int p = 0; p < HB_MAX_LOBES; p++)
        if (m->lobe_beta_n[p] != 0.0 && !in_range(m->lobe_beta_n[p], BETA_N_MIN, beta_n_max))
            return hb_plan_fail(error, HB_ERR_PARAM, "lobe_beta_n[%d] = %s must be 0 (derived) or in [%s, %s]", p,
                                HB_NUM(m->lobe_beta_n[p]), HB_NUM(BETA_N_MIN), HB_NUM(beta_n_max));
    return HB_OK;
}

static hb_status validate_material(const hb_material *m, hb_error *error)
{
    if (!(m->eta > 1.0 && m->eta <= ETA_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "eta = %s must be in (1, %s]", HB_NUM(m->eta), HB_NUM(ETA_MAX));
    static const char *const channel[3] = { "r", "g", "b" };
    for (int c = 0; c < 3; c++)
        if (!(m->sigma_a[c] >= 0.0 && isfinite(m->sigma_a[c])))
            return hb_plan_fail(error, HB_ERR_PARAM, "sigma_a.%s = %s must be finite and >= 0", channel[c], HB_NUM(m->sigma_a[c]));
    if (!(m->eumelanin >= 0.0 && isfinite(m->eumelanin)))
        return hb_plan_fail(error, HB_ERR_PARAM, "eumelanin = %s must be finite and >= 0", HB_NUM(m->eumelanin));
    if (!(m->pheomelanin >= 0.0 && isfinite(m->pheomelanin)))
        return hb_plan_fail(error, HB_ERR_PARAM, "pheomelanin = %s must be finite and >= 0", HB_NUM(m->pheomelanin));
    if (!in_range(m->alpha, -ALPHA_MAX, ALPHA_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "alpha = %s must be in [%s, %s] radians", HB_NUM(m->alpha), HB_NUM(-ALPHA_MAX), HB_NUM(ALPHA_MAX));
    for (int p = 0; p < HB_MAX_LOBES; p++)
        if ((m->lobe_alpha_override >> p & 1u) && !in_range(m->lobe_alpha[p], -LOBE_ALPHA_MAX, LOBE_ALPHA_MAX))
            return hb_plan_fail(error, HB_ERR_PARAM, "lobe_alpha[%d] = %s must be in [%s, %s] radians", p, HB_NUM(m->lobe_alpha[p]),
                        HB_NUM(-LOBE_ALPHA_MAX), HB_NUM(LOBE_ALPHA_MAX));
    if (m->ndf != HB_NDF_GGX && m->ndf != HB_NDF_BECKMANN)
        return hb_plan_fail(error, HB_ERR_PARAM, "ndf = %d is neither HB_NDF_GGX nor HB_NDF_BECKMANN", (int)m->ndf);
    if (!in_range(m->roughness, ROUGHNESS_MIN, ROUGHNESS_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "roughness = %s must be in [%s, %s]", HB_NUM(m->roughness), HB_NUM(ROUGHNESS_MIN),
                    HB_NUM(ROUGHNESS_MAX));
    if (!in_range(m->eccentricity, 0.0, ECCENTRICITY_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "eccentricity = %s must be in [0, %s]", HB_NUM(m->eccentricity),
                    HB_NUM(ECCENTRICITY_MAX));
    if (!in_range(m->glint_scale, 0.0, 100.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "glint_scale = %s must be in [0, 100]", HB_NUM(m->glint_scale));
    if (!in_range(m->caustic_width, 1e-3, 1.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "caustic_width = %s must be in [0.001, 1] radians", HB_NUM(m->caustic_width));
    if (!in_range(m->caustic_fade, 1e-3, 2.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "caustic_fade = %s must be in [0.001, 2]", HB_NUM(m->caustic_fade));
    if (!in_range(m->caustic_limit, 0.0, 2.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "caustic_limit = %s must be in [0, 2]", HB_NUM(m->caustic_limit));
    return HB_OK;
}

/* The options' ranges and the combinations no model has; each model then checks its own. */
static hb_status validate_options(const hb_options *o, hb_error *error)
{
    if (!hb_model_ops_of(o->model))
        return hb_plan_fail(error, HB_ERR_PARAM, "model = %d is not a model", (int)o->model);
    if ((unsigned)o->tt_trt > HB_TT_TRT_AUTO)
        return hb_plan_fail(error, HB_ERR_PARAM, "tt_trt = %d is not a TT/TRT evaluation method", (int)o->tt_trt);
    if (o->tt_panels < 0 || o->tt_panels > HB_MAX_TT_PANELS || o->tt_panels % 2)
        return hb_plan_fail(error, HB_ERR_PARAM, "tt_panels = %d must be 0 (from quality) or even, in [2, %d]", o->tt_panels,
                            HB_MAX_TT_PANELS);
    if (o->term != HB_TERM_FULL && o->term != HB_TERM_LONGITUDINAL)
        return hb_plan_fail(error, HB_ERR_PARAM, "term = %d is not a term", (int)o->term);
    if (o->pmax < 0 || o->pmax >= HB_MAX_LOBES)
        return hb_plan_fail(error, HB_ERR_PARAM, "pmax = %d must be in [0, %d]", o->pmax, HB_MAX_LOBES - 1);
    unsigned allowed = (2u << o->pmax) - 1u;
    if (o->term == HB_TERM_LONGITUDINAL && o->lobes != HB_LOBES_DEFAULT && o->lobes != 1u << HB_LOBE_R)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the longitudinal term is evaluated for the R lobe only");
    if (o->term == HB_TERM_FULL && (o->lobes & ~(allowed | 1u << HB_LOBE_RESIDUAL)))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "lobes = 0x%x asks for an order above pmax = %d", o->lobes, o->pmax);
    if ((unsigned)o->quality > HB_QUALITY_REFERENCE)
        return hb_plan_fail(error, HB_ERR_PARAM, "quality = %d is not a quality level", (int)o->quality);
    if (o->i0 != HB_I0_ABRAMOWITZ && o->i0 != HB_I0_PAPER)
        return hb_plan_fail(error, HB_ERR_PARAM, "i0 = %d is not an I0 variant", (int)o->i0);
    if (o->absorption != HB_ABSORPTION_CORRECTED && o->absorption != HB_ABSORPTION_PAPER)
        return hb_plan_fail(error, HB_ERR_PARAM, "absorption = %d is not an absorption variant", (int)o->absorption);
    if (o->r_fresnel != HB_R_FRESNEL_HALF_ANGLE && o->r_fresnel != HB_R_FRESNEL_OFFSET)
        return hb_plan_fail(error, HB_ERR_PARAM, "r_fresnel = %d is not a variant", (int)o->r_fresnel);
    if (o->pole_floor != HB_POLE_FLOOR_AUTO && o->pole_floor != HB_POLE_FLOOR_BOUNDED && o->pole_floor != HB_POLE_FLOOR_PAPER)
        return hb_plan_fail(error, HB_ERR_PARAM, "pole_floor = %d is not a variant", (int)o->pole_floor);
    if (!(o->tolerance == 0.0 || in_range(o->tolerance, 1e-6, 0.5)))
        return hb_plan_fail(error, HB_ERR_PARAM, "tolerance = %g must be 0 (none) or in [1e-6, 0.5]", o->tolerance);
    if (!(o->budget_ns == 0.0 || in_range(o->budget_ns, 1e-3, 1e9)))
        return hb_plan_fail(error, HB_ERR_PARAM, "budget_ns = %g must be 0 (none) or in [0.001, 1e9]", o->budget_ns);
    if (o->tolerance > 0.0 && o->budget_ns > 0.0)
        return hb_plan_fail(error, HB_ERR_PARAM, "tolerance and budget_ns exclude each other: a plan meets one or the other");
    if ((o->tolerance > 0.0 || o->budget_ns > 0.0) && (o->quality == HB_QUALITY_REFERENCE || o->term != HB_TERM_FULL))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "a tolerance or budget plan chooses among the float configurations of "
                    "the full model: not with the reference quality or the longitudinal term");
    if ((o->table_file != NULL) != (o->table_file_size > 0))
        return hb_plan_fail(error, HB_ERR_PARAM, "table_file and table_file_size go together: give both or neither");
    if (o->table_file_size > HB_TABLE_FILE_MAX_BYTES)
        return hb_plan_fail(error, HB_ERR_FILE, "table file: %zu bytes, larger than any plan's table file (at most %zu)",
                            o->table_file_size, HB_TABLE_FILE_MAX_BYTES);
    if (o->table_file && (o->tolerance > 0.0 || o->budget_ns > 0.0))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "a table file fixes the configuration it was baked with: give its "
                    "quality and options, not a tolerance or budget_ns");
    if (o->azimuthal != HB_AZIMUTHAL_QUADRATURE && o->azimuthal != HB_AZIMUTHAL_TABLE &&
        o->azimuthal != HB_AZIMUTHAL_COLOUR_TABLE)
        return hb_plan_fail(error, HB_ERR_PARAM, "azimuthal = %d is not a variant", (int)o->azimuthal);
    if (!(o->table_tolerance == 0.0 || in_range(o->table_tolerance, 1e-6, 0.5)))
        return hb_plan_fail(error, HB_ERR_PARAM, "table_tolerance = %g must be 0 (from quality) or in [1e-6, 0.5]",
                    o->table_tolerance);
    if (o->quadrature_order < 0 || o->quadrature_order > HB_MAX_QUADRATURE_ORDER)
        return hb_plan_fail(error, HB_ERR_PARAM, "quadrature_order = %d must be 0 (from quality) or in [1, %d]",
                    o->quadrature_order, HB_MAX_QUADRATURE_ORDER);
    if (o->detector_tolerance != 0.0 && !in_range(o->detector_tolerance, 1e-12, 0.1))
        return hb_plan_fail(error, HB_ERR_PARAM, "detector_tolerance = %g must be 0 (from quality) or in [1e-12, 0.1]",
                    o->detector_tolerance);
    if ((unsigned)o->isa >= HB_ISA_COUNT)
        return hb_plan_fail(error, HB_ERR_PARAM, "isa = %d is not an instruction set", (int)o->isa);
    if (o->shadowing != HB_SHADOWING_SMITH && o->shadowing != HB_SHADOWING_NONE)
        return hb_plan_fail(error, HB_ERR_PARAM, "shadowing = %d is not a shadowing variant", (int)o->shadowing);
    if ((unsigned)o->r_integration > HB_R_INTEGRATION_NUMERIC)
        return hb_plan_fail(error, HB_ERR_PARAM, "r_integration = %d is not an integration method", (int)o->r_integration);
    if (o->r_panels < 0 || o->r_panels > HB_MAX_R_PANELS || o->r_panels % 2)
        return hb_plan_fail(error, HB_ERR_PARAM, "r_panels = %d must be 0 (from quality) or even, in [2, %d]", o->r_panels,
                    HB_MAX_R_PANELS);
    if (!(o->r_step == 0.0 || in_range(o->r_step, 1e-3, 10.0)))
        return hb_plan_fail(error, HB_ERR_PARAM, "r_step = %g must be 0 (peak-following panels) or in [0.001, 10]",
                    o->r_step);
    if (o->r_step > 0.0 && o->r_panels > 0)
        return hb_plan_fail(error, HB_ERR_PARAM, "r_step and r_panels exclude each other: the step fixes the panels");
    return HB_OK;
}

hb_status hb_plan_validate(const hb_material *m, const hb_options *o, hb_error *error)
{
    hb_status st = validate_options(o, error);
    if (st == HB_OK)
        st = validate_material(m, error);
    if (st == HB_OK)
        st = validate_roughnesses(m, hb_model_ops_of(o->model), error);
    return st == HB_OK ? hb_model_ops_of(o->model)->validate(m, o, error) : st;
}

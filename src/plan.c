/* Material and option defaults, validation, and plan creation: everything that
 * depends only on the material is computed here, once, in double precision. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plan.h"
#include "quadrature.h"

/* Valid ranges. v = beta_m^2 in [1e-4, 10] is where M_p's accuracy is tested. */
#define BETA_M_MIN 0.01
#define BETA_M_MAX 3.1622776601683795
#define BETA_N_MIN 0.02
#define BETA_N_MAX 3.0
#define ALPHA_MAX 0.2
#define LOBE_ALPHA_MAX 0.6 /* three times ALPHA_MAX, written out: 3 * 0.2 rounds above 0.6 */
#define ETA_MAX 10.0
#define ROUGHNESS_MIN 1e-3
#define ROUGHNESS_MAX 1.0
#define ECCENTRICITY_MAX 0.99

void hb_material_default(hb_material *m)
{
    if (!m)
        return;
    memset(m, 0, sizeof *m);
    m->struct_size = sizeof *m;
    m->eta = 1.55;
    m->beta_m = 0.1;
    m->beta_n = 0.3;
    m->alpha = 0.035;
    m->ndf = HB_NDF_GGX;
    m->roughness = 0.1;
    m->glint_scale = 0.5;
    m->caustic_width = 15.0 * M_PI / 180.0;
    m->caustic_fade = 0.3;
    m->caustic_limit = 0.5;
}

void hb_material_absorption(const hb_material *m, double out[3])
{
    /* dFH11 sec. 6.1: RGB absorption of eumelanin and pheomelanin per unit concentration. */
    static const double eumelanin_rgb[3] = { 0.419, 0.697, 1.37 };
    static const double pheomelanin_rgb[3] = { 0.187, 0.4, 1.05 };
    for (int c = 0; c < 3; c++)
        out[c] = m->sigma_a[c] + m->eumelanin * eumelanin_rgb[c] + m->pheomelanin * pheomelanin_rgb[c];
}

void hb_options_default(hb_options *o)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->struct_size = sizeof *o;
    o->model = HB_MODEL_DEON;
    o->lobes = HB_LOBES_DEFAULT;
    o->term = HB_TERM_FULL;
    o->quality = HB_QUALITY_BALANCED;
    o->isa = HB_ISA_AUTO;
    o->i0 = HB_I0_ABRAMOWITZ;
    o->pmax = 3;
    o->absorption = HB_ABSORPTION_CORRECTED;
}

hb_status hb_plan_fail(hb_error *error, hb_status status, const char *fmt, ...)
{
    if (error) {
        va_list ap;
        va_start(ap, fmt);
        error->status = status;
        vsnprintf(error->message, sizeof error->message, fmt, ap);
        va_end(ap);
    }
    return status;
}

static int in_range(double x, double lo, double hi) { return x >= lo && x <= hi; } /* false for NaN */

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

static hb_status upgrade_structs(const hb_material *material, const hb_options *options, hb_material *m,
                                 hb_options *o, hb_error *error)
{
    hb_material_default(m);
    hb_options_default(o);
    hb_status st = upgrade_struct("hb_material", material, material->struct_size, m, sizeof *m, _Alignof(hb_material), error);
    if (st == HB_OK)
        st = upgrade_struct("hb_options", options, options->struct_size, o, sizeof *o, _Alignof(hb_options), error);
    m->struct_size = sizeof *m;
    o->struct_size = sizeof *o;
    return st;
}

static hb_status validate_material(const hb_material *m, hb_error *error)
{
    if (!(m->eta > 1.0 && m->eta <= ETA_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "eta = %g must be in (1, %g]", m->eta, ETA_MAX);
    static const char *const channel[3] = { "r", "g", "b" };
    for (int c = 0; c < 3; c++)
        if (!(m->sigma_a[c] >= 0.0 && isfinite(m->sigma_a[c])))
            return hb_plan_fail(error, HB_ERR_PARAM, "sigma_a.%s = %g must be finite and >= 0", channel[c], m->sigma_a[c]);
    if (!(m->eumelanin >= 0.0 && isfinite(m->eumelanin)))
        return hb_plan_fail(error, HB_ERR_PARAM, "eumelanin = %g must be finite and >= 0", m->eumelanin);
    if (!(m->pheomelanin >= 0.0 && isfinite(m->pheomelanin)))
        return hb_plan_fail(error, HB_ERR_PARAM, "pheomelanin = %g must be finite and >= 0", m->pheomelanin);
    if (!in_range(m->beta_m, BETA_M_MIN, BETA_M_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "beta_m = %g must be in [%g, %g] (v = beta_m^2 in [1e-4, 10])",
                    m->beta_m, BETA_M_MIN, BETA_M_MAX);
    for (int p = 0; p < HB_MAX_LOBES; p++)
        if (m->lobe_beta_m[p] != 0.0 && !in_range(m->lobe_beta_m[p], BETA_M_MIN, BETA_M_MAX))
            return hb_plan_fail(error, HB_ERR_PARAM, "lobe_beta_m[%d] = %g must be 0 (derived) or in [%g, %g]", p,
                        m->lobe_beta_m[p], BETA_M_MIN, BETA_M_MAX);
    if (!in_range(m->beta_n, BETA_N_MIN, BETA_N_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "beta_n = %g must be in [%g, %g]", m->beta_n, BETA_N_MIN, BETA_N_MAX);
    for (int p = 0; p < HB_MAX_LOBES; p++)
        if (m->lobe_beta_n[p] != 0.0 && !in_range(m->lobe_beta_n[p], BETA_N_MIN, BETA_N_MAX))
            return hb_plan_fail(error, HB_ERR_PARAM, "lobe_beta_n[%d] = %g must be 0 (derived) or in [%g, %g]", p,
                        m->lobe_beta_n[p], BETA_N_MIN, BETA_N_MAX);
    if (!in_range(m->alpha, -ALPHA_MAX, ALPHA_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "alpha = %g must be in [%g, %g] radians", m->alpha, -ALPHA_MAX, ALPHA_MAX);
    for (int p = 0; p < HB_MAX_LOBES; p++)
        if ((m->lobe_alpha_override >> p & 1u) && !in_range(m->lobe_alpha[p], -LOBE_ALPHA_MAX, LOBE_ALPHA_MAX))
            return hb_plan_fail(error, HB_ERR_PARAM, "lobe_alpha[%d] = %g must be in [%g, %g] radians", p, m->lobe_alpha[p],
                        -LOBE_ALPHA_MAX, LOBE_ALPHA_MAX);
    if (m->ndf != HB_NDF_GGX && m->ndf != HB_NDF_BECKMANN)
        return hb_plan_fail(error, HB_ERR_PARAM, "ndf = %d is neither HB_NDF_GGX nor HB_NDF_BECKMANN", (int)m->ndf);
    if (!in_range(m->roughness, ROUGHNESS_MIN, ROUGHNESS_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "roughness = %g must be in [%g, %g]", m->roughness, ROUGHNESS_MIN,
                    ROUGHNESS_MAX);
    if (!in_range(m->eccentricity, 0.0, ECCENTRICITY_MAX))
        return hb_plan_fail(error, HB_ERR_PARAM, "eccentricity = %g must be in [0, %g]", m->eccentricity,
                    ECCENTRICITY_MAX);
    if (!in_range(m->glint_scale, 0.0, 100.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "glint_scale = %g must be in [0, 100]", m->glint_scale);
    if (!in_range(m->caustic_width, 1e-3, 1.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "caustic_width = %g must be in [0.001, 1] radians", m->caustic_width);
    if (!in_range(m->caustic_fade, 1e-3, 2.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "caustic_fade = %g must be in [0.001, 2]", m->caustic_fade);
    if (!in_range(m->caustic_limit, 0.0, 2.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "caustic_limit = %g must be in [0, 2]", m->caustic_limit);
    return HB_OK;
}

/* What exists so far: the dFH11 model, and its longitudinal function M_p of the R lobe alone. */
static hb_status validate_options(const hb_options *o, hb_error *error)
{
    if (o->model != HB_MODEL_DEON && o->model != HB_MODEL_MARSCHNER && o->model != HB_MODEL_HUANG)
        return hb_plan_fail(error, HB_ERR_PARAM, "model = %d is not a model", (int)o->model);
    if (o->model == HB_MODEL_MARSCHNER && o->term == HB_TERM_FULL && o->lobes != HB_LOBES_DEFAULT &&
        (o->lobes & ~7u))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "lobes = 0x%x: the marschner model has R, TT and TRT only", o->lobes);
    if (o->model == HB_MODEL_HUANG && o->lobes != HB_LOBES_DEFAULT && (o->lobes & ~7u))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "lobes = 0x%x: the huang model has R, TT and TRT only (HHH22 eq. 3)",
                            o->lobes);
    if ((unsigned)o->tt_trt > HB_TT_TRT_TABLE)
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
    if (!(o->tolerance == 0.0 || in_range(o->tolerance, 1e-6, 0.5)))
        return hb_plan_fail(error, HB_ERR_PARAM, "tolerance = %g must be 0 (none) or in [1e-6, 0.5]", o->tolerance);
    if (!(o->budget_ns == 0.0 || in_range(o->budget_ns, 1e-3, 1e9)))
        return hb_plan_fail(error, HB_ERR_PARAM, "budget_ns = %g must be 0 (none) or in [0.001, 1e9]", o->budget_ns);
    if (o->tolerance > 0.0 && o->budget_ns > 0.0)
        return hb_plan_fail(error, HB_ERR_PARAM, "tolerance and budget_ns exclude each other: a plan meets one or the other");
    if ((o->tolerance > 0.0 || o->budget_ns > 0.0) && (o->quality == HB_QUALITY_REFERENCE || o->term != HB_TERM_FULL))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "a tolerance or budget plan chooses among the float configurations of "
                    "the full model: not with the reference quality or the longitudinal term");
    if (o->azimuthal != HB_AZIMUTHAL_QUADRATURE && o->azimuthal != HB_AZIMUTHAL_TABLE)
        return hb_plan_fail(error, HB_ERR_PARAM, "azimuthal = %d is not a variant", (int)o->azimuthal);
    if (!(o->table_tolerance == 0.0 || in_range(o->table_tolerance, 1e-6, 0.5)))
        return hb_plan_fail(error, HB_ERR_PARAM, "table_tolerance = %g must be 0 (from quality) or in [1e-6, 0.5]",
                    o->table_tolerance);
    if (o->azimuthal == HB_AZIMUTHAL_TABLE) {
        if (o->model != HB_MODEL_DEON)
            return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the N_p table is dFH11's (model deon); huang tabulates TT/TRT "
                        "with tt_trt = table, marschner has none");
        if (o->term != HB_TERM_FULL || o->quality == HB_QUALITY_REFERENCE)
            return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the N_p table is a float fast path of the full model: not with "
                        "the longitudinal term or the reference quality");
        if (o->r_fresnel != HB_R_FRESNEL_OFFSET)
            return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the N_p table needs the offset R Fresnel: eq. 12's half-angle "
                        "factor is not a function of (phi, theta_d)");
    }
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

/* HHH22: R, TT and TRT; the R lobe's closed form (App. A) covers GGX without G on circular fibres. */
static hb_status validate_huang(const hb_material *m, const hb_options *o, hb_error *error)
{
    if (o->term != HB_TERM_FULL)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the huang model is not separable: it has no longitudinal term");
    if (o->tt_trt == HB_TT_TRT_TABLE && o->quality == HB_QUALITY_REFERENCE)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the TT/TRT table is a float fast path: the reference quality "
                                               "evaluates TT and TRT by nested quadrature instead");
    if (o->absorption != HB_ABSORPTION_CORRECTED)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED,
                    "huang traces the chord itself (HHH22 eq. 17 note): there is no paper absorption variant");
    if (o->r_integration == HB_R_INTEGRATION_ANALYTIC) {
        if (m->ndf != HB_NDF_GGX)
            return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the analytic R integral (HHH22 App. A) exists for GGX only");
        if (o->shadowing != HB_SHADOWING_NONE)
            return hb_plan_fail(error, HB_ERR_UNSUPPORTED,
                        "the analytic R integral (HHH22 App. A) has no shadowing term: ask for no shadowing");
        if (m->eccentricity > 0.0)
            return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the analytic R integral (HHH22 App. A) is for circular fibres");
        if (o->r_step > 0.0 || o->r_panels > 0)
            return hb_plan_fail(error, HB_ERR_PARAM, "r_step and r_panels set the numeric R integral, not the analytic one");
    }
    if (o->r_step > 0.0 && ceil(M_PI / (o->r_step * m->roughness)) > HB_MAX_R_PANELS)
        return hb_plan_fail(error, HB_ERR_PARAM, "r_step = %g at roughness %g needs %.0f panels, more than %d", o->r_step,
                    m->roughness, 2.0 * ceil(M_PI / (2.0 * o->r_step * m->roughness)), HB_MAX_R_PANELS);
    return HB_OK;
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

/* Each quality level is an error target for f (docs/conventions.md): 1e-2, 1e-3, 1e-4. The quality
 * rules integrate N_p by Gauss-Legendre in a mapped variable (deon_nodes), whose node count the
 * narrowest lobe sets: R's exit azimuth -2 gamma_i moves twice as fast as gamma_i, so its detector
 * is beta_n / 2 wide in gamma_i. Measured against the reference (white, blond, brown and black hair,
 * beta_m 0.05 and 0.3, beta_n 0.02..1, 512 directions), nodes = ceil(c / beta_n + d), at least
 * min_nodes, meets each target with one to four nodes to spare (none for fast at 0.7, balanced at 0.4)
 * (docs/deon.md), nodes being the rule's points with gamma_i >= 0 (order 2 nodes). */
static const struct {
    double c, d; /* nodes = ceil(c / smallest beta_n of the plan's lobes + d) */
    int min_nodes;
    double detector_tolerance;
} quality_levels[] = {
    [HB_QUALITY_FAST] = { 2.25, 1.0, 5, 1e-3 },
    [HB_QUALITY_BALANCED] = { 2.7, 1.0, 8, 1e-4 },
    [HB_QUALITY_HIGH] = { 3.05, 1.5, 10, 1e-6 },
    [HB_QUALITY_REFERENCE] = { 3.05, 1.5, 10, 1e-6 }, /* unused: the reference converges on its own */
};

/* The map of the quality rules' nodes: gamma_i = (pi/2) asin(a u) / asin(a) for Gauss-Legendre
 * points u in [-1, 1] (Kosloff and Tal-Ezer's map, J. Comput. Phys. 104, 1993), which spreads the
 * points that Gauss-Legendre crowds toward h = +-1 over the middle of the fibre, where R's narrow
 * detector moves; a = 0.8 keeps the mapped integrand analytic well beyond [-1, 1] (its branch points
 * at u = +-1.25), so convergence stays geometric. At beta_n 0.3 it needs 8 / 9 / 11 nodes for
 * 1e-2 / 1e-3 / 1e-4 where Gauss-Legendre in gamma_i needs 9 / 11 / 12 (the quality rules above take
 * 9 / 10 / 12, the paper's order 35 is 18); at beta_n 0.02, 110 / 132 / 151 against 128 / 153 / 175. */
#define HB_NODE_MAP 0.8

/* dFH11 sec. 6 shifts: M_p is evaluated at theta_o - alpha_p with alpha_R = -2 alpha
 * (the R highlight moves toward the root for alpha > 0), alpha_TT = alpha, alpha_TRT = 3 alpha
 * (MJC03 Table 1 ratios -alpha_R/2 and -3 alpha_R/2), and no shift above TRT. */
static double lobe_shift(const hb_material *m, int p)
{
    if (p < HB_MAX_LOBES && (m->lobe_alpha_override >> p & 1u))
        return m->lobe_alpha[p];
    static const double ratio[3] = { -2.0, 1.0, 3.0 };
    return p < 3 ? ratio[p] * m->alpha : 0.0;
}

/* An absorption coefficient as the kernels' float: any finite double is valid, but one above
 * FLT_MAX would become +Inf and Inf * 0 (a zero path length) NaN; past 1e30 per radius every
 * path but a zero-length one is absorbed entirely, so 1e30 stands for all of them. */
static float absorption_float(double sigma_a) { return (float)fmin(sigma_a, 1e30); }

static hb_dielectric dielectric_of(double eta)
{
    return (hb_dielectric){ (float)eta, (float)(1.0 / (eta * eta)), (float)((eta - 1.0) * (eta + 1.0)) };
}

/* dFH11 eq. 7 constants, in double, and rounded for the float path. */
static void derive_longitudinal(hb_longitudinal *l, double v, double shift, hb_quality quality)
{
    l->inv_v = 1.0 / v;
    l->log_norm = -log(v) - log(-expm1(-2.0 / v));
    l->shift = shift;
    l->cos_shift = cos(shift);
    l->sin_shift = sin(shift);
    l->single = quality < HB_QUALITY_HIGH;
    l->inv_v_f = (float)l->inv_v;
    l->inv_v_log2e_f = (float)(l->inv_v * M_LOG2E);
    l->log2_norm_f = (float)(l->log_norm * M_LOG2E);
    l->cos_shift_f = (float)l->cos_shift;
    l->sin_shift_f = (float)l->sin_shift;
    /* theta_o - shift reflected across a pole: pi - (theta_o - shift) = -theta_o - (-shift - pi),
     * -pi - (theta_o - shift) = -theta_o - (pi - shift) */
    const double c[3] = { shift, -shift - M_PI, M_PI - shift };
    for (int k = 0; k < 3; k++) {
        l->shift_hi[k] = (float)c[k];
        l->shift_lo[k] = (float)(c[k] - (double)l->shift_hi[k]);
    }
}

/* The cheaper truncation of the wrapped Gaussian (eq. 11) whose error, relative to its
 * peak, is below tol. Cost model: a direct term is two exponentials (detection at phi
 * and -phi); the Fourier series needs one cosine per node and one multiply-add per term. */
static void derive_detector(hb_detector *d, double beta, double tol)
{
    int k = 0; /* direct: |x| <= pi after wrapping, the first neglected Gaussian is (2k+1) pi away */
    while (k < HB_MAX_DETECTOR_TERMS && 2.0 * exp(-pow((2 * k + 1) * M_PI, 2) / (2 * beta * beta)) > tol)
        k++;
    int n = 1; /* Fourier: the tail after n terms, relative to the peak >= 1/(2 pi) */
    while (n < HB_MAX_DETECTOR_TERMS && 2.0 * exp(-pow(n + 1, 2) * beta * beta / 2) /
                                            (1.0 - exp(-(2.0 * n + 3.0) * beta * beta / 2)) > tol)
        n++;
    int fourier_converged = 2.0 * exp(-pow(n + 1, 2) * beta * beta / 2) /
                                (1.0 - exp(-(2.0 * n + 3.0) * beta * beta / 2)) <= tol;
    double direct_cost = 2.0 * (2 * k + 1) * 18.0, fourier_cost = 28.0 + 4.0 * n;
    memset(d, 0, sizeof *d);
    d->fourier = fourier_converged && fourier_cost < direct_cost;
    d->terms = d->fourier ? n : k;
    d->log2e_over_two_beta2 = (float)(M_LOG2E / (2.0 * beta * beta));
    d->gauss_norm = (float)(1.0 / (beta * sqrt(2.0 * M_PI)));
    d->coeff[0] = (float)(0.5 / M_PI);
    for (int j = 1; j <= HB_MAX_DETECTOR_TERMS; j++)
        d->coeff[j] = (float)(exp(-0.5 * j * j * beta * beta) / M_PI);
}

/* eq. 10's integral over h in [-1, 1] by the order-n Gauss-Legendre rule in gamma_i over
 * [-pi/2, pi/2] (h = sin gamma_i, so the h^(1/2) behaviour of gamma_i at h = +-1 is smooth; the
 * weight carries dh = cos gamma_i dgamma_i and eq. 10's 1/2), or with `mapped` in u of
 * HB_NODE_MAP (the weight then carries dgamma_i / du too). By the symmetry of dFH11 sec. 6
 * (A even in h, Phi odd), nodes +-gamma pair into one node at gamma >= 0 detected at phi and -phi:
 * (n + 1) / 2 nodes are evaluated, the centre (n odd) with half its weight. The paper's
 * "quadrature of order 35" is n = 35 unmapped: 18 nodes. */
static void deon_nodes(hb_deon *d, int n, int mapped)
{
    double gamma[HB_MAX_QUADRATURE_ORDER], w[HB_MAX_QUADRATURE_ORDER];
    hb_gauss_legendre(n, -1.0, 1.0, gamma, w);
    d->order = n;
    d->mapped = mapped;
    d->nodes = (n + 1) / 2;
    const double a = HB_NODE_MAP, asin_a = asin(a);
    for (int j = 0; j < d->nodes; j++) {
        int k = n / 2 + j, centre = (n & 1) && j == 0;
        double u = centre ? 0.0 : gamma[k]; /* the rule's centre is 0 up to rounding */
        double g = mapped ? M_PI_2 * asin(a * u) / asin_a : M_PI_2 * u;
        w[k] *= mapped ? M_PI_2 * a / (asin_a * sqrt(1.0 - a * a * u * u)) : M_PI_2; /* dgamma_i / du */
        d->gamma_i[j] = (float)g;
        d->cos_gamma_i[j] = (float)cos(g);
        d->h[j] = (float)sin(g);
        d->weight[j] = (float)((centre ? 0.25 : 0.5) * w[k] * cos(g));
    }
}

static void derive_deon(hb_plan *plan)
{
    const hb_material *m = &plan->material;
    const hb_options *o = &plan->options;
    hb_deon *d = &plan->deon;
    hb_material_absorption(m, plan->sigma_a);
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        /* the residual lobe takes the roughness of the highest explicit order, and no shift */
        int q = p == HB_LOBE_RESIDUAL ? o->pmax : p;
        double beta = m->lobe_beta_m[q] > 0.0 ? m->lobe_beta_m[q] : m->beta_m;
        plan->v[p] = beta * beta;
        derive_longitudinal(&d->longitudinal[p], plan->v[p], p == HB_LOBE_RESIDUAL ? 0.0 : lobe_shift(m, p), o->quality);
    }
    double tol = o->detector_tolerance > 0.0 ? o->detector_tolerance : quality_levels[o->quality].detector_tolerance;
    for (int p = 0; p < HB_MAX_LOBES; p++) {
        plan->beta_n[p] = m->lobe_beta_n[p] > 0.0 ? m->lobe_beta_n[p] : m->beta_n;
        derive_detector(&d->detector[p], plan->beta_n[p], tol);
    }
    unsigned all = ((2u << o->pmax) - 1u) | 1u << HB_LOBE_RESIDUAL;
    d->lobes = o->lobes == HB_LOBES_DEFAULT ? all : o->lobes;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        d->m_group[p] = p;
        for (int q = 0; q < p; q++)
            if ((d->lobes >> q & 1u) && q <= o->pmax && d->m_group[q] == q &&
                d->longitudinal[q].inv_v == d->longitudinal[p].inv_v &&
                d->longitudinal[q].shift == d->longitudinal[p].shift) {
                d->m_group[p] = q;
                break;
            }
    }
    d->pmax = o->pmax;
    d->fourier_terms = 0;
    for (int p = 0; p <= o->pmax; p++)
        if (d->detector[p].fourier && d->detector[p].terms > d->fourier_terms)
            d->fourier_terms = d->detector[p].terms;
    d->absorption_paper = o->absorption == HB_ABSORPTION_PAPER;
    d->r_fresnel_offset = o->r_fresnel == HB_R_FRESNEL_OFFSET;
    int nearest = 1;
    for (int p = 0; p <= o->pmax; p++)
        nearest = nearest && !d->detector[p].fourier && d->detector[p].terms == 0;
    d->standard = o->pmax == HB_STANDARD_PMAX && nearest && !d->absorption_paper && d->r_fresnel_offset;
    d->ior = dielectric_of(m->eta);
    for (int c = 0; c < 3; c++)
        d->sigma_a_log2e[c] = absorption_float(plan->sigma_a[c] * M_LOG2E);
    d->channels = d->sigma_a_log2e[0] == d->sigma_a_log2e[1] && d->sigma_a_log2e[1] == d->sigma_a_log2e[2] ? 1 : 3;
    double beta_min = HUGE_VAL;
    for (int p = 0; p <= o->pmax; p++)
        beta_min = fmin(beta_min, plan->beta_n[p]);
    double rule = quality_levels[o->quality].c / beta_min + quality_levels[o->quality].d;
    int nodes = rule > HB_MAX_NODES ? HB_MAX_NODES : (int)ceil(rule - 1e-9); /* 1e-9: c / beta is exact only in reals */
    nodes = nodes < quality_levels[o->quality].min_nodes ? quality_levels[o->quality].min_nodes : nodes;
    if (o->quadrature_order > 0)
        deon_nodes(d, o->quadrature_order, 0); /* the paper's rule, of the caller's order */
    else
        deon_nodes(d, 2 * nodes, 1);
    for (int p = 0; p <= HB_STANDARD_PMAX && p <= o->pmax; p++) {
        hb_scaled_detector *s = &d->scaled[p];
        double sigma = sqrt(M_LOG2E / (2.0 * plan->beta_n[p] * plan->beta_n[p])), period = 2.0 * M_PI * sigma;
        s->scale = (float)sigma;
        s->slope = (float)(2.0 * p * sigma);
        s->period_hi = (float)period;
        s->period_lo = (float)(period - (double)s->period_hi);
        s->inv_period = (float)(1.0 / period);
        for (int j = 0; j < d->nodes; j++) /* eq. 8 at gamma_t = 0, p pi - 2 gamma_i, less floor(p / 2) turns */
            s->offset[j] = (float)(sigma * ((p % 2) * M_PI - 2.0 * (double)d->gamma_i[j]));
    }
    d->asin_narrow = m->eta >= 4.0 / 3.0;
}

/* The largest |phi_hat(p, gamma) - p pi| over gamma in [-pi/2, pi/2] for index eta': the
 * endpoint |2pc - pi| or, where the cubic folds, the fold value (2/3) B gamma_c. */
static double marschner_cubic_span(int p, double eta_prime)
{
    double c = asin(1.0 / eta_prime), a = -8.0 * p * c / (M_PI * M_PI * M_PI), b = 6.0 * p * c / M_PI - 2.0;
    double span = fabs(2.0 * p * c - M_PI);
    if (b > 0.0) {
        double gamma_c = sqrt(b / (-3.0 * a));
        if (gamma_c < M_PI_2)
            span = fmax(span, 2.0 / 3.0 * b * gamma_c);
    }
    return span;
}

/* MJC03 lobes (Table 1 ratios, docs/conventions.md): beta_R = beta_m, beta_TT = beta_R / 2,
 * beta_TRT = 2 beta_R; means alpha_R = -alpha (the R highlight toward the root, as dFH11's),
 * alpha_TT = -alpha_R / 2, alpha_TRT = -3 alpha_R / 2; per-lobe overrides win. */
static void derive_marschner(hb_plan *plan)
{
    const hb_material *m = &plan->material;
    hb_marschner *k = &plan->marschner;
    static const double beta_ratio[3] = { 1.0, 0.5, 2.0 }, mean_ratio[3] = { -1.0, 0.5, 1.5 };
    for (int p = 0; p < 3; p++) {
        double beta = m->lobe_beta_m[p] > 0.0 ? m->lobe_beta_m[p] : beta_ratio[p] * m->beta_m;
        double mean = (m->lobe_alpha_override >> p & 1u) ? m->lobe_alpha[p] : mean_ratio[p] * m->alpha;
        plan->marschner_beta[p] = beta;
        plan->marschner_mean[p] = mean;
        k->lobe[p].mean = (float)mean;
        k->lobe[p].log2e_over_two_beta2 = (float)(M_LOG2E / (2.0 * beta * beta));
        k->lobe[p].norm = (float)(1.0 / (beta * sqrt(2.0 * M_PI)));
    }
    k->lobes = plan->options.lobes == HB_LOBES_DEFAULT ? 7u : plan->options.lobes;
    k->absorption_paper = plan->options.absorption == HB_ABSORPTION_PAPER;
    k->eta2_minus_one = (float)((m->eta - 1.0) * (m->eta + 1.0));
    k->eta = (float)m->eta;
    for (int c = 0; c < 3; c++)
        k->sigma_a_log2e[c] = absorption_float(plan->sigma_a[c] * M_LOG2E);
    /* eta* (MJC03 sec. 4.4) with the axis ratio a = sqrt(1 - e^2): eta1 = 2(eta - 1) a^2 - eta + 2
     * at phi_h = 0 (both directions along z, the minor axis), eta2 = 2(eta - 1) / a^2 - eta + 2 at
     * phi_h = pi/2; clamped to 1.0001 where a very flat fibre would take it below 1 */
    double a2 = 1.0 - m->eccentricity * m->eccentricity;
    double eta1 = 2.0 * (m->eta - 1.0) * a2 - m->eta + 2.0, eta2 = 2.0 * (m->eta - 1.0) / a2 - m->eta + 2.0;
    k->eccentric = m->eccentricity > 0.0;
    plan->eta_star_mean = 0.5 * (eta1 + eta2);
    plan->eta_star_swing = 0.5 * (eta1 - eta2);
    k->eta_star_excess = (float)(plan->eta_star_mean - 1.0); /* its digits near eta = 1 */
    k->eta_star_swing = (float)plan->eta_star_swing;
    plan->eta_star_min = k->eccentric ? fmax(1.0001, fmin(eta1, eta2)) : m->eta;
    /* eta' >= eta, so the smallest index a lobe sees decides which roots and caustics can exist */
    for (int p = 1; p < 3; p++) {
        double smallest = p == 2 ? plan->eta_star_min : m->eta;
        double fold = 1.0 / sin(M_PI / (3.0 * p));
        k->fold_index[p] = (float)fold;
        k->folds[p] = smallest < fold;
        k->caustic[p] = smallest < fold + m->caustic_fade;
    }
    k->trt_branches = marschner_cubic_span(2, plan->eta_star_min) > M_PI - 1e-6 ? 3 : 1;
    k->caustic_width = (float)m->caustic_width;
    k->caustic_log2e_over_two_w2 = (float)(M_LOG2E / (2.0 * m->caustic_width * m->caustic_width));
    k->caustic_norm = (float)(1.0 / (m->caustic_width * sqrt(2.0 * M_PI)));
    k->inv_caustic_fade = (float)(1.0 / m->caustic_fade);
    k->caustic_limit = (float)m->caustic_limit;
    k->glint_scale = (float)m->glint_scale;
}

/* HHH22 R lobe: Simpson panels in the peak-following variable per quality (docs/huang.md:
 * measured against the reference over roughness 0.02..0.6, tilts and directions). */
static const int huang_r_panels[] = {
    [HB_QUALITY_FAST] = 16, [HB_QUALITY_BALANCED] = 32, [HB_QUALITY_HIGH] = 64, [HB_QUALITY_REFERENCE] = 64,
};

/* HHH22 TT and TRT: Simpson's step over the entry azimuth per quality, in units of the roughness
 * (the paper's 0.7 for balanced, sec. 3.4.2), and the panels covering the widest window, pi. */
static const double huang_tt_step[] = {
    [HB_QUALITY_FAST] = 1.4, [HB_QUALITY_BALANCED] = 0.7, [HB_QUALITY_HIGH] = 0.35, [HB_QUALITY_REFERENCE] = 0.35,
};

static int huang_tt_panels(const hb_options *o, double roughness)
{
    if (o->tt_panels > 0)
        return o->tt_panels;
    double panels = 2.0 * ceil(M_PI / (2.0 * huang_tt_step[o->quality] * roughness));
    return (int)fmin(fmax(panels, 4.0), HB_MAX_TT_PANELS);
}

/* The mesonormal's inclination tau = -alpha, so that, as in dFH11 and MJC03, alpha > 0 moves the R
 * highlight toward the root (theta_o = -theta_i - 2 alpha at phi = 0); lobe_alpha[R] sets tau itself. */
static void derive_huang(hb_plan *plan)
{
    const hb_material *m = &plan->material;
    const hb_options *o = &plan->options;
    hb_huang *h = &plan->huang;
    double r = m->roughness, c = sqrt(1.0 - r * r);
    plan->huang_tilt = (m->lobe_alpha_override & 1u) ? m->lobe_alpha[HB_LOBE_R] : -m->alpha;
    h->lobes = o->lobes == HB_LOBES_DEFAULT ? 7u : o->lobes;
    h->tt_panels = huang_tt_panels(o, r);
    unsigned long long key = hb_mix64(o->seed + 0x9e3779b97f4a7c15ull);
    h->rng_key = (uint32_t)key;
    h->rng_key2 = (uint32_t)(key >> 32);
    for (int k = 0; k < 3; k++)
        h->sigma_a[k] = absorption_float(plan->sigma_a[k]);
    h->beckmann = m->ndf == HB_NDF_BECKMANN;
    h->shadowing = o->shadowing == HB_SHADOWING_SMITH;
    h->elliptical = m->eccentricity > 0.0;
    h->analytic = o->r_integration == HB_R_INTEGRATION_ANALYTIC ||
                  (o->r_integration == HB_R_INTEGRATION_AUTO && !h->beckmann && !h->shadowing && !h->elliptical);
    h->step_rule = o->r_step > 0.0;
    h->step = (float)(o->r_step * r);
    h->panels = h->step_rule ? 2 * (int)ceil(M_PI / (2.0 * o->r_step * r))
                : o->r_panels > 0 ? o->r_panels : huang_r_panels[o->quality];
    h->pdf_panels = huang_r_panels[o->quality];
    h->tilted = plan->huang_tilt != 0.0;
    h->roughness = (float)r;
    h->roughness2 = (float)(r * r);
    h->c_rough = (float)c;
    h->one_minus_c = (float)(r * r / (1.0 + c));
    h->cos_tilt = (float)cos(plan->huang_tilt);
    h->sin_tilt = (float)sin(plan->huang_tilt);
    h->ior = dielectric_of(m->eta);
    h->e2 = (float)(m->eccentricity * m->eccentricity);
    h->b = (float)sqrt(1.0 - m->eccentricity * m->eccentricity);
    h->b2 = (float)(1.0 - m->eccentricity * m->eccentricity);
}

static hb_status build_plan(const hb_material *material, const hb_options *options, hb_isa isa,
                            const hb_selection *selection, hb_plan **out, hb_error *error);

hb_status hb_plan_create(const hb_material *given_material, const hb_options *given_options, hb_plan **out,
                         hb_error *error)
{
    if (error) {
        error->status = HB_OK;
        error->message[0] = '\0';
    }
    if (!out)
        return hb_plan_fail(error, HB_ERR_NULL, "plan output pointer is NULL");
    *out = NULL;
    if (!given_material || !given_options)
        return hb_plan_fail(error, HB_ERR_NULL, "%s is NULL", given_material ? "options" : "material");
    hb_material material_copy;
    hb_options options_copy;
    hb_status st = upgrade_structs(given_material, given_options, &material_copy, &options_copy, error);
    if (st != HB_OK)
        return st;
    const hb_material *material = &material_copy;
    const hb_options *options = &options_copy;
    st = validate_material(material, error);
    if (st == HB_OK)
        st = validate_options(options, error);
    if (st == HB_OK && options->model == HB_MODEL_HUANG)
        st = validate_huang(material, options, error);
    if (st == HB_OK && options->model == HB_MODEL_DEON && material->eccentricity > 0.0)
        st = hb_plan_fail(error, HB_ERR_UNSUPPORTED, "eccentricity = %g: the deon model is for circular fibres (dFH11 sec. 4); "
                  "marschner and huang have elliptical ones", material->eccentricity);
    hb_isa isa = HB_ISA_SCALAR;
    if (st == HB_OK && options->quality != HB_QUALITY_REFERENCE)
        st = resolve_isa(options->isa, &isa, error);
    if (st != HB_OK)
        return st;
    if (options->tolerance == 0.0 && options->budget_ns == 0.0)
        return build_plan(material, options, isa, NULL, out, error);
    /* a tolerance or budget plan: the best configuration, or the next when its table cannot be built */
    hb_selection selection = { 0 };
    for (;;) {
        hb_options chosen;
        st = hb_plan_select(material, options, isa, &chosen, &selection, error);
        if (st != HB_OK)
            return st;
        st = build_plan(material, &chosen, isa, &selection, out, error);
        if (st == HB_OK && error) /* an earlier attempt's message is not this call's */
            error->status = HB_OK, error->message[0] = '\0';
        if (st != HB_ERR_UNSUPPORTED || selection.preset >= 32)
            return st;
        selection.refused |= 1u << selection.preset;
        snprintf(selection.refusal, sizeof selection.refusal, "%s: %.120s", selection.configuration,
                 error ? error->message : "could not be built");
    }
}

/* The plan of concrete options; selection (NULL for a plain plan) is what chose them. */
static hb_status build_plan(const hb_material *material, const hb_options *options, hb_isa isa,
                            const hb_selection *selection, hb_plan **out, hb_error *error)
{
    hb_status st = HB_OK;
    hb_plan *plan = calloc(1, sizeof *plan);
    if (!plan)
        return hb_plan_fail(error, HB_ERR_NOMEM, "could not allocate a plan");
    plan->material = *material;
    plan->options = *options;
    if (selection)
        plan->selection = *selection;
    plan->isa = isa;
    int reference = options->quality == HB_QUALITY_REFERENCE ||
                    (options->model == HB_MODEL_HUANG && options->tt_trt == HB_TT_TRT_REFERENCE);
    plan->kernels = reference ? NULL : hb_kernels_for(isa);
    derive_deon(plan);
    derive_marschner(plan);
    derive_huang(plan);
    if (options->model == HB_MODEL_DEON)
        hb_plan_derive_sampling(plan);
    if (options->model == HB_MODEL_DEON && options->azimuthal == HB_AZIMUTHAL_TABLE)
        st = hb_plan_build_deon_table(plan, error);
    if (st == HB_OK && options->model == HB_MODEL_HUANG && options->tt_trt == HB_TT_TRT_TABLE &&
        (plan->huang.lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT)))
        st = hb_plan_build_huang_table(plan, error);
    if (st != HB_OK) {
        hb_plan_destroy(plan);
        return st;
    }
    *out = plan;
    return HB_OK;
}

void hb_plan_destroy(hb_plan *plan)
{
    if (plan) {
        free(plan->huang_table);
        free(plan->deon_table);
    }
    free(plan);
}

hb_isa hb_plan_isa(const hb_plan *plan) { return plan ? plan->isa : HB_ISA_SCALAR; }

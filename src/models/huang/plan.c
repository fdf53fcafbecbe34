/* HHH22's plan: its own option checks, and its constants (R lobe rule, TT/TRT panels, tilt,
 * cross-section) and TT/TRT table derived from the material and options. */
#include <math.h>
#include <stdlib.h>

#include "huang.h"
#include "kernel/isas.h"
#include "math/hash.h"
#include "models/build/derive.h"
#include "state.h"

/* HHH22: R, TT and TRT; the R lobe's closed form (App. A) covers GGX without G on circular fibres. */
hb_status hb_huang_validate(const hb_material *m, const hb_options *o, hb_error *error)
{
    if (o->lobes != HB_LOBES_DEFAULT && (o->lobes & ~7u))
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "lobes = 0x%x: the huang model has R, TT and TRT only (HHH22 eq. 3)",
                            o->lobes);
    if (o->azimuthal != HB_AZIMUTHAL_QUADRATURE)
        return hb_plan_fail(error, HB_ERR_UNSUPPORTED, "the N_p table is dFH11's (model deon); huang tabulates TT/TRT "
                            "with tt_trt = table");
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

int hb_huang_tt_panels(const hb_options *o, hb_quality quality, double roughness)
{
    if (o->tt_panels > 0)
        return o->tt_panels;
    double panels = 2.0 * ceil(M_PI / (2.0 * huang_tt_step[quality] * roughness));
    return (int)fmin(fmax(panels, 4.0), HB_MAX_TT_PANELS);
}

/* Eq. 10's projected width 2 cos(theta_o) is the macrosurface's; the paper keeps it for the tilted
 * mesosurface and without G, whose projected widths stay finite at the pole: the scales' pi |sin tau|
 * and, without G, the rough surface's pi r / 2 (GGX; r / (2 sqrt(pi)) per unit for Beckmann: the
 * grazing limit of (1 + Lambda) cos). cos(theta_o) is kept above half of the larger, so the energy
 * near the poles stays bounded, and so is cos(theta_i), so S stays reciprocal; elsewhere f is the
 * paper's. Unbounded (the paper's form, options.pole_floor), only the pole itself is floored. */
static double huang_cos_floor(const hb_options *o, double tilt, double roughness, int beckmann, int shadowing)
{
    int bounded = o->pole_floor == HB_POLE_FLOOR_BOUNDED ||
                  (o->pole_floor == HB_POLE_FLOOR_AUTO && o->quality != HB_QUALITY_REFERENCE);
    if (!bounded)
        return 1e-8;
    double scales = 0.5 * M_PI * fabs(sin(tilt));
    double rough = shadowing ? 0.0 : 0.25 * M_PI * roughness * (beckmann ? 1.0 / sqrt(M_PI) : 1.0);
    return fmax(1e-8, fmax(scales, rough));
}

/* The mesonormal's inclination tau = -alpha, so that, as in dFH11 and MJC03, alpha > 0 moves the R
 * highlight toward the root (theta_o = -theta_i - 2 alpha at phi = 0); lobe_alpha[R] sets tau itself. */
static void derive_constants(hb_plan *plan)
{
    const hb_material *m = &plan->material;
    const hb_options *o = &plan->options;
    hb_huang *h = &hb_huang_mut(plan)->kernel;
    double r = m->roughness, c = sqrt(1.0 - r * r);
    hb_huang_mut(plan)->tilt = (m->lobe_alpha_override & 1u) ? m->lobe_alpha[HB_LOBE_R] : -m->alpha;
    h->lobes = o->lobes == HB_LOBES_DEFAULT ? 7u : o->lobes;
    h->tt_panels = hb_huang_tt_panels(o, o->quality, r);
    unsigned long long key = hb_mix64(o->seed + 0x9e3779b97f4a7c15ull);
    h->rng_key = (uint32_t)key;
    h->rng_key2 = (uint32_t)(key >> 32);
    for (int k = 0; k < 3; k++)
        h->sigma_a[k] = hb_absorption_float(plan->sigma_a[k]);
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
    h->tilted = hb_huang_of(plan)->tilt != 0.0;
    h->roughness = (float)r;
    h->roughness2 = (float)(r * r);
    h->c_rough = (float)c;
    h->one_minus_c = (float)(r * r / (1.0 + c));
    h->cos_tilt = (float)cos(hb_huang_of(plan)->tilt);
    h->sin_tilt = (float)sin(hb_huang_of(plan)->tilt);
    double cos_floor = huang_cos_floor(o, hb_huang_of(plan)->tilt, r, h->beckmann, h->shadowing);
    h->cos_floor = (float)cos_floor;
    h->inv_cos_floor = (float)(1.0 / cos_floor);
    h->ior = hb_dielectric_of(m->eta);
    h->e2 = (float)(m->eccentricity * m->eccentricity);
    h->b = (float)sqrt(1.0 - m->eccentricity * m->eccentricity);
    h->b2 = (float)(1.0 - m->eccentricity * m->eccentricity);
}


hb_status hb_huang_derive(hb_plan *plan, hb_error *error)
{
    HB_PER_ISA(hb_huang_kernels, huang_kernels, kernels_by_isa);
    hb_options *o = &plan->options;
    unsigned lobes = o->lobes == HB_LOBES_DEFAULT ? 7u : o->lobes;
    int with_tt_trt = (lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT)) != 0;
    if (o->tt_trt == HB_TT_TRT_AUTO && (o->quality == HB_QUALITY_REFERENCE || !with_tt_trt))
        o->tt_trt = o->quality == HB_QUALITY_REFERENCE ? HB_TT_TRT_REFERENCE : HB_TT_TRT_MC;
    int reference = o->quality == HB_QUALITY_REFERENCE || o->tt_trt == HB_TT_TRT_REFERENCE;
    HB_PLAN_SET_KERNELS(plan, kernels_by_isa, reference);
    derive_constants(plan);
    hb_huang_mut(plan)->kernel.table_grid = hb_huang_table_grid_of(o->quality);
    if (o->tt_trt == HB_TT_TRT_AUTO) { /* the finest grid up to the plan's quality's that builds in about a
                                          second (a table file's too: it was saved by a plan of this rule) */
        while (!hb_huang_table_fits(plan) && hb_huang_of(plan)->kernel.table_grid > 0)
            hb_huang_mut(plan)->kernel.table_grid--;
        hb_huang_mut(plan)->kernel.table_too_costly = !o->table_file && !hb_huang_table_fits(plan);
        o->tt_trt = hb_huang_of(plan)->kernel.table_too_costly ? HB_TT_TRT_MC : HB_TT_TRT_TABLE;
    }
    if (o->tt_trt == HB_TT_TRT_TABLE && (hb_huang_of(plan)->kernel.lobes & (1u << HB_LOBE_TT | 1u << HB_LOBE_TRT)))
        return hb_huang_build_table(plan, error);
    return HB_OK;
}

void hb_huang_release(hb_plan *plan) { free(hb_huang_of(plan)->table); }

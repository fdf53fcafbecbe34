/* The public defaults of a material and of options (plan creation fills what an older struct lacks
 * with them), a material's absorption, and the absorption of a hair colour. */
#include <math.h>
#include <string.h>

#include "colour_fit.h"
#include "models/interface/plan.h"
#include "models/text/text.h"

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

/* dFH11 sec. 6.1: RGB absorption of eumelanin and pheomelanin per unit concentration. */
static const double eumelanin_rgb[3] = { 0.419, 0.697, 1.37 };
static const double pheomelanin_rgb[3] = { 0.187, 0.4, 1.05 };

void hb_melanin_absorption(double eumelanin, double pheomelanin, double sigma_a[3])
{
    for (int c = 0; c < 3; c++)
        sigma_a[c] = eumelanin * eumelanin_rgb[c] + pheomelanin * pheomelanin_rgb[c];
}

void hb_material_absorption(const hb_material *m, double out[3])
{
    hb_melanin_absorption(m->eumelanin, m->pheomelanin, out);
    for (int c = 0; c < 3; c++)
        out[c] += m->sigma_a[c];
}

double hb_colour_fit_depth(double b)
{
    return 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * pow(b, 3) + 5.574 * pow(b, 4) + 0.245 * pow(b, 5);
}

hb_status hb_absorption_from_colour(const double rgb[3], double beta_n, double sigma_a[3], hb_error *error)
{
    if (!rgb || !sigma_a)
        return hb_plan_fail(error, HB_ERR_NULL, "rgb and sigma_a_rgb must not be NULL");
    if (!(beta_n >= 0.0 && beta_n <= 1.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "beta_n = %s must be in [0, 1] (CBTB16's scale)", HB_NUM(beta_n));
    static const char *const channel[3] = { "r", "g", "b" };
    for (int c = 0; c < 3; c++)
        if (!(rgb[c] > 0.0 && rgb[c] <= 1.0))
            return hb_plan_fail(error, HB_ERR_PARAM, "rgb.%s = %s must be in (0, 1]", channel[c], HB_NUM(rgb[c]));
    /* CBTB16 eq. 9 inverted: sigma_a = (log(C) / d(beta_n))^2 */
    double d = hb_colour_fit_depth(beta_n);
    for (int c = 0; c < 3; c++)
        sigma_a[c] = (log(rgb[c]) / d) * (log(rgb[c]) / d);
    return HB_OK;
}

hb_status hb_melanin_from_colour(const double rgb[3], double beta_n, double *eumelanin, double *pheomelanin,
                                 hb_error *error)
{
    if (!eumelanin || !pheomelanin)
        return hb_plan_fail(error, HB_ERR_NULL, "eumelanin and pheomelanin must not be NULL");
    double sigma[3];
    hb_status st = hb_absorption_from_colour(rgb, beta_n, sigma, error);
    if (st != HB_OK)
        return st;
    /* weighted least squares over (eu, pheo) >= 0: the unconstrained 2x2 normal equations, else the
     * better of the two one-pigment fits (the minimum of a convex quadratic on the quadrant's edge) */
    double a11 = 0.0, a12 = 0.0, a22 = 0.0, b1 = 0.0, b2 = 0.0;
    for (int c = 0; c < 3; c++) {
        double w2 = 1.0 / fmax(sigma[c], 1e-6); /* (1 / sqrt(sigma))^2 */
        a11 += w2 * eumelanin_rgb[c] * eumelanin_rgb[c];
        a12 += w2 * eumelanin_rgb[c] * pheomelanin_rgb[c];
        a22 += w2 * pheomelanin_rgb[c] * pheomelanin_rgb[c];
        b1 += w2 * eumelanin_rgb[c] * sigma[c];
        b2 += w2 * pheomelanin_rgb[c] * sigma[c];
    }
    double det = a11 * a22 - a12 * a12, eu = (a22 * b1 - a12 * b2) / det, pheo = (a11 * b2 - a12 * b1) / det;
    if (!(eu >= 0.0 && pheo >= 0.0)) {
        double eu_only = fmax(b1 / a11, 0.0), pheo_only = fmax(b2 / a22, 0.0);
        /* the quadratic's value less its constant: a x^2 - 2 b x at each edge's minimum */
        int eu_better = a11 * eu_only * eu_only - 2.0 * b1 * eu_only <= a22 * pheo_only * pheo_only - 2.0 * b2 * pheo_only;
        eu = eu_better ? eu_only : 0.0;
        pheo = eu_better ? 0.0 : pheo_only;
    }
    *eumelanin = eu;
    *pheomelanin = pheo;
    return HB_OK;
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
    o->tt_trt = HB_TT_TRT_AUTO;
}

/* The public defaults of a material and of options (plan creation fills what an older struct lacks
 * with them), and a material's absorption. */
#include <math.h>
#include <string.h>

#include "hairbsdf.h"

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

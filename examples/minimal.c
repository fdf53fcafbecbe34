/* The README's minimal example: one plan per material, then batches of samples. */
#include <stdio.h>
#include "hairbsdf.h"

int main(void)
{
    hb_material material;
    hb_options options;
    hb_material_default(&material);          /* eta 1.55, beta_m 0.1, beta_n 0.3, alpha 0.035 */
    material.eumelanin = 0.3;                 /* light brown (dFH11 sec. 6.1) */
    hb_options_default(&options);             /* d'Eon 2011, R..TRRT + residual, balanced quality */
    hb_plan *plan;
    hb_error error;
    if (hb_plan_create(&material, &options, &plan, &error) != HB_OK) {
        fprintf(stderr, "%s\n", error.message);
        return 1;
    }
    float theta_i[4] = { 0.3f, 0.3f, -1.0f, 1.5f }, phi_i[4] = { 0 };
    float theta_o[4] = { -0.37f, 0.2f, 1.0f, -1.5f }, phi_o[4] = { 0.5f, 1.0f, 2.0f, 3.0f };
    float r[4], g[4], b[4];
    hb_eval_angles(plan, 4, (hb_angles_soa){ theta_i, phi_i, theta_o, phi_o }, (hb_rgb_soa){ r, g, b }, NULL);
    for (int k = 0; k < 4; k++)
        printf("f = %g %g %g  (%s)\n", r[k], g[k], b[k], hb_isa_name(hb_plan_isa(plan)));
    hb_plan_destroy(plan);
    return 0;
}

/* How an engine integrates hairbsdf: one plan per hair material, built once at load time;
 * per frame and per light, one batched call over all shaded hair samples (SoA, caller-owned
 * buffers, no allocation, any thread); and, for a GPU path, the plan's table to upload. */
#include <math.h>
#include <stdio.h>

#include "hairbsdf.h"

enum { SAMPLES = 256 };

/* Load time: a material's plan. Tables are built here, never per frame. */
static hb_plan *load_material(double eumelanin, hb_azimuthal azimuthal)
{
    hb_material material;
    hb_options options;
    hb_material_default(&material);
    hb_options_default(&options);
    material.eumelanin = eumelanin;
    options.azimuthal = azimuthal; /* HB_AZIMUTHAL_TABLE: N_p from a table (dFH11 sec. 6) */
    hb_plan *plan = NULL;
    hb_error error;
    if (hb_plan_create(&material, &options, &plan, &error) != HB_OK)
        fprintf(stderr, "material: %s\n", error.message);
    return plan;
}

int main(void)
{
    hb_plan *brown = load_material(0.6, HB_AZIMUTHAL_QUADRATURE), *blond = load_material(0.06, HB_AZIMUTHAL_TABLE);
    if (!brown || !blond)
        return 1;
    /* Per frame: the G-buffer gives each hair sample its w_o in the fibre frame; a light gives w_i. */
    static float wi_x[SAMPLES], wi_y[SAMPLES], wi_z[SAMPLES], wo_x[SAMPLES], wo_y[SAMPLES], wo_z[SAMPLES];
    static float r[SAMPLES], g[SAMPLES], b[SAMPLES];
    for (int k = 0; k < SAMPLES; k++) {
        float t = (float)k / SAMPLES;
        wo_x[k] = 0.6f * t, wo_y[k] = 0.8f * (1.0f - t), wo_z[k] = 0.0f;
        float len = wo_x[k] * wo_x[k] + wo_y[k] * wo_y[k];
        wo_z[k] = len < 1.0f ? sqrtf(1.0f - len) : 0.0f;
        wi_x[k] = 0.0f, wi_y[k] = -0.28f, wi_z[k] = 0.96f; /* one light, the same for every sample */
    }
    hb_vectors_soa in = { wi_x, wi_y, wi_z, wo_x, wo_y, wo_z };
    hb_eval_report report;
    const hb_plan *plans[2] = { brown, blond };
    for (int m = 0; m < 2; m++) {
        hb_eval_vectors(plans[m], SAMPLES, in, (hb_rgb_soa){ r, g, b }, &report); /* L_o += f L_i per sample */
        int top = 0;
        for (int k = 1; k < SAMPLES; k++)
            top = r[k] > r[top] ? k : top;
        printf("%s: brightest sample %d, f = (%.4f, %.4f, %.4f); %zu invalid samples\n",
               m ? "blond (N_p table)" : "brown", top, r[top], g[top], b[top], report.invalid);
    }
    /* GPU path: the blond plan's N_p table, ready to upload as an RGB texture array (one layer per slot). */
    hb_table_view table;
    if (hb_plan_table(blond, &table) == HB_OK)
        printf("N_p table: %d x %d nodes (%s; %s), %d slots, %zu floats, midpoint error %.2g\n", table.size[0],
               table.size[1], table.axis[0], table.axis[1], table.slots, table.count, table.error);
    hb_plan_destroy(brown);
    hb_plan_destroy(blond);
    return 0;
}

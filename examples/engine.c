/* How an engine integrates hairbsdf: one plan per hair material, built once at load time;
 * per frame and per light, one batched call over all shaded hair samples (SoA, caller-owned
 * buffers, no allocation, any thread); for a GPU path, the plan's table to upload; and the table
 * saved as a file at bake time, so that loading the level does not rebuild it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hairbsdf.h"

enum { SAMPLES = 256 };

/* Load time: a material's plan. Tables are built here (or loaded from table_file), never per frame. */
static hb_plan *load_material(double eumelanin, hb_azimuthal azimuthal, const void *table_file, size_t table_size)
{
    hb_material material;
    hb_options options;
    hb_material_default(&material);
    hb_options_default(&options);
    material.eumelanin = eumelanin;
    options.azimuthal = azimuthal; /* HB_AZIMUTHAL_TABLE: N_p from a table (dFH11 sec. 6) */
    options.table_file = table_file, options.table_file_size = table_size; /* NULL, 0: build it */
    hb_plan *plan = NULL;
    hb_error error;
    if (hb_plan_create(&material, &options, &plan, &error) != HB_OK)
        fprintf(stderr, "material: %s\n", error.message);
    return plan;
}

/* The brightest sample of one light's result, as a quick look at the plan. */
static void print_brightest(const char *what, const float *r, const float *g, const float *b, size_t invalid)
{
    int top = 0;
    for (int k = 1; k < SAMPLES; k++)
        top = r[k] > r[top] ? k : top;
    printf("%s: brightest sample %d, f = (%.4f, %.4f, %.4f); %zu invalid samples\n", what, top, r[top], g[top], b[top],
           invalid);
}

int main(void)
{
    hb_plan *brown = load_material(0.6, HB_AZIMUTHAL_QUADRATURE, NULL, 0),
            *blond = load_material(0.06, HB_AZIMUTHAL_TABLE, NULL, 0);
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
        print_brightest(m ? "blond (N_p table)" : "brown", r, g, b, report.invalid);
    }
    /* GPU path: the blond plan's N_p table, ready to upload as an RGB texture array (one layer per slot). */
    hb_table_view table = { .struct_size = sizeof table };
    if (hb_plan_table(blond, &table) == HB_OK)
        printf("N_p table: %d x %d nodes (%s; %s), %d slots, %zu floats, midpoint error %.2g\n", table.size[0],
               table.size[1], table.axis[0], table.axis[1], table.slots, table.count, table.error);
    /* Bake time: the blond table as a file for the game's data; level load: the plan from that file. */
    size_t size = 0;
    hb_table_save(blond, NULL, 0, &size);
    void *file = malloc(size);
    hb_plan *loaded = NULL;
    if (file && hb_table_save(blond, file, size, &size) == HB_OK)
        loaded = load_material(0.06, HB_AZIMUTHAL_TABLE, file, size);
    free(file); /* the plan copied what it needs */
    if (loaded) {
        hb_eval_vectors(loaded, SAMPLES, in, (hb_rgb_soa){ r, g, b }, &report);
        print_brightest("blond (N_p table loaded from its file)", r, g, b, report.invalid);
    }
    hb_plan_destroy(loaded);
    hb_plan_destroy(brown);
    hb_plan_destroy(blond);
    return 0;
}

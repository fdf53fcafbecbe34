/* hairbsdf dual --engine: a material family's engine-wide dual-scattering table (hb_dual_engine;
 * docs/multiple-scattering.md, "One table for every hair colour") over theta, R roughness and
 * absorption, as CSV of its nodes or as a file for an engine (--save, hb_dual_engine_save). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"

/* The nodes as CSV: one row per (roughness, absorption, theta), the six stored terms of one channel. */
static void print_nodes(const hb_dual_engine *engine, const hb_dual_engine_axes *a)
{
    size_t count = 0;
    const float *f = hb_dual_engine_nodes(engine, &count);
    printf("roughness,sigma_a,theta,a_f,a_b,alpha_f,beta_f2,alpha_b,beta_b2\n");
    for (int r = 0; r < a->roughnesses; r++)
        for (int j = 0; j < a->absorptions; j++) {
            double roughness = a->roughness_min + (a->roughness_max - a->roughness_min) * r / (a->roughnesses - 1);
            double sigma_a = 0.0 - log(1.0 - (1.0 - exp(-a->absorption_max)) * j / (a->absorptions - 1)); /* 0, not -0 */
            for (int k = 0; k < a->thetas; k++, f += HB_DUAL_ENGINE_NODE_FLOATS)
                printf("%.6g,%.6g,%.6f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", roughness, sigma_a,
                       -M_PI_2 + M_PI * (k + 0.5) / a->thetas, f[0], f[1], f[2], f[3], f[4], f[5]);
        }
}

/* The file of the engine at path; 0, or 1 (it cannot be written) said on stderr. */
static int save_engine(const hb_dual_engine *engine, const char *path)
{
    size_t size = 0;
    hb_dual_engine_save(engine, NULL, 0, &size);
    void *bytes = malloc(size);
    FILE *f = NULL;
    int written = bytes && hb_dual_engine_save(engine, bytes, size, &size) == HB_OK && (f = fopen(path, "wb")) &&
                  fwrite(bytes, 1, size, f) == size;
    if ((f && fclose(f) != 0) || !written) {
        fprintf(stderr, "hairbsdf dual: cannot write %s\n", path);
        free(bytes);
        return 1;
    }
    free(bytes);
    return 0;
}

int cmd_dual_engine(const cli_model_args *args, int thetas, int roughnesses, int absorptions, const int sampled[2],
                    double density, const char *save)
{
    hb_dual_engine_axes axes;
    hb_dual_engine_axes_default(&axes);
    axes.thetas = thetas, axes.roughnesses = roughnesses, axes.absorptions = absorptions;
    axes.sampled_directions = sampled[0], axes.sampled_azimuths = sampled[1];
    hb_material material;
    hb_options o = args->options;
    cli_build_hooks(args, &o);
    hb_dual_engine *engine = NULL;
    hb_error e;
    if (cli_material(args, &material, &e) != HB_OK ||
        hb_dual_engine_create(&material, &o, &axes, density, &engine, &e) != HB_OK) {
        fprintf(stderr, "hairbsdf dual: %s\n", e.message);
        return 2;
    }
    int st = 0;
    if (save)
        st = save_engine(engine, save);
    else
        print_nodes(engine, &axes);
    hb_dual_engine_destroy(engine);
    return st;
}

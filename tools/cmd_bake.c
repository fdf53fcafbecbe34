/* hairbsdf bake: the table a shader or engine bakes for a material (docs/engines.md):
 * dFH11 N_p per M_p group over (sqrt(cos(theta_d)), |phi|), or HHH22 f_TT + f_TRT; as a table file
 * (hb_table_save), or as float RGB EXR (one image row per line of the table, slots stacked). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "image.h"

static void bake_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf bake [options] [--table-tolerance X] -o FILE.hbt|FILE.exr\n"
                "deon: N_p per group of lobes sharing an M_p, over (sqrt(cos(theta_d)), |phi|), refined until the\n"
                "midpoint interpolation error is below X of each group's peak (default: from --quality); with\n"
                "--azimuthal colour-table one table for every hair colour, one channel over a third axis,\n"
                "exp(-sigma_a / 2) (.hbt only);\n"
                "huang: its TT + TRT table (resolution from --quality and the roughness). Prints the axes.\n"
                "FILE.hbt: the table file of docs/engines.md (header with the material, options, library version\n"
                "and a checksum; f32 values, axes row-major, then slot, then RGB), which --table FILE.hbt loads\n"
                "into a plan of the same material and options. FILE.exr (with OpenEXR): width = the last axis,\n"
                "one row per node of the other axes, slots stacked top to bottom.\n%s",
            cli_model_options_help);
}

/* The plan's table file (hb_table_save), which --table loads back. */
static int write_hbt(const char *path, const hb_plan *plan)
{
    size_t size;
    if (hb_table_save(plan, NULL, 0, &size) != HB_OK)
        return -1;
    unsigned char *bytes = malloc(size);
    FILE *f = bytes ? fopen(path, "wb") : NULL;
    int st = f && hb_table_save(plan, bytes, size, &size) == HB_OK && fwrite(bytes, 1, size, f) == size ? 0 : -1;
    if (f && fclose(f) != 0)
        st = -1;
    free(bytes);
    return st;
}

static int write_exr(const char *path, const hb_table_view *v)
{
    int width = v->size[v->axes - 1], lines = (int)(v->count / (size_t)(3 * v->slots * width));
    float *rgb = malloc(v->count * sizeof *rgb);
    if (!rgb)
        return -1;
    for (int s = 0; s < v->slots; s++)
        for (int y = 0; y < lines; y++)
            for (int x = 0; x < width; x++)
                memcpy(rgb + (((size_t)s * lines + y) * width + x) * 3,
                       v->values + (((size_t)y * width + x) * v->slots + s) * 3, 3 * sizeof *rgb);
    int st = image_write_exr(path, width, lines * v->slots, rgb);
    free(rgb);
    return st;
}

int cmd_bake(int argc, char **argv)
{
    cli_model_args args;
    cli_model_args_default(&args);
    const char *path = NULL;
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            bake_usage(stdout);
            return 0;
        }
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            path = argv[++i];
        } else {
            int r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
            if (r <= 0) {
                fprintf(stderr, "hairbsdf bake: %s\n", r < 0 ? err : "unknown option (see hairbsdf bake --help)");
                return 2;
            }
        }
    }
    size_t n = path ? strlen(path) : 0;
    int exr = n > 4 && strcmp(path + n - 4, ".exr") == 0;
    if (!path || !(exr || (n > 4 && strcmp(path + n - 4, ".hbt") == 0))) {
        fprintf(stderr, "hairbsdf bake: -o FILE.hbt or FILE.exr is required\n");
        return 2;
    }
    if (exr && !image_exr_available()) {
        fprintf(stderr, "hairbsdf bake: this build has no OpenEXR (install libopenexr-dev and rebuild); use .hbt\n");
        return 2;
    }
    hb_options *o = &args.options;
    if (o->model == HB_MODEL_DEON) {
        if (o->azimuthal != HB_AZIMUTHAL_COLOUR_TABLE)
            o->azimuthal = HB_AZIMUTHAL_TABLE;
        if (exr && o->azimuthal == HB_AZIMUTHAL_COLOUR_TABLE) {
            fprintf(stderr, "hairbsdf bake: the colour table holds one channel per slot: write it as .hbt\n");
            return 2;
        }
    } else if (o->model == HB_MODEL_HUANG && o->table_tolerance == 0.0) {
        o->tt_trt = HB_TT_TRT_TABLE;
    } else {
        static const char *const names[] = { "marschner", "deon", "huang", "chiang" };
        if (o->model == HB_MODEL_HUANG)
            fprintf(stderr, "hairbsdf bake: the huang table's resolution follows --quality, not --table-tolerance\n");
        else
            fprintf(stderr, "hairbsdf bake: the %s model has no tables (deon and huang do)\n", names[o->model]);
        return 2;
    }
    hb_plan *plan;
    hb_error error;
    if (cli_plan_create(&args, o, &plan, &error) != HB_OK) {
        fprintf(stderr, "hairbsdf bake: %s\n", error.message);
        return 2;
    }
    hb_table_view v = { .struct_size = sizeof v };
    int st = hb_plan_table(plan, &v) == HB_OK ? 0 : 2;
    if (st)
        fprintf(stderr, "hairbsdf bake: this plan has no table (huang without TT and TRT?)\n");
    if (!st && (exr ? write_exr(path, &v) : write_hbt(path, plan)) != 0) {
        fprintf(stderr, "hairbsdf bake: cannot write %s\n", path);
        st = 1;
    }
    for (int k = 0; !st && k < v.axes; k++)
        printf("axis %d: %d nodes, %g to %g, %s\n", k, v.size[k], v.lo[k], v.hi[k], v.axis[k]);
    for (int s = 0; !st && s < v.slots; s++) {
        printf("slot %d: lobes ", s);
        for (int p = 0, first = 1; p <= HB_LOBE_RESIDUAL; p++)
            if (v.slot_lobes[s] >> p & 1u) {
                printf("%s%s", first ? "" : "+", cli_lobe_name(p));
                first = 0;
            }
        printf(" (mask 0x%x)\n", v.slot_lobes[s]);
    }
    if (!st && isnan(v.error))
        printf("%zu floats (%.1f KiB); its error against the reference is measured by the tests (docs/huang.md)\n",
               v.count, (double)v.count * 4.0 / 1024.0);
    else if (!st)
        printf("%zu floats (%.1f KiB), measured midpoint error %.3g of each slot's peak\n", v.count,
               (double)v.count * 4.0 / 1024.0, v.error);
    hb_plan_destroy(plan);
    return st;
}

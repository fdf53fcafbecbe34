/* hairbsdf tress: a bundle of fibres seen from the side, by the traced light and by dual scattering
 * through the same fibres, with their difference (hb_assembly_render; docs/multiple-scattering.md,
 * "A tress, traced and dual-scattered"), as a labelled PNG; its totals as CSV. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_threads.h"
#include "figure.h"
#include "image.h"

enum { UPSCALE = 6 };

static void tress_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf tress [options] -o FILE.png [--view front|behind] [--layers L] [--packing P]\n"
                "       [--light THETA] [--paths N] [--rows R] [--columns C] [--rays N] [--dual D_F,D_B]\n"
                "       [--exposure X] [--seed S]\n"
                "Renders a round bundle of radius L fibre diameters (default 8) at packing P (default 0.3),\n"
                "lit by a directional light at inclination THETA (default 0.3) and azimuth 0, seen by an\n"
                "orthographic camera on the light's side (front, default) or opposite it (behind): R rows\n"
                "of the view's inclination (default 24) by C columns across the bundle (default 32). The\n"
                "left panel traces N paths (default 4000000) through the fibres; the middle one shades the\n"
                "fibre each of N view rays per pixel (default 256) meets with v f + f_DS (the density\n"
                "factors D_F,D_B, default 0.7,0.7); the right one is their difference |traced - dual|. Each\n"
                "pixel is L / E, radiance over the light's irradiance, green shown as grey; prints per\n"
                "channel the pictures' sums with their standard errors. --threads N traces on N threads.\n%s",
            cli_model_options_help);
}

typedef struct tress_args {
    hb_assembly a;
    hb_assembly_image image;
    double density[2], exposure;
    int behind;
    const char *out;
} tress_args;

/* Parses one tress option at argv[*i]: 1 consumed, 0 not one, -1 a bad value. */
static int parse_tress_option(int argc, char **argv, int *i, tress_args *t)
{
    const char *o = argv[*i];
    if (*i + 1 >= argc)
        return 0;
    const char *v = argv[*i + 1];
    double x;
    char *end;
    int ok;
    if (strcmp(o, "-o") == 0)
        ok = (t->out = v, 1);
    else if (strcmp(o, "--view") == 0)
        ok = strcmp(v, "front") == 0 ? (t->behind = 0, 1) : strcmp(v, "behind") == 0 ? (t->behind = 1, 1) : 0;
    else if (strcmp(o, "--layers") == 0)
        ok = cli_parse_range(v, 1.0, 1024.0, &t->a.layers);
    else if (strcmp(o, "--packing") == 0)
        ok = cli_parse_range(v, 1e-6, 0.5, &t->a.packing);
    else if (strcmp(o, "--light") == 0)
        ok = cli_parse_range(v, -1.5, 1.5, &t->a.theta_light);
    else if (strcmp(o, "--paths") == 0)
        ok = cli_parse_range(v, 1.0, 1e12, &x) && x == floor(x) ? (t->a.paths = (long long)x, 1) : 0;
    else if (strcmp(o, "--rows") == 0)
        ok = cli_parse_range(v, 1.0, 1024.0, &x) && x == floor(x) ? (t->a.theta_bins = (int)x, 1) : 0;
    else if (strcmp(o, "--columns") == 0)
        ok = cli_parse_range(v, 1.0, 1024.0, &x) && x == floor(x) ? (t->image.columns = (int)x, 1) : 0;
    else if (strcmp(o, "--rays") == 0)
        ok = cli_parse_range(v, 1.0, 1048576.0, &x) && x == floor(x) ? (t->image.rays = (int)x, 1) : 0;
    else if (strcmp(o, "--exposure") == 0)
        ok = cli_parse_range(v, 1e-6, 1e6, &t->exposure);
    else if (strcmp(o, "--seed") == 0)
        ok = cli_parse_u64(v, &t->a.seed);
    else if (strcmp(o, "--dual") == 0)
        ok = (t->density[0] = strtod(v, &end), *end == ',') &&
             cli_parse_range(end + 1, 0.0, 1.0, &t->density[1]) && t->density[0] >= 0.0 && t->density[0] <= 1.0;
    else
        return 0;
    if (!ok) {
        fprintf(stderr, "hairbsdf tress: %s: '%s' is not a valid value (see hairbsdf tress --help)\n", o, v);
        return -1;
    }
    ++*i;
    return 1;
}

/* The three panels' green channel, each pixel UPSCALE x UPSCALE, side by side, tone-mapped and framed. */
static int write_tress(const tress_args *t, const cli_model_args *args, const double *traced, const double *dual)
{
    int rows = t->a.theta_bins, columns = t->image.columns, width = columns * UPSCALE, height = rows * UPSCALE;
    size_t pixels = (size_t)3 * (size_t)width * (size_t)height;
    float *rgb = malloc(pixels * 3 * sizeof *rgb);
    uint8_t *rgb8 = malloc(pixels * 3);
    if (!rgb || !rgb8) {
        free(rgb), free(rgb8);
        return -1;
    }
    for (int y = 0; y < height; y++)
        for (int x = 0; x < 3 * width; x++) {
            int panel = x / width, k = ((y / UPSCALE) * columns + (x % width) / UPSCALE) * 3 + 1;
            double v = panel == 0 ? traced[k] : panel == 1 ? dual[k] : fabs(traced[k] - dual[k]);
            float *px = rgb + ((size_t)y * (size_t)(3 * width) + (size_t)x) * 3;
            px[0] = px[1] = px[2] = (float)v;
        }
    image_tonemap(pixels, rgb, (float)t->exposure, rgb8);
    double radius = 2.0 * t->a.layers; /* in fibre radii; the axis is in diameters */
    figure_axes axes = { "ACROSS THE TRESS (FIBRE DIAMETERS)", "THETA_O (DEGREES)", "L/E", -radius / 2.0, radius / 2.0,
                         90.0, -90.0 };
    char caption[256];
    snprintf(caption, sizeof caption, "%s eumelanin %g pheomelanin %g; tress radius %g, packing %g; light at theta %g; "
             "seen from %s; exposure %g",
             cli_model_paper(args->options.model), args->material.eumelanin, args->material.pheomelanin, t->a.layers,
             t->a.packing, t->a.theta_light, t->behind ? "behind" : "the front", t->exposure);
    char dual_title[64];
    snprintf(dual_title, sizeof dual_title, "dual scattering (d_f %g, d_b %g)", t->density[0], t->density[1]);
    const char *titles[3] = { "traced", dual_title, "|traced - dual|" };
    int fw = 0, fh = 0;
    uint8_t *framed = figure_frame_axes(rgb8, width, height, 3, caption, titles, &axes, t->exposure, &fw, &fh);
    int st = framed ? image_write_png(t->out, fw, fh, framed) : -1;
    free(rgb), free(rgb8), free(framed);
    return st;
}

int cmd_tress(int argc, char **argv)
{
    cli_model_args args;
    cli_model_args_default(&args);
    tress_args t = { .density = { HB_DUAL_DENSITY, HB_DUAL_DENSITY }, .exposure = 1.0 };
    hb_assembly_default(&t.a);
    t.a.shape = HB_ASSEMBLY_BUNDLE, t.a.theta_bins = 24, t.a.phi_bins = 24, t.a.paths = 4000000;
    t.image = (hb_assembly_image){ .struct_size = sizeof t.image, .columns = 32, .rays = 256 };
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            tress_usage(stdout);
            return 0;
        }
        int r = parse_tress_option(argc, argv, &i, &t);
        if (r < 0)
            return 2;
        if (r > 0)
            continue;
        r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
        if (r <= 0) {
            fprintf(stderr, "hairbsdf tress: %s\n", r < 0 ? err : "unknown option (see hairbsdf tress --help)");
            return 2;
        }
    }
    if (!t.out) {
        fprintf(stderr, "hairbsdf tress: -o FILE.png is required (see hairbsdf tress --help)\n");
        return 2;
    }
    t.image.view_phi = t.behind ? M_PI : 0.0;
    hb_plan *plan = NULL;
    hb_dual_table *table = NULL;
    hb_error e;
    if (cli_plan_create(&args, &args.options, &plan, &e) != HB_OK) {
        fprintf(stderr, "hairbsdf tress: %s\n", e.message);
        return 2;
    }
    if (hb_dual_table_create(plan, 64, t.density[0], t.density[1], NULL, NULL, NULL, NULL, &table) != HB_OK) {
        fprintf(stderr, "hairbsdf tress: %s\n", hb_last_error()->message);
        hb_plan_destroy(plan);
        return 2;
    }
    size_t pixels = (size_t)t.a.theta_bins * (size_t)t.image.columns * 3;
    double *planes = calloc(4 * pixels, sizeof *planes);
    int status = 0;
    if (!planes) {
        fprintf(stderr, "hairbsdf tress: out of memory\n");
        status = 1;
    } else {
        t.image.traced = planes, t.image.traced_se = planes + pixels, t.image.dual = planes + 2 * pixels;
        t.image.dual_se = planes + 3 * pixels;
        hb_assembly_result r = { .struct_size = sizeof r };
        if (hb_assembly_render(plan, table, &t.a, &t.image, &r, args.progress ? cli_tracing_progress : NULL, NULL,
                               args.threads > 1 ? cli_parallel : NULL, &args.threads) != HB_OK) {
            fprintf(stderr, "hairbsdf tress: %s\n", hb_last_error()->message);
            status = 2;
        } else {
            printf("# %ld fibres, packing %.4f, %lld scatterings\n", r.fibres, r.packing, r.events);
            printf("picture,r,g,b,se_r,se_g,se_b\n");
            for (int which = 0; which < 2; which++) {
                const double *v = which ? t.image.dual : t.image.traced, *se = which ? t.image.dual_se : t.image.traced_se;
                double sum[3] = { 0, 0, 0 }, var[3] = { 0, 0, 0 };
                for (size_t k = 0; k < pixels; k++)
                    sum[k % 3] += v[k], var[k % 3] += se[k] * se[k];
                printf("%s,%.5g,%.5g,%.5g,%.2g,%.2g,%.2g\n", which ? "dual" : "traced", sum[0], sum[1], sum[2],
                       sqrt(var[0]), sqrt(var[1]), sqrt(var[2]));
            }
            if (write_tress(&t, &args, t.image.traced, t.image.dual) != 0) {
                fprintf(stderr, "hairbsdf tress: cannot write %s\n", t.out);
                status = 1;
            }
        }
    }
    free(planes);
    hb_dual_table_destroy(table);
    hb_plan_destroy(plan);
    return status;
}

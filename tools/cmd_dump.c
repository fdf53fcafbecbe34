/* hairbsdf dump: a lat-long image of f over (theta_o, phi_o) for one w_i, like dFH11 Fig. 8 and
 * HHH22 Figs. 6-11: phi_o across (-pi at the left), theta_o from +pi/2 (top) to -pi/2 (bottom);
 * side by side with a second configuration and the difference, like the papers' comparison strips. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "figure.h"
#include "image.h"

static void dump_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf dump [options] --theta-i X --phi-i Y [--width W --height H]\n"
                "                     [--exposure E] [--compare OPTION=VALUE ...] -o FILE.pfm|FILE.exr|FILE.png\n"
                "Writes f(w_i, w_o) over all w_o as a lat-long image: float RGB (PFM; EXR when built with\n"
                "OpenEXR), or tone-mapped 8-bit sRGB (PNG, x/(1+x) of exposure * f) framed as a figure: axes\n"
                "in degrees, a title per panel, a caption and the colour scale with the values of f.\n"
                "--compare OPTION=VALUE (repeatable, any model option without its dashes, e.g. model=marschner\n"
                "or quality=fast): side by side, three panels: f of the options, f with these changed, and\n"
                "|difference|; the largest difference relative to the first panel's peak goes to stderr.\n%s",
            cli_model_options_help);
}

/* A panel's title: the model's short name, its quality and its pigment or absorption. */
static void describe(const cli_model_args *args, char *out, size_t size)
{
    static const char *const models[] = { [HB_MODEL_DEON] = "dFH11", [HB_MODEL_MARSCHNER] = "MJC03",
                                          [HB_MODEL_HUANG] = "HHH22", [HB_MODEL_CHIANG] = "CBTB16" };
    static const char *const qualities[] = { "fast", "balanced", "high", "reference" };
    hb_material material;
    if (cli_material(args, &material, NULL) != HB_OK) /* the plan reports it */
        material = args->material;
    const hb_material *m = &material;
    const hb_options *o = &args->options;
    int n = snprintf(out, size, "%s %s", (unsigned)o->model <= HB_MODEL_CHIANG ? models[o->model] : "?",
                     (unsigned)o->quality <= HB_QUALITY_REFERENCE ? qualities[o->quality] : "?");
    if (n > 0 && (size_t)n < size && (m->eumelanin > 0.0 || m->pheomelanin > 0.0))
        snprintf(out + n, size - (size_t)n, ", eumelanin %g, pheomelanin %g", m->eumelanin, m->pheomelanin);
    else if (n > 0 && (size_t)n < size)
        snprintf(out + n, size - (size_t)n, ", sigma_a %g/%g/%g", m->sigma_a[0], m->sigma_a[1], m->sigma_a[2]);
}

/* The PNG: the tone-mapped panels framed as a figure (tools/figure.c). */
static int write_figure(const char *path, const cli_model_args *first, const cli_model_args *second, int panels,
                        const float *rgb, int width, int height, double theta_i, double phi_i, double exposure)
{
    size_t pixels = (size_t)width * (size_t)panels * (size_t)height;
    uint8_t *rgb8 = malloc(pixels * 3);
    if (!rgb8)
        return -1;
    image_tonemap(pixels, rgb, (float)exposure, rgb8);
    char caption[192], title[2][96];
    describe(first, title[0], sizeof title[0]);
    describe(second, title[1], sizeof title[1]); /* a single panel shows the first title alone */
    const char *titles[3] = { title[0], title[1], "|difference|" };
    snprintf(caption, sizeof caption, "f(w_i, w_o) at theta_i %.3g (%.0f deg), phi_i %.3g, exposure %g", theta_i,
             theta_i * 180.0 / M_PI, phi_i, exposure);
    int fw = 0, fh = 0;
    uint8_t *framed = figure_frame(rgb8, width, height, panels, caption, titles, exposure, &fw, &fh);
    int st = framed ? image_write_png(path, fw, fh, framed) : -1;
    free(rgb8);
    free(framed);
    return st;
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

/* One panel: f of the plan over the lat-long grid, into columns [x0, x0 + width) of an image
 * `stride` pixels wide. row: scratch for 7 planes of width floats. */
static int render_panel(const cli_model_args *args, double theta_i, double phi_i, int width, int height,
                        int x0, int stride, float *row, float *rgb)
{
    hb_plan *plan;
    hb_error error;
    if (cli_plan_create(args, &args->options, &plan, &error) != HB_OK) {
        fprintf(stderr, "hairbsdf dump: %s\n", error.message);
        return 2;
    }
    float *ti = row, *pi = row + width, *to = row + 2 * width, *po = row + 3 * width;
    float *r = row + 4 * width, *g = row + 5 * width, *b = row + 6 * width;
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            ti[x] = (float)theta_i, pi[x] = (float)phi_i;
            to[x] = (float)(1.5707963267948966 - 3.141592653589793 * (y + 0.5) / height);
            po[x] = (float)(-3.141592653589793 + 6.283185307179586 * (x + 0.5) / width);
        }
        hb_eval_angles(plan, (size_t)width, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ r, g, b }, NULL);
        for (int x = 0; x < width; x++) {
            float *px = rgb + ((size_t)y * stride + x0 + x) * 3;
            px[0] = r[x], px[1] = g[x], px[2] = b[x];
        }
    }
    hb_plan_destroy(plan);
    return 0;
}

/* The third panel: |first - second| per channel; prints the largest relative to the first's peak. */
static void difference_panel(int width, int height, float *rgb)
{
    double peak = 0.0, largest = 0.0;
    for (int y = 0; y < height; y++)
        for (int k = 0; k < width * 3; k++) {
            float *line = rgb + (size_t)y * width * 9;
            float a = line[k], b = line[width * 3 + k], d = fabsf(a - b);
            line[2 * width * 3 + k] = d;
            peak = a > peak ? a : peak;
            largest = d > largest ? d : largest;
        }
    fprintf(stderr, "hairbsdf dump: largest |difference| %.4g = %.3g of the first panel's peak %.4g\n", largest,
            peak > 0.0 ? largest / peak : 0.0, peak);
}

/* --compare OPTION=VALUE: applies "--OPTION VALUE" to the second panel's options. */
static int apply_compare(const char *spec, cli_model_args *second)
{
    char name[64], value[192], err[256];
    const char *eq = strchr(spec, '=');
    if (!eq || eq == spec || (size_t)(eq - spec) + 3 > sizeof name || strlen(eq + 1) + 1 > sizeof value) {
        fprintf(stderr, "hairbsdf dump: --compare wants OPTION=VALUE, e.g. model=marschner (got '%s')\n", spec);
        return 2;
    }
    snprintf(name, sizeof name, "--%.*s", (int)(eq - spec), spec);
    snprintf(value, sizeof value, "%s", eq + 1);
    char *argv[] = { name, value };
    int i = 0, r = cli_parse_model_option(2, argv, &i, second, err, sizeof err);
    if (r <= 0 || i != 1) {
        fprintf(stderr, "hairbsdf dump: --compare %s: %s\n", spec, r < 0 ? err : "not a model option taking a value");
        return 2;
    }
    return 0;
}

int cmd_dump(int argc, char **argv)
{
    cli_model_args args, second;
    cli_model_args_default(&args);
    double theta_i = 0.0, phi_i = 0.0, exposure = 1.0;
    int width = 512, height = 256, compares = 0;
    const char *path = NULL, *compare[16];
    char err[256];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            dump_usage(stdout);
            return 0;
        }
        int is_value = i + 1 < argc;
        if (is_value && strcmp(a, "-o") == 0) {
            path = argv[++i];
        } else if (is_value && strcmp(a, "--compare") == 0) {
            if (compares == 16) {
                fprintf(stderr, "hairbsdf dump: at most 16 --compare options\n");
                return 2;
            }
            compare[compares++] = argv[++i];
        } else if (is_value && (strcmp(a, "--theta-i") == 0 || strcmp(a, "--phi-i") == 0 ||
                                strcmp(a, "--exposure") == 0)) {
            char *end;
            double x = strtod(argv[++i], &end);
            /* theta_i a valid inclination, phi_i a valid azimuth, the exposure positive and finite as a float */
            double limit = strcmp(a, "--theta-i") == 0 ? 1.5707963267948966 : strcmp(a, "--phi-i") == 0 ? HB_PHI_LIMIT : 3.4e38;
            int ok = !*end && end != argv[i] && fabs(x) <= limit && (strcmp(a, "--exposure") != 0 || x > 0.0);
            if (!ok) {
                fprintf(stderr, "hairbsdf dump: %s: '%s' is not %s\n", a, argv[i],
                        strcmp(a, "--theta-i") == 0 ? "an angle in [-pi/2, pi/2]"
                        : strcmp(a, "--phi-i") == 0 ? "an angle in [-1e4, 1e4]" : "a positive number below 3.4e38");
                return 2;
            }
            *(strcmp(a, "--theta-i") == 0 ? &theta_i : strcmp(a, "--phi-i") == 0 ? &phi_i : &exposure) = x;
        } else if (is_value && (strcmp(a, "--width") == 0 || strcmp(a, "--height") == 0)) {
            int n = atoi(argv[++i]);
            if (n < 1 || n > 8192) {
                fprintf(stderr, "hairbsdf dump: %s must be in 1..8192\n", a);
                return 2;
            }
            *(strcmp(a, "--width") == 0 ? &width : &height) = n;
        } else {
            int r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
            if (r <= 0) {
                fprintf(stderr, "hairbsdf dump: %s\n", r < 0 ? err : "unknown option (see hairbsdf dump --help)");
                return 2;
            }
        }
    }
    int exr = path && ends_with(path, ".exr");
    if (!path || !(ends_with(path, ".pfm") || ends_with(path, ".png") || exr)) {
        fprintf(stderr, "hairbsdf dump: -o FILE.pfm, FILE.exr or FILE.png is required\n");
        return 2;
    }
    if (exr && !image_exr_available()) {
        fprintf(stderr, "hairbsdf dump: this build has no OpenEXR (install libopenexr-dev and rebuild); "
                        "use .pfm for float RGB\n");
        return 2;
    }
    second = args;
    for (int k = 0; k < compares; k++)
        if (apply_compare(compare[k], &second) != 0)
            return 2;
    int panels = compares > 0 ? 3 : 1, image_width = width * panels;
    size_t pixels = (size_t)image_width * height;
    float *rgb = malloc(pixels * 3 * sizeof(float)), *row = malloc((size_t)width * 7 * sizeof(float));
    int st = !rgb || !row ? 1 : 0;
    if (st)
        fprintf(stderr, "hairbsdf dump: out of memory\n");
    if (!st)
        st = render_panel(&args, theta_i, phi_i, width, height, 0, image_width, row, rgb);
    if (!st && panels == 3 && (st = render_panel(&second, theta_i, phi_i, width, height, width, image_width, row, rgb)) == 0)
        difference_panel(width, height, rgb);
    if (!st) {
        if (ends_with(path, ".pfm")) {
            st = image_write_pfm(path, image_width, height, rgb);
        } else if (exr) {
            st = image_write_exr(path, image_width, height, rgb);
        } else {
            st = write_figure(path, &args, &second, panels, rgb, width, height, theta_i, phi_i, exposure);
        }
        if (st != 0)
            fprintf(stderr, "hairbsdf dump: cannot write %s\n", path);
        st = st != 0;
    }
    free(rgb), free(row);
    return st;
}

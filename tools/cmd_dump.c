/* hairbsdf dump: a lat-long image of f over (theta_o, phi_o) for one w_i, like dFH11 Fig. 8 and
 * HHH22 Figs. 6-11: phi_o across (-pi at the left), theta_o from +pi/2 (top) to -pi/2 (bottom). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "image.h"

static void dump_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf dump [options] --theta-i X --phi-i Y [--width W --height H]\n"
                "                     [--exposure E] -o FILE.pfm|FILE.png\n"
                "Writes f(w_i, w_o) over all w_o as a lat-long image: float RGB (PFM), or tone-mapped\n"
                "8-bit sRGB (PNG, x/(1+x) of exposure * f).\n%s",
            cli_model_options_help);
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

int cmd_dump(int argc, char **argv)
{
    cli_model_args args;
    cli_model_args_default(&args);
    double theta_i = 0.0, phi_i = 0.0, exposure = 1.0;
    int width = 512, height = 256;
    const char *path = NULL;
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
        } else if (is_value && (strcmp(a, "--theta-i") == 0 || strcmp(a, "--phi-i") == 0 ||
                                strcmp(a, "--exposure") == 0)) {
            char *end;
            double x = strtod(argv[++i], &end);
            if (*end || end == argv[i]) {
                fprintf(stderr, "hairbsdf dump: %s: '%s' is not a number\n", a, argv[i]);
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
    if (!path || !(ends_with(path, ".pfm") || ends_with(path, ".png"))) {
        fprintf(stderr, "hairbsdf dump: -o FILE.pfm or FILE.png is required\n");
        return 2;
    }
    hb_plan *plan;
    hb_error error;
    if (hb_plan_create(&args.material, &args.options, &plan, &error) != HB_OK) {
        fprintf(stderr, "hairbsdf dump: %s\n", error.message);
        return 2;
    }
    size_t pixels = (size_t)width * height;
    float *rgb = malloc(pixels * 3 * sizeof(float)), *row = malloc((size_t)width * 7 * sizeof(float));
    uint8_t *rgb8 = malloc(pixels * 3);
    if (!rgb || !row || !rgb8) {
        fprintf(stderr, "hairbsdf dump: out of memory\n");
        return 1;
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
            float *px = rgb + ((size_t)y * width + x) * 3;
            px[0] = r[x], px[1] = g[x], px[2] = b[x];
        }
    }
    hb_plan_destroy(plan);
    int st;
    if (ends_with(path, ".pfm")) {
        st = image_write_pfm(path, width, height, rgb);
    } else {
        image_tonemap(pixels, rgb, (float)exposure, rgb8);
        st = image_write_png(path, width, height, rgb8);
    }
    free(rgb), free(row), free(rgb8);
    if (st != 0) {
        fprintf(stderr, "hairbsdf dump: cannot write %s\n", path);
        return 1;
    }
    return 0;
}

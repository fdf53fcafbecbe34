/* dFH11's colour table (HB_AZIMUTHAL_COLOUR_TABLE): one table serves every hair colour. Over
 * eumelanin 0..8 and pheomelanin 0..4 it reproduces each material's quadrature within the quality's
 * target of that material's peak f; a strand's absorption per sample gives what a colour-table plan of
 * that strand's material gives; one table file loads into plans of any colour. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"

enum { N = 2048 };

static float ti[N], pi[N], to[N], po[N];

static void directions(hb_test_ctx *t)
{
    for (int k = 0; k < N; k++) { /* a quarter on the specular cone, the rest anywhere */
        ti[k] = (float)hb_test_range(t, -1.55, 1.55);
        to[k] = k % 4 == 0 ? -ti[k] + (float)hb_test_range(t, -0.05, 0.05) : (float)hb_test_range(t, -1.55, 1.55);
        to[k] = fmaxf(-1.5707f, fminf(1.5707f, to[k]));
        pi[k] = (float)hb_test_range(t, -M_PI, M_PI), po[k] = (float)hb_test_range(t, -M_PI, M_PI);
    }
}

static const double melanins[][2] = { { 0.0, 0.0 }, { 0.3, 0.1 }, { 1.3, 0.4 }, { 3.0, 0.0 }, { 0.2, 4.0 }, { 8.0, 4.0 } };
enum { COLOURS = sizeof melanins / sizeof melanins[0] };

/* The largest |f_colour - f_quadrature| over the material's peak f, for each colour through the
 * colour-table plan `colour` at that strand's absorption per sample. */
static double colour_error(hb_test_ctx *t, const hb_plan *colour, const hb_material *base, const hb_options *o,
                           double worst[COLOURS])
{
    static float f[3][N], q[3][N], s[3][N];
    double largest = 0.0;
    for (int ci = 0; ci < COLOURS; ci++) {
        hb_material m = *base;
        m.eumelanin = melanins[ci][0], m.pheomelanin = melanins[ci][1];
        double sigma[3];
        hb_material_absorption(&m, sigma);
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < N; k++)
                s[c][k] = (float)sigma[c];
        hb_angles_soa in = { ti, pi, to, po };
        CHECK(t, hb_eval_angles_absorption(colour, N, in, (hb_absorption_soa){ s[0], s[1], s[2] },
                                           (hb_rgb_soa){ f[0], f[1], f[2] }, NULL) == HB_OK, "per-sample absorption");
        hb_options quadrature = *o;
        quadrature.azimuthal = HB_AZIMUTHAL_QUADRATURE;
        hb_plan *plan;
        CHECK(t, hb_plan_create(&m, &quadrature, &plan, NULL) == HB_OK, "quadrature plan");
        hb_eval_angles(plan, N, in, (hb_rgb_soa){ q[0], q[1], q[2] }, NULL);
        hb_plan_destroy(plan);
        double peak = 0.0, err = 0.0;
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < N; k++)
                peak = fmax(peak, q[c][k]);
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < N; k++)
                err = fmax(err, fabs(f[c][k] - q[c][k]) / peak);
        worst[ci] = err;
        largest = fmax(largest, err);
    }
    return largest;
}

static void test_every_colour(hb_test_ctx *t)
{
    directions(t);
    static const hb_quality qualities[] = { HB_QUALITY_FAST, HB_QUALITY_BALANCED };
    static const double target[] = { 1e-2, 1e-3 };
    int levels = t->quick ? 1 : 2; /* balanced builds a 65 MiB table in about 1.7 s: the long tier */
    for (int qi = 0; qi < levels; qi++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        o.quality = qualities[qi], o.isa = t->isa, o.azimuthal = HB_AZIMUTHAL_COLOUR_TABLE;
        hb_plan *colour;
        hb_error error;
        CHECK(t, hb_plan_create(&m, &o, &colour, &error) == HB_OK, "colour table: %s", error.message);
        if (!colour)
            continue;
        hb_table_view v = { .struct_size = sizeof v };
        CHECK(t, hb_plan_table(colour, &v) == HB_OK && v.axes == 3 && hb_plan_table_channels(colour) == 1 &&
                     v.count == (size_t)v.size[0] * (size_t)v.size[1] * (size_t)v.size[2] * (size_t)v.slots,
              "a 3-axis view of one channel per slot");
        double worst[COLOURS];
        double largest = colour_error(t, colour, &m, &o, worst);
        CHECK(t, largest <= target[qi], "quality %d: the colour table is %.3g of the peak from the quadrature (target %g)",
              (int)qualities[qi], largest, target[qi]);
        hb_test_note(t, "quality %d: %d x %d x %d nodes x %d slots (%.1f MiB), midpoint error %.2g; of each material's peak "
                        "f: %.1e (white) %.1e %.1e %.1e %.1e %.1e (black)",
                     (int)qualities[qi], v.size[0], v.size[1], v.size[2], v.slots, (double)v.count * 4.0 / (1 << 20),
                     v.error, worst[0], worst[1], worst[2], worst[3], worst[4], worst[5]);
        hb_plan_destroy(colour);
    }
}

static void test_per_sample_and_files(hb_test_ctx *t)
{
    directions(t);
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.quality = HB_QUALITY_FAST, o.azimuthal = HB_AZIMUTHAL_COLOUR_TABLE;
    m.eumelanin = 1.3, m.pheomelanin = 0.4;
    hb_plan *brown, *white, *loaded;
    CHECK(t, hb_plan_create(&m, &o, &brown, NULL) == HB_OK, "brown colour plan");
    /* its own absorption per sample gives what the plan gives */
    double sigma[3];
    hb_material_absorption(&m, sigma);
    static float s[3][N], f[3][N], g[3][N];
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < N; k++)
            s[c][k] = (float)sigma[c];
    hb_angles_soa in = { ti, pi, to, po };
    hb_eval_angles(brown, N, in, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    hb_eval_angles_absorption(brown, N, in, (hb_absorption_soa){ s[0], s[1], s[2] }, (hb_rgb_soa){ g[0], g[1], g[2] }, NULL);
    double diff = 0.0;
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < N; k++)
            diff = fmax(diff, fabs(f[c][k] - g[c][k]) / fmax(fabs(f[c][k]), 1e-30));
    CHECK(t, diff <= 1e-6, "the plan's own absorption per sample: %.3g relative", diff);
    /* a table file of a white plan loads into the brown plan: the same table serves both */
    hb_material white_m = m;
    white_m.eumelanin = white_m.pheomelanin = 0.0;
    CHECK(t, hb_plan_create(&white_m, &o, &white, NULL) == HB_OK, "white colour plan");
    size_t size = 0;
    hb_table_save(white, NULL, 0, &size);
    unsigned char *bytes = malloc(size);
    CHECK(t, bytes && hb_table_save(white, bytes, size, &size) == HB_OK, "save");
    hb_options from_file = o;
    from_file.table_file = bytes, from_file.table_file_size = size;
    hb_error error;
    CHECK(t, hb_plan_create(&m, &from_file, &loaded, &error) == HB_OK, "load into the brown plan: %s", error.message);
    free(bytes);
    if (loaded) {
        hb_eval_angles(loaded, N, in, (hb_rgb_soa){ g[0], g[1], g[2] }, NULL);
        CHECK(t, memcmp(f, g, sizeof f) == 0, "the loaded white table gives the brown plan's values bit for bit");
    }
    /* a material's own table cannot take per-sample absorption */
    hb_options own = o;
    own.azimuthal = HB_AZIMUTHAL_TABLE;
    hb_plan *own_plan;
    CHECK(t, hb_plan_create(&m, &own, &own_plan, NULL) == HB_OK, "own table plan");
    CHECK(t, hb_eval_angles_absorption(own_plan, N, in, (hb_absorption_soa){ s[0], s[1], s[2] },
                                       (hb_rgb_soa){ g[0], g[1], g[2] }, NULL) == HB_ERR_UNSUPPORTED,
          "a material's own table refuses per-sample absorption");
    CHECK(t, hb_plan_table_channels(own_plan) == 3 && hb_plan_table_channels(brown) == 1, "channels 3 and 1");
    hb_plan_destroy(own_plan);
    hb_plan_destroy(loaded);
    hb_plan_destroy(white);
    hb_plan_destroy(brown);
}

const hb_test hb_tests_colour_table[] = {
    { "colour_table_every_colour", test_every_colour, 1 },
    { "colour_table_per_sample_and_files", test_per_sample_and_files, 0 },
    { NULL, NULL, 0 },
};

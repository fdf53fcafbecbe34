/* dFH11 N_p from a table (HB_AZIMUTHAL_TABLE) and `hairbsdf bake`: with alpha = 0 every lobe
 * shares one M_p (a single slot), so f = M N exactly and the table's error in f is bounded by
 * the tolerance times M times the slot's peak N; the baked file holds the plan's table bit for bit. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "portable.h"
#include "test.h"
#include "image.h"

typedef struct table_case {
    double beta_n, eumelanin, eta, tolerance;
} table_case;

static void case_material(const table_case *c, hb_material *m, hb_options *o, hb_isa isa)
{
    hb_material_default(m);
    hb_options_default(o);
    m->alpha = 0.0;
    m->beta_n = c->beta_n, m->eumelanin = c->eumelanin, m->eta = c->eta;
    o->isa = isa;
}

static void test_table_within_tolerance(hb_test_ctx *t)
{
    static const table_case cases[] = {
        { 0.3, 0.3, 1.55, 1e-3 }, { 0.15, 0.0, 1.55, 1e-2 }, { 0.6, 1.0, 1.3, 1e-3 }, { 0.3, 0.05, 1.9, 1e-4 } };
    enum { N = 2048 };
    static float ti[N], pi[N], to[N], po[N], ft[3][N], fq[3][N], M[3][N];
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const table_case *c = &cases[k];
        hb_material m;
        hb_options o;
        case_material(c, &m, &o, t->isa);
        hb_plan *quadrature, *table, *longitudinal;
        CHECK(t, hb_plan_create(&m, &o, &quadrature, NULL) == HB_OK, "quadrature plan");
        o.term = HB_TERM_LONGITUDINAL, o.lobes = 1u << HB_LOBE_R;
        CHECK(t, hb_plan_create(&m, &o, &longitudinal, NULL) == HB_OK, "longitudinal plan");
        o.term = HB_TERM_FULL, o.lobes = HB_LOBES_DEFAULT;
        o.azimuthal = HB_AZIMUTHAL_TABLE, o.table_tolerance = c->tolerance;
        hb_error error;
        CHECK(t, hb_plan_create(&m, &o, &table, &error) == HB_OK, "table plan: %s", error.message);
        hb_table_view v = { .struct_size = sizeof v };
        CHECK(t, hb_plan_table(table, &v) == HB_OK && v.slots == 1 && v.slot_lobes[0] == 0x10fu && v.axes == 2,
              "alpha = 0: one slot holding R..TRRT and the residual (%d slots)", v.slots);
        CHECK(t, v.error <= c->tolerance, "measured error %g above the tolerance %g", v.error, c->tolerance);
        double peak[3] = { 0, 0, 0 };
        for (size_t j = 0; j < v.count; j++)
            peak[j % 3] = fmax(peak[j % 3], v.values[j]);
        for (int j = 0; j < N; j++) { /* a quarter of the directions at grazing theta */
            double spread = j % 4 == 0 ? 1.5707 : 1.4;
            ti[j] = (float)hb_test_range(t, -spread, spread), to[j] = (float)hb_test_range(t, -spread, spread);
            pi[j] = (float)hb_test_range(t, -M_PI, M_PI), po[j] = (float)hb_test_range(t, -M_PI, M_PI);
        }
        hb_angles_soa in = { ti, pi, to, po };
        hb_eval_angles(table, N, in, (hb_rgb_soa){ ft[0], ft[1], ft[2] }, NULL);
        hb_eval_angles(quadrature, N, in, (hb_rgb_soa){ fq[0], fq[1], fq[2] }, NULL);
        hb_eval_angles(longitudinal, N, in, (hb_rgb_soa){ M[0], M[1], M[2] }, NULL); /* M in every channel */
        double worst = 0.0;
        for (int j = 0; j < N; j++)
            for (int ch = 0; ch < 3; ch++) {
                double bound = c->tolerance * M[0][j] * peak[ch] + 1e-5 * fabs(fq[ch][j]) + 1e-30;
                worst = fmax(worst, fabs(ft[ch][j] - fq[ch][j]) / bound);
            }
        CHECK(t, worst <= 1.0, "case %zu: |f_table - f_quadrature| reaches %.3g of tolerance x M x peak N", k, worst);
        hb_test_note(t, "case %zu: %dx%d nodes, measured %.2g, worst %.2f of the bound", k, v.size[0], v.size[1],
                     v.error, worst);
        hb_plan_destroy(quadrature), hb_plan_destroy(table), hb_plan_destroy(longitudinal);
    }
}

static void test_table_refusals(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    hb_plan *plan = NULL;
    hb_table_view v = { .struct_size = sizeof v };
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK && hb_plan_table(plan, &v) == HB_ERR_UNSUPPORTED,
          "a quadrature plan has no table");
    hb_plan_destroy(plan);
    CHECK(t, hb_plan_table(NULL, &v) == HB_ERR_NULL, "NULL plan");
    hb_error error;
    o.azimuthal = HB_AZIMUTHAL_TABLE;
    o.model = HB_MODEL_MARSCHNER;
    CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_ERR_UNSUPPORTED && strstr(error.message, "deon"), "marschner");
    o.model = HB_MODEL_DEON, o.r_fresnel = HB_R_FRESNEL_HALF_ANGLE;
    CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_ERR_UNSUPPORTED && strstr(error.message, "Fresnel"),
          "half-angle Fresnel");
    o.r_fresnel = HB_R_FRESNEL_OFFSET, o.quality = HB_QUALITY_REFERENCE;
    CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_ERR_UNSUPPORTED, "reference quality");
    o.quality = HB_QUALITY_BALANCED, o.table_tolerance = -1.0;
    CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_ERR_PARAM && strstr(error.message, "table_tolerance"),
          "negative tolerance");
    o.table_tolerance = NAN;
    CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_ERR_PARAM, "NaN tolerance");
    o.table_tolerance = 0.0, o.azimuthal = (hb_azimuthal)7;
    CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_ERR_PARAM, "not a variant");
}

/* hairbsdf bake: the .hbt file is the plan's table file (hb_table_save) byte for byte, `eval --table`
 * from it prints what the plan that baked it prints, and the EXR holds the same floats, slots stacked. */
static void test_bake_files(hb_test_ctx *t)
{
    if (!hb_test_tool(t))
        return;
    static const char *const models[] = { "--model deon --eumelanin 0.3 --table-tolerance 1e-2",
                                          "--model huang --quality fast --roughness 0.3" };
    static const char *const built[] = { "--azimuthal table", "--tt-trt table" };
    for (int which = 0; which < 2; which++) {
        char path[600], args[1024];
        hb_tool_run run;
        CHECK(t, hb_test_temp_file(path, sizeof path, ".hbt") == 0, "no temporary file");
        snprintf(args, sizeof args, "bake %s -o \"%s\"", models[which], path);
        CHECK(t, hb_test_run_tool(t, args, "", 0, &run) && run.status == 0, "%s: %s", args, run.err);
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        if (which == 0) {
            m.eumelanin = 0.3, o.azimuthal = HB_AZIMUTHAL_TABLE, o.table_tolerance = 1e-2;
        } else {
            o.model = HB_MODEL_HUANG, o.quality = HB_QUALITY_FAST, o.tt_trt = HB_TT_TRT_TABLE, m.roughness = 0.3;
        }
        hb_plan *plan;
        hb_table_view v = { .struct_size = sizeof v };
        CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK && hb_plan_table(plan, &v) == HB_OK, "plan's table");
        FILE *f = fopen(path, "rb");
        static unsigned char data[1 << 22], saved[1 << 22];
        size_t n = f ? fread(data, 1, sizeof data, f) : 0, size = 0;
        if (f)
            fclose(f);
        CHECK(t, hb_table_save(plan, saved, sizeof saved, &size) == HB_OK && n == size && memcmp(data, saved, n) == 0,
              "the baked file (%zu bytes) is not the plan's table file (%zu bytes)", n, size);
        static const char rows[] = "0.3,0.1,-0.2,2.0\n0.5,1,0.1,-3\n-1.2,0,1.1,0.2\n";
        static hb_tool_run from_file, from_plan;
        snprintf(args, sizeof args, "eval %s --table \"%s\"", models[which], path);
        hb_test_run_tool(t, args, rows, sizeof rows - 1, &from_file);
        snprintf(args, sizeof args, "eval %s %s", models[which], built[which]);
        hb_test_run_tool(t, args, rows, sizeof rows - 1, &from_plan);
        CHECK(t, from_file.status == 0 && from_plan.status == 0 && strcmp(from_file.out, from_plan.out) == 0,
              "eval --table printed '%s' (%s), the plan '%s'", from_file.out, from_file.err, from_plan.out);
        snprintf(args, sizeof args, "eval %s --eta 1.4 --table \"%s\"", models[which], path);
        hb_test_run_tool(t, args, "0,0,0,0\n", 8, &run);
        CHECK(t, run.status != 0 && strstr(run.err, "eta"), "eval --table of another material must fail: %d %s",
              run.status, run.err);
        unlink(path);
        if (image_exr_available()) {
            char exr[600];
            CHECK(t, hb_test_temp_file(exr, sizeof exr, ".exr") == 0, "no temporary file");
            snprintf(args, sizeof args, "bake %s -o \"%s\"", models[which], exr);
            CHECK(t, hb_test_run_tool(t, args, "", 0, &run) && run.status == 0, "%s: %s", args, run.err);
            int w = 0, h = 0;
            float *rgb = image_read_exr(exr, &w, &h);
            int width = v.size[v.axes - 1], lines = (int)(v.count / (size_t)(3 * v.slots * width));
            CHECK(t, rgb && w == width && h == lines * v.slots, "EXR %dx%d", w, h);
            for (int s = 0; rgb && s < v.slots; s++)
                for (int y = 0; y < lines; y++)
                    for (int x = 0; x < width; x++)
                        CHECK(t, memcmp(rgb + (((size_t)s * lines + y) * width + x) * 3,
                                        v.values + (((size_t)y * width + x) * v.slots + s) * 3, 12) == 0,
                              "EXR slot %d at (%d, %d): %g vs %g", s, x, y,
                              (double)rgb[(((size_t)s * lines + y) * width + x) * 3],
                              (double)v.values[(((size_t)y * width + x) * v.slots + s) * 3]);
            free(rgb);
            unlink(exr);
        }
        hb_plan_destroy(plan);
    }
}

const hb_test hb_tests_deon_table[] = {
    { "deon_table_within_tolerance", test_table_within_tolerance, 1 },
    { "deon_table_refusals", test_table_refusals, 0 },
    { "bake_files", test_bake_files, 0 },
    { NULL, NULL, 0 },
};

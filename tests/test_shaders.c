/* The shaders of shaders/ run for real: compiled to SPIR-V by glslangValidator (GLSL, and HLSL with -D)
 * and dispatched as compute shaders on a Vulkan device (Mesa's lavapipe in CI), over 4096 directions
 * for 4 dFH11 materials: with each material's own table for 3 hair colours, and with one colour table
 * per material and each direction's strand colour (blond, brown or black) as an input; every value
 * agrees with the CPU's table path of the same plan within 1e-4 of the material's peak. Skipped,
 * saying why, where glslang or Vulkan is missing, under emulation and in sanitizer builds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "portable.h"
#include "test.h"

enum { DIRECTIONS = 4096, GROUP = 64, PARAMS = HB_SHADER_CONSTANTS + 2 }; /* then the count and the strand flag */

/* Compiles a test kernel to SPIR-V with glslangValidator; returns its words (free them) or NULL. */
static uint32_t *compile(const char *source, int hlsl, size_t *size, char *why, size_t why_size)
{
    char path[600], cmd[2048];
    if (hb_test_temp_file(path, sizeof path, "") != 0) {
        snprintf(why, why_size, "no temporary file in %s", hb_test_temp_dir());
        return NULL;
    }
    snprintf(cmd, sizeof cmd, "glslangValidator -V --target-env vulkan1.0 %s -Ishaders -o %s %s > %s.log 2>&1",
             hlsl ? "-D -S comp -e main" : "", path, source, path);
    int st = system(cmd);
    FILE *f = st == 0 ? fopen(path, "rb") : NULL;
    uint32_t *code = NULL;
    if (f) {
        fseek(f, 0, SEEK_END);
        long n = ftell(f);
        fseek(f, 0, SEEK_SET);
        code = n > 0 ? malloc((size_t)n) : NULL;
        *size = code ? fread(code, 1, (size_t)n, f) : 0;
        fclose(f);
    } else {
        snprintf(why, why_size, "glslangValidator failed on %.80s (see %.130s.log)", source, path);
    }
    unlink(path);
    return code;
}

typedef struct shader_material {
    const char *name;
    double beta_m, beta_n, eta, alpha;
} shader_material;

/* The Vulkan device and both kernels compiled, or NULL with the test skipped (or failed) saying why. */
static hb_gpu *open_kernels(hb_test_ctx *t, const char *glsl, const char *hlsl, uint32_t *code[2], size_t sizes[2],
                            char *name, size_t name_size)
{
    char why[256] = "";
#ifdef HB_SANITIZED
    const int sanitized = 1; /* the sanitizers would instrument this program, not Mesa's JIT-compiled shaders */
#else
    const int sanitized = 0;
#endif
    code[0] = code[1] = NULL;
    if (t->emulated || sanitized || system("glslangValidator --version > /dev/null 2>&1") != 0) {
        hb_test_skip(t, t->emulated ? "emulated" : sanitized ? "a sanitizer build (Mesa's JIT is not instrumented)"
                                                             : "no glslangValidator (Debian's glslang-tools)");
        return NULL;
    }
    hb_gpu *gpu = hb_gpu_open(name, name_size, why, sizeof why);
    if (!gpu) {
        hb_test_skip(t, why);
        return NULL;
    }
    code[0] = compile(glsl, 0, &sizes[0], why, sizeof why);
    code[1] = compile(hlsl, 1, &sizes[1], why, sizeof why);
    CHECK(t, code[0] && code[1], "%s", why);
    return gpu;
}

/* The largest |GPU - CPU| / peak of the CPU's f over a dispatch of both kernels, into worst[language];
 * each within limit. */
static void compare_kernels(hb_test_ctx *t, hb_gpu *gpu, uint32_t *const code[2], const size_t sizes[2], int buffers,
                            float *const *data, const size_t *counts, const float (*cpu_f)[DIRECTIONS], const char *what,
                            double worst[2], double limit)
{
    static float gpu_f[3 * DIRECTIONS];
    char why[256];
    double peak = 0.0;
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < DIRECTIONS; k++)
            peak = fmax(peak, cpu_f[c][k]);
    float *bound[8];
    for (int b = 0; b < buffers; b++)
        bound[b] = b == 3 ? gpu_f : data[b]; /* buffer 3 is the output */
    for (int lang = 0; lang < 2; lang++) {
        memset(gpu_f, 0, sizeof gpu_f);
        if (hb_gpu_run(gpu, code[lang], sizes[lang], buffers, bound, counts, DIRECTIONS / GROUP, why, sizeof why) != 0) {
            CHECK(t, 0, "%s: %s", lang ? "HLSL" : "GLSL", why);
            continue;
        }
        double err = 0.0;
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < DIRECTIONS; k++)
                err = fmax(err, fabs((double)gpu_f[c * DIRECTIONS + k] - cpu_f[c][k]) / peak);
        CHECK(t, err <= limit, "%s, %s: shader differs from the CPU by %.3g of the peak %.3g", lang ? "HLSL" : "GLSL",
              what, err, peak);
        worst[lang] = fmax(worst[lang], err);
    }
}

/* Directions for the shader tests: a quarter on the specular cone, a tenth grazing. */
static void shader_directions(hb_test_ctx *t, float *angles)
{
    for (int k = 0; k < DIRECTIONS; k++) {
        float ti = (float)hb_test_range(t, -1.55, 1.55);
        float to = k % 4 == 0 ? -ti + (float)hb_test_range(t, -0.1, 0.1) : (float)hb_test_range(t, -1.55, 1.55);
        if (k % 10 == 1)
            to = (float)hb_test_range(t, 1.5, 1.5707);
        angles[k] = ti, angles[DIRECTIONS + k] = (float)hb_test_range(t, -M_PI, M_PI);
        angles[2 * DIRECTIONS + k] = fmaxf(-1.5707f, fminf(1.5707f, to));
        angles[3 * DIRECTIONS + k] = (float)hb_test_range(t, -M_PI, M_PI);
    }
}

static void test_shaders_match_cpu(hb_test_ctx *t)
{
    char name[256] = "";
    size_t sizes[2] = { 0, 0 };
    uint32_t *code[2];
    hb_gpu *gpu = open_kernels(t, "tests/shaders/deon_eval.comp", "tests/shaders/deon_eval.hlsl", code, sizes, name,
                               sizeof name);
    if (!gpu)
        return;
    static const shader_material materials[] = {
        { "default", 0.1, 0.3, 1.55, 0.035 },
        { "smooth", 0.05, 0.15, 1.55, 0.05 },
        { "rough, eta 1.3", 0.3, 0.6, 1.3, 0.02 },
        { "untilted, eta 1.9", 0.15, 0.4, 1.9, 0.0 },
    };
    static const double colours[3][2] = { { 0.1, 0.05 }, { 1.3, 0.4 }, { 3.0, 0.2 } }; /* blond, brown, dark brown */
    static float angles[4 * DIRECTIONS], cpu_f[3][DIRECTIONS], params[PARAMS];
    static float sigma_a[3 * DIRECTIONS];
    shader_directions(t, angles);
    double worst[2][2] = { { 0.0, 0.0 }, { 0.0, 0.0 } }; /* [strand colours][language] */
    for (int k = 0; k < DIRECTIONS; k++) { /* each direction's strand: blond, brown or black */
        static const double strand[3][2] = { { 0.1, 0.05 }, { 1.3, 0.4 }, { 8.0, 0.0 } };
        double sigma[3];
        hb_melanin_absorption(strand[k % 3][0], strand[k % 3][1], sigma);
        for (int c = 0; c < 3; c++)
            sigma_a[c * DIRECTIONS + k] = (float)sigma[c];
    }
    hb_angles_soa in = { angles, angles + DIRECTIONS, angles + 2 * DIRECTIONS, angles + 3 * DIRECTIONS };
    for (size_t mi = 0; code[0] && code[1] && mi < sizeof materials / sizeof materials[0]; mi++)
        for (int ci = 0; ci < 4; ci++) { /* 3 colours with the material's own table, then the colour table */
            const shader_material *s = &materials[mi];
            int strands = ci == 3;
            hb_material m;
            hb_options o;
            hb_material_default(&m);
            hb_options_default(&o);
            m.beta_m = s->beta_m, m.beta_n = s->beta_n, m.eta = s->eta, m.alpha = s->alpha;
            if (!strands)
                m.eumelanin = colours[ci][0], m.pheomelanin = colours[ci][1];
            o.azimuthal = strands ? HB_AZIMUTHAL_COLOUR_TABLE : HB_AZIMUTHAL_TABLE;
            o.quality = strands ? HB_QUALITY_FAST : HB_QUALITY_BALANCED;
            hb_plan *plan;
            hb_error error;
            hb_table_view v = { .struct_size = sizeof v };
            if (hb_plan_create(&m, &o, &plan, &error) != HB_OK || hb_plan_table(plan, &v) != HB_OK ||
                hb_plan_shader_constants(plan, params) != HB_OK) {
                CHECK(t, 0, "%s: %s", s->name, error.message);
                continue;
            }
            params[HB_SHADER_CONSTANTS] = (float)DIRECTIONS, params[HB_SHADER_CONSTANTS + 1] = (float)strands;
            if (strands)
                hb_eval_angles_absorption(plan, DIRECTIONS, in,
                                          (hb_absorption_soa){ sigma_a, sigma_a + DIRECTIONS, sigma_a + 2 * DIRECTIONS },
                                          (hb_rgb_soa){ cpu_f[0], cpu_f[1], cpu_f[2] }, NULL);
            else
                hb_eval_angles(plan, DIRECTIONS, in, (hb_rgb_soa){ cpu_f[0], cpu_f[1], cpu_f[2] }, NULL);
            float *data[5] = { params, (float *)v.values, angles, NULL, sigma_a };
            size_t counts[5] = { PARAMS, v.count, 4 * DIRECTIONS, 3 * DIRECTIONS, 3 * DIRECTIONS };
            char what[96];
            snprintf(what, sizeof what, "%s, %s", s->name, strands ? "strand colours" : "one colour");
            compare_kernels(t, gpu, code, sizes, 5, data, counts, (const float(*)[DIRECTIONS])cpu_f, what, worst[strands], 1e-4);
            hb_plan_destroy(plan);
        }
    hb_test_note(t, "%s: largest difference from the CPU table path, of each material's peak: own tables GLSL %.2g, "
                    "HLSL %.2g; colour table with strand colours GLSL %.2g, HLSL %.2g",
                 name, worst[0][0], worst[0][1], worst[1][0], worst[1][1]);
    free(code[0]);
    free(code[1]);
    hb_gpu_close(gpu);
}

/* HHH22: the App. A R lobe and the TT/TRT table, 4 materials x 3 colours (each its own plan). */
static void test_huang_shader(hb_test_ctx *t)
{
    char name[256] = "";
    size_t sizes[2] = { 0, 0 };
    uint32_t *code[2];
    hb_gpu *gpu = open_kernels(t, "tests/shaders/huang_eval.comp", "tests/shaders/huang_eval.hlsl", code, sizes, name,
                               sizeof name);
    if (!gpu)
        return;
    static const struct {
        const char *name;
        double roughness, eta, alpha;
    } materials[] = { { "GGX 0.1", 0.1, 1.55, 0.035 }, { "GGX 0.3, eta 1.3", 0.3, 1.3, 0.0 },
                      { "GGX 0.2, tilt 0.06", 0.2, 1.55, 0.06 }, { "GGX 0.5, eta 1.9", 0.5, 1.9, 0.02 } };
    static const double colours[3][2] = { { 0.1, 0.05 }, { 1.3, 0.4 }, { 3.0, 0.2 } };
    static float angles[4 * DIRECTIONS], cpu_f[3][DIRECTIONS], params[PARAMS];
    shader_directions(t, angles);
    double worst[2] = { 0.0, 0.0 };
    for (size_t mi = 0; code[0] && code[1] && mi < sizeof materials / sizeof materials[0]; mi++)
        for (int ci = 0; ci < 3; ci++) {
            hb_material m;
            hb_options o;
            hb_material_default(&m);
            hb_options_default(&o);
            m.roughness = materials[mi].roughness, m.eta = materials[mi].eta, m.alpha = materials[mi].alpha;
            m.eumelanin = colours[ci][0], m.pheomelanin = colours[ci][1];
            o.model = HB_MODEL_HUANG, o.quality = HB_QUALITY_FAST, o.tt_trt = HB_TT_TRT_TABLE;
            o.shadowing = HB_SHADOWING_NONE; /* App. A's closed form is without G */
            hb_plan *plan;
            hb_error error;
            hb_table_view v = { .struct_size = sizeof v };
            if (hb_plan_create(&m, &o, &plan, &error) != HB_OK || hb_plan_table(plan, &v) != HB_OK ||
                hb_plan_shader_constants(plan, params) != HB_OK) {
                CHECK(t, 0, "%s: %s", materials[mi].name, error.message);
                continue;
            }
            params[HB_SHADER_CONSTANTS] = (float)DIRECTIONS;
            hb_eval_angles(plan, DIRECTIONS,
                           (hb_angles_soa){ angles, angles + DIRECTIONS, angles + 2 * DIRECTIONS, angles + 3 * DIRECTIONS },
                           (hb_rgb_soa){ cpu_f[0], cpu_f[1], cpu_f[2] }, NULL);
            float *data[4] = { params, (float *)v.values, angles, NULL };
            size_t counts[4] = { PARAMS, v.count, 4 * DIRECTIONS, 3 * DIRECTIONS };
            char what[96];
            snprintf(what, sizeof what, "%s, colour %d", materials[mi].name, ci);
            compare_kernels(t, gpu, code, sizes, 4, data, counts, (const float(*)[DIRECTIONS])cpu_f, what, worst, 1e-4);
            hb_plan_destroy(plan);
        }
    hb_test_note(t, "%s: HHH22 R + TT/TRT, largest difference from the CPU, of each material's peak: GLSL %.2g, HLSL %.2g",
                 name, worst[0], worst[1]);
    free(code[0]);
    free(code[1]);
    hb_gpu_close(gpu);
}

/* Dual scattering's f_DS from a plan's table: dFH11 and CBTB16, blond and brown, each direction with
 * its own fibre count n in [0, 16] and the default visibility, against hb_dual_eval on the CPU. */
static void test_dual_shader(hb_test_ctx *t)
{
    char name[256] = "";
    size_t sizes[2] = { 0, 0 };
    uint32_t *code[2];
    hb_gpu *gpu = open_kernels(t, "tests/shaders/dual_eval.comp", "tests/shaders/dual_eval.hlsl", code, sizes, name,
                               sizeof name);
    if (!gpu)
        return;
    static const struct {
        const char *name;
        hb_model model;
        double eumelanin, pheomelanin;
    } materials[] = { { "dFH11 blond", HB_MODEL_DEON, 0.3, 0.0 }, { "dFH11 brown", HB_MODEL_DEON, 1.3, 0.0 },
                      { "CBTB16 blond", HB_MODEL_CHIANG, 0.3, 0.0 }, { "CBTB16 red", HB_MODEL_CHIANG, 0.0, 2.0 } };
    static float angles[4 * DIRECTIONS], cpu_f[3][DIRECTIONS], params[4], fibres[DIRECTIONS];
    shader_directions(t, angles);
    for (int k = 0; k < DIRECTIONS; k++)
        fibres[k] = k % 5 == 0 ? 0.0f : (float)hb_test_range(t, 0.0, 16.0);
    double worst[2] = { 0.0, 0.0 };
    for (size_t mi = 0; code[0] && code[1] && mi < sizeof materials / sizeof materials[0]; mi++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        m.eumelanin = materials[mi].eumelanin, m.pheomelanin = materials[mi].pheomelanin;
        o.model = materials[mi].model;
        hb_plan *plan = NULL;
        hb_dual_table *table = NULL;
        hb_error error;
        if (hb_plan_create(&m, &o, &plan, &error) != HB_OK ||
            hb_dual_table_create(plan, 64, HB_DUAL_DENSITY, HB_DUAL_DENSITY, NULL, NULL, NULL, NULL, &table) != HB_OK) {
            CHECK(t, 0, "%s: %s", materials[mi].name, hb_last_error()->message);
            hb_plan_destroy(plan);
            continue;
        }
        int thetas;
        const float *nodes = hb_dual_table_nodes(table, &thetas);
        params[0] = (float)thetas, params[1] = (float)HB_DUAL_DENSITY, params[2] = (float)HB_DUAL_DENSITY;
        params[3] = (float)DIRECTIONS;
        hb_dual_eval(table, DIRECTIONS,
                     (hb_angles_soa){ angles, angles + DIRECTIONS, angles + 2 * DIRECTIONS, angles + 3 * DIRECTIONS }, fibres,
                     NULL, (hb_rgb_soa){ cpu_f[0], cpu_f[1], cpu_f[2] }, NULL);
        float *data[5] = { params, (float *)nodes, angles, NULL, fibres };
        size_t counts[5] = { 4, (size_t)thetas * HB_DUAL_NODE_FLOATS, 4 * DIRECTIONS, 3 * DIRECTIONS, DIRECTIONS };
        compare_kernels(t, gpu, code, sizes, 5, data, counts, (const float(*)[DIRECTIONS])cpu_f, materials[mi].name,
                        worst, 1e-5);
        hb_dual_table_destroy(table);
        hb_plan_destroy(plan);
    }
    hb_test_note(t, "%s: dual scattering's f_DS, largest difference from hb_dual_eval, of each material's peak: GLSL %.2g, "
                    "HLSL %.2g",
                 name, worst[0], worst[1]);
    free(code[0]);
    free(code[1]);
    hb_gpu_close(gpu);
}

/* Dual scattering's f_DS from an engine-wide table (16 theta x 8 roughnesses x 8 absorptions, dFH11),
 * the fibre's roughness and absorption given to the shader, against hb_dual_eval of the plan's
 * table from it (hb_dual_engine_table): dFH11 fibres between the roughness nodes, lossless, blond,
 * brown and red. */
static void test_dual_engine_shader(hb_test_ctx *t)
{
    char name[256] = "";
    size_t sizes[2] = { 0, 0 };
    uint32_t *code[2];
    hb_gpu *gpu = open_kernels(t, "tests/shaders/dual_engine_eval.comp", "tests/shaders/dual_engine_eval.hlsl", code,
                               sizes, name, sizeof name);
    if (!gpu)
        return;
    static const struct {
        const char *name;
        double beta_m, eumelanin, pheomelanin;
    } materials[] = { { "lossless, beta_m 0.13", 0.13, 0.0, 0.0 }, { "blond, beta_m 0.13", 0.13, 0.3, 0.0 },
                      { "brown, beta_m 0.27", 0.27, 1.3, 0.0 }, { "red, beta_m 0.41", 0.41, 0.0, 2.0 } };
    static float angles[4 * DIRECTIONS], cpu_f[3][DIRECTIONS], params[13], fibres[DIRECTIONS];
    shader_directions(t, angles);
    for (int k = 0; k < DIRECTIONS; k++)
        fibres[k] = k % 5 == 0 ? 0.0f : (float)hb_test_range(t, 0.0, 16.0);
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    hb_dual_engine_axes axes;
    hb_dual_engine_axes_default(&axes);
    axes.thetas = 16, axes.roughnesses = 8, axes.absorptions = 8;
    hb_dual_engine *engine = NULL;
    hb_error error;
    CHECK(t, hb_dual_engine_create(&m, &o, &axes, HB_DUAL_DENSITY, &engine, &error) == HB_OK, "%s", error.message);
    size_t floats = 0;
    const float *nodes = hb_dual_engine_nodes(engine, &floats);
    hb_dual_engine_constants(engine, HB_DUAL_DENSITY, params);
    double worst[2] = { 0.0, 0.0 };
    for (size_t mi = 0; engine && code[0] && code[1] && mi < sizeof materials / sizeof materials[0]; mi++) {
        m.beta_m = materials[mi].beta_m, m.eumelanin = materials[mi].eumelanin, m.pheomelanin = materials[mi].pheomelanin;
        hb_plan *plan = NULL;
        hb_dual_table *table = NULL;
        if (hb_plan_create(&m, &o, &plan, &error) != HB_OK ||
            hb_dual_engine_table(engine, plan, HB_DUAL_DENSITY, &table) != HB_OK) {
            CHECK(t, 0, "%s: %s", materials[mi].name, hb_last_error()->message);
            hb_plan_destroy(plan);
            continue;
        }
        double sigma_a[3];
        hb_material_absorption(&m, sigma_a);
        params[8] = (float)DIRECTIONS, params[9] = (float)m.beta_m;
        for (int c = 0; c < 3; c++)
            params[10 + c] = (float)sigma_a[c];
        hb_dual_eval(table, DIRECTIONS,
                     (hb_angles_soa){ angles, angles + DIRECTIONS, angles + 2 * DIRECTIONS, angles + 3 * DIRECTIONS }, fibres,
                     NULL, (hb_rgb_soa){ cpu_f[0], cpu_f[1], cpu_f[2] }, NULL);
        float *data[5] = { params, (float *)nodes, angles, NULL, fibres };
        size_t counts[5] = { 13, floats, 4 * DIRECTIONS, 3 * DIRECTIONS, DIRECTIONS };
        compare_kernels(t, gpu, code, sizes, 5, data, counts, (const float(*)[DIRECTIONS])cpu_f, materials[mi].name,
                        worst, 1e-5);
        hb_dual_table_destroy(table);
        hb_plan_destroy(plan);
    }
    hb_test_note(t, "%s: f_DS from the engine-wide table, largest difference from hb_dual_eval of the plan's table, of "
                    "each material's peak: GLSL %.2g, HLSL %.2g",
                 name, worst[0], worst[1]);
    hb_dual_engine_destroy(engine);
    free(code[0]);
    free(code[1]);
    hb_gpu_close(gpu);
}

const hb_test hb_tests_shaders[] = {
    { "shaders_match_cpu_table_path", test_shaders_match_cpu, 0 },
    { "shaders_huang_match_cpu", test_huang_shader, 0 },
    { "shaders_dual_match_cpu", test_dual_shader, 0 },
    { "shaders_dual_engine_match_cpu", test_dual_engine_shader, 0 },
    { NULL, NULL, 0 },
};

/* The hairbsdf tool, driven through $HB_TOOL (set by make test; under qemu it
 * includes the emulator): eval's output equals the library's, headers and blank
 * lines are skipped, malformed rows, bad options and bad values are clear errors. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "portable.h"
#include "test.h"

static int run_tool(hb_test_ctx *t, const char *args, const char *input, hb_tool_run *r)
{
    return hb_test_run_tool(t, args, input, strlen(input), r);
}

/* A temporary file with the suffix into path, then the tool run with args_format's %s as that path. */
static int run_tool_writing(hb_test_ctx *t, const char *suffix, char *path, size_t path_size, const char *args_format,
                            hb_tool_run *r)
{
    char args[1024];
    if (hb_test_temp_file(path, path_size, suffix) != 0) {
        CHECK(t, 0, "no temporary file in %s", hb_test_temp_dir());
        return 0;
    }
    snprintf(args, sizeof args, args_format, path);
    return run_tool(t, args, "", r);
}

static void test_eval_matches_library(hb_test_ctx *t)
{
    const float rows[][4] = { { 0.3f, 0.0f, -0.3f, 0.5f }, { 0.3f, 0.0f, -0.2f, 0.5f }, { -1.2f, 1.0f, 1.1f, -2.0f },
                              { 1.5707963f, 0.0f, -1.5707963f, 3.14159f }, { 0.0f, 0.0f, 0.0f, 0.0f } };
    enum { N = sizeof rows / sizeof rows[0] };
    char input[1024] = "theta_i,phi_i,theta_o,phi_o\n\n";
    for (int k = 0; k < N; k++) {
        char line[128];
        snprintf(line, sizeof line, "%.9g, %.9g,%.9g ,%.9g\r\n%s", rows[k][0], rows[k][1], rows[k][2], rows[k][3],
                 k == 2 ? "\n" : "");
        strcat(input, line);
    }
    hb_material m;
    hb_options o;
    hb_test_longitudinal_setup(t, &m, &o);
    m.beta_m = 0.05;
    m.alpha = 0.02;
    o.isa = HB_ISA_SCALAR;
    for (int quality = 0; quality < 2; quality++) {
        o.quality = quality ? HB_QUALITY_REFERENCE : HB_QUALITY_BALANCED;
        hb_tool_run r;
        char args[256];
        snprintf(args, sizeof args, "eval --model deon --term longitudinal --beta-m 0.05 --alpha=0.02 --isa scalar%s",
                 quality ? " --quality reference" : "");
        if (!run_tool(t, args, input, &r))
            return;
        CHECK(t, r.status == 0, "exit %d, stderr: %s", r.status, r.err);
        hb_plan *plan;
        hb_plan_create(&m, &o, &plan, NULL);
        float ti[N], pi[N], to[N], po[N], f[3][N];
        for (int k = 0; k < N; k++)
            ti[k] = rows[k][0], pi[k] = rows[k][1], to[k] = rows[k][2], po[k] = rows[k][3];
        hb_eval_angles(plan, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        hb_plan_destroy(plan);
        char *line = r.out;
        for (int k = 0; k < N; k++) {
            float got[3];
            int ok = line && sscanf(line, "%g,%g,%g", &got[0], &got[1], &got[2]) == 3;
            CHECK(t, ok && got[0] == f[0][k] && got[1] == f[1][k] && got[2] == f[2][k],
                  "row %d: tool '%.40s' vs library %.9g", k, line ? line : "(missing)", f[0][k]);
            line = line ? strchr(line, '\n') : NULL;
            line = line ? line + 1 : NULL;
        }
        CHECK(t, line && *line == '\0', "extra output: '%s'", line ? line : "");
    }
}

static void test_eval_errors(hb_test_ctx *t)
{
    hb_tool_run r;
    if (!run_tool(t, "eval --term longitudinal", "0.1,0,0.2,0\n0.2,0,0.1,0\n\n0.1,0,0.2\n0.3,0,0.3,0\n", &r))
        return;
    CHECK(t, r.status != 0, "malformed row accepted");
    CHECK(t, strstr(r.err, "line 4") != NULL, "malformed row's line number not reported: %s", r.err);
    int lines = 0;
    for (const char *p = r.out; *p; p++)
        lines += *p == '\n';
    CHECK(t, lines == 2, "rows before the malformed one must be written: got %d lines", lines);

    run_tool(t, "eval --term longitudinal", "0.1,0,0.2,0\nabc,0,0,0\n", &r);
    CHECK(t, r.status != 0 && strstr(r.err, "line 2"), "a non-first text line is malformed, not a header");

    run_tool(t, "eval --term longitudinal", "nan,0,0.2,0\n0.1,inf,0.2,0\n0.1,0,0.2,0\n", &r);
    CHECK(t, r.status == 0 && strncmp(r.out, "0,0,0\n0,0,0\n", 12) == 0, "NaN/Inf rows give 0,0,0: %s", r.out);
    CHECK(t, strstr(r.err, "2 invalid samples") != NULL, "invalid rows counted on stderr: %s", r.err);

    run_tool(t, "assembly --packing 0.9", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--packing"), "assembly packing 0.9: %d %s", r.status, r.err);
    run_tool(t, "assembly --model huang --quality fast --paths 10", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "estimate"), "HHH22 under the light's transport: %d %s", r.status, r.err);
    run_tool(t, "assembly --model chiang --layers 2 --paths 600", "", &r);
    CHECK(t, r.status == 0 && strstr(r.out, "\nreflected,"), "CBTB16 under the light's transport: %d %s", r.status, r.err);
    run_tool(t, "assembly --layers 2 --packing 0.5 --paths 10", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "reached packing"), "assembly that cannot be packed: %d %s", r.status, r.err);
    run_tool(t, "eval --bogus 3", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--bogus"), "unknown option: %d %s", r.status, r.err);
    run_tool(t, "eval --term longitudinal --beta-m 7", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "beta_m"), "out of range beta_m: %d %s", r.status, r.err);
    run_tool(t, "eval --term longitudinal --eta abc", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--eta"), "non-numeric value: %d %s", r.status, r.err);
    run_tool(t, "eval --term longitudinal --beta-m", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "needs a value"), "missing value: %d %s", r.status, r.err);
    run_tool(t, "eval --model huang --lobes R,TT,TRT,TRRT", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "R, TT and TRT only"), "a lobe the model lacks: %d %s", r.status, r.err);
    run_tool(t, "eval --model huang --lobes R --r-integration analytic", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "no shadowing"), "analytic with G: %d %s", r.status, r.err);
    run_tool(t, "eval --model huang --lobes R --r-panels 7", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "even"), "odd panel count: %d %s", r.status, r.err);
    /* every HHH22 switch of the issue, and the reference */
    run_tool(t, "eval --model huang --lobes R --ndf beckmann --roughness 0.2 --alpha 0.05 --eccentricity 0.5 "
                "--no-shadowing --r-integration numeric --r-step 0.7", "0.3,0,-0.35,0.2\n", &r);
    CHECK(t, r.status == 0 && strchr(r.out, ','), "huang switches: %d %s %s", r.status, r.out, r.err);
    run_tool(t, "eval --model huang --lobes R --quality reference", "0.3,0,-0.35,0.2\n", &r);
    CHECK(t, r.status == 0 && atof(r.out) > 0.0, "huang reference: %d %s %s", r.status, r.out, r.err);
    run_tool(t, "eval --term longitudinal --isa avx9", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--isa"), "unknown isa: %d %s", r.status, r.err);
    /* the near-field model reads h in a fifth column (header included); |h| > 1 is an invalid sample */
    run_tool(t, "eval --model chiang", "theta_i,phi_i,theta_o,phi_o,h\n0.1,0.2,-0.3,0.4,0.5\n0.1,0.2,-0.3,0.4,1.5\n", &r);
    CHECK(t, r.status == 0 && atof(r.out) > 0.0 && strstr(r.out, "\n0,0,0\n") && strstr(r.err, "1 invalid sample"),
          "chiang near field: %d %s %s", r.status, r.out, r.err);
    run_tool(t, "eval --model chiang", "0.1,0.2,-0.3,0.4\n", &r);
    CHECK(t, r.status == 1 && strstr(r.err, "phi_o,h"), "chiang without h: %d %s", r.status, r.err);
    run_tool(t, "eval --model chiang --far", "0.1,0.2,-0.3,0.4\n", &r);
    CHECK(t, r.status == 0 && atof(r.out) > 0.0, "chiang far field: %d %s %s", r.status, r.out, r.err);
    /* a header decides: dFH11 at h where it names h, its far field where it does not or without one */
    hb_tool_run near, far, plain;
    run_tool(t, "eval --model deon", "theta_i,phi_i,theta_o,phi_o,h\n0.1,0.2,-0.3,0.4,0.5\n", &near);
    run_tool(t, "eval --model deon", "theta_i,phi_i,theta_o,phi_o\n0.1,0.2,-0.3,0.4\n", &far);
    run_tool(t, "eval --model deon", "0.1,0.2,-0.3,0.4\n", &plain);
    CHECK(t, near.status == 0 && far.status == 0 && plain.status == 0 && strcmp(far.out, plain.out) == 0 &&
                 strcmp(near.out, far.out) != 0 && atof(near.out) > 0.0,
          "deon near '%s' (%s), far '%s', plain '%s'", near.out, near.err, far.out, plain.out);
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    hb_plan *plan = NULL;
    float ti = 0.1f, pi = 0.2f, to = -0.3f, po = 0.4f, h = 0.5f, f[3];
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK &&
                 hb_eval_near(plan, 1, (hb_near_soa){ &ti, &pi, &to, &po, &h }, (hb_rgb_soa){ f, f + 1, f + 2 }, NULL) ==
                     HB_OK && fabs(atof(near.out) / f[0] - 1.0) < 1e-6,
          "deon near through the tool %s, the library %.9g", near.out, f[0]);
    hb_plan_destroy(plan);
    run_tool(t, "sample --model deon --theta-o 0.3 --h 0.5 --count 4", "", &r);
    CHECK(t, r.status == 0 && strchr(r.out, ','), "deon sample --h: %d %s %s", r.status, r.out, r.err);
}

/* Inputs an attacker or a slip of the hand gives: a table "file" that is a directory or a device,
 * a bake for a model without tables, limits just missed, and output that cannot be written. */
static void test_hostile_inputs(hb_test_ctx *t)
{
    hb_tool_run r;
    char args[640];
    snprintf(args, sizeof args, "eval --table \"%s\"", hb_test_temp_dir());
    run_tool(t, args, "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "not a regular file"), "a directory as the table: %d %s", r.status, r.err);
#ifndef _WIN32
    run_tool(t, "eval --table /dev/zero", "", &r); /* read whole, it would grow without end */
    CHECK(t, r.status == 2 && strstr(r.err, "not a regular file"), "/dev/zero as the table: %d %s", r.status, r.err);
#endif
    run_tool(t, "bake --model chiang -o x.hbt", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "the chiang model has no tables"), "bake chiang: %d %s", r.status, r.err);
    run_tool(t, "eval --model chiang --beta-m 1.0000001", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "beta_m = 1.0000001 must be in [0.0027464, 1] for the chiang model"),
          "a limit just missed: %s", r.err);
    run_tool(t, "eval --beta-m 0.00099999998", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "beta_m = 0.00099999998 must be in [0.001, "), "the lower limit: %s", r.err);
    run_tool(t, "eval --model chiang --beta-n 0.01", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "beta_n = 0.01 must be in [0.02, 1] for the chiang model"),
          "CBTB16's beta_n range: %s", r.err);
#ifndef _WIN32
    /* a full device: every command says so and fails (the shell redirects, so the emulator prefix works) */
    const char *tool = hb_test_tool(t);
    char err_path[600];
    if (!tool || access("/dev/full", W_OK) != 0 || hb_test_temp_file(err_path, sizeof err_path, ".err") != 0)
        return;
    static const char *const commands[] = { "plan", "isa", "sample --theta-o 0.3 --count 4", "version" };
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; k++) {
        char command[1400], err[512];
        snprintf(command, sizeof command, "%s %s > /dev/full 2> \"%s\" < /dev/null", tool, commands[k], err_path);
        int status = system(command);
        hb_test_read_text(err_path, err, sizeof err);
        CHECK(t, status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 1 && strstr(err, "cannot write"),
              "%s > /dev/full: status %d, stderr '%s'", commands[k], status, err);
    }
    remove(err_path);
#endif
}

static void test_help(hb_test_ctx *t)
{
    hb_tool_run r;
    if (!run_tool(t, "--help", "", &r))
        return;
    CHECK(t, r.status == 0 && strstr(r.out, "eval") && strstr(r.out, "isa") && strstr(r.out, "--beta-m"),
          "--help lists subcommands and options: %s", r.out);
    run_tool(t, "frobnicate", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "frobnicate"), "unknown command");
    run_tool(t, "isa", "", &r);
    CHECK(t, r.status == 0 && strstr(r.out, "scalar") && strstr(r.out, "(auto)"), "isa listing: %s", r.out);
}

/* The full dFH11 model's options reach the library, and furnace prints energies. */
static void test_deon_commands(hb_test_ctx *t)
{
    hb_tool_run r;
    if (!run_tool(t, "eval --pmax 5 --lobes R,TT,4,residual --absorption paper --r-fresnel half-angle --quadrature 40 "
                     "--detector-tolerance 1e-6 --sigma-a 0.1,0.2,0.3",
                  "0.3,0,-0.37,0.5\n", &r))
        return;
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.sigma_a[0] = 0.1, m.sigma_a[1] = 0.2, m.sigma_a[2] = 0.3;
    o.pmax = 5;
    o.lobes = 1u << 0 | 1u << 1 | 1u << 4 | 1u << HB_LOBE_RESIDUAL;
    o.absorption = HB_ABSORPTION_PAPER;
    o.r_fresnel = HB_R_FRESNEL_HALF_ANGLE;
    o.quadrature_order = 40;
    o.detector_tolerance = 1e-6;
    hb_plan *plan;
    hb_plan_create(&m, &o, &plan, NULL);
    float ti = 0.3f, pi = 0.0f, to = -0.37f, po = 0.5f, f[3], got[3];
    hb_eval_angles(plan, 1, (hb_angles_soa){ &ti, &pi, &to, &po }, (hb_rgb_soa){ &f[0], &f[1], &f[2] }, NULL);
    hb_plan_destroy(plan);
    CHECK(t, r.status == 0 && sscanf(r.out, "%g,%g,%g", &got[0], &got[1], &got[2]) == 3 && got[0] == f[0] &&
                 got[2] == f[2],
          "eval with every dFH11 option: '%s' vs %.9g (stderr %s)", r.out, f[0], r.err);
    run_tool(t, "eval --lobe-beta-m 1=0.2 --lobe-beta-n 2=0.5 --lobe-alpha 0=-0.05 --quality reference",
             "0.3,0,-0.2,2.5\n", &r);
    hb_material_default(&m);
    hb_options_default(&o);
    m.lobe_beta_m[1] = 0.2, m.lobe_beta_n[2] = 0.5, m.lobe_alpha[0] = -0.05, m.lobe_alpha_override = 1u;
    o.quality = HB_QUALITY_REFERENCE;
    hb_plan_create(&m, &o, &plan, NULL);
    to = -0.2f, po = 2.5f;
    hb_eval_angles(plan, 1, (hb_angles_soa){ &ti, &pi, &to, &po }, (hb_rgb_soa){ &f[0], &f[1], &f[2] }, NULL);
    hb_plan_destroy(plan);
    CHECK(t, r.status == 0 && sscanf(r.out, "%g,%g,%g", &got[0], &got[1], &got[2]) == 3 && got[0] == f[0],
          "per-lobe overrides: '%s' vs %.9g (stderr %s)", r.out, f[0], r.err);
    run_tool(t, "eval --lobe-alpha 9=0.1", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--lobe-alpha"), "bad lobe order: %s", r.err);
    run_tool(t, "eval --pmax 2 --lobes TRRT", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "pmax"), "lobe above pmax: %s", r.err);
    run_tool(t, "furnace --alpha 0 --theta-o 0.3,-1.2", "", &r);
    double theta, e[3];
    CHECK(t, r.status == 0 && sscanf(strchr(r.out, '\n') + 1, "%lf,%lf,%lf,%lf", &theta, &e[0], &e[1], &e[2]) == 4 &&
                 fabs(e[0] - 1.0) < 1e-3,
          "furnace output: %s", r.out);
}

/* hairbsdf eval --model marschner with every option it has, against the library, and the
 * double reference by --quality reference; the full-model furnace runs. */
static void test_marschner_commands(hb_test_ctx *t)
{
    hb_tool_run r;
    if (!run_tool(t, "eval --model marschner --lobes R,TT,TRT --eta 1.6 --sigma-a 0.2,0.3,0.5 --beta-m 0.12 "
                     "--alpha 0.05 --eccentricity 0.4 --glint-scale 2 --caustic-width 0.2 --caustic-fade 0.25 "
                     "--caustic-limit 0.4 --absorption paper --lobe-beta-m 2=0.3 --lobe-alpha 1=0.02",
                  "0.3,0.2,-0.37,0.5\n", &r))
        return;
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eta = 1.6, m.beta_m = 0.12, m.alpha = 0.05, m.eccentricity = 0.4;
    m.sigma_a[0] = 0.2, m.sigma_a[1] = 0.3, m.sigma_a[2] = 0.5;
    m.glint_scale = 2, m.caustic_width = 0.2, m.caustic_fade = 0.25, m.caustic_limit = 0.4;
    m.lobe_beta_m[2] = 0.3, m.lobe_alpha[1] = 0.02, m.lobe_alpha_override = 2u;
    o.model = HB_MODEL_MARSCHNER;
    o.lobes = 7u;
    o.absorption = HB_ABSORPTION_PAPER;
    float ti = 0.3f, pi = 0.2f, to = -0.37f, po = 0.5f, f[3], got[3];
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            run_tool(t, "eval --model marschner --quality reference --eccentricity 0.4", "0.3,0.2,-0.37,0.5\n", &r);
            hb_material_default(&m);
            hb_options_default(&o);
            m.eccentricity = 0.4;
            o.model = HB_MODEL_MARSCHNER;
            o.quality = HB_QUALITY_REFERENCE;
        }
        hb_plan *plan = NULL;
        CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "plan");
        if (!plan)
            return;
        hb_eval_angles(plan, 1, (hb_angles_soa){ &ti, &pi, &to, &po }, (hb_rgb_soa){ &f[0], &f[1], &f[2] }, NULL);
        hb_plan_destroy(plan);
        CHECK(t, r.status == 0 && sscanf(r.out, "%g,%g,%g", &got[0], &got[1], &got[2]) == 3 && got[0] == f[0] &&
                     got[2] == f[2] && f[0] > 0.0f,
              "marschner eval pass %d: '%s' vs %.9g (stderr %s)", pass, r.out, f[0], r.err);
    }
    run_tool(t, "eval --model marschner --lobes TRRT", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "marschner"), "marschner TRRT: %s", r.err);
    run_tool(t, "eval --model marschner --caustic-width 0", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "caustic_width"), "caustic width 0: %s", r.err);
    run_tool(t, "furnace --model marschner --theta-o 0.3", "", &r);
    double theta, e[3];
    CHECK(t, r.status == 0 && sscanf(strchr(r.out, '\n') + 1, "%lf,%lf,%lf,%lf", &theta, &e[0], &e[1], &e[2]) == 4 &&
                 e[0] > 1.5 && e[0] < 2.5,
          "marschner furnace: %s", r.out);
    /* HHH22 Fig. 16: energy by order, the share beyond TRT falling from blond to black */
    run_tool(t, "furnace --fig16 --theta-o 0 --paths 2000 --tt-trt mc", "", &r);
    double share[4] = { -1.0, -1.0, -1.0, -1.0 };
    const char *line = r.out;
    for (int k = 0; k < 4 && line && (line = strchr(line, '\n')); k++) {
        char name[16];
        double th, er, ett, etrt, eb, se;
        if (sscanf(++line, "%15[a-z],%lf,%lf,%lf,%lf,%lf,%lf,%lf", name, &th, &er, &ett, &etrt, &eb, &se, &share[k]) != 8)
            share[k] = -1.0;
    }
    CHECK(t, r.status == 0 && share[0] > share[1] && share[1] > share[2] && share[2] > share[3] && share[3] >= 0.0,
          "furnace --fig16: %s", r.out);
    run_tool(t, "furnace --model huang --eccentricity 0.5 --orders --theta-o 0", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "circular"), "elliptical --orders: %s", r.err);
}

/* hairbsdf sample and pdf: rows that are the library's samples, a summary whose mean weight is
 * the white-furnace energy, a pdf column that matches the sampled pdf, and refusals. */
/* `hairbsdf sample <args> --theta-o 0.5 --phi-o 0.2 --count 3 --seed 9` prints the library's samples
 * for the plan (m, o), and `hairbsdf pdf <args>` the pdf of one of them. */
static void check_sample_rows(hb_test_ctx *t, const char *args, const hb_material *m, const hb_options *o)
{
    hb_tool_run r;
    char command[256];
    snprintf(command, sizeof command, "sample %s --theta-o 0.5 --phi-o 0.2 --count 3 --seed 9", args);
    if (!run_tool(t, command, "", &r))
        return;
    CHECK(t, r.status == 0, "'%s' exit %d: %s", command, r.status, r.err);
    hb_plan *plan = NULL;
    CHECK(t, hb_plan_create(m, o, &plan, NULL) == HB_OK, "plan");
    if (!plan)
        return;
    float to[3] = { 0.5f, 0.5f, 0.5f }, po[3] = { 0.2f, 0.2f, 0.2f }, u[5][3], ti[3], pi[3], pdf[3], w[3][3];
    float *streams[5] = { u[0], u[1], u[2], u[3], u[4] };
    hb_uniforms(9, 0, 3, hb_plan_sample_dimensions(plan), streams);
    hb_sample_angles(plan, 3, &(hb_sample_in){ to, po, (const float *const[]){ u[0], u[1], u[2], u[3], u[4] } },
                     &(hb_sample_out){ ti, pi, pdf, { w[0], w[1], w[2] } }, NULL);
    char want[1024] = "theta_i,phi_i,pdf,w_r,w_g,w_b\n", row[256];
    for (int k = 0; k < 3; k++) {
        snprintf(row, sizeof row, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", ti[k], pi[k], pdf[k], w[0][k], w[1][k], w[2][k]);
        strcat(want, row);
    }
    CHECK(t, strcmp(r.out, want) == 0, "'%s' printed\n%s\nwant\n%s", command, r.out, want);
    char input[128];
    snprintf(input, sizeof input, "theta_i,phi_i,theta_o,phi_o\n%.9g,%.9g,0.5,0.2\n", ti[1], pi[1]);
    snprintf(command, sizeof command, "pdf %s", args);
    if (run_tool(t, command, input, &r))
        CHECK(t, r.status == 0 && fabs(atof(r.out) - pdf[1]) <= 1e-6 * pdf[1], "'%s' printed '%s', sampled %.9g (%s)",
              command, r.out, pdf[1], r.err);
    hb_plan_destroy(plan);
}

static void test_sample_commands(hb_test_ctx *t)
{
    hb_tool_run r;
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.beta_m = 0.2;
    check_sample_rows(t, "--beta-m 0.2", &m, &o);
    hb_material_default(&m);
    m.ndf = HB_NDF_BECKMANN;
    m.roughness = 0.2;
    m.eccentricity = 0.5;
    o.model = HB_MODEL_HUANG;
    o.lobes = 1u << HB_LOBE_R;
    check_sample_rows(t, "--model huang --lobes R --ndf beckmann --roughness 0.2 --eccentricity 0.5", &m, &o);
    hb_material_default(&m);
    hb_options_default(&o);
    hb_plan *plan = NULL;

    if (!run_tool(t, "sample --theta-o -0.7 --count 20000 --summary --sigma-a 0.3,0.6,1.2", "", &r))
        return;
    double mean[3], se[3], e[3];
    unsigned long long count = 0;
    const char *line = strchr(r.out, '\n');
    CHECK(t, line && sscanf(line + 1, "%llu,%lf,%lf,%lf,%lf,%lf,%lf", &count, &mean[0], &mean[1], &mean[2], &se[0], &se[1],
                            &se[2]) == 7, "summary '%s'", r.out);
    m.beta_m = 0.1;
    m.sigma_a[0] = 0.3, m.sigma_a[1] = 0.6, m.sigma_a[2] = 1.2;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "plan");
    hb_furnace(plan, -0.7, e);
    hb_plan_destroy(plan);
    for (int c = 0; c < 3; c++)
        CHECK(t, count == 20000 && fabs(mean[c] - e[c]) <= 4.0 * se[c] + 1e-4, "channel %d: mean weight %.5f +- %.1e, E %.5f",
              c, mean[c], se[c], e[c]);

    /* CBTB16 at one offset: a lossless fibre's weights are its albedo, 1, each (docs/chiang.md) */
    if (!run_tool(t, "sample --model chiang --theta-o 0.3 --h 0.5 --count 4096 --summary", "", &r))
        return;
    line = strchr(r.out, '\n');
    CHECK(t, line && sscanf(line + 1, "%llu,%lf,%lf,%lf,%lf,%lf,%lf", &count, &mean[0], &mean[1], &mean[2], &se[0], &se[1],
                            &se[2]) == 7 && count == 4096 && fabs(mean[0] - 1.0) <= 1e-3 && se[0] <= 1e-3,
          "chiang at h 0.5: '%s'", r.out);

    static const char *const refused[] = { "sample --model marschner --quality reference --theta-o 0.1", "sample --count 10",
                                           "sample --theta-o 2", "sample --theta-o 0.1 --count 0",
                                           "sample --theta-o 0.1 --seed -3", "pdf --model marschner --quality reference",
                                           "sample --model huang --theta-o 0.1 --h 0.5", "sample --model chiang --theta-o 0.1 --h 2" };
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        if (!run_tool(t, refused[k], "0,0,0,0\n", &r))
            return;
        CHECK(t, r.status == 2 && r.err[0], "'%s': exit %d, stderr '%s'", refused[k], r.status, r.err);
    }
}

/* Counts the occurrences of needle in haystack. */
static int count_of(const char *haystack, const char *needle)
{
    int n = 0;
    for (const char *p = strstr(haystack, needle); p; p = strstr(p + 1, needle))
        n++;
    return n;
}

/* The points of the k-th polyline of an SVG: returns their count, up to max. */
static int polyline_points(const char *svg, int k, double *x, double *y, int max)
{
    const char *p = svg;
    for (int j = 0; j <= k && p; j++)
        p = strstr(p + (j > 0), "<polyline");
    p = p ? strstr(p, "points='") : NULL;
    int n = 0;
    for (p = p ? p + 8 : NULL; p && *p != '\'' && n < max; n++) {
        char *end;
        x[n] = strtod(p, &end);
        if (end == p || *end != ',')
            break;
        y[n] = strtod(end + 1, &end);
        p = end + (*end == ' ');
    }
    return n;
}

/* hairbsdf plot: a table's series become polylines whose points lie on the data (y = 2x - 1 is a
 * straight line in pixels, one polyline per numeric column and per value of the text column); a
 * bench results file draws each ISA's Pareto front only; furnace --svg plots what it prints. */
static void test_plot_commands(hb_test_ctx *t)
{
    char svg_path[600], args[1024], svg[65536];
    if (hb_test_temp_file(svg_path, sizeof svg_path, ".svg") != 0) {
        CHECK(t, 0, "no temporary file in %s", hb_test_temp_dir());
        return;
    }
    hb_tool_run r;
    snprintf(args, sizeof args, "plot - -o \"%s\" --title lines", svg_path);
    if (!run_tool(t, args, "fibre,x,line,square\na,0,-1,0\na,1,1,1\na,2,3,4\nb,0,5,0\nb,3,5,9\n", &r))
        return;
    hb_test_read_text(svg_path, svg, sizeof svg);
    CHECK(t, r.status == 0 && count_of(svg, "<polyline") == 4 && strstr(svg, "a line") && strstr(svg, "b square"),
          "two columns for two fibres: %d polylines, %s", count_of(svg, "<polyline"), r.err);
    double x[8], y[8];
    int n = polyline_points(svg, 0, x, y, 8);
    CHECK(t, n == 3 && x[1] > x[0] && y[1] < y[0], "series 'a line' has 3 points, rising: %d", n);
    if (n == 3) {
        double slope0 = (y[1] - y[0]) / (x[1] - x[0]), slope1 = (y[2] - y[1]) / (x[2] - x[1]);
        CHECK(t, fabs(slope0 - slope1) < 1e-2 * fabs(slope0), "y = 2x - 1 is straight in pixels: %g vs %g", slope0,
              slope1);
    }
    snprintf(args, sizeof args, "plot - -o \"%s\"", svg_path);
    run_tool(t, args, "configuration,isa,ns_per_sample,max_error\nfast,avx2,10,1e-2\nslow,avx2,20,1e-4\n"
                      "dominated,avx2,30,1e-3\nfast,scalar,80,1e-2\n", &r);
    hb_test_read_text(svg_path, svg, sizeof svg);
    CHECK(t, r.status == 0 && count_of(svg, "<polyline") == 2, "bench file: one front per ISA (%s)", r.err);
    CHECK(t, polyline_points(svg, 0, x, y, 8) == 2, "the dominated configuration is off avx2's front");
    CHECK(t, count_of(svg, "<circle") == 4 + 2, "every configuration is marked, plus a legend dot per ISA");
    run_tool(t, args, "a,b\nx,y\n", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "numeric"), "a table without numbers is refused: %s", r.err);

    snprintf(args, sizeof args, "furnace --model deon --by-lobe --theta-o 0,0.5,1 --svg \"%s\"", svg_path);
    run_tool(t, args, "", &r);
    hb_tool_run plain;
    run_tool(t, "furnace --model deon --by-lobe --theta-o 0,0.5,1", "", &plain);
    hb_test_read_text(svg_path, svg, sizeof svg);
    CHECK(t, r.status == 0 && strcmp(r.out, plain.out) == 0, "--svg prints the same table");
    CHECK(t, count_of(svg, "<polyline") == 7 && count_of(svg, "<circle") == 21,
          "7 columns of 3 rows: %d polylines, %d points", count_of(svg, "<polyline"), count_of(svg, "<circle"));

    snprintf(args, sizeof args, "dual --model deon --quality fast --thetas 3 --svg \"%s\" --plot a_f,A_b", svg_path);
    run_tool(t, args, "", &r);
    run_tool(t, "dual --model deon --quality fast --thetas 3", "", &plain);
    hb_test_read_text(svg_path, svg, sizeof svg);
    CHECK(t, r.status == 0 && strcmp(r.out, plain.out) == 0, "dual --svg prints the same table");
    CHECK(t, count_of(svg, "<polyline") == 6 && strstr(svg, "a_f_g") && strstr(svg, "A_b_b") && strstr(svg, "energy (fraction"),
          "a_f and A_b per channel: %d polylines", count_of(svg, "<polyline"));
    run_tool(t, "dual --svg x.svg --plot a_f,beta", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--plot"), "an unknown term: %d %s", r.status, r.err);
    unlink(svg_path);
}

/* dFH11's default material with eumelanin 0.3, default options; NULL if it is refused. */
static hb_plan *blond_plan(void)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = 0.3;
    hb_plan *plan = NULL;
    hb_plan_create(&m, &o, &plan, NULL);
    return plan;
}

/* eval with an n column (and v) prints f and then the dual-scattering term, as hb_dual_eval gives it
 * from the plan's 64-node table; an invalid v writes zeros; pdf has no such column. */
static void test_eval_dual_columns(hb_test_ctx *t)
{
    hb_tool_run r;
    if (!run_tool(t, "eval --model deon --eumelanin 0.3", "theta_i,phi_i,theta_o,phi_o,n,v\n0.3,0,-0.2,0.4,2,0.25\n"
                                                          "0.3,0,-0.2,2.9,5,0\n0.3,0,-0.2,0.4,2,1.5\n",
                  &r))
        return;
    hb_plan *plan = blond_plan();
    hb_dual_table *table = NULL;
    CHECK(t, plan && hb_dual_table_create(plan, 64, HB_DUAL_DENSITY, HB_DUAL_DENSITY, NULL, NULL, NULL, NULL, &table) == HB_OK,
          "table");
    float ti[2] = { 0.3f, 0.3f }, pi[2] = { 0, 0 }, to[2] = { -0.2f, -0.2f }, po[2] = { 0.4f, 2.9f }, n[2] = { 2, 5 },
          v[2] = { 0.25f, 0 }, f[6][2];
    hb_angles_soa in = { ti, pi, to, po };
    hb_eval_angles(plan, 2, in, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    hb_dual_eval(table, 2, in, n, v, (hb_rgb_soa){ f[3], f[4], f[5] }, NULL);
    char want[512];
    snprintf(want, sizeof want, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n0,0,0,0,0,0\n", f[0][0],
             f[1][0], f[2][0], f[3][0], f[4][0], f[5][0], f[0][1], f[1][1], f[2][1], f[3][1], f[4][1], f[5][1]);
    CHECK(t, r.status == 0 && strcmp(r.out, want) == 0 && strstr(r.err, "1 invalid sample") && f[3][0] > 0.0f,
          "eval with n,v:\n%s%s, the library:\n%s", r.out, r.err, want);
    run_tool(t, "pdf --model deon", "theta_i,phi_i,theta_o,phi_o,n\n0.3,0,-0.2,0.4,1\n", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "use eval"), "pdf with n: %d %s", r.status, r.err);
    hb_dual_table_destroy(table);
    hb_plan_destroy(plan);
}

/* dual --save writes the table eval --dual-table loads: the same f_DS as eval's own 64-node table; a
 * table of another material is refused, naming the field. */
static void test_dual_save(hb_test_ctx *t)
{
    char path[600], args[1024];
    hb_tool_run r, own;
    if (!run_tool_writing(t, ".hbdt", path, sizeof path, "dual --eumelanin 0.3 --save \"%s\"", &r))
        return;
    CHECK(t, r.status == 0 && r.out[0] == '\0', "dual --save: %d %s", r.status, r.err);
    const char *rows = "theta_i,phi_i,theta_o,phi_o,n\n0.3,0,-0.2,0.4,2\n-0.6,1,0.5,2.9,7\n";
    run_tool(t, "eval --eumelanin 0.3", rows, &own);
    snprintf(args, sizeof args, "eval --eumelanin 0.3 --dual-table \"%s\"", path);
    run_tool(t, args, rows, &r);
    CHECK(t, r.status == 0 && own.status == 0 && strcmp(r.out, own.out) == 0, "eval --dual-table:\n%s\nits own:\n%s",
          r.out, own.out);
    snprintf(args, sizeof args, "eval --eumelanin 1.3 --dual-table \"%s\"", path);
    run_tool(t, args, rows, &r);
    CHECK(t, r.status == 2 && strstr(r.err, "eumelanin"), "another material: %d %s", r.status, r.err);
    unlink(path);
}

/* dual --engine --save writes the engine-wide table eval --dual-engine loads: eval's f_DS is that of
 * the library's own engine of the same axes, looked up for the material; without --save the nodes
 * print as CSV; a file of another family and a malformed --sampled are refused. */
static void test_dual_engine_save(hb_test_ctx *t)
{
    char path[600], args[1024];
    hb_tool_run r;
    if (!run_tool_writing(t, ".hbde", path, sizeof path, "dual --engine --thetas 8 --roughnesses 2 --absorptions 3 --save \"%s\"", &r))
        return;
    CHECK(t, r.status == 0 && r.out[0] == '\0', "dual --engine --save: %d %s", r.status, r.err);
    hb_dual_engine_axes axes;
    hb_dual_engine_axes_default(&axes);
    axes.thetas = 8, axes.roughnesses = 2, axes.absorptions = 3;
    hb_dual_engine *engine = hb_test_dual_engine(t, &axes);
    hb_dual_table *table = NULL;
    hb_plan *plan = blond_plan();
    CHECK(t, plan && hb_dual_engine_table(engine, plan, HB_DUAL_DENSITY, &table) == HB_OK, "%s", hb_last_error()->message);
    float ti[2] = { 0.3f, -0.6f }, pi[2] = { 0.0f, 1.0f }, to[2] = { -0.2f, 0.5f }, po[2] = { 0.4f, 2.9f }, n[2] = { 2, 7 };
    float f[3][2] = { { 0 } };
    if (table)
        hb_dual_eval(table, 2, (hb_angles_soa){ ti, pi, to, po }, n, NULL, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    snprintf(args, sizeof args, "eval --eumelanin 0.3 --dual-engine \"%s\"", path);
    run_tool(t, args, "theta_i,phi_i,theta_o,phi_o,n\n0.3,0,-0.2,0.4,2\n-0.6,1,0.5,2.9,7\n", &r);
    const char *row = r.out;
    for (int k = 0; k < 2 && r.status == 0; k++) {
        float x[6] = { 0 };
        CHECK(t, sscanf(row, "%g,%g,%g,%g,%g,%g", &x[0], &x[1], &x[2], &x[3], &x[4], &x[5]) == 6 && x[3] == f[0][k] &&
                     x[4] == f[1][k] && x[5] == f[2][k] && f[1][k] > 0.0f,
              "row %d: %.60s, the library's f_DS %.9g %.9g %.9g", k, row, f[0][k], f[1][k], f[2][k]);
        row = strchr(row, '\n') ? strchr(row, '\n') + 1 : "";
    }
    CHECK(t, r.status == 0, "eval --dual-engine: %d %s", r.status, r.err);
    snprintf(args, sizeof args, "eval --eumelanin 0.3 --eta 1.5 --dual-engine \"%s\"", path);
    run_tool(t, args, "theta_i,phi_i,theta_o,phi_o,n\n0.3,0,-0.2,0.4,2\n", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "eta"), "another family: %d %s", r.status, r.err);
    run_tool(t, "dual --engine --thetas 2 --roughnesses 2 --absorptions 2", "", &r);
    int lines = 0;
    for (const char *c = r.out; *c; c++)
        lines += *c == '\n';
    CHECK(t, r.status == 0 && lines == 9 && strstr(r.out, "roughness,sigma_a,theta,a_f,a_b,alpha_f,beta_f2,alpha_b,beta_b2\n"),
          "dual --engine: %d %s%s", r.status, r.out, r.err);
    hb_dual_engine_axes small = axes;
    small.thetas = 2, small.absorptions = 2;
    hb_dual_engine *two = hb_test_dual_engine(t, &small);
    size_t count = 0;
    const float *nodes = hb_dual_engine_nodes(two, &count);
    char first[64];
    snprintf(first, sizeof first, "\n0.05,0,-0.785398,%.6g,", nodes ? nodes[0] : 0.0f);
    CHECK(t, nodes && strstr(r.out, first), "the first node: want '%s' in %s", first + 1, r.out);
    run_tool(t, "dual --engine --sampled 128,x", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--sampled"), "--sampled 128,x: %d %s", r.status, r.err);
    hb_dual_engine_destroy(two);
    hb_dual_table_destroy(table);
    hb_plan_destroy(plan);
    hb_dual_engine_destroy(engine);
    unlink(path);
}

/* eval --wavelengths prints f at each wavelength as hb_eval_near_spectral gives it at the material's
 * melanin absorption there (the far field without h), with --colour at its absorption spectrum, and
 * refuses sigma_a, HHH22 (no spectral call) and a malformed list. */
static void test_eval_wavelengths(hb_test_ctx *t)
{
    hb_tool_run r;
    if (!run_tool(t, "eval --model chiang --eumelanin 1.3 --pheomelanin 0.2 --wavelengths 450,550,650,700",
                  "0.3,0,-0.35,2.9,0.2\n0.1,0.5,0.2,-1,2\n", &r))
        return;
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = HB_MODEL_CHIANG;
    m.eumelanin = 1.3, m.pheomelanin = 0.2;
    hb_plan *plan = NULL;
    hb_plan_create(&m, &o, &plan, NULL);
    static const double lambda[4] = { 450.0, 550.0, 650.0, 700.0 };
    float sigma[4][2], f[4][2], ti[2] = { 0.3f, 0.1f }, pi[2] = { 0.0f, 0.5f }, to[2] = { -0.35f, 0.2f },
          po[2] = { 2.9f, -1.0f }, h[2] = { 0.2f, 2.0f };
    for (int j = 0; j < 4; j++) {
        double s;
        hb_melanin_absorption_spectral(1.3, 0.2, lambda[j], &s);
        sigma[j][0] = sigma[j][1] = (float)s;
    }
    hb_eval_near_spectral(plan, 2, (hb_near_soa){ ti, pi, to, po, h },
                          (hb_spectral_absorption){ 4, (const float *const[]){ sigma[0], sigma[1], sigma[2], sigma[3] } },
                          (float *const[]){ f[0], f[1], f[2], f[3] }, NULL);
    char want[256];
    snprintf(want, sizeof want, "%.9g,%.9g,%.9g,%.9g\n0,0,0,0\n", f[0][0], f[1][0], f[2][0], f[3][0]);
    CHECK(t, r.status == 0 && strcmp(r.out, want) == 0 && strstr(r.err, "1 invalid sample") && f[0][0] > 0.0f,
          "eval --wavelengths:\n%s%s, the library:\n%s", r.out, r.err, want);
    /* --colour: the colour's absorption spectrum at each wavelength */
    if (!run_tool(t, "eval --model chiang --colour 0.2,0.35,0.5 --wavelengths 450,650", "0.3,0,-0.35,2.9,0.2\n", &r))
        return;
    hb_absorption_spectrum spectrum;
    hb_absorption_from_colour_spectral((double[3]){ 0.2, 0.35, 0.5 }, m.beta_n, &spectrum, NULL);
    for (int j = 0; j < 2; j++) {
        double s;
        hb_absorption_spectrum_at(&spectrum, j ? 650.0 : 450.0, &s);
        sigma[j][0] = (float)s;
    }
    hb_eval_near_spectral(plan, 1, (hb_near_soa){ ti, pi, to, po, h },
                          (hb_spectral_absorption){ 2, (const float *const[]){ sigma[0], sigma[1] } },
                          (float *const[]){ f[0], f[1] }, NULL);
    snprintf(want, sizeof want, "%.9g,%.9g\n", f[0][0], f[1][0]);
    CHECK(t, r.status == 0 && strcmp(r.out, want) == 0 && f[0][0] != f[1][0],
          "eval --colour --wavelengths:\n%s%s, the library:\n%s", r.out, r.err, want);
    hb_plan_destroy(plan);
    run_tool(t, "eval --model chiang --sigma-a 0.1,0.2,0.3 --wavelengths 500", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "no spectrum"), "sigma_a: %d %s", r.status, r.err);
    run_tool(t, "eval --model huang --wavelengths 500", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "spectral"), "huang: %d %s", r.status, r.err);
    run_tool(t, "eval --model chiang --wavelengths 500,x", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--wavelengths"), "a malformed list: %d %s", r.status, r.err);
    run_tool(t, "eval --model chiang --wavelengths 1200", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--wavelengths"), "1200 nm: %d %s", r.status, r.err);
}

/* hairbsdf assembly --dual prints dual scattering's prediction beside the trace, and refuses density
 * factors outside [0, 1] and the bundle. */
static void test_assembly_dual(hb_test_ctx *t)
{
    hb_tool_run r;
    if (!run_tool(t, "assembly --eumelanin 0.3 --layers 2 --paths 2000 --bins 6,12 --dual 0.7,0.7 --radiance", "", &r))
        return;
    CHECK(t, r.status == 0 && strstr(r.out, "\ndual_reflected,") && strstr(r.out, "\nsingle_transmitted,") &&
             strstr(r.out, ",dual_r,dual_g,dual_b,single_r,single_g,single_b\n"),
          "--dual: %d %s", r.status, r.err);
    run_tool(t, "assembly --paths 100 --dual 1.5,0.7", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--dual"), "d_f 1.5: %d %s", r.status, r.err);
    run_tool(t, "assembly --paths 100 --shape bundle --dual 0.7,0.7", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "slab"), "a bundle: %d %s", r.status, r.err);
}

/* hairbsdf tress writes the labelled PNG of the two pictures and prints their sums; it needs -o. */
static void test_tress(hb_test_ctx *t)
{
    char path[600];
    hb_tool_run r;
    if (!run_tool_writing(t, ".png", path, sizeof path,
                          "tress --eumelanin 0.3 --layers 2 --paths 2000 --rays 4 --rows 6 --columns 8 -o \"%s\"", &r))
        return;
    CHECK(t, r.status == 0 && strstr(r.out, "\ntraced,") && strstr(r.out, "\ndual,"), "tress: %d %s", r.status, r.err);
    FILE *f = fopen(path, "rb");
    unsigned char head[8] = { 0 };
    CHECK(t, f && fread(head, 1, 8, f) == 8 && memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0, "tress -o wrote no PNG");
    if (f)
        fclose(f);
    unlink(path);
    run_tool(t, "tress --paths 100", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "-o FILE.png"), "without -o: %d %s", r.status, r.err);
}

/* hairbsdf plan describes the plan of the same options eval would use; --tolerance and --budget-ns reach
 * the library through every command. */
static void test_plan_commands(hb_test_ctx *t)
{
    hb_tool_run r;
    if (!run_tool(t, "plan --eumelanin 8 --tolerance 1e-2", "", &r))
        return;
    CHECK(t, r.status == 0 && strstr(r.out, "lobes: R\n") && strstr(r.out, "TT: largest value") &&
             strstr(r.out, "expected error"), "plan for black hair at 1e-2: %s%s", r.out, r.err);
    run_tool(t, "eval --budget-ns 1", "0.3,0,-0.3,0\n", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "fastest"), "a budget nothing meets: %s", r.err);
    run_tool(t, "eval --eumelanin 8 --tolerance 1e-2", "0.3,0,-0.3,0\n", &r);
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = 8.0, o.tolerance = 1e-2;
    hb_plan *plan;
    float ti = 0.3f, pi = 0.0f, to = -0.3f, po = 0.0f, f[3];
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "plan");
    hb_eval_angles(plan, 1, (hb_angles_soa){ &ti, &pi, &to, &po }, (hb_rgb_soa){ &f[0], &f[1], &f[2] }, NULL);
    hb_plan_destroy(plan);
    char expected[128];
    snprintf(expected, sizeof expected, "%.9g,%.9g,%.9g\n", f[0], f[1], f[2]);
    CHECK(t, r.status == 0 && strcmp(r.out, expected) == 0, "eval --tolerance: %s vs %s", r.out, expected);
    run_tool(t, "plan --tolerance 1e-2 --budget-ns 50", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "exclude"), "tolerance and budget together: %s", r.err);
}

/* What a careless input file or a typo must get: a byte-order mark and a spaced header are read,
 * anything else on the first line that is not the header, and a row with a NUL byte, are errors that
 * say so; options out of their range are refused with the option and its range named. */
static void test_input_edges(hb_test_ctx *t)
{
    hb_tool_run r;
    if (!run_tool(t, "eval --term longitudinal", "\xef\xbb\xbftheta_i,phi_i,theta_o,phi_o\n0.1,0,0.2,0\n", &r))
        return;
    CHECK(t, r.status == 0 && strchr(r.out, '\n') == strrchr(r.out, '\n'), "header after a byte-order mark: %d '%s' %s",
          r.status, r.out, r.err);
    run_tool(t, "eval --term longitudinal", " theta_i , phi_i,theta_o,phi_o\n0.1,0,0.2,0\n", &r);
    CHECK(t, r.status == 0, "spaced header refused: %s", r.err);
    run_tool(t, "eval --term longitudinal", "theta_x,phi_i,theta_o,phi_o\n0.1,0,0.2,0\n", &r);
    CHECK(t, r.status != 0 && strstr(r.err, "line 1"), "a first line that is not the header: %d %s", r.status, r.err);
    static const char nul_row[] = "0.1,0,0.2,0\n0.1,0,0.2,0\0junk\n";
    hb_test_run_tool(t, "eval --term longitudinal", nul_row, sizeof nul_row - 1, &r);
    CHECK(t, r.status != 0 && strstr(r.err, "line 2") && strstr(r.err, "NUL"), "a row with a NUL byte: %d %s", r.status,
          r.err);
    run_tool(t, "sample --theta-o 0.3 --count 2 --seed 18446744073709551616", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--seed"), "a seed past 2^64: %d %s", r.status, r.err);
    run_tool(t, "eval --model huang --seed 99999999999999999999", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--seed"), "a model seed past 2^64: %d %s", r.status, r.err);
    run_tool(t, "eval --eta 1e-320", "", &r);
    CHECK(t, r.status != 0 && strstr(r.err, "eta") && !strstr(r.err, "finite"), "a subnormal eta: %d %s", r.status, r.err);
    run_tool(t, "furnace --theta-o 2", "", &r);
    CHECK(t, r.status != 0 && strstr(r.err, "--theta-o 2"), "furnace at theta_o 2: %d %s", r.status, r.err);
    run_tool(t, "furnace --theta-o \"\"", "", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--theta-o"), "furnace with an empty angle list: %d %s", r.status, r.err);
    run_tool(t, "--version", "", &r);
    CHECK(t, r.status == 0 && strncmp(r.out, "hairbsdf ", 9) == 0, "--version: %d '%s'", r.status, r.out);
#ifndef _WIN32 /* a device that is always full */
    run_tool(t, "eval --term longitudinal -o /dev/full", "0.1,0,0.2,0\n", &r);
    CHECK(t, r.status == 1 && strstr(r.err, "cannot write") && strstr(r.err, "space"), "a failed write: %d %s", r.status,
          r.err);
#endif
    run_tool(t, "eval --term longitudinal", "0.1,0,0.2,0\nnan,0,0,0\n0.1,0,0.2,0\n", &r);
    CHECK(t, r.status == 0 && strstr(r.err, "line 2"), "the first invalid sample's line: %d %s", r.status, r.err);
    run_tool(t, "eval --term longitudinal --strict", "0.1,0,0.2,0\n0.1,0,3,0\n0.1,0,0.2,0\n", &r);
    CHECK(t, r.status == 1 && strstr(r.err, "line 2") && strchr(r.out, '\n') == strrchr(r.out, '\n'),
          "--strict stops at an invalid sample: %d '%s' %s", r.status, r.out, r.err);
    run_tool(t, "eval --term longitudinal /nonexistent/rows.csv", "", &r);
    CHECK(t, r.status == 1 && strstr(r.err, "/nonexistent/rows.csv") && strstr(r.err, "No such file"),
          "a missing input file: %d %s", r.status, r.err);
    static const char *const dumps[] = { "--theta-i nan", "--theta-i 2", "--exposure 1e39", "--exposure 0" };
    for (size_t k = 0; k < sizeof dumps / sizeof dumps[0]; k++) {
        char args[128];
        snprintf(args, sizeof args, "dump %s -o /dev/null.pfm", dumps[k]);
        run_tool(t, args, "", &r);
        CHECK(t, r.status == 2 && strstr(r.err, dumps[k][2] == 't' ? "--theta-i" : "--exposure"), "dump %s: %d %s",
              dumps[k], r.status, r.err);
    }
}

/* --colour and --melanin-colour give the material hb_absorption_from_colour and
 * hb_melanin_from_colour give (CBTB16's beta_n for chiang; for deon the b of the same azimuthal
 * standard deviation, 0.3 radians -> about 0.375): the same f as the resolved numbers, bit for bit. */
static void test_colour_options(hb_test_ctx *t)
{
    const char *input = "theta_i,phi_i,theta_o,phi_o\n0.3,0,-0.3,2.5\n-0.2,1,0.4,0.3\n";
    const double colour[3] = { 0.3, 0.18, 0.1 };
    static const struct { const char *model; double b_fit; int melanin; } cases[] = {
        { "chiang", 0.3, 0 }, { "deon", -1.0, 0 }, { "deon", -1.0, 1 } };
    for (int k = 0; k < 3; k++) {
        double b = cases[k].b_fit;
        if (b < 0.0) { /* the b whose logistic's standard deviation is 0.3 */
            double lo = 0.0, hi = 1.0;
            for (int i = 0; i < 60; i++) {
                double mid = 0.5 * (lo + hi);
                double s = sqrt(M_PI / 8.0) * (0.265 * mid + 1.194 * mid * mid + 5.372 * pow(mid, 22));
                *(s * M_PI / sqrt(3.0) < 0.3 ? &lo : &hi) = mid;
            }
            b = 0.5 * (lo + hi);
            CHECK(t, fabs(b - 0.375) < 0.01, "deon beta_n 0.3 maps to CBTB16's %g", b);
        }
        char resolved[160], args[256], near[64] = "";
        if (strcmp(cases[k].model, "chiang") == 0)
            snprintf(near, sizeof near, " --far");
        if (cases[k].melanin) {
            double eu, pheo;
            CHECK(t, hb_melanin_from_colour(colour, b, &eu, &pheo, NULL) == HB_OK, "melanin");
            snprintf(resolved, sizeof resolved, "--eumelanin %.17g --pheomelanin %.17g", eu, pheo);
        } else {
            double sigma[3];
            CHECK(t, hb_absorption_from_colour(colour, b, sigma, NULL) == HB_OK, "sigma_a");
            snprintf(resolved, sizeof resolved, "--sigma-a %.17g,%.17g,%.17g", sigma[0], sigma[1], sigma[2]);
        }
        hb_tool_run from_colour, from_numbers;
        snprintf(args, sizeof args, "eval --model %s%s --beta-n 0.3 --%scolour 0.3,0.18,0.1", cases[k].model, near,
                 cases[k].melanin ? "melanin-" : "");
        if (!run_tool(t, args, input, &from_colour))
            return;
        snprintf(args, sizeof args, "eval --model %s%s --beta-n 0.3 %s", cases[k].model, near, resolved);
        run_tool(t, args, input, &from_numbers);
        CHECK(t, from_colour.status == 0 && from_numbers.status == 0 && strcmp(from_colour.out, from_numbers.out) == 0,
              "case %d: '%s' (%s) against '%s' (%s)", k, from_colour.out, from_colour.err, from_numbers.out,
              from_numbers.err);
    }
    hb_tool_run r;
    run_tool(t, "eval --colour 0.3,0,0.1", input, &r);
    CHECK(t, r.status == 2 && strstr(r.err, "rgb.g = 0"), "a zero channel: %d '%s'", r.status, r.err);
    run_tool(t, "eval --colour 0.3,0.2", input, &r);
    CHECK(t, r.status == 2 && strstr(r.err, "--colour"), "two numbers: %d '%s'", r.status, r.err);
}

/* Per-sample absorption columns: each row of a melanin or sigma_a header gives what a run with that
 * material gives (the concentrations rounded to float once on the way: within 1e-6), a bad absorption
 * is an invalid sample, and models without the path say so. */
static void test_absorption_columns(hb_test_ctx *t)
{
    static const char *const models[] = { "--model deon", "--model marschner" };
    static const double melanin[3][2] = { { 0.0, 0.0 }, { 1.3, 0.4 }, { 8.0, 4.0 } };
    for (int mi = 0; mi < 2; mi++) {
        char input[512] = "theta_i,phi_i,theta_o,phi_o,eumelanin,pheomelanin\n", args[256];
        for (int k = 0; k < 3; k++)
            snprintf(input + strlen(input), sizeof input - strlen(input), "0.3,0.1,-0.25,0.6,%g,%g\n", melanin[k][0],
                     melanin[k][1]);
        hb_tool_run rows, one;
        if (!hb_test_tool(t))
            return;
        snprintf(args, sizeof args, "eval %s", models[mi]);
        run_tool(t, args, input, &rows);
        CHECK(t, rows.status == 0, "%s with melanin columns: %d %s", models[mi], rows.status, rows.err);
        const char *line = rows.out;
        for (int k = 0; k < 3 && line; k++) {
            snprintf(args, sizeof args, "eval %s --eumelanin %g --pheomelanin %g", models[mi], melanin[k][0], melanin[k][1]);
            run_tool(t, args, "0.3,0.1,-0.25,0.6\n", &one);
            double a[3], b[3];
            int parsed = sscanf(line, "%lf,%lf,%lf", &a[0], &a[1], &a[2]) == 3 &&
                         sscanf(one.out, "%lf,%lf,%lf", &b[0], &b[1], &b[2]) == 3;
            for (int c = 0; c < 3 && parsed; c++)
                CHECK(t, fabs(a[c] - b[c]) <= 1e-6 * fabs(b[c]) + 1e-12, "%s strand %d channel %d: %.9g per row, %.9g per material",
                      models[mi], k, c, a[c], b[c]);
            CHECK(t, parsed, "%s strand %d: '%s' and '%s'", models[mi], k, line, one.out);
            line = strchr(line, '\n');
            line = line ? line + 1 : NULL;
        }
    }
    hb_tool_run r;
    run_tool(t, "eval --model marschner",
             "theta_i,phi_i,theta_o,phi_o,sigma_a_r,sigma_a_g,sigma_a_b\n0.3,0,-0.3,0.5,0.1,0.2,0.3\n0.3,0,-0.3,0.5,-1,0,0\n", &r);
    CHECK(t, r.status == 0 && atof(r.out) > 0.0 && strstr(r.out, "\n0,0,0\n") && strstr(r.err, "1 invalid sample"),
          "sigma_a columns with a negative one: %d '%s' %s", r.status, r.out, r.err);
    run_tool(t, "eval --model huang", "theta_i,phi_i,theta_o,phi_o,sigma_a_r,sigma_a_g,sigma_a_b\n0.3,0,-0.3,0.5,0.1,0.2,0.3\n", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "absorption columns"), "huang refuses them: %d %s", r.status, r.err);
    run_tool(t, "eval --model marschner", "theta_i,phi_i,theta_o,phi_o,h\n0.3,0,-0.3,0.5,0.1\n", &r);
    CHECK(t, r.status == 2 && strstr(r.err, "near field"), "marschner refuses h: %d %s", r.status, r.err);
}

/* Every command with every model: each runs, or refuses in a message naming the model and why. */
static void test_model_by_command(hb_test_ctx *t)
{
    static const char *const models[] = { "deon", "marschner", "huang", "chiang" };
    static const char *const lobe_columns[] = { "theta_o,R,TT,TRT,TRRT,residual,total", "theta_o,R,TT,TRT,total",
                                                "theta_o,R,TT,TRT,total", "theta_o,R,TT,TRT,residual,total" };
    static const int has_tables[] = { 1, 0, 1, 0 };
    static const char *const rows[] = { "0.3,0,-0.2,1\n", "0.3,0,-0.2,1\n", "0.3,0,-0.2,1\n", "0.3,0,-0.2,1,0.2\n" };
    char dir_image[512], table[512], args[1400];
    if (hb_test_temp_file(dir_image, sizeof dir_image, ".pfm") != 0 || hb_test_temp_file(table, sizeof table, ".hbt") != 0) {
        CHECK(t, 0, "temporary files");
        return;
    }
    static hb_tool_run r;
    for (int m = 0; m < 4; m++) {
        const char *model = models[m];
        static const char *const commands[] = {
            "eval", "pdf", "sample --theta-o 0.5 --count 4", "plan", "furnace --theta-o -1,0.5",
            "furnace --by-lobe --theta-o -1,0.5", "dual --thetas 2", "dual --thetas 2 --by-lobe",
            "assembly --transport sampler --layers 2 --paths 600 --bins 2,4 --depth-bins 2 --radiance --depth",
        };
        for (size_t c = 0; c < sizeof commands / sizeof commands[0]; c++) {
            snprintf(args, sizeof args, "%s --model %s --quality fast", commands[c], model);
            int reads = c < 2; /* eval and pdf read rows; CBTB16's with their offset h */
            if (!hb_test_run_tool(t, args, reads ? rows[m] : NULL, reads ? strlen(rows[m]) : 0, &r))
                return;
            CHECK(t, r.status == 0 && r.out[0] && !r.err[0], "%s: exit %d, stdout '%.80s', stderr '%s'", args, r.status,
                  r.out, r.err);
            if (strstr(commands[c], "furnace --by-lobe"))
                CHECK(t, strncmp(r.out, lobe_columns[m], strlen(lobe_columns[m])) == 0, "%s: header '%.80s', expected '%s'",
                      args, r.out, lobe_columns[m]);
            if (strstr(commands[c], "assembly"))
                CHECK(t, strstr(r.out, "\nreflected,") && strstr(r.out, "\nreflected_order_8+,") &&
                             strstr(r.out, "\nside,theta_lo,") && strstr(r.out, "\n1,3+,"),
                      "%s: '%.300s'", args, r.out);
            if (strstr(commands[c], "dual --thetas 2 --by-lobe"))
                CHECK(t, strstr(r.out, ",a_f_TT_r,") && strstr(r.out, ",a_b_R_b,"), "%s: header '%.300s'", args, r.out);
        }
        snprintf(args, sizeof args, "dump --model %s --quality fast --theta-i 0.3 --phi-i 0 --width 16 --height 8 -o \"%s\"",
                 model, dir_image);
        if (!hb_test_run_tool(t, args, NULL, 0, &r))
            return;
        CHECK(t, r.status == 0, "%s: exit %d, stderr '%s'", args, r.status, r.err);
        snprintf(args, sizeof args, "bake --model %s --quality fast -o \"%s\"", model, table);
        if (!hb_test_run_tool(t, args, NULL, 0, &r))
            return;
        if (has_tables[m])
            CHECK(t, r.status == 0, "%s: exit %d, stderr '%s'", args, r.status, r.err);
        else
            CHECK(t, r.status != 0 && strstr(r.err, model) && strstr(r.err, "no table"), "%s: exit %d, stderr '%s'", args,
                  r.status, r.err);
    }
    remove(dir_image);
    remove(table);
}

const hb_test hb_tests_cli[] = {
    { "cli_model_by_command", test_model_by_command, 0 },
    { "cli_absorption_columns", test_absorption_columns, 0 },
    { "cli_colour_options", test_colour_options, 0 },
    { "cli_deon_commands", test_deon_commands, 0 },
    { "cli_marschner_commands", test_marschner_commands, 0 },
    { "cli_eval_matches_library", test_eval_matches_library, 0 },
    { "cli_eval_errors", test_eval_errors, 0 },
    { "cli_eval_dual_columns", test_eval_dual_columns, 0 },
    { "cli_eval_wavelengths", test_eval_wavelengths, 0 },
    { "cli_dual_save", test_dual_save, 0 },
    { "cli_dual_engine_save", test_dual_engine_save, 0 },
    { "cli_assembly_dual", test_assembly_dual, 0 },
    { "cli_tress", test_tress, 0 },
    { "cli_input_edges", test_input_edges, 0 },
    { "cli_help", test_help, 0 },
    { "cli_hostile_inputs", test_hostile_inputs, 0 },
    { "cli_sample_commands", test_sample_commands, 0 },
    { "cli_plot_commands", test_plot_commands, 0 },
    { "cli_plan_commands", test_plan_commands, 0 },
    { NULL, NULL, 0 },
};

/* hairbsdf eval: CSV rows theta_i,phi_i,theta_o,phi_o (near-field models: and h; per-sample absorption:
 * and eumelanin,pheomelanin or sigma_a_r,sigma_a_g,sigma_a_b; dual scattering: and n, or n,v) from a
 * file or stdin, f_r,f_g,f_b (and the dual-scattering term after them; with --wavelengths, f at each
 * wavelength instead) to a file or stdout
 * hairbsdf pdf: the same rows, the sampling pdf of w_i given w_o (docs/sampling.md). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "csv.h"

#define BATCH 1024

/* What a row holds after the angles, as its header names it. */
typedef enum row_kind { ROW_ANGLES, ROW_NEAR, ROW_FIBRES, ROW_FIBRES_VISIBLE, ROW_MELANIN, ROW_SIGMA } row_kind;

static const int row_columns[] = { 4, 5, 5, 6, 6, 7 };

static const char *const row_names[][7] = {
    { "theta_i", "phi_i", "theta_o", "phi_o" },
    { "theta_i", "phi_i", "theta_o", "phi_o", "h" },
    { "theta_i", "phi_i", "theta_o", "phi_o", "n" },
    { "theta_i", "phi_i", "theta_o", "phi_o", "n", "v" },
    { "theta_i", "phi_i", "theta_o", "phi_o", "eumelanin", "pheomelanin" },
    { "theta_i", "phi_i", "theta_o", "phi_o", "sigma_a_r", "sigma_a_g", "sigma_a_b" },
};

typedef struct eval_batch {
    float in[7][BATCH]; /* the angles, then h, or n (and v), or sigma_a per channel */
    float out[6][BATCH]; /* f, then f_DS */
    size_t count;
    hb_dual_table *dual; /* for the rows with n: the plan's dual-scattering table */
    /* --wavelengths: their count, the material's absorption at each (every row alike) and f per wavelength */
    int wavelengths;
    float sigma_a[HB_WAVELENGTHS_MAX][BATCH], spectral[HB_WAVELENGTHS_MAX][BATCH];
} eval_batch;

/* Whether a row is a valid sample as hb_eval_angles (hb_dual_eval) defines it (hairbsdf.h): finite
 * angles, |theta| at most the float pi/2, |phi| at most HB_PHI_LIMIT, |h| <= 1 (near field), v in
 * [0, 1], n, absorptions and concentrations finite and >= 0. */
static int row_valid(const float *row, row_kind kind)
{
    for (int c = 0; c < row_columns[kind]; c++) {
        int ok = c < 4                      ? fabsf(row[c]) <= (c % 2 ? HB_PHI_LIMIT : 1.57079637f)
                 : kind == ROW_NEAR         ? fabsf(row[c]) <= 1.0f
                 : c == 5 && kind == ROW_FIBRES_VISIBLE ? row[c] >= 0.0f && row[c] <= 1.0f
                                            : row[c] >= 0.0f && row[c] <= 3.4e38f;
        if (!ok)
            return 0;
    }
    return 1;
}

/* A row's columns into the batch: concentrations become sigma_a (hb_melanin_absorption). */
static void batch_row(eval_batch *b, const float *row, row_kind kind)
{
    for (int c = 0; c < (kind == ROW_MELANIN ? 4 : row_columns[kind]); c++)
        b->in[c][b->count] = row[c];
    if (kind == ROW_MELANIN) {
        double sigma_a[3];
        hb_melanin_absorption(row[4], row[5], sigma_a);
        for (int c = 0; c < 3; c++)
            b->in[4 + c][b->count] = (float)sigma_a[c];
    }
}

/* Evaluates and prints the rows held so far (f, or the pdf) to out; returns the invalid-sample count. */
static size_t flush(const hb_plan *plan, int pdf, row_kind kind, eval_batch *b, FILE *out)
{
    if (!b->count)
        return 0;
    hb_angles_soa in = { b->in[0], b->in[1], b->in[2], b->in[3] };
    hb_near_soa in_near = { b->in[0], b->in[1], b->in[2], b->in[3], b->in[4] };
    hb_absorption_soa sigma_a = { b->in[4], b->in[5], b->in[6] };
    hb_rgb_soa rgb = { b->out[0], b->out[1], b->out[2] };
    hb_eval_report report = { 0 };
    int near = kind == ROW_NEAR;
    if (b->wavelengths) {
        const float *planes[HB_WAVELENGTHS_MAX];
        float *f[HB_WAVELENGTHS_MAX];
        for (int j = 0; j < b->wavelengths; j++)
            planes[j] = b->sigma_a[j], f[j] = b->spectral[j];
        hb_spectral_absorption a = { b->wavelengths, planes };
        near ? hb_eval_near_spectral(plan, b->count, in_near, a, f, &report)
             : hb_eval_angles_spectral(plan, b->count, in, a, f, &report);
        for (size_t k = 0; k < b->count; k++)
            for (int j = 0; j < b->wavelengths; j++)
                fprintf(out, j + 1 < b->wavelengths ? "%.9g," : "%.9g\n", b->spectral[j][k]);
        b->count = 0;
        return report.invalid;
    }
    if (pdf)
        near ? hb_pdf_near(plan, b->count, in_near, b->out[0], &report) : hb_pdf_angles(plan, b->count, in, b->out[0], &report);
    else if (kind >= ROW_MELANIN)
        hb_eval_angles_absorption(plan, b->count, in, sigma_a, rgb, &report);
    else
        near ? hb_eval_near(plan, b->count, in_near, rgb, &report) : hb_eval_angles(plan, b->count, in, rgb, &report);
    int dual = kind == ROW_FIBRES || kind == ROW_FIBRES_VISIBLE;
    if (dual)
        hb_dual_eval(b->dual, b->count, in, b->in[4], kind == ROW_FIBRES_VISIBLE ? b->in[5] : NULL,
                     (hb_rgb_soa){ b->out[3], b->out[4], b->out[5] }, &report); /* its invalid include f's */
    for (size_t k = 0; dual && k < b->count; k++) { /* a row invalid for its n or v: 0 in every column */
        float row[6] = { b->in[0][k], b->in[1][k], b->in[2][k], b->in[3][k], b->in[4][k], b->in[5][k] };
        if (!row_valid(row, kind))
            b->out[0][k] = b->out[1][k] = b->out[2][k] = 0.0f;
    }
    for (size_t k = 0; k < b->count; k++)
        if (pdf)
            fprintf(out, "%.9g\n", b->out[0][k]);
        else if (dual)
            fprintf(out, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", b->out[0][k], b->out[1][k], b->out[2][k], b->out[3][k],
                    b->out[4][k], b->out[5][k]);
        else
            fprintf(out, "%.9g,%.9g,%.9g\n", b->out[0][k], b->out[1][k], b->out[2][k]);
    b->count = 0;
    return report.invalid;
}

static void eval_usage(FILE *to, int pdf)
{
    fprintf(to, "usage: hairbsdf %s [options] [--strict] [--far]%s [-o OUTPUT] [INPUT.csv]\n"
                "Reads theta_i,phi_i,theta_o,phi_o (radians) per line from INPUT.csv or stdin, and h (the offset in\n"
                "[-1, 1]) after them where a header theta_i,phi_i,theta_o,phi_o,h names it (deon, chiang: the near\n"
                "field at h) or, without a header, for chiang unless --far (its mean over h); writes %s\n"
                "per line to OUTPUT or stdout. eval also takes each row's absorption where the header names it:\n"
                "theta_i,phi_i,theta_o,phi_o,eumelanin,pheomelanin or ...,sigma_a_r,sigma_a_g,sigma_a_b (deon with\n"
                "the quadrature, marschner, chiang). With a header theta_i,phi_i,theta_o,phi_o,n (the fibres between the point\n"
                "and the light) or ...,n,v (and the light's direct visibility in [0, 1]) eval writes the far field\n"
                "f_r,f_g,f_b and after it the dual-scattering term f_ds_r,f_ds_g,f_ds_b (hb_dual_eval, a 64-node table,\n"
                "density factors 0.7; --dual-table FILE loads a table 'hairbsdf dual --save' wrote, --dual-engine FILE\n"
                "the material's from an engine-wide table 'hairbsdf dual --engine --save' wrote). An invalid sample\n"
                "(NaN or Inf angle, |theta| > pi/2, |phi| > 1e4, |h| > 1,\n"
                "a negative absorption) gives %s and is reported with its line; with --strict it is an error.\n%s%s",
            pdf ? "pdf" : "eval", pdf ? "" : " [--wavelengths L1,L2,...]",
            pdf ? "the solid-angle pdf with which 'hairbsdf sample' draws w_i given w_o" : "f_r,f_g,f_b",
            pdf ? "0" : "0,0,0",
            pdf ? "" : "With --wavelengths L1,L2,... (nm, at most 8, in [300, 1000]; chiang, deon, marschner) eval writes f at each\n"
                       "wavelength per line instead, at the absorption the material's eumelanin and pheomelanin give\n"
                       "there (hb_melanin_absorption_spectral) plus, with --colour R,G,B, that colour's absorption\n"
                       "spectrum (hb_absorption_from_colour_spectral); the rows are the angles, or the angles and h.\n",
            cli_model_options_help);
}

/* Where the rows' dual-scattering table comes from: --dual-table FILE (hairbsdf dual --save), or
 * --dual-engine FILE (hairbsdf dual --engine --save: the family's table looked up for the plan's
 * material), else the plan's own at 64 nodes; the density factors 0.7 where the file has none. */
typedef struct dual_source {
    const char *table_path, *engine_path;
    const cli_model_args *args;
} dual_source;

/* The plan's table from the engine-wide table at path, loaded for the family of the plan's material. */
static hb_status engine_table(const hb_plan *plan, const dual_source *source, const void *bytes, size_t size,
                              hb_dual_table **table, hb_error *error)
{
    hb_material material;
    hb_dual_engine *engine = NULL;
    hb_status st = cli_material(source->args, &material, error);
    if (st == HB_OK)
        st = hb_dual_engine_load(&material, &source->args->options, bytes, size, &engine, error);
    if (st == HB_OK && (st = hb_dual_engine_table(engine, plan, HB_DUAL_DENSITY, table)) != HB_OK)
        *error = *hb_last_error();
    hb_dual_engine_destroy(engine);
    return st;
}

static hb_status dual_table_of(const hb_plan *plan, const dual_source *source, hb_dual_table **table, char *why,
                               size_t why_size)
{
    const char *path = source->engine_path ? source->engine_path : source->table_path;
    if (!path) {
        hb_status st = hb_dual_table_create(plan, 64, HB_DUAL_DENSITY, HB_DUAL_DENSITY, NULL, NULL, NULL, NULL, table);
        snprintf(why, why_size, "%s", st == HB_OK ? "" : hb_last_error()->message);
        return st;
    }
    const char *unreadable;
    size_t size = 0;
    void *bytes = cli_read_table_file(path, &size, &unreadable);
    if (!bytes) {
        snprintf(why, why_size, "%s: cannot read %s: %s", source->engine_path ? "--dual-engine" : "--dual-table", path,
                 unreadable);
        return HB_ERR_FILE;
    }
    hb_error error = { HB_OK, "" };
    hb_status st = source->engine_path ? engine_table(plan, source, bytes, size, table, &error)
                                       : hb_dual_table_load(plan, bytes, size, table);
    free(bytes);
    snprintf(why, why_size, "%s", st == HB_OK ? "" : source->engine_path ? error.message : hb_last_error()->message);
    return st;
}

/* --wavelengths: the list into batch->wavelengths and the material's absorption at each; 0, or 2 after
 * saying what is wrong. */
static int spectral_setup(const char *name, const char *list, const cli_model_args *args, const hb_plan *plan,
                          eval_batch *batch)
{
    double lambda[HB_WAVELENGTHS_MAX];
    int k = 0;
    for (const char *p = list; *p; k++) {
        char *end;
        double value = strtod(p, &end);
        if (end == p || k == HB_WAVELENGTHS_MAX || (*end && *end != ',')) {
            fprintf(stderr, "%s: --wavelengths '%s': want at most %d numbers in nm, comma-separated\n", name, list,
                    HB_WAVELENGTHS_MAX);
            return 2;
        }
        lambda[k] = value;
        p = *end ? end + 1 : end;
    }
    hb_material m;
    hb_error error;
    if (k == 0 || cli_material(args, &m, &error) != HB_OK) {
        fprintf(stderr, "%s: --wavelengths: %s\n", name, k ? error.message : "no wavelength given");
        return 2;
    }
    int from_colour = args->colour_to == CLI_COLOUR_SIGMA_A; /* --colour: its absorption spectrum */
    hb_absorption_spectrum spectrum;
    if (from_colour && cli_colour_spectrum(args, &spectrum, &error) != HB_OK) {
        fprintf(stderr, "%s: --wavelengths: %s\n", name, error.message);
        return 2;
    }
    if (!from_colour && (m.sigma_a[0] != 0.0 || m.sigma_a[1] != 0.0 || m.sigma_a[2] != 0.0)) {
        fprintf(stderr, "%s: --wavelengths takes the absorption from eumelanin and pheomelanin or --colour's "
                        "spectrum: sigma_a is RGB, with no spectrum\n", name);
        return 2;
    }
    const float *none[HB_WAVELENGTHS_MAX] = { NULL };
    if (hb_eval_angles_spectral(plan, 0, (hb_angles_soa){ 0 }, (hb_spectral_absorption){ k, none }, NULL, NULL) !=
        HB_OK) {
        fprintf(stderr, "%s: --wavelengths: %s\n", name, hb_last_error()->message);
        return 2;
    }
    for (int j = 0; j < k; j++) {
        double sigma_a, dye = 0.0;
        if (hb_melanin_absorption_spectral(m.eumelanin, m.pheomelanin, lambda[j], &sigma_a) != HB_OK ||
            (from_colour && hb_absorption_spectrum_at(&spectrum, lambda[j], &dye) != HB_OK)) {
            fprintf(stderr, "%s: --wavelengths: %s\n", name, hb_last_error()->message);
            return 2;
        }
        sigma_a += dye;
        for (size_t s = 0; s < BATCH; s++)
            batch->sigma_a[j][s] = (float)sigma_a;
    }
    batch->wavelengths = k;
    return 0;
}

int cmd_eval(int argc, char **argv, int pdf)
{
    const char *name = pdf ? "hairbsdf pdf" : "hairbsdf eval";
    const char *input_path = NULL, *output_path = NULL, *wavelengths_arg = NULL;
    dual_source dual = { NULL, NULL, NULL };
    int strict = 0, far = 0;
    cli_model_args args;
    cli_model_args_default(&args);
    dual.args = &args;
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            eval_usage(stdout, pdf);
            return 0;
        }
        if (strcmp(argv[i], "--strict") == 0) {
            strict = 1;
            continue;
        }
        if (strcmp(argv[i], "--far") == 0) {
            far = 1;
            continue;
        }
        if (strcmp(argv[i], "--wavelengths") == 0 && i + 1 < argc && !pdf) {
            wavelengths_arg = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--dual-table") == 0 && i + 1 < argc && !pdf) {
            dual.table_path = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--dual-engine") == 0 && i + 1 < argc && !pdf) {
            dual.engine_path = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            output_path = argv[++i];
            continue;
        }
        if (argv[i][0] != '-' && !input_path) {
            input_path = argv[i];
            continue;
        }
        int r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
        if (r == 0) {
            fprintf(stderr, "%s: unknown option '%s' (see %s --help)\n", name, argv[i], name);
            return 2;
        }
        if (r < 0) {
            fprintf(stderr, "%s: %s\n", name, err);
            return 2;
        }
    }
    hb_plan *plan = NULL;
    hb_error error;
    if (cli_plan_create(&args, &args.options, &plan, &error) != HB_OK) {
        fprintf(stderr, "%s: %s\n", name, error.message);
        return 2;
    }
    if (pdf && hb_plan_sample_dimensions(plan) == 0) {
        fprintf(stderr, "%s: this model and term have no sampler yet (docs/sampling.md)\n", name);
        hb_plan_destroy(plan);
        return 2;
    }
    /* A model with a near field answers a call of no samples. A header names the columns: with h, the
     * near field; without, the far field. Without a header CBTB16, a near-field model, reads h. */
    int near_field = !far && hb_eval_near(plan, 0, (hb_near_soa){ 0 }, (hb_rgb_soa){ 0 }, NULL) == HB_OK;
    int absorbing = !pdf && hb_eval_angles_absorption(plan, 0, (hb_angles_soa){ 0 }, (hb_absorption_soa){ 0 },
                                                      (hb_rgb_soa){ 0 }, NULL) == HB_OK;
    row_kind kind = near_field && args.options.model == HB_MODEL_CHIANG ? ROW_NEAR : ROW_ANGLES;
    static eval_batch batch;
    if (wavelengths_arg && spectral_setup(name, wavelengths_arg, &args, plan, &batch) != 0) {
        hb_plan_destroy(plan);
        return 2;
    }
    FILE *in = input_path ? fopen(input_path, "r") : stdin;
    FILE *out = output_path ? fopen(output_path, "w") : stdout;
    if (!in || !out) {
        fprintf(stderr, "%s: cannot open %s: %s\n", name, !in ? input_path : output_path, strerror(errno));
        if (in && in != stdin)
            fclose(in);
        hb_plan_destroy(plan);
        return 1;
    }

    char *line = NULL;
    size_t cap = 0, invalid = 0;
    long lineno = 0, first_invalid = 0;
    int seen_content = 0, status = 0;
    long length;
    while ((length = csv_read_line(&line, &cap, in)) >= 0) {
        lineno++;
        int nul = memchr(line, '\0', (size_t)length) != NULL; /* a byte C strings would stop at */
        char *s = csv_trim(lineno == 1 ? csv_skip_bom(line) : line);
        if (!*s && !nul)
            continue;
        float row[7];
        char copy[512];
        snprintf(copy, sizeof copy, "%s", s);
        if (!nul && !seen_content) {
            int header = -1;
            for (int k = ROW_SIGMA; k >= ROW_ANGLES && header < 0; k--)
                if (csv_is_named_header(s, row_names[k], row_columns[k]))
                    header = k;
            if (header == ROW_NEAR && !near_field) {
                fprintf(stderr, "%s: this model has no near field: the h column needs --model deon or chiang\n", name);
                status = 2;
                break;
            }
            if ((header == ROW_FIBRES || header == ROW_FIBRES_VISIBLE) && !batch.dual) {
                char why[300] = "pdf has no dual-scattering term (use eval)";
                hb_status st = pdf ? HB_ERR_UNSUPPORTED : dual_table_of(plan, &dual, &batch.dual, why, sizeof why);
                if (st != HB_OK) {
                    fprintf(stderr, "%s: the n column: %s\n", name, why);
                    status = 2;
                    break;
                }
            }
            if (header > ROW_NEAR && batch.wavelengths) {
                fprintf(stderr, "%s: --wavelengths takes the angles, or the angles and h\n", name);
                status = 2;
                break;
            }
            if (header >= ROW_MELANIN && !absorbing) {
                fprintf(stderr, "%s: absorption columns need eval with deon (quadrature), marschner or chiang\n", name);
                status = 2;
                break;
            }
            if (header >= 0) {
                kind = (row_kind)header;
                seen_content = 1;
                continue;
            }
        }
        int parsed = !nul && csv_parse_row(s, row, row_columns[kind]);
        if (parsed && !row_valid(row, kind)) {
            first_invalid = first_invalid ? first_invalid : lineno;
            if (strict) {
                flush(plan, pdf, kind, &batch, out);
                fprintf(stderr, "%s: line %ld: invalid sample '%s' (NaN or Inf angle, |theta| > pi/2, |phi| > 1e4, |h| > 1, "
                        "v outside [0, 1] or a negative n or absorption)\n", name, lineno, copy);
                status = 1;
                break;
            }
        }
        if (!parsed) {
            invalid += flush(plan, pdf, kind, &batch, out);
            fprintf(stderr, "%s: line %ld: malformed row '%s'%s (want ", name, lineno, copy, nul ? " with a NUL byte" : "");
            for (int c = 0; c < row_columns[kind]; c++)
                fprintf(stderr, "%s%s", c ? "," : "", row_names[kind][c]);
            fprintf(stderr, "%s)\n", lineno == 1 ? ", or that header" : "");
            status = 1;
            break;
        }
        seen_content = 1;
        batch_row(&batch, row, kind);
        if (++batch.count == BATCH)
            invalid += flush(plan, pdf, kind, &batch, out);
    }
    if (!status)
        invalid += flush(plan, pdf, kind, &batch, out);
    free(line);
    hb_dual_table_destroy(batch.dual);
    batch.dual = NULL;
    hb_plan_destroy(plan);
    if (invalid)
        fprintf(stderr, "%s: %zu invalid sample%s (NaN/Inf angle, |theta| > pi/2, |phi| > 1e4, |h| > 1, v outside [0, 1] or "
                        "a negative n or absorption), the first on line %ld, written as %s\n",
                name, invalid, invalid == 1 ? "" : "s", first_invalid,
                pdf ? "0" : kind == ROW_FIBRES || kind == ROW_FIBRES_VISIBLE ? "0,0,0,0,0,0" : "0,0,0");
    int read_failed = ferror(in);
    if (in != stdin)
        fclose(in);
    if (read_failed) {
        fprintf(stderr, "%s: cannot read %s\n", name, input_path ? input_path : "standard input");
        status = 1;
    }
    if (fflush(out) != 0 || ferror(out) || (out != stdout && fclose(out) != 0)) {
        fprintf(stderr, "%s: cannot write %s: %s\n", name, output_path ? output_path : "standard output",
                strerror(errno));
        return 1;
    }
    return status;
}

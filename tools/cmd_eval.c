/* hairbsdf eval: CSV rows theta_i,phi_i,theta_o,phi_o on stdin, f_r,f_g,f_b on stdout (docs/cli.md).
 * hairbsdf pdf: the same rows, the sampling pdf of w_i given w_o on stdout (docs/sampling.md). */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "csv.h"

#define BATCH 1024

typedef struct eval_batch {
    float in[4][BATCH];
    float out[3][BATCH];
    size_t count;
} eval_batch;

/* Evaluates and prints the rows held so far (f, or the pdf); returns the invalid-sample count. */
static size_t flush(const hb_plan *plan, int pdf, eval_batch *b)
{
    if (!b->count)
        return 0;
    hb_angles_soa in = { b->in[0], b->in[1], b->in[2], b->in[3] };
    hb_rgb_soa out = { b->out[0], b->out[1], b->out[2] };
    hb_eval_report report = { 0 };
    if (pdf)
        hb_pdf_angles(plan, b->count, in, b->out[0], &report);
    else
        hb_eval_angles(plan, b->count, in, out, &report);
    for (size_t k = 0; k < b->count; k++)
        if (pdf)
            printf("%.9g\n", b->out[0][k]);
        else
            printf("%.9g,%.9g,%.9g\n", b->out[0][k], b->out[1][k], b->out[2][k]);
    b->count = 0;
    return report.invalid;
}

static void eval_usage(FILE *to, int pdf)
{
    if (pdf)
        fprintf(to, "usage: hairbsdf pdf [options] < rows.csv\n"
                    "Reads theta_i,phi_i,theta_o,phi_o (radians) per line; writes the solid-angle pdf with\n"
                    "which 'hairbsdf sample' draws w_i given w_o, one per line.\n%s",
                cli_model_options_help);
    else
        fprintf(to, "usage: hairbsdf eval [options] < rows.csv\n"
                    "Reads theta_i,phi_i,theta_o,phi_o (radians) per line; writes f_r,f_g,f_b per line.\n%s",
                cli_model_options_help);
}

int cmd_eval(int argc, char **argv, int pdf)
{
    const char *name = pdf ? "hairbsdf pdf" : "hairbsdf eval";
    cli_model_args args;
    cli_model_args_default(&args);
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            eval_usage(stdout, pdf);
            return 0;
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
    if (hb_plan_create(&args.material, &args.options, &plan, &error) != HB_OK) {
        fprintf(stderr, "%s: %s\n", name, error.message);
        return 2;
    }
    if (pdf && hb_plan_sample_dimensions(plan) == 0) {
        fprintf(stderr, "%s: this model and term have no sampler yet (docs/sampling.md)\n", name);
        hb_plan_destroy(plan);
        return 2;
    }

    static eval_batch batch;
    char *line = NULL;
    size_t cap = 0, invalid = 0;
    long lineno = 0;
    int seen_content = 0, status = 0;
    ssize_t length;
    while ((length = getline(&line, &cap, stdin)) >= 0) {
        lineno++;
        int nul = memchr(line, '\0', (size_t)length) != NULL; /* a byte C strings would stop at */
        char *s = csv_trim(lineno == 1 ? csv_skip_bom(line) : line);
        if (!*s && !nul)
            continue;
        float row[4];
        char copy[512];
        snprintf(copy, sizeof copy, "%s", s);
        if (!nul && !seen_content && csv_is_header(s)) {
            seen_content = 1;
            continue;
        }
        if (nul || !csv_parse_row(s, row)) {
            invalid += flush(plan, pdf, &batch);
            fprintf(stderr, "%s: line %ld: malformed row '%s'%s (want theta_i,phi_i,theta_o,phi_o%s)\n", name, lineno,
                    copy, nul ? " with a NUL byte" : "", lineno == 1 ? ", or that header" : "");
            status = 1;
            break;
        }
        seen_content = 1;
        for (int c = 0; c < 4; c++)
            batch.in[c][batch.count] = row[c];
        if (++batch.count == BATCH)
            invalid += flush(plan, pdf, &batch);
    }
    if (!status)
        invalid += flush(plan, pdf, &batch);
    free(line);
    hb_plan_destroy(plan);
    if (invalid)
        fprintf(stderr, "%s: %zu invalid sample%s (NaN/Inf angle, |theta| > pi/2 or |phi| > 1e4) written as %s\n",
                name, invalid, invalid == 1 ? "" : "s", pdf ? "0" : "0,0,0");
    if (fflush(stdout) != 0)
        return 1;
    return status;
}

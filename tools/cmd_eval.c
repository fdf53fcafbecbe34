/* hairbsdf eval: CSV rows theta_i,phi_i,theta_o,phi_o on stdin, f_r,f_g,f_b on stdout (SPEC.md section 5). */
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

/* Evaluates and prints the rows held so far; returns the invalid-sample count. */
static size_t flush(const hb_plan *plan, eval_batch *b)
{
    if (!b->count)
        return 0;
    hb_angles_soa in = { b->in[0], b->in[1], b->in[2], b->in[3] };
    hb_rgb_soa out = { b->out[0], b->out[1], b->out[2] };
    hb_eval_report report = { 0 };
    hb_eval_angles(plan, b->count, in, out, &report);
    for (size_t k = 0; k < b->count; k++)
        printf("%.9g,%.9g,%.9g\n", b->out[0][k], b->out[1][k], b->out[2][k]);
    b->count = 0;
    return report.invalid;
}

static void eval_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf eval [options] < rows.csv\n"
                "Reads theta_i,phi_i,theta_o,phi_o (radians) per line; writes f_r,f_g,f_b per line.\n%s",
            cli_model_options_help);
}

int cmd_eval(int argc, char **argv)
{
    cli_model_args args;
    cli_model_args_default(&args);
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            eval_usage(stdout);
            return 0;
        }
        int r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
        if (r == 0) {
            fprintf(stderr, "hairbsdf eval: unknown option '%s' (see hairbsdf eval --help)\n", argv[i]);
            return 2;
        }
        if (r < 0) {
            fprintf(stderr, "hairbsdf eval: %s\n", err);
            return 2;
        }
    }
    hb_plan *plan = NULL;
    hb_error error;
    if (hb_plan_create(&args.material, &args.options, &plan, &error) != HB_OK) {
        fprintf(stderr, "hairbsdf eval: %s\n", error.message);
        return 2;
    }

    static eval_batch batch;
    char *line = NULL;
    size_t cap = 0, invalid = 0;
    long lineno = 0;
    int seen_content = 0, status = 0;
    while (getline(&line, &cap, stdin) >= 0) {
        lineno++;
        char *s = csv_trim(line);
        if (!*s)
            continue;
        float row[4];
        char copy[512];
        snprintf(copy, sizeof copy, "%s", s);
        if (!csv_parse_row(s, row)) {
            if (!seen_content && isalpha((unsigned char)*s)) { /* a header line */
                seen_content = 1;
                continue;
            }
            invalid += flush(plan, &batch);
            fprintf(stderr, "hairbsdf eval: line %ld: malformed row '%s' (want theta_i,phi_i,theta_o,phi_o)\n",
                    lineno, copy);
            status = 1;
            break;
        }
        seen_content = 1;
        for (int c = 0; c < 4; c++)
            batch.in[c][batch.count] = row[c];
        if (++batch.count == BATCH)
            invalid += flush(plan, &batch);
    }
    if (!status)
        invalid += flush(plan, &batch);
    free(line);
    hb_plan_destroy(plan);
    if (invalid)
        fprintf(stderr, "hairbsdf eval: %zu invalid sample%s (NaN/Inf angle, |theta| > pi/2 or |phi| > 1e4) written as 0,0,0\n",
                invalid, invalid == 1 ? "" : "s");
    if (fflush(stdout) != 0)
        return 1;
    return status;
}

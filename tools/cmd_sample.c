/* hairbsdf sample: importance-sampled w_i for one w_o (and, for a near-field model, one offset h;
 * docs/sampling.md), as CSV rows
 * theta_i,phi_i,pdf,w_r,w_g,w_b, or with --summary the mean weight per channel and its
 * standard error (for a lossless fibre: the white-furnace energy E(w_o)). */
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#define BATCH 1024

static void sample_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf sample [options] --theta-o X [--phi-o Y] [--h H] [--count N] [--seed S] [--summary]\n"
                "Draws N directions w_i (default 16) for w_o = (theta_o, phi_o), at the offset H in [-1, 1] for a\n"
                "model with a near field (deon, chiang; without --h the far field), with random numbers from\n"
                "hb_uniforms(seed), and prints theta_i,phi_i,pdf,w_r,w_g,w_b per sample, where the weight\n"
                "w = f / pdf (huang with TT or TRT: the traced path's throughput, whose mean is that of f / pdf);\n--summary prints count,mean_w_r,mean_w_g,mean_w_b,stderr_r,stderr_g,stderr_b.\n%s",
            cli_model_options_help);
}

static int parse_number(const char *option, const char *s, double limit, double *out)
{
    char *end;
    *out = strtod(s, &end);
    if (end == s || *end || !(*out >= -limit && *out <= limit)) {
        fprintf(stderr, "hairbsdf sample: %s: '%s' is not a number in [-%g, %g]\n", option, s, limit, limit);
        return 0;
    }
    return 1;
}

int cmd_sample(int argc, char **argv)
{
    cli_model_args args;
    cli_model_args_default(&args);
    double theta_o = 0.0, phi_o = 0.0, h = 0.0;
    unsigned long long seed = 1, count = 16;
    int have_theta = 0, have_h = 0, summary = 0;
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            sample_usage(stdout);
            return 0;
        }
        if (strcmp(argv[i], "--summary") == 0) {
            summary = 1;
        } else if (strcmp(argv[i], "--theta-o") == 0 && i + 1 < argc) {
            if (!parse_number("--theta-o", argv[++i], 1.5707963267948966, &theta_o))
                return 2;
            have_theta = 1;
        } else if (strcmp(argv[i], "--phi-o") == 0 && i + 1 < argc) {
            if (!parse_number("--phi-o", argv[++i], 3.141592653589793, &phi_o))
                return 2;
        } else if (strcmp(argv[i], "--h") == 0 && i + 1 < argc) {
            if (!parse_number("--h", argv[++i], 1.0, &h))
                return 2;
            have_h = 1;
        } else if ((strcmp(argv[i], "--count") == 0 || strcmp(argv[i], "--seed") == 0) && i + 1 < argc) {
            const char *option = argv[i++];
            unsigned long long v = 0;
            if (!cli_parse_u64(argv[i], &v) || (option[2] == 'c' && (v == 0 || v > 100000000ull))) {
                fprintf(stderr, "hairbsdf sample: %s: '%s' is not %s\n", option, argv[i],
                        option[2] == 'c' ? "a count in 1..1e8" : "an integer from 0 to 2^64 - 1");
                return 2;
            }
            *(option[2] == 'c' ? &count : &seed) = v;
            if (option[2] == 's')
                args.options.seed = v; /* also keys a model's own Monte-Carlo numbers */
        } else {
            int r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
            if (r <= 0) {
                fprintf(stderr, "hairbsdf sample: %s\n", r < 0 ? err : "unknown option (see hairbsdf sample --help)");
                return 2;
            }
        }
    }
    if (!have_theta) {
        fprintf(stderr, "hairbsdf sample: --theta-o is required\n");
        return 2;
    }
    hb_plan *plan = NULL;
    hb_error error;
    if (cli_plan_create(&args, &args.options, &plan, &error) != HB_OK) {
        fprintf(stderr, "hairbsdf sample: %s\n", error.message);
        return 2;
    }
    int dims = hb_plan_sample_dimensions(plan);
    if (dims == 0) {
        fprintf(stderr, "hairbsdf sample: this model and term have no sampler yet (docs/sampling.md)\n");
        hb_plan_destroy(plan);
        return 2;
    }
    if (have_h && hb_eval_near(plan, 0, (hb_near_soa){ 0 }, (hb_rgb_soa){ 0 }, NULL) != HB_OK) {
        fprintf(stderr, "hairbsdf sample: --h: this model has no near field (deon and chiang have)\n");
        hb_plan_destroy(plan);
        return 2;
    }
    static float to[BATCH], po[BATCH], hs[BATCH], u[HB_SAMPLE_DIMENSIONS][BATCH], ti[BATCH], pi[BATCH], pdf[BATCH],
        w[3][BATCH];
    float *streams[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        streams[d] = u[d];
    for (int k = 0; k < BATCH; k++) {
        to[k] = (float)theta_o;
        po[k] = (float)phi_o;
        hs[k] = (float)h;
    }
    double sum[3] = { 0 }, sum2[3] = { 0 };
    if (!summary)
        printf("theta_i,phi_i,pdf,w_r,w_g,w_b\n");
    for (unsigned long long first = 0; first < count; first += BATCH) {
        size_t n = count - first < BATCH ? (size_t)(count - first) : BATCH;
        hb_uniforms(seed, first, n, dims, streams);
        hb_sample_out out = { ti, pi, pdf, { w[0], w[1], w[2] } };
        if (have_h) {
            hb_sample_near_in in = { to, po, hs, (const float *const *)streams };
            hb_sample_near(plan, n, &in, &out, NULL);
        } else {
            hb_sample_in in = { to, po, (const float *const *)streams };
            hb_sample_angles(plan, n, &in, &out, NULL);
        }
        for (size_t k = 0; k < n; k++) {
            for (int c = 0; c < 3; c++) {
                sum[c] += w[c][k];
                sum2[c] += (double)w[c][k] * w[c][k];
            }
            if (!summary)
                printf("%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", ti[k], pi[k], pdf[k], w[0][k], w[1][k], w[2][k]);
        }
    }
    if (summary) {
        double n = (double)count, mean[3], se[3];
        for (int c = 0; c < 3; c++) {
            mean[c] = sum[c] / n;
            se[c] = n > 1 ? sqrt(fmax(sum2[c] / n - mean[c] * mean[c], 0.0) / (n - 1)) : 0.0;
        }
        printf("count,mean_w_r,mean_w_g,mean_w_b,stderr_r,stderr_g,stderr_b\n%llu,%.6f,%.6f,%.6f,%.2e,%.2e,%.2e\n", count,
               mean[0], mean[1], mean[2], se[0], se[1], se[2]);
    }
    hb_plan_destroy(plan);
    return 0; /* main reports a failed write */
}

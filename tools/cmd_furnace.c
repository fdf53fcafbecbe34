/* hairbsdf furnace: white-furnace energy E(w_o) (SPEC.md section 2) against theta_o, in total
 * or split by lobe (dFH11 Fig. 5: the share of TRRT and above). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static void furnace_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf furnace [options] [--theta-o A,B,...] [--by-lobe]\n"
                "Prints theta_o,E_r,E_g,E_b: the integral of f over all w_i. With --by-lobe, the red\n"
                "channel's energy per lobe (R..pmax, residual), the total, and the share of p >= 3.\n%s",
            cli_model_options_help);
}

static int energy(const cli_model_args *args, unsigned lobes, double theta_o, double e[3])
{
    hb_options o = args->options;
    o.lobes = lobes;
    hb_plan *plan;
    hb_error err;
    if (hb_plan_create(&args->material, &o, &plan, &err) != HB_OK) {
        fprintf(stderr, "hairbsdf furnace: %s\n", err.message);
        return 0;
    }
    hb_status st = hb_furnace(plan, theta_o, e);
    hb_plan_destroy(plan);
    if (st != HB_OK)
        fprintf(stderr, "hairbsdf furnace: %s\n", hb_status_string(st));
    return st == HB_OK;
}

int cmd_furnace(int argc, char **argv)
{
    cli_model_args args;
    cli_model_args_default(&args);
    double thetas[64];
    int ntheta = 0, by_lobe = 0;
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            furnace_usage(stdout);
            return 0;
        }
        if (strcmp(argv[i], "--by-lobe") == 0) {
            by_lobe = 1;
            continue;
        }
        if (strcmp(argv[i], "--theta-o") == 0 && i + 1 < argc) {
            char *s = argv[++i], *end;
            for (ntheta = 0; ntheta < 64 && *s; ntheta++) {
                thetas[ntheta] = strtod(s, &end);
                if (end == s || (*end && *end != ',')) {
                    fprintf(stderr, "hairbsdf furnace: --theta-o: '%s' is not a comma list of angles\n", argv[i]);
                    return 2;
                }
                s = *end ? end + 1 : end;
            }
            continue;
        }
        int r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
        if (r <= 0) {
            fprintf(stderr, "hairbsdf furnace: %s\n", r < 0 ? err : "unknown option (see hairbsdf furnace --help)");
            return 2;
        }
    }
    if (!ntheta)
        for (; ntheta < 13; ntheta++)
            thetas[ntheta] = -1.5 + 0.25 * ntheta;
    int pmax = args.options.pmax;
    if (by_lobe) {
        printf("theta_o");
        static const char *const names[] = { "R", "TT", "TRT", "TRRT", "p4", "p5", "p6", "p7" };
        for (int p = 0; p <= pmax; p++)
            printf(",%s", names[p]);
        printf(",residual,total,share_p3_and_above\n");
    } else {
        printf("theta_o,E_r,E_g,E_b\n");
    }
    for (int k = 0; k < ntheta; k++) {
        double e[3];
        if (!by_lobe) {
            if (!energy(&args, args.options.lobes, thetas[k], e))
                return 2;
            printf("%.4f,%.6f,%.6f,%.6f\n", thetas[k], e[0], e[1], e[2]);
            continue;
        }
        double total = 0.0, high = 0.0;
        printf("%.4f", thetas[k]);
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
            if (p > pmax && p != HB_LOBE_RESIDUAL)
                continue;
            if (!energy(&args, 1u << p, thetas[k], e))
                return 2;
            total += e[0];
            high += p >= 3 ? e[0] : 0.0;
            printf(",%.6f", e[0]);
        }
        printf(",%.6f,%.4f\n", total, high / total);
    }
    return 0;
}

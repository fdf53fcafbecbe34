/* hairbsdf furnace: white-furnace energy E(w_o) (docs/conventions.md) against theta_o, in total
 * or split by lobe (dFH11 Fig. 5: the share of TRRT and above). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "plot.h"

static void furnace_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf furnace [options] [--theta-o A,B,...] [--by-lobe | --orders [--paths N] | --fig16]\n"
                "                        [--svg FILE]\n"
                "Prints theta_o,E_r,E_g,E_b: the integral of f over all w_i. With --by-lobe, the red\n"
                "channel's energy per lobe the model has (R..pmax, residual), the total, and the share\n"
                "of p >= 3.\n"
                "--orders (huang, circular): the energy leaving by order, R, TT, TRT and all beyond, by a\n"
                "random walk of N paths (default 20000) per theta (channel mean, standard error of the\n"
                "beyond column), and the share beyond TRT, which the model drops (HHH22 Fig. 16).\n"
                "--fig16: --orders for HHH22 Fig. 16's fibres (alpha 2 deg, Beckmann 0.15, eumelanin\n"
                "0.06 blond, 0.6 brown, 1.8 black) and a lossless one.\n"
                "--svg FILE: also plots the table against theta (one line per column; by order: the share\n"
                "beyond TRT per fibre, as in HHH22 Fig. 16).\n%s",
            cli_model_options_help);
}

static int energy(const cli_model_args *args, unsigned lobes, double theta_o, double e[3])
{
    hb_options o = args->options;
    o.lobes = lobes;
    hb_plan *plan;
    hb_error err;
    if (cli_plan_create(args, &o, &plan, &err) != HB_OK) {
        fprintf(stderr, "hairbsdf furnace: %s\n", err.message);
        return 0;
    }
    hb_status st = hb_furnace(plan, theta_o, e);
    hb_plan_destroy(plan);
    if (st == HB_ERR_PARAM)
        fprintf(stderr, "hairbsdf furnace: --theta-o %g is outside [-pi/2, pi/2]\n", theta_o);
    else if (st != HB_OK)
        fprintf(stderr, "hairbsdf furnace: %s\n", hb_status_string(st));
    return st == HB_OK;
}

/* The lobes of --by-lobe: orders 0..pmax and the residual, those the model has (a plan of the lobe
 * alone is not refused as unsupported). 0 and a message when a plan fails for another reason. */
static int model_lobes(const cli_model_args *args, unsigned *lobes)
{
    *lobes = 0;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
        if (p > args->options.pmax && p != HB_LOBE_RESIDUAL)
            continue;
        hb_options o = args->options;
        o.lobes = 1u << p;
        hb_plan *plan;
        hb_error err;
        hb_status st = cli_plan_create(args, &o, &plan, &err);
        hb_plan_destroy(plan);
        if (st == HB_OK)
            *lobes |= 1u << p;
        else if (st != HB_ERR_UNSUPPORTED) {
            fprintf(stderr, "hairbsdf furnace: %s\n", err.message);
            return 0;
        }
    }
    return 1;
}

/* --orders: one row per theta for the material (named `fibre`). */
static int orders(FILE *out, const cli_model_args *args, const char *fibre, const double *thetas, int ntheta, long paths)
{
    hb_plan *plan;
    hb_error err;
    if (cli_plan_create(args, &args->options, &plan, &err) != HB_OK) {
        fprintf(stderr, "hairbsdf furnace: %s\n", err.message);
        return 0;
    }
    for (int k = 0; k < ntheta; k++) {
        double e[HB_ORDER_GROUPS][3], se[HB_ORDER_GROUPS], mean[HB_ORDER_GROUPS], total = 0.0;
        hb_status st = hb_furnace_orders(plan, thetas[k], paths, 1, e, se);
        if (st != HB_OK) {
            fprintf(stderr, "hairbsdf furnace: --orders: %s (huang plans of circular fibres, |theta| < pi/2)\n",
                    hb_status_string(st));
            hb_plan_destroy(plan);
            return 0;
        }
        for (int g = 0; g < HB_ORDER_GROUPS; g++) {
            mean[g] = (e[g][0] + e[g][1] + e[g][2]) / 3.0;
            total += mean[g];
        }
        fprintf(out, "%s,%.4f,%.5f,%.5f,%.5f,%.5f,%.5f,%.4f\n", fibre, thetas[k], mean[0], mean[1], mean[2], mean[3],
               se[3], total > 0.0 ? mean[3] / total : 0.0);
    }
    hb_plan_destroy(plan);
    return 1;
}

/* What to compute: parsed from the command line. */
typedef struct furnace_request {
    cli_model_args args;
    double thetas[64];
    int ntheta, by_lobe, by_order, fig16;
    long paths;
} furnace_request;

/* The CSV table of the request into out. Returns the exit status. */
static int furnace_rows(FILE *out, const furnace_request *q)
{
    const cli_model_args args = q->args;
    const double *thetas = q->thetas;
    int ntheta = q->ntheta, by_lobe = q->by_lobe, fig16 = q->fig16;
    long paths = q->paths;
    if (q->by_order) {
        fprintf(out, "fibre,theta,E_R,E_TT,E_TRT,E_beyond,stderr_beyond,share_beyond\n");
        if (!fig16)
            return orders(out, &args, "material", thetas, ntheta, paths) ? 0 : 2;
        /* HHH22 Fig. 16: alpha 2 degrees, Beckmann 0.15, e = 0; sigma_a = 0 and three melanin contents */
        static const struct { const char *name; double eumelanin; } fibres[] = {
            { "lossless", 0.0 }, { "blond", 0.06 }, { "brown", 0.6 }, { "black", 1.8 } };
        for (int f = 0; f < 4; f++) {
            cli_model_args fig = args;
            fig.colour_to = CLI_COLOUR_NONE;
            fig.options.model = HB_MODEL_HUANG;
            fig.material.alpha = 2.0 * M_PI / 180.0;
            fig.material.ndf = HB_NDF_BECKMANN;
            fig.material.roughness = 0.15;
            fig.material.eccentricity = 0.0;
            fig.material.sigma_a[0] = fig.material.sigma_a[1] = fig.material.sigma_a[2] = 0.0;
            fig.material.eumelanin = fibres[f].eumelanin;
            fig.material.pheomelanin = 0.0;
            if (!orders(out, &fig, fibres[f].name, thetas, ntheta, paths))
                return 2;
        }
        return 0;
    }
    unsigned lobes = 0;
    if (by_lobe) {
        if (!model_lobes(&args, &lobes))
            return 2;
        fprintf(out, "theta_o");
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            if (lobes >> p & 1u)
                fprintf(out, ",%s", cli_lobe_name(p));
        fprintf(out, ",total,share_p3_and_above\n");
    } else {
        fprintf(out, "theta_o,E_r,E_g,E_b\n");
    }
    for (int k = 0; k < ntheta; k++) {
        double e[3];
        if (!by_lobe) {
            if (!energy(&args, args.options.lobes, thetas[k], e))
                return 2;
            fprintf(out, "%.4f,%.6f,%.6f,%.6f\n", thetas[k], e[0], e[1], e[2]);
            continue;
        }
        double total = 0.0, high = 0.0;
        fprintf(out, "%.4f", thetas[k]);
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
            if (!(lobes >> p & 1u))
                continue;
            if (!energy(&args, 1u << p, thetas[k], e))
                return 2;
            total += e[0];
            high += p >= 3 ? e[0] : 0.0;
            fprintf(out, ",%.6f", e[0]);
        }
        fprintf(out, ",%.6f,%.4f\n", total, high / total);
    }
    return 0;
}

static int furnace_table(FILE *out, void *request) { return furnace_rows(out, request); }

int cmd_furnace(int argc, char **argv)
{
    furnace_request q = { .paths = 20000 };
    cli_model_args_default(&q.args);
    const char *svg = NULL;
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            furnace_usage(stdout);
            return 0;
        }
        if (strcmp(argv[i], "--by-lobe") == 0) {
            q.by_lobe = 1;
            continue;
        }
        if (strcmp(argv[i], "--orders") == 0 || strcmp(argv[i], "--fig16") == 0) {
            q.by_order = 1;
            q.fig16 |= strcmp(argv[i], "--fig16") == 0;
            continue;
        }
        if (strcmp(argv[i], "--paths") == 0 && i + 1 < argc) {
            char *end;
            q.paths = strtol(argv[++i], &end, 10);
            if (*end || q.paths < 1) {
                fprintf(stderr, "hairbsdf furnace: --paths: '%s' is not a positive count\n", argv[i]);
                return 2;
            }
            continue;
        }
        if (strcmp(argv[i], "--svg") == 0 && i + 1 < argc) {
            svg = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--theta-o") == 0 && i + 1 < argc) {
            char *s = argv[++i], *end;
            if (!*s) {
                fprintf(stderr, "hairbsdf furnace: --theta-o: an empty list (give angles, or leave the option out)\n");
                return 2;
            }
            for (q.ntheta = 0; q.ntheta < 64 && *s; q.ntheta++) {
                q.thetas[q.ntheta] = strtod(s, &end);
                if (end == s || (*end && *end != ',') || !isfinite(q.thetas[q.ntheta])) {
                    fprintf(stderr, "hairbsdf furnace: --theta-o: '%s' is not a comma list of angles\n", argv[i]);
                    return 2;
                }
                s = *end ? end + 1 : end;
            }
            continue;
        }
        int r = cli_parse_model_option(argc, argv, &i, &q.args, err, sizeof err);
        if (r <= 0) {
            fprintf(stderr, "hairbsdf furnace: %s\n", r < 0 ? err : "unknown option (see hairbsdf furnace --help)");
            return 2;
        }
    }
    if (!q.ntheta)
        for (; q.ntheta < 13; q.ntheta++)
            q.thetas[q.ntheta] = -1.5 + 0.25 * q.ntheta;
    if (!svg)
        return furnace_rows(stdout, &q);
    /* --svg: the same table, printed and plotted */
    char title[160];
    snprintf(title, sizeof title, "hairbsdf furnace: %s",
             q.by_order ? "share of the energy beyond TRT (HHH22 Fig. 16)" : q.by_lobe ? "energy by lobe" : "white furnace energy");
    const char *y_label = q.by_order ? "share of the energy beyond TRT"
                          : q.by_lobe ? "energy per lobe (fraction of the incident light)"
                                      : "white-furnace energy E (fraction of the incident light)";
    int st = plot_table(furnace_table, &q, svg, title, NULL, q.by_order ? "share_beyond" : NULL, "theta_o (radians)", y_label,
                        err, sizeof err);
    if (st && err[0])
        fprintf(stderr, "hairbsdf furnace: --svg: %s\n", err);
    return st;
}

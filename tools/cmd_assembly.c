/* hairbsdf assembly: light traced through a slab or a bundle of fibres of one material
 * (hb_assembly_trace; docs/multiple-scattering.md), as CSV. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_threads.h"
#include "plot.h"

static void assembly_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf assembly [options] [--shape slab|bundle] [--layers L] [--packing P]\n"
                "       [--period W] [--light THETA,PHI] [--paths N] [--bounces B] [--seed S]\n"
                "       [--bins NT,NP] [--depth-bins ND] [--radiance] [--depth] [--svg FILE]\n"
                "       [--transport light|sampler] [--dual D_F,D_B]\n"
                "Traces N paths (default 100000) of light from the direction (THETA, PHI) (default 0.3,0)\n"
                "through a slab L fibre diameters thick (default 8; periodic along x every W diameters,\n"
                "default 32) or a bundle of radius L diameters, its fibres covering a share P (default 0.3)\n"
                "of the cross-section, and prints the reflected, transmitted, absorbed and unfinished\n"
                "shares with their standard errors, then the shares by scattering order. --radiance adds\n"
                "the light leaving per unit solid angle in NT x NP bins of theta and phi (default 18,36),\n"
                "--depth the light arriving at each of ND depths (default 8) by order, and --svg FILE\n"
                "plots it (green channel). --transport: each scattering weighed by the model's S from\n"
                "where the light came (light, default: far field, any model but HHH22's estimated pdf)\n"
                "or by the sampler's own weight (sampler: near field at the hit's offset; exact where S\n"
                "is reciprocal). --threads N runs the paths on N threads, the same numbers. --dual D_F,D_B\n"
                "(a slab) adds what dual scattering predicts with those density factors (the paper's: 0.7,0.7),\n"
                "rendered through the same fibres (hb_assembly_dual, 512 view rays per bin): its reflected and\n"
                "transmitted shares and those of single scattering alone, and with --radiance their bins.\n%s",
            cli_model_options_help);
}

static int parse_pair(const char *s, double *a, double *b)
{
    char *end;
    *a = strtod(s, &end);
    if (end == s || *end != ',')
        return 0;
    const char *rest = end + 1;
    *b = strtod(rest, &end);
    return end != rest && !*end && isfinite(*a) && isfinite(*b);
}

/* Parses one assembly option at argv[*i]: 1 consumed, 0 not one, -1 a bad value. */
static int parse_assembly_option(int argc, char **argv, int *i, hb_assembly *a, int *radiance, int *depth,
                                 const char **svg, double density[2])
{
    const char *o = argv[*i];
    if (strcmp(o, "--radiance") == 0)
        return *radiance = 1;
    if (strcmp(o, "--depth") == 0)
        return *depth = 1;
    if (*i + 1 >= argc)
        return 0;
    const char *v = argv[*i + 1];
    double x, y;
    int ok;
    if (strcmp(o, "--svg") == 0)
        ok = (*svg = v, *depth = 1);
    else if (strcmp(o, "--transport") == 0)
        ok = strcmp(v, "light") == 0     ? (a->transport = HB_ASSEMBLY_LIGHT_TRANSPORT, 1)
             : strcmp(v, "sampler") == 0 ? (a->transport = HB_ASSEMBLY_SAMPLER_WEIGHTS, 1)
                                         : 0;
    else if (strcmp(o, "--shape") == 0)
        ok = strcmp(v, "slab") == 0 ? (a->shape = HB_ASSEMBLY_SLAB, 1) : strcmp(v, "bundle") == 0 ? (a->shape = HB_ASSEMBLY_BUNDLE, 1) : 0;
    else if (strcmp(o, "--layers") == 0)
        ok = cli_parse_range(v, 1.0, 1024.0, &a->layers);
    else if (strcmp(o, "--packing") == 0)
        ok = cli_parse_range(v, 1e-6, 0.5, &a->packing);
    else if (strcmp(o, "--period") == 0)
        ok = cli_parse_range(v, 4.0, 4096.0, &x) && x == floor(x) ? (a->period = (int)x, 1) : 0;
    else if (strcmp(o, "--light") == 0)
        ok = parse_pair(v, &a->theta_light, &a->phi_light);
    else if (strcmp(o, "--paths") == 0)
        ok = cli_parse_range(v, 1.0, 1e12, &x) && x == floor(x) ? (a->paths = (long long)x, 1) : 0;
    else if (strcmp(o, "--bounces") == 0)
        ok = cli_parse_range(v, 1.0, 100000.0, &x) && x == floor(x) ? (a->max_bounces = (int)x, 1) : 0;
    else if (strcmp(o, "--seed") == 0)
        ok = cli_parse_u64(v, &a->seed);
    else if (strcmp(o, "--bins") == 0)
        ok = parse_pair(v, &x, &y) && x >= 1 && x <= 4096 && y >= 1 && y <= 4096 && x == floor(x) && y == floor(y)
                 ? (a->theta_bins = (int)x, a->phi_bins = (int)y, 1)
                 : 0;
    else if (strcmp(o, "--dual") == 0)
        ok = parse_pair(v, &density[0], &density[1]) && density[0] >= 0.0 && density[0] <= 1.0 && density[1] >= 0.0 &&
             density[1] <= 1.0;
    else if (strcmp(o, "--depth-bins") == 0)
        ok = cli_parse_range(v, 1.0, 4096.0, &x) && x == floor(x) ? (a->depth_bins = (int)x, 1) : 0;
    else
        return 0;
    if (!ok) {
        fprintf(stderr, "hairbsdf assembly: %s: '%s' is not a valid value (see hairbsdf assembly --help)\n", o, v);
        return -1;
    }
    ++*i;
    return 1;
}

static void print_row(const char *name, const double v[3], const double se[3])
{
    printf("%s,%.6g,%.6g,%.6g", name, v[0], v[1], v[2]);
    if (se)
        printf(",%.3g,%.3g,%.3g", se[0], se[1], se[2]);
    else
        printf(",,,");
    printf("\n");
}

/* What dual scattering predicts (hb_assembly_dual), per bin and its standard error, and single scattering alone. */
typedef struct prediction {
    double *dual, *dual_se, *single;
} prediction;

static void print_tables(const hb_assembly *a, const hb_assembly_result *r, int radiance, int depth, const prediction *p)
{
    if (radiance) {
        printf("\nside,theta_lo,theta_hi,phi_lo,phi_hi,radiance_r,radiance_g,radiance_b,se_r,se_g,se_b%s\n",
               p ? ",dual_r,dual_g,dual_b,single_r,single_g,single_b" : "");
        for (int side = 0; side < 2; side++)
            for (int i = 0; i < a->theta_bins; i++)
                for (int j = 0; j < a->phi_bins; j++) {
                    size_t k = (size_t)((side * a->theta_bins + i) * a->phi_bins + j) * 3;
                    printf("%s,%.4f,%.4f,%.4f,%.4f,%.5g,%.5g,%.5g,%.2g,%.2g,%.2g", side ? "transmitted" : "reflected",
                           -M_PI_2 + M_PI * i / a->theta_bins, -M_PI_2 + M_PI * (i + 1) / a->theta_bins,
                           -M_PI + 2.0 * M_PI * j / a->phi_bins, -M_PI + 2.0 * M_PI * (j + 1) / a->phi_bins, r->radiance[k],
                           r->radiance[k + 1], r->radiance[k + 2], r->radiance_se[k], r->radiance_se[k + 1],
                           r->radiance_se[k + 2]);
                    if (p)
                        printf(",%.5g,%.5g,%.5g,%.5g,%.5g,%.5g", p->dual[k], p->dual[k + 1], p->dual[k + 2], p->single[k],
                               p->single[k + 1], p->single[k + 2]);
                    printf("\n");
                }
    }
    if (depth) {
        printf("\ndepth,order,arriving_r,arriving_g,arriving_b\n");
        for (int d = 0; d < a->depth_bins; d++)
            for (int o = 0; o < 3; o++) {
                const double *v = r->depth + (size_t)(d * 3 + o) * 3;
                printf("%d,%s,%.6g,%.6g,%.6g\n", d, o == 0 ? "1" : o == 1 ? "2" : "3+", v[0], v[1], v[2]);
            }
    }
}

/* The prediction's share leaving through a side: its bins times their solid angles, with the
 * standard error of the sum (se may be NULL). */
static void side_shares(const hb_assembly *a, const double *bins, const double *bins_se, int side, double share[3],
                        double se[3])
{
    for (int c = 0; c < 3; c++) {
        double sum = 0.0, var = 0.0;
        for (int i = 0; i < a->theta_bins; i++) {
            double solid = (sin(-M_PI_2 + M_PI * (i + 1) / a->theta_bins) - sin(-M_PI_2 + M_PI * i / a->theta_bins)) * 2.0 *
                           M_PI / a->phi_bins;
            for (int j = 0; j < a->phi_bins; j++) {
                size_t k = (size_t)((side * a->theta_bins + i) * a->phi_bins + j) * 3 + (size_t)c;
                sum += bins[k] * solid;
                if (bins_se)
                    var += bins_se[k] * bins_se[k] * solid * solid;
            }
        }
        share[c] = sum;
        if (se)
            se[c] = sqrt(var);
    }
}

/* Dual scattering's prediction for the assembly with the density factors, and its rows. */
static int predict(const hb_plan *plan, const hb_assembly *a, const double density[2], prediction *p)
{
    hb_dual_table *table;
    if (hb_dual_table_create(plan, 64, density[0], density[1], NULL, NULL, NULL, NULL, &table) != HB_OK ||
        hb_assembly_dual(plan, table, a, 512, p->dual, p->dual_se, p->single) != HB_OK) {
        fprintf(stderr, "hairbsdf assembly: --dual: %s\n", hb_last_error()->message);
        if (table)
            hb_dual_table_destroy(table);
        return 2;
    }
    hb_dual_table_destroy(table);
    static const char *const names[2][2] = { { "dual_reflected", "dual_transmitted" },
                                             { "single_reflected", "single_transmitted" } };
    for (int side = 0; side < 2; side++) {
        double share[3], se[3];
        side_shares(a, p->dual, p->dual_se, side, share, se);
        print_row(names[0][side], share, se);
        side_shares(a, p->single, NULL, side, share, NULL);
        print_row(names[1][side], share, NULL);
    }
    return 0;
}

/* The light arriving at each depth by order, the green channel, as lines. */
static int plot_depth(const char *path, const hb_assembly *a, const hb_assembly_result *r, const cli_model_args *args)
{
    double *x = malloc((size_t)a->depth_bins * 4 * sizeof(double));
    if (!x)
        return -1;
    double *y = x + a->depth_bins;
    for (int d = 0; d < a->depth_bins; d++) {
        x[d] = d + 0.5;
        for (int o = 0; o < 3; o++)
            y[o * a->depth_bins + d] = r->depth[(size_t)(d * 3 + o) * 3 + 1];
    }
    plot_series series[3] = { { "first scattering", x, y, a->depth_bins },
                              { "second", x, y + a->depth_bins, a->depth_bins },
                              { "third and later", x, y + 2 * a->depth_bins, a->depth_bins } };
    char title[256];
    snprintf(title, sizeof title, "%s (eumelanin %.2g, pheomelanin %.2g), %s of %g layers at packing %.2f, light at theta %.2f, "
             "phi %.2f: light arriving by depth",
             cli_model_paper(args->options.model), args->material.eumelanin, args->material.pheomelanin, a->shape == HB_ASSEMBLY_SLAB ? "slab" : "bundle", a->layers, r->packing,
             a->theta_light, a->phi_light);
    int status = plot_write_lines_svg(path, title, "depth from the lit side (fibre diameters)",
                                      "light arriving at the fibres (fraction of incident, green)", series, 3);
    free(x);
    return status;
}

int cmd_assembly(int argc, char **argv)
{
    cli_model_args args;
    cli_model_args_default(&args);
    hb_assembly a;
    hb_assembly_default(&a);
    int radiance = 0, depth = 0;
    double density[2] = { NAN, NAN };
    const char *svg = NULL;
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            assembly_usage(stdout);
            return 0;
        }
        int r = parse_assembly_option(argc, argv, &i, &a, &radiance, &depth, &svg, density);
        if (r < 0)
            return 2;
        if (r > 0)
            continue;
        r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
        if (r <= 0) {
            fprintf(stderr, "hairbsdf assembly: %s\n", r < 0 ? err : "unknown option (see hairbsdf assembly --help)");
            return 2;
        }
    }
    hb_plan *plan;
    hb_error e;
    if (cli_plan_create(&args, &args.options, &plan, &e) != HB_OK) {
        fprintf(stderr, "hairbsdf assembly: %s\n", e.message);
        return 2;
    }
    size_t bins = (size_t)2 * a.theta_bins * a.phi_bins * 3;
    hb_assembly_result r = { .struct_size = sizeof r };
    r.radiance = radiance ? malloc(bins * sizeof(double)) : NULL;
    r.radiance_se = radiance ? malloc(bins * sizeof(double)) : NULL;
    r.depth = depth ? malloc((size_t)a.depth_bins * 9 * sizeof(double)) : NULL;
    int dual = !isnan(density[0]);
    prediction p = { dual ? malloc(bins * sizeof(double)) : NULL, dual ? malloc(bins * sizeof(double)) : NULL,
                     dual ? malloc(bins * sizeof(double)) : NULL };
    int status = 0;
    if ((radiance && (!r.radiance || !r.radiance_se)) || (depth && !r.depth) || (dual && (!p.dual || !p.dual_se || !p.single))) {
        fprintf(stderr, "hairbsdf assembly: out of memory\n");
        status = 1;
    } else if (hb_assembly_trace(plan, &a, &r, args.progress ? cli_tracing_progress : NULL, NULL,
                                 args.threads > 1 ? cli_parallel : NULL, &args.threads) != HB_OK) {
        fprintf(stderr, "hairbsdf assembly: %s\n", hb_last_error()->message);
        status = 2;
    } else {
        printf("# %ld fibres, packing %.4f, %lld scatterings, %lld refused samples\n", r.fibres, r.packing, r.events,
               r.invalid);
        printf("quantity,r,g,b,se_r,se_g,se_b\n");
        print_row("reflected", r.reflected, r.reflected_se);
        print_row("transmitted", r.transmitted, r.transmitted_se);
        print_row("absorbed", r.absorbed, r.absorbed_se);
        print_row("unfinished", r.unfinished, NULL);
        for (int side = 0; side < 2; side++)
            for (int o = 0; o < HB_ASSEMBLY_ORDERS; o++) {
                char name[48];
                snprintf(name, sizeof name, "%s_order_%d%s", side ? "transmitted" : "reflected", o,
                         o == HB_ASSEMBLY_ORDERS - 1 ? "+" : "");
                double se[3];
                for (int c = 0; c < 3; c++) /* the header's rule for one order */
                    se[c] = sqrt(fmax(r.by_order_square[side][o][c] - r.by_order[side][o][c] * r.by_order[side][o][c], 0.0) /
                                 (double)(a.paths > 1 ? a.paths - 1 : 1));
                print_row(name, r.by_order[side][o], se);
            }
        if (dual)
            status = predict(plan, &a, density, &p);
        print_tables(&a, &r, radiance, depth, dual && !status ? &p : NULL);
        if (svg && plot_depth(svg, &a, &r, &args) != 0) {
            fprintf(stderr, "hairbsdf assembly: --svg: cannot write %s\n", svg);
            status = 1;
        }
    }
    free(r.radiance), free(r.radiance_se), free(r.depth), free(p.dual), free(p.dual_se), free(p.single);
    hb_plan_destroy(plan);
    return status;
}

/* hairbsdf dual: a fibre's dual-scattering terms against the light's inclination theta (Zinke et al.
 * 2008; docs/multiple-scattering.md), as CSV, or its table as a file (--save); with --engine, its
 * family's engine-wide table (cmd_dual_engine.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_threads.h"
#include "plot.h"

static void dual_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf dual [options] [--thetas N] [--density D] [--by-lobe] [--svg FILE [--plot TERMS]]\n"
                "       hairbsdf dual [options] [--thetas N] [--density D] --save FILE.hbdt\n"
                "       hairbsdf dual [options] --engine [--thetas N] [--roughnesses R] [--absorptions A]\n"
                "                     [--sampled D,Z] [--density D] [--save FILE.hbde]\n"
                "Prints, per channel at N inclinations theta of the light (the midpoints of N equal parts\n"
                "of (-pi/2, pi/2), default 64): the forward and backward energies a_f, a_b, their mean\n"
                "theta_h alpha_f, alpha_b and variances beta_f2, beta_b2, and the multiple back-scattering\n"
                "A_b, delta_b, sigma_b2 with the density factor D (default 0.7). With --by-lobe, each\n"
                "lobe's part of a_f and a_b follows (hb_dual_lobe_energies). --svg FILE also plots the terms\n"
                "TERMS (a comma list of the names above, default a_f,a_b) per channel against theta.\n"
                "--threads N computes the rows on N threads (hb_dual_terms_grid), the same numbers.\n"
                "--save FILE writes the material's table at N nodes (hb_dual_table_save; default 64) for an\n"
                "engine to load (hb_dual_table_load; hairbsdf eval --dual-table FILE) instead of the CSV.\n"
                "--engine makes the engine-wide table of the material's family instead (hb_dual_engine_create:\n"
                "N thetas, --roughnesses R over [0.05, 0.6], default 16, --absorptions A up to 12, default 16;\n"
                "--sampled D,Z by the engines' estimate at D directions and Z azimuths, HDRP's 128,90) and\n"
                "prints its nodes (roughness, sigma_a, theta, a_f, a_b, alpha_f, beta_f2, alpha_b, beta_b2),\n"
                "or with --save FILE writes it (hb_dual_engine_save; hairbsdf eval --dual-engine FILE).\n%s",
            cli_model_options_help);
}

static const char *const term_names[] = { "a_f", "a_b", "alpha_f", "beta_f2", "alpha_b", "beta_b2", "A_b", "delta_b", "sigma_b2" };

/* What the table holds: the plan's terms at `thetas` inclinations, on *threads threads. */
typedef struct dual_request {
    const hb_plan *plan;
    int thetas;
    double density;
    int by_lobe;
    int *threads;
} dual_request;

/* The table: a header, then one row per theta. 0, or 1 (out of memory) or 2 (a refusal), said on stderr. */
static int dual_table(FILE *out, void *request)
{
    const dual_request *q = request;
    const hb_plan *plan = q->plan;
    int thetas = q->thetas, by_lobe = q->by_lobe;
    fprintf(out, "theta");
    for (size_t k = 0; k < sizeof term_names / sizeof term_names[0]; k++)
        fprintf(out, ",%s_r,%s_g,%s_b", term_names[k], term_names[k], term_names[k]);
    double forward[HB_MAX_LOBES + 1][3], backward[HB_MAX_LOBES + 1][3];
    unsigned lobes = 0; /* the lobes with energy at the first theta: the plan's set */
    if (by_lobe) {
        if (hb_dual_lobe_energies(plan, -M_PI_2 + M_PI * 0.5 / thetas, forward, backward) != HB_OK) {
            fprintf(stderr, "hairbsdf dual: %s\n", hb_last_error()->message);
            return 2;
        }
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
            if (forward[p][1] > 0.0 || backward[p][1] > 0.0) {
                lobes |= HB_LOBE_BIT(p);
                for (int h = 0; h < 2; h++)
                    fprintf(out, ",%s_%s_r,%s_%s_g,%s_%s_b", h ? "a_b" : "a_f", cli_lobe_name(p), h ? "a_b" : "a_f",
                            cli_lobe_name(p), h ? "a_b" : "a_f", cli_lobe_name(p));
            }
    }
    fprintf(out, "\n");
    hb_dual_terms *grid = calloc((size_t)thetas, sizeof *grid);
    if (!grid) {
        fprintf(stderr, "hairbsdf dual: out of memory\n");
        return 1;
    }
    grid[0].struct_size = sizeof *grid; /* the rows on --threads threads (the CLI's job system) */
    hb_dual_terms_grid(plan, thetas, q->density, grid, NULL, NULL, *q->threads > 1 ? cli_parallel : NULL, q->threads);
    for (int k = 0; k < thetas; k++) {
        double theta = -M_PI_2 + M_PI * (k + 0.5) / thetas;
        const hb_dual_terms d = grid[k];
        const double *columns[] = { d.a_f, d.a_b, d.alpha_f, d.beta_f2, d.alpha_b, d.beta_b2, d.A_b, d.delta_b, d.sigma_b2 };
        fprintf(out, "%.6f", theta);
        for (size_t c = 0; c < sizeof columns / sizeof columns[0]; c++)
            fprintf(out, ",%.6g,%.6g,%.6g", columns[c][0], columns[c][1], columns[c][2]);
        if (lobes && hb_dual_lobe_energies(plan, theta, forward, backward) == HB_OK)
            for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
                if (lobes >> p & 1u)
                    fprintf(out, ",%.6g,%.6g,%.6g,%.6g,%.6g,%.6g", forward[p][0], forward[p][1], forward[p][2],
                            backward[p][0], backward[p][1], backward[p][2]);
        fprintf(out, "\n");
    }
    free(grid);
    return 0;
}

/* TERMS as plot columns (each name's _r, _g, _b) and the y axis's label from the terms' kind
 * (energies, shifts in radians, variances in radians squared). 0, or -1 for a name not a term. */
static int plot_columns(const char *terms, char *columns, size_t size, const char **y_label)
{
    static const char kind_of[] = { 'e', 'e', 'r', 's', 'r', 's', 'e', 'r', 's' }; /* per term_names */
    char kind = 0;
    size_t used = 0;
    columns[0] = '\0';
    for (const char *p = terms; *p;) {
        size_t len = strcspn(p, ",");
        size_t k = 0;
        while (k < sizeof term_names / sizeof term_names[0] && !(strlen(term_names[k]) == len && !strncmp(p, term_names[k], len)))
            k++;
        if (k == sizeof term_names / sizeof term_names[0])
            return -1;
        kind = !kind || kind == kind_of[k] ? kind_of[k] : 'm';
        int n = snprintf(columns + used, size - used, "%s%s_r,%s_g,%s_b", used ? "," : "", term_names[k], term_names[k],
                         term_names[k]);
        if (n < 0 || (size_t)n >= size - used)
            return -1;
        used += (size_t)n;
        p += len + (p[len] == ',');
    }
    *y_label = kind == 'e' ? "energy (fraction of the light arriving)"
               : kind == 'r' ? "shift of theta_h (radians)"
               : kind == 's' ? "variance of theta_h (radians squared)"
                             : "value (energies; radians; radians squared)";
    return used ? 0 : -1;
}

/* --save: the plan's table at `thetas` nodes (at least 2) into a file; 0, or 1 (it cannot be written) or
 * 2 (a refusal), said on stderr. */
static int save_table(const hb_plan *plan, int thetas, double density, int *threads, const char *path)
{
    hb_dual_table *table = NULL;
    size_t size = 0;
    if (hb_dual_table_create(plan, thetas < 2 ? 2 : thetas, density, density, NULL, NULL, cli_parallel, threads,
                             &table) != HB_OK ||
        hb_dual_table_save(table, NULL, 0, &size) != HB_OK) {
        fprintf(stderr, "hairbsdf dual: %s\n", hb_last_error()->message);
        hb_dual_table_destroy(table);
        return 2;
    }
    void *bytes = malloc(size);
    int st = bytes && hb_dual_table_save(table, bytes, size, &size) == HB_OK ? 0 : 2;
    hb_dual_table_destroy(table);
    FILE *f = st ? NULL : fopen(path, "wb");
    if (!st) {
        int written = f && fwrite(bytes, 1, size, f) == size;
        if ((f && fclose(f) != 0) || !written) {
            fprintf(stderr, "hairbsdf dual: cannot write %s\n", path);
            st = 1;
        }
    }
    free(bytes);
    return st;
}

int cmd_dual(int argc, char **argv)
{
    cli_model_args args;
    cli_model_args_default(&args);
    int thetas = 64, by_lobe = 0, engine = 0, roughnesses = 16, absorptions = 16, sampled[2] = { 0, 0 };
    double density = HB_DUAL_DENSITY;
    const char *svg = NULL, *terms = "a_f,a_b", *save = NULL;
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            dual_usage(stdout);
            return 0;
        }
        char *end;
        if (strcmp(argv[i], "--by-lobe") == 0) {
            by_lobe = 1;
            continue;
        }
        if (strcmp(argv[i], "--engine") == 0) {
            engine = 1;
            continue;
        }
        if ((strcmp(argv[i], "--roughnesses") == 0 || strcmp(argv[i], "--absorptions") == 0) && i + 1 < argc) {
            long n = strtol(argv[i + 1], &end, 10);
            if (*end || n < 2 || n > 256) {
                fprintf(stderr, "hairbsdf dual: %s: '%s' is not a count in [2, 256]\n", argv[i], argv[i + 1]);
                return 2;
            }
            *(argv[i][2] == 'r' ? &roughnesses : &absorptions) = (int)n;
            i++;
            continue;
        }
        if (strcmp(argv[i], "--sampled") == 0 && i + 1 < argc) {
            if (sscanf(argv[++i], "%d,%d%c", &sampled[0], &sampled[1], &(char){ 0 }) != 2 || sampled[0] < 1 ||
                sampled[0] > 65536 || sampled[1] < 1 || sampled[1] > 65536) {
                fprintf(stderr, "hairbsdf dual: --sampled: '%s' is not D,Z with counts in [1, 65536]\n", argv[i]);
                return 2;
            }
            continue;
        }
        if (strcmp(argv[i], "--svg") == 0 && i + 1 < argc) {
            svg = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--save") == 0 && i + 1 < argc) {
            save = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--plot") == 0 && i + 1 < argc) {
            terms = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--thetas") == 0 && i + 1 < argc) {
            long n = strtol(argv[++i], &end, 10);
            if (*end || n < 1 || n > 4096) {
                fprintf(stderr, "hairbsdf dual: --thetas: '%s' is not a count in [1, 4096]\n", argv[i]);
                return 2;
            }
            thetas = (int)n;
            continue;
        }
        if (strcmp(argv[i], "--density") == 0 && i + 1 < argc) {
            density = strtod(argv[++i], &end);
            if (*end || !(density >= 0.0 && density <= 1.0)) {
                fprintf(stderr, "hairbsdf dual: --density: '%s' is not in [0, 1]\n", argv[i]);
                return 2;
            }
            continue;
        }
        int r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
        if (r <= 0) {
            fprintf(stderr, "hairbsdf dual: %s\n", r < 0 ? err : "unknown option (see hairbsdf dual --help)");
            return 2;
        }
    }
    if (engine) {
        if (svg || by_lobe) {
            fprintf(stderr, "hairbsdf dual: --engine prints or saves its nodes; --svg and --by-lobe are for one material\n");
            return 2;
        }
        return cmd_dual_engine(&args, thetas < 2 ? 2 : thetas, roughnesses, absorptions, sampled, density, save);
    }
    char columns[512];
    const char *y_label = NULL;
    if (svg && plot_columns(terms, columns, sizeof columns, &y_label) != 0) {
        fprintf(stderr, "hairbsdf dual: --plot: '%s' is not a comma list of a_f, a_b, alpha_f, beta_f2, alpha_b, beta_b2, "
                        "A_b, delta_b, sigma_b2\n", terms);
        return 2;
    }
    hb_plan *plan;
    hb_error e;
    if (cli_plan_create(&args, &args.options, &plan, &e) != HB_OK) {
        fprintf(stderr, "hairbsdf dual: %s\n", e.message);
        return 2;
    }
    dual_request q = { plan, thetas, density, by_lobe, &args.threads };
    int st;
    if (save) {
        st = save_table(plan, thetas, density, &args.threads, save);
    } else if (!svg) {
        st = dual_table(stdout, &q);
    } else { /* the same table, printed and plotted */
        char title[200];
        snprintf(title, sizeof title, "hairbsdf dual: %s (eumelanin %.2g, pheomelanin %.2g), %s against the light's inclination",
                 cli_model_paper(args.options.model), args.material.eumelanin, args.material.pheomelanin, terms);
        st = plot_table(dual_table, &q, svg, title, "theta", columns, "theta of the light (radians)", y_label, err, sizeof err);
        if (st && err[0])
            fprintf(stderr, "hairbsdf dual: --svg: %s\n", err);
    }
    hb_plan_destroy(plan);
    return st;
}

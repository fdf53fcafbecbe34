/* hairbsdf plot: an SVG plot of a CSV table, the bench's accuracy-vs-time results (with each
 * ISA's Pareto front) or any table with a numeric column to plot against (the furnace's). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "plot.h"

static void plot_usage(FILE *to)
{
    fprintf(to, "usage: hairbsdf plot FILE.csv|- -o FILE.svg [--title T] [--x COLUMN] [--y COLUMN,...]\n"
                "A bench results file (" BENCH_CSV_HEADER ") becomes error against time on\n"
                "log axes with each ISA's Pareto front; any other table becomes lines of its numeric columns\n"
                "against --x (default: the first numeric column), one set per value of its first text column.\n");
}

int cmd_plot(int argc, char **argv)
{
    const char *input = NULL, *path = NULL, *title = NULL, *x = NULL, *y = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            plot_usage(stdout);
            return 0;
        }
        const char **value = strcmp(a, "-o") == 0 ? &path : strcmp(a, "--title") == 0 ? &title
                           : strcmp(a, "--x") == 0 ? &x : strcmp(a, "--y") == 0 ? &y : NULL;
        if (value && i + 1 < argc) {
            *value = argv[++i];
        } else if (!value && !input && (a[0] != '-' || strcmp(a, "-") == 0)) {
            input = a;
        } else {
            fprintf(stderr, "hairbsdf plot: unexpected '%s' (see hairbsdf plot --help)\n", a);
            return 2;
        }
    }
    if (!input || !path) {
        fprintf(stderr, "hairbsdf plot: an input CSV (or -) and -o FILE.svg are required\n");
        return 2;
    }
    FILE *in = strcmp(input, "-") == 0 ? stdin : fopen(input, "r");
    if (!in) {
        fprintf(stderr, "hairbsdf plot: cannot read %s\n", input);
        return 2;
    }
    char err[256];
    int st = plot_csv(in, path, title ? title : input, x, y, NULL, NULL, err, sizeof err);
    if (in != stdin)
        fclose(in);
    if (st != 0)
        fprintf(stderr, "hairbsdf plot: %s: %s\n", input, err);
    return st != 0 ? 2 : 0;
}

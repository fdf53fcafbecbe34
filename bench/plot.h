/* Results of a bench run as CSV and as an SVG plot of error against time with the Pareto fronts. */
#ifndef HB_BENCH_PLOT_H
#define HB_BENCH_PLOT_H

typedef struct bench_point {
    const char *label; /* term/variant */
    const char *isa;
    double ns, error;
} bench_point;

int bench_write_csv(const char *path, const bench_point *points, int n);
int bench_write_svg(const char *path, const char *title, const bench_point *points, int n);

#endif

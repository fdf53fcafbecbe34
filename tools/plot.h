/* SVG plots: the bench's error against time with each ISA's Pareto front, and line plots of
 * any CSV table (the furnace's energy curves), written without a library. */
#ifndef HB_PLOT_H
#define HB_PLOT_H

#include <stddef.h>
#include <stdio.h>

typedef struct bench_point {
    const char *label; /* term/variant */
    const char *isa;
    double ns, error;
} bench_point;

/* The bench's results: CSV with the header BENCH_CSV_HEADER, and the error-vs-time plot. */
#define BENCH_CSV_HEADER "configuration,isa,ns_per_sample,max_error"
int bench_write_csv(const char *path, const bench_point *points, int n);
int bench_write_svg(const char *path, const char *title, const bench_point *points, int n);

/* One curve of a line plot. */
typedef struct plot_series {
    const char *name;
    const double *x, *y;
    int n;
} plot_series;

/* Linear axes labelled x_label and y_label (units included), one coloured polyline with point marks
 * per series, a legend. */
int plot_write_lines_svg(const char *path, const char *title, const char *x_label, const char *y_label,
                         const plot_series *series, int count);

/* Reads a CSV table with a header row and plots it into path: a bench results file as
 * bench_write_svg; any other table as lines, x the column named x_column (NULL: the first numeric
 * column), one series per other numeric column (or the comma list y_columns), split by the value
 * of the first non-numeric column when there is one. The axes are labelled x_label and y_label
 * (NULL: the x column's name, and the y columns' names). Returns 0, or -1 with err filled. */
int plot_csv(FILE *csv, const char *path, const char *title, const char *x_column, const char *y_columns,
             const char *x_label, const char *y_label, char *err, size_t err_size);

/* A command's table, printed and plotted: rows(out, context) writes it (0 on success) to a temporary
 * file, which is copied to stdout and plotted into path as plot_csv. Returns rows' status, 1 with
 * err filled when the plot or the temporary file fails. */
typedef int plot_rows_fn(FILE *out, void *context);
int plot_table(plot_rows_fn *rows, void *context, const char *path, const char *title, const char *x_column,
               const char *y_columns, const char *x_label, const char *y_label, char *err, size_t err_size);

#endif

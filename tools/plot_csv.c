/* A CSV table (header row, comma-separated cells) into an SVG plot: `hairbsdf plot` and
 * `hairbsdf furnace --svg`. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csv.h"
#include "plot.h"

#define MAX_COLUMNS 32
#define MAX_GROUPS 16

typedef struct csv_table {
    char *header[MAX_COLUMNS];
    int columns, rows;
    char **cell; /* rows x columns, row-major; all strings live in `text` */
    char *text;
} csv_table;

static void table_free(csv_table *t)
{
    free(t->cell);
    free(t->text);
}

/* Splits line at commas into at most MAX_COLUMNS trimmed cells; returns the count. */
static int split(char *line, char **cells)
{
    int n = 0;
    for (char *s = line; n < MAX_COLUMNS;) {
        char *comma = strchr(s, ',');
        if (comma)
            *comma = '\0';
        cells[n++] = csv_trim(s);
        if (!comma)
            break;
        s = comma + 1;
    }
    return n;
}

static int read_table(FILE *in, csv_table *t, char *err, size_t err_size)
{
    memset(t, 0, sizeof *t);
    size_t size = 0, used = 0;
    for (int ch; (ch = fgetc(in)) != EOF;) {
        if (used + 2 > size) {
            char *grown = realloc(t->text, size = size ? 2 * size : 4096);
            if (!grown)
                return snprintf(err, err_size, "out of memory"), -1;
            t->text = grown;
        }
        t->text[used++] = (char)ch;
    }
    if (!used)
        return snprintf(err, err_size, "empty input"), -1;
    t->text[used] = '\0';
    int lines = 0;
    for (size_t k = 0; k < used; k++)
        lines += t->text[k] == '\n';
    t->cell = malloc(((size_t)lines + 1) * MAX_COLUMNS * sizeof *t->cell);
    if (!t->cell)
        return snprintf(err, err_size, "out of memory"), -1;
    char *save = NULL;
    for (char *line = strtok_r(t->text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        if (!*csv_trim(line))
            continue;
        if (!t->columns) {
            t->columns = split(line, t->header);
            continue;
        }
        char **row = t->cell + (size_t)t->rows * MAX_COLUMNS;
        if (split(line, row) != t->columns)
            return snprintf(err, err_size, "row %d has not %d cells like the header", t->rows + 2, t->columns), -1;
        t->rows++;
    }
    if (!t->rows)
        return snprintf(err, err_size, "no rows below the header"), -1;
    return 0;
}

static const char *cell(const csv_table *t, int row, int column) { return t->cell[(size_t)row * MAX_COLUMNS + column]; }

static int parse_number(const char *s, double *x)
{
    char *end;
    *x = strtod(s, &end);
    return end != s && !*end && isfinite(*x);
}

static int column_numeric(const csv_table *t, int column)
{
    double x;
    for (int r = 0; r < t->rows; r++)
        if (!parse_number(cell(t, r, column), &x))
            return 0;
    return 1;
}

static int column_named(const csv_table *t, const char *name)
{
    for (int c = 0; c < t->columns; c++)
        if (strcmp(t->header[c], name) == 0)
            return c;
    return -1;
}

static int plot_bench(const csv_table *t, const char *path, const char *title, char *err, size_t err_size)
{
    bench_point *points = malloc((size_t)t->rows * sizeof *points);
    if (!points)
        return snprintf(err, err_size, "out of memory"), -1;
    for (int r = 0; r < t->rows; r++) {
        points[r] = (bench_point){ cell(t, r, 0), cell(t, r, 1), 0.0, 0.0 };
        if (!parse_number(cell(t, r, 2), &points[r].ns) || !(points[r].ns > 0.0)) {
            free(points);
            return snprintf(err, err_size, "row %d: ns_per_sample '%s'", r + 2, cell(t, r, 2)), -1;
        }
        if (!parse_number(cell(t, r, 3), &points[r].error)) /* rows without an error (nan) plot at the floor */
            points[r].error = 0.0;
    }
    int st = bench_write_svg(path, title, points, t->rows);
    free(points);
    return st ? (snprintf(err, err_size, "cannot write %s", path), -1) : 0;
}

int plot_csv(FILE *csv, const char *path, const char *title, const char *x_column, const char *y_columns,
             const char *x_label, const char *y_label, char *err, size_t err_size)
{
    csv_table t;
    if (read_table(csv, &t, err, err_size) != 0) {
        table_free(&t);
        return -1;
    }
    if (t.columns == 4 && !strcmp(t.header[0], "configuration") && !strcmp(t.header[1], "isa") &&
        !strcmp(t.header[2], "ns_per_sample") && !strcmp(t.header[3], "max_error")) {
        int st = plot_bench(&t, path, title, err, err_size);
        table_free(&t);
        return st;
    }
    int numeric[MAX_COLUMNS], x = -1, group = -1, wanted[MAX_COLUMNS] = { 0 };
    for (int c = 0; c < t.columns; c++) {
        numeric[c] = column_numeric(&t, c);
        if (numeric[c] && x < 0 && !x_column)
            x = c;
        if (!numeric[c] && group < 0)
            group = c;
    }
    if (x_column && (x = column_named(&t, x_column)) < 0)
        return snprintf(err, err_size, "no column named '%s'", x_column), table_free(&t), -1;
    if (x < 0 || !numeric[x])
        return snprintf(err, err_size, "no numeric x column"), table_free(&t), -1;
    char names[512];
    snprintf(names, sizeof names, "%s", y_columns ? y_columns : "");
    char *save = NULL;
    for (char *name = strtok_r(names, ",", &save); y_columns && name; name = strtok_r(NULL, ",", &save)) {
        int c = column_named(&t, csv_trim(name));
        if (c < 0 || !numeric[c])
            return snprintf(err, err_size, "no numeric column named '%s'", name), table_free(&t), -1;
        wanted[c] = 1;
    }
    for (int c = 0; !y_columns && c < t.columns; c++)
        wanted[c] = numeric[c] && c != x;
    const char *groups[MAX_GROUPS];
    int ngroups = 0;
    for (int r = 0; r < t.rows && group >= 0; r++) {
        int seen = 0;
        for (int g = 0; g < ngroups; g++)
            seen |= strcmp(groups[g], cell(&t, r, group)) == 0;
        if (!seen && ngroups == MAX_GROUPS)
            return snprintf(err, err_size, "more than %d values in column '%s'", MAX_GROUPS, t.header[group]),
                   table_free(&t), -1;
        if (!seen)
            groups[ngroups++] = cell(&t, r, group);
    }
    if (group < 0)
        ngroups = 1;
    plot_series series[MAX_COLUMNS * MAX_GROUPS];
    char labels[MAX_COLUMNS * MAX_GROUPS][96];
    double *values = malloc((size_t)ngroups * MAX_COLUMNS * 2 * (size_t)t.rows * sizeof *values);
    if (!values)
        return snprintf(err, err_size, "out of memory"), table_free(&t), -1;
    int count = 0;
    for (int g = 0; g < ngroups; g++)
        for (int c = 0; c < t.columns; c++) {
            if (!wanted[c])
                continue;
            double *xs = values + (size_t)count * 2 * t.rows, *ys = xs + t.rows;
            int n = 0;
            for (int r = 0; r < t.rows; r++)
                if (group < 0 || strcmp(cell(&t, r, group), groups[g]) == 0) {
                    parse_number(cell(&t, r, x), &xs[n]);
                    parse_number(cell(&t, r, c), &ys[n++]);
                }
            snprintf(labels[count], sizeof labels[count], "%s%s%s", group < 0 ? "" : groups[g], group < 0 ? "" : " ",
                     t.header[c]);
            series[count] = (plot_series){ labels[count], xs, ys, n };
            count++;
        }
    char names_label[256] = "";
    for (int c = 0; !y_label && c < t.columns; c++) /* the y columns' names */
        if (wanted[c])
            snprintf(names_label + strlen(names_label), sizeof names_label - strlen(names_label), "%s%s",
                     *names_label ? ", " : "", t.header[c]);
    int st = plot_write_lines_svg(path, title, x_label ? x_label : t.header[x], y_label ? y_label : names_label, series,
                                  count);
    free(values);
    table_free(&t);
    if (st)
        return snprintf(err, err_size, "cannot write %s", path), -1;
    return 0;
}

int plot_table(plot_rows_fn *rows, void *context, const char *path, const char *title, const char *x_column,
               const char *y_columns, const char *x_label, const char *y_label, char *err, size_t err_size)
{
    FILE *table = tmpfile(); /* the table, written, copied and read back */
    if (!table) {
        snprintf(err, err_size, "cannot open a temporary file for the table");
        return 1;
    }
    int st = rows(table, context);
    if (st == 0) {
        rewind(table);
        for (int c; (c = getc(table)) != EOF;)
            putchar(c);
        rewind(table);
        if (plot_csv(table, path, title, x_column, y_columns, x_label, y_label, err, err_size) != 0)
            st = 1;
    } else {
        err[0] = '\0';
    }
    fclose(table);
    return st;
}

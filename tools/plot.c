#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plot.h"

static const char *const colours[] = { "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                       "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf" };
#define COLOURS ((int)(sizeof colours / sizeof colours[0]))

/* An SVG of W x H on white with the title at the top left; NULL if the file cannot be opened. */
static FILE *svg_open(const char *path, double W, double H, double left, const char *title)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return NULL;
    fprintf(f, "<svg xmlns='http://www.w3.org/2000/svg' width='%.0f' height='%.0f' font-family='sans-serif' "
               "font-size='11'>\n<rect width='100%%' height='100%%' fill='white'/>\n", W, H);
    fprintf(f, "<text x='%.0f' y='20' font-size='13'>%s</text>\n", left, title);
    return f;
}

int bench_write_csv(const char *path, const bench_point *p, int n)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fprintf(f, BENCH_CSV_HEADER "\n");
    for (int k = 0; k < n; k++)
        fprintf(f, "%s,%s,%.3f,%.3e\n", p[k].label, p[k].isa, p[k].ns, p[k].error);
    return fclose(f);
}

/* Log-log axes: x = ns/sample, y = max error (floored at 1e-8). The Pareto front of each ISA
 * (no other point of that ISA is both faster and more accurate) is joined by a line. */
int bench_write_svg(const char *path, const char *title, const bench_point *p, int n)
{
    const double W = 720, H = 460, left = 70, right = 170, top = 40, bottom = 50;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int k = 0; k < n; k++) {
        x0 = fmin(x0, log10(p[k].ns)), x1 = fmax(x1, log10(p[k].ns));
        double e = log10(fmax(p[k].error, 1e-8));
        y0 = fmin(y0, e), y1 = fmax(y1, e);
    }
    x0 = floor(x0), x1 = ceil(x1), y0 = floor(y0), y1 = ceil(y1);
    if (x1 <= x0) x1 = x0 + 1;
    if (y1 <= y0) y1 = y0 + 1;
#define PX(v) (left + (log10(v) - x0) / (x1 - x0) * (W - left - right))
#define PY(e) (top + (y1 - log10(fmax(e, 1e-8))) / (y1 - y0) * (H - top - bottom))
    FILE *f = svg_open(path, W, H, left, title);
    if (!f)
        return -1;
    for (double d = x0; d <= x1; d += 1) /* decades */
        fprintf(f, "<line x1='%.1f' y1='%.0f' x2='%.1f' y2='%.0f' stroke='#ddd'/><text x='%.1f' y='%.0f' "
                   "text-anchor='middle'>%g ns</text>\n", PX(pow(10, d)), top, PX(pow(10, d)), H - bottom,
                PX(pow(10, d)), H - bottom + 15, pow(10, d));
    for (double d = y0; d <= y1; d += 1)
        fprintf(f, "<line x1='%.0f' y1='%.1f' x2='%.0f' y2='%.1f' stroke='#ddd'/><text x='%.0f' y='%.1f' "
                   "text-anchor='end'>1e%g</text>\n", left, PY(pow(10, d)), W - right, PY(pow(10, d)), left - 5,
                PY(pow(10, d)) + 4, d);
    fprintf(f, "<text x='%.0f' y='%.0f' text-anchor='middle'>time per sample (one core, log)</text>\n",
            (left + W - right) / 2, H - 12);
    fprintf(f, "<text x='15' y='%.0f' transform='rotate(-90 15 %.0f)' text-anchor='middle'>max error vs double "
               "reference (log)</text>\n", (top + H - bottom) / 2, (top + H - bottom) / 2);
    const char *isas[8];
    int nisa = 0;
    for (int k = 0; k < n; k++) {
        int seen = 0;
        for (int j = 0; j < nisa; j++)
            seen |= strcmp(isas[j], p[k].isa) == 0;
        if (!seen && nisa < 8)
            isas[nisa++] = p[k].isa;
    }
    for (int j = 0; j < nisa; j++) {
        const char *c = colours[j % COLOURS];
        fprintf(f, "<polyline fill='none' stroke='%s' stroke-width='1.5' points='", c);
        for (;;) { /* Pareto front: walk from the fastest point to ever more accurate ones */
            double last_ns = -1.0, best_err = INFINITY;
            for (int step = 0; step < n; step++) {
                int next = -1;
                for (int k = 0; k < n; k++)
                    if (!strcmp(p[k].isa, isas[j]) && p[k].ns > last_ns && p[k].error < best_err &&
                        (next < 0 || p[k].ns < p[next].ns))
                        next = k;
                if (next < 0)
                    break;
                fprintf(f, "%.1f,%.1f ", PX(p[next].ns), PY(p[next].error));
                last_ns = p[next].ns, best_err = p[next].error;
            }
            break;
        }
        fprintf(f, "'/>\n");
        for (int k = 0; k < n; k++)
            if (!strcmp(p[k].isa, isas[j]))
                fprintf(f, "<circle cx='%.1f' cy='%.1f' r='3.5' fill='%s'><title>%s %s: %.3g ns, %.2g</title>"
                           "</circle>\n", PX(p[k].ns), PY(p[k].error), c, p[k].label, p[k].isa, p[k].ns, p[k].error);
        fprintf(f, "<circle cx='%.0f' cy='%.0f' r='4' fill='%s'/><text x='%.0f' y='%.0f'>%s</text>\n", W - right + 20,
                top + 18.0 * j, c, W - right + 30, top + 18.0 * j + 4, isas[j]);
    }
    /* label each configuration once, at its fastest ISA, moved down a line at a time past the labels
     * already placed that it would overlap (9 px type: about 5 px a character, 11 px a line) */
    enum { MAX_LABELS = 64 };
    double placed[MAX_LABELS][3]; /* x, y (baseline), width */
    int nplaced = 0;
    for (int k = 0; k < n; k++) {
        if (strcmp(p[k].isa, isas[nisa - 1]))
            continue;
        double x = PX(p[k].ns) + 5, y = PY(p[k].error) - 5, w = 5.0 * (double)strlen(p[k].label);
        for (int moved = 1; moved;) {
            moved = 0;
            for (int j = 0; j < nplaced; j++)
                if (x < placed[j][0] + placed[j][2] && placed[j][0] < x + w && fabs(y - placed[j][1]) < 11.0) {
                    y = placed[j][1] + 11.0;
                    moved = 1;
                }
        }
        if (nplaced < MAX_LABELS)
            placed[nplaced][0] = x, placed[nplaced][1] = y, placed[nplaced++][2] = w;
        fprintf(f, "<text x='%.1f' y='%.1f' font-size='9' fill='#444'>%s</text>\n", x, y, p[k].label);
    }
    fprintf(f, "</svg>\n");
#undef PX
#undef PY
    return fclose(f);
}

/* A round step of about a fifth of the range (1, 2 or 5 times a power of ten). */
static double tick_step(double range)
{
    double raw = range / 5.0, decade = pow(10.0, floor(log10(raw))), m = raw / decade;
    return decade * (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0);
}

int plot_write_lines_svg(const char *path, const char *title, const char *x_label, const char *y_label,
                         const plot_series *s, int count)
{
    const double W = 760, H = 460, left = 80, right = 190, top = 40, bottom = 50;
    double x0 = INFINITY, x1 = -INFINITY, y0 = 0.0, y1 = -INFINITY; /* y from 0: energies and shares */
    for (int j = 0; j < count; j++)
        for (int k = 0; k < s[j].n; k++) {
            x0 = fmin(x0, s[j].x[k]), x1 = fmax(x1, s[j].x[k]);
            y0 = fmin(y0, s[j].y[k]), y1 = fmax(y1, s[j].y[k]);
        }
    if (!(x1 > x0))
        x0 -= 0.5, x1 = x0 + 1.0;
    if (!(y1 > y0))
        y1 = y0 + 1.0;
    double dx = tick_step(x1 - x0), dy = tick_step(y1 - y0);
    x0 = floor(x0 / dx) * dx, x1 = ceil(x1 / dx) * dx, y0 = floor(y0 / dy) * dy, y1 = ceil(y1 / dy) * dy;
#define LX(v) (left + ((v) - x0) / (x1 - x0) * (W - left - right))
#define LY(v) (top + (y1 - (v)) / (y1 - y0) * (H - top - bottom))
    FILE *f = svg_open(path, W, H, left, title);
    if (!f)
        return -1;
    for (double v = x0; v <= x1 + 0.5 * dx; v += dx)
        fprintf(f, "<line x1='%.1f' y1='%.0f' x2='%.1f' y2='%.0f' stroke='#ddd'/><text x='%.1f' y='%.0f' "
                   "text-anchor='middle'>%g</text>\n", LX(v), top, LX(v), H - bottom, LX(v), H - bottom + 15,
                fabs(v) < 1e-9 * dx ? 0.0 : v);
    for (double v = y0; v <= y1 + 0.5 * dy; v += dy)
        fprintf(f, "<line x1='%.0f' y1='%.1f' x2='%.0f' y2='%.1f' stroke='#ddd'/><text x='%.0f' y='%.1f' "
                   "text-anchor='end'>%g</text>\n", left, LY(v), W - right, LY(v), left - 5, LY(v) + 4,
                fabs(v) < 1e-9 * dy ? 0.0 : v);
    fprintf(f, "<text x='%.0f' y='%.0f' text-anchor='middle'>%s</text>\n", (left + W - right) / 2, H - 12, x_label);
    fprintf(f, "<text x='15' y='%.0f' transform='rotate(-90 15 %.0f)' text-anchor='middle'>%s</text>\n",
            (top + H - bottom) / 2, (top + H - bottom) / 2, y_label);
    for (int j = 0; j < count; j++) {
        const char *c = colours[j % COLOURS];
        fprintf(f, "<polyline fill='none' stroke='%s' stroke-width='1.5'%s points='", c,
                j >= COLOURS ? " stroke-dasharray='5,3'" : "");
        for (int k = 0; k < s[j].n; k++)
            fprintf(f, "%.1f,%.1f ", LX(s[j].x[k]), LY(s[j].y[k]));
        fprintf(f, "'/>\n");
        for (int k = 0; k < s[j].n; k++)
            fprintf(f, "<circle cx='%.1f' cy='%.1f' r='2.5' fill='%s'><title>%s: %g, %g</title></circle>\n",
                    LX(s[j].x[k]), LY(s[j].y[k]), c, s[j].name, s[j].x[k], s[j].y[k]);
        fprintf(f, "<line x1='%.0f' y1='%.0f' x2='%.0f' y2='%.0f' stroke='%s' stroke-width='2'/><text x='%.0f' "
                   "y='%.0f'>%s</text>\n", W - right + 12, top + 16.0 * j, W - right + 28, top + 16.0 * j, c,
                W - right + 34, top + 16.0 * j + 4, s[j].name);
    }
    fprintf(f, "</svg>\n");
#undef LX
#undef LY
    return fclose(f);
}

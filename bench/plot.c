#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plot.h"

int bench_write_csv(const char *path, const bench_point *p, int n)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fprintf(f, "configuration,isa,ns_per_sample,max_error\n");
    for (int k = 0; k < n; k++)
        fprintf(f, "%s,%s,%.3f,%.3e\n", p[k].label, p[k].isa, p[k].ns, p[k].error);
    return fclose(f);
}

/* Log-log axes: x = ns/sample, y = max error (floored at 1e-8). The Pareto front of each ISA
 * (no other point of that ISA is both faster and more accurate) is joined by a line. */
int bench_write_svg(const char *path, const char *title, const bench_point *p, int n)
{
    static const char *const colours[] = { "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd" };
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
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fprintf(f, "<svg xmlns='http://www.w3.org/2000/svg' width='%.0f' height='%.0f' font-family='sans-serif' "
               "font-size='11'>\n<rect width='100%%' height='100%%' fill='white'/>\n", W, H);
    fprintf(f, "<text x='%.0f' y='20' font-size='13'>%s</text>\n", left, title);
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
        const char *c = colours[j % 5];
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
    for (int k = 0; k < n; k++) /* label each configuration once, at its fastest ISA */
        if (!strcmp(p[k].isa, isas[nisa - 1]))
            fprintf(f, "<text x='%.1f' y='%.1f' font-size='9' fill='#444'>%s</text>\n", PX(p[k].ns) + 5,
                    PY(p[k].error) - 5, p[k].label);
    fprintf(f, "</svg>\n");
#undef PX
#undef PY
    return fclose(f);
}

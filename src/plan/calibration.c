/* The calibration table: built in (src/calibration_builtin.h, made by `make calibration` from the
 * bench/results/calibration.csv of the last full `make bench` run, docs/benchmarks.md), or read from such a CSV.
 * Rows with the clock they were measured at are costs in cycles, taken at the running clock. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibration.h"
#include "models/interface/plan.h"

static const hb_calibration_entry builtin[] = {
#include "calibration_builtin.h"
};

static hb_status bad_file(hb_error *error, const char *path, int line, const char *what, hb_calibration *c)
{
    hb_calibration_close(c);
    return hb_plan_fail(error, HB_ERR_PARAM, "calibration %s, line %d: %s", path, line, what);
}

hb_status hb_calibration_open(const char *path, hb_calibration *c, hb_error *error)
{
    *c = (hb_calibration){ builtin, (int)(sizeof builtin / sizeof builtin[0]), NULL, hb_cpu_clock_ghz() };
    if (!path)
        return HB_OK;
    double ghz = c->ghz;
    FILE *f = fopen(path, "r");
    if (!f)
        return bad_file(error, path, 0, "cannot be read", c);
    char line[512];
    int capacity = 0, n = 0, number = 0;
    hb_calibration_entry *rows = NULL;
    *c = (hb_calibration){ NULL, 0, NULL, 0.0 };
    int columns = 0; /* 6 with the clock, 5 in files of benches that did not measure it */
    while (fgets(line, sizeof line, f)) {
        number++;
        if (number == 1) {
            static const char header[] = "model,configuration,isa,ns_per_sample,max_error";
            if (strncmp(line, header, sizeof header - 1) != 0) {
                fclose(f);
                return bad_file(error, path, 1, "the header is not model,configuration,isa,ns_per_sample,max_error[,ghz]",
                                c);
            }
            columns = strncmp(line + sizeof header - 1, ",ghz", 4) == 0 ? 6 : 5;
            continue;
        }
        if (line[0] == '\n' || line[0] == '\0')
            continue;
        if (n == capacity) {
            hb_calibration_entry *grown = realloc(rows, (size_t)(capacity = capacity ? 2 * capacity : 64) * sizeof *rows);
            if (!grown) {
                free(rows), fclose(f);
                return bad_file(error, path, number, "out of memory", c);
            }
            rows = grown;
        }
        hb_calibration_entry *e = &rows[n];
        e->ghz = 0.0;
        if (sscanf(line, "%15[^,],%31[^,],%15[^,],%lf,%lf,%lf", e->model, e->configuration, e->isa, &e->ns, &e->error,
                   &e->ghz) != columns ||
            !(e->ns > 0.0) || !(e->ghz >= 0.0)) {
            free(rows), fclose(f);
            return bad_file(error, path, number,
                            columns == 6 ? "not model,configuration,isa,ns,error,ghz with ns > 0 and ghz >= 0"
                                         : "not model,configuration,isa,ns,error with ns > 0",
                            c);
        }
        n++;
    }
    fclose(f);
    *c = (hb_calibration){ rows, n, rows, ghz };
    return HB_OK;
}

void hb_calibration_close(hb_calibration *c)
{
    free(c->owned);
    *c = (hb_calibration){ NULL, 0, NULL, 0.0 };
}

double hb_calibration_ns(const hb_calibration *c, const hb_calibration_entry *e)
{
    return e->ghz > 0.0 && c->ghz > 0.0 ? e->ns * e->ghz / c->ghz : e->ns;
}

const hb_calibration_entry *hb_calibration_find(const hb_calibration *c, const char *model, const char *configuration,
                                                const char *isa)
{
    for (int k = 0; k < c->count; k++)
        if (!strcmp(c->rows[k].model, model) && !strcmp(c->rows[k].configuration, configuration) &&
            !strcmp(c->rows[k].isa, isa))
            return &c->rows[k];
    return NULL;
}

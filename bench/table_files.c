/* Table files in the bench: plan creation that builds a table against plan creation from its file. */
#include <stdlib.h>

#include "clock.h"
#include "table_files.h"

enum { LOADS = 5 };

typedef struct table_config {
    const char *name;
    hb_model model;
    hb_quality quality;
    hb_azimuthal azimuthal; /* dFH11: its own table or the colour table */
} table_config;

void bench_table_files(const hb_material *m, FILE *report)
{
    static const table_config configs[] = {
        { "deon/full/table-balanced", HB_MODEL_DEON, HB_QUALITY_BALANCED, HB_AZIMUTHAL_TABLE },
        { "deon/full/table-high", HB_MODEL_DEON, HB_QUALITY_HIGH, HB_AZIMUTHAL_TABLE },
        { "deon/full/colour-table-fast", HB_MODEL_DEON, HB_QUALITY_FAST, HB_AZIMUTHAL_COLOUR_TABLE },
        { "deon/full/colour-table-balanced", HB_MODEL_DEON, HB_QUALITY_BALANCED, HB_AZIMUTHAL_COLOUR_TABLE },
        { "huang/all/table-fast", HB_MODEL_HUANG, HB_QUALITY_FAST, HB_AZIMUTHAL_QUADRATURE },
        { "huang/all/table-balanced", HB_MODEL_HUANG, HB_QUALITY_BALANCED, HB_AZIMUTHAL_QUADRATURE },
    };
    fprintf(report, "Table files (hb_table_save; plan creation that builds the table, then from its file):\n");
    for (size_t k = 0; k < sizeof configs / sizeof configs[0]; k++) {
        hb_options o;
        hb_options_default(&o);
        o.model = configs[k].model, o.quality = configs[k].quality;
        if (o.model == HB_MODEL_DEON)
            o.azimuthal = configs[k].azimuthal;
        else
            o.tt_trt = HB_TT_TRT_TABLE;
        hb_plan *plan;
        double t0 = now_ns();
        if (hb_plan_create(m, &o, &plan, NULL) != HB_OK)
            continue;
        double build_ms = (now_ns() - t0) * 1e-6, load_ms = 1e30;
        size_t size = 0;
        hb_table_save(plan, NULL, 0, &size);
        void *bytes = malloc(size);
        if (bytes && hb_table_save(plan, bytes, size, &size) == HB_OK) {
            o.table_file = bytes, o.table_file_size = size;
            for (int r = 0; r < LOADS; r++) {
                hb_plan *loaded;
                t0 = now_ns();
                if (hb_plan_create(m, &o, &loaded, NULL) != HB_OK)
                    break;
                double ms = (now_ns() - t0) * 1e-6;
                load_ms = ms < load_ms ? ms : load_ms;
                hb_plan_destroy(loaded);
            }
        }
        if (load_ms < 1e30)
            fprintf(report, "  %s (%s): %.0f KiB, built in %.1f ms, loaded in %.2f ms (%.0fx)\n", configs[k].name,
                    hb_isa_name(hb_plan_isa(plan)), (double)size / 1024.0, build_ms, load_ms, build_ms / load_ms);
        free(bytes);
        hb_plan_destroy(plan);
    }
}

/* Cost and accuracy of the named configurations a tolerance or budget plan chooses from: measured
 * by `make bench` (bench/results/calibration.csv), built in or loaded from such a file. Internal. */
#ifndef HB_CALIBRATION_H
#define HB_CALIBRATION_H

#include "hairbsdf.h"

typedef struct hb_calibration_entry {
    char model[16], configuration[32], isa[16];
    double ns, error; /* minimum ns per sample on one core; max error against the double reference */
    double ghz;       /* the clock hb_cpu_clock_ghz measured beside ns; 0: not measured */
} hb_calibration_entry;

typedef struct hb_calibration {
    const hb_calibration_entry *rows;
    int count;
    hb_calibration_entry *owned; /* rows read from a file */
    double ghz;                  /* the running core's clock (hb_cpu_clock_ghz); 0: not measured */
} hb_calibration;

/* path NULL: the built-in table. Fails with HB_ERR_PARAM (message: file and line) on a bad file. */
hb_status hb_calibration_open(const char *path, hb_calibration *calibration, hb_error *error);
void hb_calibration_close(hb_calibration *calibration);

/* An entry's cost in ns at the running clock: its cycles (ns x ghz) over calibration->ghz, or its
 * ns where either clock is unmeasured. */
double hb_calibration_ns(const hb_calibration *calibration, const hb_calibration_entry *entry);

/* The entry for (model, configuration) on isa; NULL if the file has none. */
const hb_calibration_entry *hb_calibration_find(const hb_calibration *calibration, const char *model,
                                                const char *configuration, const char *isa);

#endif

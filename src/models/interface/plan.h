/* The plan's data (struct hb_plan): the validated inputs, what a tolerance or budget plan chose,
 * and after them the model's own state (src/models/<model>/state.h). Written once at plan creation
 * (src/plan/create.c and the model's derive), read by every evaluation; also hb_plan_fail and
 * hb_fail, which word a failure. Internal. */
#ifndef HB_MODELS_PLAN_H
#define HB_MODELS_PLAN_H

#include <stddef.h>

#include "hairbsdf.h"
#include "simd/compiler.h"

/* What a tolerance or budget plan chose and why (src/plan/select.c), for hb_plan_describe. */
typedef struct hb_selection {
    int active;
    double tolerance, budget_ns;
    unsigned measured, dropped;         /* lobes measured at creation, lobes dropped */
    double share[HB_MAX_LOBES + 1];     /* each measured lobe's largest value over the peak of f */
    double dropped_bound;               /* twice the dropped lobes' summed shares */
    char configuration[32];             /* the chosen preset, as the bench names it */
    int preset;                         /* its index; bit k of refused: preset k failed to build */
    unsigned refused;
    char refusal[160];                  /* why the last refused preset failed */
    double expected_error, expected_ns; /* calibrated error plus dropped_bound; ns on the plan's ISA */
    int ranked_by_scalar;               /* the ISA has no calibration: figures are scalar x86's */
    char calibration[128];              /* "built in" or the file */
} hb_selection;

struct hb_plan {
    hb_material material;
    hb_options options;
    const void *kernels; /* the model's kernel table for the plan's ISA; NULL: the double reference */
    const void *narrow_kernels; /* the scalar ISA's table where the plan's ISA is wider, else NULL (model.h) */
    const struct hb_reference_ops *reference; /* the model's double-precision procedures (src/ref/reference.h) */
    hb_isa isa;
    double sigma_a[3];   /* sigma_a plus melanin */
    hb_selection selection; /* tolerance and budget plans */
    size_t table_file_size; /* the table file the table was loaded from (0: built); options.table_file is NULL */
    size_t state_size;      /* the bytes of state, the model's hb_model_ops.state_size */
    max_align_t state[];    /* the model's own state: hb_<model>_of (src/models/<model>/state.h) */
};

/* A failure (src/models/text/fail.c): records status and the formatted message as the calling
 * thread's last error (hb_last_error), copies it to error if not NULL, and returns status. */
hb_status hb_plan_fail(hb_error *error, hb_status status, const char *fmt, ...) HB_PRINTF_FORMAT(3, 4);
hb_status hb_fail(hb_status status, const char *fmt, ...) HB_PRINTF_FORMAT(2, 3);
/* HB_ERR_NULL, "call: argument is NULL". */
hb_status hb_fail_null(const char *call, const char *argument);
const hb_error *hb_thread_error(void);

#endif

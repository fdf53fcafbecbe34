/* libFuzzer: bytes as a table file loaded into a plan. Byte 0 picks the plan (bit 0: a dFH11 N_p
 * table, or an HHH22 TT/TRT table) and whether the harness rewrites the file's checksum over the
 * mutated bytes (bit 1), so that mutations also reach the fields the checksum guards. Creation
 * either refuses with HB_ERR_FILE and a message, or succeeds, and then f is finite and >= 0.
 * The corpus starts from files of `hairbsdf bake` for these two materials. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hairbsdf.h"
#include "math/hash.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.quality = HB_QUALITY_FAST;
    m.eumelanin = 0.4;
    if (data[0] & 1)
        o.model = HB_MODEL_HUANG, o.tt_trt = HB_TT_TRT_TABLE, m.roughness = 0.5;
    else
        o.azimuthal = HB_AZIMUTHAL_TABLE, o.table_tolerance = 0.1;
    size_t n = size - 1;
    uint8_t *file = malloc(n ? n : 1); /* its own allocation, so that ASan sees a read past its end */
    if (!file)
        return 0;
    memcpy(file, data + 1, n);
    if ((data[0] & 2) && n >= 8) {
        unsigned long long sum = hb_xxh64(file, n - 8);
        for (int k = 0; k < 8; k++)
            file[n - 8 + (size_t)k] = (uint8_t)(sum >> (8 * k));
    }
    o.table_file = n ? file : NULL, o.table_file_size = n;
    hb_plan *plan;
    hb_error error;
    hb_status st = hb_plan_create(&m, &o, &plan, &error);
    free(file);
    if (st != HB_OK) {
        if (!error.message[0] || (n && st != HB_ERR_FILE && st != HB_ERR_NOMEM))
            abort(); /* every refusal of a file says why, as a file refusal */
        return 0;
    }
    enum { N = 64 };
    float ti[N], pi[N], to[N], po[N], f[3][N];
    for (int k = 0; k < N; k++) { /* a spread of directions, grazing ones included */
        ti[k] = -1.5707963f + 3.1415926f * (float)k / (N - 1);
        to[k] = 1.5707963f - 3.1415926f * (float)((k * 37) % N) / (N - 1);
        pi[k] = -3.1415926f + 6.2831853f * (float)((k * 11) % N) / (N - 1), po[k] = 0.1f * (float)k;
    }
    hb_eval_angles(plan, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < N; k++)
            if (!(f[c][k] >= 0.0f && isfinite(f[c][k])))
                abort();
    hb_plan_destroy(plan);
    return 0;
}

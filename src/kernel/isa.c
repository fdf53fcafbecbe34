/* The public instruction-set queries. HB_ISA in the environment overrides what HB_ISA_AUTO picks
 * (src/plan/create.c; tests and benches force each path this way). They live with the dispatch,
 * which plan creation below the public entry points also asks. */
#include <string.h>

#include "isas.h"

static const char *const isa_names[HB_ISA_COUNT] = {
    [HB_ISA_AUTO] = "auto", [HB_ISA_SCALAR] = "scalar", [HB_ISA_SSE41] = "sse4.1",
    [HB_ISA_AVX2] = "avx2", [HB_ISA_AVX512] = "avx512", [HB_ISA_NEON] = "neon",
};

const char *hb_isa_name(hb_isa isa)
{
    return (unsigned)isa < HB_ISA_COUNT ? isa_names[isa] : "unknown";
}

hb_isa hb_isa_from_name(const char *name)
{
    for (int i = 0; name && i < HB_ISA_COUNT; i++)
        if (strcmp(name, isa_names[i]) == 0)
            return (hb_isa)i;
    return HB_ISA_COUNT;
}

int hb_isa_available(hb_isa isa)
{
    return isa > HB_ISA_AUTO && isa < HB_ISA_COUNT && hb_cpu_runs(isa);
}

hb_isa hb_isa_best(void)
{
    for (int i = HB_ISA_COUNT - 1; i > HB_ISA_AUTO; i--)
        if (hb_isa_available((hb_isa)i))
            return (hb_isa)i;
    return HB_ISA_SCALAR;
}

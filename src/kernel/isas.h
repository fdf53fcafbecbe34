/* The instruction sets compiled in on this architecture: one list for the dispatch, every model's
 * table of per-ISA kernels and the tests (the Makefile's ISAS names the same set). Each entry is
 * X(symbol, hb_isa, a, b): symbol is the ISA's part of hb_<symbol>_<name>, the name every
 * per-ISA unit gives its table (src/kernel/batch.h, HB_ISA_SYMBOL). Internal. */
#ifndef HB_KERNEL_ISAS_H
#define HB_KERNEL_ISAS_H

#include "hairbsdf.h"
#include "simd/compiler.h"

#if defined(HB_ARCH_X86)
#define HB_FOR_EACH_ISA(X, a, b) \
    X(scalar, HB_ISA_SCALAR, a, b) X(sse41, HB_ISA_SSE41, a, b) X(avx2, HB_ISA_AVX2, a, b) X(avx512, HB_ISA_AVX512, a, b)
#elif defined(HB_ARCH_ARM64)
#define HB_FOR_EACH_ISA(X, a, b) X(scalar, HB_ISA_SCALAR, a, b) X(neon, HB_ISA_NEON, a, b)
#else
#define HB_FOR_EACH_ISA(X, a, b) X(scalar, HB_ISA_SCALAR, a, b)
#endif

#define HB_ISA_DECLARE_(isa, id, type, name) extern const type hb_##isa##_##name;
#define HB_ISA_ENTRY_(isa, id, type, name) [id] = &hb_##isa##_##name,
#define HB_ISA_BIT_(isa, id, a, b) | 1u << id

/* `table`: a static array by hb_isa of the per-ISA objects hb_<isa>_<name> of type `type`
 * (NULL where the ISA is not compiled in). */
#define HB_PER_ISA(type, name, table)              \
    HB_FOR_EACH_ISA(HB_ISA_DECLARE_, type, name)   \
    static const type *const table[HB_ISA_COUNT] = { HB_FOR_EACH_ISA(HB_ISA_ENTRY_, type, name) }

/* The bit mask (1u << hb_isa) of the ISAs compiled in. */
#define HB_ISAS_COMPILED_IN (0u HB_FOR_EACH_ISA(HB_ISA_BIT_, _, _))

/* Whether this CPU and OS run the ISA (src/kernel/cpu.c); false for one not compiled in. */
int hb_cpu_runs(hb_isa isa);

#endif

/* CPU features are read once; a plan asks for the kernels of one ISA. HB_ISA in
 * the environment overrides what HB_ISA_AUTO picks (tests and benches force each
 * path this way). */
#include <stdlib.h>
#include <string.h>

#include "hairbsdf.h"
#include "kernels.h"

extern const hb_kernels hb_scalar_kernels;
#if defined(__x86_64__) || defined(__i386__)
extern const hb_kernels hb_sse41_kernels, hb_avx2_kernels, hb_avx512_kernels;
#include <cpuid.h>
#elif defined(__aarch64__)
extern const hb_kernels hb_neon_kernels;
#endif

static const hb_kernels *const compiled_in[HB_ISA_COUNT] = {
    [HB_ISA_SCALAR] = &hb_scalar_kernels,
#if defined(__x86_64__) || defined(__i386__)
    [HB_ISA_SSE41] = &hb_sse41_kernels,
    [HB_ISA_AVX2] = &hb_avx2_kernels,
    [HB_ISA_AVX512] = &hb_avx512_kernels,
#elif defined(__aarch64__)
    [HB_ISA_NEON] = &hb_neon_kernels,
#endif
};

static const char *const isa_names[HB_ISA_COUNT] = {
    [HB_ISA_AUTO] = "auto", [HB_ISA_SCALAR] = "scalar", [HB_ISA_SSE41] = "sse4.1",
    [HB_ISA_AVX2] = "avx2", [HB_ISA_AVX512] = "avx512", [HB_ISA_NEON] = "neon",
};

#if defined(__x86_64__) || defined(__i386__)
static unsigned long long read_xcr0(void)
{
    unsigned lo, hi;
    __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    return ((unsigned long long)hi << 32) | lo;
}

/* Bit mask of the ISAs this CPU and OS support: CPUID for the instructions,
 * XGETBV for whether the OS saves the YMM / ZMM state. */
static unsigned detect_cpu(void)
{
    unsigned features = 1u << HB_ISA_SCALAR;
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d))
        return features;
    if (c & bit_SSE4_1)
        features |= 1u << HB_ISA_SSE41;
    int osxsave = (c & bit_OSXSAVE) != 0, fma = (c & bit_FMA) != 0, avx = (c & bit_AVX) != 0;
    if (!osxsave || !avx)
        return features;
    unsigned long long xcr0 = read_xcr0();
    if (!__get_cpuid_count(7, 0, &a, &b, &c, &d))
        return features;
    if ((xcr0 & 0x6) == 0x6 && (b & bit_AVX2) && fma)
        features |= 1u << HB_ISA_AVX2;
    if ((xcr0 & 0xe6) == 0xe6 && (b & bit_AVX512F) && (features & (1u << HB_ISA_AVX2)))
        features |= 1u << HB_ISA_AVX512;
    return features;
}
#elif defined(__aarch64__)
static unsigned detect_cpu(void) { return (1u << HB_ISA_SCALAR) | (1u << HB_ISA_NEON); }
#else
static unsigned detect_cpu(void) { return 1u << HB_ISA_SCALAR; }
#endif

static unsigned cpu_features(void)
{
    static unsigned cached; /* 0 = not read yet; the scalar bit is always set once read */
    unsigned features = __atomic_load_n(&cached, __ATOMIC_ACQUIRE);
    if (!features) {
        features = detect_cpu();
        __atomic_store_n(&cached, features, __ATOMIC_RELEASE);
    }
    return features;
}

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
    return isa > HB_ISA_AUTO && isa < HB_ISA_COUNT && compiled_in[isa] && (cpu_features() >> isa & 1u);
}

hb_isa hb_isa_best(void)
{
    for (int i = HB_ISA_COUNT - 1; i > HB_ISA_AUTO; i--)
        if (hb_isa_available((hb_isa)i))
            return (hb_isa)i;
    return HB_ISA_SCALAR;
}

const hb_kernels *hb_kernels_for(hb_isa isa)
{
    return hb_isa_available(isa) ? compiled_in[isa] : NULL;
}

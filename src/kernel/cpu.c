/* Which instruction sets this CPU and OS run, read once. */
#include "isas.h"

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>

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

int hb_cpu_runs(hb_isa isa)
{
    return (unsigned)isa < HB_ISA_COUNT && ((HB_ISAS_COMPILED_IN & cpu_features()) >> isa & 1u);
}

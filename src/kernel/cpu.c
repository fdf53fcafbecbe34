/* Which instruction sets this CPU and OS run, read once. */
#include "isas.h"

#if defined(_MSC_VER)
#include <intrin.h>
#endif

#if defined(HB_ARCH_X86)
#if defined(_MSC_VER)

/* CPUID leaf and subleaf into r = eax, ebx, ecx, edx; 0 if the leaf is beyond the CPU's highest. */
static int cpuid(unsigned leaf, unsigned subleaf, unsigned r[4])
{
    int v[4];
    __cpuid(v, (int)(leaf & 0x80000000u));
    if ((unsigned)v[0] < leaf)
        return 0;
    __cpuidex(v, (int)leaf, (int)subleaf);
    for (int k = 0; k < 4; k++)
        r[k] = (unsigned)v[k];
    return 1;
}

static unsigned long long read_xcr0(void) { return _xgetbv(0); }
#else
#include <cpuid.h>

static int cpuid(unsigned leaf, unsigned subleaf, unsigned r[4])
{
    if ((unsigned)__get_cpuid_max(leaf & 0x80000000u, 0) < leaf) /* int in clang's cpuid.h, unsigned in GCC's */
        return 0;
    __cpuid_count(leaf, subleaf, r[0], r[1], r[2], r[3]);
    return 1;
}

static unsigned long long read_xcr0(void)
{
    unsigned lo, hi;
    __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    return ((unsigned long long)hi << 32) | lo;
}
#endif

/* The feature bits read (Intel SDM vol. 2A, CPUID): leaf 1 ecx and leaf 7 ebx. */
enum {
    CPUID1_ECX_FMA = 1u << 12, CPUID1_ECX_SSE41 = 1u << 19, CPUID1_ECX_OSXSAVE = 1u << 27, CPUID1_ECX_AVX = 1u << 28,
    CPUID7_EBX_AVX2 = 1u << 5, CPUID7_EBX_AVX512F = 1u << 16
};

/* Bit mask of the ISAs this CPU and OS support: CPUID for the instructions,
 * XGETBV for whether the OS saves the YMM / ZMM state. */
static unsigned detect_cpu(void)
{
    unsigned features = 1u << HB_ISA_SCALAR, r[4];
    if (!cpuid(1, 0, r))
        return features;
    unsigned c = r[2];
    if (c & CPUID1_ECX_SSE41)
        features |= 1u << HB_ISA_SSE41;
    int osxsave = (c & CPUID1_ECX_OSXSAVE) != 0, fma = (c & CPUID1_ECX_FMA) != 0, avx = (c & CPUID1_ECX_AVX) != 0;
    if (!osxsave || !avx)
        return features;
    unsigned long long xcr0 = read_xcr0();
    if (!cpuid(7, 0, r))
        return features;
    unsigned b = r[1];
    if ((xcr0 & 0x6) == 0x6 && (b & CPUID7_EBX_AVX2) && fma)
        features |= 1u << HB_ISA_AVX2;
    if ((xcr0 & 0xe6) == 0xe6 && (b & CPUID7_EBX_AVX512F) && (features & (1u << HB_ISA_AVX2)))
        features |= 1u << HB_ISA_AVX512;
    return features;
}
#elif defined(HB_ARCH_ARM64)
static unsigned detect_cpu(void) { return (1u << HB_ISA_SCALAR) | (1u << HB_ISA_NEON); }
#else
static unsigned detect_cpu(void) { return 1u << HB_ISA_SCALAR; }
#endif

/* The features, read once; threads that race to read them first store the same value. */
#if defined(_MSC_VER) && !defined(__clang__)
static unsigned cpu_features(void)
{
    static volatile long cached; /* 0 = not read yet; the scalar bit is always set once read */
    long features = _InterlockedOr(&cached, 0);
    if (!features)
        _InterlockedExchange(&cached, features = (long)detect_cpu());
    return (unsigned)features;
}
#else
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
#endif

int hb_cpu_runs(hb_isa isa)
{
    return (unsigned)isa < HB_ISA_COUNT && ((HB_ISAS_COMPILED_IN & cpu_features()) >> isa & 1u);
}

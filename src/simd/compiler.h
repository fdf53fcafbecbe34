/* What differs between the compilers the library builds with (GCC, Clang, MinGW's GCC; MSVC and
 * clang-cl): forced inlining, loop unrolling hints, printf-format checking, thread-local storage, bit counting, and which
 * architecture this is. Everything else in the library is C11. Internal. */
#ifndef HB_SIMD_COMPILER_H
#define HB_SIMD_COMPILER_H

#if defined(_MSC_VER) && !defined(__clang__)
#define HB_ALWAYS_INLINE __forceinline
#define HB_NOINLINE __declspec(noinline)
#define HB_PRAGMA_UNROLL
#define HB_PRINTF_FORMAT(fmt, args)
#define HB_THREAD_LOCAL __declspec(thread)
#else
#define HB_THREAD_LOCAL _Thread_local
#define HB_ALWAYS_INLINE inline __attribute__((always_inline))
#define HB_NOINLINE __attribute__((noinline, unused))
#define HB_PRAGMA_UNROLL _Pragma("GCC unroll 8")
#if defined(__MINGW32__) /* built with __USE_MINGW_ANSI_STDIO: C99 formats such as %zu */
#define HB_PRINTF_FORMAT(fmt, args) __attribute__((format(gnu_printf, fmt, args)))
#else
#define HB_PRINTF_FORMAT(fmt, args) __attribute__((format(printf, fmt, args)))
#endif
#endif

#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)
#define HB_ARCH_X86 1
#elif defined(__aarch64__) || defined(_M_ARM64)
#define HB_ARCH_ARM64 1
#endif

/* The number of set bits of x (SWAR: no instruction beyond the baseline). */
static inline int hb_popcount32(unsigned x)
{
    x = x - ((x >> 1) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
    return (int)((((x + (x >> 4)) & 0x0f0f0f0fu) * 0x01010101u) >> 24);
}

#endif

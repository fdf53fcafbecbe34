/* W doubles held as two halves, for ISAs whose double vector is half as wide as
 * their float vector. The including ISA header defines HB_PD_T (the half type)
 * and HB_PD_ADD, _SUB, _MUL, _FMA, _MIN, _MAX, _ROUND, _SET1 (intrinsics on one half). */
#ifndef HB_SIMD_VDW_PAIR_H
#define HB_SIMD_VDW_PAIR_H

typedef struct { HB_PD_T lo, hi; } vdw;

#define HB_VDW_BINARY(name, op) \
    HB_INLINE vdw name(vdw a, vdw b) { vdw r = { op(a.lo, b.lo), op(a.hi, b.hi) }; return r; }
HB_VDW_BINARY(vdw_add, HB_PD_ADD)
HB_VDW_BINARY(vdw_sub, HB_PD_SUB)
HB_VDW_BINARY(vdw_mul, HB_PD_MUL)
HB_VDW_BINARY(vdw_div, HB_PD_DIV)
HB_VDW_BINARY(vdw_min, HB_PD_MIN)
HB_VDW_BINARY(vdw_max, HB_PD_MAX)
#undef HB_VDW_BINARY

HB_INLINE vdw vdw_fma(vdw a, vdw b, vdw c)
{
    vdw r = { HB_PD_FMA(a.lo, b.lo, c.lo), HB_PD_FMA(a.hi, b.hi, c.hi) };
    return r;
}
HB_INLINE vdw vdw_sqrt(vdw a) { vdw r = { HB_PD_SQRT(a.lo), HB_PD_SQRT(a.hi) }; return r; }
HB_INLINE vdw vdw_round(vdw a) { vdw r = { HB_PD_ROUND(a.lo), HB_PD_ROUND(a.hi) }; return r; }
HB_INLINE vdw vdw_set1(double a) { vdw r = { HB_PD_SET1(a), HB_PD_SET1(a) }; return r; }

#endif

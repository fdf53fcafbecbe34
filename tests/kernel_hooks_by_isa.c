/* The tests' per-ISA kernel hooks (kernel_hooks.c), by hb_isa. */
#include "kernel/isas.h"
#include "kernel_hooks.h"

HB_PER_ISA(hb_kernel_hooks, kernel_hooks, hooks_by_isa);

const hb_kernel_hooks *hb_kernel_hooks_for(hb_isa isa)
{
    return hb_isa_available(isa) ? hooks_by_isa[isa] : NULL;
}

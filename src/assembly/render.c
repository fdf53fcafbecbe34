/* hb_assembly_render: a bundle seen from the side, by the traced paths and by dual scattering
 * rendered through the same fibres (docs/multiple-scattering.md, "A tress, traced and
 * dual-scattered"). The argument checks; the pictures are trace.c's and dual_view.c's. */
#include <math.h>

#include "api/checks.h"
#include "assembly/fibres.h"

hb_status hb_assembly_render(const hb_plan *plan, const hb_dual_table *table, const hb_assembly *a,
                             hb_assembly_image *image, hb_assembly_result *result, hb_progress_fn progress,
                             void *progress_context, hb_parallel_fn parallel, void *parallel_context)
{
    static const char call[] = "hb_assembly_render";
    if (!plan || !table || !a || !image)
        return hb_fail_null(call, !plan ? "plan" : !table ? "table" : !a ? "assembly" : "image");
    hb_status st = hb_assembly_check(call, a);
    if (st == HB_OK)
        st = hb_api_struct_size(call, "image", image->struct_size, sizeof *image, sizeof *image);
    if (st != HB_OK)
        return st;
    if (a->shape != HB_ASSEMBLY_BUNDLE)
        return hb_fail(HB_ERR_UNSUPPORTED, "%s: only a bundle is pictured (assembly.shape is the slab)", call);
    if (image->columns < 1 || image->columns > 4096 || image->rays < 1 || image->rays > 1 << 20 ||
        !isfinite(image->view_phi))
        return hb_fail(HB_ERR_PARAM, "%s: image.columns = %d (1..4096), image.rays = %d (1..2^20), image.view_phi = %g "
                       "(finite): one is outside its range", call, image->columns, image->rays, image->view_phi);
    hb_assembly_result own = { .struct_size = sizeof own };
    st = hb_assembly_trace_image(plan, a, result ? result : &own, image, progress, progress_context, parallel,
                                 parallel_context);
    return st == HB_OK ? hb_assembly_dual_image(plan, table, a, image) : st;
}

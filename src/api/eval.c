/* Public batch entry points: argument checks, then the plan's model (its kernels) or, for a
 * reference plan, the double-precision path. No allocation. */
#include "models/model.h"
#include "ref/reference.h"

static hb_status check_out(const hb_plan *plan, size_t n, hb_rgb_soa out)
{
    if (!plan)
        return HB_ERR_NULL;
    if (n && (!out.r || !out.g || !out.b))
        return HB_ERR_NULL;
    return HB_OK;
}

static void report_invalid(hb_eval_report *report, size_t invalid)
{
    if (report)
        report->invalid = invalid;
}

hb_status hb_eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out, hb_eval_report *report)
{
    hb_status st = check_out(plan, n, out);
    if (st != HB_OK)
        return st;
    if (n && (!in.theta_i || !in.phi_i || !in.theta_o || !in.phi_o))
        return HB_ERR_NULL;
    size_t invalid = 0;
    if (plan->kernels)
        hb_model_ops_of(plan->options.model)->eval_angles(plan, n, in, out, &invalid);
    else
        invalid = hb_ref_eval_angles(plan, n, in, out);
    report_invalid(report, invalid);
    return HB_OK;
}

hb_status hb_eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out, hb_eval_report *report)
{
    hb_status st = check_out(plan, n, out);
    if (st != HB_OK)
        return st;
    if (n && (!in.wi_x || !in.wi_y || !in.wi_z || !in.wo_x || !in.wo_y || !in.wo_z))
        return HB_ERR_NULL;
    size_t invalid = 0;
    if (plan->kernels)
        hb_model_ops_of(plan->options.model)->eval_vectors(plan, n, in, out, &invalid);
    else
        invalid = hb_ref_eval_vectors(plan, n, in, out);
    report_invalid(report, invalid);
    return HB_OK;
}

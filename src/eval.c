/* Public batch entry points: argument checks, then the plan's kernel (or the
 * double reference for HB_QUALITY_REFERENCE). No allocation. */
#include <string.h>

#include "plan.h"
#include "ref/reference.h"

static hb_status check_out(const hb_plan *plan, size_t n, hb_rgb_soa out)
{
    if (!plan)
        return HB_ERR_NULL;
    if (n && (!out.r || !out.g || !out.b))
        return HB_ERR_NULL;
    return HB_OK;
}

/* The longitudinal term is one scalar per sample, the same in every channel. */
static void spread_channels(size_t n, hb_rgb_soa out)
{
    if (out.g != out.r)
        memcpy(out.g, out.r, n * sizeof(float));
    if (out.b != out.r)
        memcpy(out.b, out.r, n * sizeof(float));
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
    const hb_kernels *k = plan->kernels;
    if (!k) {
        invalid = hb_ref_eval_angles(plan, n, in, out);
    } else if (plan->options.term == HB_TERM_LONGITUDINAL) {
        if (plan->options.model == HB_MODEL_MARSCHNER)
            k->marschner->longitudinal_angles(&plan->marschner.lobe[HB_LOBE_R], n, in, out.r, &invalid);
        else
            k->deon->longitudinal_angles[plan->options.i0](&plan->deon.longitudinal[HB_LOBE_R], n, in, out.r, &invalid);
        spread_channels(n, out);
    } else if (plan->options.model == HB_MODEL_MARSCHNER) {
        k->marschner->angles(&plan->marschner, n, in, out, &invalid);
    } else if (plan->options.model == HB_MODEL_HUANG) {
        k->huang->angles(&plan->huang, n, in, out, &invalid);
    } else {
        k->deon->angles[plan->options.i0](&plan->deon, n, in, out, &invalid);
    }
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
    const hb_kernels *k = plan->kernels;
    if (!k) {
        invalid = hb_ref_eval_vectors(plan, n, in, out);
    } else if (plan->options.term == HB_TERM_LONGITUDINAL) {
        if (plan->options.model == HB_MODEL_MARSCHNER)
            k->marschner->longitudinal_vectors(&plan->marschner.lobe[HB_LOBE_R], n, in, out.r, &invalid);
        else
            k->deon->longitudinal_vectors[plan->options.i0](&plan->deon.longitudinal[HB_LOBE_R], n, in, out.r, &invalid);
        spread_channels(n, out);
    } else if (plan->options.model == HB_MODEL_MARSCHNER) {
        k->marschner->vectors(&plan->marschner, n, in, out, &invalid);
    } else if (plan->options.model == HB_MODEL_HUANG) {
        k->huang->vectors(&plan->huang, n, in, out, &invalid);
    } else {
        k->deon->vectors[plan->options.i0](&plan->deon, n, in, out, &invalid);
    }
    report_invalid(report, invalid);
    return HB_OK;
}

/* Public batch entry points: argument checks, then the plan's model (its kernels) or, for a
 * reference plan, the double-precision path. No allocation. */
#include <math.h>

#include "checks.h"
#include "math/valid.h"
#include "models/interface/model.h"
#include "ref/reference.h"

static hb_status check_out(const char *call, const hb_plan *plan, size_t n, const hb_rgb_soa *out)
{
    return plan ? hb_api_rgb_present(call, n, "out", out) : hb_fail_null(call, "plan");
}

static void report_invalid(hb_eval_report *report, size_t invalid)
{
    if (report)
        report->invalid = invalid;
}

hb_status hb_eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out, hb_eval_report *report)
{
    hb_status st = check_out(__func__, plan, n, &out);
    if (st == HB_OK)
        st = hb_api_angles_present(__func__, n, &in);
    if (st != HB_OK)
        return st;
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
    hb_status st = check_out(__func__, plan, n, &out);
    if (st == HB_OK)
        st = hb_api_vectors_present(__func__, n, &in);
    if (st != HB_OK)
        return st;
    size_t invalid = 0;
    if (plan->kernels)
        hb_model_ops_of(plan->options.model)->eval_vectors(plan, n, in, out, &invalid);
    else
        invalid = hb_ref_eval_vectors(plan, n, in, out);
    report_invalid(report, invalid);
    return HB_OK;
}

/* The per-sample absorption entry points: the model's kernels, where its path takes them. */
static hb_status eval_absorption(const char *call, const hb_plan *plan, size_t n, const hb_pair_batch *pairs,
                                 hb_absorption_soa sigma_a, hb_rgb_soa out, hb_eval_report *report)
{
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    if (!ops->eval_absorption || !plan->kernels)
        return hb_api_unsupported(call, plan, "per-sample absorption");
    hb_rgb_soa planes = { (float *)sigma_a.r, (float *)sigma_a.g, (float *)sigma_a.b };
    hb_status st = hb_api_rgb_present(call, n, "sigma_a", &planes);
    if (st != HB_OK)
        return st;
    hb_absorbing_batch batch = { *pairs, { sigma_a.r, sigma_a.g, sigma_a.b } };
    size_t invalid = 0;
    st = ops->eval_absorption(plan, n, &batch, out, &invalid);
    if (st == HB_OK)
        report_invalid(report, invalid);
    else
        hb_api_unsupported(call, plan, "per-sample absorption on this path");
    return st;
}

hb_status hb_eval_angles_absorption(const hb_plan *plan, size_t n, hb_angles_soa in, hb_absorption_soa sigma_a,
                                    hb_rgb_soa out, hb_eval_report *report)
{
    hb_status st = check_out(__func__, plan, n, &out);
    if (st == HB_OK)
        st = hb_api_angles_present(__func__, n, &in);
    if (st != HB_OK)
        return st;
    hb_pair_batch pairs = { .angles = in };
    return eval_absorption(__func__, plan, n, &pairs, sigma_a, out, report);
}

hb_status hb_eval_vectors_absorption(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_absorption_soa sigma_a,
                                     hb_rgb_soa out, hb_eval_report *report)
{
    hb_status st = check_out(__func__, plan, n, &out);
    if (st == HB_OK)
        st = hb_api_vectors_present(__func__, n, &in);
    if (st != HB_OK)
        return st;
    hb_pair_batch pairs = { .vectors = in };
    return eval_absorption(__func__, plan, n, &pairs, sigma_a, out, report);
}

static int near_valid(const hb_near_soa *in, size_t k)
{
    return hb_theta_valid(in->theta_i[k]) && hb_theta_valid(in->theta_o[k]) && hb_phi_valid(in->phi_i[k]) &&
           hb_phi_valid(in->phi_o[k]) && hb_offset_valid(in->h[k]);
}

hb_status hb_eval_near(const hb_plan *plan, size_t n, hb_near_soa in, hb_rgb_soa out, hb_eval_report *report)
{
    hb_status st = check_out(__func__, plan, n, &out);
    if (st != HB_OK)
        return st;
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    if (!ops->eval_near || plan->options.term != HB_TERM_FULL)
        return hb_api_unsupported(__func__, plan, "near field");
    st = hb_api_near_present(__func__, n, &in);
    if (st != HB_OK)
        return st;
    size_t invalid = 0;
    if (plan->kernels) {
        ops->eval_near(plan, n, in, out, &invalid);
    } else {
        for (size_t k = 0; k < n; k++) {
            double f[3] = { 0.0, 0.0, 0.0 };
            if (near_valid(&in, k))
                hb_ref_eval_near_pair(plan, in.theta_i[k], in.phi_i[k], in.theta_o[k], in.phi_o[k], in.h[k], f);
            else
                invalid++;
            out.r[k] = (float)f[0], out.g[k] = (float)f[1], out.b[k] = (float)f[2];
        }
    }
    report_invalid(report, invalid);
    return HB_OK;
}

hb_status hb_eval_near_absorption(const hb_plan *plan, size_t n, hb_near_soa in, hb_absorption_soa sigma_a, hb_rgb_soa out,
                                  hb_eval_report *report)
{
    hb_status st = check_out(__func__, plan, n, &out);
    if (st != HB_OK)
        return st;
    const hb_model_ops *ops = hb_model_ops_of(plan->options.model);
    if (!ops->eval_near_absorption || !plan->kernels || plan->options.term != HB_TERM_FULL)
        return hb_api_unsupported(__func__, plan, "near field at per-sample absorption");
    hb_rgb_soa planes = { (float *)sigma_a.r, (float *)sigma_a.g, (float *)sigma_a.b };
    st = hb_api_near_present(__func__, n, &in);
    if (st == HB_OK)
        st = hb_api_rgb_present(__func__, n, "sigma_a", &planes);
    if (st != HB_OK)
        return st;
    hb_absorbing_near batch = { in, { sigma_a.r, sigma_a.g, sigma_a.b } };
    size_t invalid = 0;
    st = ops->eval_near_absorption(plan, n, &batch, out, &invalid);
    if (st != HB_OK)
        return hb_api_unsupported(__func__, plan, "near field at per-sample absorption on this path");
    report_invalid(report, invalid);
    return HB_OK;
}

/* The double-precision reference over batches and by model: the loops hb_eval_* run for a
 * reference plan, and the sampler and pdf of each model that has them. */
#include <math.h>

#include "math/valid.h"
#include "models/plan.h"
#include "reference.h"


/* The plan's term at one direction pair, in double; writes three channels. The oracle keeps its
 * own dispatch by model: it shares nothing with the fast path but the equations. */
void hb_ref_eval_pair(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3])
{
    if (plan->options.model == HB_MODEL_HUANG) {
        hb_ref_huang(plan, theta_i, phi_i, theta_o, phi_o, f);
        return;
    }
    if (plan->options.model == HB_MODEL_CHIANG) {
        hb_ref_chiang_far(plan, theta_i, phi_i, theta_o, phi_o, f, NULL);
        return;
    }
    if (plan->options.model == HB_MODEL_MARSCHNER) {
        if (plan->options.term == HB_TERM_LONGITUDINAL)
            f[0] = f[1] = f[2] = hb_ref_marschner_longitudinal(plan->marschner_beta[HB_LOBE_R],
                                                               plan->marschner_mean[HB_LOBE_R], theta_i, theta_o);
        else
            hb_ref_marschner(plan, theta_i, phi_i, theta_o, phi_o, f);
        return;
    }
    if (plan->options.term == HB_TERM_LONGITUDINAL) {
        f[0] = f[1] = f[2] = hb_ref_deon_longitudinal(plan->v[HB_LOBE_R], theta_i,
                                                      theta_o - plan->deon.longitudinal[HB_LOBE_R].shift,
                                                      plan->options.i0);
        return;
    }
    hb_ref_deon(plan, theta_i, phi_i, theta_o, phi_o, f);
}

static void store(hb_rgb_soa out, size_t k, const double f[3])
{
    out.r[k] = (float)f[0];
    out.g[k] = (float)f[1];
    out.b[k] = (float)f[2];
}

size_t hb_ref_eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out)
{
    size_t invalid = 0;
    for (size_t k = 0; k < n; k++) {
        double f[3] = { 0.0, 0.0, 0.0 };
        if (hb_theta_valid(in.theta_i[k]) && hb_theta_valid(in.theta_o[k]) && hb_phi_valid(in.phi_i[k]) &&
            hb_phi_valid(in.phi_o[k]))
            hb_ref_eval_pair(plan, in.theta_i[k], in.phi_i[k], in.theta_o[k], in.phi_o[k], f);
        else
            invalid++;
        store(out, k, f);
    }
    return invalid;
}

/* Inclination and azimuth of a unit-length-within-tolerance vector; 0 when it is not one. */
int hb_ref_direction(float x, float y, float z, double *theta, double *phi)
{
    double norm2 = (double)x * x + (double)y * y + (double)z * z;
    if (!(fabs(norm2 - 1.0) <= HB_UNIT_TOLERANCE))
        return 0;
    *theta = atan2(y, hypot(x, z));
    *phi = x == 0.0 && z == 0.0 ? 0.0 : atan2(x, z); /* along the fibre: azimuth 0, signed zeros too */
    return 1;
}

size_t hb_ref_eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out)
{
    size_t invalid = 0;
    for (size_t k = 0; k < n; k++) {
        double f[3] = { 0.0, 0.0, 0.0 }, ti, pi, to, po;
        if (hb_ref_direction(in.wi_x[k], in.wi_y[k], in.wi_z[k], &ti, &pi) &&
            hb_ref_direction(in.wo_x[k], in.wo_y[k], in.wo_z[k], &to, &po))
            hb_ref_eval_pair(plan, ti, pi, to, po, f);
        else
            invalid++;
        store(out, k, f);
    }
    return invalid;
}

void hb_ref_eval_near_pair(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h,
                           double f[3])
{
    if (plan->options.model == HB_MODEL_DEON)
        hb_ref_deon_near(plan, theta_i, phi_i, theta_o, phi_o, h, f);
    else
        hb_ref_chiang_near(plan, theta_i, phi_i, theta_o, phi_o, h, f, NULL);
}

void hb_ref_sample_near(const hb_plan *plan, double theta_o, double phi_o, double h, const double *u,
                        double *theta_i, double *phi_i)
{
    if (plan->options.model == HB_MODEL_DEON)
        hb_ref_deon_sample_near(plan, theta_o, phi_o, h, u, theta_i, phi_i);
    else
        hb_ref_chiang_sample_near(plan, theta_o, phi_o, h, u, theta_i, phi_i);
}

double hb_ref_pdf_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h)
{
    if (plan->options.model == HB_MODEL_DEON)
        return hb_ref_deon_pdf_near(plan, theta_i, phi_i, theta_o, phi_o, h);
    double f[3], pdf;
    hb_ref_chiang_near(plan, theta_i, phi_i, theta_o, phi_o, h, f, &pdf);
    return pdf;
}

void hb_ref_sample(const hb_plan *plan, double theta_o, double phi_o, const double *u, double *theta_i,
                   double *phi_i)
{
    if (plan->options.model == HB_MODEL_CHIANG)
        hb_ref_chiang_sample_near(plan, theta_o, phi_o, 2.0 * u[HB_CHIANG_NEAR_DIMENSIONS] - 1.0, u, theta_i, phi_i);
    else if (plan->options.model == HB_MODEL_HUANG)
        hb_ref_huang_sample(plan, theta_o, phi_o, u, theta_i, phi_i);
    else
        hb_ref_deon_sample(plan, theta_o, phi_o, u, theta_i, phi_i);
}

double hb_ref_pdf(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o)
{
    if (plan->options.model == HB_MODEL_CHIANG) {
        double f[3], pdf;
        hb_ref_chiang_far(plan, theta_i, phi_i, theta_o, phi_o, f, &pdf);
        return pdf;
    }
    return plan->options.model == HB_MODEL_HUANG ? hb_ref_huang_pdf(plan, theta_i, phi_i, theta_o, phi_o)
                                                 : hb_ref_deon_pdf(plan, theta_i, phi_i, theta_o, phi_o);
}

/* The double-precision reference over batches: the loops hb_eval_* run for a reference plan, and
 * the entry points to the plan's model's own procedures (plan->reference, hb_reference_ops). */
#include <math.h>

#include "math/valid.h"
#include "models/interface/plan.h"
#include "reference.h"


/* The plan's term at one direction pair, in double; writes three channels. Each model's procedures
 * come from its reference file (hb_reference_ops): they share nothing with the fast path but the
 * equations. */
void hb_ref_eval_pair(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double f[3])
{
    plan->reference->eval(plan, theta_i, phi_i, theta_o, phi_o, f);
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
    plan->reference->eval_near(plan, theta_i, phi_i, theta_o, phi_o, h, f);
}

void hb_ref_sample_near(const hb_plan *plan, double theta_o, double phi_o, double h, const double *u,
                        double *theta_i, double *phi_i)
{
    plan->reference->sample_near(plan, theta_o, phi_o, h, u, theta_i, phi_i);
}

double hb_ref_pdf_near(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o, double h)
{
    return plan->reference->pdf_near(plan, theta_i, phi_i, theta_o, phi_o, h);
}

void hb_ref_sample(const hb_plan *plan, double theta_o, double phi_o, const double *u, double *theta_i,
                   double *phi_i)
{
    plan->reference->sample(plan, theta_o, phi_o, u, theta_i, phi_i);
}

double hb_ref_pdf(const hb_plan *plan, double theta_i, double phi_i, double theta_o, double phi_o)
{
    return plan->reference->pdf(plan, theta_i, phi_i, theta_o, phi_o);
}

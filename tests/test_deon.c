/* The full dFH11 model: detector series, SIMD vs double reference per quality,
 * white furnace, reciprocity, symmetries, the smooth-fibre limit of N_TT, the unit
 * integral of N_R / F_R, and the h in [0, 1] symmetry the quadrature relies on. */
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "models/interface/plan.h"
#include "math/quadrature.h"
#include "ref/reference.h"
#include "models/deon/reference.h"
#include "models/deon/state.h"

static hb_plan *deon_plan(hb_test_ctx *t, const hb_material *m, hb_quality quality, unsigned lobes)
{
    hb_options o;
    hb_options_default(&o);
    o.quality = quality;
    o.lobes = lobes;
    o.isa = t->isa == HB_ISA_AUTO ? hb_isa_best() : t->isa;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(m, &o, &plan, &err) == HB_OK, "plan: %s", err.message);
    return plan;
}

static void eval1(const hb_plan *plan, float ti, float pi, float to, float po, float f[3])
{
    hb_angles_soa in = { &ti, &pi, &to, &po };
    hb_eval_angles(plan, 1, in, (hb_rgb_soa){ &f[0], &f[1], &f[2] }, NULL);
}

/* Both series of eq. 11 agree, and the converged detector integrates to 1, for beta in [0.02, 3]. */
static void test_detector_series(hb_test_ctx *t)
{
    const double betas[] = { 0.02, 0.05, 0.1, 0.3, 0.5, 0.8, 1.0, 1.5, 2.0, 3.0 };
    for (size_t b = 0; b < sizeof betas / sizeof betas[0]; b++) {
        double beta = betas[b], peak = fmax(1.0 / (beta * sqrt(2 * M_PI)), 0.5 / M_PI), worst = 0.0, sum = 0.0;
        enum { N = 1000 };
        int fourier_terms = (int)ceil(40.0 / beta); /* e^(-n^2 beta^2 / 2) < 1e-300 beyond */
        for (int k = 0; k < N; k++) {
            double x = -M_PI + 2 * M_PI * k / N;
            double direct = hb_ref_detector_direct(beta, x, 30), fourier = hb_ref_detector_fourier(beta, x, fourier_terms);
            worst = fmax(worst, fabs(direct - fourier) / peak);
            sum += direct;
        }
        CHECK(t, worst < 1e-12, "beta %g: direct and Fourier series differ by %.3g of the peak", beta, worst);
        CHECK(t, fabs(sum * 2 * M_PI / N - 1.0) < 1e-12, "beta %g: integral %.15f", beta, sum * 2 * M_PI / N);
    }
}

/* The plan's truncated detector on this ISA: within its tolerance of the converged one,
 * unit integral, continuous and periodic across phi = +-pi. */
static void test_detector_kernel(hb_test_ctx *t)
{
    const double betas[] = { 0.02, 0.05, 0.1, 0.3, 0.5, 0.8, 1.0, 1.5, 2.0, 3.0 };
    const double tolerances[] = { 1e-3, 1e-5, 1e-7 };
    enum { N = 4096 };
    static float x[N + 4], out[N + 4];
    for (size_t b = 0; b < sizeof betas / sizeof betas[0]; b++) {
        for (size_t it = 0; it < 3; it++) {
            hb_material m;
            hb_material_default(&m);
            m.beta_n = betas[b];
            hb_options o;
            hb_options_default(&o);
            o.detector_tolerance = tolerances[it];
            o.isa = t->isa;
            hb_plan *plan;
            hb_plan_create(&m, &o, &plan, NULL);
            const hb_detector *d = &hb_deon_of(plan)->kernel.detector[0];
            double peak = fmax(1.0 / (betas[b] * sqrt(2 * M_PI)), 0.5 / M_PI);
            for (int k = 0; k < N; k++)
                x[k] = (float)(-M_PI + 2 * M_PI * k / N);
            x[N] = 3.14159250f, x[N + 1] = -3.14159250f, x[N + 2] = 1.0f, x[N + 3] = (float)(1.0 + 2 * M_PI);
            t->hooks->detector_map(d, N + 4, x, out);
            double worst = 0.0, sum = 0.0;
            for (int k = 0; k < N; k++) {
                worst = fmax(worst, fabs(out[k] - hb_ref_detector(betas[b], x[k])) / peak);
                sum += out[k];
            }
            double float_error = 2e-6; /* a few ulp of exp and of the recurrence */
            CHECK(t, worst <= tolerances[it] + float_error, "beta %g tol %g (%s, %d terms): error %.3g of peak",
                  betas[b], tolerances[it], d->fourier ? "Fourier" : "direct", d->terms, worst);
            CHECK(t, fabs(sum * 2 * M_PI / N - 1.0) <= tolerances[it] + float_error, "beta %g tol %g: integral %.9f",
                  betas[b], tolerances[it], sum * 2 * M_PI / N);
            CHECK(t, fabsf(out[N] - out[N + 1]) <= 1e-6f * (float)peak, "beta %g: D(pi-) %g != D(-pi+) %g",
                  betas[b], out[N], out[N + 1]);
            CHECK(t, fabsf(out[N + 2] - out[N + 3]) <= 2e-6f * (float)peak, "beta %g: not 2 pi periodic", betas[b]);
            hb_plan_destroy(plan);
        }
    }
}

typedef struct material_case {
    const char *name;
    double sigma_a[3], beta_m, beta_n, alpha;
} material_case;

static const material_case materials[] = {
    { "white", { 0, 0, 0 }, 0.1, 0.3, 0.035 },
    { "blond", { 0.1, 0.25, 0.6 }, 0.25, 0.5, 0.035 },
    { "brown", { 0.9, 1.5, 2.8 }, 0.15, 0.3, 0.05 },
    { "rough", { 0.2, 0.3, 0.5 }, 0.6, 1.2, 0.0 },
    { "sharp", { 0.05, 0.1, 0.2 }, 0.05, 0.1, 0.035 },
    { "glossy", { 0.02, 0.05, 0.1 }, 0.005, 0.05, 0.035 },
};

static void set_material(hb_material *m, const material_case *c)
{
    hb_material_default(m);
    memcpy(m->sigma_a, c->sigma_a, sizeof m->sigma_a);
    m->beta_m = c->beta_m;
    m->beta_n = c->beta_n;
    m->alpha = c->alpha;
}

/* SIMD float kernels against the double reference, error as in docs/conventions.md, per
 * quality; random directions (uniform on the sphere) plus grazing and specular ones. */
static void test_matches_reference(hb_test_ctx *t)
{
    static const double bound[3] = { [HB_QUALITY_FAST] = 1e-2, [HB_QUALITY_BALANCED] = 1e-3,
                                      [HB_QUALITY_HIGH] = 1e-4 };
    enum { N = 96 };
    float ti[N], pi[N], to[N], po[N], f[3][N], ref[3][N];
    for (size_t mc = 0; mc < sizeof materials / sizeof materials[0]; mc++) {
        hb_material m;
        set_material(&m, &materials[mc]);
        for (int k = 0; k < N; k++) {
            ti[k] = (float)asin(hb_test_range(t, -1, 1));
            pi[k] = (float)hb_test_range(t, -M_PI, M_PI);
            to[k] = k % 3 ? (float)asin(hb_test_range(t, -1, 1)) : -ti[k] + (float)hb_test_range(t, -0.1, 0.1);
            po[k] = (float)hb_test_range(t, -M_PI, M_PI);
            if (k < 6) /* grazing, and exact forward / backward scattering */
                ti[k] = k % 2 ? 1.5707963f : -1.5707f, po[k] = k < 3 ? pi[k] : pi[k] + 3.14159265f;
        }
        for (int k = 0; k < N; k++)
            to[k] = fmaxf(-1.5707963f, fminf(1.5707963f, to[k]));
        hb_plan *ref_plan = deon_plan(t, &m, HB_QUALITY_REFERENCE, HB_LOBES_DEFAULT);
        hb_angles_soa in = { ti, pi, to, po };
        hb_eval_angles(ref_plan, N, in, (hb_rgb_soa){ ref[0], ref[1], ref[2] }, NULL);
        hb_plan_destroy(ref_plan);
        for (int q = HB_QUALITY_FAST; q <= HB_QUALITY_HIGH; q++) {
            hb_plan *plan = deon_plan(t, &m, (hb_quality)q, HB_LOBES_DEFAULT);
            hb_eval_angles(plan, N, in, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
            hb_plan_destroy(plan);
            for (int c = 0; c < 3; c++)
                for (int k = 0; k < N; k++)
                    CHECK(t, isfinite(f[c][k]) && f[c][k] >= 0.0f, "%s: f = %g", materials[mc].name, f[c][k]);
            size_t worst_k = 0;
            double worst = hb_test_spec_error((float *const[3]){ f[0], f[1], f[2] },
                                              (float *const[3]){ ref[0], ref[1], ref[2] }, N, &worst_k);
            hb_test_note(t, "%-5s quality %d: max error %.2e (bound %.0e)", materials[mc].name, q, worst, bound[q]);
            CHECK(t, worst <= bound[q], "%s quality %d: error %.3g at (%g, %g, %g, %g)", materials[mc].name, q,
                  worst, ti[worst_k], pi[worst_k], to[worst_k], po[worst_k]);
        }
    }
}

static double furnace(const hb_plan *plan, double theta_o)
{
    double e[3];
    hb_furnace(plan, theta_o, e);
    return e[0];
}

/* White furnace. With the R lobe's Fresnel per offset (eq. 14, the default), sum_p A(p, h) = 1
 * and the untilted model conserves energy up to quadrature: the 0.97..1.03 bound is
 * checked there. The tilt (sec. 6: "only approximate") and eq. 12 (the paper's half-angle
 * Fresnel for R) move energy by design; their ranges are reported beside it. */
static void test_white_furnace(hb_test_ctx *t)
{
    const double betas[] = { 0.05, 0.3, 0.7, 1.2 }, thetas[] = { -1.55, -0.8, 0.0, 0.6, 1.2, 1.55 };
    const int corner_beta[] = { 1, 1, 0, 1 }, corner_theta[] = { 1, 0, 0, 0, 1, 1 }; /* where eq. 12 deviates most */
    static const char *const labels[4] = { "R Fresnel per offset, alpha 0", "R Fresnel per offset, alpha 0.035",
                                           "eq. 12, alpha 0", "eq. 12, alpha 0.035" };
    for (int variant = 0; variant < 4; variant++) {
        double lo = 2.0, hi = 0.0, worst[3] = { 0, 0, 0 };
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++) {
                if (variant > 0 && !(corner_beta[a] && corner_beta[b]))
                    continue;
                if (t->quick && (variant > 0 || a != b)) /* quick tier: the diagonal of the bound only */
                    continue;
                hb_material m;
                hb_material_default(&m);
                m.beta_m = betas[a];
                m.beta_n = betas[b];
                m.alpha = variant % 2 ? 0.035 : 0.0;
                hb_options o;
                hb_options_default(&o);
                o.quality = HB_QUALITY_BALANCED;
                o.r_fresnel = variant < 2 ? HB_R_FRESNEL_OFFSET : HB_R_FRESNEL_HALF_ANGLE;
                o.isa = hb_isa_best();
                hb_plan *plan;
                hb_plan_create(&m, &o, &plan, NULL);
                for (int j = 0; j < 6; j++) {
                    if (variant > 0 && !corner_theta[j])
                        continue;
                    double e = furnace(plan, thetas[j]);
                    if (fabs(e - 1.0) >= fmax(1.0 - lo, hi - 1.0))
                        worst[0] = betas[a], worst[1] = betas[b], worst[2] = thetas[j];
                    lo = fmin(lo, e), hi = fmax(hi, e);
                    CHECK(t, isfinite(e) && e > 0.5 && e < 1.5, "%s: E = %g", labels[variant], e);
                    if (variant == 0)
                        CHECK(t, e >= 0.97 && e <= 1.03, "beta_m %g beta_n %g theta_o %g: E = %.5f", betas[a],
                              betas[b], thetas[j], e);
                }
                hb_plan_destroy(plan);
            }
        hb_test_note(t, "white furnace, %s: E in [%.4f, %.4f], worst at beta_m %g beta_n %g theta_o %g",
                     labels[variant], lo, hi, worst[0], worst[1], worst[2]);
    }
}

/* f(w_i, w_o) = f(w_o, w_i) without tilt; f(phi) = f(-phi) for a circular fibre. */
static void test_reciprocity_and_symmetry(hb_test_ctx *t)
{
    hb_material m;
    set_material(&m, &materials[1]);
    m.alpha = 0.0;
    hb_plan *plan = deon_plan(t, &m, HB_QUALITY_BALANCED, HB_LOBES_DEFAULT);
    double worst_recip = 0.0, worst_sym = 0.0;
    for (int k = 0; k < 400; k++) {
        float ti = (float)asin(hb_test_range(t, -1, 1)), to = (float)asin(hb_test_range(t, -1, 1));
        float pi = (float)hb_test_range(t, -M_PI, M_PI), po = (float)hb_test_range(t, -M_PI, M_PI);
        float a[3], b[3], c[3];
        eval1(plan, ti, pi, to, po, a);
        eval1(plan, to, po, ti, pi, b);
        eval1(plan, ti, -pi, to, -po, c);
        for (int ch = 0; ch < 3; ch++) {
            double scale = fmax(a[ch], 1e-4);
            worst_recip = fmax(worst_recip, fabs(a[ch] - b[ch]) / scale);
            worst_sym = fmax(worst_sym, fabs(a[ch] - c[ch]) / scale);
        }
    }
    CHECK(t, worst_recip < 2e-5, "reciprocity: relative difference %.3g", worst_recip);
    CHECK(t, worst_sym < 2e-5, "phi <-> -phi: relative difference %.3g", worst_sym);
    hb_plan_destroy(plan);
}

/* As beta_n -> 0, N_TT -> MJC03's smooth TT: A(1, h) / |2 dPhi/dh| at dFH11's closed-form
 * root h_TT (sec. 5), and that root solves Phi(1, h) = phi. Checked on the reference. */
static void test_tt_smooth_limit(hb_test_ctx *t)
{
    hb_material m;
    hb_material_default(&m);
    m.beta_n = 0.02;
    m.beta_m = 0.3;
    m.alpha = 0.0;
    m.sigma_a[0] = 0.3, m.sigma_a[1] = 0.3, m.sigma_a[2] = 0.3;
    hb_plan *plan = deon_plan(t, &m, HB_QUALITY_REFERENCE, 1u << HB_LOBE_TT);
    double ti = 0.2, to = -0.1, eta = m.eta, td = 0.5 * (to - ti);
    double eta_prime = sqrt(eta * eta - sin(td) * sin(td)) / cos(td), a = 1.0 / eta_prime;
    double mu = m.sigma_a[0] / sqrt(1.0 - sin(td) * sin(td) / (eta * eta));
    double M = hb_ref_longitudinal(hb_deon_of(plan)->v[1], ti, to, HB_I0_ABRAMOWITZ);
    const double phis[] = { 2.9, 2.6, -2.7, 3.1, -3.05 };
    for (int k = 0; k < 5; k++) {
        double phi = phis[k], s = phi >= 0 ? 1.0 : -1.0;
        double h = s * cos(phi / 2) / sqrt(1 + a * a - 2 * a * s * sin(phi / 2));
        double gi = asin(h), gt = asin(h / eta_prime);
        double Phi = remainder(2 * gt - 2 * gi + M_PI, 2 * M_PI);
        CHECK(t, fabs(remainder(Phi - phi, 2 * M_PI)) < 1e-12, "h_TT(%g) = %g gives Phi = %g", phi, h, Phi);
        double dPhi_dh = 2.0 / (eta_prime * cos(gt)) - 2.0 / cos(gi);
        double f = hb_ref_fresnel(eta, cos(td) * cos(gi));
        double A = (1 - f) * (1 - f) * exp(-2.0 * mu * cos(gt));
        double smooth = 0.5 * A / fabs(dPhi_dh);
        double f_ref[3];
        hb_ref_deon(plan, ti, 0.0, to, phi, f_ref);
        double rough = f_ref[0] / M;
        CHECK(t, fabs(rough / smooth - 1.0) < 0.01, "phi %g: N_TT(beta_n 0.02) = %.6g, smooth %.6g", phi, rough,
              smooth);
    }
    hb_plan_destroy(plan);
}

/* The R lobe's azimuthal integral is its Fresnel weight. eq. 12 (A(0, h) = F_R at half the
 * angle between w_i and w_o): N_R / F_R integrates to 1 over phi. The default (eq. 14 per
 * offset): N_R integrates to (1/2) integral over h of F(eta', eta''; cos(theta_d) cos(gamma)). */
static void test_nr_integral(hb_test_ctx *t)
{
    const double betas[] = { 0.05, 0.3, 1.0, 2.5 };
    for (int variant = 0; variant < 2; variant++)
        for (int b = 0; b < 4; b++) {
            hb_material m;
            hb_material_default(&m);
            m.beta_n = betas[b];
            m.alpha = 0.0;
            hb_options o;
            hb_options_default(&o);
            o.quality = HB_QUALITY_HIGH;
            o.lobes = 1u << HB_LOBE_R;
            o.isa = t->isa;
            o.r_fresnel = variant ? HB_R_FRESNEL_HALF_ANGLE : HB_R_FRESNEL_OFFSET;
            hb_plan *plan = NULL;
            CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "plan");
            if (!plan)
                return;
            double ti = 0.4, to = -0.25, M = hb_ref_longitudinal(hb_deon_of(plan)->v[0], ti, to, HB_I0_ABRAMOWITZ);
            double sum = 0.0, expected = 1.0;
            enum { N = 2048 };
            for (int k = 0; k < N; k++) {
                double phi = -M_PI + 2 * M_PI * (k + 0.5) / N;
                float f[3];
                eval1(plan, (float)ti, 0.0f, (float)to, (float)phi, f);
                double dot = cos(ti) * cos(to) * cos(phi) + sin(ti) * sin(to);
                sum += f[0] / (M * (variant ? hb_ref_fresnel(m.eta, sqrt(0.5 * (1 + dot))) : 1.0));
            }
            sum *= 2 * M_PI / N;
            if (!variant) { /* (1/2) integral over h in [-1, 1], h = sin(gamma), midpoint rule in gamma */
                expected = 0.0;
                for (int k = 0; k < N; k++) {
                    double gamma = -M_PI / 2 + M_PI * (k + 0.5) / N;
                    expected += hb_ref_fresnel(m.eta, cos(0.5 * (to - ti)) * cos(gamma)) * cos(gamma);
                }
                expected *= 0.5 * M_PI / N;
            }
            CHECK(t, fabs(sum / expected - 1.0) < 1e-4, "%s, beta_n %g: integral of N_R = %.7f, expected %.7f",
                  variant ? "eq. 12" : "eq. 14", betas[b], sum, expected);
            hb_plan_destroy(plan);
        }

}

/* The quadrature's h in [0, 1] with detection at +-phi equals eq. 10 over h in [-1, 1]. */
static void test_half_range_symmetry(hb_test_ctx *t)
{
    hb_material m;
    hb_material_default(&m);
    m.sigma_a[0] = 0.4, m.sigma_a[1] = 0.4, m.sigma_a[2] = 0.4;
    m.alpha = 0.0;
    double ti = 0.3, to = -0.5, td = 0.5 * (to - ti), eta = m.eta;
    double inv_eta_prime = cos(td) / sqrt(eta * eta - sin(td) * sin(td));
    double mu = 0.4 / sqrt(1.0 - sin(td) * sin(td) / (eta * eta));
    for (int p = 1; p <= 3; p++) {
        hb_plan *plan = deon_plan(t, &m, HB_QUALITY_REFERENCE, 1u << p);
        for (int k = 0; k < 4; k++) {
            double phi = -2.5 + 1.7 * k, full = 0.0;
            enum { N = 20000 };
            for (int j = 0; j < N; j++) { /* midpoint rule in gamma over [-pi/2, pi/2] */
                double gi = -M_PI_2 + M_PI * (j + 0.5) / N, h = sin(gi), gt = asin(h * inv_eta_prime);
                double f = hb_ref_fresnel(eta, cos(td) * cos(gi));
                double A = (1 - f) * (1 - f) * pow(f, p - 1) * exp(-2.0 * p * mu * cos(gt));
                full += 0.5 * A * hb_ref_detector(m.beta_n, phi - (2 * p * gt - 2 * gi + p * M_PI)) * cos(gi);
            }
            full *= M_PI / N;
            double f_ref[3];
            hb_ref_deon(plan, ti, 0.0, to, phi, f_ref);
            double half = f_ref[0] / hb_ref_longitudinal(hb_deon_of(plan)->v[p], ti, to - hb_deon_of(plan)->kernel.longitudinal[p].shift,
                                                              HB_I0_ABRAMOWITZ);
            CHECK(t, fabs(half - full) <= 1e-7 * fmax(full, 1e-3), "p %d phi %g: half range %.10g, full %.10g", p,
                  phi, half, full);
        }
        hb_plan_destroy(plan);
    }
}

/* dFH11 Fig. 5: for a white fibre, TRRT and above carry almost 15% of the energy at grazing
 * incidence and next to nothing at normal incidence. */
static void test_fig5_high_orders(hb_test_ctx *t)
{
    hb_material m;
    hb_material_default(&m);
    m.alpha = 0.0;
    const double thetas[] = { 0.0, 1.45 };
    double share[2];
    for (int k = 0; k < 2; k++) {
        double total = 0.0, high = 0.0;
        for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
            if (p > 3 && p != HB_LOBE_RESIDUAL)
                continue;
            hb_plan *plan = deon_plan(t, &m, HB_QUALITY_BALANCED, 1u << p);
            double e[3];
            CHECK(t, hb_furnace(plan, thetas[k], e) == HB_OK, "furnace");
            total += e[0];
            high += p >= 3 ? e[0] : 0.0;
            hb_plan_destroy(plan);
        }
        share[k] = high / total;
    }
    hb_test_note(t, "white fibre: TRRT and above carry %.1f%% of the energy at theta 0, %.1f%% at 1.45",
                 100 * share[0], 100 * share[1]);
    CHECK(t, share[1] > 0.10 && share[1] < 0.20, "grazing share %.3f is not 'almost 15%%'", share[1]);
    CHECK(t, share[0] < 0.02, "normal incidence share %.3f", share[0]);
}

/* dFH11 Fig. 3 / eq. 5 with N_R integrating to 1: the energy of a longitudinal function M
 * that goes with MJC03's 1/cos^2(theta_d), H(theta_i) = integral of M / cos^2(theta_d) cos^2(theta_r)
 * over theta_r, for the Gaussian of eq. 4 in theta_h (MJC03) or 2 theta_h (ZW07). */
static double gaussian_energy(double beta, double theta_i, int twice)
{
    enum { N = 20000 };
    double sum = 0.0;
    for (int k = 0; k < N; k++) {
        double tr = -M_PI_2 + M_PI * (k + 0.5) / N, th = 0.5 * (theta_i + tr), td = 0.5 * (tr - theta_i);
        double x = twice ? 2 * th : th;
        double g = exp(-x * x / (2 * beta * beta)) / (sqrt(2 * M_PI) * beta); /* eq. 4 */
        sum += g / (cos(td) * cos(td)) * cos(tr) * cos(tr);
    }
    return sum * M_PI / N;
}

/* Fig. 3: the Gaussian doubles the energy (theta_h) or, in 2 theta_h, gains at grazing angles and
 * loses at high roughness; eq. 7 (through hb_furnace on the longitudinal term) gives 1 throughout. */
static void test_fig3_longitudinal_energy(hb_test_ctx *t)
{
    const double betas[] = { 0.1, 0.3, 0.6 }, thetas[] = { -1.5, -1.0, 0.0, 0.5, 1.2, 1.5 };
    for (int b = 0; b < 3; b++) {
        hb_material m;
        hb_material_default(&m);
        m.beta_m = betas[b];
        m.alpha = 0.0;
        hb_options o;
        hb_options_default(&o);
        o.term = HB_TERM_LONGITUDINAL;
        hb_plan *plan;
        hb_plan_create(&m, &o, &plan, NULL);
        for (int k = 0; k < 6; k++) {
            double e[3];
            hb_furnace(plan, thetas[k], e);
            CHECK(t, fabs(e[0] - 1.0) < 1e-5, "eq. 7, beta %g theta %g: energy %.7f", betas[b], thetas[k], e[0]);
        }
        hb_plan_destroy(plan);
        hb_test_note(t, "beta %.1f: Gaussian(theta_h) energy %.3f at theta 0; Gaussian(2 theta_h) %.3f at 0, %.3f at 1.5",
                     betas[b], gaussian_energy(betas[b], 0.0, 0), gaussian_energy(betas[b], 0.0, 1),
                     gaussian_energy(betas[b], 1.5, 1));
    }
    /* the paper's reading of Fig. 3: "near 2 for most theta_i" at small roughness; with 2 theta_h,
     * "extra energy at grazing angles and energy loss for high roughnesses" */
    for (int k = 1; k < 5; k++)
        CHECK(t, gaussian_energy(0.1, thetas[k], 0) > 1.8, "theta_h Gaussian at theta %g: %.3f, not near 2",
              thetas[k], gaussian_energy(0.1, thetas[k], 0));
    CHECK(t, gaussian_energy(0.3, 1.5, 1) > 1.1, "2 theta_h Gaussian should gain energy at grazing angles");
    CHECK(t, gaussian_energy(0.6, 0.0, 1) < 0.9, "2 theta_h Gaussian should lose energy at high roughness");
}

/* Extreme but valid materials and directions: every output finite and >= 0 on every ISA. */
static void test_hard_cases_finite(hb_test_ctx *t)
{
    const double etas[] = { 1.0001, 2.5 }, sigmas[] = { 0.0, 1e3 }, beta_ms[] = { 0.001, 1.5 }, beta_ns[] = { 0.02, 3.0 };
    const float edge[] = { 1.57079637f, -1.57079637f, 0.0f, -0.0f, 1e-40f, 1.5707960f, 3.14159274f, -3.14159274f };
    enum { N = 128 };
    float ti[N], pi[N], to[N], po[N], f[3][N];
    for (int k = 0; k < N; k++) {
        ti[k] = k < 64 ? edge[k % 8] : (float)asin(hb_test_range(t, -1, 1));
        to[k] = k < 64 ? edge[(k / 8) % 8] : (float)asin(hb_test_range(t, -1, 1));
        pi[k] = k < 64 ? edge[(k + 3) % 8] : (float)hb_test_range(t, -M_PI, M_PI);
        po[k] = k < 64 ? edge[(k / 8 + 5) % 8] : (float)hb_test_range(t, -M_PI, M_PI);
        ti[k] = fmaxf(-1.57079637f, fminf(1.57079637f, ti[k]));
        to[k] = fmaxf(-1.57079637f, fminf(1.57079637f, to[k]));
    }
    for (int combo = 0; combo < 16; combo++) {
        hb_material m;
        hb_material_default(&m);
        m.eta = etas[combo & 1];
        m.sigma_a[0] = m.sigma_a[1] = m.sigma_a[2] = sigmas[combo >> 1 & 1];
        m.beta_m = beta_ms[combo >> 2 & 1];
        m.beta_n = beta_ns[combo >> 3 & 1];
        for (int q = HB_QUALITY_FAST; q <= HB_QUALITY_BALANCED; q++) {
            hb_plan *plan = deon_plan(t, &m, (hb_quality)q, HB_LOBES_DEFAULT);
            hb_eval_report rep;
            hb_eval_angles(plan, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, &rep);
            CHECK(t, rep.invalid == 0, "valid extreme directions counted invalid: %zu", rep.invalid);
            for (int c = 0; c < 3; c++)
                for (int k = 0; k < N; k++)
                    CHECK(t, isfinite(f[c][k]) && f[c][k] >= 0.0f,
                          "eta %g sigma %g beta_m %g beta_n %g: f(%g, %g, %g, %g) = %g", m.eta, m.sigma_a[0], m.beta_m,
                          m.beta_n, ti[k], pi[k], to[k], po[k], f[c][k]);
            hb_plan_destroy(plan);
        }
    }
}

/* The vector entry point against the double reference of the same float vectors. */
static void test_vectors_match_reference(hb_test_ctx *t)
{
    enum { N = 64 };
    float w[6][N], f[3][N], ref[3][N];
    hb_material m;
    set_material(&m, &materials[1]);
    for (int k = 0; k < N; k++) {
        double ti = asin(hb_test_range(t, -1, 1)), pi = hb_test_range(t, -M_PI, M_PI);
        double to = k % 2 ? -ti + hb_test_range(t, -0.1, 0.1) : asin(hb_test_range(t, -1, 1));
        double po = hb_test_range(t, -M_PI, M_PI);
        to = fmax(-M_PI_2, fmin(M_PI_2, to));
        if (k < 4) /* grazing and at the poles */
            ti = k % 2 ? M_PI_2 : -M_PI_2, to = k < 2 ? 0.3 : -M_PI_2;
        double dirs[2][2] = { { ti, pi }, { to, po } };
        for (int d = 0; d < 2; d++) {
            w[3 * d + 0][k] = (float)(sin(dirs[d][1]) * cos(dirs[d][0]));
            w[3 * d + 1][k] = (float)sin(dirs[d][0]);
            w[3 * d + 2][k] = (float)(cos(dirs[d][1]) * cos(dirs[d][0]));
        }
    }
    hb_vectors_soa in = { w[0], w[1], w[2], w[3], w[4], w[5] };
    hb_plan *ref_plan = deon_plan(t, &m, HB_QUALITY_REFERENCE, HB_LOBES_DEFAULT);
    hb_eval_vectors(ref_plan, N, in, (hb_rgb_soa){ ref[0], ref[1], ref[2] }, NULL);
    hb_plan_destroy(ref_plan);
    hb_plan *plan = deon_plan(t, &m, HB_QUALITY_HIGH, HB_LOBES_DEFAULT);
    hb_eval_report rep;
    hb_eval_vectors(plan, N, in, (hb_rgb_soa){ f[0], f[1], f[2] }, &rep);
    hb_plan_destroy(plan);
    CHECK(t, rep.invalid == 0, "unit vectors counted invalid: %zu", rep.invalid);
    double worst = hb_test_spec_error((float *const[3]){ f[0], f[1], f[2] },
                                      (float *const[3]){ ref[0], ref[1], ref[2] }, N, NULL);
    CHECK(t, worst <= 1e-4, "vector entry point, quality high: error %.3g against the reference", worst);
}

const hb_test hb_tests_deon[] = {
    { "deon_vectors_match_reference", test_vectors_match_reference, 1 },
    { "deon_hard_cases_finite", test_hard_cases_finite, 1 },
    { "deon_fig3_longitudinal_energy", test_fig3_longitudinal_energy, 0 },
    { "deon_fig5_high_orders", test_fig5_high_orders, 0 },
    { "deon_detector_series", test_detector_series, 0 },
    { "deon_detector_kernel", test_detector_kernel, 1 },
    { "deon_matches_reference", test_matches_reference, 1 },
    { "deon_white_furnace", test_white_furnace, 0 },
    { "deon_reciprocity_and_symmetry", test_reciprocity_and_symmetry, 1 },
    { "deon_tt_smooth_limit", test_tt_smooth_limit, 0 },
    { "deon_nr_integral", test_nr_integral, 1 },
    { "deon_half_range_symmetry", test_half_range_symmetry, 0 },
    { NULL, NULL, 0 },
};

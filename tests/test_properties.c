/* Property tests on random materials and directions, for every model, on every ISA.
 * The runner prints the seed; rerun with --seed N to reproduce a failure. Each property is
 * checked on the same random batch:
 *   finite and >= 0; phi <-> -phi symmetry; continuity across phi = +-pi; reciprocity (dFH11
 *   without tilt: f; MJC03: S = f / cos(theta_i); HHH22's R lobe: S a(phi_o), since eq. 28 averages
 *   over the width a(phi_o) the fibre shows to w_o, and the cross-section S a is what light's
 *   reversibility makes symmetric); this ISA against the scalar kernel; angles against vectors.
 * HHH22's TT and TRT are a Monte-Carlo estimate per sample (eqs. 31, 32): the mirrored and the
 * swapped directions draw other paths, so symmetry and reciprocity are properties of its mean
 * (test_huang_internal checks them on the quadrature); the comparisons that reuse a sample's
 * numbers (same index) hold per sample, except where float rounding moves a path across one of
 * its conditions (visibility, total internal reflection): such flips are counted and bounded. */
#include <string.h>

#include "test.h"

enum { N = 256, MATERIALS = 12 };

typedef struct batch {
    float ti[N], pi[N], to[N], po[N];
} batch;

/* What a row of the table runs: a model, its lobes, and which properties hold sample by sample. */
typedef struct property_model {
    const char *name;
    hb_model model;
    unsigned lobes;
    int monte_carlo;  /* HHH22 TT/TRT: no per-sample symmetry or reciprocity; flips counted */
    int reciprocal_s; /* reciprocity of S = f / cos(theta_i) rather than of f */
    int width_normalised; /* HHH22 eq. 28 divides by the projected half width a(phi_o) seen from w_o */
    int nonreciprocal; /* CBTB16: pbrt-v4's attenuation and offset are w_o's (its N_p at h = sin(gamma_o)) */
} property_model;

static const property_model models[] = {
    { "deon", HB_MODEL_DEON, HB_LOBES_DEFAULT, 0, 0, 0, 0 },
    { "chiang", HB_MODEL_CHIANG, HB_LOBES_DEFAULT, 0, 0, 0, 1 },
    { "marschner", HB_MODEL_MARSCHNER, HB_LOBES_DEFAULT, 0, 1, 0, 0 },
    { "huang R", HB_MODEL_HUANG, 1u << HB_LOBE_R, 0, 1, 1, 0 },
    { "huang R+TT+TRT", HB_MODEL_HUANG, HB_LOBES_DEFAULT, 1, 1, 1, 0 },
};

static void eval(const hb_plan *plan, const batch *b, float f[3][N])
{
    hb_eval_angles(plan, N, (hb_angles_soa){ b->ti, b->pi, b->to, b->po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
}

/* A random valid material for the model: eta 1.0001..2.5, absorption 0..5, roughness over the
 * whole valid range (log-uniform), tilt, for MJC03 eccentricity and caustic parameters, for HHH22
 * either NDF, roughness 0.01..1 and eccentricity; CBTB16's roughnesses on its [0, 1] scale. dFH11
 * is reciprocal only without tilt (sec. 6). */
static void random_material(hb_test_ctx *t, hb_model model, int untilted, hb_material *m)
{
    hb_material_default(m);
    m->eta = 1.0001 + 1.5 * hb_test_uniform(t);
    for (int c = 0; c < 3; c++)
        m->sigma_a[c] = hb_test_uniform(t) < 0.3 ? 0.0 : 5.0 * pow(hb_test_uniform(t), 3);
    int unit_scale = model == HB_MODEL_CHIANG; /* CBTB16's beta_m and beta_n are in [0, 1] */
    m->beta_m = exp(hb_test_range(t, log(unit_scale ? 0.0028 : 0.001), log(unit_scale ? 1.0 : 1.5)));
    m->beta_n = exp(hb_test_range(t, log(0.05), log(unit_scale ? 1.0 : 2.0)));
    m->alpha = untilted ? 0.0 : hb_test_range(t, -0.1, 0.1);
    if (model == HB_MODEL_MARSCHNER) {
        m->eccentricity = hb_test_uniform(t) < 0.5 ? 0.0 : hb_test_range(t, 0.0, 0.9);
        m->glint_scale = hb_test_range(t, 0.0, 5.0);
        m->caustic_width = hb_test_range(t, 0.1, 0.5);
    }
    if (model == HB_MODEL_HUANG) {
        m->ndf = hb_test_uniform(t) < 0.5 ? HB_NDF_GGX : HB_NDF_BECKMANN;
        m->roughness = exp(hb_test_range(t, log(0.01), log(1.0)));
        m->eccentricity = hb_test_uniform(t) < 0.5 ? 0.0 : hb_test_range(t, 0.0, 0.9);
    }
}

static hb_plan *plan_for(hb_test_ctx *t, const hb_material *m, const property_model *pm, hb_isa isa)
{
    hb_options o;
    hb_options_default(&o);
    o.model = pm->model;
    o.lobes = pm->lobes;
    o.quality = HB_QUALITY_FAST; /* the cheapest level must hold every property too */
    o.tt_trt = HB_TT_TRT_MC;      /* HHH22: its estimator over random materials (the table's: test_huang_table.c) */
    o.isa = isa;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(m, &o, &plan, &err) == HB_OK, "plan: %s", err.message);
    return plan;
}

/* |a - b| / max(|a|, |b|, floor): relative, with a floor for values near zero. */
static double rel(double a, double b, double floor)
{
    return fabs(a - b) / fmax(fmax(fabs(a), fabs(b)), floor);
}

enum { SYMMETRY, RECIPROCITY, CONTINUITY, AGAINST_SCALAR, VECTORS, PROPERTIES };

/* The worst relative difference of a property, and how many values exceeded its bound. */
typedef struct tally {
    double worst;
    int over, total, worst_lane;
} tally;

static void tally_add(tally *t, double err, double bound, int lane)
{
    if (err > t->worst)
        t->worst = err, t->worst_lane = lane;
    t->over += err > bound;
    t->total++;
}

static void test_properties(hb_test_ctx *t)
{
    static batch b, mirrored, swapped, near_pi, near_minus_pi, inside_pi;
    static float f[3][N], g[3][N], h[3][N], s[3][N], w[6][N];
    /* float rounding only: symmetric forms are exact up to it; ISA against scalar is the kernels'
     * stated float tolerance (3e-5, the scalar kernel rounds each fma twice and uses no FMA);
     * vectors add the float atan2 of both inclinations and of phi */
    const double bound[PROPERTIES] = { 1e-5, 2e-5, 1e-5, 3e-5, 2e-4 };
    static const char *const what[PROPERTIES] = { "phi <-> -phi", "reciprocity", "continuity at +-pi",
                                                  "against scalar", "angles vs vectors" };
    for (size_t mi = 0; mi < sizeof models / sizeof models[0]; mi++) {
        const property_model *pm = &models[mi];
        tally flips[PROPERTIES];
        memset(flips, 0, sizeof flips);
        for (int k = 0; k < MATERIALS; k++) {
            int untilted = k % 2 == 0;
            hb_material m;
            random_material(t, pm->model, untilted, &m);
            for (int j = 0; j < N; j++) { /* uniform on the sphere, and some grazing */
                b.ti[j] = (float)asin(hb_test_range(t, -1, 1));
                b.to[j] = j % 16 == 0 ? 1.57079637f * (j % 32 ? 1.0f : -1.0f) : (float)asin(hb_test_range(t, -1, 1));
                /* every eighth lane with azimuths anywhere in the valid |phi| <= 1e4, reduced alike on every ISA */
                double span = j % 8 == 5 ? HB_PHI_LIMIT : M_PI;
                b.pi[j] = (float)hb_test_range(t, -span, span);
                b.po[j] = (float)hb_test_range(t, -span, span);
                /* x -> -x mirrors both azimuths: a symmetry of every fibre here, elliptical and tilted too */
                mirrored.ti[j] = b.ti[j], mirrored.to[j] = b.to[j], mirrored.pi[j] = -b.pi[j], mirrored.po[j] = -b.po[j];
                swapped.ti[j] = b.to[j], swapped.to[j] = b.ti[j], swapped.pi[j] = b.po[j], swapped.po[j] = b.pi[j];
                /* phi_o just inside +pi against just inside -pi, lane for lane (the same numbers) */
                near_pi.ti[j] = near_minus_pi.ti[j] = inside_pi.ti[j] = b.ti[j];
                near_pi.to[j] = near_minus_pi.to[j] = inside_pi.to[j] = b.to[j];
                near_pi.pi[j] = near_minus_pi.pi[j] = inside_pi.pi[j] = 0.0f;
                near_pi.po[j] = 3.1415925f, near_minus_pi.po[j] = -3.1415925f;
                inside_pi.po[j] = 3.1415920f; /* a step inside the domain longer than the one across the seam */
                hb_test_vectors_of(b.ti[j], b.pi[j], b.to[j], b.po[j], (float *const[6]){ w[0], w[1], w[2], w[3], w[4], w[5] },
                                   (size_t)j);
            }
            hb_plan *plan = plan_for(t, &m, pm, t->isa), *scalar = plan_for(t, &m, pm, HB_ISA_SCALAR);
            if (!plan || !scalar)
                return;
            eval(plan, &b, f);
            double peak = 0.0;
            for (int c = 0; c < 3; c++)
                for (int j = 0; j < N; j++) {
                    CHECK(t, isfinite(f[c][j]) && f[c][j] >= 0.0f,
                          "%s material %d (eta %.17g, roughness %.17g, e %.17g, alpha %.17g, ndf %d, sigma_a %.17g "
                          "%.17g %.17g): f(%.9g, %.9g, %.9g, %.9g) = %g at index %d",
                          pm->name, k, m.eta, m.roughness, m.eccentricity, m.alpha, (int)m.ndf, m.sigma_a[0],
                          m.sigma_a[1], m.sigma_a[2], b.ti[j], b.pi[j], b.to[j], b.po[j], f[c][j], j);
                    peak = fmax(peak, f[c][j]);
                }
            double floor = 1e-3 * peak + 1e-30;
            /* HHH22's NDF at roughness r turns a rounding of the directions into a relative change
             * of up to ~2 ulp / r in D (its log-slope peaks at 2 / r): below r = 0.05 the float
             * bounds grow as 1 / r */
            double steep = pm->model == HB_MODEL_HUANG ? fmax(1.0, 0.05 / m.roughness) : 1.0;
            tally here[PROPERTIES];
            memset(here, 0, sizeof here);
            if (!pm->monte_carlo) {
                eval(plan, &mirrored, g);
                /* HHH22's S grows as 1 / cos(theta_o) toward the pole down to the plan's floor (eq. 28: the
                 * width the fibre shows to w_o vanishes; the floor is 1e-8 for an untilted fibre with G,
                 * where f there is 1e4 times its value at theta_o = 1.5707), and at the float pole
                 * it is the ratio of two quantities of the size of cos(theta_o) = -4e-8, each with the
                 * absolute rounding of the float directions: 1e-5 relative there, 10x the bound */
                for (int j = 0; j < N; j++) {
                    int pole = pm->model == HB_MODEL_HUANG && fabsf(b.to[j]) >= 1.5707963f;
                    tally_add(&here[SYMMETRY], rel(f[0][j], g[0][j], floor), (pole ? 10.0 : 1.0) * steep * bound[SYMMETRY], j);
                }
                eval(plan, &swapped, g);
                for (int j = 0; j < N && !pm->nonreciprocal && (pm->reciprocal_s || untilted); j++) {
                    double ci = cos(b.ti[j]), co = cos(b.to[j]);
                    if (pm->reciprocal_s && (ci < 1e-3 || co < 1e-3))
                        continue; /* S = f / cos(theta_i) */
                    double s1 = pm->reciprocal_s ? f[0][j] / ci : f[0][j];
                    double s2 = pm->reciprocal_s ? g[0][j] / co : g[0][j];
                    if (pm->width_normalised) {
                        double e2 = m.eccentricity * m.eccentricity;
                        s1 *= sqrt(1.0 - e2 * pow(sin(b.po[j]), 2));
                        s2 *= sqrt(1.0 - e2 * pow(sin(b.pi[j]), 2));
                    }
                    double scale = pm->reciprocal_s ? floor / fmin(ci, co) : floor;
                    tally_add(&here[RECIPROCITY], rel(s1, s2, scale), steep * bound[RECIPROCITY], j);
                }
            }
            eval(plan, &near_pi, g);
            eval(plan, &near_minus_pi, h);
            /* a Monte-Carlo path samples its exit lobe at one point, so at roughness 0.01 a step of 3e-7 in
             * w_o moves it by ~1e-5 anywhere: across the seam it may move no more than over a longer
             * step inside the domain */
            if (pm->monte_carlo)
                eval(plan, &inside_pi, s);
            for (int j = 0; j < N; j++) {
                double inside = pm->monte_carlo ? rel(g[0][j], s[0][j], floor) : 0.0;
                tally_add(&here[CONTINUITY], fmax(rel(g[0][j], h[0][j], floor) - inside, 0.0), steep * bound[CONTINUITY], j);
            }
            eval(scalar, &b, g);
            for (int c = 0; c < 3; c++)
                for (int j = 0; j < N; j++)
                    tally_add(&here[AGAINST_SCALAR], rel(f[c][j], g[c][j], floor), steep * bound[AGAINST_SCALAR], j);
            hb_eval_vectors(plan, N, (hb_vectors_soa){ w[0], w[1], w[2], w[3], w[4], w[5] },
                            (hb_rgb_soa){ g[0], g[1], g[2] }, NULL);
            /* not at the pole: there the vector's azimuth is that of a planar part of 4e-8 (the float
             * pi/2 is past the pole, so it points opposite to phi), while the models still depend on
             * the phi the angle entry point was given */
            for (int c = 0; c < 3; c++)
                for (int j = 0; j < N; j++)
                    if (fabsf(b.to[j]) < 1.5707f)
                        tally_add(&here[VECTORS], rel(f[c][j], g[c][j], floor), steep * bound[VECTORS], j);
            for (int p = 0; p < PROPERTIES; p++) {
                int j = here[p].worst_lane;
                CHECK(t, pm->monte_carlo || here[p].over == 0,
                      "%s material %d (eta %.4g, beta_m %.3g, beta_n %.3g, roughness %.3g, e %.2g, alpha %.3g): %s %.3g "
                      "at (%.9g, %.9g, %.9g, %.9g)",
                      pm->name, k, m.eta, m.beta_m, m.beta_n, m.roughness, m.eccentricity, m.alpha, what[p], here[p].worst,
                      b.ti[j], b.pi[j], b.to[j], b.po[j]);
                flips[p].worst = fmax(flips[p].worst, here[p].worst);
                flips[p].over += here[p].over;
                flips[p].total += here[p].total;
            }
            hb_plan_destroy(plan);
            hb_plan_destroy(scalar);
        }
        if (pm->monte_carlo)
            for (int p = CONTINUITY; p < PROPERTIES; p++) {
                hb_test_note(t, "%s: %s: %d of %d values past %.0e (a path condition flipped by rounding)",
                             pm->name, what[p], flips[p].over, flips[p].total, bound[p]);
                CHECK(t, flips[p].over * 100 <= flips[p].total, "%s: %s: %d of %d values past %.0e", pm->name,
                      what[p], flips[p].over, flips[p].total, bound[p]);
            }
    }
}

/* The near fields (CBTB16, dFH11 at h) on random materials whose eta reaches down to 1 + 1e-9 and whose
 * absorption reaches 1e3, at offsets h up to an ulp from +-1 (where the refracted ray grazes the
 * fibre and the path inside is shortest): f finite and >= 0, within NEAR_BOUND of the double
 * reference (docs/conventions.md's metric; docs/accuracy.md), and within the ISAs' 3e-5 of the scalar kernel. */
enum { NEAR_MATERIALS = 8 };
#define NEAR_BOUND 3e-4

static void near_material(hb_test_ctx *t, hb_model model, int k, hb_material *m)
{
    hb_material_default(m);
    m->eta = k % 2 == 0 ? 1.0 + pow(10.0, hb_test_range(t, -9.0, -4.0)) : 1.0001 + 1.5 * hb_test_uniform(t);
    for (int c = 0; c < 3; c++)
        m->sigma_a[c] = hb_test_uniform(t) < 0.3 ? 0.0 : pow(10.0, hb_test_range(t, -2.0, 3.0));
    double beta_max = model == HB_MODEL_CHIANG ? 1.0 : 1.5;
    m->beta_m = exp(hb_test_range(t, log(model == HB_MODEL_CHIANG ? 0.01 : 0.005), log(beta_max)));
    m->beta_n = exp(hb_test_range(t, log(0.02), log(beta_max)));
    m->alpha = hb_test_range(t, -0.1, 0.1);
}

static void test_near_properties(hb_test_ctx *t)
{
    static float ti[N], pi[N], to[N], po[N], h[N], f[3][N], g[3][N], r[3][N];
    static const hb_model near_models[] = { HB_MODEL_CHIANG, HB_MODEL_DEON };
    static const char *const names[] = { "chiang", "deon" };
    for (int mi = 0; mi < 2; mi++) {
        double worst_ref = 0.0, worst_scalar = 0.0;
        for (int k = 0; k < NEAR_MATERIALS; k++) {
            hb_material m;
            near_material(t, near_models[mi], k, &m);
            for (int j = 0; j < N; j++) {
                ti[j] = (float)asin(hb_test_range(t, -1, 1)), to[j] = (float)asin(hb_test_range(t, -1, 1));
                pi[j] = (float)hb_test_range(t, -M_PI, M_PI), po[j] = (float)hb_test_range(t, -M_PI, M_PI);
                float edge = nextafterf(1.0f, 0.0f) - (float)(j % 3) * 6e-8f; /* 1 - 1, 2, 3 ulp */
                h[j] = j % 4 == 0 ? (j % 8 ? edge : -edge) : j % 4 == 1 ? (j % 8 == 1 ? 1.0f : -1.0f)
                                                                         : (float)hb_test_range(t, -1, 1);
            }
            hb_plan *plan[3] = { NULL, NULL, NULL };
            for (int q = 0; q < 3; q++) {
                hb_options o;
                hb_options_default(&o);
                o.model = near_models[mi];
                o.quality = q == 2 ? HB_QUALITY_REFERENCE : HB_QUALITY_HIGH;
                o.isa = q == 0 ? t->isa : HB_ISA_SCALAR;
                hb_error err;
                CHECK(t, hb_plan_create(&m, &o, &plan[q], &err) == HB_OK, "%s plan: %s", names[mi], err.message);
            }
            if (!plan[0] || !plan[1] || !plan[2])
                return;
            hb_near_soa in = { ti, pi, to, po, h };
            hb_eval_near(plan[0], N, in, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
            hb_eval_near(plan[1], N, in, (hb_rgb_soa){ g[0], g[1], g[2] }, NULL);
            hb_eval_near(plan[2], N, in, (hb_rgb_soa){ r[0], r[1], r[2] }, NULL);
            int bad = 0;
            for (int c = 0; c < 3; c++)
                for (int j = 0; j < N; j++)
                    bad += !(isfinite(f[c][j]) && f[c][j] >= 0.0f);
            size_t at = 0, at_scalar = 0;
            double e = hb_test_spec_error((float *const[3]){ f[0], f[1], f[2] }, (float *const[3]){ r[0], r[1], r[2] }, N, &at);
            double es = hb_test_spec_error((float *const[3]){ f[0], f[1], f[2] }, (float *const[3]){ g[0], g[1], g[2] }, N,
                                           &at_scalar);
            CHECK(t, bad == 0 && e <= NEAR_BOUND && es <= 3e-5,
                  "%s material %d (eta %.17g, sigma_a %.3g %.3g %.3g, beta_m %.3g, beta_n %.3g, alpha %.3g): %d values not "
                  "finite or < 0; against the reference %.3g at (%.9g, %.9g, %.9g, %.9g, h %.9g), against scalar %.3g at h %.9g",
                  names[mi], k, m.eta, m.sigma_a[0], m.sigma_a[1], m.sigma_a[2], m.beta_m, m.beta_n, m.alpha, bad, e, ti[at],
                  pi[at], to[at], po[at], h[at], es, h[at_scalar]);
            worst_ref = fmax(worst_ref, e), worst_scalar = fmax(worst_scalar, es);
            for (int q = 0; q < 3; q++)
                hb_plan_destroy(plan[q]);
        }
        hb_test_note(t, "%s near field: worst %.2g against the reference, %.2g against the scalar kernel", names[mi],
                     worst_ref, worst_scalar);
    }
}

const hb_test hb_tests_properties[] = {
    { "properties_random_materials", test_properties, 1 },
    { "properties_near_field", test_near_properties, 1 },
    { NULL, NULL, 0 },
};

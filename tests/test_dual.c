/* hb_dual_terms_at (Zinke et al. 2008; docs/multiple-scattering.md): a lossless, untilted dFH11
 * fibre with every order sends all the light somewhere (a_f + a_b = 1); the energies and moments
 * equal those of an independent rule (the midpoint rule over the whole sphere of w_o, 1024 x 1024,
 * no symmetry used) for dFH11 and CBTB16 fibres from lossless to black and red, one MJC03 and one
 * HHH22 fibre (1e-4 in the energies; HHH22's f, whose TT and TRT are a multilinear table with
 * kinks at every cell and whose R lobe has the visibility window's edges, is integrated by the
 * Gauss-Legendre panels to 1e-3 only, a panel's error where a kink falls inside it); A_b, Delta_b
 * and sigma_b^2 follow eqs. 14-17 in the form docs/multiple-scattering.md gives; invalid arguments
 * are refused. */
#include <math.h>
#include <string.h>

#include "test.h"

typedef struct dual_case {
    const char *name;
    hb_model model;
    double eumelanin, pheomelanin, alpha;
    double bound; /* the energies' against the midpoint rule; 10 times it for the moments */
} dual_case;

static const dual_case cases[] = {
    { "dFH11 lossless", HB_MODEL_DEON, 0.0, 0.0, 0.035, 1e-4 },   { "dFH11 blond", HB_MODEL_DEON, 0.3, 0.0, 0.035, 1e-4 },
    { "dFH11 brown", HB_MODEL_DEON, 1.3, 0.0, 0.035, 1e-4 },      { "dFH11 black", HB_MODEL_DEON, 8.0, 0.0, 0.035, 1e-4 },
    { "dFH11 red", HB_MODEL_DEON, 0.0, 2.0, 0.035, 1e-4 },        { "CBTB16 lossless", HB_MODEL_CHIANG, 0.0, 0.0, 0.035, 1e-4 },
    { "CBTB16 blond", HB_MODEL_CHIANG, 0.3, 0.0, 0.035, 1e-4 },   { "CBTB16 brown", HB_MODEL_CHIANG, 1.3, 0.0, 0.035, 1e-4 },
    { "CBTB16 black", HB_MODEL_CHIANG, 8.0, 0.0, 0.035, 1e-4 },   { "CBTB16 red", HB_MODEL_CHIANG, 0.0, 2.0, 0.035, 1e-4 },
    { "MJC03 blond", HB_MODEL_MARSCHNER, 0.3, 0.0, 0.035, 1e-4 }, { "HHH22 blond", HB_MODEL_HUANG, 0.3, 0.0, 0.035, 1e-3 },
};

static hb_plan *dual_plan(hb_test_ctx *t, const dual_case *c)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = c->eumelanin, m.pheomelanin = c->pheomelanin, m.alpha = c->alpha;
    o.model = c->model;
    if (c->model == HB_MODEL_HUANG)
        m.roughness = 0.3, o.quality = HB_QUALITY_FAST; /* TT and TRT from the fast table: deterministic */
    hb_plan *plan = NULL;
    hb_error e;
    CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "%s: %s", c->name, e.message);
    return plan;
}

/* theta of node k of n, the midpoints of n equal parts of (-pi/2, pi/2). */
static double theta_node(int k, int n) { return -M_PI_2 + M_PI * (k + 0.5) / n; }

static void test_lossless_sum(hb_test_ctx *t)
{
    const dual_case lossless = { "dFH11 lossless, untilted", HB_MODEL_DEON, 0.0, 0.0, 0.0, 1e-4 };
    hb_plan *plan = dual_plan(t, &lossless);
    if (!plan)
        return;
    int n = t->quick ? 16 : 64;
    double worst = 0.0;
    for (int k = 0; k < n; k++) {
        hb_dual_terms d = { .struct_size = sizeof d };
        CHECK(t, hb_dual_terms_at(plan, theta_node(k, n), HB_DUAL_DENSITY, &d) == HB_OK, "theta %g", theta_node(k, n));
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fabs(d.a_f[c] + d.a_b[c] - 1.0));
    }
    hb_test_note(t, "lossless untilted dFH11: |a_f + a_b - 1| <= %.1e over %d thetas", worst, n);
    CHECK(t, worst <= 1e-4, "a_f + a_b is %.3g off 1", worst);
    hb_plan_destroy(plan);
}

/* The independent rule: the midpoint rule in theta_o and in phi_o over [-pi, pi], N x N nodes. */
enum { N = 1024 };

static void midpoint_terms(const hb_plan *plan, double theta, double energy[2][3], double mean[2][3], double variance[2][3])
{
    static float ti[N], pi[N], to[N], po[N], f[3][N];
    double sum[2][3][3] = { { { 0 } } };
    for (int j = 0; j < N; j++) {
        double theta_o = theta_node(j, N), dw = M_PI / N * (2.0 * M_PI / N) * cos(theta_o), theta_h = 0.5 * (theta + theta_o);
        for (int l = 0; l < N; l++) {
            ti[l] = (float)theta, pi[l] = 0.0f, to[l] = (float)theta_o;
            po[l] = (float)(-M_PI + 2.0 * M_PI * (l + 0.5) / N);
        }
        hb_eval_angles(plan, N, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        for (int l = 0; l < N; l++) {
            int back = fabsf(po[l]) < (float)M_PI_2;
            for (int c = 0; c < 3; c++) {
                double e = dw * f[c][l];
                sum[back][c][0] += e, sum[back][c][1] += e * theta_h, sum[back][c][2] += e * theta_h * theta_h;
            }
        }
    }
    for (int h = 0; h < 2; h++)
        for (int c = 0; c < 3; c++) {
            energy[h][c] = sum[h][c][0];
            mean[h][c] = sum[h][c][0] > 0.0 ? sum[h][c][1] / sum[h][c][0] : 0.0;
            variance[h][c] = sum[h][c][0] > 0.0 ? sum[h][c][2] / sum[h][c][0] - mean[h][c] * mean[h][c] : 0.0;
        }
}

static void test_independent_rule(hb_test_ctx *t)
{
    size_t count = t->quick ? 3 : sizeof cases / sizeof cases[0];
    int n = t->quick ? 2 : 8;
    for (size_t k = 0; k < count; k++) {
        const dual_case *c = &cases[t->quick ? k * 5 : k]; /* quick: dFH11 and CBTB16 lossless, MJC03 blond */
        hb_plan *plan = dual_plan(t, c);
        if (!plan)
            continue;
        double worst_energy = 0.0, worst_mean = 0.0, worst_variance = 0.0;
        for (int j = 0; j < n; j++) {
            double theta = theta_node(j, n) * 0.97, energy[2][3], mean[2][3], variance[2][3];
            hb_dual_terms d = { .struct_size = sizeof d };
            hb_dual_terms_at(plan, theta, HB_DUAL_DENSITY, &d);
            midpoint_terms(plan, theta, energy, mean, variance);
            const double *got_energy[2] = { d.a_f, d.a_b }, *got_mean[2] = { d.alpha_f, d.alpha_b },
                         *got_variance[2] = { d.beta_f2, d.beta_b2 };
            for (int h = 0; h < 2; h++)
                for (int ch = 0; ch < 3; ch++) {
                    worst_energy = fmax(worst_energy, fabs(got_energy[h][ch] - energy[h][ch]));
                    if (energy[h][ch] > 1e-3) { /* moments where there is energy to weigh them */
                        worst_mean = fmax(worst_mean, fabs(got_mean[h][ch] - mean[h][ch]));
                        worst_variance = fmax(worst_variance, fabs(got_variance[h][ch] / variance[h][ch] - 1.0));
                    }
                }
        }
        hb_test_note(t, "%-16s: energies within %.1e, shifts %.1e rad, variances %.1e relative of the midpoint rule", c->name,
                     worst_energy, worst_mean, worst_variance);
        CHECK(t, worst_energy <= c->bound, "%s: a_f or a_b %.3g off the midpoint rule", c->name, worst_energy);
        CHECK(t, worst_mean <= 10.0 * c->bound, "%s: a shift %.3g rad off", c->name, worst_mean);
        CHECK(t, worst_variance <= 10.0 * c->bound, "%s: a variance %.3g off (relative)", c->name, worst_variance);
        hb_plan_destroy(plan);
    }
}

/* An elliptical fibre's terms are the mean over its orientations to the light: against the midpoint
 * rule over 24 orientations (other nodes than the library's 16), both sides of phi_o, 512 x 512 nodes
 * each (256 x 256 in the quick tier), for MJC03 and e = 0.5. */
enum { NE_MAX = 512, ORIENTED = 24 };

static void oriented_energies(const hb_plan *plan, double theta, int NE, double energy[2][3])
{
    static float ti[NE_MAX], pi[NE_MAX], to[NE_MAX], po[NE_MAX], f[3][NE_MAX];
    memset(energy, 0, 2 * 3 * sizeof energy[0][0]);
    for (int o = 0; o < ORIENTED; o++) {
        double psi = M_PI * (o + 0.5) / ORIENTED;
        for (int j = 0; j < NE; j++) {
            double theta_o = theta_node(j, NE), dw = M_PI / NE * (2.0 * M_PI / NE) * cos(theta_o) / ORIENTED;
            for (int l = 0; l < NE; l++) {
                ti[l] = (float)theta, pi[l] = (float)psi, to[l] = (float)theta_o;
                po[l] = (float)(psi - M_PI + 2.0 * M_PI * (l + 0.5) / NE);
            }
            hb_eval_angles(plan, NE, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
            for (int l = 0; l < NE; l++) {
                int back = fabs(-M_PI + 2.0 * M_PI * (l + 0.5) / NE) < M_PI_2;
                for (int c = 0; c < 3; c++)
                    energy[back][c] += dw * f[c][l];
            }
        }
    }
}

static void test_elliptical_orientations(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = 0.3, m.eccentricity = 0.5;
    o.model = HB_MODEL_MARSCHNER;
    hb_plan *plan;
    CHECK(t, hb_plan_create(&m, &o, &plan, NULL) == HB_OK, "MJC03 elliptical plan");
    if (!plan)
        return;
    double worst = 0.0;
    int n = t->quick ? 1 : 6;
    for (int j = 0; j < n; j++) {
        double theta = theta_node(j, n) * 0.97, energy[2][3];
        hb_dual_terms d = { .struct_size = sizeof d };
        CHECK(t, hb_dual_terms_at(plan, theta, HB_DUAL_DENSITY, &d) == HB_OK, "theta %g", theta);
        oriented_energies(plan, theta, t->quick ? NE_MAX / 2 : NE_MAX, energy);
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fmax(fabs(d.a_f[c] - energy[0][c]), fabs(d.a_b[c] - energy[1][c])));
    }
    hb_test_note(t, "MJC03 e = 0.5, blond: a_f and a_b within %.1e of 24 orientations by the midpoint rule", worst);
    CHECK(t, worst <= 1e-4, "the orientation mean is %.3g off the midpoint rule", worst);
    hb_plan_destroy(plan);
}

/* Eqs. 14-17 in the form docs/multiple-scattering.md gives, from the terms' own a_f, a_b and moments; finite and non-negative where
 * the fibre absorbs. */
static void test_back_scattering(hb_test_ctx *t)
{
    const dual_case *c = &cases[1];
    hb_plan *plan = dual_plan(t, c);
    if (!plan)
        return;
    double worst = 0.0;
    for (int k = 0; k < 8; k++) {
        hb_dual_terms d = { .struct_size = sizeof d };
        hb_dual_terms_at(plan, theta_node(k, 8), 0.5, &d);
        for (int ch = 0; ch < 3; ch++) {
            double af = d.a_f[ch], ab = d.a_b[ch], af2 = af * af, ab2 = ab * ab, one = 1.0 - af2;
            double A1 = ab * af2 / one, A3 = ab * ab2 * af2 / (one * one);
            double delta = d.alpha_b[ch] * (1.0 - 2.0 * ab2 / (one * one)) +
                           d.alpha_f[ch] * (2.0 * one * one + 4.0 * af2 * ab2) / (one * one * one);
            double bf = sqrt(d.beta_f2[ch]), bb = sqrt(d.beta_b2[ch]);
            double sigma = (1.0 + 0.5 * af2) * (ab * sqrt(2.0 * bf * bf + bb * bb) + ab * ab2 * sqrt(2.0 * bf * bf + 3.0 * bb * bb)) /
                           (ab + ab * ab2 * (2.0 * bf + 3.0 * bb));
            worst = fmax(worst, fabs(d.A_b[ch] - (A1 + A3)) / (A1 + A3));
            worst = fmax(worst, fabs(d.delta_b[ch] - delta) / fmax(fabs(delta), 1e-3));
            worst = fmax(worst, fabs(d.sigma_b2[ch] - sigma * sigma) / (sigma * sigma));
            CHECK(t, isfinite(d.A_b[ch]) && d.A_b[ch] >= 0.0 && isfinite(d.delta_b[ch]) && d.sigma_b2[ch] > 0.0,
                  "%s theta %g: A_b %g delta_b %g sigma_b^2 %g", c->name, theta_node(k, 8), d.A_b[ch], d.delta_b[ch],
                  d.sigma_b2[ch]);
        }
    }
    hb_test_note(t, "A_b, Delta_b, sigma_b^2 against eqs. 14-17: within %.1e relative", worst);
    CHECK(t, worst <= 1e-12, "eqs. 14-17 differ by %.3g", worst);
    hb_dual_terms d = { .struct_size = sizeof d };
    CHECK(t, hb_dual_terms_at(plan, M_PI_2, 0.7, &d) == HB_ERR_PARAM && hb_dual_terms_at(plan, NAN, 0.7, &d) == HB_ERR_PARAM &&
                 hb_dual_terms_at(plan, 0.0, 1.5, &d) == HB_ERR_PARAM && hb_dual_terms_at(NULL, 0.0, 0.7, &d) == HB_ERR_NULL &&
                 hb_dual_terms_at(plan, 0.0, 0.7, NULL) == HB_ERR_NULL,
          "invalid arguments accepted");
    hb_plan_destroy(plan);
}

/* hb_dual_lobe_energies: each lobe's part of a_f and a_b, its own plan on the parent's nodes, sums to
 * the parent's energies (the integrals are linear in f) to 1e-6; HHH22's TT and TRT plans build a
 * table each, where the parent tabulates their sum, and the tables' own errors (docs/huang.md: a mean
 * 2e-3 of the peak at the fast grid) differ, so its bound is 5e-3. The parts are non-negative; TT
 * carries most of a blond fibre's forward energy, R and TRT its backward. */
static void test_lobe_energies(hb_test_ctx *t)
{
    static const int picks[] = { 1, 6, 10, 11 }; /* dFH11, CBTB16, MJC03 and HHH22 blond */
    static const double bounds[] = { 1e-6, 1e-6, 1e-6, 5e-3 };
    for (int k = 0; k < 4; k++) {
        double worst = 0.0;
        const dual_case *c = &cases[picks[k]];
        hb_plan *plan = dual_plan(t, c);
        if (!plan)
            continue;
        for (int j = 0; j < (t->quick ? 2 : 4); j++) {
            double theta = theta_node(j, 4), forward[HB_MAX_LOBES + 1][3], backward[HB_MAX_LOBES + 1][3];
            hb_dual_terms d = { .struct_size = sizeof d };
            hb_status st = hb_dual_lobe_energies(plan, theta, forward, backward);
            CHECK(t, st == HB_OK && hb_dual_terms_at(plan, theta, HB_DUAL_DENSITY, &d) == HB_OK, "%s: %s", c->name,
                  hb_last_error()->message);
            if (st != HB_OK)
                break;
            for (int ch = 0; ch < 3; ch++) {
                double sum_f = 0.0, sum_b = 0.0;
                for (int p = 0; p <= HB_LOBE_RESIDUAL; p++) {
                    CHECK(t, forward[p][ch] >= 0.0 && backward[p][ch] >= 0.0, "%s: lobe %d negative", c->name, p);
                    sum_f += forward[p][ch], sum_b += backward[p][ch];
                }
                worst = fmax(worst, fabs(sum_f - d.a_f[ch]) / d.a_f[ch]);
                worst = fmax(worst, fabs(sum_b - d.a_b[ch]) / d.a_b[ch]);
            }
            if (j == 1)
                hb_test_note(t, "%-13s theta %+.2f, green: a_f %.4f of which TT %.4f; a_b %.4f of which R %.4f, TRT %.4f",
                             c->name, theta, d.a_f[1], forward[HB_LOBE_TT][1], d.a_b[1], backward[HB_LOBE_R][1],
                             backward[HB_LOBE_TRT][1]);
            CHECK(t, forward[HB_LOBE_TT][1] > 0.5 * d.a_f[1], "%s: TT carries %g of a_f %g", c->name,
                  forward[HB_LOBE_TT][1], d.a_f[1]);
        }
        hb_plan_destroy(plan);
        hb_test_note(t, "%-13s the lobes' parts sum to a_f and a_b within %.1e relative", c->name, worst);
        CHECK(t, worst <= bounds[k], "%s: the lobes' parts differ from the whole by %.3g", c->name, worst);
    }
}

/* The engines' way: HDRP's pre-integration (Unity's Graphics repository, HairMultipleScattering-
 * PreIntegration.compute) estimates a_f and a_b per theta from 128 outgoing directions of a
 * Hammersley set uniform on the sphere, each against 90 light azimuths 2 degrees apart
 * (hb_dual_terms_sampled). That estimate against hb_dual_terms_grid's converged terms at 64 theta
 * (whose own error is dual_independent_rule's, 1e-4 and below), for dFH11 blond fibres from smooth to
 * rough: the noise an engine's table carries. */
static void test_engine_recipe(hb_test_ctx *t)
{
    enum { THETAS = 64 };
    static hb_dual_terms terms[THETAS];
    static const double roughness[] = { 0.05, 0.1, 0.2, 0.4 };
    hb_test_note(t, "a_f and a_b by HDRP's recipe (128 x 90 pairs per theta) against the converged terms, dFH11 blond, "
                    "green, 64 theta:");
    double worst_all = 0.0;
    for (int r = 0; r < (t->quick ? 2 : 4); r++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        m.eumelanin = 0.3, m.beta_m = roughness[r];
        hb_plan *plan = NULL;
        hb_error e;
        CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "%s", e.message);
        if (!plan)
            return;
        terms[0].struct_size = sizeof terms[0];
        CHECK(t, hb_dual_terms_grid(plan, THETAS, HB_DUAL_DENSITY, terms, NULL, NULL, NULL, NULL) == HB_OK, "%s",
              hb_last_error()->message);
        double worst[2] = { 0.0, 0.0 }, mean[2] = { 0.0, 0.0 };
        for (int k = 0; k < THETAS; k++) {
            hb_dual_terms recipe = { .struct_size = sizeof recipe };
            CHECK(t, hb_dual_terms_sampled(plan, theta_node(k, THETAS), 128, 90, HB_DUAL_DENSITY, &recipe) == HB_OK, "%s",
                  hb_last_error()->message);
            double err[2] = { fabs(recipe.a_f[1] - terms[k].a_f[1]), fabs(recipe.a_b[1] - terms[k].a_b[1]) };
            for (int h = 0; h < 2; h++)
                worst[h] = fmax(worst[h], err[h]), mean[h] += err[h] / THETAS;
        }
        hb_test_note(t, "beta_m %.2f: a_f off by %.4f mean, %.4f at most (a_f at theta 0: %.4f); a_b by %.4f mean, "
                        "%.4f at most (%.4f)",
                     roughness[r], mean[0], worst[0], terms[THETAS / 2].a_f[1], mean[1], worst[1], terms[THETAS / 2].a_b[1]);
        worst_all = fmax(worst_all, fmax(worst[0], worst[1]));
        hb_plan_destroy(plan);
    }
    CHECK(t, worst_all > 1e-4, "the recipe is as close as the quadrature (%.3g): the comparison measures nothing", worst_all);
}

const hb_test hb_tests_dual[] = {
    { "dual_lobe_energies", test_lobe_energies, 0 },
    { "dual_elliptical_orientations", test_elliptical_orientations, 0 },
    { "dual_lossless_sum", test_lossless_sum, 0 },
    { "dual_independent_rule", test_independent_rule, 0 },
    { "dual_back_scattering", test_back_scattering, 0 },
    { "dual_engine_recipe", test_engine_recipe, 0 },
    { NULL, NULL, 0 },
};

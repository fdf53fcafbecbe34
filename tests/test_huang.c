/* HHH22 R lobe: the closed form (App. A) against adaptive quadrature, the SIMD kernels against
 * the double reference for every integration method, NDF and fibre, the microsurface identities
 * (D and Smith G1), the forward-scattering focus of sec. 4.1.1, and the fibre's orientation. */
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "models/interface/plan.h"
#include "ref/reference.h"
#include "models/huang/reference.h"

#define DEG (M_PI / 180.0)

typedef struct huang_setup {
    double roughness, alpha, eccentricity;
    hb_ndf ndf;
    hb_shadowing shadowing;
    hb_r_integration integration;
    int panels;
    double step;
    hb_quality quality;
} huang_setup;

static hb_plan *huang_plan(hb_test_ctx *t, const huang_setup *s)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.roughness = s->roughness;
    m.alpha = s->alpha;
    m.eccentricity = s->eccentricity;
    m.ndf = s->ndf;
    o.model = HB_MODEL_HUANG;
    o.lobes = 1u << HB_LOBE_R;
    o.shadowing = s->shadowing;
    o.r_integration = s->integration;
    o.r_panels = s->panels;
    o.r_step = s->step;
    o.quality = s->quality;
    o.pole_floor = HB_POLE_FLOOR_BOUNDED; /* the kernels' choice at every quality: the errors are the quadratures' */
    o.isa = t->isa == HB_ISA_AUTO ? hb_isa_best() : t->isa;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "plan (r %g, alpha %g): %s", s->roughness, s->alpha,
          err.message);
    return plan;
}

/* Directions: a third near the R highlight (theta_o = -theta_i - 2 alpha), some grazing (|theta|
 * within 1e-2..1e-6 of pi/2), some with phi_o - phi_i within 1e-2..1e-6 of +-pi, the rest uniform.
 * With grazing = 0 no |theta| exceeds 1.55: without G the lobe grows as 1 / cos(theta_o), so a set
 * with grazing w_o has a peak (the metric of docs/conventions.md) orders of magnitude above the rest. */
enum { N = 240 };
static void directions(hb_test_ctx *t, double alpha, int grazing, float *ti, float *pi, float *to, float *po)
{
    for (int k = 0; k < N; k++) {
        ti[k] = (float)asin(hb_test_range(t, -1, 1));
        to[k] = (float)asin(hb_test_range(t, -1, 1));
        pi[k] = (float)hb_test_range(t, -M_PI, M_PI);
        po[k] = (float)hb_test_range(t, -M_PI, M_PI);
        double edge = pow(10.0, -2.0 - 4.0 * hb_test_uniform(t)), sign = k % 2 ? 1.0 : -1.0;
        switch (k % 6) {
        case 0: case 1:
            to[k] = (float)fmax(-1.55, fmin(1.55, -ti[k] - 2.0 * alpha + hb_test_range(t, -0.1, 0.1)));
            break;
        case 2:
            ti[k] = (float)(sign * (M_PI_2 - edge));
            break;
        case 3:
            to[k] = (float)(sign * (grazing ? M_PI_2 - edge : 1.55 - edge));
            break;
        case 4:
            po[k] = (float)(pi[k] + sign * (M_PI - edge));
            to[k] = k % 4 ? (float)-ti[k] : to[k];
            break;
        default:
            break;
        }
        if (!grazing)
            to[k] = (float)fmax(-1.55, fmin(1.55, to[k]));
    }
}

static double relative(double got, double want) { return fabs(got - want) / fmax(fabs(want), 1e-300); }

/* App. A's closed form equals the numeric integral without G to 1e-5 relative (double),
 * roughness 0.02..0.6, alpha 0, +-2, +-5 degrees, grazing theta and phi near +-pi included. */
static void analytic_matches_numeric_double(hb_test_ctx *t)
{
    static const double roughness[] = { 0.02, 0.05, 0.1, 0.2, 0.4, 0.6 };
    static const double alpha[] = { 0.0, 2 * DEG, -2 * DEG, 5 * DEG, -5 * DEG };
    float ti[N], pi[N], to[N], po[N];
    double worst = 0.0;
    int compared = 0;
    for (size_t r = 0; r < sizeof roughness / sizeof roughness[0]; r++)
        for (size_t a = 0; a < sizeof alpha / sizeof alpha[0]; a++) {
            huang_setup s = { roughness[r], alpha[a], 0.0, HB_NDF_GGX, HB_SHADOWING_NONE,
                              HB_R_INTEGRATION_ANALYTIC, 0, 0.0, HB_QUALITY_BALANCED };
            hb_plan *plan = huang_plan(t, &s);
            if (!plan)
                return;
            directions(t, alpha[a], 1, ti, pi, to, po);
            int cases = t->quick ? N / 8 : N;
            for (int k = 0; k < cases; k++) {
                double closed = hb_ref_huang_r_integral_analytic(plan, ti[k], pi[k], to[k], po[k]);
                double numeric = hb_ref_huang_r_integral(plan, ti[k], pi[k], to[k], po[k], 0);
                double e = relative(closed, numeric);
                if (numeric > 0.0)
                    compared++;
                if (e > worst)
                    worst = e;
                CHECK(t, e <= 1e-5, "r %g alpha %g (%g, %g, %g, %g): eq. 43 %.12g, quadrature %.12g", roughness[r],
                      alpha[a], ti[k], pi[k], to[k], po[k], closed, numeric);
            }
            hb_plan_destroy(plan);
        }
    hb_test_note(t, "eq. 43 vs adaptive quadrature: worst relative difference %.2e over %d non-zero cases", worst,
                 compared);
}

/* The SIMD kernel of a setup against the double reference of the same physics, the metric of docs/conventions.md. */
static double kernel_error(hb_test_ctx *t, const huang_setup *s, const float *ti, const float *pi, const float *to,
                           const float *po, int vectors)
{
    huang_setup reference = *s;
    reference.quality = HB_QUALITY_REFERENCE;
    reference.integration = HB_R_INTEGRATION_AUTO;
    reference.panels = 0;
    reference.step = 0.0;
    hb_plan *plan = huang_plan(t, s), *ref = huang_plan(t, &reference);
    static float f[3][N], g[3][N], w[6][N];
    float *fp[3] = { f[0], f[1], f[2] }, *gp[3] = { g[0], g[1], g[2] };
    double err = INFINITY;
    if (plan && ref) {
        hb_angles_soa in = { ti, pi, to, po };
        hb_eval_report report;
        if (vectors) {
            float *wp[6] = { w[0], w[1], w[2], w[3], w[4], w[5] };
            for (int k = 0; k < N; k++)
                hb_test_vectors_of(ti[k], pi[k], to[k], po[k], wp, (size_t)k);
            hb_vectors_soa vin = { w[0], w[1], w[2], w[3], w[4], w[5] };
            CHECK(t, hb_eval_vectors(plan, N, vin, (hb_rgb_soa){ f[0], f[1], f[2] }, &report) == HB_OK, "eval");
        } else {
            CHECK(t, hb_eval_angles(plan, N, in, (hb_rgb_soa){ f[0], f[1], f[2] }, &report) == HB_OK, "eval");
        }
        CHECK(t, report.invalid == 0, "%zu invalid samples", report.invalid);
        /* the reference sees the same float inputs: near the forward focus the window is as narrow as
         * pi - |phi|, which the rounding of angles to vectors changes by 1e-7 */
        if (vectors)
            CHECK(t, hb_eval_vectors(ref, N, (hb_vectors_soa){ w[0], w[1], w[2], w[3], w[4], w[5] },
                                     (hb_rgb_soa){ g[0], g[1], g[2] }, NULL) == HB_OK, "reference eval");
        else
            CHECK(t, hb_eval_angles(ref, N, in, (hb_rgb_soa){ g[0], g[1], g[2] }, NULL) == HB_OK, "reference eval");
        for (int k = 0; k < N; k++)
            CHECK(t, isfinite(f[0][k]) && f[0][k] >= 0.0f, "f = %g at (%g, %g, %g, %g)", f[0][k], ti[k], pi[k], to[k],
                  po[k]);
        size_t worst;
        err = hb_test_spec_error(fp, gp, N, &worst);
        if (err > 1e-3)
            hb_test_detail(t, "  worst (r %g alpha %g ndf %d G %d e %g): (%.9g, %.9g, %.9g, %.9g) f %.6g ref %.6g", s->roughness,
                         s->alpha, (int)s->ndf, (int)s->shadowing, s->eccentricity, ti[worst], pi[worst], to[worst],
                         po[worst], f[0][worst], g[0][worst]);
    }
    hb_plan_destroy(plan);
    hb_plan_destroy(ref);
    return err;
}

static const double kernel_roughness[] = { 0.02, 0.1, 0.3, 0.6 };
static const double kernel_alpha[] = { 0.0, 2 * DEG, -5 * DEG };

/* The worst error (docs/conventions.md) of a setup over roughness and tilt. */
static double worst_error(hb_test_ctx *t, huang_setup s, int vectors, int grazing)
{
    float ti[N], pi[N], to[N], po[N];
    double worst = 0.0;
    size_t roughnesses = sizeof kernel_roughness / sizeof kernel_roughness[0];
    size_t alphas = t->quick ? 1 : sizeof kernel_alpha / sizeof kernel_alpha[0]; /* quick tier: fewer cases */
    for (size_t r = t->quick ? 1 : 0; r < roughnesses; r += t->quick ? (t->emulated ? 4 : 2) : 1) /* emulated: one roughness */
        for (size_t a = 0; a < alphas; a++) {
            s.roughness = kernel_roughness[r];
            s.alpha = kernel_alpha[a];
            directions(t, s.alpha, grazing, ti, pi, to, po);
            double e = kernel_error(t, &s, ti, pi, to, po, vectors);
            if (e > worst)
                worst = e;
        }
    return worst;
}

/* The float closed form on this ISA against the double reference (the metric of docs/conventions.md), angles and vectors. */
static void analytic_kernel(hb_test_ctx *t)
{
    huang_setup s = { 0, 0, 0.0, HB_NDF_GGX, HB_SHADOWING_NONE, HB_R_INTEGRATION_ANALYTIC, 0, 0.0,
                      HB_QUALITY_BALANCED };
    double angles = worst_error(t, s, 0, 0), vectors = worst_error(t, s, 1, 0);
    hb_test_note(t, "analytic GGX R lobe vs double reference: %.2e (angles), %.2e (vectors)", angles, vectors);
    /* angles: near the peak D varies as 1/P-^2 with P- ~ r^2/2, so the float sines and cosines of the
     * inputs (6e-8) move f by about 2.4e-7 / r relative: 1.2e-5 at r = 0.02. Vectors form w_i + w_o in
     * double and are not limited by that. */
    CHECK(t, angles <= 5e-5, "analytic kernel error %.3e", angles);
    CHECK(t, vectors <= 2e-5, "analytic kernel error from vectors %.3e", vectors);
}

/* Simpson in the peak-following variable per quality, for both NDFs, with and without G, circular
 * and elliptical, against the reference (the metric of docs/conventions.md). The bounds are the errors measured when
 * the panel counts were chosen (docs/huang.md), with a factor 2 for other seeds and ISAs: they
 * guard against regressions. Smith G is what limits accuracy: it falls to 0 over about one
 * roughness at the window's ends, where the peak-following variable spaces its nodes widest. */
static void numeric_kernel(hb_test_ctx *t)
{
    static const struct {
        hb_ndf ndf;
        hb_shadowing shadowing;
        double eccentricity, bound[3]; /* fast, balanced, high */
    } families[] = {
        { HB_NDF_GGX, HB_SHADOWING_NONE, 0.0, { 2.5e-3, 4e-4, 6e-5 } },
        { HB_NDF_GGX, HB_SHADOWING_NONE, 0.8, { 7e-3, 1.5e-3, 2.5e-4 } },
        { HB_NDF_GGX, HB_SHADOWING_SMITH, 0.0, { 3.5e-2, 8e-3, 3.5e-3 } },
        { HB_NDF_GGX, HB_SHADOWING_SMITH, 0.8, { 7e-2, 3e-2, 5.5e-3 } }, /* fast: 4.8e-2 on the quick subset */
        { HB_NDF_BECKMANN, HB_SHADOWING_NONE, 0.0, { 1.4e-2, 1e-3, 1.6e-4 } },
        { HB_NDF_BECKMANN, HB_SHADOWING_NONE, 0.8, { 2.6e-2, 2e-3, 2e-4 } },
        { HB_NDF_BECKMANN, HB_SHADOWING_SMITH, 0.0, { 1.4e-2, 1e-3, 1.3e-4 } },
        { HB_NDF_BECKMANN, HB_SHADOWING_SMITH, 0.8, { 2.7e-2, 2e-3, 1.7e-4 } },
    };
    for (size_t k = 0; k < sizeof families / sizeof families[0]; k++)
        for (int q = HB_QUALITY_FAST; q <= HB_QUALITY_HIGH; q++) {
            huang_setup s = { 0, 0, families[k].eccentricity, families[k].ndf, families[k].shadowing,
                              HB_R_INTEGRATION_NUMERIC, 0, 0.0, (hb_quality)q };
            double e = worst_error(t, s, 0, 0);
            hb_test_note(t, "%s%s%s quality %d: %.2e", families[k].ndf ? "beckmann" : "ggx",
                         families[k].shadowing == HB_SHADOWING_SMITH ? " + G" : "",
                         families[k].eccentricity > 0.0 ? " e=0.8" : "", q, e);
            CHECK(t, e <= families[k].bound[q], "family %zu quality %d: error %.3e > %.1e", k, q, e,
                  families[k].bound[q]);
        }
}

/* Smith's G1 and the NDF satisfy the visible-area identity (Heitz 2014): for every direction w,
 * integral over the hemisphere of G1(w) max(0, w . w_h) D(w_h) dw_h = w . w_m; D alone integrates to 1
 * against cos (eq. 5). Both NDFs, several roughnesses and inclinations, in double. */
static void microsurface_identities(hb_test_ctx *t)
{
    static const double roughness[] = { 0.05, 0.2, 0.6, 1.0 };
    static const double theta_w[] = { 0.0, 0.5, 1.0, 1.4, 1.55 };
    enum { NT = 4000, NP = 256 };
    double worst = 0.0;
    for (int ndf = 0; ndf < 2; ndf++)
        for (size_t r = 0; r < sizeof roughness / sizeof roughness[0]; r++)
            for (size_t a = 0; a < sizeof theta_w / sizeof theta_w[0]; a++) {
                double cos_w = cos(theta_w[a]), sin_w = sin(theta_w[a]), norm = 0.0, visible = 0.0;
                double g1 = 1.0 / (1.0 + hb_ref_huang_lambda((hb_ndf)ndf, roughness[r], cos_w));
                /* w_h at polar angle u from w_m (midpoint in u^2 spacing to resolve a narrow peak) */
                for (int i = 0; i < NT; i++) {
                    double s0 = (double)i / NT, s1 = (i + 1.0) / NT;
                    double u0 = M_PI_2 * s0 * s0, u1 = M_PI_2 * s1 * s1, u = 0.5 * (u0 + u1);
                    double d = hb_ref_huang_ndf((hb_ndf)ndf, roughness[r], cos(u)) * sin(u) * (u1 - u0);
                    norm += d * cos(u) * 2.0 * M_PI;
                    for (int j = 0; j < NP; j++) {
                        double az = 2.0 * M_PI * (j + 0.5) / NP;
                        double dot = sin_w * sin(u) * cos(az) + cos_w * cos(u);
                        visible += g1 * fmax(dot, 0.0) * d * 2.0 * M_PI / NP;
                    }
                }
                double e = fmax(fabs(norm - 1.0), fabs(visible - cos_w));
                worst = fmax(worst, e);
                CHECK(t, e <= 2e-4, "%s r %g theta %g: integral of D cos %.6f, of G1 D <w, w_h> %.6f vs %.6f",
                      ndf ? "beckmann" : "ggx", roughness[r], theta_w[a], norm, visible, cos_w);
            }
    hb_test_note(t, "D normalisation and Smith visible-area identity: worst error %.1e", worst);
}

/* The forward-scattering focus of sec. 4.1.1 (without tilt the R lobe at theta_o =
 * -theta_i brightens toward |phi| -> pi: without G to within about two roughnesses of pi, as the
 * visible window (width pi - |phi|) narrows onto the microfacets facing w_h, and falls to 0 as the
 * window closes; with G until both directions graze the few normals left, the last 0.3 rad; with tilt phi = +-pi is unreachable at oblique theta_i, eq. 40), and the fibre's
 * orientation: a circular fibre depends on phi only, an elliptical one (e = 0.8) on phi_i and
 * phi_o (Fig. 11a). */
static void focus_and_orientation(hb_test_ctx *t)
{
    huang_setup flat = { 0.08, 0.0, 0.0, HB_NDF_GGX, HB_SHADOWING_NONE, HB_R_INTEGRATION_AUTO, 0, 0.0,
                         HB_QUALITY_HIGH };
    huang_setup tilted = flat, ellipse = flat, shadowed = flat;
    shadowed.shadowing = tilted.shadowing = ellipse.shadowing = HB_SHADOWING_SMITH;
    tilted.alpha = 4 * DEG;
    ellipse.eccentricity = 0.8;
    hb_plan *p0 = huang_plan(t, &flat), *p1 = huang_plan(t, &tilted), *p2 = huang_plan(t, &ellipse);
    hb_plan *p3 = huang_plan(t, &shadowed);
    if (!p0 || !p1 || !p2 || !p3)
        return;
    enum { M = 7 };
    static const float phi[M] = { 2.0f, 2.5f, 2.8f, 3.0f, 3.1f, 3.13f, 3.14f };
    float ti[M], pi[M], to[M], f[3][M], g[3][M], h[3][M];
    for (int k = 0; k < M; k++) {
        ti[k] = 0.5f;
        to[k] = -0.5f;
        pi[k] = 0.0f;
    }
    hb_eval_angles(p0, M, (hb_angles_soa){ ti, pi, to, phi }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    hb_eval_angles(p1, M, (hb_angles_soa){ ti, pi, to, phi }, (hb_rgb_soa){ g[0], g[1], g[2] }, NULL);
    hb_eval_angles(p3, M, (hb_angles_soa){ ti, pi, to, phi }, (hb_rgb_soa){ h[0], h[1], h[2] }, NULL);
    for (int k = 1; k < 4; k++) /* up to 3.0; closer to pi the window closes and f falls to 0 */
        CHECK(t, f[0][k] > f[0][k - 1], "alpha 0 without G: f(phi %g) = %g is not above f(phi %g) = %g", phi[k],
              f[0][k], phi[k - 1], f[0][k - 1]);
    CHECK(t, h[0][2] > 3.0f * h[0][0], "alpha 0 with G: f(2.8) = %g is not 3x f(2.0) = %g", h[0][2], h[0][0]);
    hb_test_note(t, "theta_o = -theta_i = -0.5, f at phi 2.0, 2.8, 3.14: %.3g, %.3g, %.3g (no G), %.3g, %.3g, %.3g (G), "
                 "%.3g, %.3g, %.3g (G, alpha 4 deg)", f[0][0], f[0][2], f[0][6], h[0][0], h[0][2], h[0][6], g[0][0],
                 g[0][2], g[0][6]);
    CHECK(t, g[0][6] == 0.0f, "alpha 4 deg: phi = 3.14 should be unreachable at theta_i 0.5, f = %g", g[0][6]);
    /* turning both directions about the fibre */
    float ta[8], pa[8], tb[8], pb[8], c[3][8], e[3][8];
    for (int k = 0; k < 8; k++) {
        ta[k] = 0.3f;
        tb[k] = -0.4f;
        pa[k] = (float)(-3.0 + 0.8 * k);
        pb[k] = pa[k] + 2.2f;
    }
    hb_eval_angles(p0, 8, (hb_angles_soa){ ta, pa, tb, pb }, (hb_rgb_soa){ c[0], c[1], c[2] }, NULL);
    hb_eval_angles(p2, 8, (hb_angles_soa){ ta, pa, tb, pb }, (hb_rgb_soa){ e[0], e[1], e[2] }, NULL);
    double spread_circle = 0.0, spread_ellipse = 0.0;
    for (int k = 1; k < 8; k++) {
        spread_circle = fmax(spread_circle, fabs(c[0][k] - c[0][0]) / c[0][0]);
        spread_ellipse = fmax(spread_ellipse, fabs(e[0][k] - e[0][0]) / e[0][0]);
    }
    hb_test_note(t, "turning the pair about the fibre: relative spread %.1e (circular), %.2f (e = 0.8)",
                 spread_circle, spread_ellipse);
    CHECK(t, spread_circle <= 2e-5, "circular fibre depends on phi_i: spread %g", spread_circle);
    CHECK(t, spread_ellipse >= 0.05, "elliptical fibre should depend on its orientation: spread %g", spread_ellipse);
    hb_plan_destroy(p0);
    hb_plan_destroy(p1);
    hb_plan_destroy(p2);
    hb_plan_destroy(p3);
}

/* Requests that cannot be met fail at plan creation with a message naming the reason. */
static void refusals(hb_test_ctx *t)
{
    static const struct {
        hb_ndf ndf;
        hb_shadowing shadowing;
        double eccentricity;
        hb_r_integration integration;
        unsigned lobes;
        hb_term term;
        const char *words;
    } cases[] = {
        { HB_NDF_BECKMANN, HB_SHADOWING_NONE, 0.0, HB_R_INTEGRATION_ANALYTIC, 1u, HB_TERM_FULL, "GGX only" },
        { HB_NDF_GGX, HB_SHADOWING_SMITH, 0.0, HB_R_INTEGRATION_ANALYTIC, 1u, HB_TERM_FULL, "no shadowing" },
        { HB_NDF_GGX, HB_SHADOWING_NONE, 0.5, HB_R_INTEGRATION_ANALYTIC, 1u, HB_TERM_FULL, "circular" },
        { HB_NDF_GGX, HB_SHADOWING_SMITH, 0.0, HB_R_INTEGRATION_AUTO, 15u, HB_TERM_FULL, "R, TT and TRT only" },
        { HB_NDF_GGX, HB_SHADOWING_SMITH, 0.0, HB_R_INTEGRATION_AUTO, 1u, HB_TERM_LONGITUDINAL, "not separable" },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        m.ndf = cases[k].ndf;
        m.eccentricity = cases[k].eccentricity;
        o.model = HB_MODEL_HUANG;
        o.shadowing = cases[k].shadowing;
        o.r_integration = cases[k].integration;
        o.lobes = cases[k].lobes;
        o.term = cases[k].term;
        hb_plan *plan = NULL;
        hb_error err;
        hb_status st = hb_plan_create(&m, &o, &plan, &err);
        CHECK(t, st == HB_ERR_UNSUPPORTED && !plan && strstr(err.message, cases[k].words),
              "case %zu: status %d, message '%s' (expected '%s')", k, (int)st, err.message, cases[k].words);
        hb_plan_destroy(plan);
    }
}

/* The white furnace of a lossless fibre near and at the poles (the float nearest pi/2 and the one
 * below it, both signs) stays bounded: eq. 10's width 2 cos(theta_o) is kept above the scales' and,
 * without G, the rough surface's own (docs/huang.md, "At the poles"). The bounds are the model's own
 * excess over 1 away from the poles (no G) and 1 with G. The paper's form, noted beside, grows as
 * 1 / cos(theta_o) at the float pole. */
static void pole_energy(hb_test_ctx *t)
{
    static const struct {
        const char *name;
        hb_ndf ndf;
        double roughness, alpha, eccentricity;
        hb_shadowing shadowing;
        unsigned lobes;
        double bound;
    } cases[] = {
        { "Beckmann 0.3, e 0.8, tilted, G, R", HB_NDF_BECKMANN, 0.3, 0.035, 0.8, HB_SHADOWING_SMITH, 1u, 1.0 },
        { "Beckmann 0.3, e 0.8, tilted, G, all", HB_NDF_BECKMANN, 0.3, 0.035, 0.8, HB_SHADOWING_SMITH, 7u, 1.0 },
        { "GGX 0.2, untilted, G, all", HB_NDF_GGX, 0.2, 0.0, 0.0, HB_SHADOWING_SMITH, 7u, 1.0 },
        { "GGX 0.02, tilted, no G, R", HB_NDF_GGX, 0.02, 0.035, 0.0, HB_SHADOWING_NONE, 1u, 1.35 },
        { "GGX 0.02, untilted, no G, R", HB_NDF_GGX, 0.02, 0.0, 0.0, HB_SHADOWING_NONE, 1u, 1.35 },
        { "Beckmann 0.02, tilted, no G, R", HB_NDF_BECKMANN, 0.02, -0.1, 0.0, HB_SHADOWING_NONE, 1u, 1.35 },
        { "GGX 0.2, tilted, no G, all", HB_NDF_GGX, 0.2, 0.035, 0.0, HB_SHADOWING_NONE, 7u, 1.35 },
    };
    static const double thetas[] = { 1.57079637f, 1.5707963f, 1.569, 1.56, 1.54, 1.52, 1.5 };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        m.eumelanin = m.pheomelanin = 0.0;
        m.ndf = cases[c].ndf, m.roughness = cases[c].roughness, m.alpha = cases[c].alpha;
        m.eccentricity = cases[c].eccentricity;
        o.model = HB_MODEL_HUANG, o.quality = HB_QUALITY_FAST, o.lobes = cases[c].lobes;
        o.shadowing = cases[c].shadowing, o.tt_trt = HB_TT_TRT_TABLE;
        hb_plan *plan;
        hb_error e;
        CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "%s: %s", cases[c].name, e.message);
        if (!plan)
            continue;
        double most = 0.0, at = 0.0;
        for (size_t k = 0; k < sizeof thetas / sizeof thetas[0]; k++)
            for (int side = -1; side <= 1; side += 2) {
                double energy[3] = { NAN, NAN, NAN };
                double theta = side * thetas[k] < -M_PI_2 ? -M_PI_2 : side * thetas[k] > M_PI_2 ? M_PI_2 : side * thetas[k];
                CHECK(t, hb_furnace(plan, theta, energy) == HB_OK, "%s: furnace at %.9g", cases[c].name, theta);
                CHECK(t, energy[0] >= 0.0 && energy[0] <= cases[c].bound, "%s: E(%.9g) = %.6g, above %g", cases[c].name,
                      theta, energy[0], cases[c].bound);
                if (!(energy[0] <= most))
                    most = energy[0], at = theta;
            }
        hb_plan_destroy(plan);
        o.pole_floor = HB_POLE_FLOOR_PAPER;
        double paper[3] = { NAN, NAN, NAN };
        CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "%s, the paper's form: %s", cases[c].name, e.message);
        CHECK(t, plan && hb_furnace(plan, -(double)1.57079637f < -M_PI_2 ? -M_PI_2 : -(double)1.57079637f, paper) == HB_OK,
              "%s: the paper's furnace", cases[c].name);
        hb_test_note(t, "%s: largest E %.4f at theta_o %.7f; the paper's form at theta_o = -pi/2: %.2g", cases[c].name,
                     most, at, paper[0]);
        hb_plan_destroy(plan);
    }
}

const hb_test hb_tests_huang[] = {
    { "huang_analytic_matches_numeric_double", analytic_matches_numeric_double, 0 },
    { "huang_analytic_kernel", analytic_kernel, 1 },
    { "huang_numeric_kernel", numeric_kernel, 1 },
    { "huang_microsurface_identities", microsurface_identities, 0 },
    { "huang_focus_and_orientation", focus_and_orientation, 1 },
    { "huang_refusals", refusals, 0 },
    { "huang_pole_energy", pole_energy, 0 },
    { NULL, NULL, 0 },
};

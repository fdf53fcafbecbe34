/* hb_assembly_dual (docs/multiple-scattering.md, "Dual scattering against the reference"): dual
 * scattering rendered through the same fibres as hb_assembly_trace. A slab of one fibre checks the
 * renderer: with d_f = d_b = 0 it is single scattering at the fibre the view sees, which equals the
 * traced light that scattered once, per side, within 3 standard errors of both. Then the error of
 * single scattering alone and of dual scattering against the traced light, per fibre, packing and
 * light angle, and the density factors d_f, d_b that fit the traced radiance best. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"

/* A plan of the default dFH11 material's look (hb_material_convert for another model). */
static hb_plan *dual_plan(hb_test_ctx *t, hb_model model, double eumelanin, double pheomelanin)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = eumelanin, m.pheomelanin = pheomelanin;
    o.model = model;
    hb_plan *plan = NULL;
    hb_error e;
    if (model != HB_MODEL_DEON)
        CHECK(t, hb_material_convert(&m, HB_MODEL_DEON, model, &m, &e) == HB_OK, "%s", e.message);
    CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "%s", e.message);
    return plan;
}

static hb_dual_table *table_of(hb_test_ctx *t, const hb_plan *plan, double d_f, double d_b)
{
    hb_dual_table *table = NULL;
    CHECK(t, hb_dual_table_create(plan, 64, d_f, d_b, NULL, NULL, NULL, NULL, &table) == HB_OK, "%s",
          hb_last_error()->message);
    return table;
}

static double bin_solid_angle(const hb_assembly *a, int i)
{
    return (sin(-M_PI_2 + M_PI * (i + 1) / a->theta_bins) - sin(-M_PI_2 + M_PI * i / a->theta_bins)) * 2.0 * M_PI /
           a->phi_bins;
}

/* A side's radiance bins integrated over their solid angles, green channel, and the standard error of
 * the sum (NULL se: none). */
static double side_total(const hb_assembly *a, const double *radiance, const double *se, int side, double *total_se)
{
    double sum = 0.0, var = 0.0;
    for (int i = 0; i < a->theta_bins; i++)
        for (int j = 0; j < a->phi_bins; j++) {
            size_t k = (size_t)((side * a->theta_bins + i) * a->phi_bins + j) * 3 + 1;
            double solid = bin_solid_angle(a, i);
            sum += radiance[k] * solid;
            if (se)
                var += se[k] * se[k] * solid * solid;
        }
    if (total_se)
        *total_se = sqrt(var);
    return sum;
}

static void test_one_fibre(hb_test_ctx *t)
{
    hb_plan *plan = dual_plan(t, HB_MODEL_DEON, 0.3, 0.0);
    hb_dual_table *none = plan ? table_of(t, plan, 0.0, 0.0) : NULL;
    if (!none) {
        hb_plan_destroy(plan);
        return;
    }
    hb_assembly a;
    hb_assembly_default(&a);
    a.layers = 1.0, a.period = 64, a.packing = M_PI / 256.0; /* one fibre in 64 x 1 diameters */
    a.theta_bins = 6, a.phi_bins = 12, a.paths = t->quick ? 400000 : 4000000;
    int rays = t->quick ? 4096 : 32768;
    size_t bins = (size_t)2 * a.theta_bins * a.phi_bins * 3;
    double *predicted = malloc(bins * sizeof(double)), *predicted_se = malloc(bins * sizeof(double));
    hb_assembly_result r = { .struct_size = sizeof r };
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_OK && r.fibres == 1, "trace: %ld fibres",
          r.fibres);
    CHECK(t, hb_assembly_dual(plan, none, &a, rays, predicted, predicted_se, NULL) == HB_OK, "%s", hb_last_error()->message);
    double worst = 0.0;
    for (int side = 0; side < 2 && !t->failures; side++) {
        double once = r.by_order[side][1][1], n = (double)a.paths;
        double once_se = sqrt(fmax(r.by_order_square[side][1][1] - once * once, 0.0) / (n - 1.0)), view_se;
        double view = side_total(&a, predicted, predicted_se, side, &view_se);
        double z = fabs(view - once) / hypot(once_se, view_se);
        worst = fmax(worst, z);
        CHECK(t, z < 3.0, "side %d: single scattering at the fibre the view sees %.6f +- %.6f, traced %.6f +- %.6f", side, view,
              view_se, once, once_se);
    }
    hb_test_note(t, "one dFH11 blond fibre: single scattering rendered from the view equals the traced light that scattered "
                    "once within %.2f standard errors on both sides (%lld paths, %d rays per bin)",
                 worst, a.paths, rays);
    free(predicted), free(predicted_se);
    hb_dual_table_destroy(none);
    hb_plan_destroy(plan);
}

/* The table an engine bakes by HDRP's recipe (hb_dual_terms_sampled, 128 directions x 90 azimuths at
 * each of 64 theta), with the density factors d_f, d_b. */
static hb_dual_table *recipe_table_of(hb_test_ctx *t, const hb_plan *plan, double d_f, double d_b)
{
    enum { THETAS = 64 };
    hb_dual_terms terms[THETAS];
    for (int k = 0; k < THETAS; k++) {
        terms[k].struct_size = sizeof terms[k];
        CHECK(t, hb_dual_terms_sampled(plan, -M_PI_2 + M_PI * (k + 0.5) / THETAS, 128, 90, d_b, &terms[k]) == HB_OK, "%s",
              hb_last_error()->message);
    }
    hb_dual_table *table = NULL;
    CHECK(t, hb_dual_table_from_terms(plan, THETAS, terms, d_f, d_b, &table) == HB_OK, "%s", hb_last_error()->message);
    return table;
}

/* hb_assembly_render's two pictures agree where they must: with d_f = d_b = 0 the dual picture is
 * single scattering at the fibres the camera sees, the traced light that scattered once, lit from
 * the front and from behind. For one fibre, in every pixel the trace resolves; for a bundle of
 * several, in total: the far field leaves a fibre from where the light met it and the camera sees
 * the fibre where its view ray meets it, two lines through the fibre that neighbours shadow
 * differently, so single scattering moves between neighbouring pixels (measured) and not in total. */
static void test_render_single(hb_test_ctx *t)
{
    enum { ROWS = 6, COLUMNS = 8, PIXELS = ROWS * COLUMNS * 3 };
    hb_plan *plan = dual_plan(t, HB_MODEL_DEON, 0.3, 0.0);
    hb_dual_table *none = plan ? table_of(t, plan, 0.0, 0.0) : NULL;
    if (!none) {
        hb_plan_destroy(plan);
        return;
    }
    static double traced[PIXELS], traced_se[PIXELS], once[PIXELS], dual[PIXELS], dual_se[PIXELS], single[PIXELS];
    static const struct { const char *name; double layers, packing; } bundles[] = { { "one fibre", 1.0, 0.25 },
                                                                                  { "a bundle of 7", 3.0, 0.2 } };
    for (int b = 0; b < 2; b++)
        for (int view = 0; view < 2; view++) {
            hb_assembly a;
            hb_assembly_default(&a);
            a.shape = HB_ASSEMBLY_BUNDLE, a.layers = bundles[b].layers, a.packing = bundles[b].packing;
            a.theta_bins = ROWS, a.phi_bins = 12, a.paths = t->quick ? 200000 : 2000000;
            hb_assembly_image im = { .struct_size = sizeof im, .view_phi = view ? M_PI : 0.0, .columns = COLUMNS,
                                     .rays = t->quick ? 256 : 2048, .traced = traced, .traced_se = traced_se,
                                     .traced_single = once, .dual = dual, .dual_se = dual_se, .dual_single = single };
            hb_assembly_result r = { .struct_size = sizeof r };
            CHECK(t, hb_assembly_render(plan, none, &a, &im, &r, NULL, NULL, NULL, NULL) == HB_OK, "%s",
                  hb_last_error()->message);
            double sum[2] = { 0.0, 0.0 }, var = 0.0, worst = 0.0;
            for (int k = 1; k < PIXELS; k += 3) { /* green */
                CHECK(t, dual[k] == single[k], "pixel %d: the dual picture without its term is not v f", k / 3);
                sum[0] += once[k], sum[1] += single[k];
                double pixel_var = traced_se[k] * traced_se[k] + dual_se[k] * dual_se[k];
                var += pixel_var;
                if (once[k] > 3.0 * traced_se[k]) /* the pixels the trace resolves; where no path arrived, its se is 0 */
                    worst = fmax(worst, fabs(once[k] - single[k]) / sqrt(pixel_var));
            }
            double z = fabs(sum[0] - sum[1]) / sqrt(var);
            hb_test_note(t, "%s (%ld), lit from %s, single scattering: traced %.4f, rendered %.4f (sum of L / E over the "
                            "pixels), %.2f standard errors; the worst pixel %.2f",
                         bundles[b].name, r.fibres, view ? "behind" : "the front", sum[0], sum[1], z, worst);
            CHECK(t, z < 3.0 && (b == 1 || worst < 4.0), "the pictures differ by %.2f standard errors in total, %.2f in "
                                                         "a pixel", z, worst);
            CHECK(t, sum[0] > 0.0, "no light reached the camera");
        }
    hb_dual_table_destroy(none);
    hb_plan_destroy(plan);
}

/* The tress of `hairbsdf tress` (docs/images/tress_blond_*.png): a blond dFH11 bundle of radius 8
 * diameters at packing 0.3, lit at theta 0.3, seen from the front and from behind, 24 x 32 pixels:
 * the pictures' sums, traced against dual scattering at the paper's density factors, with their
 * standard errors. Each picture holds more than its single scattering. */
static void test_render_tress(hb_test_ctx *t)
{
    enum { ROWS = 24, COLUMNS = 32, PIXELS = ROWS * COLUMNS * 3 };
    hb_plan *plan = dual_plan(t, HB_MODEL_DEON, 0.3, 0.0);
    hb_dual_table *table = plan ? table_of(t, plan, HB_DUAL_DENSITY, HB_DUAL_DENSITY) : NULL;
    if (!table) {
        hb_plan_destroy(plan);
        return;
    }
    static double traced[PIXELS], traced_se[PIXELS], once[PIXELS], dual[PIXELS], dual_se[PIXELS], single[PIXELS];
    hb_assembly a;
    hb_assembly_default(&a);
    a.shape = HB_ASSEMBLY_BUNDLE, a.theta_bins = ROWS, a.phi_bins = 24, a.paths = t->quick ? 100000 : 4000000;
    for (int view = 0; view < 2; view++) {
        hb_assembly_image im = { .struct_size = sizeof im, .view_phi = view ? M_PI : 0.0, .columns = COLUMNS,
                                 .rays = t->quick ? 16 : 256, .traced = traced, .traced_se = traced_se,
                                 .traced_single = once, .dual = dual, .dual_se = dual_se, .dual_single = single };
        CHECK(t, hb_assembly_render(plan, table, &a, &im, NULL, NULL, NULL, NULL, NULL) == HB_OK, "%s",
              hb_last_error()->message);
        double sum[4] = { 0, 0, 0, 0 }, var[2] = { 0, 0 };
        for (int k = 1; k < PIXELS; k += 3) {
            sum[0] += traced[k], sum[1] += dual[k], sum[2] += once[k], sum[3] += single[k];
            var[0] += traced_se[k] * traced_se[k], var[1] += dual_se[k] * dual_se[k];
        }
        double ratio = sum[1] / sum[0], ratio_se = ratio * hypot(sqrt(var[0]) / sum[0], sqrt(var[1]) / sum[1]);
        hb_test_note(t, "blond tress seen from %-9s: traced %.3f +- %.3f (single scattering %.3f), dual %.3f +- %.3f "
                        "(v f %.3f): dual %+.1f%% +- %.1f%% (green, sum of L / E)",
                     view ? "behind" : "the front", sum[0], sqrt(var[0]), sum[2], sum[1], sqrt(var[1]), sum[3],
                     100.0 * (ratio - 1.0), 100.0 * ratio_se);
        CHECK(t, sum[0] > sum[2] && sum[1] > sum[3] && isfinite(ratio), "a picture without its multiple scattering: "
              "traced %g (single %g), dual %g (v f %g)", sum[0], sum[2], sum[1], sum[3]);
    }
    hb_dual_table_destroy(table);
    hb_plan_destroy(plan);
}

/* The traced reflected light and what single scattering alone and dual scattering predict, green;
 * dual_recipe: dual scattering from the recipe's table (recipe NULL: not computed). */
typedef struct cell_result {
    double traced, traced_se, single, dual, dual_recipe, median_bin;
} cell_result;

static void compare(hb_test_ctx *t, const hb_plan *plan, const hb_dual_table *table, const hb_dual_table *recipe,
                    const hb_assembly *a, int rays, cell_result *out)
{
    size_t bins = (size_t)2 * a->theta_bins * a->phi_bins * 3;
    double *traced = malloc(bins * sizeof(double)), *traced_se = malloc(bins * sizeof(double));
    double *dual = malloc(bins * sizeof(double)), *single = malloc(bins * sizeof(double));
    hb_assembly_result r = { .struct_size = sizeof r, .radiance = traced, .radiance_se = traced_se };
    CHECK(t, hb_assembly_trace(plan, a, &r, NULL, NULL, NULL, NULL) == HB_OK, "%s", hb_last_error()->message);
    CHECK(t, hb_assembly_dual(plan, table, a, rays, dual, NULL, single) == HB_OK, "%s", hb_last_error()->message);
    out->traced = side_total(a, traced, traced_se, 0, &out->traced_se);
    out->single = side_total(a, single, NULL, 0, NULL);
    out->dual = side_total(a, dual, NULL, 0, NULL);
    out->dual_recipe = NAN;
    if (recipe) {
        double *by_recipe = malloc(bins * sizeof(double));
        CHECK(t, hb_assembly_dual(plan, recipe, a, rays, by_recipe, NULL, NULL) == HB_OK, "%s", hb_last_error()->message);
        out->dual_recipe = side_total(a, by_recipe, NULL, 0, NULL);
        free(by_recipe);
    }
    double *errors = malloc(bins * sizeof(double));
    int count = 0;
    for (size_t k = 1; k < bins / 2; k += 3) /* the reflected bins the trace resolves */
        if (traced[k] > 3.0 * traced_se[k])
            errors[count++] = fabs(dual[k] / traced[k] - 1.0);
    for (int i = 1; i < count; i++) /* insertion sort for the median */
        for (int j = i; j > 0 && errors[j - 1] > errors[j]; j--) {
            double x = errors[j];
            errors[j] = errors[j - 1], errors[j - 1] = x;
        }
    out->median_bin = count ? errors[count / 2] : NAN;
    CHECK(t, out->dual >= out->single && isfinite(out->dual), "dual scattering adds light: %g against %g", out->dual,
          out->single);
    free(errors), free(traced), free(traced_se), free(dual), free(single);
}

static const struct fibre {
    const char *name;
    double eumelanin, pheomelanin;
} fibres[] = { { "lossless", 0.0, 0.0 }, { "blond", 0.3, 0.0 }, { "brown", 1.3, 0.0 }, { "black", 8.0, 0.0 }, { "red", 0.0, 2.0 } };

static double percent(double x, double reference) { return 100.0 * (x / reference - 1.0); }

static void test_errors(hb_test_ctx *t)
{
    static const double packings[] = { 0.1, 0.3 }, thetas[] = { 0.0, 0.6 };
    long long paths = t->quick ? 20000 : 200000;
    int rays = t->quick ? 64 : 512;
    static const hb_model models[] = { HB_MODEL_DEON, HB_MODEL_CHIANG };
    static const char *const model_names[] = { "dFH11", "CBTB16" };
    hb_test_note(t, "slab of 8 layers lit from above (phi 0), the reflected light (the backward hemisphere), green; "
                    "%lld paths, %d view rays per bin; d_f = d_b = 0.7; CBTB16 of dFH11's look (hb_material_convert):",
                 paths, rays);
    hb_test_note(t, "model  fibre     packing theta  traced             single alone  dual scattering  median bin (dual)  "
                    "dual, HDRP's table");
    for (size_t mi = 0; mi < (t->quick ? 1u : 2u); mi++) {
        for (size_t m = t->quick ? 1 : 0; m < (t->quick ? 2 : sizeof fibres / sizeof fibres[0]); m++) {
            hb_plan *plan = dual_plan(t, models[mi], fibres[m].eumelanin, fibres[m].pheomelanin);
            hb_dual_table *table = plan ? table_of(t, plan, HB_DUAL_DENSITY, HB_DUAL_DENSITY) : NULL;
            hb_dual_table *recipe = plan ? recipe_table_of(t, plan, HB_DUAL_DENSITY, HB_DUAL_DENSITY) : NULL;
            for (size_t p = t->quick ? 1 : 0; table && p < 2; p++)
                for (size_t l = 0; l < (t->quick ? 1u : 2u); l++) {
                    hb_assembly a;
                    hb_assembly_default(&a);
                    a.packing = packings[p], a.theta_light = thetas[l], a.paths = paths;
                    cell_result c;
                    compare(t, plan, table, recipe, &a, rays, &c);
                    hb_test_note(t, "%-6s %-9s %7.2f %5.1f  %.5f +- %.5f  %+6.1f%%       %+6.1f%%          %5.1f%%"
                                    "             %+6.1f%%",
                                 model_names[mi], fibres[m].name,
                                 a.packing, a.theta_light, c.traced, c.traced_se, percent(c.single, c.traced),
                                 percent(c.dual, c.traced), 100.0 * c.median_bin, percent(c.dual_recipe, c.traced));
                }
            hb_dual_table_destroy(table);
            hb_dual_table_destroy(recipe);
            hb_plan_destroy(plan);
        }
    }
}

/* d_f and d_b on a grid of tenths, for blond hair in the default slab: the pair whose prediction of
 * both sides' bins has the least chi-square against the trace (f_DS is linear in d_f, so two
 * tables per d_b give every d_f), beside the paper's 0.7 and the factor on f_DS alone that makes the
 * reflected light right. */
static void test_density_fit(hb_test_ctx *t)
{
    hb_plan *plan = dual_plan(t, HB_MODEL_DEON, 0.3, 0.0);
    if (!plan)
        return;
    hb_assembly a;
    hb_assembly_default(&a);
    a.paths = t->quick ? 20000 : 400000;
    int rays = t->quick ? 64 : 512, steps = t->quick ? 2 : 10;
    size_t bins = (size_t)2 * a.theta_bins * a.phi_bins * 3;
    double *traced = malloc(bins * sizeof(double)), *traced_se = malloc(bins * sizeof(double));
    double *p0 = malloc(bins * sizeof(double)), *p1 = malloc(bins * sizeof(double)), *single = malloc(bins * sizeof(double));
    hb_assembly_result r = { .struct_size = sizeof r, .radiance = traced, .radiance_se = traced_se };
    CHECK(t, hb_assembly_trace(plan, &a, &r, NULL, NULL, NULL, NULL) == HB_OK, "%s", hb_last_error()->message);
    double best = INFINITY, best_f = 0.0, best_b = 0.0, paper = NAN, reflected_se;
    double reflected = side_total(&a, traced, traced_se, 0, &reflected_se), transmitted = side_total(&a, traced, traced_se, 1, NULL);
    double best_sides[2] = { 0, 0 }, paper_sides[2] = { 0, 0 }, single_reflected = 0.0;
    for (int s = 1; s <= steps && !t->failures; s++) {
        double d_b = (double)s / steps;
        hb_dual_table *zero = table_of(t, plan, 0.0, d_b), *one = table_of(t, plan, 1.0, d_b);
        if (zero && one) {
            hb_assembly_dual(plan, zero, &a, rays, p0, NULL, single);
            hb_assembly_dual(plan, one, &a, rays, p1, NULL, NULL);
            single_reflected = side_total(&a, single, NULL, 0, NULL);
        }
        for (int q = 0; zero && one && q <= steps; q++) {
            double d_f = (double)q / steps, chi2 = 0.0, sides[2] = { 0, 0 };
            for (int side = 0; side < 2; side++)
                for (int i = 0; i < a.theta_bins; i++)
                    for (int j = 0; j < a.phi_bins; j++) {
                        size_t k = (size_t)((side * a.theta_bins + i) * a.phi_bins + j) * 3 + 1;
                        double predicted = p0[k] + d_f * (p1[k] - p0[k]);
                        sides[side] += predicted * bin_solid_angle(&a, i);
                        if (traced[k] > 3.0 * traced_se[k])
                            chi2 += pow((predicted - traced[k]) / traced_se[k], 2.0);
                    }
            if (chi2 < best)
                best = chi2, best_f = d_f, best_b = d_b, best_sides[0] = sides[0], best_sides[1] = sides[1];
            if (fabs(d_f - 0.7) < 1e-9 && fabs(d_b - 0.7) < 1e-9)
                paper = chi2, paper_sides[0] = sides[0], paper_sides[1] = sides[1];
        }
        hb_dual_table_destroy(zero);
        hb_dual_table_destroy(one);
    }
    CHECK(t, isfinite(best) && best_sides[0] > 0.0, "a fit: chi-square %g", best);
    hb_test_note(t, "dFH11 blond, the default slab (8 layers, packing %.2f, light at theta %.1f), %lld paths, green: traced "
                    "reflected %.5f +- %.5f, transmitted %.5f",
                 r.packing, a.theta_light, a.paths, reflected, reflected_se, transmitted);
    if (!isnan(paper))
        hb_test_note(t, "the paper's d_f = d_b = 0.7: reflected %+.1f%%, transmitted %+.1f%%, chi-square %.0f over the bins",
                     percent(paper_sides[0], reflected), percent(paper_sides[1], transmitted), paper);
    hb_test_note(t, "the best of d_f, d_b in tenths of [0, 1]: d_f = %.1f, d_b = %.1f: reflected %+.1f%%, transmitted %+.1f%%, "
                    "chi-square %.0f",
                 best_f, best_b, percent(best_sides[0], reflected), percent(best_sides[1], transmitted), best);
    if (!isnan(paper) && paper_sides[0] > single_reflected)
        hb_test_note(t, "f_DS at 0.7 would need a factor %.2f to make the reflected light right",
                     (reflected - single_reflected) / (paper_sides[0] - single_reflected));
    free(traced), free(traced_se), free(p0), free(p1), free(single);
    hb_plan_destroy(plan);
}

static void test_refusals(hb_test_ctx *t)
{
    hb_plan *plan = dual_plan(t, HB_MODEL_DEON, 0.3, 0.0);
    hb_dual_table *table = plan ? table_of(t, plan, 0.7, 0.7) : NULL;
    if (!table) {
        hb_plan_destroy(plan);
        return;
    }
    hb_assembly a;
    hb_assembly_default(&a);
    double out[2 * 18 * 36 * 3];
    a.shape = HB_ASSEMBLY_BUNDLE;
    CHECK(t, hb_assembly_dual(plan, table, &a, 16, out, NULL, NULL) == HB_ERR_UNSUPPORTED &&
                 strstr(hb_last_error()->message, "slab"),
          "a bundle: %s", hb_last_error()->message);
    a.shape = HB_ASSEMBLY_SLAB, a.packing = 0.7;
    CHECK(t, hb_assembly_dual(plan, table, &a, 16, out, NULL, NULL) == HB_ERR_PARAM && strstr(hb_last_error()->message, "packing"),
          "packing 0.7: %s", hb_last_error()->message);
    a.packing = 0.3;
    CHECK(t, hb_assembly_dual(plan, table, &a, 0, out, NULL, NULL) == HB_ERR_PARAM && strstr(hb_last_error()->message, "rays"),
          "no rays: %s", hb_last_error()->message);
    CHECK(t, hb_assembly_dual(plan, table, &a, 16, NULL, NULL, NULL) == HB_ERR_NULL, "no radiance");
    hb_dual_table_destroy(table);
    hb_plan_destroy(plan);
}

const hb_test hb_tests_assembly_dual[] = {
    { "assembly_render_single", test_render_single, 0 },
    { "assembly_render_tress", test_render_tress, 0 },
    { "assembly_dual_one_fibre", test_one_fibre, 0 },
    { "assembly_dual_errors", test_errors, 0 },
    { "assembly_dual_density_fit", test_density_fit, 0 },
    { "assembly_dual_refusals", test_refusals, 0 },
    { NULL, NULL, 0 },
};

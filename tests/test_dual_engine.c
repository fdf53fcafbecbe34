/* The engines' way of baking the dual-scattering terms, and one engine-wide table for every colour
 * (docs/multiple-scattering.md, "The engines' tables" and "One table for every hair colour"):
 * hb_dual_terms_sampled converges to hb_dual_terms_at as its points grow; hb_dual_engine reproduces
 * the converged terms of a fibre whose roughness and absorption lie on its nodes, and between them
 * misses the per-material terms by what its interpolation costs, printed beside the same table
 * built by HDRP's estimate at HDRP's counts; a plan's table from it is what hb_dual_eval and the
 * shaders read; saved and loaded it is the same table; what it cannot serve is refused by name. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"

static hb_plan *deon_plan(hb_test_ctx *t, double beta_m, double eumelanin, double pheomelanin, const double sigma_a[3])
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.beta_m = beta_m, m.eumelanin = eumelanin, m.pheomelanin = pheomelanin;
    if (sigma_a)
        memcpy(m.sigma_a, sigma_a, sizeof m.sigma_a);
    hb_plan *plan = NULL;
    hb_error e;
    CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "%s", e.message);
    return plan;
}

/* The estimate against the quadrature, dFH11 blond, smooth and rough, at 512, 2048 and (long tier)
 * 8192 directions x 256 azimuths: a quasi-Monte Carlo rule in (sin theta_o, which half of the
 * azimuths a row covers), its error falls about as 1 / directions. */
static double sampled_error(hb_test_ctx *t, const hb_plan *plan, int directions)
{
    double worst = 0.0;
    for (int k = 0; k < 3; k++) {
        double theta = -0.9 + 0.8 * k;
        hb_dual_terms exact = { .struct_size = sizeof exact }, sampled = { .struct_size = sizeof sampled };
        CHECK(t, hb_dual_terms_at(plan, theta, HB_DUAL_DENSITY, &exact) == HB_OK &&
                     hb_dual_terms_sampled(plan, theta, directions, 256, HB_DUAL_DENSITY, &sampled) == HB_OK,
              "%s", hb_last_error()->message);
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fmax(fabs(exact.a_f[c] - sampled.a_f[c]), fabs(exact.a_b[c] - sampled.a_b[c])));
    }
    return worst;
}

static void test_sampled_converges(hb_test_ctx *t)
{
    static const double roughness[] = { 0.1, 0.4 };
    for (int r = 0; r < 2; r++) {
        hb_plan *plan = deon_plan(t, roughness[r], 0.3, 0.0, NULL);
        if (!plan)
            return;
        double err[3] = { sampled_error(t, plan, 512), sampled_error(t, plan, 2048),
                          t->quick ? 0.0 : sampled_error(t, plan, 8192) };
        hb_test_note(t, "beta_m %.1f: a_f and a_b within %.1e, %.1e%s%.1e of the quadrature at 512, 2048%s directions x "
                        "256 azimuths", roughness[r], err[0], err[1], t->quick ? "" : ", ", err[2],
                     t->quick ? "" : " and 8192");
        CHECK(t, err[1] < 0.5 * err[0], "2048 directions (%.3g) do no better than 512 (%.3g)", err[1], err[0]);
        CHECK(t, t->quick || err[2] < 0.5 * err[1], "8192 directions (%.3g) do no better than 2048 (%.3g)", err[2], err[1]);
        CHECK(t, err[t->quick ? 1 : 2] <= 1e-3, "the estimate misses by %.3g", err[t->quick ? 1 : 2]);
        hb_plan_destroy(plan);
    }
    hb_dual_terms d = { .struct_size = sizeof d };
    hb_plan *plan = deon_plan(t, 0.2, 0.3, 0.0, NULL);
    if (!plan)
        return;
    CHECK(t, hb_dual_terms_sampled(plan, 0.1, 0, 90, 0.7, &d) == HB_ERR_PARAM &&
                 strstr(hb_last_error()->message, "directions"), "0 directions: %s", hb_last_error()->message);
    CHECK(t, hb_dual_terms_sampled(plan, 0.1, 128, 70000, 0.7, &d) == HB_ERR_PARAM &&
                 strstr(hb_last_error()->message, "azimuths"), "70000 azimuths: %s", hb_last_error()->message);
    CHECK(t, hb_dual_terms_sampled(plan, 1.6, 128, 90, 0.7, &d) == HB_ERR_PARAM, "theta 1.6 accepted");
    hb_plan_destroy(plan);
}

hb_dual_engine *hb_test_dual_engine(hb_test_ctx *t, const hb_dual_engine_axes *axes)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    hb_dual_engine *e = NULL;
    hb_error error;
    CHECK(t, hb_dual_engine_create(&m, &o, axes, HB_DUAL_DENSITY, &e, &error) == HB_OK, "%s", error.message);
    return e;
}

static double node_absorption(const hb_dual_engine_axes *a, int j)
{
    return -log(1.0 - (1.0 - exp(-a->absorption_max)) * j / (a->absorptions - 1));
}

/* The largest relative difference (floor 1e-3) between the plan's hb_dual_terms_at and the engine's
 * lookup at roughness and the plan's absorptions sigma_a, over the engine's theta nodes. */
static double node_error(hb_test_ctx *t, const hb_plan *plan, const hb_dual_engine *e, int thetas, double roughness,
                         const double sigma_a[3])
{
    double worst = 0.0;
    for (int k = 0; k < thetas; k++) {
        double theta = -M_PI_2 + M_PI * (k + 0.5) / thetas;
        hb_dual_terms exact = { .struct_size = sizeof exact }, table = { .struct_size = sizeof table };
        CHECK(t, hb_dual_terms_at(plan, theta, HB_DUAL_DENSITY, &exact) == HB_OK &&
                     hb_dual_engine_terms(e, theta, roughness, sigma_a, &table) == HB_OK,
              "%s", hb_last_error()->message);
        const double *x = &exact.a_f[0], *y = &table.a_f[0];
        for (int q = 0; q < 27; q++)
            worst = fmax(worst, fabs(x[q] - y[q]) / fmax(1e-3, fabs(x[q])));
    }
    return worst;
}

/* On its nodes the table is the quadrature: a fibre at roughness node 1 with absorption nodes 0, 2
 * and 3 as its channels, at the theta nodes, gives hb_dual_terms_at's terms. */
static void test_engine_nodes(hb_test_ctx *t)
{
    hb_dual_engine_axes a;
    hb_dual_engine_axes_default(&a);
    a.thetas = 8, a.roughnesses = 3, a.absorptions = 5, a.roughness_min = 0.1, a.roughness_max = 0.3;
    hb_dual_engine *e = hb_test_dual_engine(t, &a);
    double sigma_a[3] = { node_absorption(&a, 0), node_absorption(&a, 2), node_absorption(&a, 3) };
    hb_plan *plan = deon_plan(t, 0.2, 0.0, 0.0, sigma_a);
    if (!e || !plan)
        return;
    double worst = node_error(t, plan, e, a.thetas, 0.2, sigma_a);
    hb_test_note(t, "on its nodes the engine table gives the quadrature's terms within %.1e", worst);
    CHECK(t, worst <= 1e-12, "the table's nodes differ from the quadrature by %.3g", worst);

    /* a plan's table at the engine's thetas is the engine's lookup, and hb_dual_eval reads it */
    hb_dual_table *table = NULL;
    CHECK(t, hb_dual_engine_table(e, plan, HB_DUAL_DENSITY, &table) == HB_OK, "%s", hb_last_error()->message);
    if (table) {
        double largest = 0.0;
        for (int k = 0; k < 9; k++) {
            double theta = -1.57 + 0.39 * k;
            hb_dual_terms from_table = { .struct_size = sizeof from_table }, lookup = { .struct_size = sizeof lookup };
            CHECK(t, hb_dual_table_terms(table, theta, &from_table) == HB_OK &&
                         hb_dual_engine_terms(e, theta, 0.2, sigma_a, &lookup) == HB_OK, "%s", hb_last_error()->message);
            const double *x = &from_table.a_f[0], *y = &lookup.a_f[0];
            for (int q = 0; q < 27; q++)
                largest = fmax(largest, fabs(x[q] - y[q]));
        }
        CHECK(t, largest == 0.0, "the plan's table and the engine's lookup differ by %.3g", largest);
        float ti[1] = { 0.3f }, pi[1] = { 0.0f }, to[1] = { 0.2f }, po[1] = { 3.0f }, n[1] = { 2.0f }, f[3][1];
        hb_eval_report report;
        CHECK(t, hb_dual_eval(table, 1, (hb_angles_soa){ ti, pi, to, po }, n, NULL, (hb_rgb_soa){ f[0], f[1], f[2] },
                              &report) == HB_OK && report.invalid == 0 && f[1][0] > 0.0f,
              "hb_dual_eval of the engine's table: %s", hb_last_error()->message);
        hb_dual_table_destroy(table);
    }
    /* what the table cannot serve */
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eta = 1.6;
    hb_plan *other = NULL;
    hb_error error;
    CHECK(t, hb_plan_create(&m, &o, &other, &error) == HB_OK, "%s", error.message);
    CHECK(t, hb_dual_engine_table(e, other, HB_DUAL_DENSITY, &table) == HB_ERR_PARAM && !table &&
                 strstr(hb_last_error()->message, "eta"), "eta 1.6: %s", hb_last_error()->message);
    hb_plan_destroy(other);
    o.model = HB_MODEL_CHIANG;
    CHECK(t, hb_plan_create(&m, &o, &other, &error) == HB_OK, "%s", error.message);
    CHECK(t, hb_dual_engine_table(e, other, HB_DUAL_DENSITY, &table) == HB_ERR_PARAM && strstr(hb_last_error()->message,
                                                                                                 "model"),
          "a CBTB16 plan: %s", hb_last_error()->message);
    hb_plan_destroy(other);
    hb_dual_engine_axes bad = a;
    bad.roughness_min = 0.0;
    hb_dual_engine *none = NULL;
    CHECK(t, hb_dual_engine_create(&m, &o, &bad, 0.7, &none, &error) == HB_ERR_PARAM && !none &&
                 strstr(error.message, "roughness"), "roughness axis from 0: %s", error.message);
    bad = a, bad.sampled_directions = 128;
    CHECK(t, hb_dual_engine_create(&m, &o, &bad, 0.7, &none, &error) == HB_ERR_PARAM && strstr(error.message, "sampled"),
          "directions without azimuths: %s", error.message);
    hb_plan_destroy(plan);
    hb_dual_engine_destroy(e);
}

/* The engine of another model's family: a CBTB16 base at 4 thetas x 2 roughnesses x 3 absorptions, on
 * its nodes, against hb_dual_terms_at of the base with the node's R width (the beta_m
 * hb_material_convert gives a dFH11 material of that beta_m) and the nodes' absorptions as its
 * channels. */
static void test_engine_other_model(hb_test_ctx *t)
{
    hb_dual_engine_axes a;
    hb_dual_engine_axes_default(&a);
    a.thetas = 4, a.roughnesses = 2, a.absorptions = 3, a.roughness_min = 0.15, a.roughness_max = 0.3;
    hb_material base, look, m;
    hb_options o;
    hb_material_default(&base);
    hb_options_default(&o);
    o.model = HB_MODEL_CHIANG;
    hb_dual_engine *e = NULL;
    hb_error error;
    CHECK(t, hb_dual_engine_create(&base, &o, &a, HB_DUAL_DENSITY, &e, &error) == HB_OK, "%s", error.message);
    hb_material_default(&look);
    look.beta_m = 0.3;
    CHECK(t, hb_material_convert(&look, HB_MODEL_DEON, HB_MODEL_CHIANG, &m, &error) == HB_OK, "%s", error.message);
    double beta_m = m.beta_m; /* the look's R width alone: every other field is the base's */
    m = base;
    m.beta_m = beta_m;
    m.eumelanin = m.pheomelanin = 0.0;
    for (int c = 0; c < 3; c++)
        m.sigma_a[c] = node_absorption(&a, c);
    hb_plan *plan = NULL;
    CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_OK, "%s", error.message);
    if (!e || !plan)
        return;
    double worst = node_error(t, plan, e, a.thetas, 0.3, m.sigma_a);
    hb_test_note(t, "CBTB16: on its nodes the engine table gives the quadrature's terms within %.1e", worst);
    CHECK(t, worst <= 1e-12, "CBTB16: the table's nodes differ from the quadrature by %.3g", worst);
    hb_plan_destroy(plan);
    hb_dual_engine_destroy(e);
}

/* Between its nodes: the default axes (64 theta x 16 roughnesses in [0.05, 0.6] x 16 absorptions),
 * converged and by HDRP's estimate, against each fibre's own terms at the 64 theta, for dFH11 fibres
 * lossless, blond, brown, black and red at roughnesses between the nodes. */
typedef struct errors {
    double a_max, a_mean, shift_max, width_max;
} errors;

static void add_errors(errors *err, const hb_dual_terms *exact, const hb_dual_terms *table, double count)
{
    for (int c = 0; c < 3; c++) {
        double da = fmax(fabs(exact->a_f[c] - table->a_f[c]), fabs(exact->a_b[c] - table->a_b[c]));
        err->a_max = fmax(err->a_max, da), err->a_mean += da / count;
        err->shift_max = fmax(err->shift_max, fabs(exact->alpha_f[c] - table->alpha_f[c]));
        err->width_max = fmax(err->width_max, fabs(sqrt(exact->beta_f2[c]) - sqrt(table->beta_f2[c])));
    }
}

static void test_engine_between_nodes(hb_test_ctx *t)
{
    enum { THETAS = 64 };
    static const struct { const char *name; double eumelanin, pheomelanin; } fibres[] = {
        { "lossless", 0, 0 }, { "blond", 0.3, 0 }, { "brown", 1.3, 0 }, { "black", 8, 0 }, { "red", 0, 2 },
    };
    static const double roughness[] = { 0.08, 0.14, 0.25, 0.45 };
    hb_dual_engine_axes a, sampled;
    hb_dual_engine_axes_default(&a);
    if (t->quick)
        a.thetas = 16, a.roughnesses = 4, a.absorptions = 6;
    sampled = a, sampled.sampled_directions = 128, sampled.sampled_azimuths = 90;
    hb_dual_engine *tables[2] = { hb_test_dual_engine(t, &a), t->quick ? NULL : hb_test_dual_engine(t, &sampled) };
    if (!tables[0])
        return;
    hb_test_note(t, "engine-wide table (%d theta x %d roughness in [%.2f, %.2f] x %d absorption), dFH11, against each "
                    "fibre's own terms at its %d theta: |a_f|, |a_b| error max / mean, alpha_f and beta_f max (rad)",
                 a.thetas, a.roughnesses, a.roughness_min, a.roughness_max, a.absorptions, a.thetas);
    static hb_dual_terms exact[THETAS];
    double worst[2] = { 0.0, 0.0 }, mean[2] = { 0.0, 0.0 };
    int rows = t->quick ? 2 : 4;
    for (int r = 0; r < rows; r++) {
        errors err[2];
        memset(err, 0, sizeof err);
        for (size_t f = 0; f < sizeof fibres / sizeof *fibres; f++) {
            if (t->quick && f % 2)
                continue;
            hb_plan *plan = deon_plan(t, roughness[r], fibres[f].eumelanin, fibres[f].pheomelanin, NULL);
            if (!plan)
                return;
            exact[0].struct_size = sizeof exact[0];
            CHECK(t, hb_dual_terms_grid(plan, a.thetas, HB_DUAL_DENSITY, exact, NULL, NULL, NULL, NULL) == HB_OK, "%s",
                  hb_last_error()->message);
            double sigma_a[3];
            hb_material m;
            hb_material_default(&m);
            m.eumelanin = fibres[f].eumelanin, m.pheomelanin = fibres[f].pheomelanin;
            hb_material_absorption(&m, sigma_a);
            for (int b = 0; b < 2; b++) {
                if (!tables[b])
                    continue;
                for (int k = 0; k < a.thetas; k++) {
                    hb_dual_terms table = { .struct_size = sizeof table };
                    CHECK(t, hb_dual_engine_terms(tables[b], -M_PI_2 + M_PI * (k + 0.5) / a.thetas, roughness[r], sigma_a,
                                                  &table) == HB_OK, "%s", hb_last_error()->message);
                    add_errors(&err[b], &exact[k], &table, 3.0 * a.thetas * (t->quick ? 3 : 5));
                }
            }
            hb_plan_destroy(plan);
        }
        for (int b = 0; b < 2; b++) {
            if (!tables[b])
                continue;
            hb_test_note(t, "beta_m %.2f, %-22s: energies %.4f / %.5f, alpha_f %.4f, beta_f %.4f", roughness[r],
                         b ? "HDRP's 128 x 90 pairs" : "converged", err[b].a_max, err[b].a_mean, err[b].shift_max,
                         err[b].width_max);
            worst[b] = fmax(worst[b], err[b].a_max), mean[b] += err[b].a_mean / rows;
        }
    }
    /* The largest miss is a_b at grazing theta for the smoothest fibres, about 1.2 there and changing
     * fastest with roughness: linear interpolation between roughness nodes 0.037 apart. */
    double mean_bound = t->quick ? 1e-2 : 2e-3; /* the quick tier's axes: 4 roughnesses, 6 absorptions */
    CHECK(t, worst[0] <= 0.05 && mean[0] <= mean_bound, "the converged table's interpolation misses by %.3g (mean %.3g)",
          worst[0], mean[0]);
    CHECK(t, t->quick || mean[1] > 5.0 * mean[0], "HDRP's estimate (mean %.3g) is not far worse than the quadrature's "
                                                  "table (%.3g)", mean[1], mean[0]);
    hb_dual_engine_destroy(tables[0]);
    hb_dual_engine_destroy(tables[1]);
}

/* An engine table saved and loaded is the built one node for node, for a base of any absorption and
 * R roughness (the axes replace both); the loaded table saves to the same bytes; a file of another
 * family or model, a damaged byte, a short file, a material's table file and a small buffer are
 * refused, naming why. */
static void test_engine_file(hb_test_ctx *t)
{
    hb_dual_engine_axes a;
    hb_dual_engine_axes_default(&a);
    a.thetas = 6, a.roughnesses = 2, a.absorptions = 4, a.roughness_min = 0.1, a.roughness_max = 0.3;
    hb_dual_engine *e = hb_test_dual_engine(t, &a);
    if (!e)
        return;
    size_t size = 0, small = 0, again = 0, count = 0, loaded_count = 0;
    CHECK(t, hb_dual_engine_save(e, NULL, 0, &size) == HB_OK && size > 6 * 2 * 4 * 6 * 8, "the length: %zu", size);
    unsigned char *bytes = malloc(size), *resaved = malloc(size);
    CHECK(t, hb_dual_engine_save(e, bytes, size - 1, &small) == HB_ERR_BUFFER && small == size &&
                 strstr(hb_last_error()->message, "capacity"), "a buffer a byte short: %s", hb_last_error()->message);
    CHECK(t, hb_dual_engine_save(e, bytes, size, &size) == HB_OK, "save: %s", hb_last_error()->message);
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = 5.0, m.beta_m = 0.4; /* what the axes replace */
    hb_dual_engine *loaded = NULL, *refused = NULL;
    hb_error error;
    CHECK(t, hb_dual_engine_load(&m, &o, bytes, size, &loaded, &error) == HB_OK, "load: %s", error.message);
    const float *built = hb_dual_engine_nodes(e, &count), *read = hb_dual_engine_nodes(loaded, &loaded_count);
    CHECK(t, read && count == loaded_count && memcmp(built, read, count * sizeof *built) == 0,
          "the loaded nodes are the built ones");
    double sigma_a[3] = { 0.2, 1.5, 7.0 };
    hb_dual_terms x = { .struct_size = sizeof x }, y = { .struct_size = sizeof y };
    CHECK(t, loaded && hb_dual_engine_terms(e, 0.37, 0.17, sigma_a, &x) == HB_OK &&
                 hb_dual_engine_terms(loaded, 0.37, 0.17, sigma_a, &y) == HB_OK && memcmp(&x, &y, sizeof x) == 0,
          "the loaded engine's terms between nodes are the built one's bit for bit");
    CHECK(t, loaded && hb_dual_engine_save(loaded, resaved, size, &again) == HB_OK && again == size &&
                 memcmp(bytes, resaved, size) == 0, "the loaded engine saves to the same bytes");
    hb_material other = m;
    other.eta = 1.5;
    CHECK(t, hb_dual_engine_load(&other, &o, bytes, size, &refused, &error) == HB_ERR_FILE && !refused &&
                 strstr(error.message, "eta") && strstr(error.message, "hb_dual_engine_load"),
          "another family: %s", error.message);
    hb_options chiang = o;
    chiang.model = HB_MODEL_CHIANG;
    CHECK(t, hb_dual_engine_load(&m, &chiang, bytes, size, &refused, &error) == HB_ERR_FILE && strstr(error.message, "model"),
          "another model: %s", error.message);
    bytes[size / 2] ^= 1;
    CHECK(t, hb_dual_engine_load(&m, &o, bytes, size, &refused, &error) == HB_ERR_FILE && strstr(error.message, "checksum"),
          "a damaged byte: %s", error.message);
    bytes[size / 2] ^= 1;
    CHECK(t, hb_dual_engine_load(&m, &o, bytes, size - 8, &refused, &error) == HB_ERR_FILE &&
                 strstr(error.message, "truncated"), "a short file: %s", error.message);
    CHECK(t, hb_dual_engine_load(&m, &o, "HBDUALT1", 8, &refused, &error) == HB_ERR_FILE &&
                 strstr(error.message, "HBDUALE1"), "a material's table file: %s", error.message);
    CHECK(t, hb_dual_engine_load(&m, &o, NULL, 8, &refused, &error) == HB_ERR_NULL && strstr(error.message, "bytes"),
          "no bytes: %s", error.message);
    free(bytes), free(resaved);
    hb_dual_engine_destroy(loaded);
    hb_dual_engine_destroy(e);
}

const hb_test hb_tests_dual_engine[] = {
    { "dual_sampled_converges", test_sampled_converges, 0 },
    { "dual_engine_nodes", test_engine_nodes, 0 },
    { "dual_engine_file", test_engine_file, 0 },
    { "dual_engine_other_model", test_engine_other_model, 0 },
    { "dual_engine_between_nodes", test_engine_between_nodes, 0 },
    { NULL, NULL, 0 },
};

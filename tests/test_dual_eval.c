/* hb_dual_eval and hb_dual_radiance, the dual-scattering radiance term (docs/multiple-scattering.md,
 * "The radiance term"): each lobe integrates over w_o to its energy, so the double reference's
 * integral over the sphere equals the closed form v d_b A_b + (1 - v) d_f a_f^n (a_f + a_b + d_b A_b),
 * each Gaussian cut where theta_o leaves [-pi/2, pi/2] (erf); the kernels equal the double reference
 * of the same table on every ISA; the table's interpolation in theta_i against the exact terms is
 * measured; hard cases stay finite and invalid ones are counted; refusals name what is wrong; a table
 * saved and loaded is the same table. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"

enum { THETAS = 64 };

static hb_plan *blond_plan(hb_test_ctx *t, hb_model model, hb_isa isa)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = 0.3;
    o.model = model, o.isa = isa == HB_ISA_AUTO ? HB_ISA_SCALAR : isa;
    hb_plan *plan = NULL;
    hb_error e;
    CHECK(t, hb_plan_create(&m, &o, &plan, &e) == HB_OK, "plan: %s", e.message);
    return plan;
}

/* The share of a unit Gaussian in theta_h of mean m and variance v inside [lo, hi]. */
static double inside(double lo, double hi, double m, double v)
{
    double s = sqrt(2.0 * fmax(v, 1e-8));
    return 0.5 * (erf((hi - m) / s) - erf((lo - m) / s));
}

/* The closed form of the integral of f_DS over w_o, channel c. */
static double expected_energy(const hb_dual_terms *d, int c, double theta_i, double n, double v)
{
    double lo = 0.5 * (theta_i - M_PI_2), hi = 0.5 * (theta_i + M_PI_2), s = n * d->beta_f2[c];
    double local = v * HB_DUAL_DENSITY * d->A_b[c] * inside(lo, hi, d->delta_b[c], d->sigma_b2[c]);
    double global = (1.0 - v) * HB_DUAL_DENSITY * pow(d->a_f[c], n) *
                    (d->a_f[c] * inside(lo, hi, d->alpha_f[c], d->beta_f2[c] + s) +
                     d->a_b[c] * inside(lo, hi, d->alpha_b[c], d->beta_b2[c] + s) +
                     HB_DUAL_DENSITY * d->A_b[c] * inside(lo, hi, d->delta_b[c], d->sigma_b2[c] + s));
    return local + global;
}

static void test_energy(hb_test_ctx *t)
{
    hb_plan *plan = blond_plan(t, HB_MODEL_DEON, HB_ISA_AUTO);
    if (!plan)
        return;
    static const double thetas[] = { 0.4, -0.9, 0.0 };
    static const double states[][2] = { { 0.0, -1.0 }, { 3.0, 0.0 }, { 0.5, -1.0 }, { 3.0, 0.25 } };
    int cells = t->quick ? 400 : 1200, cases = t->quick ? 2 : 4, angles = t->quick ? 1 : 3;
    double worst = 0.0;
    for (int a = 0; a < angles; a++) {
        hb_dual_terms d = { .struct_size = sizeof d };
        CHECK(t, hb_dual_terms_at(plan, thetas[a], HB_DUAL_DENSITY, &d) == HB_OK, "terms at %g", thetas[a]);
        for (int s = 0; s < cases; s++) {
            double n = states[s][0], v = states[s][1] >= 0.0 ? states[s][1] : fmax(0.0, 1.0 - n);
            double sum[3] = { 0 }, step = M_PI / cells;
            for (int i = 0; i < cells; i++) {
                double theta_o = -M_PI_2 + step * (i + 0.5), row[3] = { 0 };
                for (int j = 0; j < 2 * cells; j++) {
                    double f[3];
                    hb_dual_radiance(&d, HB_DUAL_DENSITY, HB_DUAL_DENSITY, thetas[a], 0.0, theta_o,
                                     -M_PI + step * (j + 0.5), n, states[s][1], f);
                    for (int c = 0; c < 3; c++)
                        row[c] += f[c];
                }
                for (int c = 0; c < 3; c++)
                    sum[c] += row[c] * cos(theta_o) * step * step;
            }
            for (int c = 0; c < 3; c++) {
                double want = expected_energy(&d, c, thetas[a], n, v), error = fabs(sum[c] - want) / want;
                worst = fmax(worst, error);
                CHECK(t, error < 1e-5, "theta_i %g, n %g, v %g, channel %d: integral %.8f, closed form %.8f", thetas[a], n,
                      v, c, sum[c], want);
            }
        }
    }
    hb_test_note(t, "dFH11 blond: the integral of f_DS over w_o is the closed form within %.1e relative "
                    "(%d x %d midpoints, %d inclinations x %d fibre states)",
                 worst, cells, 2 * cells, angles, cases);
    hb_plan_destroy(plan);
}

/* A batch of directions with the hard ones first: the poles, theta_o = -theta_i, phi at the
 * hemispheres' edge, n = 0, huge n and a full visibility. */
typedef struct dual_batch {
    float ti[4096], pi[4096], to[4096], po[4096], n[4096], v[4096];
    float r[4096], g[4096], b[4096];
} dual_batch;

static void fill_batch(hb_test_ctx *t, dual_batch *s, size_t count)
{
    for (size_t k = 0; k < count; k++) {
        s->ti[k] = (float)hb_test_range(t, -M_PI_2, M_PI_2);
        s->to[k] = k % 7 == 0 ? -s->ti[k] : (float)hb_test_range(t, -M_PI_2, M_PI_2);
        s->pi[k] = (float)hb_test_range(t, -M_PI, M_PI);
        s->po[k] = k % 11 == 0 ? s->pi[k] + 1.5707964f : (float)hb_test_range(t, -M_PI, M_PI);
        s->n[k] = k % 5 == 0 ? 0.0f : k % 13 == 0 ? FLT_MAX : (float)hb_test_range(t, 0.0, 20.0);
        s->v[k] = k % 3 == 0 ? 1.0f : (float)hb_test_uniform(t);
    }
    static const float poles[][2] = { { 1.5707964f, 1.5707964f }, { -1.5707964f, 1.5707964f }, { 1.5707964f, -1.5707964f },
                                      { 0.0f, 1.5707964f },        { 1.5707964f, 0.0f } };
    for (int k = 0; k < 5; k++)
        s->ti[k] = poles[k][0], s->to[k] = poles[k][1];
}

static void test_isas(hb_test_ctx *t)
{
    hb_plan *plan = blond_plan(t, HB_MODEL_DEON, t->isa);
    hb_dual_table *table = NULL; /* the kernel against the reference of the same table: any node count */
    if (!plan || hb_dual_table_create(plan, t->quick ? 16 : THETAS, HB_DUAL_DENSITY, HB_DUAL_DENSITY, NULL, NULL, NULL, NULL,
                                      &table) != HB_OK) {
        CHECK(t, 0, "table: %s", hb_last_error()->message);
        hb_plan_destroy(plan);
        return;
    }
    size_t count = t->quick ? 1024 : 4096;
    dual_batch *s = malloc(sizeof *s);
    fill_batch(t, s, count);
    hb_angles_soa in = { s->ti, s->pi, s->to, s->po };
    double worst = 0.0, peak = 0.0;
    for (int with_direct = 0; with_direct < 2; with_direct++) {
        hb_eval_report report;
        CHECK(t, hb_dual_eval(table, count, in, s->n, with_direct ? s->v : NULL, (hb_rgb_soa){ s->r, s->g, s->b }, &report) == HB_OK &&
                     report.invalid == 0,
              "eval: %zu invalid", report.invalid);
        double want[3], error[3] = { 0 }, at_want = 0.0, at_got = 0.0;
        size_t at = 0;
        for (size_t k = 0; k < count; k++) {
            hb_dual_terms d = { .struct_size = sizeof d };
            CHECK(t, hb_dual_table_terms(table, s->ti[k], &d) == HB_OK, "terms at %g", s->ti[k]);
            double v = with_direct ? s->v[k] : -1.0, other[3];
            hb_dual_radiance(&d, HB_DUAL_DENSITY, HB_DUAL_DENSITY, s->ti[k], s->pi[k], s->to[k], s->po[k], s->n[k], v, want);
            const float got[3] = { s->r[k], s->g[k], s->b[k] };
            /* at the hemispheres' edge the float difference of the azimuths may fall on either side */
            double edge = fabs(fabs(remainder((double)s->po[k] - s->pi[k], 2.0 * M_PI)) - M_PI_2);
            for (int side = -1; edge < 1e-6 && side <= 1; side += 2) {
                hb_dual_radiance(&d, HB_DUAL_DENSITY, HB_DUAL_DENSITY, s->ti[k], s->pi[k], s->to[k], s->po[k] + side * 2e-6,
                                 s->n[k], v, other);
                for (int c = 0; c < 3; c++)
                    if (fabs(got[c] - other[c]) < fabs(got[c] - want[c]))
                        want[c] = other[c];
            }
            for (int c = 0; c < 3; c++) {
                CHECK(t, isfinite(got[c]) && got[c] >= 0.0f, "sample %zu: f_DS %g", k, got[c]);
                peak = fmax(peak, want[c]);
                if (fabs(got[c] - want[c]) > error[c])
                    error[c] = fabs(got[c] - want[c]), at = k, at_want = want[c], at_got = got[c];
            }
        }
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, error[c]);
        hb_test_detail(t, "worst at sample %zu: theta_i %.9g theta_o %.9g phi %g %g n %g v %g: %.9g, reference %.9g", at,
                       s->ti[at], s->to[at], s->pi[at], s->po[at], s->n[at], with_direct ? s->v[at] : -1.0, at_got, at_want);
    }
    CHECK(t, worst <= 2e-6 * peak, "%s: the kernel is %.2e of the peak %.4g off the double reference", hb_isa_name(t->isa),
          worst / peak, peak);
    hb_test_note(t, "%s: f_DS within %.1e of the peak of the double reference of the same table (%zu samples, poles, n = 0 "
                    "and FLT_MAX)",
                 hb_isa_name(t->isa), worst / peak, count);
    free(s);
    hb_dual_table_destroy(table);
    hb_plan_destroy(plan);
}

/* The table's linear interpolation between its 64 nodes against the exact terms at theta_i: the
 * error of f_DS as a share of its peak over directions, within |theta_i| <= 1.2 and nearer grazing,
 * where the terms change fastest. */
static void test_interpolation(hb_test_ctx *t)
{
    hb_plan *plan = blond_plan(t, HB_MODEL_DEON, HB_ISA_AUTO);
    hb_dual_table *table = NULL;
    if (!plan || hb_dual_table_create(plan, THETAS, HB_DUAL_DENSITY, HB_DUAL_DENSITY, NULL, NULL, NULL, NULL, &table) != HB_OK) {
        hb_plan_destroy(plan);
        CHECK(t, 0, "table");
        return;
    }
    int inclinations = t->quick ? 4 : 24;
    double worst[2] = { 0.0, 0.0 }; /* |theta_i| <= 1.2, beyond */
    for (int a = 0; a < inclinations; a++) {
        double theta_i = -1.4 + 2.8 * (a + 0.37) / inclinations;
        hb_dual_terms exact = { .struct_size = sizeof exact }, near = { .struct_size = sizeof near };
        hb_dual_terms_at(plan, theta_i, HB_DUAL_DENSITY, &exact);
        hb_dual_table_terms(table, theta_i, &near);
        double peak = 0.0, error = 0.0;
        for (int i = 0; i < 64; i++)
            for (int j = 0; j < 32; j++)
                for (int s = 0; s < 2; s++) {
                    double fe[3], fn[3], theta_o = -M_PI_2 + M_PI * (i + 0.5) / 64, phi = M_PI * (j + 0.5) / 32;
                    hb_dual_radiance(&exact, HB_DUAL_DENSITY, HB_DUAL_DENSITY, theta_i, 0.0, theta_o, phi, s ? 3.0 : 0.0, -1.0, fe);
                    hb_dual_radiance(&near, HB_DUAL_DENSITY, HB_DUAL_DENSITY, theta_i, 0.0, theta_o, phi, s ? 3.0 : 0.0, -1.0, fn);
                    for (int c = 0; c < 3; c++)
                        peak = fmax(peak, fe[c]), error = fmax(error, fabs(fe[c] - fn[c]));
                }
        int grazing = fabs(theta_i) > 1.2;
        worst[grazing] = fmax(worst[grazing], error / peak);
        hb_test_detail(t, "theta_i %.4f: %.2e of the peak %.4g", theta_i, error / peak, peak);
    }
    CHECK(t, worst[0] < 5e-3 && worst[1] < 4e-2, "the 64-node table is %.2e (|theta_i| <= 1.2), %.2e (beyond) of the peak "
                                                 "off the exact terms", worst[0], worst[1]);
    hb_test_note(t, "dFH11 blond, %d nodes: f_DS from the table within %.1e of its peak from the exact terms for "
                    "|theta_i| <= 1.2, %.1e nearer grazing (%d inclinations between nodes, n = 0 and 3)",
                 THETAS, worst[0], worst[1], inclinations);
    hb_dual_table_destroy(table);
    hb_plan_destroy(plan);
}

/* Invalid samples get 0 and are counted; the default visibility is max(0, 1 - n) bit for bit;
 * n = 0 with full visibility leaves only the local back-scattering. */
static void test_samples(hb_test_ctx *t)
{
    hb_plan *plan = blond_plan(t, HB_MODEL_DEON, t->isa);
    hb_dual_table *table = NULL;
    if (!plan || hb_dual_table_create(plan, 16, 0.6, 0.8, NULL, NULL, NULL, NULL, &table) != HB_OK) {
        hb_plan_destroy(plan);
        CHECK(t, 0, "table");
        return;
    }
    enum { N = 9 };
    float ti[N] = { 0.3f, NAN, 0.3f, 0.3f, 0.3f, 0.3f, INFINITY, 0.3f, 0.3f };
    float to[N] = { -0.2f, 0.1f, 2.0f, -0.2f, -0.2f, -0.2f, 0.1f, -0.2f, -0.2f };
    float pi[N] = { 0 }, po[N] = { 0.4f, 0.4f, 0.4f, 0.4f, 0.4f, 2e4f, 0.4f, 0.4f, 2.9f };
    float n[N] = { 2.0f, 1.0f, 1.0f, -1.0f, NAN, 1.0f, 1.0f, INFINITY, 0.25f };
    float v[N] = { 0.0f, 0, 0, 0, 0, 0, 0, 0, 0.75f }, bad_v[N] = { 1.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, -0.1f };
    float r[N], g[N], b[N], r2[N], g2[N], b2[N];
    hb_angles_soa in = { ti, pi, to, po };
    hb_eval_report report;
    CHECK(t, hb_dual_eval(table, N, in, n, NULL, (hb_rgb_soa){ r, g, b }, &report) == HB_OK && report.invalid == 7,
          "7 invalid samples, %zu counted", report.invalid);
    for (int k = 1; k < 8; k++)
        CHECK(t, r[k] == 0.0f && g[k] == 0.0f && b[k] == 0.0f, "invalid sample %d gets 0", k);
    CHECK(t, r[0] > 0.0f && r[8] > 0.0f, "valid samples have light");
    hb_dual_eval(table, N, in, n, v, (hb_rgb_soa){ r2, g2, b2 }, NULL);
    CHECK(t, r2[0] == r[0] && g2[0] == g[0] && b2[0] == b[0] && r2[8] == r[8] && b2[8] == b[8],
          "v = max(0, 1 - n) is the default");
    hb_dual_eval(table, N, in, n, bad_v, (hb_rgb_soa){ r2, g2, b2 }, &report);
    CHECK(t, report.invalid == 9, "v outside [0, 1] is invalid: %zu", report.invalid);
    /* n = 0, v = 1: v d_b f_back(0) alone, in the backward half only */
    float zero = 0.0f, one = 1.0f, theta_i = 0.3f, theta_o = -0.2f, phi_back = 0.4f, phi_front = 2.9f, zero_phi = 0.0f;
    float f[3], f_front[3];
    hb_dual_eval(table, 1, (hb_angles_soa){ &theta_i, &zero_phi, &theta_o, &phi_back }, &zero, &one,
                 (hb_rgb_soa){ f, f + 1, f + 2 }, NULL);
    hb_dual_eval(table, 1, (hb_angles_soa){ &theta_i, &zero_phi, &theta_o, &phi_front }, &zero, &one,
                 (hb_rgb_soa){ f_front, f_front + 1, f_front + 2 }, NULL);
    hb_dual_terms d = { .struct_size = sizeof d };
    hb_dual_table_terms(table, theta_i, &d);
    double want = 0.8 * d.A_b[0] * exp(-pow(0.5 * (0.3 - 0.2) - d.delta_b[0], 2) / (2 * d.sigma_b2[0])) /
                  sqrt(2 * M_PI * d.sigma_b2[0]) / (2 * M_PI * cos(0.2));
    CHECK(t, fabs(f[0] - want) < 1e-5 * want && f_front[0] == 0.0f && f_front[2] == 0.0f,
          "n = 0, v = 1: %.7g against d_b A_b g / (2 pi cos theta_o) = %.7g; forward %g", f[0], want, f_front[0]);
    hb_dual_table_destroy(table);
    hb_plan_destroy(plan);
}

static void expect(hb_test_ctx *t, hb_status got, hb_status want, const char *words)
{
    CHECK(t, got == want && strstr(hb_last_error()->message, words), "%s: status %d, \"%s\"", words, (int)got,
          hb_last_error()->message);
}

static void test_refusals(hb_test_ctx *t)
{
    hb_plan *plan = blond_plan(t, HB_MODEL_DEON, HB_ISA_AUTO), *mjc = blond_plan(t, HB_MODEL_MARSCHNER, HB_ISA_AUTO);
    hb_dual_table *table = NULL;
    if (!plan || !mjc) {
        hb_plan_destroy(plan);
        hb_plan_destroy(mjc);
        return;
    }
    expect(t, hb_dual_table_create(plan, 1, 0.7, 0.7, NULL, NULL, NULL, NULL, &table), HB_ERR_PARAM, "thetas = 1");
    expect(t, hb_dual_table_create(plan, 8, 1.5, 0.7, NULL, NULL, NULL, NULL, &table), HB_ERR_PARAM, "d_f = 1.5");
    expect(t, hb_dual_table_create(plan, 8, 0.7, -0.1, NULL, NULL, NULL, NULL, &table), HB_ERR_PARAM, "d_b = -0.1");
    expect(t, hb_dual_table_create(mjc, 8, 0.7, 0.7, NULL, NULL, NULL, NULL, &table), HB_ERR_LIMIT, "diverge");
    CHECK(t, table == NULL, "no table after a refusal");
    CHECK(t, hb_dual_table_create(plan, 8, 0.7, 0.7, NULL, NULL, NULL, NULL, &table) == HB_OK, "table");
    float x = 0.0f, out[3];
    expect(t, hb_dual_eval(table, 1, (hb_angles_soa){ &x, &x, &x, &x }, NULL, NULL, (hb_rgb_soa){ out, out + 1, out + 2 }, NULL),
           HB_ERR_NULL, "fibres");
    expect(t, hb_dual_eval(table, 1, (hb_angles_soa){ &x, &x, &x, NULL }, &x, NULL, (hb_rgb_soa){ out, out + 1, out + 2 }, NULL),
           HB_ERR_NULL, "phi_o");
    hb_dual_terms d = { .struct_size = sizeof d };
    double f[3];
    hb_dual_table_terms(table, 0.2, &d);
    expect(t, hb_dual_radiance(&d, 0.7, 0.7, 0.2, 0.0, 0.1, 0.0, -1.0, -1.0, f), HB_ERR_PARAM, "fibres = -1");
    expect(t, hb_dual_radiance(&d, 0.7, 0.7, 0.2, 0.0, 2.0, 0.0, 1.0, -1.0, f), HB_ERR_PARAM, "not a valid sample");
    expect(t, hb_dual_table_terms(table, 2.0, &d), HB_ERR_PARAM, "theta = 2");
    hb_dual_table_destroy(table);
    hb_plan_destroy(plan);
    hb_plan_destroy(mjc);
}

/* A table saved and loaded gives the same f_DS bit for bit; a file of another material, a damaged
 * byte, a short file and a small buffer are refused, naming why. */
static void test_table_file(hb_test_ctx *t)
{
    hb_plan *plan = blond_plan(t, HB_MODEL_DEON, t->isa);
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = 0.31, o.isa = plan ? hb_plan_isa(plan) : HB_ISA_SCALAR;
    hb_plan *other = NULL;
    hb_plan_create(&m, &o, &other, NULL);
    hb_dual_table *table = NULL, *loaded = NULL, *refused = NULL;
    if (!plan || !other || hb_dual_table_create(plan, 16, 0.6, 0.8, NULL, NULL, NULL, NULL, &table) != HB_OK) {
        CHECK(t, 0, "table");
        hb_plan_destroy(plan);
        hb_plan_destroy(other);
        return;
    }
    size_t size = 0, small;
    CHECK(t, hb_dual_table_save(table, NULL, 0, &size) == HB_OK && size > 16 * 27 * 8, "the length: %zu", size);
    unsigned char *bytes = malloc(size);
    CHECK(t, hb_dual_table_save(table, bytes, size - 1, &small) == HB_ERR_BUFFER && small == size &&
                 strstr(hb_last_error()->message, "capacity"),
          "a buffer a byte short: %s", hb_last_error()->message);
    CHECK(t, hb_dual_table_save(table, bytes, size, &size) == HB_OK, "save: %s", hb_last_error()->message);
    CHECK(t, hb_dual_table_load(plan, bytes, size, &loaded) == HB_OK, "load: %s", hb_last_error()->message);
    enum { N = 512 };
    static float ti[N], pi[N], to[N], po[N], n[N], f[6][N];
    for (int k = 0; k < N; k++)
        ti[k] = (float)hb_test_range(t, -M_PI_2, M_PI_2), to[k] = (float)hb_test_range(t, -M_PI_2, M_PI_2),
        pi[k] = 0.0f, po[k] = (float)hb_test_range(t, -M_PI, M_PI), n[k] = (float)hb_test_range(t, 0.0, 10.0);
    hb_angles_soa in = { ti, pi, to, po };
    hb_dual_eval(table, N, in, n, NULL, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
    if (loaded)
        hb_dual_eval(loaded, N, in, n, NULL, (hb_rgb_soa){ f[3], f[4], f[5] }, NULL);
    CHECK(t, loaded && memcmp(f[0], f[3], sizeof f[0] * 3) == 0, "the loaded table's f_DS is the built one's bit for bit");
    CHECK(t, hb_dual_table_load(other, bytes, size, &refused) == HB_ERR_FILE && !refused &&
                 strstr(hb_last_error()->message, "eumelanin"),
          "another material: %s", hb_last_error()->message);
    bytes[size / 2] ^= 1;
    CHECK(t, hb_dual_table_load(plan, bytes, size, &refused) == HB_ERR_FILE && strstr(hb_last_error()->message, "checksum"),
          "a damaged byte: %s", hb_last_error()->message);
    bytes[size / 2] ^= 1;
    CHECK(t, hb_dual_table_load(plan, bytes, size - 8, &refused) == HB_ERR_FILE && strstr(hb_last_error()->message, "truncated"),
          "a short file: %s", hb_last_error()->message);
    CHECK(t, hb_dual_table_load(plan, "HBTABLE3", 8, &refused) == HB_ERR_FILE && strstr(hb_last_error()->message, "HBDUALT1"),
          "a plan's table file: %s", hb_last_error()->message);
    free(bytes);
    hb_dual_table_destroy(loaded);
    hb_dual_table_destroy(table);
    hb_plan_destroy(other);
    hb_plan_destroy(plan);
}

/* hb_plan_describe says after how many fibres the global term falls below the plan's target: for a
 * blond dFH11 fibre, ceil(log(1e-3 / d_f) / log(a_f)) per channel from hb_dual_terms_at at theta 0;
 * black hair's is a few fibres; MJC03's lossless fibre, whose a_f exceeds 1, has none. */
static void test_describe(hb_test_ctx *t)
{
    static const struct { hb_model model; double eumelanin; } cases[] = {
        { HB_MODEL_DEON, 0.3 }, { HB_MODEL_DEON, 8.0 }, { HB_MODEL_MARSCHNER, 0.0 } };
    for (int c = 0; c < 3; c++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        o.model = cases[c].model;
        m.eumelanin = cases[c].eumelanin;
        hb_plan *plan = NULL;
        hb_error err;
        CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s", err.message);
        if (!plan)
            return;
        char text[4096], want[160];
        hb_plan_describe(plan, text, sizeof text);
        hb_dual_terms d = { .struct_size = sizeof d };
        hb_dual_terms_at(plan, 0.0, HB_DUAL_DENSITY, &d);
        const char *line = strstr(text, "multiple scattering");
        if (d.a_f[0] >= 1.0) {
            CHECK(t, line && strstr(line, "diverge"), "MJC03 lossless: %s", text);
        } else {
            int n[3];
            for (int ch = 0; ch < 3; ch++)
                n[ch] = (int)ceil(log(1e-3 / HB_DUAL_DENSITY) / log(d.a_f[ch]));
            snprintf(want, sizeof want, "below 1e-03 after n = %d %d %d fibres", n[0], n[1], n[2]);
            CHECK(t, line && strstr(line, want), "eumelanin %g: want '%s' in: %s", m.eumelanin, want, text);
            CHECK(t, cases[c].eumelanin < 8.0 || n[0] <= 3, "black hair: the term matters after %d fibres", n[0]);
            hb_test_note(t, "eumelanin %g: %s", m.eumelanin, want);
        }
        hb_plan_destroy(plan);
    }
}

/* A tolerance plan keeps dual scattering only where it adds at least its tolerance: the share
 * hb_dual_table_included reports is the largest over the table's nodes of eq. 14's local term d_b A_b
 * and the global term at one fibre, d_f a_f (a_f + a_b + d_b A_b), over a_f + a_b, recomputed here from
 * a plain plan's terms; below the tolerance the table's terms and f_DS are zeros, and
 * hb_plan_describe says which it is. Black and blond dFH11 fibres at tolerances 0.4 and 0.05. */
static void test_included(hb_test_ctx *t)
{
    static const struct { double eumelanin, tolerance; } cases[] = { { 8.0, 0.4 }, { 8.0, 0.05 }, { 0.3, 0.4 } };
    for (int c = 0; c < 3; c++) {
        hb_material m;
        hb_options o;
        hb_material_default(&m);
        hb_options_default(&o);
        m.eumelanin = cases[c].eumelanin;
        hb_plan *plain = NULL, *plan = NULL;
        hb_error err;
        CHECK(t, hb_plan_create(&m, &o, &plain, &err) == HB_OK, "%s", err.message);
        o.tolerance = cases[c].tolerance;
        CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s", err.message);
        hb_dual_table *table = NULL;
        if (plan)
            CHECK(t, hb_dual_table_create(plan, 16, HB_DUAL_DENSITY, HB_DUAL_DENSITY, NULL, NULL, NULL, NULL, &table) ==
                         HB_OK, "%s", hb_last_error()->message);
        if (!table) {
            hb_plan_destroy(plain), hb_plan_destroy(plan);
            return;
        }
        double share = 0.0, want = 0.0;
        int included = hb_dual_table_included(table, &share);
        for (int k = 0; k < 16; k++) {
            hb_dual_terms d = { .struct_size = sizeof d };
            hb_dual_terms_at(plan, -M_PI_2 + M_PI * (k + 0.5) / 16, HB_DUAL_DENSITY, &d);
            for (int ch = 0; ch < 3; ch++)
                want = fmax(want, fmax(HB_DUAL_DENSITY * d.A_b[ch],
                                       HB_DUAL_DENSITY * d.a_f[ch] * (d.a_f[ch] + d.a_b[ch] + HB_DUAL_DENSITY * d.A_b[ch])) /
                                      (d.a_f[ch] + d.a_b[ch]));
        }
        CHECK(t, fabs(share - want) <= 1e-12 * want, "share %.17g, recomputed %.17g", share, want);
        CHECK(t, included == !(share < cases[c].tolerance), "share %g at tolerance %g: included %d", share,
              cases[c].tolerance, included);
        float ti[1] = { 0.3f }, pi[1] = { 0.0f }, to[1] = { 0.2f }, po[1] = { 3.0f }, n[1] = { 1.0f }, f[3][1];
        hb_dual_eval(table, 1, (hb_angles_soa){ ti, pi, to, po }, n, NULL, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        CHECK(t, included ? f[1][0] > 0.0f : f[1][0] == 0.0f, "f_DS %g where included is %d", f[1][0], included);
        char text[4096];
        hb_plan_describe(plan, text, sizeof text);
        CHECK(t, strstr(text, included ? "multiple scattering: included" : "multiple scattering: dropped"),
              "describe disagrees with the table (included %d): %s", included, text);
        hb_plan_describe(plain, text, sizeof text);
        CHECK(t, !strstr(text, "multiple scattering: included") && !strstr(text, "multiple scattering: dropped"),
              "a plain plan decides nothing: %s", text);
        hb_test_note(t, "eumelanin %g, tolerance %g: dual scattering adds at most %.2f of the fibre's energy: %s",
                     cases[c].eumelanin, cases[c].tolerance, share, included ? "included" : "dropped");
        hb_dual_table_destroy(table);
        hb_plan_destroy(plain), hb_plan_destroy(plan);
    }
}

const hb_test hb_tests_dual_eval[] = {
    { "dual_eval_energy", test_energy, 0 },
    { "dual_eval_isas", test_isas, 1 },
    { "dual_eval_interpolation", test_interpolation, 0 },
    { "dual_eval_samples", test_samples, 1 },
    { "dual_eval_refusals", test_refusals, 0 },
    { "dual_eval_table_file", test_table_file, 1 },
    { "dual_describe", test_describe, 0 },
    { "dual_included", test_included, 0 },
    { NULL, NULL, 0 },
};

/* Table files (hb_table_save, options.table_file): a plan loaded from a file evaluates bit for bit
 * as the plan that saved it; a truncated, damaged, other-version, other-format or mismatched file
 * is refused with a message that names the problem, and never read past its end. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "math/hash.h"
#include "test.h"

enum { FILE_MAX = 1 << 18, SAMPLES = 1024 };

/* dFH11 with a fast N_p table, and HHH22 with a fast TT/TRT table (rough, so both are small). */
static void table_material(int huang, hb_material *m, hb_options *o, hb_isa isa)
{
    hb_material_default(m);
    hb_options_default(o);
    o->quality = HB_QUALITY_FAST, o->isa = isa;
    m->eumelanin = 0.4;
    if (huang)
        o->model = HB_MODEL_HUANG, o->tt_trt = HB_TT_TRT_TABLE, m->roughness = 0.5;
    else
        o->azimuthal = HB_AZIMUTHAL_TABLE;
}

/* The plan's table file into bytes; its length, 0 on failure. */
static size_t save(hb_test_ctx *t, const hb_plan *plan, unsigned char *bytes)
{
    size_t size = 0;
    CHECK(t, hb_table_save(plan, NULL, 0, &size) == HB_OK && size > 0 && size <= FILE_MAX, "length %zu", size);
    if (size == 0 || size > FILE_MAX)
        return 0;
    size_t short_size;
    CHECK(t, hb_table_save(plan, bytes, size - 1, &short_size) == HB_ERR_BUFFER && short_size == size &&
                 strstr(hb_last_error()->message, "capacity"),
          "a short buffer is refused, naming the size it needs");
    CHECK(t, hb_table_save(plan, bytes, size, &size) == HB_OK, "save");
    return size;
}

/* The status of a plan created from bytes; the message into error. */
static hb_status load(const hb_material *m, const hb_options *given, const void *bytes, size_t size, hb_plan **plan,
                      hb_error *error)
{
    hb_options o = *given;
    o.table_file = bytes, o.table_file_size = size;
    *plan = NULL;
    error->message[0] = '\0';
    return hb_plan_create(m, &o, plan, error);
}

/* The first place of n bytes in the file, or NULL. */
static unsigned char *find_bytes(unsigned char *bytes, size_t size, const char *what, size_t n)
{
    for (size_t k = 0; k + n <= size; k++)
        if (memcmp(bytes + k, what, n) == 0)
            return bytes + k;
    return NULL;
}

/* The value count of a table file: the u64 just before its last 4 count bytes and the checksum. */
static size_t value_count(const unsigned char *bytes, size_t size)
{
    for (size_t count = 1; 8 + 4 * count + 8 <= size; count++) {
        unsigned long long stated = 0;
        for (int k = 7; k >= 0; k--)
            stated = stated << 8 | bytes[size - 8 - 4 * count - 8 + (size_t)k];
        if (stated == count)
            return count;
    }
    return 0;
}

static void fix_checksum(unsigned char *bytes, size_t size)
{
    unsigned long long sum = hb_xxh64(bytes, size - 8);
    for (int k = 0; k < 8; k++)
        bytes[size - 8 + (size_t)k] = (unsigned char)(sum >> (8 * k));
}

static void test_round_trip(hb_test_ctx *t)
{
    static unsigned char bytes[FILE_MAX], again[FILE_MAX];
    static float ti[SAMPLES], pi[SAMPLES], to[SAMPLES], po[SAMPLES], f[2][3][SAMPLES];
    for (int k = 0; k < SAMPLES; k++) {
        ti[k] = (float)hb_test_range(t, -1.5707, 1.5707), to[k] = (float)hb_test_range(t, -1.5707, 1.5707);
        pi[k] = (float)hb_test_range(t, -M_PI, M_PI), po[k] = (float)hb_test_range(t, -M_PI, M_PI);
    }
    hb_angles_soa in = { ti, pi, to, po };
    for (int huang = 0; huang < 2; huang++) {
        hb_material m;
        hb_options o;
        table_material(huang, &m, &o, t->isa);
        hb_plan *built, *loaded;
        hb_error error;
        CHECK(t, hb_plan_create(&m, &o, &built, &error) == HB_OK, "built: %s", error.message);
        size_t size = save(t, built, bytes);
        CHECK(t, load(&m, &o, bytes, size, &loaded, &error) == HB_OK, "loaded: %s", error.message);
        if (!loaded) {
            hb_plan_destroy(built);
            continue;
        }
        hb_eval_angles(built, SAMPLES, in, (hb_rgb_soa){ f[0][0], f[0][1], f[0][2] }, NULL);
        memset(bytes, 0xff, size); /* the plan keeps no pointer into the file */
        hb_eval_angles(loaded, SAMPLES, in, (hb_rgb_soa){ f[1][0], f[1][1], f[1][2] }, NULL);
        CHECK(t, memcmp(f[0], f[1], sizeof f[0]) == 0, "%s: the loaded plan's f differs from the saving plan's",
              huang ? "huang" : "deon");
        size_t size_again = save(t, loaded, again), size_built = save(t, built, bytes);
        CHECK(t, size_again == size_built && memcmp(bytes, again, size_built) == 0,
              "%s: the loaded plan saves the same file", huang ? "huang" : "deon");
        char text[1024];
        hb_plan_describe(loaded, text, sizeof text);
        CHECK(t, strstr(text, "loaded from a table file"), "describe says the table was loaded: %s", text);
        hb_plan_destroy(built), hb_plan_destroy(loaded);
    }
}

/* The plan of (m, o) refuses these bytes with status and a message holding `says`. */
static void expect_refusal(hb_test_ctx *t, const hb_material *m, const hb_options *o, const unsigned char *bytes,
                           size_t size, hb_status status, const char *says, const char *what)
{
    hb_plan *plan;
    hb_error error;
    hb_status st = load(m, o, bytes, size, &plan, &error);
    CHECK(t, st == status && !plan && strstr(error.message, says), "%s: status %d, message '%s' (expected '%s')", what,
          (int)st, error.message, says);
    hb_plan_destroy(plan);
}

static void test_refusals(hb_test_ctx *t)
{
    static unsigned char good[FILE_MAX], bad[FILE_MAX], huang_file[FILE_MAX];
    hb_material m, hm;
    hb_options o, ho;
    table_material(0, &m, &o, t->isa);
    table_material(1, &hm, &ho, t->isa);
    hb_plan *plan;
    hb_error error;
    CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_OK, "%s", error.message);
    size_t size = save(t, plan, good);
    hb_plan_destroy(plan);
    CHECK(t, hb_plan_create(&hm, &ho, &plan, &error) == HB_OK, "%s", error.message);
    size_t huang_size = save(t, plan, huang_file);
    hb_plan_destroy(plan);
    if (!size || !huang_size)
        return;
    /* truncated or padded: each length is refused before anything past it is read (ASan checks the
     * copies, which end exactly at their length) */
    const size_t lengths[] = { 0, 1, 7, 8, 15, 16, 23, 24, 100, size / 2, size - 8, size - 1 };
    for (size_t k = 0; k < sizeof lengths / sizeof lengths[0]; k++) {
        unsigned char *copy = malloc(lengths[k] + 1);
        memcpy(copy, good, lengths[k]);
        expect_refusal(t, &m, &o, copy, lengths[k] ? lengths[k] : 1, HB_ERR_FILE, "table file", "truncated");
        free(copy);
    }
    memcpy(bad, good, size), bad[size] = 0;
    expect_refusal(t, &m, &o, bad, size + 1, HB_ERR_FILE, "truncated or padded", "one byte more");
    /* any flipped bit: the checksum */
    for (int k = 0; k < 64; k++) {
        size_t at = 8 + (size_t)k * (size - 8) / 64;
        memcpy(bad, good, size);
        bad[at] ^= (unsigned char)(1u << (k % 8));
        expect_refusal(t, &m, &o, bad, size, HB_ERR_FILE, at < 16 ? "header says" : "checksum", "a flipped bit");
    }
    /* well-formed but not this library's or this plan's: each names the difference */
    memcpy(bad, good, size);
    bad[7] = '1';
    expect_refusal(t, &m, &o, bad, size, HB_ERR_FILE, "format '1'", "an older format");
    /* another release of the same table version reads it: X.Y.Z's file under X.Y.(Z+1) */
    memcpy(bad, good, size);
    char next_patch[16] = { 0 };
    snprintf(next_patch, sizeof next_patch, "%d.%d.%d", HB_VERSION_MAJOR, HB_VERSION_MINOR, HB_VERSION_PATCH + 1);
    CHECK(t, memcmp(bad + 16, HB_VERSION_STRING, sizeof HB_VERSION_STRING) == 0, "the writer's version at byte 16");
    memcpy(bad + 16, next_patch, sizeof next_patch);
    fix_checksum(bad, size);
    CHECK(t, load(&m, &o, bad, size, &plan, &error) == HB_OK, "a file of release %s: %s", next_patch, error.message);
    hb_plan_destroy(plan);
    /* a table version this library does not read is refused, naming both */
    memcpy(bad, good, size);
    const size_t table_version_at = 8 + 8 + 32 + 4;
    CHECK(t, bad[table_version_at] == 1 && bad[table_version_at + 1] == 0, "table version 1 at byte %zu", table_version_at);
    bad[table_version_at] = 7;
    memcpy(bad + 16, "0.0.1\0", 6);
    fix_checksum(bad, size);
    expect_refusal(t, &m, &o, bad, size, HB_ERR_FILE, "deon tables of version 7 (baked by hairbsdf 0.0.1), this library's are version 1",
                   "another table version");
    /* a field named twice, standing in for one the plan depends on: sigma_a[0]'s entry renamed eta */
    memcpy(bad, good, size);
    unsigned char *sigma = find_bytes(bad, size, "sigma_a[0]", 11);
    CHECK(t, sigma && memcmp(sigma - 32, "eta", 4) == 0, "the field eta before sigma_a[0] in the file");
    if (sigma && memcmp(sigma - 32, "eta", 4) == 0) {
        memcpy(sigma, sigma - 32, 32); /* name and value */
        fix_checksum(bad, size);
        hb_material any = m;
        any.sigma_a[0] += 3.0;
        expect_refusal(t, &any, &o, bad, size, HB_ERR_FILE, "names the field 'eta' twice", "a repeated field");
    }
    expect_refusal(t, &m, &o, (const unsigned char *)"PNG, not a table file, at all", 30, HB_ERR_FILE,
                   "not a hairbsdf table", "another kind of file");
    hb_material other = m;
    other.eta = 1.5;
    expect_refusal(t, &other, &o, good, size, HB_ERR_FILE, "baked for eta = 1.55, this plan's is 1.5", "another eta");
    other = m, other.pheomelanin = 0.1;
    expect_refusal(t, &other, &o, good, size, HB_ERR_FILE, "pheomelanin", "another pheomelanin");
    hb_options other_o = o;
    other_o.quality = HB_QUALITY_BALANCED;
    expect_refusal(t, &m, &other_o, good, size, HB_ERR_FILE, "quality", "another quality");
    other_o = o, other_o.pmax = 2;
    expect_refusal(t, &m, &other_o, good, size, HB_ERR_FILE, "pmax", "another pmax");
    expect_refusal(t, &m, &o, huang_file, huang_size, HB_ERR_FILE, "baked for model huang, this plan's is deon",
                   "another model");
    /* a value that is not finite, behind a valid checksum */
    memcpy(bad, good, size);
    const float nan_value = NAN;
    memcpy(bad + size - 8 - 4 * 7, &nan_value, 4);
    fix_checksum(bad, size);
    expect_refusal(t, &m, &o, bad, size, HB_ERR_FILE, "outside [0, 1e+12]", "a NaN value");
    /* a finite value that would overflow f once multiplied by M_p (the fuzzer found it) */
    memcpy(bad, good, size);
    const float huge = 4.25e37f;
    memcpy(bad + size - 8 - 4 * 11, &huge, 4);
    fix_checksum(bad, size);
    expect_refusal(t, &m, &o, bad, size, HB_ERR_FILE, "outside [0, 1e+12]", "a value near FLT_MAX");
    /* HHH22's nodes hold square roots, squared by the lookup: 1e19 (inside a bound of 1e20) made every
     * f Inf; at the bound of 1e12 everywhere, f is finite at every direction, the poles included */
    size_t values = value_count(huang_file, huang_size);
    CHECK(t, values > 11, "the HHH22 file's value count");
    memcpy(bad, huang_file, huang_size);
    const float root_huge = 1e19f;
    memcpy(bad + huang_size - 8 - 4 * 11, &root_huge, 4);
    fix_checksum(bad, huang_size);
    expect_refusal(t, &hm, &ho, bad, huang_size, HB_ERR_FILE, "outside [0, 1e+12]", "an HHH22 root past the bound");
    memcpy(bad, huang_file, huang_size);
    const float at_bound = 1e12f;
    for (size_t k = 0; k < values; k++)
        memcpy(bad + huang_size - 8 - 4 * (k + 1), &at_bound, 4);
    fix_checksum(bad, huang_size);
    CHECK(t, load(&hm, &ho, bad, huang_size, &plan, &error) == HB_OK, "every value at the bound: %s", error.message);
    if (plan) {
        enum { GRID = 33 };
        static float ti[GRID * GRID], pi[GRID * GRID], to[GRID * GRID], po[GRID * GRID], f[3][GRID * GRID];
        for (int a = 0; a < GRID; a++)
            for (int b = 0; b < GRID; b++) {
                int j = a * GRID + b;
                ti[j] = (float)(-M_PI_2 + M_PI * a / (GRID - 1)), to[j] = (float)(-M_PI_2 + M_PI * b / (GRID - 1));
                pi[j] = 0.3f * (float)a, po[j] = -0.2f * (float)b;
            }
        hb_eval_angles(plan, GRID * GRID, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        int bad_values = 0;
        for (int c = 0; c < 3; c++)
            for (int j = 0; j < GRID * GRID; j++)
                bad_values += !(isfinite(f[c][j]) && f[c][j] >= 0.0f);
        CHECK(t, bad_values == 0, "%d values of f not finite with every table value 1e12", bad_values);
        hb_plan_destroy(plan);
    }
    /* the first axis one node shorter, its value count consistent with the length: no layout of this plan */
    memcpy(bad, good, size);
    const size_t first_axis = 8 + 8 + 32 + 20;
    bad[first_axis] = (unsigned char)(bad[first_axis] - 1);
    fix_checksum(bad, size);
    expect_refusal(t, &m, &o, bad, size, HB_ERR_FILE, "table file", "another resolution");
    /* options that cannot take a file */
    other_o = o, other_o.azimuthal = HB_AZIMUTHAL_QUADRATURE;
    expect_refusal(t, &m, &other_o, good, size, HB_ERR_UNSUPPORTED, "no table to load", "a quadrature plan");
    other_o = o, other_o.tolerance = 1e-2;
    expect_refusal(t, &m, &other_o, good, size, HB_ERR_UNSUPPORTED, "tolerance", "a tolerance plan");
    other_o = o, other_o.table_file_size = 100;
    CHECK(t, hb_plan_create(&m, &other_o, &plan, &error) == HB_ERR_PARAM && strstr(error.message, "table_file"),
          "a size without bytes: %s", error.message);
    CHECK(t, hb_table_save(NULL, bad, size, &size) == HB_ERR_NULL, "NULL plan");
    other_o = o, other_o.azimuthal = HB_AZIMUTHAL_QUADRATURE;
    CHECK(t, hb_plan_create(&m, &other_o, &plan, NULL) == HB_OK, "quadrature plan");
    CHECK(t, hb_table_save(plan, NULL, 0, &size) == HB_ERR_UNSUPPORTED, "a plan without a table has no file");
    hb_plan_destroy(plan);
}

/* HHH22's pole bound: the default's file names no pole_floor (files of releases without the option
 * load), a pole_floor = paper table is its own and loads only into such a plan, bounded and auto's
 * files are one. */
static void test_pole_floor(hb_test_ctx *t)
{
    static unsigned char bounded[FILE_MAX], paper[FILE_MAX];
    hb_material m;
    hb_options o, po;
    table_material(1, &m, &o, t->isa);
    po = o, po.pole_floor = HB_POLE_FLOOR_PAPER;
    hb_plan *plan;
    hb_error error;
    CHECK(t, hb_plan_create(&m, &o, &plan, &error) == HB_OK, "%s", error.message);
    size_t bounded_size = plan ? save(t, plan, bounded) : 0;
    hb_plan_destroy(plan);
    CHECK(t, hb_plan_create(&m, &po, &plan, &error) == HB_OK, "%s", error.message);
    size_t paper_size = plan ? save(t, plan, paper) : 0;
    hb_plan_destroy(plan);
    if (!bounded_size || !paper_size)
        return;
    CHECK(t, !find_bytes(bounded, bounded_size, "pole_floor", 11), "the default's file names pole_floor");
    CHECK(t, paper_size == bounded_size + 32, "the paper's file: %zu bytes, the default's %zu", paper_size, bounded_size);
    expect_refusal(t, &m, &o, paper, paper_size, HB_ERR_FILE, "baked for pole_floor = 1, this plan's is 0",
                   "a paper table into a bounded plan");
    expect_refusal(t, &m, &po, bounded, bounded_size, HB_ERR_FILE, "no field 'pole_floor' (baked at 0)",
                   "a bounded table into a paper plan");
    hb_options bo = o;
    bo.pole_floor = HB_POLE_FLOOR_BOUNDED;
    CHECK(t, load(&m, &bo, bounded, bounded_size, &plan, &error) == HB_OK, "auto's table, bounded plan: %s", error.message);
    hb_plan_destroy(plan);
    CHECK(t, load(&m, &po, paper, paper_size, &plan, &error) == HB_OK, "the paper's own: %s", error.message);
    hb_plan_destroy(plan);
}

/* The checksum is XXH64: these values are xxhsum -H64's (Debian's xxhash), an independent implementation. */
static void test_checksum(hb_test_ctx *t)
{
    static const struct {
        const char *text;
        unsigned long long xxh64;
    } vectors[] = { { "", 0xef46db3751d8e999ull }, { "a", 0xd24ec4f1a98c6e5bull }, { "abc", 0x44bc2cf5ad770999ull },
                    { "0123456789abcdef0123456789abcdef0123456789", 0xa76190c3acf08a1cull },
                    { "hairbsdf table file checksum, a stripe and a tail!", 0xd4509123eabe8738ull } };
    for (size_t k = 0; k < sizeof vectors / sizeof vectors[0]; k++) {
        unsigned long long h = hb_xxh64((const unsigned char *)vectors[k].text, strlen(vectors[k].text));
        CHECK(t, h == vectors[k].xxh64, "XXH64('%s') = %016llx, xxhsum gives %016llx", vectors[k].text, h,
              vectors[k].xxh64);
    }
}

const hb_test hb_tests_table_file[] = {
    { "table_file_checksum", test_checksum, 0 },
    { "table_file_round_trip", test_round_trip, 1 },
    { "table_file_refusals", test_refusals, 0 },
    { "table_file_pole_floor", test_pole_floor, 0 },
    { NULL, NULL, 0 },
};

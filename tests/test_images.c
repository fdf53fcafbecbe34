/* The CLI's image writers, read back: PFM floats, PNG chunks (CRC-32), stored deflate blocks,
 * Adler-32 and pixels; and `hairbsdf dump` against the library. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "portable.h"
#include "test.h"
#include "image.h"

/* A file's bytes (tests/runner.c). */
static uint8_t *slurp(const char *path, size_t *n) { return (uint8_t *)hb_test_read_file(path, n); }

static uint32_t be32(const uint8_t *p) { return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]; }

/* The standard check values of CRC-32 and Adler-32. */
static void test_checksums(hb_test_ctx *t)
{
    CHECK(t, image_crc32((const uint8_t *)"123456789", 9, 0) == 0xcbf43926u, "CRC-32 check value");
    CHECK(t, image_adler32((const uint8_t *)"Wikipedia", 9) == 0x11e60398u, "Adler-32 check value");
}

/* Reads a float-RGB PFM back, bottom row first in the file. */
static float *read_pfm(const char *path, int *w, int *h)
{
    size_t n;
    uint8_t *d = slurp(path, &n);
    if (!d)
        return NULL;
    float scale;
    int used = 0;
    if (sscanf((const char *)d, "PF\n%d %d\n%f\n%n", w, h, &scale, &used) != 3 || scale >= 0 ||
        n != (size_t)used + (size_t)*w * *h * 12) {
        free(d);
        return NULL;
    }
    float *rgb = malloc((size_t)*w * *h * 12);
    for (int y = 0; y < *h; y++)
        memcpy(rgb + (size_t)y * *w * 3, d + used + (size_t)(*h - 1 - y) * *w * 12, (size_t)*w * 12);
    free(d);
    return rgb;
}

static void test_pfm_round_trip(hb_test_ctx *t)
{
    float rgb[3 * 2 * 3];
    for (int k = 0; k < 18; k++)
        rgb[k] = (float)(k * 0.37 - 2.0);
    char path[600];
    CHECK(t, hb_test_temp_file(path, sizeof path, "") == 0, "no temporary file");
    CHECK(t, image_write_pfm(path, 3, 2, rgb) == 0, "write");
    int w, h;
    float *back = read_pfm(path, &w, &h);
    CHECK(t, back && w == 3 && h == 2 && memcmp(back, rgb, sizeof rgb) == 0, "PFM read back differs");
    free(back);
    unlink(path);
}

/* Parses the PNG: signature, chunk CRCs, IHDR, stored deflate blocks, Adler-32, filter bytes, pixels. */
static void test_png_round_trip(hb_test_ctx *t)
{
    enum { W = 300, H = 250 }; /* more than one 65535-byte stored block */
    static uint8_t rgb[W * H * 3];
    for (size_t k = 0; k < sizeof rgb; k++)
        rgb[k] = (uint8_t)(k * 7 + k / 13);
    char path[600];
    CHECK(t, hb_test_temp_file(path, sizeof path, "") == 0, "no temporary file");
    CHECK(t, image_write_png(path, W, H, rgb) == 0, "write");
    size_t n;
    uint8_t *d = slurp(path, &n);
    CHECK(t, d && n > 8 && memcmp(d, "\x89PNG\r\n\x1a\n", 8) == 0, "signature");
    size_t raw_size = (size_t)(W * 3 + 1) * H, raw_n = 0, pos = 8;
    uint8_t *raw = malloc(raw_size);
    int seen_end = 0;
    while (d && pos + 12 <= n && !seen_end) {
        uint32_t len = be32(d + pos);
        const uint8_t *type = d + pos + 4, *data = d + pos + 8;
        CHECK(t, image_crc32(type, 4 + len, 0) == be32(data + len), "chunk %.4s CRC", (const char *)type);
        if (memcmp(type, "IHDR", 4) == 0)
            CHECK(t, be32(data) == W && be32(data + 4) == H && data[8] == 8 && data[9] == 2, "IHDR");
        if (memcmp(type, "IDAT", 4) == 0) {
            CHECK(t, data[0] == 0x78 && (data[0] * 256 + data[1]) % 31 == 0, "zlib header");
            size_t z = 2;
            for (int final = 0; !final && z + 5 <= len;) {
                final = data[z] & 1;
                CHECK(t, (data[z] >> 1 & 3) == 0, "not a stored block");
                size_t blen = data[z + 1] | (size_t)data[z + 2] << 8, nlen = data[z + 3] | (size_t)data[z + 4] << 8;
                CHECK(t, (blen ^ 0xffff) == nlen && raw_n + blen <= raw_size, "stored block length");
                if (raw_n + blen > raw_size)
                    break;
                memcpy(raw + raw_n, data + z + 5, blen);
                raw_n += blen, z += 5 + blen;
            }
            CHECK(t, z + 4 == len && be32(data + z) == image_adler32(raw, raw_n), "Adler-32 trailer");
        }
        seen_end = memcmp(type, "IEND", 4) == 0;
        pos += 12 + len;
    }
    CHECK(t, seen_end && raw_n == raw_size, "IEND and all rows");
    for (int y = 0; y < H && raw_n == raw_size; y++) {
        CHECK(t, raw[(size_t)y * (W * 3 + 1)] == 0, "filter byte of row %d", y);
        CHECK(t, memcmp(raw + (size_t)y * (W * 3 + 1) + 1, rgb + (size_t)y * W * 3, W * 3) == 0, "row %d", y);
    }
    free(raw);
    free(d);
    unlink(path);
    uint8_t px[3];
    float f[3] = { 0.0f, 1.0f, 1e9f };
    image_tonemap(1, f, 1.0f, px);
    CHECK(t, px[0] == 0 && px[1] == 188 && px[2] == 255, "tone map: %d %d %d", px[0], px[1], px[2]);
}

/* OpenEXR, when built with it: float RGB read back bit for bit through OpenEXR's own decoder,
 * over several chunks; without it the writer refuses with -2. */
static void test_exr_round_trip(hb_test_ctx *t)
{
    enum { W = 37, H = 41 };
    static float rgb[W * H * 3];
    for (int k = 0; k < W * H * 3; k++)
        rgb[k] = (float)((k % 97) * 0.37 - 2.0) * (k % 5 == 0 ? 1e-30f : 1.0f);
    rgb[5] = 3.4e38f, rgb[6] = 1e-40f; /* the largest float, a denormal */
    char path[600];
    CHECK(t, hb_test_temp_file(path, sizeof path, ".exr") == 0, "no temporary file");
    if (!image_exr_available()) {
        CHECK(t, image_write_exr(path, W, H, rgb) == -2, "without OpenEXR the writer must refuse");
        hb_test_note(t, "built without OpenEXR: EXR round trip not run");
        unlink(path);
        return;
    }
    CHECK(t, image_write_exr(path, W, H, rgb) == 0, "write");
    int w = 0, h = 0;
    float *back = image_read_exr(path, &w, &h);
    CHECK(t, back && w == W && h == H && memcmp(back, rgb, sizeof rgb) == 0, "EXR read back differs (%dx%d)", w, h);
    free(back);
    unlink(path);
}

/* Runs `hairbsdf dump ARGS -o FILE.EXT` and reads the image back (PFM, or EXR). */
static float *run_dump(hb_test_ctx *t, const char *args, const char *ext, int *w, int *h)
{
    char path[600], suffix[8], command[1024];
    hb_tool_run run;
    snprintf(suffix, sizeof suffix, ".%s", ext);
    if (hb_test_temp_file(path, sizeof path, suffix) != 0) {
        CHECK(t, 0, "no temporary file in %s", hb_test_temp_dir());
        return NULL;
    }
    snprintf(command, sizeof command, "dump %s -o \"%s\"", args, path);
    float *img = NULL;
    if (hb_test_run_tool(t, command, "", 0, &run)) {
        CHECK(t, run.status == 0, "%s: %d %s", command, run.status, run.err);
        img = strcmp(ext, "exr") == 0 ? image_read_exr(path, w, h) : read_pfm(path, w, h);
    }
    unlink(path);
    return img;
}

/* Whether columns [x0, x0 + w) of an image `stride` wide hold the library's f at the pixel centres
 * for w_i = (0.3, 0.2) under the given material and options. */
static void check_panel(hb_test_ctx *t, const float *img, int stride, int x0, int w, int h, const hb_material *m,
                        const hb_options *o)
{
    hb_plan *plan;
    CHECK(t, hb_plan_create(m, o, &plan, NULL) == HB_OK, "plan");
    enum { ROW = 512 };
    float ti[ROW], pi[ROW], to[ROW], po[ROW], f[3][ROW];
    for (int y = 0; img && y < h && w <= ROW; y++) { /* a row per call, as the tool batches them */
        for (int x = 0; x < w; x++) {
            ti[x] = 0.3f, pi[x] = 0.2f;
            to[x] = (float)(M_PI_2 - M_PI * (y + 0.5) / h), po[x] = (float)(-M_PI + 2 * M_PI * (x + 0.5) / w);
        }
        hb_eval_angles(plan, (size_t)w, (hb_angles_soa){ ti, pi, to, po }, (hb_rgb_soa){ f[0], f[1], f[2] }, NULL);
        for (int x = 0; x < w; x++) {
            const float *px = img + ((size_t)y * stride + x0 + x) * 3;
            CHECK(t, px[0] == f[0][x] && px[1] == f[1][x] && px[2] == f[2][x], "panel at %d, pixel (%d, %d): %g vs %g",
                  x0, x, y, px[0], f[0][x]);
        }
    }
    hb_plan_destroy(plan);
}

/* hairbsdf dump: the PFM's pixels are the library's f at the pixel centres, and so are the EXR's. */
static void test_dump_matches_library(hb_test_ctx *t)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    m.eumelanin = 0.3;
    int w = 0, h = 0;
    float *img = run_dump(t, "--theta-i 0.3 --phi-i 0.2 --eumelanin 0.3 --width 16 --height 8", "pfm", &w, &h);
    CHECK(t, img && w == 16 && h == 8, "PFM %dx%d", w, h);
    check_panel(t, img, w, 0, w, h, &m, &o);
    if (image_exr_available()) {
        int we = 0, he = 0;
        float *exr = run_dump(t, "--theta-i 0.3 --phi-i 0.2 --eumelanin 0.3 --width 16 --height 8", "exr", &we, &he);
        CHECK(t, img && exr && we == w && he == h && memcmp(exr, img, (size_t)w * h * 12) == 0, "EXR differs from PFM");
        free(exr);
    }
    free(img);
}

/* A PNG dump is a figure: the panels framed by axes, titles, a caption and a colour scale, so the
 * picture is larger than its panels; the float formats hold the panels alone (above). */
static void test_dump_png_figure(hb_test_ctx *t)
{
    static const char *const args[2] = { "--width 64 --height 32", "--width 64 --height 32 --compare model=marschner" };
    for (int k = 0; k < 2; k++) {
        char path[600], command[1024];
        hb_tool_run run;
        if (hb_test_temp_file(path, sizeof path, ".png") != 0) {
            CHECK(t, 0, "no temporary file in %s", hb_test_temp_dir());
            return;
        }
        snprintf(command, sizeof command, "dump --theta-i 0.3 %s -o \"%s\"", args[k], path);
        if (!hb_test_run_tool(t, command, "", 0, &run))
            return;
        CHECK(t, run.status == 0, "%s: %d %s", command, run.status, run.err);
        size_t n = 0;
        uint8_t *d = slurp(path, &n);
        unlink(path);
        CHECK(t, d && n > 24 && memcmp(d + 12, "IHDR", 4) == 0, "%s: no PNG header", args[k]);
        if (!d || n <= 24)
            continue;
        unsigned w = (unsigned)d[16] << 24 | (unsigned)d[17] << 16 | (unsigned)d[18] << 8 | d[19];
        unsigned h = (unsigned)d[20] << 24 | (unsigned)d[21] << 16 | (unsigned)d[22] << 8 | d[23];
        unsigned panels = k ? 3u : 1u;
        CHECK(t, w > 64u * panels + 60u && h > 32u + 40u, "%s: a %u x %u figure for %u panels of 64 x 32", args[k], w, h,
              panels);
        free(d);
    }
}

/* Side by side: the first panel is the options, the second the options with --compare applied,
 * the third their absolute difference. */
static void test_dump_side_by_side(hb_test_ctx *t)
{
    int w = 0, h = 0;
    float *img = run_dump(t, "--model deon --theta-i 0.3 --phi-i 0.2 --width 12 --height 6 --compare model=marschner "
                             "--compare quality=fast", "pfm", &w, &h);
    CHECK(t, img && w == 36 && h == 6, "PFM %dx%d: three panels of 12x6", w, h);
    hb_material m;
    hb_options first, second;
    hb_material_default(&m);
    hb_options_default(&first);
    second = first;
    second.model = HB_MODEL_MARSCHNER, second.quality = HB_QUALITY_FAST;
    check_panel(t, img, w, 0, 12, h, &m, &first);
    check_panel(t, img, w, 12, 12, h, &m, &second);
    for (int y = 0; img && y < h; y++)
        for (int k = 0; k < 36; k++) {
            const float *line = img + (size_t)y * w * 3;
            CHECK(t, line[72 + k] == fabsf(line[k] - line[36 + k]), "difference at row %d, value %d", y, k);
        }
    free(img);
    hb_tool_run run;
    hb_test_run_tool(t, "dump --compare nosuch=1 -o never.pfm", "", 0, &run);
    CHECK(t, run.status == 2 && strstr(run.err, "nosuch"), "an unknown --compare option must fail: %d %s", run.status,
          run.err);
}

const hb_test hb_tests_images[] = {
    { "image_checksums", test_checksums, 0 },
    { "image_pfm_round_trip", test_pfm_round_trip, 0 },
    { "image_png_round_trip", test_png_round_trip, 0 },
    { "image_dump_png_figure", test_dump_png_figure, 0 },
    { "image_exr_round_trip", test_exr_round_trip, 0 },
    { "image_dump_matches_library", test_dump_matches_library, 0 },
    { "image_dump_side_by_side", test_dump_side_by_side, 0 },
    { NULL, NULL, 0 },
};

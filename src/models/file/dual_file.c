/* Dual-scattering table files. Both formats are framed alike (little-endian): an 8-byte magic, u64
 * file length, char[16] library version (informative), the body, u64 XXH64 (seed 0) of every byte
 * before.
 * A material's table, "HBDUALT1": u32 model, u32 nodes, f64 d_f, f64 d_b, the fields section of the
 * plan it was built for (table_file.h), u64 value count (27 per node), f64 values (per node a_f,
 * a_b, alpha_f, beta_f2, alpha_b, beta_b2, A_b, delta_b, sigma_b2, each r, g, b).
 * An engine-wide table, "HBDUALE1": u32 model, u32 thetas, u32 roughnesses, u32 absorptions, u32
 * sampled directions, u32 sampled azimuths, f64 roughness_min, f64 roughness_max, f64
 * absorption_max, f64 d_b, the base plan's fields section, u64 value count (6 per node), f64 values
 * (per node a_f, a_b, alpha_f, beta_f2, alpha_b, beta_b2; node (r, j, k) at
 * (r * absorptions + j) * thetas + k). */
#include <math.h>

#include "dual_file.h"
#include "math/hash.h"

#define MAGIC "HBDUALT1"
#define ENGINE_MAGIC "HBDUALE1"
#define TEXT_BYTES 16
#define MOST_NODES 4096
#define MOST_AXIS_NODES 65536

/* The frame's head: the magic, the length (patched by frame_close) and the version. */
static void frame_open(hb_writer *w, const char *magic)
{
    hb_put(w, magic, 8);
    hb_put_uint(w, 0, 8);
    hb_put_text(w, HB_VERSION_STRING, TEXT_BYTES);
}

/* The frame's tail: the length into the head, then the checksum. The file's length. */
static size_t frame_close(hb_writer *w)
{
    if (w->out) {
        hb_writer length = { w->out + 8, 0 };
        hb_put_uint(&length, w->at + 8, 8);
    }
    hb_put_uint(w, w->out ? hb_xxh64(w->out, w->at) : 0, 8);
    return w->at;
}

/* Checks the frame of a file of `what` (its magic, length and checksum) and gives a reader of its body. */
static hb_status frame_read(const char *what, const char *magic, const unsigned char *bytes, size_t size, hb_reader *body,
                            hb_error *error)
{
    hb_reader r = { bytes, bytes + size };
    char head[8], version[TEXT_BYTES];
    unsigned long long length = 0, sum = 0;
    if (!hb_take(&r, head, 8) || memcmp(head, magic, 8) != 0)
        return hb_plan_fail(error, HB_ERR_FILE, "%s file: it does not start with %s: not a hairbsdf %s of this format",
                            what, magic, what);
    if (!hb_take_uint(&r, &length, 8) || length != size || size < 8 + 8 + TEXT_BYTES + 8)
        return hb_plan_fail(error, HB_ERR_FILE, "%s file: %zu bytes where its header says %llu: truncated or padded", what,
                            size, length);
    hb_reader tail = { bytes + size - 8, bytes + size };
    if (!hb_take_uint(&tail, &sum, 8) || sum != hb_xxh64(bytes, size - 8))
        return hb_plan_fail(error, HB_ERR_FILE, "%s file: its checksum does not match its bytes: the file is damaged", what);
    r.end = bytes + size - 8;
    hb_take_text(&r, version, sizeof version);
    *body = r;
    return HB_OK;
}

/* The model (against the plan's), then the plan's fields, then the value count against `count`. */
static hb_status body_read(const char *what, hb_reader *r, int model, const hb_plan *plan, unsigned long long count,
                           hb_error *error)
{
    if ((hb_model)model != plan->options.model)
        return hb_plan_fail(error, HB_ERR_FILE, "%s file: built for model %d, this plan's is %d", what, model,
                            (int)plan->options.model);
    hb_status st = hb_table_file_fields_read(r, plan, error);
    if (st != HB_OK)
        return st;
    unsigned long long stored = 0;
    if (!hb_take_uint(r, &stored, 8) || stored != count || (unsigned long long)(r->end - r->at) != count * 8)
        return hb_plan_fail(error, HB_ERR_FILE, "%s file: its value count does not match its nodes and length", what);
    return HB_OK;
}

/* Every value finite, and the energies and variances among each node's `per_node` (the indices whose
 * bit is set in `positive`) not negative. */
static hb_status values_check(const char *what, const unsigned char *values, size_t count, int per_node,
                              unsigned long long positive, hb_error *error)
{
    for (size_t k = 0; k < count; k++) {
        double x = hb_dual_file_value(values, k);
        if (!isfinite(x) || (positive >> (k % (size_t)per_node) & 1u && x < 0.0))
            return hb_plan_fail(error, HB_ERR_FILE, "%s file: value %zu is %g", what, k, x);
    }
    return HB_OK;
}

static void values_write(hb_writer *w, const double *values, size_t count)
{
    hb_put_uint(w, count, 8);
    for (size_t k = 0; k < count; k++) /* counting (out NULL) reads no value */
        hb_put_f64(w, w->out ? values[k] : 0.0);
}

size_t hb_dual_file_write(hb_model model, int thetas, double d_f, double d_b, const unsigned char *fields,
                          size_t fields_size, const double *values, unsigned char *out)
{
    hb_writer w = { out, 0 };
    frame_open(&w, MAGIC);
    hb_put_uint(&w, (unsigned)model, 4), hb_put_uint(&w, (unsigned)thetas, 4);
    hb_put_f64(&w, d_f), hb_put_f64(&w, d_b);
    hb_put(&w, fields, fields_size);
    values_write(&w, values, (size_t)thetas * HB_DUAL_FILE_TERMS);
    return frame_close(&w);
}

double hb_dual_file_value(const unsigned char *values, size_t k)
{
    hb_reader r = { values + 8 * k, values + 8 * k + 8 };
    double x = 0.0;
    hb_take_f64(&r, &x);
    return x;
}

hb_status hb_dual_file_read(const hb_plan *plan, const unsigned char *bytes, size_t size, int *thetas, double *d_f,
                            double *d_b, const unsigned char **values, hb_error *error)
{
    const char *what = "dual table";
    hb_reader r;
    hb_status st = frame_read(what, MAGIC, bytes, size, &r, error);
    if (st != HB_OK)
        return st;
    int model;
    if (!hb_take_u32(&r, &model, 3) || !hb_take_u32(&r, thetas, MOST_NODES) || !hb_take_f64(&r, d_f) ||
        !hb_take_f64(&r, d_b) || *thetas < 2 || !(*d_f >= 0.0 && *d_f <= 1.0) || !(*d_b >= 0.0 && *d_b <= 1.0))
        return hb_plan_fail(error, HB_ERR_FILE, "%s file: its model, node count or density factors are out of range", what);
    size_t count = (size_t)*thetas * HB_DUAL_FILE_TERMS;
    st = body_read(what, &r, model, plan, count, error);
    if (st != HB_OK)
        return st;
    *values = r.at;
    return values_check(what, r.at, count, HB_DUAL_FILE_TERMS, 0x3full, error); /* a_f, a_b: 6 values */
}

size_t hb_dual_engine_file_write(hb_model model, const hb_dual_engine_axes *axes, double d_b,
                                 const unsigned char *fields, size_t fields_size, const double *values,
                                 unsigned char *out)
{
    hb_writer w = { out, 0 };
    frame_open(&w, ENGINE_MAGIC);
    const int counts[] = { (int)model, axes->thetas, axes->roughnesses, axes->absorptions, axes->sampled_directions,
                           axes->sampled_azimuths };
    for (size_t k = 0; k < sizeof counts / sizeof *counts; k++)
        hb_put_uint(&w, (unsigned)counts[k], 4);
    hb_put_f64(&w, axes->roughness_min), hb_put_f64(&w, axes->roughness_max), hb_put_f64(&w, axes->absorption_max);
    hb_put_f64(&w, d_b);
    hb_put(&w, fields, fields_size);
    values_write(&w, values,
                 (size_t)axes->thetas * (size_t)axes->roughnesses * (size_t)axes->absorptions * HB_DUAL_ENGINE_TERMS);
    return frame_close(&w);
}

hb_status hb_dual_engine_file_read(const hb_plan *plan, const unsigned char *bytes, size_t size,
                                   hb_dual_engine_axes *axes, double *d_b, const unsigned char **values,
                                   hb_error *error)
{
    const char *what = "dual engine table";
    hb_reader r;
    hb_status st = frame_read(what, ENGINE_MAGIC, bytes, size, &r, error);
    if (st != HB_OK)
        return st;
    int model;
    *axes = (hb_dual_engine_axes){ .struct_size = sizeof *axes };
    if (!hb_take_u32(&r, &model, 3) || !hb_take_u32(&r, &axes->thetas, MOST_AXIS_NODES) ||
        !hb_take_u32(&r, &axes->roughnesses, MOST_AXIS_NODES) || !hb_take_u32(&r, &axes->absorptions, MOST_AXIS_NODES) ||
        !hb_take_u32(&r, &axes->sampled_directions, MOST_AXIS_NODES) ||
        !hb_take_u32(&r, &axes->sampled_azimuths, MOST_AXIS_NODES) || !hb_take_f64(&r, &axes->roughness_min) ||
        !hb_take_f64(&r, &axes->roughness_max) || !hb_take_f64(&r, &axes->absorption_max) || !hb_take_f64(&r, d_b) ||
        !(*d_b >= 0.0 && *d_b <= 1.0))
        return hb_plan_fail(error, HB_ERR_FILE, "%s file: its model, axes or density factor are out of range", what);
    size_t count = (size_t)axes->thetas * (size_t)axes->roughnesses * (size_t)axes->absorptions * HB_DUAL_ENGINE_TERMS;
    st = body_read(what, &r, model, plan, count, error);
    if (st != HB_OK)
        return st;
    *values = r.at;
    return values_check(what, r.at, count, HB_DUAL_ENGINE_TERMS, 0x2bull, error); /* a_f, a_b, beta_f2, beta_b2 */
}

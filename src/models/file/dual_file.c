/* Dual-scattering table files. Layout (little-endian): "HBDUALT1", u64 file length, char[16] library
 * version (informative), u32 model, u32 nodes, f64 d_f, f64 d_b, the fields section of the plan it
 * was built for (table_file.h), u64 value count (27 per node), f64 values (per node a_f, a_b,
 * alpha_f, beta_f2, alpha_b, beta_b2, A_b, delta_b, sigma_b2, each r, g, b), u64 XXH64 (seed 0) of
 * every byte before. */
#include <math.h>

#include "dual_file.h"
#include "math/hash.h"

#define MAGIC "HBDUALT1"
#define TEXT_BYTES 16
#define MOST_NODES 4096

size_t hb_dual_file_write(hb_model model, int thetas, double d_f, double d_b, const unsigned char *fields,
                          size_t fields_size, const double *values, unsigned char *out)
{
    size_t count = (size_t)thetas * HB_DUAL_FILE_TERMS;
    hb_writer w = { out, 0 };
    hb_put(&w, MAGIC, 8);
    hb_put_uint(&w, 8 + 8 + TEXT_BYTES + 8 + 16 + fields_size + 8 + count * 8 + 8, 8);
    hb_put_text(&w, HB_VERSION_STRING, TEXT_BYTES);
    hb_put_uint(&w, (unsigned)model, 4), hb_put_uint(&w, (unsigned)thetas, 4);
    hb_put_f64(&w, d_f), hb_put_f64(&w, d_b);
    hb_put(&w, fields, fields_size);
    hb_put_uint(&w, count, 8);
    for (size_t k = 0; k < count; k++) /* counting (out NULL) reads no value */
        hb_put_f64(&w, out ? values[k] : 0.0);
    hb_put_uint(&w, out ? hb_xxh64(out, w.at) : 0, 8);
    return w.at;
}

double hb_dual_file_value(const unsigned char *values, size_t k)
{
    hb_reader r = { values + 8 * k, values + 8 * k + 8 };
    double x = 0.0;
    hb_take_f64(&r, &x);
    return x;
}

static hb_status refuse(hb_error *error, const char *why)
{
    return hb_plan_fail(error, HB_ERR_FILE, "dual table file: %s", why);
}

hb_status hb_dual_file_read(const hb_plan *plan, const unsigned char *bytes, size_t size, int *thetas, double *d_f,
                            double *d_b, const unsigned char **values, hb_error *error)
{
    hb_reader r = { bytes, bytes + size };
    char magic[8], version[TEXT_BYTES];
    unsigned long long length = 0, sum = 0, count = 0;
    if (!hb_take(&r, magic, 8) || memcmp(magic, MAGIC, 8) != 0)
        return refuse(error, "it does not start with " MAGIC ": not a hairbsdf dual-scattering table of this format");
    if (!hb_take_uint(&r, &length, 8) || length != size || size < 8 + 8 + 8)
        return hb_plan_fail(error, HB_ERR_FILE, "dual table file: %zu bytes where its header says %llu: truncated or padded",
                            size, length);
    hb_reader tail = { bytes + size - 8, bytes + size };
    if (!hb_take_uint(&tail, &sum, 8) || sum != hb_xxh64(bytes, size - 8))
        return refuse(error, "its checksum does not match its bytes: the file is damaged");
    r.end = bytes + size - 8;
    int model;
    if (!hb_take_text(&r, version, sizeof version) || !hb_take_u32(&r, &model, 3) || !hb_take_u32(&r, thetas, MOST_NODES) ||
        !hb_take_f64(&r, d_f) || !hb_take_f64(&r, d_b) || *thetas < 2 || !(*d_f >= 0.0 && *d_f <= 1.0) ||
        !(*d_b >= 0.0 && *d_b <= 1.0))
        return refuse(error, "its model, node count or density factors are out of range");
    if ((hb_model)model != plan->options.model)
        return hb_plan_fail(error, HB_ERR_FILE, "dual table file: built for model %d, this plan's is %d", model,
                            (int)plan->options.model);
    hb_status st = hb_table_file_fields_read(&r, plan, error);
    if (st != HB_OK)
        return st;
    if (!hb_take_uint(&r, &count, 8) || count != (unsigned long long)*thetas * HB_DUAL_FILE_TERMS ||
        (unsigned long long)(r.end - r.at) != count * 8)
        return refuse(error, "its value count does not match its nodes and length");
    *values = r.at;
    for (size_t k = 0; k < count; k++) {
        double x = hb_dual_file_value(r.at, k);
        if (!isfinite(x) || (k % HB_DUAL_FILE_TERMS < 6 && x < 0.0)) /* a_f, a_b are never negative */
            return hb_plan_fail(error, HB_ERR_FILE, "dual table file: value %zu is %g", k, x);
    }
    return HB_OK;
}

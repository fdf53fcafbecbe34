/* Table files: writing a plan's table with its header, and reading one back against a plan.
 * Layout (little-endian; docs/engines.md): "HBTABLE3", u64 file length, char[16] library version and
 * char[16] ISA that built it (both informative), u32 model, its table version (the parameterisation
 * of the values), axes, slots, channels (3, or 1 for a colour table); per axis u32 nodes, f64 lo,
 * f64 hi, char[64] what it is; per slot u32 lobe mask; f64 measured error; u32 field count, then
 * per field char[24] name and f64 value (the material and options the table depends on); u64
 * value count; f32 values (axes row-major, then slot, then RGB); u64 XXH64 (seed 0) of every byte before. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bytes.h"
#include "math/hash.h"
#include "models/interface/model.h"
#include "table_file.h"

#define NAME_BYTES 24
#define AXIS_BYTES 64
#define TEXT_BYTES 16
#define MAX_FIELDS 64
/* No table holds more (N_p is at most about 1 / beta_n, HHH22's square roots of TT + TRT far below
 * this at the smallest roughness). The kernels square a value (HHH22), multiply it by M_p or by the
 * pole's width factor (at most 1e8) and sum a few: (1e12)^2 1e8 stays finite in float. */
#define HB_TABLE_VALUE_LIMIT 1e12f

/* An optional field is written only where its value is not 0, and a file without it was baked at 0:
 * an option added in a later release whose default keeps the tables as they were. */
typedef struct field {
    char name[NAME_BYTES];
    double value;
    int optional;
} field;

static int add(field *f, int k, const char *name, double value)
{
    memset(f[k].name, 0, sizeof f[k].name); /* the padding is written too */
    snprintf(f[k].name, sizeof f[k].name, "%s", name);
    f[k].value = value;
    f[k].optional = 0;
    return k + 1;
}

static int add_optional(field *f, int k, const char *name, double value)
{
    k = add(f, k, name, value);
    f[k - 1].optional = 1;
    return k;
}

static int written(const field *f) { return !f->optional || f->value != 0.0; }

static int add_array(field *f, int k, const char *name, const double *v, int n)
{
    char indexed[NAME_BYTES];
    for (int j = 0; j < n; j++) {
        snprintf(indexed, sizeof indexed, "%s[%d]", name, j);
        k = add(f, k, indexed, v[j]);
    }
    return k;
}

/* Everything of the material and options a table depends on, by name: a colour table serves every
 * absorption, so its file names none. */
static int plan_fields(const hb_plan *plan, field *f)
{
    const hb_material *m = &plan->material;
    const hb_options *o = &plan->options;
    int k = add(f, 0, "eta", m->eta);
    if (o->azimuthal != HB_AZIMUTHAL_COLOUR_TABLE) {
        k = add_array(f, k, "sigma_a", m->sigma_a, 3);
        k = add(f, k, "eumelanin", m->eumelanin), k = add(f, k, "pheomelanin", m->pheomelanin);
    }
    k = add(f, k, "beta_m", m->beta_m), k = add(f, k, "beta_n", m->beta_n), k = add(f, k, "alpha", m->alpha);
    k = add(f, k, "ndf", m->ndf), k = add(f, k, "roughness", m->roughness), k = add(f, k, "eccentricity", m->eccentricity);
    k = add_array(f, k, "lobe_beta_m", m->lobe_beta_m, HB_MAX_LOBES);
    k = add_array(f, k, "lobe_beta_n", m->lobe_beta_n, HB_MAX_LOBES);
    k = add_array(f, k, "lobe_alpha", m->lobe_alpha, HB_MAX_LOBES);
    k = add(f, k, "lobe_alpha_override", m->lobe_alpha_override);
    k = add(f, k, "glint_scale", m->glint_scale), k = add(f, k, "caustic_width", m->caustic_width);
    k = add(f, k, "caustic_fade", m->caustic_fade), k = add(f, k, "caustic_limit", m->caustic_limit);
    k = add(f, k, "lobes", o->lobes), k = add(f, k, "term", o->term), k = add(f, k, "quality", o->quality);
    k = add(f, k, "i0", o->i0), k = add(f, k, "pmax", o->pmax), k = add(f, k, "absorption", o->absorption);
    k = add(f, k, "quadrature_order", o->quadrature_order);
    k = add(f, k, "detector_tolerance", o->detector_tolerance), k = add(f, k, "r_fresnel", o->r_fresnel);
    k = add(f, k, "shadowing", o->shadowing), k = add(f, k, "tt_trt", o->tt_trt), k = add(f, k, "tt_panels", o->tt_panels);
    k = add(f, k, "azimuthal", o->azimuthal), k = add(f, k, "table_tolerance", o->table_tolerance);
    /* HHH22's tables are bounded at the poles below reference quality but for pole_floor = paper */
    return add_optional(f, k, "pole_floor", o->pole_floor == HB_POLE_FLOOR_PAPER);
}

size_t hb_table_file_fields_write(const hb_plan *plan, unsigned char *out)
{
    field fields[MAX_FIELDS];
    int n_own = plan_fields(plan, fields), n_fields = 0;
    for (int k = 0; k < n_own; k++)
        if (written(&fields[k]))
            fields[n_fields++] = fields[k];
    hb_writer w = { out, 0 };
    hb_put_uint(&w, (unsigned)n_fields, 4);
    for (int k = 0; k < n_fields; k++) {
        hb_put(&w, fields[k].name, NAME_BYTES);
        hb_put_f64(&w, fields[k].value);
    }
    return w.at;
}

size_t hb_table_file_write(const hb_plan *plan, const hb_table_view *v, int channels, unsigned char *out)
{
    hb_writer w = { out, 0 };
    hb_put(&w, "HBTABLE" HB_TABLE_FILE_FORMAT_DIGIT, 8);
    size_t length = 8 + 8 + 2 * TEXT_BYTES + 20 + (size_t)v->axes * (4 + 16 + AXIS_BYTES) + (size_t)v->slots * 4 + 8 +
                    hb_table_file_fields_write(plan, NULL) + 8 + v->count * 4 + 8;
    hb_put_uint(&w, length, 8);
    hb_put_text(&w, HB_VERSION_STRING, TEXT_BYTES);
    hb_put_text(&w, hb_isa_name(plan->isa), TEXT_BYTES);
    hb_put_uint(&w, (unsigned)v->model, 4), hb_put_uint(&w, (unsigned)hb_model_ops_of(v->model)->table_version, 4);
    hb_put_uint(&w, (unsigned)v->axes, 4), hb_put_uint(&w, (unsigned)v->slots, 4);
    hb_put_uint(&w, (unsigned)channels, 4);
    for (int k = 0; k < v->axes; k++) {
        hb_put_uint(&w, (unsigned)v->size[k], 4);
        hb_put_f64(&w, v->lo[k]), hb_put_f64(&w, v->hi[k]);
        hb_put_text(&w, v->axis[k], AXIS_BYTES);
    }
    for (int s = 0; s < v->slots; s++)
        hb_put_uint(&w, v->slot_lobes[s], 4);
    hb_put_f64(&w, v->error);
    w.at += hb_table_file_fields_write(plan, out ? out + w.at : NULL);
    hb_put_uint(&w, v->count, 8);
    for (size_t k = 0; k < v->count; k++) {
        unsigned bits;
        memcpy(&bits, &v->values[k], 4);
        hb_put_uint(&w, bits, 4);
    }
    hb_put_uint(&w, out ? hb_xxh64(out, w.at) : 0, 8);
    return w.at;
}

static hb_status refuse(hb_error *error, const char *why)
{
    return hb_plan_fail(error, HB_ERR_FILE, "table file: %s", why);
}

hb_status hb_table_file_fields_read(hb_reader *r, const hb_plan *plan, hb_error *error)
{
    field own[MAX_FIELDS];
    int n_own = plan_fields(plan, own), n_file, seen[MAX_FIELDS] = { 0 };
    if (!hb_take_u32(r, &n_file, MAX_FIELDS))
        return refuse(error, "its field count is damaged");
    for (int k = 0; k < n_file; k++) {
        char name[NAME_BYTES];
        double value;
        if (!hb_take_text(r, name, sizeof name) || !hb_take_f64(r, &value))
            return refuse(error, "it ends inside its fields");
        int j = 0;
        while (j < n_own && strcmp(own[j].name, name) != 0)
            j++;
        if (j == n_own)
            return hb_plan_fail(error, HB_ERR_FILE, "table file: it names a field '%.23s' this library does not know", name);
        if (seen[j]++) /* each field once: a repeated one would stand in for another that is then never checked */
            return hb_plan_fail(error, HB_ERR_FILE, "table file: it names the field '%.23s' twice", name);
        if (memcmp(&own[j].value, &value, sizeof value) != 0)
            return hb_plan_fail(error, HB_ERR_FILE,
                                "table file: baked for %s = %.17g, this plan's is %.17g: bake it for this material and "
                                "these options", name, value, own[j].value);
    }
    for (int j = 0; j < n_own; j++)
        if (!seen[j] && written(&own[j]))
            return hb_plan_fail(error, HB_ERR_FILE,
                                "table file: it has no field '%s'%s, this plan's is %.17g: bake it for this material "
                                "and these options", own[j].name, own[j].optional ? " (baked at 0)" : "", own[j].value);
    return HB_OK;
}

static const char *const model_names[] = { "marschner", "deon", "huang", "chiang" };

hb_status hb_table_file_read(const hb_plan *plan, hb_table_file *file, hb_error *error)
{
    const unsigned char *bytes = plan->options.table_file;
    size_t size = plan->options.table_file_size;
    hb_reader r = { bytes, bytes + size };
    char magic[9] = { 0 }, version[TEXT_BYTES], isa[TEXT_BYTES];
    if (!hb_take(&r, magic, 8) || memcmp(magic, "HBTABLE", 7) != 0)
        return refuse(error, "it does not start with HBTABLE: not a hairbsdf table");
    if (magic[7] != '0' + HB_TABLE_FILE_FORMAT)
        return hb_plan_fail(error, HB_ERR_FILE, "table file: format '%c', this library reads format %d: bake it again",
                            magic[7], HB_TABLE_FILE_FORMAT);
    unsigned long long length;
    if (size < 16 + 8)
        return hb_plan_fail(error, HB_ERR_FILE, "table file: %zu bytes, shorter than any table file", size);
    if (!hb_take_uint(&r, &length, 8) || length != size)
        return hb_plan_fail(error, HB_ERR_FILE, "table file: %zu bytes where its header says %llu: truncated or padded",
                            size, length);
    unsigned long long sum = 0;
    hb_reader tail = { bytes + size - 8, bytes + size };
    if (!hb_take_uint(&tail, &sum, 8) || sum != hb_xxh64(bytes, size - 8))
        return refuse(error, "its checksum does not match its bytes: the file is damaged");
    r.end = bytes + size - 8;
    if (!hb_take_text(&r, version, sizeof version) || !hb_take_text(&r, isa, sizeof isa))
        return refuse(error, "it ends inside its header");
    hb_table_view *v = &file->layout;
    *v = (hb_table_view){ 0 };
    int model, table_version;
    if (!hb_take_u32(&r, &model, 3) || !hb_take_u32(&r, &table_version, 0x7fffffffu) ||
        !hb_take_u32(&r, &v->axes, HB_TABLE_MAX_AXES) ||
        !hb_take_u32(&r, &v->slots, HB_MAX_LOBES + 1) || !hb_take_u32(&r, &file->channels, 3) ||
        (file->channels != 3 && file->channels != 1) || v->axes < 1)
        return refuse(error, "its model, axes, slots or channels are out of range");
    v->model = (hb_model)model;
    if (v->model != plan->options.model)
        return hb_plan_fail(error, HB_ERR_FILE, "table file: baked for model %s, this plan's is %s", model_names[model],
                            model_names[plan->options.model]);
    /* the library version is informative: any release whose model's tables have the file's
     * parameterisation reads it */
    int own_version = hb_model_ops_of(v->model)->table_version;
    if (table_version != own_version)
        return hb_plan_fail(error, HB_ERR_FILE,
                            "table file: %s tables of version %d (baked by hairbsdf %.15s), this library's are version %d: "
                            "bake it again with this library", model_names[model], table_version, version, own_version);
    for (int k = 0; k < v->axes; k++)
        if (!hb_take_u32(&r, &v->size[k], 1u << 20) || !hb_take_f64(&r, &v->lo[k]) || !hb_take_f64(&r, &v->hi[k]) ||
            !hb_take(&r, NULL, AXIS_BYTES))
            return refuse(error, "it ends inside its axes");
    for (int s = 0; s < v->slots; s++) {
        int lobes;
        if (!hb_take_u32(&r, &lobes, (2u << HB_LOBE_RESIDUAL) - 1))
            return refuse(error, "a slot's lobe mask is damaged");
        v->slot_lobes[s] = (unsigned)lobes;
    }
    if (!hb_take_f64(&r, &v->error))
        return refuse(error, "it ends inside its header");
    hb_status st = hb_table_file_fields_read(&r, plan, error);
    if (st != HB_OK)
        return st;
    unsigned long long count;
    if (!hb_take_uint(&r, &count, 8) || count != (unsigned long long)(r.end - r.at) / 4 || (r.end - r.at) % 4)
        return refuse(error, "its value count does not match its length");
    v->count = (size_t)count;
    file->values = r.at;
    return HB_OK;
}

hb_status hb_table_file_values(const hb_table_file *file, const hb_table_view *expected, int channels, float *out,
                               hb_error *error)
{
    const hb_table_view *v = &file->layout;
    if (v->axes != expected->axes || v->slots != expected->slots || v->count != expected->count ||
        file->channels != channels)
        return hb_plan_fail(error, HB_ERR_FILE,
                            "table file: %d axes, %d slots, %d channels and %zu values where this plan's table has %d, %d, "
                            "%d and %zu", v->axes, v->slots, file->channels, v->count, expected->axes, expected->slots,
                            channels, expected->count);
    for (int k = 0; k < v->axes; k++)
        if (v->size[k] != expected->size[k] || v->lo[k] != expected->lo[k] || v->hi[k] != expected->hi[k])
            return hb_plan_fail(error, HB_ERR_FILE,
                                "table file: axis %d has %d nodes over [%.9g, %.9g] where this plan's has %d over [%.9g, %.9g]",
                                k, v->size[k], v->lo[k], v->hi[k], expected->size[k], expected->lo[k], expected->hi[k]);
    for (int s = 0; s < v->slots; s++)
        if (v->slot_lobes[s] != expected->slot_lobes[s])
            return hb_plan_fail(error, HB_ERR_FILE, "table file: slot %d sums lobes 0x%x where this plan's sums 0x%x", s,
                                v->slot_lobes[s], expected->slot_lobes[s]);
    for (size_t k = 0; k < v->count; k++) {
        const unsigned char *b = file->values + 4 * k;
        unsigned bits = (unsigned)b[0] | (unsigned)b[1] << 8 | (unsigned)b[2] << 16 | (unsigned)b[3] << 24;
        memcpy(&out[k], &bits, 4);
        if (!(out[k] >= 0.0f && out[k] <= HB_TABLE_VALUE_LIMIT))
            return hb_plan_fail(error, HB_ERR_FILE, "table file: value %zu is %g, outside [0, %g]", k, (double)out[k],
                                (double)HB_TABLE_VALUE_LIMIT);
    }
    return HB_OK;
}

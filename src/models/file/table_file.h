/* Table files (`.hbt`, docs/engines.md): a plan's table with what it was built for, written by
 * hb_table_save and read back at plan creation (options.table_file) instead of being rebuilt.
 * Reading never touches a byte outside the given size; every refusal says why. Internal. */
#ifndef HB_MODELS_TABLE_FILE_H
#define HB_MODELS_TABLE_FILE_H

#include "bytes.h"
#include "models/interface/plan.h"

#define HB_TABLE_FILE_FORMAT 3 /* the digit after "HBTABLE" */
#define HB_TABLE_FILE_FORMAT_DIGIT "3"

/* A file's table after its header was checked against a plan: its layout as hb_table_view gives it
 * (without axis names) and its values, still little-endian bytes inside the caller's file. */
typedef struct hb_table_file {
    hb_table_view layout;
    int channels; /* per node and slot: 3, or 1 (a colour table) */
    const unsigned char *values;
} hb_table_file;

/* The floats of a table of this layout: the product of its sizes, times slots, times channels. */
static inline size_t hb_table_count(const hb_table_view *v, int channels)
{
    size_t count = (size_t)v->slots * (size_t)channels;
    for (int k = 0; k < v->axes; k++)
        count *= (size_t)v->size[k];
    return count;
}

/* The fields section of a file baked for the plan (u32 count, then per field char[24] name and f64
 * value: every material and option field its tables depend on); its length when out is NULL. */
size_t hb_table_file_fields_write(const hb_plan *plan, unsigned char *out);

/* Reads a fields section and checks it against the plan's own: each field once, every one the plan
 * writes present, every value equal (HB_ERR_FILE naming the first that is not, as "table file: ..."). */
hb_status hb_table_file_fields_read(hb_reader *r, const hb_plan *plan, hb_error *error);

/* The file's length for the plan's table view (hb_table_file_write with out NULL), or writes it. */
size_t hb_table_file_write(const hb_plan *plan, const hb_table_view *view, int channels, unsigned char *out);

/* Checks plan->options.table_file: length, format, checksum, model and its table version, and every
 * material and option field the table depends on; fills file on success. */
hb_status hb_table_file_read(const hb_plan *plan, hb_table_file *file, hb_error *error);

/* The file's values into out (expected->count floats) when its layout is `expected` (axes, sizes,
 * ranges, slots and their lobes); every value must be in [0, 1e12]. */
hb_status hb_table_file_values(const hb_table_file *file, const hb_table_view *expected, int channels, float *out,
                               hb_error *error);

#endif

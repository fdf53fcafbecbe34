/* Little-endian bytes of the file formats (table_file.c, dual_file.c): a writer that counts when it
 * has no buffer, and a reader that refuses to pass its end. Internal. */
#ifndef HB_MODELS_FILE_BYTES_H
#define HB_MODELS_FILE_BYTES_H

#include <stdio.h>
#include <string.h>

typedef struct hb_writer {
    unsigned char *out; /* NULL: count only */
    size_t at;
} hb_writer;

static inline void hb_put(hb_writer *w, const void *bytes, size_t n)
{
    if (w->out)
        memcpy(w->out + w->at, bytes, n);
    w->at += n;
}

static inline void hb_put_uint(hb_writer *w, unsigned long long v, int n)
{
    unsigned char b[8];
    for (int k = 0; k < n; k++)
        b[k] = (unsigned char)(v >> (8 * k));
    hb_put(w, b, (size_t)n);
}

static inline void hb_put_f64(hb_writer *w, double x)
{
    unsigned long long bits;
    memcpy(&bits, &x, 8);
    hb_put_uint(w, bits, 8);
}

/* text NUL-padded to n bytes (n at most 64). */
static inline void hb_put_text(hb_writer *w, const char *text, size_t n)
{
    char padded[64] = { 0 };
    snprintf(padded, n, "%s", text ? text : "");
    hb_put(w, padded, n);
}

typedef struct hb_reader {
    const unsigned char *at, *end;
} hb_reader;

static inline int hb_take(hb_reader *r, void *out, size_t n)
{
    if ((size_t)(r->end - r->at) < n)
        return 0;
    if (out)
        memcpy(out, r->at, n);
    r->at += n;
    return 1;
}

static inline int hb_take_uint(hb_reader *r, unsigned long long *v, int n)
{
    unsigned char b[8];
    if (!hb_take(r, b, (size_t)n))
        return 0;
    *v = 0;
    for (int k = n - 1; k >= 0; k--)
        *v = *v << 8 | b[k];
    return 1;
}

static inline int hb_take_u32(hb_reader *r, int *v, unsigned limit)
{
    unsigned long long x;
    if (!hb_take_uint(r, &x, 4) || x > limit)
        return 0;
    *v = (int)x;
    return 1;
}

static inline int hb_take_f64(hb_reader *r, double *x)
{
    unsigned long long bits;
    if (!hb_take_uint(r, &bits, 8))
        return 0;
    memcpy(x, &bits, 8);
    return 1;
}

/* A text field (NUL-padded), terminated. */
static inline int hb_take_text(hb_reader *r, char *text, size_t n)
{
    if (!hb_take(r, text, n))
        return 0;
    text[n - 1] = '\0';
    return 1;
}

#endif

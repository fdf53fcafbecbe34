/* A growing description (hb_plan_describe): appended to a caller's buffer, truncated to its size,
 * the full length counted. Internal. */
#ifndef HB_MODELS_TEXT_H
#define HB_MODELS_TEXT_H

#include <stddef.h>

#include "simd/compiler.h"

typedef struct hb_text {
    char *out;
    size_t size, length;
} hb_text;

void hb_say(hb_text *t, const char *fmt, ...) HB_PRINTF_FORMAT(2, 3);

/* "R, TT, TRT" for a lobe mask, "none" for 0. */
void hb_say_lobes(hb_text *t, unsigned lobes);

/* x with the fewest significant digits that read back as x ("0.0099999998", "1.0000001", "0.01"),
 * written into buf; for messages that name a value beside a limit it just misses. HB_NUM(x) gives
 * it a buffer that lives to the end of the enclosing expression's block. */
const char *hb_shortest(char buf[32], double x);
#define HB_NUM(x) hb_shortest((char[32]){ 0 }, (x))

/* The name of lobe p (an order, or HB_LOBE_RESIDUAL) and of a quality level. */
const char *hb_lobe_name(int p);
const char *hb_quality_name(int quality);

#endif

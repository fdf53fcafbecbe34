/* The description text helpers: see text.h. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "hairbsdf.h"
#include "text.h"

void hb_say(hb_text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(t->length < t->size ? t->out + t->length : NULL, t->length < t->size ? t->size - t->length : 0,
                      fmt, ap);
    va_end(ap);
    t->length += n > 0 ? (size_t)n : 0;
}

const char *hb_shortest(char buf[32], double x)
{
    for (int digits = 6; digits <= 17; digits++) {
        snprintf(buf, 32, "%.*g", digits, x);
        if (strtod(buf, NULL) == x || x != x)
            break;
    }
    return buf;
}

const char *hb_lobe_name(int p)
{
    static const char *const names[HB_MAX_LOBES + 1] = { "R", "TT", "TRT", "TRRT", "p = 4", "p = 5", "p = 6", "p = 7",
                                                         "residual" };
    return p >= 0 && p <= HB_LOBE_RESIDUAL ? names[p] : "?";
}

const char *hb_quality_name(int quality)
{
    static const char *const names[] = { "fast", "balanced", "high", "reference" };
    return quality >= 0 && quality <= HB_QUALITY_REFERENCE ? names[quality] : "?";
}

void hb_say_lobes(hb_text *t, unsigned lobes)
{
    int first = 1;
    for (int p = 0; p <= HB_LOBE_RESIDUAL; p++)
        if (lobes >> p & 1u) {
            hb_say(t, "%s%s", first ? "" : ", ", hb_lobe_name(p));
            first = 0;
        }
    if (first)
        hb_say(t, "none");
}

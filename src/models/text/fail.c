/* hb_plan_fail: a refusal's status and message. */
#include <stdarg.h>
#include <stdio.h>

#include "models/interface/plan.h"

hb_status hb_plan_fail(hb_error *error, hb_status status, const char *fmt, ...)
{
    if (error) {
        va_list ap;
        va_start(ap, fmt);
        error->status = status;
        vsnprintf(error->message, sizeof error->message, fmt, ap);
        va_end(ap);
    }
    return status;
}

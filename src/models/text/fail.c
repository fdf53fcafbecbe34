/* A failure's status and message: the calling thread's last error, and the caller's hb_error. */
#include <stdarg.h>
#include <stdio.h>

#include "models/interface/plan.h"

static HB_THREAD_LOCAL hb_error thread_error;

const hb_error *hb_thread_error(void) { return &thread_error; }

static hb_status fail_va(hb_error *error, hb_status status, const char *fmt, va_list ap)
{
    thread_error.status = status;
    vsnprintf(thread_error.message, sizeof thread_error.message, fmt, ap);
    if (error)
        *error = thread_error;
    return status;
}

hb_status hb_plan_fail(hb_error *error, hb_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fail_va(error, status, fmt, ap);
    va_end(ap);
    return status;
}

hb_status hb_fail(hb_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fail_va(NULL, status, fmt, ap);
    va_end(ap);
    return status;
}

hb_status hb_fail_null(const char *call, const char *argument)
{
    return hb_fail(HB_ERR_NULL, "%s: %s is NULL", call, argument);
}

#include "hairbsdf.h"
#include "models/interface/plan.h"

const char *hb_version(int *major, int *minor, int *patch)
{
    if (major)
        *major = HB_VERSION_MAJOR;
    if (minor)
        *minor = HB_VERSION_MINOR;
    if (patch)
        *patch = HB_VERSION_PATCH;
    return HB_VERSION_STRING;
}

const char *hb_status_string(hb_status status)
{
    switch (status) {
    case HB_OK: return "ok";
    case HB_ERR_NULL: return "a required pointer is NULL";
    case HB_ERR_PARAM: return "a parameter is out of range";
    case HB_ERR_UNSUPPORTED: return "the plan's model, lobes or options do not offer this";
    case HB_ERR_ISA: return "instruction set not available on this CPU";
    case HB_ERR_VERSION: return "struct_size is from a newer header than this library";
    case HB_ERR_NOMEM: return "out of memory";
    case HB_ERR_FILE: return "the table file is damaged or was baked for another material, options or version";
    case HB_ERR_CANCELLED: return "plan creation was cancelled by its progress callback";
    case HB_ERR_LIMIT: return "what was asked costs more than its limit";
    case HB_ERR_BUFFER: return "a buffer is smaller than the result";
    }
    return "unknown status";
}

const hb_error *hb_last_error(void) { return hb_thread_error(); }

/* What the entry points refuse, worded as "call: what is wrong" (the calling thread's last error,
 * hb_last_error). Each check passes when n is 0: an empty batch reads no plane. The checks are
 * inline, so that a per-hit call pays for the tests alone and words a failure only when it fails.
 * Internal. */
#ifndef HB_API_CHECKS_H
#define HB_API_CHECKS_H

#include "models/interface/plan.h"

/* HB_ERR_VERSION unless an output struct's struct_size lies in [least, its size in this header]: least
 * is the end of the fields of the first release that had it. */
hb_status hb_api_struct_size(const char *call, const char *name, size_t size, size_t least, size_t own);

/* HB_ERR_UNSUPPORTED: the plan's model (and, where it matters, its options) does not offer what. */
hb_status hb_api_unsupported(const char *call, const hb_plan *plan, const char *what);

/* HB_ERR_NULL naming the first of count planes that is NULL (names[k] is planes[k]'s), or HB_OK:
 * for the calls off the per-hit path. */
hb_status hb_api_present(const char *call, size_t n, int count, const void *const *planes, const char *const *names);

/* The planes of an input or output batch, tested inline; the naming is out of line. */
hb_status hb_api_angles_missing(const char *call, const hb_angles_soa *in);
hb_status hb_api_vectors_missing(const char *call, const hb_vectors_soa *in);
hb_status hb_api_near_missing(const char *call, const hb_near_soa *in);
hb_status hb_api_rgb_missing(const char *call, const char *name, const hb_rgb_soa *rgb);

static inline hb_status hb_api_angles_present(const char *call, size_t n, const hb_angles_soa *in)
{
    int present = in->theta_i && in->phi_i && in->theta_o && in->phi_o;
    return !n || present ? HB_OK : hb_api_angles_missing(call, in);
}

static inline hb_status hb_api_vectors_present(const char *call, size_t n, const hb_vectors_soa *in)
{
    int present = in->wi_x && in->wi_y && in->wi_z && in->wo_x && in->wo_y && in->wo_z;
    return !n || present ? HB_OK : hb_api_vectors_missing(call, in);
}

static inline hb_status hb_api_near_present(const char *call, size_t n, const hb_near_soa *in)
{
    int present = in->theta_i && in->phi_i && in->theta_o && in->phi_o && in->h;
    return !n || present ? HB_OK : hb_api_near_missing(call, in);
}

/* name is the argument's ("out", "f"): "out.g is NULL". */
static inline hb_status hb_api_rgb_present(const char *call, size_t n, const char *name, const hb_rgb_soa *rgb)
{
    return n && (!rgb->r || !rgb->g || !rgb->b) ? hb_api_rgb_missing(call, name, rgb) : HB_OK;
}

#endif

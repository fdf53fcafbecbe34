/* The fibre frame from a renderer's tangent and normal (docs/conventions.md): y = t / |t|, z = the
 * normal's part perpendicular to y, normalised, x = y cross z. Without a usable normal, z is the
 * perpendicular of Duff et al., "Building an orthonormal basis, revisited" (JCGT 6(1), 2017) about y,
 * which has no singular direction (it changes branch where y_z changes sign). Formed in double, so
 * each vector is orthonormal to float rounding even for a normal close to the tangent. */
#include <math.h>

#include "models/interface/plan.h"

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* v / |v|; 0 when |v| is 0, not finite, or at most `floor`. */
static int normalise(double v[3], double floor)
{
    double length = sqrt(dot3(v, v));
    if (!(length > floor) || !isfinite(length))
        return 0;
    for (int k = 0; k < 3; k++)
        v[k] /= length;
    return 1;
}

hb_status hb_frame_from_tangent(const float tangent[3], const float *normal, hb_frame *frame)
{
    if (!tangent || !frame)
        return hb_fail_null(__func__, !tangent ? "tangent" : "frame");
    double y[3] = { tangent[0], tangent[1], tangent[2] }, z[3] = { 0.0, 0.0, 0.0 };
    if (!normalise(y, 0.0))
        return hb_fail(HB_ERR_PARAM, "%s: the tangent (%g, %g, %g) has no direction (zero, or not finite)", __func__,
                       tangent[0], tangent[1], tangent[2]);
    int have_normal = 0;
    if (normal) { /* Gram-Schmidt: the normal less its part along y, kept above 1e-6 of the normal */
        double n[3] = { normal[0], normal[1], normal[2] }, along = dot3(n, y), scale = sqrt(dot3(n, n));
        for (int k = 0; k < 3; k++)
            z[k] = n[k] - along * y[k];
        have_normal = isfinite(scale) && normalise(z, 1e-6 * scale);
    }
    if (!have_normal) {
        double sign = copysign(1.0, y[2]), a = -1.0 / (sign + y[2]), b = y[0] * y[1] * a;
        z[0] = 1.0 + sign * y[0] * y[0] * a, z[1] = sign * b, z[2] = -sign * y[0];
    }
    double x[3] = { y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0] };
    for (int k = 0; k < 3; k++)
        frame->x[k] = (float)x[k], frame->y[k] = (float)y[k], frame->z[k] = (float)z[k];
    return HB_OK;
}

void hb_frame_to_local(const hb_frame *frame, const float world[3], float local[3])
{
    float w[3] = { world[0], world[1], world[2] }; /* local may alias world */
    const float *axes[3] = { frame->x, frame->y, frame->z };
    for (int k = 0; k < 3; k++)
        local[k] = axes[k][0] * w[0] + axes[k][1] * w[1] + axes[k][2] * w[2];
}

void hb_frame_to_world(const hb_frame *frame, const float local[3], float world[3])
{
    float l[3] = { local[0], local[1], local[2] };
    for (int k = 0; k < 3; k++)
        world[k] = l[0] * frame->x[k] + l[1] * frame->y[k] + l[2] * frame->z[k];
}

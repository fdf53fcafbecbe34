/* hb_assembly_dual: what dual scattering predicts for an assembly's radiance bins, rendered the way
 * an engine renders hair: view rays from outside the slab into it, the first fibre each meets shaded
 * with v f + f_DS (the plan's far field and hb_dual_eval), n and v from a ray from the point it meets
 * toward the light, counting the fibres it crosses, as a deep opacity map would at that point. The same fibres as
 * hb_assembly_trace (the seed places them), the same bins. */
#include <math.h>
#include <stdlib.h>

#include "api/checks.h"
#include "assembly/fibres.h"
#include "math/hash.h"

enum {
    CHUNK = 4096,       /* samples evaluated per call */
    MOST_CROSSED = 4096 /* fibres a light ray counts before it stops counting */
};

typedef struct pending {
    float theta_i[CHUNK], phi_i[CHUNK], theta_o[CHUNK], phi_o[CHUNK], fibres[CHUNK], direct[CHUNK];
    float f[3][CHUNK], ds[3][CHUNK];
    double weight[CHUNK];
    size_t bin[CHUNK];
    int count;
} pending;

typedef struct view {
    const hb_plan *plan;
    const hb_dual_table *table;
    pending *q;
    double *radiance, *single, *square; /* square: per bin the sum of each ray's squared share */
} view;

static void flush(view *v)
{
    pending *q = v->q;
    if (!q->count)
        return;
    hb_angles_soa in = { q->theta_i, q->phi_i, q->theta_o, q->phi_o };
    hb_eval_angles(v->plan, (size_t)q->count, in, (hb_rgb_soa){ q->f[0], q->f[1], q->f[2] }, NULL);
    hb_dual_eval(v->table, (size_t)q->count, in, q->fibres, q->direct, (hb_rgb_soa){ q->ds[0], q->ds[1], q->ds[2] }, NULL);
    for (int k = 0; k < q->count; k++)
        for (int c = 0; c < 3; c++) {
            double direct = q->weight[k] * q->direct[k] * q->f[c][k], all = direct + q->weight[k] * q->ds[c][k];
            v->radiance[q->bin[k] + c] += all;
            if (v->square)
                v->square[q->bin[k] + c] += all * all;
            if (v->single)
                v->single[q->bin[k] + c] += direct;
        }
    q->count = 0;
}

/* The fibres a ray from fibre (cx, cz)'s surface crosses toward the light before it leaves. */
static int crossed(const hb_fibres *f, double x, double z, double ux, double uz, double cx, double cz)
{
    int n = 0;
    for (; n < MOST_CROSSED; n++) {
        hb_ray2 ray = { x, z, ux, uz };
        double t, nx, nz;
        if (hb_fibres_hit(f, &ray, cx, cz, &t, &nx, &nz) != 1)
            break;
        x += t * ux, z += t * uz, cx = nx, cz = nz;
    }
    return n;
}

/* The view ray's first fibre: 1 with the point it meets and the fibre's centre, 0 where it meets none. */
static int view_hit(const hb_fibres *f, const hb_ray2 *ray, double *px, double *pz, double *cx, double *cz)
{
    double t;
    if (hb_fibres_hit(f, ray, NAN, NAN, &t, cx, cz) != 1)
        return 0;
    *px = ray->x + t * ray->ux, *pz = ray->z + t * ray->uz;
    return 1;
}

/* The point (px, pz) of fibre (cx, cz) seen along w_o = w(theta, phi), shaded with v f + f_DS into
 * `bin` with weight `weight`; n and v from a ray toward the light. */
static void shade(view *v, const hb_fibres *f, const hb_assembly *a, double theta, double phi, const double point[4],
                  double weight, size_t bin)
{
    int n = crossed(f, point[0], point[1], sin(a->phi_light), cos(a->phi_light), point[2], point[3]);
    pending *q = v->q;
    q->theta_i[q->count] = (float)a->theta_light, q->phi_i[q->count] = (float)a->phi_light;
    q->theta_o[q->count] = (float)theta, q->phi_o[q->count] = (float)phi;
    q->fibres[q->count] = (float)n, q->direct[q->count] = n == 0 ? 1.0f : 0.0f;
    q->weight[q->count] = weight, q->bin[q->count] = bin;
    if (++q->count == CHUNK)
        flush(v);
}

static double uniform(unsigned long long key, unsigned long long index)
{
    return (double)(hb_mix64(key ^ hb_mix64(index)) >> 11) * 0x1p-53;
}

hb_status hb_assembly_dual(const hb_plan *plan, const hb_dual_table *table, const hb_assembly *a, int rays,
                           double *radiance, double *radiance_se, double *single)
{
    static const char call[] = "hb_assembly_dual";
    if (!plan || !table || !a || !radiance)
        return hb_fail_null(call, !plan ? "plan" : !table ? "table" : !a ? "assembly" : "radiance");
    hb_status st = hb_assembly_check(call, a);
    if (st != HB_OK)
        return st;
    if (a->shape != HB_ASSEMBLY_SLAB)
        return hb_fail(HB_ERR_UNSUPPORTED, "%s: only a slab is rendered (assembly.shape is the bundle)", call);
    if (rays < 1 || rays > 1 << 20)
        return hb_fail(HB_ERR_PARAM, "%s: rays = %d is outside [1, 2^20]", call, rays);
    hb_fibres f;
    st = hb_fibres_place(a, &f);
    if (st != HB_OK)
        return st;
    size_t bins = (size_t)2 * a->theta_bins * a->phi_bins * 3;
    for (size_t k = 0; k < bins; k++) {
        radiance[k] = 0.0;
        if (single)
            single[k] = 0.0;
        if (radiance_se)
            radiance_se[k] = 0.0;
    }
    view v = { plan, table, malloc(sizeof(pending)), radiance, single, radiance_se };
    if (!v.q) {
        hb_fibres_free(&f);
        return hb_fail(HB_ERR_NOMEM, "%s: no memory for a chunk of samples", call);
    }
    v.q->count = 0;
    double ct = cos(a->theta_light), light[3] = { sin(a->phi_light) * ct, sin(a->theta_light), cos(a->phi_light) * ct };
    unsigned long long key = hb_mix64(a->seed ^ 0x6475616c76696577ull); /* "dualview" */
    for (int side = 0; side < 2; side++)
        for (int i = 0; i < a->theta_bins; i++)
            for (int j = 0; j < a->phi_bins; j++) {
                size_t bin = (size_t)((side * a->theta_bins + i) * a->phi_bins + j) * 3;
                double s0 = sin(-M_PI_2 + M_PI * i / a->theta_bins), s1 = sin(-M_PI_2 + M_PI * (i + 1) / a->theta_bins);
                for (int r = 0; r < rays; r++) {
                    unsigned long long index = (((unsigned long long)bin * (unsigned long long)rays + (unsigned long long)r) << 2);
                    /* w_o uniform in the bin's solid angle; the view ray enters the slab's face at x */
                    double theta = asin(s0 + (s1 - s0) * uniform(key, index));
                    double phi = -M_PI + 2.0 * M_PI * (j + uniform(key, index + 1)) / a->phi_bins;
                    double w[3] = { sin(phi) * cos(theta), sin(theta), cos(phi) * cos(theta) };
                    double across = hypot(w[0], w[2]);
                    if ((side == 0) != (w[2] > 0.0) || !(across > 1e-9))
                        continue;
                    hb_ray2 ray = { f.width * (r + uniform(key, index + 2)) / rays, side == 0 ? f.height : 0.0,
                                    -w[0] / across, -w[2] / across };
                    /* I / P = L / E (w_o . z) / (w_light . z) for each ray's share of the face */
                    double point[4];
                    if (view_hit(&f, &ray, &point[0], &point[1], &point[2], &point[3]))
                        shade(&v, &f, a, theta, phi, point, fabs(w[2]) / light[2] / (double)rays, bin);
                }
            }
    flush(&v);
    for (size_t k = 0; radiance_se && k < bins; k++) /* each ray's share x = y / rays: se^2 = (rays sum x^2 - (sum x)^2) / (rays - 1) */
        radiance_se[k] = rays > 1 ? sqrt(fmax(0.0, rays * radiance_se[k] - radiance[k] * radiance[k]) / (rays - 1)) : 0.0;
    free(v.q);
    hb_fibres_free(&f);
    return HB_OK;
}

hb_status hb_assembly_dual_image(const hb_plan *plan, const hb_dual_table *table, const hb_assembly *a,
                                 const hb_assembly_image *image)
{
    hb_fibres f;
    hb_status st = hb_fibres_place(a, &f);
    if (st != HB_OK)
        return st;
    size_t pixels = (size_t)a->theta_bins * (size_t)image->columns * 3;
    double *sums = calloc(3 * pixels, sizeof *sums);
    view v = { plan, table, malloc(sizeof(pending)), sums, sums + pixels, sums + 2 * pixels };
    if (!sums || !v.q) {
        free(sums), free(v.q);
        hb_fibres_free(&f);
        return hb_fail(HB_ERR_NOMEM, "hb_assembly_render: no memory for %zu pixels", pixels / 3);
    }
    v.q->count = 0;
    unsigned long long key = hb_mix64(a->seed ^ 0x6475616c696d6167ull); /* "dualimag" */
    double radius = f.height, half_bin = M_PI / a->phi_bins;
    /* per row, rays x columns view rays across the bundle's width 2 R for each direction, each binned
     * by the fibre it meets (its centre) across the camera's view, as the trace bins the fibre paths
     * last scattered at: a pixel's L / E is the strip's mean, sum L (2 R / rays) / (2 R / columns) */
    long rays = (long)image->rays * image->columns;
    double cv = cos(image->view_phi), sv = sin(image->view_phi);
    for (int row = 0; row < a->theta_bins; row++) {
        int i = a->theta_bins - 1 - row; /* row 0 is the highest theta_o */
        double s0 = sin(-M_PI_2 + M_PI * i / a->theta_bins), s1 = sin(-M_PI_2 + M_PI * (i + 1) / a->theta_bins);
        for (long r = 0; r < rays; r++) {
            unsigned long long index = ((unsigned long long)row * (unsigned long long)rays + (unsigned long long)r) << 2;
            /* w_o uniform in the row's solid angle about view_phi, the ray stratified across the bundle */
            double theta = asin(s0 + (s1 - s0) * uniform(key, index));
            double phi = image->view_phi + half_bin * (2.0 * uniform(key, index + 1) - 1.0);
            double across = radius * (2.0 * (r + uniform(key, index + 2)) / rays - 1.0);
            double along = sqrt(fmax(radius * radius - across * across, 0.0));
            double wx = sin(phi), wz = cos(phi), point[4];
            hb_ray2 ray = { across * wz + along * wx, -across * wx + along * wz, -wx, -wz };
            if (!view_hit(&f, &ray, &point[0], &point[1], &point[2], &point[3]))
                continue;
            int j = (int)floor(((point[2] * cv - point[3] * sv) + radius) / (2.0 * radius) * image->columns);
            j = j < 0 ? 0 : j >= image->columns ? image->columns - 1 : j;
            shade(&v, &f, a, theta, phi, point, (double)image->columns / (double)rays,
                  ((size_t)row * (size_t)image->columns + (size_t)j) * 3);
        }
    }
    flush(&v);
    for (size_t k = 0; k < pixels; k++) {
        double sum = v.radiance[k], square = v.square[k];
        if (image->dual)
            image->dual[k] = sum;
        if (image->dual_se) /* over the row's rays: se^2 = (rays sum x^2 - (sum x)^2) / (rays - 1) */
            image->dual_se[k] = rays > 1 ? sqrt(fmax(0.0, (double)rays * square - sum * sum) / (double)(rays - 1)) : 0.0;
        if (image->dual_single)
            image->dual_single[k] = v.single[k];
    }
    free(sums), free(v.q);
    hb_fibres_free(&f);
    return HB_OK;
}

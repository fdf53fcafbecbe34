/* hb_assembly_trace: light from a directional source through an assembly of fibres, path by path,
 * each batch of paths advanced one scattering at a time through one call of the plan's sampler. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "api/checks.h"
#include "assembly/fibres.h"
#include "math/hash.h"
#include "models/build/build_tasks.h"
#include "models/interface/model.h"

#define BATCH HB_ASSEMBLY_BATCH
#define ROULETTE_AFTER 3    /* scatterings before Russian roulette may end a path */
#define BOUNCE_BITS 17      /* a path's numbers are keyed by (path, scattering) with 2^17 scatterings */
#define LAUNCH_DIMENSION 15 /* the number that places a path's start on the lit side */
#define MOST_SLOTS 64       /* tasks running at once, each with its own tallies */
#define DEPTH_ORDERS 3      /* depth's classes of order: 1, 2, 3 and above */

void hb_assembly_default(hb_assembly *a)
{
    *a = (hb_assembly){ .struct_size = sizeof *a, .shape = HB_ASSEMBLY_SLAB, .layers = 8.0, .packing = 0.3,
                        .period = 32, .theta_light = 0.3, .phi_light = 0.0, .paths = 100000, .max_bounces = 10000,
                        .seed = 1, .theta_bins = 18, .phi_bins = 36, .depth_bins = 8 };
}

/* One task slot's sums over its paths: per path's light leaving each side, its square, and the
 * same per bin; what was absorbed per path; what arrived at each depth. */
typedef struct tally {
    double side[2][3], side2[2][3], absorbed[3], absorbed2[3], unfinished[3];
    double order[2][HB_ASSEMBLY_ORDERS][3], order2[2][HB_ASSEMBLY_ORDERS][3];
    double *bins, *bins2, *depth; /* 2 theta_bins phi_bins 3; the same; depth_bins DEPTH_ORDERS 3 */
    double *image, *image2, *image1; /* hb_assembly_render's pixels (theta_bins columns 3): sum, squares, order 1 */
    long long events, invalid;
} tally;

/* A batch's paths: where each is, where it goes, what it carries. */
typedef struct path_state {
    double x[BATCH], z[BATCH], dx[BATCH], dy[BATCH], dz[BATCH], beta[3][BATCH], skip_x[BATCH], skip_z[BATCH];
    int order[BATCH], live[BATCH], queued[BATCH];
    float theta_o[BATCH], phi_o[BATCH], h[BATCH], u[HB_SAMPLE_DIMENSIONS][BATCH];
    float theta_i[BATCH], phi_i[BATCH], pdf[BATCH], weight[3][BATCH], f[3][BATCH];
} path_state;

typedef struct run {
    const hb_plan *plan;
    const hb_assembly *a;
    const hb_fibres *fibres;
    int near, dimensions; /* the near-field sampler (HB_ASSEMBLY_SAMPLER_WEIGHTS), and the numbers it reads */
    int light_transport;  /* HB_ASSEMBLY_LIGHT_TRANSPORT: weighed by S(w_from, w_next) */
    double light[3];      /* w toward the light */
    double lx, lz;        /* its unit part in the x-z plane */
    unsigned long long key;
    const hb_assembly_image *image; /* NULL: no picture */
    int slots;
    tally *tallies;
    path_state *states;
} run;

static float uniform24(unsigned long long key, unsigned long long path, int bounce, int d)
{
    unsigned long long index = ((path << BOUNCE_BITS | (unsigned long long)bounce) << 4) | (unsigned long long)d;
    return (float)(hb_mix64(key ^ hb_mix64(index)) >> 40) * 0x1p-24f;
}

static double uniform53(unsigned long long key, unsigned long long path)
{
    unsigned long long index = (path << BOUNCE_BITS << 4) | LAUNCH_DIMENSION;
    return (double)(hb_mix64(key ^ hb_mix64(index)) >> 11) * 0x1p-53;
}

/* A path's end: the light it carries leaves through `side` (0 reflected, 1 transmitted) along
 * (dx, dy, dz), or, for side -1, is still going after max_bounces; the rest of its unit was absorbed. */
/* A path leaving toward the camera (its azimuth within half a bin of view_phi) into its pixel: the
 * row of its theta_o, the column of the fibre it last scattered at (its centre) across the camera's
 * view: the far field scatters from the fibre as a whole. */
static void add_pixel(const run *r, tally *t, const path_state *s, int k)
{
    const hb_assembly *a = r->a;
    const hb_assembly_image *im = r->image;
    double phi = atan2(s->dx[k], s->dz[k]);
    if (!(fabs(remainder(phi - im->view_phi, 2.0 * M_PI)) < M_PI / a->phi_bins))
        return;
    double theta = asin(fmax(-1.0, fmin(1.0, s->dy[k]))), radius = r->fibres->height;
    double across = s->skip_x[k] * cos(im->view_phi) - s->skip_z[k] * sin(im->view_phi);
    int i = (int)floor((theta + M_PI_2) / M_PI * a->theta_bins), j = (int)floor((across + radius) / (2.0 * radius) * im->columns);
    i = i < 0 ? 0 : i >= a->theta_bins ? a->theta_bins - 1 : i;
    j = j < 0 ? 0 : j >= im->columns ? im->columns - 1 : j;
    size_t pixel = ((size_t)(a->theta_bins - 1 - i) * (size_t)im->columns + (size_t)j) * 3;
    /* L / E = (dP / P) (E 2 R cos theta_light / E) / (dA dw), dA = (2 R / columns) cos theta_o per unit
     * length: each path's share carries cos theta_light / cos theta_o (gather_image the rest) */
    double projected = cos(a->theta_light) / fmax(cos(theta), 1e-6);
    for (int c = 0; c < 3; c++) {
        double v = s->beta[c][k] * projected;
        t->image[pixel + c] += v, t->image2[pixel + c] += v * v;
        if (s->order[k] == 1)
            t->image1[pixel + c] += v;
    }
}

static void finish(const run *r, tally *t, const path_state *s, int k, int side)
{
    const hb_assembly *a = r->a;
    int bin = -1;
    if (side >= 0) {
        double theta = asin(fmax(-1.0, fmin(1.0, s->dy[k]))), phi = atan2(s->dx[k], s->dz[k]);
        int i = (int)floor((theta + M_PI_2) / M_PI * a->theta_bins), j = (int)floor((phi + M_PI) / (2.0 * M_PI) * a->phi_bins);
        i = i < 0 ? 0 : i >= a->theta_bins ? a->theta_bins - 1 : i;
        j = j < 0 ? 0 : j >= a->phi_bins ? a->phi_bins - 1 : j;
        bin = ((side * a->theta_bins + i) * a->phi_bins + j) * 3;
    }
    int order = s->order[k] < HB_ASSEMBLY_ORDERS - 1 ? s->order[k] : HB_ASSEMBLY_ORDERS - 1;
    for (int c = 0; c < 3; c++) {
        double v = s->beta[c][k];
        if (side >= 0) {
            t->side[side][c] += v, t->side2[side][c] += v * v, t->order[side][order][c] += v,
            t->order2[side][order][c] += v * v;
            if (s->order[k] > 0) /* the bins hold scattered light; what met no fibre is by_order[1][0] alone */
                t->bins[bin + c] += v, t->bins2[bin + c] += v * v;
        } else {
            t->unfinished[c] += v;
        }
        double lost = 1.0 - v;
        t->absorbed[c] += lost, t->absorbed2[c] += lost * lost;
    }
    if (side >= 0 && s->order[k] > 0 && r->image)
        add_pixel(r, t, s, k);
}

static void launch(const run *r, path_state *s, int k, unsigned long long path)
{
    const hb_fibres *f = r->fibres;
    double u = uniform53(r->key, path);
    if (f->shape == HB_ASSEMBLY_SLAB) {
        s->x[k] = f->width * u, s->z[k] = f->height;
    } else { /* across the bundle's width, on the circle's lit half */
        double across = (2.0 * u - 1.0) * f->height, along = sqrt(fmax(f->height * f->height - across * across, 0.0));
        s->x[k] = across * r->lz + along * r->lx, s->z[k] = -across * r->lx + along * r->lz;
    }
    s->dx[k] = -r->light[0], s->dy[k] = -r->light[1], s->dz[k] = -r->light[2];
    s->beta[0][k] = s->beta[1][k] = s->beta[2][k] = 1.0;
    s->skip_x[k] = s->skip_z[k] = NAN;
    s->order[k] = 0;
}

/* Moves path k to the next fibre it meets: 1 with the sampler's inputs at that hit written to slot
 * `slot` of the batch (w_o back along the path, h where the ray meets the fibre), 0 when it ended. */
static int advance(const run *r, tally *t, path_state *s, int k, int slot)
{
    double len = hypot(s->dx[k], s->dz[k]);
    if (!(len > 1e-12)) { /* along the fibres: it never leaves, and is unfinished */
        finish(r, t, s, k, -1);
        return 0;
    }
    hb_ray2 ray = { s->x[k], s->z[k], s->dx[k] / len, s->dz[k] / len };
    double dist, cx, cz;
    int hit = hb_fibres_hit(r->fibres, &ray, s->skip_x[k], s->skip_z[k], &dist, &cx, &cz);
    if (hit < 0) { /* along the slab's faces for 2^20 cells: counted as unfinished */
        finish(r, t, s, k, -1);
        return 0;
    }
    if (!hit) {
        int side = r->fibres->shape == HB_ASSEMBLY_SLAB ? ray.uz < 0.0 : ray.ux * r->lx + ray.uz * r->lz <= 0.0;
        finish(r, t, s, k, side);
        return 0;
    }
    double px = ray.x + dist * ray.ux, pz = ray.z + dist * ray.uz;
    int d = (int)floor(r->fibres->shape == HB_ASSEMBLY_SLAB ? (r->fibres->height - cz) / 2.0
                                                               : (r->fibres->height - (cx * r->lx + cz * r->lz)) / 2.0);
    d = d < 0 ? 0 : d >= r->a->depth_bins ? r->a->depth_bins - 1 : d;
    int order_class = s->order[k] < DEPTH_ORDERS ? s->order[k] : DEPTH_ORDERS - 1;
    for (int c = 0; c < 3; c++)
        t->depth[(d * DEPTH_ORDERS + order_class) * 3 + c] += s->beta[c][k];
    if (s->order[k] >= r->a->max_bounces) {
        finish(r, t, s, k, -1);
        return 0;
    }
    s->x[k] = px, s->z[k] = pz, s->skip_x[k] = cx, s->skip_z[k] = cz;
    /* w_o = -d; the normal at the hit is at azimuth phi_o + gamma_o, so h = sin(gamma_o) is the
     * cross product of w_o's and the normal's unit parts in the x-z plane (docs/multiple-scattering.md) */
    double nx = px - cx, nz = pz - cz, n = hypot(nx, nz), wx = -ray.ux, wz = -ray.uz;
    double h = (nx * wz - nz * wx) / n;
    s->theta_o[slot] = (float)asin(fmax(-1.0, fmin(1.0, -s->dy[k])));
    s->phi_o[slot] = (float)atan2(-s->dx[k], -s->dz[k]);
    s->h[slot] = (float)fmax(-1.0, fmin(1.0, h));
    return 1;
}

/* The sampler at every queued hit; then each path's new direction, weight and roulette. */
static void scatter(const run *r, tally *t, path_state *s, int queued, unsigned long long first)
{
    const float *planes[HB_SAMPLE_DIMENSIONS];
    for (int d = 0; d < HB_SAMPLE_DIMENSIONS; d++)
        planes[d] = s->u[d];
    for (int m = 0; m < queued; m++) {
        int k = s->queued[m];
        for (int d = 0; d < r->dimensions; d++)
            s->u[d][m] = uniform24(r->key, first + (unsigned long long)k, s->order[k], d);
    }
    hb_sample_out out = { s->theta_i, s->phi_i, s->pdf, { s->weight[0], s->weight[1], s->weight[2] } };
    hb_eval_report report = { 0 };
    if (r->near) {
        hb_sample_near_in in = { s->theta_o, s->phi_o, s->h, planes };
        hb_sample_near(r->plan, (size_t)queued, &in, &out, &report);
    } else {
        hb_sample_in in = { s->theta_o, s->phi_o, planes };
        hb_sample_angles(r->plan, (size_t)queued, &in, &out, &report);
    }
    if (r->light_transport) { /* S(w_from, w_next): f with the sampled direction as w_o */
        hb_angles_soa sent = { s->theta_o, s->phi_o, s->theta_i, s->phi_i };
        hb_eval_angles(r->plan, (size_t)queued, sent, (hb_rgb_soa){ s->f[0], s->f[1], s->f[2] }, NULL);
        for (int m = 0; m < queued; m++) {
            double pdf = s->pdf[m], scale = cos((double)s->theta_i[m]) / (cos((double)s->theta_o[m]) * pdf);
            for (int c = 0; c < 3; c++)
                s->weight[c][m] = pdf > 0.0 ? (float)(s->f[c][m] * scale) : 0.0f;
        }
    }
    t->invalid += (long long)report.invalid;
    t->events += queued;
    for (int m = 0; m < queued; m++) {
        int k = s->queued[m];
        double most = 0.0;
        for (int c = 0; c < 3; c++) {
            double w = s->weight[c][m];
            s->beta[c][k] *= isfinite(w) && w > 0.0 ? w : 0.0;
            most = fmax(most, s->beta[c][k]);
        }
        double ct = cos((double)s->theta_i[m]);
        s->dx[k] = sin((double)s->phi_i[m]) * ct, s->dy[k] = sin((double)s->theta_i[m]), s->dz[k] = cos((double)s->phi_i[m]) * ct;
        s->order[k]++;
        if (s->order[k] >= ROULETTE_AFTER && most < 1.0) { /* survive with probability `most`, carrying 1 / most */
            float u = uniform24(r->key, first + (unsigned long long)k, s->order[k] - 1, HB_SAMPLE_DIMENSIONS);
            if (!(u < most)) {
                s->live[k] = 0;
                s->beta[0][k] = s->beta[1][k] = s->beta[2][k] = 0.0;
                finish(r, t, s, k, -1); /* carries 0: all of it counts as absorbed */
                continue;
            }
            for (int c = 0; c < 3; c++)
                s->beta[c][k] /= most;
        }
    }
}

static void trace_task(void *context, int index)
{
    const run *r = context;
    int slot = index % r->slots;
    tally *t = &r->tallies[slot];
    path_state *s = &r->states[slot];
    unsigned long long first = (unsigned long long)index * BATCH;
    long long left = r->a->paths - (long long)first;
    int count = left < BATCH ? (int)left : BATCH;
    for (int k = 0; k < count; k++) {
        launch(r, s, k, first + (unsigned long long)k);
        s->live[k] = 1;
    }
    for (int going = count; going > 0;) {
        int queued = 0;
        for (int k = 0; k < count; k++) {
            if (!s->live[k])
                continue;
            if (advance(r, t, s, k, queued))
                s->queued[queued++] = k;
            else
                s->live[k] = 0;
        }
        if (queued)
            scatter(r, t, s, queued, first);
        going = 0;
        for (int k = 0; k < count; k++)
            going += s->live[k];
    }
}

hb_status hb_assembly_check(const char *call, const hb_assembly *a)
{
    hb_status st = hb_api_struct_size(call, "assembly", a->struct_size, sizeof *a, sizeof *a);
    if (st != HB_OK)
        return st;
    const char *bad = NULL;
    if (a->shape != HB_ASSEMBLY_SLAB && a->shape != HB_ASSEMBLY_BUNDLE)
        bad = "shape is neither HB_ASSEMBLY_SLAB nor HB_ASSEMBLY_BUNDLE";
    else if (!(a->layers >= 1.0 && a->layers <= 1024.0))
        bad = "layers is outside [1, 1024]";
    else if (!(a->packing > 0.0 && a->packing <= 0.5))
        bad = "packing is outside (0, 0.5]";
    else if (a->shape == HB_ASSEMBLY_SLAB && (a->period < 4 || a->period > 4096))
        bad = "period is outside [4, 4096]";
    else if (!(fabs(a->theta_light) < M_PI_2 - 1e-6) || !isfinite(a->phi_light))
        bad = "theta_light is outside (-pi/2, pi/2) or phi_light is not finite";
    else if (a->shape == HB_ASSEMBLY_SLAB && !(fabs(a->phi_light) < M_PI_2 - 1e-6))
        bad = "phi_light is outside (-pi/2, pi/2): the slab's light comes from above it";
    else if (a->paths < 1 || a->paths > (1LL << 39)) /* at most 2^30 tasks of HB_ASSEMBLY_BATCH paths */
        bad = "paths is outside [1, 2^39]";
    else if (a->max_bounces < 1 || a->max_bounces > 100000)
        bad = "max_bounces is outside [1, 100000]";
    else if (a->transport != HB_ASSEMBLY_LIGHT_TRANSPORT && a->transport != HB_ASSEMBLY_SAMPLER_WEIGHTS)
        bad = "transport is neither HB_ASSEMBLY_LIGHT_TRANSPORT nor HB_ASSEMBLY_SAMPLER_WEIGHTS";
    else if (a->theta_bins < 1 || a->theta_bins > 4096 || a->phi_bins < 1 || a->phi_bins > 4096 || a->depth_bins < 1 ||
             a->depth_bins > 4096)
        bad = "a count of bins is outside [1, 4096]";
    return bad ? hb_fail(HB_ERR_PARAM, "%s: assembly.%s", call, bad) : HB_OK;
}

static hb_status check(const hb_plan *plan, const hb_assembly *a, hb_assembly_result *result)
{
    static const char call[] = "hb_assembly_trace";
    if (!plan || !a || !result)
        return hb_fail_null(call, !plan ? "plan" : !a ? "assembly" : "result");
    hb_status st = hb_assembly_check(call, a);
    if (st == HB_OK)
        st = hb_api_struct_size(call, "result", result->struct_size, sizeof *result, sizeof *result);
    if (st != HB_OK)
        return st;
    if (hb_plan_sample_dimensions(plan) <= 0)
        return hb_api_unsupported(call, plan, "sampler, which the paths scatter by");
    if (a->transport == HB_ASSEMBLY_LIGHT_TRANSPORT && hb_plan_pdf_is_estimate(plan))
        return hb_fail(HB_ERR_UNSUPPORTED,
                       "%s: the plan's pdf is a Monte-Carlo estimate, which the light's transport (f / pdf of another "
                       "direction) cannot divide by without bias; HB_ASSEMBLY_SAMPLER_WEIGHTS uses the sampler's own weights",
                       call);
    if (plan->material.eccentricity != 0.0)
        return hb_fail(HB_ERR_UNSUPPORTED, "%s: the plan's fibre is elliptical (eccentricity %g); the assembly's are circular",
                       call, plan->material.eccentricity);
    return HB_OK;
}

/* The mean over n paths of sums (sum, sum of squares), and its standard error. */
static void mean_se(double sum, double sum2, double n, double *mean, double *se)
{
    double m = sum / n, var = n > 1.0 ? fmax(sum2 / n - m * m, 0.0) * n / (n - 1.0) : 0.0;
    *mean = m;
    if (se)
        *se = sqrt(var / n);
}

/* The pictures' pixels over every slot, as L / E: a pixel's share of the paths (each already times
 * cos theta_light / cos theta_o) times the lit width 2 R over the pixel's width 2 R / columns and its
 * solid angle. */
static void gather_image(const run *r, double n)
{
    const hb_assembly *a = r->a;
    const hb_assembly_image *im = r->image;
    size_t pixels = (size_t)a->theta_bins * (size_t)im->columns * 3;
    for (size_t k = 0; k < pixels; k++) {
        double sum = 0.0, sum2 = 0.0, once = 0.0;
        for (int slot = 0; slot < r->slots; slot++) /* in slot order: the same sums however the tasks ran */
            sum += r->tallies[slot].image[k], sum2 += r->tallies[slot].image2[k], once += r->tallies[slot].image1[k];
        int i = a->theta_bins - 1 - (int)(k / 3 / (size_t)im->columns);
        double solid = (sin(-M_PI_2 + M_PI * (i + 1) / a->theta_bins) - sin(-M_PI_2 + M_PI * i / a->theta_bins)) * 2.0 *
                       M_PI / a->phi_bins;
        double scale = im->columns / solid, mean, se;
        mean_se(sum, sum2, n, &mean, &se);
        if (im->traced)
            im->traced[k] = mean * scale;
        if (im->traced_se)
            im->traced_se[k] = se * scale;
        if (im->traced_single)
            im->traced_single[k] = once / n * scale;
    }
}

static void gather(const run *r, hb_assembly_result *out)
{
    const hb_assembly *a = r->a;
    size_t nbins = (size_t)2 * a->theta_bins * a->phi_bins * 3, ndepth = (size_t)a->depth_bins * DEPTH_ORDERS * 3;
    tally sum = { .bins = calloc(nbins, sizeof(double)), .bins2 = calloc(nbins, sizeof(double)),
                  .depth = calloc(ndepth, sizeof(double)) };
    for (int s = 0; s < r->slots; s++) { /* in slot order: the same sums however the tasks ran */
        const tally *t = &r->tallies[s];
        for (int c = 0; c < 3; c++) {
            for (int side = 0; side < 2; side++) {
                sum.side[side][c] += t->side[side][c], sum.side2[side][c] += t->side2[side][c];
                for (int o = 0; o < HB_ASSEMBLY_ORDERS; o++)
                    sum.order[side][o][c] += t->order[side][o][c], sum.order2[side][o][c] += t->order2[side][o][c];
            }
            sum.absorbed[c] += t->absorbed[c], sum.absorbed2[c] += t->absorbed2[c], sum.unfinished[c] += t->unfinished[c];
        }
        if (sum.bins && sum.bins2 && sum.depth) {
            for (size_t k = 0; k < nbins; k++)
                sum.bins[k] += t->bins[k], sum.bins2[k] += t->bins2[k];
            for (size_t k = 0; k < ndepth; k++)
                sum.depth[k] += t->depth[k];
        }
        sum.events += t->events, sum.invalid += t->invalid;
    }
    double n = (double)a->paths;
    for (int c = 0; c < 3; c++) {
        mean_se(sum.side[0][c], sum.side2[0][c], n, &out->reflected[c], &out->reflected_se[c]);
        mean_se(sum.side[1][c], sum.side2[1][c], n, &out->transmitted[c], &out->transmitted_se[c]);
        mean_se(sum.absorbed[c], sum.absorbed2[c], n, &out->absorbed[c], &out->absorbed_se[c]);
        out->unfinished[c] = sum.unfinished[c] / n;
        for (int side = 0; side < 2; side++)
            for (int o = 0; o < HB_ASSEMBLY_ORDERS; o++)
                out->by_order[side][o][c] = sum.order[side][o][c] / n,
                out->by_order_square[side][o][c] = sum.order2[side][o][c] / n;
    }
    for (int i = 0; sum.bins && sum.bins2 && i < a->theta_bins; i++) {
        double t0 = -M_PI_2 + M_PI * i / a->theta_bins, t1 = -M_PI_2 + M_PI * (i + 1) / a->theta_bins;
        double solid = (sin(t1) - sin(t0)) * 2.0 * M_PI / a->phi_bins;
        for (int side = 0; side < 2; side++)
            for (int j = 0; j < a->phi_bins; j++)
                for (int c = 0; c < 3; c++) {
                    size_t k = (size_t)((side * a->theta_bins + i) * a->phi_bins + j) * 3 + (size_t)c;
                    double mean, se;
                    mean_se(sum.bins[k], sum.bins2[k], n, &mean, &se);
                    if (out->radiance)
                        out->radiance[k] = mean / solid;
                    if (out->radiance_se)
                        out->radiance_se[k] = se / solid;
                }
    }
    for (size_t k = 0; out->depth && sum.depth && k < ndepth; k++)
        out->depth[k] = sum.depth[k] / n;
    if (r->image)
        gather_image(r, n);
    out->events = sum.events, out->invalid = sum.invalid;
    free(sum.bins), free(sum.bins2), free(sum.depth);
}

hb_status hb_assembly_trace(const hb_plan *plan, const hb_assembly *a, hb_assembly_result *result,
                            hb_progress_fn progress, void *progress_context, hb_parallel_fn parallel,
                            void *parallel_context)
{
    return hb_assembly_trace_image(plan, a, result, NULL, progress, progress_context, parallel, parallel_context);
}

hb_status hb_assembly_trace_image(const hb_plan *plan, const hb_assembly *a, hb_assembly_result *result,
                                  const hb_assembly_image *image, hb_progress_fn progress, void *progress_context,
                                  hb_parallel_fn parallel, void *parallel_context)
{
    hb_status st = check(plan, a, result);
    if (st != HB_OK)
        return st;
    hb_fibres fibres;
    st = hb_fibres_place(a, &fibres);
    if (st != HB_OK)
        return st;
    int light = a->transport == HB_ASSEMBLY_LIGHT_TRANSPORT;
    int near = !light && hb_model_ops_of(plan->options.model)->sample_near != NULL;
    run r = { .plan = plan, .a = a, .fibres = &fibres, .near = near, .light_transport = light,
              .dimensions = hb_plan_sample_dimensions(plan) - near, .image = image };
    double ct = cos(a->theta_light);
    r.light[0] = sin(a->phi_light) * ct, r.light[1] = sin(a->theta_light), r.light[2] = cos(a->phi_light) * ct;
    r.lx = sin(a->phi_light), r.lz = cos(a->phi_light);
    r.key = hb_mix64(a->seed + 0x9e3779b97f4a7c15ull);
    long long tasks = (a->paths + BATCH - 1) / BATCH;
    int part = hb_build_part((int)tasks);
    r.slots = part < MOST_SLOTS ? part : MOST_SLOTS;
    size_t nbins = (size_t)2 * a->theta_bins * a->phi_bins * 3, ndepth = (size_t)a->depth_bins * DEPTH_ORDERS * 3;
    size_t npixels = image ? (size_t)a->theta_bins * (size_t)image->columns * 3 : 0, per_slot = 2 * nbins + ndepth + 3 * npixels;
    r.tallies = calloc((size_t)r.slots, sizeof *r.tallies);
    r.states = malloc((size_t)r.slots * sizeof *r.states);
    double *arrays = calloc((size_t)r.slots * per_slot, sizeof(double));
    if (!r.tallies || !r.states || !arrays) {
        st = hb_fail(HB_ERR_NOMEM, "hb_assembly_trace: no memory for %d batches of %d paths", r.slots, BATCH);
    } else {
        for (int s = 0; s < r.slots; s++) {
            double *base = arrays + (size_t)s * per_slot;
            r.tallies[s].bins = base, r.tallies[s].bins2 = base + nbins, r.tallies[s].depth = base + 2 * nbins;
            if (image) {
                double *pixels = base + 2 * nbins + ndepth;
                r.tallies[s].image = pixels, r.tallies[s].image2 = pixels + npixels, r.tallies[s].image1 = pixels + 2 * npixels;
            }
        }
        hb_options o = { .progress = progress, .progress_context = progress_context, .parallel = parallel,
                         .parallel_context = parallel_context };
        st = hb_build_tasks(&o, (int)tasks, r.slots, trace_task, &r, 0.0, 1.0, NULL);
        if (st == HB_OK)
            st = hb_build_finish(&o, NULL);
        if (st == HB_OK) {
            double *radiance = result->radiance, *radiance_se = result->radiance_se, *depth = result->depth;
            size_t size = result->struct_size;
            memset(result, 0, sizeof *result);
            *result = (hb_assembly_result){ .struct_size = size, .radiance = radiance, .radiance_se = radiance_se,
                                            .depth = depth, .fibres = fibres.count };
            double area = a->shape == HB_ASSEMBLY_SLAB ? fibres.height * fibres.width : M_PI * fibres.height * fibres.height;
            result->packing = (double)fibres.count * M_PI / area;
            gather(&r, result);
        }
    }
    free(arrays);
    free(r.states);
    free(r.tallies);
    hb_fibres_free(&fibres);
    return st;
}

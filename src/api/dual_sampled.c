/* hb_dual_terms_sampled: the dual-scattering terms estimated the way the engines bake their tables
 * (HDRP's pre-integration pattern; docs/multiple-scattering.md, "The engines' tables"): outgoing
 * directions from a Hammersley set uniform on the sphere against evenly spaced light azimuths, each
 * hemisphere's energy 2 pi times the mean f of the pairs that fell in it. The plan's own batch
 * evaluation, in stack chunks; the terms from the sums as hb_dual_terms_at makes them. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "checks.h"
#include "dual_sums.h"

enum { CHUNK = 512, COUNT_MAX = 65536 };

/* The radical inverse of k in base 2: the Hammersley set's second coordinate. */
static double radical_inverse_2(unsigned k)
{
    double x = 0.0, f = 0.5;
    for (; k; k >>= 1, f *= 0.5)
        x += (double)(k & 1u) * f;
    return x;
}

typedef struct pairs {
    float ti[CHUNK], pi[CHUNK], to[CHUNK], po[CHUNK];
    double theta_h[CHUNK];
    int backward[CHUNK];
    int count;
} pairs;

/* Evaluates the pending pairs and adds f, f theta_h and f theta_h^2 to each one's hemisphere. */
static void flush(const hb_plan *plan, pairs *q, hb_dual_sums *s, long long counted[2])
{
    float f[3][CHUNK];
    hb_eval_angles(plan, (size_t)q->count, (hb_angles_soa){ q->ti, q->pi, q->to, q->po }, (hb_rgb_soa){ f[0], f[1], f[2] },
                   NULL);
    for (int k = 0; k < q->count; k++) {
        int h = q->backward[k];
        counted[h]++;
        for (int c = 0; c < 3; c++) {
            double e = f[c][k];
            s->energy[h][c] += e, s->first[h][c] += e * q->theta_h[k], s->second[h][c] += e * q->theta_h[k] * q->theta_h[k];
        }
    }
    q->count = 0;
}

hb_status hb_dual_terms_sampled(const hb_plan *plan, double theta, int directions, int azimuths, double d_b,
                                hb_dual_terms *terms)
{
    hb_status st = hb_dual_check_call(__func__, plan, theta, d_b, terms);
    if (st != HB_OK)
        return st;
    if (directions < 1 || directions > COUNT_MAX || azimuths < 1 || azimuths > COUNT_MAX)
        return hb_fail(HB_ERR_PARAM, "%s: %s = %d is outside [1, %d]", __func__,
                       directions < 1 || directions > COUNT_MAX ? "directions" : "azimuths",
                       directions < 1 || directions > COUNT_MAX ? directions : azimuths, COUNT_MAX);
    hb_dual_sums sums = { { { 0 } }, { { 0 } }, { { 0 } } };
    long long counted[2] = { 0, 0 };
    pairs q;
    q.count = 0;
    for (int d = 0; d < directions; d++) {
        double z = 1.0 - 2.0 * (d + 0.5) / directions, a = 2.0 * M_PI * radical_inverse_2((unsigned)d);
        double theta_o = asin(z), phi_o = remainder(a, 2.0 * M_PI);
        for (int j = 0; j < azimuths; j++) {
            double phi_i = -M_PI_2 + M_PI * j / azimuths;
            q.ti[q.count] = (float)theta, q.pi[q.count] = (float)phi_i;
            q.to[q.count] = (float)theta_o, q.po[q.count] = (float)phi_o;
            q.theta_h[q.count] = 0.5 * (theta + theta_o);
            q.backward[q.count] = !(fabs(remainder(phi_o - phi_i, 2.0 * M_PI)) > M_PI_2);
            if (++q.count == CHUNK)
                flush(plan, &q, &sums, counted);
        }
    }
    if (q.count)
        flush(plan, &q, &sums, counted);
    for (int h = 0; h < 2; h++) /* eq. 6 by the mean over the hemisphere's pairs: its solid angle is 2 pi */
        for (int c = 0; c < 3; c++) {
            double scale = counted[h] ? 2.0 * M_PI / (double)counted[h] : 0.0;
            sums.energy[h][c] *= scale, sums.first[h][c] *= scale, sums.second[h][c] *= scale;
        }
    size_t size = terms->struct_size;
    hb_dual_terms all = { .struct_size = size };
    hb_dual_terms_of_sums(&sums, d_b, &all);
    memcpy(terms, &all, size);
    return HB_OK;
}

/* MJC03's batch kernels for one ISA: the Makefile compiles this file once per instruction
 * set (-DHB_TARGET_<NAME> and that ISA's flags) into hb_<isa>_marschner_kernels. */
#include "../../isa/batch.h"
#include "azimuthal.h"

static void longitudinal_angles(const hb_gaussian_lobe *lobe, size_t n, hb_angles_soa in, float *out,
                                size_t *invalid)
{
    HB_BATCH(load_angles, 4, in, n, invalid,
             store_block(out, i, lanes,
                         vf_keep(valid, longitudinal_marschner_angles(lobe, a[0], a[2]))));
}

static void longitudinal_vectors(const hb_gaussian_lobe *lobe, size_t n, hb_vectors_soa in, float *out,
                                 size_t *invalid)
{
    HB_BATCH(load_vectors, 6, in, n, invalid,
             store_block(out, i, lanes,
                         vf_keep(valid, longitudinal_marschner_vectors(lobe, a, a + 3))));
}

static void angles_kernel(const hb_marschner *mjc, size_t n, hb_angles_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_angles, 4, in, n, invalid,
             (marschner_angles(mjc, a[0], a[1], a[2], a[3], f), store_rgb(out, i, lanes, valid, f)));
}

static void vectors_kernel(const hb_marschner *mjc, size_t n, hb_vectors_soa in, hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_vectors, 6, in, n, invalid, (marschner_vectors(mjc, a, a + 3, f), store_rgb(out, i, lanes, valid, f)));
}

/* The cubic solver on arrays, all three roots (NaN where a root is not real), for the tests. */
static void cubic_map(size_t n, const float *P, const float *Q, float *roots)
{
    const float *src[2] = { P, Q };
    for (size_t i = 0; i < n; i += HB_W) {
        size_t lanes = n - i < HB_W ? n - i : HB_W;
        vf pq[2], root[3];
        vm real[3];
        load_block(src, 2, i, lanes, 1.0f, pq);
        cubic_roots(pq[0], pq[1], 1, root, real);
        for (int k = 0; k < 3; k++) {
            float buf[HB_W];
            vf_storeu(buf, vf_select(real[k], root[k], vf_set1(__builtin_nanf(""))));
            for (size_t j = 0; j < lanes; j++)
                roots[3 * (i + j) + (size_t)k] = buf[j];
        }
    }
}

const hb_marschner_kernels HB_ISA_SYMBOL(marschner_kernels) = {
    .longitudinal_angles = longitudinal_angles,
    .longitudinal_vectors = longitudinal_vectors,
    .angles = angles_kernel,
    .vectors = vectors_kernel,
    .cubic_map = cubic_map,
};

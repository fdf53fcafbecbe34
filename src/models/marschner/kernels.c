/* MJC03's batch kernels for one ISA: the Makefile compiles this file once per instruction
 * set (-DHB_TARGET_<NAME> and that ISA's flags) into hb_<isa>_marschner_kernels. */
#include "kernel/batch.h"
#include "azimuthal.h"
#include "kernels.h"

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

const hb_marschner_kernels HB_ISA_SYMBOL(marschner_kernels) = {
    .longitudinal_angles = longitudinal_angles,
    .longitudinal_vectors = longitudinal_vectors,
    .angles = angles_kernel,
    .vectors = vectors_kernel,
};

/* The entry kernels of one I0 variant of dFH11 (kernels.c includes this once per variant, so that
 * the variant is a constant inside each kernel). Parameters, defined by the includer and undefined
 * at the end:
 *   HB_DEON_SUFFIX  the variant's name, which ends every kernel's name (abramowitz, paper)
 *   HB_DEON_I0      its hb_i0 value (HB_I0_ABRAMOWITZ, HB_I0_PAPER)
 * No include guard: it is included once per variant. */
#define HB_DEON_JOIN(base, suffix) base##_##suffix
#define HB_DEON_NAME(base, suffix) HB_DEON_JOIN(base, suffix)
#define HB_DEON_VARIANT(base) HB_DEON_NAME(base, HB_DEON_SUFFIX)

/* a call of a few samples, each alone: f, and the pdf where pdf is not NULL */
static void HB_DEON_VARIANT(deon_angles_few)(const hb_deon *deon, size_t n, hb_angles_soa in, hb_rgb_soa out,
                                     float *pdf, size_t *invalid)
{
    vf f[3], p;
    HB_ONE_BY_ONE(load_angles_one, 4, in, n, invalid,
                  (deon_one_angles(deon, a, HB_DEON_I0, f, pdf ? &p : NULL),
                   pdf ? store_one(pdf, k, valid, p) : (void)0, store_rgb_one(out, k, valid, f)));
}

static void HB_DEON_VARIANT(deon_near_few)(const hb_deon *deon, size_t n, hb_near_soa in, hb_rgb_soa out,
                                   size_t *invalid)
{
    vf f[3];
    HB_ONE_BY_ONE(load_near_one, 5, in, n, invalid,
                  (deon_near_one_sample(deon, a, HB_DEON_I0, f), store_rgb_one(out, k, valid, f)));
}

static void HB_DEON_VARIANT(longitudinal_angles)(const hb_longitudinal *lobe, size_t n, hb_angles_soa in,
                                         float *out, size_t *invalid)
{
    HB_BATCH(load_angles, 4, in, n, invalid,
             store_block(out, i, lanes,
                         vf_keep(valid, longitudinal_deon_angles(lobe, a[0], a[2], HB_DEON_I0))));
}

static void HB_DEON_VARIANT(longitudinal_vectors)(const hb_longitudinal *lobe, size_t n, hb_vectors_soa in,
                                          float *out, size_t *invalid)
{
    HB_BATCH(load_vectors, 6, in, n, invalid,
             store_block(out, i, lanes,
                         vf_keep(valid, longitudinal_deon_vectors(lobe, a, a + 3, HB_DEON_I0))));
}

static void HB_DEON_VARIANT(deon_angles)(const hb_deon *deon, size_t n, hb_angles_soa in, hb_rgb_soa out,
                                 size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_angles, 4, in, n, invalid,
             (deon_angles(deon, a[0], a[1], a[2], a[3], HB_DEON_I0, f), store_rgb(out, i, lanes, valid, f)));
}

static void HB_DEON_VARIANT(deon_sample)(const hb_deon *deon, size_t n, const hb_sample_batch *b,
                                 size_t *invalid)
{
    vf theta_i, phi_i, pdf, weight[3];
    HB_BATCH(load_deon_sample, 2 + HB_DEON_SAMPLE_DIMENSIONS, b, n, invalid,
             (deon_sample(deon, a[0], a[1], a + 2, HB_DEON_I0, &theta_i, &phi_i, &pdf, weight),
              store_sampled(b, i, lanes, valid, theta_i, phi_i, pdf, weight)));
}

static void HB_DEON_VARIANT(deon_pdf)(const hb_deon *deon, size_t n, const hb_pair_batch *in, float *pdf,
                              size_t *invalid)
{
    HB_BATCH(load_pairs, 4, in, n, invalid,
             store_block(pdf, i, lanes,
                         vf_keep(valid, deon_pdf_angles(deon, a[0], a[1], a[2], a[3], HB_DEON_I0))));
}

static void HB_DEON_VARIANT(deon_f_pdf)(const hb_deon *deon, size_t n, const hb_pair_batch *in, hb_rgb_soa out,
                                float *pdf, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_pairs, 4, in, n, invalid,
             (store_block(pdf, i, lanes, vf_keep(valid, deon_f_pdf_angles(deon, a, HB_DEON_I0, f))),
              store_rgb(out, i, lanes, valid, f)));
}

static void HB_DEON_VARIANT(deon_absorbing)(const hb_deon *deon, size_t n, const hb_absorbing_batch *in,
                                    hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_absorbing, 7, in, n, invalid,
             (deon_absorbing_angles(deon, a, HB_DEON_I0, f), store_rgb(out, i, lanes, valid, f)));
}

/* k wavelengths per sample, pbrt-v4's four with the channel loops straight, any other count as it
 * comes: the near field at h, f and the pdf where the batch asks (every plan), or the far field's f
 * (standard quadrature plans). */
#define HB_DEON_SPECTRAL_BLOCKS(k)                                                                              \
    (b->near.h ? deon_near_spectral_angles(deon, k, a, HB_DEON_I0, f, b->pdf ? &p : NULL)                    \
               : deon_spectral_angles(deon, k, a, HB_DEON_I0, f),                                             \
     b->f ? store_planes(b->f, k, i, lanes, valid, f) : (void)0,                                             \
     b->pdf ? store_block(b->pdf, i, lanes, vf_keep(valid, p)) : (void)0)
static void HB_DEON_VARIANT(deon_spectral)(const hb_deon *deon, size_t n, const hb_spectral_batch *b,
                                   size_t *invalid)
{
    vf f[HB_DEON_CHANNELS], p = vf_set1(0.0f);
    if (b->wavelengths == 4)
        HB_BATCH(load_spectral, 5 + HB_DEON_CHANNELS, b, n, invalid, HB_DEON_SPECTRAL_BLOCKS(4));
    else
        HB_BATCH(load_spectral, 5 + HB_DEON_CHANNELS, b, n, invalid, HB_DEON_SPECTRAL_BLOCKS(b->wavelengths));
}
#undef HB_DEON_SPECTRAL_BLOCKS

/* The near-field sampler at k wavelengths (load_deon_sample_spectral): the lobe by the attenuations' mean
 * over the k, f / pdf per wavelength. */
static void HB_DEON_VARIANT(deon_sample_spectral)(const hb_deon *deon, size_t n, const hb_spectral_sample_batch *b,
                                          size_t *invalid)
{
    enum { FIRST = 3 + HB_DEON_NEAR_DIMENSIONS };
    vf theta_i, phi_i, pdf, weight[HB_DEON_CHANNELS];
    HB_BATCH(load_deon_sample_spectral, FIRST + HB_DEON_CHANNELS, b, n, invalid,
             (deon_sample_near_of(deon, b->wavelengths, a + FIRST, a[0], a[1], a[FIRST - 1], a + 2, HB_DEON_I0,
                                  &theta_i, &phi_i, &pdf, weight),
              store_sample_spectral(&b->out, b->wavelengths, i, lanes, valid, theta_i, phi_i, pdf, weight)));
}

static void HB_DEON_VARIANT(deon_near)(const hb_deon *deon, size_t n, hb_near_soa in, hb_rgb_soa out,
                               size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_near, 5, in, n, invalid,
             (deon_near_angles(deon, a, HB_DEON_I0, f, NULL), store_rgb(out, i, lanes, valid, f)));
}

static void HB_DEON_VARIANT(deon_near_absorbing)(const hb_deon *deon, size_t n, const hb_absorbing_near *in,
                                         hb_rgb_soa out, size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_near_absorbing, 8, in, n, invalid,
             (deon_near_absorbing_angles(deon, a, HB_DEON_I0, f), store_rgb(out, i, lanes, valid, f)));
}

static void HB_DEON_VARIANT(deon_pdf_near)(const hb_deon *deon, size_t n, hb_near_soa in, float *pdf,
                                   size_t *invalid)
{
    vf f[3], p;
    HB_BATCH(load_near, 5, in, n, invalid,
             (deon_near_angles(deon, a, HB_DEON_I0, f, &p), store_block(pdf, i, lanes, vf_keep(valid, p))));
}

static void HB_DEON_VARIANT(deon_sample_near)(const hb_deon *deon, size_t n, hb_sample_streams in,
                                      hb_sample_out out, size_t *invalid)
{
    vf theta_i, phi_i, pdf, weight[3];
    HB_BATCH(load_deon_sample_near, 3 + HB_DEON_NEAR_DIMENSIONS, in, n, invalid,
             (deon_sample_near(deon, a[0], a[1], a[2 + HB_DEON_NEAR_DIMENSIONS], a + 2, HB_DEON_I0, &theta_i,
                               &phi_i, &pdf, weight),
              store_sample(out, i, lanes, valid, theta_i, phi_i, pdf, weight)));
}

static void HB_DEON_VARIANT(deon_vectors)(const hb_deon *deon, size_t n, hb_vectors_soa in, hb_rgb_soa out,
                                  size_t *invalid)
{
    vf f[3];
    HB_BATCH(load_vectors, 6, in, n, invalid,
             (deon_vectors(deon, a, a + 3, HB_DEON_I0, f), store_rgb(out, i, lanes, valid, f)));
}

#undef HB_DEON_VARIANT
#undef HB_DEON_NAME
#undef HB_DEON_JOIN
#undef HB_DEON_SUFFIX
#undef HB_DEON_I0

/* MJC03 sampling (src/models/marschner/sample.h; docs/sampling.md): the sampler draws the density
 * its pdf states (chi-square over equal-area cells, the pdf integrating to 1), every weight is f / pdf
 * with hb_pdf_angles at the sample equal to the sampled pdf, and the mean weight is the white
 * furnace's energy. */
#include "sampling.h"

typedef struct mjc_case {
    const char *name;
    double beta_m, alpha, sigma_a, eta, eccentricity;
    unsigned lobes;
    double theta_o;
    int caustic; /* the sampling density has a caustic's integrable singularity (TRT or a folding TT) */
} mjc_case;

static const mjc_case cases[] = {
    { "blond", 0.15, 0.05, 0.1, 1.55, 0.0, HB_LOBES_DEFAULT, 0.3, 1 },
    { "dark, grazing", 0.1, -0.05, 1.5, 1.55, 0.0, HB_LOBES_DEFAULT, 1.3, 1 },
    { "TRT caustics (eta 1.9)", 0.2, 0.0, 0.05, 1.9, 0.0, 1u << HB_LOBE_TRT, -0.4, 1 },
    { "elliptical", 0.15, 0.05, 0.2, 1.55, 0.6, HB_LOBES_DEFAULT, 0.8, 1 },
    { "eta near 1", 0.3, 0.0, 0.0, 1.05, 0.0, HB_LOBES_DEFAULT, -1.0, 1 },
    { "R alone, narrow", 0.05, 0.08, 0.0, 1.55, 0.0, 1u << HB_LOBE_R, 0.0, 0 },
    { "R + TT", 0.2, 0.03, 0.3, 1.55, 0.0, 3u, -0.6, 0 },
};

static hb_plan *mjc_plan(hb_test_ctx *t, const mjc_case *c, hb_isa isa)
{
    hb_material m;
    hb_options o;
    hb_material_default(&m);
    hb_options_default(&o);
    o.model = HB_MODEL_MARSCHNER;
    o.lobes = c->lobes;
    o.isa = isa;
    m.beta_m = c->beta_m, m.alpha = c->alpha, m.eta = c->eta, m.eccentricity = c->eccentricity;
    m.sigma_a[0] = c->sigma_a, m.sigma_a[1] = 1.5 * c->sigma_a, m.sigma_a[2] = 2.5 * c->sigma_a;
    hb_plan *plan = NULL;
    hb_error err;
    CHECK(t, hb_plan_create(&m, &o, &plan, &err) == HB_OK, "%s: %s", c->name, err.message);
    return plan;
}

enum { NT = 24, NP = 48, GL = 6 };

/* Where the density is smooth (R, TT without a fold), chi-square over equal-area cells (p >= 1e-3)
 * and the pdf integrating to 1 within 2e-3. Everywhere, the weights estimate f in every cell (each
 * cell's mean weight within 5 standard errors of f's integral there: a wrong density in a cell would
 * bias it; cells of fewer than 20 samples or under 1e-3 of f are left out) and their mean is the white furnace's energy
 * within 3%; every weight is f / pdf. The pdf
 * of a caustic is singular (1/sqrt) at the fold, which the cells' Gauss-Legendre integrals of the pdf
 * cannot resolve, so those cases take the weighted test alone. */
static void test_marschner_chi_square(hb_test_ctx *t)
{
    static double prob[NT * NP], f_cells[NT * NP];
    size_t n = t->quick ? 40000 : HB_TEST_MAX_SAMPLES;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        hb_plan *plan = mjc_plan(t, &cases[c], HB_ISA_AUTO);
        if (!plan)
            return;
        CHECK(t, hb_plan_sample_dimensions(plan) == 3, "%s: MJC03 reads 3 numbers", cases[c].name);
        double integral = hb_test_cell_integrals(plan, 1, cases[c].theta_o, 0.3, NT, NP, 1, GL, prob);
        hb_test_cell_integrals(plan, 0, cases[c].theta_o, 0.3, NT, NP, 1, GL, f_cells);
        unsigned long long seed = hb_test_next_seed(t);
        hb_test_sample_batch(t, plan, n, cases[c].theta_o, 0.3, seed);
        double chi2, worst_weight = 0.0;
        int cells, weighted_cells;
        double p_value = hb_test_chi_square(n, prob, integral, NT, NP, &chi2, &cells);
        double uncompared;
        double worst_z = hb_test_weighted_cells(n, f_cells, NT, NP, &weighted_cells, &uncompared);
        hb_sample_buffers *b = &hb_samples;
        hb_angles_soa at = { b->ti, b->pi, b->to, b->po };
        hb_pdf_angles(plan, n, at, b->pdf2, NULL);
        hb_eval_angles(plan, n, at, (hb_rgb_soa){ b->f[0], b->f[1], b->f[2] }, NULL);
        hb_test_check_sampled_weights(t, n, cases[c].name, &worst_weight);
        double mean = 0.0, energy[3];
        for (size_t k = 0; k < n; k++)
            mean += b->w[0][k] / (double)n;
        hb_furnace(plan, cases[c].theta_o, energy);
        hb_test_note(t, "%-24s (seed %llu): pdf integral %.6f, chi2 %.1f over %d cells, p = %.3f; weighted cells: "
                        "largest z %.2f over %d (%.1e of f elsewhere); mean weight %.4f, furnace %.4f; weights f / pdf to %.1e",
                     cases[c].name, seed, integral, chi2, cells, p_value, worst_z, weighted_cells, uncompared, mean, energy[0],
                     worst_weight);
        if (!cases[c].caustic) {
            CHECK(t, fabs(integral - 1.0) <= 2e-3, "%s: pdf integrates to %.6f", cases[c].name, integral);
            CHECK(t, p_value >= 1e-3, "%s: chi-square p-value %.2e below the 1e-3 significance", cases[c].name, p_value);
        }
        CHECK(t, worst_z <= 5.0, "%s: a cell's mean weight is %.2f standard errors from f's integral", cases[c].name,
              worst_z);
        CHECK(t, worst_weight <= 1e-5, "%s: weight differs from f / pdf by %.3g", cases[c].name, worst_weight);
        CHECK(t, fabs(mean / energy[0] - 1.0) <= 0.03, "%s: mean weight %.4f, furnace %.4f", cases[c].name, mean,
              energy[0]);
        hb_plan_destroy(plan);
    }
}

/* On every ISA: finite non-negative samples and weights from random w_o (poles included), the pdf at
 * the sample equal to the sampled one bit for bit; a fully absorbing fibre samples with a finite pdf. */
static void test_marschner_sample_isa(hb_test_ctx *t)
{
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        hb_plan *plan = mjc_plan(t, &cases[c], t->isa);
        if (!plan)
            return;
        static const double thetas[] = { -1.5707963, -1.2, 0.0, 0.7, 1.5707963 };
        for (int k = 0; k < 5; k++) {
            size_t n = 2048;
            double worst_weight = 0.0;
            hb_test_sample_batch(t, plan, n, thetas[k], -2.0, hb_test_next_seed(t));
            hb_sample_buffers *b = &hb_samples;
            hb_angles_soa at = { b->ti, b->pi, b->to, b->po };
            hb_pdf_angles(plan, n, at, b->pdf2, NULL);
            hb_eval_angles(plan, n, at, (hb_rgb_soa){ b->f[0], b->f[1], b->f[2] }, NULL);
            hb_test_check_sampled_weights(t, n, cases[c].name, &worst_weight);
            CHECK(t, worst_weight <= 1e-5, "%s at theta_o %g: weight differs from f / pdf by %.3g", cases[c].name,
                  thetas[k], worst_weight);
        }
        hb_plan_destroy(plan);
    }
    /* a fibre whose absorption leaves every lobe 0: the lobes are drawn in equal shares, pdf finite */
    const mjc_case black = { "absorbed", 0.2, 0.0, 1e30, 1.55, 0.0, 1u << HB_LOBE_TRT, 0.0, 1 };
    hb_plan *plan = mjc_plan(t, &black, t->isa);
    if (!plan)
        return;
    hb_test_sample_batch(t, plan, 256, 0.4, 0.0, hb_test_next_seed(t));
    for (int k = 0; k < 256; k++)
        CHECK(t, isfinite(hb_samples.pdf[k]) && hb_samples.pdf[k] > 0.0f && hb_samples.w[0][k] == 0.0f,
              "absorbed sample %d: pdf %g weight %g", k, hb_samples.pdf[k], hb_samples.w[0][k]);
    hb_plan_destroy(plan);
}

const hb_test hb_tests_marschner_sample[] = {
    { "marschner_sample_chi_square", test_marschner_chi_square, 0 },
    { "marschner_sample_isa", test_marschner_sample_isa, 1 },
    { 0 },
};

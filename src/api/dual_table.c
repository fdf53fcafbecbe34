/* The dual-scattering table and radiance term (hb_dual_table_create, hb_dual_eval, hb_dual_radiance;
 * docs/multiple-scattering.md): the terms of hb_dual_terms_grid kept in double and as the kernels'
 * floats, the plan's ISA's kernel, and the double reference behind the argument checks. */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "dual_sums.h"
#include "dual/kernels.h"
#include "kernel/isas.h"
#include "math/dual_scattering.h"
#include "math/valid.h"
#include "models/file/dual_file.h"

enum { THETAS_MAX = 4096 };

static hb_status check_density(const char *call, double d_f, double d_b)
{
    if (!(d_f >= 0.0 && d_f <= 1.0))
        return hb_fail(HB_ERR_PARAM, "%s: d_f = %g is outside [0, 1]", call, d_f);
    if (!(d_b >= 0.0 && d_b <= 1.0))
        return hb_fail(HB_ERR_PARAM, "%s: d_b = %g is outside [0, 1]", call, d_b);
    return HB_OK;
}

/* The kernels' floats of node k: per channel the nine terms, then the padding. */
static void node_floats(const hb_dual_terms *t, float *node)
{
    for (int k = 0; k < HB_DUAL_PER_NODE; k++)
        node[k] = 0.0f;
    for (int c = 0; c < 3; c++) {
        float *m = node + c * HB_DUAL_PER_CHANNEL;
        m[HB_DUAL_A_F] = (float)t->a_f[c], m[HB_DUAL_A_B] = (float)t->a_b[c];
        m[HB_DUAL_ALPHA_F] = (float)t->alpha_f[c], m[HB_DUAL_BETA_F2] = (float)t->beta_f2[c];
        m[HB_DUAL_ALPHA_B] = (float)t->alpha_b[c], m[HB_DUAL_BETA_B2] = (float)t->beta_b2[c];
        m[HB_DUAL_A_BACK] = (float)t->A_b[c], m[HB_DUAL_DELTA_B] = (float)t->delta_b[c];
        m[HB_DUAL_SIGMA_B2] = (float)t->sigma_b2[c];
    }
}

void hb_dual_table_destroy(hb_dual_table *table)
{
    if (!table)
        return;
    free(table->terms);
    free(table->nodes);
    free(table->fields);
    free(table);
}

/* A table of `thetas` nodes for the plan's ISA and model, its terms still to be filled. */
static hb_status table_alloc(const char *call, const hb_plan *plan, int thetas, double d_f, double d_b,
                             hb_dual_table **table)
{
    hb_dual_table *t = calloc(1, sizeof *t);
    if (t) {
        t->terms = calloc((size_t)thetas, sizeof *t->terms);
        t->nodes = malloc((size_t)thetas * HB_DUAL_PER_NODE * sizeof *t->nodes);
        t->fields_size = hb_table_file_fields_write(plan, NULL);
        t->fields = malloc(t->fields_size);
    }
    if (!t || !t->terms || !t->nodes || !t->fields) {
        hb_dual_table_destroy(t);
        return hb_fail(HB_ERR_NOMEM, "%s: no memory for %d nodes", call, thetas);
    }
    hb_table_file_fields_write(plan, t->fields);
    HB_PER_ISA(hb_dual_kernels, dual_kernels, kernels_by_isa);
    t->isa = kernels_by_isa[plan->isa] ? plan->isa : HB_ISA_SCALAR;
    t->kernels = kernels_by_isa[t->isa];
    t->thetas = thetas, t->d_f = d_f, t->d_b = d_b, t->model = plan->options.model;
    for (int k = 0; k < thetas; k++)
        t->terms[k].struct_size = sizeof *t->terms;
    *table = t;
    return HB_OK;
}

/* The kernels' floats from the terms, once no node's a_f reaches 1; frees the table on a refusal. */
static hb_status table_finish(const char *call, hb_dual_table *t)
{
    for (int k = 0; k < t->thetas; k++)
        for (int c = 0; c < 3; c++)
            if (!(t->terms[k].a_f[c] < 1.0)) {
                hb_status st = hb_fail(HB_ERR_LIMIT,
                                       "%s: a_f = %.4f at theta %.4f (channel %d) is not below 1: the forward scatterings "
                                       "of eqs. 14-15 diverge",
                                       call, t->terms[k].a_f[c], -M_PI_2 + M_PI * (k + 0.5) / t->thetas, c);
                hb_dual_table_destroy(t);
                return st;
            }
    t->share = 0.0;
    for (int k = 0; k < t->thetas; k++)
        for (int c = 0; c < 3; c++)
            t->share = fmax(t->share, hb_dual_share(t->terms[k].a_f[c], t->terms[k].a_b[c], t->terms[k].A_b[c], t->d_f,
                                                    t->d_b));
    t->included = t->share > 0.0; /* a file of a dropped table holds zeros */
    for (int k = 0; k < t->thetas; k++)
        node_floats(&t->terms[k], t->nodes + (size_t)k * HB_DUAL_PER_NODE);
    return HB_OK;
}

double hb_dual_drop_target(const hb_plan *plan)
{
    if (!plan->selection.active)
        return 0.0;
    return plan->selection.tolerance > 0.0 ? plan->selection.tolerance : plan->selection.expected_error;
}

/* A tolerance or budget plan's table keeps the term only where it adds at least the plan's target. */
static void drop_if_negligible(const hb_plan *plan, hb_dual_table *t)
{
    if (!(t->share < hb_dual_drop_target(plan)))
        return;
    t->included = 0;
    for (int k = 0; k < t->thetas; k++) {
        size_t size = t->terms[k].struct_size;
        t->terms[k] = (hb_dual_terms){ .struct_size = size };
        node_floats(&t->terms[k], t->nodes + (size_t)k * HB_DUAL_PER_NODE);
    }
}

int hb_dual_table_included(const hb_dual_table *table, double *share)
{
    if (share)
        *share = table ? table->share : 0.0;
    return table ? table->included : 0;
}

hb_status hb_dual_table_create(const hb_plan *plan, int thetas, double d_f, double d_b, hb_progress_fn progress,
                               void *progress_context, hb_parallel_fn parallel, void *parallel_context,
                               hb_dual_table **table)
{
    if (!plan || !table)
        return hb_fail_null(__func__, !plan ? "plan" : "table");
    *table = NULL;
    if (thetas < 2 || thetas > THETAS_MAX)
        return hb_fail(HB_ERR_PARAM, "%s: thetas = %d is outside [2, %d]", __func__, thetas, THETAS_MAX);
    hb_status st = check_density(__func__, d_f, d_b);
    hb_dual_table *t = NULL;
    if (st == HB_OK)
        st = table_alloc(__func__, plan, thetas, d_f, d_b, &t);
    if (st != HB_OK)
        return st;
    st = hb_dual_terms_grid(plan, thetas, d_b, t->terms, progress, progress_context, parallel, parallel_context);
    if (st != HB_OK) {
        hb_dual_table_destroy(t);
        return st;
    }
    st = table_finish(__func__, t);
    if (st == HB_OK) {
        drop_if_negligible(plan, t);
        *table = t;
    }
    return st;
}

/* HB_ERR_PARAM unless every term of the node is finite and its energies and variances are not negative. */
static hb_status check_terms(const char *call, const hb_dual_terms *t, int k)
{
    const double *signed_terms[] = { t->alpha_f, t->alpha_b, t->delta_b };
    const double *positive[] = { t->a_f, t->a_b, t->beta_f2, t->beta_b2, t->A_b, t->sigma_b2 };
    for (int c = 0; c < 3; c++) {
        for (size_t j = 0; j < sizeof signed_terms / sizeof *signed_terms; j++)
            if (!isfinite(signed_terms[j][c]))
                return hb_fail(HB_ERR_PARAM, "%s: terms[%d] has a shift of %g (channel %d)", call, k, signed_terms[j][c], c);
        for (size_t j = 0; j < sizeof positive / sizeof *positive; j++)
            if (!(positive[j][c] >= 0.0 && positive[j][c] <= DBL_MAX))
                return hb_fail(HB_ERR_PARAM, "%s: terms[%d] has an energy or variance of %g (channel %d)", call, k,
                               positive[j][c], c);
    }
    return HB_OK;
}

hb_status hb_dual_table_from_terms(const hb_plan *plan, int thetas, const hb_dual_terms *terms, double d_f, double d_b,
                                   hb_dual_table **table)
{
    if (!plan || !terms || !table)
        return hb_fail_null(__func__, !plan ? "plan" : !terms ? "terms" : "table");
    *table = NULL;
    if (thetas < 2 || thetas > THETAS_MAX)
        return hb_fail(HB_ERR_PARAM, "%s: thetas = %d is outside [2, %d]", __func__, thetas, THETAS_MAX);
    hb_status st = check_density(__func__, d_f, d_b);
    for (int k = 0; k < thetas && st == HB_OK; k++)
        st = terms[k].struct_size != sizeof *terms
                 ? hb_fail(HB_ERR_VERSION, "%s: terms[%d].struct_size = %zu; this release's is %zu", __func__, k,
                           terms[k].struct_size, sizeof *terms)
                 : check_terms(__func__, &terms[k], k);
    hb_dual_table *t = NULL;
    if (st == HB_OK)
        st = table_alloc(__func__, plan, thetas, d_f, d_b, &t);
    if (st != HB_OK)
        return st;
    memcpy(t->terms, terms, (size_t)thetas * sizeof *terms);
    st = table_finish(__func__, t);
    if (st == HB_OK)
        *table = t;
    return st;
}

/* A node's terms as the file stores them: the nine per-channel arrays in the struct's order. */
static double *term_doubles(hb_dual_terms *t) { return (double *)((char *)t + offsetof(hb_dual_terms, a_f)); }

hb_status hb_dual_table_save(const hb_dual_table *table, void *bytes, size_t capacity, size_t *size)
{
    if (!table || !size)
        return hb_fail_null(__func__, !table ? "table" : "size");
    size_t count = (size_t)table->thetas * HB_DUAL_FILE_TERMS;
    *size = hb_dual_file_write(table->model, table->thetas, table->d_f, table->d_b, table->fields, table->fields_size, NULL,
                               NULL);
    if (!bytes)
        return HB_OK;
    if (capacity < *size)
        return hb_fail(HB_ERR_BUFFER, "%s: the table file takes %zu bytes, capacity is %zu (*size has the length)",
                       __func__, *size, capacity);
    double *values = malloc(count * sizeof *values);
    if (!values)
        return hb_fail(HB_ERR_NOMEM, "%s: no memory for %zu values", __func__, count);
    for (int k = 0; k < table->thetas; k++)
        memcpy(values + (size_t)k * HB_DUAL_FILE_TERMS, term_doubles(&table->terms[k]), HB_DUAL_FILE_TERMS * sizeof(double));
    hb_dual_file_write(table->model, table->thetas, table->d_f, table->d_b, table->fields, table->fields_size, values, bytes);
    free(values);
    return HB_OK;
}

hb_status hb_dual_table_load(const hb_plan *plan, const void *bytes, size_t size, hb_dual_table **table)
{
    if (!plan || !bytes || !table)
        return hb_fail_null(__func__, !plan ? "plan" : !bytes ? "bytes" : "table");
    *table = NULL;
    int thetas;
    double d_f, d_b;
    const unsigned char *values;
    hb_error error;
    if (hb_dual_file_read(plan, bytes, size, &thetas, &d_f, &d_b, &values, &error) != HB_OK)
        return hb_fail(error.status, "%s: %s", __func__, error.message);
    hb_dual_table *t;
    hb_status st = table_alloc(__func__, plan, thetas, d_f, d_b, &t);
    if (st != HB_OK)
        return st;
    for (int k = 0; k < thetas; k++)
        for (int j = 0; j < HB_DUAL_FILE_TERMS; j++)
            term_doubles(&t->terms[k])[j] = hb_dual_file_value(values, (size_t)k * HB_DUAL_FILE_TERMS + (size_t)j);
    st = table_finish(__func__, t);
    if (st == HB_OK)
        *table = t;
    return st;
}

const float *hb_dual_table_nodes(const hb_dual_table *table, int *thetas)
{
    if (thetas)
        *thetas = table ? table->thetas : 0;
    return table ? table->nodes : NULL;
}

hb_status hb_dual_table_terms(const hb_dual_table *table, double theta, hb_dual_terms *terms)
{
    if (!table || !terms)
        return hb_fail_null(__func__, !table ? "table" : "terms");
    if (terms->struct_size != sizeof *terms)
        return hb_fail(HB_ERR_VERSION, "%s: terms->struct_size = %zu; this release's is %zu", __func__,
                       terms->struct_size, sizeof *terms);
    if (!hb_theta_valid(theta))
        return hb_fail(HB_ERR_PARAM, "%s: theta = %g is outside [-pi/2, pi/2]", __func__, theta);
    hb_dual_interpolate(table, theta, terms);
    return HB_OK;
}

hb_status hb_dual_eval(const hb_dual_table *table, size_t n, hb_angles_soa in, const float *fibres,
                       const float *direct, hb_rgb_soa out, hb_eval_report *report)
{
    if (!table)
        return hb_fail_null(__func__, "table");
    hb_status st = hb_api_rgb_present(__func__, n, "out", &out);
    if (st == HB_OK)
        st = hb_api_angles_present(__func__, n, &in);
    if (st == HB_OK && n && !fibres)
        st = hb_fail_null(__func__, "fibres");
    if (st != HB_OK)
        return st;
    hb_dual_batch batch = { in, fibres, direct };
    size_t invalid = 0;
    table->kernels->eval(table, n, &batch, out, &invalid);
    if (report)
        report->invalid = invalid;
    return HB_OK;
}

hb_status hb_dual_radiance(const hb_dual_terms *terms, double d_f, double d_b, double theta_i, double phi_i,
                           double theta_o, double phi_o, double fibres, double direct, double f[3])
{
    if (!terms || !f)
        return hb_fail_null(__func__, !terms ? "terms" : "f");
    hb_status st = check_density(__func__, d_f, d_b);
    if (st != HB_OK)
        return st;
    if (!(hb_theta_valid(theta_i) && hb_theta_valid(theta_o) && fabs(phi_i) <= HB_PHI_LIMIT &&
          fabs(phi_o) <= HB_PHI_LIMIT))
        return hb_fail(HB_ERR_PARAM, "%s: the direction (%g, %g) -> (%g, %g) is not a valid sample", __func__, theta_i,
                       phi_i, theta_o, phi_o);
    if (!(fibres >= 0.0 && fibres <= FLT_MAX))
        return hb_fail(HB_ERR_PARAM, "%s: fibres = %g is not a count in [0, FLT_MAX]", __func__, fibres);
    if (!(direct <= 1.0) || isnan(direct))
        return hb_fail(HB_ERR_PARAM, "%s: direct = %g is above 1 (negative: the default)", __func__, direct);
    hb_dual_radiance_reference(terms, d_f, d_b, theta_i, phi_i, theta_o, phi_o, fibres,
                               direct >= 0.0 ? direct : fmax(0.0, 1.0 - fibres), f);
    return HB_OK;
}

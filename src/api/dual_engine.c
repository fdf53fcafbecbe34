/* hb_dual_engine: one material family's dual-scattering terms over (theta, R roughness, absorption),
 * the engine-wide table of docs/multiple-scattering.md ("One table for every hair colour"). A
 * channel's terms depend on its own absorption alone, so each plan of the build carries three
 * absorption nodes as its three channels; the roughness is the model's look (its R lobe's
 * longitudinal width), set through the model's own operations. Lookups interpolate the six
 * hemisphere terms trilinearly and derive eqs. 14-17's from them. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "math/dual_scattering.h"
#include "models/build/build_tasks.h"
#include "models/file/dual_file.h"
#include "models/interface/model.h"
#include "plan/creation.h"

enum { PRIMARY = HB_DUAL_ENGINE_TERMS, CHANNELS = 3 }; /* a_f, a_b, alpha_f, beta_f2, alpha_b, beta_b2 per node */
#define FAMILY_ROUGHNESS 0.3 /* the base's R roughness as its file records it (radians) */

struct hb_dual_engine {
    hb_material base;  /* the family's material, its own absorption and roughness unused */
    hb_options options; /* the node plans' concrete options */
    hb_dual_engine_axes axes;
    double d_b;
    double *nodes; /* [roughness][absorption][theta][PRIMARY] */
    float *floats; /* the same, HB_DUAL_ENGINE_NODE_FLOATS a node, for the shaders */
    size_t node_count;
    unsigned char *fields; /* the base plan's fields section, for its file */
    size_t fields_size;
};

void hb_dual_engine_axes_default(hb_dual_engine_axes *axes)
{
    *axes = (hb_dual_engine_axes){ .struct_size = sizeof *axes, .thetas = 64, .roughnesses = 16, .roughness_min = 0.05,
                                   .roughness_max = 0.6, .absorptions = 16, .absorption_max = 12.0 };
}

static double theta_at(const hb_dual_engine_axes *a, int k) { return -M_PI_2 + M_PI * (k + 0.5) / a->thetas; }
static double roughness_at(const hb_dual_engine_axes *a, int r)
{
    return a->roughness_min + (a->roughness_max - a->roughness_min) * r / (a->roughnesses - 1);
}
/* The nodes are even in the transmittance along one radius, exp(-sigma_a). */
static double absorption_at(const hb_dual_engine_axes *a, int j)
{
    return -log(1.0 - (1.0 - exp(-a->absorption_max)) * j / (a->absorptions - 1));
}

static double *node(const hb_dual_engine *e, int r, int j, int k)
{
    return e->nodes + (((size_t)r * (size_t)e->axes.absorptions + (size_t)j) * (size_t)e->axes.thetas + (size_t)k) * PRIMARY;
}

/* m with the look's longitudinal width set to roughness, through the model's own parameters. */
static hb_status set_roughness(const hb_model_ops *ops, hb_material *m, double roughness, hb_error *error)
{
    hb_look look;
    ops->look(m, &look);
    look.longitudinal = roughness;
    return ops->set_look(&look, m, error);
}

typedef struct build {
    hb_dual_engine *e;
    hb_status *status;
    hb_error *errors;
} build;

/* Task r * groups + g: the plan of roughness node r whose channels are absorption nodes 3g .. 3g + 2. */
static void build_task(void *context, int index)
{
    const build *b = context;
    hb_dual_engine *e = b->e;
    const hb_dual_engine_axes *a = &e->axes;
    int groups = (a->absorptions + CHANNELS - 1) / CHANNELS, r = index / groups, g = index % groups;
    const hb_model_ops *ops = hb_model_ops_of(e->options.model);
    hb_material m = e->base;
    m.eumelanin = m.pheomelanin = 0.0;
    for (int c = 0; c < CHANNELS; c++)
        m.sigma_a[c] = absorption_at(a, g * CHANNELS + c < a->absorptions ? g * CHANNELS + c : a->absorptions - 1);
    hb_plan *plan = NULL;
    hb_status st = set_roughness(ops, &m, roughness_at(a, r), &b->errors[index]);
    if (st == HB_OK)
        st = hb_plan_create(&m, &e->options, &plan, &b->errors[index]);
    for (int k = 0; k < a->thetas && st == HB_OK; k++) {
        hb_dual_terms t = { .struct_size = sizeof t };
        st = a->sampled_directions ? hb_dual_terms_sampled(plan, theta_at(a, k), a->sampled_directions,
                                                           a->sampled_azimuths, e->d_b, &t)
                                   : hb_dual_terms_at(plan, theta_at(a, k), e->d_b, &t);
        for (int c = 0; c < CHANNELS && st == HB_OK; c++) {
            if (g * CHANNELS + c >= a->absorptions)
                break;
            double *v = node(e, r, g * CHANNELS + c, k);
            v[0] = t.a_f[c], v[1] = t.a_b[c], v[2] = t.alpha_f[c], v[3] = t.beta_f2[c], v[4] = t.alpha_b[c],
            v[5] = t.beta_b2[c];
        }
        if (st != HB_OK)
            b->errors[index] = *hb_last_error(); /* the terms' refusal, on this task's thread */
    }
    hb_plan_destroy(plan);
    b->status[index] = st;
}

static hb_status check_axes(const char *call, const hb_dual_engine_axes *a, hb_error *error)
{
    if (a->struct_size != sizeof *a)
        return hb_plan_fail(error, HB_ERR_VERSION, "%s: axes->struct_size = %zu; this release's is %zu", call,
                            a->struct_size, sizeof *a);
    if (a->thetas < 2 || a->thetas > 1024)
        return hb_plan_fail(error, HB_ERR_PARAM, "%s: axes->thetas = %d is outside [2, 1024]", call, a->thetas);
    if (a->roughnesses < 2 || a->roughnesses > 256)
        return hb_plan_fail(error, HB_ERR_PARAM, "%s: axes->roughnesses = %d is outside [2, 256]", call, a->roughnesses);
    if (!(a->roughness_min > 0.0 && a->roughness_max > a->roughness_min && a->roughness_max <= M_PI_2))
        return hb_plan_fail(error, HB_ERR_PARAM, "%s: the roughness axis [%g, %g] is not an interval in (0, pi/2]", call,
                            a->roughness_min, a->roughness_max);
    if (a->absorptions < 2 || a->absorptions > 256)
        return hb_plan_fail(error, HB_ERR_PARAM, "%s: axes->absorptions = %d is outside [2, 256]", call, a->absorptions);
    if (!(a->absorption_max > 0.0 && a->absorption_max <= 700.0))
        return hb_plan_fail(error, HB_ERR_PARAM, "%s: axes->absorption_max = %g is outside (0, 700]", call,
                            a->absorption_max);
    int sampled = a->sampled_directions || a->sampled_azimuths;
    if (sampled && !(a->sampled_directions >= 1 && a->sampled_directions <= 65536 && a->sampled_azimuths >= 1 &&
                     a->sampled_azimuths <= 65536))
        return hb_plan_fail(error, HB_ERR_PARAM,
                            "%s: sampled_directions = %d and sampled_azimuths = %d: both 0, or both in [1, 65536]", call,
                            a->sampled_directions, a->sampled_azimuths);
    return HB_OK;
}

void hb_dual_engine_destroy(hb_dual_engine *engine)
{
    if (!engine)
        return;
    free(engine->nodes);
    free(engine->floats);
    free(engine->fields);
    free(engine);
}

/* An engine of the base plan's family with these axes and d_b, its nodes still to be filled. */
static hb_status engine_alloc(const char *call, const hb_plan *probe, const hb_dual_engine_axes *axes, double d_b,
                              hb_dual_engine **engine, hb_error *error)
{
    hb_dual_engine *e = calloc(1, sizeof *e);
    if (e) {
        e->node_count = (size_t)axes->roughnesses * (size_t)axes->absorptions * (size_t)axes->thetas;
        e->nodes = malloc(e->node_count * PRIMARY * sizeof *e->nodes);
        e->floats = calloc(e->node_count * HB_DUAL_ENGINE_NODE_FLOATS, sizeof *e->floats);
        e->fields_size = hb_table_file_fields_write(probe, NULL);
        e->fields = malloc(e->fields_size);
    }
    if (!e || !e->nodes || !e->floats || !e->fields) {
        hb_dual_engine_destroy(e);
        return hb_plan_fail(error, HB_ERR_NOMEM, "%s: no memory for the table", call);
    }
    hb_table_file_fields_write(probe, e->fields);
    e->base = probe->material, e->options = probe->options, e->axes = *axes, e->d_b = d_b;
    e->options.tolerance = 0.0, e->options.budget_ns = 0.0;
    e->options.progress = NULL, e->options.parallel = NULL;
    e->options.table_file = NULL, e->options.table_file_size = 0;
    *engine = e;
    return HB_OK;
}

/* The shaders' floats from the nodes. */
static void engine_floats(hb_dual_engine *e)
{
    for (size_t k = 0; k < e->node_count; k++)
        for (int q = 0; q < PRIMARY; q++)
            e->floats[k * HB_DUAL_ENGINE_NODE_FLOATS + (size_t)q] = (float)e->nodes[k * PRIMARY + (size_t)q];
}

/* The plan of the family's base (its checks, the concrete options every node plan uses and the
 * fields its file holds): the base without absorption, at the look's roughness FAMILY_ROUGHNESS,
 * since the axes replace both. */
static hb_status probe_create(const char *call, const hb_material *base, const hb_options *options, hb_plan **probe,
                              hb_error *error)
{
    hb_material m;
    hb_status st = hb_material_upgrade(base, &m, error);
    m.eumelanin = m.pheomelanin = 0.0;
    m.sigma_a[0] = m.sigma_a[1] = m.sigma_a[2] = 0.0;
    const hb_model_ops *ops = (unsigned)options->model <= HB_MODEL_CHIANG ? hb_model_ops_of(options->model) : NULL;
    if (st == HB_OK && ops) /* an unknown model is plan creation's to refuse */
        st = set_roughness(ops, &m, FAMILY_ROUGHNESS, error);
    if (st == HB_OK)
        st = hb_plan_create(&m, options, probe, error);
    if (st != HB_OK) {
        hb_error last = *hb_last_error();
        hb_plan_fail(error, st, "%s: %s", call, last.message);
    }
    return st;
}

hb_status hb_dual_engine_create(const hb_material *base, const hb_options *options, const hb_dual_engine_axes *axes,
                                double d_b, hb_dual_engine **engine, hb_error *error)
{
    if (!base || !options || !axes || !engine)
        return hb_plan_fail(error, HB_ERR_NULL, "%s: %s is NULL", __func__,
                            !base ? "base" : !options ? "options" : !axes ? "axes" : "engine");
    *engine = NULL;
    hb_status st = check_axes(__func__, axes, error);
    if (st == HB_OK && !(d_b >= 0.0 && d_b <= 1.0))
        st = hb_plan_fail(error, HB_ERR_PARAM, "%s: d_b = %g is outside [0, 1]", __func__, d_b);
    hb_plan *probe = NULL;
    if (st == HB_OK)
        st = probe_create(__func__, base, options, &probe, error);
    hb_dual_engine *e = NULL;
    if (st == HB_OK)
        st = engine_alloc(__func__, probe, axes, d_b, &e, error);
    hb_plan_destroy(probe);
    if (st != HB_OK)
        return st;
    size_t tasks = (size_t)axes->roughnesses * (size_t)((axes->absorptions + CHANNELS - 1) / CHANNELS);
    hb_status *status = calloc(tasks, sizeof *status);
    hb_error *errors = calloc(tasks, sizeof *errors);
    if (!status || !errors) {
        hb_dual_engine_destroy(e);
        free(status), free(errors);
        return hb_plan_fail(error, HB_ERR_NOMEM, "%s: no memory for the table", __func__);
    }
    build b = { e, status, errors };
    st = hb_build_tasks(options, (int)tasks, hb_build_part((int)tasks), build_task, &b, 0.0, 1.0, error);
    for (size_t k = 0; k < tasks && st == HB_OK; k++)
        if (status[k] != HB_OK)
            st = hb_plan_fail(error, status[k], "%s: %s", __func__, errors[k].message);
    if (st == HB_OK)
        st = hb_build_finish(options, error);
    free(status), free(errors);
    if (st != HB_OK) {
        hb_dual_engine_destroy(e);
        return st;
    }
    engine_floats(e);
    *engine = e;
    return HB_OK;
}

hb_status hb_dual_engine_save(const hb_dual_engine *engine, void *bytes, size_t capacity, size_t *size)
{
    if (!engine || !size)
        return hb_fail_null(__func__, !engine ? "engine" : "size");
    const hb_dual_engine *e = engine;
    *size = hb_dual_engine_file_write(e->options.model, &e->axes, e->d_b, e->fields, e->fields_size, NULL, NULL);
    if (!bytes)
        return HB_OK;
    if (capacity < *size)
        return hb_fail(HB_ERR_BUFFER, "%s: the table file takes %zu bytes, capacity is %zu (*size has the length)",
                       __func__, *size, capacity);
    hb_dual_engine_file_write(e->options.model, &e->axes, e->d_b, e->fields, e->fields_size, e->nodes, bytes);
    return HB_OK;
}

hb_status hb_dual_engine_load(const hb_material *base, const hb_options *options, const void *bytes, size_t size,
                              hb_dual_engine **engine, hb_error *error)
{
    if (!base || !options || !bytes || !engine)
        return hb_plan_fail(error, HB_ERR_NULL, "%s: %s is NULL", __func__,
                            !base ? "base" : !options ? "options" : !bytes ? "bytes" : "engine");
    *engine = NULL;
    hb_plan *probe = NULL;
    hb_status st = probe_create(__func__, base, options, &probe, error);
    hb_dual_engine_axes axes;
    double d_b = 0.0;
    const unsigned char *values = NULL;
    hb_error why;
    if (st == HB_OK && (st = hb_dual_engine_file_read(probe, bytes, size, &axes, &d_b, &values, &why)) != HB_OK)
        hb_plan_fail(error, st, "%s: %s", __func__, why.message);
    if (st == HB_OK && check_axes(__func__, &axes, &why) != HB_OK)
        st = hb_plan_fail(error, HB_ERR_FILE, "%s (the file's axes)", why.message);
    hb_dual_engine *e = NULL;
    if (st == HB_OK)
        st = engine_alloc(__func__, probe, &axes, d_b, &e, error);
    hb_plan_destroy(probe);
    if (st != HB_OK)
        return st;
    for (size_t k = 0; k < e->node_count * PRIMARY; k++)
        e->nodes[k] = hb_dual_file_value(values, k);
    engine_floats(e);
    *engine = e;
    return HB_OK;
}

const float *hb_dual_engine_nodes(const hb_dual_engine *engine, size_t *count)
{
    if (count)
        *count = engine ? engine->node_count * HB_DUAL_ENGINE_NODE_FLOATS : 0;
    return engine ? engine->floats : NULL;
}

hb_status hb_dual_engine_constants(const hb_dual_engine *engine, double d_f, float constants[8])
{
    if (!engine || !constants)
        return hb_fail_null(__func__, !engine ? "engine" : "constants");
    if (!(d_f >= 0.0 && d_f <= 1.0))
        return hb_fail(HB_ERR_PARAM, "%s: d_f = %g is outside [0, 1]", __func__, d_f);
    const hb_dual_engine_axes *a = &engine->axes;
    const double values[8] = { a->thetas, a->roughnesses, a->roughness_min, a->roughness_max, a->absorptions,
                               1.0 - exp(-a->absorption_max), d_f, engine->d_b };
    for (int k = 0; k < 8; k++)
        constants[k] = (float)values[k];
    return HB_OK;
}

/* Position x along an axis of `count` nodes: the lower node and the weight of the upper, clamped. */
static void locate(double x, int count, int *lower, double *weight)
{
    x = fmin(fmax(x, 0.0), count - 1.0);
    int i = (int)x < count - 1 ? (int)x : count - 2;
    *lower = i, *weight = x - i;
}

/* The six hemisphere terms of one channel at theta node k, bilinear in roughness and exp(-sigma_a). */
static void lookup(const hb_dual_engine *e, int k, double roughness, double sigma_a, double v[PRIMARY])
{
    const hb_dual_engine_axes *a = &e->axes;
    int r, j;
    double wr, wj;
    locate((roughness - a->roughness_min) / (a->roughness_max - a->roughness_min) * (a->roughnesses - 1), a->roughnesses,
           &r, &wr);
    locate((1.0 - exp(-sigma_a)) / (1.0 - exp(-a->absorption_max)) * (a->absorptions - 1), a->absorptions, &j, &wj);
    for (int q = 0; q < PRIMARY; q++)
        v[q] = 0.0;
    for (int corner = 0; corner < 4; corner++) {
        int dr = corner & 1, dj = corner >> 1;
        double weight = (dr ? wr : 1.0 - wr) * (dj ? wj : 1.0 - wj);
        const double *n = node(e, r + dr, j + dj, k);
        for (int q = 0; q < PRIMARY; q++)
            v[q] += weight * n[q];
    }
}

/* The terms at theta node k: the lookup per channel, then eqs. 14-17. */
static hb_status node_terms(const hb_dual_engine *e, int k, double roughness, const double sigma_a[3], hb_dual_terms *t)
{
    for (int c = 0; c < CHANNELS; c++) {
        double v[PRIMARY];
        lookup(e, k, roughness, sigma_a[c], v);
        t->a_f[c] = v[0], t->a_b[c] = v[1], t->alpha_f[c] = v[2], t->beta_f2[c] = v[3], t->alpha_b[c] = v[4],
        t->beta_b2[c] = v[5];
        if (!(v[0] < 1.0))
            return hb_fail(HB_ERR_LIMIT,
                           "a_f = %.4f at theta %.4f (channel %d) is not below 1: the forward scatterings of eqs. 14-15 "
                           "diverge", v[0], theta_at(&e->axes, k), c);
        t->A_b[c] = hb_dual_back_energy(v[0], v[1]);
        t->delta_b[c] = hb_dual_back_shift(v[0], v[1], v[2], v[4]);
        t->sigma_b2[c] = hb_dual_back_variance(v[0], v[1], v[3], v[5], e->d_b);
    }
    return HB_OK;
}

/* The terms at theta: node_terms at the two nodes about it, linear between them (constant beyond
 * the outer nodes), as a per-material table of those nodes gives them. */
static hb_status engine_terms(const hb_dual_engine *e, double theta, double roughness, const double sigma_a[3],
                              hb_dual_terms *t)
{
    int k;
    double w;
    locate((theta + M_PI_2) * e->axes.thetas / M_PI - 0.5, e->axes.thetas, &k, &w);
    hb_dual_terms lower = { .struct_size = sizeof lower }, upper = { .struct_size = sizeof upper };
    hb_status st = node_terms(e, k, roughness, sigma_a, &lower);
    if (st == HB_OK)
        st = node_terms(e, k + 1, roughness, sigma_a, &upper);
    const double *x = lower.a_f, *y = upper.a_f;
    double *out = t->a_f;
    for (int q = 0; q < 9 * CHANNELS && st == HB_OK; q++) /* a_f .. sigma_b2: nine arrays of three, in order */
        out[q] = x[q] + w * (y[q] - x[q]);
    return st;
}

/* The thread's last failure again with the call's name before it (copied first: the message is
 * formatted into the same buffer). */
static hb_status prefixed(const char *call, hb_status st)
{
    hb_error last = *hb_last_error();
    return hb_fail(st, "%s: %s", call, last.message);
}

hb_status hb_dual_engine_terms(const hb_dual_engine *engine, double theta, double roughness, const double sigma_a[3],
                               hb_dual_terms *terms)
{
    if (!engine || !sigma_a || !terms)
        return hb_fail_null(__func__, !engine ? "engine" : !sigma_a ? "sigma_a" : "terms");
    if (terms->struct_size != sizeof *terms)
        return hb_fail(HB_ERR_VERSION, "%s: terms->struct_size = %zu; this release's is %zu", __func__,
                       terms->struct_size, sizeof *terms);
    if (!(fabs(theta) <= M_PI_2) || !(roughness > 0.0) || !isfinite(roughness))
        return hb_fail(HB_ERR_PARAM, "%s: theta = %g, roughness = %g: theta in [-pi/2, pi/2], roughness above 0",
                       __func__, theta, roughness);
    for (int c = 0; c < CHANNELS; c++)
        if (!(sigma_a[c] >= 0.0) || isinf(sigma_a[c]))
            return hb_fail(HB_ERR_PARAM, "%s: sigma_a[%d] = %g is not a finite absorption >= 0", __func__, c, sigma_a[c]);
    hb_dual_terms t = { .struct_size = sizeof t };
    hb_status st = engine_terms(engine, theta, roughness, sigma_a, &t);
    if (st != HB_OK)
        return prefixed(__func__, st);
    *terms = t;
    return HB_OK;
}

/* The first field other than absorption and roughness in which m differs from the family's base. */
static const char *differing_field(const hb_material *m, const hb_material *base)
{
    static const struct { const char *name; size_t offset; int count; } fields[] = {
        { "eta", offsetof(hb_material, eta), 1 },
        { "beta_m", offsetof(hb_material, beta_m), 1 },
        { "beta_n", offsetof(hb_material, beta_n), 1 },
        { "alpha", offsetof(hb_material, alpha), 1 },
        { "roughness", offsetof(hb_material, roughness), 1 },
        { "eccentricity", offsetof(hb_material, eccentricity), 1 },
        { "lobe_beta_m", offsetof(hb_material, lobe_beta_m), HB_MAX_LOBES },
        { "lobe_beta_n", offsetof(hb_material, lobe_beta_n), HB_MAX_LOBES },
        { "lobe_alpha", offsetof(hb_material, lobe_alpha), HB_MAX_LOBES },
        { "glint_scale", offsetof(hb_material, glint_scale), 1 },
        { "caustic_width", offsetof(hb_material, caustic_width), 1 },
        { "caustic_fade", offsetof(hb_material, caustic_fade), 1 },
        { "caustic_limit", offsetof(hb_material, caustic_limit), 1 },
    };
    for (size_t f = 0; f < sizeof fields / sizeof *fields; f++)
        for (int k = 0; k < fields[f].count; k++) {
            double x = ((const double *)((const char *)m + fields[f].offset))[k];
            double y = ((const double *)((const char *)base + fields[f].offset))[k];
            if (!(fabs(x - y) <= 1e-9 * fmax(fabs(x), fabs(y))))
                return fields[f].name;
        }
    if (m->ndf != base->ndf)
        return "ndf";
    return m->lobe_alpha_override != base->lobe_alpha_override ? "lobe_alpha_override" : NULL;
}

hb_status hb_dual_engine_table(const hb_dual_engine *engine, const hb_plan *plan, double d_f, hb_dual_table **table)
{
    if (!engine || !plan || !table)
        return hb_fail_null(__func__, !engine ? "engine" : !plan ? "plan" : "table");
    *table = NULL;
    const hb_model_ops *ops = hb_model_ops_of(engine->options.model);
    if (plan->options.model != engine->options.model || ops->lobes(&plan->options) != ops->lobes(&engine->options))
        return hb_fail(HB_ERR_PARAM, "%s: the plan's model and lobes are not the engine table's (%s, lobes 0x%x)",
                       __func__, ops->name, ops->lobes(&engine->options));
    hb_look look;
    ops->look(&plan->material, &look);
    hb_material m = plan->material;
    memcpy(m.sigma_a, engine->base.sigma_a, sizeof m.sigma_a);
    m.eumelanin = engine->base.eumelanin, m.pheomelanin = engine->base.pheomelanin;
    hb_look base_look;
    ops->look(&engine->base, &base_look);
    hb_error error;
    if (set_roughness(ops, &m, base_look.longitudinal, &error) != HB_OK)
        return hb_fail(HB_ERR_PARAM, "%s: %s", __func__, error.message);
    const char *differs = differing_field(&m, &engine->base);
    if (differs)
        return hb_fail(HB_ERR_PARAM, "%s: the plan's material differs from the engine table's family in %s", __func__,
                       differs);
    double sigma_a[3];
    hb_material_absorption(&plan->material, sigma_a);
    hb_dual_terms *terms = calloc((size_t)engine->axes.thetas, sizeof *terms);
    if (!terms)
        return hb_fail(HB_ERR_NOMEM, "%s: no memory for %d nodes", __func__, engine->axes.thetas);
    hb_status st = HB_OK;
    for (int k = 0; k < engine->axes.thetas && st == HB_OK; k++) {
        terms[k].struct_size = sizeof *terms;
        st = node_terms(engine, k, look.longitudinal, sigma_a, &terms[k]);
    }
    st = st == HB_OK ? hb_dual_table_from_terms(plan, engine->axes.thetas, terms, d_f, engine->d_b, table)
                     : prefixed(__func__, st);
    free(terms);
    return st;
}

/* Model and material options shared by the subcommands, named as in docs/conventions.md. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "cli_threads.h"

const char cli_model_options_help[] =
    "Model options:\n"
    "  --model deon|marschner|huang|chiang  scattering model (default deon; chiang: pbrt-v4's, near-field)\n"
    "  --term full|longitudinal       full f, or only dFH11's M_p of the R lobe (default full)\n"
    "  --lobes R,TT,TRT,TRRT,residual|all  orders p to include (default all: up to --pmax plus residual)\n"
    "  --quality fast|balanced|high|reference   reference runs the double-precision path\n"
    "  --isa auto|scalar|sse4.1|avx2|avx512|neon  instruction set (default auto, or $HB_ISA)\n"
    "  --i0 abramowitz|paper          I0 in dFH11 eq. 7: A&S 9.8.1/9.8.2, or the eq. 15 series\n"
    "  --pmax N                       dFH11: highest explicit order (default 3); 'all' lobes add the residual\n"
    "  --quadrature N                 dFH11: N_p's Gauss-Legendre order across the fibre, (N + 1) / 2 nodes\n"
    "                                 evaluated by symmetry (paper: 35; default: from quality and beta_n)\n"
    "  --detector-tolerance X         dFH11: truncation error of the Gaussian detector (default: from quality)\n"
    "  --absorption corrected|paper   path length 2 cos(gamma_t), or the printed 2 (1 + cos 2 gamma_t)\n"
    "  --r-fresnel offset|half-angle  dFH11 R lobe Fresnel: eq. 14 per offset (default, exact energy), or eq. 12 (paper)\n"
    "  --no-shadowing                 huang: G = 1 in R (default: separable Smith G1(w_i) G1(w_o));\n"
    "                                 TT and TRT keep G, without which they diverge\n"
    "  --pole-floor auto|bounded|paper  huang: f's 1 / cos(theta_o) bounded near the poles (auto: below\n"
    "                                 reference quality), or the paper's everywhere (docs/huang.md)\n"
    "  --r-integration auto|analytic|numeric  huang R lobe: App. A closed form (GGX, no G, circular) or Simpson\n"
    "  --r-panels N                   huang: Simpson panels in the peak-following variable (default: from quality)\n"
    "  --r-step X                     huang: the paper's rule instead, steps of X * roughness in phi_m (HHH22: 0.7)\n"
    "  --tt-trt auto|mc|table|reference  huang TT and TRT: a table on the quality's own grid, built at plan\n"
    "                                 creation (deterministic, real-time; seconds to minutes), Monte-Carlo/Simpson\n"
    "                                 (eqs. 31, 32), or nested quadrature (slow); auto (default): a table on the\n"
    "                                 finest grid that builds in about a second, mc where none does, reference at\n"
    "                                 --quality reference\n"
    "  --tt-panels N                  huang TT/TRT: Simpson panels over the entry azimuth (default: from quality)\n"
    "  --seed S                       huang TT/TRT: key of the Monte-Carlo numbers (with the row index; default 0)\n"
    "  --lobe-beta-m P=X  --lobe-beta-n P=X  --lobe-alpha P=X   per-lobe overrides for order P (repeatable)\n"
    "  --azimuthal quadrature|table|colour-table   dFH11 N_p per sample, or from a table built at plan\n"
    "                                 creation: the material's, or one for every hair colour\n"
    "  --table-tolerance X            dFH11 N_p table: midpoint error bound (default: from quality)\n"
    "  --table FILE.hbt               load the table of `hairbsdf bake` instead of building it (the same\n"
    "                                 material and options as the bake; implies --azimuthal table or --tt-trt table)\n"
    "  --threads N                    build tables on N threads (default 1)\n"
    "  --progress                     report a table build's progress on stderr\n"
    "  --tolerance X                  choose the configuration: the cheapest whose error (of the peak f) is at most X,\n"
    "                                 dropping lobes that cannot matter (see hairbsdf plan)\n"
    "  --budget-ns X                  choose the most accurate configuration that takes at most X ns per sample\n"
    "  --calibration FILE             costs and errors for those choices (bench/results/calibration.csv; default built in)\n"
    "Material options (default; valid range), angles in radians (docs/conventions.md):\n"
    "  --eta X                        index of refraction (1.55; (1, 10])\n"
    "  --sigma-a R,G,B                absorption per unit fibre radius (0,0,0; finite, >= 0)\n"
    "  --eumelanin X  --pheomelanin X pigment concentrations, added to sigma-a (0; finite, >= 0)\n"
    "  --colour R,G,B                 sigma-a for this hair colour (each in (0, 1]; CBTB16's fit at beta-n)\n"
    "  --melanin-colour R,G,B         eumelanin and pheomelanin for the nearest melanin hair to this colour\n"
    "  --beta-m X                     longitudinal roughness (0.1; [0.01, 3.162])\n"
    "  --beta-n X                     azimuthal roughness, dFH11 (0.3; [0.02, 3])\n"
    "  --alpha X                      cuticle tilt (0.035; [-0.2, 0.2])\n"
    "  --ndf ggx|beckmann  --roughness X   HHH22 microfacets (ggx, 0.1; [0.001, 1])\n"
    "  --eccentricity X               elliptical fibre, MJC03 and HHH22 (0; [0, 0.99])\n"
    "  --glint-scale X  --caustic-width X  --caustic-fade X  --caustic-limit X   MJC03 TRT caustics\n"
    "                                 (k_G 0.5, w_c 0.2618, Delta eta' 0.3, Delta h_M 0.5)\n";

void cli_model_args_default(cli_model_args *args)
{
    hb_material_default(&args->material);
    hb_options_default(&args->options);
    args->colour_to = CLI_COLOUR_NONE;
    args->table_path = NULL;
    args->threads = 1;
    args->progress = 0;
}

/* CBTB16's azimuthal roughness b in [0, 1] for the colour fit: the material's beta_n for CBTB16;
 * for the other models, whose beta_n is a Gaussian's standard deviation in radians, the b whose
 * logistic has that standard deviation, s(b) pi / sqrt(3) (s(b): CBTB16 eq. 8's fit), by bisection. */
static double colour_fit_beta_n(const cli_model_args *args)
{
    double beta_n = args->material.beta_n;
    if (args->options.model == HB_MODEL_CHIANG)
        return beta_n;
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 60; k++) {
        double b = 0.5 * (lo + hi);
        double s = 0.626657069 * (0.265 * b + 1.194 * b * b + 5.372 * pow(b, 22)); /* sqrt(pi / 8) (...) */
        if (s * 1.813799364 < beta_n) /* pi / sqrt(3) */
            lo = b;
        else
            hi = b;
    }
    return 0.5 * (lo + hi);
}

hb_status cli_material(const cli_model_args *args, hb_material *material, hb_error *error)
{
    *material = args->material;
    double b = colour_fit_beta_n(args);
    if (args->colour_to == CLI_COLOUR_SIGMA_A)
        return hb_absorption_from_colour(args->colour, b, material->sigma_a, error);
    if (args->colour_to == CLI_COLOUR_MELANIN)
        return hb_melanin_from_colour(args->colour, b, &material->eumelanin, &material->pheomelanin, error);
    return HB_OK;
}

hb_status cli_colour_spectrum(const cli_model_args *args, hb_absorption_spectrum *spectrum, hb_error *error)
{
    return hb_absorption_from_colour_spectral(args->colour, colour_fit_beta_n(args), spectrum, error);
}

void cli_build_hooks(const cli_model_args *args, hb_options *options)
{
    if (args->threads > 1)
        options->parallel = cli_parallel, options->parallel_context = (void *)&args->threads;
    if (args->progress)
        options->progress = cli_progress;
}

void *cli_read_table_file(const char *path, size_t *size, const char **why)
{
    struct stat st;
    *why = "it cannot be read";
    if (stat(path, &st) != 0)
        return NULL;
    if (!S_ISREG(st.st_mode)) {
        *why = "it is not a regular file";
        return NULL;
    }
    if ((unsigned long long)st.st_size > HB_TABLE_FILE_MAX_BYTES) {
        *why = "it is larger than any table file (HB_TABLE_FILE_MAX_BYTES)";
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t n = (size_t)st.st_size;
    unsigned char *bytes = malloc(n + 1); /* + 1: one byte past the stated size shows that it grew */
    if (!bytes || fread(bytes, 1, n + 1, f) != n || ferror(f)) {
        *why = bytes ? "it changed while it was read" : "there is no memory for it";
        free(bytes);
        bytes = NULL;
    }
    fclose(f);
    *size = n;
    return bytes;
}

hb_status cli_plan_create(const cli_model_args *args, const hb_options *options, hb_plan **plan, hb_error *error)
{
    hb_material material;
    hb_status st = cli_material(args, &material, error);
    if (st != HB_OK)
        return st;
    hb_options o = *options;
    cli_build_hooks(args, &o);
    if (!args->table_path)
        return hb_plan_create(&material, &o, plan, error);
    const char *why;
    o.table_file = cli_read_table_file(args->table_path, &o.table_file_size, &why);
    if (!o.table_file) {
        snprintf(error->message, sizeof error->message, "cannot read the table file %s: %s", args->table_path, why);
        return error->status = HB_ERR_FILE;
    }
    if (o.model == HB_MODEL_HUANG)
        o.tt_trt = HB_TT_TRT_TABLE;
    else if (o.azimuthal != HB_AZIMUTHAL_COLOUR_TABLE)
        o.azimuthal = HB_AZIMUTHAL_TABLE;
    st = hb_plan_create(&material, &o, plan, error);
    free((void *)o.table_file);
    return st;
}

/* A whole field as a finite number. strtod's ERANGE also flags a subnormal result, which is a
 * number (a range check then names the option's range); only an overflow is refused here. */
static int parse_number(const char *s, double *out)
{
    char *end;
    errno = 0;
    double x = strtod(s, &end);
    if (end == s || *end != '\0' || !isfinite(x))
        return 0;
    *out = x;
    return 1;
}

int cli_parse_u64(const char *s, unsigned long long *out)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (end == s || *end || s[0] == '-' || s[0] == '+' || errno == ERANGE)
        return 0;
    *out = v;
    return 1;
}

int cli_parse_range(const char *s, double lo, double hi, double *out)
{
    char *end;
    double v = strtod(s, &end);
    if (end == s || *end || !(v >= lo && v <= hi))
        return 0;
    *out = v;
    return 1;
}

static int parse_triple(const char *s, double out[3])
{
    char buf[256];
    if (strlen(s) >= sizeof buf)
        return 0;
    strcpy(buf, s);
    char *save = NULL, *tok = strtok_r(buf, ",", &save);
    for (int c = 0; c < 3; c++, tok = strtok_r(NULL, ",", &save))
        if (!tok || !parse_number(tok, &out[c]))
            return 0;
    return tok == NULL;
}

/* A whole field as an integer in [lo, hi]. */
static int parse_int(const char *s, int lo, int hi, int *out)
{
    char *end;
    errno = 0;
    long x = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || x < lo || x > hi)
        return 0;
    *out = (int)x;
    return 1;
}

const char *cli_lobe_name(int p)
{
    static const char *const names[HB_MAX_LOBES + 1] = { "R", "TT", "TRT", "TRRT", "p4", "p5", "p6", "p7", "residual" };
    return p >= 0 && p <= HB_LOBE_RESIDUAL ? names[p] : "?";
}

const char *cli_model_paper(hb_model model)
{
    static const char *const papers[] = { "MJC03", "dFH11", "HHH22", "CBTB16" }; /* hb_model's order */
    return (unsigned)model < sizeof papers / sizeof papers[0] ? papers[model] : "?";
}

/* Lobe names R, TT, TRT, TRRT, residual, or an order p as a number. */
static int parse_lobes(const char *s, unsigned *mask)
{
    static const char *const names[] = { "R", "TT", "TRT", "TRRT" };
    if (strcmp(s, "all") == 0) {
        *mask = HB_LOBES_DEFAULT;
        return 1;
    }
    char buf[128];
    if (strlen(s) >= sizeof buf)
        return 0;
    strcpy(buf, s);
    unsigned m = 0;
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        int found = 0, p;
        for (unsigned k = 0; k < sizeof names / sizeof names[0]; k++)
            if (strcmp(tok, names[k]) == 0) {
                m |= 1u << k;
                found = 1;
            }
        if (strcmp(tok, "residual") == 0) {
            m |= 1u << HB_LOBE_RESIDUAL;
            found = 1;
        } else if (!found && parse_int(tok, 0, HB_MAX_LOBES - 1, &p)) {
            m |= 1u << p;
            found = 1;
        }
        if (!found)
            return 0;
    }
    *mask = m;
    return m != 0;
}

/* Index of s in a NULL-terminated list, or -1. */
static int pick(const char *s, const char *const *choices)
{
    for (int k = 0; choices[k]; k++)
        if (strcmp(s, choices[k]) == 0)
            return k;
    return -1;
}

int cli_parse_model_option(int argc, char **argv, int *i, cli_model_args *args, char *err, size_t err_size)
{
    static const char *const numeric[] = { "--eta", "--eumelanin", "--pheomelanin", "--beta-m", "--beta-n",
                                           "--alpha", "--roughness", "--eccentricity", "--detector-tolerance",
                                           "--glint-scale", "--caustic-width", "--caustic-fade", "--caustic-limit",
                                           "--r-step", "--tolerance", "--budget-ns", "--table-tolerance", NULL };
    static const char *const with_value[] = { "--model", "--term", "--lobes", "--quality", "--isa", "--i0",
                                              "--ndf", "--sigma-a", "--pmax", "--quadrature", "--absorption",
                                              "--r-fresnel", "--r-integration", "--r-panels", "--tt-trt",
                                              "--tt-panels", "--seed", "--calibration", "--azimuthal", "--colour",
                                              "--melanin-colour", "--table", "--threads", "--pole-floor", NULL };
    static const char *const per_lobe[] = { "--lobe-beta-m", "--lobe-beta-n", "--lobe-alpha", NULL };
    static const char *const absorptions[] = { "corrected", "paper", NULL };
    static const char *const r_fresnels[] = { "offset", "half-angle", NULL };
    static const char *const pole_floors[] = { "auto", "bounded", "paper", NULL };
    static const char *const r_integrations[] = { "auto", "analytic", "numeric", NULL };
    static const char *const tt_trts[] = { "mc", "reference", "table", "auto", NULL };
    static const char *const azimuthals[] = { "quadrature", "table", "colour-table", NULL };
    static const char *const models[] = { "marschner", "deon", "huang", "chiang", NULL };
    static const char *const terms[] = { "full", "longitudinal", NULL };
    static const char *const qualities[] = { "fast", "balanced", "high", "reference", NULL };
    static const char *const i0s[] = { "abramowitz", "paper", NULL };
    static const char *const ndfs[] = { "ggx", "beckmann", NULL };

    if (strcmp(argv[*i], "--no-shadowing") == 0) {
        args->options.shadowing = HB_SHADOWING_NONE;
        return 1;
    }
    if (strcmp(argv[*i], "--progress") == 0) {
        args->progress = 1;
        return 1;
    }
    char name[64];
    const char *arg = argv[*i], *value = NULL, *eq = strchr(arg, '=');
    size_t len = eq ? (size_t)(eq - arg) : strlen(arg);
    if (len >= sizeof name)
        return 0;
    memcpy(name, arg, len);
    name[len] = '\0';
    int num = pick(name, numeric), other = pick(name, with_value), lobe_option = pick(name, per_lobe);
    if (num < 0 && other < 0 && lobe_option < 0)
        return 0;
    if (eq) {
        value = eq + 1;
    } else if (*i + 1 < argc) {
        value = argv[++*i];
    } else {
        snprintf(err, err_size, "%s needs a value", name);
        return -1;
    }

    hb_material *m = &args->material;
    hb_options *o = &args->options;
    double x;
    if (num >= 0) {
        if (!parse_number(value, &x)) {
            snprintf(err, err_size, "%s: '%s' is not a finite number", name, value);
            return -1;
        }
        double *const fields[] = { &m->eta, &m->eumelanin, &m->pheomelanin, &m->beta_m, &m->beta_n,
                                   &m->alpha, &m->roughness, &m->eccentricity, &o->detector_tolerance,
                                   &m->glint_scale, &m->caustic_width, &m->caustic_fade, &m->caustic_limit,
                                   &o->r_step, &o->tolerance, &o->budget_ns, &o->table_tolerance };
        *fields[num] = x;
        return 1;
    }
    if (lobe_option >= 0) { /* P=X */
        char order[8];
        const char *sep = strchr(value, '=');
        int p;
        if (!sep || (size_t)(sep - value) >= sizeof order || !parse_number(sep + 1, &x)) {
            snprintf(err, err_size, "%s: '%s' is not P=X (an order and a number)", name, value);
            return -1;
        }
        memcpy(order, value, (size_t)(sep - value));
        order[sep - value] = '\0';
        if (!parse_int(order, 0, HB_MAX_LOBES - 1, &p)) {
            snprintf(err, err_size, "%s: order '%s' is not in 0..%d", name, order, HB_MAX_LOBES - 1);
            return -1;
        }
        if (lobe_option == 0)
            m->lobe_beta_m[p] = x;
        else if (lobe_option == 1)
            m->lobe_beta_n[p] = x;
        else {
            m->lobe_alpha[p] = x;
            m->lobe_alpha_override |= 1u << p;
        }
        return 1;
    }
    int k = 0;
    const char *expected = NULL;
    if (strcmp(name, "--model") == 0) {
        if ((k = pick(value, models)) >= 0) o->model = (hb_model)k; else expected = "marschner, deon, huang or chiang";
    } else if (strcmp(name, "--term") == 0) {
        if ((k = pick(value, terms)) >= 0) o->term = (hb_term)k; else expected = "full or longitudinal";
    } else if (strcmp(name, "--quality") == 0) {
        if ((k = pick(value, qualities)) >= 0) o->quality = (hb_quality)k;
        else expected = "fast, balanced, high or reference";
    } else if (strcmp(name, "--i0") == 0) {
        if ((k = pick(value, i0s)) >= 0) o->i0 = (hb_i0)k; else expected = "abramowitz or paper";
    } else if (strcmp(name, "--ndf") == 0) {
        if ((k = pick(value, ndfs)) >= 0) m->ndf = (hb_ndf)k; else expected = "ggx or beckmann";
    } else if (strcmp(name, "--isa") == 0) {
        hb_isa isa = hb_isa_from_name(value);
        if (isa != HB_ISA_COUNT) o->isa = isa; else expected = "auto, scalar, sse4.1, avx2, avx512 or neon";
    } else if (strcmp(name, "--lobes") == 0) {
        if (!parse_lobes(value, &o->lobes)) expected = "a comma list of R, TT, TRT, TRRT, residual, orders 0-7, or all";
    } else if (strcmp(name, "--absorption") == 0) {
        if ((k = pick(value, absorptions)) >= 0) o->absorption = (hb_absorption)k; else expected = "corrected or paper";
    } else if (strcmp(name, "--r-fresnel") == 0) {
        if ((k = pick(value, r_fresnels)) >= 0) o->r_fresnel = (hb_r_fresnel)k; else expected = "offset or half-angle";
    } else if (strcmp(name, "--pole-floor") == 0) {
        if ((k = pick(value, pole_floors)) >= 0) o->pole_floor = (hb_pole_floor)k; else expected = "auto, bounded or paper";
    } else if (strcmp(name, "--r-integration") == 0) {
        if ((k = pick(value, r_integrations)) >= 0) o->r_integration = (hb_r_integration)k;
        else expected = "auto, analytic or numeric";
    } else if (strcmp(name, "--r-panels") == 0) {
        if (!parse_int(value, 2, HB_MAX_R_PANELS, &o->r_panels) || o->r_panels % 2) expected = "an even panel count";
    } else if (strcmp(name, "--tt-trt") == 0) {
        if ((k = pick(value, tt_trts)) >= 0) o->tt_trt = (hb_tt_trt)k; else expected = "auto, mc, table or reference";
    } else if (strcmp(name, "--tt-panels") == 0) {
        if (!parse_int(value, 2, HB_MAX_TT_PANELS, &o->tt_panels) || o->tt_panels % 2) expected = "an even panel count";
    } else if (strcmp(name, "--seed") == 0) {
        unsigned long long seed;
        if (cli_parse_u64(value, &seed)) o->seed = seed; else expected = "an integer from 0 to 2^64 - 1";
    } else if (strcmp(name, "--pmax") == 0) {
        if (!parse_int(value, 0, HB_MAX_LOBES - 1, &o->pmax)) expected = "an order from 0 to 7";
    } else if (strcmp(name, "--quadrature") == 0) {
        if (!parse_int(value, 1, HB_MAX_QUADRATURE_ORDER, &o->quadrature_order)) expected = "a quadrature order from 1 to 512";
    } else if (strcmp(name, "--calibration") == 0) {
        o->calibration = value;
    } else if (strcmp(name, "--azimuthal") == 0) {
        if ((k = pick(value, azimuthals)) >= 0) o->azimuthal = (hb_azimuthal)k;
        else expected = "quadrature, table or colour-table";
    } else if (strcmp(name, "--sigma-a") == 0) {
        if (!parse_triple(value, m->sigma_a)) expected = "three finite numbers R,G,B";
    } else if (strcmp(name, "--table") == 0) {
        args->table_path = value;
    } else if (strcmp(name, "--threads") == 0) {
        if (!parse_int(value, 1, 64, &args->threads)) expected = "a thread count from 1 to 64";
    } else if (strcmp(name, "--colour") == 0 || strcmp(name, "--melanin-colour") == 0) {
        args->colour_to = name[2] == 'c' ? CLI_COLOUR_SIGMA_A : CLI_COLOUR_MELANIN;
        if (!parse_triple(value, args->colour)) expected = "three numbers R,G,B in (0, 1]";
    }
    if (expected) {
        snprintf(err, err_size, "%s: '%s' is not %s", name, value, expected);
        return -1;
    }
    return 1;
}

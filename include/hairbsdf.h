/* hairbsdf: batched, fixed-budget evaluation of hair fibre scattering functions.
 * MIT licence (LICENSE); documentation in README.md and docs/.
 *
 * Frame (docs/conventions.md): y is the fibre tangent (root to tip), a direction is
 * w(theta, phi) = (sin(phi) cos(theta), sin(theta), cos(phi) cos(theta)),
 * w_i points to the light, w_o to the viewer. Every model returns
 * f(w_i, w_o) = S(w_i, w_o) cos(theta_i), so L_o = integral f L_i dw_i.
 *
 * Use: fill an hb_material, build an hb_plan once per material (this validates
 * everything and picks the kernel), then evaluate caller-owned structure-of-arrays
 * batches with it from any number of threads. Evaluation never allocates. */
#ifndef HAIRBSDF_H
#define HAIRBSDF_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The version of this header (the Makefile and CMake read it from here). The ABI promise (README):
 * while HB_VERSION_MAJOR is 0, a minor release may change the ABI and the soname names it
 * (libhairbsdf.so.0.MINOR), so a program never loads a library it was not built for; a patch release
 * keeps the ABI. Within a release, the structs with a struct_size grow only at their end: a program
 * built against an older header passes its smaller struct_size, and the library reads (hb_material,
 * hb_options) or writes (hb_table_view, hb_dual_terms) only that much. */
#define HB_VERSION_MAJOR 0
#define HB_VERSION_MINOR 6
#define HB_VERSION_PATCH 0
#define HB_VERSION_STRING "0.6.0"

/* HB_API marks what the library exports; the shared library exports nothing else. Define
 * HB_STATIC when linking the static library on Windows. */
#if defined(_WIN32) && !defined(HB_STATIC)
#if defined(HB_BUILDING_LIBRARY)
#define HB_API __declspec(dllexport)
#else
#define HB_API __declspec(dllimport)
#endif
#elif defined(__GNUC__) && !defined(_WIN32)
#define HB_API __attribute__((visibility("default")))
#else
#define HB_API
#endif

typedef enum hb_status {
    HB_OK = 0,
    HB_ERR_NULL,        /* a required pointer was NULL */
    HB_ERR_PARAM,       /* a parameter or an argument is out of range (the message names it) */
    HB_ERR_UNSUPPORTED, /* the plan's model, lobes, term or options do not offer this (docs/api.md's matrix) */
    HB_ERR_ISA,         /* the requested instruction set is not available on this CPU */
    HB_ERR_VERSION,     /* a struct_size from a newer header than this library's, or no release's */
    HB_ERR_NOMEM,       /* plan creation could not allocate */
    HB_ERR_FILE,        /* a table file is damaged, of another format or library version, or baked for another
                           material or options (the message names the difference) */
    HB_ERR_CANCELLED,   /* plan creation was cancelled by options.progress */
    HB_ERR_LIMIT,       /* what was asked costs more than its limit: a table's work, a tolerance no configuration
                           reaches, a budget none fits (the message names the limit and what it would take) */
    HB_ERR_BUFFER       /* a caller's buffer is smaller than the call's result (the call reports the size) */
} hb_status;

/* The library's version at run time, "major.minor.patch"; major, minor and patch (each may be NULL)
 * receive its numbers. Compare with HB_VERSION_* to detect a library older than the header. */
HB_API const char *hb_version(int *major, int *minor, int *patch);

/* A short constant description of a status code. */
HB_API const char *hb_status_string(hb_status status);

/* Detail for a failed call: the message names the call and the offending argument or parameter. */
typedef struct hb_error {
    hb_status status;
    char message[256];
} hb_error;

/* The calling thread's last failure: every call that returns a status other than HB_OK records it
 * here (the calls taking an hb_error also fill theirs), and a call that succeeds leaves it as it
 * was, so read it right after a failed call. Never NULL; {HB_OK, ""} before any failure. */
HB_API const hb_error *hb_last_error(void);

/* MJC03, dFH11, HHH22 and CBTB16 (Chiang, Bitterli, Tappan and Burley 2016, as pbrt-v4's HairBxDF;
 * docs/chiang.md). */
typedef enum hb_model { HB_MODEL_MARSCHNER, HB_MODEL_DEON, HB_MODEL_HUANG, HB_MODEL_CHIANG } hb_model;

/* Orders p of scattering; a lobe set is a bit mask of (1u << p). HB_LOBE_RESIDUAL stands
 * for every order above the plan's pmax, folded into one lobe (dFH11; docs/deon.md). */
enum { HB_LOBE_R = 0, HB_LOBE_TT = 1, HB_LOBE_TRT = 2, HB_LOBE_TRRT = 3, HB_MAX_LOBES = 8,
       HB_LOBE_RESIDUAL = HB_MAX_LOBES };
#define HB_LOBES_DEFAULT 0u /* the model's full set: for dFH11 every order up to pmax plus the residual */
#define HB_LOBE_BIT(p) (1u << (p)) /* the lobe set of order p: HB_LOBE_BIT(HB_LOBE_R) | HB_LOBE_BIT(HB_LOBE_TT) */

typedef enum hb_ndf { HB_NDF_GGX, HB_NDF_BECKMANN } hb_ndf;

/* Material parameters (docs/conventions.md). hb_material_default() fills the defaults. */
typedef struct hb_material {
    size_t struct_size;  /* sizeof(hb_material), set by hb_material_default; an older header's is accepted */
    double eta;          /* index of refraction, default 1.55 */
    double sigma_a[3];   /* RGB absorption per unit fibre radius, default 0 */
    double eumelanin;    /* concentrations; their absorption (dFH11 sec. 6.1) adds to sigma_a */
    double pheomelanin;
    double beta_m;       /* longitudinal roughness in radians (dFH11: v = beta_m^2), default 0.1 */
    double beta_n;       /* azimuthal roughness in radians (dFH11), default 0.3 */
    double alpha;        /* cuticle scale tilt in radians, default 0.035; docs/conventions.md has the per-model shifts */
    hb_ndf ndf;          /* HHH22 microfacet distribution, default GGX */
    double roughness;    /* HHH22 microfacet roughness, default 0.1 */
    double eccentricity; /* elliptical fibre (HHH22, MJC03), default 0 */
    /* Per-lobe overrides, index p. Roughness 0 means "derived": dFH11 uses beta_m and beta_n
     * for every lobe. A shift applies when bit p of lobe_alpha_override is set, in the model's
     * own terms (dFH11: M_p at theta_o - alpha_p; MJC03: the mean of M_p in theta_h); otherwise
     * dFH11 shifts by alpha_R = -2 alpha, alpha_TT = alpha, alpha_TRT = 3 alpha, 0 above, and
     * MJC03's R lobe is centred at theta_h = -alpha. */
    double lobe_beta_m[HB_MAX_LOBES];
    double lobe_beta_n[HB_MAX_LOBES];
    double lobe_alpha[HB_MAX_LOBES];
    unsigned lobe_alpha_override;
    /* MJC03 TRT caustic treatment (its sec. 4.3 and Table 1; docs/marschner.md): near a
     * caustic the cubic's N_TRT is faded out over a Gaussian of width caustic_width and a
     * glint of glint_scale * A(h_c) * dh * that Gaussian is added, dh at most caustic_limit;
     * the caustic fades out over eta' in [2, 2 + caustic_fade] as it merges at phi = 0. */
    double glint_scale;   /* k_G, default 0.5 (MJC03: 0.5 to 5) */
    double caustic_width; /* w_c in radians, default 15 degrees (MJC03: 10 to 25 degrees) */
    double caustic_fade;  /* Delta eta', default 0.3 (MJC03: 0.2 to 0.4) */
    double caustic_limit; /* Delta h_M, default 0.5 (MJC03: 0.5) */
} hb_material;

HB_API void hb_material_default(hb_material *material);

/* The material for model `to` that looks as close as the two models allow to `material` under model
 * `from` (docs/conventions.md, "One look across models"): the R lobe's longitudinal standard
 * deviation, the azimuthal spread as a Gaussian's standard deviation and the highlight's shift are
 * kept; beta_m, beta_n and alpha (HHH22: roughness and alpha) are rewritten in the target's terms,
 * the rest copied. HB_ERR_PARAM when the look is beyond the target's range (CBTB16's scales end at
 * 1), HB_ERR_UNSUPPORTED for a material with per-lobe overrides (each model's own terms). */
HB_API hb_status hb_material_convert(const hb_material *material, hb_model from, hb_model to, hb_material *converted,
                                     hb_error *error);

/* sigma_a of the material: sigma_a plus the melanin absorption of dFH11 sec. 6.1. */
HB_API void hb_material_absorption(const hb_material *material, double sigma_a_rgb[3]);

/* The absorption per unit radius that gives a fibre of CBTB16 azimuthal roughness beta_n in [0, 1]
 * the multiply-scattered colour rgb (each channel in (0, 1]): CBTB16 eq. 9's fit, as pbrt-v4's
 * SigmaAFromReflectance. Returns HB_ERR_PARAM (naming the channel) outside those ranges. */
HB_API hb_status hb_absorption_from_colour(const double rgb[3], double beta_n, double sigma_a_rgb[3], hb_error *error);

/* Eumelanin and pheomelanin concentrations (both >= 0) whose absorption (dFH11 sec. 6.1) comes
 * closest to hb_absorption_from_colour's for rgb and beta_n, closest in log colour (least squares
 * with each channel weighted by 1 / sqrt(sigma_a): d log C = -d sqrt(sigma_a) / (2 sigma_a) under
 * CBTB16's fit). Melanins make browns, reds and blacks: a colour outside that range (a blue, a
 * grey) gets the nearest such hair (docs/conventions.md gives the error). */
HB_API hb_status hb_melanin_from_colour(const double rgb[3], double beta_n, double *eumelanin, double *pheomelanin,
                                        hb_error *error);

/* The spectral mode of hb_melanin_from_colour (docs/spectral.md), for a spectral renderer: the
 * concentrations whose colour as such a renderer shows it comes closest to rgb in log colour. That
 * colour is CBTB16 eq. 9's colour at the melanins' absorption per wavelength
 * (hb_melanin_absorption_spectral), reduced to linear sRGB under D65 (CIE 1931, 41 bands from 380 to
 * 780 nm), each channel over white's; found by 40 damped Gauss-Newton steps from
 * hb_melanin_from_colour's concentrations. The same ranges and refusals as hb_melanin_from_colour. */
HB_API hb_status hb_melanin_from_colour_spectral(const double rgb[3], double beta_n, double *eumelanin,
                                                 double *pheomelanin, hb_error *error);

/* The spectral mode of hb_absorption_from_colour (docs/spectral.md), for any colour, dyed ones
 * included: a smooth absorption spectrum whose colour in a spectral renderer (CBTB16 eq. 9's colour
 * per wavelength, reduced as hb_melanin_from_colour_spectral reduces it) comes closest to rgb in log
 * colour. Eq. 9's colour per wavelength is a sigmoid of a quadratic in wavelength (Jakob and Hanika
 * 2019's smooth uplift), found by damped Gauss-Newton from a flat spectrum; the same ranges and
 * refusals as hb_absorption_from_colour. hb_absorption_spectrum_at gives the absorption per unit
 * radius at a wavelength in [300, 1000] nm, for a spectral call's sigma_a. */
typedef struct hb_absorption_spectrum {
    double shape[3]; /* the quadratic's coefficients in x = (lambda - 580 nm) / 200 nm */
    double depth;    /* eq. 9's d(beta_n) */
} hb_absorption_spectrum;
HB_API hb_status hb_absorption_from_colour_spectral(const double rgb[3], double beta_n,
                                                    hb_absorption_spectrum *spectrum, hb_error *error);
HB_API hb_status hb_absorption_spectrum_at(const hb_absorption_spectrum *spectrum, double wavelength,
                                           double *sigma_a);

/* Speed/accuracy levels: error targets of about 1e-2, 1e-3 and 1e-4 relative to the
 * double reference for N_p (dFH11: the node count follows from beta_n). dFH11's M_p is
 * formed in float at FAST and BALANCED (relative error about 1e-6 on the lobe, 2e-5 far in
 * its tail) and with double where it matters from HIGH up (1e-6 everywhere; docs/deon.md). */
typedef enum hb_quality {
    HB_QUALITY_FAST,
    HB_QUALITY_BALANCED,
    HB_QUALITY_HIGH,
    HB_QUALITY_REFERENCE /* the scalar double-precision path that converges to the paper */
} hb_quality;

typedef enum hb_isa {
    HB_ISA_AUTO = 0, /* best available, or the HB_ISA environment variable */
    HB_ISA_SCALAR,
    HB_ISA_SSE41,
    HB_ISA_AVX2,   /* AVX2 + FMA */
    HB_ISA_AVX512, /* AVX-512F */
    HB_ISA_NEON,
    HB_ISA_COUNT
} hb_isa;

/* What a plan evaluates. */
typedef enum hb_term {
    HB_TERM_FULL,         /* f, the whole BCSDF times cos(theta_i) */
    HB_TERM_LONGITUDINAL  /* the R lobe's longitudinal factor T = f / N_R, in every channel: dFH11's
                             M_p(v_R, theta_i, theta_o - alpha_R) (eq. 7), or MJC03's
                             g(alpha_R, beta_R; theta_h) cos(theta_i) / cos^2(theta_d) */
} hb_term;

/* The modified Bessel function I0 inside dFH11 eq. 7. */
typedef enum hb_i0 {
    HB_I0_ABRAMOWITZ, /* A&S 9.8.1 / 9.8.2 in log space: accurate for v from 1e-6 to 10 */
    HB_I0_PAPER       /* the 10-term series of dFH11 eq. 15: too small for large arguments (small v) */
} hb_i0;

/* Absorption path length inside a unit-radius fibre (docs/conventions.md). */
typedef enum hb_absorption {
    HB_ABSORPTION_CORRECTED, /* 2 cos(gamma_t) per traversal (HHH22 sec. 3.1.2) */
    HB_ABSORPTION_PAPER      /* T = exp(-2 mu_a (1 + cos 2 gamma_t)) as printed in MJC03 / dFH11 */
} hb_absorption;

/* The Fresnel factor of dFH11's R lobe. The default makes a lossless fibre conserve energy
 * (white furnace E = 1 to 1e-4); the paper's eq. 12 leaves E in about [0.92, 1.08]. */
typedef enum hb_r_fresnel {
    HB_R_FRESNEL_OFFSET,    /* eq. 14 at each offset h, like the other lobes: sum_p A(p, h) = 1, exact energy */
    HB_R_FRESNEL_HALF_ANGLE /* eq. 12: at half the angle between w_i and w_o (the paper) */
} hb_r_fresnel;

/* HHH22 shadowing-masking at the microsurface (eq. 12's G). */
typedef enum hb_shadowing {
    HB_SHADOWING_SMITH, /* separable Smith G = G1(w_i) G1(w_o), each relative to the mesonormal (the default) */
    HB_SHADOWING_NONE   /* G = 1 in the R lobe, what HHH22 App. A integrates in closed form; TT and TRT
                           keep G at their interfaces, where G = 1 makes their integrals diverge */
} hb_shadowing;

/* HHH22 at the poles: f's 1 / cos(theta_o) (eqs. 10, 12, 28) grows without bound as w_o turns toward
 * the fibre axis where the scales or a rough surface without G still collect light (docs/huang.md,
 * "At the poles"). The bound keeps cos(theta_o) above half the width those show at the pole. */
typedef enum hb_pole_floor {
    HB_POLE_FLOOR_AUTO,    /* bounded below HB_QUALITY_REFERENCE, the paper's at HB_QUALITY_REFERENCE */
    HB_POLE_FLOOR_BOUNDED, /* bounded at every quality, the reference included */
    HB_POLE_FLOOR_PAPER    /* the paper's 1 / cos(theta_o) at every quality, floored at 1e-8 (the pole itself) */
} hb_pole_floor;

/* How HHH22's R lobe integrates over the azimuth phi_m of the macro/mesonormal (eq. 12). */
typedef enum hb_r_integration {
    HB_R_INTEGRATION_AUTO,     /* analytic where it is exact (GGX, no shadowing, circular), else numeric */
    HB_R_INTEGRATION_ANALYTIC, /* App. A, eq. 43 (44 for alpha = 0): GGX, no shadowing, circular only */
    HB_R_INTEGRATION_NUMERIC   /* composite Simpson over the visible window (r_panels, r_step) */
} hb_r_integration;

/* How HHH22's TT and TRT lobes (eqs. 23, 24: 3D and 5D integrals) are evaluated. */
typedef enum hb_tt_trt {
    HB_TT_TRT_MC,       /* the paper's combined Monte-Carlo/Simpson estimator (eqs. 31, 32): Simpson over
                           the entry azimuth, one internal path per node from a counter-based generator keyed
                           by the seed and the sample's index in the batch; unbiased for Simpson's sum */
    HB_TT_TRT_REFERENCE, /* nested quadrature in double (slow: for tests and accuracy tables) */
    HB_TT_TRT_TABLE,     /* deterministic and real-time: interpolated from a table of f_TT + f_TRT that plan
                            creation builds for the material (3D, 4D for elliptical fibres; HHH22 sec. 3.4.2),
                            its resolution and build cost from quality and roughness (docs/huang.md gives both and the error); not with HB_QUALITY_REFERENCE */
    HB_TT_TRT_AUTO       /* hb_options_default's: below HB_QUALITY_REFERENCE the table (deterministic) on the
                            finest grid up to the quality's that builds in about a second, else the Monte-Carlo
                            estimator; the nested quadrature at HB_QUALITY_REFERENCE. hb_plan_describe names it */
} hb_tt_trt;

/* How dFH11's azimuthal terms N_p (eq. 10) are evaluated. */
typedef enum hb_azimuthal {
    HB_AZIMUTHAL_QUADRATURE, /* the plan's Gauss-Legendre rule at every sample (the default) */
    HB_AZIMUTHAL_TABLE,      /* bilinear in a table over (sqrt(cos(theta_d)), |phi|) per group of lobes sharing one M_p
                                (dFH11 sec. 6), built at plan creation with that rule; its resolution is refined
                                until the interpolation error at cell midpoints is below table_tolerance of each
                                group's peak (hb_plan_table). Evaluation only: sampling keeps the quadrature.
                                With the default R Fresnel (HB_R_FRESNEL_OFFSET) only */
    HB_AZIMUTHAL_COLOUR_TABLE /* one table for every hair colour: N per M_p group for one channel over
                                (sqrt(cos(theta_d)), |phi|, exp(-sigma_a / 2)) with sigma_a from 0 to
                                HB_COLOUR_TABLE_SIGMA_MAX (N of a channel depends on that channel's absorption
                                alone), looked up at each channel's absorption: the plan's, or each sample's
                                (hb_eval_angles_absorption). Refined until the midpoint error is below
                                table_tolerance of each group's peak over all absorptions; otherwise as
                                HB_AZIMUTHAL_TABLE (docs/engines.md) */
} hb_azimuthal;

/* The colour table's absorption range: black hair (eumelanin 8 and pheomelanin 4) has sigma_a 15.2 in
 * blue; a larger absorption is looked up as this one. */
#define HB_COLOUR_TABLE_SIGMA_MAX 16.0

/* Callbacks of a long plan creation (hb_options.progress and .parallel). */
typedef int (*hb_progress_fn)(void *context, double fraction);
typedef void (*hb_task_fn)(void *task_context, int index);
typedef void (*hb_parallel_fn)(void *context, int count, hb_task_fn task, void *task_context);

typedef struct hb_options {
    size_t struct_size; /* sizeof(hb_options), set by hb_options_default; an older header's is accepted */
    hb_model model;     /* default HB_MODEL_DEON */
    unsigned lobes;     /* bit mask of (1u << p) and (1u << HB_LOBE_RESIDUAL), HB_LOBES_DEFAULT for the full set */
    hb_term term;       /* default HB_TERM_FULL */
    hb_quality quality; /* default HB_QUALITY_BALANCED */
    hb_isa isa;         /* default HB_ISA_AUTO */
    hb_i0 i0;           /* default HB_I0_ABRAMOWITZ */
    int pmax;           /* dFH11: highest explicit order, 0..7 (default 3, TRRT) */
    hb_absorption absorption; /* default HB_ABSORPTION_CORRECTED */
    int quadrature_order;     /* dFH11 N_p: order of the Gauss-Legendre rule in gamma_i across the fibre
                                 (h = sin gamma_i in [-1, 1]; (order + 1) / 2 nodes are evaluated, by
                                 symmetry); 0 = from quality and beta_n, else 1..HB_MAX_QUADRATURE_ORDER */
    double detector_tolerance; /* dFH11 D_p truncation error bound; 0 = from quality */
    hb_r_fresnel r_fresnel;    /* default HB_R_FRESNEL_OFFSET */
    hb_shadowing shadowing;    /* HHH22, default HB_SHADOWING_SMITH */
    hb_r_integration r_integration; /* HHH22 R lobe, default HB_R_INTEGRATION_AUTO */
    /* HHH22 numeric R lobe. r_step = 0: Simpson with r_panels panels (0 = from quality) in a
     * variable that follows the NDF's peak, so the count is the same for every roughness (docs/huang.md). r_step > 0: the paper's rule, uniform steps of at most r_step * roughness in phi_m
     * (HHH22 sec. 3.4.2 uses 0.7); every sample then pays for the widest window, 2 ceil(pi / (2 r_step
     * roughness)) panels, so the cost is fixed by the plan and grows as 1 / roughness. */
    int r_panels;
    double r_step;
    /* HHH22 TT and TRT. tt_panels: Simpson panels over the entry window (even; 0 = from quality and
     * roughness, for the table twice as many at fast and balanced: docs/huang.md); seed: keys the
     * Monte-Carlo numbers, so the same seed and sample index give the same value on every ISA
     * (change it per frame to accumulate), and the table's lattice shifts. */
    hb_tt_trt tt_trt;
    int tt_panels;
    unsigned long long seed;
    hb_azimuthal azimuthal;  /* dFH11, default HB_AZIMUTHAL_QUADRATURE */
    double table_tolerance;  /* dFH11 N_p table: 0 = from quality (1e-2, 1e-3, 1e-4), else in [1e-6, 0.5] */
    /* Plans that choose their own configuration (docs/engines.md;
     * hb_plan_describe says what was chosen and why). tolerance > 0: the cheapest configuration whose
     * expected error, relative to the material's peak f, is at most this; lobes whose largest value
     * (measured at plan creation on a grid of directions) cannot matter are dropped (dFH11, MJC03).
     * budget_ns > 0: the most accurate configuration whose calibrated cost per sample on the plan's ISA
     * fits. The two exclude each other; each overrides quality, quadrature_order and azimuthal (and
     * tt_trt for HHH22). Costs and errors come from `calibration`, a CSV written by `make bench`
     * (bench/results/calibration.csv), or from the table built in (NULL); costs are cycles, taken at
     * the clock hb_cpu_clock_ghz measures at plan creation (docs/engines.md). */
    double tolerance;
    double budget_ns;
    const char *calibration;
    /* A table file (hb_table_save's bytes) to load instead of building the plan's table: plan creation
     * checks its format, checksum, model and its table version, material and options against this plan's
     * and copies its values (the bytes may be freed afterwards), or refuses with HB_ERR_FILE. A file
     * is read by every release whose model's table version is the file's (docs/engines.md). Only for
     * plans that have a table (dFH11 azimuthal = table, HHH22 tt_trt = table), not with tolerance or
     * budget_ns; at most HB_TABLE_FILE_MAX_BYTES. NULL: the table is built. */
    const void *table_file;
    size_t table_file_size;
    /* Long plan creations (table builds; HHH22's TT/TRT table takes seconds at high quality). progress,
     * if not NULL, is called on the creating thread as the build goes, with an estimate of the fraction
     * done (non-decreasing, 1 at the end); returning nonzero cancels it, and hb_plan_create returns
     * HB_ERR_CANCELLED. parallel, if not NULL, runs a part of the build as `count` independent tasks:
     * it must call task(task_context, k) once for every k in [0, count), on any threads in any order,
     * and return when all have returned (an engine's job system; the CLI's --threads). The table is
     * the same bit for bit however its tasks run. Plans without a table call neither. */
    hb_progress_fn progress;
    void *progress_context;
    hb_parallel_fn parallel;
    void *parallel_context;
    hb_pole_floor pole_floor; /* HHH22, default HB_POLE_FLOOR_AUTO */
} hb_options;

#define HB_MAX_TT_PANELS 2048

#define HB_MAX_R_PANELS 16384

#define HB_MAX_QUADRATURE_ORDER 512
#define HB_MAX_DETECTOR_TERMS 16

HB_API void hb_options_default(hb_options *options);

typedef struct hb_plan hb_plan;

/* Validates material and options and builds an immutable plan. On failure returns
 * the status, leaves *plan NULL and, if error is not NULL, fills it. */
HB_API hb_status hb_plan_create(const hb_material *material, const hb_options *options, hb_plan **plan,
                         hb_error *error);
HB_API void hb_plan_destroy(hb_plan *plan);

/* What the plan simulates and what it skipped, in plain words: model, lobes, quadrature, detector,
 * tables, ISA; for a tolerance or budget plan also the lobes dropped (with their measured share of
 * the peak), the configuration chosen, its expected error and expected ns per sample. Writes at most
 * size bytes (always terminated); returns the length the whole text needs, like snprintf. */
HB_API size_t hb_plan_describe(const hb_plan *plan, char *text, size_t size);

/* The instruction set the plan's kernel uses (never HB_ISA_AUTO). */
HB_API hb_isa hb_plan_isa(const hb_plan *plan);

/* Caller-owned structure-of-arrays batches. */
typedef struct hb_angles_soa {
    const float *theta_i, *phi_i, *theta_o, *phi_o; /* radians */
} hb_angles_soa;

typedef struct hb_vectors_soa {
    const float *wi_x, *wi_y, *wi_z, *wo_x, *wo_y, *wo_z; /* unit vectors in the fibre frame */
} hb_vectors_soa;

typedef struct hb_rgb_soa {
    float *r, *g, *b;
} hb_rgb_soa;

/* Per-call report. A sample is invalid when an angle is NaN or +-Inf, |theta| exceeds
 * pi/2 (as a float, 1.57079637f), |phi| exceeds HB_PHI_LIMIT (phi is wrapped into
 * (-pi, pi], and a float that large has no sub-radian precision left), or a vector is not
 * finite or its squared length differs from 1 by more than HB_UNIT_TOLERANCE. Invalid
 * samples get f = 0 in every channel. */
#define HB_UNIT_TOLERANCE 1e-3f
#define HB_PHI_LIMIT 1e4f
typedef struct hb_eval_report {
    size_t invalid;
} hb_eval_report;

/* Evaluate n samples. report may be NULL. Output arrays must not alias inputs. The batch entry
 * points (eval, sample, pdf) run with subnormal floats flushed to zero and restore the caller's
 * floating-point mode before returning: results below FLT_MIN are 0. */
HB_API hb_status hb_eval_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa out,
                         hb_eval_report *report);
HB_API hb_status hb_eval_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa out,
                          hb_eval_report *report);

/* Per-sample absorption, for hair whose colour varies per strand in one batch: f as hb_eval_angles
 * (hb_eval_vectors) gives it, with the material's absorption (sigma_a and melanins) replaced at sample
 * k by sigma_a.r[k], .g[k], .b[k] per unit radius (hb_melanin_absorption turns concentrations into
 * it); roughness, eta, tilt, lobes and quality stay the plan's, and so does the fixed work per
 * sample. A sample is also invalid when an absorption is NaN, negative or infinite. For dFH11
 * quadrature and colour-table plans, MJC03 (HB_TERM_FULL) and CBTB16 (its far field here, its near
 * field in hb_eval_near_absorption); HB_ERR_UNSUPPORTED for the others: a material's own N_p table
 * (HB_AZIMUTHAL_TABLE) holds the plan's own absorption, HHH22's R lobe does not depend on it
 * (hb_eval_angles) and its TT and TRT have no per-sample path, and reference plans have none
 * (compare with a reference plan per material). A tolerance or budget plan chose its lobes for its own
 * material. */
typedef struct hb_absorption_soa {
    const float *r, *g, *b;
} hb_absorption_soa;
HB_API hb_status hb_eval_angles_absorption(const hb_plan *plan, size_t n, hb_angles_soa in, hb_absorption_soa sigma_a,
                                           hb_rgb_soa out, hb_eval_report *report);
HB_API hb_status hb_eval_vectors_absorption(const hb_plan *plan, size_t n, hb_vectors_soa in,
                                            hb_absorption_soa sigma_a, hb_rgb_soa out, hb_eval_report *report);

/* The absorption of eumelanin and pheomelanin concentrations (dFH11 sec. 6.1), as
 * hb_material_absorption adds it to sigma_a. */
HB_API void hb_melanin_absorption(double eumelanin, double pheomelanin, double sigma_a[3]);

/* The same at one wavelength in [300, 1000] nm (docs/spectral.md): the concentrations times Donner
 * and Jensen 2006's cross-sections, eumelanin's as lambda^-3.33 and pheomelanin's as lambda^-4.75,
 * each scaled (its value at 550 nm per unit radius) so that a fibre's spectral transmittance
 * reduced to sRGB (CIE 1931, D65, 41 bands from 380 to 780 nm) comes closest to dFH11's RGB
 * cross-sections above; the RGB form stays the library's default. HB_ERR_PARAM outside the range or
 * for a negative or non-finite concentration. */
HB_API hb_status hb_melanin_absorption_spectral(double eumelanin, double pheomelanin, double wavelength,
                                                double *sigma_a);

/* Near-field evaluation (CBTB16, dFH11): each sample also gives h in [-1, 1], the signed offset
 * across the fibre's width at which w_o's ray meets it (docs/chiang.md: h's sign and pbrt's).
 * hb_eval_angles of the same plan is the far-field f, the mean over h (docs/deon.md for dFH11's
 * near field). A sample is invalid as in hb_eval_angles, or when h is NaN or |h| > 1. Plans of models
 * without a near field (MJC03, HHH22) or of HB_TERM_LONGITUDINAL return HB_ERR_UNSUPPORTED. */
typedef struct hb_near_soa {
    const float *theta_i, *phi_i, *theta_o, *phi_o, *h;
} hb_near_soa;
HB_API hb_status hb_eval_near(const hb_plan *plan, size_t n, hb_near_soa in, hb_rgb_soa out, hb_eval_report *report);
/* The near field at each sample's absorption, as hb_eval_angles_absorption is the far field's: sample k
 * at h[k] with sigma_a.r[k], .g[k], .b[k] per unit radius (an absorption that is NaN, negative or
 * infinite makes an invalid sample). The plans of hb_eval_near. */
HB_API hb_status hb_eval_near_absorption(const hb_plan *plan, size_t n, hb_near_soa in, hb_absorption_soa sigma_a,
                                         hb_rgb_soa out, hb_eval_report *report);

/* Importance sampling, for path tracers (docs/sampling.md). Given w_o (toward the viewer) and
 * uniform random numbers, hb_sample_angles draws w_i (toward the light) with a density close
 * to f(w_i, w_o), and returns w_i, its solid-angle pdf and the weight f / pdf per channel (so an
 * estimate of L_o is the mean of weight * L_i). hb_pdf_angles returns the same pdf for given
 * directions, for multiple importance sampling. Sampling reads hb_plan_sample_dimensions(plan)
 * numbers per sample, u[0][k], u[1][k], ...; a plan without a sampler (the model or term has
 * none yet) returns HB_ERR_UNSUPPORTED. Invalid samples (a direction as in hb_eval_angles, or a
 * u outside [0, 1] or NaN) get theta_i = phi_i = 0, pdf 0 and weight 0 and are counted.
 * The reverse use (w_o given w_i, for light tracing) is the same call with the two directions'
 * roles swapped; it samples f(w_o, w_i), which equals f(w_i, w_o) where the model is reciprocal
 * (dFH11 with alpha = 0; docs/engines.md).
 * HHH22 plans with TT or TRT (not HB_QUALITY_REFERENCE) read 8 numbers and trace one path through
 * the fibre from w_o (sec. 3.4.1): the weight is that path's throughput over the lobe choice, whose
 * mean is the mean of f / pdf (unbiased, with the cuticle tilt too: docs/sampling.md); the pdf is eq. 33 estimated with one path per Simpson node from
 * the seed and the sample's index, so hb_pdf_angles at the same index returns the sampled pdf.
 * Such an estimate has the true pdf as its mean but can be 0 where the drawn paths of every node miss
 * w_i, at a sample whose weight is > 0 (7e-3 of samples at fast quality and roughness 0.6, 7e-4 at
 * balanced, 5e-5 at high): hb_plan_pdf_is_estimate says which plans estimate it, and docs/sampling.md
 * how a renderer's multiple importance sampling treats those samples. */
#define HB_SAMPLE_DIMENSIONS 8 /* the most numbers any sampler of this version reads */

/* The sampling calls take their streams by pointer. u points to the caller's array of
 * hb_plan_sample_dimensions(plan) planes, u[d][k] uniform in [0, 1) for sample k: a later model
 * that reads more numbers needs a longer array, not another struct. */
typedef struct hb_sample_in {
    const float *theta_o, *phi_o;
    const float *const *u;
} hb_sample_in;

typedef struct hb_sample_out {
    float *theta_i, *phi_i;
    float *pdf;        /* per unit solid angle */
    hb_rgb_soa weight; /* f(w_i, w_o) / pdf (HHH22 with TT or TRT: an unbiased estimate of it) */
} hb_sample_out;

HB_API int hb_plan_sample_dimensions(const hb_plan *plan); /* 0 when the plan cannot sample */
HB_API int hb_plan_pdf_is_estimate(const hb_plan *plan); /* 1: the pdf is a Monte-Carlo estimate (above); 0: exact */
HB_API hb_status hb_sample_angles(const hb_plan *plan, size_t n, const hb_sample_in *in, const hb_sample_out *out,
                                  hb_eval_report *report);
HB_API hb_status hb_pdf_angles(const hb_plan *plan, size_t n, hb_angles_soa in, float *pdf, hb_eval_report *report);

/* The same with fibre-frame unit vectors (as hb_eval_vectors; a vector is valid as there): w_o
 * given, w_i returned as a unit vector ((0, 0, 0) for an invalid sample). Sample index k keys the
 * same numbers as in hb_sample_angles, so the two give the same samples up to the vectors' rounding. */
typedef struct hb_sample_vectors_in {
    const float *wo_x, *wo_y, *wo_z;
    const float *const *u; /* as hb_sample_in's */
} hb_sample_vectors_in;

typedef struct hb_sample_vectors_out {
    float *wi_x, *wi_y, *wi_z;
    float *pdf;
    hb_rgb_soa weight;
} hb_sample_vectors_out;

HB_API hb_status hb_sample_vectors(const hb_plan *plan, size_t n, const hb_sample_vectors_in *in,
                                   const hb_sample_vectors_out *out, hb_eval_report *report);
HB_API hb_status hb_pdf_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, float *pdf, hb_eval_report *report);

/* f and the pdf of the same directions in one call, for multiple importance sampling: f as
 * hb_eval_angles (hb_eval_vectors) returns it, pdf as hb_pdf_angles (hb_pdf_vectors) does. dFH11
 * quadrature plans and CBTB16 form both in one pass over the batch (the pdf then costs a few
 * operations more than f alone; docs/sampling.md); HHH22 and dFH11 table plans make two passes.
 * Plans that cannot sample return HB_ERR_UNSUPPORTED. */
HB_API hb_status hb_eval_pdf_angles(const hb_plan *plan, size_t n, hb_angles_soa in, hb_rgb_soa f, float *pdf,
                                    hb_eval_report *report);
HB_API hb_status hb_eval_pdf_vectors(const hb_plan *plan, size_t n, hb_vectors_soa in, hb_rgb_soa f, float *pdf,
                                     hb_eval_report *report);

/* From a renderer's world space to the fibre frame (docs/conventions.md): y along the tangent (root
 * to tip), z along the part of `normal` perpendicular to it, x = y cross z. normal may be NULL (any
 * perpendicular z: a circular fibre's f depends on phi_o - phi_i alone; for an elliptical fibre
 * give the direction of its minor axis). HB_ERR_PARAM when the tangent is zero or not finite; a
 * normal parallel to the tangent, zero or not finite is treated as NULL. */
typedef struct hb_frame {
    float x[3], y[3], z[3]; /* orthonormal, right-handed, in world coordinates */
} hb_frame;
HB_API hb_status hb_frame_from_tangent(const float tangent[3], const float *normal, hb_frame *frame);
HB_API void hb_frame_to_local(const hb_frame *frame, const float world[3], float local[3]);
HB_API void hb_frame_to_world(const hb_frame *frame, const float local[3], float world[3]);

/* Near-field sampling and pdf (CBTB16, dFH11): as hb_sample_angles and hb_pdf_angles at each
 * sample's offset h (hb_eval_near), reading hb_plan_sample_dimensions(plan) - 1 numbers;
 * HB_ERR_UNSUPPORTED for plans without a near-field sampler. */
typedef struct hb_sample_near_in {
    const float *theta_o, *phi_o, *h;
    const float *const *u; /* as hb_sample_in's */
} hb_sample_near_in;
HB_API hb_status hb_sample_near(const hb_plan *plan, size_t n, const hb_sample_near_in *in, const hb_sample_out *out,
                                hb_eval_report *report);
HB_API hb_status hb_pdf_near(const hb_plan *plan, size_t n, hb_near_soa in, float *pdf, hb_eval_report *report);
/* f and the pdf at h in one call, for multiple importance sampling (eval_near, then pdf_near). */
HB_API hb_status hb_eval_pdf_near(const hb_plan *plan, size_t n, hb_near_soa in, hb_rgb_soa f, float *pdf,
                                  hb_eval_report *report);

/* The near field with fibre-frame unit vectors, as a path tracer has them at a hit: each call turns
 * the vectors into angles in double (an invalid vector, as for hb_eval_vectors, makes an invalid
 * sample) and runs the angle call above on them, in chunks on the stack; the sampler returns w_i as
 * a unit vector, (0, 0, 0) for an invalid sample. The results are the angle calls' on the rounded
 * angles, bit for bit. */
typedef struct hb_near_vectors_soa {
    const float *wi_x, *wi_y, *wi_z, *wo_x, *wo_y, *wo_z, *h;
} hb_near_vectors_soa;
typedef struct hb_sample_near_vectors_in {
    const float *wo_x, *wo_y, *wo_z, *h;
    const float *const *u; /* as hb_sample_in's */
} hb_sample_near_vectors_in;
HB_API hb_status hb_eval_near_vectors(const hb_plan *plan, size_t n, hb_near_vectors_soa in, hb_rgb_soa out,
                                      hb_eval_report *report);
HB_API hb_status hb_pdf_near_vectors(const hb_plan *plan, size_t n, hb_near_vectors_soa in, float *pdf,
                                     hb_eval_report *report);
HB_API hb_status hb_eval_pdf_near_vectors(const hb_plan *plan, size_t n, hb_near_vectors_soa in, hb_rgb_soa f,
                                          float *pdf, hb_eval_report *report);
HB_API hb_status hb_sample_near_vectors(const hb_plan *plan, size_t n, const hb_sample_near_vectors_in *in,
                                        const hb_sample_vectors_out *out, hb_eval_report *report);

/* Spectral evaluation (docs/spectral.md): k wavelengths per sample, 1 <= k <= HB_WAVELENGTHS_MAX,
 * each with its own absorption per unit radius, sigma_a[j][s] for wavelength j of sample s (a
 * renderer's sigma_a spectrum samples as they are, or hb_melanin_absorption_spectral's); f comes back
 * as k planes f[j][s]. Roughness, eta, tilt, lobes and quality are the plan's: the directions,
 * Fresnel, M_p and N_p are computed once per sample for its k wavelengths, only the attenuations per
 * wavelength. A sample is invalid as in the RGB calls, or when one of its absorptions is NaN, negative
 * or infinite: it gets 0 in every plane (pdf and direction too) and is counted. CBTB16 plans: the far
 * field (hb_eval_angles_spectral), the near field at h, its sampler and its pdf, by the plan's kernels
 * or, for a reference plan, in double. The sampler chooses the lobe by A_p's mean over the sample's k
 * wavelengths, as pbrt-v4's HairBxDF::Sample_f does, so the pdf depends on the absorptions; weight[j]
 * is f / pdf at wavelength j. dFH11 plans: the same calls, its near-field sampler choosing the lobe
 * the same way; its standard quadrature plans evaluate the far field by their own spectral kernels.
 * The other dFH11 far fields and MJC03's, where their per-sample absorption calls work, evaluate f
 * (hb_eval_angles_spectral) through them, three wavelengths a call; MJC03's sampling and HHH22
 * return HB_ERR_UNSUPPORTED. */
#define HB_WAVELENGTHS_MAX 8
typedef struct hb_spectral_absorption {
    int wavelengths;             /* k */
    const float *const *sigma_a; /* k planes of n values */
} hb_spectral_absorption;
typedef struct hb_sample_spectral_out {
    float *theta_i, *phi_i;
    float *pdf;
    float *const *weight; /* k planes: f / pdf per wavelength */
} hb_sample_spectral_out;
HB_API hb_status hb_eval_angles_spectral(const hb_plan *plan, size_t n, hb_angles_soa in, hb_spectral_absorption sigma_a,
                                         float *const *f, hb_eval_report *report);
HB_API hb_status hb_eval_near_spectral(const hb_plan *plan, size_t n, hb_near_soa in, hb_spectral_absorption sigma_a,
                                       float *const *f, hb_eval_report *report);
HB_API hb_status hb_pdf_near_spectral(const hb_plan *plan, size_t n, hb_near_soa in, hb_spectral_absorption sigma_a,
                                      float *pdf, hb_eval_report *report);
HB_API hb_status hb_sample_near_spectral(const hb_plan *plan, size_t n, const hb_sample_near_in *in,
                                         hb_spectral_absorption sigma_a, const hb_sample_spectral_out *out,
                                         hb_eval_report *report);

/* pbrt-v4's HairBxDF at one hit, in pbrt's own terms (docs/spectral.md), for a CBTB16 plan of pbrt's
 * beta_m, beta_n, eta and alpha (the plan's own absorption is not used): w_o and w_i in pbrt's hair
 * frame (the tangent on x), pbrt's offset h, and sigma_a[0..k) at its k sampled wavelengths (its
 * SampledSpectrum of sigma_a). hb_pbrt_f writes f[0..k) as HairBxDF::f returns it (the sum over p
 * divided by |w_i.z|) and the pdf as HairBxDF::PDF; hb_pbrt_sample_f draws w_i from u[0..3] (the
 * near-field sampler's four numbers: pbrt's Sample_f reads three, reusing uc) and writes w_i, f and
 * the pdf as pbrt's BSDFSample holds them, so that f |w_i.z| / pdf is the weight per wavelength. An
 * invalid hit gets zeros; the statuses are the spectral calls'. */
HB_API hb_status hb_pbrt_f(const hb_plan *plan, const float wo[3], const float wi[3], float h, int wavelengths,
                           const float *sigma_a, float *f, float *pdf);
HB_API hb_status hb_pbrt_sample_f(const hb_plan *plan, const float wo[3], float h, const float u[4], int wavelengths,
                                  const float *sigma_a, float wi[3], float *f, float *pdf);

/* One hit at a time, with plain arrays, for renderers that shade one hit per call: the vector calls
 * above at n = 1. w_o and w_i are fibre-frame unit vectors (toward the viewer and the light); h
 * points to the hit's offset for the near field (CBTB16, dFH11), or is NULL for the far field.
 * hb_hit_sample reads hb_plan_sample_dimensions(plan) numbers from u (uniform in [0, 1)) and writes
 * the sampled w_i, its pdf and f / pdf; hb_hit_eval_pdf writes f and the pdf with which the sampler
 * draws w_i, for multiple importance sampling. An invalid hit gets zeros, as in the batch calls,
 * whose statuses these return. */
HB_API hb_status hb_hit_sample(const hb_plan *plan, const float wo[3], const float *h, const float *u, float wi[3],
                               float *pdf, float weight[3]);
HB_API hb_status hb_hit_eval_pdf(const hb_plan *plan, const float wi[3], const float wo[3], const float *h, float f[3],
                                 float *pdf);

/* Counter-based uniform numbers in [0, 1) (24 bits): u[d][k] for sample index first + k and
 * dimension d < dimensions, a pure function of (seed, index, d), the same on every machine. */
HB_API void hb_uniforms(unsigned long long seed, unsigned long long first, size_t n, int dimensions, float *const *u);

/* A plan's precomputed table, for engines that bake it into a texture (`hairbsdf bake`, docs/engines.md): dFH11 N_p (HB_AZIMUTHAL_TABLE) or HHH22 f_TT + f_TRT (HB_TT_TRT_TABLE).
 * Nodes are uniform from lo to hi on each axis; values are row-major over the axes, then the slot,
 * then the channel (RGB innermost; one channel for the colour table, hb_plan_table_channels). HHH22's
 * values are square roots over a closing factor: interpolate them, square, multiply the factor back
 * (docs/engines.md). The view points into the
 * plan and lives as long as it. */
#define HB_TABLE_MAX_AXES 4
/* No plan's table file is larger (HHH22's finest elliptical grid: 961 MiB; dFH11's: 217 MiB): a loader
 * may refuse a larger file before reading it, and plan creation refuses a larger table_file_size. */
#define HB_TABLE_FILE_MAX_BYTES ((size_t)1 << 30)
typedef struct hb_table_view {
    size_t struct_size; /* the caller sets sizeof(hb_table_view); the library fills that much */
    hb_model model;
    int axes;
    int size[HB_TABLE_MAX_AXES];
    double lo[HB_TABLE_MAX_AXES], hi[HB_TABLE_MAX_AXES];
    const char *axis[HB_TABLE_MAX_AXES]; /* what the axis is, as a formula of the directions */
    int slots;                            /* dFH11: one per M_p group; HHH22: 1 */
    unsigned slot_lobes[HB_MAX_LOBES + 1]; /* the lobes (bits (1u << p), HB_LOBE_RESIDUAL) summed in each slot */
    const float *values;
    size_t count;                         /* floats: product of sizes x slots x channels */
    double error;  /* dFH11: the largest midpoint interpolation error relative to its slot's peak, measured
                      at build; HHH22: NaN (docs/huang.md gives its measured error) */
} hb_table_view;

/* HB_ERR_UNSUPPORTED when the plan has no table. */
HB_API hb_status hb_plan_table(const hb_plan *plan, hb_table_view *view);

/* The floats per node and slot of the plan's table: 3 (RGB) for a material's own table, 1 for dFH11's
 * colour table (HB_AZIMUTHAL_COLOUR_TABLE, whose last axis is the absorption coordinate); 0 without a
 * table. hb_table_view.count is the product of the sizes, the slots and this. */
HB_API int hb_plan_table_channels(const hb_plan *plan);

/* The plan's table as a table file (`.hbt`, docs/engines.md gives the layout), to ship with an engine's
 * data and load with options.table_file: writes at most capacity bytes to bytes and the file's length
 * to *size (bytes may be NULL to ask for the length). HB_ERR_UNSUPPORTED when the plan has no table,
 * HB_ERR_PARAM when capacity is less than the length. A plan loaded from the file evaluates bit for
 * bit as the plan that saved it on the same instruction set. */
HB_API hb_status hb_table_save(const hb_plan *plan, void *bytes, size_t capacity, size_t *size);

/* The constants the shaders of shaders/ read beside the plan's table (docs/engines.md), a block of 16
 * vec4s. dFH11 table plans: floats 0..3 the table's nodes in sqrt(cos(theta_d)) and in |phi|, its
 * slots, and its absorption nodes (a colour table; else 0); then slot s's M_p (eq. 7) at 4 + 4 s:
 * 1 / v, log2(e) / v, log2 of eq. 7's norm (csch(1/v) / (2v) without e^(-1/v)) and its shift alpha_p;
 * at 40, a colour table's absorption axis: 1 / knee and its nodes per unit of log(1 + sigma_a / knee).
 * HHH22 plans of a circular fibre whose R lobe is analytic (GGX without shadowing) or absent and whose
 * TT and TRT come from the table or are absent: 0..3 R (1 or 0), the table (1 or 0), eta, eta^2 - 1;
 * 4..7 1 / eta^2, App. A's c and 1 - c, roughness^2 / (4 pi); 8..10 cos and sin of the tilt and
 * whether it is tilted; 11 the least cos(theta) of eq. 10's projected width; 12..14 the table's
 * nodes in theta_i, the warped sum and |phi|; 16..19 the warped sum's first node and nodes per unit,
 * |phi|'s first node and nodes per radian; 20, 21 the sum's centre and 1 / roughness.
 * HB_ERR_UNSUPPORTED for other plans. */
#define HB_SHADER_CONSTANTS 64
HB_API hb_status hb_plan_shader_constants(const hb_plan *plan, float constants[HB_SHADER_CONSTANTS]);

/* White furnace: E(w_o) = integral over the sphere of f(w_i, w_o) dw_i per channel, by
 * quadrature fine enough for the plan's roughness (docs/conventions.md). A lossless fibre with
 * every order gives E = 1 up to the model's approximations. For HB_TERM_LONGITUDINAL the
 * term T = f / N_p is integrated as T cos(theta_i) over theta_i (dFH11 eq. 5, Fig. 3). */
HB_API hb_status hb_furnace(const hb_plan *plan, double theta_o, double energy[3]);

/* HHH22's energy by scattering order (its Fig. 16: what dropping the lobes beyond TRT loses): the
 * energy leaving a fibre lit along w = (theta, 0), split into R, TT, TRT and every order beyond, by a
 * random walk of `paths` paths through the rough fibre (visible normals at each interface, in double;
 * docs/huang.md, energy beyond TRT); standard_error (may be NULL) gets each group's standard error
 * of the channel mean. The first three groups equal hb_furnace of the R, TT and TRT lobes for
 * alpha = 0 (where the model is reciprocal). HHH22 plans of circular fibres only (else
 * HB_ERR_UNSUPPORTED); the walk's cost grows with paths, not with the plan's quality. */
#define HB_ORDER_GROUPS 4
HB_API hb_status hb_furnace_orders(const hb_plan *plan, double theta, long paths, unsigned long long seed,
                            double energy[HB_ORDER_GROUPS][3], double standard_error[HB_ORDER_GROUPS]);

/* Dual scattering (Zinke, Yuksel, Weber and Keyser 2008, "Dual Scattering Approximation for Fast
 * Multiple Scattering in Hair"; docs/multiple-scattering.md): what one fibre of the plan does to
 * light arriving at inclination theta, per channel, split into the hemisphere the light goes on
 * into (forward, |phi_o - phi_i| > pi/2) and the one it returns to (backward). Energies are the
 * integrals of f(w_i, w_o) = S cos(theta_i) over the hemisphere of w_o, w_i at theta: for a
 * reciprocal model a_f + a_b is the white furnace, 1 for a lossless fibre; the shifts and variances are the first and second central moments of
 * theta_h = (theta_i + theta_o) / 2 over that energy (the variable of the paper's Gaussian lobes,
 * for which they are its eqs. 12 and 13; for the lobes of the other models they include the spread
 * of the lobes' means). */
typedef struct hb_dual_terms {
    size_t struct_size;                     /* the caller sets sizeof(hb_dual_terms); the library fills that much */
    double a_f[3], a_b[3];                  /* eq. 6: the forward and backward energy */
    double alpha_f[3], beta_f2[3];          /* the forward energy's mean theta_h and its variance */
    double alpha_b[3], beta_b2[3];          /* the backward energy's */
    double A_b[3], delta_b[3], sigma_b2[3]; /* eqs. 14-17: multiple back-scattering's energy, shift and variance */
} hb_dual_terms;
#define HB_DUAL_DENSITY 0.7 /* the paper's density factors d_f and d_b */

/* The terms at theta in (-pi/2, pi/2), by deterministic quadrature over w_o fine enough for the
 * plan's roughness (the furnace's rule, Gauss-Legendre on each quarter of the azimuths), with the
 * plan's own evaluation (its kernels, or its double reference for a reference plan); d_b is the
 * backward density factor of eq. 17 (HB_DUAL_DENSITY). The far field of a near-field model; for an
 * elliptical fibre, the mean over its orientations to the light (16 of them, each over both sides).
 * HB_ERR_PARAM for theta outside (-pi/2, pi/2) or d_b outside [0, 1]. */
HB_API hb_status hb_dual_terms_at(const hb_plan *plan, double theta, double d_b, hb_dual_terms *terms);

/* The terms at `count` inclinations, the midpoints theta_k = -pi/2 + pi (k + 1/2) / count (the
 * function of theta an engine bakes per material): terms[k] as hb_dual_terms_at writes it, the array's
 * elements terms[0].struct_size bytes apart (set it, as for one). Rows run as `count` tasks through
 * parallel (an engine's job system, as hb_options.parallel; NULL: in order on this thread), in parts,
 * with progress (as hb_options.progress, may be NULL) called between parts; a nonzero return cancels
 * with HB_ERR_CANCELLED. The terms are the same bit for bit however the tasks run. */
HB_API hb_status hb_dual_terms_grid(const hb_plan *plan, int count, double d_b, hb_dual_terms *terms,
                                    hb_progress_fn progress, void *progress_context, hb_parallel_fn parallel,
                                    void *parallel_context);

/* Each lobe's part of a_f and a_b at theta: forward[p] and backward[p] per channel for the orders p
 * of the plan's lobe set and HB_LOBE_RESIDUAL (0 for the others), integrated on the plan's own nodes,
 * so that they sum to hb_dual_terms_at's a_f and a_b. Creates (and frees) a plan of each lobe alone,
 * which costs what that plan's creation costs (a table plan builds its table). */
HB_API hb_status hb_dual_lobe_energies(const hb_plan *plan, double theta, double forward[HB_MAX_LOBES + 1][3],
                                       double backward[HB_MAX_LOBES + 1][3]);

/* The dual-scattering radiance term per sample (Zinke et al. 2008 sec. 4; docs/multiple-scattering.md,
 * "The radiance term"): what the light that scattered off other fibres before reaching a shading point
 * adds to that point's f. An engine shades v f + f_DS, with f the plan's own f (hb_eval_angles), v
 * the light's direct visibility at the point and f_DS from hb_dual_eval:
 *   f_DS = v d_b f_back(0) + (1 - v) T_f (f_G(sigma_f^2) + d_b f_back(sigma_f^2)),
 *   T_f = d_f a_f^n and sigma_f^2 = n beta_f^2 (the paper's global transmittance and spread), n the
 * fibres between the point and the light,
 * every term at the light's inclination theta_i and theta_h = (theta_i + theta_o) / 2;
 *   f_back(s^2) = A_b g(theta_h - delta_b, sigma_b^2 + s^2) / (2 pi cos theta_o) where |phi| < pi/2
 * (A_b, delta_b, sigma_b^2 of eqs. 14-17), 0 elsewhere; and the forward-scattered light's next scattering
 *   f_G(s^2) = [a_f |phi| g(theta_h - alpha_f, beta_f^2 + s^2) + a_b (pi - |phi|) g(theta_h - alpha_b,
 *              beta_b^2 + s^2)] / (2 pi^2 cos theta_o),
 * phi = phi_o - phi_i in [-pi, pi], g the unit Gaussian: each term integrates over w_o to its energy
 * (A_b, a_f, a_b), cos theta_o no less than 2^-12. The table holds the terms of hb_dual_terms_grid at
 * `thetas` midpoints, interpolated linearly in theta_i (constant beyond the outer nodes). */
typedef struct hb_dual_table hb_dual_table;

/* Builds the table of a plan (its model, lobes and quality; its ISA for hb_dual_eval) with the density
 * factors d_f and d_b in [0, 1] (HB_DUAL_DENSITY), `thetas` in 2..4096 (64 is an engine's choice);
 * progress and parallel as hb_dual_terms_grid. HB_ERR_LIMIT when a_f >= 1 at a node (eqs. 14-15's
 * series of forward scatterings diverges: MJC03's lossless forward energy exceeds 1), naming it.
 * A tolerance or budget plan drops the term where it adds less than the plan's target (its
 * tolerance, or the error its budget accepts): the table's terms are then zeros, f_DS is 0, and
 * hb_dual_table_included says so. */
HB_API hb_status hb_dual_table_create(const hb_plan *plan, int thetas, double d_f, double d_b, hb_progress_fn progress,
                                      void *progress_context, hb_parallel_fn parallel, void *parallel_context,
                                      hb_dual_table **table);
HB_API void hb_dual_table_destroy(hb_dual_table *table);

/* 1 when the table carries dual scattering, 0 when its tolerance or budget plan dropped it (or for a
 * NULL table). *share (may be NULL) gets the largest, over the nodes and channels, of what the term
 * adds to the fibre's own scattering as a share of its energy a_f + a_b: the local back-scattering
 * d_b A_b, or the global term at one fibre d_f a_f (a_f + a_b + d_b A_b), whichever is larger
 * (docs/multiple-scattering.md, "When a scene needs it"); of the terms the plan gave when built, of
 * the file's when loaded. */
HB_API int hb_dual_table_included(const hb_dual_table *table, double *share);

/* A table as a file (docs/multiple-scattering.md, "Table files"), for an engine to bake once and load:
 * hb_dual_table_save writes it into bytes (*size gets its length; bytes NULL: the length alone;
 * HB_ERR_BUFFER when capacity is smaller), hb_dual_table_load builds the table from it for a plan of
 * the material and options it was built for (its model and every field its terms depend on, else
 * HB_ERR_FILE naming the first that differs), in that plan's ISA, without the quadrature. */
HB_API hb_status hb_dual_table_save(const hb_dual_table *table, void *bytes, size_t capacity, size_t *size);
HB_API hb_status hb_dual_table_load(const hb_plan *plan, const void *bytes, size_t size, hb_dual_table **table);

/* The table's floats as the shaders read them (shaders/hairbsdf_dual.glsl, .hlsl): *thetas nodes at
 * the midpoints -pi/2 + pi (k + 1/2) / thetas, HB_DUAL_NODE_FLOATS floats each, per channel r, g, b
 * twelve: a_f, a_b, alpha_f, beta_f2, alpha_b, beta_b2, A_b, delta_b, sigma_b2 and three zeros.
 * Valid while the table lives; NULL for a NULL table. */
#define HB_DUAL_NODE_FLOATS 36
HB_API const float *hb_dual_table_nodes(const hb_dual_table *table, int *thetas);

/* The terms the table gives at theta (its interpolation, in double): what hb_dual_eval evaluates. */
HB_API hb_status hb_dual_table_terms(const hb_dual_table *table, double theta, hb_dual_terms *terms);

/* f_DS for n samples, in the table's ISA: fibres[k] = n >= 0, direct[k] = v in [0, 1] (direct NULL:
 * v = max(0, 1 - n), full visibility fading out over the first fibre). A sample is invalid as for
 * hb_eval_angles, or when n is NaN, negative or infinite, or v is outside [0, 1]; it gets 0. */
HB_API hb_status hb_dual_eval(const hb_dual_table *table, size_t n, hb_angles_soa in, const float *fibres,
                              const float *direct, hb_rgb_soa out, hb_eval_report *report);

/* The double-precision reference of f_DS at one sample from the terms at theta_i (hb_dual_terms_at
 * for the exact ones, hb_dual_table_terms for a table's) with the density factor d_f (d_b is in the
 * terms' sigma_b2 and passed again for eq. 18's weights); direct < 0 for the default v. */
HB_API hb_status hb_dual_radiance(const hb_dual_terms *terms, double d_f, double d_b, double theta_i, double phi_i,
                                  double theta_o, double phi_o, double fibres, double direct, double f[3]);

/* The engines' estimate of the terms (docs/multiple-scattering.md, "The engines' tables"), for
 * comparing a table built their way with the converged one: HDRP's pre-integration pattern, w_o from
 * `directions` points of a Hammersley set uniform on the sphere (stratified in sin theta_o, the
 * radical inverse in base 2 in phi_o), each against `azimuths` light azimuths phi_i evenly spaced
 * over [-pi/2, pi/2), every pair sorted into the hemisphere w_o lies in relative to the light; each
 * hemisphere's energy is 2 pi times its pairs' mean f and its moments are the f-weighted moments of
 * theta_h over its pairs; A_b, delta_b and sigma_b2 follow by eqs. 14-17 as in hb_dual_terms_at.
 * Deterministic, with the error of a quadrature of that many points (HDRP: 128 x 90). directions
 * and azimuths in 1..65536, theta in (-pi/2, pi/2), d_b in [0, 1], else HB_ERR_PARAM. */
HB_API hb_status hb_dual_terms_sampled(const hb_plan *plan, double theta, int directions, int azimuths, double d_b,
                                       hb_dual_terms *terms);

/* A table from terms the caller has (an engine's own, hb_dual_terms_sampled's, a lookup of
 * hb_dual_engine's): terms[k] (struct_size sizeof(hb_dual_terms)) at the midpoints
 * -pi/2 + pi (k + 1/2) / thetas, used as hb_dual_table_create's, for the plan's ISA and the density
 * factors d_f, d_b. HB_ERR_PARAM for a term that is not finite, an energy or variance below 0;
 * HB_ERR_LIMIT for a_f >= 1, as hb_dual_table_create. */
HB_API hb_status hb_dual_table_from_terms(const hb_plan *plan, int thetas, const hb_dual_terms *terms, double d_f,
                                          double d_b, hb_dual_table **table);

/* An engine-wide table (docs/multiple-scattering.md, "One table for every hair colour"): the terms
 * of one material family, the base material and options given with its absorption and its R lobe's
 * longitudinal roughness (the model's look: dFH11's beta_m, CBTB16's and MJC03's in radians, HHH22's
 * from its microfacet roughness) as axes, so that one texture serves every colour and roughness of
 * that family. Each channel's terms depend on that channel's absorption alone, so a node holds one
 * channel: a_f, a_b, alpha_f, beta_f2, alpha_b, beta_b2 at (theta, roughness, absorption); A_b,
 * delta_b and sigma_b2 follow from them by eqs. 14-17 after interpolation. */
typedef struct hb_dual_engine_axes {
    size_t struct_size;   /* sizeof(hb_dual_engine_axes), set by hb_dual_engine_axes_default */
    int thetas;           /* theta_i at the midpoints of (-pi/2, pi/2), 2..1024; default 64 */
    int roughnesses;      /* evenly spaced over [roughness_min, roughness_max], 2..256; default 16 */
    double roughness_min, roughness_max; /* radians; default 0.05 and 0.6 */
    int absorptions;      /* evenly spaced in exp(-sigma_a) over [exp(-absorption_max), 1], 2..256; default 16 */
    double absorption_max; /* sigma_a per unit radius at the last node; default 12 */
    /* 0 (the default): every node by hb_dual_terms_at, converged; else the engines' estimate,
     * hb_dual_terms_sampled with these many directions and azimuths (HDRP: 128 and 90) */
    int sampled_directions, sampled_azimuths;
} hb_dual_engine_axes;
HB_API void hb_dual_engine_axes_default(hb_dual_engine_axes *axes);

typedef struct hb_dual_engine hb_dual_engine;

/* Builds the engine-wide table of the family of `base` (its absorption and melanins ignored, its
 * roughness replaced by the axis) under `options` (their progress and parallel drive the build: the
 * roughnesses times ceil(absorptions / 3) plans of three absorptions each are the tasks, each over
 * every theta), with d_b for sigma_b2. HB_ERR_PARAM names an axis outside its range. */
HB_API hb_status hb_dual_engine_create(const hb_material *base, const hb_options *options,
                                       const hb_dual_engine_axes *axes, double d_b, hb_dual_engine **engine,
                                       hb_error *error);
HB_API void hb_dual_engine_destroy(hb_dual_engine *engine);

/* The terms at theta for a fibre of the family with R roughness `roughness` and absorption sigma_a
 * per channel: at the two theta nodes about theta, the nodes interpolated linearly in roughness and
 * exp(-sigma_a), each clamped to its axis (as the engines clamp), and eqs. 14-17 from them; between
 * the two, linear in theta, as hb_dual_engine_table's table gives them. HB_ERR_LIMIT where a_f >= 1. */
HB_API hb_status hb_dual_engine_terms(const hb_dual_engine *engine, double theta, double roughness,
                                      const double sigma_a[3], hb_dual_terms *terms);

/* The per-material table of a plan of the family (its roughness and absorption, melanins included,
 * looked up; every other field and its model and lobes those of the base, else HB_ERR_PARAM naming
 * the first that differs) at the engine's thetas, for hb_dual_eval and the shaders. */
HB_API hb_status hb_dual_engine_table(const hb_dual_engine *engine, const hb_plan *plan, double d_f,
                                      hb_dual_table **table);

/* The engine-wide table as the shaders read it (shaders/hairbsdf_dual.glsl, .hlsl: hb_dual_engine_f):
 * HB_DUAL_ENGINE_NODE_FLOATS floats per node, a_f, a_b, alpha_f, beta_f2, alpha_b, beta_b2 and two
 * zeros, node (roughness r, absorption j, theta k) at ((r * absorptions + j) * thetas + k); *count
 * gets the floats' count. Valid while the engine lives; NULL for a NULL engine. */
#define HB_DUAL_ENGINE_NODE_FLOATS 8
HB_API const float *hb_dual_engine_nodes(const hb_dual_engine *engine, size_t *count);

/* The shaders' hb_dual_engine_constants for density factor d_f: thetas, roughnesses, roughness_min,
 * roughness_max, absorptions, 1 - exp(-absorption_max), d_f and the table's d_b. */
HB_API hb_status hb_dual_engine_constants(const hb_dual_engine *engine, double d_f, float constants[8]);

/* The engine-wide table as a file (docs/multiple-scattering.md, "Engine table files"): its axes, d_b,
 * the base plan's fields and every node's six terms in double, so that a tool bakes it once and an
 * engine loads it. hb_dual_engine_save writes it into bytes (*size gets its length; bytes NULL: the
 * length alone; HB_ERR_BUFFER when capacity is smaller). hb_dual_engine_load builds the engine from
 * it for the same base and options as hb_dual_engine_create's (the file's fields must equal those of
 * their plan; HB_ERR_FILE names the first that differs, or the damage). Loading equals the saved
 * engine node for node. */
HB_API hb_status hb_dual_engine_save(const hb_dual_engine *engine, void *bytes, size_t capacity, size_t *size);
HB_API hb_status hb_dual_engine_load(const hb_material *base, const hb_options *options, const void *bytes,
                                     size_t size, hb_dual_engine **engine, hb_error *error);

/* Light in a fibre assembly, traced fibre by fibre (docs/multiple-scattering.md): the ground truth the
 * dual-scattering terms and the engines' tables approximate. Parallel circular fibres of radius 1
 * along the frame's y, placed at random without overlap (random sequential addition from the seed),
 * fill a slab (0 <= z <= 2 layers radii, periodic along x with the given period) or a round bundle
 * (a tress of radius 2 layers radii about the origin). A directional light from w(theta_light,
 * phi_light) (the fibre frame's angles; for the slab above it, |phi_light| < pi/2) falls uniformly on
 * the assembly's width. Each path starts at the light and scatters at every fibre it meets, the
 * plan's own sampler drawing where it goes next (its w_o toward where the light came from), the path
 * leaving from the hit point and passing the fibre it scattered from; `transport` says what weighs
 * each scattering. After 3 scatterings Russian roulette ends a path with
 * probability 1 - min(1, its largest channel), unbiased; a path still going after max_bounces, or
 * running along the fibres or a slab's faces without end, is counted as unfinished, never dropped.
 * Paths run as tasks of HB_ASSEMBLY_BATCH paths, each advanced as one batch through the plan's batch
 * calls once per bounce; the numbers are a pure function of the seed and the path's index, so the
 * result is the same bit for bit however the tasks run. */
typedef enum hb_assembly_shape {
    HB_ASSEMBLY_SLAB = 0, /* reflected: leaving through z = 2 layers (the lit side); transmitted: through z = 0 */
    HB_ASSEMBLY_BUNDLE    /* reflected: leaving toward the light's half (w . w_light's part in the x-z plane > 0) */
} hb_assembly_shape;

typedef enum hb_assembly_transport {
    /* The far-field sampler draws w_next from w_o = w_from (where the light came from) and the path
     * carries S(w_from, w_next) cos(theta_next) / pdf, S the plan's far field (hb_eval_angles):
     * light scattered by the model as the model's equations send it, for any model, reciprocal or
     * not, what a path tracer from the eye converges to. Two calls per bounce (sample, evaluate).
     * Plans whose pdf is an estimate (hb_plan_pdf_is_estimate) return HB_ERR_UNSUPPORTED. */
    HB_ASSEMBLY_LIGHT_TRANSPORT = 0,
    /* The sampler's own weight f(w_next, w_from) / pdf, the near field at the hit's offset h where the
     * model has one (hb_sample_near) and the far field otherwise: the same as the light's transport
     * where S is reciprocal (MJC03, untilted dFH11), that of S transposed where it is not (CBTB16,
     * tilted dFH11; docs/multiple-scattering.md measures by how much). One call per bounce. */
    HB_ASSEMBLY_SAMPLER_WEIGHTS
} hb_assembly_transport;

typedef struct hb_assembly {
    size_t struct_size; /* sizeof(hb_assembly), set by hb_assembly_default */
    hb_assembly_shape shape; /* default HB_ASSEMBLY_SLAB */
    double layers;     /* the slab's thickness, the bundle's radius, in fibre diameters (default 8) */
    double packing;    /* the fibres' share of the cross-section's area, in (0, 0.5] (default 0.3) */
    int period;        /* the slab's period along x in fibre diameters, at least 4 (default 32) */
    double theta_light, phi_light; /* default (0.3, 0) */
    long long paths;   /* default 100000 */
    int max_bounces;   /* 1..100000, default 10000 */
    unsigned long long seed; /* places the fibres and keys the paths' numbers; default 1 */
    int theta_bins, phi_bins; /* the exit directions' bins: uniform in theta over [-pi/2, pi/2] and in
                                 phi_o over [-pi, pi]; default 18 and 36 */
    int depth_bins;    /* the bins of fibre depth, one per fibre diameter from the lit side (default 8) */
    hb_assembly_transport transport; /* default HB_ASSEMBLY_LIGHT_TRANSPORT */
} hb_assembly;
HB_API void hb_assembly_default(hb_assembly *assembly);

#define HB_ASSEMBLY_BATCH 512 /* the paths of one task, advanced together through the same calls each bounce */
#define HB_ASSEMBLY_ORDERS 9 /* by_order[side][k]: the light that scattered k times, k < 8, and 8 or more at k = 8 */

/* Every figure is a fraction of the light falling on the assembly, per channel, with the standard
 * error of its mean over paths (_se). The caller may point the three arrays at storage, or leave them
 * NULL: radiance and radiance_se, 2 x theta_bins x phi_bins x 3 doubles ([side][theta][phi][channel],
 * side 0 reflected): each bin's fraction per unit solid angle (the exit's radiant intensity over the
 * incident power) of the light that scattered at least once; depth, depth_bins x 3 x 3 doubles ([depth][order 1, 2, 3 and above][channel]): the
 * light arriving at the fibres of each depth, by the order of the scattering it arrives for. */
typedef struct hb_assembly_result {
    size_t struct_size; /* the caller sets sizeof(hb_assembly_result); the library fills that much */
    double reflected[3], transmitted[3], absorbed[3], unfinished[3];
    double reflected_se[3], transmitted_se[3], absorbed_se[3];
    double by_order[2][HB_ASSEMBLY_ORDERS][3]; /* reflected (0) and transmitted (1) by scattering order
                                                  (order 0: light that met no fibre) */
    double by_order_square[2][HB_ASSEMBLY_ORDERS][3]; /* the mean over paths of the square of what each path carries
                                                         out in that order; a path leaves in one order, so the standard
                                                         error of the sum over a set K of orders is
                                                         sqrt((sum_K square - (sum_K by_order)^2) / (paths - 1)) */
    double *radiance, *radiance_se, *depth;
    long fibres;           /* the fibres placed (in one period of the slab) */
    double packing;        /* their share of the area, as placed */
    long long events;      /* the scatterings traced */
    long long invalid;     /* samples the sampler refused (their light counts as absorbed) */
} hb_assembly_result;

/* Traces assembly->paths paths through the assembly with plan's sampler (plans that can sample;
 * circular fibres only, else HB_ERR_UNSUPPORTED). HB_ERR_PARAM for a field outside its range (named),
 * HB_ERR_LIMIT when random placement cannot reach the packing (the message gives what it reached),
 * HB_ERR_VERSION for a struct_size this release does not know; progress and parallel as for
 * hb_dual_terms_grid. */
HB_API hb_status hb_assembly_trace(const hb_plan *plan, const hb_assembly *assembly, hb_assembly_result *result,
                                   hb_progress_fn progress, void *progress_context, hb_parallel_fn parallel,
                                   void *parallel_context);

/* What dual scattering predicts for hb_assembly_trace's radiance bins (the same assembly, fibres and
 * bins; docs/multiple-scattering.md, "Dual scattering against the reference"), rendered as an engine
 * renders hair: per bin `rays` view rays, each along a direction uniform in the bin's solid angle
 * entering the slab's face at stratified x, shade the first fibre they meet with v f + f_DS (the
 * plan's far field, hb_dual_eval of the table), n the fibres a ray from that point toward the light
 * crosses (past its own fibre; v = 1 where it crosses none). radiance (2 x
 * theta_bins x phi_bins x 3, as hb_assembly_result's) gets the prediction; radiance_se (may be NULL)
 * the standard error of its mean over the rays; single (may be NULL) the part v f alone, single
 * scattering at the fibres the view sees. Slabs only (else HB_ERR_UNSUPPORTED). */
HB_API hb_status hb_assembly_dual(const hb_plan *plan, const hb_dual_table *table, const hb_assembly *assembly, int rays,
                                  double *radiance, double *radiance_se, double *single);

/* A picture of a bundle (a tress) seen from the side (docs/multiple-scattering.md, "A tress, traced
 * and dual-scattered"): an orthographic camera looking at the bundle along -w(theta_o, view_phi),
 * image rows the assembly's theta_bins in theta_o (row 0 the highest), columns `columns` strips
 * across the bundle's width 2 R (R its radius, column 0 at -R along (cos view_phi, 0, -sin view_phi)),
 * each pixel's value L / E, the radiance over the light's irradiance, per channel:
 * - traced: hb_assembly_trace's paths of the same assembly that leave with theta_o in the row and
 *   |phi_o - view_phi| < pi / phi_bins (one azimuth bin about the camera), by where they last
 *   scattered; traced_single the part that scattered once;
 * - dual: `rays` view rays per pixel, uniform in the pixel's strip and solid angle, each shading the
 *   first fibre it meets with v f + f_DS as hb_assembly_dual does (0 where it meets none);
 *   dual_single the part v f.
 * Each of the six arrays (rows x columns x 3 doubles, [row][column][channel]) may be NULL. */
typedef struct hb_assembly_image {
    size_t struct_size; /* sizeof(hb_assembly_image) */
    double view_phi;    /* the camera's azimuth in the fibre frame: 0 lit from the front at phi_light 0, pi from behind */
    int columns;        /* 1..4096 */
    int rays;           /* 1..2^20 */
    double *traced, *traced_se, *traced_single, *dual, *dual_se, *dual_single;
} hb_assembly_image;

/* Renders both pictures of assembly (a bundle, else HB_ERR_UNSUPPORTED) with the plan and its table;
 * the trace as hb_assembly_trace (result may be NULL; progress and parallel drive it), the same bit
 * for bit however its tasks run. */
HB_API hb_status hb_assembly_render(const hb_plan *plan, const hb_dual_table *table, const hb_assembly *assembly,
                                    hb_assembly_image *image, hb_assembly_result *result, hb_progress_fn progress,
                                    void *progress_context, hb_parallel_fn parallel, void *parallel_context);

/* Instruction sets: names as used by --isa and the HB_ISA environment variable
 * ("scalar", "sse4.1", "avx2", "avx512", "neon"). */
HB_API const char *hb_isa_name(hb_isa isa);
HB_API hb_isa hb_isa_from_name(const char *name); /* HB_ISA_COUNT if unknown */
HB_API int hb_isa_available(hb_isa isa);          /* compiled in and supported by this CPU and OS */
HB_API hb_isa hb_isa_best(void);                  /* what HB_ISA_AUTO picks without HB_ISA */

/* The calling core's clock in GHz, measured now by a dependent chain of integer
 * additions, one per cycle on x86-64 and AArch64. 0 where it cannot be measured (other CPUs, MSVC).
 * make bench states costs in cycles with it; budget plans convert the built-in calibration's
 * cycles to nanoseconds at this clock (docs/engines.md). */
HB_API double hb_cpu_clock_ghz(void);

#ifdef __cplusplus
}
#endif

#endif

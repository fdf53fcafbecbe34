/* Shared pieces of the hairbsdf command-line tool. */
#ifndef HB_CLI_H
#define HB_CLI_H

#include <stddef.h>
#include "hairbsdf.h"

/* Options every model subcommand takes (docs/cli.md). */
typedef struct cli_model_args {
    hb_material material;
    hb_options options;
    /* --colour (CLI_COLOUR_SIGMA_A: sigma_a by CBTB16's fit) or --melanin-colour (CLI_COLOUR_MELANIN:
     * the concentrations), resolved when the plan is created, when beta_n and the model are known */
    enum { CLI_COLOUR_NONE, CLI_COLOUR_SIGMA_A, CLI_COLOUR_MELANIN } colour_to;
    double colour[3];
    const char *table_path; /* --table: a table file to load (the plan then evaluates from its table) */
    int threads;            /* --threads: for table builds (hb_options.parallel), default 1 */
    int progress;           /* --progress: table builds report to stderr */
} cli_model_args;

void cli_model_args_default(cli_model_args *args);

/* The material the options describe: args->material with a colour option resolved. */
hb_status cli_material(const cli_model_args *args, hb_material *material, hb_error *error);

/* --colour's absorption spectrum, for a spectral evaluation (hb_absorption_from_colour_spectral at the
 * colour fit's beta_n). */
hb_status cli_colour_spectrum(const cli_model_args *args, hb_absorption_spectrum *spectrum, hb_error *error);

/* --threads and --progress into the options of a table build (their parallel and progress). */
void cli_build_hooks(const cli_model_args *args, hb_options *options);

/* One of the library's table files whole, in a buffer the caller frees; NULL with the reason in why.
 * Only a regular file of at most HB_TABLE_FILE_MAX_BYTES is opened: a device, a FIFO or a directory
 * could stream without end or block, and a larger file is no table. */
void *cli_read_table_file(const char *path, size_t *size, const char **why);

/* hb_plan_create of cli_material(args) and options; with --table, from that file's table. */
hb_status cli_plan_create(const cli_model_args *args, const hb_options *options, hb_plan **plan, hb_error *error);

/* Parses argv[*i] (and its value) if it is a model or material option. Returns 1 when
 * consumed (advancing *i past a separate value), 0 when it is not such an option,
 * -1 on a bad value (err holds the message). */
int cli_parse_model_option(int argc, char **argv, int *i, cli_model_args *args, char *err, size_t err_size);

/* The name of lobe p (an order, or HB_LOBE_RESIDUAL) in columns and messages: R, TT, TRT, TRRT, p4..p7, residual. */
const char *cli_lobe_name(int p);

/* The paper a model follows, as titles name it: MJC03, dFH11, HHH22, CBTB16. */
const char *cli_model_paper(hb_model model);

/* A whole field as an integer in [0, 2^64 - 1]; 0 for anything else (a sign, an overflow). */
int cli_parse_u64(const char *s, unsigned long long *out);

/* A whole field as a number in [lo, hi]: 1 with *out, 0 for anything else. */
int cli_parse_range(const char *s, double lo, double hi, double *out);

/* The help text of the model options. */
extern const char cli_model_options_help[];

int cmd_eval(int argc, char **argv, int pdf); /* pdf: hairbsdf pdf */
int cmd_sample(int argc, char **argv);
int cmd_furnace(int argc, char **argv);
int cmd_dual(int argc, char **argv);
/* hairbsdf dual --engine: the material family's engine-wide table (tools/cmd_dual_engine.c) */
int cmd_dual_engine(const cli_model_args *args, int thetas, int roughnesses, int absorptions, const int sampled[2],
                    double density, const char *save);
int cmd_assembly(int argc, char **argv);
int cmd_tress(int argc, char **argv);
int cmd_dump(int argc, char **argv);
int cmd_plot(int argc, char **argv);
int cmd_bake(int argc, char **argv);
int cmd_plan(int argc, char **argv);

#endif

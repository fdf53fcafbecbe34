/* Shared pieces of the hairbsdf command-line tool. */
#ifndef HB_CLI_H
#define HB_CLI_H

#include <stddef.h>
#include "hairbsdf.h"

/* Options every model subcommand takes (docs/cli.md). */
typedef struct cli_model_args {
    hb_material material;
    hb_options options;
} cli_model_args;

void cli_model_args_default(cli_model_args *args);

/* Parses argv[*i] (and its value) if it is a model or material option. Returns 1 when
 * consumed (advancing *i past a separate value), 0 when it is not such an option,
 * -1 on a bad value (err holds the message). */
int cli_parse_model_option(int argc, char **argv, int *i, cli_model_args *args, char *err, size_t err_size);

/* A whole field as an integer in [0, 2^64 - 1]; 0 for anything else (a sign, an overflow). */
int cli_parse_u64(const char *s, unsigned long long *out);

/* The help text of the model options. */
extern const char cli_model_options_help[];

int cmd_eval(int argc, char **argv, int pdf); /* pdf: hairbsdf pdf */
int cmd_sample(int argc, char **argv);
int cmd_furnace(int argc, char **argv);
int cmd_dump(int argc, char **argv);
int cmd_plot(int argc, char **argv);
int cmd_bake(int argc, char **argv);
int cmd_plan(int argc, char **argv);

#endif

/* hairbsdf plan: builds the plan the same options would give `eval` and says what it simulates,
 * what it skipped and why, and its expected error and cost (hb_plan_describe). */
#include <stdio.h>
#include <string.h>

#include "cli.h"

int cmd_plan(int argc, char **argv)
{
    cli_model_args args;
    cli_model_args_default(&args);
    char err[256];
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            printf("usage: hairbsdf plan [options]\nDescribes the plan of these options: with --tolerance X or "
                   "--budget-ns X, what was chosen and why.\n%s", cli_model_options_help);
            return 0;
        }
        int r = cli_parse_model_option(argc, argv, &i, &args, err, sizeof err);
        if (r <= 0) {
            fprintf(stderr, "hairbsdf plan: %s\n", r < 0 ? err : "unknown option (see hairbsdf plan --help)");
            return 2;
        }
    }
    hb_plan *plan;
    hb_error error;
    if (cli_plan_create(&args, &args.options, &plan, &error) != HB_OK) {
        fprintf(stderr, "hairbsdf plan: %s\n", error.message);
        return 2;
    }
    char text[4096];
    hb_plan_describe(plan, text, sizeof text);
    fputs(text, stdout);
    hb_plan_destroy(plan);
    return 0;
}

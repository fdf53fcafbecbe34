/* libFuzzer: the CLI's CSV rows and option parsing (with the plan validation behind them). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "csv.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char buf[1024];
    if (size == 0)
        return 0;
    size_t n = size - 1 < sizeof buf - 1 ? size - 1 : sizeof buf - 1;
    memcpy(buf, data + 1, n);
    buf[n] = '\0';
    if (data[0] & 1) { /* one CSV row */
        float row[5];
        csv_parse_row(csv_trim(buf), row, data[0] & 2 ? 5 : 4);
        return 0;
    }
    char *argv[24] = { "eval" }; /* options, one per line, as the eval command reads them */
    int argc = 1;
    for (char *save = NULL, *tok = strtok_r(buf, "\n", &save); tok && argc < 24; tok = strtok_r(NULL, "\n", &save))
        argv[argc++] = tok;
    cli_model_args args;
    cli_model_args_default(&args);
    char err[256];
    for (int i = 1; i < argc; i++)
        if (cli_parse_model_option(argc, argv, &i, &args, err, sizeof err) <= 0)
            return 0;
    if (args.options.quality == HB_QUALITY_REFERENCE)
        return 0; /* the reference is slow; fuzz_eval covers it with one sample */
    hb_plan *plan;
    hb_error error;
    if (hb_plan_create(&args.material, &args.options, &plan, &error) == HB_OK)
        hb_plan_destroy(plan);
    else if (!error.message[0])
        abort(); /* every refusal must say why */
    return 0;
}

/* hairbsdf: the command-line tool (docs/cli.md). */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hairbsdf <command> [options]\n"
            "Commands:\n"
            "  eval      evaluate f for CSV rows theta_i,phi_i,theta_o,phi_o on stdin\n"
            "  sample    importance-sample w_i given w_o: directions, pdfs and weights f/pdf\n"
            "  pdf       the sampling pdf for CSV rows theta_i,phi_i,theta_o,phi_o on stdin\n"
            "  furnace   white-furnace energy against theta_o, in total, by lobe or by order (--svg plots it)\n"
            "  dual      dual-scattering terms (Zinke 2008) against the light's inclination, as CSV\n"
            "  assembly  light traced through a slab or bundle of fibres: reflected, transmitted, by order\n"
            "  tress     a bundle of fibres seen from the side, traced and by dual scattering (PNG)\n"
            "  dump      a lat-long image of f over all w_o for one w_i (PFM, EXR or PNG), or two side by side\n"
            "  plan      what a plan simulates, skipped and costs (with --tolerance X or --budget-ns X: what it chose)\n"
            "  bake      the table an engine bakes for a material (dFH11 N_p, HHH22 TT+TRT), binary or EXR\n"
            "  plot      an SVG plot of a CSV table: bench results (error vs time) or furnace curves\n"
            "  isa       list the instruction sets, which this CPU has, and which auto picks\n"
            "  version   print the library version\n"
            "Run 'hairbsdf <command> --help' for a command's options.\n\n%s",
            cli_model_options_help);
}

static int cmd_isa(void)
{
    hb_isa best = hb_isa_best();
    for (int i = HB_ISA_SCALAR; i < HB_ISA_COUNT; i++)
        printf("%-8s %s%s\n", hb_isa_name((hb_isa)i), hb_isa_available((hb_isa)i) ? "available" : "-",
               (hb_isa)i == best ? " (auto)" : "");
    return 0;
}

/* The command's status, or 1 with a message where a command that succeeded could not write its
 * output (a full disk, a closed pipe): stdout's error flag stays set. A failed command has said why. */
static int finish(const char *cmd, int status)
{
    if ((fflush(stdout) != 0 || ferror(stdout)) && status == 0) {
        fprintf(stderr, "hairbsdf %s: cannot write standard output: %s\n", cmd, strerror(errno));
        return 1;
    }
    return status;
}

static int run(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        usage(stdout);
        return 0;
    }
    if (strcmp(cmd, "eval") == 0)
        return cmd_eval(argc - 1, argv + 1, 0);
    if (strcmp(cmd, "pdf") == 0)
        return cmd_eval(argc - 1, argv + 1, 1);
    if (strcmp(cmd, "sample") == 0)
        return cmd_sample(argc - 1, argv + 1);
    if (strcmp(cmd, "dump") == 0)
        return cmd_dump(argc - 1, argv + 1);
    if (strcmp(cmd, "furnace") == 0)
        return cmd_furnace(argc - 1, argv + 1);
    if (strcmp(cmd, "dual") == 0)
        return cmd_dual(argc - 1, argv + 1);
    if (strcmp(cmd, "assembly") == 0)
        return cmd_assembly(argc - 1, argv + 1);
    if (strcmp(cmd, "tress") == 0)
        return cmd_tress(argc - 1, argv + 1);
    if (strcmp(cmd, "plan") == 0)
        return cmd_plan(argc - 1, argv + 1);
    if (strcmp(cmd, "bake") == 0)
        return cmd_bake(argc - 1, argv + 1);
    if (strcmp(cmd, "plot") == 0)
        return cmd_plot(argc - 1, argv + 1);
    if (strcmp(cmd, "isa") == 0)
        return cmd_isa();
    if (strcmp(cmd, "version") == 0 || strcmp(cmd, "--version") == 0) {
        printf("hairbsdf %s\n", hb_version(NULL, NULL, NULL));
        return 0;
    }
    fprintf(stderr, "hairbsdf: unknown command '%s' (see hairbsdf --help)\n", cmd);
    return 2;
}

int main(int argc, char **argv)
{
    return finish(argc > 1 ? argv[1] : "", run(argc, argv));
}

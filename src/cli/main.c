/* rtedge: runs each of rtedge's algorithms on an image file, one subcommand
 * per algorithm, the way the OpenCV tutorial rtedge grew from runs them one by
 * one. `rtedge` alone lists the subcommands; `rtedge CMD --help` explains one. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "rte_version.h"

static void list_commands(FILE *out)
{
    fprintf(out, "usage: rtedge COMMAND [options] (rtedge COMMAND --help for each;\n"
                 "rtedge --version)\n\ncommands:\n");
    for (const cli_entry *e = cli_commands; e->name; e++)
        fprintf(out, "  %-10s %s\n", e->name, e->summary);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        list_commands(stderr);
        return CLI_EXIT_USAGE;
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("rtedge %s (git %s)\n", RTE_VERSION, RTE_REVISION);
        return CLI_EXIT_OK;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
        strcmp(argv[1], "help") == 0) {
        list_commands(stdout);
        return CLI_EXIT_OK;
    }
    for (const cli_entry *e = cli_commands; e->name; e++)
        if (strcmp(e->name, argv[1]) == 0)
            return e->run(e, argc - 1, argv + 1);
    fprintf(stderr, "rtedge: unknown command '%s'\n", argv[1]);
    list_commands(stderr);
    return CLI_EXIT_USAGE;
}

/* SPDX-License-Identifier: MIT */
/* `conica`: dispatcher for the subcommands in cmd_*.c (the list is made by
 * the Makefile from the file names, see CMD_DEF). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "conica/common.h"

#define CONICA_CMD(name)                          \
    int conica_cmd_##name(int argc, char **argv); \
    extern const char conica_cmd_##name##_summary[];
#include "commands.def"
#undef CONICA_CMD

struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary; /* one line for `conica --help` */
};

#define CONICA_CMD(name) {#name, conica_cmd_##name, conica_cmd_##name##_summary},
static const struct command commands[] = {
#include "commands.def"
    {NULL, NULL, NULL}
};
#undef CONICA_CMD

static void usage(FILE *f)
{
    fprintf(f, "usage: conica COMMAND [OPTIONS] [ARGS]\n\ncommands:\n");
    for (const struct command *c = commands; c->name; c++)
        fprintf(f, "  %-10s  %s\n", c->name, c->summary);
    fprintf(f, "\n'conica COMMAND --help' describes a command.\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        usage(stdout);
        return CLI_EXIT_OK;
    }
    if (strcmp(argv[1], "--version") == 0) {
        return cli_version("conica");
    }
    for (const struct command *c = commands; c->name; c++)
        if (strcmp(argv[1], c->name) == 0)
            return c->run(argc - 1, argv + 1);
    return cli_usage_error("conica", "unknown command '%s'", argv[1]);
}

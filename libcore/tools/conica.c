/* SPDX-License-Identifier: MIT */
/* `conica`: dispatcher for the subcommands in cmd_*.c (the list is made by
 * the Makefile from the file names, see CMD_DEF). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "cli_opt.h"
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

static const cli_opt opts[] = {
    {0, NULL, 0, NULL, NULL, NULL, {0, 0, 0}},
};

/* The operands: the subcommand's name, for completions ("combs|errors|..."). */
#define CONICA_CMD(name) "|" #name
static const char command_words[] = "" 
#include "commands.def"
    ;
#undef CONICA_CMD

static void list_commands(FILE *f);

static const cli_tool tool = {
    "conica",
    "COMMAND [OPTION]... [ARG]...",
    "Conic-preserving curve subdivision, adaptive spline plotting and curve\n"
    "diagnostics. 'conica COMMAND --help' describes a command.\n",
    opts,
    NULL,
    command_words + 1,
    1,
    list_commands,
};

static void list_commands(FILE *f)
{
    fprintf(f, "\nCommands:\n");
    for (const struct command *c = commands; c->name; c++)
        fprintf(f, "  %-10s  %s\n", c->name, c->summary);
}

/* Every table: the dispatcher's, its commands, then each command's own. */
static int dump(void)
{
    cli_opt_dump(&tool, stdout);
    for (const struct command *c = commands; c->name; c++)
        printf("cmd\t%s\t%s\n", c->name, c->summary);
    for (const struct command *c = commands; c->name; c++) {
        char name[32], flag[] = "--dump-options";
        char *args[] = {name, flag, NULL};
        snprintf(name, sizeof name, "%s", c->name);
        if (c->run(2, args) != CLI_EXIT_OK)
            return CLI_EXIT_ERROR;
    }
    return fflush(stdout) == 0 ? CLI_EXIT_OK : CLI_EXIT_ERROR;
}

int main(int argc, char **argv)
{
    cli_parser p;
    int c;
    if (cli_opt_is_dump(argc, argv))
        return dump();
    cli_opt_begin(&p, &tool, argc, argv);
    while ((c = cli_opt_next(&p)) != CLI_OPT_END) {
        /* the table has no options: --help and --version end here */
        if (c == CLI_OPT_EXIT)
            return p.status;
    }
    if (p.optind >= argc)
        return cli_usage_error("conica", "no command (one of: %s)", command_words + 1);
    for (const struct command *cmd = commands; cmd->name; cmd++)
        if (strcmp(argv[p.optind], cmd->name) == 0)
            return cmd->run(argc - p.optind, argv + p.optind);
    return cli_usage_error("conica", "unknown command '%s'", argv[p.optind]);
}

/* SPDX-License-Identifier: MIT */
/* One option table per tool and subcommand (conica COMMAND, svgsmooth,
 * scadprofile) and everything made from it: the parser (glibc's
 * getopt_long: long options with `=VALUE` or a separate value, unambiguous
 * abbreviations, attached short values `-k5`, combined flags `-rj2`, `--`
 * ends the options), the --help text, --version, one wording for usage
 * errors, and the machine-readable listing (`TOOL --dump-options`) that
 * scripts/completions.sh turns into bash and zsh completions and that
 * tests/cli/cli_conventions.sh checks the man pages against.
 * Uses cli.h (messages, --version) and nothing else of the project. */
#ifndef CONICA_CLI_OPT_H
#define CONICA_CLI_OPT_H

#include <getopt.h>
#include <stddef.h>
#include <stdio.h>

/* Does an option take a value? */
enum { CLI_ARG_NONE = 0, CLI_ARG_REQUIRED = 1, CLI_ARG_OPTIONAL = 2 };

/* Ids of options without a short letter start here (above every char). */
#define CLI_OPT_LONG 256

/* What cli_opt_next() returns besides an option's id. */
enum {
    CLI_OPT_END = -1, /* no more options: operands are argv[optind..argc) */
    CLI_OPT_EXIT = -2 /* stop with exit status p->status (help, version or a usage error printed) */
};

/* Options in one table, at most (the parser's arrays are this big). */
#define CLI_OPT_MAX 64

typedef struct cli_opt {
    int id;            /* the short letter ('k' for -k), or CLI_OPT_LONG + n */
    const char *name;  /* long name without "--"; NULL: short option only */
    int arg;           /* CLI_ARG_* */
    const char *meta;  /* the value's name in --help ("K", "FILE") */
    /* what the value is, for completions: "file" (an empty value is a
     * usage error), or the words it may be separated by '|'
     * ("area|circle"); NULL: anything */
    const char *complete;
    /* the description, a printf format of up to three %g-style numbers
     * taken from v[] ("levels, 0..%.0f (default %.0f)"); lines after the
     * first are separated by '\n' and indented by the help printer */
    const char *help;
    double v[3];
} cli_opt;

typedef struct cli_tool {
    const char *prog;     /* "svgsmooth", "conica subdivide": usage errors and help */
    const char *synopsis; /* the operands after PROG, one usage form a line:
                             "[OPTION]... [IN]\n[OPTION]... FILE... -o DIR/" */
    const char *about;    /* paragraph(s) after the synopsis */
    const cli_opt *opts;  /* ended by an entry with id 0; --help, --version added */
    const char *epilog;   /* text after the options (exit status, notes) */
    const char *operands; /* what operands are, for completions: "file", "svg",
                             "dir" or '|'-separated words; NULL: none */
    int stop_at_operand;  /* options end at the first operand (the dispatcher) */
    void (*more_help)(FILE *f); /* what --help prints after the options (NULL: nothing) */
} cli_tool;

/* The parser's state. Read arg (the option's value, NULL when it has none)
 * and spelled (how the option is named in messages: "-k" or the full
 * "--levels", whatever abbreviation was typed) after each cli_opt_next(). */
typedef struct cli_parser {
    const cli_tool *tool;
    int argc;
    char **argv;
    const char *arg;
    char spelled[48];
    int status; /* exit status after CLI_OPT_EXIT */
    int optind; /* first operand after CLI_OPT_END */
    char shorts[3 * CLI_OPT_MAX + 4];
    struct option longs[CLI_OPT_MAX + 3];
} cli_parser;

/* Start parsing argv[1..argc) of one tool (resets getopt's state: call
 * once per command line, subcommands included). */
void cli_opt_begin(cli_parser *p, const cli_tool *t, int argc, char **argv);

/* The next option's id, CLI_OPT_END, or CLI_OPT_EXIT after --help or
 * --version was handled or a usage error printed (unknown or ambiguous
 * option, missing value, value given to a flag). */
int cli_opt_next(cli_parser *p);

/* A usage error about the current option's value: `PROG: usage error:
 * SPELLED MESSAGE` plus the hint to --help; returns the exit status 2
 * (also left in p->status): `return cli_opt_bad(p, "needs ...", ...)`. */
int cli_opt_bad(cli_parser *p, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* --help of the tool on f (what cli_opt_next prints for --help). */
void cli_opt_help(const cli_tool *t, FILE *f);

/* Consume the next argument as the value of an option with an optional
 * value when it satisfies accept() and none was attached (`--opt VALUE` as
 * well as `--opt=VALUE`); returns it, or NULL (nothing consumed). */
const char *cli_opt_optional_next(cli_parser *p, int (*accept)(const char *));

/* The machine-readable table of one tool, tab-separated, one record a
 * line: `tool PROG OPERANDS` then `opt SHORT LONG ARG META COMPLETE HELP`
 * (`-` for an empty field; HELP: the first line of the description). */
void cli_opt_dump(const cli_tool *t, FILE *f);

/* Is argv exactly `PROG --dump-options`? (Checked before parsing, so that
 * the hidden option takes no part in abbreviations.) */
int cli_opt_is_dump(int argc, char **argv);

/* The whole parse of one command line: `PROG --dump-options` listed,
 * then every option handed to take(p, id, ctx), which returns -1 to go on
 * or an exit status to stop with. Returns -1 with *first_operand set (the
 * operands are argv[*first_operand..argc)), or the exit status to end the
 * tool with (0 after --help, --version or --dump-options, 2 after a usage
 * error). */
int cli_opt_parse(const cli_tool *t, int argc, char **argv,
                  int (*take)(cli_parser *p, int id, void *ctx), void *ctx, int *first_operand);

/* The one input file of a command that reads one: argv[first] into *path
 * (NULL when there is none and none is required). Returns -1 to go on, or
 * 2 after a usage error (none given, or more than one). */
int cli_opt_one_operand(const cli_tool *t, int argc, char **argv, int first, int required,
                        const char **path);

/* "1 element" / "2 elements": the plural form for n (s appended). */
const char *cli_plural(size_t n);

#endif

/* SPDX-License-Identifier: MIT */
/* The option tables of the tools (cli_opt.h): getopt_long's arrays built
 * from a table, the errors it reports said in the tools' one wording, the
 * --help text and the --dump-options listing. Calls cli.h and libc only.
 *
 * getopt_long (glibc) rather than a parser of our own: it is what users'
 * other tools do (abbreviations, `--opt=VALUE`, `-k5`, `-rj2`, `--`,
 * operands among options), and it keeps global state, so every command
 * line starts with optind = 0 (glibc's full reset). */
#include "cli_opt.h"

#include <stdarg.h>
#include <string.h>

#include "cli.h"

/* Ids of the options every tool has (beyond any table's ids). */
enum { ID_HELP = 'h', ID_VERSION = CLI_OPT_LONG + 4096 };

/* The entries of --help and --version in help and listings. */
static const cli_opt std_opts[2] = {
    {ID_HELP, "help", CLI_ARG_NONE, NULL, NULL, "display this help and exit", {0, 0, 0}},
    {ID_VERSION, "version", CLI_ARG_NONE, NULL, NULL, "output version information and exit",
     {0, 0, 0}},
};

/* Column where --help's descriptions start. */
#define HELP_COLUMN 26

const char *cli_plural(size_t n)
{
    return n == 1 ? "" : "s";
}

static size_t count_opts(const cli_opt *o)
{
    size_t n = 0;
    while (o[n].id != 0)
        n++;
    return n;
}

void cli_opt_begin(cli_parser *p, const cli_tool *t, int argc, char **argv)
{
    size_t n = count_opts(t->opts), k = 0, s = 0;
    memset(p, 0, sizeof *p);
    p->tool = t;
    p->argc = argc;
    p->argv = argv;
    if (n > CLI_OPT_MAX) /* a table too big is the programmer's error: drop the rest */
        n = CLI_OPT_MAX;
    if (t->stop_at_operand)
        p->shorts[s++] = '+';
    p->shorts[s++] = ':'; /* a missing value returns ':' rather than '?' */
    p->shorts[s++] = 'h';
    for (size_t i = 0; i < n; i++) {
        const cli_opt *o = &t->opts[i];
        if (o->id < CLI_OPT_LONG) {
            p->shorts[s++] = (char)o->id;
            if (o->arg != CLI_ARG_NONE)
                p->shorts[s++] = ':';
            if (o->arg == CLI_ARG_OPTIONAL)
                p->shorts[s++] = ':';
        }
        if (o->name) {
            p->longs[k].name = o->name;
            p->longs[k].has_arg = o->arg == CLI_ARG_REQUIRED   ? required_argument
                                  : o->arg == CLI_ARG_OPTIONAL ? optional_argument
                                                               : no_argument;
            p->longs[k].flag = NULL;
            p->longs[k].val = o->id;
            k++;
        }
    }
    p->shorts[s] = '\0';
    p->longs[k].name = "help";
    p->longs[k].has_arg = no_argument;
    p->longs[k++].val = ID_HELP;
    p->longs[k].name = "version";
    p->longs[k].has_arg = no_argument;
    p->longs[k++].val = ID_VERSION;
    memset(&p->longs[k], 0, sizeof p->longs[k]);
    optind = 0; /* glibc: reinitialise completely (the "+" and POSIXLY_CORRECT too) */
    opterr = 0; /* the errors are said below, in the tools' wording */
}

static const cli_opt *find_id(const cli_tool *t, int id)
{
    for (const cli_opt *o = t->opts; o->id != 0; o++)
        if (o->id == id)
            return o;
    return NULL;
}

/* "-k" or "--levels" for the option with this id, as the user typed it. */
static void spell(cli_parser *p, int id, int as_long)
{
    const cli_opt *o = find_id(p->tool, id);
    const char *name = id == ID_HELP ? "help" : id == ID_VERSION ? "version" : o ? o->name : NULL;
    if (as_long && name)
        snprintf(p->spelled, sizeof p->spelled, "--%s", name);
    else if (id < CLI_OPT_LONG)
        snprintf(p->spelled, sizeof p->spelled, "-%c", (char)id);
    else
        snprintf(p->spelled, sizeof p->spelled, "--%s", name ? name : "?");
}

static int usage_exit(cli_parser *p, const char *fmt, ...) CLI_PRINTF(2, 3);
static int usage_exit(cli_parser *p, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    p->status = cli_usage_error(p->tool->prog, "%s", msg);
    return CLI_OPT_EXIT;
}

int cli_opt_bad(cli_parser *p, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    usage_exit(p, "%s %s", p->spelled, msg);
    return p->status;
}

/* A long option getopt_long refused: unknown, ambiguous, or a flag given
 * `=VALUE`. word is the argument as typed ("--ma=3"). */
static int bad_long(cli_parser *p, const char *word)
{
    size_t len = strcspn(word + 2, "=");
    const struct option *hit = NULL;
    char list[256] = "";
    size_t used = 0;
    int hits = 0;
    for (const struct option *l = p->longs; l->name; l++) {
        if (strncmp(l->name, word + 2, len) != 0)
            continue;
        if (strlen(l->name) == len) { /* exact: a flag with a value */
            hit = l;
            hits = 1;
            break;
        }
        hit = l;
        hits++;
        if (used + strlen(l->name) + 5 < sizeof list)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s--%s", used ? ", " : "",
                                     l->name);
    }
    if (hits > 1)
        return usage_exit(p, "option '%.*s' is ambiguous (%s)", (int)len + 2, word, list);
    if (hits == 1 && word[2 + len] == '=' && hit->has_arg == no_argument)
        return usage_exit(p, "option '--%s' takes no value", hit->name);
    return usage_exit(p, "unknown option '%.*s'", (int)len + 2, word);
}

int cli_opt_next(cli_parser *p)
{
    int idx = -1, c;
    p->arg = NULL;
    p->spelled[0] = '\0';
    c = getopt_long(p->argc, p->argv, p->shorts, p->longs, &idx);
    if (c == -1) {
        p->optind = optind;
        return CLI_OPT_END;
    }
    if (c == '?') {
        /* glibc: optopt 0 for an unknown or ambiguous long option, the
         * option's value for a flag given `=VALUE`, the letter of an
         * unknown short option; a long one is argv[optind - 1] */
        if (optopt == 0 || (optopt != '?' && (optopt >= CLI_OPT_LONG || find_id(p->tool, optopt) ||
                                              optopt == ID_HELP)))
            if (optind >= 1 && optind - 1 < p->argc && strncmp(p->argv[optind - 1], "--", 2) == 0)
                return bad_long(p, p->argv[optind - 1]);
        return usage_exit(p, "unknown option '-%c'", optopt > 32 && optopt < 127 ? optopt : '?');
    }
    if (c == ':') {
        /* only the last argument can lack its value */
        const char *w = p->argv[p->argc - 1];
        spell(p, optopt, strncmp(w, "--", 2) == 0);
        const cli_opt *o = find_id(p->tool, optopt);
        return usage_exit(p, "%s needs a value (%s)", p->spelled, o && o->meta ? o->meta : "ARG");
    }
    spell(p, c, idx >= 0);
    p->arg = optarg;
    {
        /* a file name given as '' (`-o ''`): said here, once for every tool */
        const cli_opt *o = find_id(p->tool, c);
        if (o && o->complete && strcmp(o->complete, "file") == 0 && optarg && !*optarg)
            return usage_exit(p, "%s needs a file name", p->spelled);
    }
    if (c == ID_HELP) {
        cli_opt_help(p->tool, stdout);
        p->status = fflush(stdout) == 0 && !ferror(stdout)
                        ? CLI_EXIT_OK
                        : cli_error(p->tool->prog, "<stdout>", "write error");
        return CLI_OPT_EXIT;
    }
    if (c == ID_VERSION) {
        /* one version line per program: `conica (Conica) V` for its subcommands too */
        char name[64];
        snprintf(name, sizeof name, "%.*s", (int)strcspn(p->tool->prog, " "), p->tool->prog);
        p->status = cli_version(name);
        return CLI_OPT_EXIT;
    }
    return c;
}

const char *cli_opt_optional_next(cli_parser *p, int (*accept)(const char *))
{
    if (p->arg || optind >= p->argc || !accept(p->argv[optind]))
        return NULL;
    p->arg = p->argv[optind++];
    return p->arg;
}

int cli_opt_parse(const cli_tool *t, int argc, char **argv,
                  int (*take)(cli_parser *p, int id, void *ctx), void *ctx, int *first_operand)
{
    cli_parser p;
    int c, rc;
    if (cli_opt_is_dump(argc, argv)) {
        cli_opt_dump(t, stdout);
        return fflush(stdout) == 0 ? CLI_EXIT_OK : CLI_EXIT_ERROR;
    }
    cli_opt_begin(&p, t, argc, argv);
    while ((c = cli_opt_next(&p)) != CLI_OPT_END) {
        if (c == CLI_OPT_EXIT)
            return p.status;
        if ((rc = take(&p, c, ctx)) >= 0)
            return rc;
    }
    *first_operand = p.optind;
    return -1;
}

int cli_opt_one_operand(const cli_tool *t, int argc, char **argv, int first, int required,
                        const char **path)
{
    *path = first < argc ? argv[first] : NULL;
    if (first + 1 < argc)
        return cli_usage_error(t->prog, "one input file only ('%s', '%s')", argv[first],
                               argv[first + 1]);
    if (!*path && required)
        return cli_usage_error(t->prog, "no input file (a file name, or - for standard input)");
    return -1;
}

/* ---------------------------------------------------------------- help */

/* The option column of one entry: "  -k, --levels=K". */
static int option_column(const cli_opt *o, char *buf, size_t cap)
{
    int n;
    const char *m = o->meta ? o->meta : "ARG";
    if (o->id < CLI_OPT_LONG && o->name)
        n = snprintf(buf, cap, "  -%c, --%s", (char)o->id, o->name);
    else if (o->id < CLI_OPT_LONG)
        n = snprintf(buf, cap, "  -%c", (char)o->id);
    else
        n = snprintf(buf, cap, "      --%s", o->name);
    if (n < 0 || (size_t)n >= cap)
        return n;
    if (o->arg == CLI_ARG_REQUIRED)
        n += snprintf(buf + n, cap - (size_t)n, o->name ? "=%s" : " %s", m);
    else if (o->arg == CLI_ARG_OPTIONAL)
        n += snprintf(buf + n, cap - (size_t)n, o->name ? "[=%s]" : "[%s]", m);
    return n;
}

static void print_entry(FILE *f, const cli_opt *o)
{
    char col[96], text[1024];
    int n = option_column(o, col, sizeof col);
    /* the table's formats take up to three numbers from v[] */
    snprintf(text, sizeof text, o->help, o->v[0], o->v[1], o->v[2]);
    fputs(col, f);
    if (n + 2 > HELP_COLUMN)
        fprintf(f, "\n%*s", HELP_COLUMN, "");
    else
        fprintf(f, "%*s", HELP_COLUMN - n, "");
    for (const char *s = text; *s; s++) {
        fputc(*s, f);
        if (*s == '\n' && s[1])
            fprintf(f, "%*s", HELP_COLUMN, "");
    }
    fputc('\n', f);
}

void cli_opt_help(const cli_tool *t, FILE *f)
{
    const char *s = t->synopsis;
    int first = 1;
    while (*s) {
        size_t len = strcspn(s, "\n");
        fprintf(f, "%s %s %.*s\n", first ? "Usage:" : "  or: ", t->prog, (int)len, s);
        first = 0;
        s += len + (s[len] == '\n');
    }
    if (t->about)
        fprintf(f, "%s", t->about);
    fputs("\nOptions:\n", f);
    for (const cli_opt *o = t->opts; o->id != 0; o++)
        print_entry(f, o);
    print_entry(f, &std_opts[0]);
    print_entry(f, &std_opts[1]);
    if (t->more_help)
        t->more_help(f);
    fputs("\nLong options may be abbreviated while unambiguous, and take their value\n"
          "as --name=VALUE or --name VALUE; short ones as -kVALUE or -k VALUE.\n",
          f);
    if (t->epilog)
        fprintf(f, "\n%s", t->epilog);
}

/* ---------------------------------------------------------------- dump */

static void dump_entry(FILE *f, const cli_opt *o)
{
    char text[1024];
    snprintf(text, sizeof text, o->help, o->v[0], o->v[1], o->v[2]);
    text[strcspn(text, "\n\t")] = '\0';
    fprintf(f, "opt\t%c\t%s\t%s\t%s\t%s\t%s\n", o->id < CLI_OPT_LONG ? (char)o->id : '-',
            o->name ? o->name : "-",
            o->arg == CLI_ARG_REQUIRED   ? "required"
            : o->arg == CLI_ARG_OPTIONAL ? "optional"
                                         : "none",
            o->meta ? o->meta : "-", o->complete ? o->complete : "-", text);
}

void cli_opt_dump(const cli_tool *t, FILE *f)
{
    fprintf(f, "tool\t%s\t%s\n", t->prog, t->operands ? t->operands : "-");
    for (const cli_opt *o = t->opts; o->id != 0; o++)
        dump_entry(f, o);
    dump_entry(f, &std_opts[0]);
    dump_entry(f, &std_opts[1]);
}

int cli_opt_is_dump(int argc, char **argv)
{
    return argc == 2 && strcmp(argv[1], "--dump-options") == 0;
}

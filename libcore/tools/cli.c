/* SPDX-License-Identifier: MIT */
/* realpath() is XSI, outside the POSIX base the build asks for. */
#define _XOPEN_SOURCE 700

#include "cli.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "conica/curve.h"

static void vmessage(const char *prog, const char *kind, const char *where,
                     const char *fmt, va_list ap)
{
    fprintf(stderr, "%s: %s: ", prog, kind);
    if (where && *where)
        fprintf(stderr, "%s: ", where);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
}

int cli_error(const char *prog, const char *where, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(prog, "error", where, fmt, ap);
    va_end(ap);
    return CLI_EXIT_ERROR;
}

void cli_warning(const char *prog, const char *where, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(prog, "warning", where, fmt, ap);
    va_end(ap);
}

int cli_usage_error(const char *prog, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmessage(prog, "usage error", NULL, fmt, ap);
    va_end(ap);
    fprintf(stderr, "Try '%s --help' for more information.\n", prog);
    return CLI_EXIT_USAGE;
}

size_t cli_max_input(const char *prog)
{
    const char *v = getenv(CLI_MAX_INPUT_ENV);
    long n;
    if (!v || !*v)
        return CLI_DEFAULT_MAX_INPUT;
    if (cli_parse_int(v, 1, (long)1 << 40, &n) != 0) {
        cli_warning(prog, NULL, "%s='%s' is not a whole number of bytes in 1..2^40; using %zu",
                    CLI_MAX_INPUT_ENV, v, (size_t)CLI_DEFAULT_MAX_INPUT);
        return CLI_DEFAULT_MAX_INPUT;
    }
    return (size_t)n;
}

int cli_read_file(const char *prog, const char *path, size_t max_bytes, char **buf, size_t *len)
{
    int is_stdin = path == NULL || strcmp(path, "-") == 0;
    const char *name = is_stdin ? "<stdin>" : path;
    FILE *f = is_stdin ? stdin : fopen(path, "rb");
    size_t cap = 4096, n = 0;
    char *data;

    if (!f)
        return cli_error(prog, name, "cannot open: %s", strerror(errno));
    data = malloc(cap);
    if (!data) {
        if (!is_stdin)
            fclose(f);
        return cli_error(prog, name, "out of memory");
    }
    for (;;) {
        size_t got;
        if (cap - n < 2) {
            size_t ncap = cap * 2;
            char *p;
            if (cap > max_bytes) {
                free(data);
                if (!is_stdin)
                    fclose(f);
                return cli_error(prog, name, "input larger than the limit of %zu bytes", max_bytes);
            }
            p = realloc(data, ncap);
            if (!p) {
                free(data);
                if (!is_stdin)
                    fclose(f);
                return cli_error(prog, name, "out of memory");
            }
            data = p;
            cap = ncap;
        }
        got = fread(data + n, 1, cap - n - 1, f);
        n += got;
        if (n > max_bytes) {
            free(data);
            if (!is_stdin)
                fclose(f);
            return cli_error(prog, name, "input larger than the limit of %zu bytes", max_bytes);
        }
        if (got == 0)
            break;
    }
    if (ferror(f)) {
        int e = errno;
        free(data);
        if (!is_stdin)
            fclose(f);
        return cli_error(prog, name, "read error: %s", strerror(e));
    }
    if (!is_stdin)
        fclose(f);
    data[n] = '\0';
    *buf = data;
    *len = n;
    return 0;
}

/* ------------------------------------------------------------ signals */

/* The signals that remove the temporary before the tool dies: the terminal
 * and session ones (Ctrl-C, kill, timeout(1), a closed terminal), a broken
 * pipe, and the file-size limit (ulimit -f) that writing the temporary can
 * hit. SIGKILL cannot be caught: it leaves the hidden temporary. */
static const int cli_sig_list[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGXFSZ};
static const char *const cli_sig_names[] = {"SIGINT", "SIGTERM", "SIGHUP", "SIGPIPE",
                                            "SIGXFSZ (file size limit exceeded)"};
#define CLI_NSIG (sizeof cli_sig_list / sizeof cli_sig_list[0])

/* The one piece of global state of the tools (STYLE.md allows it for a
 * signal handler): what the handler needs to remove the open temporary and
 * say so, and the dispositions to restore. Set and cleared with the
 * signals blocked; the handler only reads it. One output at a time. */
static struct {
    const char *volatile tmp; /* the temporary to unlink, NULL when none */
    const char *prog;         /* for the message */
    const char *target;       /* the output it stands for */
    struct sigaction old[CLI_NSIG];
    int installed[CLI_NSIG];
} cli_sig;

static void cli_sig_write(const char *s)
{
    size_t n = strlen(s);
    while (n > 0) {
        ssize_t k = write(STDERR_FILENO, s, n);
        if (k <= 0)
            return;
        s += k;
        n -= (size_t)k;
    }
}

/* Async-signal-safe only: unlink, write, sigaction, sigprocmask, raise, _exit. */
static void cli_sig_handler(int signo)
{
    const char *tmp = cli_sig.tmp;
    const char *name = "a signal";
    size_t i;
    int saved = errno;
    for (i = 0; i < CLI_NSIG; i++)
        if (cli_sig_list[i] == signo)
            name = cli_sig_names[i];
    if (tmp) {
        cli_sig.tmp = NULL;
        unlink(tmp);
        cli_sig_write(cli_sig.prog);
        cli_sig_write(": error: ");
        cli_sig_write(cli_sig.target);
        cli_sig_write(": stopped by ");
        cli_sig_write(name);
        cli_sig_write("; output not written (the temporary file was removed)\n");
    }
    errno = saved;
    if (signo == SIGXFSZ)
        _exit(128 + signo); /* its default action would dump core */
    /* Die of the signal itself, so a calling shell sees what happened
     * (a loop in a script stops at Ctrl-C): status 128 + signo. */
    {
        struct sigaction dfl;
        sigset_t set;
        memset(&dfl, 0, sizeof dfl);
        dfl.sa_handler = SIG_DFL;
        sigemptyset(&dfl.sa_mask);
        sigaction(signo, &dfl, NULL);
        sigemptyset(&set);
        sigaddset(&set, signo);
        sigprocmask(SIG_UNBLOCK, &set, NULL);
        raise(signo);
    }
    _exit(128 + signo);
}

static void cli_sig_block(sigset_t *old)
{
    sigset_t set;
    size_t i;
    sigemptyset(&set);
    for (i = 0; i < CLI_NSIG; i++)
        sigaddset(&set, cli_sig_list[i]);
    sigprocmask(SIG_BLOCK, &set, old);
}

/* Register tmp (signals blocked by the caller) and catch the signals,
 * except those the tool was started with ignored (nohup, a background
 * job's SIGINT): they stay ignored. */
static void cli_sig_arm(const char *prog, const char *target, const char *tmp)
{
    struct sigaction sa;
    size_t i;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = cli_sig_handler;
    sigemptyset(&sa.sa_mask);
    for (i = 0; i < CLI_NSIG; i++)
        sigaddset(&sa.sa_mask, cli_sig_list[i]); /* one handler runs at a time */
    cli_sig.prog = prog;
    cli_sig.target = target;
    cli_sig.tmp = tmp;
    for (i = 0; i < CLI_NSIG; i++) {
        cli_sig.installed[i] = 0;
        if (sigaction(cli_sig_list[i], NULL, &cli_sig.old[i]) != 0 ||
            cli_sig.old[i].sa_handler == SIG_IGN)
            continue;
        cli_sig.installed[i] = sigaction(cli_sig_list[i], &sa, NULL) == 0;
    }
}

/* Forget the temporary and restore the dispositions (signals blocked). */
static void cli_sig_disarm(void)
{
    size_t i;
    cli_sig.tmp = NULL;
    for (i = 0; i < CLI_NSIG; i++)
        if (cli_sig.installed[i]) {
            sigaction(cli_sig_list[i], &cli_sig.old[i], NULL);
            cli_sig.installed[i] = 0;
        }
}

/* ------------------------------------------------------------ output */

/* The temporary beside target: ".NAME.conica-tmp.XXXXXX" in the same
 * directory (rename() within one file system is atomic), hidden so that
 * the one that SIGKILL or a crash can leave behind does not show up in
 * listings and globs, and named so that it says what it is. */
static char *temp_name(const char *target)
{
    static const char suffix[] = ".conica-tmp.XXXXXX";
    const char *slash = strrchr(target, '/');
    size_t dlen = slash ? (size_t)(slash - target) + 1 : 0;
    size_t blen = strlen(target + dlen);
    char *t = malloc(dlen + 1 + blen + sizeof suffix);
    if (!t)
        return NULL;
    memcpy(t, target, dlen);
    t[dlen] = '.';
    memcpy(t + dlen + 1, target + dlen, blen);
    memcpy(t + dlen + 1 + blen, suffix, sizeof suffix);
    return t;
}

int cli_output_open(const char *prog, const char *path, cli_output *out)
{
    struct stat sb, lsb;
    char *target = NULL;
    sigset_t held;
    int fd, e;

    out->f = NULL;
    out->path = NULL;
    out->tmp = NULL;
    out->mode = 0;
    if (path == NULL || strcmp(path, "-") == 0) {
        out->f = stdout;
        return 0;
    }
    if (stat(path, &sb) == 0) {
        if (S_ISDIR(sb.st_mode))
            return cli_error(prog, path, "is a directory");
        if (!S_ISREG(sb.st_mode)) {
            out->f = fopen(path, "wb");
            if (!out->f)
                return cli_error(prog, path, "cannot open output: %s", strerror(errno));
            return 0;
        }
        /* An existing regular file: the replacement gets the permissions
         * the user chose for it. When the name is a symbolic link (to a
         * link ...), replace the file the links lead to, not the link; a
         * link among the directories does not matter to rename(). */
        out->mode = (unsigned)(sb.st_mode & 0777); /* not set-id bits */
        if (lstat(path, &lsb) == 0 && S_ISLNK(lsb.st_mode)) {
            target = realpath(path, NULL);
            if (!target)
                return cli_error(prog, path, "cannot resolve the symbolic link: %s",
                                 strerror(errno));
        }
    } else if (lstat(path, &lsb) == 0 && S_ISLNK(lsb.st_mode)) {
        /* rename() would replace the link itself with a regular file */
        return cli_error(prog, path, "is a symbolic link to a missing file; "
                         "not replacing the link");
    } else {
        mode_t mask = umask(0);
        umask(mask);
        out->mode = (unsigned)(0666 & ~mask);
    }
    if (!target) {
        target = malloc(strlen(path) + 1);
        if (!target)
            return cli_error(prog, path, "out of memory");
        memcpy(target, path, strlen(path) + 1);
    }
    out->path = target;
    out->tmp = temp_name(target);
    if (!out->tmp) {
        free(out->path);
        out->path = NULL;
        return cli_error(prog, path, "out of memory");
    }
    /* The temporary lives beside the (resolved) target so rename() is
     * atomic; from its creation on, a signal removes it (cli_sig_*). */
    cli_sig_block(&held);
    fd = mkstemp(out->tmp);
    e = errno;
    if (fd >= 0)
        cli_sig_arm(prog, out->path, out->tmp);
    sigprocmask(SIG_SETMASK, &held, NULL);
    if (fd < 0) {
        free(out->path);
        free(out->tmp);
        out->path = out->tmp = NULL;
        return cli_error(prog, path, "cannot create output: %s", strerror(e));
    }
    out->f = fdopen(fd, "wb");
    if (!out->f) {
        e = errno;
        close(fd);
        cli_output_abort(out);
        return cli_error(prog, path, "cannot open output: %s", strerror(e));
    }
    return 0;
}

int cli_output_commit(const char *prog, cli_output *out)
{
    int failed = 0, e = 0;

    if (!out->f)
        return cli_error(prog, out->path, "output not open");
    if (!out->tmp) {
        /* stdout, or a device written in place */
        int bad = fflush(out->f) != 0 || ferror(out->f);
        int err = errno;
        int is_stdout = out->f == stdout;
        if (!is_stdout && fclose(out->f) != 0 && !bad) {
            bad = 1;
            err = errno;
        }
        out->f = NULL;
        if (bad)
            return cli_error(prog, is_stdout ? "<stdout>" : "<output>", "write error: %s",
                             strerror(err));
        return 0;
    }
    if (fflush(out->f) != 0 || ferror(out->f) || fsync(fileno(out->f)) != 0) {
        failed = 1;
        e = errno;
    }
    /* mkstemp made the temporary 0600: give it the old file's mode (or a
     * new file's 0666 & ~umask) before it becomes visible. A file system
     * without permissions may refuse; the file then stays 0600, the safe
     * side, so that is not an error. */
    if (!failed)
        (void)fchmod(fileno(out->f), (mode_t)out->mode);
    if (fclose(out->f) != 0 && !failed) {
        failed = 1;
        e = errno;
    }
    out->f = NULL;
    {
        /* rename or unlink, and forget the temporary, with the signals
         * held: a handler then never removes a name already renamed */
        sigset_t mask;
        cli_sig_block(&mask);
        if (!failed && rename(out->tmp, out->path) != 0) {
            failed = 1;
            e = errno;
        }
        if (failed)
            unlink(out->tmp);
        cli_sig_disarm();
        sigprocmask(SIG_SETMASK, &mask, NULL);
    }
    if (failed)
        cli_error(prog, out->path, "cannot write output: %s", strerror(e));
    free(out->tmp);
    free(out->path);
    out->tmp = out->path = NULL;
    return failed;
}

void cli_output_abort(cli_output *out)
{
    if (out->f && out->f != stdout)
        fclose(out->f);
    if (out->tmp) {
        sigset_t mask;
        cli_sig_block(&mask);
        unlink(out->tmp);
        cli_sig_disarm();
        sigprocmask(SIG_SETMASK, &mask, NULL);
    }
    free(out->tmp);
    free(out->path);
    out->f = NULL;
    out->tmp = out->path = NULL;
}

int cli_ends_with_ci(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix), i;
    if (n < m)
        return 0;
    for (i = 0; i < m; i++) {
        char c = s[n - m + i];
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
        if (c != suffix[i])
            return 0;
    }
    return 1;
}

int cli_parse_int(const char *s, long lo, long hi, long *out)
{
    long v = 0;
    int neg = 0;
    const char *p = s;

    if (!s || !*s)
        return 1;
    if (*p == '+' || *p == '-')
        neg = *p++ == '-';
    if (!*p)
        return 1;
    for (; *p; p++) {
        if (*p < '0' || *p > '9')
            return 1;
        if (v > (LONG_MAX - (*p - '0')) / 10)
            return 1;
        v = v * 10 + (*p - '0');
    }
    if (neg)
        v = -v;
    if (v < lo || v > hi)
        return 1;
    *out = v;
    return 0;
}

int cli_parse_double(const char *s, double *out)
{
    /* Validate the grammar ourselves (digits, one '.', optional exponent:
     * nothing locale-dependent, no hex, no inf/nan), then let strtod do the
     * correctly rounded conversion: the tools never call setlocale(), so
     * LC_NUMERIC is "C" and '.' is the decimal point. */
    const char *p = s;
    char *end;
    double v;
    int digits = 0;

    if (!s || !*s)
        return 1;
    if (*p == '+' || *p == '-')
        p++;
    while (*p >= '0' && *p <= '9') { p++; digits++; }
    if (*p == '.') {
        p++;
        while (*p >= '0' && *p <= '9') { p++; digits++; }
    }
    if (!digits)
        return 1;
    if (*p == 'e' || *p == 'E') {
        p++;
        if (*p == '+' || *p == '-')
            p++;
        if (!(*p >= '0' && *p <= '9'))
            return 1;
        while (*p >= '0' && *p <= '9')
            p++;
    }
    if (*p)
        return 1;
    errno = 0;
    v = strtod(s, &end);
    if (*end || !isfinite(v))
        return 1;
    *out = v;
    return 0;
}

/* A subdivision whose output overflowed: the input point of the largest
 * coordinate when that is beyond CLI_HUGE_COORD (its index in *index and
 * the coordinate in *value), else 0. */
static int huge_input_point(const char *buf, size_t len, conica_code code,
                            const conica_status *st, size_t *index, double *value)
{
    conica_curve c;
    size_t i, best = 0;
    double big = 0.0;
    if (code != CONICA_ERR_NUMERIC || !strstr(st->message, "of the output is not finite"))
        return 0;
    conica_curve_init(&c);
    if (conica_curve_parse(buf, len, &c, NULL) != CONICA_OK) {
        conica_curve_free(&c);
        return 0;
    }
    for (i = 0; i < 2 * c.n; i++)
        if (fabs(c.xy[i]) > big) {
            big = fabs(c.xy[i]);
            best = i;
        }
    if (big > CLI_HUGE_COORD)
        *value = c.xy[best];
    conica_curve_free(&c);
    if (!(big > CLI_HUGE_COORD))
        return 0;
    *index = best / 2;
    return 1;
}

size_t cli_point_failure(const char *buf, size_t len, conica_code code, const conica_status *st,
                         char *msg, size_t cap)
{
    size_t index = 0;
    double value = 0.0;
    const char *what = st->message[0] ? st->message : conica_strerror(code);
    if (huge_input_point(buf, len, code, st, &index, &value)) {
        snprintf(msg, cap,
                 "coordinate %g of point %zu is too large for the subdivision (its squares "
                 "overflow: keep coordinates within +-%g); %s",
                 value, index + 1, CLI_HUGE_COORD, what);
        return conica_curve_line_of_point(buf, len, index, 0);
    }
    snprintf(msg, cap, "%s", what);
    return cli_point_line(buf, len, code, st);
}

size_t cli_point_line(const char *buf, size_t len, conica_code code, const conica_status *st)
{
    if (code != CONICA_ERR_DEGENERATE && code != CONICA_ERR_NONFINITE)
        return 0;
    if (strncmp(st->message, "point", 5) == 0)
        return conica_curve_line_of_point(buf, len, st->offset, 0);
    if (strncmp(st->message, "normal", 6) == 0)
        return conica_curve_line_of_point(buf, len, st->offset, 1);
    return 0;
}

int cli_version(const char *tool)
{
    printf("%s (Conica) %s\n", tool, conica_version());
    if (fflush(stdout) != 0 || ferror(stdout))
        return cli_error(tool, "<stdout>", "write error");
    return CLI_EXIT_OK;
}

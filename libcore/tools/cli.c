/* SPDX-License-Identifier: MIT */
/* realpath() is XSI, outside the POSIX base the build asks for. */
#define _XOPEN_SOURCE 700
/* O_TMPFILE, SIGSTKFLT and SIGPWR are Linux extensions. */
#define _GNU_SOURCE

#include "cli.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
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

/* Every signal whose default action ends the process (POSIX's "T" and "A"
 * signals, and Linux's own), so that none of them can leave the temporary:
 * the terminal's and the session's (Ctrl-C, Ctrl-\, a closed terminal),
 * kill's and timeout(1)'s, the timers (SIGALRM, SIGVTALRM, SIGPROF), the
 * resource limits (ulimit -t: SIGXCPU, ulimit -f: SIGXFSZ), a broken pipe,
 * the user signals, abort() and the faults of a crash. The real-time
 * signals (their default ends the process too) are caught as well
 * (cli_sig_each). SIGKILL and SIGSTOP cannot be caught; a temporary made
 * with O_TMPFILE has no name until the commit, so even SIGKILL leaves
 * nothing then. */
static const struct {
    int no;
    const char *name;
    int fault; /* a synchronous fault: re-run by the kernel after the handler */
} cli_sig_list[] = {
    {SIGHUP, "SIGHUP", 0},     {SIGINT, "SIGINT", 0},       {SIGQUIT, "SIGQUIT", 0},
    {SIGILL, "SIGILL", 1},     {SIGTRAP, "SIGTRAP", 1},     {SIGABRT, "SIGABRT", 0},
    {SIGBUS, "SIGBUS", 1},     {SIGFPE, "SIGFPE", 1},       {SIGUSR1, "SIGUSR1", 0},
    {SIGSEGV, "SIGSEGV", 1},   {SIGUSR2, "SIGUSR2", 0},     {SIGPIPE, "SIGPIPE", 0},
    {SIGALRM, "SIGALRM", 0},   {SIGTERM, "SIGTERM", 0},     {SIGXCPU, "SIGXCPU", 0},
    {SIGXFSZ, "SIGXFSZ (file size limit exceeded)", 0},
    {SIGVTALRM, "SIGVTALRM", 0}, {SIGPROF, "SIGPROF", 0},   {SIGSYS, "SIGSYS", 1},
#ifdef SIGSTKFLT
    {SIGSTKFLT, "SIGSTKFLT", 0},
#endif
#ifdef SIGPOLL
    {SIGPOLL, "SIGPOLL", 0},
#endif
#ifdef SIGPWR
    {SIGPWR, "SIGPWR", 0},
#endif
};
#define CLI_NSIG (sizeof cli_sig_list / sizeof cli_sig_list[0])
/* Slots for the real-time signals after the fixed list. */
#define CLI_NSIG_RT 64
#define CLI_NSIG_ALL (CLI_NSIG + CLI_NSIG_RT)

/* The one piece of global state of the tools (STYLE.md allows it for a
 * signal handler): what the handler needs to remove the open temporary and
 * say so, and the dispositions to restore. Set and cleared with the
 * signals blocked; the handler only reads it. One output at a time. */
static struct {
    volatile int armed;     /* a temporary is open */
    int dirfd;              /* its directory (the handle, not the path) */
    const char *tmp;        /* its name in dirfd, NULL when it has none (O_TMPFILE) */
    const char *prog;       /* for the message */
    const char *target;     /* the output it stands for */
    int no[CLI_NSIG_ALL];   /* the signals caught, 0 for an unused slot */
    struct sigaction old[CLI_NSIG_ALL];
    int installed[CLI_NSIG_ALL];
} cli_sig;

/* Fill cli_sig.no: the fixed list, then SIGRTMIN..SIGRTMAX. */
static size_t cli_sig_each(void)
{
    size_t i, n = 0;
    for (i = 0; i < CLI_NSIG; i++)
        cli_sig.no[n++] = cli_sig_list[i].no;
#if defined(SIGRTMIN) && defined(SIGRTMAX)
    {
        int r;
        for (r = SIGRTMIN; r <= SIGRTMAX && n < CLI_NSIG_ALL; r++)
            cli_sig.no[n++] = r;
    }
#endif
    return n;
}

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

/* The signal's name, or "signal N" written into buf (async-signal-safe). */
static const char *cli_sig_name(int signo, int *fault, char *buf, size_t cap)
{
    size_t i, k = 0;
    char digits[12];
    int v = signo;
    *fault = 0;
    for (i = 0; i < CLI_NSIG; i++)
        if (cli_sig_list[i].no == signo) {
            *fault = cli_sig_list[i].fault;
            return cli_sig_list[i].name;
        }
    do {
        digits[k++] = (char)('0' + v % 10);
        v /= 10;
    } while (v > 0 && k < sizeof digits);
    memcpy(buf, "signal ", 7);
    for (i = 0; i < k && 7 + i + 1 < cap; i++)
        buf[7 + i] = digits[k - 1 - i];
    buf[7 + i] = '\0';
    return buf;
}

/* Async-signal-safe only: unlinkat, write, sigaction, sigprocmask, raise,
 * _exit. The temporary goes through the directory handle, so a directory
 * renamed while the tool wrote does not strand it. */
static void cli_sig_handler(int signo, siginfo_t *info, void *uc)
{
    char buf[24];
    int fault, saved = errno;
    size_t i;
    const char *name = cli_sig_name(signo, &fault, buf, sizeof buf);
    (void)uc;
    if (cli_sig.armed) {
        cli_sig.armed = 0;
        if (cli_sig.tmp)
            unlinkat(cli_sig.dirfd, cli_sig.tmp, 0);
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
    /* A fault the kernel raised (a crash) goes back to what handled it
     * before (the default action, or a sanitizer's report) and comes back
     * by itself when the instruction runs again. Any other signal is
     * raised again with its default action, unblocked, so a calling shell
     * sees the tool die of it (a loop in a script stops at Ctrl-C):
     * status 128 + signo. */
    if (fault && info && info->si_code > 0) {
        for (i = 0; i < CLI_NSIG_ALL; i++)
            if (cli_sig.no[i] == signo && cli_sig.installed[i]) {
                sigaction(signo, &cli_sig.old[i], NULL);
                cli_sig.installed[i] = 0;
            }
        return;
    }
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
    sigfillset(&set);
    sigprocmask(SIG_BLOCK, &set, old);
}

/* Register the temporary (signals blocked by the caller) and catch the
 * signals, except those the tool was started with ignored (nohup, a
 * background job's SIGINT): they stay ignored. */
static void cli_sig_arm(const char *prog, const char *target, int dirfd, const char *tmp)
{
    struct sigaction sa;
    size_t i, n = cli_sig_each();
    memset(&sa, 0, sizeof sa);
    sa.sa_sigaction = cli_sig_handler;
    sa.sa_flags = SA_SIGINFO;
    sigfillset(&sa.sa_mask); /* one handler runs at a time */
    cli_sig.prog = prog;
    cli_sig.target = target;
    cli_sig.dirfd = dirfd;
    cli_sig.tmp = tmp;
    cli_sig.armed = 1;
    for (i = 0; i < n; i++) {
        cli_sig.installed[i] = 0;
        if (sigaction(cli_sig.no[i], NULL, &cli_sig.old[i]) != 0 ||
            cli_sig.old[i].sa_handler == SIG_IGN)
            continue;
        cli_sig.installed[i] = sigaction(cli_sig.no[i], &sa, NULL) == 0;
    }
}

/* Forget the temporary and restore the dispositions (signals blocked). */
static void cli_sig_disarm(void)
{
    size_t i;
    cli_sig.armed = 0;
    cli_sig.tmp = NULL;
    for (i = 0; i < CLI_NSIG_ALL; i++)
        if (cli_sig.installed[i]) {
            sigaction(cli_sig.no[i], &cli_sig.old[i], NULL);
            cli_sig.installed[i] = 0;
        }
}

/* ------------------------------------------------------------ output */

/* The temporary's name in the target's directory: ".NAME.conica-tmp.XXXXXX"
 * (rename() within one directory is atomic), hidden so that one that a
 * crash can leave behind does not show up in listings and globs, and named
 * so that it says what it is. NAME is cut to what keeps the whole within
 * the directory's name limit (a valid 250-byte output name works). */
#define CLI_TMP_SUFFIX ".conica-tmp."
#define CLI_TMP_RANDOM 6
static char *temp_name(const char *base, long name_max)
{
    size_t blen = strlen(base), room, fixed = 1 + strlen(CLI_TMP_SUFFIX) + CLI_TMP_RANDOM;
    char *t;
    if (name_max <= 0)
        name_max = 255;
    room = (size_t)name_max > fixed ? (size_t)name_max - fixed : 0;
    if (blen > room)
        blen = room;
    t = malloc(fixed + blen + 1);
    if (!t)
        return NULL;
    t[0] = '.';
    memcpy(t + 1, base, blen);
    memcpy(t + 1 + blen, CLI_TMP_SUFFIX, strlen(CLI_TMP_SUFFIX));
    memset(t + 1 + blen + strlen(CLI_TMP_SUFFIX), 'X', CLI_TMP_RANDOM);
    t[fixed + blen] = '\0';
    return t;
}

/* Replace the trailing X's of name by letters and digits from a mix of
 * the clock, the process id and a counter (like mkstemp; the name need not
 * be secret: O_EXCL makes its creation safe). */
static void temp_fill(char *name, unsigned long long *state)
{
    static const char set[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    size_t n = strlen(name), i;
    unsigned long long x;
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
    x = *state ^ (*state >> 29);
    for (i = n - CLI_TMP_RANDOM; i < n; i++) {
        name[i] = set[x % (sizeof set - 1)];
        x /= sizeof set - 1;
    }
}

/* Create the temporary in dirfd: an unnamed O_TMPFILE file where the
 * file system has them and /proc can name it for linkat (nothing to leave
 * behind, even after SIGKILL), else a fresh name made with O_EXCL. Returns
 * the descriptor, *named 1 when the name in tmp is in use; -1 with errno. */
static int temp_create(int dirfd, char *tmp, int *named)
{
    struct timespec ts;
    unsigned long long state;
    int fd, tries;
    *named = 0;
#ifdef O_TMPFILE
    const char *mode = getenv(CLI_TMPFILE_ENV);
    if (!(mode && strcmp(mode, "named") == 0) && access("/proc/self/fd", X_OK) == 0) {
        fd = openat(dirfd, ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
        if (fd >= 0)
            return fd;
    }
#endif
    clock_gettime(CLOCK_REALTIME, &ts);
    state = (unsigned long long)ts.tv_nsec ^ ((unsigned long long)ts.tv_sec << 20) ^
            ((unsigned long long)getpid() << 40);
    for (tries = 0; tries < 1000; tries++) {
        temp_fill(tmp, &state);
        fd = openat(dirfd, tmp, O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0600);
        if (fd >= 0) {
            *named = 1;
            return fd;
        }
        if (errno != EEXIST)
            return -1;
    }
    return -1;
}

/* Give an unnamed temporary the name in tmp (fresh, retried on EEXIST).
 * Returns 0, or -1 with errno. */
static int temp_link(int fd, int dirfd, char *tmp)
{
    char proc[64];
    unsigned long long state = (unsigned long long)getpid() * 2654435761ULL;
    int tries;
    snprintf(proc, sizeof proc, "/proc/self/fd/%d", fd);
    for (tries = 0; tries < 1000; tries++) {
        temp_fill(tmp, &state);
        if (linkat(AT_FDCWD, proc, dirfd, tmp, AT_SYMLINK_FOLLOW) == 0)
            return 0;
        if (errno != EEXIST)
            return -1;
    }
    return -1;
}

/* The directory part of target (".", or up to its last slash) opened as a
 * handle, and a copy of its last component in *base. -1 with errno. */
static int open_dir_of(const char *target, const char **base)
{
    const char *slash = strrchr(target, '/');
    char *dir;
    int fd;
    if (!slash) {
        *base = target;
        return open(".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    }
    *base = slash + 1;
    dir = malloc((size_t)(slash - target) + 2);
    if (!dir) {
        errno = ENOMEM;
        return -1;
    }
    if (slash == target) {
        dir[0] = '/';
        dir[1] = '\0';
    } else {
        memcpy(dir, target, (size_t)(slash - target));
        dir[slash - target] = '\0';
    }
    fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    free(dir);
    return fd;
}

static void output_reset(cli_output *out)
{
    out->f = NULL;
    out->path = NULL;
    out->tmp = NULL;
    out->base = NULL;
    out->mode = 0;
    out->dirfd = -1;
    out->named = 0;
}

static char *copy_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *c = malloc(n);
    if (c)
        memcpy(c, s, n);
    return c;
}

int cli_output_open(const char *prog, const char *path, cli_output *out)
{
    struct stat sb, lsb;
    char *target = NULL;
    sigset_t held;
    int fd, e, named;
    long name_max;

    output_reset(out);
    if (path == NULL || strcmp(path, "-") == 0) {
        out->f = stdout;
        return 0;
    }
    if (stat(path, &sb) == 0) {
        if (S_ISDIR(sb.st_mode))
            return cli_error(prog, path, "is a directory");
        if (!S_ISREG(sb.st_mode)) {
            out->path = copy_str(path); /* named in a write error */
            if (!out->path)
                return cli_error(prog, path, "out of memory");
            out->f = fopen(path, "wb");
            if (!out->f) {
                e = errno;
                free(out->path);
                out->path = NULL;
                return cli_error(prog, path, "cannot open output: %s", strerror(e));
            }
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
    } else if (errno == ELOOP) {
        return cli_error(prog, path, "too many levels of symbolic links (a symbolic link "
                         "loop?); not replacing the link");
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
        target = copy_str(path);
        if (!target)
            return cli_error(prog, path, "out of memory");
    }
    out->path = target;
    /* The temporary is made and renamed through a handle on the target's
     * directory (openat/renameat): a directory renamed while the tool
     * writes takes the temporary with it, and the rename and any unlink
     * still find it. */
    out->dirfd = open_dir_of(target, &out->base);
    if (out->dirfd < 0) {
        e = errno;
        free(out->path);
        output_reset(out);
        return cli_error(prog, path, "cannot open the output's directory: %s", strerror(e));
    }
    name_max = fpathconf(out->dirfd, _PC_NAME_MAX);
    out->tmp = temp_name(out->base, name_max);
    if (!out->tmp) {
        close(out->dirfd);
        free(out->path);
        output_reset(out);
        return cli_error(prog, path, "out of memory");
    }
    /* from its creation on, a signal removes it (cli_sig_*) */
    cli_sig_block(&held);
    fd = temp_create(out->dirfd, out->tmp, &named);
    e = errno;
    if (fd >= 0) {
        out->named = named;
        cli_sig_arm(prog, out->path, out->dirfd, named ? out->tmp : NULL);
    }
    sigprocmask(SIG_SETMASK, &held, NULL);
    if (fd < 0) {
        close(out->dirfd);
        free(out->path);
        free(out->tmp);
        output_reset(out);
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
            cli_error(prog, is_stdout ? "<stdout>" : out->path, "write error: %s",
                      err ? strerror(err) : "the stream reported an error");
        free(out->path);
        out->path = NULL;
        return bad;
    }
    errno = 0;
    if (fflush(out->f) != 0 || ferror(out->f) || fsync(fileno(out->f)) != 0) {
        failed = 1;
        e = errno;
    }
    /* the temporary is 0600: give it the old file's mode (or a new file's
     * 0666 & ~umask) before it becomes visible. A file system without
     * permissions may refuse; the file then stays 0600, the safe side, so
     * that is not an error. */
    if (!failed)
        (void)fchmod(fileno(out->f), (mode_t)out->mode);
    {
        /* name (O_TMPFILE), rename or unlink, and forget the temporary,
         * with the signals held: a handler then never removes a name
         * already renamed */
        sigset_t mask;
        cli_sig_block(&mask);
        if (!failed && !out->named) {
            if (temp_link(fileno(out->f), out->dirfd, out->tmp) != 0) {
                failed = 1;
                e = errno;
            } else {
                out->named = 1;
            }
        }
        if (fclose(out->f) != 0 && !failed) {
            failed = 1;
            e = errno;
        }
        out->f = NULL;
        if (!failed && renameat(out->dirfd, out->tmp, out->dirfd, out->base) != 0) {
            failed = 1;
            e = errno;
        }
        if (failed && out->named)
            unlinkat(out->dirfd, out->tmp, 0);
        cli_sig_disarm();
        sigprocmask(SIG_SETMASK, &mask, NULL);
    }
    if (failed)
        cli_error(prog, out->path, "cannot write output: %s",
                  e ? strerror(e) : "the stream reported an error");
    close(out->dirfd);
    free(out->tmp);
    free(out->path);
    output_reset(out);
    return failed;
}

void cli_output_abort(cli_output *out)
{
    sigset_t mask;
    if (out->f && out->f != stdout)
        fclose(out->f);
    if (out->tmp) {
        cli_sig_block(&mask);
        if (out->named)
            unlinkat(out->dirfd, out->tmp, 0);
        cli_sig_disarm();
        sigprocmask(SIG_SETMASK, &mask, NULL);
    }
    if (out->dirfd >= 0)
        close(out->dirfd);
    free(out->tmp);
    free(out->path);
    output_reset(out);
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
        return cli_error(tool, "<stdout>", "write error: %s", strerror(errno ? errno : EIO));
    return CLI_EXIT_OK;
}

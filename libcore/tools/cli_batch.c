/* SPDX-License-Identifier: MIT */
#include "cli_batch.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "cli_opt.h"

void cli_batch_init(cli_batch *b)
{
    b->items = NULL;
    b->n = b->cap = 0;
    b->progress = CLI_PROGRESS_AUTO;
    b->failed_plan = 0;
}

void cli_batch_free(cli_batch *b)
{
    size_t i;
    for (i = 0; i < b->n; i++) {
        if (b->items[i].out != b->items[i].in)
            free(b->items[i].out);
        free(b->items[i].in);
    }
    free(b->items);
    cli_batch_init(b);
}

int cli_is_dir_target(const char *path)
{
    struct stat sb;
    size_t n = strlen(path);
    return (n > 0 && path[n - 1] == '/') || (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode));
}

int cli_batch_default_jobs(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    if (n < 1)
        return 1;
    return n > CLI_BATCH_MAX_JOBS ? CLI_BATCH_MAX_JOBS : (int)n;
}

/* ------------------------------------------------------------ plan */

static char *join3(const char *a, const char *b, const char *c)
{
    size_t la = strlen(a), lb = strlen(b), lc = strlen(c);
    char *s = malloc(la + lb + lc + 1);
    if (!s)
        return NULL;
    memcpy(s, a, la);
    memcpy(s + la, b, lb);
    memcpy(s + la + lb, c, lc + 1);
    return s;
}

typedef struct planner {
    const char *prog;
    const cli_batch_spec *spec;
    cli_batch *b;
    char *outdir;          /* spec->outdir without trailing slashes */
    int have_outdir_id;    /* the output directory exists: skip it in walks */
    dev_t out_dev;
    ino_t out_ino;
} planner;

/* Add in (taken over) with output DIR/rel (rel: below the output
 * directory; the extension replaced when asked). */
static int add_item(planner *p, char *in, const char *rel)
{
    cli_batch_item *it;
    if (p->b->n == CLI_BATCH_MAX_FILES) {
        free(in);
        cli_error(p->prog, NULL, "more than %zu input files in one call; split the run",
                  (size_t)CLI_BATCH_MAX_FILES);
        return CLI_EXIT_USAGE;
    }
    if (p->b->n == p->b->cap) {
        size_t ncap = p->b->cap ? 2 * p->b->cap : 64;
        cli_batch_item *ni = realloc(p->b->items, ncap * sizeof *ni);
        if (!ni) {
            free(in);
            return cli_error(p->prog, NULL, "out of memory");
        }
        p->b->items = ni;
        p->b->cap = ncap;
    }
    it = &p->b->items[p->b->n];
    it->in = in;
    if (p->spec->in_place) {
        it->out = in;
    } else {
        char *name = NULL;
        if (p->spec->out_ext) {
            const char *slash = strrchr(rel, '/'), *base = slash ? slash + 1 : rel;
            const char *dot = strrchr(base, '.');
            size_t keep = dot && dot != base ? (size_t)(dot - rel) : strlen(rel);
            name = malloc(keep + strlen(p->spec->out_ext) + 1);
            if (name) {
                memcpy(name, rel, keep);
                strcpy(name + keep, p->spec->out_ext);
            }
        }
        it->out = name || !p->spec->out_ext ? join3(p->outdir, "/", name ? name : rel) : NULL;
        free(name);
        if (!it->out) {
            free(in);
            return cli_error(p->prog, NULL, "out of memory");
        }
    }
    p->b->n++;
    return 0;
}

/* Every matching file below dir (path so far), as rel (below the
 * directory argument). */
static int walk(planner *p, const char *dir, const char *rel, int depth)
{
    struct dirent **ents = NULL;
    int n, i, rc = 0;
    if (depth > CLI_BATCH_MAX_DEPTH) {
        cli_error(p->prog, dir, "directories nested deeper than %d levels", CLI_BATCH_MAX_DEPTH);
        return CLI_EXIT_USAGE;
    }
    n = scandir(dir, &ents, NULL, alphasort);
    if (n < 0)
        return cli_error(p->prog, dir, "cannot read the directory: %s", strerror(errno));
    for (i = 0; i < n; i++) {
        const char *name = ents[i]->d_name;
        char *path, *sub;
        struct stat lsb, sb;
        if (rc != 0 || name[0] == '.')
            continue;
        path = join3(dir, "/", name);
        sub = *rel ? join3(rel, "/", name) : join3("", "", name);
        if (!path || !sub) {
            free(path);
            free(sub);
            rc = cli_error(p->prog, NULL, "out of memory");
            continue;
        }
        if (lstat(path, &lsb) != 0) {
            free(path);
            free(sub);
            continue; /* gone since the listing */
        }
        if (S_ISDIR(lsb.st_mode)) {
            if (!(p->have_outdir_id && lsb.st_dev == p->out_dev && lsb.st_ino == p->out_ino))
                rc = walk(p, path, sub, depth + 1);
            free(path);
        } else if (cli_ends_with_ci(name, p->spec->ext) &&
                   (S_ISREG(lsb.st_mode) ||
                    (S_ISLNK(lsb.st_mode) && stat(path, &sb) == 0 && S_ISREG(sb.st_mode)))) {
            rc = add_item(p, path, sub);
        } else {
            free(path);
        }
        free(sub);
    }
    for (i = 0; i < n; i++)
        free(ents[i]);
    free(ents);
    return rc;
}

static int cmp_out(const void *a, const void *b)
{
    const cli_batch_item *const *x = a, *const *y = b;
    return strcmp((*x)->out, (*y)->out);
}

/* Two inputs written to one output: refused before anything is written. */
static int check_unique(planner *p)
{
    const cli_batch_item **v;
    size_t i;
    int rc = 0;
    if (p->b->n < 2)
        return 0;
    v = malloc(p->b->n * sizeof *v);
    if (!v)
        return cli_error(p->prog, NULL, "out of memory");
    for (i = 0; i < p->b->n; i++)
        v[i] = &p->b->items[i];
    qsort(v, p->b->n, sizeof *v, cmp_out);
    for (i = 1; i < p->b->n && !rc; i++)
        if (strcmp(v[i - 1]->out, v[i]->out) == 0)
            rc = cli_usage_error(p->prog,
                                 "'%s' and '%s' would both be written to '%s'%s", v[i - 1]->in,
                                 v[i]->in, v[i]->out,
                                 p->spec->in_place ? ""
                                                   : " (inputs with the same name: give their "
                                                     "directory with -r to keep relative paths)");
    free(v);
    return rc;
}

int cli_batch_plan(const char *prog, char *const *inputs, size_t n, const cli_batch_spec *spec,
                   cli_batch *b)
{
    planner p;
    size_t i;
    int rc = 0;
    struct stat sb;

    memset(&p, 0, sizeof p);
    p.prog = prog;
    p.spec = spec;
    p.b = b;
    if (!spec->in_place) {
        size_t len = strlen(spec->outdir);
        while (len > 1 && spec->outdir[len - 1] == '/')
            len--;
        p.outdir = malloc(len + 1);
        if (!p.outdir)
            return cli_error(prog, NULL, "out of memory");
        memcpy(p.outdir, spec->outdir, len);
        p.outdir[len] = '\0';
        if (strcmp(p.outdir, "/") == 0)
            p.outdir[0] = '\0'; /* join3 puts the slash */
        if (stat(spec->outdir, &sb) == 0) {
            if (!S_ISDIR(sb.st_mode)) {
                free(p.outdir);
                return cli_usage_error(prog, "-o '%s' is not a directory", spec->outdir);
            }
            p.have_outdir_id = 1;
            p.out_dev = sb.st_dev;
            p.out_ino = sb.st_ino;
        }
    }
    for (i = 0; i < n && rc == 0; i++) {
        const char *a = inputs[i];
        char *copy;
        if (strcmp(a, "-") == 0) {
            rc = cli_usage_error(prog, "'-' (stdin) works with one input only");
            break;
        }
        if (stat(a, &sb) == 0 && S_ISDIR(sb.st_mode)) {
            size_t len = strlen(a);
            if (!spec->recurse) {
                /* one bad input among many, like a missing or broken file:
                 * the others are still written, the run ends with 1 */
                cli_error(prog, a, "is a directory, not written (-r processes the %s files "
                                   "under it)",
                          spec->ext);
                b->failed_plan++;
                continue;
            }
            while (len > 1 && a[len - 1] == '/')
                len--;
            copy = malloc(len + 1);
            if (!copy) {
                rc = cli_error(prog, NULL, "out of memory");
                break;
            }
            memcpy(copy, a, len);
            copy[len] = '\0';
            rc = walk(&p, copy, "", 0);
            free(copy);
            continue;
        }
        /* a file (or a missing one: its run reports it, the others go on) */
        copy = join3(a, "", "");
        if (!copy) {
            rc = cli_error(prog, NULL, "out of memory");
            break;
        }
        {
            const char *slash = strrchr(a, '/');
            rc = add_item(&p, copy, slash ? slash + 1 : a);
        }
    }
    if (rc == 0 && b->n == 0 && b->failed_plan)
        rc = CLI_EXIT_ERROR; /* only directories without -r: each said so */
    else if (rc == 0 && b->n == 0)
        rc = cli_usage_error(prog, "no %s files found in the input directories", spec->ext);
    if (rc == 0)
        rc = check_unique(&p);
    free(p.outdir);
    if (rc != 0)
        cli_batch_free(b);
    return rc;
}

/* ------------------------------------------------------------ run */

/* mkdir -p of the directory part of path. Returns 0 or errno. */
static int make_parents(char *path)
{
    char *slash = strrchr(path, '/'), *p;
    int e = 0;
    struct stat sb;
    if (!slash || slash == path)
        return 0;
    *slash = '\0';
    if (stat(path, &sb) == 0) {
        e = S_ISDIR(sb.st_mode) ? 0 : ENOTDIR;
        *slash = '/';
        return e;
    }
    for (p = path + 1; ; p++) {
        if (*p == '/' || *p == '\0') {
            char c = *p;
            *p = '\0';
            if (mkdir(path, 0777) != 0 && errno != EEXIST)
                e = errno;
            *p = c;
            if (e || c == '\0')
                break;
        }
    }
    *slash = '/';
    return e;
}

/* The signals that stop a batch (the terminal's and kill's); SIGPIPE and
 * SIGXFSZ concern the children's writes, which handle them (cli.c). The
 * parent's one piece of global state, for its handler. */
static const int batch_sigs[] = {SIGINT, SIGTERM, SIGHUP};
#define BATCH_NSIG (sizeof batch_sigs / sizeof batch_sigs[0])
static volatile sig_atomic_t batch_stop;

static void batch_handler(int signo)
{
    batch_stop = signo;
}

typedef struct running {
    pid_t pid;
    size_t item;
} running;

static const char *sig_name(int s)
{
    switch (s) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    case SIGSEGV: return "SIGSEGV";
    case SIGABRT: return "SIGABRT";
    case SIGKILL: return "SIGKILL";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    default: return "a signal";
    }
}

int cli_batch_run(const char *prog, const cli_batch *b, int jobs, cli_batch_fn fn, void *ctx)
{
    struct sigaction old[BATCH_NSIG], sa;
    int installed[BATCH_NSIG];
    sigset_t block, held;
    running *run;
    cli_progress progress;
    size_t next = 0, nrun = 0, written = 0, failed = b->failed_plan, i, k;
    int stop = 0;

    if (jobs < 1)
        jobs = 1;
    if ((size_t)jobs > b->n)
        jobs = (int)b->n;
    run = calloc((size_t)(jobs > 0 ? jobs : 1), sizeof *run);
    if (!run)
        return cli_error(prog, NULL, "out of memory");

    memset(&sa, 0, sizeof sa);
    sa.sa_handler = batch_handler; /* no SA_RESTART: waitpid returns EINTR */
    sigemptyset(&sa.sa_mask);
    sigemptyset(&block);
    for (k = 0; k < BATCH_NSIG; k++)
        sigaddset(&block, batch_sigs[k]);
    batch_stop = 0;
    for (k = 0; k < BATCH_NSIG; k++) {
        installed[k] = 0;
        if (sigaction(batch_sigs[k], NULL, &old[k]) == 0 && old[k].sa_handler != SIG_IGN)
            installed[k] = sigaction(batch_sigs[k], &sa, NULL) == 0;
    }
    fflush(NULL); /* nothing buffered is written twice by the children */
    cli_progress_start(&progress, prog, "files", b->n + b->failed_plan, b->progress);

    while (next < b->n || nrun > 0) {
        int status;
        pid_t pid;
        stop = batch_stop;
        while (!stop && next < b->n && nrun < (size_t)jobs) {
            const cli_batch_item *it = &b->items[next];
            int e = make_parents(it->out);
            if (e) {
                cli_error(prog, it->out, "cannot create the output directory: %s", strerror(e));
                failed++;
                next++;
                continue;
            }
            sigprocmask(SIG_BLOCK, &block, &held);
            pid = fork();
            if (pid == 0) {
                /* the child: the tool's own dispositions, then one file */
                int rc;
                for (k = 0; k < BATCH_NSIG; k++)
                    if (installed[k])
                        sigaction(batch_sigs[k], &old[k], NULL);
                sigprocmask(SIG_SETMASK, &held, NULL);
                rc = fn(ctx, it->in, it->out);
                fflush(NULL);
                _exit(rc == 0 ? 0 : 1);
            }
            sigprocmask(SIG_SETMASK, &held, NULL);
            if (pid < 0) {
                if (nrun == 0) {
                    cli_error(prog, it->in, "cannot start a process: %s", strerror(errno));
                    failed++;
                    next++;
                }
                break; /* wait for a running one to end, then retry */
            }
            run[nrun].pid = pid;
            run[nrun].item = next++;
            nrun++;
            stop = batch_stop;
        }
        if (nrun == 0)
            continue;
        pid = waitpid(-1, &status, 0);
        if (pid < 0) {
            if (errno == EINTR) {
                if (batch_stop && !stop)
                    for (i = 0; i < nrun; i++)
                        kill(run[i].pid, (int)batch_stop);
                stop = batch_stop;
                continue;
            }
            cli_error(prog, NULL, "waiting for a file's process: %s", strerror(errno));
            failed += nrun;
            nrun = 0;
            break;
        }
        for (i = 0; i < nrun && run[i].pid != pid; i++)
            ;
        if (i == nrun)
            continue; /* not one of ours */
        if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
            written++;
        } else {
            failed++;
            if (WIFSIGNALED(status) && WTERMSIG(status) != (int)batch_stop)
                cli_error(prog, b->items[run[i].item].in,
                          "the process for this file died of %s (signal %d); output not written",
                          sig_name(WTERMSIG(status)), WTERMSIG(status));
        }
        run[i] = run[--nrun];
        cli_progress_update(&progress, written + failed);
        if (batch_stop && !stop) {
            for (i = 0; i < nrun; i++)
                kill(run[i].pid, (int)batch_stop);
            stop = batch_stop;
        }
        if (stop && next < b->n && nrun == 0)
            break;
    }
    free(run);
    cli_progress_end(&progress);
    for (k = 0; k < BATCH_NSIG; k++)
        if (installed[k])
            sigaction(batch_sigs[k], &old[k], NULL);
    if (stop) {
        int s = (int)stop;
        fprintf(stderr, "%s: error: stopped by %s: %zu files written, %zu failed, %zu not started\n",
                prog, sig_name(s), written, failed, b->n + b->failed_plan - written - failed);
        signal(s, SIG_DFL);
        raise(s);
        return 128 + s;
    }
    fprintf(stderr, "%s: %zu file%s written, %zu failed\n", prog, written, cli_plural(written),
            failed);
    return failed ? CLI_EXIT_ERROR : CLI_EXIT_OK;
}

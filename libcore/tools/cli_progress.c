/* SPDX-License-Identifier: MIT */
/* The progress line of the tools (cli_progress.h). libc and POSIX only. */
#include "cli_progress.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Seconds between two redraws. */
#define PROGRESS_INTERVAL 0.1

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void cli_progress_start(cli_progress *p, const char *prog, const char *unit, size_t total,
                        cli_progress_mode mode)
{
    const char *term = getenv("TERM");
    int tty = isatty(STDERR_FILENO);
    memset(p, 0, sizeof *p);
    p->prog = prog;
    p->unit = unit;
    p->total = total;
    p->on = mode == CLI_PROGRESS_ON || (mode == CLI_PROGRESS_AUTO && tty);
    /* erase-to-end-of-line on terminals that have it; padding otherwise */
    p->ansi = tty && !(term && strcmp(term, "dumb") == 0);
    p->start = p->last = seconds();
}

static void draw(cli_progress *p, double now)
{
    char line[160];
    double t = now - p->start, rate = t > 0 ? (double)p->done / t : 0.0;
    int n = snprintf(line, sizeof line, "%s: %zu/%zu %s", p->prog, p->done, p->total, p->unit);
    if (rate > 0 && n > 0 && (size_t)n < sizeof line) {
        double eta = (double)(p->total - p->done) / rate;
        n += snprintf(line + n, sizeof line - (size_t)n,
                      rate >= 100 ? ", %.0f %s/s, ETA %.0f s" : ", %.3g %s/s, ETA %.0f s", rate,
                      p->unit, eta);
    }
    fprintf(stderr, p->ansi ? "\r%s\033[K" : "\r%-70s", line);
    fflush(stderr);
    p->drawn = 1;
    p->last = now;
}

void cli_progress_update(cli_progress *p, size_t done)
{
    double now;
    if (!p->on)
        return;
    p->done = done;
    now = seconds();
    if (!p->drawn || now - p->last >= PROGRESS_INTERVAL || done == p->total)
        draw(p, now);
}

void cli_progress_end(cli_progress *p)
{
    if (!p->on || !p->drawn)
        return;
    fprintf(stderr, p->ansi ? "\r\033[K" : "\r%70s\r", "");
    fflush(stderr);
    p->drawn = 0;
}

void cli_progress_job_init(cli_progress_job *j, const char *prog, const char *unit,
                           cli_progress_mode mode, size_t min_total, size_t per_unit)
{
    memset(j, 0, sizeof *j);
    j->prog = prog;
    j->unit = unit;
    j->mode = mode;
    j->min_total = min_total;
    j->per_unit = per_unit ? per_unit : 1;
}

void cli_progress_report(void *job, size_t done, size_t total)
{
    cli_progress_job *j = job;
    size_t k = j->per_unit, all = total / k + (total % k != 0);
    if (!j->started) {
        cli_progress_mode m = j->mode;
        if (m == CLI_PROGRESS_AUTO && total < j->min_total)
            m = CLI_PROGRESS_OFF;
        cli_progress_start(&j->line, j->prog, j->unit, all, m);
        j->started = 1;
    }
    cli_progress_update(&j->line, done >= total ? all : done / k);
}

void cli_progress_job_end(cli_progress_job *j)
{
    if (j->started)
        cli_progress_end(&j->line);
}

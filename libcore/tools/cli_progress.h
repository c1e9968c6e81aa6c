/* SPDX-License-Identifier: MIT */
/* A one-line progress indicator on stderr for the tools' long jobs
 * (batches of files): `PROG: 120/10000 files, 250 files/s, ETA 40 s`,
 * redrawn in place at most ten times a second and erased at the end.
 * Shown when stderr is a terminal, or always / never when the user says so
 * (--progress, -q/--quiet). Uses libc only. */
#ifndef CONICA_CLI_PROGRESS_H
#define CONICA_CLI_PROGRESS_H

#include <stddef.h>

/* When to show it. */
typedef enum cli_progress_mode {
    CLI_PROGRESS_AUTO = 0, /* when stderr is a terminal (the default) */
    CLI_PROGRESS_ON,       /* --progress */
    CLI_PROGRESS_OFF       /* -q, --quiet */
} cli_progress_mode;

typedef struct cli_progress {
    const char *prog, *unit; /* "svgsmooth", "files" */
    size_t total, done;
    double start, last;      /* seconds (CLOCK_MONOTONIC) */
    int on, drawn, ansi;     /* shown; something is on the line; the terminal erases (ESC[K) */
} cli_progress;

/* Start counting toward total units. */
void cli_progress_start(cli_progress *p, const char *prog, const char *unit, size_t total,
                        cli_progress_mode mode);
/* done units so far (redraws when a tenth of a second has passed). */
void cli_progress_update(cli_progress *p, size_t done);
/* Erase the line (the tool's summary follows on a clean line). */
void cli_progress_end(cli_progress *p);

/* The line of one long library call, fed by its settings' progress report
 * (a conica_progress_fn: cli_progress_report with this as its context).
 * The line starts at the first report, when the total is known: in AUTO
 * mode only for a total of at least `min_total`; counts are shown divided
 * by `per_unit` (1000 for kB of bytes; 0 counts as 1). */
typedef struct cli_progress_job {
    cli_progress line;
    const char *prog, *unit;
    cli_progress_mode mode;
    size_t min_total, per_unit;
    int started;
} cli_progress_job;

void cli_progress_job_init(cli_progress_job *j, const char *prog, const char *unit,
                           cli_progress_mode mode, size_t min_total, size_t per_unit);
void cli_progress_report(void *job, size_t done, size_t total);
/* Erase the line, if one was started. */
void cli_progress_job_end(cli_progress_job *j);

#endif

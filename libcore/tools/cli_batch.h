/* SPDX-License-Identifier: MIT */
/* Many files in one call, shared by svgsmooth and scadprofile:
 *
 *   TOOL [options] FILE... -o DIR/      one output per input in DIR
 *   TOOL [options] --in-place FILE...   each input replaced
 *   TOOL -r [options] DIR... -o OUT/    every matching file under DIR,
 *                                       the tree mirrored under OUT
 *
 * cli_batch_plan() turns the arguments into (input, output) pairs and
 * refuses what cannot work before anything is written (two inputs that
 * would be written to one output, too many files); a directory among the
 * inputs without -r is one failed input (its error printed, counted in
 * failed_plan), the others are still written;
 * cli_batch_run() processes each pair in a child process of its own (at
 * most `jobs` at a time), so each file is written through its own
 * temporary (cli_output), a file that fails or even crashes its process
 * leaves every other file written, and the per-file code is exactly the
 * single-file code. One summary line ends the run. */
#ifndef CONICA_CLI_BATCH_H
#define CONICA_CLI_BATCH_H

#include <stddef.h>

#include "cli_progress.h"

/* Caps (input-controlled counts): files in one call, parallel jobs (-j),
 * directory nesting followed by -r. */
#define CLI_BATCH_MAX_FILES ((size_t)1 << 20)
#define CLI_BATCH_MAX_JOBS 256
#define CLI_BATCH_MAX_DEPTH 64

typedef struct cli_batch_item {
    char *in;  /* input path */
    char *out; /* output path (== in with --in-place) */
} cli_batch_item;

typedef struct cli_batch {
    cli_batch_item *items;
    size_t n, cap;
    cli_progress_mode progress; /* the progress line of cli_batch_run (default: on a terminal) */
    size_t failed_plan; /* inputs refused while planning (a directory without -r) */
} cli_batch;

typedef struct cli_batch_spec {
    const char *outdir; /* -o DIR (NULL with in_place) */
    int in_place;       /* replace each input */
    int recurse;        /* -r: directories are walked */
    const char *ext;    /* what -r picks from directories, e.g. ".svg" (any case) */
    const char *out_ext; /* NULL: outputs keep the input's name; else the
                          * input's extension is replaced by this one */
} cli_batch_spec;

void cli_batch_init(cli_batch *b);
void cli_batch_free(cli_batch *b);

/* Does -o PATH name a directory: it ends with '/' or is an existing one. */
int cli_is_dir_target(const char *path);

/* The default of -j: the number of online processors, 1..CLI_BATCH_MAX_JOBS. */
int cli_batch_default_jobs(void);

/* Fill b from the n input arguments. File arguments give DIR/BASENAME;
 * with -r a directory argument gives every file under it whose name ends
 * with spec->ext, as DIR/PATH-BELOW-IT (names starting with '.' are
 * skipped, symbolic links to directories are not followed, the output
 * directory itself is skipped, entries in name order). "-" is refused.
 * Returns 0, or CLI_EXIT_USAGE / CLI_EXIT_ERROR after printing why. */
int cli_batch_plan(const char *prog, char *const *inputs, size_t n, const cli_batch_spec *spec,
                   cli_batch *b);

/* The per-file work: the exit status of a single-file run (0 ok, 1 after
 * printing the error). Runs in a child process. */
typedef int (*cli_batch_fn)(void *ctx, const char *in, const char *out);

/* Create the output directories, run fn on every item in child processes
 * (at most jobs at a time), and print `prog: N files written, M failed`
 * on stderr. A child that dies of a signal is named as failed. SIGINT,
 * SIGTERM and SIGHUP to the tool stop the batch: the running children get
 * the signal too (each removes its temporary), no new one starts, and the
 * tool dies of the signal after saying how many files were written.
 * Returns 0 when every file was written, 1 otherwise. */
int cli_batch_run(const char *prog, const cli_batch *b, int jobs, cli_batch_fn fn, void *ctx);

#endif

/* SPDX-License-Identifier: MIT */
/* Helpers shared by every Conica command-line tool (conica, svgsmooth,
 * scadprofile): whole-file input with a size limit, output through a
 * temporary file renamed into place, and POSIX-style messages. */
#ifndef CONICA_CLI_H
#define CONICA_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "conica/common.h"

#if defined(__GNUC__)
#define CLI_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define CLI_PRINTF(a, b)
#endif

/* Default cap on an input file (input-controlled size). */
#define CLI_DEFAULT_MAX_INPUT ((size_t)256 << 20)

/* The input size cap of every tool: the environment variable
 * CONICA_MAX_INPUT_BYTES (a whole number of bytes, 1 .. 2^40) when set,
 * else CLI_DEFAULT_MAX_INPUT. A malformed value is reported as a warning
 * and the default applies. svgsmooth's --max-input-bytes overrides both. */
#define CLI_MAX_INPUT_ENV "CONICA_MAX_INPUT_BYTES"
size_t cli_max_input(const char *prog);

/* Exit statuses shared by every tool. */
enum { CLI_EXIT_OK = 0, CLI_EXIT_ERROR = 1, CLI_EXIT_USAGE = 2 };

/* `prog: error: where: what` on stderr (where may be NULL). Returns 1. */
int cli_error(const char *prog, const char *where, const char *fmt, ...) CLI_PRINTF(3, 4);
/* `prog: warning: where: what` on stderr. */
void cli_warning(const char *prog, const char *where, const char *fmt, ...) CLI_PRINTF(3, 4);
/* `prog: usage error: what` plus a hint to --help on stderr. Returns 2. */
int cli_usage_error(const char *prog, const char *fmt, ...) CLI_PRINTF(2, 3);

/* The line of a point-normal file (buf, len) that a subdivision failure
 * names: the engine reports a bad point by its index in st->offset with a
 * message starting "point" or "normal" (libcore/src/subdiv.c). 0 when the
 * failure names no point. */
size_t cli_point_line(const char *buf, size_t len, conica_code code, const conica_status *st);

/* Coordinates beyond this make the subdivision's squared distances
 * overflow (1e150^2 = 1e300 < DBL_MAX); the _conica extension refuses
 * them up front, the tools name them when the output comes out non-finite. */
#define CLI_HUGE_COORD 1e150

/* As cli_point_line(), and the message to print into msg: the engine's,
 * or, when the output came out non-finite (CONICA_ERR_NUMERIC) and an
 * input point has a coordinate beyond CLI_HUGE_COORD, one that names that
 * coordinate, with the returned line being that point's. */
size_t cli_point_failure(const char *buf, size_t len, conica_code code, const conica_status *st,
                         char *msg, size_t cap);

/* Read all of path ("-" or NULL = stdin) into a new NUL-terminated buffer
 * (*len excludes the NUL). Fails with a message (file name included) when
 * the file cannot be read or is larger than max_bytes. Caller frees *buf.
 * Returns 0 on success, 1 after printing an error. */
int cli_read_file(const char *prog, const char *path, size_t max_bytes, char **buf, size_t *len);

/* Output that never leaves a half-written file: data goes to a temporary
 * file in the target's directory and is renamed over the target only by
 * cli_output_commit(). "-" or NULL writes to stdout directly. An existing
 * target that is not a regular file (/dev/null, a FIFO, a terminal) is
 * written in place: renaming over it would replace the device node with a
 * regular file (as root that succeeds). A directory is an error.
 *
 * Replacing an existing file keeps what the user set up around it: a
 * symbolic link is resolved (realpath) so the temporary is created beside
 * the real file and the rename replaces the real file, leaving the link a
 * link; the new file gets the old file's permission bits (rwx, not the
 * set-id bits: a 0600 file stays 0600). A new file gets 0666 & ~umask, as fopen() would give it. A
 * symbolic link to nothing (dangling) is an error rather than replaced.
 * Not kept: the owner (only root could), hard links (rename makes a new
 * inode), extended attributes.
 *
 * The temporary is made in the target's directory through a handle on it
 * (openat, linkat, renameat: a directory renamed during the write takes the
 * temporary with it and the commit still finds it). Where the file system
 * has O_TMPFILE it has no name until the commit; else it is
 * `.NAME.conica-tmp.XXXXXX` (hidden, saying what it is; NAME cut so the
 * whole stays within the directory's name limit). While it exists every
 * catchable signal whose default action ends the process (SIGINT, SIGTERM,
 * SIGHUP, SIGQUIT, SIGPIPE, SIGUSR1/2, SIGALRM, SIGVTALRM, SIGPROF,
 * SIGXCPU, SIGXFSZ, the faults, the real-time signals, ...) removes it,
 * prints `prog: error: target: stopped by SIG...; output not written ...`
 * and is raised again with its default action, so the tool ends with
 * status 128 + signo (SIGXFSZ by _exit: its default would dump core; a
 * fault the kernel raised goes back to the handler before it, e.g. a
 * sanitizer's report); signals the tool was started with ignored stay ignored.
 * SIGKILL leaves at most the named temporary (none with O_TMPFILE) and
 * the target untouched. One output open at a time (the handler knows one
 * temporary). The environment variable CONICA_TMPFILE=named makes the
 * tools use the named temporary even where O_TMPFILE works (the tests
 * exercise the fallback that way). */
#define CLI_TMPFILE_ENV "CONICA_TMPFILE"
typedef struct cli_output {
    FILE *f;          /* where to write */
    char *path;       /* final path (symlinks resolved), NULL for stdout */
    char *tmp;        /* the temporary's name in dirfd, NULL for stdout and devices */
    const char *base; /* the target's name in dirfd (points into path) */
    unsigned mode;    /* permission bits the committed file gets */
    int dirfd;        /* the target's directory, -1 when none */
    int named;        /* tmp names the temporary (0 while an O_TMPFILE has no name) */
} cli_output;

/* Returns 0, or 1 after printing an error. */
int cli_output_open(const char *prog, const char *path, cli_output *out);
/* Flush, fsync and rename into place; on any write error the temporary is
 * removed and the target is untouched. Returns 0, or 1 after an error. */
int cli_output_commit(const char *prog, cli_output *out);
/* Drop the temporary file (target untouched). Safe after commit. */
void cli_output_abort(cli_output *out);

/* `--version`: the one line every tool prints, `TOOL (Conica) VERSION`
 * with the version of the library it runs on (conica_version()), on
 * stdout. Returns 0, or 1 after a write error. */
int cli_version(const char *tool);

/* Does s end with suffix (lower case), ignoring the case of s's ASCII
 * letters: file extensions (".svg", ".SVG"). */
int cli_ends_with_ci(const char *s, const char *suffix);

/* Parse a whole decimal integer in [lo, hi]; returns 0 on success. */
int cli_parse_int(const char *s, long lo, long hi, long *out);
/* Parse a finite number without the C locale; returns 0 on success. */
int cli_parse_double(const char *s, double *out);

#endif

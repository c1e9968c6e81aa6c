/* SPDX-License-Identifier: MIT */
/* `conica subdivide`: conic-preserving interpolatory subdivision of a
 * point-normal curve in the reference implementation's text format
 * (CONIS §1.1; README.md). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli.h"
#include "cli_opt.h"
#include "cli_progress.h"
#include "conica/curve.h"
#include "conica/subdiv.h"

#define PROG "conica"
#define USAGE_PROG "conica subdivide"
/* --time: best of this many in-memory runs (the first one's output is written). */
#define TIME_RUNS 5
/* --threads upper bound (a typo guard; the engine clamps to what it uses). */
#define MAX_THREADS 256
/* Default number of levels when -k is not given (the reference's examples use 5). */
#define DEFAULT_LEVELS 5
/* Outputs of fewer points take well under a second: no progress line. */
#define PROGRESS_POINTS 1000000

enum {
    OPT_OPEN = CLI_OPT_LONG,
    OPT_CLOSED,
    OPT_PRECISE,
    OPT_ESTIMATE,
    OPT_NORMALS,
    OPT_REFCOMPAT,
    OPT_MAX_POINTS,
    OPT_MAX_INPUT,
    OPT_THREADS,
    OPT_NOISE,
    OPT_TIME,
    OPT_PROGRESS,
};

static const cli_opt opts[] = {
    {'k', "levels", CLI_ARG_REQUIRED, "K", NULL, "subdivision levels, 0..%.0f (default %.0f)",
     {CONICA_SUBDIV_MAX_LEVELS, DEFAULT_LEVELS, 0}},
    {OPT_OPEN, "open", CLI_ARG_NONE, NULL, NULL, "the curve is open (n points -> 2n-1 per level)",
     {0, 0, 0}},
    {OPT_CLOSED, "closed", CLI_ARG_NONE, NULL, NULL,
     "the curve is closed (default; n -> 2n per level)", {0, 0, 0}},
    {OPT_PRECISE, "precise", CLI_ARG_NONE, NULL, NULL,
     "read, compute and write in long double (input\n"
     "correctly rounded to long double, output %%.21Lg)",
     {0, 0, 0}},
    {OPT_ESTIMATE, "estimate-normals", CLI_ARG_NONE, NULL, NULL,
     "ignore `vn` lines and estimate normals", {0, 0, 0}},
    {OPT_NORMALS, "normals", CLI_ARG_REQUIRED, "METHOD", "area|circle",
     "how to estimate normals (input without `vn`, or\n"
     "--estimate-normals): area (default, area-weighted\n"
     "edge normals) or circle (circle through neighbours)",
     {0, 0, 0}},
    {OPT_REFCOMPAT, "reference-compatible", CLI_ARG_NONE, NULL, NULL,
     "fit in absolute coordinates with the SVD, as the\n"
     "reference implementation does (for comparisons)",
     {0, 0, 0}},
    {OPT_MAX_POINTS, "max-points", CLI_ARG_REQUIRED, "N", NULL,
     "refuse outputs of more than N points\n(default %.0f)",
     {(double)CONICA_SUBDIV_DEFAULT_MAX_POINTS, 0, 0}},
    {OPT_MAX_INPUT, "max-input-points", CLI_ARG_REQUIRED, "N", NULL,
     "refuse inputs of more than N points (default %.0f;\n"
     "the input file size is capped by the environment\n"
     "variable CONICA_MAX_INPUT_BYTES, default %.0f)",
     {(double)CONICA_CURVE_MAX_INPUT_POINTS, (double)CLI_DEFAULT_MAX_INPUT, 0}},
    {OPT_THREADS, "threads", CLI_ARG_REQUIRED, "N", NULL,
     "worker threads, 1..%.0f (results are bit-identical\nfor any N)", {MAX_THREADS, 0, 0}},
    {OPT_NOISE, "noise", CLI_ARG_REQUIRED, "X", NULL,
     "rounding of the input coordinates (e.g. half a\n"
     "unit of the last digit written): turns within it\n"
     "make no inflection points (default 0: the doubles'\n"
     "own)",
     {0, 0, 0}},
    {OPT_TIME, "time", CLI_ARG_NONE, NULL, NULL,
     "print `subdivide: N edge points in S s\n"
     "(U us/point)` on stderr: the subdivision alone,\n"
     "best of %.0f runs",
     {TIME_RUNS, 0, 0}},
    {'q', "quiet", CLI_ARG_NONE, NULL, NULL, "no progress line", {0, 0, 0}},
    {OPT_PROGRESS, "progress", CLI_ARG_NONE, NULL, NULL,
     "a progress line on stderr (edge points, rate, ETA)\n"
     "even when it is not a terminal (default: only on a\n"
     "terminal, and only from %.0f output points)",
     {(double)PROGRESS_POINTS, 0, 0}},
    {'o', "output", CLI_ARG_REQUIRED, "OUT", "file",
     "write to OUT (`-` = stdout) via a temporary file", {0, 0, 0}},
    {0, NULL, 0, NULL, NULL, NULL, {0, 0, 0}},
};

static const cli_tool tool = {
    USAGE_PROG,
    "[OPTION]... [IN]",
    "Refine a point-normal curve with conic-preserving interpolatory subdivision\n"
    "(the CONIS scheme of Bügel, Romani and Kosinka): every level keeps the old\n"
    "points and inserts one point per edge.\n"
    "\n"
    "Input: `v x y` lines, then optional `vn nx ny` lines paired with the points by\n"
    "order; `#`/`%` lines and blank lines are ignored. IN of `-` or none: stdin.\n"
    "Output: `v x y` lines, then `vn nx ny` lines (unit normals), to OUT or stdout.\n",
    opts,
    "Exit status: 0 success, 1 error (bad input, I/O; nothing is written),\n"
    "2 usage error.\n",
    "file",
    0,
    NULL,
};

typedef struct options {
    long levels;
    int open, precise, estimate, refcompat, time;
    cli_progress_mode progress;
    conica_normal_method method;
    size_t max_points, max_input_points;
    int threads;
    double noise;
    const char *in, *out;
} options;

/* One option's value into *o; returns -1 to go on, or an exit status. */
static int take_option(cli_parser *p, int c, void *ctx)
{
    options *o = ctx;
    const char *v = p->arg;
    long num;
    switch (c) {
    case OPT_OPEN: o->open = 1; break;
    case OPT_CLOSED: o->open = 0; break;
    case OPT_PRECISE: o->precise = 1; break;
    case OPT_ESTIMATE: o->estimate = 1; break;
    case OPT_REFCOMPAT: o->refcompat = 1; break;
    case OPT_TIME: o->time = 1; break;
    case 'q': o->progress = CLI_PROGRESS_OFF; break;
    case OPT_PROGRESS: o->progress = CLI_PROGRESS_ON; break;
    case 'k':
        if (cli_parse_int(v, 0, CONICA_SUBDIV_MAX_LEVELS, &num))
            return cli_opt_bad(p, "needs an integer in 0..%d, not '%s'", CONICA_SUBDIV_MAX_LEVELS,
                               v);
        o->levels = num;
        break;
    case 'o':
        o->out = v;
        break;
    case OPT_NORMALS:
        if (strcmp(v, "area") == 0)
            o->method = CONICA_NORMALS_AREA;
        else if (strcmp(v, "circle") == 0)
            o->method = CONICA_NORMALS_CIRCLE;
        else
            return cli_opt_bad(p, "takes 'area' or 'circle', not '%s'", v);
        break;
    case OPT_MAX_POINTS:
    case OPT_MAX_INPUT:
        if (cli_parse_int(v, 1, LONG_MAX, &num))
            return cli_opt_bad(p, "needs a positive integer, not '%s'", v);
        *(c == OPT_MAX_POINTS ? &o->max_points : &o->max_input_points) = (size_t)num;
        break;
    case OPT_THREADS:
        if (cli_parse_int(v, 1, MAX_THREADS, &num))
            return cli_opt_bad(p, "needs an integer in 1..%d, not '%s'", MAX_THREADS, v);
        o->threads = (int)num;
        break;
    case OPT_NOISE:
        if (cli_parse_double(v, &o->noise) || !(o->noise >= 0) || !isfinite(o->noise))
            return cli_opt_bad(p, "needs a finite number >= 0, not '%s'", v);
        break;
    default:
        return cli_opt_bad(p, "is not handled"); /* a table entry without a case */
    }
    return -1;
}

/* Returns -1 to go on, or an exit status. */
static int parse_args(int argc, char **argv, options *o)
{
    int first, rc;
    o->levels = DEFAULT_LEVELS;
    o->open = o->precise = o->estimate = o->refcompat = o->time = 0;
    o->progress = CLI_PROGRESS_AUTO;
    o->method = CONICA_NORMALS_AREA;
    o->max_points = CONICA_SUBDIV_DEFAULT_MAX_POINTS;
    o->max_input_points = CONICA_CURVE_MAX_INPUT_POINTS;
    o->threads = 0;
    o->noise = 0.0;
    o->in = NULL;
    o->out = NULL;

    if ((rc = cli_opt_parse(&tool, argc, argv, take_option, o, &first)) >= 0)
        return rc;
    return cli_opt_one_operand(&tool, argc, argv, first, 0, &o->in);
}

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* One subdivision in the mode the options ask for: precise mode from the
 * long double input *inl into *outl, else from *in into *out. */
static conica_code run(const conica_curve *in, const conica_curvel *inl,
                       const conica_subdiv_settings *s, conica_curve *out, conica_curvel *outl,
                       conica_subdiv_info *info, conica_status *st)
{
    if (s->precise)
        return conica_subdivide_curvel(inl, s, outl, info, st);
    return conica_subdivide(in, s, out, info, st);
}

static int write_precise(FILE *f, const conica_curvel *c)
{
    size_t i;
    /* %.21Lg round-trips the 64-bit significand of x87 long double. */
    for (i = 0; i < c->n; i++)
        if (fprintf(f, "v %.21Lg %.21Lg\n", c->xy[2 * i], c->xy[2 * i + 1]) < 0)
            return 1;
    if (c->nxy)
        for (i = 0; i < c->n; i++)
            if (fprintf(f, "vn %.21Lg %.21Lg\n", c->nxy[2 * i], c->nxy[2 * i + 1]) < 0)
                return 1;
    return ferror(f) != 0;
}

/* Called by the dispatcher (conica.c), which declares it from commands.def. */
extern const char conica_cmd_subdivide_summary[];
const char conica_cmd_subdivide_summary[] = "conic-preserving subdivision of a point-normal curve";
int conica_cmd_subdivide(int argc, char **argv);

int conica_cmd_subdivide(int argc, char **argv)
{
    options o;
    int rc = parse_args(argc, argv, &o);
    const char *name;
    char *buf = NULL;
    size_t len = 0;
    conica_curve in, out;
    conica_curvel inl, outl;
    conica_subdiv_settings s;
    conica_subdiv_info info;
    conica_status st;
    cli_output co;
    conica_code code;
    double best = 0.0;
    cli_progress_job prog;

    if (rc >= 0)
        return rc;
    name = (o.in == NULL || strcmp(o.in, "-") == 0) ? "<stdin>" : o.in;

    if (cli_read_file(PROG, o.in, cli_max_input(PROG), &buf, &len))
        return CLI_EXIT_ERROR;
    conica_curve_init(&in);
    conica_curve_init(&out);
    conica_curvel_init(&inl);
    conica_curvel_init(&outl);
    conica_subdiv_info_init(&info);
    memset(&st, 0, sizeof st);

    /* --precise reads long double, so that 21- to 25-digit samples reach
     * the long double engine unrounded (CONIS, Table 1 through the CLI). */
    code = o.precise ? conica_curvel_parse_ex(buf, len, o.max_input_points, &inl, &st)
                     : conica_curve_parse_ex(buf, len, o.max_input_points, &in, &st);
    if (code != CONICA_OK) {
        char where[4096];
        free(buf);
        if (st.line > 0)
            snprintf(where, sizeof where, "%s:%zu", name, st.line);
        else
            snprintf(where, sizeof where, "%s", name);
        cli_error(PROG, where, "%s%s", st.message,
                  code == CONICA_ERR_LIMIT ? "; raise the cap with --max-input-points N" : "");
        conica_curve_free(&in);
        conica_curvel_free(&inl);
        return CLI_EXIT_ERROR;
    }
    in.closed = !o.open;
    inl.closed = !o.open;

    s = conica_subdiv_defaults();
    s.levels = (int)o.levels;
    s.precise = o.precise;
    s.reference_compatible = o.refcompat;
    s.estimate_normals = o.estimate;
    s.normal_method = o.method;
    s.max_points = o.max_points;
    if (o.threads > 0)
        s.threads = o.threads;
    s.noise = o.noise;
    cli_progress_job_init(&prog, "conica subdivide", "edge points", o.progress, PROGRESS_POINTS, 1);
    if (o.progress != CLI_PROGRESS_OFF && !o.time) { /* --time measures the subdivision alone */
        s.progress = cli_progress_report;
        s.progress_ctx = &prog;
    }

    /* Open the output first so that an unwritable target fails before a long
     * computation; the temporary file is dropped on any later failure. */
    if (cli_output_open(PROG, o.out, &co)) {
        free(buf);
        conica_curve_free(&in);
        conica_curvel_free(&inl);
        return CLI_EXIT_ERROR;
    }

    {
        int r, runs = o.time ? TIME_RUNS : 1;
        for (r = 0; r < runs; r++) {
            /* later runs go to scratch curves: only the first is written */
            conica_curve scratch;
            conica_curvel scratchl;
            double t0, t;
            conica_curve_init(&scratch);
            conica_curvel_init(&scratchl);
            t0 = now_seconds();
            code = r == 0 ? run(&in, &inl, &s, &out, &outl, &info, &st)
                          : run(&in, &inl, &s, &scratch, &scratchl, NULL, &st);
            t = now_seconds() - t0;
            conica_curve_free(&scratch);
            conica_curvel_free(&scratchl);
            cli_progress_job_end(&prog);
            if (code != CONICA_OK)
                break;
            if (r == 0 || t < best)
                best = t;
        }
    }
    conica_curve_free(&in);
    conica_curvel_free(&inl);
    if (code != CONICA_OK) {
        char where[4096], msg[sizeof st.message + 200];
        size_t line = cli_point_failure(buf, len, code, &st, msg, sizeof msg);
        if (line > 0)
            snprintf(where, sizeof where, "%s:%zu", name, line);
        else
            snprintf(where, sizeof where, "%s", name);
        free(buf);
        cli_error(PROG, where, "%s", msg);
        cli_output_abort(&co);
        conica_curve_free(&out);
        conica_curvel_free(&outl);
        conica_subdiv_info_free(&info);
        return CLI_EXIT_ERROR;
    }

    free(buf);
    if (o.precise)
        rc = write_precise(co.f, &outl);
    else
        rc = conica_curve_write(co.f, &out, NULL) != CONICA_OK;
    conica_curve_free(&out);
    conica_curvel_free(&outl);
    if (rc) {
        cli_error(PROG, o.out && strcmp(o.out, "-") != 0 ? o.out : "<stdout>", "write error: %s", strerror(errno ? errno : EIO));
        cli_output_abort(&co);
        conica_subdiv_info_free(&info);
        return CLI_EXIT_ERROR;
    }
    if (cli_output_commit(PROG, &co)) {
        conica_subdiv_info_free(&info);
        return CLI_EXIT_ERROR;
    }
    if (o.time)
        fprintf(stderr, "subdivide: %zu edge points in %.6g s (%.4g us/point)\n", info.edge_points,
                best, info.edge_points ? best * 1e6 / (double)info.edge_points : 0.0);
    conica_subdiv_info_free(&info);
    return CLI_EXIT_OK;
}

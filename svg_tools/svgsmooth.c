/* SPDX-License-Identifier: MIT */
/* svgsmooth: smooth the outlines of an SVG file with conic-preserving
 * subdivision (corners kept, arcs reproduced), or flatten its curves within
 * a tolerance; nothing else in the document changes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "cli_batch.h"
#include "cli_opt.h"
#include "conica_svg.h"
#include "svg_cli.h"

#define PROG "svgsmooth"
#define MAX_SELECT 4096 /* ids in one --select list */

enum {
    OPT_FIDELITY = CLI_OPT_LONG,
    OPT_CORNER,
    OPT_LINES,
    OPT_SIMPLIFY,
    OPT_FLATTEN,
    OPT_PRECISION,
    OPT_SELECT,
    OPT_SHAPES,
    OPT_STATS,
    OPT_IN_PLACE,
    OPT_MAX_INPUT,
    OPT_MAX_POINTS,
    OPT_PROGRESS,
    OPT_LIMITS, /* CONICA_SVG_CLI_LIMIT_COUNT ids from here */
};

static const cli_opt opts[] = {
    {'k', "levels", CLI_ARG_REQUIRED, "K", NULL,
     "subdivision levels, 0..30 (default 4; 0 writes the\nvertices)", {0, 0, 0}},
    {'t', "tolerance", CLI_ARG_REQUIRED, "T", NULL,
     "smoothing: the fewest levels (per piece) whose\n"
     "chords stay within T user units of the smoothed\n"
     "curve; with --flatten: maximum distance from the\n"
     "drawn curve",
     {0, 0, 0}},
    {OPT_FIDELITY, "fidelity", CLI_ARG_REQUIRED, "T", NULL,
     "largest distance of the smoothed curve from the\n"
     "drawn one, user units (default 1e-3 of each\n"
     "subpath's bounding-box diagonal)",
     {0, 0, 0}},
    {OPT_CORNER, "corner-angle", CLI_ARG_REQUIRED, "DEG", NULL,
     "tangent turn that makes a corner (default 40; 180\ndisables corners)", {0, 0, 0}},
    {OPT_LINES, "lines-as-samples", CLI_ARG_NONE, NULL, NULL,
     "smooth through the vertices of subpaths made only\n"
     "of straight segments (traced outlines); by default\n"
     "straight segments stay straight",
     {0, 0, 0}},
    {OPT_SIMPLIFY, "simplify", CLI_ARG_REQUIRED, "T", NULL,
     "before smoothing traced outlines (polygons,\n"
     "polylines; paths of straight segments with\n"
     "--lines-as-samples), keep the fewest vertices whose\n"
     "smoothed curve passes within T user units of every\n"
     "vertex; corners kept. Other paths of straight\n"
     "segments stay straight: the fewest vertices whose\n"
     "polygon is within T of them",
     {0, 0, 0}},
    {OPT_FLATTEN, "flatten", CLI_ARG_NONE, NULL, NULL,
     "flatten curves within --tolerance (required) with\n"
     "the guaranteed adaptive plotter; straight segments\n"
     "stay",
     {0, 0, 0}},
    {OPT_PRECISION, "precision", CLI_ARG_REQUIRED, "N", NULL,
     "significant digits written (1..17); by default\n"
     "enough that rounding takes at most 1%% of the\n"
     "tolerance (--tolerance with --flatten, else the\n"
     "fidelity); fewer digits can put the output outside it",
     {0, 0, 0}},
    {OPT_SELECT, "select", CLI_ARG_REQUIRED, "IDS", NULL,
     "only the elements with these ids or inside groups\n"
     "with these ids (comma separated)",
     {0, 0, 0}},
    {OPT_SHAPES, "convert-shapes", CLI_ARG_NONE, NULL, NULL,
     "also rect, circle, ellipse, line (rewritten as\npaths)", {0, 0, 0}},
    {OPT_STATS, "stats", CLI_ARG_NONE, NULL, NULL, "counts and CPU seconds on stderr", {0, 0, 0}},
    {OPT_IN_PLACE, "in-place", CLI_ARG_NONE, NULL, NULL,
     "replace each input (through a temporary file)", {0, 0, 0}},
    {'o', "output", CLI_ARG_REQUIRED, "OUT", "file",
     "output file (default stdout); with a name ending in\n"
     "'/', or a directory with several inputs or -r: the\n"
     "directory the outputs go to, named as the inputs",
     {0, 0, 0}},
    {'r', "recursive", CLI_ARG_NONE, NULL, NULL,
     "inputs may be directories: every *.svg under them,\n"
     "the tree mirrored under -o DIR/ (or --in-place)",
     {0, 0, 0}},
    {'j', "jobs", CLI_ARG_REQUIRED, "N", NULL,
     "files processed in parallel (1..%.0f, default: the\n"
     "number of processors); each file runs on its own",
     {CLI_BATCH_MAX_JOBS, 0, 0}},
    {'q', "quiet", CLI_ARG_NONE, NULL, NULL,
     "no progress line (errors and the summary still print)", {0, 0, 0}},
    {OPT_PROGRESS, "progress", CLI_ARG_NONE, NULL, NULL,
     "a progress line on stderr (files, or kB of path data\n"
     "of one document; rate, ETA) even when it is not a\n"
     "terminal (default: only on a terminal, and for one\n"
     "document only from 1 MB of path data)",
     {0, 0, 0}},
    {OPT_MAX_INPUT, "max-input-bytes", CLI_ARG_REQUIRED, "N", NULL,
     "document size cap (default 64 MiB)", {0, 0, 0}},
    CONICA_SVG_CLI_LIMIT_OPTS(OPT_LIMITS),
    {OPT_MAX_POINTS, "max-points", CLI_ARG_REQUIRED, "N", NULL,
     "cap on output points in the document (default\n67108864)", {0, 0, 0}},
    {0, NULL, 0, NULL, NULL, NULL, {0, 0, 0}},
};

static const cli_tool tool = {
    PROG,
    "[OPTION]... IN [-o OUT]\n"
    "[OPTION]... FILE... -o DIR/\n"
    "[OPTION]... --in-place FILE...\n"
    "-r [OPTION]... DIR... (-o OUTDIR/ | --in-place)",
    "Smooth the outlines of an SVG file (paths, polylines, polygons) with\n"
    "conic-preserving subdivision that stays within --fidelity of the drawn\n"
    "curves: corners stay sharp, straight segments straight, arcs and conics\n"
    "exact. polygon and polyline vertices are samples of a smooth curve and\n"
    "are interpolated: a join turning by less than --corner-angle is rounded\n"
    "(--corner-angle 30 keeps a 38.7 degree join; --levels 0 writes them\n"
    "unchanged). Or flatten every curve to a polyline within a tolerance.\n"
    "Everything else in the document is kept as it is.\n"
    "IN and OUT may be '-' for stdin/stdout.\n",
    opts,
    "Several files: one error line per failed file, one summary line on stderr;\n"
    "every other file is still written. At most 1048576 files in one call.\n"
    "\n"
    "Exit status: 0 ok (warnings included), 1 error (output untouched; several\n"
    "files: some failed), 2 usage.\n",
    "svg",
    0,
    NULL,
};

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct warn_ctx {
    const char *name;
} warn_ctx;

static void on_warning(void *ctx, size_t line, const char *message)
{
    const warn_ctx *w = ctx;
    char where[1100];
    if (line)
        snprintf(where, sizeof where, "%s:%zu", w->name, line);
    else
        snprintf(where, sizeof where, "%s", w->name);
    cli_warning(PROG, where, "%s", message);
}

static int fail_status(const char *name, const conica_status *st)
{
    char where[1100];
    if (st->line)
        snprintf(where, sizeof where, "%s:%zu", name, st->line);
    else
        snprintf(where, sizeof where, "%s", name);
    return cli_error(PROG, where, "%s", st->message);
}

static int size_arg(const char *flag, const char *v, size_t *out)
{
    long x;
    if (!v || cli_parse_int(v, 1, 0x7fffffffL, &x))
        return cli_usage_error(PROG, "%s needs a whole number in 1..2147483647", flag);
    *out = (size_t)x;
    return 0;
}

/* Split "a,b,c" into ids (pointers into s, which is modified). */
static int split_ids(char *s, const char **ids, size_t *n)
{
    char *p = s;
    *n = 0;
    while (*p) {
        char *c = strchr(p, ',');
        if (c)
            *c = '\0';
        if (*p) {
            if (*n == MAX_SELECT)
                return 1;
            ids[(*n)++] = p;
        }
        if (!c)
            break;
        p = c + 1;
    }
    return 0;
}

/* What one run applies to every file. */
typedef struct run_opts {
    conica_svg_settings set; /* select, warn and warn_ctx set per file */
    int want_stats;
    /* a single document's progress line (a batch has its own, per file):
     * AUTO shows it for documents of at least DOC_PROGRESS_BYTES of path
     * data, on a terminal; ON for any; OFF never */
    cli_progress_mode doc_progress;
} run_opts;

/* About 10^5 vertices of path data: below it a document takes well under
 * a second and needs no progress line. */
#define DOC_PROGRESS_BYTES 1000000u

/* One document: read in, write out ("-" or NULL = stdout). The whole work
 * of a single-file run, and of each file of a batch (in its own process). */
static int smooth_file(void *ctx, const char *in, const char *out_path)
{
    const run_opts *ro = ctx;
    conica_svg_settings set = ro->set;
    cli_progress_job dp;
    conica_svg_stats stats, *want;
    conica_svg_doc *doc = NULL;
    conica_code prc;
    conica_status st;
    warn_ctx wc;
    char *buf = NULL;
    size_t len = 0;
    int rc = 1;
    double t_start, t_io = 0.0, t0;
    cli_output out;

    memset(&stats, 0, sizeof stats);
    memset(&out, 0, sizeof out);
    wc.name = strcmp(in, "-") ? in : "<stdin>";
    set.warn = on_warning;
    set.warn_ctx = &wc;
    cli_progress_job_init(&dp, PROG, "kB", ro->doc_progress, DOC_PROGRESS_BYTES, 1000);
    if (ro->doc_progress != CLI_PROGRESS_OFF) {
        set.progress = cli_progress_report;
        set.progress_ctx = &dp;
    }

    t_start = now();
    if (cli_read_file(PROG, in, set.limits.max_bytes, &buf, &len))
        goto done;
    t0 = now();
    /* the document keeps buf (the byte-true save needs it): no second copy */
    if (conica_svg_doc_load_owned(buf, len, &set.limits, &doc, &st) != CONICA_OK) {
        fail_status(wc.name, &st);
        goto done;
    }
    buf = NULL;
    t_io += now() - t0;
    t0 = now();
    /* opened first: a file gets each element's new path data as soon as it
     * is made (into the temporary, which a failure removes) instead of all
     * of it held in memory; stdout and devices get the document once all
     * of it succeeded */
    if (cli_output_open(PROG, out_path, &out))
        goto done;
    t_io += now() - t0;
    /* the CPU clock is a system call: read it only when asked to report */
    want = ro->want_stats ? &stats : NULL;
    if (out.tmp)
        prc = conica_svg_process_write(doc, &set, want, out.f, &st);
    else
        prc = conica_svg_process(doc, &set, want, &st);
    cli_progress_job_end(&dp);
    if (prc != CONICA_OK) {
        int write_error = out.tmp && ferror(out.f);
        cli_output_abort(&out);
        if (write_error)
            cli_error(PROG, out_path, "%s", st.message);
        else
            fail_status(wc.name, &st);
        goto done;
    }
    t0 = now();
    /* the two-step path: serialised straight into the output */
    if (!out.tmp && conica_svg_doc_write(doc, out.f, &st) != CONICA_OK) {
        cli_output_abort(&out);
        cli_error(PROG, out_path ? out_path : "<stdout>", "%s", st.message);
        goto done;
    }
    if (cli_output_commit(PROG, &out))
        goto done;
    t_io += now() - t0;
    if (ro->want_stats)
        fprintf(stderr,
                "svgsmooth: stats: %zu element%s, %zu subpath%s, %zu input vert%s, %zu output "
                "point%s, %.3f s (XML+path I/O %.3f s, geometry %.3f s)\n",
                stats.elements, cli_plural(stats.elements), stats.subpaths,
                cli_plural(stats.subpaths), stats.in_vertices,
                stats.in_vertices == 1 ? "ex" : "ices", stats.out_points,
                cli_plural(stats.out_points), now() - t_start, t_io + stats.io_seconds,
                stats.geometry_seconds);
    rc = 0;
done:
    conica_svg_doc_free(doc);
    free(buf);
    return rc;
}

/* What the command line asks for, as parsed (checked together in main). */
typedef struct cmdline {
    run_opts *ro;
    const char *out_path, *select;
    int have_levels, have_tol, flatten, in_place, recurse, jobs;
    cli_progress_mode progress;
} cmdline;

/* One option's value into *ctx; returns -1 to go on, or an exit status. */
static int take_option(cli_parser *p, int c, void *ctx)
{
    cmdline *cl = ctx;
    conica_svg_settings *setp = &cl->ro->set;
    const char *v = p->arg;
    long x;
    double d;
    switch (c) {
    case 'k':
        if (cli_parse_int(v, 0, 30, &x))
            return cli_opt_bad(p, "needs a whole number in 0..30, not '%s'", v);
        setp->levels = (int)x;
        cl->have_levels = 1;
        break;
    case 't':
        if (cli_parse_double(v, &d) || !(d > 0.0))
            return cli_opt_bad(p, "needs a number > 0, not '%s'", v);
        setp->tolerance = d;
        cl->have_tol = 1;
        break;
    case OPT_FIDELITY:
    case OPT_SIMPLIFY:
        if (cli_parse_double(v, &d) || !(d > 0.0) || !(d < 1e300))
            return cli_opt_bad(p, "needs a number > 0, not '%s'", v);
        *(c == OPT_FIDELITY ? &setp->fidelity : &setp->simplify) = d;
        break;
    case OPT_LINES: setp->lines_as_samples = 1; break;
    case OPT_CORNER:
        if (cli_parse_double(v, &d) || !(d >= 0.0 && d <= 180.0))
            return cli_opt_bad(p, "needs degrees in 0..180, not '%s'", v);
        setp->corner_angle_deg = d;
        break;
    case OPT_PRECISION:
        if (cli_parse_int(v, 1, 17, &x))
            return cli_opt_bad(p, "needs a whole number in 1..17, not '%s'", v);
        setp->precision = (int)x;
        break;
    case OPT_SELECT: cl->select = v; break;
    case OPT_FLATTEN: cl->flatten = 1; break;
    case OPT_SHAPES: setp->convert_shapes = 1; break;
    case OPT_STATS: cl->ro->want_stats = 1; break;
    case OPT_IN_PLACE: cl->in_place = 1; break;
    case 'r': cl->recurse = 1; break;
    case 'q': cl->progress = CLI_PROGRESS_OFF; break;
    case OPT_PROGRESS: cl->progress = CLI_PROGRESS_ON; break;
    case 'j':
        if (cli_parse_int(v, 1, CLI_BATCH_MAX_JOBS, &x))
            return cli_opt_bad(p, "needs a whole number in 1..%d, not '%s'", CLI_BATCH_MAX_JOBS, v);
        cl->jobs = (int)x;
        break;
    case 'o':
        cl->out_path = v;
        break;
    case OPT_MAX_POINTS:
        if (size_arg(p->spelled, v, &setp->limits.max_points))
            return CLI_EXIT_USAGE;
        break;
    default: /* --max-input-bytes and the XML limits */
        if (conica_svg__cli_limit(PROG, p->spelled, v, &setp->limits) != 1)
            return CLI_EXIT_USAGE;
        break;
    }
    return -1;
}

int main(int argc, char **argv)
{
    run_opts ro;
    conica_svg_settings *setp = &ro.set;
    const char *out_path, **ids = NULL;
    char *sel = NULL, **inputs;
    size_t nids = 0, nin = 0;
    int i, first, have_levels, have_tol, flatten, in_place, recurse, rc, jobs;
    cmdline cl;

    memset(&ro, 0, sizeof ro);
    ro.set = conica_svg_defaults();
    ro.set.precision = 0; /* digits from the tolerance unless --precision */
    ro.doc_progress = CLI_PROGRESS_OFF; /* a batch shows its own */
    memset(&cl, 0, sizeof cl);
    cl.ro = &ro;
    if ((rc = cli_opt_parse(&tool, argc, argv, take_option, &cl, &first)) >= 0)
        return rc;
    out_path = cl.out_path;
    have_levels = cl.have_levels;
    have_tol = cl.have_tol;
    flatten = cl.flatten;
    in_place = cl.in_place;
    recurse = cl.recurse;
    jobs = cl.jobs;
    /* the input names, in order: at most argc of them */
    inputs = malloc((size_t)argc * sizeof *inputs);
    sel = cl.select ? strdup(cl.select) : NULL; /* split_ids() writes into it */
    if (!inputs || (cl.select && !sel)) {
        free(inputs);
        free(sel);
        return cli_error(PROG, NULL, "out of memory");
    }
#define USAGE_FAIL(...) do { free(sel); free(inputs); return cli_usage_error(PROG, __VA_ARGS__); } while (0)
    for (i = first; i < argc; i++)
        inputs[nin++] = argv[i];
    if (nin == 0)
        USAGE_FAIL("no input file (use '-' for stdin)");
    if (have_levels && have_tol)
        USAGE_FAIL("--levels and --tolerance exclude each other");
    if (flatten && !have_tol)
        USAGE_FAIL("--flatten needs --tolerance T");
    if (flatten && have_levels)
        USAGE_FAIL("--flatten takes --tolerance, not --levels");
    if (flatten && setp->simplify > 0)
        USAGE_FAIL("--simplify cleans outlines for smoothing, not with --flatten");
    if (in_place && (out_path || !strcmp(inputs[0], "-")))
        USAGE_FAIL("--in-place needs a named input file and no -o");
    /* many files: several inputs, -r, or -o DIR/ (with one input only the
     * slash says so: `-o existing-dir` stays the error it always was) */
    int batch = nin > 1 || recurse || (out_path && out_path[strlen(out_path) - 1] == '/');
    if (batch && !in_place && !out_path)
        USAGE_FAIL("several inputs need -o DIR/ or --in-place");
    if (nin > 1 && out_path && !cli_is_dir_target(out_path))
        USAGE_FAIL("several inputs need -o DIR/ (a directory: end it with '/'), not '%s'",
                   out_path);
    if (!batch && jobs)
        USAGE_FAIL("-j applies to several files (-o DIR/, --in-place FILE..., -r)");
#undef USAGE_FAIL
    if (flatten)
        setp->mode = CONICA_SVG_FLATTEN;
    if (sel) {
        ids = malloc(MAX_SELECT * sizeof *ids);
        if (!ids) {
            free(inputs);
            return cli_error(PROG, NULL, "out of memory");
        }
        if (split_ids(sel, ids, &nids)) {
            free(ids);
            free(sel);
            free(inputs);
            return cli_usage_error(PROG, "--select takes at most %d ids", MAX_SELECT);
        }
        setp->select = ids;
        setp->nselect = nids;
    }

    if (!batch) {
        ro.doc_progress = cl.progress;
        rc = smooth_file(&ro, inputs[0], in_place ? inputs[0] : out_path);
    } else {
        cli_batch b;
        cli_batch_spec spec;
        memset(&spec, 0, sizeof spec);
        spec.outdir = in_place ? NULL : out_path;
        spec.in_place = in_place;
        spec.recurse = recurse;
        spec.ext = ".svg";
        cli_batch_init(&b);
        b.progress = cl.progress;
        rc = cli_batch_plan(PROG, inputs, nin, &spec, &b);
        if (rc == 0)
            rc = cli_batch_run(PROG, &b, jobs ? jobs : cli_batch_default_jobs(), smooth_file, &ro);
        cli_batch_free(&b);
    }
    free(ids);
    free(sel);
    free(inputs);
    return rc;
}

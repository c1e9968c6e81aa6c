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
#include "conica_svg.h"
#include "svg_cli.h"

#define PROG "svgsmooth"
#define MAX_SELECT 4096 /* ids in one --select list */

static const char usage_text[] =
    "Usage: svgsmooth [OPTION]... IN [-o OUT]\n"
    "       svgsmooth [OPTION]... FILE... -o DIR/\n"
    "       svgsmooth [OPTION]... --in-place FILE...\n"
    "       svgsmooth -r [OPTION]... DIR... (-o OUTDIR/ | --in-place)\n"
    "Smooth the outlines of an SVG file (paths, polylines, polygons) with\n"
    "conic-preserving subdivision that stays within --fidelity of the drawn\n"
    "curves: corners stay sharp, straight segments straight, arcs and conics\n"
    "exact. polygon and polyline vertices are samples of a smooth curve and\n"
    "are interpolated: a join turning by less than --corner-angle is rounded\n"
    "(--corner-angle 30 keeps a 38.7 degree join; --levels 0 writes them\n"
    "unchanged). Or flatten every curve to a polyline within a tolerance.\n"
    "Everything else in the document is kept as it is.\n"
    "IN and OUT may be '-' for stdin/stdout.\n"
    "\n";
/* (two strings: ISO C caps one at 4095 characters) */
static const char usage_options[] =
    ""
    "  --levels K          subdivision levels (default 4; 0 writes the vertices)\n"
    "  --tolerance T       smoothing: the fewest levels (per piece) whose chords\n"
    "                      stay within T user units of the smoothed curve; with\n"
    "                      --flatten: maximum distance from the drawn curve\n"
    "  --fidelity T        largest distance of the smoothed curve from the drawn\n"
    "                      one, user units (default 1e-3 of each subpath's\n"
    "                      bounding-box diagonal)\n"
    "  --corner-angle DEG  tangent turn that makes a corner (default 40; 180\n"
    "                      disables corners)\n"
    "  --lines-as-samples  smooth through the vertices of subpaths made only of\n"
    "                      straight segments (traced outlines); by default\n"
    "                      straight segments stay straight\n"
    "  --simplify T        before smoothing traced outlines (polygons, polylines;\n"
    "                      paths of straight segments with --lines-as-samples),\n"
    "                      keep the fewest vertices whose smoothed curve passes\n"
    "                      within T user units of every vertex; corners kept.\n"
    "                      Other paths of straight segments stay straight: the\n"
    "                      fewest vertices whose polygon is within T of them\n"
    "  --flatten           flatten curves within --tolerance (required) with the\n"
    "                      guaranteed adaptive plotter; straight segments stay\n"
    "  --precision N       significant digits written (1..17); by default enough\n"
    "                      that rounding takes at most 1% of the tolerance\n"
    "                      (--tolerance with --flatten, else the fidelity);\n"
    "                      fewer digits can put the output outside it\n"
    "  --select IDS        only the elements with these ids or inside groups with\n"
    "                      these ids (comma separated)\n"
    "  --convert-shapes    also rect, circle, ellipse, line (rewritten as paths)\n"
    "  --stats             counts and CPU seconds on stderr\n"
    "  --in-place          replace each input (through a temporary file)\n"
    "  -o OUT              output file (default stdout); with a name ending in\n"
    "                      '/', or a directory with several inputs or -r: the\n"
    "                      directory the outputs go to, named as the inputs\n"
    "  -r, --recursive     inputs may be directories: every *.svg under them,\n"
    "                      the tree mirrored under -o DIR/ (or --in-place)\n"
    "  -j, --jobs N        files processed in parallel (1..256, default: the\n"
    "                      number of processors); each file runs on its own\n"
    "  --max-input-bytes N   document size cap (default 64 MiB)\n"
    CONICA_SVG_CLI_LIMITS_HELP
    "  --max-points N        cap on output points in the document (default 67108864)\n"
    "  --help              this text\n"
    "  --version           the version\n"
    "\n"
    "Several files: one error line per failed file, one summary line on stderr;\n"
    "every other file is still written. At most 1048576 files in one call.\n"
    "\n"
    "Exit status: 0 ok (warnings included), 1 error (output untouched; several\n"
    "files: some failed), 2 usage.\n";

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
} run_opts;

/* One document: read in, write out ("-" or NULL = stdout). The whole work
 * of a single-file run, and of each file of a batch (in its own process). */
static int smooth_file(void *ctx, const char *in, const char *out_path)
{
    const run_opts *ro = ctx;
    conica_svg_settings set = ro->set;
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
                "svgsmooth: stats: %zu elements, %zu subpaths, %zu input vertices, %zu output "
                "points, %.3f s (XML+path I/O %.3f s, geometry %.3f s)\n",
                stats.elements, stats.subpaths, stats.in_vertices, stats.out_points,
                now() - t_start, t_io + stats.io_seconds, stats.geometry_seconds);
    rc = 0;
done:
    conica_svg_doc_free(doc);
    free(buf);
    return rc;
}

int main(int argc, char **argv)
{
    run_opts ro;
    conica_svg_settings *setp = &ro.set;
    const char *out_path = NULL, **ids = NULL;
    char *sel = NULL, **inputs;
    size_t nids = 0, nin = 0;
    int i, have_levels = 0, have_tol = 0, flatten = 0, in_place = 0, recurse = 0, rc;
    int jobs = 0;

    memset(&ro, 0, sizeof ro);
    ro.set = conica_svg_defaults();
    ro.set.precision = 0; /* digits from the tolerance unless --precision */
    /* the input names, in order: at most argc of them */
    inputs = malloc((size_t)argc * sizeof *inputs);
    if (!inputs)
        return cli_error(PROG, NULL, "out of memory");
#define USAGE_FAIL(...) do { free(sel); free(inputs); return cli_usage_error(PROG, __VA_ARGS__); } while (0)
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        long x;
        double d;
        int lr;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(usage_text, stdout);
            fputs(usage_options, stdout);
            free(sel);
            free(inputs);
            return 0;
        } else if (!strcmp(a, "--version")) {
            free(sel);
            free(inputs);
            return cli_version("svgsmooth");
        } else if (!strcmp(a, "--levels")) {
            if (!v || cli_parse_int(v, 0, 30, &x))
                USAGE_FAIL("--levels needs a whole number in 0..30");
            setp->levels = (int)x;
            have_levels = 1;
            i++;
        } else if (!strcmp(a, "--tolerance")) {
            if (!v || cli_parse_double(v, &d) || !(d > 0.0))
                USAGE_FAIL("--tolerance needs a number > 0");
            setp->tolerance = d;
            have_tol = 1;
            i++;
        } else if (!strcmp(a, "--fidelity")) {
            if (!v || cli_parse_double(v, &d) || !(d > 0.0) || !(d < 1e300))
                USAGE_FAIL("--fidelity needs a number > 0");
            setp->fidelity = d;
            i++;
        } else if (!strcmp(a, "--lines-as-samples")) {
            setp->lines_as_samples = 1;
        } else if (!strcmp(a, "--simplify")) {
            if (!v || cli_parse_double(v, &d) || !(d > 0.0) || !(d < 1e300))
                USAGE_FAIL("--simplify needs a number > 0");
            setp->simplify = d;
            i++;
        } else if (!strcmp(a, "--corner-angle")) {
            if (!v || cli_parse_double(v, &d) || !(d >= 0.0 && d <= 180.0))
                USAGE_FAIL("--corner-angle needs degrees in 0..180");
            setp->corner_angle_deg = d;
            i++;
        } else if (!strcmp(a, "--precision")) {
            if (!v || cli_parse_int(v, 1, 17, &x))
                USAGE_FAIL("--precision needs a whole number in 1..17");
            setp->precision = (int)x;
            i++;
        } else if (!strcmp(a, "--select")) {
            if (!v)
                USAGE_FAIL("--select needs a list of ids");
            free(sel);
            sel = strdup(v);
            if (!sel) {
                free(inputs);
                return cli_error(PROG, NULL, "out of memory");
            }
            i++;
        } else if (!strcmp(a, "--flatten")) {
            flatten = 1;
        } else if (!strcmp(a, "--convert-shapes")) {
            setp->convert_shapes = 1;
        } else if (!strcmp(a, "--stats")) {
            ro.want_stats = 1;
        } else if (!strcmp(a, "--in-place")) {
            in_place = 1;
        } else if (!strcmp(a, "-r") || !strcmp(a, "--recursive")) {
            recurse = 1;
        } else if (!strcmp(a, "-j") || !strcmp(a, "--jobs")) {
            if (!v || cli_parse_int(v, 1, CLI_BATCH_MAX_JOBS, &x))
                USAGE_FAIL("%s needs a whole number in 1..%d", a, CLI_BATCH_MAX_JOBS);
            jobs = (int)x;
            i++;
        } else if (!strcmp(a, "-o")) {
            if (!v || !*v)
                USAGE_FAIL("-o needs a file name");
            out_path = v;
            i++;
        } else if ((lr = conica_svg__cli_limit(PROG, a, v, &setp->limits)) != 0) {
            if (lr < 0) {
                free(sel);
                free(inputs);
                return CLI_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--max-points")) {
            if (size_arg(a, v, &setp->limits.max_points)) {
                free(sel);
                free(inputs);
                return CLI_EXIT_USAGE;
            }
            i++;
        } else if (a[0] == '-' && a[1] != '\0') {
            USAGE_FAIL("unknown option '%s'", a);
        } else {
            inputs[nin++] = argv[i];
        }
    }
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

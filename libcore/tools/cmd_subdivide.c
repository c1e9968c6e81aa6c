/* SPDX-License-Identifier: MIT */
/* `conica subdivide`: conic-preserving interpolatory subdivision of a
 * point-normal curve in the reference implementation's text format
 * (seed 000, Section 1.1; README.md). */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli.h"
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

static void usage(FILE *f)
{
    fprintf(f,
            "usage: conica subdivide [-k LEVELS] [--open|--closed] [--precise]\n"
            "                        [--estimate-normals] [--normals area|circle]\n"
            "                        [--reference-compatible] [--max-points N]\n"
            "                        [--max-input-points N] [--threads N] [--time]\n"
            "                        [-o OUT] [IN]\n"
            "\n"
            "Refine a point-normal curve with conic-preserving interpolatory subdivision\n"
            "(the CONIS scheme of Bügel, Romani and Kosinka): every level keeps the old\n"
            "points and inserts one point per edge.\n"
            "\n"
            "Input: `v x y` lines, then optional `vn nx ny` lines paired with the points by\n"
            "order; `#`/`%%` lines and blank lines are ignored. IN of `-` or none: stdin.\n"
            "Output: `v x y` lines, then `vn nx ny` lines (unit normals), to OUT or stdout.\n"
            "\n"
            "options:\n"
            "  -k, --levels LEVELS     subdivision levels, 0..%d (default %d)\n"
            "      --open              the curve is open (n points -> 2n-1 per level)\n"
            "      --closed            the curve is closed (default; n -> 2n per level)\n"
            "      --precise           read, compute and write in long double (input\n"
            "                          correctly rounded to long double, output %%.21Lg)\n"
            "      --estimate-normals  ignore `vn` lines and estimate normals\n"
            "      --normals METHOD    how to estimate normals (input without `vn`, or\n"
            "                          --estimate-normals): area (default, area-weighted\n"
            "                          edge normals) or circle (circle through neighbours)\n"
            "      --reference-compatible  fit in absolute coordinates with the SVD, as the\n"
            "                          reference implementation does (for comparisons)\n"
            "      --max-points N      refuse outputs of more than N points (default %zu)\n"
            "      --max-input-points N  refuse inputs of more than N points (default %zu;\n"
            "                          the input file size is capped by the environment\n"
            "                          variable CONICA_MAX_INPUT_BYTES, default %zu bytes)\n"
            "      --threads N         worker threads (results are bit-identical for any N)\n"
            "      --time              print `subdivide: N edge points in S s (U us/point)` on\n"
            "                          stderr: the subdivision alone, best of %d runs\n"
            "  -o, --output OUT        write to OUT (`-` = stdout) via a temporary file\n"
            "  -h, --help              show this help\n"
            "\n"
            "exit status: 0 success, 1 error (bad input, I/O; nothing is written),\n"
            "2 usage error.\n",
            CONICA_SUBDIV_MAX_LEVELS, DEFAULT_LEVELS, (size_t)CONICA_SUBDIV_DEFAULT_MAX_POINTS,
            (size_t)CONICA_CURVE_MAX_INPUT_POINTS, (size_t)CLI_DEFAULT_MAX_INPUT, TIME_RUNS);
}

typedef struct options {
    long levels;
    int open, precise, estimate, refcompat, time;
    conica_normal_method method;
    size_t max_points, max_input_points;
    int threads;
    const char *in, *out;
} options;

/* Value of an option given as "--name VALUE", "--name=VALUE" or "-kVALUE".
 * Returns NULL (after a usage message) when it is missing. */
static const char *opt_value(int argc, char **argv, int *i, const char *arg, size_t name_len)
{
    if (arg[name_len] == '=')
        return arg + name_len + 1;
    if (arg[name_len] != '\0' && arg[1] != '-') /* -k5 */
        return arg + name_len;
    if (*i + 1 >= argc)
        return NULL;
    return argv[++*i];
}

/* Returns -1 to go on, or an exit status. */
static int parse_args(int argc, char **argv, options *o)
{
    int i, positional_only = 0;
    o->levels = DEFAULT_LEVELS;
    o->open = o->precise = o->estimate = o->refcompat = o->time = 0;
    o->method = CONICA_NORMALS_AREA;
    o->max_points = CONICA_SUBDIV_DEFAULT_MAX_POINTS;
    o->max_input_points = CONICA_CURVE_MAX_INPUT_POINTS;
    o->threads = 0;
    o->in = NULL;
    o->out = NULL;

    for (i = 1; i < argc; i++) {
        const char *a = argv[i], *v;
        long num;
        if (positional_only || a[0] != '-' || strcmp(a, "-") == 0) {
            if (o->in)
                return cli_usage_error(USAGE_PROG, "more than one input file ('%s' and '%s')",
                                       o->in, a);
            o->in = a;
            continue;
        }
        if (strcmp(a, "--") == 0) {
            positional_only = 1;
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return fflush(stdout) == 0 ? CLI_EXIT_OK : CLI_EXIT_ERROR;
        } else if (strcmp(a, "--open") == 0) {
            o->open = 1;
        } else if (strcmp(a, "--closed") == 0) {
            o->open = 0;
        } else if (strcmp(a, "--precise") == 0) {
            o->precise = 1;
        } else if (strcmp(a, "--estimate-normals") == 0) {
            o->estimate = 1;
        } else if (strcmp(a, "--reference-compatible") == 0) {
            o->refcompat = 1;
        } else if (strcmp(a, "--time") == 0) {
            o->time = 1;
        } else if (strncmp(a, "-k", 2) == 0 || strncmp(a, "--levels", 8) == 0) {
            size_t nl = a[1] == '-' ? 8 : 2;
            if (a[1] == '-' && a[nl] != '\0' && a[nl] != '=')
                return cli_usage_error(USAGE_PROG, "unknown option '%s'", a);
            v = opt_value(argc, argv, &i, a, nl);
            if (!v)
                return cli_usage_error(USAGE_PROG, "%s needs a number of levels", a);
            if (cli_parse_int(v, 0, CONICA_SUBDIV_MAX_LEVELS, &num))
                return cli_usage_error(USAGE_PROG, "levels must be an integer in 0..%d, not '%s'",
                                       CONICA_SUBDIV_MAX_LEVELS, v);
            o->levels = num;
        } else if (strncmp(a, "-o", 2) == 0 || strncmp(a, "--output", 8) == 0) {
            size_t nl = a[1] == '-' ? 8 : 2;
            if (a[1] == '-' && a[nl] != '\0' && a[nl] != '=')
                return cli_usage_error(USAGE_PROG, "unknown option '%s'", a);
            v = opt_value(argc, argv, &i, a, nl);
            if (!v || !*v)
                return cli_usage_error(USAGE_PROG, "%s needs a file name", a);
            o->out = v;
        } else if (strncmp(a, "--normals", 9) == 0 && (a[9] == '\0' || a[9] == '=')) {
            v = opt_value(argc, argv, &i, a, 9);
            if (v && strcmp(v, "area") == 0)
                o->method = CONICA_NORMALS_AREA;
            else if (v && strcmp(v, "circle") == 0)
                o->method = CONICA_NORMALS_CIRCLE;
            else
                return cli_usage_error(USAGE_PROG, "--normals takes 'area' or 'circle'%s%s%s",
                                       v ? ", not '" : "", v ? v : "", v ? "'" : "");
        } else if (strncmp(a, "--max-points", 12) == 0 && (a[12] == '\0' || a[12] == '=')) {
            v = opt_value(argc, argv, &i, a, 12);
            if (!v || cli_parse_int(v, 1, LONG_MAX, &num))
                return cli_usage_error(USAGE_PROG, "--max-points needs a positive integer%s%s%s",
                                       v ? ", not '" : "", v ? v : "", v ? "'" : "");
            o->max_points = (size_t)num;
        } else if (strncmp(a, "--max-input-points", 18) == 0 && (a[18] == '\0' || a[18] == '=')) {
            v = opt_value(argc, argv, &i, a, 18);
            if (!v || cli_parse_int(v, 1, LONG_MAX, &num))
                return cli_usage_error(USAGE_PROG,
                                       "--max-input-points needs a positive integer%s%s%s",
                                       v ? ", not '" : "", v ? v : "", v ? "'" : "");
            o->max_input_points = (size_t)num;
        } else if (strncmp(a, "--threads", 9) == 0 && (a[9] == '\0' || a[9] == '=')) {
            v = opt_value(argc, argv, &i, a, 9);
            if (!v || cli_parse_int(v, 1, MAX_THREADS, &num))
                return cli_usage_error(USAGE_PROG, "--threads needs an integer in 1..%d%s%s%s",
                                       MAX_THREADS, v ? ", not '" : "", v ? v : "", v ? "'" : "");
            o->threads = (int)num;
        } else {
            return cli_usage_error(USAGE_PROG, "unknown option '%s'", a);
        }
    }
    return -1;
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
     * the long double engine unrounded (seed 000, Table 1 through the CLI). */
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

/* SPDX-License-Identifier: MIT */
/* `conica plot`: plot a B-spline (.spl, docs/file-formats.md) as a
 * polyline with any method of seed 004 or the guaranteed plotter
 * (README.md). Output: one `x y` (or `x y z`) line per vertex, a blank
 * line between pieces split at discontinuities. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "conica/bspline.h"
#include "conica/plot.h"

#define PROG "conica"
#define USAGE_PROG "conica plot"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: conica plot [--method METHOD] [--criterion NAME] [--rule NAME]\n"
            "                   [--stop movement|threshold|budget] [--knot-budget K]\n"
            "                   [--abs-tolerance E | --tolerance PX [--viewport WxH]]\n"
            "                   [--points N] [--curve-points] [--prephase K]\n"
            "                   [--local-weight length|angle|both] [--angle DEG]\n"
            "                   [--max-recursion N] [--max-points N] [--max-knots N]\n"
            "                   [--max-iterations N] [--max-control-points N]\n"
            "                   [--max-degree N] [--stats] [-o OUT] IN.spl\n"
            "\n"
            "Plot a B-spline function or curve (optionally rational) as a polyline\n"
            "(after T. Dahl, \"Adaptive plotting of splines\", Oslo 2019).\n"
            "\n"
            "Input: `degree P`, `knots ...`, one `c x [y [z]]` line per control point,\n"
            "optional `w ...` weights; `#` starts a comment. IN of `-`: stdin.\n"
            "Output: one `x y` line per vertex (`t f(t)` for a spline function, `x y z`\n"
            "for a 3-D curve); a blank line separates pieces split at discontinuities.\n"
            "\n"
            "options:\n"
            "      --method METHOD     guaranteed (default: every point of the spline within\n"
            "                          the tolerance of the polyline and back), adaptive (the\n"
            "                          thesis's knot-insertion loop), uniform, local-uniform,\n"
            "                          chaikin, lane-riesenfeld, mathematica\n"
            "      --criterion NAME    adaptive: simplified-length, length, length-ratio\n"
            "                          (default), simplified-angle, angle, base-line,\n"
            "                          extended-base-line\n"
            "      --rule NAME         adaptive: midpoint (default, R = 0.5), knot-average,\n"
            "                          chaikin\n"
            "      --stop NAME         adaptive: movement (default), threshold, budget\n"
            "      --knot-budget K     adaptive: knots inserted at most (default %zu)\n"
            "      --curve-points      adaptive: emit curve points at the knot averages\n"
            "                          instead of the refined control polygon\n"
            "      --prephase K        adaptive: insert K uniform knots before the loop\n"
            "      --local-weight W    local-uniform: share points by control polygon\n"
            "                          length, angle or both (default, omega = 0.5)\n"
            "      --angle DEG         mathematica: angle threshold (default 5)\n"
            "      --max-recursion N   mathematica: recursion depth (default 6)\n"
            "      --abs-tolerance E   tolerance in curve units\n"
            "      --tolerance PX      tolerance in pixels (default %g) for the viewport,\n"
            "                          eps = PX / diagonal * (control point box diagonal)\n"
            "      --viewport WxH      viewport in pixels (default 1000x1000)\n"
            "      --points N          uniform / local-uniform / chaikin / lane-riesenfeld:\n"
            "                          number of points (default %zu); mathematica: initial\n"
            "                          points (default 50)\n"
            "      --stats             print `plot: <points> points, <K> knots inserted,\n"
            "                          <ops> flops, <S> s` on stderr\n"
            "  -o, --output OUT        write to OUT (`-` = stdout) via a temporary file\n"
            "  -h, --help              show this help\n"
            "\n"
            "limits (the run fails with exit 1 and a message naming the flag when one is\n"
            "hit; nothing is written):\n"
            "      --max-points N      refuse outputs of more than N points (default %zu)\n"
            "      --max-knots N       refuse to insert more than N knots, in all (default\n"
            "                          %zu); --knot-budget and --prephase must not exceed it\n"
            "      --max-iterations N  refuse to run more than N plotter iterations / trial\n"
            "                          steps (default %zu)\n"
            "      --max-control-points N  refuse input splines with more than N control\n"
            "                          points (default and maximum %zu)\n"
            "      --max-degree N      refuse input splines of degree above N (default and\n"
            "                          maximum %d)\n"
            "      (the input file size: environment variable CONICA_MAX_INPUT_BYTES,\n"
            "      default %zu bytes)\n"
            "\n"
            "exit status: 0 success, 1 error (bad input, I/O; nothing is written),\n"
            "2 usage error.\n",
            (size_t)CONICA_PLOT_DEFAULT_KNOT_BUDGET, CONICA_PLOT_DEFAULT_PIXEL_TOLERANCE,
            (size_t)CONICA_PLOT_DEFAULT_UNIFORM_POINTS, (size_t)CONICA_PLOT_MAX_POINTS_DEFAULT,
            (size_t)CONICA_PLOT_MAX_KNOTS_DEFAULT, (size_t)CONICA_PLOT_MAX_ITERATIONS_DEFAULT,
            (size_t)CONICA_BSPLINE_MAX_CTRL, CONICA_BSPLINE_MAX_DEGREE,
            (size_t)CLI_DEFAULT_MAX_INPUT);
}

typedef struct options {
    conica_plot_settings set;
    conica_bspline_parse_limits read; /* caps of the .spl reader */
    int stats, have_abs, have_px, have_points, have_budget;
    const char *in, *out;
} options;

/* "--name VALUE" or "--name=VALUE"; NULL when missing. */
static const char *opt_value(int argc, char **argv, int *i, const char *arg, size_t name_len)
{
    if (arg[name_len] == '=')
        return arg + name_len + 1;
    if (arg[name_len] != '\0' && arg[1] != '-') /* -oFILE */
        return arg + name_len;
    if (*i + 1 >= argc)
        return NULL;
    return argv[++*i];
}

static int is_opt(const char *a, const char *name)
{
    size_t n = strlen(name);
    return strncmp(a, name, n) == 0 && (a[n] == '\0' || a[n] == '=');
}

static int parse_viewport(const char *v, double *w, double *h)
{
    const char *x = strchr(v, 'x');
    if (!x)
        x = strchr(v, 'X');
    if (!x || x == v || strlen(x) > 40 || (size_t)(x - v) > 40)
        return 1;
    char a[48], b[48];
    memcpy(a, v, (size_t)(x - v));
    a[x - v] = '\0';
    strcpy(b, x + 1);
    if (cli_parse_double(a, w) || cli_parse_double(b, h) || !(*w > 0) || !(*h > 0))
        return 1;
    return 0;
}

#define NEED(cond, ...)                                                                       \
    do {                                                                                      \
        if (!(cond))                                                                          \
            return cli_usage_error(USAGE_PROG, __VA_ARGS__);                                  \
    } while (0)

/* Returns -1 to go on, or an exit status. */
static int parse_args(int argc, char **argv, options *o)
{
    int positional_only = 0;
    o->set = conica_plot_defaults();
    o->read = conica_bspline_parse_limits_defaults();
    o->stats = o->have_abs = o->have_px = o->have_points = o->have_budget = 0;
    o->in = o->out = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v;
        long num;
        double x;
        if (positional_only || a[0] != '-' || strcmp(a, "-") == 0) {
            NEED(!o->in, "more than one input file ('%s' and '%s')", o->in, a);
            o->in = a;
            continue;
        }
        if (strcmp(a, "--") == 0) {
            positional_only = 1;
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return fflush(stdout) == 0 ? CLI_EXIT_OK : CLI_EXIT_ERROR;
        } else if (strcmp(a, "--stats") == 0) {
            o->stats = 1;
        } else if (strcmp(a, "--curve-points") == 0) {
            o->set.output = CONICA_OUTPUT_CURVE_POINTS;
        } else if (is_opt(a, "--method")) {
            v = opt_value(argc, argv, &i, a, 8);
            int m = conica_plot_method_from_name(v);
            NEED(m >= 0, "unknown method '%s' (see --help)", v ? v : "");
            o->set.method = (conica_plot_method)m;
        } else if (is_opt(a, "--criterion")) {
            v = opt_value(argc, argv, &i, a, 11);
            int c = conica_plot_criterion_from_name(v);
            NEED(c >= 0, "unknown criterion '%s' (see --help)", v ? v : "");
            o->set.criterion = (conica_plot_criterion)c;
        } else if (is_opt(a, "--rule")) {
            v = opt_value(argc, argv, &i, a, 6);
            int r = conica_plot_rule_from_name(v);
            NEED(r >= 0, "unknown rule '%s' (see --help)", v ? v : "");
            o->set.rule = (conica_plot_rule)r;
        } else if (is_opt(a, "--stop")) {
            v = opt_value(argc, argv, &i, a, 6);
            if (v && strcmp(v, "movement") == 0)
                o->set.stop = CONICA_STOP_MOVEMENT;
            else if (v && strcmp(v, "threshold") == 0)
                o->set.stop = CONICA_STOP_THRESHOLD;
            else if (v && strcmp(v, "budget") == 0)
                o->set.stop = CONICA_STOP_BUDGET;
            else
                NEED(0, "--stop takes movement, threshold or budget");
        } else if (is_opt(a, "--knot-budget")) {
            v = opt_value(argc, argv, &i, a, 13);
            NEED(v && !cli_parse_int(v, 0, LONG_MAX, &num),
                 "--knot-budget needs a whole number of knots");
            o->set.knot_budget = (size_t)num;
            o->have_budget = 1;
        } else if (is_opt(a, "--prephase")) {
            v = opt_value(argc, argv, &i, a, 10);
            NEED(v && !cli_parse_int(v, 0, LONG_MAX, &num),
                 "--prephase needs a whole number of knots");
            o->set.prephase_knots = (size_t)num;
        } else if (is_opt(a, "--local-weight")) {
            v = opt_value(argc, argv, &i, a, 14);
            if (v && strcmp(v, "length") == 0)
                o->set.local_weight = CONICA_LOCAL_LENGTH;
            else if (v && strcmp(v, "angle") == 0)
                o->set.local_weight = CONICA_LOCAL_ANGLE;
            else if (v && strcmp(v, "both") == 0)
                o->set.local_weight = CONICA_LOCAL_BOTH;
            else
                NEED(0, "--local-weight takes length, angle or both");
        } else if (is_opt(a, "--angle")) {
            v = opt_value(argc, argv, &i, a, 7);
            NEED(v && !cli_parse_double(v, &x) && x > 0 && x < 180,
                 "--angle needs degrees in (0, 180)");
            o->set.math_angle = x * 3.14159265358979323846 / 180.0;
        } else if (is_opt(a, "--max-recursion")) {
            v = opt_value(argc, argv, &i, a, 15);
            NEED(v && !cli_parse_int(v, 0, 60, &num), "--max-recursion needs an integer in 0..60");
            o->set.math_max_recursion = (size_t)num;
        } else if (is_opt(a, "--abs-tolerance")) {
            v = opt_value(argc, argv, &i, a, 15);
            NEED(v && !cli_parse_double(v, &x) && x > 0,
                 "--abs-tolerance needs a positive number");
            o->set.abs_tolerance = x;
            o->have_abs = 1;
        } else if (is_opt(a, "--tolerance")) {
            v = opt_value(argc, argv, &i, a, 11);
            NEED(v && !cli_parse_double(v, &x) && x > 0, "--tolerance needs a positive number");
            o->set.pixel_tolerance = x;
            o->have_px = 1;
        } else if (is_opt(a, "--viewport")) {
            v = opt_value(argc, argv, &i, a, 10);
            NEED(v && !parse_viewport(v, &o->set.viewport_w, &o->set.viewport_h),
                 "--viewport needs WxH with positive numbers, e.g. 1000x800");
        } else if (is_opt(a, "--points")) {
            v = opt_value(argc, argv, &i, a, 8);
            NEED(v && !cli_parse_int(v, 2, LONG_MAX, &num), "--points needs an integer >= 2");
            o->set.points = (size_t)num;
            o->have_points = 1;
        } else if (is_opt(a, "--max-points")) {
            v = opt_value(argc, argv, &i, a, 12);
            NEED(v && !cli_parse_int(v, 2, LONG_MAX, &num), "--max-points needs an integer >= 2");
            o->set.max_points = (size_t)num;
        } else if (is_opt(a, "--max-knots")) {
            v = opt_value(argc, argv, &i, a, 11);
            NEED(v && !cli_parse_int(v, 0, LONG_MAX, &num), "--max-knots needs an integer >= 0");
            o->set.max_knots = (size_t)num;
        } else if (is_opt(a, "--max-iterations")) {
            v = opt_value(argc, argv, &i, a, 16);
            NEED(v && !cli_parse_int(v, 1, LONG_MAX, &num),
                 "--max-iterations needs an integer >= 1");
            o->set.max_iterations = (size_t)num;
        } else if (is_opt(a, "--max-control-points")) {
            v = opt_value(argc, argv, &i, a, 20);
            NEED(v && !cli_parse_int(v, 1, (long)CONICA_BSPLINE_MAX_CTRL, &num),
                 "--max-control-points needs an integer in 1..%zu",
                 (size_t)CONICA_BSPLINE_MAX_CTRL);
            o->read.max_ctrl = (size_t)num;
        } else if (is_opt(a, "--max-degree")) {
            v = opt_value(argc, argv, &i, a, 12);
            NEED(v && !cli_parse_int(v, 1, CONICA_BSPLINE_MAX_DEGREE, &num),
                 "--max-degree needs an integer in 1..%d", CONICA_BSPLINE_MAX_DEGREE);
            o->read.max_degree = (int)num;
        } else if (strncmp(a, "-o", 2) == 0 || is_opt(a, "--output")) {
            size_t nl = a[1] == '-' ? 8 : 2;
            v = opt_value(argc, argv, &i, a, nl);
            NEED(v && *v, "%s needs a file name", a);
            o->out = v;
        } else {
            return cli_usage_error(USAGE_PROG, "unknown option '%s'", a);
        }
    }
    NEED(!(o->have_abs && o->have_px), "give --abs-tolerance or --tolerance, not both");
    NEED(o->in, "no input file (use `-` for stdin)");
    if (o->have_points && o->set.method == CONICA_PLOT_MATHEMATICA)
        o->set.math_initial_points = o->set.points;
    /* --points is input-controlled too: it must not lift the output cap */
    NEED(!o->have_points || o->set.points <= o->set.max_points,
         "--points %zu exceeds --max-points %zu",
         o->set.points, o->set.max_points);
    /* the adaptive loop's budgets are knots inserted too: a lower
     * --max-knots lowers the default budget, an explicit one must fit */
    if (!o->have_budget && o->set.knot_budget > o->set.max_knots)
        o->set.knot_budget = o->set.max_knots;
    NEED(o->set.knot_budget <= o->set.max_knots, "--knot-budget %zu exceeds --max-knots %zu",
         o->set.knot_budget, o->set.max_knots);
    NEED(o->set.prephase_knots <= o->set.max_knots, "--prephase %zu exceeds --max-knots %zu",
         o->set.prephase_knots, o->set.max_knots);
    return -1;
}

static int write_polyline(FILE *f, const conica_polyline *pl)
{
    size_t d = (size_t)pl->dim;
    size_t k = 0;
    for (size_t i = 0; i < pl->n; i++) {
        while (k < pl->npieces && pl->piece_start[k] == i) {
            if (k > 0 && fputc('\n', f) == EOF)
                return 1;
            k++;
        }
        for (size_t c = 0; c < d; c++)
            if (fprintf(f, c + 1 < d ? "%.17g " : "%.17g\n", pl->xy[i * d + c]) < 0)
                return 1;
    }
    return ferror(f) != 0;
}

/* The flag behind a CONICA_ERR_LIMIT: the library names the settings field
 * it hit in parentheses ("(max_knots)"); say which flag moves that cap. */
static const char *limit_hint(const char *msg, const options *o, char *buf, size_t cap)
{
    if (strstr(msg, "(max_ctrl)"))
        snprintf(buf, cap, "; %s --max-control-points N",
                 o->read.max_ctrl < CONICA_BSPLINE_MAX_CTRL ? "raise the cap with"
                                                             : "already the largest");
    else if (strstr(msg, "(max_degree)"))
        snprintf(buf, cap, "; raise the cap with --max-degree N (at most %d)",
                 CONICA_BSPLINE_MAX_DEGREE);
    else if (strstr(msg, "max_points"))
        snprintf(buf, cap, "; raise the cap with --max-points N");
    else if (strstr(msg, "max_knots"))
        snprintf(buf, cap, "; raise the cap with --max-knots N");
    else if (strstr(msg, "max_iterations"))
        snprintf(buf, cap, "; raise the cap with --max-iterations N");
    else
        buf[0] = '\0';
    return buf;
}

/* Called by the dispatcher (conica.c), which declares it from commands.def. */
extern const char conica_cmd_plot_summary[];
const char conica_cmd_plot_summary[] = "B-spline or NURBS to a polyline within a tolerance";
int conica_cmd_plot(int argc, char **argv);

int conica_cmd_plot(int argc, char **argv)
{
    options o;
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0)
        return rc;
    const char *name = strcmp(o.in, "-") == 0 ? "<stdin>" : o.in;
    char *buf = NULL;
    size_t len = 0;
    if (cli_read_file(PROG, o.in, cli_max_input(PROG), &buf, &len))
        return CLI_EXIT_ERROR;
    conica_bspline s;
    conica_bspline_init(&s);
    conica_status st;
    memset(&st, 0, sizeof st);
    char where[4096], hint[96];
    conica_code code = conica_bspline_parse_ex(buf, len, &o.read, &s, &st);
    free(buf);
    if (code != CONICA_OK) {
        if (st.line > 0)
            snprintf(where, sizeof where, "%s:%zu", name, st.line);
        else
            snprintf(where, sizeof where, "%s", name);
        cli_error(PROG, where, "%s%s", st.message[0] ? st.message : conica_strerror(code),
                  code == CONICA_ERR_LIMIT ? limit_hint(st.message, &o, hint, sizeof hint) : "");
        return CLI_EXIT_ERROR;
    }
    cli_output co;
    if (cli_output_open(PROG, o.out, &co)) {
        conica_bspline_free(&s);
        return CLI_EXIT_ERROR;
    }
    conica_polyline pl;
    conica_polyline_init(&pl);
    conica_plot_stats stats;
    code = conica_plot(&s, &o.set, &pl, &stats, &st);
    conica_bspline_free(&s);
    if (code != CONICA_OK) {
        cli_error(PROG, name, "%s%s", st.message[0] ? st.message : conica_strerror(code),
                  code == CONICA_ERR_LIMIT ? limit_hint(st.message, &o, hint, sizeof hint) : "");
        cli_output_abort(&co);
        return CLI_EXIT_ERROR;
    }
    rc = write_polyline(co.f, &pl);
    conica_polyline_free(&pl);
    if (rc) {
        cli_error(PROG, o.out && strcmp(o.out, "-") != 0 ? o.out : "<stdout>", "write error: %s", strerror(errno ? errno : EIO));
        cli_output_abort(&co);
        return CLI_EXIT_ERROR;
    }
    if (cli_output_commit(PROG, &co))
        return CLI_EXIT_ERROR;
    if (o.stats)
        fprintf(stderr, "plot: %zu points, %zu knots inserted, %.0f flops, %.6g s\n",
                stats.points, stats.knots_inserted, stats.flops, stats.seconds);
    return CLI_EXIT_OK;
}

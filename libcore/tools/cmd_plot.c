/* SPDX-License-Identifier: MIT */
/* `conica plot`: plot a B-spline (.spl, docs/file-formats.md) as a
 * polyline with any method of Dahl 2019 or the guaranteed plotter
 * (README.md). Output: one `x y` (or `x y z`) line per vertex, a blank
 * line between pieces split at discontinuities. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_opt.h"
#include "conica/bspline.h"
#include "conica/dxf.h"
#include "conica/plot.h"

#define PROG "conica"
#define USAGE_PROG "conica plot"

enum {
    OPT_METHOD = CLI_OPT_LONG,
    OPT_CRITERION,
    OPT_RULE,
    OPT_STOP,
    OPT_KNOT_BUDGET,
    OPT_CURVE_POINTS,
    OPT_PREPHASE,
    OPT_LOCAL_WEIGHT,
    OPT_ANGLE,
    OPT_MAX_RECURSION,
    OPT_ABS_TOLERANCE,
    OPT_TOLERANCE,
    OPT_VIEWPORT,
    OPT_POINTS,
    OPT_STATS,
    OPT_MAX_POINTS,
    OPT_MAX_KNOTS,
    OPT_MAX_ITERATIONS,
    OPT_MAX_CTRL,
    OPT_MAX_DEGREE,
    OPT_ENTITY,
};

static const cli_opt opts[] = {
    {OPT_METHOD, "method", CLI_ARG_REQUIRED, "METHOD",
     "guaranteed|adaptive|uniform|local-uniform|chaikin|lane-riesenfeld|mathematica",
     "guaranteed (default: every point of the spline\n"
     "within the tolerance of the polyline and back),\n"
     "adaptive (the thesis's knot-insertion loop),\n"
     "uniform, local-uniform, chaikin, lane-riesenfeld,\n"
     "mathematica",
     {0, 0, 0}},
    {OPT_CRITERION, "criterion", CLI_ARG_REQUIRED, "NAME",
     "simplified-length|length|length-ratio|simplified-angle|angle|base-line|extended-base-line",
     "adaptive: simplified-length, length, length-ratio\n"
     "(default), simplified-angle, angle, base-line,\n"
     "extended-base-line",
     {0, 0, 0}},
    {OPT_RULE, "rule", CLI_ARG_REQUIRED, "NAME", "midpoint|knot-average|chaikin",
     "adaptive: midpoint (default, R = 0.5),\nknot-average, chaikin", {0, 0, 0}},
    {OPT_STOP, "stop", CLI_ARG_REQUIRED, "NAME", "movement|threshold|budget",
     "adaptive: movement (default), threshold, budget", {0, 0, 0}},
    {OPT_KNOT_BUDGET, "knot-budget", CLI_ARG_REQUIRED, "K", NULL,
     "adaptive: knots inserted at most (default %.0f)",
     {(double)CONICA_PLOT_DEFAULT_KNOT_BUDGET, 0, 0}},
    {OPT_CURVE_POINTS, "curve-points", CLI_ARG_NONE, NULL, NULL,
     "adaptive: emit curve points at the knot averages\n"
     "instead of the refined control polygon",
     {0, 0, 0}},
    {OPT_PREPHASE, "prephase", CLI_ARG_REQUIRED, "K", NULL,
     "adaptive: insert K uniform knots before the loop", {0, 0, 0}},
    {OPT_LOCAL_WEIGHT, "local-weight", CLI_ARG_REQUIRED, "W", "length|angle|both",
     "local-uniform: share points by control polygon\n"
     "length, angle or both (default, omega = 0.5)",
     {0, 0, 0}},
    {OPT_ANGLE, "angle", CLI_ARG_REQUIRED, "DEG", NULL,
     "mathematica: angle threshold (default 5)", {0, 0, 0}},
    {OPT_MAX_RECURSION, "max-recursion", CLI_ARG_REQUIRED, "N", NULL,
     "mathematica: recursion depth (default 6)", {0, 0, 0}},
    {OPT_ABS_TOLERANCE, "abs-tolerance", CLI_ARG_REQUIRED, "E", NULL, "tolerance in curve units",
     {0, 0, 0}},
    {OPT_TOLERANCE, "tolerance", CLI_ARG_REQUIRED, "PX", NULL,
     "tolerance in pixels (default %g) for the viewport,\n"
     "eps = PX / diagonal * (control point box diagonal)",
     {CONICA_PLOT_DEFAULT_PIXEL_TOLERANCE, 0, 0}},
    {OPT_VIEWPORT, "viewport", CLI_ARG_REQUIRED, "WxH", NULL,
     "viewport in pixels (default 1000x1000)", {0, 0, 0}},
    {OPT_POINTS, "points", CLI_ARG_REQUIRED, "N", NULL,
     "uniform / local-uniform / chaikin / lane-riesenfeld:\n"
     "number of points (default %.0f); mathematica:\n"
     "initial points (default 50)",
     {(double)CONICA_PLOT_DEFAULT_UNIFORM_POINTS, 0, 0}},
    {OPT_STATS, "stats", CLI_ARG_NONE, NULL, NULL,
     "print `plot: <points> points, <K> knots inserted,\n"
     "<ops> flops, <S> s` on stderr",
     {0, 0, 0}},
    {'o', "output", CLI_ARG_REQUIRED, "OUT", "file",
     "write to OUT (`-` = stdout) via a temporary file", {0, 0, 0}},
    {OPT_MAX_POINTS, "max-points", CLI_ARG_REQUIRED, "N", NULL,
     "limit: refuse outputs of more than N points\n(default %.0f)",
     {(double)CONICA_PLOT_MAX_POINTS_DEFAULT, 0, 0}},
    {OPT_MAX_KNOTS, "max-knots", CLI_ARG_REQUIRED, "N", NULL,
     "limit: refuse to insert more than N knots, in all\n"
     "(default %.0f); --knot-budget and --prephase must\n"
     "not exceed it",
     {(double)CONICA_PLOT_MAX_KNOTS_DEFAULT, 0, 0}},
    {OPT_MAX_ITERATIONS, "max-iterations", CLI_ARG_REQUIRED, "N", NULL,
     "limit: refuse to run more than N plotter\n"
     "iterations / trial steps (default %.0f)",
     {(double)CONICA_PLOT_MAX_ITERATIONS_DEFAULT, 0, 0}},
    {OPT_MAX_CTRL, "max-control-points", CLI_ARG_REQUIRED, "N", NULL,
     "limit: refuse input splines with more than N\n"
     "control points (default and maximum %.0f)",
     {(double)CONICA_BSPLINE_MAX_CTRL, 0, 0}},
    {OPT_MAX_DEGREE, "max-degree", CLI_ARG_REQUIRED, "N", NULL,
     "limit: refuse input splines of degree above N\n(default and maximum %.0f)",
     {CONICA_BSPLINE_MAX_DEGREE, 0, 0}},
    {OPT_ENTITY, "entity", CLI_ARG_REQUIRED, "HANDLE", NULL,
     "DXF: the SPLINE with this handle (default: the\nonly one)", {0, 0, 0}},
    {0, NULL, 0, NULL, NULL, NULL, {0, 0, 0}},
};

static const cli_tool tool = {
    USAGE_PROG,
    "[OPTION]... IN.spl | IN.dxf",
    "Plot a B-spline function or curve (optionally rational) as a polyline\n"
    "(after T. Dahl, \"Adaptive plotting of splines\", Oslo 2019).\n"
    "\n"
    "Input: `degree P`, `knots ...`, one `c x [y [z]]` line per control point,\n"
    "optional `w ...` weights; `#` starts a comment. IN of `-`: stdin. Or an\n"
    "ASCII DXF drawing (.dxf): one SPLINE of its model space, in drawing units.\n"
    "Output: one `x y` line per vertex (`t f(t)` for a spline function, `x y z`\n"
    "for a 3-D curve); a blank line separates pieces split at discontinuities.\n",
    opts,
    "A limit that is hit fails the run with exit 1 and a message naming the\n"
    "flag; nothing is written. The input file size is capped by the environment\n"
    "variable CONICA_MAX_INPUT_BYTES (default 268435456 bytes).\n"
    "\n"
    "Exit status: 0 success, 1 error (bad input, I/O; nothing is written),\n"
    "2 usage error.\n",
    "file",
    0,
    NULL,
};

typedef struct options {
    conica_plot_settings set;
    conica_bspline_parse_limits read; /* caps of the .spl reader */
    int stats, have_abs, have_px, have_points, have_budget;
    const char *in, *out;
    const char *entity; /* DXF: the handle of the SPLINE to plot */
} options;

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

/* A value that must be one of names (NULL-terminated); its index or -1. */
static int word_index(const char *v, const char *const *names)
{
    for (int k = 0; names[k]; k++)
        if (strcmp(v, names[k]) == 0)
            return k;
    return -1;
}

/* One option's value into *o; returns -1 to go on, or an exit status. */
static int take_option(cli_parser *p, int c, void *ctx)
{
    options *o = ctx;
    static const char *const stops[] = {"movement", "threshold", "budget", NULL};
    static const conica_plot_stop stop_values[] = {CONICA_STOP_MOVEMENT, CONICA_STOP_THRESHOLD,
                                                   CONICA_STOP_BUDGET};
    static const char *const weights[] = {"length", "angle", "both", NULL};
    static const conica_plot_local_weight weight_values[] = {CONICA_LOCAL_LENGTH, CONICA_LOCAL_ANGLE,
                                                         CONICA_LOCAL_BOTH};
    const char *v = p->arg;
    long num;
    double x;
    int k;
    switch (c) {
    case OPT_STATS: o->stats = 1; break;
    case OPT_CURVE_POINTS: o->set.output = CONICA_OUTPUT_CURVE_POINTS; break;
    case OPT_METHOD:
        if ((k = conica_plot_method_from_name(v)) < 0)
            return cli_opt_bad(p, "takes a method named in --help, not '%s'", v);
        o->set.method = (conica_plot_method)k;
        break;
    case OPT_CRITERION:
        if ((k = conica_plot_criterion_from_name(v)) < 0)
            return cli_opt_bad(p, "takes a criterion named in --help, not '%s'", v);
        o->set.criterion = (conica_plot_criterion)k;
        break;
    case OPT_RULE:
        if ((k = conica_plot_rule_from_name(v)) < 0)
            return cli_opt_bad(p, "takes a rule named in --help, not '%s'", v);
        o->set.rule = (conica_plot_rule)k;
        break;
    case OPT_STOP:
        if ((k = word_index(v, stops)) < 0)
            return cli_opt_bad(p, "takes movement, threshold or budget, not '%s'", v);
        o->set.stop = stop_values[k];
        break;
    case OPT_KNOT_BUDGET:
    case OPT_PREPHASE:
        if (cli_parse_int(v, 0, LONG_MAX, &num))
            return cli_opt_bad(p, "needs a whole number of knots, not '%s'", v);
        if (c == OPT_KNOT_BUDGET) {
            o->set.knot_budget = (size_t)num;
            o->have_budget = 1;
        } else {
            o->set.prephase_knots = (size_t)num;
        }
        break;
    case OPT_LOCAL_WEIGHT:
        if ((k = word_index(v, weights)) < 0)
            return cli_opt_bad(p, "takes length, angle or both, not '%s'", v);
        o->set.local_weight = weight_values[k];
        break;
    case OPT_ANGLE:
        if (cli_parse_double(v, &x) || !(x > 0 && x < 180))
            return cli_opt_bad(p, "needs degrees in (0, 180), not '%s'", v);
        o->set.math_angle = x * 3.14159265358979323846 / 180.0;
        break;
    case OPT_MAX_RECURSION:
        if (cli_parse_int(v, 0, 60, &num))
            return cli_opt_bad(p, "needs an integer in 0..60, not '%s'", v);
        o->set.math_max_recursion = (size_t)num;
        break;
    case OPT_ABS_TOLERANCE:
    case OPT_TOLERANCE:
        if (cli_parse_double(v, &x) || !(x > 0))
            return cli_opt_bad(p, "needs a positive number, not '%s'", v);
        if (c == OPT_ABS_TOLERANCE) {
            o->set.abs_tolerance = x;
            o->have_abs = 1;
        } else {
            o->set.pixel_tolerance = x;
            o->have_px = 1;
        }
        break;
    case OPT_VIEWPORT:
        if (parse_viewport(v, &o->set.viewport_w, &o->set.viewport_h))
            return cli_opt_bad(p, "needs WxH with positive numbers, e.g. 1000x800, not '%s'", v);
        break;
    case OPT_POINTS:
    case OPT_MAX_POINTS:
        if (cli_parse_int(v, 2, LONG_MAX, &num))
            return cli_opt_bad(p, "needs an integer >= 2, not '%s'", v);
        if (c == OPT_POINTS) {
            o->set.points = (size_t)num;
            o->have_points = 1;
        } else {
            o->set.max_points = (size_t)num;
        }
        break;
    case OPT_MAX_KNOTS:
        if (cli_parse_int(v, 0, LONG_MAX, &num))
            return cli_opt_bad(p, "needs an integer >= 0, not '%s'", v);
        o->set.max_knots = (size_t)num;
        break;
    case OPT_MAX_ITERATIONS:
        if (cli_parse_int(v, 1, LONG_MAX, &num))
            return cli_opt_bad(p, "needs an integer >= 1, not '%s'", v);
        o->set.max_iterations = (size_t)num;
        break;
    case OPT_MAX_CTRL:
        if (cli_parse_int(v, 1, (long)CONICA_BSPLINE_MAX_CTRL, &num))
            return cli_opt_bad(p, "needs an integer in 1..%zu, not '%s'",
                               (size_t)CONICA_BSPLINE_MAX_CTRL, v);
        o->read.max_ctrl = (size_t)num;
        break;
    case OPT_MAX_DEGREE:
        if (cli_parse_int(v, 1, CONICA_BSPLINE_MAX_DEGREE, &num))
            return cli_opt_bad(p, "needs an integer in 1..%d, not '%s'", CONICA_BSPLINE_MAX_DEGREE,
                               v);
        o->read.max_degree = (int)num;
        break;
    case 'o':
        o->out = v;
        break;
    case OPT_ENTITY:
        if (!*v)
            return cli_opt_bad(p, "needs the handle of a DXF SPLINE (group 5)");
        o->entity = v;
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
    o->set = conica_plot_defaults();
    o->read = conica_bspline_parse_limits_defaults();
    o->stats = o->have_abs = o->have_px = o->have_points = o->have_budget = 0;
    o->in = o->out = o->entity = NULL;
    if ((rc = cli_opt_parse(&tool, argc, argv, take_option, o, &first)) >= 0)
        return rc;
    if ((rc = cli_opt_one_operand(&tool, argc, argv, first, 1, &o->in)) >= 0)
        return rc;
    NEED(!(o->have_abs && o->have_px), "give --abs-tolerance or --tolerance, not both");
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
    /* a DXF drawing: one SPLINE of its model space, in drawing units */
    int dxf = cli_ends_with_ci(o.in, ".dxf") || conica_dxf_sniff(buf, len);
    conica_code code;
    if (dxf) {
        conica_dxf_limits dl = conica_dxf_limits_defaults();
        dl.max_vertices = o.read.max_ctrl < dl.max_vertices ? o.read.max_ctrl : dl.max_vertices;
        code = conica_dxf_spline(buf, len, o.entity, &dl, &s, NULL, &st);
        if (code == CONICA_OK && s.degree > o.read.max_degree) {
            snprintf(st.message, sizeof st.message,
                     "degree %d exceeds %d (max_degree); raise the cap with --max-degree N",
                     s.degree, o.read.max_degree);
            st.code = code = CONICA_ERR_LIMIT;
            conica_bspline_free(&s);
        }
    } else if (o.entity) {
        free(buf);
        return cli_usage_error(USAGE_PROG, "--entity names a SPLINE of a DXF input");
    } else {
        code = conica_bspline_parse_ex(buf, len, &o.read, &s, &st);
    }
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

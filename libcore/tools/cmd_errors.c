/* SPDX-License-Identifier: MIT */
/* `conica errors`: per subdivision level k = 0..MAX, the conic error of seed
 * 000 (eqs. (13)-(14): mean and max of |f|/|grad f| over the vertices, when
 * the input is sampled from one conic) and the normal angle error (scheme
 * normals vs normals estimated from the points, Section 3.2, Figures 3-5);
 * a table on stdout and optionally a log-scale SVG plot. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_opt.h"
#include "conica/curve.h"
#include "conica/subdiv.h"
#include "plotsvg.h"

#define ERRORS_DEFAULT_MAX 8
/* Levels beyond this measure nothing new and cost 2^k points per curve
 * point; the output budget of the subdivision caps the size as well. */
#define ERRORS_MAX_LEVEL 20

static const char *const prog = "conica";

enum { OPT_CONIC = CLI_OPT_LONG, OPT_VARIANT, OPT_OPEN, OPT_CLOSED, OPT_PLOT };

static const cli_opt opts[] = {
    {'k', "levels", CLI_ARG_REQUIRED, "MAX", NULL,
     "the last level measured (default %.0f, at most %.0f)",
     {ERRORS_DEFAULT_MAX, ERRORS_MAX_LEVEL, 0}},
    {OPT_CONIC, "conic", CLI_ARG_REQUIRED, "Q20,Q02,Q11,Q10,Q01,Q00", NULL,
     "the conic of eq. (3), coefficients in its order:\n"
     "f = Q20 x^2 + Q02 y^2 + 2 Q11 xy + 2 Q10 x\n"
     "    + 2 Q01 y + Q00\n"
     "(circle x^2+y^2=25: --conic 1,1,0,0,0,-25)",
     {0, 0, 0}},
    {OPT_VARIANT, "variant", CLI_ARG_REQUIRED, "V", "base|norm-skip|final|precise",
     "numerics of the CONIS paper, Sec. 3.2: base\n"
     "(normals normalised each level, plain quadratic\n"
     "formula), norm-skip, final (default), precise\n"
     "(long double)",
     {0, 0, 0}},
    {OPT_OPEN, "open", CLI_ARG_NONE, NULL, NULL, "the curve is open", {0, 0, 0}},
    {OPT_CLOSED, "closed", CLI_ARG_NONE, NULL, NULL, "the curve is closed (default)", {0, 0, 0}},
    {OPT_PLOT, "plot", CLI_ARG_REQUIRED, "OUT.svg", "file",
     "also draw the table as an SVG chart (log-scale y)", {0, 0, 0}},
    {0, NULL, 0, NULL, NULL, NULL, {0, 0, 0}},
};

static const cli_tool tool = {
    "conica errors",
    "[OPTION]... IN",
    "For every level k = 0..MAX, subdivide IN ('-' = stdin) and print n_k, the\n"
    "conic error E, E_max (CONIS paper, eqs. (13)-(14), with --conic) and the\n"
    "mean / max angle in degrees between the scheme's normals and normals\n"
    "estimated from the points.\n",
    opts,
    "Exit status: 0 success, 1 error (nothing is printed), 2 usage error.\n",
    "file",
    0,
    NULL,
};

/* Six comma-separated numbers, no locale. */
static int parse_conic(const char *s, plotsvg_conic *q)
{
    double v[6];
    char buf[64];
    for (int i = 0; i < 6; i++) {
        size_t len = strcspn(s, ",");
        if (len == 0 || len >= sizeof buf)
            return 1;
        memcpy(buf, s, len);
        buf[len] = '\0';
        if (cli_parse_double(buf, &v[i]))
            return 1;
        s += len;
        if (i < 5) {
            if (*s != ',')
                return 1;
            s++;
        }
    }
    if (*s)
        return 1;
    q->q20 = v[0];
    q->q02 = v[1];
    q->q11 = v[2];
    q->q10 = v[3];
    q->q01 = v[4];
    q->q00 = v[5];
    return 0;
}

static int write_plot(const char *path, const char *in_path, const char *variant, int have_conic,
                      const plotsvg_errors *e, int n)
{
    cli_output o;
    double x[ERRORS_MAX_LEVEL + 1], em[ERRORS_MAX_LEVEL + 1], ex[ERRORS_MAX_LEVEL + 1];
    double nm[ERRORS_MAX_LEVEL + 1], nx[ERRORS_MAX_LEVEL + 1];
    double w = 760.0, h = have_conic ? 760.0 : 380.0, y = 0.0;
    char title[300];
    for (int k = 0; k < n; k++) {
        x[k] = k;
        em[k] = e[k].e_mean;
        ex[k] = e[k].e_max;
        nm[k] = e[k].n_mean;
        nx[k] = e[k].n_max;
    }
    if (cli_output_open(prog, path, &o))
        return 1;
    snprintf(title, sizeof title, "%s (%s)", in_path, variant);
    plotsvg_begin(o.f, w, h, title);
    if (have_conic) {
        plotsvg_series s[2] = {
            {"E (mean)", x, em, (size_t)n, "#1f77b4", 0},
            {"E_max", x, ex, (size_t)n, "#d62728", 1},
        };
        snprintf(title, sizeof title, "conic error, %s (%s)", in_path, variant);
        plotsvg_logchart(o.f, 0.0, y, w, 380.0, title, "subdivision level k", "|f| / |grad f|",
                         s, 2);
        y += 380.0;
    }
    {
        plotsvg_series s[2] = {
            {"mean", x, nm, (size_t)n, "#2ca02c", 0},
            {"max", x, nx, (size_t)n, "#9467bd", 1},
        };
        snprintf(title, sizeof title, "normal angle error, %s (%s)", in_path, variant);
        plotsvg_logchart(o.f, 0.0, y, w, 380.0, title, "subdivision level k", "degrees", s, 2);
    }
    plotsvg_end(o.f);
    if (cli_output_commit(prog, &o)) {
        cli_output_abort(&o);
        return 1;
    }
    return 0;
}

/* What the options set. */
typedef struct errors_opts {
    long kmax;
    int closed, have_conic;
    const char *plot_path, *variant;
    plotsvg_conic q;
    conica_subdiv_settings set;
} errors_opts;

/* One option's value into *o; returns -1 to go on, or an exit status. */
static int take_option(cli_parser *p, int c, void *ctx)
{
    errors_opts *o = ctx;
    const char *v = p->arg;
    switch (c) {
    case OPT_OPEN: o->closed = 0; break;
    case OPT_CLOSED: o->closed = 1; break;
    case 'k':
        if (cli_parse_int(v, 0, ERRORS_MAX_LEVEL, &o->kmax))
            return cli_opt_bad(p, "wants an integer 0..%d, got '%s'", ERRORS_MAX_LEVEL, v);
        break;
    case OPT_CONIC:
        if (parse_conic(v, &o->q))
            return cli_opt_bad(p, "wants six numbers Q20,Q02,Q11,Q10,Q01,Q00, got '%s'", v);
        /* the error of eq. (13) divides by the gradient: with only Q00
         * left the gradient is 0 everywhere and there is no curve */
        if (o->q.q20 == 0 && o->q.q02 == 0 && o->q.q11 == 0 && o->q.q10 == 0 && o->q.q01 == 0)
            return cli_opt_bad(p, "'%s' is not a curve: Q20, Q02, Q11, Q10 and Q01 are all zero",
                               v);
        o->have_conic = 1;
        break;
    case OPT_VARIANT:
        o->variant = v;
        if (plotsvg_variant(v, &o->set))
            return cli_opt_bad(p, "wants base, norm-skip, final or precise, got '%s'", v);
        break;
    case OPT_PLOT:
        o->plot_path = v;
        break;
    default:
        return cli_opt_bad(p, "is not handled"); /* a table entry without a case */
    }
    return -1;
}

extern const char conica_cmd_errors_summary[];
const char conica_cmd_errors_summary[] = "conic error and normal error per subdivision level, as a table";
int conica_cmd_errors(int argc, char **argv);
int conica_cmd_errors(int argc, char **argv)
{
    errors_opts a = {ERRORS_DEFAULT_MAX, 1, 0, NULL, "final", {0, 0, 0, 0, 0, 0},
                     conica_subdiv_defaults()};
    int first, rc = cli_opt_parse(&tool, argc, argv, take_option, &a, &first);
    if (rc >= 0)
        return rc;
    const char *in_path;
    if ((rc = cli_opt_one_operand(&tool, argc, argv, first, 1, &in_path)) >= 0)
        return rc;
    long kmax = a.kmax;
    int closed = a.closed, have_conic = a.have_conic;
    const char *plot_path = a.plot_path, *variant = a.variant;
    plotsvg_conic q = a.q;
    plotsvg_errors e[ERRORS_MAX_LEVEL + 1];
    conica_curve in;
    conica_subdiv_settings set = a.set;
    conica_status st;

    rc = CLI_EXIT_ERROR;

    conica_curve_init(&in);
    if (plotsvg_load_curve(prog, in_path, closed, &in))
        goto done;
    /* Measure every level before printing, so a failure prints no table. */
    for (int k = 0; k <= kmax; k++) {
        set.levels = k;
        if (plotsvg_measure(&in, &set, have_conic ? &q : NULL, &e[k], &st) != CONICA_OK) {
            cli_error(prog, in_path, "subdivision to level %d failed: %s", k, st.message);
            goto done;
        }
        if (have_conic && (!isfinite(e[k].e_mean) || !isfinite(e[k].e_max))) {
            /* a point where the conic's gradient vanishes (its centre when
             * it degenerates to a point, a line pair's crossing) */
            cli_error(prog, in_path,
                      "the conic error at level %d is not finite: the gradient of the conic "
                      "vanishes at a point of the curve (a degenerate conic?)", k);
            goto done;
        }
    }
    printf("# conica errors %s, variant %s", in_path, variant);
    if (have_conic)
        printf(", conic (q20,q02,q11,q10,q01,q00) = (%.17g, %.17g, %.17g, %.17g, %.17g, %.17g)",
               q.q20, q.q02, q.q11, q.q10, q.q01, q.q00);
    printf("\n#  k    points         E_mean          E_max  normal_mean_deg  normal_max_deg\n");
    for (int k = 0; k <= kmax; k++) {
        printf("%4d %9zu ", k, e[k].points);
        if (have_conic)
            printf("%14.3e %14.3e ", e[k].e_mean, e[k].e_max);
        else
            printf("%14s %14s ", "-", "-");
        printf("%16.3e %15.3e\n", e[k].n_mean, e[k].n_max);
    }
    if (fflush(stdout) != 0) {
        cli_error(prog, "<stdout>", "write error: %s", strerror(errno ? errno : EIO));
        goto done;
    }
    if (plot_path && write_plot(plot_path, in_path, variant, have_conic, e, (int)kmax + 1))
        goto done;
    rc = CLI_EXIT_OK;
done:
    conica_curve_free(&in);
    return rc;
}

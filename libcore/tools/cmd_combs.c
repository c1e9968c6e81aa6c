/* SPDX-License-Identifier: MIT */
/* `conica combs`: an SVG of a curve's curvature comb (CONIS §2.2):
 * the control polygon dashed, the subdivided curve, and at every vertex a
 * tooth along the unit normal of length S * kappa, kappa from the circle
 * through the vertex and its two neighbours (Code 3, in double), the tooth
 * tips joined into the comb outline. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_opt.h"
#include "conica/curve.h"
#include "conica/subdiv.h"
#include "plotsvg.h"

#define COMBS_DEFAULT_LEVELS 5
#define COMBS_DEFAULT_WIDTH 900.0
#define COMBS_MAX_WIDTH 20000.0

static const char *const prog = "conica";

enum { OPT_SCALE = CLI_OPT_LONG, OPT_OPEN, OPT_CLOSED, OPT_SIGNED, OPT_MAX_TEETH, OPT_WIDTH,
       OPT_STATS };

static const cli_opt opts[] = {
    {'k', "levels", CLI_ARG_REQUIRED, "K", NULL, "subdivision levels (default %.0f, max %.0f)",
     {COMBS_DEFAULT_LEVELS, CONICA_SUBDIV_MAX_LEVELS, 0}},
    {OPT_SCALE, "scale", CLI_ARG_REQUIRED, "S", NULL,
     "tooth length per unit curvature (default: the\n"
     "largest tooth is %.0f%% of the curve's size, not\n"
     "counting the top 2%% of teeth, which are cut at\n"
     "twice that length)",
     {PLOTSVG_COMB_FRACTION * 100.0, 0, 0}},
    {OPT_OPEN, "open", CLI_ARG_NONE, NULL, NULL, "the curve is open", {0, 0, 0}},
    {OPT_CLOSED, "closed", CLI_ARG_NONE, NULL, NULL, "the curve is closed (default)", {0, 0, 0}},
    {OPT_SIGNED, "signed", CLI_ARG_NONE, NULL, NULL,
     "flip teeth to the other side where the curve\n"
     "bends towards its normal (shows inflections);\n"
     "default: unsigned 1/R",
     {0, 0, 0}},
    {OPT_MAX_TEETH, "max-teeth", CLI_ARG_REQUIRED, "N", NULL,
     "draw at most N teeth (default %.0f; every vertex\n"
     "still shapes the comb outline)",
     {PLOTSVG_DEFAULT_MAX_TEETH, 0, 0}},
    {OPT_WIDTH, "width", CLI_ARG_REQUIRED, "PX", NULL, "picture width, 100..%.0f (default %.0f)",
     {COMBS_MAX_WIDTH, COMBS_DEFAULT_WIDTH, 0}},
    {OPT_STATS, "stats", CLI_ARG_NONE, NULL, NULL,
     "print points, curvature range and scale to stderr", {0, 0, 0}},
    {'o', "output", CLI_ARG_REQUIRED, "OUT.svg", "file",
     "output file (default stdout); written atomically", {0, 0, 0}},
    {0, NULL, 0, NULL, NULL, NULL, {0, 0, 0}},
};

static const cli_tool tool = {
    "conica combs",
    "[OPTION]... IN",
    "Subdivide the point-normal curve IN (`v x y` / `vn nx ny` lines, '-' = stdin)\n"
    "and draw its curvature comb as SVG: control polygon dashed, subdivided curve,\n"
    "a tooth of length S*kappa along the unit normal at every vertex (kappa from\n"
    "the circle through three consecutive points, the CONIS paper's Code 3), tips\n"
    "joined.\n",
    opts,
    "Exit status: 0 success, 1 error (nothing is written), 2 usage error.\n",
    "file",
    0,
    NULL,
};

typedef struct combs_opts {
    long levels, max_teeth;
    double scale, width;
    int closed, signed_comb, stats;
    const char *in_path, *out_path;
} combs_opts;

/* One option's value into *o; returns -1 to go on, or an exit status. */
static int take_option(cli_parser *p, int c, void *ctx)
{
    combs_opts *o = ctx;
    const char *v = p->arg;
    switch (c) {
    case OPT_OPEN: o->closed = 0; break;
    case OPT_CLOSED: o->closed = 1; break;
    case OPT_SIGNED: o->signed_comb = 1; break;
    case OPT_STATS: o->stats = 1; break;
    case 'k':
        if (cli_parse_int(v, 0, CONICA_SUBDIV_MAX_LEVELS, &o->levels))
            return cli_opt_bad(p, "wants an integer 0..%d, got '%s'", CONICA_SUBDIV_MAX_LEVELS, v);
        break;
    case OPT_SCALE:
        if (cli_parse_double(v, &o->scale) || !(o->scale > 0.0))
            return cli_opt_bad(p, "wants a positive number, got '%s'", v);
        break;
    case OPT_MAX_TEETH:
        if (cli_parse_int(v, 0, PLOTSVG_MAX_TEETH_LIMIT, &o->max_teeth))
            return cli_opt_bad(p, "wants an integer 0..%d, got '%s'", PLOTSVG_MAX_TEETH_LIMIT, v);
        break;
    case OPT_WIDTH:
        if (cli_parse_double(v, &o->width) || !(o->width >= 100.0) || o->width > COMBS_MAX_WIDTH)
            return cli_opt_bad(p, "wants 100..%.0f px, got '%s'", COMBS_MAX_WIDTH, v);
        break;
    case 'o':
        o->out_path = v;
        break;
    default:
        return cli_opt_bad(p, "is not handled"); /* a table entry without a case */
    }
    return -1;
}

/* Returns -1 to go on, or an exit status. */
static int parse_args(int argc, char **argv, combs_opts *o)
{
    int first, rc;
    if ((rc = cli_opt_parse(&tool, argc, argv, take_option, o, &first)) >= 0)
        return rc;
    return cli_opt_one_operand(&tool, argc, argv, first, 1, &o->in_path);
}

extern const char conica_cmd_combs_summary[];
const char conica_cmd_combs_summary[] = "curvature comb of a point-normal curve, as SVG";
int conica_cmd_combs(int argc, char **argv);
int conica_cmd_combs(int argc, char **argv)
{
    combs_opts a = {COMBS_DEFAULT_LEVELS, PLOTSVG_DEFAULT_MAX_TEETH, 0.0, COMBS_DEFAULT_WIDTH,
                    1, 0, 0, NULL, NULL};
    int rc = parse_args(argc, argv, &a);
    conica_curve in, out;
    conica_subdiv_settings set = conica_subdiv_defaults();
    conica_status st;
    double *kappa = NULL, *tips = NULL;
    cli_output o = {0};
    long levels = a.levels, max_teeth = a.max_teeth;
    double scale = a.scale, width = a.width;
    int closed = a.closed, signed_comb = a.signed_comb, stats = a.stats;
    const char *in_path = a.in_path, *out_path = a.out_path;

    if (rc >= 0)
        return rc;
    rc = CLI_EXIT_ERROR;
    conica_curve_init(&in);
    conica_curve_init(&out);
    if (plotsvg_load_curve(prog, in_path, closed, &in))
        goto done;
    set.levels = (int)levels;
    if (conica_subdivide(&in, &set, &out, NULL, &st) != CONICA_OK) {
        cli_error(prog, in_path, "subdivision failed: %s", st.message);
        goto done;
    }
    kappa = malloc(out.n * sizeof *kappa);
    tips = malloc(2 * out.n * sizeof *tips);
    if (!kappa || !tips || !out.nxy) {
        cli_error(prog, in_path, out.nxy ? "out of memory" : "subdivision gave no normals");
        goto done;
    }
    {
        double kmax = plotsvg_curvatures(out.xy, out.nxy, out.n, out.closed, signed_comb, kappa);
        double size = plotsvg_size(out.xy, out.n), box[4], height, max_len = 0.0;
        char title[160];
        if (scale <= 0.0) /* tips is scratch space until the tips are made */
            scale = plotsvg_comb_scale(kappa, out.n, size, tips, &max_len);
        plotsvg_comb_tips(out.xy, out.nxy, kappa, out.n, scale, max_len, tips);
        plotsvg_box_empty(box);
        plotsvg_box_add(box, in.xy, in.n);
        plotsvg_box_add(box, out.xy, out.n);
        plotsvg_box_add(box, tips, out.n);
        /* picture height from the drawing's aspect, within sane bounds */
        height = box[2] > box[0] ? width * (box[3] - box[1]) / (box[2] - box[0]) : width;
        height = fmin(fmax(height, 0.25 * width), 2.0 * width) + 40.0;
        snprintf(title, sizeof title, "curvature comb, k = %ld, %zu points", levels, out.n);
        if (cli_output_open(prog, out_path, &o))
            goto done;
        plotsvg_begin(o.f, width, height, title);
        plotsvg_comb_panel(o.f, 0.0, 0.0, width, height, &in, &out, tips, (size_t)max_teeth,
                           title);
        plotsvg_end(o.f);
        if (cli_output_commit(prog, &o)) {
            cli_output_abort(&o);
            goto done;
        }
        if (stats)
            fprintf(stderr, "combs: %zu points, max curvature %.6g, scale %.6g, curve size %.6g\n",
                    out.n, kmax, scale, size);
    }
    rc = CLI_EXIT_OK;
done:
    free(kappa);
    free(tips);
    conica_curve_free(&in);
    conica_curve_free(&out);
    return rc;
}

/* SPDX-License-Identifier: MIT */
/* `conica combs`: an SVG of a curve's curvature comb (seed 000, Section 2.2):
 * the control polygon dashed, the subdivided curve, and at every vertex a
 * tooth along the unit normal of length S * kappa, kappa from the circle
 * through the vertex and its two neighbours (Code 3, in double), the tooth
 * tips joined into the comb outline. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "conica/curve.h"
#include "conica/subdiv.h"
#include "plotsvg.h"

#define COMBS_DEFAULT_LEVELS 5
#define COMBS_DEFAULT_WIDTH 900.0
#define COMBS_MAX_WIDTH 20000.0

static const char *const prog = "conica";
static const char *const usage_prog = "conica combs";

static void usage(FILE *f)
{
    fprintf(f,
            "usage: conica combs [-k LEVELS] [--scale S] [--open|--closed] [--signed]\n"
            "                    [--max-teeth N] [--width PX] [--stats] [-o OUT.svg] IN\n"
            "\n"
            "Subdivide the point-normal curve IN (`v x y` / `vn nx ny` lines, '-' = stdin)\n"
            "and draw its curvature comb as SVG: control polygon dashed, subdivided curve,\n"
            "a tooth of length S*kappa along the unit normal at every vertex (kappa from\n"
            "the circle through three consecutive points, the CONIS paper's Code 3), tips\n"
            "joined.\n"
            "\n"
            "  -k LEVELS      subdivision levels (default %d, max %d)\n"
            "  --scale S      tooth length per unit curvature (default: the largest tooth\n"
            "                 is %.0f%% of the curve's size, not counting the top 2%% of\n"
            "                 teeth, which are cut at twice that length)\n"
            "  --open         the curve is open; --closed (default) joins last to first\n"
            "  --signed       flip teeth to the other side where the curve bends towards\n"
            "                 its normal (shows inflections); default: unsigned 1/R\n"
            "  --max-teeth N  draw at most N teeth (default %d; every vertex still shapes\n"
            "                 the comb outline)\n"
            "  --width PX     picture width (default %.0f)\n"
            "  --stats        print points, curvature range and scale to stderr\n"
            "  -o OUT.svg     output file (default stdout); written atomically\n",
            COMBS_DEFAULT_LEVELS, CONICA_SUBDIV_MAX_LEVELS, PLOTSVG_COMB_FRACTION * 100.0,
            PLOTSVG_DEFAULT_MAX_TEETH, COMBS_DEFAULT_WIDTH);
}

extern const char conica_cmd_combs_summary[];
const char conica_cmd_combs_summary[] = "curvature comb of a point-normal curve, as SVG";
int conica_cmd_combs(int argc, char **argv);
int conica_cmd_combs(int argc, char **argv)
{
    long levels = COMBS_DEFAULT_LEVELS, max_teeth = PLOTSVG_DEFAULT_MAX_TEETH;
    double scale = 0.0, width = COMBS_DEFAULT_WIDTH;
    int closed = 1, signed_comb = 0, stats = 0, rc = CLI_EXIT_ERROR;
    const char *in_path = NULL, *out_path = NULL;
    conica_curve in, out;
    conica_subdiv_settings set = conica_subdiv_defaults();
    conica_status st;
    double *kappa = NULL, *tips = NULL;
    cli_output o = {0};

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int has_next = i + 1 < argc;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return CLI_EXIT_OK;
        } else if (!strcmp(a, "-k") && has_next) {
            if (cli_parse_int(argv[++i], 0, CONICA_SUBDIV_MAX_LEVELS, &levels))
                return cli_usage_error(usage_prog, "-k wants an integer 0..%d, got '%s'",
                                       CONICA_SUBDIV_MAX_LEVELS, argv[i]);
        } else if (!strcmp(a, "--scale") && has_next) {
            if (cli_parse_double(argv[++i], &scale) || !(scale > 0.0))
                return cli_usage_error(usage_prog, "--scale wants a positive number, got '%s'",
                                       argv[i]);
        } else if (!strcmp(a, "--max-teeth") && has_next) {
            if (cli_parse_int(argv[++i], 0, PLOTSVG_MAX_TEETH_LIMIT, &max_teeth))
                return cli_usage_error(usage_prog, "--max-teeth wants an integer 0..%d, got '%s'",
                                       PLOTSVG_MAX_TEETH_LIMIT, argv[i]);
        } else if (!strcmp(a, "--width") && has_next) {
            if (cli_parse_double(argv[++i], &width) || !(width >= 100.0) ||
                width > COMBS_MAX_WIDTH)
                return cli_usage_error(usage_prog, "--width wants 100..%.0f px, got '%s'",
                                       COMBS_MAX_WIDTH, argv[i]);
        } else if (!strcmp(a, "-o") && has_next) {
            out_path = argv[++i];
            if (!*out_path)
                return cli_usage_error(usage_prog, "-o needs a file name");
        } else if (!strcmp(a, "--signed")) {
            signed_comb = 1;
        } else if (!strcmp(a, "--stats")) {
            stats = 1;
        } else if (plotsvg_common_arg(usage_prog, a, has_next, &closed, &in_path)) {
            return CLI_EXIT_USAGE;
        }
    }
    if (!in_path)
        return cli_usage_error(usage_prog, "no input file (a file name, or - for standard input)");

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

/* SPDX-License-Identifier: MIT */
/* scadprofile: smooth, exact 2D profiles as OpenSCAD modules.
 *
 *   scadprofile [OPTION]... [-o OUT.scad] IN     (options: the table below)
 *
 * IN is a point-normal file (`v`/`vn`, refined by conic subdivision), an SVG
 * document (every closed subpath of the selected elements) or a spline file
 * (.spl, through the adaptive plotter). The file it writes defines NAME(),
 * NAME_points(), NAME_paths(), NAME_bbox() and has no top-level geometry
 * unless asked (--demo-call, --extrude, --rotate-extrude). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "cli_batch.h"
#include "cli_opt.h"
#include "conica/curve.h"
#include "conica/dxf.h"
#include "conica/subdiv.h"
#include "conica_scad.h"
#include "conica_svg.h"
#include "conica_svg_render.h"
#include "scad_region.h"
#include "svg_cli.h"
#include "conica/bspline.h"
#include "conica/plot.h"

#define PROG "scadprofile"
/* Tolerance (output units) when neither --levels nor --tolerance is given. */
#define DEFAULT_TOLERANCE 0.01
/* Curves are made dense within this fraction of the tolerance, then thinned
 * to the fewest points within the rest (see README.md). */
#define DENSE_FRACTION (1.0 / 256.0)
/* A spline whose end points are closer than this fraction of its bounding
 * box diagonal is closed; otherwise a straight segment closes it. */
#define SPLINE_CLOSE_REL 1e-9

typedef enum kind { IN_POINTS, IN_SVG, IN_SPLINE, IN_DXF } kind;
typedef enum units { U_DEFAULT, U_PX, U_MM, U_IN } units;
/* --fit: the first three are conica_path_fit values (the SVG layer's
 * conica_svg_settings.fit); clearance runs inside and outside. */
typedef enum fit { FIT_INSIDE = 0, FIT_OUTSIDE = 1, FIT_MIDDLE = 2, FIT_CLEARANCE = 3 } fit;
static const char *const fit_names[4] = {"inside", "outside", "middle", "clearance"};
static const char *const fit_meaning[4] = {
    "the polygon lies within the painted region, within the tolerance of its edge",
    "the polygon contains the painted region, within the tolerance of its edge",
    "the polygon is within the tolerance of the painted region's edge both ways",
    "outlines inside, holes outside: the polygon within the painted region (as inside)",
};
/* --paint: what of each SVG element is material */
static const char *const paint_names[4] = {"as-drawn", "fill", "stroke", "both"};
static const char *const paint_meaning[4] = {
    "fills and strokes where the document paints them: what a browser shows",
    "the fill of every shape, painted or not; no strokes",
    "the stroke of every shape, painted or not (its stroke-width); no fills",
    "the fill and the stroke of every shape",
};

typedef struct options {
    int levels;          /* -1: not given */
    double tolerance;    /* 0: not given */
    const char *module;
    int module_given;
    fit fit;
    conica__paint paint;
    int demo_call;       /* -1: not given (--extrude / --rotate-extrude imply it), 0, 1 */
    units unit;
    int extrude, revolve;
    double height, angle;
    const char *select;
    int force, stats, flatten_only;
    int paint_given;
    size_t max_points;
    conica_svg_limits limits; /* SVG: XML caps; max_bytes also caps other inputs when given */
    int max_input_given;
    const char *out, *in;
    /* several inputs (-o DIR/): the input arguments, and which argv
     * entries they and -o's value are (each file's header records the
     * command that makes that file alone) */
    char **inputs;
    size_t ninputs;
    int out_arg;
    int jobs;           /* -j N, 0: not given */
    char **argv0;       /* the command line in the order typed */
    int out_attached;   /* -o's value is part of its argument (-oDIR/, --output=DIR/) */
    cli_progress_mode progress; /* -q, --progress */
    /* DXF: --layer (repeatable), --gap, --open; what the header says of
     * the drawing read (load_dxf, freed by profile_file) */
    const char **layers;
    size_t nlayers;
    double gap;
    int dxf_open;
    char *dxf_note;
} options;

typedef struct stats {
    const char *kind;
    size_t input_points, dense_points, points;
    size_t elements, subpaths;  /* SVG */
    size_t skipped;             /* contours without area (conica_scad_drop_empty) */
    size_t fills, strokes;      /* SVG: items whose fill / stroke became material */
    int levels;
    double seconds;
} stats;

enum {
    OPT_MODULE = CLI_OPT_LONG,
    OPT_FIT,
    OPT_PAINT,
    OPT_DEMO_CALL,
    OPT_NO_DEMO_CALL,
    OPT_UNITS,
    OPT_EXTRUDE,
    OPT_REVOLVE,
    OPT_SELECT,
    OPT_MAX_POINTS,
    OPT_MAX_INPUT,
    OPT_FLATTEN_ONLY,
    OPT_FORCE,
    OPT_STATS,
    OPT_PROGRESS,
    OPT_LAYER,
    OPT_GAP,
    OPT_DXF_OPEN,
    OPT_LIMITS, /* CONICA_SVG_CLI_LIMIT_COUNT ids from here */
};

static const cli_opt opts[] = {
    {'t', "tolerance", CLI_ARG_REQUIRED, "T", NULL,
     "largest distance between the polygon and the\n"
     "curve, in output units (default %g); fewest points\n"
     "that meet it. Numbers are written with the fewest\n"
     "digits that keep each point within T/1000 (inside\n"
     "T); the input's own numbers (corners, straight\n"
     "edges) stay exact when that is cheap",
     {DEFAULT_TOLERANCE, 0, 0}},
    {'k', "levels", CLI_ARG_REQUIRED, "K", NULL,
     "subdivide exactly K levels instead (0..%.0f); every\n"
     "point is kept and written exactly (round-trip\n"
     "decimals)",
     {CONICA_SUBDIV_MAX_LEVELS, 0, 0}},
    {OPT_FLATTEN_ONLY, "flatten-only", CLI_ARG_NONE, NULL, NULL,
     "keep the input geometry: only flatten curves (SVG,\n.spl)", {0, 0, 0}},
    {OPT_FIT, "fit", CLI_ARG_REQUIRED, "F", "inside|outside|middle|clearance",
     "which side of the painted region the polygon keeps\n"
     "to (SVG and DXF input; point-normal and spline\n"
     "input: inside only):\n"
     "  inside     within the painted region: the part\n"
     "             never larger than drawn, its holes\n"
     "             never smaller (default)\n"
     "  outside    contains the painted region: the\n"
     "             part never smaller, its holes never\n"
     "             larger\n"
     "  middle     within the tolerance both ways:\n"
     "             fewest points\n"
     "  clearance  outlines inside, holes outside (the\n"
     "             same polygon as inside)\n"
     "Corners, straight edges and their ends stay exact;\n"
     "the polygon is checked against the drawn region\n"
     "before it is written (exit 1 when it would lose or\n"
     "add material)",
     {0, 0, 0}},
    {OPT_PAINT, "paint", CLI_ARG_REQUIRED, "P", "as-drawn|fill|stroke|both",
     "SVG: what is material: as-drawn (default; fills\n"
     "and strokes as a browser shows them), fill (every\n"
     "shape filled), stroke (every shape stroked), both",
     {0, 0, 0}},
    {OPT_MODULE, "module", CLI_ARG_REQUIRED, "NAME", NULL,
     "module name (default: the input file's name made\n"
     "into an identifier, e.g. bracket-v2.svg ->\n"
     "bracket_v2, with a warning when it had to be\n"
     "changed; stdin: profile)",
     {0, 0, 0}},
    {OPT_UNITS, "units", CLI_ARG_REQUIRED, "U", "px|mm|in",
     "SVG and DXF: output units px, mm (default) or in;\n"
     "96 px per inch, the SVG's viewBox/width/height and\n"
     "the DXF's $INSUNITS / $MEASUREMENT honoured",
     {0, 0, 0}},
    {OPT_DEMO_CALL, "demo-call", CLI_ARG_NONE, NULL, NULL,
     "end the file with a top-level call of NAME() (or of\n"
     "the wrapper below) so that it renders alone",
     {0, 0, 0}},
    {OPT_EXTRUDE, "extrude", CLI_ARG_REQUIRED, "H", NULL,
     "also emit NAME_extruded(height=H, center=false);\n"
     "implies --demo-call (the file renders the solid\n"
     "alone)",
     {0, 0, 0}},
    {OPT_REVOLVE, "rotate-extrude", CLI_ARG_OPTIONAL, "ANGLE", NULL,
     "also emit NAME_revolved(angle=ANGLE, default 360),\n"
     "implies --demo-call; the profile must not have\n"
     "x < 0 (the angle may follow as the next argument)",
     {0, 0, 0}},
    {OPT_NO_DEMO_CALL, "no-demo-call", CLI_ARG_NONE, NULL, NULL,
     "no top-level call even with --extrude /\n--rotate-extrude", {0, 0, 0}},
    {OPT_SELECT, "select", CLI_ARG_REQUIRED, "IDS", NULL,
     "SVG only: comma-separated element ids (default:\nall)", {0, 0, 0}},
    {OPT_LAYER, "layer", CLI_ARG_REQUIRED, "NAME", NULL,
     "DXF only: read this layer (repeatable; default:\n"
     "every layer not frozen or off)",
     {0, 0, 0}},
    {OPT_GAP, "gap", CLI_ARG_REQUIRED, "D", NULL,
     "DXF only: join entity ends up to D apart (output\n"
     "units; default 1e-9 of the drawing's size, or 4x\n"
     "the precision its coordinates are written with,\n"
     "whichever is larger)",
     {0, 0, 0}},
    {OPT_DXF_OPEN, "open", CLI_ARG_NONE, NULL, NULL,
     "DXF only: close an outline that does not close by\n"
     "a straight edge, with a warning (default: an error)",
     {0, 0, 0}},
    {OPT_MAX_POINTS, "max-points", CLI_ARG_REQUIRED, "N", NULL,
     "cap on the dense points of one curve (default\n%.0f)",
     {(double)CONICA_SCAD_DEFAULT_MAX_DENSE, 0, 0}},
    {OPT_MAX_INPUT, "max-input-bytes", CLI_ARG_REQUIRED, "N", NULL,
     "input size cap (default 256 MiB, SVG 64 MiB, or\n"
     "the environment variable CONICA_MAX_INPUT_BYTES)",
     {0, 0, 0}},
    CONICA_SVG_CLI_LIMIT_OPTS(OPT_LIMITS),
    {OPT_FORCE, "force", CLI_ARG_NONE, NULL, NULL,
     "write even if validation fails (warnings instead\n"
     "of errors; coordinates beyond +-1e12 are refused\n"
     "all the same)",
     {0, 0, 0}},
    {OPT_STATS, "stats", CLI_ARG_NONE, NULL, NULL, "figures on stderr", {0, 0, 0}},
    {'q', "quiet", CLI_ARG_NONE, NULL, NULL,
     "no progress line (errors and the summary still print)", {0, 0, 0}},
    {OPT_PROGRESS, "progress", CLI_ARG_NONE, NULL, NULL,
     "several inputs: a progress line on stderr (count,\n"
     "rate, ETA) even when it is not a terminal (default:\n"
     "only on a terminal)",
     {0, 0, 0}},
    {'o', "output", CLI_ARG_REQUIRED, "FILE", "file",
     "output (default stdout; written via a temporary\n"
     "file); a name ending in '/' (or several inputs): a\n"
     "directory, one DIR/NAME.scad per input, module\n"
     "names from the file names",
     {0, 0, 0}},
    {'j', "jobs", CLI_ARG_REQUIRED, "N", NULL,
     "inputs processed in parallel (1..%.0f, default: the\n"
     "number of processors); one summary line, exit 1 if\n"
     "any failed",
     {CLI_BATCH_MAX_JOBS, 0, 0}},
    {0, NULL, 0, NULL, NULL, NULL, {0, 0, 0}},
};

static const cli_tool tool = {
    PROG,
    "[OPTION]... [-o OUT.scad] IN\n"
    "[OPTION]... [-j N] IN... -o DIR/",
    "Write a 2D profile as an OpenSCAD library file: module NAME(center=false)\n"
    "(a polygon with holes; center=true centres its bounding box on the origin),\n"
    "functions NAME_points(), NAME_paths(), NAME_bbox() = [[xmin,ymin],[xmax,ymax]],\n"
    "plus NAME_extruded(height, center) / NAME_revolved(angle) when asked. The\n"
    "file has no top-level geometry, so `use <OUT.scad>` and `include <OUT.scad>`\n"
    "both work, then e.g. `linear_extrude(3) NAME();`.\n"
    "\n"
    "IN: a point-normal file (`v x y` / `vn nx ny`, refined by conic subdivision),\n"
    "    an SVG file (every closed subpath of the selected elements; y flipped),\n"
    "    a spline file (.spl, through the adaptive plotter) or an ASCII DXF drawing\n"
    "    (.dxf: lines, arcs, circles, ellipses, polylines with bulges, splines,\n"
    "    blocks; ends that meet are joined into closed contours); - reads stdin.\n",
    opts,
    "Subpaths that enclose no area (fewer than 3 points, all on one line) are\n"
    "skipped with a warning; messages name a subpath as the SVG does: the element\n"
    "(id or tag) and line, and the subpath's number within the element from 1.\n"
    "\n"
    "Exit status: 0 success, 1 error (nothing written), 2 usage error.\n",
    "file",
    0,
    NULL,
};

static int is_number(const char *s)
{
    double d;
    return s && cli_parse_double(s, &d) == 0;
}

/* Index of s in names[0..n), or -1. */
static int name_index(const char *s, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if (strcmp(s, names[i]) == 0)
            return i;
    return -1;
}

/* One option's value into *o; returns -1 to go on, or an exit status. */
static int take_option(cli_parser *p, int c, void *ctx)
{
    options *o = ctx;
    const char *v = p->arg;
    long l;
    switch (c) {
    case 'k':
        if (cli_parse_int(v, 0, CONICA_SUBDIV_MAX_LEVELS, &l) != 0)
            return cli_usage_error(PROG, "--levels needs an integer in 0..%d, not '%s'",
                                   CONICA_SUBDIV_MAX_LEVELS, v);
        o->levels = (int)l;
        break;
    case 't':
        if (cli_parse_double(v, &o->tolerance) != 0 || !(o->tolerance > 0))
            return cli_usage_error(PROG, "--tolerance needs a number > 0, not '%s'", v);
        break;
    case OPT_MODULE: {
        const char *why = conica_scad_name_problem(v);
        if (why)
            return cli_usage_error(PROG,
                                   "--module '%.80s' is %s; use a name like 'profile' "
                                   "([A-Za-z_][A-Za-z0-9_]*, at most %d characters)",
                                   v, why, CONICA_SCAD_MAX_MODULE_NAME);
        o->module = v;
        o->module_given = 1;
        break;
    }
    case OPT_FIT: {
        int f = name_index(v, fit_names, 4);
        if (f < 0)
            return cli_usage_error(PROG,
                                   "--fit must be inside, outside, middle or clearance, not '%s'",
                                   v);
        o->fit = (fit)f;
        break;
    }
    case OPT_PAINT: {
        int f = name_index(v, paint_names, 4);
        if (f < 0)
            return cli_usage_error(PROG,
                                   "--paint must be as-drawn, fill, stroke or both, not '%s'", v);
        o->paint = (conica__paint)f;
        o->paint_given = 1;
        break;
    }
    case OPT_DEMO_CALL: o->demo_call = 1; break;
    case OPT_NO_DEMO_CALL: o->demo_call = 0; break;
    case OPT_UNITS:
        if (strcmp(v, "px") == 0)
            o->unit = U_PX;
        else if (strcmp(v, "mm") == 0)
            o->unit = U_MM;
        else if (strcmp(v, "in") == 0)
            o->unit = U_IN;
        else
            return cli_usage_error(PROG, "--units must be px, mm or in, not '%s'", v);
        break;
    case OPT_EXTRUDE:
        if (cli_parse_double(v, &o->height) != 0 || !(o->height > 0))
            return cli_usage_error(PROG, "--extrude needs a height > 0, not '%s'", v);
        o->extrude = 1;
        break;
    case OPT_REVOLVE:
        /* the angle as --rotate-extrude=A, or the next argument when it is a number */
        if (!v)
            v = cli_opt_optional_next(p, is_number);
        if (v && (cli_parse_double(v, &o->angle) != 0 || !(o->angle > 0 && o->angle <= 360)))
            return cli_usage_error(PROG, "--rotate-extrude angle must be in (0, 360], not '%s'",
                                   v);
        o->revolve = 1;
        break;
    case OPT_SELECT: o->select = v; break;
    case OPT_LAYER: o->layers[o->nlayers++] = v; break;
    case OPT_GAP:
        if (cli_parse_double(v, &o->gap) != 0 || !(o->gap > 0))
            return cli_usage_error(PROG, "--gap needs a distance > 0, not '%s'", v);
        break;
    case OPT_DXF_OPEN: o->dxf_open = 1; break;
    case OPT_MAX_POINTS:
        if (cli_parse_int(v, 16, (long)CONICA_SCAD_MAX_POINTS, &l) != 0)
            return cli_usage_error(PROG, "--max-points needs an integer in 16..%zu",
                                   (size_t)CONICA_SCAD_MAX_POINTS);
        o->max_points = (size_t)l;
        break;
    case OPT_FLATTEN_ONLY: o->flatten_only = 1; break;
    case OPT_FORCE: o->force = 1; break;
    case OPT_STATS: o->stats = 1; break;
    case 'q': o->progress = CLI_PROGRESS_OFF; break;
    case OPT_PROGRESS: o->progress = CLI_PROGRESS_ON; break;
    case 'o':
        o->out = v;
        /* which argument holds the value: the header of each file of a
         * batch repeats the command with the value replaced */
        for (int i = 1; i < p->argc; i++)
            if (v >= o->argv0[i] && v < o->argv0[i] + strlen(o->argv0[i]) + 1) {
                o->out_arg = i;
                o->out_attached = v != o->argv0[i];
            }
        break;
    case 'j':
        if (cli_parse_int(v, 1, CLI_BATCH_MAX_JOBS, &l) != 0)
            return cli_opt_bad(p, "needs a whole number in 1..%d", CLI_BATCH_MAX_JOBS);
        o->jobs = (int)l;
        break;
    default: /* --max-input-bytes and the XML limits */
        if (conica_svg__cli_limit(PROG, p->spelled, v, &o->limits) != 1)
            return CLI_EXIT_USAGE;
        o->max_input_given |= c == OPT_MAX_INPUT;
        break;
    }
    return -1;
}

static int parse_args(int argc, char **argv, options *o, int *exit_now)
{
    int first, rc;
    memset(o, 0, sizeof *o);
    o->out_arg = -1;
    *exit_now = 0;
    /* the inputs point into argv: at most argc of them; argv0 keeps the
     * order as typed (getopt_long moves the operands to the end) */
    o->inputs = malloc((size_t)argc * sizeof *o->inputs);
    o->argv0 = malloc(((size_t)argc + 1) * sizeof *o->argv0);
    o->layers = malloc((size_t)argc * sizeof *o->layers); /* each --layer */
    if (!o->inputs || !o->argv0 || !o->layers)
        return cli_error(PROG, NULL, "out of memory");
    memcpy(o->argv0, argv, ((size_t)argc + 1) * sizeof *argv);
    o->levels = -1;
    o->module = "profile";
    o->fit = FIT_INSIDE;
    o->demo_call = -1;
    o->height = 10;
    o->angle = 360;
    o->max_points = CONICA_SCAD_DEFAULT_MAX_DENSE;
    o->limits = conica_svg_limits_defaults();
    if ((rc = cli_opt_parse(&tool, argc, argv, take_option, o, &first)) >= 0) {
        *exit_now = 1;
        return rc;
    }
    for (int i = first; i < argc; i++)
        o->inputs[o->ninputs++] = argv[i];
    if (o->ninputs == 0)
        return cli_usage_error(PROG, "no input file");
    o->in = o->inputs[0];
    if (o->ninputs > 1 && (!o->out || !cli_is_dir_target(o->out)))
        return cli_usage_error(PROG, "several input files need -o DIR/ (one .scad per input)");
    if (o->ninputs > 1 && o->module_given)
        return cli_usage_error(PROG, "--module names one module; with several inputs each "
                                     "module is named from its file name");
    if (o->jobs && !(o->ninputs > 1 || (o->out && o->out[strlen(o->out) - 1] == '/')))
        return cli_usage_error(PROG, "-j applies to several inputs (-o DIR/)");
    if (o->levels >= 0 && o->tolerance > 0)
        return cli_usage_error(PROG, "--levels and --tolerance exclude each other");
    if (o->extrude && o->revolve)
        return cli_usage_error(PROG, "--extrude and --rotate-extrude exclude each other");
    if (o->flatten_only && o->levels >= 0)
        return cli_usage_error(PROG, "--flatten-only and --levels exclude each other");
    if (o->fit != FIT_INSIDE && o->levels >= 0)
        return cli_usage_error(PROG,
                               "--fit %s applies to flattening to a tolerance; --levels keeps "
                               "every subdivision point (on the curve)",
                               fit_names[o->fit]);
    if (o->tolerance <= 0)
        o->tolerance = DEFAULT_TOLERANCE;
    return 0;
}

/* Does the word at buf[i..len) equal w (followed by a blank or the end)? */
static int word_is(const char *buf, size_t len, size_t i, const char *w)
{
    size_t m = strlen(w);
    if (len - i < m || memcmp(buf + i, w, m) != 0)
        return 0;
    return i + m == len || buf[i + m] == ' ' || buf[i + m] == '\t' || buf[i + m] == '\r' ||
           buf[i + m] == '\n';
}

/* The kind of input: by extension, else (stdin, other names) by content:
 * the first thing that is not blank or a `#`/`%` comment line is `<` (SVG),
 * a spline keyword (degree, knots, c, w: the .spl format) or anything else
 * (a point file, whose reader names what it does not understand). */
static kind detect(const char *path, const char *buf, size_t len)
{
    if (cli_ends_with_ci(path, ".svg"))
        return IN_SVG;
    if (cli_ends_with_ci(path, ".spl"))
        return IN_SPLINE;
    if (cli_ends_with_ci(path, ".dxf") || conica_dxf_sniff(buf, len))
        return IN_DXF;
    if (cli_ends_with_ci(path, ".txt") || cli_ends_with_ci(path, ".obj"))
        return IN_POINTS;
    size_t i = 0;
    if (len >= 3 && memcmp(buf, "\xEF\xBB\xBF", 3) == 0) /* UTF-8 byte order mark */
        i = 3;
    for (;;) {
        while (i < len && (buf[i] == ' ' || buf[i] == '\t' || buf[i] == '\r' || buf[i] == '\n'))
            i++;
        if (i < len && (buf[i] == '#' || buf[i] == '%')) {
            while (i < len && buf[i] != '\n')
                i++;
            continue;
        }
        break;
    }
    if (i < len && buf[i] == '<')
        return IN_SVG;
    if (i < len && (word_is(buf, len, i, "degree") || word_is(buf, len, i, "knots") ||
                    word_is(buf, len, i, "c") || word_is(buf, len, i, "w")))
        return IN_SPLINE;
    return IN_POINTS;
}

static const char *base_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

/* The default module name: the input file's base name without its
 * extension, made into an OpenSCAD identifier (each run of other
 * characters becomes one '_', a leading digit gets a '_' before it, at
 * most CONICA_SCAD_MAX_MODULE_NAME characters, a reserved word or built-in
 * gets a '_' after it); "profile" for stdin or when nothing is left.
 * *changed: the name is not the base name as it was. buf: at least
 * CONICA_SCAD_MAX_MODULE_NAME + 1 bytes. */
static void default_module(const char *in, char *buf, size_t cap, int *changed)
{
    const char *b = base_name(in), *dot = strrchr(b, '.');
    size_t len = dot && dot != b ? (size_t)(dot - b) : strlen(b), n = 0;
    int gap = 0;
    *changed = 0;
    if (strcmp(in, "-") == 0 || cap < CONICA_SCAD_MAX_MODULE_NAME + 1) {
        snprintf(buf, cap, "profile");
        return;
    }
    for (size_t i = 0; i < len && n < CONICA_SCAD_MAX_MODULE_NAME; i++) {
        char c = b[i];
        int ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                 c == '_';
        if (!ok) {
            *changed = 1;
            gap = 1;
            continue;
        }
        if (gap && n > 0 && n < CONICA_SCAD_MAX_MODULE_NAME)
            buf[n++] = '_';
        gap = 0;
        if (n == 0 && c >= '0' && c <= '9') {
            buf[n++] = '_';
            *changed = 1;
        }
        if (n < CONICA_SCAD_MAX_MODULE_NAME)
            buf[n++] = c;
    }
    if (n == CONICA_SCAD_MAX_MODULE_NAME && n < len)
        *changed = 1;
    buf[n] = '\0';
    if (n == 0) {
        snprintf(buf, cap, "profile");
        *changed = 1;
        return;
    }
    if (!conica_scad_valid_name(buf)) { /* a reserved word or built-in */
        if (n == CONICA_SCAD_MAX_MODULE_NAME)
            n--;
        buf[n++] = '_';
        buf[n] = '\0';
        *changed = 1;
    }
}

/* `scadprofile: error: FILE[:LINE]: what` from a library status. */
static int status_error(const char *file, const conica_status *st)
{
    char where[1024];
    if (st->line)
        snprintf(where, sizeof where, "%s:%zu", file, st->line);
    else
        snprintf(where, sizeof where, "%s", file);
    return cli_error(PROG, where, "%s", st->message[0] ? st->message : conica_strerror(st->code));
}

/* ------------------------------------------------------------ point-normal */

/* Report a subdivision failure at the line of the point it names (see
 * cli_point_line), as `conica subdivide` does. */
static int point_error(const char *file, const char *buf, size_t len, const conica_status *st)
{
    char msg[sizeof st->message + 200];
    size_t line = cli_point_failure(buf, len, st->code, st, msg, sizeof msg);
    if (line > 0) {
        char where[1024];
        snprintf(where, sizeof where, "%s:%zu", file, line);
        return cli_error(PROG, where, "%s", msg);
    }
    return status_error(file, st);
}

/* 0, or an error naming the line of the first input point beyond
 * CONICA_SCAD_MAX_COORD (subdivision interpolates: it stays in the output). */
static int points_in_range(const char *name, const char *buf, size_t len, const conica_curve *in)
{
    for (size_t i = 0; i < in->n; i++)
        if (!(fabs(in->xy[2 * i]) <= CONICA_SCAD_MAX_COORD) ||
            !(fabs(in->xy[2 * i + 1]) <= CONICA_SCAD_MAX_COORD)) {
            char where[1024], xs[40], ys[40];
            snprintf(where, sizeof where, "%s:%zu", name,
                     conica_curve_line_of_point(buf, len, i, 0));
            conica_scad_format_double(in->xy[2 * i], xs, sizeof xs);
            conica_scad_format_double(in->xy[2 * i + 1], ys, sizeof ys);
            return cli_error(PROG, where,
                             "point %zu (%s, %s) is out of range: coordinates must lie within "
                             "+-%g (OpenSCAD ignores points beyond about 1e15)",
                             i + 1, xs, ys, CONICA_SCAD_MAX_COORD);
        }
    return 0;
}

static int load_points(const options *o, const char *name, const char *buf, size_t len,
                       conica_scad_profile *prof, stats *sx)
{
    conica_curve in, sub;
    conica_status st;
    double *pts = NULL;
    size_t n = 0, g;
    conica_code rc;
    conica_curve_init(&in);
    conica_curve_init(&sub);
    if (conica_curve_parse(buf, len, &in, &st) != CONICA_OK) {
        conica_curve_free(&in);
        return status_error(name, &st);
    }
    in.closed = 1;
    sx->kind = "point-normal";
    sx->input_points = in.n;
    if (in.n < 3) {
        size_t got = in.n; /* conica_curve_free() zeroes in.n */
        conica_curve_free(&in);
        return cli_error(PROG, name, "a profile needs at least 3 points, the file has %zu", got);
    }
    /* before refining (a huge curve would only exhaust the point cap);
     * --levels keeps the subdivision's own report of huge input */
    if (o->levels < 0 && points_in_range(name, buf, len, &in) != 0) {
        conica_curve_free(&in);
        return CLI_EXIT_ERROR;
    }
    if (o->flatten_only) {
        rc = CONICA_OK;
        pts = in.xy;
        n = in.n;
        sx->dense_points = n;
    } else if (o->levels >= 0) {
        conica_subdiv_settings s = conica_subdiv_defaults();
        s.levels = o->levels;
        s.max_points = o->max_points;
        rc = conica_subdivide(&in, &s, &sub, NULL, &st);
        pts = sub.xy;
        n = sub.n;
        sx->levels = o->levels;
        sx->dense_points = n;
    } else {
        conica_scad_refine_info info;
        memset(&info, 0, sizeof info);
        /* the written digits may move a point by tol * ROUND_FRACTION */
        rc = conica_scad_refine(&in, o->tolerance * (1 - CONICA_SCAD_ROUND_FRACTION),
                                o->max_points, &pts, &n, &info, &st);
        sx->levels = info.levels;
        sx->dense_points = info.dense_points;
        if (rc == CONICA_ERR_LIMIT && strncmp(st.message, "tolerance ", 10) == 0) {
            /* it names the tolerance less the digits' share: say the user's */
            const char *rest = strchr(st.message + 10, ' ');
            char msg[sizeof st.message], num[40];
            size_t m;
            conica_scad_format_double(o->tolerance, num, sizeof num);
            m = (size_t)snprintf(msg, sizeof msg, "tolerance %s", num);
            if (rest && m < sizeof msg)
                memcpy(msg + m, rest, strnlen(rest, sizeof msg - m - 1) + 1);
            msg[sizeof msg - 1] = '\0';
            memcpy(st.message, msg, sizeof msg);
        }
    }
    if (rc == CONICA_OK && o->levels >= 0 && points_in_range(name, buf, len, &in) != 0) {
        if (pts != in.xy && pts != sub.xy)
            free(pts);
        conica_curve_free(&in);
        conica_curve_free(&sub);
        return CLI_EXIT_ERROR;
    }
    if (rc == CONICA_OK)
        rc = conica_scad_add_group(prof, "", CONICA_SCAD_FILL_NONZERO, 0, &g, &st);
    if (rc == CONICA_OK)
        rc = conica_scad_add_contour(prof, g, pts, n, &st);
    if (pts != in.xy && pts != sub.xy)
        free(pts);
    conica_curve_free(&in);
    conica_curve_free(&sub);
    if (rc != CONICA_OK)
        return point_error(name, buf, len, &st);
    return 0;
}

/* ------------------------------------------------------------ splines */

static int load_spline(const options *o, const char *name, const char *buf, size_t len,
                       conica_scad_profile *prof, stats *sx)
{
    conica_bspline s;
    conica_polyline pl;
    conica_status st;
    conica_code rc;
    double *pts = NULL;
    size_t n = 0, g;
    if (o->levels >= 0)
        return cli_error(PROG, name, "--levels applies to point-normal and SVG input; "
                                     "use --tolerance for a spline");
    conica_bspline_init(&s);
    conica_polyline_init(&pl);
    if (conica_bspline_parse(buf, len, &s, &st) != CONICA_OK) {
        conica_bspline_free(&s);
        return status_error(name, &st);
    }
    sx->kind = "spline";
    sx->input_points = s.n;
    if (s.dim != 2) {
        int dim = s.dim;
        conica_bspline_free(&s);
        return cli_error(PROG, name, "a profile needs a planar spline (2 coordinates), "
                                     "this one has %d", dim);
    }
    conica_plot_settings ps = conica_plot_defaults();
    ps.method = CONICA_PLOT_GUARANTEED;
    ps.abs_tolerance = o->flatten_only ? o->tolerance * (1 - CONICA_SCAD_ROUND_FRACTION)
                                       : o->tolerance * DENSE_FRACTION;
    ps.max_points = o->max_points;
    rc = conica_plot(&s, &ps, &pl, NULL, &st);
    conica_bspline_free(&s);
    if (rc != CONICA_OK) {
        conica_polyline_free(&pl);
        return status_error(name, &st);
    }
    n = pl.n;
    sx->dense_points = n;
    /* drop the closing point of a closed spline (the polygon closes itself) */
    if (n >= 2) {
        double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            xmin = fmin(xmin, pl.xy[2 * i]);
            xmax = fmax(xmax, pl.xy[2 * i]);
            ymin = fmin(ymin, pl.xy[2 * i + 1]);
            ymax = fmax(ymax, pl.xy[2 * i + 1]);
        }
        double gap = hypot(pl.xy[2 * n - 2] - pl.xy[0], pl.xy[2 * n - 1] - pl.xy[1]);
        if (gap <= SPLINE_CLOSE_REL * hypot(xmax - xmin, ymax - ymin))
            n--;
        else
            cli_warning(PROG, name, "the spline is open; a straight segment closes the profile");
    }
    if (n >= 3 && !o->flatten_only) {
        rc = conica_scad_thin(pl.xy, n, 1,
                              o->tolerance * (1 - DENSE_FRACTION - CONICA_SCAD_ROUND_FRACTION),
                              &pts, &n, &st);
    } else {
        rc = CONICA_OK;
        pts = pl.xy;
    }
    if (rc == CONICA_OK)
        rc = conica_scad_add_group(prof, "", CONICA_SCAD_FILL_NONZERO, 0, &g, &st);
    if (rc == CONICA_OK)
        rc = conica_scad_add_contour(prof, g, pts, n, &st);
    if (pts != pl.xy)
        free(pts);
    conica_polyline_free(&pl);
    if (rc != CONICA_OK)
        return status_error(name, &st);
    return 0;
}

/* ------------------------------------------------------------ SVG */

/* SVG layer warnings as `scadprofile: warning: FILE[:LINE]: what`; ctx is
 * the file name. */
static void svg_warn(void *ctx, size_t line, const char *message)
{
    char where[1024];
    if (line)
        snprintf(where, sizeof where, "%s:%zu", (const char *)ctx, line);
    cli_warning(PROG, line ? where : (const char *)ctx, "%s", message);
}

/* Split "a,b,c" into a NULL-terminated array of copies (caller frees both). */
static char **split_ids(const char *s, size_t *count)
{
    size_t n = 1, k = 0;
    for (const char *p = s; *p; p++)
        n += *p == ',';
    char **ids = calloc(n + 1, sizeof *ids);
    char *copy = malloc(strlen(s) + 1);
    if (!ids || !copy) {
        free(ids);
        free(copy);
        return NULL;
    }
    strcpy(copy, s);
    for (char *p = copy, *tok; p; p = tok) {
        tok = strchr(p, ',');
        if (tok)
            *tok++ = '\0';
        if (*p)
            ids[k++] = p;
    }
    if (k == 0)
        free(copy);
    *count = k;
    return ids;
}

/* The SVG's own name of an element, as the SVG layer's messages say it
 * (svg_doc.c describe()): "path 'plate'", "rect (no id)". */
static void element_name(const conica_svg_element *el, char *buf, size_t cap)
{
    if (el->id)
        snprintf(buf, cap, "%s '%.60s'", el->tag, el->id);
    else
        snprintf(buf, cap, "%s (no id)", el->tag);
}

/* Every subpath of the selected elements, in output units, into prof[r]
 * for each of the nruns fit modes fits[r] (the document is parsed once; the
 * runs have the same elements and subpaths in the same order). One group
 * per element, one contour per subpath, numbered as the element's
 * subpaths from 1. Warnings come from the first run only. */
static int load_svg(const options *o, const char *name, const char *buf, size_t len,
                    const fit *fits, size_t nruns, conica_scad_profile *prof, stats *sx)
{
    conica_svg_doc *doc = NULL;
    conica_svg_shapes shapes;
    conica_svg_viewport vp;
    conica_status st;
    conica_code rc;
    char **ids = NULL;
    size_t nids = 0;
    int result = 0;

    if (conica_svg_doc_load(buf, len, &o->limits, &doc, &st) != CONICA_OK)
        return status_error(name, &st);
    if (conica_svg_doc_viewport(doc, &vp, &st) != CONICA_OK) {
        conica_svg_doc_free(doc);
        return status_error(name, &st);
    }
    /* Output units per user unit: the root's width (height) in the output
     * unit over the viewBox width (height); without a viewBox a user unit
     * is a CSS px. Converted in one step (conica_svg_convert_length), so a
     * px document written in px keeps its numbers exactly. */
    const char *unit = o->unit == U_PX ? "px" : o->unit == U_IN ? "in" : "mm";
    double sxu, syu;
    if (vp.has_viewbox) {
        sxu = vp.has_width ? conica_svg_convert_length(vp.width, vp.width_unit, unit) / vp.viewbox[2]
                           : NAN;
        syu = vp.has_height
                  ? conica_svg_convert_length(vp.height, vp.height_unit, unit) / vp.viewbox[3]
                  : NAN;
    } else {
        sxu = syu = conica_svg_convert_length(1.0, "px", unit);
    }
    if (!(isfinite(sxu) && sxu > 0) || !(isfinite(syu) && syu > 0)) {
        cli_warning(PROG, name, "the document's size is relative or missing: 1 user unit = 1 px");
        sxu = syu = conica_svg_convert_length(1.0, "px", unit);
    }
    /* y flipped about the viewBox (or the height): the drawing keeps its
     * place in the first quadrant, y up as in OpenSCAD. */
    double x0 = vp.has_viewbox ? vp.viewbox[0] : 0;
    double hpx = vp.has_height ? conica_svg_convert_length(vp.height, vp.height_unit, "px") : NAN;
    double ytop = vp.has_viewbox ? vp.viewbox[1] + vp.viewbox[3] : isfinite(hpx) ? hpx : 0;
    double tol_user = o->tolerance / fmax(sxu, syu);

    conica_svg_settings set = conica_svg_defaults();
    set.convert_shapes = 1;
    set.limits = o->limits;
    set.limits.max_points = o->max_points * 16;
    /* SVG fills an open subpath as if closed (as OpenSCAD's import() does) */
    set.close_open = 1;
    if (o->levels >= 0) {
        set.mode = CONICA_SVG_SMOOTH;
        set.levels = o->levels;
        set.tolerance = 0;
        set.fidelity = tol_user;
    } else {
        /* The drawn curves are the ground truth: flattened within the
         * tolerance of them, straight edges and their ends exact; the
         * written digits get tolerance * ROUND_FRACTION of it. */
        set.mode = CONICA_SVG_FLATTEN;
        set.tolerance = tol_user * (1 - CONICA_SCAD_ROUND_FRACTION);
    }
    if (o->select) {
        ids = split_ids(o->select, &nids);
        if (!ids) {
            conica_svg_doc_free(doc);
            return cli_error(PROG, name, "out of memory");
        }
        set.select = (const char *const *)ids;
        set.nselect = nids;
    }
    sx->kind = "SVG";
    for (size_t r = 0; r < nruns && result == 0; r++) {
        set.fit = (int)fits[r];
        set.warn = r == 0 ? svg_warn : NULL;
        set.warn_ctx = (void *)name;
        conica_svg_shapes_init(&shapes);
        rc = conica_svg_extract(doc, &set, &shapes, &st);
        if (rc != CONICA_OK) {
            result = status_error(name, &st);
            conica_svg_shapes_free(&shapes);
            break;
        }
        if (r == 0)
            sx->elements = shapes.nelements;
        for (size_t e = 0; e < shapes.nelements && result == 0; e++) {
            const conica_svg_element *el = &shapes.elements[e];
            char gname[CONICA_SCAD_MAX_GROUP_NAME], where[1024];
            size_t g;
            snprintf(where, sizeof where, "%s:%zu", name, el->line);
            element_name(el, gname, sizeof gname);
            if (el->has_transform && r == 0)
                cli_warning(PROG, where, "%s has a transform, which is not applied", gname);
            if (conica_scad_add_group(&prof[r], gname,
                                      el->fill_rule == CONICA_SVG_EVENODD
                                          ? CONICA_SCAD_FILL_EVENODD
                                          : CONICA_SCAD_FILL_NONZERO,
                                      el->line, &g, &st) != CONICA_OK) {
                result = status_error(name, &st);
                break;
            }
            for (size_t k = 0; k < el->nsubpaths; k++) {
                const conica_svg_subpath *sp = &shapes.subpaths[el->first_subpath + k];
                double *xy;
                size_t n = sp->n;
                if (r == 0) {
                    sx->dense_points += n;
                    sx->subpaths++;
                }
                if (n == 0)
                    continue;
                xy = malloc(2 * n * sizeof *xy);
                if (!xy) {
                    result = cli_error(PROG, name, "out of memory");
                    break;
                }
                for (size_t i = 0; i < n; i++) {
                    xy[2 * i] = (sp->xy[2 * i] - x0) * sxu;
                    xy[2 * i + 1] = (ytop - sp->xy[2 * i + 1]) * syu;
                }
                rc = conica_scad_add_contour(&prof[r], g, xy, n, &st);
                free(xy);
                if (rc != CONICA_OK) {
                    result = cli_error(PROG, where, "%s: subpath %zu: %s", gname, k + 1,
                                       st.message);
                    break;
                }
                /* the SVG's own numbering, whatever was left out before */
                prof[r].contours[prof[r].ncontours - 1].subpath = k + 1;
            }
        }
        conica_svg_shapes_free(&shapes);
        if (result == 0 && prof[r].ncontours == 0)
            result = cli_error(PROG, name, "no closed subpath in the %s elements",
                               o->select ? "selected" : "document's");
    }
    conica_svg_doc_free(doc);
    if (ids) {
        if (nids)
            free(ids[0]);
        free(ids);
    }
    return result;
}

/* 0, or an error naming the item, subpath and point of the first
 * coordinate (in output units, y up) beyond CONICA_SCAD_MAX_COORD: before
 * the booleans, whose grid could not hold it, and in the words
 * conica_scad_check_range() uses. */
static int scene_in_range(const options *o, const char *name, const conica_svg_scene *sc)
{
    double height = sc->has_size ? sc->height : 0.0;
    for (size_t i = 0; i < sc->n; i++) {
        const conica_svg_item *it = &sc->items[i];
        size_t sub = 0, pt = 0;
        for (size_t k = 0; k < it->path.n; k++) {
            const conica_svg_seg *g = &it->path.seg[k];
            double q[2];
            if (g->type == CONICA_SVG_SEG_CLOSE)
                continue;
            if (g->type == CONICA_SVG_SEG_MOVE) {
                sub++;
                pt = 0;
            } else if (k == 0 || it->path.seg[k - 1].type == CONICA_SVG_SEG_CLOSE) {
                pt = 1; /* drawn on from the start of the closed subpath */
            }
            pt++;
            conica_svg_matrix_apply(&it->ctm, g->x1, g->y1, q);
            q[1] = height - q[1];
            if (!(fabs(q[0]) <= CONICA_SCAD_MAX_COORD && fabs(q[1]) <= CONICA_SCAD_MAX_COORD)) {
                char where[1024], xs[40], ys[40];
                snprintf(where, sizeof where, "%s:%zu", name, it->line);
                conica_scad_format_double(q[0], xs, sizeof xs);
                conica_scad_format_double(q[1], ys, sizeof ys);
                return cli_error(PROG, where,
                                 "%s: subpath %zu: point %zu (%s, %s) is out of range: coordinates "
                                 "must lie within +-%g (OpenSCAD ignores points beyond about "
                                 "1e15); the numbers are in %s, after unit conversion",
                                 it->name, sub ? sub : 1, pt, xs, ys, CONICA_SCAD_MAX_COORD,
                                 o->unit == U_PX ? "px" : o->unit == U_IN ? "in" : "mm");
            }
        }
    }
    return 0;
}

/* --fit as the region's side: clearance is inside (holes drawn at least
 * as large are the inside polygon's). */
static conica__region_fit region_fit(fit f)
{
    return f == FIT_OUTSIDE ? CONICA__REGION_OUTSIDE
           : f == FIT_MIDDLE ? CONICA__REGION_MIDDLE
                             : CONICA__REGION_INSIDE;
}

/* The fitted region into prof as one group of simple contours, named gname. */
static int add_region(const char *name, const char *gname, const conica__polys *region,
                      conica_scad_profile *prof)
{
    conica_status st;
    size_t g;
    if (conica_scad_add_group(prof, gname, CONICA_SCAD_FILL_NONZERO, 0, &g, &st) != CONICA_OK)
        return status_error(name, &st);
    for (size_t i = 0; i < region->n; i++)
        if (conica_scad_add_contour(prof, g, region->xy + 2 * region->start[i],
                                    region->start[i + 1] - region->start[i], &st) != CONICA_OK)
            return status_error(name, &st);
    return 0;
}

/* What the document paints (the SVG layer's render: <use>, viewports,
 * styles, transforms) as one region: fills under their fill rule and
 * strokes as areas, clipped and unioned with Clipper, fitted to one side
 * and checked against the drawn region (scad_region.h), into prof as one
 * group of simple contours in output units, y up. */
static int load_svg_region(const options *o, const char *name, const char *buf, size_t len,
                           conica_scad_profile *prof, stats *sx)
{
    conica_svg_doc *doc = NULL;
    conica_svg_scene scene;
    conica_svg_render_settings rs = conica_svg_render_defaults();
    conica__region_settings gs;
    conica__region_stats gx;
    conica__polys region;
    conica_status st;
    char **ids = NULL;
    size_t nids = 0;
    int result = 0;

    if (conica_svg_doc_load(buf, len, &o->limits, &doc, &st) != CONICA_OK)
        return status_error(name, &st);
    rs.unit = o->unit == U_PX ? "px" : o->unit == U_IN ? "in" : "mm";
    rs.warn = svg_warn;
    rs.warn_ctx = (void *)name;
    rs.unpainted = o->paint != CONICA__PAINT_AS_DRAWN;
    if (o->select) {
        ids = split_ids(o->select, &nids);
        if (!ids) {
            conica_svg_doc_free(doc);
            return cli_error(PROG, name, "out of memory");
        }
        rs.select = (const char *const *)ids;
        rs.nselect = nids;
    }
    conica_svg_scene_init(&scene);
    conica__polys_init(&region);
    {
        /* the document's caps on path data and points (--max-path-bytes,
         * --max-points), which the render does not read: a pass that only
         * reads the vertices */
        conica_svg_settings ks = conica_svg_defaults();
        conica_svg_shapes sh;
        ks.mode = CONICA_SVG_KEEP;
        ks.convert_shapes = 1;
        ks.limits = o->limits;
        ks.select = rs.select;
        ks.nselect = rs.nselect;
        conica_svg_shapes_init(&sh);
        conica_code kc = conica_svg_extract(doc, &ks, &sh, &st);
        conica_svg_shapes_free(&sh);
        if (kc == CONICA_ERR_LIMIT) {
            result = status_error(name, &st);
            goto done;
        }
    }
    if (conica_svg_render(doc, &rs, &scene, &st) != CONICA_OK) {
        result = status_error(name, &st);
        goto done;
    }
    if (!scene.has_size)
        cli_warning(PROG, name, "the document's size is relative or missing: 1 user unit = 1 px");
    if ((result = scene_in_range(o, name, &scene)) != 0)
        goto done;
    memset(&gs, 0, sizeof gs);
    /* the written digits get tolerance * ROUND_FRACTION of the tolerance */
    gs.tolerance = o->tolerance * (1 - CONICA_SCAD_ROUND_FRACTION);
    gs.fit = region_fit(o->fit);
    gs.paint = o->paint;
    gs.warn = svg_warn;
    gs.warn_ctx = (void *)name;
    gs.max_points = o->max_points * 16;
    memset(&gx, 0, sizeof gx);
    sx->kind = "SVG";
    sx->elements = scene.n;
    if (conica__scad_region(&scene, &gs, &region, &gx, &st) != CONICA_OK) {
        result = status_error(name, &st);
        goto done;
    }
    sx->subpaths = gx.subpaths;
    sx->dense_points = gx.dense_points;
    sx->fills = gx.fills;
    sx->strokes = gx.strokes;
    if (region.n == 0 && gx.subpaths > 0) {
        /* one element: its line, as the warnings before name it */
        char where[1024];
        if (scene.n == 1)
            snprintf(where, sizeof where, "%s:%zu", name, scene.items[0].line);
        else
            snprintf(where, sizeof where, "%s", name);
        result = cli_error(PROG, where, "nothing to write: none of the %zu subpath%s encloses an area",
                           gx.subpaths, gx.subpaths == 1 ? "" : "s");
        goto done;
    }
    if (region.n == 0) {
        result = cli_error(PROG, name, "nothing is painted: no shape of the document is filled or "
                                       "stroked%s",
                           o->paint == CONICA__PAINT_AS_DRAWN
                               ? " (--paint fill fills every shape, painted or not)"
                               : "");
        goto done;
    }
    result = add_region(name, "painted region", &region, prof);
done:
    conica__polys_free(&region);
    conica_svg_scene_free(&scene);
    conica_svg_doc_free(doc);
    if (ids) {
        if (nids)
            free(ids[0]);
        free(ids);
    }
    return result;
}

/* ------------------------------------------------------------ DXF */

static const char *kinds_of(kind k)
{
    return k == IN_DXF ? "DXF" : k == IN_SVG ? "SVG" : k == IN_SPLINE ? "spline" : "point-normal";
}

/* DXF reader warnings as `scadprofile: warning: FILE[:LINE]: what`. */
static void dxf_warn(void *ctx, size_t line, const char *message)
{
    svg_warn(ctx, line, message);
}

/* The header's account of the drawing: units, layers, entities, gap. */
static char *dxf_note(const conica_dxf_drawing *d, const char *unit)
{
    size_t cap = 256;
    for (size_t i = 0; i < d->nlayers; i++)
        cap += strlen(d->layers[i]) + 4;
    char *t = malloc(cap), g[40];
    if (!t)
        return NULL;
    conica_scad_format_double(d->gap, g, sizeof g);
    size_t n = (size_t)snprintf(t, cap,
                                "DXF: %zu entities read, %zu skipped; drawing units %s; %zu "
                                "contours (%zu joined from several entities, gap %s %s)\nlayers read:",
                                d->entities, d->skipped, d->file_unit, d->path.nsub, d->joined, g,
                                unit);
    for (size_t i = 0; i < d->nlayers && n < cap; i++)
        n += (size_t)snprintf(t + n, cap - n, "%s %s", i ? "," : "", d->layers[i]);
    return t;
}

/* A DXF drawing (conica/dxf.h) into prof: every contour filled even-odd,
 * so holes are holes whatever their layer, as one region fitted to one
 * side of the entities and checked against them (scad_region.h, the SVG
 * region's own fit and check). */
static int load_dxf(options *o, const char *name, const char *buf, size_t len,
                    conica_scad_profile *prof, stats *sx)
{
    conica_dxf_settings ds = conica_dxf_defaults();
    conica_dxf_drawing d;
    conica__region_settings gs;
    conica__region_source src;
    conica__region_stats gx;
    conica__polys region;
    conica_status st;
    int result = 0;
    if (o->levels >= 0)
        return cli_error(PROG, name, "--levels applies to point-normal and SVG input; "
                                     "use --tolerance for a DXF drawing");
    ds.unit_mm = o->unit == U_IN ? 25.4 : o->unit == U_PX ? 25.4 / 96 : 1;
    ds.gap = o->gap;
    ds.open_mode = o->dxf_open ? CONICA_DXF_OPEN_CLOSE : CONICA_DXF_OPEN_ERROR;
    ds.layers = o->layers;
    ds.nlayers = o->nlayers;
    ds.warn = dxf_warn;
    ds.warn_ctx = (void *)name;
    if (o->max_input_given)
        ds.limits.max_bytes = o->limits.max_bytes;
    ds.limits.max_points = o->max_points; /* control points, like the dense points of one curve */
    conica_dxf_drawing_init(&d);
    if (conica_dxf_read(buf, len, &ds, &d, &st) != CONICA_OK) {
        conica_dxf_drawing_free(&d);
        if (st.code == CONICA_ERR_PARSE && strncmp(st.message, "an outline does not close", 25) == 0) {
            status_error(name, &st);
            fprintf(stderr, PROG ": note: --gap D joins ends up to D apart (output units); "
                            "--open closes such an outline by a straight edge\n");
            return CLI_EXIT_ERROR;
        }
        return status_error(name, &st);
    }
    sx->kind = "DXF";
    sx->elements = d.entities;
    sx->subpaths = d.path.nsub;
    o->dxf_note = dxf_note(&d, o->unit == U_IN ? "in" : o->unit == U_PX ? "px" : "mm");
    if (!o->dxf_note) {
        conica_dxf_drawing_free(&d);
        return cli_error(PROG, name, "out of memory");
    }
    memset(&gs, 0, sizeof gs);
    /* the written digits get tolerance * ROUND_FRACTION of the tolerance */
    gs.tolerance = o->tolerance * (1 - CONICA_SCAD_ROUND_FRACTION);
    gs.fit = region_fit(o->fit);
    gs.warn = dxf_warn;
    gs.warn_ctx = (void *)name;
    gs.max_points = o->max_points * 16;
    memset(&src, 0, sizeof src);
    src.path = &d.path;
    src.rule = CONICA__CLIP_EVENODD;
    src.name = "the drawing";
    src.part = "contour";
    src.sub_line = d.sub_line;
    src.nsub_line = d.path.nsub;
    conica__polys_init(&region);
    memset(&gx, 0, sizeof gx);
    if (conica__scad_region_path(&src, &gs, &region, &gx, &st) != CONICA_OK)
        result = status_error(name, &st);
    else if (region.n == 0)
        result = cli_error(PROG, name, "nothing to write: none of the %zu contour%s encloses an "
                                       "area",
                           gx.subpaths, cli_plural(gx.subpaths));
    else
        result = add_region(name, "drawing", &region, prof);
    sx->dense_points = gx.dense_points;
    conica__polys_free(&region);
    conica_dxf_drawing_free(&d);
    return result;
}

/* --fit clearance: the contours that are holes in the inside run *in
 * (arranged as *lay) take their points from the outside run *out, which
 * holds the same subpaths in the same order (*in may have lost some to
 * conica_scad_drop_empty; group and subpath number find the rest). */
static int take_holes(conica_scad_profile *in, const conica_scad_layout *lay,
                      const conica_scad_profile *out, const char *name, size_t *taken)
{
    unsigned char *hole = calloc(in->ncontours ? in->ncontours : 1, 1);
    size_t j = 0;
    *taken = 0;
    if (!hole)
        return cli_error(PROG, name, "out of memory");
    for (size_t i = 0; i < lay->npaths; i++)
        if (lay->paths[i].hole)
            hole[lay->paths[i].contour] = 1;
    for (size_t c = 0; c < in->ncontours; c++) {
        conica_scad_contour *k = &in->contours[c];
        while (j < out->ncontours &&
               (out->contours[j].group != k->group || out->contours[j].subpath != k->subpath))
            j++;
        if (j == out->ncontours) {
            free(hole);
            return cli_error(PROG, name,
                             "--fit clearance: the outside run lacks a subpath of the inside run");
        }
        if (!hole[c])
            continue;
        const conica_scad_contour *q = &out->contours[j];
        double *xy = malloc(2 * q->n * sizeof *xy);
        if (!xy) {
            free(hole);
            return cli_error(PROG, name, "out of memory");
        }
        memcpy(xy, q->xy, 2 * q->n * sizeof *xy);
        free(k->xy);
        in->npoints = in->npoints - k->n + q->n;
        k->xy = xy;
        k->n = q->n;
        (*taken)++;
    }
    free(hole);
    return 0;
}

/* ------------------------------------------------------------ main */

static char *header_text(int argc, char **argv, const options *o, const char *kind_name,
                         int exact, const stats *sx, int region)
{
    size_t cap = 1024 + (o->dxf_note ? strlen(o->dxf_note) : 0);
    for (int i = 0; i < argc; i++)
        cap += strlen(argv[i]) + 3;
    char *h = malloc(cap), num[40], step[40];
    if (!h)
        return NULL;
    size_t n = (size_t)snprintf(h, cap, "Generated by " PROG " (Conica) %s.\ncommand:", conica_version());
    for (int i = 0; i < argc && n < cap; i++)
        n += (size_t)snprintf(h + n, cap - n, " %s", i == 0 ? PROG : argv[i]);
    conica_scad_format_double(o->tolerance, num, sizeof num);
    conica_scad_format_double(o->tolerance * CONICA_SCAD_ROUND_FRACTION, step, sizeof step);
    if (n < cap)
        n += (size_t)snprintf(h + n, cap - n, "\nsource: %s (%s)\n", o->in, kind_name);
    /* SVG output units are chosen; other inputs keep their own units */
    const char *u = strcmp(kind_name, "SVG") != 0 && strcmp(kind_name, "DXF") != 0 ? "(input units)"
                    : o->unit == U_PX                ? "px"
                    : o->unit == U_IN                ? "in"
                                                     : "mm";
    if (n < cap) {
        if (o->levels >= 0)
            n += (size_t)snprintf(h + n, cap - n,
                                  "refinement: %d subdivision level%s, every point kept", o->levels,
                                  cli_plural((size_t)o->levels));
        else if (o->flatten_only)
            n += (size_t)snprintf(h + n, cap - n,
                                  "tolerance: %s %s (curves flattened, input geometry kept)", num, u);
        else
            n += (size_t)snprintf(h + n, cap - n,
                                  "tolerance: %s %s (largest distance between the polygon and the "
                                  "curve)",
                                  num, u);
    }
    if (n < cap)
        n += (size_t)snprintf(h + n, cap - n, "\nfit: %s (%s)", fit_names[o->fit],
                              fit_meaning[o->fit]);
    if (n < cap && o->dxf_note)
        n += (size_t)snprintf(h + n, cap - n, "\n%s", o->dxf_note);
    if (n < cap && region)
        n += (size_t)snprintf(h + n, cap - n,
                              "\npaint: %s (%s): %zu fill%s and %zu stroke%s made material",
                              paint_names[o->paint], paint_meaning[o->paint], sx->fills,
                              sx->fills == 1 ? "" : "s", sx->strokes, sx->strokes == 1 ? "" : "s");
    if (n < cap) {
        if (exact)
            snprintf(h + n, cap - n, "\ncoordinates: exact (the shortest decimals that read "
                                     "back to the computed doubles)");
        else
            snprintf(h + n, cap - n,
                     "\ncoordinates: fewest digits within %s %s (tolerance/1000) of each point,\n"
                     "  the input's own numbers kept exactly where that is short",
                     step, u);
    }
    return h;
}

/* Where a validation problem is: FILE:LINE of the contour's element, or,
 * for a point file written as it is (--flatten-only), the line of the
 * point the problem names. */
static void problem_where(const char *name, kind k, const options *o, const char *buf, size_t len,
                          const conica_scad_profile *p, const conica_scad_violation *v,
                          char *where, size_t cap)
{
    const conica_scad_group *g = v->problem != CONICA_SCAD_OK && v->contour_a < p->ncontours
                                     ? &p->groups[p->contours[v->contour_a].group]
                                     : NULL;
    size_t pline = k == IN_POINTS && o->flatten_only &&
                           (v->problem == CONICA_SCAD_DUPLICATE_POINT ||
                            v->problem == CONICA_SCAD_NEGATIVE_X ||
                            v->problem == CONICA_SCAD_OUT_OF_RANGE)
                       ? conica_curve_line_of_point(buf, len, v->segment_a, 0)
                       : 0;
    if (pline)
        snprintf(where, cap, "%s:%zu", name, pline);
    else if (g && g->line)
        snprintf(where, cap, "%s:%zu", name, g->line);
    else
        snprintf(where, cap, "%s", name);
}

/* conica_scad_drop_empty()'s report: a warning per skipped contour, or,
 * for a profile of one contour, the message kept for the error. */
typedef struct drop_ctx {
    const char *name;
    int quiet;
    char where[1024];
    char first[sizeof ((conica_status *)0)->message];
} drop_ctx;

static void on_drop(void *ctx, const conica_scad_profile *p, size_t contour,
                    const conica_scad_violation *v, const char *message)
{
    drop_ctx *d = ctx;
    const conica_scad_group *g = &p->groups[p->contours[contour].group];
    (void)v;
    if (g->line)
        snprintf(d->where, sizeof d->where, "%s:%zu", d->name, g->line);
    else
        snprintf(d->where, sizeof d->where, "%s", d->name);
    if (d->quiet)
        snprintf(d->first, sizeof d->first, "%s", message);
    else
        cli_warning(PROG, d->where, "%s; skipped", message);
}

/* Validation failed: an error (returns 1), or with --force a warning
 * (returns 0). Coordinates out of range are refused even then. */
static int invalid(const char *name, kind k, const options *o, const char *buf, size_t len,
                   const conica_scad_profile *p, const conica_scad_violation *v,
                   const conica_status *st)
{
    char where[1024];
    problem_where(name, k, o, buf, len, p, v, where, sizeof where);
    if (v->problem == CONICA_SCAD_OUT_OF_RANGE) {
        if (k == IN_SVG)
            cli_error(PROG, where, "%s; the numbers are in %s, after unit conversion", st->message,
                      o->unit == U_PX ? "px" : o->unit == U_IN ? "in" : "mm");
        else
            cli_error(PROG, where, "%s", st->message);
        return 1;
    }
    if (!o->force) {
        cli_error(PROG, where, "%s (nothing written; --force writes it anyway)", st->message);
        return 1;
    }
    cli_warning(PROG, where, "%s (written anyway: --force)", st->message);
    return 0;
}

/* What every file of a run shares: the options, and the command line for
 * the header (a batch gives each file its own, see file_command()). */
typedef struct run_ctx {
    const options *o;
    int argc;
    char **argv;
} run_ctx;

/* One input to one output: the whole of a single-file run, and each file
 * of a batch (in a process of its own). */
static int profile_file(void *ctx, const char *in, const char *outp)
{
    const run_ctx *rcx = ctx;
    options o = *rcx->o;
    int argc = rcx->argc;
    char **argv = rcx->argv;
    int rc, exact = 0;
    char *buf = NULL, modbuf[CONICA_SCAD_MAX_MODULE_NAME + 1];
    size_t len = 0;
    conica_scad_profile prof[2], rounded;
    const conica_scad_profile *use;
    conica_scad_layout lay;
    conica_scad_violation viol;
    conica_status st;
    stats sx;
    struct timespec t0, t1;
    const char *name;

    o.in = in;
    o.out = outp;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    if (cli_read_file(PROG, o.in, o.max_input_given ? o.limits.max_bytes : cli_max_input(PROG),
                      &buf, &len) != 0)
        return CLI_EXIT_ERROR;
    name = strcmp(o.in, "-") == 0 ? "<stdin>" : o.in;
    kind k = detect(o.in, buf, len);
    if (k != IN_DXF && (o.nlayers || o.gap > 0 || o.dxf_open)) {
        free(buf);
        return cli_usage_error(PROG, "--layer, --gap and --open apply to DXF input only");
    }
    if (k != IN_SVG && (o.select || o.paint_given || (o.unit != U_DEFAULT && k != IN_DXF))) {
        free(buf);
        return cli_usage_error(PROG, "--units, --select and --paint apply to SVG input only "
                                     "(--units also to DXF)");
    }
    if (k == IN_SVG && o.levels >= 0 && o.paint_given) {
        free(buf);
        return cli_usage_error(PROG, "--paint applies to --tolerance (the painted region); "
                                     "--levels smooths each path's fill as it is");
    }
    if (k != IN_SVG && k != IN_DXF && o.fit != FIT_INSIDE) {
        free(buf);
        return cli_usage_error(PROG,
                               "--fit %s: %s input supports only --fit inside (for now; "
                               "--fit outside, middle and clearance need SVG or DXF input)",
                               fit_names[o.fit], k == IN_SPLINE ? "spline" : "point-normal");
    }
    if (!o.module_given) {
        int changed;
        default_module(o.in, modbuf, sizeof modbuf, &changed);
        o.module = modbuf;
        if (changed)
            cli_warning(PROG, name,
                        "the module is named '%s' (the file name made into an OpenSCAD "
                        "identifier; --module NAME sets it)",
                        modbuf);
    }
    memset(&sx, 0, sizeof sx);
    sx.levels = -1;
    conica_scad_profile_init(&prof[0]);
    conica_scad_profile_init(&prof[1]);
    conica_scad_profile_init(&rounded);
    conica_scad_layout_init(&lay);
    /* --fit clearance: an inside run, and an outside one for the holes */
    /* --levels on SVG smooths each path as it is (the region's booleans
     * need polygons): --fit clearance runs inside and outside there */
    int region = (k == IN_SVG && o.levels < 0) || k == IN_DXF;
    fit fits[2] = {o.fit == FIT_CLEARANCE ? FIT_INSIDE : o.fit, FIT_OUTSIDE};
    size_t nruns = o.fit == FIT_CLEARANCE && !region ? 2 : 1;
    if (region && k == IN_SVG)
        rc = load_svg_region(&o, name, buf, len, &prof[0], &sx);
    else if (k == IN_SVG)
        rc = load_svg(&o, name, buf, len, fits, nruns, prof, &sx);
    else if (k == IN_SPLINE)
        rc = load_spline(&o, name, buf, len, &prof[0], &sx);
    else if (k == IN_DXF)
        rc = load_dxf(&o, name, buf, len, &prof[0], &sx);
    else
        rc = load_points(&o, name, buf, len, &prof[0], &sx);
    if (rc != 0)
        goto fail;
    if (nruns == 2 &&
        (prof[0].ncontours != prof[1].ncontours || prof[0].ngroups != prof[1].ngroups)) {
        cli_error(PROG, name, "--fit clearance: the inside and outside runs have different "
                              "subpaths (%zu and %zu)",
                  prof[0].ncontours, prof[1].ncontours);
        goto fail;
    }

    /* out of range first (an overflowing area says nothing), then the
     * subpaths without area go, with a warning each */
    if (conica_scad_check_range(&prof[0], &viol, &st) != CONICA_OK) {
        invalid(name, k, &o, buf, len, &prof[0], &viol, &st);
        goto fail;
    }
    {
        drop_ctx dc;
        memset(&dc, 0, sizeof dc);
        dc.name = name;
        dc.quiet = prof[0].ncontours == 1;
        size_t before = prof[0].ncontours, dropped = 0;
        if (conica_scad_drop_empty(&prof[0], on_drop, &dc, &dropped, &st) != CONICA_OK) {
            status_error(name, &st);
            goto fail;
        }
        sx.skipped = dropped;
        if (prof[0].ncontours == 0) {
            if (dc.quiet)
                cli_error(PROG, dc.where, "%s; nothing to write", dc.first);
            else
                cli_error(PROG, name,
                          "nothing to write: none of the %zu subpaths encloses an area", before);
            goto fail;
        }
    }
    if (nruns == 2) {
        /* which contours are holes, from the inside run's arrangement */
        size_t taken = 0;
        if (conica_scad_validate(&prof[0], o.revolve, &viol, &st) != CONICA_OK &&
            invalid(name, k, &o, buf, len, &prof[0], &viol, &st))
            goto fail;
        if (conica_scad_arrange(&prof[0], &lay, &st) != CONICA_OK) {
            status_error(name, &st);
            goto fail;
        }
        if (take_holes(&prof[0], &lay, &prof[1], name, &taken) != 0)
            goto fail;
        conica_scad_profile_free(&prof[1]);
        conica_scad_layout_free(&lay);
        conica_scad_layout_init(&lay);
    }

    /* the written digits: within tolerance/1000 of each point (--levels:
     * exact); what is validated and arranged is what is written */
    use = &prof[0];
    exact = o.levels >= 0;
    if (!exact) {
        double h = o.tolerance * CONICA_SCAD_ROUND_FRACTION / sqrt(2.0);
        if (conica_scad_round(&prof[0], h, &rounded, &st) != CONICA_OK) {
            status_error(name, &st);
            goto fail;
        }
        use = &rounded;
    }
    if (conica_scad_validate(use, o.revolve, &viol, &st) != CONICA_OK) {
        conica_scad_violation v0;
        conica_status st0;
        if (use == &rounded) {
            if (conica_scad_validate(&prof[0], o.revolve, &v0, &st0) == CONICA_OK) {
                char step[40];
                conica_scad_format_double(o.tolerance * CONICA_SCAD_ROUND_FRACTION, step,
                                          sizeof step);
                cli_warning(PROG, name,
                            "coordinates rounded to within %s (tolerance/1000) would make the "
                            "profile invalid (%s); written exactly instead",
                            step, st.message);
                exact = 1;
                use = &prof[0];
                viol.problem = CONICA_SCAD_OK;
            } else {
                /* the problem is the geometry's: report it in its own numbers */
                exact = 1;
                use = &prof[0];
                viol = v0;
                st = st0;
            }
        }
        if (viol.problem != CONICA_SCAD_OK && invalid(name, k, &o, buf, len, use, &viol, &st))
            goto fail;
    }
    if (conica_scad_arrange(use, &lay, &st) != CONICA_OK) {
        status_error(name, &st);
        goto fail;
    }
    {
        char *header = header_text(argc, argv, &o, kinds_of(k), exact, &sx, k == IN_SVG && o.levels < 0);
        conica_scad_write_options wo = conica_scad_write_defaults();
        cli_output out;
        if (!header) {
            cli_error(PROG, NULL, "out of memory");
            goto fail;
        }
        wo.module = o.module;
        wo.header = header;
        wo.extrude = o.extrude;
        wo.extrude_height = o.height;
        wo.revolve = o.revolve;
        wo.revolve_angle = o.angle;
        /* --extrude / --rotate-extrude make a file that renders the solid
         * alone, as before --demo-call existed (scripts/demo-scad.sh) */
        wo.instantiate = o.demo_call == 1 || (o.demo_call < 0 && (o.extrude || o.revolve));
        if (cli_output_open(PROG, o.out, &out) != 0) {
            free(header);
            goto fail;
        }
        if (conica_scad_write(out.f, use, &lay, &wo, &st) != CONICA_OK) {
            cli_output_abort(&out);
            free(header);
            cli_error(PROG, o.out ? o.out : "<stdout>", "%s", st.message);
            goto fail;
        }
        free(header);
        if (cli_output_commit(PROG, &out) != 0)
            goto fail;
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (o.stats) {
        size_t pts = 0;
        for (size_t i = 0; i < lay.npaths; i++)
            pts += use->contours[lay.paths[i].contour].n;
        if (k == IN_SVG)
            fprintf(stderr, PROG ": input SVG, %zu element%s, %zu closed subpath%s", sx.elements,
                    cli_plural(sx.elements), sx.subpaths, cli_plural(sx.subpaths));
        else if (k == IN_DXF)
            fprintf(stderr, PROG ": input DXF, %zu entit%s, %zu closed contour%s", sx.elements,
                    sx.elements == 1 ? "y" : "ies", sx.subpaths, cli_plural(sx.subpaths));
        else
            fprintf(stderr, PROG ": input %s, %zu input points", sx.kind ? sx.kind : "?",
                    sx.input_points);
        fprintf(stderr, "; %zu dense points%s", sx.dense_points,
                o.flatten_only ? " (flatten only)" : "");
        if (sx.levels >= 0)
            fprintf(stderr, "; level %d", sx.levels);
        if (sx.skipped)
            fprintf(stderr, "; %zu without area skipped", sx.skipped);
        fprintf(stderr,
                "\n" PROG ": %zu points written in %zu paths (%zu outer, %zu holes, %zu dropped), "
                "convexity %d; %.3f ms\n",
                pts, lay.npaths, lay.outers, lay.holes, lay.dropped, lay.convexity,
                1e3 * ((double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec)));
    }
    conica_scad_layout_free(&lay);
    conica_scad_profile_free(&prof[0]);
    conica_scad_profile_free(&prof[1]);
    conica_scad_profile_free(&rounded);
    free(buf);
    free(o.dxf_note);
    return CLI_EXIT_OK;
fail:
    free(buf);
    free(o.dxf_note);
    conica_scad_layout_free(&lay);
    conica_scad_profile_free(&prof[0]);
    conica_scad_profile_free(&prof[1]);
    conica_scad_profile_free(&rounded);
    return CLI_EXIT_ERROR;
}

/* The command line that makes one file of a batch alone: the options as
 * given, -o's value replaced by out, and in at the end (fresh argv; the
 * strings are the caller's). NULL when out of memory. */
static char **file_command(int argc, char **argv, const options *o, const char *in,
                           const char *out, int *n)
{
    char **v = malloc(((size_t)argc + 2) * sizeof *v);
    size_t k = 0;
    if (!v)
        return NULL;
    for (int i = 0; i < argc; i++) {
        int is_input = 0;
        for (size_t j = 0; j < o->ninputs && !is_input; j++)
            is_input = o->inputs[j] == argv[i];
        if (is_input || (strcmp(argv[i], "--") == 0 && i > 0))
            continue;
        if (i == o->out_arg && o->out_attached)
            v[k++] = (char *)"-o"; /* -oDIR/ or --output=DIR/: -o FILE */
        v[k++] = i == o->out_arg ? (char *)out : argv[i];
    }
    v[k++] = (char *)in;
    *n = (int)k;
    return v;
}

static int profile_batch_file(void *ctx, const char *in, const char *out)
{
    const run_ctx *b = ctx; /* the whole command line */
    run_ctx r;
    int n, rc;
    char **v = file_command(b->argc, b->argv, b->o, in, out, &n);
    if (!v)
        return cli_error(PROG, in, "out of memory");
    r.o = b->o;
    r.argc = n;
    r.argv = v;
    rc = profile_file(&r, in, out);
    free(v);
    return rc;
}

int main(int argc, char **argv)
{
    options o;
    int exit_now = 0, rc;

    if ((rc = parse_args(argc, argv, &o, &exit_now)) != 0 || exit_now) {
        free(o.inputs);
        free(o.argv0);
        free(o.layers);
        return rc;
    }
    if (o.ninputs > 1 || (o.out && o.out[strlen(o.out) - 1] == '/')) {
        cli_batch b;
        cli_batch_spec spec;
        run_ctx bc;
        memset(&spec, 0, sizeof spec);
        spec.outdir = o.out;
        spec.ext = ".svg";
        spec.out_ext = ".scad";
        bc.o = &o;
        bc.argc = argc;
        bc.argv = o.argv0;
        cli_batch_init(&b);
        b.progress = o.progress;
        rc = cli_batch_plan(PROG, o.inputs, o.ninputs, &spec, &b);
        if (rc == 0)
            rc = cli_batch_run(PROG, &b, o.jobs ? o.jobs : cli_batch_default_jobs(),
                               profile_batch_file, &bc);
        cli_batch_free(&b);
    } else {
        run_ctx r;
        r.o = &o;
        r.argc = argc;
        r.argv = o.argv0;
        rc = profile_file(&r, o.in, o.out);
    }
    free(o.inputs);
    free(o.argv0);
    free(o.layers);
    return rc;
}

/* SPDX-License-Identifier: MIT */
/* Visual diagnostics shared by `conica combs`, `conica errors` and
 * bench/bench_ablation (issue 9): curvature combs (CONIS §2.2,
 * Code 3), conic and normal errors (Section 3.2, eqs. (13)-(14)) and a
 * small SVG writer (viewBox, y flipped, compact fixed-point numbers that do
 * not depend on the C locale). Internal to the command-line tools. */
#ifndef CONICA_PLOTSVG_H
#define CONICA_PLOTSVG_H

#include <stddef.h>
#include <stdio.h>

#include "conica/curve.h"
#include "conica/subdiv.h"

/* Auto comb scale: the largest tooth is this fraction of the curve's size
 * (the larger side of its bounding box). */
#define PLOTSVG_COMB_FRACTION 0.15
/* Fraction of teeth left out when choosing the auto scale, and how much
 * longer than the largest regular tooth a spike may be drawn. */
#define PLOTSVG_COMB_OUTLIERS 0.02
#define PLOTSVG_COMB_CLIP 2.0
/* Default cap on drawn teeth (every vertex still shapes the comb outline);
 * keeps an SVG of a level-12 curve small. */
#define PLOTSVG_DEFAULT_MAX_TEETH 2000
/* Polylines are thinned where straight to within this many pixels, in runs
 * of at most PLOTSVG_SIMPLIFY_RUN vertices (bounds the work per vertex). */
#define PLOTSVG_SIMPLIFY_PX 0.1
#define PLOTSVG_SIMPLIFY_RUN 64
/* Upper bound a user may ask for with --max-teeth. */
#define PLOTSVG_MAX_TEETH_LIMIT 1000000

/* Read and parse the point-normal file path ('-' = stdin) into *c with the
 * given closed flag; errors go to stderr as `prog: error: FILE:LINE: what`.
 * Returns 0, or 1 after printing an error. */
int plotsvg_load_curve(const char *prog, const char *path, int closed, conica_curve *c);

/* ------------------------------------------------------------ curvature */

/* Curvature 1/R of the circle through a, b, c (CONIS, Code 3, in
 * double, times the factor 2 Code 3 leaves out); 0 when two of the points
 * coincide. */
double plotsvg_curvature(const double a[2], const double b[2], const double c[2]);

/* kappa[i] at every vertex from its two neighbours (closed: all vertices;
 * open: the two end vertices get NAN, they have no osculating circle).
 * With signed_comb, kappa is negative where the curve bends towards its
 * normal nxy[i] (so a comb drawn along the normal flips side at an
 * inflection); otherwise it is the CONIS paper's unsigned 1/R. Returns the
 * largest |kappa| (0 if none). */
double plotsvg_curvatures(const double *xy, const double *nxy, size_t n, int closed,
                          int signed_comb, double *kappa);

/* Largest side of the bounding box of n points (0 for fewer than 2). */
double plotsvg_size(const double *xy, size_t n);

/* Auto comb scale (tooth length per unit curvature): the largest tooth is
 * PLOTSVG_COMB_FRACTION of size, where "largest" ignores the top
 * PLOTSVG_COMB_OUTLIERS fraction of teeth, so that a few spikes (e.g. next to
 * an inflection point) do not flatten the rest of the comb; *max_len gets
 * the length those spikes are cut at (PLOTSVG_COMB_CLIP times the largest).
 * Needs n scratch doubles in tmp. Returns 0 when the curve is straight. */
double plotsvg_comb_scale(const double *kappa, size_t n, double size, double *tmp,
                          double *max_len);

/* Comb tooth tips tips[i] = p_i + scale * kappa_i * n_i (CONIS, Section
 * 2.2); a tooth longer than max_len (if > 0) is cut to max_len so that one
 * wild spike does not flatten the picture. NAN kappa gives a NAN tip. */
void plotsvg_comb_tips(const double *xy, const double *nxy, const double *kappa, size_t n,
                       double scale, double max_len, double *tips);

/* Noise of the comb: median over vertices of the second difference
 * |kappa_{i-1} - 2 kappa_i + kappa_{i+1}|, divided by the median |kappa|.
 * Medians, so a few genuine spikes (next to inflection points) do not
 * decide it; a fair curve at a fine level scores near 0, numerical noise of
 * the kind CONIS Figure 6 shows scores high. tmp: n scratch doubles. */
double plotsvg_comb_roughness(const double *kappa, size_t n, int closed, double *tmp);

/* --------------------------------------------------------------- errors */

/* A conic in the order of CONIS, eq. (3):
 * f(x,y) = q20 x^2 + q02 y^2 + 2 q11 xy + 2 q10 x + 2 q01 y + q00. */
typedef struct plotsvg_conic {
    double q20, q02, q11, q10, q01, q00;
} plotsvg_conic;

/* Mean and max of |f(p)| / |grad f(p)| over the points (eqs. (13)-(14)),
 * evaluated in long double. Points where the gradient vanishes count as
 * infinite error. */
void plotsvg_conic_error(const plotsvg_conic *q, const double *xy, size_t n, double *mean,
                         double *max);
void plotsvg_conic_errorl(const plotsvg_conic *q, const long double *xy, size_t n, double *mean,
                          double *max);

/* Mean and max angle in degrees between each normal of c and the normal
 * estimated from c's points alone (area-weighted, CONIS Section 3.2).
 * The estimate's orientation is matched to c's by the sign of the summed
 * dot products. Returns 0, or -1 if estimation fails (degenerate curve). */
int plotsvg_normal_error(const conica_curve *c, double *mean_deg, double *max_deg);

/* The numerics ablation of CONIS §3.2, as run-time settings of
 * the one implementation: "base" (double, normals normalised every level,
 * plain quadratic formula), "norm-skip" (no normalisation, plain formula),
 * "final" (our defaults: no normalisation, Kahan/FMA root), "precise" (final
 * in long double). Returns 0, or -1 for an unknown name. */
int plotsvg_variant(const char *name, conica_subdiv_settings *s);

/* What one subdivision level measures. */
typedef struct plotsvg_errors {
    size_t points;         /* n_k */
    double e_mean, e_max;  /* eqs. (13)-(14); NAN without a conic */
    double n_mean, n_max;  /* normal angle error, degrees */
} plotsvg_errors;

/* Subdivide in (s->levels levels; long double output when s->precise) and
 * measure it against the conic q (may be NULL). Returns the subdivision's
 * code; st carries its message. */
conica_code plotsvg_measure(const conica_curve *in, const conica_subdiv_settings *s,
                            const plotsvg_conic *q, plotsvg_errors *e, conica_status *st);

/* ------------------------------------------------------------ SVG writer */

/* World -> picture map: px = x0 + s*x, py = y0 - s*y (y flipped so the
 * picture is not mirrored). */
typedef struct plotsvg_frame {
    double x0, y0, s;
} plotsvg_frame;

/* Frame fitting the world box {minx, miny, maxx, maxy} centred in the
 * picture rectangle (px, py, pw, ph), aspect kept. */
plotsvg_frame plotsvg_fit(const double box[4], double px, double py, double pw, double ph);

/* Grow box {minx, miny, maxx, maxy} by the finite points (box starts as
 * {+inf, +inf, -inf, -inf} from plotsvg_box_empty). */
void plotsvg_box_empty(double box[4]);
void plotsvg_box_add(double box[4], const double *xy, size_t n);

/* Document start and end; width/height in px, viewBox 0 0 width height. */
void plotsvg_begin(FILE *f, double width, double height, const char *title);
void plotsvg_end(FILE *f);

/* One <path> through n points (closed adds Z); non-finite points break the
 * line; vertices within PLOTSVG_SIMPLIFY_PX of a straight run are left out. attrs is raw attribute text (style), e.g. `stroke="#000"`. */
void plotsvg_path(FILE *f, const plotsvg_frame *fr, const double *xy, size_t n, int closed,
                  const char *attrs);

/* One <path> of segments base[i] -> tip[i], at most max_teeth of them
 * (evenly strided), skipping non-finite tips. */
void plotsvg_teeth(FILE *f, const plotsvg_frame *fr, const double *base, const double *tips,
                   size_t n, size_t max_teeth, const char *attrs);

/* <text> at picture coordinates, XML-escaped. anchor: start|middle|end. */
void plotsvg_text(FILE *f, double x, double y, double size, const char *anchor,
                  const char *text);

/* A comb panel: control polygon (dashed grey), refined curve, teeth and the
 * joined comb outline (tips connected), into the picture rectangle. */
void plotsvg_comb_panel(FILE *f, double px, double py, double pw, double ph,
                        const conica_curve *control, const conica_curve *refined,
                        const double *tips, size_t max_teeth, const char *title);

/* One series of a chart. */
typedef struct plotsvg_series {
    const char *label;
    const double *x, *y;
    size_t n;
    const char *color;
    int dashed;
} plotsvg_series;

/* Line chart with a log-scale y axis (decade ticks) and linear x axis in the
 * rectangle (px, py, pw, ph); non-positive or non-finite y values are left
 * out (the line breaks there). */
void plotsvg_logchart(FILE *f, double px, double py, double pw, double ph, const char *title,
                      const char *xlabel, const char *ylabel, const plotsvg_series *s,
                      size_t ns);

#endif

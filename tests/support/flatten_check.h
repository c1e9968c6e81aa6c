/* SPDX-License-Identifier: MIT */
/* An exact-by-dense-search checker of flattened B-splines and the greedy
 * reference it defines, independent of the plotters (tests/test_plot.c,
 * bench/bench_flatten.c). It only evaluates the curve (conica_bspline_eval)
 * and measures distances; it never looks at a certificate.
 *
 * True deviation of a chord [f(ua), f(ub)]: the largest distance of f(u),
 * u in [ua, ub], to the segment, found by FC_SAMPLES samples and a
 * golden-section refinement around the largest two. For a chord whose
 * ends are on the curve this bounds the other direction too (every point
 * of the segment is the nearest-point projection of some f(u)), but the
 * checker measures that direction separately as well. */
#ifndef CONICA_FLATTEN_CHECK_H
#define CONICA_FLATTEN_CHECK_H

#include <stddef.h>

#include "conica/bspline.h"
#include "conica/plot.h"

/* Samples per chord of the dense search (each refined, see above). */
#define FC_SAMPLES 96

/* Point of s at t in plot coordinates ((t, f(t)) for a function), out[3]. */
void fc_point(const conica_bspline *s, double t, double *out);
/** Distance from the 3-D point q to the segment [a, b]. */
double fc_dist_seg(const double *q, const double *a, const double *b);

/* Largest distance of `samples` + 1 equally spaced points of the planar
 * curve s (over its domain) to the polyline xy[0..n) (points without
 * parameters, e.g. another library's). */
double fc_curve_to_polyline(const conica_bspline *s, const double *xy, size_t n, int samples);

/* Largest distance of f([ua, ub]) to the segment [f(ua), f(ub)]. */
double fc_chord_dev(const conica_bspline *s, double ua, double ub);

/* Largest distance of a point of the segment [f(ua), f(ub)] to f([ua, ub])
 * (nearest arc point by dense search and refinement). */
double fc_chord_dev_back(const conica_bspline *s, double ua, double ub);

/* Points of the greedy reference: from each point the longest chord whose
 * true deviation is at most tol (first failure found by doubling, then
 * bisection to 1e-9 of the domain), vertices on the curve. */
size_t fc_greedy(const conica_bspline *s, double tol);

/* Largest deviation, both directions, of a plot whose points carry their
 * parameters (pl->t), chord by chord within each piece; *worst_back gets
 * the polyline -> curve direction (may be NULL). Returns -1 when pl->t is
 * NULL. */
double fc_plot_dev(const conica_bspline *s, const conica_polyline *pl, double *worst_back);

/* Guaranteed plot of s at absolute tolerance tol into *pl (replaced). */
conica_code fc_plot(const conica_bspline *s, double tol, conica_polyline *pl);

/* The kind of curve set: the thesis curves sptest0..4 (from
 * splines_dir, skipped when it is NULL or they are absent), the four
 * examples/ .spl files (from examples_dir), nrandom random B-splines of degrees
 * 2-7 (fixed seed), three rational ones and two near-cusps. */
#define FC_SET_MAX 128
typedef struct fc_set {
    size_t n, thesis; /* thesis: how many thesis curves were found */
    conica_bspline s[FC_SET_MAX];
    char name[FC_SET_MAX][40];
} fc_set;

void fc_set_make(fc_set *set, const char *splines_dir, const char *examples_dir, size_t nrandom);
void fc_set_free(fc_set *set);

#endif

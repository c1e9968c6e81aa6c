/* SPDX-License-Identifier: MIT */
/* Internal plumbing shared by plot*.c and surface.c. */
#ifndef CONICA_PLOT_INTERNAL_H
#define CONICA_PLOT_INTERNAL_H

#include <stddef.h>

#include "conica/plot.h"

/* Continuous pieces of a spline (Section 1.1.2, check_continuous): each
 * clamped to its domain, interior knot multiplicities <= p-1 (p at kept G1 joins, see below). joined[k] is
 * 1 when piece k starts where piece k-1 ends (C0 join), so the output keeps
 * one polyline piece. */
typedef struct conica__pieces {
    size_t count;
    conica_bspline *sp;
    int *joined;
} conica__pieces;

/* Split s. With graph != 0 a spline function becomes the planar curve
 * (t, f(t)) with control points (t*_j, c_j) (exact by linear precision;
 * rational functions are refused with CONICA_ERR_UNSUPPORTED). With
 * keep_g1, a curve is not split at a knot of multiplicity p where it is
 * tangent-continuous (the joins of a NURBS circle): the guaranteed
 * plotter's chords may cross it (its certificate needs only C0 inside a
 * piece), so the piece ends cost no extra points; the piece then keeps
 * that knot of multiplicity p. */
conica_code conica__pieces_make(const conica_bspline *s, int graph, int keep_g1,
                                conica__pieces *out, conica_status *st);
void conica__pieces_free(conica__pieces *pc);

/* Output accumulation with the max_points cap. */
typedef struct conica__out {
    conica_polyline pl;
    size_t max_points;
    /* 1: pl.xy and pl.t (may be NULL) are the caller's arrays of
     * max_points entries, never reallocated (conica_plot_bezier) */
    int fixed;
} conica__out;

void conica__out_init(conica__out *o, int dim, size_t max_points);
/* Start a new output piece unless `joined` (then the next point, equal to
 * the last one, is skipped by the caller via conica__out_push_join). */
conica_code conica__out_piece(conica__out *o, conica_status *st);
/* Append a point; t is its parameter on the curve, NAN when it has none.
 * Inline for the common case (room left; 15 calls per cubic piece of
 * conica_plot_bezier at T = 0.1, where the call was 6% of the time);
 * growing the arrays and the max_points error are conica__out_grow's. */
conica_code conica__out_grow(conica__out *o, const double *pt, double t, conica_status *st);
static inline conica_code conica__out_push(conica__out *o, const double *pt, double t,
                                           conica_status *st)
{
    size_t n = o->pl.n, d = (size_t)o->pl.dim;
    if (n >= o->max_points || (!o->fixed && n == o->pl.cap))
        return conica__out_grow(o, pt, t, st);
    if (d == 2) { /* planar: no loop (the guaranteed march's points) */
        o->pl.xy[2 * n] = pt[0];
        o->pl.xy[2 * n + 1] = pt[1];
    } else {
        for (size_t i = 0; i < d; i++)
            o->pl.xy[n * d + i] = pt[i];
    }
    if (o->pl.t)
        o->pl.t[n] = t;
    o->pl.n = n + 1;
    return CONICA_OK;
}

/* Point of s at t in plot coordinates: (t, f(t)) for a function. */
void conica__plot_point(const conica_bspline *s, double t, double *out);

/* Method implementations: each plots all pieces into o, adding flops,
 * knots and iterations to *stats. tol is the absolute tolerance. */
conica_code conica__plot_guaranteed(const conica__pieces *pc, const conica_plot_settings *set,
                                    double tol, conica__out *o, conica_plot_stats *stats,
                                    conica_status *st);
conica_code conica__plot_adaptive(const conica__pieces *pc, const conica_plot_settings *set,
                                  double tol, conica__out *o, conica_plot_stats *stats,
                                  conica_status *st);
conica_code conica__plot_baseline(const conica__pieces *pc, const conica_plot_settings *set,
                                  double tol, conica__out *o, conica_plot_stats *stats,
                                  conica_status *st);

/* Guaranteed plot of one continuous piece returning its parameters too
 * (used by surfaces): params (may be NULL) receives the parameter of each
 * emitted point; *np their count. Points go to o when o != NULL. */
conica_code conica__guaranteed_piece(const conica_bspline *g, double tol,
                                     const conica_plot_settings *set, int first_is_join,
                                     conica__out *o, double **params, size_t *np,
                                     conica_plot_stats *stats, conica_status *st);

/* Turning angle at q between a->q and q->b, eq. (3.15) (0 when a segment
 * is degenerate). */
double conica__turn_angle(const double *a, const double *q, const double *b, int d);

/* Bounding-box diagonal of the control points (Delta c of eq. (3.26)). */
double conica__ctrl_diagonal(const conica_bspline *s);

double conica__now(void);

/* Planar rational quadratics (plot_conic.c). conica__r2_absmax: the
 * largest |sum B_i w_i s_i / sum B_i w_i| over [0, 1] (quadratic
 * Bernstein B_i, w_i > 0), exact. conica__r2_step: for a remainder R of
 * three homogeneous points (x w, y w, w), the lam in (0, 1] where the
 * distance of the arc [0, lam] to its chord's line is T (2 when the whole
 * remainder is within T), from the guess lam (<= 0: none); *evals counts
 * the steps. */
double conica__r2_absmax(const double *s, const double *w);
double conica__r2_step(const double *R, double T, double lam, size_t *evals);

#endif

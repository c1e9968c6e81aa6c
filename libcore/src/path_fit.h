/* SPDX-License-Identifier: MIT */
/* One-sided flattening of a closed drawn subpath (path_fit.c): a polygon
 * that lies within a region the caller knows, or contains it, within the
 * tolerance of the drawn curve, by construction rather than by moving
 * chords after the fact. */
#ifndef CONICA_PATH_FIT_H
#define CONICA_PATH_FIT_H

#include "conica/path.h"

/* Which way the polygon may leave the drawn curve. */
typedef enum conica__fit_side {
    CONICA__FIT_CHORDS = 0, /* vertices on the curve, chords within the tolerance both ways */
    CONICA__FIT_IN,         /* the polygon within the painted region */
    CONICA__FIT_OUT         /* the polygon contains the painted region */
} conica__fit_side;

/* Which side of the curve is painted near `pt`: +1 the side to the left of
 * the direction of travel `dir` (y up), -1 the right, 0 neither or both
 * (the curve bounds nothing there); dir NULL: 1 when pt itself is painted,
 * else 0. */
typedef int (*conica__painted_fn)(void *ctx, const double pt[2], const double dir[2]);

/* The polygon of subpath `sub` of p (a DRAWN subpath; an open one is
 * closed by a straight edge, as a fill closes it): every curve split at its
 * inflections; on each stretch that turns one way chords (vertices on the
 * curve) where they lie on the wanted side, else the polygon of tangent
 * lines (vertices where consecutive tangents meet), each piece within `tol`
 * of the curve both ways. Segment ends (corners, straight edges, inflection
 * points) are vertices, exactly as drawn. `painted` decides the side per
 * stretch (ignored for CONICA__FIT_CHORDS; NULL or 0: chords).
 * Appends 2 * (new points) doubles to *xy (grown with realloc, *cap its
 * capacity in points) and adds their number to *n; at most max_points in
 * all.
 * Returns CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_LIMIT, CONICA_ERR_NOMEM. */
conica_code conica__path_fit(const conica_path *p, size_t sub, double tol, conica__fit_side side,
                             conica__painted_fn painted, void *ctx, size_t max_points,
                             double **xy, size_t *n, size_t *cap, conica_status *st);

/* The polyline of subpath `sub` as drawn (open or closed), vertices on the
 * curve, chords within tol: the centre line of a stroke. A closed subpath
 * does not repeat its first point. Each curved segment also gets a point a
 * short way along each end tangent (within tol of the curve), so that caps
 * and corner joins of the polyline's stroke are square to the exact
 * tangents. No chord turns by more than max_turn radians (> 0; a stroke's
 * miter joins between chords overshoot its offset curve by half-width
 * (1 / cos(turn / 2) - 1); <= 0: no limit beyond the fit's own). Other
 * arguments as conica__path_fit(). */
conica_code conica__path_chords(const conica_path *p, size_t sub, double tol, double max_turn,
                                size_t max_points, double **xy, size_t *n, size_t *cap,
                                conica_status *st);

/* Parameters in (0, 1) where drawn segment `seg` changes its turning
 * direction (inflections and cusps), ascending, at most cap (path.c: the
 * engine's own test, judged to rounding). */
size_t conica__path_seg_inflections(const conica_path *p, size_t seg, double *out, size_t cap);

#endif

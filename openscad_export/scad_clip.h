/* SPDX-License-Identifier: MIT */
/* Polygon booleans and offsets for scadprofile's regions: a C face on
 * Clipper (libpolyclipping, Angus Johnson's library, the one OpenSCAD uses
 * for its own 2D geometry), in scad_clip.cpp. Nothing here throws: every
 * Clipper or allocation failure becomes a status.
 *
 * Coordinates are doubles; each call rounds them to integers at `scale`
 * units per unit (the caller picks a power of two, conica__clip_scale()),
 * and every output vertex that is an input vertex gets that input's exact
 * doubles back, so corners and the input's own numbers survive a boolean
 * unchanged; new vertices (intersections, offsets) move by at most
 * 0.5 sqrt(2) / scale. */
#ifndef CONICA_SCAD_CLIP_H
#define CONICA_SCAD_CLIP_H

#include <stddef.h>

#include "conica/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A set of closed polygons (or open polylines for strokes), each with its
 *  points in xy[2 * start[i] .. 2 * start[i + 1]). */
typedef struct conica__polys {
    size_t n, cap;     /* polygons */
    size_t *start;     /* n + 1 entries when n > 0 */
    size_t npts, ptcap;
    double *xy;
} conica__polys;

void conica__polys_init(conica__polys *p);
void conica__polys_free(conica__polys *p);
/* Append a polygon of n points (0 on success, -1 out of memory). */
int conica__polys_add(conica__polys *p, const double *xy, size_t n);
/* Append every polygon of q. */
int conica__polys_append(conica__polys *p, const conica__polys *q);
/* Twice the signed area of polygon i (counter-clockwise in y-up > 0). */
double conica__polys_area2(const conica__polys *p, size_t i);
/* Largest |coordinate| (0 when empty). */
double conica__polys_max_abs(const conica__polys *p);
/* Winding number of (x, y) summed over every polygon (points on an edge
 * count as either side). */
int conica__polys_winding(const conica__polys *p, double x, double y);
/* What the edge u -> v adds to the winding number of (x, y): +1, -1 or 0
 * (the rule of conica__polys_winding(), for callers with their own edge
 * lists). */
int conica__winding_step(const double *u, const double *v, double x, double y);

/* Largest coordinate Clipper takes (its hiRange is 2^62 - 1), with room for
 * offsets. */
#define CONICA__CLIP_MAX_INT 2.3e18

/* The power-of-two scale whose rounding moves a new vertex by at most
 * `frac` of `tol` (0.5 sqrt(2) / scale <= frac tol), or, when coordinates of
 * size max_abs would not fit at that scale, 0. */
double conica__clip_scale(double tol, double frac, double max_abs);

typedef enum conica__clip_op {
    CONICA__CLIP_UNION = 0,
    CONICA__CLIP_INTERSECTION,
    CONICA__CLIP_DIFFERENCE /* a minus b */
} conica__clip_op;

/* How a polygon set is filled (SVG's fill-rule). */
typedef enum conica__clip_fill {
    CONICA__CLIP_NONZERO = 0,
    CONICA__CLIP_EVENODD
} conica__clip_fill;

/* The region `in` fills under `rule` as polygons that do not cross:
 * outlines counter-clockwise, holes clockwise (y up), so the result means
 * the same under nonzero. strict: also none touching itself (Clipper's
 * strictly simple output, slower; what the writer needs). */
conica_code conica__clip_fill_region(const conica__polys *in, conica__clip_fill rule, double scale,
                                     int strict, conica__polys *out, conica_status *st);

/* a op b, both read under nonzero; output as conica__clip_fill_region()
 * (not strict). */
conica_code conica__clip_bool(conica__clip_op op, const conica__polys *a, const conica__polys *b,
                              double scale, conica__polys *out, conica_status *st);

typedef enum conica__clip_join {
    CONICA__CLIP_JOIN_MITER = 0,
    CONICA__CLIP_JOIN_ROUND,
    CONICA__CLIP_JOIN_SQUARE
} conica__clip_join;

typedef enum conica__clip_end {
    CONICA__CLIP_END_POLYGON = 0, /* a region grown (delta > 0) or shrunk */
    CONICA__CLIP_END_CLOSED_LINE, /* the stroke of a closed subpath */
    CONICA__CLIP_END_BUTT,
    CONICA__CLIP_END_SQUARE,
    CONICA__CLIP_END_ROUND
} conica__clip_end;

/* Offset by delta (> 0 grows; a line's stroke has half-width delta): miter
 * joins up to miterlimit * delta from the vertex, round joins and ends
 * within arctol of the true arc. The result is unioned (nonzero), output as
 * conica__clip_fill_region() (not strict). */
conica_code conica__clip_offset(const conica__polys *in, conica__clip_end end,
                                conica__clip_join join, double miterlimit, double delta,
                                double arctol, double scale, conica__polys *out,
                                conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

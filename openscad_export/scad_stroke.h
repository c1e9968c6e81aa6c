/* SPDX-License-Identifier: MIT */
/* The stroke of a polyline as convex pieces (scad_stroke.c). */
#ifndef CONICA_SCAD_STROKE_H
#define CONICA_SCAD_STROKE_H

#include "scad_clip.h"

typedef enum conica__stroke_join {
    CONICA__JOIN_MITER = 0,
    CONICA__JOIN_ROUND,
    CONICA__JOIN_BEVEL
} conica__stroke_join;

typedef enum conica__stroke_cap {
    CONICA__CAP_BUTT = 0,
    CONICA__CAP_ROUND,
    CONICA__CAP_SQUARE
} conica__stroke_cap;

typedef struct conica__stroke_style {
    double half_width;  /* > 0 */
    conica__stroke_join join;
    conica__stroke_cap cap;
    double miterlimit;  /* >= 1 */
    double arctol;      /* round pieces: chords within this of the arc (inside it) */
    double max_turn;    /* vertices turning by at most this (radians) are a curve's chords:
                           round pieces there */
} conica__stroke_style;

/* Append the pieces of the stroke of xy (n points; closed: the last joins
 * the first) to out, each convex and counter-clockwise (y up): their
 * nonzero union is the stroke. 0, or -1 when out of memory. */
int conica__scad_stroke(const double *xy, size_t n, int closed, const conica__stroke_style *s,
                        conica__polys *out);

#endif

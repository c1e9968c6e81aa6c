/* SPDX-License-Identifier: MIT */
/* What an SVG scene paints, as one region for scadprofile (scad_region.c):
 * fills under their fill rule and strokes as areas, clipped by their
 * viewports and unioned in the output frame (y up), fitted to one side of
 * the drawn region and checked against a dense polygon of it before
 * anything is written. A drawing already in the path model (DXF) takes
 * the same fit and check. */
#ifndef CONICA_SCAD_REGION_H
#define CONICA_SCAD_REGION_H

#include "conica_svg_render.h"
#include "scad_clip.h"

/* What of each item becomes material (--paint). */
typedef enum conica__paint {
    CONICA__PAINT_AS_DRAWN = 0, /* its fill and its stroke where painted: what a browser shows */
    CONICA__PAINT_FILL,         /* the fill of every item, painted or not */
    CONICA__PAINT_STROKE,       /* the stroke of every item */
    CONICA__PAINT_BOTH          /* both of every item */
} conica__paint;

/* Which side of the drawn region the polygon keeps to (--fit). */
typedef enum conica__region_fit {
    CONICA__REGION_INSIDE = 0, /* within the painted region */
    CONICA__REGION_OUTSIDE,    /* contains it */
    CONICA__REGION_MIDDLE      /* within the tolerance both ways, fewest points */
} conica__region_fit;

/* Dense polygons of the drawn region are within this fraction of the
 * tolerance of it (the reference the fit is checked against). */
#define CONICA__REGION_DENSE_FRACTION (1.0 / 256.0)
/* The check allows the reference's own error and the booleans' rounding
 * on the side the fit must not cross: this fraction of the tolerance. */
#define CONICA__REGION_CHECK_SLACK (1.0 / 64.0)
/* Strokes: the centre line is flattened within this fraction of the
 * tolerance and round joins and caps within ARC of it; the offset is
 * moved by both towards the side the fit keeps to. */
#define CONICA__REGION_STROKE_LINE 0.25
#define CONICA__REGION_STROKE_ARC 0.125
/* The booleans' grid: a new vertex moves by at most this fraction of the
 * tolerance (the coarsest grid allowed), and the grid used where the
 * coordinates leave room for it (fine enough for the check's slack to
 * span many grid steps). */
#define CONICA__REGION_GRID_FRACTION 0.01
#define CONICA__REGION_GRID_FINE 3e-4
/* Where contours of the result meet at a vertex, each sector of material
 * there gets its own copy of it, moved this fraction of the tolerance into
 * the sector (well under the check's slack, also where the sector is a
 * needle whose sides are themselves up to the slack from the drawing). */
#define CONICA__REGION_TOUCH_FRACTION 0.004
/* The check's slack spans at least this many grid steps. */
#define CONICA__REGION_CHECK_STEPS 16.0

typedef struct conica__region_settings {
    double tolerance;          /* > 0, output units */
    conica__region_fit fit;
    conica__paint paint;
    size_t max_points;         /* cap on the points of one polygon set */
    conica_svg_warn_fn warn;   /* optional */
    void *warn_ctx;
} conica__region_settings;

typedef struct conica__region_stats {
    size_t fills, strokes;     /* items whose fill / stroke became material */
    size_t subpaths;           /* drawn subpaths read */
    size_t fit_points;         /* points of the fitted region */
    size_t dense_points;       /* points of the dense reference */
    double lost, gained;       /* largest distance (output units) by which the fit is
                                  inside / outside the reference, estimated by the check */
} conica__region_stats;

/* The region of scene sc in the output frame flipped to y up (y' = height
 * - y; height 0 when the scene has no size), fitted per s->fit and checked:
 * CONICA_ERR_DEGENERATE (st names where) when the fit lost or gained
 * material beyond the tolerance or on the wrong side, CONICA_ERR_LIMIT for
 * a cap or coordinates the booleans cannot take. out: outlines
 * counter-clockwise, holes clockwise, no two touching. */
conica_code conica__scad_region(const conica_svg_scene *sc, const conica__region_settings *s,
                                conica__polys *out, conica__region_stats *stats,
                                conica_status *st);

/* A drawing already in the path model (scadprofile's DXF contours): every
 * drawn subpath of path, in the output frame (y up), filled under rule.
 * The names are for messages: a subpath without area is warned about as
 * "NAME: PART K" at line sub_line[K - 1] (or line when there is none), and
 * an error in a subpath's fit gets that line. */
typedef struct conica__region_source {
    const conica_path *path;
    conica__clip_fill rule;
    const char *name;       /* "the drawing" */
    const char *part;       /* "contour" */
    size_t line;
    const size_t *sub_line; /* optional: nsub_line entries */
    size_t nsub_line;
} conica__region_source;

/* The region of src, fitted per s->fit and checked exactly as
 * conica__scad_region() does (s->paint is not read); same results. */
conica_code conica__scad_region_path(const conica__region_source *src,
                                     const conica__region_settings *s, conica__polys *out,
                                     conica__region_stats *stats, conica_status *st);

#endif

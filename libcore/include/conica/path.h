/* SPDX-License-Identifier: MIT */
/**
 * @file path.h
 * @brief Drawn curves in, what the engines need out: the one curve front end
 *        of every Conica tool.
 *
 * A path is a list of subpaths, each open or closed, made of drawn
 * segments: straight lines, polynomial or rational Bézier segments up to
 * CONICA_PATH_MAX_DEGREE (quadratic and cubic Béziers, elliptic arcs as
 * exact rational quadratics, the pieces of a NURBS curve), or a list of
 * samples to interpolate (a polygon, a Blender POLY spline, a point file).
 *
 * The drawn curve is the ground truth. conica_path_flatten() writes, per
 * subpath, a polyline within the fidelity tolerance of the drawn curve in
 * both directions (the guaranteed plotter). conica_path_smooth() writes the
 * polyline of a conic-preserving subdivision (the CONIS scheme of Bügel,
 * Romani and Kosinka) whose limit curve lies within the fidelity tolerance
 * of the drawn curve in both directions: each curved segment is sampled
 * with exact points and normals from its own derivatives (its end points,
 * its inflection points, its middle) and sampled again where the
 * subdivision of the samples strays; a segment that is a conic within the
 * tolerance keeps its few samples, so conics come out exact. Rules common
 * to every tool live here once:
 *
 *  - a join of two segments whose tangents turn by more than
 *    corner_angle is a corner and stays sharp;
 *  - straight segments stay straight, their end points are output points
 *    (a Bézier whose control points lie on its chord is straight);
 *  - tangency (G1 joins) and collinearity are judged to the precision the
 *    input was written with (settings.precision);
 *  - nothing drawn is dropped: only segments of zero size are skipped;
 *  - samples subpaths are interpolated as they are; inflections are not
 *    taken from differences below the input's rounding.
 *
 * Example:
 * @code
 *   conica_path p;
 *   conica_path_result r;
 *   conica_path_settings s = conica_path_defaults();
 *   double quarter[4] = {1, 1, 0, 1};            // control point, end point
 *   double w[3] = {1, 0.70710678118654752, 1};   // a quarter circle
 *   conica_path_init(&p);
 *   conica_path_result_init(&r);
 *   conica_path_move_to(&p, 1, 0, 0, NULL);
 *   conica_path_bezier_to(&p, 2, quarter, w, 1, NULL);
 *   conica_path_line_to(&p, 0, 0, 2, NULL);
 *   conica_path_close(&p, NULL);
 *   if (conica_path_smooth(&p, &s, &r, NULL) == CONICA_OK)
 *       printf("%zu points\n", r.lines[0].n);
 *   conica_path_result_free(&r);
 *   conica_path_free(&p);
 * @endcode
 */
#ifndef CONICA_PATH_H
#define CONICA_PATH_H

#include <stddef.h>

#include "conica/bspline.h"
#include "conica/common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CONICA_PATH_MAX_DEGREE 7 /**< highest Bézier degree of one segment */
/** Default fidelity tolerance: this fraction of a subpath's bounding-box diagonal. */
#define CONICA_PATH_DEFAULT_REL_TOLERANCE 1e-3
/** Default corner angle, degrees: a tangent turn above it is a corner. */
#define CONICA_PATH_DEFAULT_CORNER_DEG 40.0
/** Default subdivision levels of conica_path_smooth(). */
#define CONICA_PATH_DEFAULT_LEVELS 4
/** Default cap on the points of one result. */
#define CONICA_PATH_DEFAULT_MAX_POINTS ((size_t)1 << 26)
/** Cap on segments, subpaths and samples held by one path. */
#define CONICA_PATH_MAX_ITEMS ((size_t)1 << 28)

/** Kind of a subpath. */
typedef enum conica_path_kind {
    CONICA_PATH_DRAWN = 0, /**< drawn segments: the curve itself is the ground truth */
    CONICA_PATH_SAMPLES    /**< points (and optional normals) to interpolate */
} conica_path_kind;

/** One subpath (read-only for callers). */
typedef struct conica_path_subpath {
    conica_path_kind kind;
    int closed;          /**< closed by conica_path_close() or as samples */
    size_t first, n;     /**< DRAWN: its segments seg[first..first+n); SAMPLES: its samples */
    double x0, y0;       /**< its first point (a DRAWN subpath of no segment is this point) */
} conica_path_subpath;

/** One drawn segment (read-only for callers). */
typedef struct conica_path_seg {
    int degree;          /**< 1 = straight line, 2..CONICA_PATH_MAX_DEGREE = Bézier */
    int rational;        /**< non-zero: the weights are not all 1 */
    size_t first;        /**< its degree+1 control points: pt[first..first+degree] */
    size_t tag;          /**< the caller's tag (e.g. a byte offset or a point index) */
} conica_path_seg;

/**
 * A path under construction. Fields are read-only; build it with the
 * conica_path_* calls. Control points are stored as (x, y, w) triples with
 * x, y the Cartesian point (not multiplied by w).
 */
typedef struct conica_path {
    size_t nsub, subcap;
    conica_path_subpath *sub;
    size_t nseg, segcap;
    conica_path_seg *seg;
    size_t npt, ptcap;
    double *pt;          /**< 3 * npt: x, y, w of each control point */
    size_t nsmp, smpcap;
    double *smp;         /**< 4 * nsmp: x, y, nx, ny of each sample (normal 0,0 = none) */
    size_t *smptag;      /**< nsmp tags */
    int open;            /**< a DRAWN subpath is being drawn */
    double cur[2], start[2];
} conica_path;

/** Which side of a closed curve conica_path_flatten()'s chords keep to. */
typedef enum conica_path_fit {
    CONICA_PATH_FIT_INSIDE = 0, /**< vertices on the curve, chords inside a convex part (OpenSCAD's circle()) */
    CONICA_PATH_FIT_OUTSIDE,    /**< chords on or outside the curve (the polygon contains what the
                                     subpath encloses), vertices at most the tolerance off it */
    CONICA_PATH_FIT_MIDDLE      /**< chords straddle the curve: within the tolerance both ways,
                                     fewer points (about 1/sqrt(2) of INSIDE for a circle) */
} conica_path_fit;

/** Settings; start from conica_path_defaults(). */
typedef struct conica_path_settings {
    /** Absolute fidelity tolerance (> 0), or 0: rel_tolerance times each
     *  subpath's bounding-box diagonal. */
    double tolerance;
    double rel_tolerance;  /**< default CONICA_PATH_DEFAULT_REL_TOLERANCE */
    /** Radians: a join whose tangents turn by more is a corner (default
     *  40 degrees); >= pi: no corners (every join is smoothed). */
    double corner_angle;
    /** Absolute precision of the input coordinates: half a unit in the last
     *  digit written, or float32 rounding (conica_path_float32_precision()).
     *  Tangency, straightness and inflections are judged to it; 0: exact. */
    double precision;
    int levels;            /**< smoothing: subdivision levels (default 4, 0..16) */
    /** Smoothing: > 0 chooses the levels of each piece instead, the fewest
     *  whose chords stay within this distance of the limit curve. */
    double level_tolerance;
    size_t max_points;     /**< cap on the points of the whole result */
    /** Flattening of closed DRAWN subpaths: which side the chords keep to
     *  (default CONICA_PATH_FIT_INSIDE; open subpaths and samples always
     *  INSIDE). The side is the subpath's own: OUTSIDE grows what a
     *  contour encloses, whichever way it runs (a hole gets bigger). */
    conica_path_fit fit;
    /** Smoothing: nonzero when the caller does not read the points' t
     *  (svgsmooth): t is then the parameter of the point's nearest dense
     *  chord point, within the check's bound of its foot, instead of the
     *  foot itself, which saves a Newton search per point. The points,
     *  normals, flags and deviation are the same either way (default 0). */
    int rough_t;
    /** Flattening: nonzero puts a vertex at every join of drawn segments
     *  (a Bézier spline's anchors, for Blender), not only at corners and
     *  straight pieces; 0 (default) lets chords pass over tangent joins. */
    int vertex_joins;
    /** Smoothing with levels (level_tolerance 0): nonzero writes exactly
     *  `levels` levels (n 2^levels points per sample edge), as a caller that
     *  promises that count needs (Blender's Conic Subdivide); its points lie
     *  on the subdivision within the tolerance, the chords between them are
     *  that level's. 0 (default): a chord at the written level that strays
     *  beyond the tolerance is split at the next level's points. */
    int exact_levels;
    /** Optional progress report (NULL: none), in drawn segments and
     *  samples done of the path's total, at subpath and piece boundaries
     *  (a long run of curved segments without a corner or a straight edge
     *  is one piece); progress_ctx is passed to it. */
    conica_progress_fn progress;
    void *progress_ctx;
} conica_path_settings;

/** Output point flags. */
#define CONICA_PATH_PT_VERTEX 1u /**< an end point of a drawn segment, or an input sample */
#define CONICA_PATH_PT_CORNER 2u /**< a corner, kept sharp */

/** One output polyline: what became of one subpath. */
typedef struct conica_path_polyline {
    size_t subpath;      /**< index of the input subpath */
    int closed;          /**< closed: the last point joins the first (not repeated) */
    size_t n;
    double *xy;          /**< 2n coordinates */
    double *nxy;         /**< 2n unit normals of the produced curve (to the right of the direction of travel) */
    size_t *seg;         /**< n: index (into path.seg, or path.smp for SAMPLES) of the segment or sample edge the point belongs to */
    double *t;           /**< n: its parameter on that segment in [0, 1] (SAMPLES: fraction along the edge) */
    unsigned char *flags;/**< n: CONICA_PATH_PT_* bits */
    double tolerance;    /**< the fidelity tolerance used for this subpath */
    double deviation;    /**< DRAWN: largest distance measured between the produced curve and the drawn one, both directions */
} conica_path_polyline;

/** Result of conica_path_flatten() / conica_path_smooth(). Owns every array. */
typedef struct conica_path_result {
    size_t n;
    conica_path_polyline *lines; /**< one per input subpath, in order */
    size_t points;           /**< total points */
    size_t samples;          /**< smoothing: point-normal samples given to the subdivision */
    size_t refinements;      /**< smoothing: samples added because the subdivision strayed */
    size_t fallbacks;        /**< smoothing: segments written as flattened instead (within tolerance) */
    size_t corners;          /**< corners kept */
    size_t inflections;      /**< inflection points of drawn segments used as samples */
    double worst_ratio;      /**< largest deviation / tolerance over DRAWN subpaths */
} conica_path_result;

/** @brief Defaults: relative tolerance 1e-3, 40 degree corners, 4 levels, exact input. */
CONICA_API conica_path_settings conica_path_defaults(void);

/** @brief Precision of float32 coordinates of magnitude up to `max_abs`
 *         (half a float32 unit in the last place there). */
CONICA_API double conica_path_float32_precision(double max_abs);

/** @brief Make *p empty (safe to free). */
CONICA_API void conica_path_init(conica_path *p);
/** @brief Release everything *p owns; accepts NULL. */
CONICA_API void conica_path_free(conica_path *p);

/**
 * @brief Start a new drawn subpath at (x, y) (an open one being drawn ends
 *        there, open).
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NONFINITE, CONICA_ERR_LIMIT, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_path_move_to(conica_path *p, double x, double y, size_t tag,
                                           conica_status *st);
/** @brief Straight segment from the current point to (x, y). Without a
 *         current point: CONICA_ERR_ARG. A zero-length line is skipped. */
CONICA_API conica_code conica_path_line_to(conica_path *p, double x, double y, size_t tag,
                                           conica_status *st);
/**
 * @brief Bézier segment of `degree` (1..CONICA_PATH_MAX_DEGREE) from the
 *        current point: ctrl holds the other `degree` control points (x, y
 *        interleaved, the end point last); w holds degree+1 positive weights
 *        (the current point's first) or is NULL for a polynomial one. A
 *        segment whose control points all coincide is skipped.
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NONFINITE, CONICA_ERR_LIMIT, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_path_bezier_to(conica_path *p, int degree, const double *ctrl,
                                             const double *w, size_t tag, conica_status *st);
/**
 * @brief Elliptic arc from the current point: centre (cx, cy), radii rx, ry,
 *        x-axis rotation phi, start angle theta1 and signed sweep dtheta
 *        (radians, |dtheta| <= 2 pi), as exact rational quadratics of at most
 *        90 degrees each; the arc's end is (x1, y1) exactly. A zero radius
 *        gives the line to (x1, y1).
 * @return CONICA_OK; CONICA_ERR_ARG when |dtheta| exceeds 2 pi by more than
 *         rounding (1e-12 relative); CONICA_ERR_NONFINITE; CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_path_arc_to(conica_path *p, double cx, double cy, double rx,
                                          double ry, double phi, double theta1, double dtheta,
                                          double x1, double y1, size_t tag, conica_status *st);
/**
 * @brief The Bézier pieces of a 2D (optionally rational) B-spline, drawn from
 *        its start: continues the current subpath when it ends where the
 *        spline starts, else starts a new one.
 */
CONICA_API conica_code conica_path_bspline(conica_path *p, const conica_bspline *bs, size_t tag,
                                           conica_status *st);
/** @brief Close the current drawn subpath (a straight edge back to its start
 *         unless it ends there within rounding). Nothing open: no effect. */
CONICA_API conica_code conica_path_close(conica_path *p, conica_status *st);
/**
 * @brief A subpath of n samples to interpolate (x, y interleaved), with unit
 *        normals nxy (or NULL: estimated), open or closed. Sample i is
 *        tagged first_tag + i. Consecutive coincident samples are merged.
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NONFINITE, CONICA_ERR_DEGENERATE (fewer than 2 distinct samples), CONICA_ERR_LIMIT, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_path_samples(conica_path *p, const double *xy, const double *nxy,
                                           size_t n, int closed, size_t first_tag,
                                           conica_status *st);

/** @brief Point and first derivative of segment `seg` at t in [0, 1] (either output may be NULL). */
CONICA_API void conica_path_seg_eval(const conica_path *p, size_t seg, double t, double pt[2],
                                     double d1[2]);

/** @brief Make *r empty (safe to free). */
CONICA_API void conica_path_result_init(conica_path_result *r);
/** @brief Release everything *r owns; accepts NULL. */
CONICA_API void conica_path_result_free(conica_path_result *r);

/**
 * @brief Every subpath as a polyline within the fidelity tolerance of the
 *        drawn curve (both directions): straight segments by their end
 *        points, curves by the guaranteed plotter. SAMPLES: the samples.
 * @param[in]  p   the path
 * @param[in]  s   settings, or NULL for defaults
 * @param[out] out receives the polylines (previous content freed on success)
 * @param[out] st  optional detail; st->offset names the subpath
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_LIMIT, CONICA_ERR_NOMEM, CONICA_ERR_NUMERIC
 */
CONICA_API conica_code conica_path_flatten(const conica_path *p, const conica_path_settings *s,
                                           conica_path_result *out, conica_status *st);

/**
 * @brief Every subpath smoothed by conic-preserving subdivision, its limit
 *        curve within the fidelity tolerance of the drawn curve (both
 *        directions), corners sharp, straight segments straight, conics
 *        exact. SAMPLES are interpolated (split at corners of their
 *        polygon).
 * @return as conica_path_flatten(), and CONICA_ERR_DEGENERATE for samples
 *         the subdivision cannot take
 */
CONICA_API conica_code conica_path_smooth(const conica_path *p, const conica_path_settings *s,
                                          conica_path_result *out, conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

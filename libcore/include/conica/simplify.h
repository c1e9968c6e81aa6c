/* SPDX-License-Identifier: MIT */
/**
 * @file simplify.h
 * @brief Fewer samples for a traced outline: keep the fewest vertices of a
 *        polygon or polyline whose smoothed curve still passes within a
 *        tolerance of every original vertex.
 *
 * A traced outline is a list of jittered samples; interpolating every one
 * (conica_path_samples() + conica_path_smooth()) carries the jitter into
 * the smooth curve as wiggles. conica_simplify() chooses a subset of the
 * vertices such that the curve conica_path_smooth() makes of the subset,
 * with the same settings (so normals are estimated and corners split as
 * there), lies within `tolerance` of every original vertex. Corners of
 * the original polygon and the ends of an open polyline are always kept,
 * and a kept vertex that is no corner of the input never becomes one of
 * the kept polygon. A corner is conica/path.h's rule (a turn above the
 * path settings' corner angle) judged at the scale of the tolerance: the
 * turn at a vertex towards the nearest vertices more than twice the
 * tolerance away on each side, the largest such turn among its
 * neighbours (jitter within the tolerance makes no corner; with the
 * tolerance below the spacing of the vertices this is the turn between
 * neighbours).
 *
 * Method: Douglas–Peucker seeding between the fixed vertices (chord
 * distance within the tolerance), then rounds of verification: the kept
 * vertices are smoothed, every original vertex is measured against the
 * smoothed polyline between its two kept neighbours, and each arc where
 * one strays gets its worst vertex back; then single vertices are dropped
 * again where the check, on the ten kept vertices each side, still passes,
 * and the rounds check the whole curve once more. Rounds and work are
 * capped; if the round cap is met before the check passes, every vertex is
 * kept (the result is never outside the tolerance). Deterministic.
 *
 * Example:
 * @code
 *   conica_simplify_settings s = conica_simplify_defaults();
 *   size_t *keep = malloc(n * sizeof *keep), m;
 *   s.tolerance = 0.5;
 *   if (conica_simplify(xy, n, 1, &s, keep, &m, NULL, NULL) == CONICA_OK)
 *       ... // xy[2*keep[i]], xy[2*keep[i]+1] for i < m: the samples to smooth
 * @endcode
 */
#ifndef CONICA_SIMPLIFY_H
#define CONICA_SIMPLIFY_H

#include <stddef.h>

#include "conica/common.h"
#include "conica/path.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Default cap on insertion rounds of conica_simplify(). */
#define CONICA_SIMPLIFY_DEFAULT_ROUNDS 64
/** Cap on the vertices of one conica_simplify() input. */
#define CONICA_SIMPLIFY_MAX_POINTS ((size_t)1 << 24)

/** Settings; start from conica_simplify_defaults(). */
typedef struct conica_simplify_settings {
    /** Largest distance (same units as the points, > 0) of an original
     *  vertex from the smoothed curve of the kept ones; 0: rel_tolerance
     *  times the bounding-box diagonal of the input. */
    double tolerance;
    double rel_tolerance; /**< default 1e-3 (as CONICA_PATH_DEFAULT_REL_TOLERANCE) */
    /** How the kept vertices are smoothed: corner_angle, precision, levels,
     *  level_tolerance as given to conica_path_smooth() afterwards. */
    conica_path_settings path;
    int max_rounds;       /**< insertion rounds (default CONICA_SIMPLIFY_DEFAULT_ROUNDS, 1..1024) */
    /** Cap on the work of the dropping pass, in vertex measurements
     *  (default 2^24): past it, what has been dropped so far stays dropped. */
    size_t max_work;
    /** Optional, n entries (one per input vertex): a non-zero entry's vertex
     *  is always kept, as corners are (a caller's refinement: svgsmooth
     *  puts back the vertices at a crossing the simplified curve made).
     *  NULL: none. A repeated vertex counts by its first copy. */
    const unsigned char *keep_mask;
} conica_simplify_settings;

/** What conica_simplify() did (all optional reading). */
typedef struct conica_simplify_info {
    size_t kept;        /**< vertices kept */
    size_t corners;     /**< of them, corners and open ends (always kept) */
    size_t rounds;      /**< verification rounds that inserted vertices */
    size_t dropped;     /**< vertices removed by the dropping pass */
    double deviation;   /**< largest measured distance of an original vertex from the smoothed curve */
    double tolerance;   /**< the tolerance used */
    int kept_all;       /**< non-zero: the round cap was met, every vertex kept */
} conica_simplify_info;

/** @brief Defaults: relative tolerance 1e-3, path defaults, 64 rounds. */
CONICA_API conica_simplify_settings conica_simplify_defaults(void);

/**
 * @brief Indices of the vertices to keep, in order.
 *
 * Consecutive coincident vertices count once (the first is kept); a closed
 * polygon's last vertex equal to its first is dropped.
 * @param[in]  xy     n points, interleaved
 * @param[in]  n      number of points (2..CONICA_SIMPLIFY_MAX_POINTS)
 * @param[in]  closed non-zero: a closed polygon
 * @param[in]  s      settings, or NULL for defaults
 * @param[out] keep   caller's array of n entries: the kept indices, ascending
 * @param[out] nkeep  how many
 * @param[out] info   optional
 * @param[out] st     optional detail
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NONFINITE, CONICA_ERR_LIMIT,
 *         CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_simplify(const double *xy, size_t n, int closed,
                                       const conica_simplify_settings *s, size_t *keep,
                                       size_t *nkeep, conica_simplify_info *info,
                                       conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

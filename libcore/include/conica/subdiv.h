/* SPDX-License-Identifier: MIT */
/**
 * @file subdiv.h
 * @brief Conic-preserving interpolatory subdivision (CONIS §1.1).
 *
 * Example:
 * @code
 *   conica_curve in, out;
 *   conica_curve_init(&in); conica_curve_init(&out);
 *   conica_curve_set(xy, nxy, n, 1, &in, NULL);
 *   conica_subdiv_settings s = conica_subdiv_defaults();
 *   s.levels = 5;
 *   conica_status st;
 *   if (conica_subdivide(&in, &s, &out, NULL, &st) != CONICA_OK)
 *       fprintf(stderr, "%s\n", st.message);
 *   conica_curve_free(&in); conica_curve_free(&out);
 * @endcode
 */
#ifndef CONICA_SUBDIV_H
#define CONICA_SUBDIV_H

#include "conica/common.h"
#include "conica/curve.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CONICA_SUBDIV_MAX_LEVELS 30                 /**< hard upper bound on levels */
#define CONICA_SUBDIV_DEFAULT_MAX_POINTS ((size_t)1 << 26) /**< default output budget */

/** Settings; get defaults from conica_subdiv_defaults(). */
typedef struct conica_subdiv_settings {
    int levels;                /**< 0..CONICA_SUBDIV_MAX_LEVELS */
    double w_edge_point;       /**< w_e^v, default 1e5 */
    double w_edge_normal;      /**< w_e^n, default 1e5 */
    double w_outer_normal;     /**< w_o^n, default 1 */
    double tau;                /**< w_o^v = tau * w_o^n, default 10 */
    int patch_grow;            /**< max outer neighbours per side when growing a patch (1..4), default 4 */
    int insert_inflections;    /**< non-zero (default): split non-convex input at inflection points */
    int precise;               /**< non-zero: compute in long double */
    int reference_compatible;  /**< non-zero: absolute coordinates + SVD fit, as the reference */
    int normalize_normals;     /**< ablation: normalise sampled normals every level (BASE); default 0 */
    int plain_quadratic;       /**< ablation: textbook quadratic formula without FMA/Kahan; default 0 */
    int force_svd;             /**< use the general weighted SVD fit even where the fast path applies */
    int estimate_normals;      /**< non-zero: ignore input normals and estimate them */
    conica_normal_method normal_method; /**< used when estimating */
    size_t max_points;         /**< output budget, default CONICA_SUBDIV_DEFAULT_MAX_POINTS */
    int threads;               /**< 0/1 = single thread; results are bit-identical for any value */
    /** Rounding of the input coordinates (absolute, e.g. float32 spacing or
     *  half a unit of the last digit written); 0 (default): exact. When > 0,
     *  a neighbour within a few times this of an edge line is on no side of
     *  it, and an end normal within a few rounding units of the chord's
     *  perpendicular counts as perpendicular (a straight run of rounded
     *  points), so rounding noise makes no inflection points and no
     *  S-shaped edges. Whatever its value, default mode reads the sign
     *  changes of the polygon's turn at the coordinates' own rounding too
     *  (a few ulps of the largest |coordinate| at each vertex): several sign changes
     *  between two turns clear of it count as their parity (one inflection
     *  point or none), so a curve gets the same inflection points wherever
     *  it sits. */
    double noise;
    /** Optional progress report (NULL: none), in edge points computed of
     *  all the levels' edge points; progress_ctx is passed to it. */
    conica_progress_fn progress;
    void *progress_ctx;
} conica_subdiv_settings;

/** What happened during a subdivision (optional output). */
typedef struct conica_subdiv_info {
    size_t edge_points;      /**< edge points computed over all levels */
    size_t inflections;      /**< inflection points inserted before level 1 */
    size_t patch_grown;      /**< edge points that needed a grown patch */
    size_t midpoint_fallbacks; /**< edge points that used a last resort (parabola of the pencil, midpoint, or the midpoint inflection point of an S-shaped edge) */
    size_t *inflection_index;  /**< indices (into the output curve) of inserted inflection points; free with conica_subdiv_info_free */
} conica_subdiv_info;

/** @brief Default settings (CONIS values, double precision, local frames). */
CONICA_API conica_subdiv_settings conica_subdiv_defaults(void);

/** @brief Make *info empty (safe to free). */
CONICA_API void conica_subdiv_info_init(conica_subdiv_info *info);
/** @brief Release arrays owned by *info. Accepts NULL. */
CONICA_API void conica_subdiv_info_free(conica_subdiv_info *info);

/**
 * @brief Number of points the output of conica_subdivide() will have for
 *        an input of n points (without inflection insertion: closed n*2^k,
 *        open (n-1)*2^k+1), or 0 on overflow.
 */
CONICA_API size_t conica_subdiv_count(size_t n, int closed, int levels);

/**
 * @brief Subdivide `in` `s->levels` times.
 *
 * Old vertices are kept bit-for-bit; each level inserts one edge point per
 * edge. If `in` has no normals (or s->estimate_normals) they are estimated.
 * Output normals are unit length and keep the input normals' orientation.
 * levels = 0 returns the input (unit normals, no inflection points).
 * Coincident consecutive points are an error (an edge of zero length has no
 * bisector), named in st->offset, as are non-finite values and zero normals.
 * The output size is checked against s->max_points before any allocation.
 * Results are bit-identical for any s->threads. See README.md.
 * @param[in]  in   input curve (at least 2 points; 3 for closed)
 * @param[in]  s    settings, or NULL for defaults
 * @param[out] out  receives the refined curve (previous content freed on success)
 * @param[out] info optional statistics (may be NULL)
 * @param[out] st   optional detail
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_DEGENERATE, CONICA_ERR_NONFINITE,
 *         CONICA_ERR_LIMIT (levels or max_points exceeded), CONICA_ERR_NOMEM,
 *         CONICA_ERR_NUMERIC
 */
CONICA_API conica_code conica_subdivide(const conica_curve *in, const conica_subdiv_settings *s,
                                        conica_curve *out, conica_subdiv_info *info,
                                        conica_status *st);

/**
 * A curve in long double, the output of precise mode when the caller wants
 * every bit of it (the CLI prints it with %.21Lg). Same layout as conica_curve.
 */
typedef struct conica_curvel {
    size_t n, cap;
    long double *xy;
    long double *nxy;
    int closed;
} conica_curvel;

/** @brief Make *c empty (safe to free). */
CONICA_API void conica_curvel_init(conica_curvel *c);
/** @brief Release *c's arrays. Accepts NULL. */
CONICA_API void conica_curvel_free(conica_curvel *c);

/**
 * @brief As conica_subdivide(), computing in long double whatever
 *        s->precise says, with the result kept in long double.
 * @return the same codes as conica_subdivide()
 */
CONICA_API conica_code conica_subdividel(const conica_curve *in, const conica_subdiv_settings *s,
                                         conica_curvel *out, conica_subdiv_info *info,
                                         conica_status *st);

/**
 * @brief As conica_subdividel(), from a long double input curve (so that
 *        samples computed in long double, e.g. exact conic samples for
 *        precise-mode accuracy tests, are not rounded to double first).
 *        Always computes in long double. If in->nxy is NULL the normals are
 *        estimated (from the points rounded to double).
 * @return the same codes as conica_subdivide()
 */
CONICA_API conica_code conica_subdivide_curvel(const conica_curvel *in,
                                               const conica_subdiv_settings *s,
                                               conica_curvel *out, conica_subdiv_info *info,
                                               conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

/* SPDX-License-Identifier: MIT */
/**
 * @file plot.h
 * @brief Plotting B-splines as polylines (Dahl 2019, Ch. 2-4): the
 *        guaranteed plotter (default for the tools), the thesis's adaptive
 *        knot-insertion loop with all its criteria, rules and stopping
 *        tests, and the baselines it compares against; tensor-product
 *        surfaces to quad grids.
 *
 * Example (every point of the curve within 1e-3 of the polyline and every
 * polyline point within 1e-3 of the curve):
 * @code
 *   conica_plot_settings set = conica_plot_defaults();   // guaranteed
 *   set.abs_tolerance = 1e-3;
 *   conica_polyline pl;
 *   conica_polyline_init(&pl);
 *   if (conica_plot(&spline, &set, &pl, NULL, NULL) == CONICA_OK) {
 *       // pl.n points of pl.dim coordinates in pl.xy, split into
 *       // pl.npieces pieces starting at pl.piece_start[k]
 *   }
 *   conica_polyline_free(&pl);
 * @endcode
 */
#ifndef CONICA_PLOT_H
#define CONICA_PLOT_H

#include <stddef.h>

#include "conica/bspline.h"
#include "conica/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Plotting methods. */
typedef enum conica_plot_method {
    CONICA_PLOT_GUARANTEED = 0,  /**< default for the tools: rigorous bound <= tolerance */
    CONICA_PLOT_ADAPTIVE,        /**< the thesis's knot-insertion loop (Section 3.5) */
    CONICA_PLOT_UNIFORM,         /**< global uniform sampling, eq. (2.3)-(2.4) */
    CONICA_PLOT_LOCAL_UNIFORM,   /**< per knot interval, eqs. (3.10), (3.17), (3.18) */
    CONICA_PLOT_CHAIKIN,         /**< corner cutting, eqs. (3.1)-(3.2) */
    CONICA_PLOT_LANE_RIESENFELD, /**< midpoint refinement (Fig. 12) */
    CONICA_PLOT_MATHEMATICA,     /**< uniform start + angle-driven recursion (Section 2.3.3) */
    CONICA_PLOT_METHOD_COUNT_
} conica_plot_method;

/** Geometric criterion C of the adaptive loop (Section 3.2, Table 2). */
typedef enum conica_plot_criterion {
    CONICA_CRIT_SIMPLIFIED_LENGTH = 0, /**< eq. (3.11) */
    CONICA_CRIT_LENGTH,                /**< eq. (3.8) */
    CONICA_CRIT_LENGTH_RATIO,          /**< eq. (3.21), triples */
    CONICA_CRIT_SIMPLIFIED_ANGLE,      /**< T(x) = -pi/2 x|x| + pi/2 (Fig. 16) */
    CONICA_CRIT_ANGLE,                 /**< eq. (3.15) */
    CONICA_CRIT_BASE_LINE,             /**< Def. 3.14 (squared distance) */
    CONICA_CRIT_EXTENDED_BASE_LINE,    /**< Def. 3.14 + Lemma 3.15 side test */
    CONICA_CRIT_COUNT_
} conica_plot_criterion;

/** Knot placement rule R (Section 3.3.3). */
typedef enum conica_plot_rule {
    CONICA_RULE_MIDPOINT = 0,  /**< z = t_mu + R (t_{mu+p} - t_mu), R = rule_ratio (thesis default) */
    CONICA_RULE_KNOT_AVERAGE,  /**< z = t*_mu */
    CONICA_RULE_CHAIKIN,       /**< new knot average midway between t*_mu and t*_{mu+1} */
    CONICA_RULE_COUNT_
} conica_plot_rule;

/** Stopping test S (Section 3.4). The knot budget always applies too. */
typedef enum conica_plot_stop {
    CONICA_STOP_MOVEMENT = 0,  /**< control points move < eps, `consec` times in a row (thesis) */
    CONICA_STOP_THRESHOLD,     /**< largest criterion value <= its threshold */
    CONICA_STOP_BUDGET,        /**< insert exactly knot_budget knots */
    CONICA_STOP_COUNT_
} conica_plot_stop;

/** What the adaptive loop emits. */
typedef enum conica_plot_output {
    CONICA_OUTPUT_CONTROL_POLYGON = 0, /**< the refined control polygon (as the thesis plots) */
    CONICA_OUTPUT_CURVE_POINTS         /**< points on the curve at the final knot averages */
} conica_plot_output;

/** Weighting of local uniform sampling. */
typedef enum conica_plot_local_weight {
    CONICA_LOCAL_BOTH = 0,   /**< eq. (3.18) with omega = local_omega */
    CONICA_LOCAL_LENGTH,     /**< eq. (3.10) */
    CONICA_LOCAL_ANGLE       /**< eq. (3.17) */
} conica_plot_local_weight;

/** Default caps (each is also a settings field). */
#define CONICA_PLOT_MAX_POINTS_DEFAULT ((size_t)4000000)
#define CONICA_PLOT_MAX_KNOTS_DEFAULT ((size_t)1000000)
#define CONICA_PLOT_MAX_ITERATIONS_DEFAULT ((size_t)20000000)
/** Thesis defaults (REFERENCE.md section 4, Section 3.4). */
#define CONICA_PLOT_DEFAULT_PIXEL_TOLERANCE 3.0
#define CONICA_PLOT_DEFAULT_KNOT_BUDGET ((size_t)500)
#define CONICA_PLOT_DEFAULT_UNIFORM_POINTS ((size_t)101) /* MATLAB fnplt */

/** Settings; start from conica_plot_defaults(). */
typedef struct conica_plot_settings {
    conica_plot_method method;
    /** Curve units; > 0 means absolute tolerance (overrides the pixel one). */
    double abs_tolerance;
    /** delta of eq. (3.26), pixels (default 3). */
    double pixel_tolerance;
    /** Viewport in pixels; rho = sqrt(w^2 + h^2) in eq. (3.26) (default 1000x1000). */
    double viewport_w, viewport_h;

    /* adaptive loop */
    conica_plot_criterion criterion; /**< default length ratio */
    conica_plot_rule rule;           /**< default midpoint, R = 0.5 */
    double rule_ratio;               /**< R of the midpoint rule (0 < R < 1) */
    conica_plot_stop stop;           /**< default movement */
    double threshold;                /**< criterion threshold; <= 0: thesis default */
    size_t skip, consec;             /**< movement test every skip iterations, consec in a row */
    size_t knot_budget;              /**< knots the adaptive loop may insert (thesis 500) */
    size_t prephase_knots;           /**< uniform knots inserted before the loop (0 = none) */
    conica_plot_output output;       /**< adaptive output (default control polygon) */

    /* baselines */
    size_t points;                   /**< N of uniform / local-uniform / Chaikin / LR (101) */
    size_t local_min_points;         /**< N_min of eq. (3.10) (2) */
    conica_plot_local_weight local_weight;
    double local_omega;              /**< omega of eq. (3.18) (0.5) */
    size_t math_initial_points;      /**< Mathematica N0 (PlotPoints, 50), at most max_points */
    double math_angle;               /**< Mathematica angle threshold, radians (5 degrees) */
    size_t math_max_recursion;       /**< Mathematica MaxRecursion (6) */

    /* caps (CONICA_ERR_LIMIT past them) */
    size_t max_points;               /**< output points */
    size_t max_knots;                /**< knots inserted (all methods) */
    size_t max_iterations;           /**< plotter iterations / trial steps */
} conica_plot_settings;

/** @brief Defaults: guaranteed method, 3 px on 1000x1000, thesis loop defaults. */
CONICA_API conica_plot_settings conica_plot_defaults(void);

/** Output polyline (possibly several pieces). */
typedef struct conica_polyline {
    size_t n, cap;
    int dim;
    double *xy;          /**< n * dim coordinates */
    size_t npieces;      /**< pieces split at discontinuities */
    size_t *piece_start; /**< npieces start indices into the points */
    double *t;           /**< parameter of each point when every point was
                              evaluated on the curve (guaranteed, uniform,
                              local-uniform, mathematica, adaptive with curve
                              points); NULL for control-polygon output */
} conica_polyline;

/** @brief Empty polyline, safe to free. */
CONICA_API void conica_polyline_init(conica_polyline *p);
/** @brief Release the arrays of p. */
CONICA_API void conica_polyline_free(conica_polyline *p);

/** Statistics of one plot. flops counts +,-,*,/,sqrt each as 1. */
typedef struct conica_plot_stats {
    size_t points, knots_inserted; double flops; double seconds;
    size_t iterations;       /**< loop iterations / trial steps */
    double tolerance;        /**< absolute tolerance used (eps) */
    double bound;            /**< guaranteed: largest certified deviation; else 0 */
} conica_plot_stats;

/**
 * @brief Plot s into *out (replaced on success).
 *
 * For a spline function (dim 1) the polyline has dim 2: (parameter, value).
 * End points are on the curve. The spline is clamped to its domain and
 * split at knots of multiplicity >= p into continuous pieces (Section
 * 1.1.2); pieces that meet in the same point are joined in the output.
 * The guaranteed method does not split where the curve is
 * tangent-continuous at a knot of multiplicity p (the joins of a NURBS
 * circle): its chords may cross such a join, as the greedy optimum's do.
 * @return CONICA_OK, CONICA_ERR_ARG (bad settings or spline),
 *         CONICA_ERR_LIMIT (a cap was reached), CONICA_ERR_NOMEM,
 *         CONICA_ERR_UNSUPPORTED (guaranteed/adaptive on a rational function)
 */
CONICA_API conica_code conica_plot(const conica_bspline *s, const conica_plot_settings *set,
        conica_polyline *out, conica_plot_stats *stats, conica_status *st);

/**
 * @brief Guaranteed plot of one planar Bézier piece into caller arrays, without
 *        the copies, checks of settings, allocations and timing of conica_plot.
 *
 * The same plotter and certificate as conica_plot with CONICA_PLOT_GUARANTEED
 * and abs_tolerance = tol on the spline conica_bspline_from_bezier(degree, 2,
 * ctrl, w) makes: the same points, from ctrl[0..1] to the last control
 * point, each chord within tol of the piece both ways.
 * @param[in] degree 1..CONICA_BSPLINE_MAX_DEGREE
 * @param[in] ctrl degree + 1 control points, x y interleaved
 * @param[in] w degree + 1 positive weights (rational piece), or NULL
 * @param[in] tol absolute tolerance, > 0
 * @param[in] max_iterations trial steps allowed (0: CONICA_PLOT_MAX_ITERATIONS_DEFAULT)
 * @param[out] xy 2 * cap doubles: the points
 * @param[out] t cap doubles: each point's parameter in [0, 1], or NULL
 * @param[in] cap room in xy and t, in points
 * @param[out] n the number of points written
 * @return CONICA_OK, CONICA_ERR_ARG (NULL array, degree, non-finite
 *         values, weights <= 0, tol <= 0 or below the coordinates'
 *         resolution), CONICA_ERR_LIMIT (more than cap points or
 *         max_iterations trials needed), CONICA_ERR_NOMEM,
 *         CONICA_ERR_NUMERIC; on failure *n is left untouched and xy, t
 *         hold unspecified values
 */
CONICA_API conica_code conica_plot_bezier(int degree, const double *ctrl, const double *w,
        double tol, size_t max_iterations, double *xy, double *t, size_t cap, size_t *n,
        conica_status *st);

/** @brief Delta c of eq. (3.26): the diagonal of the control points' bounding
 *         box ((t*_j, c_j) for a function; projected points if rational). */
CONICA_API double conica_plot_extent(const conica_bspline *s);

/** @brief Absolute tolerance the settings give for s (abs_tolerance, or eq. (3.26));
 *         NaN when s or set is NULL. */
CONICA_API double conica_plot_tolerance(const conica_bspline *s, const conica_plot_settings *set);

/**
 * @brief Measure (not bound) the deviation between s and a polyline by dense
 *        evaluation at `samples` points per knot interval.
 *
 * *curve_to_poly: largest distance of a sample to the polyline (searched
 * near the previous sample's nearest segment, so never below the true
 * value). *poly_to_curve: largest distance of a polyline vertex or segment
 * quarter point to the chain of samples (exact nearest sample, then its two
 * chords); it exceeds the true distance to the curve by at most the
 * samples' sagitta. When pl->t is set (points evaluated on the curve),
 * `samples` is per chord instead and each chord is compared with the curve
 * between its end parameters only (both values can only be over-estimated).
 * Either output may be NULL.
 * @return CONICA_OK; CONICA_ERR_ARG (NULL, samples 0, an empty polyline,
 *         dimensions differ); CONICA_ERR_LIMIT when the samples pass 2^26
 *         (per chord, or in all over the knot intervals); CONICA_ERR_NOMEM.
 */
CONICA_API conica_code conica_plot_deviation(const conica_bspline *s, const conica_polyline *pl,
        size_t samples, double *curve_to_poly, double *poly_to_curve, conica_status *st);

/** @brief Method / criterion / rule names as the CLI spells them; NULL if out of range. */
CONICA_API const char *conica_plot_method_name(conica_plot_method m);
CONICA_API const char *conica_plot_criterion_name(conica_plot_criterion c);
CONICA_API const char *conica_plot_rule_name(conica_plot_rule r);
/** @brief Reverse lookups; return -1 for an unknown name. */
CONICA_API int conica_plot_method_from_name(const char *name);
CONICA_API int conica_plot_criterion_from_name(const char *name);
CONICA_API int conica_plot_rule_from_name(const char *name);

/* ------------------------------------------------------------ surfaces */

/** A quad grid of surface points, nu x nv, 3 coordinates each. */
typedef struct conica_quadgrid {
    size_t nu, nv;
    double *u, *v;   /**< parameters of the grid lines */
    double *xyz;     /**< nu*nv*3 values, index ((i*nv)+j)*3 */
} conica_quadgrid;

CONICA_API void conica_quadgrid_init(conica_quadgrid *g);
CONICA_API void conica_quadgrid_free(conica_quadgrid *g);

/**
 * @brief Plot a tensor-product surface to a quad grid by the two-phase
 *        approach of Section 4.1.2: phase 1 plots the isocurves u = const
 *        at every distinct knot u and collects the v-parameters they need,
 *        phase 2 plots the isocurves v = const on that refined v-grid and
 *        collects the u-parameters. Each isocurve plotted is certified
 *        with its own parameters (guaranteed method); the grid is their
 *        union and quad interiors are not certified. A height surface
 *        (dim 1) is plotted as (u, v, z). Only CONICA_PLOT_GUARANTEED is
 *        accepted (CONICA_ERR_UNSUPPORTED otherwise), as are rational
 *        height surfaces.
 * @return as conica_plot
 */
CONICA_API conica_code conica_plot_surface(const conica_bspline_surface *s,
        const conica_plot_settings *set, conica_quadgrid *out, conica_plot_stats *stats,
        conica_status *st);

/**
 * @brief Plot a tensor-product surface to a quad grid like
 *        conica_plot_surface, with the same isocurves certified by the
 *        guaranteed method, but each direction's grid parameters are their
 *        envelope instead of their union: from the start of the domain,
 *        each next grid line is as far as every isocurve's own certified
 *        step allows where it lies (and no distinct knot is skipped). The
 *        union grows with the number of isocurves when their parameters
 *        do not line up (a rational sphere's meridians: 290 x 29 lines
 *        for 1e-2 on Blender's unit sphere, 17 x 29 with the envelope);
 *        each direction stays near the count of its most demanding
 *        isocurve. A step may end on a parameter of the union when that
 *        keeps 90% of it. Grid lines are
 *        not isocurves that were plotted, so neither they nor the quads
 *        are certified; the Blender suite measures the result.
 * @return as conica_plot
 */
CONICA_API conica_code conica_plot_surface_envelope(const conica_bspline_surface *s,
        const conica_plot_settings *set, conica_quadgrid *out, conica_plot_stats *stats,
        conica_status *st);

/**
 * @brief Plot a tensor-product surface to a quad grid whose every quad is
 *        certified: the distance between the surface and the quad (its
 *        bilinear interpolant, and either of its two triangulations) is at
 *        most the tolerance, both ways, by a rigorous bound. The grid lines
 *        are the distinct knots and, per knot span, equally spaced lines
 *        in each direction; a cell's bound is the convex-hull bound of
 *        (H - W Q) / W in the Bernstein basis (Q the bilinear quad, H and W
 *        the surface's homogeneous numerator and weight) over 4 x 4
 *        sub-patches obtained by blossoming, plus the distance between the
 *        bilinear quad and its triangulations (0 for planar quads). Lines
 *        are added where the worst block gains most per vertex, then
 *        removed where every cell still passes. Every grid point is
 *        evaluated on the surface. stats->bound is the largest cell bound.
 *        The settings' method is not used (the tolerance is abs_tolerance,
 *        else the pixel tolerance scaled to the net's extent).
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_LIMIT (the grid would pass
 *         max_points), CONICA_ERR_NOMEM, CONICA_ERR_UNSUPPORTED (rational
 *         height surface)
 */
CONICA_API conica_code conica_plot_surface_certified(const conica_bspline_surface *s,
        const conica_plot_settings *set, conica_quadgrid *out, conica_plot_stats *stats,
        conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

/* SPDX-License-Identifier: MIT */
/**
 * @file bspline.h
 * @brief B-spline functions and curves (optionally rational / NURBS) and
 *        tensor-product B-spline surfaces: validation, the .spl text
 *        format, evaluation (triangular algorithm), knot insertion (Böhm)
 *        and Bézier conversion. Implements Dahl 2019, Ch. 1.
 *
 * Example:
 * @code
 *   conica_bspline s;
 *   conica_bspline_init(&s);
 *   const double knots[] = {0, 0, 0, 1, 1, 1}, ctrl[] = {0, 0, 1, 2, 2, 0};
 *   if (conica_bspline_set(2, 2, knots, 6, ctrl, 3, NULL, &s, NULL) == CONICA_OK) {
 *       double xy[2];
 *       conica_bspline_eval(&s, 0.5, xy, NULL);   // (1, 1)
 *   }
 *   conica_bspline_free(&s);
 * @endcode
 *
 * Conventions: knots are 0-based here (Dahl 2019 numbers them from 1); a
 * spline of degree p with n control points has n + p + 1 knots and is
 * plotted on its domain [t_p, t_n]. Control points are interleaved, `dim`
 * doubles each. For a spline function (dim 1) the control points of the
 * control polygon are (knot average, coefficient) (Def. 1.10-1.12).
 * Rational splines carry positive weights and are evaluated in
 * homogeneous coordinates (w*c, w).
 */
#ifndef CONICA_BSPLINE_H
#define CONICA_BSPLINE_H

#include <stddef.h>

#include "conica/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Highest supported degree p. */
#define CONICA_BSPLINE_MAX_DEGREE 50
/** Highest number of control points accepted by set/parse/insert. */
#define CONICA_BSPLINE_MAX_CTRL ((size_t)1 << 22)

/** A B-spline function (dim 1) or curve (dim 2, 3), optionally rational. */
typedef struct conica_bspline {
    int degree;        /**< p, 1..CONICA_BSPLINE_MAX_DEGREE (50) */
    int dim;           /**< 1 (function), 2 or 3 */
    size_t n;          /**< number of control points */
    double *knots;     /**< n + degree + 1 non-decreasing knots */
    double *ctrl;      /**< n * dim coordinates, interleaved */
    double *w;         /**< n positive weights (rational / NURBS), or NULL */
} conica_bspline;

/** @brief Empty spline, safe to free. */
CONICA_API void conica_bspline_init(conica_bspline *s);
/** @brief Release the arrays of s (NULL and empty accepted); s becomes empty. */
CONICA_API void conica_bspline_free(conica_bspline *s);

/**
 * @brief Copy and validate a spline.
 *
 * Checks: 1 <= degree <= 50, dim in {1,2,3}, n >= degree + 1,
 * nknots == n + degree + 1, finite values, non-decreasing knots, no knot of
 * multiplicity > degree + 1, a non-empty domain [t_p, t_n], positive finite
 * weights, n <= CONICA_BSPLINE_MAX_CTRL.
 * @param[in] degree,dim,knots,nknots,ctrl,n,w  the spline (w may be NULL)
 * @param[out] out replaced on success (previous contents freed)
 * @param[out] st  optional detail (offset = index of the offending item)
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NONFINITE, CONICA_ERR_LIMIT,
 *         CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_bspline_set(int degree, int dim, const double *knots,
        size_t nknots, const double *ctrl, size_t n, const double *w,
        conica_bspline *out, conica_status *st);

/**
 * @brief Preprocessing of Section 1.1.2 (check_regular): make a knot vector
 *        (p+1)-regular.
 *
 * Knots of multiplicity > p+1 are trimmed to p+1 together with the
 * coefficients of the B-splines with empty support; end knots of
 * multiplicity < p+1 are extended by repeating the end knot, with zero
 * coefficients (weight 1) for the new B-splines, exactly as Dahl 2019's
 * worked example (t=(0,0,1,1,1,1,2,2,2), c=(1,3,2,5,4,2) becomes
 * t=(0,0,0,1,1,1,2,2,2), c=(0,1,3,5,4,2)). Other checks as
 * conica_bspline_set (except the multiplicity bound).
 * @return as conica_bspline_set
 */
CONICA_API conica_code conica_bspline_make_regular(int degree, int dim, const double *knots,
        size_t nknots, const double *ctrl, size_t n, const double *w,
        conica_bspline *out, conica_status *st);

/**
 * @brief One Bézier piece of any degree (degree+1 control points, optional
 *        weights) as a B-spline with (p+1)-fold end knots on [0,1].
 * @return as conica_bspline_set
 */
CONICA_API conica_code conica_bspline_from_bezier(int degree, int dim, const double *ctrl,
        const double *w, conica_bspline *out, conica_status *st);

/**
 * @brief Parse the .spl text format (docs/file-formats.md).
 *
 * Lines: `degree P`, `knots t...` (may repeat), `c x [y [z]]` (one control
 * point a line, all with the same count), `w w1 ... wn` (may repeat);
 * `#` starts a comment. Numbers are read without the C locale.
 * @param[in] buf,len text (need not be NUL-terminated, never written)
 * @param[out] out replaced on success
 * @param[out] st line (1-based) and byte offset of the error
 * @return CONICA_OK, CONICA_ERR_PARSE, or a conica_bspline_set code
 */
CONICA_API conica_code conica_bspline_parse(const char *buf, size_t len,
        conica_bspline *out, conica_status *st);

/**
 * Caps of the .spl reader (input-controlled sizes); start from
 * conica_bspline_parse_limits_defaults(). The library's own maxima
 * (CONICA_BSPLINE_MAX_CTRL, CONICA_BSPLINE_MAX_DEGREE) are hard limits of
 * conica_bspline_set() and the evaluators, so a cap can only lower them.
 */
typedef struct conica_bspline_parse_limits {
    size_t max_ctrl; /**< control points, 1..CONICA_BSPLINE_MAX_CTRL (default: that) */
    int max_degree;  /**< degree, 1..CONICA_BSPLINE_MAX_DEGREE (default: that) */
} conica_bspline_parse_limits;

/** @brief The reader's default caps: the library maxima. */
CONICA_API conica_bspline_parse_limits conica_bspline_parse_limits_defaults(void);

/**
 * @brief conica_bspline_parse() with caller-chosen caps.
 *
 * A file over a cap fails with CONICA_ERR_LIMIT on the line that passes it
 * (`more than N control points (max_ctrl)`, `degree D exceeds N
 * (max_degree)`), before the values past the cap are stored; the `knots`
 * and `w` lines are capped at max_ctrl + max_degree + 1 values.
 * @param[in] buf,len text (need not be NUL-terminated, never written)
 * @param[in] lim     caps; NULL means the defaults
 * @param[out] out    replaced on success
 * @param[out] st     line (1-based) and byte offset of the error
 * @return as conica_bspline_parse, and CONICA_ERR_ARG for a cap outside
 *         its range
 */
CONICA_API conica_code conica_bspline_parse_ex(const char *buf, size_t len,
        const conica_bspline_parse_limits *lim, conica_bspline *out, conica_status *st);

/**
 * @brief Point (dim values) at parameter t by the triangular algorithm
 *        (eq. (1.10)-(1.11)); t is clamped to the domain [t_p, t_n].
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NONFINITE
 */
CONICA_API conica_code conica_bspline_eval(const conica_bspline *s, double t, double *out,
        conica_status *st);

/**
 * @brief r-th derivative (dim values) at t, eq. (1.13); 0 <= r <= degree.
 *        Rational splines: derivatives of the projected curve (quotient rule).
 *        At a knot the right derivative is returned (left one at t_n).
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NONFINITE
 */
CONICA_API conica_code conica_bspline_eval_deriv(const conica_bspline *s, double t, int r,
        double *out, conica_status *st);

/**
 * @brief Knot span: the index mu with t_mu <= t < t_{mu+1} and
 *        p <= mu <= n-1 (t = t_n gives the last non-empty span); 0 for
 *        NULL or an empty (initialised, never set) spline.
 */
CONICA_API size_t conica_bspline_find_span(const conica_bspline *s, double t);

/**
 * @brief Insert knot z once by Böhm's method (Lemma 1.18), in place.
 *        z must lie in the domain; the multiplicity of z must stay <= p+1.
 * @return CONICA_OK (s changed), CONICA_ERR_ARG, CONICA_ERR_LIMIT,
 *         CONICA_ERR_NOMEM (s unchanged on failure)
 */
CONICA_API conica_code conica_bspline_insert_knot(conica_bspline *s, double z,
        conica_status *st);

/**
 * @brief Insert k knots (any order, repetitions allowed) by repeated Böhm
 *        insertion, in place; s is unchanged on failure.
 */
CONICA_API conica_code conica_bspline_insert_knots(conica_bspline *s, const double *z,
        size_t k, conica_status *st);

/**
 * @brief Bézier form: a copy of s clamped to its domain whose interior knots
 *        all have multiplicity p+1, so that piece k (0 <= k <
 *        conica_bspline_bezier_count(s)) has the control points
 *        ctrl[k*(p+1) .. k*(p+1)+p] (and weights likewise).
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NOMEM, CONICA_ERR_LIMIT
 */
CONICA_API conica_code conica_bspline_to_bezier(const conica_bspline *s, conica_bspline *out,
        conica_status *st);

/** @brief Number of non-empty knot intervals (polynomial pieces) of s; 0 for
 *         NULL or an empty spline. */
CONICA_API size_t conica_bspline_bezier_count(const conica_bspline *s);

/**
 * @brief Control points (and weights, if rational) of polynomial piece k of s
 *        (0 <= k < conica_bspline_bezier_count) as a Bézier curve on its knot
 *        interval [*a, *b]. ctrl gets (p+1)*dim values, w (if not NULL and s
 *        is rational) p+1 weights; a, b may be NULL.
 * @return CONICA_OK, CONICA_ERR_ARG
 */
CONICA_API conica_code conica_bspline_bezier_piece(const conica_bspline *s, size_t k,
        double *ctrl, double *w, double *a, double *b, conica_status *st);

/** @brief Knot averages t*_j (Greville abscissae, Def. 1.10); out gets n
 *         values. NULL or an empty spline, or out NULL: nothing written. */
CONICA_API void conica_bspline_knot_averages(const conica_bspline *s, double *out);

/**
 * @brief Control polygon (Def. 1.12): n points of dimension
 *        conica_bspline_point_dim(s) -- (t*_j, c_j) for a function,
 *        c_j (projected, for rational curves) otherwise. NULL or an empty
 *        spline, or out NULL: nothing written.
 */
CONICA_API void conica_bspline_control_polygon(const conica_bspline *s, double *out);

/** @brief Dimension of plotted points: 2 for a function, else dim; 0 for NULL. */
CONICA_API int conica_bspline_point_dim(const conica_bspline *s);

/** @brief Domain [t_p, t_n] of s; NaN and NaN for NULL or an empty spline. */
CONICA_API void conica_bspline_domain(const conica_bspline *s, double *a, double *b);

/* ------------------------------------------------------------ surfaces */

/** Tensor-product B-spline surface (Definition 4.1). */
typedef struct conica_bspline_surface {
    int degree_u, degree_v; /**< p, q */
    int dim;                /**< 1 (height z(u,v), plotted as (u,v,z)) or 3 */
    size_t nu, nv;          /**< control net size */
    double *knots_u;        /**< nu + degree_u + 1 knots */
    double *knots_v;        /**< nv + degree_v + 1 knots */
    double *ctrl;           /**< nu*nv*dim values, index ((i*nv)+j)*dim */
    double *w;              /**< nu*nv positive weights or NULL */
} conica_bspline_surface;

/** @brief Empty surface, safe to free. */
CONICA_API void conica_bspline_surface_init(conica_bspline_surface *s);
/** @brief Release the arrays of s. */
CONICA_API void conica_bspline_surface_free(conica_bspline_surface *s);
/**
 * @brief Copy and validate a surface (same checks as conica_bspline_set per
 *        direction; nu*nv <= CONICA_BSPLINE_MAX_CTRL).
 */
CONICA_API conica_code conica_bspline_surface_set(int degree_u, int degree_v, int dim,
        const double *knots_u, size_t nknots_u, const double *knots_v, size_t nknots_v,
        const double *ctrl, size_t nu, size_t nv, const double *w,
        conica_bspline_surface *out, conica_status *st);
/**
 * @brief Point at (u, v): 3 values ((u, v, z) for a height surface).
 */
CONICA_API conica_code conica_bspline_surface_eval(const conica_bspline_surface *s,
        double u, double v, double *out, conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

/* SPDX-License-Identifier: MIT */
/**
 * @file curve.h
 * @brief Point-normal curves: storage, normal estimation and the text format
 *        of the reference implementation (`v x y` / `vn nx ny` lines).
 */
#ifndef CONICA_CURVE_H
#define CONICA_CURVE_H

#include <stdio.h>

#include "conica/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Upper bound on the points a parsed file may hold (input-controlled size). */
#define CONICA_CURVE_MAX_INPUT_POINTS ((size_t)1 << 24)

/**
 * A planar polygon with an optional normal per vertex.
 * `xy` holds n points interleaved (x0,y0,x1,y1,...); `nxy` holds n normals
 * the same way, or is NULL when the curve has no normals. Owned by the
 * struct: release with conica_curve_free().
 */
typedef struct conica_curve {
    size_t n;     /**< number of points */
    size_t cap;   /**< allocated capacity, in points */
    double *xy;   /**< 2n coordinates */
    double *nxy;  /**< 2n normal components, or NULL */
    int closed;   /**< non-zero: the last point connects to the first */
} conica_curve;

/** How normals are estimated from the points alone. */
typedef enum conica_normal_method {
    CONICA_NORMALS_AREA = 0,  /**< area-weighted average of the adjacent edge normals (reference default) */
    CONICA_NORMALS_CIRCLE = 1 /**< normal of the circle through each vertex and its two neighbours */
} conica_normal_method;

/** @brief Make *c an empty curve (safe to free). */
CONICA_API void conica_curve_init(conica_curve *c);

/** @brief Release the arrays of *c and make it empty again. Accepts NULL. */
CONICA_API void conica_curve_free(conica_curve *c);

/**
 * @brief Copy n points (and normals, if nxy is not NULL) into *out.
 * @param[in] xy     n interleaved points
 * @param[in] nxy    n interleaved normals, or NULL
 * @param[in] n      number of points
 * @param[in] closed non-zero for a closed curve
 * @param[out] out   receives the copy (its previous content is freed on success)
 * @param[out] st    optional detail
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_curve_set(const double *xy, const double *nxy, size_t n,
                                        int closed, conica_curve *out, conica_status *st);

/**
 * @brief Estimate unit normals from the points, consistently oriented
 *        (pointing to the right of the direction of travel for a curve that
 *        turns left, i.e. outward for a counter-clockwise closed curve).
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_DEGENERATE (fewer than 2
 *         distinct points), CONICA_ERR_NONFINITE, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_curve_estimate_normals(conica_curve *c, conica_normal_method method,
                                                     conica_status *st);

/**
 * @brief Parse the reference's text format from a buffer.
 *
 * `v x y` lines give the points, then optional `vn nx ny` lines give the
 * normals paired by order; `#`/`%` comment lines and blank lines are
 * ignored. Numbers are read independently of the C locale. The buffer is
 * never written to and need not be NUL-terminated.
 * @param[in] buf  text
 * @param[in] len  its length in bytes
 * @param[out] out receives the curve (closed flag set to 1; callers choose)
 * @param[out] st  line of the error in st->line
 * @return CONICA_OK, CONICA_ERR_PARSE, CONICA_ERR_NONFINITE, CONICA_ERR_DEGENERATE (a zero normal), CONICA_ERR_LIMIT, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_curve_parse(const char *buf, size_t len, conica_curve *out,
                                          conica_status *st);

/**
 * @brief conica_curve_parse() with a caller-chosen cap on the points.
 *
 * The lines are counted before anything is allocated, so a file over the
 * cap fails with CONICA_ERR_LIMIT (`more than N points (the reader's
 * max_points)`, on the first line past it) without allocating; memory is
 * 16 bytes per point (32 with normals), proportional to the input. The cap may be
 * raised past the default: the input's length bounds the points anyway
 * (a `v` line takes at least 5 bytes).
 * @param[in] buf,len    text, as conica_curve_parse()
 * @param[in] max_points most `v` lines, and most `vn` lines, accepted;
 *                       0 means CONICA_CURVE_MAX_INPUT_POINTS
 * @param[out] out       receives the curve (closed flag set to 1)
 * @param[out] st        line of the error in st->line
 * @return as conica_curve_parse()
 */
CONICA_API conica_code conica_curve_parse_ex(const char *buf, size_t len, size_t max_points,
                                             conica_curve *out, conica_status *st);

struct conica_curvel; /* conica/subdiv.h */

/**
 * @brief conica_curve_parse_ex() reading every number in long double, for
 *        precise mode (`conica subdivide --precise`).
 *
 * Same format, errors and cap; the numbers are correctly rounded to long
 * double (the 64-bit significand of x87 long double on x86-64), so that
 * samples given with 21 to 25 digits are not rounded to double first.
 * Values beyond the range of double are refused as non-finite, as
 * conica_curve_parse() refuses them.
 * @param[in] buf,len    text, as conica_curve_parse()
 * @param[in] max_points as conica_curve_parse_ex()
 * @param[out] out       receives the curve (a conica_curvel of
 *                       conica/subdiv.h; closed flag set to 1; its previous
 *                       content is freed on success; free with
 *                       conica_curvel_free())
 * @param[out] st        line of the error in st->line
 * @return as conica_curve_parse()
 */
CONICA_API conica_code conica_curvel_parse_ex(const char *buf, size_t len, size_t max_points,
                                              struct conica_curvel *out, conica_status *st);

/**
 * @brief Line of the index-th `v` line (normal == 0) or `vn` line
 *        (normal != 0) of a text that conica_curve_parse() accepted, so
 *        that a later error about point `index` (conica_status::offset of
 *        a CONICA_ERR_DEGENERATE or CONICA_ERR_NONFINITE from subdivision)
 *        can name its line.
 * @param[in] buf    the parsed text
 * @param[in] len    its length in bytes
 * @param[in] index  0-based point index
 * @param[in] normal non-zero: count `vn` lines instead of `v` lines
 * @return the 1-based line number, or 0 when there is no such line
 */
CONICA_API size_t conica_curve_line_of_point(const char *buf, size_t len, size_t index,
                                             int normal);

/**
 * @brief Write `v` lines then `vn` lines (if the curve has normals),
 *        each number printed with %.17g so that it round-trips; f is
 *        flushed, so a full disk is an error here, not later.
 * @return CONICA_OK, CONICA_ERR_ARG, or CONICA_ERR_IO (with strerror)
 */
CONICA_API conica_code conica_curve_write(FILE *f, const conica_curve *c, conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

/* SPDX-License-Identifier: MIT */
/**
 * @file conica_scad.h
 * @brief OpenSCAD export of Conica: 2D profiles (contours with holes) as
 *        OpenSCAD modules, with validation, hole arrangement, compact
 *        round-trip number printing and tolerance-driven point reduction.
 *
 * Conventions as in conica/common.h: inputs, outputs, then an optional
 * conica_status; outputs untouched on failure; `_init` then `_free`.
 *
 * Example (one closed contour, written as module `gear`, coordinates to
 * within 0.01/1000 of their values):
 * @code
 *   conica_scad_profile prof, rounded;
 *   conica_scad_profile_init(&prof);
 *   conica_scad_profile_init(&rounded);
 *   size_t g;
 *   conica_scad_add_group(&prof, "path 'outline'", CONICA_SCAD_FILL_NONZERO, 0, &g, NULL);
 *   conica_scad_add_contour(&prof, g, xy, n, NULL);
 *   conica_status st;
 *   conica_scad_layout lay;
 *   conica_scad_layout_init(&lay);
 *   if (conica_scad_drop_empty(&prof, NULL, NULL, NULL, &st) == CONICA_OK &&
 *       prof.ncontours > 0 &&
 *       conica_scad_round(&prof, 0.01 * CONICA_SCAD_ROUND_FRACTION, &rounded, &st) == CONICA_OK &&
 *       conica_scad_validate(&rounded, 0, NULL, &st) == CONICA_OK &&
 *       conica_scad_arrange(&rounded, &lay, &st) == CONICA_OK) {
 *       conica_scad_write_options o = conica_scad_write_defaults();
 *       o.module = "gear";
 *       conica_scad_write(stdout, &rounded, &lay, &o, &st);
 *   }
 *   conica_scad_layout_free(&lay);
 *   conica_scad_profile_free(&rounded);
 *   conica_scad_profile_free(&prof);
 * @endcode
 *
 * Messages name a contour the way its source does: the group's name (an
 * SVG element, e.g. "path 'plate'") and the contour's `subpath` number in
 * that group, from 1 ("path 'plate': subpath 2"); a group with an empty
 * name is "the contour" (one-contour inputs).
 */
#ifndef CONICA_SCAD_H
#define CONICA_SCAD_H

#include <stdio.h>

#include "conica/common.h"
#include "conica/curve.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Caps on input-controlled sizes. */
#define CONICA_SCAD_MAX_CONTOURS ((size_t)1 << 20)     /**< contours in one profile */
#define CONICA_SCAD_MAX_POINTS ((size_t)1 << 26)       /**< points in one profile */
#define CONICA_SCAD_DEFAULT_MAX_DENSE ((size_t)1 << 22) /**< dense points while refining to a tolerance */
#define CONICA_SCAD_MAX_MODULE_NAME 64                 /**< characters of a module name */
#define CONICA_SCAD_MAX_GROUP_NAME 96                  /**< bytes of a group name, NUL included */

/**
 * Largest |coordinate| a profile may have. OpenSCAD 2021.01 drops a
 * polygon point beyond about 1e15 ("Range check failed", the point is
 * ignored); 1e12 leaves room for the 2^-16 grid OpenSCAD snaps 2D geometry
 * to and for transforms applied in a model.
 */
#define CONICA_SCAD_MAX_COORD 1e12

/**
 * Fraction of the tolerance that conica_scad_round() may move a point:
 * a tool that refines or flattens to a tolerance T leaves T times this for
 * the written digits (the curve code gets T (1 - CONICA_SCAD_ROUND_FRACTION)).
 */
#define CONICA_SCAD_ROUND_FRACTION (1.0 / 1000.0)

/**
 * conica_scad_round() keeps a coordinate to within CONICA_SCAD_EXACT_REL of
 * the profile's largest |coordinate| M (in effect exactly: the number the
 * input had, e.g. 80 rather than 79.99999999999999) when that number is a
 * decimal on the grid of CONICA_SCAD_EXACT_MAX_DIGITS significant digits at
 * M's decimal exponent and takes at most this many digits more than the
 * rounding tolerance needs. (A computed point is that close to so short a
 * decimal about once in a thousand, and then costs a few digits.)
 */
#define CONICA_SCAD_EXACT_EXTRA_DIGITS 4
#define CONICA_SCAD_EXACT_MAX_DIGITS 9 /**< see CONICA_SCAD_EXACT_EXTRA_DIGITS */
#define CONICA_SCAD_EXACT_REL 1e-12 /**< see CONICA_SCAD_EXACT_EXTRA_DIGITS */

/**
 * A contour whose signed area is at most this fraction of its bounding
 * box's squared diagonal is treated as having zero area (a polygon folded
 * onto a line computes to rounding noise, not to 0).
 */
#define CONICA_SCAD_ZERO_AREA_REL 1e-14

/** Fill rule of a group of contours (SVG's `fill-rule`). */
typedef enum conica_scad_fill {
    CONICA_SCAD_FILL_NONZERO = 0,
    CONICA_SCAD_FILL_EVENODD = 1
} conica_scad_fill;

/** A group of contours filled together (one SVG element). */
typedef struct conica_scad_group {
    /** For messages, NUL-terminated: the source's name of the element
     *  (as the SVG layer says it: "path 'plate'", "rect (no id)"), or ""
     *  for a one-contour input ("the contour"). */
    char name[CONICA_SCAD_MAX_GROUP_NAME];
    conica_scad_fill fill;
    size_t line;          /**< source line for messages, 0 if none */
} conica_scad_group;

/** A closed contour (the last point connects to the first; not repeated). */
typedef struct conica_scad_contour {
    size_t group;   /**< index into conica_scad_profile.groups */
    /** Its number within the group for messages, from 1: conica_scad_add_contour()
     *  numbers the contours added to a group one after the other 1, 2, ...;
     *  a caller that leaves some of the source's subpaths out sets the
     *  source's own number here. */
    size_t subpath;
    size_t n;       /**< points */
    double *xy;     /**< 2n coordinates, owned */
} conica_scad_contour;

/** A set of contours to be written as one polygon. Owns everything. */
typedef struct conica_scad_profile {
    size_t ncontours, ccap;
    conica_scad_contour *contours;
    size_t npoints; /**< points over all contours (kept by conica_scad_add_contour) */
    size_t ngroups, gcap;
    conica_scad_group *groups;
} conica_scad_profile;

/** @brief Make *p empty (safe to free). */
CONICA_API void conica_scad_profile_init(conica_scad_profile *p);
/** @brief Release everything *p owns. Accepts NULL. */
CONICA_API void conica_scad_profile_free(conica_scad_profile *p);

/**
 * @brief Add a group (name is truncated to CONICA_SCAD_MAX_GROUP_NAME - 1
 *        bytes; NULL gives "").
 * @param[out] index receives the new group's index (may be NULL)
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_LIMIT, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_scad_add_group(conica_scad_profile *p, const char *name,
                                             conica_scad_fill fill, size_t line, size_t *index,
                                             conica_status *st);

/**
 * @brief Copy a closed contour of n points into group `group` (its
 *        `subpath` number: one more than the previous contour's when that
 *        is in the same group, else 1).
 * @return CONICA_OK, CONICA_ERR_ARG (bad group, n == 0), CONICA_ERR_NONFINITE,
 *         CONICA_ERR_LIMIT, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_scad_add_contour(conica_scad_profile *p, size_t group,
                                               const double *xy, size_t n, conica_status *st);

/** Kinds of validation failures. */
typedef enum conica_scad_problem {
    CONICA_SCAD_OK = 0,
    CONICA_SCAD_TOO_FEW_POINTS,   /**< fewer than 3 points */
    CONICA_SCAD_DUPLICATE_POINT,  /**< two consecutive points are equal */
    CONICA_SCAD_ZERO_AREA,        /**< no enclosed area */
    CONICA_SCAD_SELF_INTERSECTION,/**< two segments of one contour meet */
    CONICA_SCAD_CONTOURS_CROSS,   /**< segments of two contours meet */
    CONICA_SCAD_NEGATIVE_X,       /**< x < 0 with rotate_extrude */
    CONICA_SCAD_OUT_OF_RANGE      /**< |x| or |y| > CONICA_SCAD_MAX_COORD */
} conica_scad_problem;

/** Where validation failed (indices are 0-based; messages are 1-based). */
typedef struct conica_scad_violation {
    conica_scad_problem problem;
    /** segment i runs from point i to point i+1 (mod n); for a problem of
     *  one point (DUPLICATE_POINT, NEGATIVE_X, OUT_OF_RANGE) segment_a is
     *  that point */
    size_t contour_a, segment_a;
    size_t contour_b, segment_b;
    double x, y;                  /**< a point near the problem */
} conica_scad_violation;

/**
 * @brief Check that the profile can be written as an OpenSCAD polygon that
 *        means what its fill rules say: every coordinate within
 *        +-CONICA_SCAD_MAX_COORD (checked first: a triangle at 1e200 is out
 *        of range, not of zero area), each contour has >= 3 points, no
 *        equal consecutive points, non-zero area, no two segments meet
 *        (within a contour or between contours; exact orientation tests on
 *        a uniform grid, about O(n) for evenly spread segments), and, with
 *        `rotate_extrude` non-zero, no point with x < 0.
 * @param[out] v  first problem found (may be NULL); problem CONICA_SCAD_OK when valid
 * @param[out] st message naming the contour (see the file comment) and the
 *                points or segment pair
 * @return CONICA_OK, CONICA_ERR_DEGENERATE (invalid profile), CONICA_ERR_LIMIT
 *         (OUT_OF_RANGE), CONICA_ERR_ARG, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_scad_validate(const conica_scad_profile *p, int rotate_extrude,
                                            conica_scad_violation *v, conica_status *st);

/**
 * @brief Only the range part of conica_scad_validate(): every coordinate
 *        within +-CONICA_SCAD_MAX_COORD.
 * @param[out] v  the first point beyond it (may be NULL)
 * @param[out] st message naming the contour, the point and the coordinate
 * @return CONICA_OK, CONICA_ERR_LIMIT, CONICA_ERR_ARG
 */
CONICA_API conica_code conica_scad_check_range(const conica_scad_profile *p,
                                               conica_scad_violation *v, conica_status *st);

/** Receives one contour conica_scad_drop_empty() removes (before it is removed). */
typedef void (*conica_scad_drop_fn)(void *ctx, const conica_scad_profile *p, size_t contour,
                                    const conica_scad_violation *v, const char *message);

/**
 * @brief Remove the contours that enclose no area: fewer than 3 points,
 *        every point on one line (exact orientation tests), or a signed
 *        area within CONICA_SCAD_ZERO_AREA_REL of the squared box diagonal
 *        and no two of its own segments meeting (a bowtie is left for
 *        conica_scad_validate() to report as self-intersecting). Contours
 *        with a coordinate beyond CONICA_SCAD_MAX_COORD are left alone.
 *        The others keep their order, group and `subpath` number.
 * @param[in]  fn      called once per removed contour, with a message as
 *                     conica_scad_validate() would give (may be NULL)
 * @param[out] dropped how many were removed (may be NULL)
 * @return CONICA_OK (also when every contour went), CONICA_ERR_ARG, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_scad_drop_empty(conica_scad_profile *p, conica_scad_drop_fn fn,
                                              void *ctx, size_t *dropped, conica_status *st);

/**
 * @brief A copy of the profile whose coordinates are the shortest
 *        decimals within `h` of each coordinate (so every point moves at
 *        most h sqrt(2)), except that a coordinate is kept to within
 *        CONICA_SCAD_EXACT_REL of the profile's largest |coordinate| when
 *        a decimal of CONICA_SCAD_EXACT_MAX_DIGITS significant digits at
 *        that size, and at most CONICA_SCAD_EXACT_EXTRA_DIGITS more than h
 *        needs, does that (the input's own numbers survive: 80, not
 *        79.99999999999999; 12.3456789 stays).
 *        conica_scad_format_double() prints each as that decimal.
 *        For a polygon within T of the curve, call it with
 *        h = T * CONICA_SCAD_ROUND_FRACTION / sqrt(2) after refining to
 *        T (1 - CONICA_SCAD_ROUND_FRACTION). Rounding can make points meet:
 *        validate the copy.
 * @param[in]  h   > 0 (absolute, the profile's units)
 * @param[out] out receives the copy (its previous content freed on success)
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_scad_round(const conica_scad_profile *p, double h,
                                         conica_scad_profile *out, conica_status *st);

/**
 * @brief The contour as messages name it: "path 'plate': subpath 2", or
 *        "the contour" when its group has an empty name.
 * @return the length written (snprintf's)
 */
CONICA_API size_t conica_scad_describe(const conica_scad_profile *p, size_t contour, char *buf,
                                       size_t cap);

/** One path of the output polygon. */
typedef struct conica_scad_path {
    size_t contour;   /**< index into the profile */
    int hole;         /**< non-zero: a hole (written clockwise), else outer (counter-clockwise) */
    int reversed;     /**< the contour's points are written in reverse order */
    size_t parent;    /**< enclosing kept path's contour, or SIZE_MAX */
} conica_scad_path;

/** Output order of the contours: outers first, then holes. */
typedef struct conica_scad_layout {
    size_t npaths;
    conica_scad_path *paths;
    size_t dropped;   /**< contours that separate no filled from unfilled region */
    size_t outers, holes;
    int convexity;    /**< estimated crossings of a straight ray / 2 (>= 1) */
} conica_scad_layout;

/** @brief Make *l empty (safe to free). */
CONICA_API void conica_scad_layout_init(conica_scad_layout *l);
/** @brief Release *l's array. Accepts NULL. */
CONICA_API void conica_scad_layout_free(conica_scad_layout *l);

/**
 * @brief Decide outer contours and holes by containment and each group's
 *        fill rule (union over groups), drop contours that do not bound the
 *        filled region, orient outers counter-clockwise and holes
 *        clockwise. Needs a profile without crossings (conica_scad_validate).
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_scad_arrange(const conica_scad_profile *p, conica_scad_layout *out,
                                           conica_status *st);

/** Writer options; start from conica_scad_write_defaults(). */
typedef struct conica_scad_write_options {
    const char *module;     /**< identifier [A-Za-z_][A-Za-z0-9_]* (default "profile") */
    const char *header;     /**< comment text (may hold newlines), or NULL */
    int extrude;            /**< non-zero: emit NAME_extruded(height, center) */
    double extrude_height;  /**< its default height */
    int revolve;            /**< non-zero: emit NAME_revolved(angle) */
    double revolve_angle;   /**< its default angle (degrees, (0, 360]) */
    /** Non-zero: end with a top-level call (NAME_extruded(), else
     *  NAME_revolved(), else NAME()) so the file renders alone. Default 0:
     *  no top-level geometry, so `include <file>` adds only definitions. */
    int instantiate;
} conica_scad_write_options;

/** @brief Defaults: module "profile", no wrappers, no top-level call. */
CONICA_API conica_scad_write_options conica_scad_write_defaults(void);

/**
 * @brief Why s cannot name the module, or NULL when it can: it must be an
 *        OpenSCAD identifier ([A-Za-z_][A-Za-z0-9_]*, at most
 *        CONICA_SCAD_MAX_MODULE_NAME characters), not a reserved word
 *        (for, module, function, if, else, let, each, assert, echo, true,
 *        false, undef, include, use), not one of OpenSCAD's built-in
 *        modules (translate, circle, polygon, union, offset, ...: a module
 *        of that name would replace the built-in) and not one of its
 *        built-in functions (sin, len, str, concat, ...). The helper names
 *        the file defines (NAME_points, NAME_paths, NAME_bbox,
 *        NAME_extruded, NAME_revolved) end in suffixes no built-in has.
 * @return a static string (never free it), or NULL
 */
CONICA_API const char *conica_scad_name_problem(const char *s);

/** @brief Non-zero when s can name the module (conica_scad_name_problem() is NULL). */
CONICA_API int conica_scad_valid_name(const char *s);

/**
 * @brief Write `function NAME_points()` ([[x, y], ...], outers then holes),
 *        `function NAME_paths()` (index lists into it),
 *        `function NAME_bbox()` ([[xmin, ymin], [xmax, ymax]], the extremes
 *        of the written numbers), `module NAME(center=false)` (the polygon;
 *        center=true translates the box's centre to the origin), the
 *        requested wrappers, and, with o->instantiate, a top-level call.
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_IO
 */
CONICA_API conica_code conica_scad_write(FILE *f, const conica_scad_profile *p,
                                         const conica_scad_layout *l,
                                         const conica_scad_write_options *o, conica_status *st);

/**
 * @brief Shortest of %.15g/%.16g/%.17g that reads back to exactly v
 *        (so 0.1 prints as 0.1, 1 as 1, and -0 as 0).
 * @param[out] buf at least 32 bytes
 * @return the length written
 */
CONICA_API size_t conica_scad_format_double(double v, char *buf, size_t cap);

/**
 * @brief Fewest points, taken from a dense polyline whose vertices lie on
 *        the curve, such that every dense vertex is within `tol` of the
 *        chord that skips it (greedy longest chord, galloping + bisection,
 *        every accepted chord checked in full; closed curves try several
 *        starting points).
 * @param[in]  xy      n dense points
 * @param[in]  closed  non-zero for a closed curve
 * @param[in]  tol     > 0
 * @param[out] out     new array of 2 * *nout doubles (free with free())
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_scad_thin(const double *xy, size_t n, int closed, double tol,
                                        double **out, size_t *nout, conica_status *st);

/** What conica_scad_refine() did. */
typedef struct conica_scad_refine_info {
    int levels;            /**< subdivision levels of the dense curve */
    size_t dense_points;   /**< its points */
    double dense_error;    /**< estimated distance of the dense polyline from the limit curve */
    size_t points;         /**< points kept */
} conica_scad_refine_info;

/**
 * @brief A closed point-normal curve refined by conic subdivision until the
 *        dense polyline is within tol/256 of the limit curve (estimated from
 *        its three-point sagittas), then thinned to the fewest points with
 *        chords within the rest of the tolerance (conica_scad_thin); one
 *        more level is thinned as well and kept when it needs fewer points.
 * @param[in]  in          closed input curve (normals optional)
 * @param[in]  tol         > 0, in the curve's units
 * @param[in]  max_dense   cap on dense points (0: CONICA_SCAD_DEFAULT_MAX_DENSE)
 * @param[out] out         new array of 2 * *nout doubles (free with free())
 * @param[out] info        optional
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_LIMIT, or a conica_subdivide() error
 */
CONICA_API conica_code conica_scad_refine(const conica_curve *in, double tol, size_t max_dense,
                                          double **out, size_t *nout,
                                          conica_scad_refine_info *info, conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

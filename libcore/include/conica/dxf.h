/* SPDX-License-Identifier: MIT */
/**
 * @file dxf.h
 * @brief ASCII DXF drawings (R12..R2018) into the shared path model: the
 *        profiles CAD tools export, arcs, bulges and splines exact.
 *
 * conica_dxf_read() reads the model space of an ASCII DXF file (binary DXF
 * is refused): LINE, ARC, CIRCLE, ELLIPSE, LWPOLYLINE and 2D POLYLINE with
 * bulges, SPLINE (control points, knots, weights), INSERT of BLOCKs (scale,
 * mirroring, rotation, column/row arrays, nesting) and, when the drawing has
 * nothing else, HATCH boundary paths. Every entity goes into a conica_path
 * exactly: straight lines as lines, arcs, bulges and ellipses as rational
 * quadratic Béziers of at most 90 degrees, splines as their Bézier pieces.
 * Separate entities whose ends meet within a gap tolerance are chained
 * into closed contours (in either direction); an outline that does not
 * close is an error naming where it stops (or, with open_mode, is closed by
 * a straight edge with a warning). Other entity types are skipped with one
 * warning per type. Coordinates come out in millimetres (or any unit the
 * caller names) from the header's $INSUNITS / $MEASUREMENT.
 *
 * Example:
 * @code
 *   conica_dxf_settings s = conica_dxf_defaults();
 *   conica_dxf_drawing d;
 *   conica_dxf_drawing_init(&d);
 *   if (conica_dxf_read(buf, len, &s, &d, &st) == CONICA_OK)
 *       conica_path_flatten(&d.path, &ps, &res, &st);
 *   conica_dxf_drawing_free(&d);
 * @endcode
 */
#ifndef CONICA_DXF_H
#define CONICA_DXF_H

#include <stddef.h>

#include "conica/bspline.h"
#include "conica/common.h"
#include "conica/path.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Default cap on the input size, bytes. */
#define CONICA_DXF_DEFAULT_MAX_BYTES ((size_t)256 << 20)
/** Default cap on the entities read (after INSERT expansion). */
#define CONICA_DXF_DEFAULT_MAX_ENTITIES ((size_t)1 << 20)
/** Default cap on the vertices (control points, polyline vertices) of one entity. */
#define CONICA_DXF_DEFAULT_MAX_VERTICES ((size_t)1 << 19)
/** Default cap on the knots of one spline. */
#define CONICA_DXF_DEFAULT_MAX_KNOTS ((size_t)1 << 19)
/** Default cap on the total control points of a drawing. */
#define CONICA_DXF_DEFAULT_MAX_POINTS ((size_t)1 << 22)
/** Default cap on the nesting of INSERTs in blocks. */
#define CONICA_DXF_DEFAULT_MAX_DEPTH 16
/** Coordinates beyond this magnitude (in the file or after transforms) are refused. */
#define CONICA_DXF_MAX_COORD 1e15
/** Default gap tolerance: this fraction of the drawing's extents (bounding-box diagonal). */
#define CONICA_DXF_DEFAULT_REL_GAP 1e-9
/** The default gap grows to four times the precision the coordinates are
 *  written with (half a unit in the last decimal of the finest number)
 *  while that stays below this fraction of the extents. */
#define CONICA_DXF_PRECISION_GAP_REL 1e-6

/** Caps on what one file may make the reader allocate. */
typedef struct conica_dxf_limits {
    size_t max_bytes;    /**< input size (default CONICA_DXF_DEFAULT_MAX_BYTES) */
    size_t max_entities; /**< entities read, after INSERT expansion */
    size_t max_vertices; /**< vertices or control points of one entity */
    size_t max_knots;    /**< knots of one spline */
    size_t max_points;   /**< control points of the whole drawing */
    int max_depth;       /**< INSERT nesting (1..64) */
} conica_dxf_limits;

/** Warning callback: line is the DXF line it concerns (0: the whole file). */
typedef void (*conica_dxf_warn_fn)(void *ctx, size_t line, const char *message);

/** What conica_dxf_read() does with an outline that does not close. */
typedef enum conica_dxf_open {
    CONICA_DXF_OPEN_ERROR = 0, /**< an error naming where it stops (default) */
    CONICA_DXF_OPEN_CLOSE      /**< closed by a straight edge, with a warning naming its length */
} conica_dxf_open;

/** Settings; start from conica_dxf_defaults(). */
typedef struct conica_dxf_settings {
    conica_dxf_limits limits;
    /** Millimetres per output unit (default 1: millimetres; 25.4: inches). */
    double unit_mm;
    /** Millimetres per drawing unit when the header names none ($INSUNITS 0
     *  or absent, no $MEASUREMENT): default 1. */
    double unitless_mm;
    /** Gap tolerance in output units (> 0), or 0: the default,
     *  CONICA_DXF_DEFAULT_REL_GAP times the extents, or four times the
     *  precision the coordinates are written with when that is larger and
     *  at most CONICA_DXF_PRECISION_GAP_REL times the extents. */
    double gap;
    conica_dxf_open open_mode;
    /** Layers to read (names, exact match), or nlayers 0: every visible one
     *  (frozen and off layers of the LAYER table are skipped). */
    const char *const *layers;
    size_t nlayers;
    conica_dxf_warn_fn warn; /**< optional */
    void *warn_ctx;
} conica_dxf_settings;

/** A drawing read into the path model. Owns everything. */
typedef struct conica_dxf_drawing {
    conica_path path;       /**< closed DRAWN subpaths in output units; segment tags are DXF lines */
    size_t *sub_line;       /**< path.nsub: the DXF line of each contour's first entity */
    char **layers;          /**< the layers geometry was read from, in order of first use */
    size_t nlayers;
    size_t entities;        /**< entities read into geometry (after INSERT expansion) */
    size_t skipped;         /**< entities skipped (other types, hidden layers, ...) */
    size_t joined;          /**< contours made of more than one entity */
    size_t closed_open;     /**< outlines that did not close, closed by a straight edge */
    double file_unit_mm;    /**< millimetres per drawing unit, from the header */
    const char *file_unit;  /**< its name ("mm", "in", "unitless", ...; static storage) */
    double gap;             /**< the gap tolerance used, output units */
    int hatch_only;         /**< the contours are HATCH boundaries (nothing else was drawn) */
} conica_dxf_drawing;

/** @brief Default limits (the CONICA_DXF_DEFAULT_* caps). */
CONICA_API conica_dxf_limits conica_dxf_limits_defaults(void);
/** @brief Default settings: millimetres, default gap, open outlines an error, every visible layer. */
CONICA_API conica_dxf_settings conica_dxf_defaults(void);
/** @brief Make *d empty (safe to free). */
CONICA_API void conica_dxf_drawing_init(conica_dxf_drawing *d);
/** @brief Release everything *d owns; accepts NULL. */
CONICA_API void conica_dxf_drawing_free(conica_dxf_drawing *d);

/** @brief Non-zero when buf looks like a DXF file (ASCII: "0" then
 *         "SECTION" or a 999 comment first; or the binary DXF sentinel). */
CONICA_API int conica_dxf_sniff(const char *buf, size_t len);

/**
 * @brief Read the model space of an ASCII DXF drawing into closed contours.
 * @param[in]  buf,len the file (need not be NUL-terminated, never written)
 * @param[in]  s       settings, or NULL for defaults
 * @param[out] out     replaced on success (previous contents freed)
 * @param[out] st      optional detail; st->line is the DXF line
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_PARSE (malformed file, an
 *         outline that does not close), CONICA_ERR_UNSUPPORTED (binary DXF,
 *         fit-point-only spline), CONICA_ERR_NONFINITE, CONICA_ERR_LIMIT,
 *         CONICA_ERR_DEGENERATE (nothing to read), CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_dxf_read(const char *buf, size_t len, const conica_dxf_settings *s,
                                       conica_dxf_drawing *out, conica_status *st);

/**
 * @brief One SPLINE entity of the model space as a B-spline, in drawing
 *        units: the one with the given handle (group 5), or, with handle
 *        NULL, the only SPLINE of the file. dim is 2, or 3 when its control
 *        points do not share one z.
 * @param[out] line the DXF line of the entity (may be NULL)
 * @return CONICA_OK, CONICA_ERR_ARG (no such spline, several without a
 *         handle), the codes of conica_dxf_read()
 */
CONICA_API conica_code conica_dxf_spline(const char *buf, size_t len, const char *handle,
                                         const conica_dxf_limits *lim, conica_bspline *out,
                                         size_t *line, conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

/* SPDX-License-Identifier: MIT */
/**
 * @file conica_svg.h
 * @brief SVG layer of Conica: safe document load/save (libxml2), the SVG 2
 *        path-data grammar to absolute segments, and outlines as polylines
 *        (smoothed by conic subdivision, flattened by the plotter, or kept).
 *
 * Conventions as in conica/common.h: inputs, outputs, then an optional
 * conica_status; outputs untouched on failure; `_init` then `_free`.
 *
 * Example (read every outline of a file as polylines, smoothed 4 levels):
 * @code
 *   conica_svg_doc *doc = NULL;
 *   conica_svg_limits lim = conica_svg_limits_defaults();
 *   conica_status st;
 *   if (conica_svg_doc_load(buf, len, &lim, &doc, &st) != CONICA_OK)
 *       fprintf(stderr, "line %zu: %s\n", st.line, st.message);
 *   conica_svg_settings set = conica_svg_defaults();   // smoothing, K = 4
 *   conica_svg_shapes shapes;
 *   conica_svg_shapes_init(&shapes);
 *   if (conica_svg_extract(doc, &set, &shapes, &st) == CONICA_OK) {
 *       for (size_t i = 0; i < shapes.nsubpaths; i++) {
 *           const conica_svg_subpath *sp = &shapes.subpaths[i];
 *           // sp->n points sp->xy[2*j], sp->xy[2*j+1]; sp->closed;
 *           // shapes.elements[sp->element].id / .fill_rule
 *       }
 *   }
 *   conica_svg_shapes_free(&shapes);
 *   conica_svg_doc_free(doc);
 * @endcode
 *
 * Geometry is in each element's own user space: transforms are NOT applied
 * (conica_svg_element.has_transform says when one is present).
 */
#ifndef CONICA_SVG_H
#define CONICA_SVG_H

#include <stddef.h>
#include <stdio.h>

#include "conica/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------ limits */

/** Default caps on input-controlled sizes (each has a setting and a flag). */
#define CONICA_SVG_DEFAULT_MAX_BYTES ((size_t)64 << 20)     /**< document bytes */
#define CONICA_SVG_DEFAULT_MAX_DEPTH ((size_t)256)          /**< XML element nesting */
#define CONICA_SVG_DEFAULT_MAX_ELEMENTS ((size_t)1 << 20)   /**< XML elements */
#define CONICA_SVG_DEFAULT_MAX_PATH_BYTES ((size_t)32 << 20) /**< one d/points attribute */
#define CONICA_SVG_DEFAULT_MAX_POINTS ((size_t)1 << 26)     /**< output points, whole document */
/** Attributes of one element (xmlns declarations not counted): libxml2's
 * duplicate-attribute check is quadratic in this (10^5 attributes on one
 * <path> took minutes); SVG elements carry a few dozen at most. */
#define CONICA_SVG_DEFAULT_MAX_ATTRIBUTES ((size_t)256)
/** Namespace declarations (xmlns, xmlns:p) in scope at one element, its
 * own and its ancestors': libxml2 looks every prefix up through all of
 * them; Inkscape and Illustrator declare about ten, on the root. */
#define CONICA_SVG_DEFAULT_MAX_NAMESPACES ((size_t)64)

/** Caps applied while loading and processing a document. */
typedef struct conica_svg_limits {
    size_t max_bytes;       /**< document size in bytes */
    size_t max_depth;       /**< element nesting depth */
    size_t max_elements;    /**< number of elements */
    size_t max_path_bytes;  /**< length of one `d` or `points` attribute */
    size_t max_points;      /**< output points over the whole document */
    size_t max_attributes;  /**< attributes of one element (xmlns declarations apart) */
    size_t max_namespaces;  /**< namespace declarations in scope at one element */
} conica_svg_limits;

/** @brief The CONICA_SVG_DEFAULT_* values. */
CONICA_API conica_svg_limits conica_svg_limits_defaults(void);

/* ------------------------------------------------------------ path data */

/** Kinds of absolute segments. */
typedef enum conica_svg_seg_type {
    CONICA_SVG_SEG_MOVE = 0,  /**< starts a subpath at (x1,y1) */
    CONICA_SVG_SEG_LINE,      /**< L/H/V, a zero-radius arc, or the line of Z */
    CONICA_SVG_SEG_QUAD,      /**< Q/T: control point c[0],c[1] */
    CONICA_SVG_SEG_CUBIC,     /**< C/S: controls c[0],c[1] and c[2],c[3] */
    CONICA_SVG_SEG_ARC,       /**< A with non-zero radii: centre parametrisation filled */
    CONICA_SVG_SEG_CLOSE      /**< Z: (x0,y0) current point, (x1,y1) subpath start */
} conica_svg_seg_type;

/**
 * One absolute segment. Every segment but MOVE runs from (x0,y0) to (x1,y1).
 * Arcs (SVG 2 implementation notes, F.6.5/F.6.6): rx, ry are the radii after
 * scaling up when too small, phi the x-axis rotation in radians, (cx,cy) the
 * centre, theta1 the start angle and dtheta the signed sweep (radians), so
 * the point at t in [0,1] is centre + R(phi) (rx cos θ, ry sin θ) with
 * θ = theta1 + t dtheta. An arc with a zero radius is a LINE; an arc whose
 * end points coincide is dropped (F.6.2).
 */
typedef struct conica_svg_seg {
    conica_svg_seg_type type;
    char cmd;             /**< command letter in effect (implicit repeats included) */
    size_t offset;        /**< byte offset of the segment's first token in the data */
    double x0, y0;        /**< start point */
    double x1, y1;        /**< end point */
    double c[4];          /**< control points (QUAD: c[0..1]; CUBIC: c[0..3]) */
    double rx, ry, phi;   /**< ARC: scaled radii, rotation (radians) */
    int large_arc, sweep; /**< ARC: flags as written */
    double cx, cy;        /**< ARC: centre */
    double theta1, dtheta;/**< ARC: start angle and signed sweep (radians) */
} conica_svg_seg;

/** A parsed `d` attribute: the valid prefix as absolute segments. */
typedef struct conica_svg_path {
    size_t n, cap;
    conica_svg_seg *seg;
    int has_error;        /**< non-zero: data after error_offset was ignored (SVG 2 error handling) */
    size_t error_offset;  /**< byte offset of the first bad token */
    char error[128];      /**< what was wrong there */
} conica_svg_path;

/** @brief Make *p empty (safe to free). */
CONICA_API void conica_svg_path_init(conica_svg_path *p);
/** @brief Release *p's array. Accepts NULL. */
CONICA_API void conica_svg_path_free(conica_svg_path *p);

/**
 * @brief Parse SVG 2 path data (the whole grammar: all commands in both
 *        cases, implicit repeats, packed numbers and arc flags, commas or
 *        whitespace anywhere allowed), numbers read without the C locale.
 *
 * Malformed data is handled as browsers do: the segments before the first
 * error are kept, p->has_error/error_offset/error say where and why, and the
 * call still returns CONICA_OK. The buffer is never written and need not be
 * NUL-terminated.
 * @param[in]  d            path data
 * @param[in]  len          its length in bytes
 * @param[in]  max_segments cap on segments (0 = no cap besides memory)
 * @param[out] out          receives the segments (previous content freed on success)
 * @param[out] st           optional detail
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_LIMIT, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_svg_path_parse(const char *d, size_t len, size_t max_segments,
                                             conica_svg_path *out, conica_status *st);

/**
 * @brief Parse a `points` attribute (polyline/polygon): pairs of numbers
 *        separated by commas/whitespace. An odd count or a bad token keeps
 *        the valid pairs before it and reports the offset in *error_offset
 *        (SIZE_MAX when the list is clean).
 * @param[out] xy  new array of 2 * *n doubles (free with free()), NULL if *n == 0
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_LIMIT, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_svg_points_parse(const char *s, size_t len, size_t max_points,
                                               double **xy, size_t *n, size_t *error_offset,
                                               conica_status *st);

/* ------------------------------------------------------------ document */

/** A loaded document (libxml2 tree). Opaque; free with conica_svg_doc_free(). */
typedef struct conica_svg_doc conica_svg_doc;

/**
 * @brief Parse an SVG document from memory, safely: no network
 *        (XML_PARSE_NONET), no external DTD, no entity substitution, no
 *        XInclude; libxml2's own caps (10 MB on one token, 256 levels)
 *        give way to ours (XML_PARSE_HUGE: the document size cap bounds
 *        every token, lim->max_path_bytes one path's data, so a single
 *        path of 10^6 vertices is read), the document parsed in one pass
 *        (linear in one long attribute value); depth and element caps are counted while
 *        parsing, so the parse stops where one is crossed; an entity declaration
 *        that could expand (external or parameter entity: XXE; text with
 *        references or markup: billion laughs; text over 1 KB) makes the
 *        load fail with CONICA_ERR_UNSUPPORTED, short plain-text entities
 *        (Illustrator's &ns_svg;) are kept; size, depth and element caps
 *        from *lim; the attributes of each element and the namespace
 *        declarations in scope at it are counted by a linear scan of the
 *        start tags before libxml2 sees them (its work per element grows
 *        with the product of those counts), so an element over
 *        lim->max_attributes or lim->max_namespaces fails the load with
 *        CONICA_ERR_LIMIT and its line before any parsing.
 *        Any error libxml2 reports fails the load, also those
 *        after which libxml2 itself goes on or stops with the document
 *        still "well-formed" (a text node over its token cap, an unbound
 *        namespace prefix): st->message then starts with what was wrong and
 *        quotes libxml2's first message; libxml2 prints nothing itself.
 *        Blank text, comments, namespaces and unknown nodes are
 *        kept, and the document keeps a copy of buf, so a save reproduces
 *        them byte for byte (conica_svg_doc_save()).
 * @param[in]  buf  document bytes
 * @param[in]  len  length
 * @param[in]  lim  caps, or NULL for defaults
 * @param[out] out  receives the document
 * @param[out] st   st->line is libxml2's line for XML errors
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_PARSE, CONICA_ERR_LIMIT,
 *         CONICA_ERR_UNSUPPORTED, CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_svg_doc_load(const char *buf, size_t len,
                                           const conica_svg_limits *lim, conica_svg_doc **out,
                                           conica_status *st);

/**
 * @brief conica_svg_doc_load() that keeps buf itself instead of a copy (a
 *        large document is not held twice).
 * @param[in]  buf  document bytes from malloc(); on success the document
 *                  owns them (conica_svg_doc_free() frees them, the caller
 *                  must not), on failure they stay the caller's
 * @param[in]  len  length
 * @param[in]  lim  caps, or NULL for defaults
 * @param[out] out  receives the document
 * @param[out] st   as for conica_svg_doc_load()
 * @return as conica_svg_doc_load()
 */
CONICA_API conica_code conica_svg_doc_load_owned(char *buf, size_t len,
                                                 const conica_svg_limits *lim,
                                                 conica_svg_doc **out, conica_status *st);

/** @brief Release a document. Accepts NULL. */
CONICA_API void conica_svg_doc_free(conica_svg_doc *doc);

/**
 * @brief Serialise the document byte for byte as it was read, except the
 *        attribute values conica_svg_process() rewrote: the loaded bytes
 *        (kept by conica_svg_doc_load()) with the new values spliced in at
 *        their attributes (same quote, its entity rules), new attributes
 *        after an element's last one, a converted shape renamed in both
 *        tags and without its geometry attributes. Where the bytes cannot
 *        be matched to the tree (a UTF-16 document), libxml2 serialises it
 *        without reformatting (the input's XML declaration verbatim, none
 *        if it had none; a document without a declared encoding is written
 *        as UTF-8).
 * @param[out] buf new buffer (free with conica_svg_buffer_free()), NUL-terminated
 * @param[out] len its length without the NUL
 * @return CONICA_OK, CONICA_ERR_NOMEM, CONICA_ERR_IO
 */
CONICA_API conica_code conica_svg_doc_save(const conica_svg_doc *doc, char **buf, size_t *len,
                                           conica_status *st);
/**
 * @brief As conica_svg_doc_save(), written to f as it is serialised (no
 *        copy of the whole document in memory). On failure part of the
 *        document may have been written: write to a temporary file.
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_IO (a write error)
 */
CONICA_API conica_code conica_svg_doc_write(const conica_svg_doc *doc, FILE *f,
                                            conica_status *st);

/** @brief Free a buffer from conica_svg_doc_save(). Accepts NULL. */
CONICA_API void conica_svg_buffer_free(char *buf);

/**
 * Size of the root `svg` element, so a caller can convert user units to mm.
 * CSS units: 1in = 25.4mm = 96px = 72pt = 6pc, 1cm = 10mm, 1Q = 0.25mm.
 */
typedef struct conica_svg_viewport {
    int has_width, has_height;   /**< the attribute is present and parsed */
    double width, height;        /**< number as written */
    char width_unit[4], height_unit[4]; /**< "", "px", "mm", "cm", "in", "pt", "pc", "Q", "%", "em", "ex" */
    double width_mm, height_mm;  /**< absolute size in mm, or NaN (relative unit / absent) */
    int has_viewbox;
    double viewbox[4];           /**< min-x, min-y, width, height */
    /** mm per user unit: width_mm / viewBox width (height for y) with a
     *  viewBox and absolute size; without a viewBox the user unit is a px
     *  (25.4/96 mm); NaN when it cannot be known (relative size + viewBox).
     *  preserveAspectRatio is not applied. */
    double mm_per_unit_x, mm_per_unit_y;
} conica_svg_viewport;

/**
 * @brief Convert a length between CSS absolute units ("" and "px", "mm",
 *        "cm", "in", "pt", "pc", "Q"; 96 px per inch) through one exact
 *        fraction: the same unit gives v unchanged, px to in is v / 96.
 * @return the length in `to`, or NaN when either unit is relative or unknown
 */
CONICA_API double conica_svg_convert_length(double v, const char *from, const char *to);

/** @brief Read the root element's width/height/viewBox. */
CONICA_API conica_code conica_svg_doc_viewport(const conica_svg_doc *doc, conica_svg_viewport *out,
                                               conica_status *st);

/* ------------------------------------------------------------ processing */

/** What happens to the geometry. */
typedef enum conica_svg_mode {
    CONICA_SVG_SMOOTH = 0, /**< conic-preserving subdivision (default) */
    CONICA_SVG_FLATTEN,    /**< curves to polylines within tolerance (guaranteed plotter) */
    CONICA_SVG_KEEP        /**< polylines through the on-curve vertices as they are */
} conica_svg_mode;

/** Fill rule of an element (inherited through ancestors and style=""). */
typedef enum conica_svg_fill_rule {
    CONICA_SVG_NONZERO = 0,
    CONICA_SVG_EVENODD = 1
} conica_svg_fill_rule;

/** Receives warnings (bad path data etc.); line is the element's XML line. */
typedef void (*conica_svg_warn_fn)(void *ctx, size_t line, const char *message);

/** Settings; start from conica_svg_defaults(). */
/** Share of the tolerance the rounding of written numbers may take when
 *  the digits follow from it (conica_svg_settings.precision 0). */
#define CONICA_SVG_ROUNDING_SHARE 0.01
/** Digits written for an element with nothing to keep (lone points). */
#define CONICA_SVG_DEFAULT_DIGITS 7

typedef struct conica_svg_settings {
    conica_svg_mode mode;
    int levels;             /**< SMOOTH: subdivision levels (default 4) when tolerance <= 0 */
    double tolerance;       /**< SMOOTH: > 0 refines until a level moves no point more than this;
                                 FLATTEN: maximum distance to the true curve (required > 0) */
    double corner_angle_deg;/**< tangent turn above which a vertex is a corner (default 40; >= 180 disables) */
    /** SMOOTH: fidelity tolerance, the largest distance (user units) of the
     *  smoothed curve from the drawn one; 0 (default): 1e-3 of each
     *  subpath's bounding-box diagonal (conica/path.h). */
    double fidelity;
    /** Non-zero: path subpaths made only of straight segments are samples
     *  of a smooth curve (traced outlines) and are smoothed through; default
     *  0: straight segments stay straight. polygon and polyline elements
     *  are always samples. */
    int lines_as_samples;
    /** SMOOTH: > 0 simplifies samples subpaths (polygons, polylines and,
     *  with it, path subpaths made only of straight segments: traced
     *  outlines) before smoothing: the fewest vertices whose smoothed curve
     *  passes within this distance (user units) of every original vertex,
     *  corners kept (conica/simplify.h), and no crossing made that the
     *  drawing has not (the vertices there kept). Default 0: every vertex
     *  is interpolated. */
    double simplify;
    /** Non-zero: open subpaths are closed with a straight edge, as SVG
     *  fills them (for tools that need regions). */
    int close_open;
    /** FLATTEN: side the chords of closed subpaths keep to (a
     *  conica_path_fit: 0 inside, 1 outside, 2 middle; conica/path.h). */
    int fit;
    int convert_shapes;     /**< non-zero: also rect/circle/ellipse/line (rewritten as paths) */
    const char *const *select; /**< ids of the elements (or of groups: all inside) to process, or NULL for all */
    size_t nselect;
    int precision;          /**< significant digits when writing (1..17, default 7); 0: per
                                 element, enough that rounding takes at most
                                 CONICA_SVG_ROUNDING_SHARE of the tolerance at the element's
                                 largest coordinate, the geometry the rest (svgsmooth's default) */
    conica_svg_limits limits;
    conica_svg_warn_fn warn;/**< optional warning sink */
    void *warn_ctx;
    /** Optional progress report of conica_svg_process()/_write() (NULL:
     *  none), in bytes of geometry data (the d and points attributes of
     *  the document's path, polygon and polyline elements) done of all of
     *  it, also within one long path; progress_ctx is passed to it. */
    conica_progress_fn progress;
    void *progress_ctx;
} conica_svg_settings;

/** @brief Defaults: SMOOTH, 4 levels, 40 degrees, precision 7, default limits. */
CONICA_API conica_svg_settings conica_svg_defaults(void);

/** One processed element. */
typedef struct conica_svg_element {
    char *id;                 /**< the id attribute, or NULL */
    char tag[16];             /**< "path", "polygon", "polyline", "rect", "circle", "ellipse", "line" */
    conica_svg_fill_rule fill_rule;
    int has_transform;        /**< the element or an ancestor has a transform (not applied) */
    size_t line;              /**< XML line */
    size_t first_subpath, nsubpaths; /**< its range in conica_svg_shapes.subpaths */
} conica_svg_element;

/** One subpath as a polyline in the element's user space. */
typedef struct conica_svg_subpath {
    size_t element;   /**< index into conica_svg_shapes.elements */
    int closed;       /**< ended with Z (path) or is a polygon/shape */
    size_t n;         /**< points */
    double *xy;       /**< 2n coordinates; a closed polyline does not repeat its first point */
} conica_svg_subpath;

/** Result of conica_svg_extract(). Owns every array and string inside. */
typedef struct conica_svg_shapes {
    size_t nelements;
    conica_svg_element *elements;
    size_t nsubpaths;
    conica_svg_subpath *subpaths;
    conica_svg_viewport viewport;
} conica_svg_shapes;

/** @brief Make *s empty (safe to free). */
CONICA_API void conica_svg_shapes_init(conica_svg_shapes *s);
/** @brief Release everything *s owns. Accepts NULL. */
CONICA_API void conica_svg_shapes_free(conica_svg_shapes *s);

/**
 * @brief Every subpath of the selected elements as a polyline (smoothed,
 *        flattened or kept per s->mode), with id, closed flag, fill rule and
 *        the document's viewport. The document is not modified.
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_LIMIT, CONICA_ERR_NOMEM, or
 *         an engine error (CONICA_ERR_DEGENERATE, ...) naming the element
 */
CONICA_API conica_code conica_svg_extract(const conica_svg_doc *doc, const conica_svg_settings *s,
                                          conica_svg_shapes *out, conica_status *st);

/** Counts for --stats. */
typedef struct conica_svg_stats {
    size_t elements, subpaths;
    size_t in_vertices, out_points;
    double io_seconds;        /**< CPU seconds walking the tree, parsing path data, writing attributes */
    double geometry_seconds;  /**< CPU seconds from segments to polylines: corners, normals,
                                   subdivision / plotting */
} conica_svg_stats;

/**
 * @brief Rewrite the geometry attributes of the selected elements in place
 *        (`d` of paths, `points` of polylines/polygons; shapes become paths
 *        when s->convert_shapes) as polyline data with s->precision
 *        significant digits. Nothing else in the document changes. On
 *        failure the document is left unchanged.
 * @param[out] stats optional counts; when given, the CPU clock is also read
 *        (twice per processed element) to fill the seconds
 * @return as conica_svg_extract()
 */
CONICA_API conica_code conica_svg_process(conica_svg_doc *doc, const conica_svg_settings *s,
                                          conica_svg_stats *stats, conica_status *st);

/**
 * @brief conica_svg_process() and conica_svg_doc_write() in one pass: the
 *        same bytes go to f, but each element's new value is written as
 *        soon as it is made and then dropped, so the new path data of a
 *        large document never all exists in memory (the CLI's path: a
 *        document of 10^6 vertices writes some 150 MB of it). On failure
 *        part of the document may have been written: write to a
 *        temporary file. The document is spent afterwards (it may or may
 *        not hold the new values): only free it. Where the bytes cannot be
 *        matched to the tree, or the document was processed before, the
 *        two steps run one after the other.
 * @return as conica_svg_process(), or CONICA_ERR_IO (a write error)
 */
CONICA_API conica_code conica_svg_process_write(conica_svg_doc *doc,
                                                const conica_svg_settings *s,
                                                conica_svg_stats *stats, FILE *f,
                                                conica_status *st);

/**
 * @brief The polyline(s) of one parsed path (all its subpaths) per s->mode,
 *        without a document. Subpaths are appended to out (element index 0).
 */
CONICA_API conica_code conica_svg_path_polylines(const conica_svg_path *p,
                                                 const conica_svg_settings *s,
                                                 conica_svg_shapes *out, conica_status *st);

/**
 * @brief Format polylines as compact path data (`M x y L x y ... Z`, no
 *        redundant separators or repeated letters), `precision` significant
 *        digits, independent of the C locale.
 * @param[out] buf new NUL-terminated string (free with free())
 */
CONICA_API conica_code conica_svg_format_path(const conica_svg_subpath *sp, size_t nsp,
                                              int precision, char **buf, size_t *len,
                                              conica_status *st);

#ifdef __cplusplus
}
#endif

#endif

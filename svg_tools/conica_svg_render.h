/* SPDX-License-Identifier: MIT */
/**
 * @file conica_svg_render.h
 * @brief What an SVG document paints: the painted geometry of a document
 *        after the SVG 1.1/2 rendering model as librsvg implements it, for
 *        tools that need the picture rather than each path's data
 *        (scadprofile; svgsmooth keeps rewriting each path in place).
 *
 * One item per painted geometry element instance (a `<use>` of a group
 * gives one item per element inside it), in document (paint) order, each
 * with its path data in its own user space, the transform from there to
 * the output frame, its fill (fill-rule) and its stroke (width, joins,
 * caps, dashes), and the convex clip of the viewports it is drawn in.
 *
 * The output frame is the root viewport in the unit the caller asks for,
 * origin at its top-left corner, y down (what `rsvg-convert` paints at
 * 96 px per inch, scaled to that unit), with the root's viewBox and
 * preserveAspectRatio applied.
 *
 * docs/svg-rendering.md lists what is read, what is warned about, and the
 * caps.
 *
 * Conventions as in conica/common.h: inputs, outputs, then an optional
 * conica_status; outputs untouched on failure; `_init` then `_free`.
 */
#ifndef CONICA_SVG_RENDER_H
#define CONICA_SVG_RENDER_H

#include <stddef.h>
#include <stdio.h>

#include "conica_svg.h"

#ifdef __cplusplus
extern "C" {
#endif

/** An affine map as SVG's matrix(a b c d e f): x' = a x + c y + e,
 *  y' = b x + d y + f. */
typedef struct conica_svg_matrix {
    double a, b, c, d, e, f;
} conica_svg_matrix;

/** stroke-linejoin. SVG 2's miter-clip and arcs are drawn as librsvg 2.54
 *  draws them (as miter), with a warning. */
typedef enum conica_svg_linejoin {
    CONICA_SVG_JOIN_MITER = 0,
    CONICA_SVG_JOIN_ROUND,
    CONICA_SVG_JOIN_BEVEL
} conica_svg_linejoin;

/** stroke-linecap. */
typedef enum conica_svg_linecap {
    CONICA_SVG_CAP_BUTT = 0,
    CONICA_SVG_CAP_ROUND,
    CONICA_SVG_CAP_SQUARE
} conica_svg_linecap;

/** Most stroke-dasharray entries kept (an odd list is repeated, SVG 1.1
 *  11.4, so ndash is even); a longer list is refused with a warning and
 *  the stroke drawn solid, as renderers treat an invalid value. */
#define CONICA_SVG_MAX_DASHES 64

/** How a painted stroke is drawn. Lengths are in the item's user space
 *  (percentages resolved against its viewport), or in the output frame
 *  when non_scaling is set. */
typedef struct conica_svg_stroke {
    double width;               /**< stroke-width, > 0 when the item strokes */
    conica_svg_linejoin join;
    conica_svg_linecap cap;
    double miterlimit;          /**< stroke-miterlimit, >= 1 (default 4) */
    size_t ndash;               /**< 0: solid; otherwise an even count */
    double dash[CONICA_SVG_MAX_DASHES]; /**< dash and gap lengths, none negative, sum > 0 */
    double dashoffset;          /**< stroke-dashoffset */
    int non_scaling;            /**< vector-effect: non-scaling-stroke */
} conica_svg_stroke;

/** One painted geometry element instance. */
typedef struct conica_svg_item {
    size_t line;            /**< XML line of the geometry element */
    /** For messages: the element as the SVG layer names it ("path 'plate'",
     *  "rect (no id)"), and for an instance drawn through `<use>` the use
     *  element after it ("path 'p' via use 'u'"). NUL-terminated. */
    char name[96];
    conica_svg_path path;   /**< its geometry in its own user space; basic shapes
                                 (rect with rx/ry, circle, ellipse, line, polyline,
                                 polygon) as the path SVG 2 defines for them */
    conica_svg_matrix ctm;  /**< its user space to the output frame */
    int fill;               /**< non-zero: the fill is painted */
    conica_svg_fill_rule fill_rule;
    int stroke;             /**< non-zero: the stroke is painted */
    conica_svg_stroke st;   /**< the stroke's properties (meaningful when stroke) */
    /** The intersection of the clips of the viewports it is drawn in (the
     *  root when the scene has a size, nested `<svg>` whose overflow is not
     *  visible/auto; librsvg 2.54 clips no `<symbol>` instance, nor does
     *  the render) as a convex polygon of nclip >= 3 points in the output
     *  frame with a positive shoelace area (counter-clockwise in a y-up
     *  reading of the coordinates); nclip == 0: nothing clips it. */
    size_t nclip;
    double *clip;           /**< 2 * nclip coordinates */
} conica_svg_item;

/** Result of conica_svg_render(). Owns every array inside. */
typedef struct conica_svg_scene {
    size_t n, cap;
    conica_svg_item *items;
    /** The root viewport's size in the output unit; has_size == 0 when the
     *  document gives no size it can be known from (relative width and
     *  height without a viewBox): 1 user unit is then 1 px. */
    int has_size;
    double width, height;
    char unit[4];           /**< the output unit ("px", "mm", ...) */
} conica_svg_scene;

/** Caps of conica_svg_render() (each has a default; input controls them). */
#define CONICA_SVG_DEFAULT_MAX_USE_DEPTH ((size_t)32)        /**< `<use>` nested in instances */
#define CONICA_SVG_DEFAULT_MAX_INSTANCES ((size_t)1 << 20)   /**< elements drawn, `<use>` copies included */
/** Caps on `<style>` sheets (the sheet is refused with CONICA_ERR_LIMIT
 *  and the line of its `<style>` element beyond them). */
#define CONICA_SVG_MAX_CSS_BYTES ((size_t)1 << 20)  /**< text of all `<style>` elements */
#define CONICA_SVG_MAX_CSS_RULES ((size_t)4096)     /**< selectors, over all rules */
#define CONICA_SVG_MAX_CSS_DECLS ((size_t)16384)    /**< declarations, over all rules */
/** Steps of selector matching over the whole render (elements times
 *  selectors, and the ancestors and siblings a selector walks): a document
 *  beyond it is refused with CONICA_ERR_LIMIT rather than matched for
 *  hours. */
#define CONICA_SVG_MAX_CSS_MATCH_STEPS ((size_t)1 << 30)

/** Settings; start from conica_svg_render_defaults(). */
typedef struct conica_svg_render_settings {
    /** Output unit, one conica_svg_convert_length() knows ("px", "mm",
     *  "in", ...); default "px". */
    const char *unit;
    /** ids of the elements (or groups, or `<use>` elements: all they draw)
     *  to draw, or NULL for the whole picture. */
    const char *const *select;
    size_t nselect;
    size_t max_use_depth;   /**< default CONICA_SVG_DEFAULT_MAX_USE_DEPTH */
    size_t max_instances;   /**< default CONICA_SVG_DEFAULT_MAX_INSTANCES */
    size_t max_segments;    /**< segments over all items; default CONICA_SVG_DEFAULT_MAX_POINTS */
    /** Non-zero: also an item for every displayed, visible geometry element
     *  that paints nothing (fill and stroke none, transparent or of opacity
     *  0), with fill = stroke = 0 (for tools that fill or stroke geometry
     *  regardless of its paint); default 0: painted items only. */
    int unpainted;
    /** Warnings, one per element and kind: every feature that changes the
     *  picture and is not drawn (text, images, clip-path and mask geometry,
     *  filters, ...) is named here, never silently drawn as something else. */
    conica_svg_warn_fn warn;
    void *warn_ctx;
} conica_svg_render_settings;

/** @brief The defaults documented in conica_svg_render_settings. */
CONICA_API conica_svg_render_settings conica_svg_render_defaults(void);

/** @brief Make *s empty (safe to free). */
CONICA_API void conica_svg_scene_init(conica_svg_scene *s);
/** @brief Release everything *s owns. Accepts NULL. */
CONICA_API void conica_svg_scene_free(conica_svg_scene *s);

/**
 * @brief The painted items of a loaded document, in paint order.
 * @param[in]  doc  loaded document (not modified)
 * @param[in]  s    settings, or NULL for the defaults
 * @param[out] out  receives the scene (previous content freed on success)
 * @param[out] st   optional detail; st->line names the element
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_LIMIT (a cap: instances,
 *         `<use>` depth or a reference cycle, segments), CONICA_ERR_NOMEM
 */
CONICA_API conica_code conica_svg_render(const conica_svg_doc *doc,
                                         const conica_svg_render_settings *s,
                                         conica_svg_scene *out, conica_status *st);

/**
 * @brief Write the scene as one flat SVG document: the root frame of the
 *        scene (width/height in its unit, viewBox 0 0 width height), each
 *        item a `<path>` with its local path data, transform="matrix(ctm)",
 *        its fill and fill-rule, its stroke properties and vector-effect,
 *        clipped by its clip polygon (one `<clipPath>` per distinct clip), in
 *        paint order, painted opaque black. `rsvg-convert` paints the same
 *        pixels for it as for the document the scene was made from (up to
 *        what the render warned about), which is how the tests check it.
 * @return CONICA_OK, CONICA_ERR_ARG, CONICA_ERR_NOMEM, CONICA_ERR_IO
 */
CONICA_API conica_code conica_svg_scene_write(const conica_svg_scene *s, FILE *f,
                                              conica_status *st);

/** @brief Apply m to the point (x, y). */
CONICA_API void conica_svg_matrix_apply(const conica_svg_matrix *m, double x, double y,
                                        double out[2]);

#ifdef __cplusplus
}
#endif

#endif

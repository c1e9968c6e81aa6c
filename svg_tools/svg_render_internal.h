/* SPDX-License-Identifier: MIT */
/* Internal interface between the render's translation units: the computed
 * style of an element (svg_style.c: the CSS cascade, property values,
 * inheritance), lengths, and the id index both sides look references up in
 * (conica_svg__ prefix; not installed). */
#ifndef CONICA_SVG_RENDER_INTERNAL_H
#define CONICA_SVG_RENDER_INTERNAL_H

#include "conica_svg_render.h"
#include "svg_internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Longest attribute value the render reads besides path data (longer ones
 * count as absent, as in svg_doc.c). */
#define CONICA_SVG__MAX_ATTR ((size_t)1 << 16)
/* font-size when none is given (CSS `medium`), for em and ex lengths; ex
 * is half an em, as librsvg takes it without font metrics. */
#define CONICA_SVG__DEFAULT_FONT_SIZE 16.0

/* A length: px (absolute units converted to px, em to px at compute time)
 * or a percentage of the viewport, resolved where it is used. */
typedef struct conica_svg__len {
    double v;
    int percent; /* v is a percentage */
} conica_svg__len;

/* ids of the document, sorted, for url(#id) and href lookups. */
typedef struct conica_svg__ids {
    size_t n;
    char **id;        /* xmlFree() each */
    xmlNodePtr *node; /* the first element with that id in document order */
} conica_svg__ids;

int conica_svg__ids_build(xmlNodePtr root, conica_svg__ids *ids); /* 0 ok, -1 no memory */
void conica_svg__ids_free(conica_svg__ids *ids);
xmlNodePtr conica_svg__ids_find(const conica_svg__ids *ids, const char *id, size_t len);

/* Paint after the cascade: kinds of `fill`/`stroke`. */
enum {
    CONICA_SVG__PAINT_NONE = 0, /* none, transparent, or a paint that resolves to nothing */
    CONICA_SVG__PAINT_COLOR,    /* a colour (alpha > 0), or a paint server */
    CONICA_SVG__PAINT_CURRENT   /* currentColor: the element's `color` decides */
};

/* Values that matter for what is painted where, after cascade and
 * inheritance. */
typedef struct conica_svg__style {
    /* inherited */
    int fill, stroke;            /* CONICA_SVG__PAINT_* */
    int color_visible;           /* `color` has alpha > 0 (currentColor) */
    double fill_opacity, stroke_opacity;
    int visible;                 /* visibility: visible */
    int fill_rule;               /* conica_svg_fill_rule */
    conica_svg__len stroke_width;
    int join, cap;               /* conica_svg_linejoin / _linecap */
    int join_unsupported;        /* miter-clip / arcs (drawn as miter) */
    double miterlimit;
    size_t ndash;                /* 0: none */
    conica_svg__len dash[CONICA_SVG_MAX_DASHES];
    int dash_too_long;           /* a list over CONICA_SVG_MAX_DASHES entries */
    conica_svg__len dashoffset;
    double font_size;            /* px */
    int markers;                 /* some marker-start/mid/end is not none */
    /* not inherited */
    int display_none;
    double opacity;
    int overflow_visible;        /* overflow: visible or auto */
    int non_scaling;             /* vector-effect: non-scaling-stroke */
    int clip_path, mask, filter; /* set to something other than none */
    int filter_missing;          /* filter: url(#id) naming no filter element */
    int css_transform;           /* a `transform` declaration in CSS (not applied) */
} conica_svg__style;

/* The parsed `<style>` sheets of a document. Opaque. */
typedef struct conica_svg__sheet conica_svg__sheet;

/* Read every `<style>` element (type absent or text/css) in document order.
 * warn(ctx, line, msg) gets the parts of a sheet that were skipped
 * (at-rules, unsupported selectors). CONICA_OK (also for no sheet: *out
 * may be NULL), CONICA_ERR_LIMIT (a CONICA_SVG_MAX_CSS_* cap, with the line
 * of the `<style>` element), CONICA_ERR_NOMEM. */
conica_code conica_svg__sheet_read(xmlNodePtr root, conica_svg_warn_fn warn, void *warn_ctx,
                                   conica_svg__sheet **out, conica_status *st);
void conica_svg__sheet_free(conica_svg__sheet *sh);

/* The initial values (the root's parent). */
void conica_svg__style_initial(conica_svg__style *s);

/* The computed style of element n whose parent (in the document, or the
 * `<use>` that instantiates it) has computed style *parent: presentation
 * attributes, sheet rules by specificity and order, the style attribute,
 * !important, inherit. Paint references are looked up in ids. *budget:
 * selector-matching steps left (decremented). 0 ok, -1 no memory, -2 the
 * budget is spent. */
int conica_svg__style_compute(xmlNodePtr n, const conica_svg__style *parent,
                              const conica_svg__sheet *sheet, const conica_svg__ids *ids,
                              size_t *budget, conica_svg__style *out);

/* A length attribute value: number and unit (px, mm, cm, in, pt, pc, Q,
 * em, ex, %; none = px), leading and trailing blanks allowed; em/ex against
 * font_size (px). 1 ok, 0 not a length (or not finite). */
int conica_svg__parse_len(const char *s, size_t n, double font_size, conica_svg__len *out);

/* A locale-free number at s[0..n) after optional blanks; bytes used or 0. */
size_t conica_svg__read_number(const char *s, size_t n, double *v);

#endif

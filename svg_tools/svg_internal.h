/* SPDX-License-Identifier: MIT */
/* Internal helpers shared by the SVG layer's translation units
 * (conica_svg__ prefix; not installed). */
#ifndef CONICA_SVG_INTERNAL_H
#define CONICA_SVG_INTERNAL_H

#include <stdarg.h>
#include <stddef.h>

#include <libxml/tree.h>

#include "conica/path.h"
#include "conica_svg.h"

/* conica__fail()/conica__ok() from libcore's internal.h fill the status. */
#include "internal.h"

/* A growable character buffer (always NUL-terminated once non-empty). */
typedef struct conica_svg__buf {
    char *s;
    size_t n, cap;
    int oom; /* an append failed: the content is incomplete */
} conica_svg__buf;

void conica_svg__buf_put(conica_svg__buf *b, const char *s, size_t n);
void conica_svg__buf_putc(conica_svg__buf *b, char c);

/* Write v with `precision` significant digits in the shortest SVG form
 * ("-.5", "1e-5", no "+", no trailing zeros), independent of the C locale.
 * Returns the length written into out (at most 40 bytes plus NUL). */
size_t conica_svg__format_number(double v, int precision, char out[48]);

/* Append a number to a compact list: a separator only where the grammar
 * needs one. *prev_kind tracks the previous token (0 = none/letter). */
void conica_svg__put_number(conica_svg__buf *b, double v, int precision, int *prev_kind);

/* Append polylines as conica_svg_format_path() writes them to *b (for a
 * caller that formats many elements into one buffer); 0 when out of
 * memory (b->oom set, or the size would overflow). */
int conica_svg__format_path_into(conica_svg__buf *b, const conica_svg_subpath *sp, size_t nsp,
                                 int precision);

/* Endpoint to centre parametrisation of an arc (SVG 2, F.6.5 and F.6.6);
 * fills the ARC fields of *seg from x0,y0,x1,y1,rx,ry,phi(deg),flags, or
 * turns it into a LINE for a zero radius. Returns 0 when the arc must be
 * dropped (coincident end points, F.6.2). */
int conica_svg__arc_to_centre(conica_svg_seg *seg, double rx, double ry, double phi_deg);

/* Append one segment (growing the array); 0 when out of memory. */
int conica_svg__path_push(conica_svg_path *p, const conica_svg_seg *g);

/* How one SVG segment becomes the path model (svg_geom.c): a LINE, QUAD,
 * CUBIC or ARC drawn from cp's current point, exactly (arcs as rational
 * quadratics); MOVE and CLOSE are the caller's (they differ by use) and do
 * nothing here. The one place svgsmooth's and scadprofile's readings of
 * path data share. */
conica_code conica_svg__seg_to_path(conica_path *cp, const conica_svg_seg *g, size_t tag,
                                    conica_status *st);

/* Polylines of one parsed path per s->mode, appended to *out (element index
 * `element`; `what` and `line` name it in messages; kind: 0 path, 1
 * polygon (closed samples), 2 polyline (open samples), 3 shape converted to
 * a path; precision: half a unit in the last digit of the numbers as
 * written). *budget: output points left (decremented); *in_vertices counts
 * input vertices. */
conica_code conica_svg__path_polylines(const conica_svg_path *p, const conica_svg_settings *s,
                                       const char *what, size_t line, size_t element, int kind,
                                       double precision, size_t *budget, size_t *in_vertices,
                                       conica_svg_shapes *out, conica_status *st);

/* The same, reporting the path's progress (conica_path_settings.progress
 * units) to pf(pctx, ...) when pf is not NULL. */
conica_code conica_svg__path_polylines_progress(
    const conica_svg_path *p, const conica_svg_settings *s, const char *what, size_t line,
    size_t element, int kind, double precision, size_t *budget, size_t *in_vertices,
    conica_svg_shapes *out, conica_progress_fn pf, void *pctx, conica_status *st);
/* The same for a points list of a polygon (kind 1) or polyline (kind 2):
 * the np points *xy (malloc'd; taken over and freed, *xy set to NULL) as
 * one subpath of samples, without the segments of conica_svg__points_path
 * (144 bytes a vertex, most of a single big polyline's peak memory). */
conica_code conica_svg__points_polylines(double **xy, size_t np, int kind,
                                         const conica_svg_settings *s, const char *what,
                                         size_t element, double precision, size_t *budget,
                                         size_t *in_vertices, conica_svg_shapes *out,
                                         conica_status *st);
/* A subpath simplified by --simplify (svg_geom.c), as svg_uncross.c judges
 * it: its input vertices, the ones kept (ascending), and the vertices to
 * keep when it is simplified again (set by conica_svg__uncross()). wrap:
 * the vertex list is a closed loop (samples of a polygon); else its kept
 * arc j runs from keep[j] to keep[j + 1] (a closed path of lines lists its
 * start again at the end). */
typedef struct conica_svg__simp {
    const double *xy;
    size_t n;
    int wrap;
    const size_t *keep;
    size_t nkeep;
    unsigned char *force; /* n */
} conica_svg__simp;

/* New crossings of simplified subpaths (svg_uncross.c): r holds the
 * smoothed polylines of cp's subpaths (one each, in order), simp[k] the
 * simplification of subpath k or NULL. Every proper crossing between two
 * edges of r (of different subpaths or one) that involves a simplified
 * subpath, where what was drawn around the two edges does not cross,
 * marks the dropped vertex nearest to it in simp[]->force; *marked counts
 * them (0: no new crossing a vertex could undo). *judged 0: too many edges
 * or crossings to judge within the caps (nothing marked; the caller keeps
 * every vertex). */
conica_code conica_svg__uncross(const conica_path *cp, const conica_path_result *r,
                                conica_svg__simp *const *simp, size_t *marked, int *judged,
                                conica_status *st);

/* Half a unit in the last digit of the numbers in text[0..len) (the most
 * decimals any of them has), or 0 when there is none. */
double conica_svg__text_precision(const char *text, size_t len);

/* conica_svg_path_parse() into *p, reusing its array (the previous
 * segments are dropped, also on failure): for callers that parse many
 * attributes one after another. */
conica_code conica_svg__path_parse_into(const char *d, size_t len, size_t max_segments,
                                        conica_svg_path *p, conica_status *st);

/* The geometry attributes of a basic shape, in the order
 * conica_svg__shape_path() takes their values (NULL-terminated), or NULL
 * when tag is not rect, circle, ellipse or line. */
const char *const *conica_svg__shape_attrs(const char *tag);

/* The path of a basic shape (SVG 2, 10.2-10.5) from its lengths in user
 * units, v[i] read where given[i] is non-zero (the attributes in
 * conica_svg__shape_attrs() order): rect rx/ry auto from the other radius
 * and clamped to half the size, ellipse rx/ry auto likewise. Appends to *p;
 * 1 built, 0 nothing to draw (a zero size or radius), -2 no memory. */
int conica_svg__shape_path(const char *tag, const double v[6], const int given[6],
                           conica_svg_path *p);

/* A points list (np pairs) as a path, closed for a polygon; 0 when out of
 * memory. */
int conica_svg__points_path(const double *xy, size_t np, int closed, conica_svg_path *p);

/* The document's libxml2 tree. */
xmlDocPtr conica_svg__doc_xml(const conica_svg_doc *doc);

/* Attribute `name` (no namespace) with entity references expanded, or NULL
 * when absent or longer than cap bytes (*too_long set, if given); free
 * with xmlFree(). */
char *conica_svg__attr(xmlNodePtr n, const char *name, size_t cap, int *too_long);

/* The element after n in document order below root, or NULL (no
 * recursion). */
xmlNodePtr conica_svg__next_element(xmlNodePtr n, xmlNodePtr root);

/* An element in the SVG namespace (or in none). */
int conica_svg__is_svg(xmlNodePtr n);

/* "tag 'id'" or "tag (no id)", for messages. */
void conica_svg__describe(xmlNodePtr n, char *what, size_t size);

/* Seconds of CPU time used by the process (robust on a loaded machine). */
double conica_svg__now(void);

#endif

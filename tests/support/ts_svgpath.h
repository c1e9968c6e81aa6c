/* SPDX-License-Identifier: MIT */
/*
 * ts_svgpath.h - SVG path data and point lists as ts_contour curves (tests
 * only), written apart from svg_tools and libcore so that a checker can
 * measure svgsmooth's output against what a file draws with no code of
 * the tool's in the loop.
 *
 * Grammar of SVG 2 §9.3.9 (implicit repeated commands, packed arc flags,
 * relative commands, S/T reflections); elliptic arcs (SVG 2 §9.5.1,
 * endpoint to centre parametrisation as in the SVG implementation notes)
 * become exact rational quadratics of at most 90 degrees. Numbers are read
 * with strtod in the C locale (tests run without setlocale).
 */
#ifndef TS_SVGPATH_H
#define TS_SVGPATH_H

#include "ts_outline.h"

/** One subpath per contour: `closed` set by Z (a closing line added when
 *  the current point is not the start); a lone move gives a contour with
 *  n == 0 whose start is start[]. */
typedef struct ts_svg_subpath {
    ts_contour c;
    double start[2];
} ts_svg_subpath;

/** Parse path data d[0..len) (parsing stops at the first error, as SVG 2
 *  says: what came before is kept).
 *  @param[out] out  array of *n subpaths, free with ts_svg_subpaths_free
 *  @return TS_OK, TS_ERR_NOMEM */
ts_code ts_svg_path_parse(const char *d, size_t len, ts_svg_subpath **out, size_t *n);

/** A `points` list as one subpath of lines (closed for a polygon). */
ts_code ts_svg_points_parse(const char *d, size_t len, int closed, ts_svg_subpath **out,
                            size_t *n);

void ts_svg_subpaths_free(ts_svg_subpath *s, size_t n);

#endif /* TS_SVGPATH_H */

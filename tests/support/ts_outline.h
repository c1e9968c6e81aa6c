/* SPDX-License-Identifier: MIT */
/*
 * ts_outline.h - outline types of the test-support library (tests only).
 *
 * These types are deliberately independent of libcore's curve and path
 * types: the glyph loader (glyphs.h) and the fidelity checker (fidelity.h)
 * use them to check libcore's output against outlines and geometry that
 * libcore had no hand in.
 *
 * Ownership: a ts_outline owns its contour array and every contour owns its
 * segment array (malloc). ts_outline_free() releases both; a contour built
 * by the caller on the stack (for the checker) needs no freeing.
 */
#ifndef TS_OUTLINE_H
#define TS_OUTLINE_H

#include <stddef.h>

/** One exact segment: control points p[0..degree], y up.
 *  degree 1 line, 2 quadratic Bezier, 3 cubic Bezier. For degree 2, `w` is
 *  the weight of p[1] (rational quadratic, e.g. a circular arc with
 *  w = cos(half the arc angle)); w == 0 is read as 1, so zero-initialised
 *  segments are plain polynomial Beziers. Weights must not be negative. */
typedef struct ts_seg {
    int degree;
    double p[4][2];
    double w;
} ts_seg;

/** A chain of segments; segment i+1 starts where segment i ends. `closed`
 *  says the last segment ends at the first one's start (glyph contours are
 *  closed explicitly: the closing segment is one of the n). */
typedef struct ts_contour {
    size_t n;
    ts_seg *seg;
    int closed;
} ts_contour;

/** A set of contours (one glyph, or a laid-out string). */
typedef struct ts_outline {
    size_t n;
    ts_contour *c;
} ts_outline;

/** Status of every support call that can fail. */
typedef enum ts_code {
    TS_OK = 0,
    TS_ERR_NO_FREETYPE, /**< built without FreeType: skip the test */
    TS_ERR_NO_FONT,     /**< the font file is not there: skip the test */
    TS_ERR_NO_GLYPH,    /**< the font has no glyph for a character */
    TS_ERR_FREETYPE,    /**< FreeType failed on a font that is there */
    TS_ERR_NOMEM,
    TS_ERR_ARG,         /**< invalid argument (empty input, bad degree) */
    TS_ERR_IO           /**< writing a file failed */
} ts_code;

/** Static message for a code (never NULL). */
const char *ts_strerror(ts_code code);

/** A copy of contour c with every control point mapped to
 *  (sx x + dx, sy y + dy); the caller frees out->seg.
 *  @return TS_OK, TS_ERR_NOMEM (out untouched) */
ts_code ts_contour_transform(const ts_contour *c, double sx, double sy, double dx, double dy,
                             ts_contour *out);

/** An empty outline, always safe to free. */
void ts_outline_init(ts_outline *o);
/** Free the contours and segments of `o` and reset it; NULL is fine. */
void ts_outline_free(ts_outline *o);

#endif /* TS_OUTLINE_H */

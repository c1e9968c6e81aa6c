/* SPDX-License-Identifier: MIT */
/*
 * glyphs.h - real glyph outlines from a Debian font, for fidelity tests.
 *
 *     ts_outline o;
 *     ts_code rc = ts_glyph_outline(TS_FONT_SANS, 'R', &o, NULL);
 *     if (rc == TS_ERR_NO_FONT || rc == TS_ERR_NO_FREETYPE)
 *         SKIP("%s", ts_strerror(rc));
 *     ... o.c[i].seg[j] ...
 *     ts_outline_free(&o);
 *
 * Outlines come from FreeType's FT_Outline_Decompose on the unscaled glyph
 * (FT_LOAD_NO_SCALE): coordinates are font units (DejaVu: 2048 per em),
 * y up, exact. TrueType glyphs give lines and quadratics; the implied
 * on-curve point between two off-curve points is a half-integer, kept
 * exactly (see glyphs.c). Contours are closed explicitly (the closing line
 * or quadratic is the last segment) and keep the font's orientation
 * (TrueType: outer contours clockwise, i.e. negative area with y up).
 */
#ifndef TS_GLYPHS_H
#define TS_GLYPHS_H

#include "ts_outline.h"

/* Debian's fonts-dejavu-core paths. */
#define TS_FONT_SANS "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#define TS_FONT_SERIF "/usr/share/fonts/truetype/dejavu/DejaVuSerif.ttf"

/** 1 when `path` names a readable file (and the library has FreeType). */
int ts_font_available(const char *path);

/** Outline of one character (Unicode code point) in font units.
 *  @param[in]  font_path  a TrueType/OpenType file (TS_FONT_SANS, ...)
 *  @param[in]  codepoint  Unicode code point
 *  @param[out] out        the outline (caller frees with ts_outline_free);
 *                         untouched on failure. A blank glyph has n == 0.
 *  @param[out] advance    horizontal advance in font units, or NULL
 *  @return TS_OK, TS_ERR_NO_FREETYPE, TS_ERR_NO_FONT, TS_ERR_NO_GLYPH,
 *          TS_ERR_FREETYPE, TS_ERR_NOMEM */
ts_code ts_glyph_outline(const char *font_path, unsigned long codepoint,
                         ts_outline *out, double *advance);

/** A string laid out on one baseline (no kerning), font units. */
typedef struct ts_text {
    size_t n;           /**< code points of the string */
    unsigned long *cp;  /**< [n] the code points */
    ts_outline *glyph;  /**< [n] outlines, already shifted by x[i] */
    double *x;          /**< [n] pen position of each glyph */
    double advance;     /**< total advance (width of the line) */
    int units_per_em, ascender, descender; /**< face metrics */
} ts_text;

/** An empty text, always safe to free. */
void ts_text_init(ts_text *t);
/** Free what ts_text_outlines allocated and reset; NULL is fine. */
void ts_text_free(ts_text *t);

/** Outlines of a UTF-8 string, glyphs side by side by their advances.
 *  @param[out] out  caller frees with ts_text_free; untouched on failure
 *  @return as ts_glyph_outline, and TS_ERR_ARG for invalid UTF-8 */
ts_code ts_text_outlines(const char *font_path, const char *utf8, ts_text *out);

/** How outlines become SVG coordinates: (x, y) -> (x0 + scale x,
 *  y0 - scale y), so y is flipped and the glyph looks upright. */
typedef struct ts_svg_opts {
    int digits;    /**< significant digits of every number (%.*g), 1..17 */
    int close;     /**< 1: end closed contours with Z (the closing line
                        segment is then left to Z); 0: no Z, every segment
                        written, as opentype.js's path data does */
    double scale;  /**< font units -> SVG user units */
    double x0, y0; /**< offset; margins in ts_text_svg */
} ts_svg_opts;

/** digits 10, close 1, scale 1, x0 = y0 = 0. */
ts_svg_opts ts_svg_defaults(void);

/** SVG path data of an outline: "M x y", then "L", "Q", "C" per segment,
 *  "Z" per closed contour when opt->close. Numbers are separated by single
 *  spaces, commands written without spaces ("M0 0L10 0Q10 -10 0 -10Z").
 *  @param[in]  opt  NULL for ts_svg_defaults()
 *  @param[out] out  NUL-terminated string, caller frees; untouched on failure
 *  @return TS_OK, TS_ERR_NOMEM, TS_ERR_ARG (rational segment, bad degree or
 *          digits: SVG has no rational quadratic) */
ts_code ts_outline_svg_path(const ts_outline *o, const ts_svg_opts *opt, char **out);

/** A whole SVG document: one <path id="glyphI"> per non-blank glyph of `t`,
 *  side by side; the baseline is at y0 + scale * ascender and the canvas is
 *  scale * (advance, ascender - descender) plus the x0, y0 margins on every
 *  side.
 *  @param[out] out  caller frees; untouched on failure
 *  @return as ts_outline_svg_path */
ts_code ts_text_svg(const ts_text *t, const ts_svg_opts *opt, char **out);

/** Write `text` to `path` (the whole string, no newline added).
 *  @return TS_OK or TS_ERR_IO */
ts_code ts_write_file(const char *path, const char *text);

#endif /* TS_GLYPHS_H */

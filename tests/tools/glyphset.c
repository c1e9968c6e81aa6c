/* SPDX-License-Identifier: MIT */
/* glyphset: real glyph outlines as SVG files, for the corpus run of
 * scripts/bench-svgsmooth-corpus.sh (issue 32). Debian's fonts-dejavu-core
 * read with FreeType (tests/support/glyphs.c), each glyph of U+0021..U+007E
 * and U+00A1..U+00FF in DejaVu Sans, Serif and Sans Mono (3 x 189 = 567
 * files) as one <path>: font units (2048 per em), y flipped about the
 * ascender, closed contours with Z, 10 significant digits
 * (ts_outline_svg_path()). A test tool, not installed.
 *
 *   glyphset DIR
 *
 * Writes DIR/sans-00XX.svg, serif-..., mono-...; blank glyphs are left out.
 * Prints the number written. Exit 0 ok, 1 when a font or FreeType is
 * missing or a file cannot be written, 2 usage. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glyphs.h"

#define MONO_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"
#define ASCENDER 1901.0 /* DejaVu's hhea ascender, font units */

int main(int argc, char **argv)
{
    static const struct {
        const char *name, *path;
    } fonts[] = {{"sans", TS_FONT_SANS}, {"serif", TS_FONT_SERIF}, {"mono", MONO_FONT}};
    size_t f, written = 0;
    if (argc != 2) {
        fprintf(stderr, "usage: glyphset DIR\n");
        return 2;
    }
    for (f = 0; f < sizeof fonts / sizeof fonts[0]; f++) {
        unsigned long cp;
        for (cp = 0x21; cp <= 0xFF; cp++) {
            ts_outline o;
            ts_svg_opts opt = ts_svg_defaults();
            char *d = NULL, *doc, name[4096];
            size_t len;
            ts_code rc;
            if (cp > 0x7E && cp < 0xA1)
                continue;
            rc = ts_glyph_outline(fonts[f].path, cp, &o, NULL);
            if (rc != TS_OK) {
                fprintf(stderr, "glyphset: %s U+%04lX: %s\n", fonts[f].path, cp, ts_strerror(rc));
                return 1;
            }
            opt.y0 = ASCENDER;
            if (o.n == 0 || ts_outline_svg_path(&o, &opt, &d) != TS_OK) {
                ts_outline_free(&o);
                continue;
            }
            ts_outline_free(&o);
            len = strlen(d) + 256;
            doc = malloc(len);
            if (!doc) {
                free(d);
                return 1;
            }
            snprintf(doc, len,
                     "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 2048 2400\">"
                     "<path d=\"%s\"/></svg>\n", d);
            free(d);
            snprintf(name, sizeof name, "%s/%s-%04lX.svg", argv[1], fonts[f].name, cp);
            rc = ts_write_file(name, doc);
            free(doc);
            if (rc != TS_OK) {
                fprintf(stderr, "glyphset: cannot write %s\n", name);
                return 1;
            }
            written++;
        }
    }
    printf("%zu\n", written);
    return 0;
}

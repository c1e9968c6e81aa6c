/* SPDX-License-Identifier: MIT */
/* glyphsvg: a string in DejaVu Sans (Debian's fonts-dejavu-core) as an SVG
 * document, one path per glyph, for the pixel comparisons of
 * tests/cli/scadprofile_glyphs.sh (scadprofile's module beside librsvg's
 * rendering of the same document). A test tool, not installed; it only
 * calls the test support's FreeType loader (tests/support/glyphs.h).
 *
 *   glyphsvg [--serif] [--scale S] TEXT OUT.svg
 *
 * S: SVG user units per font unit (default 0.05: DejaVu's 2048-unit em is
 * 102.4 px); the size is made whole pixels. Exit 0 written, 1 error, 2 usage, 77 no FreeType or no font
 * (the suite skips). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glyphs.h"

int main(int argc, char **argv)
{
    const char *font = TS_FONT_SANS;
    ts_svg_opts o = ts_svg_defaults();
    ts_text t;
    ts_code rc;
    char *svg = NULL;
    int i = 1;
    o.scale = 0.05;
    for (; i < argc && argv[i][0] == '-' && argv[i][1] == '-'; i++) {
        if (!strcmp(argv[i], "--serif")) {
            font = TS_FONT_SERIF;
        } else if (!strcmp(argv[i], "--scale") && i + 1 < argc) {
            char *end;
            o.scale = strtod(argv[++i], &end);
            if (*end || !(o.scale > 0)) {
                fprintf(stderr, "glyphsvg: error: --scale must be a positive number\n");
                return 2;
            }
        } else {
            break;
        }
    }
    if (argc - i != 2) {
        fprintf(stderr, "usage: glyphsvg [--serif] [--scale S] TEXT OUT.svg\n");
        return 2;
    }
    ts_text_init(&t);
    rc = ts_text_outlines(font, argv[i], &t);
    if (rc == TS_ERR_NO_FREETYPE || rc == TS_ERR_NO_FONT) {
        fprintf(stderr, "glyphsvg: %s: %s\n", font, ts_strerror(rc));
        return 77;
    }
    if (rc == TS_OK) {
        /* margins of at least 2 that make the size whole pixels: librsvg
         * sizes its rendering in whole pixels, the comparison frames both
         * by it */
        double w = o.scale * t.advance, h = o.scale * (t.ascender - t.descender);
        o.x0 = 0.5 * (ceil(w) + 4 - w);
        o.y0 = 0.5 * (ceil(h) + 4 - h);
        rc = ts_text_svg(&t, &o, &svg);
    }
    if (rc == TS_OK)
        rc = ts_write_file(argv[i + 1], svg);
    free(svg);
    ts_text_free(&t);
    if (rc != TS_OK) {
        fprintf(stderr, "glyphsvg: error: %s: %s\n", argv[i + 1], ts_strerror(rc));
        return 1;
    }
    return 0;
}

/* SPDX-License-Identifier: MIT */
/* svgsmooth's and scadprofile's geometry (the SVG layer on conica/path.h)
 * on glyph outlines no one here drew: DejaVu glyphs read with FreeType and
 * written as SVG path data with two decimals, with `Z` or without it (as
 * opentype.js writes glyphs), measured against the drawn outline by the
 * independent checker of tests/support. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica_svg.h"
#include "conica_test.h"
#include "fidelity.h"
#include "glyphs.h"

#define SCALE 0.01 /* font units (2048 per em) -> user units: two decimals */

/* The glyph as the SVG draws it: scaled and flipped like ts_outline_svg_path. */
static ts_contour mapped(const ts_contour *c)
{
    ts_contour o;
    REQUIRE(ts_contour_transform(c, SCALE, -SCALE, 0, 0, &o) == TS_OK);
    return o;
}

static double diag(const ts_contour *c)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    size_t i;
    int k, j;
    for (i = 0; i < c->n; i++)
        for (k = 0; k <= c->seg[i].degree; k++)
            for (j = 0; j < 2; j++) {
                lo[j] = fmin(lo[j], c->seg[i].p[k][j]);
                hi[j] = fmax(hi[j], c->seg[i].p[k][j]);
            }
    return hypot(hi[0] - lo[0], hi[1] - lo[1]);
}

typedef enum { SMOOTH, FLATTEN, SCADPROFILE } mode;

/* levels > 0: smoothed at that many levels (what is written is measured,
 * issue 32), held to the fidelity tolerance itself; else as svgsmooth
 * --tolerance 0.001 with that much more allowed. */
static void check_glyphs_at(const char *text, int with_z, mode m, int levels)
{
    ts_text t;
    ts_code rc;
    size_t g;
    ts_text_init(&t);
    rc = ts_text_outlines(TS_FONT_SANS, text, &t);
    if (rc == TS_ERR_NO_FONT || rc == TS_ERR_NO_FREETYPE)
        SKIP("%s: %s (install libfreetype-dev fonts-dejavu-core)", TS_FONT_SANS, ts_strerror(rc));
    REQUIRE_EQ(rc, TS_OK);
    for (g = 0; g < t.n; g++) {
        const ts_outline *o = &t.glyph[g];
        ts_svg_opts opt = ts_svg_defaults();
        conica_svg_settings s = conica_svg_defaults();
        conica_svg_doc *doc = NULL;
        conica_svg_shapes sh;
        conica_status st;
        char *d = NULL, *doctext;
        size_t i, len;
        if (o->n == 0)
            continue;
        INFO("glyph U+%04lX, %s, %s", t.cp[g], with_z ? "with Z" : "without Z",
             m == SMOOTH ? "smoothed" : m == FLATTEN ? "flattened" : "scadprofile");
        opt.scale = SCALE;
        opt.close = with_z;
        REQUIRE(ts_outline_svg_path(o, &opt, &d) == TS_OK);
        len = strlen(d) + 200;
        doctext = malloc(len);
        REQUIRE(doctext != NULL);
        snprintf(doctext, len, "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"%s\"/></svg>",
                 d);
        REQUIRE(conica_svg_doc_load(doctext, strlen(doctext), NULL, &doc, &st) == CONICA_OK);
        if (m == FLATTEN || m == SCADPROFILE) {
            s.mode = CONICA_SVG_FLATTEN;
            s.tolerance = 0.01;
            s.close_open = m == SCADPROFILE;
        } else if (levels > 0) {
            s.levels = levels;
        } else {
            s.tolerance = 0.001; /* chords this close to the smoothed curve */
        }
        conica_svg_shapes_init(&sh);
        REQUIRE(conica_svg_extract(doc, &s, &sh, &st) == CONICA_OK);
        REQUIRE_EQ_U(sh.nsubpaths, o->n); /* nothing dropped */
        for (i = 0; i < o->n; i++) {
            ts_contour c = mapped(&o->c[i]);
            ts_poly poly;
            ts_hausdorff h;
            ts_corner *k = NULL;
            size_t nk = 0;
            ts_corner_check kc;
            double tol = m != SMOOTH ? 0.01 : levels > 0 ? 1e-3 * diag(&c) : 1e-3 * diag(&c) + 0.001;
            poly.xy = sh.subpaths[i].xy;
            poly.n = sh.subpaths[i].n;
            poly.closed = sh.subpaths[i].closed;
            /* an open subpath stays open (svgsmooth), is filled (scadprofile) */
            CHECK_EQ(sh.subpaths[i].closed, with_z || m == SCADPROFILE);
            if (!poly.closed) {
                /* drawn without Z, the last point is the first again */
                CHECK(poly.xy[0] == poly.xy[2 * poly.n - 2] && poly.xy[1] == poly.xy[2 * poly.n - 1]);
            }
            REQUIRE(ts_hausdorff_measure(&c, 1, &poly, 1, NULL, &h) == TS_OK);
            CAPTURE_D(tol);
            CAPTURE_D(h.max);
            CHECK_LE(h.max, tol * (1 + 1e-9));
            /* drawn without Z, the start is an end, not a join */
            c.closed = poly.closed;
            REQUIRE(ts_contour_corners(&c, 40.0 * 3.14159265358979 / 180.0 + 1e-6, &k, &nk) ==
                    TS_OK);
            /* the turn is measured between the corner's neighbours: with
             * chords as long as the tolerance allows (flattening, few
             * levels) they lean off the drawn tangents */
            REQUIRE(ts_corners_kept(k, nk, &poly, 1, 1e-9,
                                    (m == SMOOTH && levels <= 0 ? 5.0 : 25.0) * 0.0174533,
                                    &kc) == TS_OK);
            CHECK_EQ_U(kc.missing, 0);
            free(k);
            free(c.seg);
        }
        conica_svg_shapes_free(&sh);
        conica_svg_doc_free(doc);
        free(doctext);
        free(d);
    }
    ts_text_free(&t);
}

static void check_glyphs(const char *text, int with_z, mode m)
{
    check_glyphs_at(text, with_z, m, 0);
}

TEST_CASE("svgsmooth on glyphs at 2, 3 and 8 levels: what is written within the fidelity tolerance",
          "[svg][fidelity][glyphs]")
{
    SECTION("2 levels")
    check_glyphs_at("Sphinx gR&8 ZY74", 0, SMOOTH, 2);
    SECTION("3 levels")
    check_glyphs_at("Sphinx gR&8 ZY74", 0, SMOOTH, 3);
    SECTION("8 levels")
    check_glyphs_at("gR&8", 1, SMOOTH, 8);
}

TEST_CASE("svgsmooth on glyphs: within the fidelity tolerance, open subpaths open, corners kept",
          "[svg][fidelity][glyphs]")
{
    SECTION("with Z, smoothed")
    check_glyphs("Sphinx gR&8 ZY74", 1, SMOOTH);
    SECTION("without Z (opentype.js), smoothed")
    check_glyphs("Sphinx gR&8 ZY74", 0, SMOOTH);
    SECTION("flattened at 0.01")
    check_glyphs("Sphinx gR&8 ZY74", 0, FLATTEN);
}

TEST_CASE("scadprofile's geometry on glyphs: open subpaths filled, within 0.01",
          "[svg][fidelity][glyphs][scad]")
{
    check_glyphs("Sphinx gR&8 o", 0, SCADPROFILE);
}

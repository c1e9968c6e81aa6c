/* SPDX-License-Identifier: MIT */
/* The DXF reader (conica/dxf.h) on small drawings written here by hand in
 * the DXF reference's group codes: exact arcs and bulges (every flattened
 * point on the circle), chaining in either direction, units, the mirrored
 * OCS, INSERT transforms, the caps and the errors with their lines. The
 * drawings CAD tools write are tests/cli/scadprofile_dxf.sh's (ezdxf). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/dxf.h"
#include "conica_test.h"

/* Groups as "code value" words separated by '|' into DXF lines (LF or CRLF). */
static char *dxf(const char *groups, int crlf, size_t *len)
{
    size_t n = strlen(groups), k = 0;
    char *b = malloc(2 * n + 64);
    REQUIRE(b != NULL);
    for (const char *p = groups; *p;) {
        const char *bar = strchr(p, '|'), *e = bar ? bar : p + strlen(p);
        const char *sp = memchr(p, ' ', (size_t)(e - p));
        REQUIRE(sp != NULL);
        memcpy(b + k, p, (size_t)(sp - p));
        k += (size_t)(sp - p);
        if (crlf)
            b[k++] = '\r';
        b[k++] = '\n';
        memcpy(b + k, sp + 1, (size_t)(e - sp - 1));
        k += (size_t)(e - sp - 1);
        if (crlf)
            b[k++] = '\r';
        b[k++] = '\n';
        p = bar ? bar + 1 : e;
    }
    *len = k;
    return b;
}

static conica_code read_str(const char *groups, const conica_dxf_settings *s,
                            conica_dxf_drawing *d, conica_status *st)
{
    size_t len;
    char *b = dxf(groups, 0, &len);
    conica_code rc = conica_dxf_read(b, len, s, d, st);
    free(b);
    return rc;
}

#define ENT(x) "0 SECTION|2 ENTITIES|" x "|0 ENDSEC|0 EOF"

/* Largest |distance to (cx, cy) - r| over the flattened points of subpath k. */
static double off_circle(const conica_dxf_drawing *d, size_t k, double cx, double cy, double r)
{
    conica_path_settings ps = conica_path_defaults();
    conica_path_result res;
    double worst = 0;
    ps.tolerance = 1e-3;
    conica_path_result_init(&res);
    REQUIRE(conica_path_flatten(&d->path, &ps, &res, NULL) == CONICA_OK);
    for (size_t i = 0; i < res.lines[k].n; i++)
        worst = fmax(worst, fabs(hypot(res.lines[k].xy[2 * i] - cx, res.lines[k].xy[2 * i + 1] - cy) - r));
    conica_path_result_free(&res);
    return worst;
}

TEST_CASE("dxf: a circle is exact rational quadratics, LF and CRLF alike", "[dxf]")
{
    const char *g = ENT("0 CIRCLE|8 0|10 1.5|20 -2|40 3");
    conica_dxf_drawing d;
    conica_status st;
    size_t len;
    conica_dxf_drawing_init(&d);
    for (int crlf = 0; crlf < 2; crlf++) {
        char *b = dxf(g, crlf, &len);
        REQUIRE(conica_dxf_sniff(b, len));
        REQUIRE(conica_dxf_read(b, len, NULL, &d, &st) == CONICA_OK);
        free(b);
        REQUIRE(d.path.nsub == 1);
        CHECK(d.path.sub[0].closed);
        CHECK(d.path.sub[0].n == 4);
        CHECK(d.path.sub[0].x0 == 4.5); /* the quarter point, exactly */
        CHECK(d.entities == 1);
        CHECK(off_circle(&d, 0, 1.5, -2, 3) < 1e-12);
    }
    conica_dxf_drawing_free(&d);
}

TEST_CASE("dxf: a bulged LWPOLYLINE edge is the arc, in a mirrored OCS too", "[dxf]")
{
    conica_dxf_drawing d;
    conica_status st;
    conica_dxf_drawing_init(&d);
    /* 40 x 20, bulge 1 (a half circle of radius 10 about (40, 10)) on the right */
    REQUIRE(read_str(ENT("0 LWPOLYLINE|90 4|70 1|10 0|20 0|10 40|20 0|42 1|10 40|20 20|10 0|20 20"),
                     NULL, &d, &st) == CONICA_OK);
    REQUIRE(d.path.nsub == 1);
    conica_path_settings ps = conica_path_defaults();
    conica_path_result r;
    ps.tolerance = 1e-3;
    conica_path_result_init(&r);
    REQUIRE(conica_path_flatten(&d.path, &ps, &r, NULL) == CONICA_OK);
    double xmax = 0;
    for (size_t i = 0; i < r.lines[0].n; i++) {
        double x = r.lines[0].xy[2 * i], y = r.lines[0].xy[2 * i + 1];
        xmax = fmax(xmax, x);
        if (x > 40)
            CHECK(fabs(hypot(x - 40, y - 10) - 10) < 1e-12);
    }
    CHECK(fabs(xmax - 50) < 1e-12);
    conica_path_result_free(&r);
    /* the same arc as an ARC in the mirrored OCS: centre (-40, 10) there */
    REQUIRE(read_str(ENT("0 ARC|10 -40|20 10|40 10|50 90|51 270|210 0|220 0|230 -1|"
                         "0 LINE|10 40|20 0|11 40|21 20"),
                     NULL, &d, &st) == CONICA_OK);
    REQUIRE(d.path.nsub == 1);
    CHECK(d.joined == 1);
    CHECK(off_circle(&d, 0, 40, 10, 10) < 1e-12); /* the line's ends are on the circle too */
    conica_path_result_init(&r);
    REQUIRE(conica_path_flatten(&d.path, &ps, &r, NULL) == CONICA_OK);
    xmax = 0;
    for (size_t i = 0; i < r.lines[0].n; i++)
        xmax = fmax(xmax, r.lines[0].xy[2 * i]);
    CHECK(fabs(xmax - 50) < 1e-12); /* mirrored to the right of x = 40 */
    conica_path_result_free(&r);
    conica_dxf_drawing_free(&d);
}

TEST_CASE("dxf: separate entities chain in either direction; a gap is an error", "[dxf]")
{
    conica_dxf_drawing d;
    conica_status st;
    conica_dxf_settings s = conica_dxf_defaults();
    conica_dxf_drawing_init(&d);
    /* a triangle of three LINEs, the second drawn backwards */
    REQUIRE(read_str(ENT("0 LINE|10 0|20 0|11 10|21 0|0 LINE|10 0|20 10|11 10|21 0|"
                         "0 LINE|10 0|20 10|11 0|21 0"),
                     NULL, &d, &st) == CONICA_OK);
    REQUIRE(d.path.nsub == 1);
    CHECK(d.path.sub[0].n == 3);
    CHECK(d.joined == 1);
    CHECK(d.sub_line[0] == 5);
    /* the same with a gap of 0.5 */
    const char *gap = ENT("0 LINE|10 0|20 0|11 10|21 0|0 LINE|10 10|20 0|11 10|21 10|"
                          "0 LINE|10 10|20 10|11 0.5|21 0");
    CHECK(read_str(gap, NULL, &d, &st) == CONICA_ERR_PARSE);
    CHECK(strstr(st.message, "does not close: it stops at (0.5, 0)") != NULL);
    CHECK(st.line == 25); /* the LINE it stops at */
    s.gap = 0.6;
    CHECK(read_str(gap, &s, &d, &st) == CONICA_OK);
    s.gap = 0;
    s.open_mode = CONICA_DXF_OPEN_CLOSE;
    CHECK(read_str(gap, &s, &d, &st) == CONICA_OK);
    CHECK(d.closed_open == 1);
    conica_dxf_drawing_free(&d);
}

TEST_CASE("dxf: units, INSERT transforms, layers", "[dxf]")
{
    conica_dxf_drawing d;
    conica_status st;
    conica_dxf_settings s = conica_dxf_defaults();
    conica_dxf_drawing_init(&d);
    REQUIRE(read_str("0 SECTION|2 HEADER|9 $INSUNITS|70 1|0 ENDSEC|" ENT("0 CIRCLE|10 1|20 0|40 1"),
                     NULL, &d, &st) == CONICA_OK);
    CHECK(d.file_unit_mm == 25.4);
    CHECK(d.path.sub[0].x0 == 50.8);
    s.unit_mm = 25.4;
    REQUIRE(read_str("0 SECTION|2 HEADER|9 $INSUNITS|70 1|0 ENDSEC|" ENT("0 CIRCLE|10 1|20 0|40 1"),
                     &s, &d, &st) == CONICA_OK);
    CHECK(d.path.sub[0].x0 == 2);
    /* a block (a circle r 1 about (1, 0), base (1, 0)) inserted at (10, 5),
     * scaled by (-2, 2) (mirrored) and rotated 90 degrees: a circle r 2 about
     * (10, 5) whose first point, block (2, 0), goes to (10, 5) + R90 (-2, 0) */
    REQUIRE(read_str("0 SECTION|2 BLOCKS|0 BLOCK|2 B|10 1|20 0|0 CIRCLE|8 0|10 1|20 0|40 1|"
                     "0 ENDBLK|0 ENDSEC|" ENT("0 INSERT|8 cut|2 B|10 10|20 5|41 -2|42 2|50 90"),
                     NULL, &d, &st) == CONICA_OK);
    REQUIRE(d.path.nsub == 1);
    CHECK(fabs(d.path.sub[0].x0 - 10) < 1e-15);
    CHECK(fabs(d.path.sub[0].y0 - 3) < 1e-15);
    CHECK(off_circle(&d, 0, 10, 5, 2) < 1e-12);
    REQUIRE(d.nlayers == 1);
    CHECK(strcmp(d.layers[0], "cut") == 0); /* layer 0 takes the INSERT's */
    /* a frozen layer is skipped; selecting it reads it */
    const char *lay = "0 SECTION|2 TABLES|0 TABLE|2 LAYER|0 LAYER|2 F|70 1|62 7|0 ENDTAB|0 ENDSEC|" ENT(
        "0 CIRCLE|8 F|10 0|20 0|40 1|0 CIRCLE|8 V|10 5|20 0|40 1|0 TEXT|8 V|1 hello");
    REQUIRE(read_str(lay, NULL, &d, &st) == CONICA_OK);
    CHECK(d.path.nsub == 1);
    CHECK(d.skipped == 2);
    const char *want[1] = {"F"};
    s = conica_dxf_defaults();
    s.layers = want;
    s.nlayers = 1;
    REQUIRE(read_str(lay, &s, &d, &st) == CONICA_OK);
    CHECK(d.path.nsub == 1);
    CHECK(d.path.sub[0].x0 == 1);
    conica_dxf_drawing_free(&d);
}

TEST_CASE("dxf: a NURBS with a repeated knot and a periodic spline", "[dxf]")
{
    conica_dxf_drawing d;
    conica_status st;
    conica_bspline bs;
    const char *sp =
        ENT("0 SPLINE|5 2A|70 8|71 2|72 8|73 5|40 0|40 0|40 0|40 1|40 1|40 2|40 2|40 2|"
            "41 1|41 0.5|41 1|41 2|41 1|10 0|20 0|30 0|10 1|20 2|30 0|10 2|20 0|30 0|10 3|20 -2|30 0|"
            "10 4|20 0|30 0|0 LINE|10 4|20 0|11 0|21 0");
    size_t len, line = 0;
    char *b = dxf(sp, 0, &len);
    conica_dxf_drawing_init(&d);
    conica_bspline_init(&bs);
    REQUIRE(conica_dxf_read(b, len, NULL, &d, &st) == CONICA_OK);
    CHECK(d.path.nsub == 1);
    CHECK(d.joined == 1);
    REQUIRE(conica_dxf_spline(b, len, NULL, NULL, &bs, &line, &st) == CONICA_OK);
    CHECK(bs.degree == 2);
    CHECK(bs.n == 5);
    CHECK(bs.dim == 2);
    CHECK(bs.w != NULL);
    CHECK(line == 5);
    CHECK(conica_dxf_spline(b, len, "99", NULL, &bs, NULL, &st) == CONICA_ERR_ARG);
    free(b);
    /* periodic: 7 control points (the first 3 repeated), uniform knots */
    REQUIRE(read_str(ENT("0 SPLINE|70 3|71 3|72 11|73 7|40 0|40 1|40 2|40 3|40 4|40 5|40 6|40 7|"
                         "40 8|40 9|40 10|10 0|20 0|10 10|20 0|10 10|20 10|10 0|20 10|10 0|20 0|"
                         "10 10|20 0|10 10|20 10"),
                     NULL, &d, &st) == CONICA_OK);
    CHECK(d.path.nsub == 1);
    CHECK(d.path.sub[0].closed);
    conica_bspline_free(&bs);
    conica_dxf_drawing_free(&d);
}

TEST_CASE("dxf: malformed and hostile input is an error with its line", "[dxf]")
{
    conica_dxf_drawing d;
    conica_status st;
    conica_dxf_settings s = conica_dxf_defaults();
    conica_dxf_drawing_init(&d);
    static const struct {
        const char *text;
        conica_code code;
        size_t line;
        const char *msg;
    } bad[] = {
        {"0\nSECTION\n2\nENTITIES\n0\nLINE\n10\n", CONICA_ERR_PARSE, 7, "no value line"},
        {"0\nSECTION\n2\nENTITIES\n0\nLINE\nx\n1\n", CONICA_ERR_PARSE, 7, "expected a group code"},
        {"0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n10\nnan\n40\n1\n", CONICA_ERR_NONFINITE, 8, "not a finite"},
        {"0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n10\n1,5\n40\n1\n", CONICA_ERR_PARSE, 8, "expected a number"},
        {"0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n10\n1e300\n40\n1\n0\nEOF\n", CONICA_ERR_LIMIT, 5, "beyond"},
        {"0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n10\n0\n40\n-1\n0\nEOF\n", CONICA_ERR_PARSE, 5, "not positive"},
        {"AutoCAD Binary DXF\r\n\x1a", CONICA_ERR_UNSUPPORTED, 1, "binary DXF"},
        /* fuzz finding: an integer group beyond 32 bits (the cast was undefined) */
        {"0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n70\n1e44\n", CONICA_ERR_PARSE, 8,
         "group 70: expected an integer"},
        {"0\nSECTION\n2\nENTITIES\n0\nTEXT\n1\nhi\n0\nENDSEC\n0\nEOF\n", CONICA_ERR_DEGENERATE, 0, "no profile"},
        {"0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nA\n0\nINSERT\n2\nA\n0\nENDBLK\n0\nENDSEC\n0\nSECTION\n2\n"
         "ENTITIES\n0\nINSERT\n2\nA\n0\nENDSEC\n0\nEOF\n", CONICA_ERR_PARSE, 9, "inserts itself"},
        {"0\nSECTION\n2\nENTITIES\n0\nSPLINE\n5\nF1\n71\n3\n11\n0\n21\n0\n0\nEOF\n", CONICA_ERR_UNSUPPORTED, 5,
         "(handle F1) has fit points only"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        memset(&st, 0, sizeof st);
        CHECK(conica_dxf_read(bad[i].text, strlen(bad[i].text), NULL, &d, &st) == bad[i].code);
        CHECK(st.line == bad[i].line);
        CHECK(strstr(st.message, bad[i].msg) != NULL);
    }
    /* caps: vertices of one entity, INSERT nesting */
    s.limits.max_vertices = 2;
    CHECK(read_str(ENT("0 LWPOLYLINE|70 1|10 0|20 0|10 1|20 0|10 1|20 1"), &s, &d, &st) ==
          CONICA_ERR_LIMIT);
    CHECK(strstr(st.message, "max_vertices") != NULL);
    conica_dxf_drawing_free(&d);
}

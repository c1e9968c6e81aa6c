/* SPDX-License-Identifier: MIT */
/* SVG path data: the SVG 2 grammar to absolute geometry (W3C-style packed
 * numbers and flags, implicit commands, error recovery), arcs in centre
 * parametrisation, and the compact writer. */
#include <float.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica_svg.h"
#include "conica_test.h"
#include "svg_internal.h" /* conica_svg__format_number */

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Canonical text of a parse: one token per segment, absolute numbers with
 * %.15g, "!OFFSET" at the end when the data had an error. */
static char desc_buf[4096];

static void put(const char *fmt, double a, double b)
{
    size_t n = strlen(desc_buf);
    snprintf(desc_buf + n, sizeof desc_buf - n, fmt, a, b);
}

static const char *desc(const char *d)
{
    conica_svg_path p;
    conica_status st;
    size_t i;
    conica_svg_path_init(&p);
    desc_buf[0] = '\0';
    if (conica_svg_path_parse(d, strlen(d), 0, &p, &st) != CONICA_OK)
        return "PARSE-FAILED";
    for (i = 0; i < p.n; i++) {
        const conica_svg_seg *g = &p.seg[i];
        if (i)
            strcat(desc_buf, " ");
        switch (g->type) {
        case CONICA_SVG_SEG_MOVE: put("M%.15g,%.15g", g->x1, g->y1); break;
        case CONICA_SVG_SEG_LINE: put("L%.15g,%.15g", g->x1, g->y1); break;
        case CONICA_SVG_SEG_QUAD:
            put("Q%.15g,%.15g", g->c[0], g->c[1]);
            put(" %.15g,%.15g", g->x1, g->y1);
            break;
        case CONICA_SVG_SEG_CUBIC:
            put("C%.15g,%.15g", g->c[0], g->c[1]);
            put(" %.15g,%.15g", g->c[2], g->c[3]);
            put(" %.15g,%.15g", g->x1, g->y1);
            break;
        case CONICA_SVG_SEG_ARC: put("A%.15g,%.15g", g->x1, g->y1); break;
        case CONICA_SVG_SEG_CLOSE: strcat(desc_buf, "Z"); break;
        }
    }
    if (p.has_error) {
        size_t n = strlen(desc_buf);
        snprintf(desc_buf + n, sizeof desc_buf - n, " !%zu", p.error_offset);
    }
    conica_svg_path_free(&p);
    return desc_buf;
}

TEST_CASE("path grammar: commands to absolute segments", "[svg][path]")
{
    CHECK_STR_EQ(desc(""), "");
    CHECK_STR_EQ(desc("   \n"), "");
    CHECK_STR_EQ(desc("M10 10L20 20"), "M10,10 L20,20");
    CHECK_STR_EQ(desc("M 10,10 l 5,-5"), "M10,10 L15,5");
    CHECK_STR_EQ(desc("M1 1h5v5H0V0z"), "M1,1 L6,1 L6,6 L0,6 L0,0 Z");
    CHECK_STR_EQ(desc("m1 1h5v5h-6z"), "M1,1 L6,1 L6,6 L0,6 Z");
    CHECK_STR_EQ(desc("M0 0C1 1 2 1 3 0"), "M0,0 C1,1 2,1 3,0");
    CHECK_STR_EQ(desc("M1 1c1 1 2 1 3 0"), "M1,1 C2,2 3,2 4,1");
    CHECK_STR_EQ(desc("M0 0Q1 1 2 0"), "M0,0 Q1,1 2,0");
    CHECK_STR_EQ(desc("M1 1q1 1 2 0"), "M1,1 Q2,2 3,1");
}

TEST_CASE("path grammar: implicit repeated commands", "[svg][path]")
{
    /* after a moveto the extra pairs are linetos (relative after m) */
    CHECK_STR_EQ(desc("M1 2 3 4 5 6"), "M1,2 L3,4 L5,6");
    CHECK_STR_EQ(desc("m1 2 3 4 5 6"), "M1,2 L4,6 L9,12");
    CHECK_STR_EQ(desc("M0 0L1 1 2 2,3 3"), "M0,0 L1,1 L2,2 L3,3");
    CHECK_STR_EQ(desc("M0 0h1 1 1"), "M0,0 L1,0 L2,0 L3,0");
    CHECK_STR_EQ(desc("M0 0c1 1 2 1 3 0 1 1 2 1 3 0"), "M0,0 C1,1 2,1 3,0 C4,1 5,1 6,0");
    /* a relative moveto after closepath starts from the subpath start */
    CHECK_STR_EQ(desc("M10 10l10 0z m5 5"), "M10,10 L20,10 Z M15,15");
    /* drawing after Z without a moveto starts at the subpath start */
    CHECK_STR_EQ(desc("M10 10L20 10Z L5 5"), "M10,10 L20,10 Z L5,5");
    CHECK_STR_EQ(desc("M10 10L20 10Zl5 5"), "M10,10 L20,10 Z L15,15");
}

TEST_CASE("path grammar: W3C-style packed numbers", "[svg][path]")
{
    CHECK_STR_EQ(desc("M.5.5.5.5"), "M0.5,0.5 L0.5,0.5");
    CHECK_STR_EQ(desc("M0 0L-.5-.5"), "M0,0 L-0.5,-0.5");
    CHECK_STR_EQ(desc("M1e-3 1E+2"), "M0.001,100");
    CHECK_STR_EQ(desc("M1e2.5"), "M100,0.5");
    CHECK_STR_EQ(desc("M-1-2-3-4"), "M-1,-2 L-3,-4");
    CHECK_STR_EQ(desc("M+1+2"), "M1,2");
    CHECK_STR_EQ(desc("M1.5.5L2."), "M1.5,0.5 !9");
    CHECK_STR_EQ(desc("M0,0L1.,2."), "M0,0 L1,2");
    CHECK_STR_EQ(desc("M\t0\r\n0\fL 1 , 2"), "M0,0 L1,2");
    CHECK_STR_EQ(desc("M0 0l1e1-1e1"), "M0,0 L10,-10");
}

TEST_CASE("path grammar: packed arc flags", "[svg][path][arc]")
{
    /* "a1 1 0 0110 10": flags 0 and 1 run into the x coordinate 10 */
    CHECK_STR_EQ(desc("M0 0a1 1 0 0110 10"), "M0,0 A10,10");
    CHECK_STR_EQ(desc("M0 0a1,1,0,0,1,10,10"), "M0,0 A10,10");
    CHECK_STR_EQ(desc("M0 0A1 1 0 1 0 5 5"), "M0,0 A5,5");
    CHECK_STR_EQ(desc("M0 0a1 1 0 11.5.5"), "M0,0 A0.5,0.5");
    /* implicit repeat of the arc */
    CHECK_STR_EQ(desc("M0 0a5 5 0 0 1 10 0 5 5 0 0 1 10 0"), "M0,0 A10,0 A20,0");
    /* a flag must be a single 0 or 1 */
    CHECK_STR_EQ(desc("M0 0a1 1 0 2 1 3 3"), "M0,0 !11");
    CHECK_STR_EQ(desc("M0 0a1 1 0 .1 1 3 3"), "M0,0 !11");
}

TEST_CASE("path grammar: errors keep the valid prefix", "[svg][path][errors]")
{
    CHECK_STR_EQ(desc("L10 10"), " !0");
    CHECK_STR_EQ(desc("M10 10L20"), "M10,10 !9");
    CHECK_STR_EQ(desc("M10 10 L20 20 X 5"), "M10,10 L20,20 !14");
    CHECK_STR_EQ(desc("M10 10,L20 20"), "M10,10 !7");
    CHECK_STR_EQ(desc("M,10 10"), " !1");
    CHECK_STR_EQ(desc("M1 2L3 4 5"), "M1,2 L3,4 !10");
    CHECK_STR_EQ(desc("M1 2L nan 3"), "M1,2 !6");
    CHECK_STR_EQ(desc("M1 2L1e999 3"), "M1,2 !5");
    CHECK_STR_EQ(desc("M1 2Z 3"), "M1,2 Z !6");
    CHECK_STR_EQ(desc("M1 2C1 2 3"), "M1,2 !10");
    CHECK_STR_EQ(desc("M1 2L3 4,"), "M1,2 L3,4 !9");
    CHECK_STR_EQ(desc("M1 2L3 4e"), "M1,2 L3,4 !8");
}

TEST_CASE("path grammar: smooth curve reflection", "[svg][path]")
{
    CHECK_STR_EQ(desc("M0 0C1 1 2 1 3 0S5 -1 6 0"), "M0,0 C1,1 2,1 3,0 C4,-1 5,-1 6,0");
    CHECK_STR_EQ(desc("M0 0C1 1 2 1 3 0s2 -1 3 0"), "M0,0 C1,1 2,1 3,0 C4,-1 5,-1 6,0");
    /* S after a non-cubic: the first control is the current point */
    CHECK_STR_EQ(desc("M0 0L3 0S5 -1 6 0"), "M0,0 L3,0 C3,0 5,-1 6,0");
    CHECK_STR_EQ(desc("M0 0Q1 1 2 0T4 0"), "M0,0 Q1,1 2,0 Q3,-1 4,0");
    CHECK_STR_EQ(desc("M0 0Q1 1 2 0t2 0t2 0"), "M0,0 Q1,1 2,0 Q3,-1 4,0 Q5,1 6,0");
    CHECK_STR_EQ(desc("M0 0C1 1 2 1 3 0T5 0"), "M0,0 C1,1 2,1 3,0 Q3,0 5,0");
}

static conica_svg_seg one_arc(const char *d)
{
    conica_svg_path p;
    conica_svg_seg g;
    conica_svg_path_init(&p);
    memset(&g, 0, sizeof g);
    REQUIRE(conica_svg_path_parse(d, strlen(d), 0, &p, NULL) == CONICA_OK);
    REQUIRE(p.n >= 2);
    g = p.seg[1];
    conica_svg_path_free(&p);
    return g;
}

static void arc_point(const conica_svg_seg *g, double t, double *x, double *y)
{
    double th = g->theta1 + t * g->dtheta;
    double ex = g->rx * cos(th), ey = g->ry * sin(th);
    *x = g->cx + cos(g->phi) * ex - sin(g->phi) * ey;
    *y = g->cy + sin(g->phi) * ex + cos(g->phi) * ey;
}

TEST_CASE("arcs: endpoint to centre parametrisation", "[svg][path][arc]")
{
    SECTION("half circle")
    {
        conica_svg_seg g = one_arc("M0 0A5 5 0 0 1 10 0");
        REQUIRE(g.type == CONICA_SVG_SEG_ARC);
        CHECK_NEAR(g.cx, 5.0, 1e-12);
        CHECK_NEAR(g.cy, 0.0, 1e-12);
        CHECK_NEAR(fabs(g.dtheta), M_PI, 1e-12);
        CHECK(g.dtheta > 0.0); /* sweep-flag 1: angles increase */
    }
    SECTION("radii scaled up when too small (F.6.6)")
    {
        conica_svg_seg g = one_arc("M0 0A1 1 0 0 1 10 0");
        CHECK_NEAR(g.rx, 5.0, 1e-12);
        CHECK_NEAR(g.ry, 5.0, 1e-12);
        CHECK_NEAR(g.cx, 5.0, 1e-12);
    }
    SECTION("the four flag combinations pick the four arcs")
    {
        const char *d[4] = {"M0 0A10 10 0 0 0 10 10", "M0 0A10 10 0 0 1 10 10",
                            "M0 0A10 10 0 1 0 10 10", "M0 0A10 10 0 1 1 10 10"};
        int k;
        for (k = 0; k < 4; k++) {
            conica_svg_seg g = one_arc(d[k]);
            int large = k >= 2, sweep = k % 2;
            double x, y;
            INFO("%s", d[k]);
            CHECK(g.type == CONICA_SVG_SEG_ARC);
            CHECK((fabs(g.dtheta) > M_PI) == large);
            CHECK((g.dtheta > 0.0) == sweep);
            arc_point(&g, 0.0, &x, &y);
            CHECK_NEAR(x, 0.0, 1e-12);
            CHECK_NEAR(y, 0.0, 1e-12);
            arc_point(&g, 1.0, &x, &y);
            CHECK_NEAR(x, 10.0, 1e-12);
            CHECK_NEAR(y, 10.0, 1e-12);
            /* centre is (10,0) or (0,10): both at radius 10 from the ends */
            CHECK_NEAR(hypot(g.cx, g.cy), 10.0, 1e-12);
        }
    }
    SECTION("rotated ellipse far from the origin passes through its end points")
    {
        conica_svg_seg g = one_arc("M5003 2998A40 15 30 1 0 4990 3011");
        double x, y;
        REQUIRE(g.type == CONICA_SVG_SEG_ARC);
        arc_point(&g, 0.0, &x, &y);
        CHECK_NEAR(x, 5003.0, 1e-9);
        CHECK_NEAR(y, 2998.0, 1e-9);
        arc_point(&g, 1.0, &x, &y);
        CHECK_NEAR(x, 4990.0, 1e-9);
        CHECK_NEAR(y, 3011.0, 1e-9);
        CHECK_NEAR(g.phi, M_PI / 6.0, 1e-15);
        CHECK(fabs(g.dtheta) > M_PI);
    }
    SECTION("zero radius is a line, coincident end points drop the arc")
    {
        CHECK_STR_EQ(desc("M0 0A0 5 0 0 1 10 0"), "M0,0 L10,0");
        CHECK_STR_EQ(desc("M0 0A5 0 0 0 1 10 0"), "M0,0 L10,0");
        CHECK_STR_EQ(desc("M3 4A5 5 0 0 1 3 4L1 1"), "M3,4 L1,1");
        /* overflow near DBL_MAX (found by fuzz_svg_path): the chord, no NaN */
        CHECK_STR_EQ(desc("M20 5e180A15 15 0 0 1 0 0"), "M20,5e+180 L0,0");
        CHECK_STR_EQ(desc("M-1e308 0A1 1 0 0 1 1e308 0"), "M-1e+308,0 L1e+308,0");
        /* negative radii are taken by absolute value */
        CHECK_STR_EQ(desc("M0 0A-5 -5 0 0 1 10 0"), "M0,0 A10,0");
    }
}

TEST_CASE("points lists", "[svg][path]")
{
    double *xy = NULL;
    size_t n = 0, bad = 0;
    const char *s = "1,2 3,4 -5-6";
    REQUIRE(conica_svg_points_parse(s, strlen(s), 0, &xy, &n, &bad, NULL) == CONICA_OK);
    CHECK_EQ_U(n, 3);
    CHECK_EQ_U(bad, (size_t)-1);
    CHECK(xy[4] == -5.0 && xy[5] == -6.0);
    free(xy);
    s = "1,2 3,4 5";
    REQUIRE(conica_svg_points_parse(s, strlen(s), 0, &xy, &n, &bad, NULL) == CONICA_OK);
    CHECK_EQ_U(n, 2);
    CHECK_EQ_U(bad, 9);
    free(xy);
    s = "1,2 3,4 5,6";
    CHECK(conica_svg_points_parse(s, strlen(s), 2, &xy, &n, &bad, NULL) == CONICA_ERR_LIMIT);
}

TEST_CASE("segment cap", "[svg][path][limits]")
{
    conica_svg_path p;
    conica_status st;
    const char *d = "M0 0L1 1 2 2 3 3 4 4";
    conica_svg_path_init(&p);
    CHECK(conica_svg_path_parse(d, strlen(d), 3, &p, &st) == CONICA_ERR_LIMIT);
    CHECK_EQ_U(p.n, 0);
    CHECK(conica_svg_path_parse(d, strlen(d), 5, &p, &st) == CONICA_OK);
    CHECK_EQ_U(p.n, 5);
    conica_svg_path_free(&p);
}

static const char *fmt(const double *xy, size_t n, int closed, int precision)
{
    conica_svg_subpath sp;
    char *s = NULL;
    size_t len = 0;
    sp.element = 0;
    sp.closed = closed;
    sp.n = n;
    sp.xy = (double *)xy;
    REQUIRE(conica_svg_format_path(&sp, 1, precision, &s, &len, NULL) == CONICA_OK);
    snprintf(desc_buf, sizeof desc_buf, "%s", s);
    CHECK_EQ_U(len, strlen(s));
    free(s);
    return desc_buf;
}

TEST_CASE("compact writer", "[svg][path][write]")
{
    const double a[] = {0, 0, 0.5, -0.5, 10, 20};
    const double b[] = {1.0 / 3.0, 1e-7, 123456789.0, -0.0, 0.25, 0.125};
    const double c[] = {1.5, 2.5, 0.5, 1e-5};
    CHECK_STR_EQ(fmt(a, 3, 1, 7), "M0 0L.5-.5 10 20Z");
    CHECK_STR_EQ(fmt(a, 3, 0, 7), "M0 0L.5-.5 10 20");
    CHECK_STR_EQ(fmt(a, 1, 0, 7), "M0 0");
    CHECK_STR_EQ(fmt(b, 3, 0, 7), "M.3333333 1e-7L1.234568e8 0 .25.125");
    CHECK_STR_EQ(fmt(c, 2, 0, 3), "M1.5 2.5L.5 1e-5");
}

TEST_CASE("writer and parser round-trip every double at 17 digits", "[svg][path][write]")
{
    double xy[400];
    unsigned long long r = 88172645463325252ULL;
    size_t i;
    conica_svg_subpath sp;
    conica_svg_path p;
    char *s = NULL;
    size_t len = 0;
    for (i = 0; i < 400; i++) {
        double m, e;
        r ^= r << 13, r ^= r >> 7, r ^= r << 17;
        m = (double)(r >> 11) / 9007199254740992.0 - 0.5;
        e = (double)((int)(r % 41) - 20);
        xy[i] = m * pow(10.0, e);
    }
    sp.element = 0;
    sp.closed = 1;
    sp.n = 200;
    sp.xy = xy;
    REQUIRE(conica_svg_format_path(&sp, 1, 17, &s, &len, NULL) == CONICA_OK);
    conica_svg_path_init(&p);
    REQUIRE(conica_svg_path_parse(s, len, 0, &p, NULL) == CONICA_OK);
    CHECK_FALSE(p.has_error);
    REQUIRE_EQ_U(p.n, 201);
    for (i = 0; i < 200; i++) {
        INFO("point %zu", i);
        CHECK(p.seg[i].x1 == xy[2 * i]);
        CHECK(p.seg[i].y1 == xy[2 * i + 1]);
    }
    CHECK(p.seg[200].type == CONICA_SVG_SEG_CLOSE);
    conica_svg_path_free(&p);
    free(s);
}

TEST_CASE("numbers are written within half a unit of the last digit", "[svg][path][write]")
{
    unsigned long long r = 0x9E3779B97F4A7C15ULL;
    int i, p;
    for (p = 1; p <= 17; p++)
        for (i = 0; i < 20000; i++) {
            double v, back = 0.0, unit;
            char buf[48];
            size_t n;
            conica_svg_path path;
            char d[64];
            r ^= r << 13, r ^= r >> 7, r ^= r << 17;
            v = ((double)(r >> 11) / 9007199254740992.0 - 0.5) *
                pow(10.0, (double)((int)(r % 61) - 30));
            if (i % 7 == 0)
                v = floor(v * 1000.0) / 8.0; /* exact binary fractions: ties */
            n = conica_svg__format_number(v, p, buf);
            REQUIRE_EQ_U(n, strlen(buf));
            snprintf(d, sizeof d, "M%s 0", buf);
            conica_svg_path_init(&path);
            REQUIRE(conica_svg_path_parse(d, strlen(d), 0, &path, NULL) == CONICA_OK);
            REQUIRE_EQ_U(path.n, 1);
            back = path.seg[0].x1;
            conica_svg_path_free(&path);
            unit = v == 0.0 ? 0.0 : pow(10.0, floor(log10(fabs(v))) - p + 1);
            INFO("v=%.17g precision %d -> %s", v, p, buf);
            /* half a unit of the last digit, plus the rounding of the
             * decimal string back to binary (a tie is not representable) */
            CHECK_LE(fabs(back - v), 0.5 * unit * (1 + 1e-9) + 4.0 * DBL_EPSILON * fabs(v));
            if (p == 17)
                CHECK(back == v);
        }
}

/* A decimal-comma LC_NUMERIC, compiled with localedef into a temporary
 * LOCPATH when none is installed (glibc reads LOCPATH at setlocale). */
static int comma_locale(char *dir, size_t cap)
{
    static const char *names[] = {"de_DE.UTF-8", "fr_FR.UTF-8", "ru_RU.UTF-8"};
    char cmd[1200];
    FILE *f;
    size_t i;
    for (i = 0; i < sizeof names / sizeof names[0]; i++)
        if (setlocale(LC_NUMERIC, names[i]) && !strcmp(localeconv()->decimal_point, ","))
            return 1;
    snprintf(dir, cap, "/tmp/conica-svg-locale.XXXXXX");
    if (!mkdtemp(dir))
        return 0;
    snprintf(cmd, sizeof cmd, "%s/src", dir);
    if (!(f = fopen(cmd, "w")))
        return 0;
    fputs("LC_NUMERIC\ndecimal_point \"<U002C>\"\nthousands_sep \"\"\ngrouping -1\n"
          "END LC_NUMERIC\n", f);
    fclose(f);
    snprintf(cmd, sizeof cmd, "localedef -c -i %s/src -f UTF-8 %s/xx_XX.UTF-8 >/dev/null 2>&1",
             dir, dir);
    if (system(cmd) == -1)
        return 0;
    setenv("LOCPATH", dir, 1);
    return setlocale(LC_NUMERIC, "xx_XX.UTF-8") && !strcmp(localeconv()->decimal_point, ",");
}

TEST_CASE("path data is read and written the same under a decimal-comma locale",
          "[svg][path][locale]")
{
    char dir[256] = "", cmd[300];
    const double xy[4] = {0.5, -1.25e-7, 1234.5678901234567, 3.0};
    conica_svg_subpath sp;
    int k, ok = comma_locale(dir, sizeof dir);
    if (!ok) {
        setlocale(LC_NUMERIC, "C");
        SKIP("no decimal-comma locale (none installed and localedef failed)");
    }
    CHECK_STR_EQ(desc("M1.5,2.5L.5-1e-1"), "M1,5,2,5 L0,5,-0,1"); /* %g of the test obeys the locale */
    sp.element = 0;
    sp.closed = 0;
    sp.n = 2;
    sp.xy = (double *)xy;
    for (k = 0; k < 2; k++) {
        char *s = NULL;
        size_t len = 0;
        conica_svg_path p;
        REQUIRE(conica_svg_format_path(&sp, 1, k ? 17 : 7, &s, &len, NULL) == CONICA_OK);
        INFO("%s", s);
        CHECK(strchr(s, ',') == NULL);
        conica_svg_path_init(&p);
        REQUIRE(conica_svg_path_parse(s, len, 0, &p, NULL) == CONICA_OK);
        REQUIRE_EQ_U(p.n, 2);
        if (k)
            CHECK(p.seg[1].x1 == xy[2]);
        CHECK_NEAR(p.seg[0].x1, 0.5, 0.0);
        conica_svg_path_free(&p);
        free(s);
    }
    setlocale(LC_NUMERIC, "C");
    if (dir[0]) {
        unsetenv("LOCPATH");
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
        CHECK(system(cmd) == 0);
    }
}

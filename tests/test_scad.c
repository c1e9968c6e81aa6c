/* SPDX-License-Identifier: MIT */
/* Unit tests of the OpenSCAD export library (openscad_export/). The tests
 * that run OpenSCAD itself are in tests/cli/scadprofile.sh. */
#include "conica_test.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/subdiv.h"
#include "conica_scad.h"
#include "scad_clip.h"
#include "scad_internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void circle(double *xy, size_t n, double cx, double cy, double r, int ccw)
{
    for (size_t i = 0; i < n; i++) {
        double t = 2 * M_PI * (double)i / (double)n * (ccw ? 1 : -1);
        xy[2 * i] = cx + r * cos(t);
        xy[2 * i + 1] = cy + r * sin(t);
    }
}

static void square(double *xy, double x0, double y0, double s, int ccw)
{
    double c[8] = {x0, y0, x0 + s, y0, x0 + s, y0 + s, x0, y0 + s};
    for (int i = 0; i < 4; i++) {
        int j = ccw ? i : (4 - i) % 4;
        xy[2 * i] = c[2 * j];
        xy[2 * i + 1] = c[2 * j + 1];
    }
}

/* Profile of groups given as (fill, contours...) built by the caller. */
static size_t group(conica_scad_profile *p, const char *name, conica_scad_fill fill)
{
    size_t g = 0;
    REQUIRE_EQ(conica_scad_add_group(p, name, fill, 0, &g, NULL), CONICA_OK);
    return g;
}

TEST_CASE("numbers print shortest and round-trip", "[scad][format]")
{
    char buf[40];
    conica_scad_format_double(0.1, buf, sizeof buf);
    CHECK_STR_EQ(buf, "0.1");
    conica_scad_format_double(1.0, buf, sizeof buf);
    CHECK_STR_EQ(buf, "1");
    conica_scad_format_double(-0.0, buf, sizeof buf);
    CHECK_STR_EQ(buf, "0");
    conica_scad_format_double(-2.5, buf, sizeof buf);
    CHECK_STR_EQ(buf, "-2.5");
    conica_scad_format_double(1.0 / 3.0, buf, sizeof buf);
    CHECK_EQ(strtod(buf, NULL) == 1.0 / 3.0, 1);
    CHECK_STR_EQ(buf, "0.3333333333333333");
    conica_scad_format_double(1e-300, buf, sizeof buf);
    CHECK_STR_EQ(buf, "1e-300");
    ct_rng r;
    ct_rng_init(&r, 7);
    for (int i = 0; i < 20000; i++) {
        double v = ct_rng_range(&r, -1, 1) * pow(10.0, ct_rng_range(&r, -20, 20));
        size_t len = conica_scad_format_double(v, buf, sizeof buf);
        INFO("value %.17g printed %s", v, buf);
        REQUIRE(strtod(buf, NULL) == v);
        REQUIRE(len == strlen(buf));
        /* shortest of the three: a shorter precision must not round-trip */
        char shorter[40];
        const char *digits = strchr(buf, 'e');
        (void)digits;
        snprintf(shorter, sizeof shorter, "%.15g", v);
        if (strtod(shorter, NULL) == v)
            REQUIRE(strlen(buf) <= strlen(shorter));
    }
}

TEST_CASE("orientation is exact near collinear points", "[scad][orient]")
{
    double a[2] = {0.5, 0.5}, b[2] = {12, 12}, c[2] = {24, 24};
    CHECK_EQ(conica__orient2d(a, b, c), 0);
    /* Shewchuk's classic grid: points x = 0.5 + i ulp around the line y = x */
    int wrong = 0;
    for (int i = 0; i < 64; i++)
        for (int j = 0; j < 64; j++) {
            double p[2] = {0.5, 0.5};
            for (int k = 0; k < i; k++)
                p[0] = nextafter(p[0], 1);
            for (int k = 0; k < j; k++)
                p[1] = nextafter(p[1], 1);
            int expect = p[1] > p[0] ? 1 : p[1] < p[0] ? -1 : 0; /* b, c on y = x */
            if (conica__orient2d(b, c, p) != expect)
                wrong++;
        }
    CHECK_EQ(wrong, 0);
    double q[2] = {0.1, nextafter(0.1, 1)};
    double o[2] = {0, 0}, e[2] = {1, 1};
    CHECK_EQ(conica__orient2d(o, e, q), 1);
    CHECK_EQ(conica__orient2d(e, o, q), -1);
}

TEST_CASE("validation refuses what OpenSCAD would render wrongly", "[scad][validate]")
{
    conica_scad_profile p;
    conica_scad_violation v;
    conica_status st;
    conica_scad_profile_init(&p);
    size_t g = group(&p, "shape", CONICA_SCAD_FILL_NONZERO);

    SECTION("a square is valid")
    {
        double xy[8];
        square(xy, 0, 0, 1, 1);
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 4, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 1, &v, &st), CONICA_OK);
        CHECK_EQ(v.problem, CONICA_SCAD_OK);
    }
    SECTION("a bowtie names its crossing segments")
    {
        double xy[8] = {0, 0, 2, 2, 2, 0, 0, 2};
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 4, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_SELF_INTERSECTION);
        CHECK_EQ_U(v.segment_a, 0);
        CHECK_EQ_U(v.segment_b, 2);
        CHECK_NEAR(v.x, 1, 1e-15);
        CHECK_NEAR(v.y, 1, 1e-15);
        INFO("%s", st.message);
        CHECK(strstr(st.message, "segment 1 (points 1-2) and segment 3 (points 3-4)") != NULL);
        /* named by its group and its number in it, nothing else */
        CHECK(strncmp(st.message, "shape: subpath 1 intersects itself", 34) == 0);
        CHECK(strstr(st.message, "contour") == NULL);
    }
    SECTION("a figure eight touching itself at one vertex")
    {
        double xy[12] = {0, 0, 1, 1, 2, 0, 2, 2, 1, 1, 0, 2};
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 6, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_SELF_INTERSECTION);
    }
    SECTION("a spike running back along its edge")
    {
        double xy[10] = {0, 0, 4, 0, 2, 0, 2, 3, 0, 3};
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 5, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_SELF_INTERSECTION);
    }
    SECTION("duplicate consecutive points, including last and first")
    {
        double xy[10] = {0, 0, 1, 0, 1, 1, 0, 1, 0, 0};
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 5, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_DUPLICATE_POINT);
        CHECK_EQ_U(v.segment_a, 4);
    }
    SECTION("zero area")
    {
        /* folded onto a line: zero area, not "intersects itself" */
        double xy[6] = {0, 0, 1, 1, 3, 3};
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 3, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_ZERO_AREA);
        CHECK(strstr(st.message, "zero area") != NULL);
    }
    SECTION("collinear beyond the first two points, in any order")
    {
        double xy[10] = {2, 2, 3, 3, 0, 0, 5, 5, 1, 1};
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 5, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_ZERO_AREA);
    }
    SECTION("a spike folding back in a contour with area still intersects itself")
    {
        double xy[10] = {0, 0, 4, 0, 4, 4, 4, 6, 4, 2};
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 5, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_SELF_INTERSECTION);
    }
    SECTION("zero area without a crossing")
    {
        double xy[6] = {0, 0, 1e-200, 1e-200, 1, 0};
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 3, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_ZERO_AREA);
    }
    SECTION("too few points")
    {
        double xy[4] = {0, 0, 1, 1};
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 2, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_TOO_FEW_POINTS);
    }
    SECTION("coordinates beyond CONICA_SCAD_MAX_COORD are out of range, checked first")
    {
        /* a triangle at 1e200: its area overflows, and it used to be
         * reported as "zero area (collinear)" */
        double big[6] = {0, 0, 1e200, 0, 0, 1e200};
        double e15[6] = {0, 0, 1e15, 0, 0, 1};
        double edge[6] = {0, 0, CONICA_SCAD_MAX_COORD, 0, 0, -CONICA_SCAD_MAX_COORD};
        double sq[8];
        square(sq, 0, 0, 1, 1);
        REQUIRE_EQ(conica_scad_add_contour(&p, g, sq, 4, NULL), CONICA_OK);
        REQUIRE_EQ(conica_scad_add_contour(&p, g, big, 3, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(v.problem, CONICA_SCAD_OUT_OF_RANGE);
        CHECK_EQ_U(v.contour_a, 1);
        CHECK_EQ_U(v.segment_a, 1);
        INFO("%s", st.message);
        CHECK(strncmp(st.message, "shape: subpath 2: point 2 (1e+200, 0) is out of range", 52) ==
              0);
        CHECK(strstr(st.message, "zero area") == NULL);
        CHECK_EQ(conica_scad_check_range(&p, &v, &st), CONICA_ERR_LIMIT);
        conica_scad_profile_free(&p);
        g = group(&p, "shape", CONICA_SCAD_FILL_NONZERO);
        REQUIRE_EQ(conica_scad_add_contour(&p, g, e15, 3, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(v.problem, CONICA_SCAD_OUT_OF_RANGE);
        conica_scad_profile_free(&p);
        g = group(&p, "shape", CONICA_SCAD_FILL_NONZERO);
        REQUIRE_EQ(conica_scad_add_contour(&p, g, edge, 3, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_check_range(&p, &v, &st), CONICA_OK); /* the bound itself is fine */
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_OK);
    }
    SECTION("rotate_extrude needs x >= 0")
    {
        double xy[8];
        square(xy, -0.5, 0, 1, 1);
        REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 4, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 1, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_NEGATIVE_X);
        CHECK(strstr(st.message, "x < 0") != NULL);
    }
    SECTION("two contours that cross")
    {
        double a[8], b[8];
        square(a, 0, 0, 2, 1);
        square(b, 1, 1, 2, 1);
        REQUIRE_EQ(conica_scad_add_contour(&p, g, a, 4, NULL), CONICA_OK);
        REQUIRE_EQ(conica_scad_add_contour(&p, g, b, 4, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_CONTOURS_CROSS);
        CHECK_EQ_U(v.contour_a, 0);
        CHECK_EQ_U(v.contour_b, 1);
    }
    SECTION("large star: valid, then one crossing found")
    {
        size_t n = 200000;
        double *xy = malloc(2 * n * sizeof *xy);
        REQUIRE(xy != NULL);
        for (size_t i = 0; i < n; i++) {
            double t = 2 * M_PI * (double)i / (double)n;
            double r = 100 + 20 * sin(2000 * t);
            xy[2 * i] = r * cos(t);
            xy[2 * i + 1] = r * sin(t);
        }
        CHECK_EQ(conica_scad_add_contour(&p, g, xy, n, NULL), CONICA_OK);
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_OK);
        /* swap two neighbouring points far apart from the start: a tiny bowtie */
        double tx = xy[2 * 1000], ty = xy[2 * 1000 + 1];
        p.contours[0].xy[2 * 1000] = xy[2 * 1001];
        p.contours[0].xy[2 * 1000 + 1] = xy[2 * 1001 + 1];
        p.contours[0].xy[2 * 1001] = tx;
        p.contours[0].xy[2 * 1001 + 1] = ty;
        CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_DEGENERATE);
        CHECK_EQ(v.problem, CONICA_SCAD_SELF_INTERSECTION);
        CHECK(v.segment_a >= 999);
        CHECK(v.segment_b <= 1001);
        free(xy);
    }
    conica_scad_profile_free(&p);
}

/* conica_scad_drop_empty()'s reports, collected. */
typedef struct drops {
    size_t n;
    size_t subpath[8];
    conica_scad_problem problem[8];
    char message[8][256];
} drops;

static void collect_drop(void *ctx, const conica_scad_profile *p, size_t c,
                         const conica_scad_violation *v, const char *message)
{
    drops *d = ctx;
    if (d->n < 8) {
        d->subpath[d->n] = p->contours[c].subpath;
        d->problem[d->n] = v->problem;
        snprintf(d->message[d->n], sizeof d->message[d->n], "%s", message);
    }
    d->n++;
}

TEST_CASE("contours without area are dropped and named; the rest stay in order",
          "[scad][validate][drop]")
{
    conica_scad_profile p;
    conica_scad_profile_init(&p);
    size_t g = group(&p, "path 'a'", CONICA_SCAD_FILL_EVENODD);
    size_t h = group(&p, "rect (no id)", CONICA_SCAD_FILL_NONZERO);
    double sq[8], two[4] = {20, 20, 30, 30}, line[6] = {40, 40, 50, 50, 60, 60};
    double dupline[8] = {70, 0, 70, 0, 71, 0, 72, 0};
    double bow[8] = {0, 20, 2, 22, 2, 20, 0, 22}; /* signed area 0, but a bowtie */
    double tri_dup[8] = {0, 30, 0, 30, 1, 30, 0, 31}; /* a duplicate, not collinear */
    double far[6] = {0, 0, 1e200, 0, 0, 1e200};
    double sq2[8];
    square(sq, 0, 0, 10, 1);
    square(sq2, 50, 0, 5, 1);
    REQUIRE_EQ(conica_scad_add_contour(&p, g, sq, 4, NULL), CONICA_OK);
    REQUIRE_EQ(conica_scad_add_contour(&p, g, two, 2, NULL), CONICA_OK);
    REQUIRE_EQ(conica_scad_add_contour(&p, g, line, 3, NULL), CONICA_OK);
    REQUIRE_EQ(conica_scad_add_contour(&p, g, dupline, 4, NULL), CONICA_OK);
    REQUIRE_EQ(conica_scad_add_contour(&p, g, bow, 4, NULL), CONICA_OK);
    REQUIRE_EQ(conica_scad_add_contour(&p, g, tri_dup, 4, NULL), CONICA_OK);
    REQUIRE_EQ(conica_scad_add_contour(&p, g, far, 3, NULL), CONICA_OK);
    REQUIRE_EQ(conica_scad_add_contour(&p, h, sq2, 4, NULL), CONICA_OK);
    CHECK_EQ_U(p.contours[6].subpath, 7);
    CHECK_EQ_U(p.contours[7].subpath, 1); /* numbered within its own group */
    size_t before = p.npoints, dropped = 0;
    drops d;
    memset(&d, 0, sizeof d);
    REQUIRE_EQ(conica_scad_drop_empty(&p, collect_drop, &d, &dropped, NULL), CONICA_OK);
    CHECK_EQ_U(dropped, 3);
    REQUIRE_EQ_U(d.n, 3);
    CHECK_EQ_U(d.subpath[0], 2);
    CHECK_EQ(d.problem[0], CONICA_SCAD_TOO_FEW_POINTS);
    INFO("%s | %s | %s", d.message[0], d.message[1], d.message[2]);
    CHECK_STR_EQ(d.message[0], "path 'a': subpath 2 has 2 points (a polygon needs 3)");
    CHECK_EQ_U(d.subpath[1], 3);
    CHECK_EQ(d.problem[1], CONICA_SCAD_ZERO_AREA);
    CHECK(strncmp(d.message[1], "path 'a': subpath 3 has zero area", 33) == 0);
    CHECK_EQ_U(d.subpath[2], 4); /* collinear with a repeated first point */
    CHECK_EQ(d.problem[2], CONICA_SCAD_ZERO_AREA);
    /* kept: the square, the bowtie (validate names its crossing), the
     * triangle with a repeated point (validate names the points), the far
     * triangle (out of range, for validate) and the other group's square */
    REQUIRE_EQ_U(p.ncontours, 5);
    CHECK_EQ_U(p.contours[0].subpath, 1);
    CHECK_EQ_U(p.contours[1].subpath, 5);
    CHECK_EQ_U(p.contours[2].subpath, 6);
    CHECK_EQ_U(p.contours[3].subpath, 7);
    CHECK_EQ_U(p.contours[4].subpath, 1);
    CHECK_EQ_U(p.contours[4].group, h);
    CHECK_EQ_U(p.npoints, before - 2 - 3 - 4);
    conica_scad_violation v;
    conica_status st;
    CHECK_EQ(conica_scad_validate(&p, 0, &v, &st), CONICA_ERR_LIMIT); /* range first */
    CHECK_EQ_U(v.contour_a, 3);
    char buf[128];
    conica_scad_describe(&p, 3, buf, sizeof buf);
    CHECK_STR_EQ(buf, "path 'a': subpath 7");
    conica_scad_describe(&p, 4, buf, sizeof buf);
    CHECK_STR_EQ(buf, "rect (no id): subpath 1");
    conica_scad_profile_free(&p);

    /* a one-contour profile without a group name is "the contour" */
    g = group(&p, "", CONICA_SCAD_FILL_NONZERO);
    REQUIRE_EQ(conica_scad_add_contour(&p, g, line, 3, NULL), CONICA_OK);
    memset(&d, 0, sizeof d);
    REQUIRE_EQ(conica_scad_drop_empty(&p, collect_drop, &d, &dropped, NULL), CONICA_OK);
    CHECK_EQ_U(p.ncontours, 0);
    CHECK_EQ_U(p.npoints, 0);
    CHECK(strncmp(d.message[0], "the contour has zero area", 25) == 0);
    conica_scad_profile_free(&p);
}

/* Significant digits of a %.17g-free decimal as printed. */
static int sig_digits(const char *s)
{
    int n = 0, started = 0, trailing = 0;
    for (; *s && *s != 'e' && *s != 'E'; s++) {
        if (*s < '0' || *s > '9')
            continue;
        if (*s != '0' || started) {
            started = 1;
            n++;
            trailing = *s == '0' ? trailing + 1 : 0;
        }
    }
    return n - trailing;
}

TEST_CASE("rounding: fewest digits within h, the input's short numbers exact",
          "[scad][format][round]")
{
    conica_scad_profile p, q;
    conica_scad_profile_init(&p);
    conica_scad_profile_init(&q);
    size_t g = group(&p, "path 'r'", CONICA_SCAD_FILL_NONZERO);
    /* exact corners computed the way a unit conversion does (80 as
     * 79.99999999999999), a curve point, a px -> mm number (not short), a
     * number just off an integer by computation noise */
    double xy[12] = {0.1 * 3, 0, 80 - 1e-14, 0.5 * 100, 37.28473829472, 12.3456789,
                     37 * 25.4 / 96, 1e-17, 12.5, 49.99999999999999, 0.19544384400537509,
                     0.0001};
    REQUIRE_EQ(conica_scad_add_contour(&p, g, xy, 6, NULL), CONICA_OK);
    p.contours[0].subpath = 4;
    const double tol = 0.01, h = tol * CONICA_SCAD_ROUND_FRACTION / sqrt(2.0);
    REQUIRE_EQ(conica_scad_round(&p, h, &q, NULL), CONICA_OK);
    REQUIRE_EQ_U(q.ncontours, 1);
    CHECK_EQ_U(q.contours[0].subpath, 4);
    CHECK_STR_EQ(q.groups[0].name, "path 'r'");
    /* a small computed number gets no more decimals than the large ones
     * (0.195443844 is within 1e-11 of this one, but is no input number);
     * a short small one stays */
    const char *want[12] = {"0.3", "0", "80", "50", "37.28474", "12.3456789", "9.78958", "0",
                            "12.5", "50", "0.19544", "0.0001"};
    for (int i = 0; i < 12; i++) {
        char buf[40];
        double r = q.contours[0].xy[i];
        conica_scad_format_double(r, buf, sizeof buf);
        INFO("coordinate %d: %.17g -> %s (want %s)", i, xy[i], buf, want[i]);
        CHECK_STR_EQ(buf, want[i]);
        CHECK_LE(fabs(r - xy[i]), h);
    }
    /* property: random points anywhere up to 1e6 move at most h per
     * coordinate, and no shorter decimal would do, unless it is kept
     * exactly (to CONICA_SCAD_EXACT_REL of the largest) in few digits */
    uint64_t seed = 12345;
    int exact = 0;
    for (int t = 0; t < 2000; t++) {
        seed = seed * 6364136223846793005u + 1442695040888963407u;
        double u = (double)(seed >> 11) / 9007199254740992.0;
        seed = seed * 6364136223846793005u + 1442695040888963407u;
        double e = (double)(seed >> 11) / 9007199254740992.0;
        double v = (u - 0.5) * pow(10, 6 * e);
        double one[6] = {v, 1, 2, 3, 4, 5};
        conica_scad_profile a;
        conica_scad_profile_init(&a);
        size_t ga = group(&a, "x", CONICA_SCAD_FILL_NONZERO);
        REQUIRE_EQ(conica_scad_add_contour(&a, ga, one, 3, NULL), CONICA_OK);
        REQUIRE_EQ(conica_scad_round(&a, h, &q, NULL), CONICA_OK);
        double r = q.contours[0].xy[0];
        char buf[40], shorter[48];
        conica_scad_format_double(r, buf, sizeof buf);
        int d = sig_digits(buf);
        CAPTURE_D(v);
        CHECK_LE(fabs(r - v), h);
        double big = fmax(fabs(v), 5);
        if (fabs(r - v) <= big * CONICA_SCAD_EXACT_REL && fabs(v) * 10 > big &&
            d <= CONICA_SCAD_EXACT_MAX_DIGITS) {
            exact++;
        } else if (d > 1) {
            snprintf(shorter, sizeof shorter, "%.*e", d - 2, v);
            CHECK(fabs(strtod(shorter, NULL) - v) > h);
        }
        conica_scad_profile_free(&a);
    }
    CHECK_LE(exact, 40); /* random numbers are rarely short */
    CHECK_EQ(conica_scad_round(&p, 0, &q, NULL), CONICA_ERR_ARG);
    conica_scad_profile_free(&q);
    conica_scad_profile_free(&p);
}

/* Count paths of the layout that are holes / outers, and check orientation. */
static void check_orientation(const conica_scad_profile *p, const conica_scad_layout *l)
{
    for (size_t i = 0; i < l->npaths; i++) {
        const conica_scad_contour *c = &p->contours[l->paths[i].contour];
        double a = conica__scad_area2(c->xy, c->n) * (l->paths[i].reversed ? -1 : 1);
        INFO("path %zu", i);
        CHECK(l->paths[i].hole ? a < 0 : a > 0);
        if (i > 0)
            CHECK(l->paths[i].hole >= l->paths[i - 1].hole); /* outers first */
    }
}

TEST_CASE("arrange: identical contours (an invalid profile, as --force) terminate",
          "[scad][arrange][reliability]")
{
    /* fuzz_scadprofile: two copies of one subpath were each other's
     * smallest containing contour, and the fill-state walk up the parent
     * links never ended (and overflowed its winding counter). */
    conica_scad_profile p;
    conica_scad_layout l;
    conica_scad_profile_init(&p);
    conica_scad_layout_init(&l);
    double a[8], b[8], c[8];
    size_t g = group(&p, "dup", CONICA_SCAD_FILL_EVENODD);
    square(a, 0, 0, 10, 1);
    square(b, 0, 0, 10, 1);
    square(c, 0, 0, 10, 1);
    conica_scad_add_contour(&p, g, a, 4, NULL);
    conica_scad_add_contour(&p, g, b, 4, NULL);
    conica_scad_add_contour(&p, g, c, 4, NULL);
    CHECK(conica_scad_validate(&p, 0, NULL, NULL) != CONICA_OK); /* they touch */
    REQUIRE_EQ(conica_scad_arrange(&p, &l, NULL), CONICA_OK);
    /* no nesting is right for coincident contours; what matters is that
     * every contour is accounted for and the first one is an outer */
    CHECK_EQ_U(l.outers + l.holes + l.dropped, 3);
    CHECK_EQ_U(l.npaths, l.outers + l.holes);
    CHECK(l.outers >= 1);
    REQUIRE(l.npaths >= 1);
    CHECK_EQ_U(l.paths[0].contour, 0);
    conica_scad_layout_free(&l);
    conica_scad_profile_free(&p);
}

/* The arrangement as it was first written, pair by pair: each contour's
 * parent is the smallest larger one (|area|, then lower index) whose
 * winding around its first vertex is not 0; the fill states walk the
 * parent chain. The naive reference for the grid and forest walk of
 * scad_arrange.c. */
static int ref_winding(const conica_scad_contour *k, const double *q)
{
    int w = 0;
    for (size_t i = 0; i < k->n; i++) {
        const double *a = &k->xy[2 * i], *b = &k->xy[2 * ((i + 1) % k->n)];
        if (a[1] <= q[1]) {
            if (b[1] > q[1] && conica__orient2d(a, b, q) > 0)
                w++;
        } else if (b[1] <= q[1] && conica__orient2d(a, b, q) < 0) {
            w--;
        }
    }
    return w;
}

static int ref_filled(const conica_scad_profile *p, const size_t *par, const double *area,
                      size_t c, int with_self)
{
    for (size_t a = with_self ? c : par[c]; a != SIZE_MAX; a = par[a]) {
        size_t g = p->contours[a].group;
        int w = 0, seen = 0;
        for (size_t b = with_self ? c : par[c]; b != a; b = par[b])
            seen |= p->contours[b].group == g;
        if (seen)
            continue;
        for (size_t b = a; b != SIZE_MAX; b = par[b])
            if (p->contours[b].group == g)
                w += area[b] > 0 ? 1 : -1;
        if (p->groups[g].fill == CONICA_SCAD_FILL_EVENODD ? (w & 1) != 0 : w != 0)
            return 1;
    }
    return 0;
}

/* Per contour: -1 dropped, else 2 * hole + reversed, and the kept parent. */
static void ref_arrange(const conica_scad_profile *p, int *kind, size_t *kept_parent)
{
    size_t n = p->ncontours;
    size_t *par = malloc(n * sizeof *par);
    double *area = malloc(n * sizeof *area);
    int *in = malloc(n * sizeof *in), *out = malloc(n * sizeof *out);
    REQUIRE(par && area && in && out);
    for (size_t c = 0; c < n; c++)
        area[c] = 0.5 * conica__scad_area2(p->contours[c].xy, p->contours[c].n);
    for (size_t c = 0; c < n; c++) {
        double best = INFINITY, ac = fabs(area[c]);
        par[c] = SIZE_MAX;
        for (size_t d = 0; d < n; d++) {
            double ad = fabs(area[d]);
            if ((ad > ac || (ad == ac && d < c)) && ad < best &&
                ref_winding(&p->contours[d], p->contours[c].xy) != 0) {
                best = ad;
                par[c] = d;
            }
        }
    }
    for (size_t c = 0; c < n; c++) {
        in[c] = ref_filled(p, par, area, c, 1);
        out[c] = ref_filled(p, par, area, c, 0);
    }
    for (size_t c = 0; c < n; c++) {
        size_t q = par[c];
        if (in[c] == out[c]) {
            kind[c] = -1;
            continue;
        }
        kind[c] = 2 * !in[c] + (!in[c] ? area[c] > 0 : area[c] < 0);
        while (q != SIZE_MAX && in[q] == out[q])
            q = par[q];
        kept_parent[c] = q;
    }
    free(par);
    free(area);
    free(in);
    free(out);
}

TEST_CASE("arrange agrees with the pairwise reference on random overlapping profiles",
          "[scad][arrange]")
{
    ct_rng r;
    ct_rng_init(&r, 17);
    for (int trial = 0; trial < 60; trial++) {
        conica_scad_profile p;
        conica_scad_layout l;
        size_t ng = 1 + (size_t)ct_rng_below(&r, 4), n = 1 + (size_t)ct_rng_below(&r, 300);
        double span = trial % 3 == 0 ? 10.0 : 100.0; /* dense piles and sparse fields */
        conica_scad_profile_init(&p);
        conica_scad_layout_init(&l);
        for (size_t g = 0; g < ng; g++)
            group(&p, "g", (size_t)ct_rng_below(&r, 2) ? CONICA_SCAD_FILL_EVENODD
                                               : CONICA_SCAD_FILL_NONZERO);
        for (size_t c = 0; c < n; c++) {
            double xy[2 * 12];
            size_t m = 3 + (size_t)ct_rng_below(&r, 10);
            double cx = ct_rng_range(&r, 0, span), cy = ct_rng_range(&r, 0, span);
            double rad = trial % 5 == 0 && c % 7 == 0 ? ct_rng_range(&r, 20, 80)
                                                     : ct_rng_range(&r, 0.5, 8);
            if (trial % 4 == 1) { /* concentric: deep nesting */
                cx = cy = 50;
                rad = 1 + (double)c * 0.25;
            }
            circle(xy, m, cx, cy, rad, (int)((size_t)ct_rng_below(&r, 2)));
            REQUIRE_EQ(conica_scad_add_contour(&p, (size_t)ct_rng_below(&r, ng), xy, m, NULL),
                       CONICA_OK);
        }
        {
            size_t total = 0;
            for (size_t c = 0; c < n; c++)
                total += p.contours[c].n;
            CHECK_EQ_U(p.npoints, total); /* kept by add_contour */
        }
        int *kind = malloc(n * sizeof *kind);
        size_t *kp = malloc(n * sizeof *kp), seen = 0;
        REQUIRE(kind && kp);
        ref_arrange(&p, kind, kp);
        conica_code rc = conica_scad_arrange(&p, &l, NULL);
        INFO("trial %d: %zu contours in %zu groups", trial, n, ng);
        if (rc != CONICA_OK) {
            for (size_t c = 0; c < n; c++)
                CHECK_EQ(kind[c], -1); /* nothing filled */
        }
        for (size_t i = 0; rc == CONICA_OK && i < l.npaths; i++) {
            size_t c = l.paths[i].contour;
            INFO("contour %zu", c);
            CHECK_EQ(kind[c], 2 * l.paths[i].hole + l.paths[i].reversed);
            CHECK_EQ_U(kp[c], l.paths[i].parent);
            seen++;
        }
        {
            size_t kept = 0;
            for (size_t c = 0; c < n; c++)
                kept += kind[c] >= 0;
            CHECK_EQ_U(seen, kept);
        }
        free(kind);
        free(kp);
        conica_scad_layout_free(&l);
        conica_scad_profile_free(&p);
    }
}

TEST_CASE("holes by containment and fill rule", "[scad][arrange]")
{
    conica_scad_profile p;
    conica_scad_layout l;
    conica_scad_profile_init(&p);
    conica_scad_layout_init(&l);
    double outer[8], inner[8], island[8];

    SECTION("evenodd: same orientation inside makes a hole, island inside it an outer")
    {
        size_t g = group(&p, "e", CONICA_SCAD_FILL_EVENODD);
        square(outer, 0, 0, 10, 0); /* clockwise: must be reversed */
        square(inner, 2, 2, 6, 0);
        square(island, 4, 4, 2, 0);
        conica_scad_add_contour(&p, g, island, 4, NULL);
        conica_scad_add_contour(&p, g, inner, 4, NULL);
        conica_scad_add_contour(&p, g, outer, 4, NULL);
        REQUIRE_EQ(conica_scad_validate(&p, 0, NULL, NULL), CONICA_OK);
        REQUIRE_EQ(conica_scad_arrange(&p, &l, NULL), CONICA_OK);
        REQUIRE_EQ_U(l.npaths, 3);
        CHECK_EQ_U(l.outers, 2);
        CHECK_EQ_U(l.holes, 1);
        CHECK_EQ_U(l.paths[2].contour, 1);
        CHECK_EQ_U(l.paths[2].parent, 2);
        check_orientation(&p, &l);
        CHECK(l.convexity >= 3);
    }
    SECTION("nonzero: same orientation inside is filled (dropped), opposite is a hole")
    {
        size_t g = group(&p, "n", CONICA_SCAD_FILL_NONZERO);
        square(outer, 0, 0, 10, 1);
        square(inner, 2, 2, 2, 1);
        square(island, 6, 6, 2, 0);
        conica_scad_add_contour(&p, g, outer, 4, NULL);
        conica_scad_add_contour(&p, g, inner, 4, NULL);
        conica_scad_add_contour(&p, g, island, 4, NULL);
        REQUIRE_EQ(conica_scad_validate(&p, 0, NULL, NULL), CONICA_OK);
        REQUIRE_EQ(conica_scad_arrange(&p, &l, NULL), CONICA_OK);
        REQUIRE_EQ_U(l.npaths, 2);
        CHECK_EQ_U(l.dropped, 1);
        CHECK_EQ_U(l.paths[0].contour, 0);
        CHECK_EQ_U(l.paths[1].contour, 2);
        CHECK_EQ(l.paths[1].hole, 1);
        check_orientation(&p, &l);
    }
    SECTION("union over groups: a shape inside another's hole stays, inside its solid goes")
    {
        size_t a = group(&p, "washer", CONICA_SCAD_FILL_EVENODD);
        size_t b = group(&p, "pin", CONICA_SCAD_FILL_NONZERO);
        size_t c = group(&p, "dot", CONICA_SCAD_FILL_NONZERO);
        double dot[8];
        square(outer, 0, 0, 10, 1);
        square(inner, 3, 3, 4, 1);
        square(island, 4, 4, 2, 0);
        square(dot, 0.5, 0.5, 1, 1);
        conica_scad_add_contour(&p, a, outer, 4, NULL);
        conica_scad_add_contour(&p, a, inner, 4, NULL);
        conica_scad_add_contour(&p, b, island, 4, NULL);
        conica_scad_add_contour(&p, c, dot, 4, NULL);
        REQUIRE_EQ(conica_scad_validate(&p, 0, NULL, NULL), CONICA_OK);
        REQUIRE_EQ(conica_scad_arrange(&p, &l, NULL), CONICA_OK);
        REQUIRE_EQ_U(l.npaths, 3);
        CHECK_EQ_U(l.dropped, 1);
        CHECK_EQ_U(l.outers, 2);
        CHECK_EQ_U(l.paths[1].contour, 2);
        CHECK_EQ(l.paths[1].reversed, 1);
        check_orientation(&p, &l);
    }
    SECTION("contours that cancel out leave nothing")
    {
        size_t g = group(&p, "z", CONICA_SCAD_FILL_NONZERO);
        size_t h = group(&p, "z2", CONICA_SCAD_FILL_NONZERO);
        square(outer, 0, 0, 10, 1);
        square(inner, 1, 1, 2, 1);
        (void)h;
        conica_scad_add_contour(&p, g, outer, 4, NULL);
        conica_scad_add_contour(&p, g, inner, 4, NULL);
        REQUIRE_EQ(conica_scad_arrange(&p, &l, NULL), CONICA_OK);
        CHECK_EQ_U(l.npaths, 1);
    }
    conica_scad_layout_free(&l);
    conica_scad_profile_free(&p);
}

TEST_CASE("the writer emits points, paths and modules", "[scad][write]")
{
    conica_scad_profile p;
    conica_scad_layout l;
    conica_scad_profile_init(&p);
    conica_scad_layout_init(&l);
    size_t g = group(&p, "w", CONICA_SCAD_FILL_EVENODD);
    double outer[8], hole[8];
    square(outer, 0, 0, 10, 0);
    square(hole, 2.5, 2.5, 0.1, 1);
    conica_scad_add_contour(&p, g, hole, 4, NULL);
    conica_scad_add_contour(&p, g, outer, 4, NULL);
    REQUIRE_EQ(conica_scad_arrange(&p, &l, NULL), CONICA_OK);
    conica_scad_write_options o = conica_scad_write_defaults();
    o.module = "bracket";
    o.header = "made by a test\nsecond line";
    o.extrude = 1;
    o.extrude_height = 3;
    o.revolve = 1;
    o.revolve_angle = 90;
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    REQUIRE(f != NULL);
    conica_status st;
    CHECK_EQ(conica_scad_write(f, &p, &l, &o, &st), CONICA_OK);
    fclose(f);
    INFO("%s", text);
    CHECK(strncmp(text, "// made by a test\n// second line\n", 33) == 0);
    /* outer first, reversed to counter-clockwise: (0,0) (0,10) (10,10) (10,0) reversed */
    CHECK(strstr(text, "function bracket_points() = [\n  [0,0],\n  [10,0],\n  [10,10],\n  [0,10],\n"
                       "  [2.5,2.5],\n  [2.5,2.6],\n  [2.6,2.6],\n  [2.6,2.5]];") != NULL);
    CHECK(strstr(text, "function bracket_paths() = [\n  [0,1,2,3],\n  [4,5,6,7]];") != NULL);
    CHECK(strstr(text, "function bracket_bbox() = [[0,0],[10,10]];") != NULL);
    CHECK(strstr(text, "module bracket(center=false)\n"
                       "  translate(center ? -(bracket_bbox()[0] + bracket_bbox()[1]) / 2 : [0, 0])\n"
                       "    polygon(points=bracket_points(), paths=bracket_paths(), convexity=2);") !=
          NULL);
    CHECK(strstr(text, "module bracket_extruded(height=3, center=false)") != NULL);
    CHECK(strstr(text, "module bracket_revolved(angle=90)") != NULL);
    /* include-safe by default: nothing but definitions and comments at the
     * top level (every line outside a definition is a comment or blank) */
    CHECK(strstr(text, "\nbracket_extruded();\n") == NULL);
    CHECK(strstr(text, "\nbracket();\n") == NULL);
    {
        int depth = 0, stray = 0;
        for (const char *line = text; *line;) {
            const char *end = strchr(line, '\n');
            size_t n = end ? (size_t)(end - line) : strlen(line);
            if (depth == 0 && n > 0 && line[0] != '/' && line[0] != ' ' &&
                strncmp(line, "function ", 9) != 0 && strncmp(line, "module ", 7) != 0)
                stray++;
            for (size_t i = 0; i < n && line[0] != '/'; i++)
                depth += (line[i] == '[') - (line[i] == ']');
            line += n + (end != NULL);
        }
        CHECK_EQ(stray, 0);
        CHECK_EQ(depth, 0);
    }
    free(text);

    /* instantiate: the call of the wrapper, for a file that renders alone */
    o.instantiate = 1;
    f = open_memstream(&text, &len);
    REQUIRE(f != NULL);
    CHECK_EQ(conica_scad_write(f, &p, &l, &o, &st), CONICA_OK);
    fclose(f);
    CHECK(strstr(text, "\nbracket_extruded();\n") != NULL);
    free(text);
    o.extrude = o.revolve = 0;
    f = open_memstream(&text, &len);
    REQUIRE(f != NULL);
    CHECK_EQ(conica_scad_write(f, &p, &l, &o, &st), CONICA_OK);
    fclose(f);
    CHECK(strstr(text, "\nbracket();\n") != NULL);
    free(text);
    o.instantiate = 0;

    o.module = "2bad";
    f = open_memstream(&text, &len);
    CHECK_EQ(conica_scad_write(f, &p, &l, &o, &st), CONICA_ERR_ARG);
    fclose(f);
    free(text);
    CHECK_EQ(conica_scad_valid_name("_ok9"), 1);
    CHECK_EQ(conica_scad_valid_name("no-dash"), 0);
    /* OpenSCAD's keywords are no identifiers: `module for()` does not parse */
    static const char *const reserved[] = {"for", "module", "function", "if", "else", "let",
                                           "each", "true", "false", "undef", "include",
                                           "use", "assert", "echo"};
    for (size_t i = 0; i < sizeof reserved / sizeof reserved[0]; i++) {
        INFO("%s", reserved[i]);
        CHECK_EQ(conica_scad_valid_name(reserved[i]), 0);
        CHECK(strstr(conica_scad_name_problem(reserved[i]), "reserved word") != NULL);
    }
    /* built-ins the file calls would be replaced by the module itself */
    CHECK_EQ(conica_scad_valid_name("polygon"), 0);
    CHECK_EQ(conica_scad_valid_name("linear_extrude"), 0);
    CHECK_EQ(conica_scad_valid_name("rotate_extrude"), 0);
    /* every built-in module (issue 31: `--module translate` made OpenSCAD
     * stop with "Recursion detected", `circle` replaced the user's circles)
     * and function */
    {
        static const char *const builtin[] = {
            "translate", "rotate", "scale", "mirror", "multmatrix", "color", "offset", "hull",
            "minkowski", "union", "difference", "intersection", "circle", "square", "text",
            "import", "projection", "surface", "cube", "sphere", "cylinder", "polyhedron",
            "children", "render", "resize", "sin", "cos", "len", "concat", "str", "max"};
        for (size_t i = 0; i < sizeof builtin / sizeof builtin[0]; i++) {
            INFO("%s", builtin[i]);
            CHECK_EQ(conica_scad_valid_name(builtin[i]), 0);
            CHECK(strstr(conica_scad_name_problem(builtin[i]), "built-in") != NULL);
        }
        CHECK_EQ(conica_scad_valid_name("translate_"), 1);
        CHECK_EQ(conica_scad_valid_name("Circle"), 1);
    }
    /* ...but words that merely contain them are fine */
    CHECK_EQ(conica_scad_valid_name("format"), 1);
    CHECK_EQ(conica_scad_valid_name("For"), 1);
    CHECK(conica_scad_name_problem("for_1") == NULL);
    o.module = "for";
    f = open_memstream(&text, &len);
    CHECK_EQ(conica_scad_write(f, &p, &l, &o, &st), CONICA_ERR_ARG);
    fclose(f);
    free(text);
    CHECK(strstr(st.message, "reserved word") != NULL);
    conica_scad_layout_free(&l);
    conica_scad_profile_free(&p);
}

TEST_CASE("thinning a dense circle comes near the minimum point count", "[scad][thin]")
{
    const double r = 50;
    const double tols[3] = {0.1, 0.01, 0.001};
    size_t n = 65536;
    double *xy = malloc(2 * n * sizeof *xy);
    REQUIRE(xy != NULL);
    circle(xy, n, 3, -7, r, 1);
    for (int k = 0; k < 3; k++) {
        double tol = tols[k], *out = NULL;
        size_t m = 0;
        REQUIRE_EQ(conica_scad_thin(xy, n, 1, tol, &out, &m, NULL), CONICA_OK);
        double minimum = ceil(M_PI / acos(1 - tol / r));
        INFO("tol %g: %zu points, minimum %g", tol, m, minimum);
        CHECK((double)m >= minimum);
        CHECK((double)m <= 1.1 * minimum);
        /* every chord within tol of the true circle: sagitta of its angle */
        double worst = 0;
        for (size_t i = 0; i < m; i++) {
            const double *a = &out[2 * i], *b = &out[2 * ((i + 1) % m)];
            double half = 0.5 * hypot(b[0] - a[0], b[1] - a[1]);
            double sag = r - sqrt(r * r - half * half);
            if (sag > worst)
                worst = sag;
        }
        CHECK_LE(worst, tol);
        free(out);
    }
    free(xy);
}

TEST_CASE("thinning keeps corners and open ends", "[scad][thin]")
{
    /* an L of 3 dense straight runs: only the 6 corners survive */
    double xy[2 * 300];
    size_t n = 0;
    const double c[7][2] = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}, {0, 0}};
    for (int s = 0; s < 6; s++)
        for (int i = 0; i < 50; i++) {
            double t = i / 50.0;
            xy[2 * n] = c[s][0] + t * (c[s + 1][0] - c[s][0]);
            xy[2 * n + 1] = c[s][1] + t * (c[s + 1][1] - c[s][1]);
            n++;
        }
    double *out = NULL;
    size_t m = 0;
    REQUIRE_EQ(conica_scad_thin(xy, n, 1, 1e-9, &out, &m, NULL), CONICA_OK);
    CHECK_EQ_U(m, 6);
    free(out);
    REQUIRE_EQ(conica_scad_thin(xy, 120, 0, 1e-9, &out, &m, NULL), CONICA_OK);
    CHECK_EQ_U(m, 4); /* start, two corners, end */
    CHECK_EQ(out[2 * 3], xy[2 * 119]);
    free(out);
    CHECK_EQ(conica_scad_thin(xy, n, 1, 0, &out, &m, NULL), CONICA_ERR_ARG);
}

TEST_CASE("refining exact circle samples to a tolerance", "[scad][refine]")
{
    /* 8 exact point-normal samples of a circle r = 50 off the origin: conic
     * subdivision reproduces the circle, thinning reaches the minimum
     * ceil(pi / acos(1 - tol / r)) = 50 / 158 / 497 within 10 %. */
    const double r = 50, cx = 1000, cy = -300;
    const double tols[3] = {0.1, 0.01, 0.001};
    double xy[16], nxy[16];
    for (int i = 0; i < 8; i++) {
        double t = 2 * M_PI * i / 8.0;
        nxy[2 * i] = cos(t);
        nxy[2 * i + 1] = sin(t);
        xy[2 * i] = cx + r * nxy[2 * i];
        xy[2 * i + 1] = cy + r * nxy[2 * i + 1];
    }
    conica_curve in;
    conica_curve_init(&in);
    REQUIRE_EQ(conica_curve_set(xy, nxy, 8, 1, &in, NULL), CONICA_OK);
    for (int k = 0; k < 3; k++) {
        double *out = NULL;
        size_t m = 0;
        conica_scad_refine_info info;
        conica_status st;
        conica_code rc = conica_scad_refine(&in, tols[k], 0, &out, &m, &info, &st);
        INFO("%s", st.message);
        REQUIRE_EQ(rc, CONICA_OK);
        double minimum = ceil(M_PI / acos(1 - tols[k] / r));
        INFO("tol %g: %zu points (minimum %g), level %d, %zu dense", tols[k], m, minimum,
             info.levels, info.dense_points);
        CHECK((double)m >= minimum);
        CHECK((double)m <= 1.1 * minimum);
        double worst_on = 0, worst_chord = 0;
        for (size_t i = 0; i < m; i++) {
            const double *a = &out[2 * i], *b = &out[2 * ((i + 1) % m)];
            worst_on = fmax(worst_on, fabs(hypot(a[0] - cx, a[1] - cy) - r));
            double half = 0.5 * hypot(b[0] - a[0], b[1] - a[1]);
            worst_chord = fmax(worst_chord, r - sqrt(r * r - half * half));
        }
        CHECK_LE(worst_on, 1e-9 * r);
        CHECK_LE(worst_chord + worst_on, tols[k]);
        free(out);
    }
    double *out = NULL;
    size_t m = 0;
    CHECK_EQ(conica_scad_refine(&in, 1e-9, 1000, &out, &m, NULL, NULL), CONICA_ERR_LIMIT);
    conica_curve_free(&in);
}

TEST_CASE("refine: the dense cap holds for curves that gain inflection points",
          "[scad][refine][limits]")
{
    /* fuzz_scadprofile: a non-convex curve gains inflection points, so its
     * levels hold more points than conica_subdiv_count() says; the cap
     * max_dense must still bound the dense polyline (or give LIMIT). */
    const double xy[] = {1.5, 0,  2, 0,    2.5, 0.8,  2.7,  2.5,  1,   3.8, 0,   4,
                         -1,  3.8, -2.7, 2.5, -2.5, 0.8, -2, 0, -1.5, 0, -1, 0.9,
                         -0.5, 1.15, 0, 1.2, 0.5, 1.15, 1, 0.9};
    conica_curve in;
    conica_curve_init(&in);
    REQUIRE_EQ(conica_curve_set(xy, NULL, 16, 1, &in, NULL), CONICA_OK);
    REQUIRE_EQ(conica_curve_estimate_normals(&in, CONICA_NORMALS_AREA, NULL), CONICA_OK);
    conica_subdiv_settings set = conica_subdiv_defaults();
    conica_subdiv_info sinfo;
    conica_subdiv_info_init(&sinfo);
    conica_curve one;
    conica_curve_init(&one);
    set.levels = 1;
    REQUIRE_EQ(conica_subdivide(&in, &set, &one, &sinfo, NULL), CONICA_OK);
    REQUIRE(sinfo.inflections > 0); /* else this case tests nothing */
    conica_curve_free(&one);
    conica_subdiv_info_free(&sinfo);
    size_t ok = 0;
    for (int level = 1; level <= 6; level++) {
        /* the count without inflection points: too small for this curve */
        size_t cap = conica_subdiv_count(16, 1, level);
        for (double tol = 10; tol > 1e-4; tol /= 4) {
            double *out = NULL;
            size_t m = 0;
            conica_scad_refine_info info;
            memset(&info, 0, sizeof info);
            conica_status st;
            conica_code rc = conica_scad_refine(&in, tol, cap, &out, &m, &info, &st);
            CAPTURE_I(level);
            CAPTURE_D(tol);
            CHECK((rc == CONICA_OK || rc == CONICA_ERR_LIMIT));
            if (rc == CONICA_OK) {
                ok++;
                CHECK_LE(info.dense_points, cap);
                CHECK_LE(m, info.dense_points);
            } else {
                CHECK(strstr(st.message, "dense points") != NULL);
            }
            free(out);
        }
    }
    CHECK_GT(ok, 0); /* some tolerance was reached within a cap */
    conica_curve_free(&in);
}

TEST_CASE("Clipper shim: fill rules resolve, input numbers survive, no exception escapes",
          "[scad][clip]")
{
    /* two squares of the same direction, one inside the other: nonzero
     * fills both (one outline), evenodd makes the inner a hole */
    const double outer[8] = {0.1, 0.1, 10.3, 0.1, 10.3, 10.3, 0.1, 10.3};
    const double inner[8] = {2.7, 2.7, 5.9, 2.7, 5.9, 5.9, 2.7, 5.9};
    conica__polys in, out;
    conica_status st;
    double scale = conica__clip_scale(0.01, 3e-4, 10.3);
    conica__polys_init(&in);
    conica__polys_init(&out);
    REQUIRE(scale > 0);
    REQUIRE(conica__polys_add(&in, outer, 4) == 0);
    REQUIRE(conica__polys_add(&in, inner, 4) == 0);
    REQUIRE(conica__clip_fill_region(&in, CONICA__CLIP_NONZERO, scale, 1, &out, &st) == CONICA_OK);
    CHECK_EQ(out.n, (size_t)1);
    REQUIRE(conica__clip_fill_region(&in, CONICA__CLIP_EVENODD, scale, 1, &out, &st) == CONICA_OK);
    REQUIRE(out.n == 2);
    {
        int pos = 0, neg = 0, exact = 1;
        for (size_t i = 0; i < out.n; i++) {
            double a = conica__polys_area2(&out, i);
            pos += a > 0;
            neg += a < 0;
        }
        CHECK_EQ(pos, 1); /* the outline counter-clockwise */
        CHECK_EQ(neg, 1); /* the hole clockwise */
        /* every vertex is an input vertex with its own doubles (0.1, not
         * 0.1 rounded to the grid) */
        for (size_t k = 0; k < out.npts; k++) {
            int found = 0;
            for (int j = 0; j < 4; j++)
                found |= (out.xy[2 * k] == outer[2 * j] && out.xy[2 * k + 1] == outer[2 * j + 1]) ||
                         (out.xy[2 * k] == inner[2 * j] && out.xy[2 * k + 1] == inner[2 * j + 1]);
            exact &= found;
        }
        CHECK(exact);
        CHECK(conica__polys_winding(&out, 4, 4) == 0);
        CHECK(conica__polys_winding(&out, 1, 1) != 0);
    }
    /* coordinates beyond the grid's range: a status, not an exception */
    {
        const double far[6] = {0, 0, 1e19, 0, 0, 1};
        conica__polys f;
        conica__polys_init(&f);
        REQUIRE(conica__polys_add(&f, far, 3) == 0);
        CHECK_EQ(conica__clip_scale(0.01, 0.01, 1e19), 0.0);
        CHECK_EQ(conica__clip_fill_region(&f, CONICA__CLIP_NONZERO, 1.0, 0, &out, &st),
                 CONICA_ERR_LIMIT);
        conica__polys_free(&f);
    }
    conica__polys_free(&in);
    conica__polys_free(&out);
}

/* SPDX-License-Identifier: MIT */
/* SVG documents: faithful round trip, conic reproduction through SVG (also
 * far from the origin), corners kept, flattening against dense evaluation,
 * hostile XML, fill-rule inheritance, viewport, selection, shapes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica_svg.h"
#include "conica_test.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static conica_svg_doc *load(const char *text)
{
    conica_svg_doc *doc = NULL;
    conica_status st;
    conica_code rc = conica_svg_doc_load(text, strlen(text), NULL, &doc, &st);
    INFO("load: %s", rc == CONICA_OK ? "ok" : st.message);
    REQUIRE(rc == CONICA_OK);
    return doc;
}

static char *save(const conica_svg_doc *doc)
{
    char *s = NULL;
    size_t n = 0;
    REQUIRE(conica_svg_doc_save(doc, &s, &n, NULL) == CONICA_OK);
    CHECK_EQ_U(n, strlen(s));
    return s;
}

/* Polylines of a document (settings given), as extract returns them. */
static void extract(const char *text, const conica_svg_settings *s, conica_svg_shapes *out)
{
    conica_svg_doc *doc = load(text);
    conica_status st;
    conica_code rc;
    conica_svg_shapes_init(out);
    rc = conica_svg_extract(doc, s, out, &st);
    INFO("extract: %s", rc == CONICA_OK ? "ok" : st.message);
    REQUIRE(rc == CONICA_OK);
    conica_svg_doc_free(doc);
}

/* Blank out the values of every d="..." and points="..." attribute. */
static char *strip_geometry(const char *s)
{
    char *o = malloc(strlen(s) + 1), *w = o;
    int in_tag = 0, in_quote = 0;
    while (*s) {
        /* libxml2 keeps no whitespace between attributes: compare tags with
         * each run of blanks there as one space */
        if (*s == '<' && !in_quote)
            in_tag = 1;
        else if (*s == '>' && !in_quote)
            in_tag = 0;
        else if (*s == '"' && in_tag)
            in_quote = !in_quote;
        if (in_tag && !in_quote && (*s == ' ' || *s == '\n' || *s == '\t')) {
            while (s[1] == ' ' || s[1] == '\n' || s[1] == '\t')
                s++;
            *w++ = ' ';
            s++;
            continue;
        }
        if (in_tag && !in_quote && (!strncmp(s, "d=\"", 3) || !strncmp(s, "points=\"", 8)) &&
            (s[-1] == ' ' || s[-1] == '\n')) {
            const char *q = strchr(s, '"');
            while (s <= q)
                *w++ = *s++;
            while (*s && *s != '"')
                s++;
            if (*s)
                *w++ = *s++; /* the closing quote */
            continue;
        }
        *w++ = *s++;
    }
    *w = '\0';
    return o;
}

static const char *roundtrip_doc =
    "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n"
    "<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" "
    "\"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd\">\n"
    "<!-- drawn by hand; keep this comment -->\n"
    "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\"\n"
    "     xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\"\n"
    "     width=\"120mm\" height=\"80mm\" viewBox=\"0 0 120 80\">\n"
    "  <title>round trip</title>\n"
    "  <defs><linearGradient id=\"g1\"><stop offset=\"0\"/></linearGradient></defs>\n"
    "  <g id=\"layer1\" inkscape:label=\"Layer 1\" transform=\"translate(1,2)\">\n"
    "    <path id=\"zig\" d=\"M 10.000,10 L 20,15 l 10,-5 H 50 v 10 h -40 z\" "
    "style=\"fill:url(#g1);stroke:#000\" data-x=\"keep\"/>\n"
    "    <polyline id=\"pl\" points=\"1,1 2,3 4,1 8,9\" fill=\"none\"/>\n"
    "    <polygon id=\"pg\" points=\"60 10, 100 10, 100 40\"/>\n"
    "    <foo:bar xmlns:foo=\"urn:x-foo\" a=\"1\">text &amp; more</foo:bar>\n"
    "    <rect id=\"untouched\" x=\"1\" y=\"2\" width=\"3\" height=\"4\"/>\n"
    "    <![CDATA[ raw <stuff> ]]>\n"
    "  </g>\n"
    "</svg>\n";

TEST_CASE("document round trip with 0 levels keeps everything but number formatting",
          "[svg][doc]")
{
    conica_svg_doc *doc = load(roundtrip_doc);
    conica_svg_settings s = conica_svg_defaults();
    conica_svg_stats stats;
    conica_svg_shapes before, after;
    char *out, *a, *b;
    s.levels = 0;
    s.precision = 17;
    REQUIRE(conica_svg_process(doc, &s, &stats, NULL) == CONICA_OK);
    CHECK_EQ_U(stats.elements, 3);
    CHECK_EQ_U(stats.subpaths, 3);
    out = save(doc);
    a = strip_geometry(roundtrip_doc);
    b = strip_geometry(out);
    CHECK_STR_EQ(b, a);
    /* the geometry is the same points */
    s.mode = CONICA_SVG_KEEP;
    extract(roundtrip_doc, &s, &before);
    extract(out, &s, &after);
    REQUIRE_EQ_U(after.nsubpaths, before.nsubpaths);
    {
        size_t i, j;
        for (i = 0; i < before.nsubpaths; i++) {
            REQUIRE_EQ_U(after.subpaths[i].n, before.subpaths[i].n);
            CHECK_EQ(after.subpaths[i].closed, before.subpaths[i].closed);
            for (j = 0; j < 2 * before.subpaths[i].n; j++)
                CHECK(after.subpaths[i].xy[j] == before.subpaths[i].xy[j]);
        }
    }
    CHECK(strstr(out, "d=\"M10 10L20 15 30 10 50 10 50 20 10 20Z\"") != NULL);
    conica_svg_shapes_free(&before);
    conica_svg_shapes_free(&after);
    free(a);
    free(b);
    free(out);
    conica_svg_doc_free(doc);
}

TEST_CASE("a document that owns its input buffer writes what a copying one writes",
          "[svg][doc]")
{
    /* conica_svg_doc_load_owned (svgsmooth's loader) keeps the caller's
     * buffer instead of a copy; the byte-true save splices into it, so the
     * output must be the same bytes as from conica_svg_doc_load. */
    size_t len = strlen(roundtrip_doc);
    char *buf = malloc(len);
    conica_svg_doc *owned = NULL, *copied = load(roundtrip_doc);
    conica_status st;
    conica_svg_settings s = conica_svg_defaults();
    s.levels = 3;
    REQUIRE(buf != NULL);
    memcpy(buf, roundtrip_doc, len); /* no terminating NUL: len is the size */
    REQUIRE_EQ(conica_svg_doc_load_owned(buf, len, NULL, &owned, &st), CONICA_OK);
    REQUIRE(conica_svg_process(owned, &s, NULL, NULL) == CONICA_OK);
    REQUIRE(conica_svg_process(copied, &s, NULL, NULL) == CONICA_OK);
    char *a = save(owned), *b = save(copied);
    CHECK_STR_EQ(a, b);
    CHECK(strstr(a, "<![CDATA[ raw <stuff> ]]>") != NULL);
    free(a);
    free(b);
    conica_svg_doc_free(owned); /* frees buf (ASan in make test-san) */
    conica_svg_doc_free(copied);

    /* on failure the buffer stays the caller's, untouched */
    static const char bad[] = "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0\"></svg>";
    buf = malloc(sizeof bad - 1);
    REQUIRE(buf != NULL);
    memcpy(buf, bad, sizeof bad - 1);
    owned = NULL;
    CHECK(conica_svg_doc_load_owned(buf, sizeof bad - 1, NULL, &owned, &st) != CONICA_OK);
    CHECK(owned == NULL);
    CHECK(memcmp(buf, bad, sizeof bad - 1) == 0);
    free(buf);
}

TEST_CASE("no XML declaration in, none out; UTF-8 text stays as it was", "[svg][doc]")
{
    const char *t = "<svg xmlns=\"http://www.w3.org/2000/svg\"><title>caf\xc3\xa9</title>"
                    "<path d=\"M0 0L1 1\"/></svg>\n";
    conica_svg_doc *doc = load(t);
    char *out = save(doc);
    CHECK_STR_EQ(out, t);
    free(out);
    conica_svg_doc_free(doc);
}

/* Largest |distance from centre - r| / r over all points of all subpaths. */
static double circle_error(const conica_svg_shapes *sh, double cx, double cy, double r)
{
    double worst = 0.0;
    size_t i, j;
    for (i = 0; i < sh->nsubpaths; i++)
        for (j = 0; j < sh->subpaths[i].n; j++) {
            double d = hypot(sh->subpaths[i].xy[2 * j] - cx, sh->subpaths[i].xy[2 * j + 1] - cy);
            if (fabs(d - r) / r > worst)
                worst = fabs(d - r) / r;
        }
    return worst;
}

static char *circle_doc(double cx, double cy, double r)
{
    char *t = malloc(1024);
    snprintf(t, 1024,
             "<svg xmlns=\"http://www.w3.org/2000/svg\"><path id=\"c\" d=\"M%.17g %.17g"
             "A%.17g %.17g 0 0 1 %.17g %.17g A%.17g %.17g 0 0 1 %.17g %.17g "
             "A%.17g %.17g 0 0 1 %.17g %.17g A%.17g %.17g 0 0 1 %.17g %.17g Z\"/></svg>",
             cx + r, cy, r, r, cx, cy + r, r, r, cx - r, cy, r, r, cx, cy - r, r, r, cx + r, cy);
    return t;
}

TEST_CASE("a circle written as four arcs comes out on the circle", "[svg][conic]")
{
    const double centres[2][2] = {{0.0, 0.0}, {5000.0, 3000.0}};
    int k;
    for (k = 0; k < 2; k++) {
        conica_svg_settings s = conica_svg_defaults();
        conica_svg_shapes sh;
        char *t = circle_doc(centres[k][0], centres[k][1], 37.5);
        double err;
        INFO("centre (%g, %g)", centres[k][0], centres[k][1]);
        s.levels = 5;
        extract(t, &s, &sh);
        REQUIRE_EQ_U(sh.nsubpaths, 1);
        /* the four arc ends with their exact normals: 4 x 2^5 */
        CHECK_EQ_U(sh.subpaths[0].n, 4 * 32);
        CHECK(sh.subpaths[0].closed);
        err = circle_error(&sh, centres[k][0], centres[k][1], 37.5);
        CAPTURE_D(err);
        CHECK_LE(err, 1e-9);
        conica_svg_shapes_free(&sh);
        /* and through the written path data at 17 digits */
        {
            conica_svg_doc *doc = load(t);
            char *out;
            s.precision = 17;
            REQUIRE(conica_svg_process(doc, &s, NULL, NULL) == CONICA_OK);
            out = save(doc);
            s.mode = CONICA_SVG_KEEP;
            extract(out, &s, &sh);
            CHECK_EQ_U(sh.subpaths[0].n, 128);
            CHECK_LE(circle_error(&sh, centres[k][0], centres[k][1], 37.5), 1e-9);
            conica_svg_shapes_free(&sh);
            free(out);
            conica_svg_doc_free(doc);
        }
        free(t);
    }
}

TEST_CASE("an ellipse as cubic Beziers with exact tangents comes out on the ellipse",
          "[svg][conic]")
{
    const double centres[2][2] = {{0.0, 0.0}, {5000.0, 3000.0}};
    int k;
    for (k = 0; k < 2; k++) {
        const double a = 60.0, b = 25.0, cx = centres[k][0], cy = centres[k][1];
        const int n = 6;
        char t[4096];
        size_t len;
        int i;
        double worst = 0.0, kk = 4.0 / 3.0 * tan(2.0 * M_PI / n / 4.0);
        conica_svg_settings s = conica_svg_defaults();
        conica_svg_shapes sh;
        size_t j;
        len = (size_t)snprintf(t, sizeof t,
                               "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M%.17g %.17g",
                               cx + a, cy);
        for (i = 0; i < n; i++) {
            double t0 = 2.0 * M_PI * i / n, t1 = 2.0 * M_PI * (i + 1) / n;
            /* control points along the exact tangents (a cubic is not an
             * ellipse, but its end points and end tangents are exact samples) */
            double x0 = cx + a * cos(t0), y0 = cy + b * sin(t0);
            double x1 = cx + a * cos(t1), y1 = cy + b * sin(t1);
            len += (size_t)snprintf(t + len, sizeof t - len, "C%.17g %.17g %.17g %.17g %.17g %.17g",
                                    x0 - kk * a * sin(t0), y0 + kk * b * cos(t0),
                                    x1 + kk * a * sin(t1), y1 - kk * b * cos(t1), x1, y1);
        }
        snprintf(t + len, sizeof t - len, "Z\"/></svg>");
        s.levels = 5;
        extract(t, &s, &sh);
        INFO("centre (%g, %g)", cx, cy);
        REQUIRE_EQ_U(sh.nsubpaths, 1);
        CHECK_EQ_U(sh.subpaths[0].n, (size_t)n * 32);
        for (j = 0; j < sh.subpaths[0].n; j++) {
            double x = (sh.subpaths[0].xy[2 * j] - cx) / a, y = (sh.subpaths[0].xy[2 * j + 1] - cy) / b;
            /* radial distance on the unit circle, scaled to the ellipse size */
            double e = fabs(hypot(x, y) - 1.0) * b / a;
            if (e > worst)
                worst = e;
        }
        INFO("centre (%g, %g)", cx, cy);
        CAPTURE_D(worst);
        CHECK_LE(worst, 1e-9);
        conica_svg_shapes_free(&sh);
    }
}

/* Is (x,y) one of the output points? */
static int has_point(const conica_svg_subpath *sp, double x, double y)
{
    size_t j;
    for (j = 0; j < sp->n; j++)
        if (sp->xy[2 * j] == x && sp->xy[2 * j + 1] == y)
            return 1;
    return 0;
}

/* Turn angle (degrees) of the output polyline at the point equal to (x,y). */
static double turn_at(const conica_svg_subpath *sp, double x, double y)
{
    size_t j, n = sp->n;
    for (j = 0; j < n; j++)
        if (sp->xy[2 * j] == x && sp->xy[2 * j + 1] == y) {
            size_t a = (j + n - 1) % n, b = (j + 1) % n;
            double ux = x - sp->xy[2 * a], uy = y - sp->xy[2 * a + 1];
            double vx = sp->xy[2 * b] - x, vy = sp->xy[2 * b + 1] - y;
            return fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy)) * 180.0 / M_PI;
        }
    return -1.0;
}

TEST_CASE("corners stay: rectangle, star, letter, traced outline", "[svg][corners]")
{
    conica_svg_settings s = conica_svg_defaults();
    conica_svg_shapes sh;
    SECTION("a rectangle stays a rectangle")
    {
        extract("<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M10 10H110V60H10Z\"/>"
                "<polygon points=\"0,0 5,0 5,5 0,5\"/></svg>",
                &s, &sh);
        REQUIRE_EQ_U(sh.nsubpaths, 2);
        REQUIRE_EQ_U(sh.subpaths[0].n, 4);
        CHECK(sh.subpaths[0].xy[0] == 10 && sh.subpaths[0].xy[1] == 10);
        CHECK(has_point(&sh.subpaths[0], 110, 10) && has_point(&sh.subpaths[0], 110, 60) &&
              has_point(&sh.subpaths[0], 10, 60));
        CHECK_EQ_U(sh.subpaths[1].n, 4);
        conica_svg_shapes_free(&sh);
    }
    SECTION("a star keeps its ten vertices and straight edges")
    {
        char t[1024];
        size_t len = 0;
        int i;
        len += (size_t)snprintf(t, sizeof t, "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"");
        for (i = 0; i < 10; i++) {
            double r = i % 2 ? 20.0 : 50.0, a = M_PI / 2 + i * M_PI / 5;
            len += (size_t)snprintf(t + len, sizeof t - len, "%c%.17g %.17g", i ? 'L' : 'M',
                                    100 + r * cos(a), 100 + r * sin(a));
        }
        snprintf(t + len, sizeof t - len, "Z\"/></svg>");
        extract(t, &s, &sh);
        REQUIRE_EQ_U(sh.nsubpaths, 1);
        CHECK_EQ_U(sh.subpaths[0].n, 10);
        conica_svg_shapes_free(&sh);
    }
    SECTION("a letter D: sharp stem corners, straight stem, round bowl")
    {
        size_t j, on_stem = 0;
        const conica_svg_subpath *sp;
        extract("<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M10 10H40C70 10 80 30 80 50"
                "C80 70 70 90 40 90H10Z\"/></svg>",
                &s, &sh);
        REQUIRE_EQ_U(sh.nsubpaths, 1);
        sp = &sh.subpaths[0];
        CHECK(has_point(sp, 10, 10) && has_point(sp, 40, 10) && has_point(sp, 80, 50) &&
              has_point(sp, 40, 90) && has_point(sp, 10, 90));
        CHECK_NEAR(turn_at(sp, 10, 10), 90.0, 1e-9);
        CHECK_NEAR(turn_at(sp, 10, 90), 90.0, 1e-9);
        /* the bowl is refined (2 cubics, 4 levels) and stays right of x = 40 */
        CHECK_GE(sp->n, 5 + 2 * 15);
        for (j = 0; j < sp->n; j++) {
            if (sp->xy[2 * j] == 10.0)
                on_stem++;
            CHECK(sp->xy[2 * j] >= 10.0);
            CHECK(sp->xy[2 * j] <= 80.0 + 1e-9);
        }
        CHECK_EQ_U(on_stem, 2); /* the stem is one straight edge */
        conica_svg_shapes_free(&sh);
    }
    SECTION("a traced outline: smooth where it was smooth, the corner kept")
    {
        /* a noisy-free polygon sampling of a half disc: arc points + a
         * diameter closing it; corners at both ends of the diameter */
        char t[8192];
        size_t len = 0;
        int i;
        const conica_svg_subpath *sp;
        len += (size_t)snprintf(t, sizeof t, "<svg xmlns=\"http://www.w3.org/2000/svg\"><polygon points=\"");
        for (i = 0; i <= 24; i++) {
            double a = M_PI * i / 24;
            len += (size_t)snprintf(t + len, sizeof t - len, "%.17g,%.17g ", 50 + 40 * cos(a),
                                    50 - 40 * sin(a));
        }
        snprintf(t + len, sizeof t - len, "\"/></svg>");
        s.levels = 3;
        extract(t, &s, &sh);
        sp = &sh.subpaths[0];
        CHECK(sp->closed);
        CHECK_NEAR(turn_at(sp, 90, 50), 90.0, 1.0);
        CHECK_NEAR(turn_at(sp, 50 + 40 * cos(M_PI), 50 - 40 * sin(M_PI)), 90.0, 1.0);
        /* smooth part refined: 24 arc edges * 8 + the diameter edge kept */
        CHECK_EQ_U(sp->n, 24 * 8 + 1);
        /* and it lands on the half circle: the estimated normals of a
         * polygon sampled from a circle are exact (circle through three
         * vertices), so conic reproduction applies */
        {
            size_t j;
            double worst = 0.0;
            for (j = 0; j < sp->n; j++) {
                double y = sp->xy[2 * j + 1], d = hypot(sp->xy[2 * j] - 50, y - 50);
                if (y < 50 - 1e-9 && fabs(d - 40) > worst)
                    worst = fabs(d - 40);
            }
            CAPTURE_D(worst);
            CHECK_LT(worst, 1e-9 * 40);
        }
        conica_svg_shapes_free(&sh);
    }
    SECTION("a rounded rectangle: straight sides, corners on their circles")
    {
        const double c[4][2] = {{25, 25}, {95, 25}, {95, 55}, {25, 55}};
        size_t j, on_sides = 0;
        double worst = 0.0;
        const conica_svg_subpath *sp;
        s.convert_shapes = 1;
        s.levels = 3;
        extract("<svg xmlns=\"http://www.w3.org/2000/svg\"><rect x=\"10\" y=\"10\" width=\"100\" "
                "height=\"60\" rx=\"15\"/></svg>",
                &s, &sh);
        REQUIRE_EQ_U(sh.nsubpaths, 1);
        sp = &sh.subpaths[0];
        /* each quarter arc: its middle added (3 pairs fix the circle), 2 * 8 edges */
        CHECK_EQ_U(sp->n, 4 * 16 + 4);
        for (j = 0; j < sp->n; j++) {
            double x = sp->xy[2 * j], y = sp->xy[2 * j + 1];
            int k, in_corner = 0;
            for (k = 0; k < 4; k++)
                if ((x < 25 || x > 95) && (y < 25 || y > 55) && fabs(x - c[k][0]) <= 15 &&
                    fabs(y - c[k][1]) <= 15) {
                    double e = fabs(hypot(x - c[k][0], y - c[k][1]) - 15);
                    in_corner = 1;
                    if (e > worst)
                        worst = e;
                }
            if (!in_corner)
                on_sides++;
        }
        CAPTURE_D(worst);
        CHECK_LE(worst, 1e-9 * 15);
        CHECK_EQ_U(on_sides, 8); /* only the 8 tangent points lie on the sides */
        conica_svg_shapes_free(&sh);
    }
    SECTION("a wave with collinear on-curve points keeps its shape")
    {
        /* C..S.. and a single S-shaped cubic: the vertices are collinear,
         * the curve is not; the output must follow the curve closely */
        const char *d[2] = {"M0 0C10 10 20 10 30 0S50 -10 60 0", "M0 0C10 20 20 -20 30 0"};
        int k;
        for (k = 0; k < 2; k++) {
            char t[256];
            conica_svg_path p;
            size_t j, i;
            double worst = 0.0, ymax = 0.0;
            snprintf(t, sizeof t, "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"%s\"/></svg>", d[k]);
            extract(t, &s, &sh);
            conica_svg_path_init(&p);
            REQUIRE(conica_svg_path_parse(d[k], strlen(d[k]), 0, &p, NULL) == CONICA_OK);
            for (j = 0; j < sh.subpaths[0].n; j++) {
                double x = sh.subpaths[0].xy[2 * j], y = sh.subpaths[0].xy[2 * j + 1], best = INFINITY;
                for (i = 1; i < p.n; i++) {
                    const conica_svg_seg *g = &p.seg[i];
                    int m;
                    for (m = 0; m <= 400; m++) {
                        double u = m / 400.0, v = 1 - u;
                        double cx = v * v * v * g->x0 + 3 * v * v * u * g->c[0] + 3 * v * u * u * g->c[2] + u * u * u * g->x1;
                        double cy = v * v * v * g->y0 + 3 * v * v * u * g->c[1] + 3 * v * u * u * g->c[3] + u * u * u * g->y1;
                        if (hypot(x - cx, y - cy) < best)
                            best = hypot(x - cx, y - cy);
                    }
                }
                if (best > worst)
                    worst = best;
                if (fabs(y) > ymax)
                    ymax = fabs(y);
            }
            INFO("%s", d[k]);
            CAPTURE_D(worst);
            CHECK_GT(ymax, 5.0);
            CHECK_LT(worst, 0.01 * 30);
            conica_svg_path_free(&p);
            conica_svg_shapes_free(&sh);
        }
    }
    SECTION("corner angle 180 disables corners")
    {
        s.corner_angle_deg = 180.0;
        s.levels = 2;
        /* drawn straight segments stay straight whatever the angle ... */
        extract("<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0H100V100H0Z\"/></svg>", &s,
                &sh);
        CHECK_EQ_U(sh.subpaths[0].n, 4);
        conica_svg_shapes_free(&sh);
        /* ... taken as samples (traced input) they are smoothed through */
        s.lines_as_samples = 1;
        extract("<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0H100V100H0Z\"/></svg>", &s,
                &sh);
        CHECK_EQ_U(sh.subpaths[0].n, 16);
        conica_svg_shapes_free(&sh);
    }
}

/* Distance from p to segment ab. */
static double seg_dist(double px, double py, const double *a, const double *b)
{
    double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((px - a[0]) * dx + (py - a[1]) * dy) / l2 : 0.0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(px - a[0] - t * dx, py - a[1] - t * dy);
}

TEST_CASE("flattening stays within the tolerance of densely evaluated curves",
          "[svg][flatten]")
{
    const char *d = "M10 80C40 10 65 10 95 80S150 150 180 80Q200 40 220 80"
                    "A30 20 30 1 1 260 120L300 120L300 200";
    char t[1024];
    double tols[2] = {0.5, 0.01};
    int k;
    snprintf(t, sizeof t, "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"%s\"/></svg>", d);
    for (k = 0; k < 2; k++) {
        conica_svg_settings s = conica_svg_defaults();
        conica_svg_shapes sh;
        conica_svg_path p;
        const conica_svg_subpath *sp;
        size_t i, j, seg = 0, nseg;
        double worst = 0.0;
        s.mode = CONICA_SVG_FLATTEN;
        s.tolerance = tols[k];
        extract(t, &s, &sh);
        REQUIRE_EQ_U(sh.nsubpaths, 1);
        sp = &sh.subpaths[0];
        /* the straight tail stays two single segments */
        REQUIRE_GE(sp->n, 3);
        CHECK(sp->xy[2 * (sp->n - 1)] == 300 && sp->xy[2 * (sp->n - 1) + 1] == 200);
        CHECK(sp->xy[2 * (sp->n - 2)] == 300 && sp->xy[2 * (sp->n - 2) + 1] == 120);
        CHECK(sp->xy[2 * (sp->n - 3)] == 260 && sp->xy[2 * (sp->n - 3) + 1] == 120);
        /* dense samples of every curve are within tol of the polyline */
        conica_svg_path_init(&p);
        REQUIRE(conica_svg_path_parse(d, strlen(d), 0, &p, NULL) == CONICA_OK);
        nseg = sp->n - 1;
        (void)seg;
        for (i = 1; i < p.n; i++) {
            const conica_svg_seg *g = &p.seg[i];
            for (j = 0; j <= 2000; j++) {
                double u = (double)j / 2000.0, x, y, best = INFINITY;
                size_t m;
                if (g->type == CONICA_SVG_SEG_ARC) {
                    double th = g->theta1 + u * g->dtheta;
                    double ex = g->rx * cos(th), ey = g->ry * sin(th);
                    x = g->cx + cos(g->phi) * ex - sin(g->phi) * ey;
                    y = g->cy + sin(g->phi) * ex + cos(g->phi) * ey;
                } else if (g->type == CONICA_SVG_SEG_CUBIC) {
                    double v = 1 - u;
                    x = v * v * v * g->x0 + 3 * v * v * u * g->c[0] + 3 * v * u * u * g->c[2] + u * u * u * g->x1;
                    y = v * v * v * g->y0 + 3 * v * v * u * g->c[1] + 3 * v * u * u * g->c[3] + u * u * u * g->y1;
                } else if (g->type == CONICA_SVG_SEG_QUAD) {
                    double v = 1 - u;
                    x = v * v * g->x0 + 2 * v * u * g->c[0] + u * u * g->x1;
                    y = v * v * g->y0 + 2 * v * u * g->c[1] + u * u * g->y1;
                } else {
                    continue;
                }
                for (m = 0; m < nseg; m++) {
                    double dd = seg_dist(x, y, sp->xy + 2 * m, sp->xy + 2 * m + 2);
                    if (dd < best)
                        best = dd;
                }
                if (best > worst)
                    worst = best;
            }
        }
        INFO("tolerance %g: %zu points", tols[k], sp->n);
        CAPTURE_D(worst);
        CHECK_LE(worst, tols[k] * (1 + 1e-9));
        /* and not absurdly many points: a smaller tolerance needs more */
        if (k == 1)
            CHECK_GT(sp->n, 40);
        conica_svg_path_free(&p);
        conica_svg_shapes_free(&sh);
    }
}

static conica_code try_load(const char *text, const conica_svg_limits *lim, conica_status *st)
{
    conica_svg_doc *doc = NULL;
    conica_code rc = conica_svg_doc_load(text, strlen(text), lim, &doc, st);
    conica_svg_doc_free(doc);
    return rc;
}

TEST_CASE("hostile XML is refused", "[svg][doc][security]")
{
    conica_status st;
    SECTION("billion laughs")
    {
        const char *t = "<?xml version=\"1.0\"?>\n<!DOCTYPE svg [\n <!ENTITY lol \"lol\">\n"
                        " <!ENTITY lol2 \"&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;\">\n"
                        " <!ENTITY lol3 \"&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;\">\n"
                        "]>\n<svg xmlns=\"http://www.w3.org/2000/svg\"><title>&lol3;</title></svg>";
        CHECK(try_load(t, NULL, &st) == CONICA_ERR_UNSUPPORTED);
        CHECK_EQ_U(st.line, 4);
        CHECK(strstr(st.message, "lol2") != NULL);
    }
    SECTION("external entity (XXE)")
    {
        const char *t = "<?xml version=\"1.0\"?>\n<!DOCTYPE svg [<!ENTITY x SYSTEM "
                        "\"file:///etc/passwd\">]>\n<svg xmlns=\"http://www.w3.org/2000/svg\">"
                        "<text>&x;</text></svg>";
        CHECK(try_load(t, NULL, &st) == CONICA_ERR_UNSUPPORTED);
        CHECK(strstr(st.message, "XXE") != NULL);
    }
    SECTION("parameter entity")
    {
        const char *t = "<!DOCTYPE svg [<!ENTITY % p SYSTEM \"http://example.com/x.dtd\"> %p;]>"
                        "<svg xmlns=\"http://www.w3.org/2000/svg\"/>";
        CHECK(try_load(t, NULL, &st) == CONICA_ERR_UNSUPPORTED);
    }
    SECTION("harmless plain-text entities (Illustrator) load and survive")
    {
        const char *t = "<?xml version=\"1.0\"?>\n<!DOCTYPE svg [<!ENTITY ns_svg "
                        "\"http://www.w3.org/2000/svg\">]>\n<svg xmlns=\"&ns_svg;\">"
                        "<path d=\"M0 0L10 0L10 10Z\"/></svg>\n";
        conica_svg_doc *doc = load(t);
        conica_svg_settings s = conica_svg_defaults();
        char *out;
        REQUIRE(conica_svg_process(doc, &s, NULL, NULL) == CONICA_OK);
        out = save(doc);
        CHECK(strstr(out, "<!ENTITY ns_svg") != NULL);
        CHECK(strstr(out, "xmlns=\"&ns_svg;\"") != NULL);
        free(out);
        conica_svg_doc_free(doc);
    }
    SECTION("entity references cannot amplify through attribute values")
    {
        /* 200 000 references to a 1000-byte entity: 200 MB if expanded */
        size_t nref = 200000, i, n = 0;
        char *t = malloc(nref * 4 + 2000);
        conica_svg_doc *doc;
        conica_svg_settings s = conica_svg_defaults();
        conica_svg_stats stats;
        n += (size_t)sprintf(t, "<!DOCTYPE svg [<!ENTITY e \"");
        for (i = 0; i < 1000; i++)
            t[n++] = 'x';
        n += (size_t)sprintf(t + n, "\"><!ENTITY m \"L1 1\">]>\n<svg xmlns=\"http://www.w3.org/2000/svg\">"
                                    "<path id=\"p\" style=\"");
        for (i = 0; i < nref; i++)
            n += (size_t)sprintf(t + n, "&e;");
        sprintf(t + n, "\" d=\"M0 0&m;L2 0&m;\"/></svg>");
        doc = load(t);
        REQUIRE(conica_svg_process(doc, &s, &stats, &st) == CONICA_OK);
        CHECK_EQ_U(stats.in_vertices, 4); /* M0 0 L1 1 L2 0 L1 1: the references in d were read */
        conica_svg_doc_free(doc);
        /* the same references in d: refused by the cap, not expanded */
        strcpy(strstr(t, "style="), "d=\"M0 0");
        n = strlen(t);
        for (i = 0; i < nref; i++)
            n += (size_t)sprintf(t + n, "&e;");
        sprintf(t + n, "\"/></svg>");
        doc = load(t);
        CHECK(conica_svg_process(doc, &s, &stats, &st) == CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "--max-path-bytes") != NULL);
        conica_svg_doc_free(doc);
        free(t);
    }
    SECTION("deep nesting")
    {
        size_t depth = 300, i, n = 0;
        char *t = malloc(depth * 8 + 200);
        conica_svg_limits lim = conica_svg_limits_defaults();
        n += (size_t)sprintf(t + n, "<svg xmlns=\"http://www.w3.org/2000/svg\">");
        for (i = 0; i < depth; i++)
            n += (size_t)sprintf(t + n, "<g>");
        for (i = 0; i < depth; i++)
            n += (size_t)sprintf(t + n, "</g>");
        sprintf(t + n, "</svg>");
        CHECK(try_load(t, NULL, &st) == CONICA_ERR_LIMIT); /* our count answers first */
        CHECK(strstr(st.message, "nested deeper than 256 (--max-depth)") != NULL);
        /* a cap above libxml2's 256 is honoured (XML_PARSE_HUGE), ours still holds */
        lim.max_depth = 1000;
        CHECK(try_load(t, &lim, &st) == CONICA_OK);
        lim.max_depth = 301; /* svg + 300 g: depth 301 */
        CHECK(try_load(t, &lim, &st) == CONICA_OK);
        lim.max_depth = 300;
        CHECK(try_load(t, &lim, &st) == CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "nested deeper than 300 (--max-depth)") != NULL);
        free(t);
    }
    SECTION("empty and non-XML documents say so")
    {
        CHECK(try_load("", NULL, &st) == CONICA_ERR_PARSE);
        CHECK(strstr(st.message, "empty document: no <svg> element") != NULL);
        CHECK(try_load(" \n\t\n", NULL, &st) == CONICA_ERR_PARSE);
        CHECK(strstr(st.message, "empty document: no <svg> element") != NULL);
        CHECK(try_load("<?xml version=\"1.0\"?>\n<!-- nothing -->\n", NULL, &st) ==
              CONICA_ERR_PARSE);
        CHECK(strstr(st.message, "no <svg> element") != NULL);
        CHECK(try_load("hello world\n", NULL, &st) == CONICA_ERR_PARSE);
        CHECK(strstr(st.message, "not XML") != NULL);
    }
    SECTION("depth and element caps are ours to set")
    {
        conica_svg_limits lim = conica_svg_limits_defaults();
        const char *t = "<svg xmlns=\"http://www.w3.org/2000/svg\"><g><g><g><path d=\"M0 0\"/>"
                        "</g></g></g><path/><path/></svg>";
        lim.max_depth = 4;
        CHECK(try_load(t, &lim, &st) == CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "--max-depth") != NULL);
        lim.max_depth = 5;
        CHECK(try_load(t, &lim, &st) == CONICA_OK);
        lim.max_elements = 6;
        CHECK(try_load(t, &lim, &st) == CONICA_ERR_LIMIT);
        lim.max_elements = 7;
        CHECK(try_load(t, &lim, &st) == CONICA_OK);
        lim.max_bytes = 20;
        CHECK(try_load(t, &lim, &st) == CONICA_ERR_LIMIT);
    }
    SECTION("huge attribute")
    {
        size_t big = (size_t)12 << 20, i;
        char *t = malloc(big + 200);
        conica_svg_limits lim = conica_svg_limits_defaults();
        strcpy(t, "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0");
        i = strlen(t);
        while (i < big) {
            memcpy(t + i, "L1 1", 4);
            i += 4;
        }
        strcpy(t + i, "\"/></svg>");
        lim.max_bytes = big + 1000;
        /* past libxml2's own 10 MB cap on one attribute value (the load
         * asks for XML_PARSE_HUGE): our caps decide, the path data one
         * (32 MiB by default) and the document size */
        CHECK(try_load(t, &lim, &st) == CONICA_OK);
        lim.max_bytes = big;
        CHECK(try_load(t, &lim, &st) == CONICA_ERR_LIMIT);
        free(t);
    }
    SECTION("a text node over libxml2's own 10 MB cap loads whole (no truncated tree)")
    {
        /* libxml2 stopped at a text node over 10 MB with wellFormed still
         * set; the load returned the tree up to there and a save lost the
         * rest of the document (issue 17). Under XML_PARSE_HUGE the node
         * is read, and the document size cap bounds it. */
        size_t big = (size_t)10000100, i;
        const char *head = "<svg xmlns=\"http://www.w3.org/2000/svg\"><text>";
        const char *tail = "</text><path id=\"after\" d=\"M0 0L1 0L1 1Z\"/></svg>";
        char *t = malloc(big + 200);
        conica_svg_limits lim = conica_svg_limits_defaults();
        strcpy(t, head);
        i = strlen(t);
        memset(t + i, 'a', big);
        strcpy(t + i + big, tail);
        lim.max_bytes = big + 1000;
        conica_svg_doc *doc = NULL;
        REQUIRE(conica_svg_doc_load(t, strlen(t), &lim, &doc, &st) == CONICA_OK);
        char *out = NULL;
        size_t olen = 0;
        REQUIRE(conica_svg_doc_save(doc, &out, &olen, NULL) == CONICA_OK);
        CHECK_EQ_U(olen, strlen(t));
        CHECK(strstr(out, "<path id=\"after\"") != NULL);
        conica_svg_buffer_free(out);
        conica_svg_doc_free(doc);
        free(t);
    }
    SECTION("an error libxml2 does not count as fatal still fails the load")
    {
        CHECK(try_load("<svg xmlns=\"http://www.w3.org/2000/svg\">\n<path xlink:href=\"#a\" "
                       "d=\"M0 0L1 0L1 1Z\"/></svg>",
                       NULL, &st) == CONICA_ERR_PARSE);
        CHECK(strstr(st.message, "XML: namespace error (libxml2: Namespace prefix xlink") != NULL);
        CHECK_EQ_U(st.line, 2);
    }
    SECTION("attributes and namespace declarations are counted before libxml2 parses")
    {
        conica_svg_limits lim = conica_svg_limits_defaults();
        char t[4096];
        size_t i, k;
        /* 5 attributes; '>' and '/' inside values and a comment, CDATA
         * section, processing instruction and DOCTYPE with '>' and quotes
         * inside are not start tags */
        const char *doc = "<?xml version=\"1.0\"?>\n<!DOCTYPE svg [<!ENTITY e \"a>b\"> <!-- x=\"1\" > -->]>"
                          "\n<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:a=\"urn:a\">"
                          "<!-- <path a=\"1\" b=\"2\" c=\"3\" d=\"4\" e=\"5\" f=\"6\"/> -->"
                          "<![CDATA[<g a=\"1\" b=\"2\" c=\"3\" d=\"4\" e=\"5\" f=\"6\">]]><?pi a=\"1\" b=\"2\" c=\"3\" d=\"4\" e=\"5\" f=\"6\"?>"
                          "\n<path id='p' d=\"M0 0L1 0L1 1Z\" class=\"a>b/c\" a:x = \"1\" style=\"\"/>"
                          "</svg>";
        lim.max_attributes = 5;
        lim.max_namespaces = 2;
        CHECK(try_load(doc, &lim, &st) == CONICA_OK);
        lim.max_attributes = 4;
        CHECK(try_load(doc, &lim, &st) == CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "element <path> has more than 4 attributes (--max-attributes)") !=
              NULL);
        CHECK_EQ_U(st.line, 4);
        lim.max_attributes = 5;
        lim.max_namespaces = 1;
        CHECK(try_load(doc, &lim, &st) == CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "element <svg> has more than 1 namespace declarations in scope "
                                 "(--max-namespaces)") != NULL);
        CHECK_EQ_U(st.line, 3);
        /* in scope: an ancestor's declarations count, a closed sibling's
         * do not (63 on the root: each <g> with one more is at 64, a <g>
         * inside one of them with another is at 65) */
        lim = conica_svg_limits_defaults();
        k = (size_t)snprintf(t, sizeof t, "<svg xmlns=\"http://www.w3.org/2000/svg\"");
        for (i = 1; i < 63; i++)
            k += (size_t)snprintf(t + k, sizeof t - k, " xmlns:n%zu=\"u\"", i);
        snprintf(t + k, sizeof t - k, "><g xmlns:b=\"u\"/><g xmlns:c=\"u\"></g><g><g "
                                      "xmlns:d=\"u\"><g xmlns:e=\"u\"/></g></g></svg>");
        CHECK(try_load(t, &lim, &st) == CONICA_ERR_LIMIT); /* 63 + d + e = 65 at <g xmlns:e> */
        CHECK(strstr(st.message, "element <g> has more than 64 namespace declarations") != NULL);
        snprintf(t + k, sizeof t - k, "><g xmlns:b=\"u\"/><g xmlns:c=\"u\"></g><g><g "
                                      "xmlns:d=\"u\"></g><g xmlns:e=\"u\"/></g></svg>");
        CHECK(try_load(t, &lim, &st) == CONICA_OK);
        /* the scan cannot be thrown off by a lone quote in a DTD
         * processing instruction or a malformed tag before the flood */
        k = (size_t)snprintf(t, sizeof t, "<!DOCTYPE svg [<?pi don't ?>]><svg xmlns=\"http://"
                                          "www.w3.org/2000/svg\"><g x><path");
        for (i = 0; i < 300; i++)
            k += (size_t)snprintf(t + k, sizeof t - k, " a%zu=''", i);
        snprintf(t + k, sizeof t - k, "/></g></svg>");
        REQUIRE(k < sizeof t - 16);
        CHECK(try_load(t, NULL, &st) != CONICA_OK);
        CHECK(strstr(st.message, "more than 256 attributes") != NULL);
        /* the defaults: 256 attributes and 64 declarations */
        k = (size_t)snprintf(t, sizeof t, "<svg xmlns=\"http://www.w3.org/2000/svg\"><path");
        for (i = 0; i < 257; i++)
            k += (size_t)snprintf(t + k, sizeof t - k, " a%zu=''", i);
        snprintf(t + k, sizeof t - k, "/></svg>");
        REQUIRE(k < sizeof t - 16);
        CHECK(try_load(t, NULL, &st) == CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "more than 256 attributes") != NULL);
    }
    SECTION("a path data cap with a clear message")
    {
        const char *t = "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<path id=\"p\" "
                        "d=\"M0 0L1 1L2 2L3 3L4 4L5 5\"/></svg>";
        conica_svg_doc *doc = load(t);
        conica_svg_settings s = conica_svg_defaults();
        s.limits.max_path_bytes = 10;
        CHECK(conica_svg_process(doc, &s, NULL, &st) == CONICA_ERR_LIMIT);
        CHECK_EQ_U(st.line, 2);
        CHECK(strstr(st.message, "path 'p'") != NULL);
        s = conica_svg_defaults();
        s.limits.max_points = 3;
        CHECK(conica_svg_process(doc, &s, NULL, &st) == CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "--max-points") != NULL);
        conica_svg_doc_free(doc);
    }
    SECTION("malformed XML names its line")
    {
        CHECK(try_load("<svg xmlns=\"http://www.w3.org/2000/svg\">\n<path d=\"M0 0\">\n</svg>",
                       NULL, &st) == CONICA_ERR_PARSE);
        CHECK_EQ_U(st.line, 3);
        CHECK(try_load("<html/>", NULL, &st) == CONICA_ERR_PARSE);
    }
}

TEST_CASE("fill rule, transforms, viewport, selection and shapes", "[svg][doc]")
{
    const char *t =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"2in\" "
        "viewBox=\"0 0 200 96\">\n"
        "<g fill-rule=\"evenodd\" transform=\"scale(2)\">\n"
        "  <path id=\"a\" d=\"M0 0L10 0L10 10Z M2 2L4 2L4 4Z\"/>\n"
        "  <path id=\"b\" style=\"stroke:red; fill-rule : nonzero\" d=\"M0 0L1 0L1 1Z\"/>\n"
        "</g>\n"
        "<path id=\"c\" d=\"M0 0L1 0L1 1\"/>\n"
        "<circle id=\"o\" cx=\"5000\" cy=\"3000\" r=\"20\" fill=\"blue\"/>\n"
        "<rect id=\"r\" x=\"0\" y=\"0\" width=\"10\" height=\"10\" rx=\"2\"/>\n"
        "<line id=\"l\" x1=\"0\" y1=\"0\" x2=\"5\" y2=\"5\"/>\n"
        "<ellipse id=\"e\" cx=\"1\" cy=\"1\" rx=\"4%\" ry=\"1\"/>\n"
        "</svg>\n";
    conica_svg_settings s = conica_svg_defaults();
    conica_svg_shapes sh;
    SECTION("elements")
    {
        s.mode = CONICA_SVG_KEEP;
        extract(t, &s, &sh);
        REQUIRE_EQ_U(sh.nelements, 3);
        CHECK_STR_EQ(sh.elements[0].id, "a");
        CHECK(sh.elements[0].fill_rule == CONICA_SVG_EVENODD);
        CHECK(sh.elements[0].has_transform);
        CHECK_EQ_U(sh.elements[0].nsubpaths, 2);
        CHECK_EQ_U(sh.elements[0].line, 3);
        CHECK(sh.elements[1].fill_rule == CONICA_SVG_NONZERO);
        CHECK_FALSE(sh.elements[2].has_transform);
        CHECK_EQ_U(sh.nsubpaths, 4);
        CHECK(sh.subpaths[0].closed && sh.subpaths[1].closed);
        CHECK_FALSE(sh.subpaths[3].closed);
        CHECK_EQ_U(sh.subpaths[1].element, 0);
        CHECK_EQ_U(sh.subpaths[3].element, 2);
        CHECK(sh.viewport.has_viewbox);
        CHECK_NEAR(sh.viewport.width_mm, 100.0, 1e-12);
        CHECK_NEAR(sh.viewport.height_mm, 50.8, 1e-12);
        CHECK_NEAR(sh.viewport.mm_per_unit_x, 0.5, 1e-12);
        CHECK_NEAR(sh.viewport.mm_per_unit_y, 50.8 / 96.0, 1e-12);
        CHECK_STR_EQ(sh.viewport.height_unit, "in");
        conica_svg_shapes_free(&sh);
    }
    SECTION("selection by id")
    {
        const char *ids[2] = {"c", "b"};
        s.select = ids;
        s.nselect = 2;
        extract(t, &s, &sh);
        REQUIRE_EQ_U(sh.nelements, 2);
        CHECK_STR_EQ(sh.elements[0].id, "b");
        CHECK_STR_EQ(sh.elements[1].id, "c");
        conica_svg_shapes_free(&sh);
    }
    SECTION("selecting a group selects what is inside")
    {
        const char *ids[1] = {"grp"};
        const char *u = "<svg xmlns=\"http://www.w3.org/2000/svg\"><g id=\"grp\"><g>"
                        "<path id=\"in1\" d=\"M0 0L1 1\"/></g><path d=\"M0 0L2 2\"/></g>"
                        "<path id=\"out\" d=\"M0 0L3 3\"/></svg>";
        s.select = ids;
        s.nselect = 1;
        extract(u, &s, &sh);
        REQUIRE_EQ_U(sh.nelements, 2);
        CHECK_STR_EQ(sh.elements[0].id, "in1");
        CHECK(sh.elements[1].id == NULL);
        conica_svg_shapes_free(&sh);
    }
    SECTION("shapes converted: the circle is reproduced, the rest keeps its attributes")
    {
        conica_svg_doc *doc = load(t);
        conica_svg_stats stats;
        char *out;
        s.convert_shapes = 1;
        s.levels = 4;
        s.precision = 17;
        extract(t, &s, &sh);
        REQUIRE_EQ_U(sh.nelements, 6); /* the ellipse in % is skipped */
        CHECK_STR_EQ(sh.elements[3].tag, "circle");
        {
            conica_svg_shapes one;
            one = sh;
            one.nsubpaths = 1;
            one.subpaths = sh.subpaths + sh.elements[3].first_subpath;
            CHECK_EQ_U(one.subpaths[0].n, 64);
            CHECK_LE(circle_error(&one, 5000, 3000, 20), 1e-9);
        }
        conica_svg_shapes_free(&sh);
        REQUIRE(conica_svg_process(doc, &s, &stats, NULL) == CONICA_OK);
        out = save(doc);
        CHECK(strstr(out, "<path id=\"o\" fill=\"blue\" d=\"M5020 3000L") != NULL);
        CHECK(strstr(out, "<path id=\"l\" d=\"M0 0L5 5\"/>") != NULL);
        CHECK(strstr(out, "<ellipse id=\"e\"") != NULL);
        free(out);
        conica_svg_doc_free(doc);
    }
}

static void count_warning(void *ctx, size_t line, const char *msg)
{
    (void)msg;
    ((size_t *)ctx)[0]++;
    ((size_t *)ctx)[1] = line;
}

TEST_CASE("bad path data: warning with the element and byte, valid prefix kept", "[svg][doc]")
{
    const char *t = "<svg xmlns=\"http://www.w3.org/2000/svg\">\n\n<path id=\"bad\" "
                    "d=\"M0 0L10 0L10 10L0 10Z L5\"/>\n<path d=\"X\"/></svg>";
    conica_svg_doc *doc = load(t);
    conica_svg_settings s = conica_svg_defaults();
    size_t seen[2] = {0, 0};
    char *out;
    s.warn = count_warning;
    s.warn_ctx = seen;
    s.levels = 0;
    REQUIRE(conica_svg_process(doc, &s, NULL, NULL) == CONICA_OK);
    CHECK_EQ_U(seen[0], 2);
    CHECK_EQ_U(seen[1], 4);
    out = save(doc);
    CHECK(strstr(out, "d=\"M0 0L10 0 10 10 0 10Z\"") != NULL);
    CHECK(strstr(out, "<path d=\"X\"/>") != NULL);
    free(out);
    conica_svg_doc_free(doc);
}

/* Collects warning texts, one a line. */
typedef struct warn_log {
    char text[1024];
    size_t count;
} warn_log;

static void log_warning(void *ctx, size_t line, const char *msg)
{
    warn_log *w = ctx;
    size_t n = strlen(w->text);
    (void)line;
    snprintf(w->text + n, sizeof w->text - n, "%s\n", msg);
    w->count++;
}

TEST_CASE("shapes with NaN or infinite geometry: warned as not a number", "[svg][doc]")
{
    /* said "units other than user units" before (issue 17) */
    const char *t = "<svg xmlns=\"http://www.w3.org/2000/svg\"><rect id=\"r\" width=\"NaN\" "
                    "height=\"5\"/><circle id=\"c\" r=\"1e999\"/><ellipse id=\"e\" rx=\"1\" "
                    "ry=\"inf\"/><line id=\"l\" x2=\"-nan\"/><rect id=\"u\" width=\"3mm\" "
                    "height=\"1\"/></svg>";
    conica_svg_doc *doc = load(t);
    conica_svg_settings s = conica_svg_defaults();
    warn_log w;
    memset(&w, 0, sizeof w);
    s.convert_shapes = 1;
    s.warn = log_warning;
    s.warn_ctx = &w;
    REQUIRE(conica_svg_process(doc, &s, NULL, NULL) == CONICA_OK);
    INFO("%s", w.text);
    CHECK_EQ_U(w.count, 5);
    CHECK(strstr(w.text, "rect 'r': geometry attribute 'width' is not a finite number") != NULL);
    CHECK(strstr(w.text, "circle 'c': geometry attribute 'r' is not a finite number") != NULL);
    CHECK(strstr(w.text, "ellipse 'e': geometry attribute 'ry' is not a finite number") != NULL);
    CHECK(strstr(w.text, "line 'l': geometry attribute 'x2' is not a finite number") != NULL);
    CHECK(strstr(w.text, "rect 'u': geometry attributes in units other than user units") != NULL);
    conica_svg_doc_free(doc);
}

TEST_CASE("--select ids that name no element are warned about", "[svg][doc]")
{
    const char *t = "<svg xmlns=\"http://www.w3.org/2000/svg\"><g id=\"g\">"
                    "<path id=\"a\" d=\"M0 0L1 0L1 1Z\"/></g><text id=\"label\">x</text></svg>";
    const char *ids[5] = {"nosuch", "a", "label", "nosuch", "zz"};
    conica_svg_settings s = conica_svg_defaults();
    conica_svg_shapes sh;
    warn_log w;
    memset(&w, 0, sizeof w);
    s.warn = log_warning;
    s.warn_ctx = &w;
    s.select = ids;
    s.nselect = 5;
    s.mode = CONICA_SVG_KEEP;
    extract(t, &s, &sh);
    CHECK_EQ_U(sh.nelements, 1);
    INFO("%s", w.text);
    /* once per missing id, in the order given; an id on a non-shape element is found */
    CHECK_EQ_U(w.count, 2);
    CHECK_STR_EQ(w.text, "--select: no element has id 'nosuch'\n"
                         "--select: no element has id 'zz'\n");
    conica_svg_shapes_free(&sh);
    /* every id found: no warning */
    memset(&w, 0, sizeof w);
    s.nselect = 2;
    s.select = ids + 1;
    extract(t, &s, &sh);
    CHECK_EQ_U(w.count, 0);
    conica_svg_shapes_free(&sh);
}

TEST_CASE("lengths convert between CSS units exactly where they can", "[svg][doc]")
{
    CHECK(conica_svg_convert_length(100.0, "px", "px") == 100.0);
    CHECK(conica_svg_convert_length(100.0, "", "px") == 100.0);
    CHECK(conica_svg_convert_length(0.1, "mm", "mm") == 0.1);
    CHECK(conica_svg_convert_length(96.0, "px", "in") == 1.0);
    CHECK(conica_svg_convert_length(3.0, "cm", "mm") == 30.0);
    CHECK(conica_svg_convert_length(72.0, "pt", "px") == 96.0);
    CHECK_NEAR(conica_svg_convert_length(96.0, "px", "mm"), 25.4, 1e-14);
    CHECK_NEAR(conica_svg_convert_length(1.0, "in", "mm"), 25.4, 1e-14);
    CHECK_NEAR(conica_svg_convert_length(4.0, "Q", "pc"), 6.0 / 25.4, 1e-15);
    /* px -> mm -> px is not the identity in floating point; one step is */
    CHECK(conica_svg_convert_length(100.0, "px", "px") ==
          conica_svg_convert_length(conica_svg_convert_length(100.0, "px", "px"), "px", "px"));
    CHECK(isnan(conica_svg_convert_length(1.0, "%", "mm")));
    CHECK(isnan(conica_svg_convert_length(1.0, "mm", "em")));
}

/* The bytes conica_svg_process_write() writes for text (len bytes). */
static char *process_write(const char *text, size_t len, const conica_svg_settings *s,
                           conica_code *rc, int processed_before)
{
    conica_svg_doc *doc = NULL;
    conica_status st;
    FILE *f = tmpfile();
    long n;
    char *out;
    REQUIRE(f != NULL);
    REQUIRE(conica_svg_doc_load(text, len, NULL, &doc, &st) == CONICA_OK);
    if (processed_before)
        REQUIRE(conica_svg_process(doc, s, NULL, &st) == CONICA_OK);
    *rc = conica_svg_process_write(doc, s, NULL, f, &st);
    INFO("process_write: %s", *rc == CONICA_OK ? "ok" : st.message);
    conica_svg_doc_free(doc);
    n = ftell(f);
    REQUIRE(n >= 0);
    out = malloc((size_t)n + 1);
    REQUIRE(out != NULL);
    rewind(f);
    REQUIRE(fread(out, 1, (size_t)n, f) == (size_t)n);
    out[n] = '\0';
    fclose(f);
    return out;
}

/* The bytes of conica_svg_process() then conica_svg_doc_save(), once or twice. */
static char *process_save(const char *text, size_t len, const conica_svg_settings *s,
                          conica_code *rc, int times)
{
    conica_svg_doc *doc = NULL;
    char *out = NULL;
    size_t n;
    REQUIRE(conica_svg_doc_load(text, len, NULL, &doc, NULL) == CONICA_OK);
    while (times-- > 0 && (*rc = conica_svg_process(doc, s, NULL, NULL)) == CONICA_OK)
        ;
    if (*rc == CONICA_OK)
        REQUIRE(conica_svg_doc_save(doc, &out, &n, NULL) == CONICA_OK);
    conica_svg_doc_free(doc);
    return out;
}

TEST_CASE("writing each element as it is made gives the bytes of process then save",
          "[svg][doc]")
{
    static const char shapes_doc[] =
        "<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 40 40'>\n"
        "<rect id='r' x='1' y='2' width='10' height='8' rx='2' d='M9 9' fill='red'/>\n"
        "<circle\n  cx='20'\tcy='20' r='5'  ></circle>\n"
        "<line x1=\"0\" y1=\"0\" x2=\"5\" y2=\"5\"/><ellipse cx='1' cy='1' rx='4%' ry='1'/>\n"
        "<path id='q' d='M0 0Q10 20 20 0' data-note='a &amp; b'/>"
        "<polygon id='t' points='0,0 10,0 5,8'/>\n"
        "</svg>";
    static const char prefixed_doc[] =
        "<?xml version=\"1.0\"?>\n"
        "<svg:svg xmlns:svg=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 10 10\">\n"
        "<svg:path d=\"M0 0C1 2 3 4 5 5L9 9\"></svg:path>\n"
        "<svg:rect x=\"1\" y=\"1\" width=\"3\" height=\"2\" rx=\"1\"></svg:rect>\n"
        "<svg:g><svg:circle cx=\"5\" cy=\"5\" r=\"2\"/></svg:g>\n"
        "</svg:svg>\n";
    const char *docs[] = {roundtrip_doc, shapes_doc, prefixed_doc};
    conica_svg_settings s = conica_svg_defaults();
    size_t i;
    int convert;
    conica_code r1, r2;
    s.levels = 3;
    for (i = 0; i < sizeof docs / sizeof docs[0]; i++)
        for (convert = 0; convert < 2; convert++) {
            char *a, *b;
            s.convert_shapes = convert;
            a = process_write(docs[i], strlen(docs[i]), &s, &r1, 0);
            b = process_save(docs[i], strlen(docs[i]), &s, &r2, 1);
            INFO("document %zu, convert_shapes %d", i, convert);
            REQUIRE_EQ(r1, CONICA_OK);
            REQUIRE_EQ(r2, CONICA_OK);
            CHECK_STR_EQ(a, b);
            free(a);
            free(b);
        }
    SECTION("a prefixed SVG element keeps its prefix in both tags, converted or not")
    {
        conica_svg_doc *doc;
        char *a;
        s.convert_shapes = 1;
        a = process_write(prefixed_doc, strlen(prefixed_doc), &s, &r1, 0);
        REQUIRE_EQ(r1, CONICA_OK);
        CHECK(strstr(a, "<svg:path d=\"M0 0L") != NULL);
        CHECK(strstr(a, "<path") == NULL);
        CHECK(strstr(a, "</svg:rect>") == NULL);
        CHECK(strstr(a, "<svg:g><svg:path d=\"M7 5L") != NULL);
        /* and it is XML again */
        doc = NULL;
        CHECK(conica_svg_doc_load(a, strlen(a), NULL, &doc, NULL) == CONICA_OK);
        conica_svg_doc_free(doc);
        free(a);
    }
    SECTION("a document processed before: the second pass over the first one's values")
    {
        char *a = process_write(shapes_doc, strlen(shapes_doc), &s, &r1, 1);
        char *b = process_save(shapes_doc, strlen(shapes_doc), &s, &r2, 2);
        REQUIRE_EQ(r1, CONICA_OK);
        REQUIRE_EQ(r2, CONICA_OK);
        CHECK_STR_EQ(a, b);
        free(a);
        free(b);
    }
    SECTION("UTF-16 is read as UTF-8 and written back in UTF-16LE with its mark")
    {
        const char *t = "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0Q1 2 2 0\"/>"
                        "</svg>";
        size_t n = strlen(t), k;
        char *u = malloc(2 * n + 2), *a, *b;
        REQUIRE(u != NULL);
        u[0] = '\xff';
        u[1] = '\xfe';
        for (k = 0; k < n; k++) {
            u[2 + 2 * k] = t[k];
            u[3 + 2 * k] = '\0';
        }
        a = process_write(u, 2 * n + 2, &s, &r1, 0);
        b = process_save(u, 2 * n + 2, &s, &r2, 1);
        REQUIRE_EQ(r1, CONICA_OK);
        REQUIRE_EQ(r2, CONICA_OK);
        /* ASCII in UTF-16LE: each character then a zero byte, after the
         * mark; the NUL the helpers append ends it at an even offset */
        CHECK(a[0] == '\xff' && a[1] == '\xfe');
        CHECK(b[0] == '\xff' && b[1] == '\xfe');
        char na[512], nb[512];
        size_t ia = 0, ib = 0;
        for (k = 2; a[k] != '\0' && ia + 1 < sizeof na; k += 2) {
            CHECK(a[k + 1] == '\0');
            na[ia++] = a[k];
        }
        for (k = 2; b[k] != '\0' && ib + 1 < sizeof nb; k += 2)
            nb[ib++] = b[k];
        na[ia] = nb[ib] = '\0';
        CHECK_STR_EQ(na, nb);
        CHECK(strstr(na, "d=\"M0 0L") != NULL);
        free(a);
        free(b);
        free(u);
    }
    SECTION("a failure is the one conica_svg_process() reports")
    {
        char *a;
        s.limits.max_points = 40;
        a = process_write(shapes_doc, strlen(shapes_doc), &s, &r1, 0);
        free(process_save(shapes_doc, strlen(shapes_doc), &s, &r2, 1));
        CHECK_EQ(r1, CONICA_ERR_LIMIT);
        CHECK_EQ(r2, CONICA_ERR_LIMIT);
        free(a);
    }
}

/* One <polyline> of n vertices of a serpentine wave (rows of 10^4, 3
 * decimals, about 17.8 bytes a vertex): a 10^6-vertex path is a 17 MB
 * attribute value. Returns a malloc'ed NUL-terminated document. */
static char *big_polyline_doc(size_t n)
{
    size_t cap = 200 + 32 * n, k = 0;
    char *t = malloc(cap);
    REQUIRE(t != NULL);
    k += (size_t)snprintf(t + k, cap - k,
                          "<svg xmlns=\"http://www.w3.org/2000/svg\"><polyline fill=\"none\" "
                          "points=\"");
    for (size_t i = 0; i < n; i++) {
        size_t r = i / 10000, c = i % 10000, x = r % 2 ? 9999 - c : c;
        k += (size_t)snprintf(t + k, cap - k, "%s%zu %.3f", i ? " " : "", x,
                              100.0 * (double)r + 30.0 * sin((double)x / 16.0));
    }
    snprintf(t + k, cap - k, "\"/></svg>");
    return t;
}

TEST_CASE("a single path of 10^6 vertices (a 17 MB attribute) is smoothed and flattened",
          "[svg][doc][limits]")
{
    /* refused before by libxml2's 10 MB cap on one attribute value, and
     * quadratic with it lifted (the push parser re-scanned the start tag
     * at every 64 KiB chunk) */
    const size_t n = 1000000;
    char *t = big_polyline_doc(n);
    size_t len = strlen(t);
    CHECK_GT((double)len, 10e6);
    for (int mode = 0; mode < 2; mode++) {
        conica_svg_doc *doc = NULL;
        conica_status st;
        REQUIRE(conica_svg_doc_load(t, len, NULL, &doc, &st) == CONICA_OK);
        conica_svg_settings s = conica_svg_defaults();
        conica_svg_stats stats;
        if (mode == 0) {
            s.levels = 1;
        } else {
            s.mode = CONICA_SVG_FLATTEN;
            s.tolerance = 0.01;
        }
        conica_code rc = conica_svg_process(doc, &s, &stats, &st);
        if (rc != CONICA_OK)
            INFO("%s", st.message);
        REQUIRE(rc == CONICA_OK);
        CHECK_EQ_U(stats.elements, 1);
        CHECK_EQ_U(stats.subpaths, 1);
        CHECK_EQ_U(stats.in_vertices, n);
        if (mode == 0) { /* an open polyline: 2n - 1 points, plus the inflection points */
            CHECK_GE((double)stats.out_points, 2.0 * (double)n - 1);
            CHECK_LE((double)stats.out_points, 2.0 * (double)n + 20000);
        } else { /* straight segments stay as they are */
            CHECK_EQ_U(stats.out_points, n);
        }
        conica_svg_doc_free(doc);
    }
    free(t);
}

/* The subpaths conica_svg_extract() makes of text under s, and the input
 * vertices conica_svg_process() counts in it. */
static size_t extract_text(const char *text, const conica_svg_settings *s, conica_svg_shapes *sh)
{
    conica_svg_doc *doc = NULL;
    conica_status st;
    conica_svg_stats stats;
    REQUIRE(conica_svg_doc_load(text, strlen(text), NULL, &doc, &st) == CONICA_OK);
    conica_svg_shapes_init(sh);
    REQUIRE(conica_svg_extract(doc, s, sh, &st) == CONICA_OK);
    REQUIRE(conica_svg_process(doc, s, &stats, &st) == CONICA_OK);
    conica_svg_doc_free(doc);
    return stats.in_vertices;
}

TEST_CASE("polygons and polylines give what the same points as straight path data give",
          "[svg][doc]")
{
    /* Points lists go to the front end as samples straight from the parsed
     * pairs (no segment structs): the result must be that of the same
     * vertices written as M/L path data read as samples. */
    char pts[4096], d[4096];
    size_t kp = 0, kd = 0;
    for (int i = 0; i < 40; i++) {
        double a = 0.15 * i, x = 50 + 30 * cos(a) + 3 * sin(3 * a), y = 40 + 20 * sin(a);
        kp += (size_t)snprintf(pts + kp, sizeof pts - kp, "%s%.3f,%.3f", i ? " " : "", x, y);
        kd += (size_t)snprintf(d + kd, sizeof d - kd, "%s%.3f,%.3f", i ? " L" : "M", x, y);
    }
    for (int closed = 0; closed < 2; closed++) {
        for (int simplify = 0; simplify < 2; simplify++) {
            char a[9000], b[9000];
            snprintf(a, sizeof a, "<svg xmlns='http://www.w3.org/2000/svg'><%s points='%s'/></svg>",
                     closed ? "polygon" : "polyline", pts);
            snprintf(b, sizeof b, "<svg xmlns='http://www.w3.org/2000/svg'><path d='%s%s'/></svg>",
                     d, closed ? "Z" : "");
            conica_svg_settings s = conica_svg_defaults();
            s.levels = 2;
            s.lines_as_samples = 1;
            s.simplify = simplify ? 0.5 : 0;
            conica_svg_shapes sa, sb;
            size_t va = extract_text(a, &s, &sa), vb = extract_text(b, &s, &sb);
            CHECK_EQ_U(va, 40);
            CHECK_EQ_U(va, vb);
            REQUIRE_EQ_U(sa.nsubpaths, 1);
            REQUIRE_EQ_U(sb.nsubpaths, 1);
            CHECK(sa.subpaths[0].closed == closed);
            CHECK(sb.subpaths[0].closed == closed);
            REQUIRE_EQ_U(sa.subpaths[0].n, sb.subpaths[0].n);
            CHECK_GT((double)sa.subpaths[0].n, simplify ? 20.0 : 100.0);
            CHECK(memcmp(sa.subpaths[0].xy, sb.subpaths[0].xy,
                         2 * sa.subpaths[0].n * sizeof(double)) == 0);
            conica_svg_shapes_free(&sa);
            conica_svg_shapes_free(&sb);
        }
    }
    /* a polygon that returns to its start has that vertex once */
    conica_svg_settings s = conica_svg_defaults();
    conica_svg_shapes sh;
    CHECK_EQ_U(extract_text("<svg xmlns='http://www.w3.org/2000/svg'><polygon points='0,0 10,0 "
                            "10,10 0,10 0,0'/></svg>",
                            &s, &sh),
               4);
    conica_svg_shapes_free(&sh);
}

/* SPDX-License-Identifier: MIT */
/* The SVG render (conica_svg_render): exact matrices of viewports and
 * preserveAspectRatio, units, what is and is not painted (paint, CSS,
 * display, visibility, non-rendered elements), <use> expansion, stroke
 * properties, clips, warnings, caps and bad arguments. The pixel checks
 * against librsvg are in tests/cli/svg_render.sh. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica_svg.h"
#include "conica_svg_render.h"
#include "conica_test.h"

typedef struct warnings {
    int n;
    char last[512];
    char all[4096];
} warnings;

static void on_warn(void *ctx, size_t line, const char *msg)
{
    warnings *w = ctx;
    size_t k = strlen(w->all);
    (void)line;
    w->n++;
    snprintf(w->last, sizeof w->last, "%s", msg);
    if (k + strlen(msg) + 2 < sizeof w->all)
        snprintf(w->all + k, sizeof w->all - k, "%s\n", msg);
}

/* Render text with settings rs (NULL: defaults, warnings into *w). */
static conica_code render(const char *text, conica_svg_render_settings *rs, warnings *w,
                          conica_svg_scene *sc, conica_status *st)
{
    conica_svg_doc *doc = NULL;
    conica_svg_render_settings def = conica_svg_render_defaults();
    conica_code rc = conica_svg_doc_load(text, strlen(text), NULL, &doc, st);
    INFO("load: %s", rc == CONICA_OK ? "ok" : st->message);
    REQUIRE(rc == CONICA_OK);
    if (!rs)
        rs = &def;
    if (w) {
        memset(w, 0, sizeof *w);
        rs->warn = on_warn;
        rs->warn_ctx = w;
    }
    conica_svg_scene_init(sc);
    rc = conica_svg_render(doc, rs, sc, st);
    conica_svg_doc_free(doc);
    return rc;
}

/* The scene of text (default settings, must succeed). */
static void scene_of(const char *text, const char *unit, conica_svg_scene *sc, warnings *w)
{
    conica_svg_render_settings rs = conica_svg_render_defaults();
    conica_status st;
    conica_code rc;
    if (unit)
        rs.unit = unit;
    rc = render(text, &rs, w, sc, &st);
    INFO("render: %s", rc == CONICA_OK ? "ok" : st.message);
    REQUIRE(rc == CONICA_OK);
}

static void check_matrix(const conica_svg_matrix *m, double a, double b, double c, double d,
                         double e, double f)
{
    CHECK_NEAR(m->a, a, 1e-12);
    CHECK_NEAR(m->b, b, 1e-12);
    CHECK_NEAR(m->c, c, 1e-12);
    CHECK_NEAR(m->d, d, 1e-12);
    CHECK_NEAR(m->e, e, 1e-12);
    CHECK_NEAR(m->f, f, 1e-12);
}

/* The bounding box of item i's path mapped through its ctm (end and
 * control points, which for the shapes below are on the outline). */
static void item_box(const conica_svg_item *it, double box[4])
{
    size_t k;
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (k = 0; k < it->path.n; k++) {
        double q[2];
        conica_svg_matrix_apply(&it->ctm, it->path.seg[k].x1, it->path.seg[k].y1, q);
        box[0] = fmin(box[0], q[0]);
        box[1] = fmin(box[1], q[1]);
        box[2] = fmax(box[2], q[0]);
        box[3] = fmax(box[3], q[1]);
    }
}

TEST_CASE("root viewBox with pAR xMidYMid meet: 1 mm per unit, centred", "[svg][render]")
{
    conica_svg_scene sc;
    scene_of("<svg xmlns='http://www.w3.org/2000/svg' width='40mm' height='20mm' "
             "viewBox='0 0 20 20'><circle cx='10' cy='10' r='10'/></svg>",
             "mm", &sc, NULL);
    REQUIRE_EQ_U(sc.n, 1);
    CHECK(sc.has_size);
    CHECK_EQ(sc.width, 40.0); /* exact: mm to mm */
    CHECK_EQ(sc.height, 20.0);
    CHECK_STR_EQ(sc.unit, "mm");
    check_matrix(&sc.items[0].ctm, 1, 0, 0, 1, 10, 0);
    {
        double box[4];
        item_box(&sc.items[0], box);
        CHECK_NEAR(box[2] - box[0], 20.0, 1e-12); /* a circle, not a 32 x 16 ellipse */
        CHECK_NEAR(box[3] - box[1], 20.0, 1e-12);
    }
    conica_svg_scene_free(&sc);
}

TEST_CASE("a mm document with its viewBox in mm keeps its numbers", "[svg][render]")
{
    conica_svg_scene sc;
    scene_of("<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='50mm' "
             "viewBox='0 0 100 50'><rect x='0.1' width='3.3' height='7'/></svg>",
             "mm", &sc, NULL);
    REQUIRE_EQ_U(sc.n, 1);
    CHECK_EQ(sc.items[0].ctm.a, 1.0);
    CHECK_EQ(sc.items[0].ctm.d, 1.0);
    CHECK_EQ(sc.items[0].ctm.e, 0.0);
    CHECK_EQ(sc.items[0].path.seg[0].x1, 0.1);
    conica_svg_scene_free(&sc);
    /* without a viewBox, user units are px: 96 px = 1 in = 25.4 mm */
    scene_of("<svg xmlns='http://www.w3.org/2000/svg' width='1in' height='1in'>"
             "<rect width='96' height='96'/></svg>", "mm", &sc, NULL);
    REQUIRE_EQ_U(sc.n, 1);
    CHECK_EQ(sc.width, 25.4);
    CHECK_NEAR(sc.items[0].ctm.a, 25.4 / 96.0, 1e-17);
    conica_svg_scene_free(&sc);
}

TEST_CASE("root size: from the viewBox, from one side and its aspect, or none", "[svg][render]")
{
    conica_svg_scene sc;
    scene_of("<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 24 16'/>", NULL, &sc, NULL);
    CHECK(sc.has_size);
    CHECK_EQ(sc.width, 24.0);
    CHECK_EQ(sc.height, 16.0);
    conica_svg_scene_free(&sc);
    scene_of("<svg xmlns='http://www.w3.org/2000/svg' width='96' viewBox='0 0 24 12'/>", NULL,
             &sc, NULL);
    CHECK_EQ(sc.height, 48.0);
    conica_svg_scene_free(&sc);
    scene_of("<svg xmlns='http://www.w3.org/2000/svg' width='100%'><rect width='5' "
             "height='5'/></svg>", NULL, &sc, NULL);
    CHECK_FALSE(sc.has_size);
    REQUIRE_EQ_U(sc.n, 1);
    CHECK_EQ_U(sc.items[0].nclip, 0); /* no size: no root clip */
    conica_svg_scene_free(&sc);
}

TEST_CASE("every preserveAspectRatio value gives the SVG 1.1 7.8 matrix", "[svg][render]")
{
    static const char *const al[] = {"xMinYMin", "xMidYMin", "xMaxYMin", "xMinYMid", "xMidYMid",
                                     "xMaxYMid", "xMinYMax", "xMidYMax", "xMaxYMax"};
    int k, slice;
    for (slice = 0; slice < 2; slice++)
        for (k = 0; k < 9; k++) {
            char doc[512];
            conica_svg_scene sc;
            /* viewport 40 x 10 at (5, 7), viewBox 10 x 5 at (1, 2) */
            double s = slice ? 4.0 : 2.0, ax = 0.5 * (k % 3), ay = 0.5 * (k / 3);
            snprintf(doc, sizeof doc,
                     "<svg xmlns='http://www.w3.org/2000/svg' width='100' height='100'>"
                     "<svg x='5' y='7' width='40' height='10' viewBox='1 2 10 5' "
                     "preserveAspectRatio='%s %s'><rect width='1' height='1'/></svg></svg>",
                     al[k], slice ? "slice" : "meet");
            scene_of(doc, NULL, &sc, NULL);
            INFO("%s %s", al[k], slice ? "slice" : "meet");
            REQUIRE_EQ_U(sc.n, 1);
            check_matrix(&sc.items[0].ctm, s, 0, 0, s, 5 - 1 * s + ax * (40 - 10 * s),
                         7 - 2 * s + ay * (10 - 5 * s));
            /* the clip is the viewport (root clip included) */
            {
                double area = 0;
                size_t i, n = sc.items[0].nclip;
                const double *p = sc.items[0].clip;
                REQUIRE(n >= 3);
                for (i = 0; i < n; i++)
                    area += p[2 * i] * p[2 * ((i + 1) % n) + 1] -
                            p[2 * ((i + 1) % n)] * p[2 * i + 1];
                CHECK_NEAR(0.5 * area, 400.0, 1e-9); /* counter-clockwise, 40 x 10 */
            }
            conica_svg_scene_free(&sc);
        }
    {
        conica_svg_scene sc;
        scene_of("<svg xmlns='http://www.w3.org/2000/svg' width='100' height='100'>"
                 "<svg x='5' y='7' width='40' height='10' viewBox='1 2 10 5' "
                 "preserveAspectRatio='none'><rect width='1' height='1'/></svg></svg>",
                 NULL, &sc, NULL);
        REQUIRE_EQ_U(sc.n, 1);
        check_matrix(&sc.items[0].ctm, 4, 0, 0, 2, 1, 3);
        conica_svg_scene_free(&sc);
    }
}

TEST_CASE("a nested svg of width 10 with a viewBox of 100 is 10 units wide", "[svg][render]")
{
    conica_svg_scene sc;
    double box[4];
    scene_of("<svg xmlns='http://www.w3.org/2000/svg' width='200' height='200'>"
             "<svg x='5' y='5' width='10' height='10' viewBox='0 0 100 100'>"
             "<rect width='100' height='100'/></svg></svg>",
             NULL, &sc, NULL);
    REQUIRE_EQ_U(sc.n, 1);
    item_box(&sc.items[0], box);
    CHECK_NEAR(box[0], 5.0, 1e-12);
    CHECK_NEAR(box[2] - box[0], 10.0, 1e-12);
    CHECK_NEAR(box[3] - box[1], 10.0, 1e-12);
    conica_svg_scene_free(&sc);
}

TEST_CASE("the tabler frame path paints nothing", "[svg][render]")
{
    static const char tabler[] =
        "<svg xmlns='http://www.w3.org/2000/svg' width='24' height='24' viewBox='0 0 24 24' "
        "fill='none' stroke='currentColor' stroke-width='2' stroke-linecap='round' "
        "stroke-linejoin='round'><path stroke='none' d='M0 0h24v24H0z' fill='none'/>"
        "<path d='M9 12l2 2l4 -4'/></svg>";
    conica_svg_render_settings rs = conica_svg_render_defaults();
    conica_svg_scene sc;
    conica_status st;
    scene_of(tabler, NULL, &sc, NULL);
    REQUIRE_EQ_U(sc.n, 1);
    CHECK_FALSE(sc.items[0].fill);
    CHECK(sc.items[0].stroke);
    CHECK_EQ(sc.items[0].st.width, 2.0);
    CHECK_EQ(sc.items[0].st.join, CONICA_SVG_JOIN_ROUND);
    CHECK_EQ(sc.items[0].st.cap, CONICA_SVG_CAP_ROUND);
    CHECK_EQ(sc.items[0].st.miterlimit, 4.0);
    conica_svg_scene_free(&sc);
    rs.unpainted = 1;
    REQUIRE(render(tabler, &rs, NULL, &sc, &st) == CONICA_OK);
    REQUIRE_EQ_U(sc.n, 2);
    CHECK_FALSE(sc.items[0].fill || sc.items[0].stroke);
    conica_svg_scene_free(&sc);
}

/* Number of painted items of a document. */
static size_t count(const char *text)
{
    conica_svg_scene sc;
    size_t n;
    scene_of(text, NULL, &sc, NULL);
    n = sc.n;
    conica_svg_scene_free(&sc);
    return n;
}

#define SVG(body) "<svg xmlns='http://www.w3.org/2000/svg' width='100' height='100'>" body "</svg>"
#define R "<rect width='5' height='5'"

TEST_CASE("what is painted: paints, opacities, display, visibility", "[svg][render]")
{
    CHECK_EQ_U(count(SVG(R "/>")), 1);            /* initial fill black */
    CHECK_EQ_U(count(SVG(R " fill='none'/>")), 0); /* and stroke none */
    CHECK_EQ_U(count(SVG(R " fill='transparent'/>")), 0);
    CHECK_EQ_U(count(SVG(R " fill='#0000'/>")), 0);
    CHECK_EQ_U(count(SVG(R " fill='rgba(1,2,3,0)'/>")), 0);
    CHECK_EQ_U(count(SVG(R " fill='bogus'/>")), 1); /* invalid: inherited black */
    CHECK_EQ_U(count(SVG("<g fill='none'>" R " fill='bogus'/></g>")), 0);
    CHECK_EQ_U(count(SVG(R " fill='url(#nothing)'/>")), 0);
    CHECK_EQ_U(count(SVG(R " fill='url(#nothing) red'/>")), 1);
    CHECK_EQ_U(count(SVG("<linearGradient id='g'><stop/></linearGradient>" R " fill='url(#g)'/>")),
               1);
    CHECK_EQ_U(count(SVG("<linearGradient id='g'/>" R " fill='url(#g) red'/>")), 0);
    CHECK_EQ_U(count(SVG(R " fill='currentColor'/>")), 1);
    CHECK_EQ_U(count(SVG(R " fill='currentColor' color='transparent'/>")), 0);
    CHECK_EQ_U(count(SVG(R " fill-opacity='0'/>")), 0);
    CHECK_EQ_U(count(SVG(R " opacity='0'/>")), 0);
    CHECK_EQ_U(count(SVG("<g opacity='0'>" R "/></g>")), 0);
    CHECK_EQ_U(count(SVG(R " fill='none' stroke='red' stroke-opacity='0'/>")), 0);
    CHECK_EQ_U(count(SVG(R " fill='none' stroke='red' stroke-width='0'/>")), 0);
    CHECK_EQ_U(count(SVG(R " fill='none' stroke='red'/>")), 1);
    CHECK_EQ_U(count(SVG(R " display='none'/>")), 0);
    CHECK_EQ_U(count(SVG("<g display='none'>" R " display='inline'/></g>")), 0);
    CHECK_EQ_U(count(SVG(R " visibility='hidden'/>")), 0);
    CHECK_EQ_U(count(SVG("<g visibility='hidden'>" R "/>" R " visibility='visible'/></g>")), 1);
    CHECK_EQ_U(count(SVG("<g style='visibility:collapse'><g>" R "/></g></g>")), 0);
    CHECK_EQ_U(count(SVG("<line x2='5' y2='5'/>")), 0); /* a line has no fill */
}

TEST_CASE("contents of defs, symbols, clipPaths, ... are not drawn", "[svg][render]")
{
    static const char *const tags[] = {"defs", "symbol", "clipPath", "mask", "marker",
                                       "pattern", "linearGradient", "radialGradient",
                                       "title", "desc", "metadata", "filter"};
    size_t k;
    for (k = 0; k < sizeof tags / sizeof tags[0]; k++) {
        char doc[256];
        snprintf(doc, sizeof doc, SVG("<%s id='x'>" R "/></%s>"), tags[k], tags[k]);
        INFO("%s", tags[k]);
        CHECK_EQ_U(count(doc), 0);
    }
    CHECK_EQ_U(count("<svg xmlns='http://www.w3.org/2000/svg' xmlns:f='urn:f' width='9' "
                     "height='9'><f:g><rect width='5' height='5'/></f:g></svg>"), 0);
}

TEST_CASE("CSS: selectors, specificity, !important, source order, style attribute",
          "[svg][render]")
{
#define CSS(sheet, body) SVG("<style>" sheet "</style>" body)
    CHECK_EQ_U(count(CSS(".a{fill:none}", R " class='a'/>")), 0);
    CHECK_EQ_U(count(CSS(".a{fill:none}", R " class='b a c'/>")), 0);
    CHECK_EQ_U(count(CSS(".a{fill:none}", R " class='ab'/>")), 1);
    CHECK_EQ_U(count(CSS("rect{fill:none}", R "/>")), 0);
    CHECK_EQ_U(count(CSS("#i{fill:none}", R " id='i'/>")), 0);
    CHECK_EQ_U(count(CSS("*{fill:none}", R " fill='red'/>")), 0); /* rules beat attributes */
    CHECK_EQ_U(count(CSS("[k]{fill:none}", R " k='1'/>")), 0);
    CHECK_EQ_U(count(CSS("[k='2']{fill:none}", R " k='1'/>")), 1);
    CHECK_EQ_U(count(CSS("[k^='ab']{fill:none}", R " k='abc'/>")), 0);
    CHECK_EQ_U(count(CSS("[k$='bc']{fill:none}", R " k='abc'/>")), 0);
    CHECK_EQ_U(count(CSS("[k*='b']{fill:none}", R " k='abc'/>")), 0);
    CHECK_EQ_U(count(CSS("[k~='b']{fill:none}", R " k='a b c'/>")), 0);
    CHECK_EQ_U(count(CSS("[k|='en']{fill:none}", R " k='en-GB'/>")), 0);
    CHECK_EQ_U(count(CSS("g rect{fill:none}", "<g><g>" R "/></g></g>")), 0);
    CHECK_EQ_U(count(CSS("g > rect{fill:none}", "<g><g>" R "/></g></g>")), 0);
    CHECK_EQ_U(count(CSS("svg > rect{fill:none}", "<g>" R "/></g>")), 1);
    CHECK_EQ_U(count(CSS(".x, .a{fill:none}", R " class='a'/>")), 0);
    CHECK_EQ_U(count(CSS("#i{fill:none} .a{fill:red}", R " id='i' class='a'/>")), 0);
    CHECK_EQ_U(count(CSS(".a{fill:none} rect{fill:red}", R " class='a'/>")), 0);
    CHECK_EQ_U(count(CSS(".a{fill:red} .a{fill:none}", R " class='a'/>")), 0);
    CHECK_EQ_U(count(CSS(".a{fill:none} .a{fill:red}", R " class='a'/>")), 1);
    CHECK_EQ_U(count(CSS(".a{fill:none}", R " class='a' style='fill:red'/>")), 1);
    CHECK_EQ_U(count(CSS(".a{fill:none !important}", R " class='a' style='fill:red'/>")), 0);
    CHECK_EQ_U(count(SVG(R " style='fill:none; fill: bogus'/>")), 0); /* invalid is dropped */
    CHECK_EQ_U(count(SVG(R " fill='none' style='fill:red'/>")), 1);
    CHECK_EQ_U(count(CSS("/* .a{fill:red} */ .a{fill:none}", R " class='a'/>")), 0);
    CHECK_EQ_U(count(CSS("rect:hover{fill:none}", R "/>")), 1);
    CHECK_EQ_U(count(CSS("rect:first-child{fill:none}", "<g>" R "/></g>")), 0);
    CHECK_EQ_U(count(CSS(".a + .b{fill:none}", R " class='a'/>" R " class='b'/>")), 1);
    CHECK_EQ_U(count(CSS("g{fill:none}", "<g>" R "/></g>")), 0); /* inherited */
    CHECK_EQ_U(count(CSS("g{opacity:0}", "<g>" R "/></g>")), 0);
    CHECK_EQ_U(count(CSS("g{display:none}", "<g>" R "/></g>")), 0);
#undef CSS
}

TEST_CASE("use: href, xlink:href, x/y after the transform, use of a use", "[svg][render]")
{
    conica_svg_scene sc;
    scene_of("<svg xmlns='http://www.w3.org/2000/svg' xmlns:xlink='http://www.w3.org/1999/xlink' "
             "width='100' height='100'><defs><path id='p' d='M0 0h1v1z'/></defs>"
             "<use href='#p' x='10' y='10'/>"
             "<use xlink:href='#p' x='1' y='2' transform='scale(2)'/>"
             "<use id='u' href='#p' x='3'/><use href='#u' x='4'/>"
             "<use href='#p' xlink:href='#nothing' x='7'/></svg>",
             NULL, &sc, NULL);
    REQUIRE_EQ_U(sc.n, 5);
    check_matrix(&sc.items[0].ctm, 1, 0, 0, 1, 10, 10);
    check_matrix(&sc.items[1].ctm, 2, 0, 0, 2, 2, 4);
    check_matrix(&sc.items[2].ctm, 1, 0, 0, 1, 3, 0);
    check_matrix(&sc.items[3].ctm, 1, 0, 0, 1, 7, 0);
    check_matrix(&sc.items[4].ctm, 1, 0, 0, 1, 7, 0); /* href wins over xlink:href */
    CHECK(strstr(sc.items[3].name, "path 'p' via use") != NULL);
    conica_svg_scene_free(&sc);
    /* a symbol: its viewBox into the use's width and height */
    scene_of(SVG("<symbol id='s' viewBox='0 0 10 10'><rect width='10' height='10'/></symbol>"
                 "<use href='#s' x='5' y='5' width='20' height='40'/>"),
             NULL, &sc, NULL);
    REQUIRE_EQ_U(sc.n, 1);
    check_matrix(&sc.items[0].ctm, 2, 0, 0, 2, 5, 15);
    conica_svg_scene_free(&sc);
    /* styles inherit from the use, not from the target's parent */
    CHECK_EQ_U(count(SVG("<g fill='red'><path id='p' d='M0 0h1v1z'/></g>"
                         "<use href='#p' fill='none'/>")), 1);
    CHECK_EQ_U(count(SVG("<defs><path id='p' d='M0 0h1v1z'/></defs><use href='#p' fill='none'/>")),
               0);
}

TEST_CASE("units and percentages in geometry and strokes", "[svg][render]")
{
    conica_svg_scene sc;
    double box[4];
    scene_of("<svg xmlns='http://www.w3.org/2000/svg' width='200' height='100' font-size='10'>"
             "<rect x='1in' y='10%' width='2.54cm' height='2em'/>"
             "<path d='M0 0H1' stroke='black' stroke-width='10%' stroke-dasharray='1mm 2%  3'/>"
             "<circle r='1pc'/></svg>",
             NULL, &sc, NULL);
    REQUIRE_EQ_U(sc.n, 3);
    item_box(&sc.items[0], box);
    CHECK_NEAR(box[0], 96.0, 1e-12);
    CHECK_NEAR(box[1], 10.0, 1e-12);
    CHECK_NEAR(box[2] - box[0], 96.0, 1e-12);
    CHECK_NEAR(box[3] - box[1], 20.0, 1e-12);
    /* other lengths: % of sqrt((w^2 + h^2) / 2) */
    CHECK_NEAR(sc.items[1].st.width, 0.1 * sqrt(0.5 * (200.0 * 200.0 + 100.0 * 100.0)), 1e-12);
    REQUIRE_EQ_U(sc.items[1].st.ndash, 6); /* an odd list is repeated */
    CHECK_NEAR(sc.items[1].st.dash[0], 96.0 / 25.4, 1e-12);
    CHECK_NEAR(sc.items[1].st.dash[5], 3.0, 1e-12);
    item_box(&sc.items[2], box);
    CHECK_NEAR(box[2] - box[0], 32.0, 1e-12);
    conica_svg_scene_free(&sc);
    scene_of(SVG("<path d='M0 0H1' stroke='black' stroke-dasharray='0 0'/>"), NULL, &sc, NULL);
    REQUIRE_EQ_U(sc.n, 1);
    CHECK_EQ_U(sc.items[0].st.ndash, 0); /* zero sum: solid */
    conica_svg_scene_free(&sc);
}

TEST_CASE("transforms: functions, quarter turns exact, singular ones not drawn", "[svg][render]")
{
    conica_svg_scene sc;
    warnings w;
    scene_of(SVG(R " transform='rotate(90)'/>" R " transform='translate(1 2) scale(3)'/>"
                 R " transform='skewX(45)'/>" R " transform='matrix(1 0 0 0 0 0)'/>"
                 R " transform='rotate(90 10 0)'/>"),
             NULL, &sc, &w);
    REQUIRE_EQ_U(sc.n, 4);
    check_matrix(&sc.items[0].ctm, 0, 1, -1, 0, 0, 0);
    CHECK_EQ(sc.items[0].ctm.a, 0.0);
    check_matrix(&sc.items[1].ctm, 3, 0, 0, 3, 1, 2);
    check_matrix(&sc.items[2].ctm, 1, 0, 1, 1, 0, 0);
    check_matrix(&sc.items[3].ctm, 0, 1, -1, 0, 10, -10);
    CHECK_EQ(w.n, 1);
    CHECK(strstr(w.last, "not invertible") != NULL);
    conica_svg_scene_free(&sc);
}

TEST_CASE("unsupported features are named once per element and kind", "[svg][render]")
{
    conica_svg_scene sc;
    warnings w;
    scene_of(SVG("<text id='t'>a<tspan>b</tspan></text>"
                 "<clipPath id='c'/>" R " id='r' clip-path='url(#c)' style='clip-path:url(#c)'/>"),
             NULL, &sc, &w);
    CHECK_EQ(w.n, 2);
    CHECK(strstr(w.all, "text 't': text is not drawn") != NULL);
    CHECK(strstr(w.all, "rect 'r': clip-path is not applied: drawn unclipped") != NULL);
    CHECK_EQ_U(sc.n, 1);
    conica_svg_scene_free(&sc);
}

TEST_CASE("caps: cycles, use depth, instances, CSS size; bad arguments", "[svg][render]")
{
    conica_svg_render_settings rs = conica_svg_render_defaults();
    conica_svg_scene sc;
    conica_status st;
    CHECK(render(SVG("\n<g id='a'>\n<use href='#a'/></g>"), NULL, NULL, &sc, &st) ==
          CONICA_ERR_LIMIT);
    CHECK_EQ_U(st.line, 3);
    CHECK_EQ_U(sc.n, 0);
    rs.max_use_depth = 1;
    CHECK(render(SVG("<path id='p' d='M0 0h1v1z'/><use id='u' href='#p'/><use href='#u'/>"), &rs,
                 NULL, &sc, &st) == CONICA_ERR_LIMIT);
    rs.max_use_depth = 2;
    CHECK(render(SVG("<path id='p' d='M0 0h1v1z'/><use id='u' href='#p'/><use href='#u'/>"), &rs,
                 NULL, &sc, &st) == CONICA_OK);
    CHECK_EQ_U(sc.n, 3);
    conica_svg_scene_free(&sc);
    rs = conica_svg_render_defaults();
    rs.max_instances = 3;
    CHECK(render(SVG(R "/>" R "/>" R "/>"), &rs, NULL, &sc, &st) == CONICA_ERR_LIMIT);
    rs.max_instances = 4;
    CHECK(render(SVG(R "/>" R "/>" R "/>"), &rs, NULL, &sc, &st) == CONICA_OK);
    conica_svg_scene_free(&sc);
    rs = conica_svg_render_defaults();
    rs.max_segments = 5;
    CHECK(render(SVG(R "/>" R "/>"), &rs, NULL, &sc, &st) == CONICA_ERR_LIMIT);
    {
        /* more selectors than CONICA_SVG_MAX_CSS_RULES */
        size_t n = CONICA_SVG_MAX_CSS_RULES + 1, i;
        char *doc = malloc(n * 8 + 256), *p = doc;
        REQUIRE(doc != NULL);
        p += sprintf(p, "<svg xmlns='http://www.w3.org/2000/svg'><style>");
        for (i = 0; i < n; i++)
            p += sprintf(p, ".a%zu,", i % 1000);
        sprintf(p, ".z{fill:none}</style></svg>");
        CHECK(render(doc, NULL, NULL, &sc, &st) == CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "CSS selectors") != NULL);
        free(doc);
    }
    rs = conica_svg_render_defaults();
    rs.unit = "furlong";
    CHECK(render(SVG(R "/>"), &rs, NULL, &sc, &st) == CONICA_ERR_ARG);
    CHECK(conica_svg_render(NULL, NULL, &sc, &st) == CONICA_ERR_ARG);
    conica_svg_scene_free(NULL);
}

TEST_CASE("select draws the chosen elements, groups and uses only", "[svg][render]")
{
    const char *sel[] = {"g", "u"};
    conica_svg_render_settings rs = conica_svg_render_defaults();
    conica_svg_scene sc;
    conica_status st;
    warnings w;
    rs.select = sel;
    rs.nselect = 2;
    REQUIRE(render(SVG("<g id='g'>" R "/>" R "/></g>" R " id='p'/><use id='u' href='#p'/>"), &rs,
                   &w, &sc, &st) == CONICA_OK);
    CHECK_EQ_U(sc.n, 3);
    conica_svg_scene_free(&sc);
    sel[1] = "nothing";
    REQUIRE(render(SVG("<g id='g'>" R "/></g>"), &rs, &w, &sc, &st) == CONICA_OK);
    CHECK_EQ_U(sc.n, 1);
    CHECK(strstr(w.last, "no element has id 'nothing'") != NULL);
    conica_svg_scene_free(&sc);
}

TEST_CASE("the flat scene document re-renders to the same scene", "[svg][render]")
{
    static const char text[] =
        "<svg xmlns='http://www.w3.org/2000/svg' width='40mm' height='20mm' viewBox='0 0 20 20'>"
        "<svg x='2' y='2' width='10' height='10' viewBox='0 0 1 1'><circle cx='.5' cy='.5' "
        "r='.5' fill='none' stroke='red' stroke-width='.1' stroke-dasharray='.1 .2'/></svg>"
        "<path d='M1 1 Q 5 5 9 1 C 1 2 3 4 5 5 A 2 3 30 1 0 8 8 Z' fill-rule='evenodd'/></svg>";
    conica_svg_scene a, b;
    conica_svg_doc *doc = NULL;
    conica_status st;
    char *buf = NULL;
    size_t len = 0, i, k;
    FILE *f;
    scene_of(text, "mm", &a, NULL);
    f = open_memstream(&buf, &len);
    REQUIRE(f != NULL);
    REQUIRE(conica_svg_scene_write(&a, f, &st) == CONICA_OK);
    fclose(f);
    REQUIRE(conica_svg_doc_load(buf, len, NULL, &doc, &st) == CONICA_OK);
    {
        conica_svg_render_settings rs = conica_svg_render_defaults();
        rs.unit = "mm";
        conica_svg_scene_init(&b);
        REQUIRE(conica_svg_render(doc, &rs, &b, &st) == CONICA_OK);
    }
    REQUIRE_EQ_U(b.n, a.n);
    CHECK_EQ(b.width, a.width);
    for (i = 0; i < a.n; i++) {
        REQUIRE_EQ_U(b.items[i].path.n, a.items[i].path.n);
        CHECK_EQ(b.items[i].fill, a.items[i].fill);
        CHECK_EQ(b.items[i].fill_rule, a.items[i].fill_rule);
        CHECK_EQ(b.items[i].stroke, a.items[i].stroke);
        CHECK_EQ(b.items[i].st.width, a.items[i].st.width);
        CHECK_EQ_U(b.items[i].st.ndash, a.items[i].st.ndash);
        CHECK_NEAR(b.items[i].ctm.a, a.items[i].ctm.a, 1e-15);
        CHECK_NEAR(b.items[i].ctm.e, a.items[i].ctm.e, 1e-14);
        for (k = 0; k < a.items[i].path.n; k++)
            CHECK_NEAR(b.items[i].path.seg[k].x1, a.items[i].path.seg[k].x1, 1e-14);
    }
    conica_svg_scene_free(&a);
    conica_svg_scene_free(&b);
    conica_svg_doc_free(doc);
    free(buf);
}

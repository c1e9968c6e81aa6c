/* SPDX-License-Identifier: MIT */
/* Regression tests for the findings of the fuzzers (tests/fuzz/) and the
 * hostile-input audit (README.md): each case is an input that once
 * crashed, hung or hit undefined behaviour. Under the sanitizer build
 * (make test-san) undefined behaviour aborts, so these cases fail there
 * until the code is right. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/bspline.h"
#include "conica/curve.h"
#include "conica/plot.h"
#include "conica/subdiv.h"
#include "conica_svg.h"
#include "conica_test.h"

static conica_code parse_spline(const char *text, conica_status *st)
{
    conica_bspline s;
    conica_bspline_init(&s);
    conica_code rc = conica_bspline_parse(text, strlen(text), &s, st);
    conica_bspline_free(&s);
    return rc;
}

TEST_CASE("spline parser: a huge or fractional degree is an error, not a cast overflow",
          "[reliability][fuzz]")
{
    conica_status st;
    /* fuzz_spline_parse: `degree 6666...6663` was converted to long (UB) */
    CHECK_EQ(parse_spline("degree 1e30\nknots 0 0 1 1\nc 0 0\nc 1 1\n", &st), CONICA_ERR_LIMIT);
    CHECK_EQ(st.line, 1);
    CHECK_EQ(parse_spline("degree -1e300\nknots 0 0 1 1\nc 0 0\nc 1 1\n", &st), CONICA_ERR_PARSE);
    CHECK_EQ(parse_spline("degree 2.5\nknots 0 0 1 1\nc 0 0\nc 1 1\n", &st), CONICA_ERR_PARSE);
    CHECK_EQ(parse_spline("degree 51\nknots 0 0 1 1\nc 0 0\nc 1 1\n", &st), CONICA_ERR_LIMIT);
    CHECK_EQ(parse_spline("degree 1\nknots 0 0 1 1\nc 0 0\nc 1 1\n", &st), CONICA_OK);
}

TEST_CASE("spline parser: caps on control points and degree (parse_ex)", "[reliability][limits]")
{
    const char *text = "degree 2\nknots 0 0 0 1 2 3 3 3\nc 0 0\nc 4 0\nc 6 3\nc 3 6\nc 0 3\n";
    const size_t len = strlen(text);
    conica_bspline_parse_limits lim = conica_bspline_parse_limits_defaults();
    conica_bspline s;
    conica_status st;
    CHECK_EQ_U(lim.max_ctrl, CONICA_BSPLINE_MAX_CTRL);
    CHECK_EQ(lim.max_degree, CONICA_BSPLINE_MAX_DEGREE);
    conica_bspline_init(&s);

    SECTION("five control points against a cap of four: LIMIT on the fifth, output untouched") {
        lim.max_ctrl = 4;
        CHECK_EQ(conica_bspline_parse_ex(text, len, &lim, &s, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(st.line, 7);
        CHECK(strstr(st.message, "more than 4 control points (max_ctrl)") != NULL);
        CHECK_EQ_U(s.n, 0);
        CHECK(s.knots == NULL);
    }
    SECTION("at the cap: accepted, same spline as conica_bspline_parse") {
        conica_bspline d;
        conica_bspline_init(&d);
        lim.max_ctrl = 5;
        lim.max_degree = 2;
        REQUIRE_EQ(conica_bspline_parse_ex(text, len, &lim, &s, &st), CONICA_OK);
        REQUIRE_EQ(conica_bspline_parse(text, len, &d, &st), CONICA_OK);
        REQUIRE_EQ_U(s.n, 5);
        CHECK_EQ_U(d.n, s.n);
        CHECK(memcmp(s.knots, d.knots, 8 * sizeof *s.knots) == 0);
        CHECK(memcmp(s.ctrl, d.ctrl, 10 * sizeof *s.ctrl) == 0);
        conica_bspline_free(&d);
    }
    SECTION("degree over a lowered cap: LIMIT on the degree line") {
        lim.max_degree = 1;
        CHECK_EQ(conica_bspline_parse_ex(text, len, &lim, &s, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(st.line, 1);
        CHECK(strstr(st.message, "degree 2 exceeds 1 (max_degree)") != NULL);
        /* a fractional degree is still a syntax error, not "exceeds" */
        const char *frac = "degree 1.5\nknots 0 0 1 1\nc 0 0\nc 1 1\n";
        CHECK_EQ(conica_bspline_parse_ex(frac, strlen(frac), &lim, &s, &st), CONICA_ERR_PARSE);
    }
    SECTION("knot and weight lines are capped at max_ctrl + max_degree + 1 values") {
        lim.max_ctrl = 3;
        lim.max_degree = 2; /* 6 values */
        const char *many = "degree 2\nknots 0 0 0 1 1 1 2\nc 0 0\n";
        CHECK_EQ(conica_bspline_parse_ex(many, strlen(many), &lim, &s, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(st.line, 2);
        const char *wts = "degree 1\nknots 0 0 1 1\nc 0 0\nc 1 1\nw 1 1 1 1 1 1 1\n";
        CHECK_EQ(conica_bspline_parse_ex(wts, strlen(wts), &lim, &s, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(st.line, 5);
    }
    SECTION("caps outside their range are CONICA_ERR_ARG; NULL caps are the defaults") {
        lim.max_ctrl = 0;
        CHECK_EQ(conica_bspline_parse_ex(text, len, &lim, &s, &st), CONICA_ERR_ARG);
        lim.max_ctrl = CONICA_BSPLINE_MAX_CTRL + 1;
        CHECK_EQ(conica_bspline_parse_ex(text, len, &lim, &s, &st), CONICA_ERR_ARG);
        lim = conica_bspline_parse_limits_defaults();
        lim.max_degree = CONICA_BSPLINE_MAX_DEGREE + 1;
        CHECK_EQ(conica_bspline_parse_ex(text, len, &lim, &s, &st), CONICA_ERR_ARG);
        lim.max_degree = 0;
        CHECK_EQ(conica_bspline_parse_ex(text, len, &lim, &s, &st), CONICA_ERR_ARG);
        CHECK_EQ_U(s.n, 0);
        CHECK_EQ(conica_bspline_parse_ex(text, len, NULL, &s, &st), CONICA_OK);
        CHECK_EQ_U(s.n, 5);
    }
    conica_bspline_free(&s);
}

TEST_CASE("curve parser: a zero normal is refused with its line", "[reliability][fuzz]")
{
    const char *text = "v 0 0\nv 1 0\nvn 0 0\nvn 0 1\n";
    conica_curve c;
    conica_status st;
    conica_curve_init(&c);
    CHECK_EQ(conica_curve_parse(text, strlen(text), &c, &st), CONICA_ERR_DEGENERATE);
    CHECK_EQ(st.line, 3);
    CHECK_EQ(c.n, 0);
    conica_curve_free(&c);
}

TEST_CASE("svg: entity declarations are refused at load", "[reliability][xml]")
{
    static const char *const docs[] = {
        "<?xml version=\"1.0\"?><!DOCTYPE svg [<!ENTITY x SYSTEM \"file:///etc/passwd\">]>"
        "<svg xmlns=\"http://www.w3.org/2000/svg\"><text>&x;</text></svg>",
        "<?xml version=\"1.0\"?><!DOCTYPE svg [<!ENTITY % p SYSTEM \"file:///etc/passwd\"> %p;]>"
        "<svg xmlns=\"http://www.w3.org/2000/svg\"/>",
        "<?xml version=\"1.0\"?><!DOCTYPE svg [<!ENTITY a \"aa\"><!ENTITY b \"&a;&a;\">]>"
        "<svg xmlns=\"http://www.w3.org/2000/svg\"><text>&b;</text></svg>",
    };
    for (size_t i = 0; i < sizeof docs / sizeof docs[0]; i++) {
        conica_svg_doc *doc = NULL;
        conica_status st;
        INFO("document %zu", i);
        CHECK_EQ(conica_svg_doc_load(docs[i], strlen(docs[i]), NULL, &doc, &st),
                 CONICA_ERR_UNSUPPORTED);
        CHECK(doc == NULL);
        conica_svg_doc_free(doc);
    }
}

TEST_CASE("subdivision: points near DBL_MAX give an error or finite points", "[reliability][fuzz]")
{
    /* fuzz_subdivide (regressions/subdivide/nonfinite-output-near-dblmax):
     * CONICA_OK with non-finite output points/normals. precise +
     * reference_compatible is enough: an edge point computed in long double
     * lies beyond DBL_MAX and becomes inf when rounded to the double output
     * (point 9, x). */
    const double xy[6] = {1.7976931348623157e308, 2.225073858507201e-308,
                          1.7976931348623157e308, 1.7976931348623157e308,
                          5e-324, 1.7976931348623157e308};
    conica_curve in, out;
    conica_status st;
    conica_curve_init(&in);
    conica_curve_init(&out);
    REQUIRE_EQ(conica_curve_set(xy, NULL, 3, 0, &in, &st), CONICA_OK);
    conica_subdiv_settings s = conica_subdiv_defaults();
    s.levels = 3;
    s.precise = 1;
    s.reference_compatible = 1;
    s.max_points = 1u << 14;
    conica_code rc = conica_subdivide(&in, &s, &out, NULL, &st);
    size_t bad = 0;
    if (rc == CONICA_OK)
        for (size_t i = 0; i < 2 * out.n; i++)
            bad += !isfinite(out.xy[i]) || !isfinite(out.nxy[i]);
    INFO("rc %d, %zu points", (int)rc, out.n);
    CHECK_EQ(bad, 0);
    conica_curve_free(&in);
    conica_curve_free(&out);
}

/* Plot a fuzz_plot finding with the guaranteed plotter and the settings
 * the fuzzer chose; the result is an error or finite points. */
static void plot_finding(int degree, const double *knots, size_t nk, const double *ctrl,
                         size_t n, double abs_tol, unsigned prephase)
{
    conica_bspline s;
    conica_polyline pl;
    conica_status st;
    conica_bspline_init(&s);
    conica_polyline_init(&pl);
    REQUIRE_EQ(conica_bspline_set(degree, 2, knots, nk, ctrl, n, NULL, &s, &st), CONICA_OK);
    conica_plot_settings set = conica_plot_defaults();
    set.method = CONICA_PLOT_GUARANTEED;
    set.output = CONICA_OUTPUT_CONTROL_POLYGON;
    set.abs_tolerance = abs_tol;
    set.pixel_tolerance = 3;
    set.prephase_knots = prephase;
    set.max_points = (size_t)1 << 13;
    set.max_knots = (size_t)1 << 12;
    set.max_iterations = (size_t)1 << 16;
    conica_code rc = conica_plot(&s, &set, &pl, NULL, &st);
    CAPTURE_I((int)rc);
    size_t bad = 0;
    if (rc == CONICA_OK)
        for (size_t i = 0; i < 2 * pl.n; i++)
            bad += isfinite(pl.xy[i]) ? 0u : 1u;
    CHECK_EQ_U(bad, 0);
    conica_polyline_free(&pl);
    conica_bspline_free(&s);
}

TEST_CASE("plot: a chord search at a full chain never runs past its last element",
          "[reliability][fuzz]")
{
    /* fuzz_plot (regressions/plot/c3-chain-end-0cf4c149, chain-end-e939bc40): the cubic and general
     * chord searches snapped a trial end to the piece's end although the
     * chain of BÃ©zier forms, full or at the knots' end, stopped short of
     * it; the search for the trial's element then ran past the chain
     * (SIGSEGV in c3_cross, pointer overflow in cross_search). */
    const double k3[] = {0, 0, 0, 0, 1, 2, 3, 4, 4.0000000000945874, 4.0000000001891749,
                         4.0000000002837623, 4.0000000002837623, 4.0000000002837623,
                         4.0000000002837623};
    const double c3[] = {1.8917489796876907e-10, 1.7976931348623157e+308,
                         2.8376234695315361e-10, 1.7976931348623157e+308,
                         3.7834979593753815e-10, 17,
                         4.7293724492192268e-10, 17.000000000094587,
                         5.6752469390630722e-10, 17.000000000189175,
                         6.6211214289069176e-10, 17.000000000283762,
                         7.5669959187507629e-10, 17.00000000037835,
                         0, 0, 0, 0, 0, 0};
    plot_finding(3, k3, 14, c3, 10, 0, 0);
    const double k2[] = {0, 0, 0, 1.625, 3.25, 4.875, 6.5, 6.5000000000727596,
                         6.5000000000727596, 6.5625000000727596, 6.5625000000727596,
                         8.3750000000727596, 8.3750000000727596, 8.3750000000727596,
                         9.3750000000727596, 11.00000000007276, 11.00000000007276,
                         11.00000000007276};
    const double c2[] = {0, 0, 4.9406564584124654e-324, 4.9406564584124654e-324,
                         4.9406564584124654e-324, 4.9406564584124654e-324,
                         4.9406564584124654e-324, 4.9406564584124654e-324,
                         4.9406564584124654e-324, 4.9406564584124654e-324,
                         4.9406564584124654e-324, 4.9406564584124654e-324,
                         4.9406564584124654e-324, 7.2759576141834259e-11,
                         7.2759576141834259e-11, 1.4551915228366852e-10,
                         1.4551915228366852e-10, 2.1827872842550278e-10,
                         2.1827872842550278e-10, 2.9103830456733704e-10,
                         12, 3.637978807091713e-10, 12, 7.2759576141834259e-11,
                         12.00000000007276, 7.0031092036515474e-11, 0, 0, 0, 0};
    plot_finding(2, k2, 18, c2, 15, 2.3283064365386963e-10, 7);
}

TEST_CASE("svg: coordinates near 1e176 end the flattener's chord search at the run's end",
          "[reliability][fuzz]")
{
    /* fuzz_svg_path (regressions/svg_path/flatten-1e176-d22ec294): a chord from
     * the run's end point to itself measured inf, so the greedy chord
     * search went on past the end of its list (pointer overflow, read past
     * the parameters). */
    static const char d[] =
        "M20 0H13 4 T5 63.4,83.4 300,35 316.5,82.3 366.6,83.4 326.6,113.7 3400000"
        "000000000000000000000000000000000000000000000000000000000000000000000000"
        "000000000000000000000000000000000000000000000000000000000000000000000000"
        "00000000000000000325984829,3 0 0 10,13309,161.6 273.4,113.7 233000000000"
        "000000000000000000000000000000000000000000000000000000000000000000000000"
        "000000000000000000000000000000000000000000000000000000000000000000000000"
        "00000000000000325984829,3 1.1,161.6 30063.4,83.4 300,35 316.5,82.3 366.6"
        ",83.4 326.6,113.7 341.1,161.6 300,133 258.13.0 0 15 0 0 1 13.4 300,35 31"
        "6.5,82.3 366.6,83.4 326.6,113.7 341.1,161.6 30063.4,83.4 300,35 316.5,82"
        ".3 3V20A15\000" "\000" "\000" "n 15 0 0 1 20; 5Z";
    conica_svg_path p;
    conica_svg_shapes sh;
    conica_status st;
    conica_svg_path_init(&p);
    conica_svg_shapes_init(&sh);
    REQUIRE_EQ(conica_svg_path_parse(d, sizeof d - 1, 4096, &p, &st), CONICA_OK);
    conica_svg_settings set = conica_svg_defaults();
    set.levels = 2; /* smoothing: its curves are flattened first */
    set.limits.max_points = 1u << 15;
    conica_code rc = conica_svg_path_polylines(&p, &set, &sh, &st);
    CAPTURE_I((int)rc);
    CHECK((rc == CONICA_OK || rc == CONICA_ERR_NONFINITE || rc == CONICA_ERR_LIMIT ||
           rc == CONICA_ERR_NUMERIC));
    conica_svg_shapes_free(&sh);
    conica_svg_path_free(&p);
}

TEST_CASE("svg: an arc at 1e44 gets no inflections from rounding noise", "[reliability][fuzz]")
{
    /* fuzz_svgsmooth (regressions/svgsmooth/inflection-noise-1e44-159290ea):
     * the turning of an arc piece sampled at coordinates near 1e44 changed
     * sign with rounding, up to 21 "inflections" per segment, and the
     * smoothing's sample list (sized for 7 per segment) overflowed. A
     * conic arc never inflects; the list is sized by the real bound. */
    static const char doc_text[] =
        "<?x-deml version=\"deml version=\"1.0\" encoding=\"UTF-8\"?>\n<!--"
        " A mountingert ckab, 80 x 50 mm-->\n<svg xmlnw=\"http://www.w2"
        ".org/2000(/svg\" width=\"80mm\" height=\"50mm\" viewBox=\"0 0 80 5"
        "0\">\n  <path id=\"bracket\" fill=\"#4a7ab5\" fill-rule=\"evenodd\"\n"
        "        d=\"M 6,50 A 6,6 0 0 1 0,3333333333333333333333333333"
        "33333333333333333s33333333333333333333333333333333333333333-"
        "333333333333333333333333333333333-3333,20\n       3 0 0 1 50,"
        "43 H 30 A  \r \r\r       \r   3,3 0 0 1 30,07 Z\"/>\n</svg>\n \r ";
    for (int levels = 0; levels <= 4; levels++) {
        conica_svg_doc *doc = NULL;
        conica_svg_shapes sh;
        conica_status st;
        conica_svg_settings set = conica_svg_defaults();
        REQUIRE_EQ(conica_svg_doc_load(doc_text, sizeof doc_text - 1, NULL, &doc, &st), CONICA_OK);
        set.levels = levels;
        set.limits.max_points = 1u << 15;
        conica_svg_shapes_init(&sh);
        conica_code rc = conica_svg_extract(doc, &set, &sh, &st);
        CAPTURE_I(levels);
        CAPTURE_I((int)rc);
        CHECK((rc == CONICA_OK || rc == CONICA_ERR_NONFINITE || rc == CONICA_ERR_LIMIT ||
               rc == CONICA_ERR_NUMERIC));
        conica_svg_shapes_free(&sh);
        conica_svg_doc_free(doc);
    }
}

/* Last: a crash here (SIGSEGV before the fix) must not hide the cases above. */
TEST_CASE("plot deviation: a polyline reaching infinity does not index the grid with NaN",
          "[reliability][fuzz]")
{
    /* fuzz_plot: conica_plot_deviation cast NaN cell coordinates to size_t */
    const double knots[] = {0, 0, 1, 1}, ctrl[] = {0, 0, 1, 1};
    conica_bspline s;
    conica_polyline pl;
    conica_status st;
    double xy[4] = {0, 0, INFINITY, 1};
    size_t start = 0;
    conica_bspline_init(&s);
    REQUIRE_EQ(conica_bspline_set(1, 2, knots, 4, ctrl, 2, NULL, &s, &st), CONICA_OK);
    conica_polyline_init(&pl);
    pl.n = 2;
    pl.dim = 2;
    pl.xy = xy;
    pl.npieces = 1;
    pl.piece_start = &start;
    double c2p = 0, p2c = 0;
    conica_code rc = conica_plot_deviation(&s, &pl, 8, &c2p, &p2c, &st);
    CHECK((rc == CONICA_OK || rc == CONICA_ERR_NONFINITE || rc == CONICA_ERR_ARG));
    conica_bspline_free(&s);
}

TEST_CASE("plot: an evaluation that fails never leaves a point unwritten",
          "[reliability][fuzz]")
{
    /* memcheck (scripts/memcheck.sh): knots near DBL_MAX made
     * conica_bspline_eval fail inside the Mathematica-style sampler, which
     * printed the caller's uninitialised buffer with exit 0. Every method
     * must give an error, or points inside the control points' bounding box
     * (the convex hull property, Lemma 1.13 of Dahl 2019). */
    const double knots[] = {0, 0, 0, 1e308, 1.7e308, 1.7e308, 1.7e308};
    const double ctrl[] = {0, 0, 1, 1, 2, 0, 3, 1};
    const conica_plot_method methods[] = {
        CONICA_PLOT_GUARANTEED, CONICA_PLOT_ADAPTIVE, CONICA_PLOT_UNIFORM,
        CONICA_PLOT_LOCAL_UNIFORM, CONICA_PLOT_CHAIKIN, CONICA_PLOT_LANE_RIESENFELD,
        CONICA_PLOT_MATHEMATICA};
    conica_bspline s;
    conica_status st;
    conica_bspline_init(&s);
    REQUIRE_EQ(conica_bspline_set(2, 2, knots, 7, ctrl, 4, NULL, &s, &st), CONICA_OK);
    for (size_t m = 0; m < sizeof methods / sizeof methods[0]; m++) {
        conica_plot_settings set = conica_plot_defaults();
        set.method = methods[m];
        set.abs_tolerance = 1e-3;
        conica_polyline pl;
        conica_polyline_init(&pl);
        conica_code rc = conica_plot(&s, &set, &pl, NULL, &st);
        CAPTURE_I((int)m);
        CAPTURE_I((int)rc);
        CHECK((rc == CONICA_OK || rc == CONICA_ERR_NUMERIC));
        if (rc == CONICA_OK) {
            size_t outside = 0;
            for (size_t i = 0; i < pl.n; i++) {
                double x = pl.xy[2 * i], y = pl.xy[2 * i + 1];
                outside += !(x >= 0 && x <= 3 && y >= 0 && y <= 1);
            }
            CHECK_EQ_U(outside, 0);
        }
        conica_polyline_free(&pl);
    }
    conica_bspline_free(&s);
}

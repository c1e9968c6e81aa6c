/* SPDX-License-Identifier: MIT */
/* Regression tests of the hostile-input battery of issue 33 on the C API:
 * sizes and counts at SIZE_MAX, tolerances finer than the coordinates
 * resolve, float-to-size_t conversions of huge values. Each case once hit
 * undefined behaviour (UBSan: float-cast-overflow), a wrapped allocation
 * (ASan: heap-buffer-overflow) or a hang; under the sanitizer build (make
 * test-san) they abort until the code is right, in the release build they
 * check the status and message. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/bspline.h"
#include "conica/curve.h"
#include "conica/path.h"
#include "conica/plot.h"
#include "conica/subdiv.h"
#include "conica_test.h"

/* A cubic with 4 control points on [0, 1]. */
static void cubic(conica_bspline *s)
{
    const double knots[] = {0, 0, 0, 0, 1, 1, 1, 1};
    const double ctrl[] = {0, 0, 1, 2, 2, -1, 3, 0};
    conica_status st;
    conica_bspline_init(s);
    REQUIRE_EQ(conica_bspline_set(3, 2, knots, 8, ctrl, 4, NULL, s, &st), CONICA_OK);
}

TEST_CASE("plot deviation: samples = SIZE_MAX is a limit, not a wrapped allocation",
          "[hostile][overflow]")
{
    conica_bspline s;
    conica_status st;
    cubic(&s);
    conica_plot_settings set = conica_plot_defaults();
    set.abs_tolerance = 1e-2;
    conica_polyline pl;
    conica_polyline_init(&pl);
    REQUIRE_EQ(conica_plot(&s, &set, &pl, NULL, &st), CONICA_OK);
    double c2p = -1, p2c = -1;
    SECTION("the local measure (the polyline has parameters)") {
        REQUIRE(pl.t != NULL);
        CHECK_EQ(conica_plot_deviation(&s, &pl, SIZE_MAX, &c2p, &p2c, &st), CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "samples per chord exceed the limit") != NULL);
        CHECK_EQ(c2p, -1);
        CHECK_EQ(conica_plot_deviation(&s, &pl, 64, &c2p, &p2c, &st), CONICA_OK);
        CHECK_LE(c2p, 1e-2);
    }
    SECTION("the global measure (no parameters)") {
        free(pl.t);
        pl.t = NULL;
        CHECK_EQ(conica_plot_deviation(&s, &pl, SIZE_MAX, &c2p, &p2c, &st), CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "exceed the limit") != NULL);
        CHECK_EQ(conica_plot_deviation(&s, &pl, SIZE_MAX / 2 + 7, &c2p, &p2c, &st),
                 CONICA_ERR_LIMIT);
        CHECK_EQ(conica_plot_deviation(&s, &pl, 1000, &c2p, &p2c, &st), CONICA_OK);
        CHECK_LE(c2p, 1e-2 * (1 + 1e-9));
    }
    conica_polyline_free(&pl);
    conica_bspline_free(&s);
}

TEST_CASE("plot: Mathematica N0 = SIZE_MAX is refused, never cast or wrapped",
          "[hostile][overflow]")
{
    /* plot_baselines.c's share of N0 per piece: (size_t)(2^64) was UB, and
     * the release build returned CONICA_OK with a 2-point polyline */
    conica_bspline s;
    conica_status st;
    cubic(&s);
    const size_t n0s[] = {SIZE_MAX, SIZE_MAX - 1, SIZE_MAX / 2, (size_t)1 << 40};
    for (size_t i = 0; i < sizeof n0s / sizeof n0s[0]; i++) {
        conica_plot_settings set = conica_plot_defaults();
        set.method = CONICA_PLOT_MATHEMATICA;
        set.math_initial_points = n0s[i];
        conica_polyline pl;
        conica_polyline_init(&pl);
        CAPTURE_U(n0s[i]);
        CHECK_EQ(conica_plot(&s, &set, &pl, NULL, &st), CONICA_ERR_LIMIT);
        CHECK(strstr(st.message, "exceed max_points") != NULL);
        CHECK_EQ_U(pl.n, 0);
        conica_polyline_free(&pl);
    }
    /* the cap itself is accepted and gives at least N0 points */
    conica_plot_settings set = conica_plot_defaults();
    set.method = CONICA_PLOT_MATHEMATICA;
    set.max_points = 5000;
    set.math_initial_points = 5000;
    set.math_max_recursion = 0;
    conica_polyline pl;
    conica_polyline_init(&pl);
    CHECK_EQ(conica_plot(&s, &set, &pl, NULL, &st), CONICA_OK);
    CHECK_EQ_U(pl.n, 5000);
    conica_polyline_free(&pl);
    conica_bspline_free(&s);
}

/* A bilinear 2 x 2 patch (the unit square lifted at one corner). */
static void bilinear(conica_bspline_surface *sf, double scale)
{
    const double k[] = {0, 0, 1, 1};
    double c[] = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 1};
    conica_status st;
    for (size_t i = 0; i < 12; i++)
        c[i] *= scale;
    conica_bspline_surface_init(sf);
    REQUIRE_EQ(conica_bspline_surface_set(1, 1, 3, k, 4, k, 4, c, 2, 2, NULL, sf, &st),
               CONICA_OK);
}

TEST_CASE("surface: a tolerance finer than the coordinates resolve is refused at once",
          "[hostile][overflow][surface]")
{
    /* _conica.surface(tolerance=1e-300) on a bilinear patch: UBSan
     * "5e+149 is outside the range of representable values of type
     * 'unsigned long'" (surface.c), 378 s of CPU in the release build;
     * 1e-16 gave a LimitError only after ~34 s */
    const double tols[] = {1e-300, 1e-200, 1e-16, 1e-15, 5e-324};
    const double scales[] = {1.0, 1e-6, 1e6, 1e300};
    for (size_t k = 0; k < sizeof scales / sizeof scales[0]; k++) {
        conica_bspline_surface sf;
        bilinear(&sf, scales[k]);
        for (size_t i = 0; i < sizeof tols / sizeof tols[0]; i++) {
            conica_plot_settings set = conica_plot_defaults();
            set.abs_tolerance = tols[i] * scales[k];
            if (!(set.abs_tolerance > 0))
                set.abs_tolerance = 5e-324;
            conica_quadgrid g;
            conica_quadgrid_init(&g);
            conica_status st;
            CAPTURE_D(scales[k]);
            CAPTURE_D(set.abs_tolerance);
            CHECK_EQ(conica_plot_surface_certified(&sf, &set, &g, NULL, &st), CONICA_ERR_LIMIT);
            CHECK(strstr(st.message, "below what the coordinates resolve") != NULL);
            CHECK_EQ(conica_plot_surface(&sf, &set, &g, NULL, &st), CONICA_ERR_LIMIT);
            CHECK_EQ(conica_plot_surface_envelope(&sf, &set, &g, NULL, &st), CONICA_ERR_LIMIT);
            CHECK_EQ_U(g.nu, 0);
            conica_quadgrid_free(&g);
        }
        if (scales[k] > 1e100) { /* squares of the coordinates overflow */
            conica_bspline_surface_free(&sf);
            continue;
        }
        /* a tolerance the coordinates do resolve still works: 1e-3 of the
         * size */
        conica_plot_settings set = conica_plot_defaults();
        set.abs_tolerance = 1e-3 * scales[k];
        conica_quadgrid g;
        conica_quadgrid_init(&g);
        conica_status st;
        CAPTURE_D(scales[k]);
        CHECK_EQ(conica_plot_surface_certified(&sf, &set, &g, NULL, &st), CONICA_OK);
        conica_quadgrid_free(&g);
        /* just above the floor: the point cap answers, quickly, no cast of
         * a huge count */
        set.abs_tolerance = 1e-13 * scales[k];
        set.max_points = 1 << 12;
        conica_code rc = conica_plot_surface_certified(&sf, &set, &g, NULL, &st);
        CHECK((rc == CONICA_OK || rc == CONICA_ERR_LIMIT));
        conica_quadgrid_free(&g);
        conica_bspline_surface_free(&sf);
    }
}

TEST_CASE("surface: max_points = SIZE_MAX never wraps a grid product",
          "[hostile][overflow][surface]")
{
    conica_bspline_surface sf;
    bilinear(&sf, 1.0);
    conica_plot_settings set = conica_plot_defaults();
    set.abs_tolerance = 1e-3;
    set.max_points = SIZE_MAX;
    conica_quadgrid g;
    conica_quadgrid_init(&g);
    conica_status st;
    conica_code rc = conica_plot_surface_certified(&sf, &set, &g, NULL, &st);
    CHECK((rc == CONICA_OK || rc == CONICA_ERR_LIMIT));
    conica_quadgrid_free(&g);
    conica_bspline_surface_free(&sf);
}

/* A rational quadratic chain of n conic arcs (every interior knot of
 * multiplicity 2 = the degree: a corner knot) with weights w_odd. */
static void conic_chain(size_t n, conica_bspline *s)
{
    size_t nc = 2 * n + 1, nk = nc + 3, k = 0;
    double *knots = malloc(nk * sizeof *knots), *ctrl = malloc(2 * nc * sizeof *ctrl);
    double *w = malloc(nc * sizeof *w);
    conica_status st;
    REQUIRE((knots && ctrl && w));
    knots[k++] = 0;
    knots[k++] = 0;
    knots[k++] = 0;
    for (size_t i = 1; i < n; i++) {
        knots[k++] = (double)i;
        knots[k++] = (double)i;
    }
    knots[k++] = (double)n;
    knots[k++] = (double)n;
    knots[k++] = (double)n;
    for (size_t i = 0; i < nc; i++) {
        ctrl[2 * i] = 0.5 * (double)i;
        ctrl[2 * i + 1] = i % 2 ? 1.0 + 0.1 * (double)(i % 7) : 0.0;
        w[i] = i % 2 ? 0.70710678118654752 : 1.0;
    }
    conica_bspline_init(s);
    REQUIRE_EQ(conica_bspline_set(2, 2, knots, nk, ctrl, nc, w, s, &st), CONICA_OK);
    free(knots);
    free(ctrl);
    free(w);
}

TEST_CASE("plot: corner knots are raised exactly as Boehm's insertion raises them",
          "[hostile][corners]")
{
    /* issue 33: conica plot on many corner knots was quadratic (one
     * insertion and array shift per corner; 100 000 corners: 64 s with
     * --method uniform); they are now raised in one pass. The plot of the
     * spline must be the plot of the same spline whose corners the caller
     * raised beforehand with conica_bspline_insert_knot. */
    const conica_plot_method methods[] = {CONICA_PLOT_GUARANTEED, CONICA_PLOT_UNIFORM,
                                          CONICA_PLOT_ADAPTIVE, CONICA_PLOT_CHAIKIN,
                                          CONICA_PLOT_MATHEMATICA};
    conica_bspline a, b;
    conica_status st;
    conic_chain(40, &a);
    conic_chain(40, &b);
    for (size_t i = 1; i < 40; i++)
        REQUIRE_EQ(conica_bspline_insert_knot(&b, (double)i, &st), CONICA_OK);
    REQUIRE_EQ_U(b.n, a.n + 39);
    for (size_t m = 0; m < sizeof methods / sizeof methods[0]; m++) {
        conica_plot_settings set = conica_plot_defaults();
        set.method = methods[m];
        set.abs_tolerance = 1e-4;
        conica_polyline pa, pb;
        conica_polyline_init(&pa);
        conica_polyline_init(&pb);
        CAPTURE_I((int)m);
        REQUIRE_EQ(conica_plot(&a, &set, &pa, NULL, &st), CONICA_OK);
        REQUIRE_EQ(conica_plot(&b, &set, &pb, NULL, &st), CONICA_OK);
        REQUIRE_EQ_U(pa.n, pb.n);
        /* equal up to the rounding of x w / w in the caller's insertion
         * (the one-pass raise copies the corner point itself) */
        double worst = 0;
        for (size_t i = 0; i < 2 * pa.n; i++)
            worst = fmax(worst, fabs(pa.xy[i] - pb.xy[i]));
        CHECK_LE(worst, 1e-13);
        /* the curve passes through every corner control point */
        size_t hit = 0;
        for (size_t c = 2; c + 2 < a.n; c += 2)
            for (size_t i = 0; i < pa.n; i++)
                if (pa.xy[2 * i] == a.ctrl[2 * c] && pa.xy[2 * i + 1] == a.ctrl[2 * c + 1]) {
                    hit++;
                    break;
                }
        CHECK_EQ_U(hit, 39);
        conica_polyline_free(&pa);
        conica_polyline_free(&pb);
    }
    conica_bspline_free(&a);
    conica_bspline_free(&b);
}

TEST_CASE("curve write: a full disk is an error, not CONICA_OK", "[hostile][io]")
{
    /* the points sat in stdio's buffer: /dev/full failed only at fclose */
    FILE *f = fopen("/dev/full", "w");
    if (!f) {
        WARN("no /dev/full here: skipped");
        return;
    }
    double xy[] = {0, 0, 1, 0, 1, 1};
    conica_curve c;
    conica_curve_init(&c);
    c.n = 3;
    c.xy = xy;
    conica_status st;
    CHECK_EQ(conica_curve_write(f, &c, &st), CONICA_ERR_IO);
    CHECK(strstr(st.message, "No space left on device") != NULL);
    fclose(f);
}

TEST_CASE("path arc: a sweep beyond a full turn is refused", "[hostile][path]")
{
    conica_path p;
    conica_status st;
    conica_path_init(&p);
    REQUIRE_EQ(conica_path_move_to(&p, 1, 0, 0, &st), CONICA_OK);
    /* the header says |dtheta| <= 2 pi; 100 rad became a silent line */
    CHECK_EQ(conica_path_arc_to(&p, 0, 0, 1, 1, 0, 0, 100.0, 1, 0, 0, &st), CONICA_ERR_ARG);
    CHECK(strstr(st.message, "exceeds a full turn") != NULL);
    CHECK_EQ(conica_path_arc_to(&p, 0, 0, 1, 1, 0, 0, -7.0, 1, 0, 0, &st), CONICA_ERR_ARG);
    /* a full turn with rounding passes */
    CHECK_EQ(conica_path_arc_to(&p, 0, 0, 1, 1, 0, 0, 2 * 3.14159265358979323846 * (1 + 1e-14),
                                1, 0, 0, &st),
             CONICA_OK);
    conica_path_free(&p);
}

/* a * b + c as the build evaluates it (not inlined into a constant) */
static double mul_add(double a, double b, double c)
{
    return a * b + c;
}

TEST_CASE("build: no silent fma contraction, so gcc and clang builds round alike",
          "[hostile][build]")
{
    /* issue 33: the release (gcc) and sanitizer (clang) builds disagreed on
     * an arc of radius ~2e161: clang contracted a*b+c into one fma, gcc in
     * C11 mode does not. With -ffp-contract=off both round the product:
     * (1 + 2^-30)(1 - 2^-30) = 1 - 2^-60 rounds to 1, and 1 - 1 is 0; a
     * contracted fma would give -2^-60. The inputs come from strtod so no
     * compiler folds them. */
    double a = strtod("1.000000000931322574615478515625", NULL); /* 1 + 2^-30 */
    double b = strtod("0.999999999068677425384521484375", NULL); /* 1 - 2^-30 */
    CHECK_EQ(mul_add(a, b, -1.0), 0.0);
}

TEST_CASE("subdivision: huge or tiny but valid normals count by their direction",
          "[hostile][normals]")
{
    /* `vn 1e308 0.65` and Python's [5e-324]*24 were refused as "point 2 of
     * the output is not finite or has no normal": their squares overflow or
     * vanish in the fit, which only needs directions */
    double xy[] = {0, 0, 1, 0, 1, 1, 0, 1};
    double unit[] = {-1, -1, 1, -1, 1, 1, -1, 1};
    const double scales[] = {5e-324, 1e-300, 1e300, 1.7e308};
    conica_subdiv_settings set = conica_subdiv_defaults();
    set.levels = 3;
    conica_curve in, ref;
    conica_status st;
    conica_curve_init(&in);
    conica_curve_init(&ref);
    REQUIRE_EQ(conica_curve_set(xy, unit, 4, 1, &in, &st), CONICA_OK);
    REQUIRE_EQ(conica_subdivide(&in, &set, &ref, NULL, &st), CONICA_OK);
    for (size_t k = 0; k < sizeof scales / sizeof scales[0]; k++) {
        double nn[8];
        for (size_t i = 0; i < 8; i++)
            nn[i] = unit[i] * scales[k];
        conica_curve c, out;
        conica_curve_init(&c);
        conica_curve_init(&out);
        REQUIRE_EQ(conica_curve_set(xy, nn, 4, 1, &c, &st), CONICA_OK);
        CAPTURE_D(scales[k]);
        CHECK_EQ(conica_subdivide(&c, &set, &out, NULL, &st), CONICA_OK);
        REQUIRE_EQ_U(out.n, ref.n);
        /* the same directions, up to the rounding of the scaled normal */
        double worst = 0;
        for (size_t i = 0; i < 2 * out.n; i++)
            worst = fmax(worst, fabs(out.xy[i] - ref.xy[i]));
        CHECK_LE(worst, 1e-12);
        conica_curve_free(&c);
        conica_curve_free(&out);
    }
    /* one huge normal among unit ones: the direction (1, 0) essentially */
    double mixed[] = {1e308, -0.65, 1, -1, 1, 1, -1, 1};
    conica_curve c, out;
    conica_curve_init(&c);
    conica_curve_init(&out);
    REQUIRE_EQ(conica_curve_set(xy, mixed, 4, 1, &c, &st), CONICA_OK);
    CHECK_EQ(conica_subdivide(&c, &set, &out, NULL, &st), CONICA_OK);
    conica_curve_free(&c);
    conica_curve_free(&out);
    conica_curve_free(&in);
    conica_curve_free(&ref);
}

TEST_CASE("path samples: the cap is checked before any value is read", "[hostile][path]")
{
    /* conica_path_samples read all 2n values before it checked its cap:
     * with n = SIZE_MAX / 2 + 1 the loop bound 2n wrapped, and a huge n
     * read far past the caller's array. A two-value array and a huge n
     * must give CONICA_ERR_LIMIT without touching xy beyond it (ASan). */
    double xy[4] = {0, 0, 1, 1};
    conica_path p;
    conica_status st;
    conica_path_init(&p);
    CHECK_EQ(conica_path_samples(&p, xy, NULL, SIZE_MAX / 2 + 1, 0, 0, &st), CONICA_ERR_LIMIT);
    CHECK_EQ(conica_path_samples(&p, xy, NULL, (size_t)1 << 40, 0, 0, &st), CONICA_ERR_LIMIT);
    CHECK(strstr(st.message, "exceed the path's limit") != NULL);
    CHECK_EQ(conica_path_samples(&p, xy, NULL, 2, 0, 0, &st), CONICA_OK);
    conica_path_free(&p);
}

TEST_CASE("spline queries without a status: NULL and empty splines are safe", "[hostile][api]")
{
    /* each of these crashed on NULL or an initialised, never set spline */
    conica_bspline e;
    conica_bspline_init(&e);
    double a = 0, b = 0, out[4] = {7, 7, 7, 7};
    CHECK_EQ_U(conica_bspline_find_span(NULL, 0.5), 0);
    CHECK_EQ_U(conica_bspline_find_span(&e, 0.5), 0);
    CHECK_EQ_U(conica_bspline_bezier_count(NULL), 0);
    CHECK_EQ_U(conica_bspline_bezier_count(&e), 0);
    conica_bspline_domain(&e, &a, &b);
    CHECK((isnan(a) && isnan(b)));
    conica_bspline_domain(NULL, &a, NULL);
    CHECK(isnan(a));
    conica_bspline_knot_averages(&e, out);
    conica_bspline_knot_averages(NULL, out);
    conica_bspline_control_polygon(&e, out);
    conica_bspline_control_polygon(NULL, out);
    CHECK_EQ(out[0], 7);
    CHECK_EQ(conica_bspline_point_dim(NULL), 0);
    conica_plot_settings set = conica_plot_defaults();
    CHECK(isnan(conica_plot_tolerance(NULL, &set)));
    CHECK(isnan(conica_plot_tolerance(&e, NULL)));
    /* a real spline still answers */
    conica_bspline s;
    cubic(&s);
    CHECK_EQ_U(conica_bspline_bezier_count(&s), 1);
    CHECK_EQ_U(conica_bspline_find_span(&s, 0.5), 3);
    conica_bspline_domain(&s, &a, &b);
    CHECK((a == 0 && b == 1));
    conica_bspline_free(&s);
}

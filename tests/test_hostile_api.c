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
#include "conica/plot.h"
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

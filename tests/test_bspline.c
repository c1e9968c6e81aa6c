/* SPDX-License-Identifier: MIT */
/* B-spline toolkit (Dahl 2019, Ch. 1): validation and preprocessing,
 * the triangular algorithm against the direct Cox-de Boor recursion,
 * derivatives against finite differences, Böhm insertion leaving the
 * spline unchanged, Bézier conversion round trips, the .spl parser. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/bspline.h"
#include "conica_test.h"

/* Cox-de Boor recursion (1.1)-(1.2) with 0/0 = 0; the last non-empty
 * interval is closed on the right so the end of the domain evaluates. */
static double cox(const double *t, size_t nk, size_t j, int p, double x, size_t last_span)
{
    if (p == 0) {
        if (t[j] <= x && x < t[j + 1])
            return 1.0;
        return (j == last_span && x == t[j + 1]) ? 1.0 : 0.0;
    }
    double r = 0;
    double d1 = t[j + (size_t)p] - t[j], d2 = t[j + (size_t)p + 1] - t[j + 1];
    if (d1 > 0)
        r += (x - t[j]) / d1 * cox(t, nk, j, p - 1, x, last_span);
    if (d2 > 0)
        r += (t[j + (size_t)p + 1] - x) / d2 * cox(t, nk, j + 1, p - 1, x, last_span);
    return r;
}

static void direct_eval(const conica_bspline *s, double x, double *out)
{
    size_t nk = s->n + (size_t)s->degree + 1, last = s->n - 1;
    while (!(s->knots[last] < s->knots[last + 1]))
        last--;
    double num[3] = {0, 0, 0}, den = 0;
    for (size_t j = 0; j < s->n; j++) {
        double b = cox(s->knots, nk, j, s->degree, x, last);
        double w = s->w ? s->w[j] : 1.0;
        for (int c = 0; c < s->dim; c++)
            num[c] += b * w * s->ctrl[j * (size_t)s->dim + (size_t)c];
        den += b * w;
    }
    for (int c = 0; c < s->dim; c++) /* no partition of unity off a regular vector */
        out[c] = s->w ? num[c] / den : num[c];
}

/* Random clamped spline with interior multiplicities up to p. */
static void random_spline(ct_rng *r, int p, int dim, size_t n, int rational, conica_bspline *s)
{
    size_t nk = n + (size_t)p + 1;
    double *k = malloc(nk * sizeof *k), *c = malloc(n * (size_t)dim * sizeof *c);
    double *w = malloc(n * sizeof *w);
    for (size_t i = 0; i <= (size_t)p; i++) {
        k[i] = 0.0;
        k[nk - 1 - i] = 10.0;
    }
    size_t i = (size_t)p + 1;
    while (i < n) {
        double z = ct_rng_range(r, 0.0, 10.0);
        size_t m = 1 + (size_t)(ct_rng_uniform(r) * (double)p);
        for (size_t q = 0; q < m && i < n; q++)
            k[i++] = z;
    }
    /* sort the interior */
    for (size_t a = (size_t)p + 1; a < n; a++)
        for (size_t b = a + 1; b < n; b++)
            if (k[b] < k[a]) {
                double tmp = k[a];
                k[a] = k[b];
                k[b] = tmp;
            }
    for (size_t q = 0; q < n * (size_t)dim; q++)
        c[q] = ct_rng_range(r, -5.0, 5.0);
    for (size_t q = 0; q < n; q++)
        w[q] = ct_rng_range(r, 0.3, 3.0);
    conica_bspline_init(s);
    conica_status st;
    conica_code rc = conica_bspline_set(p, dim, k, nk, c, n, rational ? w : NULL, s, &st);
    if (rc != CONICA_OK)
        INFO("set: %s", st.message);
    REQUIRE_EQ(rc, CONICA_OK);
    free(k);
    free(c);
    free(w);
}

TEST_CASE("set rejects inconsistent splines", "[bspline][validate]")
{
    conica_bspline s;
    conica_bspline_init(&s);
    conica_status st;
    const double k[] = {0, 0, 0, 1, 2, 2, 2};
    const double c[] = {0, 1, 2, 3};
    CHECK_EQ(conica_bspline_set(2, 1, k, 7, c, 4, NULL, &s, &st), CONICA_OK);
    SECTION("wrong knot count")
    {
        CHECK_EQ(conica_bspline_set(2, 1, k, 6, c, 4, NULL, &s, &st), CONICA_ERR_ARG);
    }
    SECTION("decreasing knots")
    {
        const double kd[] = {0, 0, 0, 1.5, 1, 2, 2};
        CHECK_EQ(conica_bspline_set(2, 1, kd, 7, c, 4, NULL, &s, &st), CONICA_ERR_ARG);
        CHECK_EQ_U(st.offset, 4);
    }
    SECTION("multiplicity above p+1")
    {
        const double km[] = {0, 0, 0, 0, 2, 2, 2};
        CHECK_EQ(conica_bspline_set(2, 1, km, 7, c, 4, NULL, &s, &st), CONICA_ERR_ARG);
    }
    SECTION("weights and NaN")
    {
        const double w0[] = {1, 0, 1, 1}, wn[] = {1, 1, -2, 1};
        CHECK_EQ(conica_bspline_set(2, 1, k, 7, c, 4, w0, &s, &st), CONICA_ERR_ARG);
        CHECK_EQ(conica_bspline_set(2, 1, k, 7, c, 4, wn, &s, &st), CONICA_ERR_ARG);
        const double cn[] = {0, NAN, 2, 3};
        CHECK_EQ(conica_bspline_set(2, 1, k, 7, cn, 4, NULL, &s, &st), CONICA_ERR_NONFINITE);
        CHECK_EQ_U(st.offset, 1);
    }
    SECTION("degree limits")
    {
        CHECK_EQ(conica_bspline_set(0, 1, k, 7, c, 4, NULL, &s, &st), CONICA_ERR_ARG);
        CHECK_EQ(conica_bspline_set(51, 1, k, 7, c, 4, NULL, &s, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(conica_bspline_set(4, 1, k, 7, c, 4, NULL, &s, &st), CONICA_ERR_ARG);
    }
    SECTION("output untouched on failure")
    {
        CHECK_EQ(conica_bspline_set(2, 1, k, 5, c, 4, NULL, &s, &st), CONICA_ERR_ARG);
        CHECK_EQ_U(s.n, 4);
        CHECK_EQ(s.degree, 2);
    }
    conica_bspline_free(&s);
}

TEST_CASE("preprocessing: Dahl 2019's worked example (§1.1.2)", "[bspline][regular]")
{
    const double t[] = {0, 0, 1, 1, 1, 1, 2, 2, 2};
    const double c[] = {1, 3, 2, 5, 4, 2};
    conica_bspline s;
    conica_bspline_init(&s);
    conica_status st;
    REQUIRE_EQ(conica_bspline_make_regular(2, 1, t, 9, c, 6, NULL, &s, &st), CONICA_OK);
    const double te[] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    const double ce[] = {0, 1, 3, 5, 4, 2};
    REQUIRE_EQ_U(s.n, 6);
    for (size_t i = 0; i < 9; i++)
        CHECK_EQ(s.knots[i] == te[i], 1);
    for (size_t i = 0; i < 6; i++)
        CHECK_NEAR(s.ctrl[i], ce[i], 0);
    /* the function is the same (zero coefficient on the new B-spline, the
     * dropped one had empty support): compare with the raw sum */
    conica_bspline raw = {2, 1, 6, (double *)t, (double *)c, NULL};
    for (int q = 0; q < 40; q++) {
        double x = q / 20.0, a, b;
        conica_bspline_eval(&s, x, &a, NULL);
        direct_eval(&raw, x, &b);
        CHECK_NEAR(a, b, 1e-14);
    }
    conica_bspline_free(&s);
}

TEST_CASE("knot averages and control polygon (Def. 1.10-1.12)", "[bspline]")
{
    const double t[] = {0, 0, 0, 1, 1, 2, 2, 3, 3, 3};
    const double c[] = {-2, -1, 0, 1, -3, 0, 2};
    conica_bspline s;
    conica_bspline_init(&s);
    REQUIRE_EQ(conica_bspline_set(2, 1, t, 10, c, 7, NULL, &s, NULL), CONICA_OK);
    double ts[7], P[14];
    conica_bspline_knot_averages(&s, ts);
    const double te[] = {0, 0.5, 1, 1.5, 2, 2.5, 3};
    for (int i = 0; i < 7; i++)
        CHECK_NEAR(ts[i], te[i], 1e-15);
    conica_bspline_control_polygon(&s, P);
    CHECK_NEAR(P[8], 2.0, 1e-15);
    CHECK_NEAR(P[9], -3.0, 0);
    /* Lemma 1.11: at a knot of multiplicity p the spline interpolates */
    double v;
    conica_bspline_eval(&s, 1.0, &v, NULL);
    CHECK_NEAR(v, 0.0, 1e-15);
    conica_bspline_eval(&s, 2.0, &v, NULL);
    CHECK_NEAR(v, -3.0, 1e-15);
    CHECK_EQ(conica_bspline_point_dim(&s), 2);
    conica_bspline_free(&s);
}

TEST_CASE("triangular algorithm matches the Cox-de Boor recursion", "[bspline][eval]")
{
    ct_rng r;
    ct_rng_init(&r, 20261122);
    for (int trial = 0; trial < 60; trial++) {
        int p = 1 + (int)(ct_rng_uniform(&r) * 9);
        int dim = 1 + trial % 3;
        size_t n = (size_t)p + 1 + (size_t)(ct_rng_uniform(&r) * 12);
        conica_bspline s;
        random_spline(&r, p, dim, n, trial % 4 == 3, &s);
        INFO("trial %d p %d dim %d n %zu", trial, p, dim, n);
        for (int q = 0; q <= 200; q++) {
            double x = 10.0 * q / 200.0, a[3], b[3];
            REQUIRE_EQ(conica_bspline_eval(&s, x, a, NULL), CONICA_OK);
            direct_eval(&s, x, b);
            for (int c = 0; c < dim; c++)
                CHECK_NEAR(a[c], b[c], 1e-11);
        }
        conica_bspline_free(&s);
    }
}

TEST_CASE("derivatives (eq. (1.13)) match finite differences", "[bspline][deriv]")
{
    ct_rng r;
    ct_rng_init(&r, 7);
    for (int trial = 0; trial < 30; trial++) {
        int p = 2 + (int)(ct_rng_uniform(&r) * 6);
        conica_bspline s;
        random_spline(&r, p, 2, (size_t)p + 6, trial % 2, &s);
        for (int q = 0; q < 50; q++) {
            double x = ct_rng_range(&r, 0.2, 9.8), h = 1e-5;
            /* stay inside one knot interval so the polynomial is smooth */
            size_t mu = conica_bspline_find_span(&s, x);
            if (x - h <= s.knots[mu] || x + h >= s.knots[mu + 1])
                continue;
            double d1[2], d2[2], fp[2], fm[2], f0[2];
            conica_bspline_eval_deriv(&s, x, 1, d1, NULL);
            conica_bspline_eval_deriv(&s, x, 2, d2, NULL);
            conica_bspline_eval(&s, x + h, fp, NULL);
            conica_bspline_eval(&s, x - h, fm, NULL);
            conica_bspline_eval(&s, x, f0, NULL);
            for (int c = 0; c < 2; c++) {
                double fd1 = (fp[c] - fm[c]) / (2 * h);
                double fd2 = (fp[c] - 2 * f0[c] + fm[c]) / (h * h);
                CHECK_NEAR(d1[c], fd1, 1e-5 * (1 + fabs(fd1)));
                CHECK_NEAR(d2[c], fd2, 2e-2 * (1 + fabs(fd2)));
            }
        }
        conica_bspline_free(&s);
    }
}

TEST_CASE("knot insertion leaves the spline unchanged (Lemma 1.18)", "[bspline][insert]")
{
    ct_rng r;
    ct_rng_init(&r, 99);
    for (int trial = 0; trial < 40; trial++) {
        int p = 1 + (int)(ct_rng_uniform(&r) * 12);
        int dim = 1 + trial % 3;
        conica_bspline s, t;
        random_spline(&r, p, dim, (size_t)p + 3 + (size_t)(ct_rng_uniform(&r) * 10),
                      trial % 3 == 0, &s);
        conica_bspline_init(&t);
        conica_bspline_set(s.degree, s.dim, s.knots, s.n + (size_t)p + 1, s.ctrl, s.n, s.w, &t,
                           NULL);
        double z[20];
        for (int q = 0; q < 20; q++)
            z[q] = ct_rng_range(&r, 0.0, 10.0);
        z[0] = 0.0; /* at the domain start: allowed up to multiplicity p+1 */
        conica_status st;
        conica_code rc = conica_bspline_insert_knots(&t, z + 1, 19, &st);
        REQUIRE_EQ(rc, CONICA_OK);
        REQUIRE_EQ_U(t.n, s.n + 19);
        for (size_t i = 1; i < t.n + (size_t)p + 1; i++)
            CHECK(t.knots[i] >= t.knots[i - 1]);
        for (int q = 0; q <= 2000; q++) {
            double x = 10.0 * q / 2000.0, a[3], b[3];
            conica_bspline_eval(&s, x, a, NULL);
            conica_bspline_eval(&t, x, b, NULL);
            for (int c = 0; c < dim; c++)
                CHECK_NEAR(a[c], b[c], 1e-11);
        }
        /* inserting beyond multiplicity p+1 or outside the domain fails */
        CHECK_EQ(conica_bspline_insert_knot(&t, 11.0, &st), CONICA_ERR_ARG);
        CHECK_EQ(conica_bspline_insert_knot(&t, 0.0, &st), CONICA_ERR_ARG);
        conica_bspline_free(&s);
        conica_bspline_free(&t);
    }
}

static void bernstein(const double *ctrl, const double *w, int p, int dim, double u, double *out)
{
    double num[3] = {0, 0, 0}, den = 0;
    for (int i = 0; i <= p; i++) {
        double b = 1;
        for (int k = 1; k <= i; k++)
            b = b * (double)(p - i + k) / (double)k;
        b *= pow(u, i) * pow(1 - u, p - i);
        double wi = w ? w[i] : 1.0;
        for (int c = 0; c < dim; c++)
            num[c] += b * wi * ctrl[i * dim + c];
        den += b * wi;
    }
    for (int c = 0; c < dim; c++)
        out[c] = num[c] / den;
}

TEST_CASE("Bezier <-> B-spline conversion round trips", "[bspline][bezier]")
{
    ct_rng r;
    ct_rng_init(&r, 4242);
    SECTION("from_bezier evaluates as the Bernstein form, any degree")
    {
        const int degrees[] = {2, 3, 7, 25, 50};
        for (int di = 0; di < 5; di++) {
            int p = degrees[di];
            double ctrl[51 * 2], w[51];
            for (int i = 0; i <= p; i++) {
                ctrl[2 * i] = ct_rng_range(&r, -1, 1);
                ctrl[2 * i + 1] = ct_rng_range(&r, -1, 1);
                w[i] = ct_rng_range(&r, 0.5, 2);
            }
            for (int rat = 0; rat < 2; rat++) {
                conica_bspline s;
                conica_bspline_init(&s);
                REQUIRE_EQ(conica_bspline_from_bezier(p, 2, ctrl, rat ? w : NULL, &s, NULL),
                           CONICA_OK);
                for (int q = 0; q <= 50; q++) {
                    double u = q / 50.0, a[2], b[2];
                    conica_bspline_eval(&s, u, a, NULL);
                    bernstein(ctrl, rat ? w : NULL, p, 2, u, b);
                    CHECK_NEAR(a[0], b[0], 1e-10);
                    CHECK_NEAR(a[1], b[1], 1e-10);
                }
                /* and back: the single piece has the same control points */
                double back[51 * 2], wb[51];
                conica_bspline_bezier_piece(&s, 0, back, wb, NULL, NULL, NULL);
                for (int i = 0; i <= 2 * p + 1; i++)
                    CHECK_NEAR(back[i], ctrl[i], 1e-12);
                conica_bspline_free(&s);
            }
        }
    }
    SECTION("to_bezier pieces reproduce the spline")
    {
        for (int trial = 0; trial < 20; trial++) {
            int p = 1 + trial % 6;
            conica_bspline s, b;
            random_spline(&r, p, 2, (size_t)p + 5, trial % 2, &s);
            conica_bspline_init(&b);
            REQUIRE_EQ(conica_bspline_to_bezier(&s, &b, NULL), CONICA_OK);
            size_t pieces = conica_bspline_bezier_count(&s);
            REQUIRE_EQ_U(b.n, pieces * (size_t)(p + 1));
            for (size_t k = 0; k < pieces; k++) {
                double pc[2 * 8], pw[8], a0, a1;
                conica_bspline_bezier_piece(&s, k, pc, pw, &a0, &a1, NULL);
                for (int i = 0; i <= p; i++) {
                    CHECK_NEAR(pc[2 * i], b.ctrl[(k * (size_t)(p + 1) + (size_t)i) * 2], 1e-10);
                    CHECK_NEAR(pc[2 * i + 1], b.ctrl[(k * (size_t)(p + 1) + (size_t)i) * 2 + 1],
                               1e-10);
                }
                for (int q = 0; q <= 20; q++) {
                    double u = q / 20.0, x = a0 + (a1 - a0) * u, e[2], f[2];
                    bernstein(pc, s.w ? pw : NULL, p, 2, u, e);
                    conica_bspline_eval(&s, x, f, NULL);
                    CHECK_NEAR(e[0], f[0], 1e-10);
                    CHECK_NEAR(e[1], f[1], 1e-10);
                }
            }
            conica_bspline_free(&s);
            conica_bspline_free(&b);
        }
    }
}

static conica_code parse_str(const char *txt, conica_bspline *s, conica_status *st)
{
    return conica_bspline_parse(txt, strlen(txt), s, st);
}

TEST_CASE(".spl parser", "[bspline][parse]")
{
    conica_bspline s;
    conica_bspline_init(&s);
    conica_status st;
    SECTION("valid input with comments, split knot lines and weights")
    {
        const char *txt = "# quarter circle\ndegree 2\nknots 0 0 0\nknots 1 1 1\n"
                          "c 1 0\nc 1 1 # corner\nc 0 1\nw 1 0.7071067811865476 1\n";
        REQUIRE_EQ(parse_str(txt, &s, &st), CONICA_OK);
        CHECK_EQ(s.dim, 2);
        CHECK_EQ_U(s.n, 3);
        REQUIRE(s.w != NULL);
        double xy[2];
        conica_bspline_eval(&s, 0.37, xy, NULL);
        CHECK_NEAR(xy[0] * xy[0] + xy[1] * xy[1], 1.0, 1e-14);
    }
    SECTION("errors carry the line")
    {
        CHECK_EQ(parse_str("degree 2\nknots 0 0 0 1 1 1\nc 0\nc 1x\nc 2\n", &s, &st),
                 CONICA_ERR_PARSE);
        CHECK_EQ_U(st.line, 4);
        CHECK_EQ(parse_str("degree 2\nfoo 1\n", &s, &st), CONICA_ERR_PARSE);
        CHECK_EQ_U(st.line, 2);
        CHECK_EQ(parse_str("knots 0 1\nc 1\n", &s, &st), CONICA_ERR_PARSE);
        CHECK_EQ(parse_str("degree 2\nknots 0 0 0 1 1 1\nc 0 1\nc 1\nc 2 2\n", &s, &st),
                 CONICA_ERR_PARSE);
        CHECK_EQ_U(st.line, 4);
        CHECK_EQ(parse_str("degree 2\nknots 0 0 0 1 1\nc 0\nc 1\nc 2\n", &s, &st),
                 CONICA_ERR_PARSE);
        CHECK_EQ_U(st.line, 2);
        CHECK_EQ(parse_str("degree 2\nknots 0 0 0 1 1 1\nc 0\nc nan\nc 2\n", &s, &st),
                 CONICA_ERR_NONFINITE);
        CHECK_EQ_U(st.line, 4);
        CHECK_EQ(parse_str("degree 2\nknots 0 0 0\nknots 2 1 1\nc 0\nc 1\nc 2\n", &s, &st),
                 CONICA_ERR_ARG);
        CHECK_EQ_U(st.line, 3);
        CHECK_EQ(parse_str("degree 2\nknots 0 0 0 1 1 1\nc 0\nc 1\nc 2\nw 1 0 1\n", &s, &st),
                 CONICA_ERR_ARG);
        CHECK_EQ_U(st.line, 6);
        CHECK_EQ(parse_str("degree 99\n", &s, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(parse_str("degree 2\ndegree 3\n", &s, &st), CONICA_ERR_PARSE);
        CHECK_EQ(s.n, 0); /* untouched */
    }
    SECTION("the thesis test set parses")
    {
        const char *names[] = {"sptest0", "sptest1", "sptest2", "sptest3", "sptest4"};
        const int deg[] = {2, 5, 25, 3, 3};
        const char *dir = ct_data_dir_or_skip();
        for (int i = 0; i < 5; i++) {
            char path[1024];
            snprintf(path, sizeof path, "%s/splines/%s.spl", dir, names[i]);
            FILE *f = fopen(path, "rb");
            REQUIRE(f != NULL);
            char buf[65536];
            size_t len = fread(buf, 1, sizeof buf, f);
            fclose(f);
            REQUIRE_EQ(conica_bspline_parse(buf, len, &s, &st), CONICA_OK);
            CHECK_EQ(s.degree, deg[i]);
        }
    }
    conica_bspline_free(&s);
}

TEST_CASE("tensor-product surface evaluation", "[bspline][surface]")
{
    /* z = x*y on [0,1]^2 as a biquadratic height surface: with Bézier knots
     * the coefficients are (i/2)(j/2) */
    const double k[] = {0, 0, 0, 1, 1, 1};
    double c[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            c[i * 3 + j] = (i / 2.0) * (j / 2.0);
    conica_bspline_surface s;
    conica_bspline_surface_init(&s);
    REQUIRE_EQ(conica_bspline_surface_set(2, 2, 1, k, 6, k, 6, c, 3, 3, NULL, &s, NULL),
               CONICA_OK);
    for (int q = 0; q < 25; q++) {
        double u = (q % 5) / 4.0, v = (q / 5) / 4.0, xyz[3];
        conica_bspline_surface_eval(&s, u, v, xyz, NULL);
        CHECK_NEAR(xyz[0], u, 1e-14);
        CHECK_NEAR(xyz[1], v, 1e-14);
        CHECK_NEAR(xyz[2], u * v, 1e-14);
    }
    conica_bspline_surface_free(&s);
}

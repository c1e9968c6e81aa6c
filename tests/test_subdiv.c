/* SPDX-License-Identifier: MIT */
/* Tests of the subdivision engine (libcore/src/subdiv.c, CONIS): conic
 * reproduction against the exact conics (eqs. (13)-(14)), interpolation,
 * invariance under similarity transforms, agreement of the closed-form fast
 * path with the weighted SVD fit, inflection points, open curves, bad input
 * and limits. Fixed seeds throughout. */
#include "conica_test.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/subdiv.h"
#include "fidelity.h"
#include "ts_fairness.h"

#define PI_L 3.14159265358979323846264338327950288L
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static ct_rng rng;

/* ------------------------------------------------------------ conics */

/* A conic f(x,y) = A x^2 + B y^2 + 2C xy + 2D x + 2E y + F (eq. (3)). */
typedef struct conic {
    long double A, B, C, D, E, F;
} conic;

static long double conic_f(const conic *q, long double x, long double y)
{
    return q->A * x * x + q->B * y * y + 2 * q->C * x * y + 2 * q->D * x + 2 * q->E * y + q->F;
}

static void conic_grad(const conic *q, long double x, long double y, long double *gx,
                       long double *gy)
{
    *gx = 2 * (q->A * x + q->C * y + q->D);
    *gy = 2 * (q->C * x + q->B * y + q->E);
}

/* |f| / |grad f|, the summand of eqs. (13)-(14). */
static long double conic_err(const conic *q, long double x, long double y)
{
    long double gx, gy;
    conic_grad(q, x, y, &gx, &gy);
    return fabsl(conic_f(q, x, y)) / sqrtl(gx * gx + gy * gy);
}

enum { C_CIRCLE, C_ELLIPSE, C_HYPERBOLA, C_PARABOLA, C_COUNT };
static const conic conics[C_COUNT] = {
    {1, 1, 0, 0, 0, -25},  /* x^2 + y^2 = 25 */
    {4, 9, 0, 0, 0, -36},  /* 4x^2 + 9y^2 = 36 */
    {-4, 1, 0, 0, 0, -4},  /* y^2 - 4x^2 = 4 */
    {1, 0, 0, 0, -0.5L, 0} /* y = x^2 */
};
static const char *const conic_names[C_COUNT] = {"circle", "ellipse", "hyperbola", "parabola"};

/* CONIS Table 1: E and E_max at k = 4, 8, 12. */
static const double table1[C_COUNT][2][3] = {
    {{1.97e-18, 4.70e-17, 1.57e-14}, {8.67e-18, 1.35e-15, 1.04e-13}},
    {{1.37e-18, 6.54e-17, 3.46e-15}, {6.17e-18, 1.10e-15, 1.53e-13}},
    {{1.14e-17, 4.67e-15, 4.55e-13}, {5.97e-16, 3.54e-13, 2.31e-12}},
    {{3.54e-16, 4.05e-15, 3.83e-13}, {3.53e-15, 1.13e-12, 8.09e-12}},
};

/* The reference's samples (REFERENCE.md section 1) in long double, with
 * exact unit normals. */
static void samples(int c, long double *xy, long double *nn, int *closed)
{
    int i;
    *closed = c == C_CIRCLE || c == C_ELLIPSE;
    for (i = 0; i < 6; i++) {
        long double t = 2 * PI_L * i / 6, x, y, gx, gy, len;
        switch (c) {
        case C_CIRCLE: x = 5 * cosl(t); y = 5 * sinl(t); break;
        case C_ELLIPSE: x = 3 * cosl(t); y = 2 * sinl(t); break;
        case C_HYPERBOLA: x = -4 + 8.0L * i / 5; y = 2 * sqrtl(1 + x * x); break;
        default: x = -4 + 8.0L * i / 6; y = x * x; break;
        }
        conic_grad(&conics[c], x, y, &gx, &gy);
        len = sqrtl(gx * gx + gy * gy);
        xy[2 * i] = x;
        xy[2 * i + 1] = y;
        nn[2 * i] = gx / len;
        nn[2 * i + 1] = gy / len;
    }
}

/* Curve of conic c's samples rounded to double. */
static void samples_d(int c, double *xy, double *nn, conica_curve *cv)
{
    long double lxy[12], lnn[12];
    int i, closed;
    samples(c, lxy, lnn, &closed);
    for (i = 0; i < 12; i++) {
        xy[i] = (double)lxy[i];
        nn[i] = (double)lnn[i];
    }
    cv->n = 6;
    cv->cap = 6;
    cv->xy = xy;
    cv->nxy = nn;
    cv->closed = closed;
}

typedef struct errs {
    long double E, Emax;
} errs;

static errs errors_d(const conic *q, const conica_curve *c)
{
    errs e = {0, 0};
    size_t i;
    for (i = 0; i < c->n; i++) {
        long double v = conic_err(q, c->xy[2 * i], c->xy[2 * i + 1]);
        e.E += v;
        if (v > e.Emax)
            e.Emax = v;
    }
    e.E /= (long double)c->n;
    return e;
}

static errs errors_l(const conic *q, const conica_curvel *c)
{
    errs e = {0, 0};
    size_t i;
    for (i = 0; i < c->n; i++) {
        long double v = conic_err(q, c->xy[2 * i], c->xy[2 * i + 1]);
        e.E += v;
        if (v > e.Emax)
            e.Emax = v;
    }
    e.E /= (long double)c->n;
    return e;
}

static int all_finite_unit(const conica_curve *c)
{
    size_t i;
    for (i = 0; i < c->n; i++) {
        double nx = c->nxy[2 * i], ny = c->nxy[2 * i + 1];
        if (!isfinite(c->xy[2 * i]) || !isfinite(c->xy[2 * i + 1]))
            return 0;
        if (!(fabs(sqrt(nx * nx + ny * ny) - 1) < 1e-14))
            return 0;
    }
    return 1;
}

/* ------------------------------------------------- conic reproduction */

/* Default mode (double): bounds met with a margin of ~4x over the measured
 * values (k=12: circle E 6.6e-16, E_max 3.9e-15); at k = 12 they are at
 * least 10x below Table 1 (the goal for double). */
TEST_CASE("conics are reproduced in default mode, k = 0..12", "[subdiv][conic]")
{
    int c, k;
    for (c = 0; c < C_COUNT; c++) {
        double xy[12], nn[12];
        conica_curve in, out;
        samples_d(c, xy, nn, &in);
        conica_curve_init(&out);
        for (k = 0; k <= 12; k++) {
            conica_subdiv_settings s = conica_subdiv_defaults();
            conica_subdiv_info info;
            errs e;
            s.levels = k;
            conica_subdiv_info_init(&info);
            INFO("%s k=%d", conic_names[c], k);
            REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
            REQUIRE_EQ_U(out.n, conica_subdiv_count(6, in.closed, k));
            CHECK(all_finite_unit(&out));
            CHECK_EQ_U(info.midpoint_fallbacks, 0);
            CHECK_EQ_U(info.inflections, 0);
            e = errors_d(&conics[c], &out);
            CHECK_LE((double)e.E, 3e-15);
            CHECK_LE((double)e.Emax, 2e-14);
            if (k == 12) {
                CHECK_LE((double)e.E, table1[c][0][2] / 10);
                CHECK_LE((double)e.Emax, table1[c][1][2] / 10);
            }
            conica_subdiv_info_free(&info);
        }
        conica_curve_free(&out);
    }
}

/* Precise mode with long double samples (as the reference's tests): at or
 * below Table 1 in all 24 cells (measured 5x to 1e5x below). */
TEST_CASE("precise mode beats Table 1 in every cell", "[subdiv][conic][precise]")
{
    int c, k;
    for (c = 0; c < C_COUNT; c++) {
        long double xy[12], nn[12];
        int closed;
        conica_curvel in, out;
        samples(c, xy, nn, &closed);
        in.n = in.cap = 6;
        in.xy = xy;
        in.nxy = nn;
        in.closed = closed;
        conica_curvel_init(&out);
        for (k = 4; k <= 12; k += 4) {
            conica_subdiv_settings s = conica_subdiv_defaults();
            errs e;
            s.levels = k;
            INFO("%s k=%d", conic_names[c], k);
            REQUIRE(conica_subdivide_curvel(&in, &s, &out, NULL, NULL) == CONICA_OK);
            REQUIRE_EQ_U(out.n, conica_subdiv_count(6, closed, k));
            e = errors_l(&conics[c], &out);
            CHECK_LE((double)e.E, table1[c][0][k / 4 - 1]);
            CHECK_LE((double)e.Emax, table1[c][1][k / 4 - 1]);
        }
        conica_curvel_free(&out);
    }
}

TEST_CASE("precise mode is at least as accurate as double", "[subdiv][conic][precise]")
{
    int c;
    for (c = 0; c < C_COUNT; c++) {
        double xy[12], nn[12];
        conica_curve in, outd;
        conica_curvel outl;
        conica_subdiv_settings s = conica_subdiv_defaults();
        errs ed, el;
        samples_d(c, xy, nn, &in);
        conica_curve_init(&outd);
        conica_curvel_init(&outl);
        s.levels = 10;
        INFO("%s", conic_names[c]);
        REQUIRE(conica_subdivide(&in, &s, &outd, NULL, NULL) == CONICA_OK);
        REQUIRE(conica_subdividel(&in, &s, &outl, NULL, NULL) == CONICA_OK);
        REQUIRE_EQ_U(outd.n, outl.n);
        ed = errors_d(&conics[c], &outd);
        el = errors_l(&conics[c], &outl);
        /* Same double input: the long double run keeps the error of the
         * input's rounding and adds less of its own. */
        CHECK_LE((double)el.E, (double)ed.E);
        CHECK_LE((double)el.Emax, (double)ed.Emax);
        conica_curve_free(&outd);
        conica_curvel_free(&outl);
    }
}

TEST_CASE("conica_subdividel equals precise conica_subdivide rounded", "[subdiv][precise]")
{
    double xy[12], nn[12];
    conica_curve in, outd;
    conica_curvel outl;
    conica_subdiv_settings s = conica_subdiv_defaults();
    size_t i, diff = 0;
    samples_d(C_ELLIPSE, xy, nn, &in);
    conica_curve_init(&outd);
    conica_curvel_init(&outl);
    s.levels = 6;
    s.precise = 1;
    REQUIRE(conica_subdivide(&in, &s, &outd, NULL, NULL) == CONICA_OK);
    s.precise = 0; /* subdividel computes in long double whatever this says */
    REQUIRE(conica_subdividel(&in, &s, &outl, NULL, NULL) == CONICA_OK);
    REQUIRE_EQ_U(outd.n, outl.n);
    CHECK(outl.closed);
    for (i = 0; i < 2 * outd.n; i++)
        diff += outd.xy[i] != (double)outl.xy[i];
    CHECK_EQ_U(diff, 0);
    conica_curve_free(&outd);
    conica_curvel_free(&outl);
}

/* ------------------------------------------- precise vs default mode */

/* Largest distance between the points of a and b over the diagonal of a's
 * bounding box, and largest angle between their normals (degrees). */
static void mode_gap(const conica_curve *a, const conica_curve *b, double *rel, double *deg)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, d = 0, g = 0;
    size_t i;
    for (i = 0; i < a->n; i++) {
        const double *p = a->xy + 2 * i, *q = b->xy + 2 * i, *m = a->nxy + 2 * i,
                     *u = b->nxy + 2 * i;
        lo[0] = fmin(lo[0], p[0]);
        lo[1] = fmin(lo[1], p[1]);
        hi[0] = fmax(hi[0], p[0]);
        hi[1] = fmax(hi[1], p[1]);
        d = fmax(d, hypot(p[0] - q[0], p[1] - q[1]));
        g = fmax(g, fabs(atan2(m[0] * u[1] - m[1] * u[0], m[0] * u[0] + m[1] * u[1])));
    }
    *rel = d / hypot(hi[0] - lo[0], hi[1] - lo[1]);
    *deg = g * 180 / M_PI;
}

/* Largest angle (degrees) between the scheme's normals and normals
 * estimated from the points (area-weighted, one global orientation): the
 * normal error of CONIS §3.2; 180 means a flipped normal. */
static double normal_error_deg(const conica_curve *c)
{
    conica_curve est;
    double dots = 0, g = 0;
    size_t i;
    conica_curve_init(&est);
    if (conica_curve_set(c->xy, NULL, c->n, c->closed, &est, NULL) != CONICA_OK ||
        conica_curve_estimate_normals(&est, CONICA_NORMALS_AREA, NULL) != CONICA_OK) {
        conica_curve_free(&est);
        return INFINITY;
    }
    for (i = 0; i < 2 * c->n; i++)
        dots += c->nxy[i] * est.nxy[i];
    for (i = 0; i < c->n; i++) {
        const double *m = c->nxy + 2 * i, *u = est.nxy + 2 * i;
        double a = fabs(atan2(m[0] * u[1] - m[1] * u[0], m[0] * u[0] + m[1] * u[1]));
        g = fmax(g, dots < 0 ? M_PI - a : a);
    }
    conica_curve_free(&est);
    return g * 180 / M_PI;
}

/* The reference's example9 (../shared/data/conis/input/example9.txt, copied
 * here so the test needs no data directory): a bowl whose given normals make
 * the edges next to its two inflection points S-shaped, so that the
 * convexity-region rule inserts inflection points at their midpoints, whose
 * neighbours lie on the edge lines to within rounding. */
static const double ex9_xy[32] = {1.5,  0,   2,    0,   2.5,  0.8,  2.7, 2.5, 1,   3.8, 0,
                                  4,    -1,  3.8,  -2.7, 2.5, -2.5, 0.8,  -2, 0,   -1.5, 0,
                                  -1,   0.9, -0.5, 1.15, 0,   1.2, 0.5,  1.15, 1,   0.9};
static const double ex9_n[32] = {
    0.79152783,  0.61113312,  -0.59736319, 0.80197084,  -0.95103173, 0.30909328,
    -0.93770505, -0.34743234, -0.33432364, -0.94245833, -0.0,       -1.0,
    0.33433092,  -0.94245575, 0.93769072,  -0.34747103, 0.95105017,  0.30903651,
    0.59749088,  0.80187571,  -0.91625824, 0.40058810,  -0.65692179, 0.75395873,
    -0.23340826, 0.97237883,  -0.0,        1.0,         0.23340826,  0.97237883,
    0.65692179,  0.75395873};

/* Issue 9 (audit): precise mode used to reach 38 deg of normal error at
 * k = 8 and 180 deg from k = 10 on example9 while default mode stayed at
 * 11.4 deg, and the two differed by 2e-4 of the size at k = 4: branch
 * decisions (neighbours on the edge line, same-side tests) followed the
 * sign of rounding errors, which differs between double and long double. */
TEST_CASE("precise mode follows default mode on S-shaped edges (example9, k = 0..12)",
          "[subdiv][precise][inflection]")
{
    conica_curve in, a, b;
    conica_subdiv_settings s = conica_subdiv_defaults();
    int k;
    conica_curve_init(&in);
    conica_curve_init(&a);
    conica_curve_init(&b);
    REQUIRE(conica_curve_set(ex9_xy, ex9_n, 16, 1, &in, NULL) == CONICA_OK);
    for (k = 0; k <= 12; k++) {
        double rel, deg;
        s.levels = k;
        s.precise = 0;
        REQUIRE(conica_subdivide(&in, &s, &a, NULL, NULL) == CONICA_OK);
        s.precise = 1;
        REQUIRE(conica_subdivide(&in, &s, &b, NULL, NULL) == CONICA_OK);
        REQUIRE_EQ_U(a.n, b.n);
        mode_gap(&a, &b, &rel, &deg);
        INFO("k = %d: positions differ by %.3g x diagonal, normals by %.3g deg", k, rel, deg);
        /* measured 4e-16 and 1.2e-10 deg at k = 12 */
        CHECK_LE(rel, 1e-13);
        CHECK_LE(deg, 1e-6);
        if (k >= 8) {
            /* No flipped or stuck normal in either mode: the error halves
             * per level (0.66 deg at k = 8, 0.038 deg at k = 12). */
            double ea = normal_error_deg(&a), eb = normal_error_deg(&b);
            INFO("k = %d: normal error default %.3g deg, precise %.3g deg", k, ea, eb);
            CHECK_LE(ea, 1.0);
            CHECK_LE(eb, 1.0);
        }
    }
    conica_curve_free(&in);
    conica_curve_free(&a);
    conica_curve_free(&b);
}

/* Random star-like polygons with noisy given normals, a third of them with
 * a vertex at the rounded midpoint of its neighbours (collinear to within
 * rounding, as in the reference's ExStar_sub0): the inflection test, the
 * inflection normal (10) and every side test must decide alike in both
 * modes. Before the fix 20% of such shapes differed by more than 1 deg. */
TEST_CASE("precise and default mode agree on random non-convex shapes", "[subdiv][precise][random]")
{
    conica_subdiv_settings s = conica_subdiv_defaults();
    double worst_rel = 0, worst_deg = 0;
    int t, split = 0;
    ct_rng_init(&rng, 2026);
    s.levels = 6;
    for (t = 0; t < 300; t++) {
        size_t n = 5 + (size_t)ct_rng_below(&rng, 12), i;
        double xy[64], nn[64], r0 = ct_rng_range(&rng, 1, 4), rel, deg;
        conica_curve in, a, b;
        for (i = 0; i < n; i++) {
            double ang = 2 * M_PI * ((double)i + ct_rng_range(&rng, 0, 0.3)) / (double)n;
            double r = r0 * ct_rng_range(&rng, 1, 1.6);
            /* two decimals, as hand-made input files have them */
            xy[2 * i] = round(r * cos(ang) * 100) / 100;
            xy[2 * i + 1] = round(r * sin(ang) * 100) / 100;
        }
        if (ct_rng_uniform(&rng) < 0.3) {
            size_t m = (size_t)ct_rng_below(&rng, n - 2);
            xy[2 * m + 2] = 0.5 * (xy[2 * m] + xy[2 * m + 4]);
            xy[2 * m + 3] = 0.5 * (xy[2 * m + 1] + xy[2 * m + 5]);
        }
        for (i = 0; i < n; i++) {
            size_t p = (i + n - 1) % n, q = (i + 1) % n;
            double ang = atan2(-(xy[2 * q] - xy[2 * p]), xy[2 * q + 1] - xy[2 * p + 1]) +
                         ct_rng_range(&rng, -0.2, 0.2);
            nn[2 * i] = cos(ang);
            nn[2 * i + 1] = sin(ang);
        }
        conica_curve_init(&in);
        conica_curve_init(&a);
        conica_curve_init(&b);
        if (conica_curve_set(xy, nn, n, 1, &in, NULL) != CONICA_OK)
            continue; /* duplicate points after rounding */
        s.precise = 0;
        REQUIRE(conica_subdivide(&in, &s, &a, NULL, NULL) == CONICA_OK);
        s.precise = 1;
        REQUIRE(conica_subdivide(&in, &s, &b, NULL, NULL) == CONICA_OK);
        REQUIRE_EQ_U(a.n, b.n);
        mode_gap(&a, &b, &rel, &deg);
        worst_rel = fmax(worst_rel, rel);
        worst_deg = fmax(worst_deg, deg);
        split += deg > 1.0;
        conica_curve_free(&in);
        conica_curve_free(&a);
        conica_curve_free(&b);
    }
    INFO("worst gap: %.3g x diagonal, %.3g deg", worst_rel, worst_deg);
    CHECK_EQ(split, 0);
    /* What remains is the general fit's conditioning on inconsistent
     * patches (LAPACK in double, Jacobi in long double): measured 2.1e-10
     * of the diagonal and 3.4e-6 deg at most. */
    CHECK_LE(worst_rel, 1e-6);
    CHECK_LE(worst_deg, 1e-2);
}

/* ------------------------------------------------------ interpolation */

static void star(size_t spikes, double r_in, double r_out, double jitter, double *xy, double *nn,
                 size_t *n)
{
    size_t i, m = 2 * spikes;
    for (i = 0; i < m; i++) {
        double t = 2 * M_PI * ((double)i + jitter * ct_rng_range(&rng, -0.3, 0.3)) / (double)m;
        double r = (i % 2 ? r_in : r_out) * ct_rng_range(&rng, 0.9, 1.1);
        xy[2 * i] = r * cos(t);
        xy[2 * i + 1] = r * sin(t);
        if (nn) {
            nn[2 * i] = cos(t);
            nn[2 * i + 1] = sin(t);
        }
    }
    *n = m;
}

TEST_CASE("old vertices are kept bit for bit", "[subdiv][interpolation]")
{
    int mode, trial;
    ct_rng_init(&rng, 1234);
    for (mode = 0; mode < 3; mode++) {
        for (trial = 0; trial < 5; trial++) {
            double xy[32], nn[32];
            size_t n, i, k = 4;
            conica_curve in, out;
            conica_subdiv_settings s = conica_subdiv_defaults();
            conica_subdiv_info info;
            star(3 + (size_t)trial, 0.6, 1.5, 1, xy, nn, &n);
            in.n = in.cap = n;
            in.xy = xy;
            in.nxy = nn;
            in.closed = 1;
            conica_curve_init(&out);
            conica_subdiv_info_init(&info);
            s.levels = (int)k;
            s.precise = mode == 1;
            s.reference_compatible = mode == 2;
            s.insert_inflections = 0;
            INFO("mode %d trial %d", mode, trial);
            REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
            REQUIRE_EQ_U(out.n, n << k);
            for (i = 0; i < n; i++) {
                CHECK(memcmp(&out.xy[2 * (i << k)], &xy[2 * i], 2 * sizeof(double)) == 0);
                /* Normals are only made unit: same direction. */
                CHECK_NEAR(out.nxy[2 * (i << k)] * nn[2 * i + 1] -
                               out.nxy[2 * (i << k) + 1] * nn[2 * i],
                           0.0, 1e-15);
            }
            CHECK(all_finite_unit(&out));
            conica_subdiv_info_free(&info);
            conica_curve_free(&out);
        }
    }
}

/* ------------------------------------------------- similarity invariance */

/* Conic c transformed by x -> s R x + t: samples in double, output mapped
 * back exactly (long double) and measured against the conic. The error is
 * compared with the rounding of the input's own coordinates,
 * eps * size * max(1, distance/size) (size = 5, the conics' scale). */
TEST_CASE("reproduction does not depend on position, size or rotation", "[subdiv][invariance]")
{
    int trial, worst_c = 0;
    double worst = 0;
    ct_rng_init(&rng, 42);
    for (trial = 0; trial < 40; trial++) {
        int c = trial % C_COUNT, i, closed;
        long double lxy[12], lnn[12];
        double xy[12], nn[12];
        long double th = (long double)ct_rng_range(&rng, 0, 2 * M_PI);
        long double sc = powl(10, (long double)ct_rng_range(&rng, -3, 6));
        long double dist = sc * 5 * powl(10, (long double)ct_rng_range(&rng, -1, 6));
        long double ph = (long double)ct_rng_range(&rng, 0, 2 * M_PI);
        long double tx = dist * cosl(ph), ty = dist * sinl(ph), cs = cosl(th), sn = sinl(th);
        conica_curve in, out;
        conica_subdiv_settings s = conica_subdiv_defaults();
        long double emax = 0, unit;
        size_t k;

        samples(c, lxy, lnn, &closed);
        for (i = 0; i < 6; i++) {
            long double x = lxy[2 * i], y = lxy[2 * i + 1];
            xy[2 * i] = (double)(sc * (cs * x - sn * y) + tx);
            xy[2 * i + 1] = (double)(sc * (sn * x + cs * y) + ty);
            nn[2 * i] = (double)(cs * lnn[2 * i] - sn * lnn[2 * i + 1]);
            nn[2 * i + 1] = (double)(sn * lnn[2 * i] + cs * lnn[2 * i + 1]);
        }
        in.n = in.cap = 6;
        in.xy = xy;
        in.nxy = nn;
        in.closed = closed;
        conica_curve_init(&out);
        s.levels = 8;
        INFO("trial %d: %s scale %Lg distance %Lg", trial, conic_names[c], sc, dist);
        REQUIRE(conica_subdivide(&in, &s, &out, NULL, NULL) == CONICA_OK);
        for (k = 0; k < out.n; k++) {
            long double x = (long double)out.xy[2 * k] - tx, y = (long double)out.xy[2 * k + 1] - ty;
            long double u = (cs * x + sn * y) / sc, v = (-sn * x + cs * y) / sc;
            long double e = conic_err(&conics[c], u, v);
            if (e > emax)
                emax = e;
        }
        unit = 5 * DBL_EPSILON * fmaxl(1, dist / (5 * sc));
        CHECK_LE((double)(emax / unit), 50.0); /* measured worst: 3.7 */
        if ((double)(emax / unit) > worst) {
            worst = (double)(emax / unit);
            worst_c = c;
        }
        conica_curve_free(&out);
    }
    INFO("worst: %.1f rounding units (%s)", worst, conic_names[worst_c]);
    CHECK_GT(worst, 0.0);
}

/* ------------------------------------------------------ random arcs */

TEST_CASE("random ellipse and hyperbola arcs are reproduced", "[subdiv][conic][random]")
{
    int trial;
    ct_rng_init(&rng, 7);
    for (trial = 0; trial < 30; trial++) {
        int hyp = trial % 2, i, n = 5 + (int)ct_rng_below(&rng, 5);
        double a = ct_rng_range(&rng, 0.5, 5), b = ct_rng_range(&rng, 0.5, 5);
        double th = ct_rng_range(&rng, 0, 2 * M_PI), cx = ct_rng_range(&rng, -10, 10);
        double cy = ct_rng_range(&rng, -10, 10), cs = cos(th), sn = sin(th);
        double xy[20], nn[20], t = 0, size = fmax(a, b);
        conic q; /* the conic in world coordinates: f(R^T (p - c)) */
        conica_curve in, out;
        conica_subdiv_settings s = conica_subdiv_defaults();
        errs e;
        /* Local conic: x^2/a^2 +- y^2/b^2 = 1 (hyperbola: branch x > 0). */
        long double A = 1 / ((long double)a * a), B = (hyp ? -1 : 1) / ((long double)b * b);
        long double c2 = (long double)cs * cs, s2 = (long double)sn * sn, csn = (long double)cs * sn;
        q.A = A * c2 + B * s2;
        q.B = A * s2 + B * c2;
        q.C = (A - B) * csn;
        q.D = -(q.A * cx + q.C * cy);
        q.E = -(q.C * cx + q.B * cy);
        q.F = A * ((long double)cs * cx + (long double)sn * cy) * ((long double)cs * cx + (long double)sn * cy) +
              B * (-(long double)sn * cx + (long double)cs * cy) * (-(long double)sn * cx + (long double)cs * cy) - 1;
        for (i = 0; i < n; i++) {
            double u, v, gu, gv, gx, gy, len;
            if (hyp) {
                /* parameters spread over [-1.5, 1.5], increasing */
                t = -1.5 + 3.0 * (i + ct_rng_range(&rng, -0.3, 0.3)) / (n - 1);
                u = a * cosh(t);
                v = b * sinh(t);
            } else {
                t = 2 * M_PI * (i + ct_rng_range(&rng, -0.3, 0.3)) / n;
                u = a * cos(t);
                v = b * sin(t);
            }
            gu = u / (a * a);
            gv = (hyp ? -v : v) / (b * b);
            xy[2 * i] = cx + cs * u - sn * v;
            xy[2 * i + 1] = cy + sn * u + cs * v;
            gx = cs * gu - sn * gv;
            gy = sn * gu + cs * gv;
            len = sqrt(gx * gx + gy * gy);
            nn[2 * i] = gx / len;
            nn[2 * i + 1] = gy / len;
        }
        in.n = in.cap = (size_t)n;
        in.xy = xy;
        in.nxy = nn;
        in.closed = !hyp;
        conica_curve_init(&out);
        s.levels = 6;
        INFO("trial %d (%s, %d points, a=%g b=%g)", trial, hyp ? "hyperbola" : "ellipse", n, a, b);
        REQUIRE(conica_subdivide(&in, &s, &out, NULL, NULL) == CONICA_OK);
        e = errors_d(&q, &out);
        /* Input rounding is ~eps * (|c| + size) ~ 4e-15 here. */
        CHECK_LE((double)e.Emax, 1e-13 * fmax(1, size));
        conica_curve_free(&out);
    }
}

TEST_CASE("a narrow ellipse sampled at its vertices is reproduced", "[subdiv][conic]")
{
    /* Tangents at the samples are parallel or perpendicular to the edges'
     * neighbours: the pencil's corner cases. x^2/100 + y^2 = 1. */
    double xy[8] = {10, 0, 0, 1, -10, 0, 0, -1}, nn[8] = {1, 0, 0, 1, -1, 0, 0, -1};
    conica_curve in = {4, 4, xy, nn, 1}, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_subdiv_info info;
    conic q = {0.01L, 1, 0, 0, 0, -1};
    int mode;
    conica_curve_init(&out);
    conica_subdiv_info_init(&info);
    for (mode = 0; mode < 2; mode++) {
        s.levels = 8;
        s.force_svd = mode;
        INFO("force_svd %d", mode);
        REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
        CHECK_EQ_U(info.midpoint_fallbacks, 0);
        CHECK_LE((double)errors_d(&q, &out).Emax, 1e-13);
        conica_subdiv_info_free(&info);
    }
    conica_curve_free(&out);
}

/* -------------------------------------------- fast path == SVD path */

/* On exact conic samples both paths reproduce the conic, so they may only
 * differ by rounding. The SVD fit has a condition number of about
 * w_e / w_o^n = 1e5 (weights 1e5 : 1), so its coefficients carry errors of
 * up to ~1e5 eps relative in the worst case; measured at k=6: 2.3e-14
 * (circle, r=5, i.e. ~20 ulps) in double, 0 after rounding in long double;
 * bound 1e-13 of the size (~20x margin). On data on no conic the two normalisations (||q|| = 1 vs
 * mu^2 + lam^2 = 1 in the pencil) give different fits; REFERENCE.md
 * measured up to ~1e-2 of the diagonal on the reference's examples; on this
 * star 3.0e-5 of the diagonal at k=5; bound 1e-3. */
TEST_CASE("fast path agrees with the weighted SVD fit", "[subdiv][svd]")
{
    int c, mode;
    for (mode = 0; mode < 2; mode++) {
        for (c = 0; c < C_COUNT; c++) {
            double xy[12], nn[12];
            conica_curve in, a, b;
            conica_subdiv_settings s = conica_subdiv_defaults();
            conica_subdiv_info ia, ib;
            size_t i;
            double dmax = 0;
            samples_d(c, xy, nn, &in);
            conica_curve_init(&a);
            conica_curve_init(&b);
            conica_subdiv_info_init(&ia);
            conica_subdiv_info_init(&ib);
            s.levels = 6;
            s.precise = mode;
            REQUIRE(conica_subdivide(&in, &s, &a, &ia, NULL) == CONICA_OK);
            s.force_svd = 1;
            REQUIRE(conica_subdivide(&in, &s, &b, &ib, NULL) == CONICA_OK);
            REQUIRE_EQ_U(a.n, b.n);
            for (i = 0; i < 2 * a.n; i++)
                dmax = fmax(dmax, fabs(a.xy[i] - b.xy[i]));
            INFO("%s precise=%d: max difference %g", conic_names[c], mode, dmax);
            CHECK_LE(dmax, 1e-13 * 5);
            CHECK_EQ_U(ib.midpoint_fallbacks, 0);
            CHECK(all_finite_unit(&b));
            conica_curve_free(&a);
            conica_curve_free(&b);
        }
    }
    {
        double xy[32], nn[32], dmax = 0, lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
        size_t n, i;
        conica_curve in, a, b;
        conica_subdiv_settings s = conica_subdiv_defaults();
        ct_rng_init(&rng, 99);
        star(5, 0.7, 1.3, 1, xy, NULL, &n);
        in.n = in.cap = n;
        in.xy = xy;
        in.nxy = NULL;
        in.closed = 1;
        (void)nn;
        conica_curve_init(&a);
        conica_curve_init(&b);
        s.levels = 5;
        REQUIRE(conica_subdivide(&in, &s, &a, NULL, NULL) == CONICA_OK);
        s.force_svd = 1;
        REQUIRE(conica_subdivide(&in, &s, &b, NULL, NULL) == CONICA_OK);
        REQUIRE_EQ_U(a.n, b.n);
        for (i = 0; i < a.n; i++) {
            dmax = fmax(dmax, hypot(a.xy[2 * i] - b.xy[2 * i], a.xy[2 * i + 1] - b.xy[2 * i + 1]));
            lo[0] = fmin(lo[0], a.xy[2 * i]);
            lo[1] = fmin(lo[1], a.xy[2 * i + 1]);
            hi[0] = fmax(hi[0], a.xy[2 * i]);
            hi[1] = fmax(hi[1], a.xy[2 * i + 1]);
        }
        INFO("star: max difference %g of the diagonal", dmax / hypot(hi[0] - lo[0], hi[1] - lo[1]));
        CHECK_LE(dmax, 1e-3 * hypot(hi[0] - lo[0], hi[1] - lo[1]));
        CHECK_GT(dmax, 0.0); /* the two fits really are different code */
        conica_curve_free(&a);
        conica_curve_free(&b);
    }
}

/* ------------------------------------------------- reference mode */

/* Reference-compatible mode is the reference's own numerics (absolute
 * coordinates, SVD): at the origin it lands near Table 1; moved to
 * (1e4, 1e4) it fails the way REFERENCE.md measured the reference failing,
 * while the default mode does not. */
TEST_CASE("reference-compatible mode reproduces the reference's behaviour", "[subdiv][reference]")
{
    long double xy[12], nn[12];
    int closed, i;
    conica_curvel in, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    errs e;
    samples(C_CIRCLE, xy, nn, &closed);
    in.n = in.cap = 6;
    in.xy = xy;
    in.nxy = nn;
    in.closed = closed;
    conica_curvel_init(&out);
    s.reference_compatible = 1;
    s.levels = 8;
    REQUIRE(conica_subdivide_curvel(&in, &s, &out, NULL, NULL) == CONICA_OK);
    e = errors_l(&conics[C_CIRCLE], &out);
    INFO("origin: E %Lg E_max %Lg", e.E, e.Emax);
    CHECK_LE((double)e.Emax, 100 * table1[C_CIRCLE][1][1]);
    for (i = 0; i < 6; i++) {
        xy[2 * i] += 1e4L;
        xy[2 * i + 1] += 1e4L;
    }
    s.levels = 4;
    REQUIRE(conica_subdivide_curvel(&in, &s, &out, NULL, NULL) == CONICA_OK);
    {
        size_t k;
        long double emax = 0;
        for (k = 0; k < out.n; k++)
            emax = fmaxl(emax, conic_err(&conics[C_CIRCLE], out.xy[2 * k] - 1e4L,
                                         out.xy[2 * k + 1] - 1e4L));
        long double eref = emax;
        INFO("moved, reference mode: E_max %Lg", eref);
        s.reference_compatible = 0;
        REQUIRE(conica_subdivide_curvel(&in, &s, &out, NULL, NULL) == CONICA_OK);
        emax = 0;
        for (k = 0; k < out.n; k++)
            emax = fmaxl(emax, conic_err(&conics[C_CIRCLE], out.xy[2 * k] - 1e4L,
                                         out.xy[2 * k + 1] - 1e4L));
        INFO("moved, default mode: E_max %Lg", emax);
        CHECK_LE((double)emax, 1e-14);
        /* Absolute coordinates lose digits far from the origin (REFERENCE.md:
         * the reference reaches 0.17 here; our one-sided Jacobi SVD keeps
         * more, measured 5e-8, still 1e6x the local frame's error). */
        CHECK_GT((double)eref, 1e-10);
        CHECK_GT((double)eref, 1e3 * (double)emax);
    }
    conica_curvel_free(&out);
}

/* ------------------------------------------------------ open curves */

TEST_CASE("open curves", "[subdiv][open]")
{
    SECTION("counts and end points")
    {
        double xy[12], nn[12];
        conica_curve in, out;
        conica_subdiv_settings s = conica_subdiv_defaults();
        int k;
        samples_d(C_PARABOLA, xy, nn, &in);
        conica_curve_init(&out);
        for (k = 1; k <= 5; k++) {
            s.levels = k;
            REQUIRE(conica_subdivide(&in, &s, &out, NULL, NULL) == CONICA_OK);
            CHECK_EQ_U(out.n, 5 * ((size_t)1 << k) + 1);
            CHECK(out.closed == 0);
            CHECK(memcmp(out.xy, xy, 2 * sizeof(double)) == 0);
            CHECK(memcmp(out.xy + 2 * (out.n - 1), xy + 10, 2 * sizeof(double)) == 0);
        }
        conica_curve_free(&out);
    }
    SECTION("two points make an arc tangent to both normals")
    {
        double xy[4] = {-1, 0, 1, 0}, nn[4] = {-1, 1, 1, 1};
        conica_curve in = {2, 2, xy, nn, 0}, out;
        conica_subdiv_settings s = conica_subdiv_defaults();
        size_t i;
        conica_curve_init(&out);
        s.levels = 5;
        REQUIRE(conica_subdivide(&in, &s, &out, NULL, NULL) == CONICA_OK);
        REQUIRE_EQ_U(out.n, 33);
        CHECK(all_finite_unit(&out));
        /* The parabola of the pencil through (+-1, 0) tangent to y = x + 1
         * and y = -x + 1: y = (1 - x^2)/2, apex (0, 0.5). */
        CHECK_NEAR(out.xy[2 * 16], 0.0, 1e-15);
        CHECK_NEAR(out.xy[2 * 16 + 1], 0.5, 1e-15);
        for (i = 0; i < out.n; i++)
            CHECK_NEAR(out.xy[2 * i + 1], (1 - out.xy[2 * i] * out.xy[2 * i]) / 2, 1e-14);
        conica_curve_free(&out);
    }
}

/* ------------------------------------------------------ inflections */

/* Naive reference: sign of the cross product in long double. */
static int side(const double *xy, size_t a, size_t b, size_t p)
{
    long double v = ((long double)xy[2 * b] - xy[2 * a]) * ((long double)xy[2 * p + 1] - xy[2 * a + 1]) -
                    ((long double)xy[2 * b + 1] - xy[2 * a + 1]) * ((long double)xy[2 * p] - xy[2 * a]);
    return v > 0 ? 1 : v < 0 ? -1 : 0;
}

TEST_CASE("inflection points on random stars", "[subdiv][inflection]")
{
    int trial;
    ct_rng_init(&rng, 2024);
    for (trial = 0; trial < 20; trial++) {
        double xy[40];
        size_t n, i, expect = 0, k = (size_t)(trial % 4) + 1, found;
        size_t where[20];
        conica_curve in, out;
        conica_subdiv_settings s = conica_subdiv_defaults();
        conica_subdiv_info info;
        size_t spikes = 3 + (size_t)ct_rng_below(&rng, 6);
        double r_in = ct_rng_range(&rng, 0.3, 0.9);
        double r_out = ct_rng_range(&rng, 1, 2);
        star(spikes, r_in, r_out, 1, xy, NULL, &n);
        for (i = 0; i < n; i++) {
            size_t a = (i + n - 1) % n, b = (i + 1) % n, d = (i + 2) % n;
            int s1 = side(xy, i, b, a), s2 = side(xy, i, b, d);
            if (s1 != 0 && s2 != 0 && s1 != s2)
                where[expect++] = i;
        }
        in.n = in.cap = n;
        in.xy = xy;
        in.nxy = NULL;
        in.closed = 1;
        conica_curve_init(&out);
        conica_subdiv_info_init(&info);
        s.levels = (int)k;
        INFO("trial %d: %zu points, %zu expected", trial, n, expect);
        REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
        REQUIRE_EQ_U(info.inflections, expect);
        REQUIRE_EQ_U(out.n, (n + expect) << k);
        CHECK(all_finite_unit(&out));
        for (found = 0; found < expect; found++) {
            size_t e = where[found], q = info.inflection_index[found];
            /* Level-0 index of edge e's inflection point: e + 1 + (number of
             * inflection points before it); at level k it is times 2^k. */
            CHECK_EQ_U(q, (e + 1 + found) << k);
            if (q < out.n) {
                CHECK(out.xy[2 * q] == 0.5 * xy[2 * e] + 0.5 * xy[2 * ((e + 1) % n)]);
                CHECK(out.xy[2 * q + 1] == 0.5 * xy[2 * e + 1] + 0.5 * xy[2 * ((e + 1) % n) + 1]);
            }
        }
        conica_subdiv_info_free(&info);
        /* insert_inflections = 0 inserts none (the CGAL checks rely on it) */
        s.insert_inflections = 0;
        REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
        CHECK_EQ_U(info.inflections, 0);
        CHECK_EQ_U(out.n, n << k);
        conica_subdiv_info_free(&info);
        conica_curve_free(&out);
    }
}

TEST_CASE("the inflection test decides alike from double and long double input",
          "[subdiv][inflection][noise]")
{
    /* Double input decides the sides in double where the error bound of
     * the orientation filter allows, long double input always in long
     * double (SFX(needs_infl)): wavy open polylines far from the origin
     * whose neighbours lie within 1e-20..1e-2 of the edge lines, some
     * exactly on them, with noise 0, random, or a quarter of one of the
     * distances (the noise test's own boundary). */
    int trial;
    size_t total = 0;
    ct_rng_init(&rng, 77);
    for (trial = 0; trial < 300; trial++) {
        enum { NP = 24 };
        double xy[2 * NP], off = pow(10, ct_rng_range(&rng, 0, 6)), h = ct_rng_range(&rng, 0.5, 2);
        long double lxy[2 * NP];
        size_t i;
        conica_curve in, out;
        conica_curvel lin, lout;
        conica_subdiv_settings s = conica_subdiv_defaults();
        conica_subdiv_info i1, i2;
        for (i = 0; i < NP; i++) {
            double d = ct_rng_uniform(&rng) < 0.15 ? 0 : pow(10, ct_rng_range(&rng, -20, -2));
            xy[2 * i] = off + h * (double)i;
            xy[2 * i + 1] = off + (ct_rng_uniform(&rng) < 0.5 ? -d : d);
        }
        if (trial % 3 == 1)
            s.noise = pow(10, ct_rng_range(&rng, -18, -4));
        else if (trial % 3 == 2)
            s.noise = fabs(xy[2 * (trial % NP) + 1] - off) / 4 * h;
        for (i = 0; i < 2 * NP; i++)
            lxy[i] = xy[i];
        s.levels = 1;
        s.estimate_normals = 1;
        in.n = in.cap = NP;
        in.xy = xy;
        in.nxy = NULL;
        in.closed = 0;
        lin.n = lin.cap = NP;
        lin.xy = lxy;
        lin.nxy = NULL;
        lin.closed = 0;
        conica_curve_init(&out);
        conica_curvel_init(&lout);
        conica_subdiv_info_init(&i1);
        conica_subdiv_info_init(&i2);
        INFO("trial %d: offset %g noise %g", trial, off, s.noise);
        REQUIRE(conica_subdivide(&in, &s, &out, &i1, NULL) == CONICA_OK);
        REQUIRE(conica_subdivide_curvel(&lin, &s, &lout, &i2, NULL) == CONICA_OK);
        REQUIRE_EQ_U(i1.inflections, i2.inflections);
        for (i = 0; i < i1.inflections; i++)
            CHECK_EQ_U(i1.inflection_index[i], i2.inflection_index[i]);
        total += i1.inflections;
        conica_subdiv_info_free(&i1);
        conica_subdiv_info_free(&i2);
        conica_curve_free(&out);
        conica_curvel_free(&lout);
    }
    INFO("%zu inflection points in all", total);
    CHECK_GT((double)total, 100.0);
}

/* Winding number of the closed polygon c about the origin. */
static double winding(const conica_curve *c)
{
    double sum = 0;
    size_t i;
    for (i = 0; i < c->n; i++) {
        const double *p = c->xy + 2 * i, *q = c->xy + 2 * ((i + 1) % c->n);
        sum += atan2(p[0] * q[1] - p[1] * q[0], p[0] * q[0] + p[1] * q[1]);
    }
    return sum / (2 * M_PI);
}

TEST_CASE("a closed polygon on part of a conic closes over the rest (long arcs)",
          "[subdiv][conic][inflection]")
{
    /* 3 to 6 exact samples of the circle or the ellipse spread over less
     * than a half turn, closed: the closing edge carries the rest of the
     * conic, an arc that turns by more than a half turn. The point eq. (6)
     * picks there, the intersection nearest the midpoint, lies on the
     * short arc inside the samples' span: the output folded back over the
     * samples (winding number 0) and changed its turning sign twice. It is
     * now the conic's far intersection (libcore/src/subdiv_impl.h,
     * SFX(long_arc)): the whole conic once round, in both modes. */
    int trial;
    ct_rng_init(&rng, 2026);
    for (trial = 0; trial < 40; trial++) {
        int c = trial % 2 ? C_ELLIPSE : C_CIRCLE, prec;
        size_t m = 3 + (size_t)ct_rng_below(&rng, 4), i;
        double span = ct_rng_range(&rng, 0.4, 0.95) * M_PI, t0 = ct_rng_range(&rng, 0, 2 * M_PI);
        double xy[12], nn[12], ra = c == C_CIRCLE ? 5 : 3, rb = c == C_CIRCLE ? 5 : 2;
        conica_curve in, out;
        conica_subdiv_settings s = conica_subdiv_defaults();
        for (i = 0; i < m; i++) {
            long double t = t0 + span * (double)i / (double)(m - 1), gx, gy, len;
            long double x = ra * cosl(t), y = rb * sinl(t);
            conic_grad(&conics[c], x, y, &gx, &gy);
            len = sqrtl(gx * gx + gy * gy);
            xy[2 * i] = (double)x;
            xy[2 * i + 1] = (double)y;
            nn[2 * i] = (double)(gx / len);
            nn[2 * i + 1] = (double)(gy / len);
        }
        in.n = in.cap = m;
        in.xy = xy;
        in.nxy = nn;
        in.closed = 1;
        s.levels = 6;
        for (prec = 0; prec < 2; prec++) {
            errs e;
            double wn;
            s.precise = prec;
            conica_curve_init(&out);
            INFO("trial %d: %s, %zu samples over %.3g pi, %s", trial, conic_names[c], m,
                 span / M_PI, prec ? "precise" : "default");
            REQUIRE(conica_subdivide(&in, &s, &out, NULL, NULL) == CONICA_OK);
            e = errors_d(&conics[c], &out);
            wn = winding(&out);
            CHECK_LE((double)e.Emax, 1e-12);
            CHECK_LE(fabs(fabs(wn) - 1), 1e-9);
            conica_curve_free(&out);
        }
    }
}

TEST_CASE("folded polygons: curvature changes sign only at the inflections",
          "[subdiv][inflection][fairness]")
{
    /* Points on a circle taken in random order (as the reference's lG2),
     * normals estimated: vertices turn by up to nearly a half turn, and
     * edges whose convex arc turns by more than a half turn (long arcs,
     * SFX(long_arc)) are common. Every piece between two inflection points
     * of eq. (9) must turn one way: the discrete curvature (circle through
     * three consecutive points, tests/support/ts_fairness.h) changes sign
     * as often as there are inflections, in both modes. Polygons with
     * nearly coincident points (an edge under 1/20 of the radius) are left
     * out: their hairpins are below the scale this test is about. */
    int trial, checked = 0;
    ct_rng_init(&rng, 20);
    for (trial = 0; trial < 60; trial++) {
        size_t n = 5 + (size_t)ct_rng_below(&rng, 5), i;
        double xy[2 * 9], shortest = 2;
        int prec;
        conica_curve in;
        for (i = 0; i < n; i++) {
            double a = ct_rng_range(&rng, 0, 2 * M_PI);
            xy[2 * i] = cos(a);
            xy[2 * i + 1] = sin(a);
        }
        for (i = 0; i < n; i++) {
            size_t j = (i + 1) % n;
            double d = hypot(xy[2 * j] - xy[2 * i], xy[2 * j + 1] - xy[2 * i + 1]);
            shortest = d < shortest ? d : shortest;
        }
        if (shortest < 0.05)
            continue;
        in.n = in.cap = n;
        in.xy = xy;
        in.nxy = NULL;
        in.closed = 1;
        for (prec = 0; prec < 2; prec++) {
            conica_curve out;
            conica_subdiv_settings s = conica_subdiv_defaults();
            conica_subdiv_info info;
            ts_fairness m;
            conica_curve_init(&out);
            conica_subdiv_info_init(&info);
            s.levels = 5;
            s.precise = prec;
            INFO("trial %d: %zu points, %s", trial, n, prec ? "precise" : "default");
            REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
            REQUIRE_EQ(ts_fairness_measure(out.xy, out.n, out.closed, &m), 0);
            CHECK_EQ_U(m.sign_changes, info.inflections);
            conica_subdiv_info_free(&info);
            conica_curve_free(&out);
        }
        checked++;
    }
    CHECK(checked >= 40);
}

/* ------------------------------------------------------ bad input */

TEST_CASE("degenerate input gives a status, never NaN", "[subdiv][errors]")
{
    conica_curve out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_status st;
    double keep[2] = {7, 8};
    conica_curve_init(&out);
    out.xy = keep; /* must stay untouched on failure */
    out.n = 1;
    s.levels = 3;

    SECTION("too few points")
    {
        double xy[4] = {0, 0, 1, 0}, nn[4] = {0, 1, 0, 1};
        conica_curve in = {2, 2, xy, nn, 1};
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_DEGENERATE);
        in.n = 1;
        in.closed = 0;
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_DEGENERATE);
        CHECK(conica_subdivide(NULL, &s, &out, NULL, &st) == CONICA_ERR_ARG);
        CHECK(conica_subdivide(&in, &s, NULL, NULL, &st) == CONICA_ERR_ARG);
        CHECK(out.xy == keep);
        CHECK_EQ_U(out.n, 1);
    }
    SECTION("duplicate consecutive points")
    {
        double xy[8] = {0, 0, 1, 0, 1, 0, 0, 1}, nn[8] = {-1, -1, 1, -1, 1, 1, -1, 1};
        conica_curve in = {4, 4, xy, nn, 1};
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_DEGENERATE);
        CHECK_EQ_U(st.offset, 1);
        CHECK(st.message[0] != 0);
        xy[4] = 0;
        xy[5] = 1; /* now point 3 == point 2, the closing edge is fine */
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_DEGENERATE);
        CHECK_EQ_U(st.offset, 2);
        CHECK(out.xy == keep);
    }
    SECTION("NaN and Inf")
    {
        double xy[8] = {0, 0, 1, 0, 1, 1, 0, 1}, nn[8] = {-1, -1, 1, -1, 1, 1, -1, 1};
        conica_curve in = {4, 4, xy, nn, 1};
        xy[5] = NAN;
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_NONFINITE);
        CHECK_EQ_U(st.offset, 2);
        xy[5] = 1;
        nn[6] = INFINITY;
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_NONFINITE);
        CHECK_EQ_U(st.offset, 3);
        CHECK(out.xy == keep);
    }
    SECTION("zero normal")
    {
        double xy[8] = {0, 0, 1, 0, 1, 1, 0, 1}, nn[8] = {-1, -1, 0, 0, 1, 1, -1, 1};
        conica_curve in = {4, 4, xy, nn, 1};
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_DEGENERATE);
        CHECK_EQ_U(st.offset, 1);
    }
    SECTION("collinear runs and opposite normals stay finite")
    {
        /* A square with three points on each side, normals along the side
         * normals, some flipped. */
        double xy[16] = {0, 0, 1, 0, 2, 0, 2, 1, 2, 2, 1, 2, 0, 2, 0, 1};
        double nn[16] = {-1, -1, 0, -1, 1, -1, 1, 0, 1, 1, 0, -1, -1, 1, -1, 0};
        conica_curve in = {8, 8, xy, nn, 1}, res;
        int mode;
        conica_curve_init(&res);
        for (mode = 0; mode < 4; mode++) {
            s.precise = mode & 1;
            s.reference_compatible = (mode & 2) != 0;
            s.levels = 6;
            INFO("mode %d", mode);
            REQUIRE(conica_subdivide(&in, &s, &res, NULL, &st) == CONICA_OK);
            CHECK(all_finite_unit(&res));
        }
        conica_curve_free(&res);
    }
    SECTION("bad settings")
    {
        double xy[6] = {0, 0, 1, 0, 0, 1};
        conica_curve in = {3, 3, xy, NULL, 1};
        s.tau = NAN;
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_ARG);
        s = conica_subdiv_defaults();
        s.patch_grow = 9;
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_ARG);
        s = conica_subdiv_defaults();
        s.levels = -1;
        CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_ARG);
        CHECK(out.xy == keep);
    }
    if (out.xy == keep)
        conica_curve_init(&out);
    conica_curve_free(&out);
}

TEST_CASE("a circle with alternating normal signs is still a circle", "[subdiv][errors][conic]")
{
    double xy[12], nn[12];
    conica_curve in, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    size_t i;
    errs e;
    samples_d(C_CIRCLE, xy, nn, &in);
    for (i = 1; i < 6; i += 2) {
        nn[2 * i] = -nn[2 * i];
        nn[2 * i + 1] = -nn[2 * i + 1];
    }
    conica_curve_init(&out);
    s.levels = 6;
    REQUIRE(conica_subdivide(&in, &s, &out, NULL, NULL) == CONICA_OK);
    e = errors_d(&conics[C_CIRCLE], &out);
    CHECK_LE((double)e.Emax, 2e-14);
    conica_curve_free(&out);
}

/* ------------------------------------------------------------ limits */

TEST_CASE("limits: levels and the output budget", "[subdiv][limits]")
{
    double xy[12], nn[12], keep[2] = {1, 2};
    conica_curve in, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_status st;
    samples_d(C_CIRCLE, xy, nn, &in);
    conica_curve_init(&out);
    out.xy = keep;
    out.n = 1;
    s.levels = 31;
    CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_LIMIT);
    CHECK(strstr(st.message, "30") != NULL);
    s.levels = 30; /* 6 * 2^30 points: over the default budget of 2^26 */
    CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_LIMIT);
    s.levels = 4;
    s.max_points = 95;
    CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_ERR_LIMIT);
    CHECK(strstr(st.message, "max_points") != NULL);
    CHECK(out.xy == keep);
    CHECK_EQ_U(out.n, 1);
    s.max_points = 96;
    conica_curve_init(&out);
    CHECK(conica_subdivide(&in, &s, &out, NULL, &st) == CONICA_OK);
    CHECK_EQ_U(out.n, 96);
    conica_curve_free(&out);
    CHECK_EQ_U(conica_subdiv_count(6, 1, 30), (size_t)6 << 30);
    CHECK_EQ_U(conica_subdiv_count(6, 0, 3), 41);
    CHECK_EQ_U(conica_subdiv_count(6, 0, 31), 0);
    CHECK_EQ_U(conica_subdiv_count(SIZE_MAX / 2, 1, 2), 0);
}

/* ------------------------------------------------- rounded (noisy) input */

/* x rounded to float32 (a volatile store: gcc 12 at -O2 has been seen to
 * drop a plain (float) cast of cos()'s result). */
static double f32(double x)
{
    volatile float f = (float)x;
    return f;
}

/* Largest | |p| - 1 | over n points (the unit circle's radial error). */
static double radial_max(const double *xy, size_t n)
{
    static const double origin[2] = {0, 0};
    return ts_ellipse_radial_error(xy, n, origin, 1, 1, 0, NULL);
}

TEST_CASE("a float32 circle decides alike in every rotation (settings.noise)",
          "[subdiv][noise]")
{
    /* What every Blender POLY spline is: 20 000 points of the unit circle
     * rounded to float32 (an edge's sag, 1.2e-8, is below the rounding,
     * 6e-8), then rotated in double as the add-on's best-fit plane does.
     * The float grid has straight runs (equal x or y); rotated, they are
     * straight to within the rotation's rounding only, and before the
     * noise-aware straightness test (SFX(make_frame)) their end normals'
     * rounding-level tilts sent them to the general fit (480 grown patches
     * at k = 3 here, and 15 000 at k = 7: 6x the time). Measured now: no
     * grown patch, the same last resorts (4136) at every angle but one
     * (0.7: 4184), and the output the rotated unrotated one to 2.2e-15. */
    const size_t n = 20000;
    const double angles[4] = {0.3, 0.7, 1.65, 4.4};
    double *xy = malloc(2 * n * sizeof *xy), *rxy = malloc(2 * n * sizeof *rxy), in_err;
    conica_curve in, plain, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_subdiv_info info, info0;
    size_t i;
    int a;
    REQUIRE(xy != NULL);
    REQUIRE(rxy != NULL);
    for (i = 0; i < n; i++) {
        double t = 2 * M_PI * (double)i / (double)n;
        xy[2 * i] = f32(cos(t));
        xy[2 * i + 1] = f32(sin(t));
    }
    in_err = radial_max(xy, n);
    CHECK_GT(in_err, 1e-8); /* the rounding is there */
    s.levels = 3;
    s.noise = 6e-8; /* the add-on's float32 precision at |x| <= 1 */
    s.estimate_normals = 1;
    s.normal_method = CONICA_NORMALS_CIRCLE;
    in.n = in.cap = n;
    in.xy = xy;
    in.nxy = NULL;
    in.closed = 1;
    conica_curve_init(&plain);
    conica_curve_init(&out);
    conica_subdiv_info_init(&info);
    conica_subdiv_info_init(&info0);
    REQUIRE(conica_subdivide(&in, &s, &plain, &info0, NULL) == CONICA_OK);
    CHECK_EQ_U(info0.patch_grown, 0);
    CHECK_EQ_U(info0.inflections, 0);
    for (a = 0; a < 4; a++) {
        double c = cos(angles[a]), sn = sin(angles[a]), d = 0;
        for (i = 0; i < n; i++) {
            rxy[2 * i] = c * xy[2 * i] - sn * xy[2 * i + 1];
            rxy[2 * i + 1] = sn * xy[2 * i] + c * xy[2 * i + 1];
        }
        in.xy = rxy;
        INFO("angle %g", angles[a]);
        REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
        REQUIRE_EQ_U(out.n, 8 * n);
        CHECK_EQ_U(info.inflections, 0);
        CHECK_EQ_U(info.patch_grown, 0); /* before: 480 at 0.3 and 1.65 */
        /* the same decisions as unrotated, to within 2% (before: 54%) */
        CHECK_LE(fabs((double)info.midpoint_fallbacks - (double)info0.midpoint_fallbacks),
                 0.02 * (double)info0.midpoint_fallbacks);
        for (i = 0; i < out.n; i++) {
            double x = plain.xy[2 * i], y = plain.xy[2 * i + 1];
            d = fmax(d, hypot(c * x - sn * y - out.xy[2 * i], sn * x + c * y - out.xy[2 * i + 1]));
        }
        CHECK_LE(d, 1e-14);
        /* as round as its input: inside the rounding's band (1.0005x) */
        CHECK_LE(radial_max(out.xy, out.n), 1.0005 * in_err);
        CHECK(all_finite_unit(&out));
        conica_subdiv_info_free(&info);
    }

    /* svgsmooth's input: the last rotated circle written with 7
     * significant digits (noise: half a unit of the last one). Measured:
     * 40 grown patches, before 3870 (and 8x the time); the output's radial
     * error 1.095x the input's, then and now. */
    for (i = 0; i < 2 * n; i++) {
        char buf[32];
        snprintf(buf, sizeof buf, "%.7g", rxy[i]);
        rxy[i] = strtod(buf, NULL);
    }
    in_err = radial_max(rxy, n);
    s.noise = 5e-8;
    REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
    REQUIRE_EQ_U(out.n, 8 * n);
    CHECK_EQ_U(info.inflections, 0);
    CHECK_LE((double)info.patch_grown, 200.0);
    CHECK_LE(radial_max(out.xy, out.n), 1.1 * in_err);
    conica_subdiv_info_free(&info);
    conica_subdiv_info_free(&info0);
    conica_curve_free(&plain);
    conica_curve_free(&out);
    free(xy);
    free(rxy);
}

TEST_CASE("threads give bit-identical results", "[subdiv][threads]")
{
    size_t n = 3000, i, k;
    double *xy = malloc(2 * n * sizeof *xy);
    conica_curve in, ref, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_subdiv_info i1, i2;
    int th, mode;
    REQUIRE(xy != NULL);
    for (i = 0; i < n; i++) { /* r = 1 + 0.3 cos 5t: inflection points too */
        double t = 2 * M_PI * (double)i / (double)n, r = 1 + 0.3 * cos(5 * t);
        xy[2 * i] = r * cos(t);
        xy[2 * i + 1] = r * sin(t);
    }
    in.n = in.cap = n;
    in.xy = xy;
    in.nxy = NULL;
    in.closed = 1;
    conica_curve_init(&ref);
    conica_curve_init(&out);
    conica_subdiv_info_init(&i1);
    conica_subdiv_info_init(&i2);
    for (mode = 0; mode < 2; mode++) {
        s.levels = 3;
        s.precise = mode;
        s.threads = 1;
        REQUIRE(conica_subdivide(&in, &s, &ref, &i1, NULL) == CONICA_OK);
        CHECK_GT((double)i1.inflections, 0.0);
        for (th = 2; th <= 5; th += 3) {
            s.threads = th;
            INFO("precise %d threads %d", mode, th);
            REQUIRE(conica_subdivide(&in, &s, &out, &i2, NULL) == CONICA_OK);
            REQUIRE_EQ_U(out.n, ref.n);
            CHECK(memcmp(out.xy, ref.xy, 2 * ref.n * sizeof(double)) == 0);
            CHECK(memcmp(out.nxy, ref.nxy, 2 * ref.n * sizeof(double)) == 0);
            CHECK_EQ_U(i2.inflections, i1.inflections);
            CHECK_EQ_U(i2.patch_grown, i1.patch_grown);
            CHECK_EQ_U(i2.midpoint_fallbacks, i1.midpoint_fallbacks);
            for (k = 0; k < i1.inflections; k++)
                CHECK_EQ_U(i2.inflection_index[k], i1.inflection_index[k]);
            conica_subdiv_info_free(&i2);
        }
        conica_subdiv_info_free(&i1);
    }
    conica_curve_free(&ref);
    conica_curve_free(&out);
    free(xy);
}

/* ------------------------------------------------------ misc settings */

TEST_CASE("estimated normals, ablations and statistics", "[subdiv][settings]")
{
    double xy[12], nn[12];
    conica_curve in, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_subdiv_info info;
    size_t i;
    samples_d(C_CIRCLE, xy, nn, &in);
    conica_curve_init(&out);
    conica_subdiv_info_init(&info);
    s.levels = 5;

    /* Output normals keep the input's (outward) orientation. */
    REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
    for (i = 0; i < out.n; i++)
        CHECK_GT(out.nxy[2 * i] * out.xy[2 * i] + out.nxy[2 * i + 1] * out.xy[2 * i + 1], 0.0);
    CHECK_EQ_U(info.edge_points, 6 * (1 + 2 + 4 + 8 + 16));
    CHECK_EQ_U(info.patch_grown, 0);

    /* Normals estimated from a regular hexagon are exact: still a circle. */
    in.nxy = NULL;
    REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
    CHECK_LE((double)errors_d(&conics[C_CIRCLE], &out).Emax, 2e-14);
    in.nxy = nn;

    s.normalize_normals = 1;
    REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
    CHECK_LE((double)errors_d(&conics[C_CIRCLE], &out).Emax, 1e-13);
    s.normalize_normals = 0;
    s.plain_quadratic = 1;
    REQUIRE(conica_subdivide(&in, &s, &out, &info, NULL) == CONICA_OK);
    CHECK_LE((double)errors_d(&conics[C_CIRCLE], &out).Emax, 1e-13);
    CHECK(all_finite_unit(&out));
    conica_subdiv_info_free(&info);
    conica_curve_free(&out);
}

/* The point i of n of the blob r = R (1 + 0.3 cos 3t + 0.1 sin 5t) (six
 * true inflections) around (ox, oy). */
static void blob_point(double ox, double oy, double R, size_t i, size_t n, double *x, double *y)
{
    double t = 6.283185307179586 * (double)i / (double)n;
    double r = R * (1 + 0.3 * cos(3 * t) + 0.1 * sin(5 * t));
    *x = ox + r * cos(t);
    *y = oy + r * sin(t);
}

/* The blob of n points subdivided `levels` times into *o, *info. */
static void blob_subdivide(double ox, double oy, double R, size_t n, int levels, conica_curve *o,
                           conica_subdiv_info *info)
{
    double *xy = malloc(2 * n * sizeof *xy);
    REQUIRE(xy != NULL);
    for (size_t i = 0; i < n; i++)
        blob_point(ox, oy, R, i, n, &xy[2 * i], &xy[2 * i + 1]);
    conica_curve c;
    conica_curve_init(&c);
    conica_curve_init(o);
    REQUIRE_EQ(conica_curve_set(xy, NULL, n, 1, &c, NULL), CONICA_OK);
    free(xy);
    conica_subdiv_settings s = conica_subdiv_defaults();
    s.levels = levels;
    conica_subdiv_info_init(info);
    REQUIRE_EQ(conica_subdivide(&c, &s, o, info, NULL), CONICA_OK);
    conica_curve_free(&c);
}

/* 10^6 points of the blob of radius 5 around (ox, oy), subdivided once:
 * the inflection count and the output size. */
static void blob_counts(double ox, double oy, size_t *infl, size_t *out_n)
{
    conica_curve o;
    conica_subdiv_info info;
    blob_subdivide(ox, oy, 5.0, 1000000, 1, &o, &info);
    *infl = info.inflections;
    *out_n = o.n;
    conica_subdiv_info_free(&info);
    conica_curve_free(&o);
}

TEST_CASE("the same inflection points wherever the curve sits (the coordinates' rounding)",
          "[subdiv][inflections][invariance]")
{
    /* At (5000, 3000) the turns near the six true inflections fall to the
     * coordinates' rounding (2^-41 there against 2^-51 at the origin), and
     * their exact signs flipped: 252 inflection points instead of 6. */
    size_t i0, n0, i1, n1;
    blob_counts(0, 0, &i0, &n0);
    blob_counts(5000, 3000, &i1, &n1);
    CHECK_EQ_U(i0, 6);
    CHECK_EQ_U(i1, i0);
    CHECK_EQ_U(n1, n0);
    CHECK_EQ_U(n0, 2 * (1000000 + 6));
}

/* Is output point k within w input points (2^levels output points each)
 * of an inflection point of a or b? */
static int near_infl(const conica_subdiv_info *a, const conica_subdiv_info *b, size_t k,
                     size_t w)
{
    for (int m = 0; m < 2; m++) {
        const conica_subdiv_info *f = m ? b : a;
        for (size_t i = 0; i < f->inflections; i++) {
            size_t d = f->inflection_index[i];
            if (k + w >= d && k <= d + w)
                return 1;
        }
    }
    return 0;
}

TEST_CASE("the same output and work wherever the curve sits (the working origin)",
          "[subdiv][invariance]")
{
    /* 10^5 points of the blob of radius 0.05, 4 levels: at level 4 an
     * edge's sagitta (1e-13) is below the rounding of coordinates near
     * (5000, 3000) (4.5e-13), where the levels' stored points made the
     * chords' directions as uncertain as the end normals' tilt: 3368
     * grown patches and 25 679 fallbacks against 8 and 19 at the origin.
     * Measured from the working origin (subdiv_origin.c) the far copy is
     * the near one translated, to the coordinates' rounding; only within
     * a few input points of an inflection point, whose edge the input's
     * own rounding moves (the turn's sign is noise there), may it differ. */
    const size_t n = 100000;
    const int L = 4;
    const double R = 0.05, ox = 5000, oy = 3000;
    const double ulp = nextafter(5000.0, 1e9) - 5000.0, edge = 6.283185307179586 * R / (double)n;
    conica_curve o0, o1;
    conica_subdiv_info i0, i1;
    blob_subdivide(0, 0, R, n, L, &o0, &i0);
    blob_subdivide(ox, oy, R, n, L, &o1, &i1);
    CHECK_EQ_U(i0.inflections, 6);
    CHECK_EQ_U(i1.inflections, i0.inflections);
    REQUIRE_EQ_U(o1.n, o0.n);
    CHECK_EQ_U(o0.n, (n + 6) << L);
    CHECK_LE((double)(i1.patch_grown + i1.midpoint_fallbacks),
             4.0 * (double)(i0.patch_grown + i0.midpoint_fallbacks) + 64);
    double dp = 0, dn = 0;
    size_t compared = 0;
    for (size_t k = 0; k < o0.n; k++) {
        if (near_infl(&i0, &i1, k, (size_t)32 << L))
            continue;
        dp = fmax(dp, fmax(fabs(o1.xy[2 * k] - ox - o0.xy[2 * k]),
                           fabs(o1.xy[2 * k + 1] - oy - o0.xy[2 * k + 1])));
        dn = fmax(dn, fmax(fabs(o1.nxy[2 * k] - o0.nxy[2 * k]),
                           fabs(o1.nxy[2 * k + 1] - o0.nxy[2 * k + 1])));
        compared++;
    }
    CHECK_GT((double)compared, 0.99 * (double)o0.n);
    CHECK_LE(dp, 2 * ulp);
    /* normals: the input's rounding tilts the estimated ones by ulp / edge */
    CHECK_LE(dn, 8 * ulp / edge);
    /* the input points are the output's old vertices bit for bit */
    size_t j = 0, m = 0, bad = 0;
    for (size_t k = 0; k < o1.n >> L; k++) {
        if (m < i1.inflections && i1.inflection_index[m] == k << L) {
            m++;
            continue;
        }
        double x, y;
        blob_point(ox, oy, R, j++, n, &x, &y);
        bad += o1.xy[2 * (k << L)] != x || o1.xy[2 * (k << L) + 1] != y;
    }
    CHECK_EQ_U(j, n);
    CHECK_EQ_U(bad, 0);
    conica_subdiv_info_free(&i0);
    conica_subdiv_info_free(&i1);
    conica_curve_free(&o0);
    conica_curve_free(&o1);
}

/* SPDX-License-Identifier: MIT */
/* conica/simplify.h on jittered samples of known curves (fixed seeds): the
 * curve smoothed through the kept vertices, measured here independently
 * (dense point-to-polyline distance against the whole smoothed polyline,
 * not the piece the library measures), passes within T of every sample and
 * within 2T of the true curve; few vertices are kept; corners are kept. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/path.h"
#include "conica/simplify.h"
#include "conica_test.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* xorshift64*: a fixed sequence on every platform */
static double rnd(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

/* Distance of p to segment ab: to the line where the foot of the
 * perpendicular falls inside, else to the nearer end. */
static double seg_dist(const double *p, const double *a, const double *b)
{
    double ux = b[0] - a[0], uy = b[1] - a[1], len = hypot(ux, uy);
    double along = len > 0 ? ((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / len : -1;
    if (along < 0 || along > len)
        return fmin(hypot(p[0] - a[0], p[1] - a[1]), hypot(p[0] - b[0], p[1] - b[1]));
    return fabs((p[0] - a[0]) * uy - (p[1] - a[1]) * ux) / len;
}

/* Distance of p to the polyline q (closed: with its closing edge). */
static double poly_dist(const double *p, const double *q, size_t n, int closed)
{
    double d = HUGE_VAL;
    size_t i;
    for (i = 0; i + 1 < n; i++)
        d = fmin(d, seg_dist(p, q + 2 * i, q + 2 * i + 2));
    if (closed && n > 1)
        d = fmin(d, seg_dist(p, q + 2 * (n - 1), q));
    if (n == 1)
        d = hypot(p[0] - q[0], p[1] - q[1]);
    return d;
}

typedef struct outcome {
    size_t kept;
    double to_samples; /* largest distance of a sample from the smoothed curve */
    double to_truth;   /* largest distance of the smoothed curve from the true one */
    int has[8];        /* whether the checked indices were kept */
    int near[8];       /* whether a kept vertex lies within the tolerance of them */
} outcome;

/* Simplify (vertices set in `mask` kept; mask may be NULL), smooth the
 * kept vertices as the tools do, and measure. */
static outcome run_masked(const double *xy, size_t n, int closed, double tol, const double *truth,
                          size_t nt, const size_t *want, size_t nwant, const unsigned char *mask)
{
    conica_simplify_settings s = conica_simplify_defaults();
    conica_simplify_info info;
    conica_path p;
    conica_path_result r;
    size_t *keep = malloc(n * sizeof *keep), m = 0, i, j;
    double *kxy = malloc(2 * n * sizeof *kxy);
    outcome o;
    memset(&o, 0, sizeof o);
    REQUIRE(keep != NULL);
    REQUIRE(kxy != NULL);
    s.tolerance = tol;
    s.keep_mask = mask;
    REQUIRE(conica_simplify(xy, n, closed, &s, keep, &m, &info, NULL) == CONICA_OK);
    CHECK_EQ_U(info.kept, m);
    CHECK_EQ(info.kept_all, 0);
    CHECK_LE(info.deviation, tol);
    for (i = 0; i < m; i++) {
        if (i)
            REQUIRE(keep[i] > keep[i - 1]);
        kxy[2 * i] = xy[2 * keep[i]];
        kxy[2 * i + 1] = xy[2 * keep[i] + 1];
        for (j = 0; j < nwant; j++) {
            if (keep[i] == want[j])
                o.has[j] = 1;
            if (hypot(xy[2 * keep[i]] - xy[2 * want[j]], xy[2 * keep[i] + 1] - xy[2 * want[j] + 1]) <=
                tol)
                o.near[j] = 1;
        }
    }
    o.kept = m;
    conica_path_init(&p);
    conica_path_result_init(&r);
    REQUIRE(conica_path_samples(&p, kxy, NULL, m, closed, 0, NULL) == CONICA_OK);
    REQUIRE(conica_path_smooth(&p, &s.path, &r, NULL) == CONICA_OK);
    REQUIRE_EQ_U(r.n, 1);
    for (i = 0; i < n; i++)
        o.to_samples = fmax(o.to_samples, poly_dist(xy + 2 * i, r.lines[0].xy, r.lines[0].n,
                                                    closed));
    for (i = 0; truth && i < r.lines[0].n; i++)
        o.to_truth = fmax(o.to_truth, poly_dist(r.lines[0].xy + 2 * i, truth, nt, closed));
    conica_path_result_free(&r);
    conica_path_free(&p);
    free(keep);
    free(kxy);
    return o;
}

static outcome run(const double *xy, size_t n, int closed, double tol, const double *truth,
                   size_t nt, const size_t *want, size_t nwant)
{
    return run_masked(xy, n, closed, tol, truth, nt, want, nwant, NULL);
}

#define DENSE 20000

TEST_CASE("simplify: jittered circle, ellipse and cubic within T of the samples and 2T of "
          "the curve",
          "[simplify]")
{
    static double xy[2 * 400], truth[2 * DENSE];
    const double tol = 0.05;
    int shape;
    for (shape = 0; shape < 3; shape++) {
        uint64_t seed = 0x9E3779B97F4A7C15ULL + (uint64_t)(unsigned)shape;
        size_t n = 240, i;
        int closed = shape < 2;
        outcome o;
        for (i = 0; i < DENSE; i++) {
            double t = (double)i / (closed ? DENSE : DENSE - 1);
            if (shape == 0) {
                truth[2 * i] = 10 * cos(2 * M_PI * t);
                truth[2 * i + 1] = 10 * sin(2 * M_PI * t);
            } else if (shape == 1) {
                truth[2 * i] = 20 * cos(2 * M_PI * t);
                truth[2 * i + 1] = 8 * sin(2 * M_PI * t);
            } else { /* cubic Bezier (0,0) (10,25) (30,-15) (40,10) */
                double u = 1 - t;
                truth[2 * i] = 3 * u * u * t * 10 + 3 * u * t * t * 30 + t * t * t * 40;
                truth[2 * i + 1] = 3 * u * u * t * 25 + 3 * u * t * t * -15 + t * t * t * 10;
            }
        }
        for (i = 0; i < n; i++) {
            size_t k = closed ? i * DENSE / n : i * (DENSE - 1) / (n - 1);
            double a = 2 * M_PI * rnd(&seed), rr = 0.4 * tol * rnd(&seed);
            xy[2 * i] = truth[2 * k] + rr * cos(a);
            xy[2 * i + 1] = truth[2 * k + 1] + rr * sin(a);
        }
        o = run(xy, n, closed, tol, truth, DENSE, NULL, 0);
        INFO("shape %d: %zu of %zu kept, %.4f from the samples, %.4f from the curve", shape,
             o.kept, n, o.to_samples, o.to_truth);
        CHECK_LE(o.to_samples, tol * (1 + 1e-9));
        CHECK_LE(o.to_truth, 2 * tol);
        CHECK_LE(o.kept, (size_t)(shape == 0 ? 16 : shape == 1 ? 24 : 16));
        CHECK_GE(o.kept, (size_t)(closed ? 3 : 2));
    }
}

TEST_CASE("simplify: a jittered square keeps its four corners", "[simplify]")
{
    double xy[2 * 160];
    size_t corners[4] = {0, 40, 80, 120}, i, k;
    const double tol = 0.05;
    uint64_t seed = 42;
    outcome o;
    for (i = 0; i < 160; i++) {
        double t = (double)(i % 40) / 40 * 10, x, y;
        switch (i / 40) {
        case 0: x = t, y = 0; break;
        case 1: x = 10, y = t; break;
        case 2: x = 10 - t, y = 10; break;
        default: x = 0, y = 10 - t; break;
        }
        if (i % 40) { /* corners exact, edges jittered */
            x += (rnd(&seed) - 0.5) * 0.4 * tol;
            y += (rnd(&seed) - 0.5) * 0.4 * tol;
        }
        xy[2 * i] = x;
        xy[2 * i + 1] = y;
    }
    o = run(xy, 160, 1, tol, NULL, 0, corners, 4);
    INFO("%zu of 160 kept, %.4f from the samples", o.kept, o.to_samples);
    for (k = 0; k < 4; k++)
        CHECK(o.has[k]);
    CHECK_LE(o.to_samples, tol * (1 + 1e-9));
    CHECK_LE(o.kept, (size_t)40);
}

TEST_CASE("simplify: dense traces, jitter above the spacing: few vertices, no false corners, "
          "true corners kept",
          "[simplify]")
{
    static double xy[2 * 8000];
    const double tol = 0.05;
    size_t n = 8000, i, corners[4] = {0, 2000, 4000, 6000}, k;
    uint64_t seed = 99;
    outcome o;
    /* a circle of radius 10 sampled every 0.008, jitter up to 0.02 */
    for (i = 0; i < n; i++) {
        double t = 2 * M_PI * (double)i / (double)n, a = 2 * M_PI * rnd(&seed);
        double rr = 0.4 * tol * rnd(&seed);
        xy[2 * i] = 10 * cos(t) + rr * cos(a);
        xy[2 * i + 1] = 10 * sin(t) + rr * sin(a);
    }
    o = run(xy, n, 1, tol, NULL, 0, NULL, 0);
    INFO("circle: %zu of %zu kept, %.4f from the samples", o.kept, n, o.to_samples);
    CHECK_LE(o.to_samples, tol * (1 + 1e-9));
    CHECK_LE(o.kept, (size_t)24);
    /* a square of side 10 sampled every 0.005, edges jittered, corners exact */
    for (i = 0; i < n; i++) {
        double t = (double)(i % 2000) / 200, x, y;
        switch (i / 2000) {
        case 0: x = t, y = 0; break;
        case 1: x = 10, y = t; break;
        case 2: x = 10 - t, y = 10; break;
        default: x = 0, y = 10 - t; break;
        }
        if (i % 2000) {
            x += (rnd(&seed) - 0.5) * 0.4 * tol;
            y += (rnd(&seed) - 0.5) * 0.4 * tol;
        }
        xy[2 * i] = x;
        xy[2 * i + 1] = y;
    }
    o = run(xy, n, 1, tol, NULL, 0, corners, 4);
    INFO("square: %zu of %zu kept, %.4f from the samples", o.kept, n, o.to_samples);
    /* judged at the tolerance's scale, the corner may be a neighbour of the
     * exact vertex within the jitter */
    for (k = 0; k < 4; k++)
        CHECK(o.near[k]);
    CHECK_LE(o.to_samples, tol * (1 + 1e-9));
    CHECK_LE(o.kept, (size_t)40);
}

TEST_CASE("simplify: deterministic, tighter tolerance keeps more, coincident points", "[simplify]")
{
    double xy[2 * 121];
    size_t a[121], b[121], c[121], na, nb, nc, i;
    conica_simplify_settings s = conica_simplify_defaults();
    uint64_t seed = 7;
    for (i = 0; i < 120; i++) {
        double t = 2 * M_PI * (double)i / 120;
        xy[2 * i] = 5 * cos(t) + 0.01 * rnd(&seed);
        xy[2 * i + 1] = 3 * sin(t) + 0.01 * rnd(&seed);
    }
    xy[240] = xy[0]; /* a closing vertex equal to the first */
    xy[241] = xy[1];
    s.tolerance = 0.05;
    REQUIRE(conica_simplify(xy, 121, 1, &s, a, &na, NULL, NULL) == CONICA_OK);
    REQUIRE(conica_simplify(xy, 121, 1, &s, b, &nb, NULL, NULL) == CONICA_OK);
    REQUIRE_EQ_U(na, nb);
    CHECK(memcmp(a, b, na * sizeof *a) == 0);
    for (i = 0; i < na; i++)
        CHECK_LT(a[i], (size_t)120); /* the repeated first vertex is not kept twice */
    s.tolerance = 0.005;
    REQUIRE(conica_simplify(xy, 121, 1, &s, c, &nc, NULL, NULL) == CONICA_OK);
    CHECK_GT(nc, na);
}

TEST_CASE("simplify: vertices the caller marks are kept, the curve still within T", "[simplify]")
{
    enum { N = 200 };
    double xy[2 * N];
    unsigned char mask[N];
    size_t want[4] = {17, 18, 101, 199}, i;
    uint64_t seed = 11;
    outcome plain, masked;
    for (i = 0; i < N; i++) { /* a jittered open wave */
        double t = 4 * M_PI * (double)i / (N - 1);
        xy[2 * i] = t + 0.01 * rnd(&seed);
        xy[2 * i + 1] = sin(t) + 0.01 * rnd(&seed);
    }
    memset(mask, 0, sizeof mask);
    plain = run(xy, N, 0, 0.05, NULL, 0, want, 3);
    CHECK_EQ(plain.has[0] && plain.has[1] && plain.has[2], 0); /* not all kept unasked */
    for (i = 0; i < 3; i++)
        mask[want[i]] = 1;
    masked = run_masked(xy, N, 0, 0.05, NULL, 0, want, 3, mask);
    CHECK(masked.has[0]);
    CHECK(masked.has[1]);
    CHECK(masked.has[2]);
    CHECK_LE(masked.to_samples, 0.05 * (1 + 1e-9));
    CHECK_LT(masked.kept, (size_t)N / 4); /* the rest still simplified */
    /* a closed curve: marked vertices kept, a repeated closing vertex never */
    for (i = 0; i < N; i++) {
        double t = 2 * M_PI * (double)i / (N - 1);
        xy[2 * i] = 5 * cos(t) + 0.01 * rnd(&seed);
        xy[2 * i + 1] = 3 * sin(t) + 0.01 * rnd(&seed);
    }
    xy[2 * N - 2] = xy[0];
    xy[2 * N - 1] = xy[1];
    memset(mask, 0, sizeof mask);
    mask[N - 1] = 1;
    mask[50] = 1;
    masked = run_masked(xy, N, 1, 0.05, NULL, 0, want, 4, mask);
    CHECK(masked.has[3] == 0); /* the copy itself is never kept */
    {
        size_t fifty = 50;
        outcome f = run_masked(xy, N, 1, 0.05, NULL, 0, &fifty, 1, mask);
        CHECK(f.has[0]);
        CHECK_LE(f.to_samples, 0.05 * (1 + 1e-9));
    }
}

TEST_CASE("simplify: bad arguments", "[simplify]")
{
    double xy[6] = {0, 0, 1, 0.01, 2, 0};
    size_t keep[3], m = 99;
    conica_simplify_settings s = conica_simplify_defaults();
    conica_status st;
    CHECK(conica_simplify(NULL, 3, 0, &s, keep, &m, NULL, &st) == CONICA_ERR_ARG);
    CHECK(conica_simplify(xy, 1, 0, &s, keep, &m, NULL, &st) == CONICA_ERR_ARG);
    s.tolerance = -1;
    CHECK(conica_simplify(xy, 3, 0, &s, keep, &m, NULL, &st) == CONICA_ERR_ARG);
    s.tolerance = 0.1;
    s.max_rounds = 0;
    CHECK(conica_simplify(xy, 3, 0, &s, keep, &m, NULL, &st) == CONICA_ERR_ARG);
    s.max_rounds = 8;
    xy[3] = NAN;
    CHECK(conica_simplify(xy, 3, 0, &s, keep, &m, NULL, &st) == CONICA_ERR_NONFINITE);
    CHECK_EQ_U(st.offset, 1);
    CHECK_EQ_U(m, 99); /* outputs untouched on failure */
    xy[3] = 0.01;
    REQUIRE(conica_simplify(xy, 3, 0, &s, keep, &m, NULL, &st) == CONICA_OK);
    CHECK_EQ_U(m, 2); /* nearly straight: its ends */
    xy[3] = 1; /* a 45-degree turn is a corner (40 by default): kept */
    REQUIRE(conica_simplify(xy, 3, 0, &s, keep, &m, NULL, &st) == CONICA_OK);
    CHECK_EQ_U(m, 3);
}

/* SPDX-License-Identifier: MIT */
/* The progress reports of long calls (conica_progress_fn in the settings of
 * conica_subdivide, conica_path_smooth/_flatten and conica_svg_process):
 * reports rise monotonically to the total, arrive a bounded number of
 * times, and the results are the same with and without them (also with
 * threads, whose levels are then cut into slices). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/path.h"
#include "conica/subdiv.h"
#include "conica_svg.h"
#include "conica_test.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct report_log {
    size_t calls, last, total, backwards, total_changed;
} report_log;

static void record(void *ctx, size_t done, size_t total)
{
    report_log *l = ctx;
    if (l->calls > 0 && done < l->last)
        l->backwards++;
    if (l->calls > 0 && total != l->total)
        l->total_changed++;
    l->calls++;
    l->last = done;
    l->total = total;
}

static void check_log(const report_log *l, size_t max_calls)
{
    INFO("calls %zu, last %zu of %zu", l->calls, l->last, l->total);
    CHECK(l->calls >= 2);
    CHECK(l->calls <= max_calls);
    CHECK_EQ(l->backwards, 0);
    CHECK_EQ(l->total_changed, 0);
    CHECK_EQ(l->last, l->total);
}

/* An ellipse of n samples with exact normals. */
static void ellipse(conica_curve *c, size_t n)
{
    double *xy = malloc(2 * n * sizeof *xy), *nxy = malloc(2 * n * sizeof *nxy);
    size_t i;
    REQUIRE(xy && nxy);
    for (i = 0; i < n; i++) {
        double t = 2 * M_PI * (double)i / (double)n, a = 3, b = 2;
        double nx = b * cos(t), ny = a * sin(t), len = hypot(nx, ny);
        xy[2 * i] = a * cos(t);
        xy[2 * i + 1] = b * sin(t);
        nxy[2 * i] = nx / len;
        nxy[2 * i + 1] = ny / len;
    }
    REQUIRE(conica_curve_set(xy, nxy, n, 1, c, NULL) == CONICA_OK);
    free(xy);
    free(nxy);
}

TEST_CASE("subdivision reports its edge points and writes the same points", "[progress][subdiv]")
{
    conica_curve in, plain, reported;
    conica_subdiv_settings s = conica_subdiv_defaults();
    int threads;
    conica_curve_init(&in);
    ellipse(&in, 24);
    s.levels = 13; /* 24 * 2^13 = 196 608 points: many slices */
    for (threads = 1; threads <= 2; threads++) {
        report_log l;
        memset(&l, 0, sizeof l);
        conica_curve_init(&plain);
        conica_curve_init(&reported);
        s.threads = threads;
        s.progress = NULL;
        REQUIRE(conica_subdivide(&in, &s, &plain, NULL, NULL) == CONICA_OK);
        s.progress = record;
        s.progress_ctx = &l;
        REQUIRE(conica_subdivide(&in, &s, &reported, NULL, NULL) == CONICA_OK);
        INFO("threads %d", threads);
        check_log(&l, 600);
        CHECK_EQ(l.total, plain.n - in.n);
        REQUIRE_EQ(plain.n, reported.n);
        CHECK(memcmp(plain.xy, reported.xy, 2 * plain.n * sizeof *plain.xy) == 0);
        CHECK(memcmp(plain.nxy, reported.nxy, 2 * plain.n * sizeof *plain.nxy) == 0);
        conica_curve_free(&plain);
        conica_curve_free(&reported);
    }
    conica_curve_free(&in);
}

/* A path of `m` subpaths, each a closed polygon of quarter-circle arcs and
 * straight pieces (so that it has several pieces). */
static void build_path(conica_path *p, size_t m)
{
    size_t k;
    conica_path_init(p);
    for (k = 0; k < m; k++) {
        double ox = 10.0 * (double)k, q[4];
        REQUIRE(conica_path_move_to(p, ox, 0, 0, NULL) == CONICA_OK);
        REQUIRE(conica_path_line_to(p, ox + 4, 0, 0, NULL) == CONICA_OK);
        q[0] = ox + 6;
        q[1] = 0;
        q[2] = ox + 6;
        q[3] = 2;
        REQUIRE(conica_path_bezier_to(p, 2, q, NULL, 0, NULL) == CONICA_OK);
        REQUIRE(conica_path_line_to(p, ox + 6, 4, 0, NULL) == CONICA_OK);
        q[0] = ox + 3;
        q[1] = 7;
        q[2] = ox;
        q[3] = 4;
        REQUIRE(conica_path_bezier_to(p, 2, q, NULL, 0, NULL) == CONICA_OK);
        REQUIRE(conica_path_close(p, NULL) == CONICA_OK);
    }
}

static int same_result(const conica_path_result *a, const conica_path_result *b)
{
    size_t i;
    if (a->n != b->n)
        return 0;
    for (i = 0; i < a->n; i++)
        if (a->lines[i].n != b->lines[i].n ||
            memcmp(a->lines[i].xy, b->lines[i].xy, 2 * a->lines[i].n * sizeof(double)))
            return 0;
    return 1;
}

TEST_CASE("the curve front end reports segments done and gives the same result",
          "[progress][path]")
{
    conica_path p;
    int smooth;
    build_path(&p, 2000);
    for (smooth = 0; smooth <= 1; smooth++) {
        conica_path_settings s = conica_path_defaults();
        conica_path_result plain, reported;
        report_log l;
        memset(&l, 0, sizeof l);
        conica_path_result_init(&plain);
        conica_path_result_init(&reported);
        s.tolerance = 0.01;
        REQUIRE((smooth ? conica_path_smooth : conica_path_flatten)(&p, &s, &plain, NULL) ==
                CONICA_OK);
        s.progress = record;
        s.progress_ctx = &l;
        REQUIRE((smooth ? conica_path_smooth : conica_path_flatten)(&p, &s, &reported, NULL) ==
                CONICA_OK);
        INFO("smooth %d", smooth);
        check_log(&l, 2 * 256 + 2001 + 2);
        CHECK_EQ(l.total, p.nseg);
        CHECK(same_result(&plain, &reported));
        conica_path_result_free(&plain);
        conica_path_result_free(&reported);
    }
    conica_path_free(&p);
}

TEST_CASE("svg processing reports bytes of path data, also within one long path",
          "[progress][svg]")
{
    /* one path of 3000 subpaths (the within-path reports) and a polygon */
    size_t cap = 3000 * 80 + 512, n = 0, k, path_bytes;
    char *doc_text = malloc(cap);
    conica_svg_doc *doc = NULL;
    conica_svg_settings s = conica_svg_defaults();
    report_log l;
    REQUIRE(doc_text != NULL);
    n += (size_t)snprintf(doc_text + n, cap - n,
                          "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"");
    path_bytes = n;
    for (k = 0; k < 3000; k++)
        n += (size_t)snprintf(doc_text + n, cap - n, "M%zu 0l4 0q2 0 2 2l0 2q-3 3-6 0z",
                              10 * k);
    path_bytes = n - path_bytes;
    n += (size_t)snprintf(doc_text + n, cap - n,
                          "\"/><polygon points=\"0 0 5 0 5 5\"/></svg>");
    REQUIRE(conica_svg_doc_load(doc_text, n, NULL, &doc, NULL) == CONICA_OK);
    memset(&l, 0, sizeof l);
    s.progress = record;
    s.progress_ctx = &l;
    REQUIRE(conica_svg_process(doc, &s, NULL, NULL) == CONICA_OK);
    check_log(&l, 300 + 8);
    CHECK_EQ(l.total, path_bytes + strlen("0 0 5 0 5 5"));
    CHECK(l.calls > 100); /* inside the one long path, not only after it */
    conica_svg_doc_free(doc);
    free(doc_text);
}

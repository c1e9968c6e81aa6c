/* SPDX-License-Identifier: MIT */
/* bench_svg: what the SVG layer costs next to the geometry it feeds
 * (issue 6). A generated document of 10 000 closed subpaths with 100
 * on-curve vertices each (10^6 vertices; half the segments straight, half
 * cubic with exact tangents) goes through svgsmooth's pipeline in process:
 * XML parse, path parse + geometry + path writing (conica_svg_process,
 * which splits its own time), XML save; then as svgsmooth itself runs it,
 * processed and written in one pass (conica_svg_process_write). Modes:
 * smoothing with 3 levels and flattening within 0.01 units. Prints
 * figures, asserts nothing.
 *
 *   build/bench/bench_svg [--write FILE] [SUBPATHS [VERTICES]]
 *   build/bench/bench_svg --samples     (the samples run below alone)
 *
 * --write FILE also saves the generated document, for timing the tool end
 * to end: `build/bin/svgsmooth --stats --levels 3 -o out.svg FILE`.
 *
 * Then samples through the front end (issue 16, "Large curves"): a closed
 * polygon of 20 000 float32-rounded points of a circle, what Blender's
 * POLY splines and `svgsmooth --lines-as-samples` give conica_path, at
 * level 7 with no corners: conica_path_smooth() beside conica_subdivide()
 * alone on the same samples (normals estimated alike), best of 3.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "conica/curve.h"
#include "conica/path.h"
#include "conica/subdiv.h"
#include "conica_svg.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct text {
    char *s;
    size_t n, cap;
} text;

static void put(text *t, const char *fmt, double a, double b)
{
    int k;
    if (t->cap - t->n < 128) {
        t->cap = 2 * t->cap + 4096;
        t->s = realloc(t->s, t->cap);
        if (!t->s) {
            fprintf(stderr, "bench_svg: out of memory\n");
            exit(1);
        }
    }
    k = snprintf(t->s + t->n, t->cap - t->n, fmt, a, b);
    t->n += (size_t)k;
}

/* Polar blob r(th) = R (1 + 0.15 sin(3 th + ph)) and its derivative. */
static void blob(double cx, double cy, double ph, double th, double p[2], double d[2])
{
    const double R = 20.0;
    double r = R * (1.0 + 0.15 * sin(3.0 * th + ph)), dr = R * 0.45 * cos(3.0 * th + ph);
    p[0] = cx + r * cos(th);
    p[1] = cy + r * sin(th);
    d[0] = dr * cos(th) - r * sin(th);
    d[1] = dr * sin(th) + r * cos(th);
}

static text make_doc(size_t nsub, size_t nv)
{
    text t = {NULL, 0, 0};
    size_t i, j, side = (size_t)ceil(sqrt((double)nsub));
    double h = 2.0 * M_PI / (double)nv;
    put(&t, "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\">\n", 0, 0);
    for (i = 0; i < nsub; i++) {
        double cx = 50.0 * (double)(i % side), cy = 50.0 * (double)(i / side), ph = 0.37 * (double)i;
        double p[2], d[2], q[2], e[2];
        if (i % 10 == 0)
            put(&t, "<path d=\"", 0, 0);
        blob(cx, cy, ph, 0.0, p, d);
        put(&t, "M%.7g %.7g", p[0], p[1]);
        for (j = 1; j <= nv; j++) {
            double th = (double)(j % nv) * h;
            blob(cx, cy, ph, th, q, e);
            if (j % 2) {
                put(&t, "L%.7g %.7g", q[0], q[1]);
            } else {
                put(&t, "C%.7g %.7g", p[0] + d[0] * h / 3.0, p[1] + d[1] * h / 3.0);
                put(&t, " %.7g %.7g", q[0] - e[0] * h / 3.0, q[1] - e[1] * h / 3.0);
                put(&t, " %.7g %.7g", q[0], q[1]);
            }
            p[0] = q[0], p[1] = q[1], d[0] = e[0], d[1] = e[1];
        }
        put(&t, "Z", 0, 0);
        if (i % 10 == 9 || i + 1 == nsub)
            put(&t, "\"/>\n", 0, 0);
    }
    put(&t, "</svg>\n", 0, 0);
    return t;
}

static int run(const char *label, const text *doc, const conica_svg_settings *s)
{
    conica_svg_doc *d = NULL;
    conica_svg_stats stats;
    conica_status st;
    char *out = NULL;
    size_t outlen = 0;
    double t0, t_load, t_proc, t_save, layer;
    t0 = now();
    if (conica_svg_doc_load(doc->s, doc->n, &s->limits, &d, &st) != CONICA_OK) {
        fprintf(stderr, "bench_svg: load: %s\n", st.message);
        return 1;
    }
    t_load = now() - t0;
    t0 = now();
    if (conica_svg_process(d, s, &stats, &st) != CONICA_OK) {
        fprintf(stderr, "bench_svg: %s: %s\n", label, st.message);
        conica_svg_doc_free(d);
        return 1;
    }
    t_proc = now() - t0;
    t0 = now();
    if (conica_svg_doc_save(d, &out, &outlen, &st) != CONICA_OK) {
        fprintf(stderr, "bench_svg: save: %s\n", st.message);
        conica_svg_doc_free(d);
        return 1;
    }
    t_save = now() - t0;
    layer = t_load + stats.io_seconds + t_save;
    printf("%-22s %10zu %10zu %11.1f %8.3f %8.3f %8.3f %9.3f %8.3f %6.2f\n", label,
           stats.in_vertices, stats.out_points, (double)outlen / 1e6, t_load, stats.io_seconds,
           t_save, stats.geometry_seconds, t_load + t_proc + t_save,
           stats.geometry_seconds > 0 ? layer / stats.geometry_seconds : 0.0);
    conica_svg_buffer_free(out);
    conica_svg_doc_free(d);
    return 0;
}

/* svgsmooth's own path, end to end: the document loaded from a buffer it
 * takes over, then processed and written in one pass
 * (conica_svg_process_write) into a temporary file. CPU seconds (user +
 * system) of the whole, and the file's size. */
static int run_stream(const char *label, const text *doc, const conica_svg_settings *s)
{
    conica_svg_doc *d = NULL;
    conica_status st;
    char *buf = malloc(doc->n);
    FILE *f = tmpfile();
    double t0, t;
    long size;
    if (!buf || !f) {
        fprintf(stderr, "bench_svg: out of memory or no temporary file\n");
        free(buf);
        if (f)
            fclose(f);
        return 1;
    }
    memcpy(buf, doc->s, doc->n);
    t0 = now();
    if (conica_svg_doc_load_owned(buf, doc->n, &s->limits, &d, &st) != CONICA_OK) {
        fprintf(stderr, "bench_svg: load: %s\n", st.message);
        free(buf);
        fclose(f);
        return 1;
    }
    if (conica_svg_process_write(d, s, NULL, f, &st) != CONICA_OK || fflush(f) != 0) {
        fprintf(stderr, "bench_svg: %s: %s\n", label, st.message);
        conica_svg_doc_free(d);
        fclose(f);
        return 1;
    }
    conica_svg_doc_free(d);
    t = now() - t0;
    size = ftell(f);
    fclose(f);
    printf("%-34s %11.1f %9.3f\n", label, (double)size / 1e6, t);
    return 0;
}

/* The 20 000-point circle through conica_path and through conica_subdivide
 * alone: CPU seconds (best of 3) and points of each. */
static int samples_run(void)
{
    const size_t n = 20000;
    const int levels = 7;
    double *xy = malloc(2 * n * sizeof *xy), best[2] = {INFINITY, INFINITY};
    size_t i, pts[2] = {0, 0};
    int rep, rc = 0;
    if (!xy)
        return 1;
    for (i = 0; i < n; i++) {
        double a = 2 * M_PI * (double)i / (double)n;
        xy[2 * i] = (double)(float)cos(a);
        xy[2 * i + 1] = (double)(float)sin(a);
    }
    for (rep = 0; rep < 3 && !rc; rep++) {
        conica_path p;
        conica_path_result r;
        conica_path_settings ps = conica_path_defaults();
        conica_curve in, out;
        conica_subdiv_settings ss = conica_subdiv_defaults();
        double t0;
        conica_path_init(&p);
        conica_path_result_init(&r);
        ps.levels = levels;
        ps.corner_angle = M_PI;
        ps.precision = conica_path_float32_precision(1.0);
        t0 = now();
        if (conica_path_samples(&p, xy, NULL, n, 1, 0, NULL) != CONICA_OK ||
            conica_path_smooth(&p, &ps, &r, NULL) != CONICA_OK)
            rc = 1;
        best[0] = fmin(best[0], now() - t0);
        pts[0] = r.points;
        conica_path_result_free(&r);
        conica_path_free(&p);
        conica_curve_init(&in);
        conica_curve_init(&out);
        ss.levels = levels;
        ss.noise = ps.precision;
        t0 = now();
        if (conica_curve_set(xy, NULL, n, 1, &in, NULL) != CONICA_OK ||
            conica_curve_estimate_normals(&in, CONICA_NORMALS_CIRCLE, NULL) != CONICA_OK ||
            conica_subdivide(&in, &ss, &out, NULL, NULL) != CONICA_OK)
            rc = 1;
        best[1] = fmin(best[1], now() - t0);
        pts[1] = out.n;
        conica_curve_free(&in);
        conica_curve_free(&out);
    }
    free(xy);
    if (rc) {
        fprintf(stderr, "bench_svg: the samples run failed\n");
        return 1;
    }
    printf("\nsamples: closed float32 circle of %zu points, level %d, no corners (CPU s, best of 3)\n\n",
           n, levels);
    printf("%-34s %10s %9s\n", "call", "points", "CPU s");
    printf("%-34s %10zu %9.3f\n", "conica_path_smooth (samples)", pts[0], best[0]);
    printf("%-34s %10zu %9.3f\n", "conica_subdivide alone", pts[1], best[1]);
    printf("%-34s %10s %9.2f\n", "front end / subdivision", "", best[0] / best[1]);
    return 0;
}

int main(int argc, char **argv)
{
    const char *write_to = NULL;
    size_t nsub, nv;
    conica_svg_settings modes[2];
    text doc;
    int rc = 0;
    if (argc == 2 && !strcmp(argv[1], "--samples"))
        return samples_run();
    if (argc > 2 && !strcmp(argv[1], "--write")) {
        write_to = argv[2];
        argc -= 2;
        argv += 2;
    }
    nsub = argc > 1 ? (size_t)atol(argv[1]) : 10000;
    nv = argc > 2 ? (size_t)atol(argv[2]) : 100;
    if (nsub == 0 || nv < 4 || nv % 2) {
        fprintf(stderr, "usage: bench_svg [--write FILE] [SUBPATHS [EVEN VERTICES >= 4]] | --samples\n");
        return 2;
    }
    doc = make_doc(nsub, nv);
    if (write_to) {
        FILE *f = fopen(write_to, "wb");
        if (!f || fwrite(doc.s, 1, doc.n, f) != doc.n || fclose(f) != 0) {
            fprintf(stderr, "bench_svg: cannot write %s\n", write_to);
            return 1;
        }
    }
    printf("bench_svg: %zu subpaths x %zu vertices (half lines, half cubics), %.1f MB of SVG\n",
           nsub, nv, (double)doc.n / 1e6);
    printf("SVG layer = XML parse + path parse/write + XML save; ratio = SVG layer / geometry\n\n");
    printf("%-22s %10s %10s %11s %8s %8s %8s %9s %8s %6s\n", "mode", "vertices", "points",
           "out MB", "XML in", "path I/O", "XML out", "geometry", "total s", "ratio");
    modes[0] = modes[1] = conica_svg_defaults();
    modes[0].levels = 3;
    modes[1].mode = CONICA_SVG_FLATTEN;
    modes[1].tolerance = 0.01;
    rc |= run("smooth --levels 3", &doc, &modes[0]);
    rc |= run("flatten --tolerance .01", &doc, &modes[1]);
    printf("\nas svgsmooth runs it: load, then process and write in one pass to a file\n"
           "(conica_svg_process_write), CPU s user + system\n\n");
    printf("%-34s %11s %9s\n", "mode", "out MB", "CPU s");
    rc |= run_stream("smooth --levels 3, streamed", &doc, &modes[0]);
    rc |= run_stream("flatten --tolerance .01, streamed", &doc, &modes[1]);
    free(doc.s);
    rc |= samples_run();
    return rc;
}

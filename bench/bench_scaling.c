/* SPDX-License-Identifier: MIT */
/* Scaling (issue 38): CPU time and peak memory of the engines from 10^3 to
 * 10^6 items, with the local slope d log(time) / d log(n) between
 * successive sizes (1.00: linear). Each run is a child process of its own,
 * so its peak RSS (wait4) is its own; its CPU time is the job's
 * (CLOCK_PROCESS_CPUTIME_ID around it, input generation excluded). Prints
 * figures, asserts nothing.
 *
 *   plot            conica_plot, guaranteed, T = 0.01, a clamped uniform
 *                   cubic wave y = sin(0.3 i) of n control points
 *   path flatten    conica_path_flatten, tolerance 0.01, one subpath of n
 *                   C1 cubic segments of a wave; beside it
 *   plot_bezier     conica_plot_bezier on the same n cubics one by one
 *                   (the plotter without the front end)
 *   svg one-path    conica_svg_doc_load + conica_svg_process + save of one
 *                   <polyline> of n vertices (a serpentine wave, rows of
 *                   10^4, 3 decimals), smoothing at 3 levels, and flattening
 *                   within 0.01
 *   svg many-path   the same vertices in n / 100 <polyline>s
 *   subdivide       conica_subdivide, 4 levels, the closed blob r = 100 (1 +
 *                   0.3 cos 3t + 0.1 sin 5t) of n points at the origin and
 *                   at (5000, 3000), with the inflection points inserted
 *
 *   build/bench/bench_scaling [--max N]   (largest n, default 10^6)
 *   build/bench/bench_scaling --blob N R LEVELS   (the blob of radius R at
 *       the origin and at (5000, 3000): counts, CPU and how far apart) */
#define _DEFAULT_SOURCE /* wait4 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "conica/bspline.h"
#include "conica/curve.h"
#include "conica/path.h"
#include "conica/plot.h"
#include "conica/subdiv.h"
#include "conica_svg.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

enum {
    J_PLOT,
    J_FLATTEN,
    J_BEZIER,
    J_SVG_ONE_SMOOTH,
    J_SVG_MANY_SMOOTH,
    J_SVG_ONE_FLAT,
    J_SVG_MANY_FLAT,
    J_SUB_ORIGIN,
    J_SUB_FAR,
    J_COUNT
};
static const char *job_name[J_COUNT] = {
    "plot (cubic wave, T 0.01)", "path flatten (n cubics, 0.01)", "plot_bezier (n cubics, 0.01)",
    "svg one-path, --levels 3", "svg many-path, --levels 3", "svg one-path, --flatten 0.01",
    "svg many-path, --flatten 0.01", "subdivide k=4, blob at (0, 0)",
    "subdivide k=4, blob at (5000, 3000)"};

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The cubic Bézier segments of a C1 wave: segment i from (i, sin(i/8)),
 * tangents from the derivative (8 doubles each). */
static double *wave_cubics(size_t n)
{
    double *c = malloc(8 * n * sizeof *c);
    if (!c)
        exit(1);
    for (size_t i = 0; i < n; i++) {
        double x0 = (double)i, x1 = x0 + 1, y0 = 20 * sin(x0 / 8), y1 = 20 * sin(x1 / 8);
        double d0 = 2.5 * cos(x0 / 8), d1 = 2.5 * cos(x1 / 8);
        double q[8] = {x0, y0, x0 + 1.0 / 3, y0 + d0 / 3, x1 - 1.0 / 3, y1 - d1 / 3, x1, y1};
        memcpy(c + 8 * i, q, sizeof q);
    }
    return c;
}

/* An SVG document of n serpentine-wave vertices in `paths` <polyline>s. */
static char *svg_doc_text(size_t n, size_t paths, size_t *len)
{
    size_t cap = 256 + 32 * n + 96 * paths, k = 0, per = n / paths;
    char *t = malloc(cap);
    if (!t)
        exit(1);
    k += (size_t)snprintf(t + k, cap - k, "<svg xmlns=\"http://www.w3.org/2000/svg\">\n");
    for (size_t i = 0; i < n; i++) {
        size_t r = i / 10000, c = i % 10000, x = r % 2 ? 9999 - c : c;
        if (i % per == 0)
            k += (size_t)snprintf(t + k, cap - k, "%s<polyline fill=\"none\" points=\"",
                                  i ? "\"/>\n" : "");
        k += (size_t)snprintf(t + k, cap - k, "%s%zu %.3f", i % per ? " " : "", x,
                              100.0 * (double)r + 30.0 * sin((double)x / 16.0));
    }
    k += (size_t)snprintf(t + k, cap - k, "\"/>\n</svg>\n");
    *len = k;
    return t;
}

/* The closed blob r = R (1 + 0.3 cos 3t + 0.1 sin 5t) of n points around
 * (ox, oy) subdivided `levels` times into *o (with *info): its CPU
 * seconds, or -1. */
static double blob_subdivide(size_t n, double R, double ox, double oy, int levels,
                             conica_curve *o, conica_subdiv_info *info)
{
    double *xy = malloc(2 * n * sizeof *xy), t0, t = -1;
    if (!xy)
        return -1;
    for (size_t i = 0; i < n; i++) {
        double a = 2 * M_PI * (double)i / (double)n;
        double r = R * (1 + 0.3 * cos(3 * a) + 0.1 * sin(5 * a));
        xy[2 * i] = ox + r * cos(a);
        xy[2 * i + 1] = oy + r * sin(a);
    }
    conica_curve c;
    conica_curve_init(&c);
    conica_curve_init(o);
    conica_subdiv_info_init(info);
    if (conica_curve_set(xy, NULL, n, 1, &c, NULL) != CONICA_OK)
        return -1;
    free(xy);
    conica_subdiv_settings s = conica_subdiv_defaults();
    s.levels = levels;
    t0 = cpu_now();
    if (conica_subdivide(&c, &s, o, info, NULL) == CONICA_OK)
        t = cpu_now() - t0;
    conica_curve_free(&c);
    return t;
}

/* Run job j on size n in this (child) process: its CPU seconds, or -1. */
static double run_job(int j, size_t n)
{
    double t0, t = -1;
    if (j == J_PLOT) {
        double *c = malloc(2 * n * sizeof *c), *k = malloc((n + 4) * sizeof *k);
        if (!c || !k)
            return -1;
        for (size_t i = 0; i < n; i++) {
            c[2 * i] = (double)i;
            c[2 * i + 1] = sin(0.3 * (double)i);
        }
        for (size_t i = 0; i < n + 4; i++)
            k[i] = i < 4 ? 0 : (i >= n ? (double)(n - 3) : (double)(i - 3));
        conica_bspline s;
        conica_bspline_init(&s);
        if (conica_bspline_set(3, 2, k, n + 4, c, n, NULL, &s, NULL) != CONICA_OK)
            return -1;
        conica_plot_settings set = conica_plot_defaults();
        set.abs_tolerance = 0.01;
        set.max_points = (size_t)1 << 26;
        conica_polyline pl;
        conica_polyline_init(&pl);
        t0 = cpu_now();
        if (conica_plot(&s, &set, &pl, NULL, NULL) == CONICA_OK)
            t = cpu_now() - t0;
    } else if (j == J_FLATTEN || j == J_BEZIER) {
        double *c = wave_cubics(n);
        if (j == J_BEZIER) {
            double xy[2 * 4096];
            size_t np;
            t0 = cpu_now();
            for (size_t i = 0; i < n; i++)
                if (conica_plot_bezier(3, c + 8 * i, NULL, 0.01, 0, xy, NULL, 4096, &np, NULL) !=
                    CONICA_OK)
                    return -1;
            return cpu_now() - t0;
        }
        conica_path p;
        conica_path_init(&p);
        if (conica_path_move_to(&p, c[0], c[1], 0, NULL) != CONICA_OK)
            return -1;
        for (size_t i = 0; i < n; i++)
            if (conica_path_bezier_to(&p, 3, c + 8 * i + 2, NULL, i, NULL) != CONICA_OK)
                return -1;
        free(c);
        conica_path_settings s = conica_path_defaults();
        s.tolerance = 0.01;
        s.max_points = (size_t)1 << 28;
        conica_path_result r;
        conica_path_result_init(&r);
        t0 = cpu_now();
        if (conica_path_flatten(&p, &s, &r, NULL) == CONICA_OK)
            t = cpu_now() - t0;
    } else if (j >= J_SVG_ONE_SMOOTH && j <= J_SVG_MANY_FLAT) {
        int many = j == J_SVG_MANY_SMOOTH || j == J_SVG_MANY_FLAT;
        int flat = j >= J_SVG_ONE_FLAT;
        size_t len;
        char *text = svg_doc_text(n, many ? (n / 100 ? n / 100 : 1) : 1, &len), *out = NULL;
        conica_svg_doc *doc = NULL;
        conica_svg_settings s = conica_svg_defaults();
        size_t olen;
        s.levels = 3;
        if (flat) {
            s.mode = CONICA_SVG_FLATTEN;
            s.tolerance = 0.01;
        }
        t0 = cpu_now();
        if (conica_svg_doc_load(text, len, NULL, &doc, NULL) == CONICA_OK &&
            conica_svg_process(doc, &s, NULL, NULL) == CONICA_OK &&
            conica_svg_doc_save(doc, &out, &olen, NULL) == CONICA_OK)
            t = cpu_now() - t0;
    } else {
        conica_curve o;
        conica_subdiv_info info;
        t = blob_subdivide(n, 100, j == J_SUB_FAR ? 5000 : 0, j == J_SUB_FAR ? 3000 : 0, 4, &o,
                           &info);
    }
    return t;
}

/* --blob N R LEVELS: the blob of radius R at the origin and at (5000,
 * 3000), its CPU, inflection points, grown patches and fallbacks, and how
 * far the far output minus (5000, 3000) is from the near one, in ulps of
 * 5000 (positions) and absolutely (unit normals), away from 32 input
 * points either side of each inflection point (whose edge the input's own
 * rounding decides). */
static int blob_table(size_t n, double R, int levels)
{
    conica_curve o[2];
    conica_subdiv_info info[2];
    double t[2], dp = 0, dn = 0, ulp = nextafter(5000.0, 1e9) - 5000.0;
    for (int k = 0; k < 2; k++)
        if ((t[k] = blob_subdivide(n, R, k ? 5000 : 0, k ? 3000 : 0, levels, &o[k], &info[k])) < 0)
            return 1;
    if (o[0].n != o[1].n)
        return 1;
    size_t w = (size_t)32 << levels;
    for (size_t i = 0; i < o[0].n; i++) {
        int skip = 0;
        for (int k = 0; k < 2; k++)
            for (size_t m = 0; m < info[k].inflections; m++) {
                size_t d = info[k].inflection_index[m];
                skip |= i + w >= d && i <= d + w;
            }
        if (skip)
            continue;
        dp = fmax(dp, fmax(fabs(o[1].xy[2 * i] - 5000 - o[0].xy[2 * i]),
                           fabs(o[1].xy[2 * i + 1] - 3000 - o[0].xy[2 * i + 1])));
        dn = fmax(dn, fmax(fabs(o[1].nxy[2 * i] - o[0].nxy[2 * i]),
                           fabs(o[1].nxy[2 * i + 1] - o[0].nxy[2 * i + 1])));
    }
    printf("| blob R = %g, %zu points, %d levels | inflections | grown | fallbacks | CPU s |\n"
           "|---|---|---|---|---|\n",
           R, n, levels);
    for (int k = 0; k < 2; k++)
        printf("| at %s | %zu | %zu | %zu | %.3f |\n", k ? "(5000, 3000)" : "(0, 0)",
               info[k].inflections, info[k].patch_grown, info[k].midpoint_fallbacks, t[k]);
    printf("\nfar - (5000, 3000) against near, outside 32 input points of the inflection points: "
           "positions %.2f ulps of 5000, normals %.2g\n",
           dp / ulp, dn);
    return 0;
}

/* Job j at size n in a child: CPU seconds (or -1) and peak RSS in MB. */
static double measure(int j, size_t n, double *rss_mb)
{
    int fd[2];
    double t = -1;
    *rss_mb = 0;
    if (pipe(fd) != 0)
        return -1;
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        close(fd[0]);
        t = run_job(j, n);
        ssize_t w = write(fd[1], &t, sizeof t);
        _exit(w == (ssize_t)sizeof t ? 0 : 1);
    }
    close(fd[1]);
    if (pid < 0 || read(fd[0], &t, sizeof t) != (ssize_t)sizeof t)
        t = -1;
    close(fd[0]);
    int status;
    struct rusage ru;
    if (pid > 0 && wait4(pid, &status, 0, &ru) == pid)
        *rss_mb = (double)ru.ru_maxrss / 1024.0;
    return t;
}

int main(int argc, char **argv)
{
    size_t max = 1000000;
    if (argc == 3 && strcmp(argv[1], "--max") == 0)
        max = strtoul(argv[2], NULL, 10);
    else if (argc == 5 && strcmp(argv[1], "--blob") == 0)
        return blob_table(strtoul(argv[2], NULL, 10), atof(argv[3]), atoi(argv[4]));
    else if (argc != 1) {
        fprintf(stderr, "usage: bench_scaling [--max N | --blob N R LEVELS]\n");
        return 2;
    }
    printf("Scaling: CPU seconds, us per item and peak RSS (MB, the whole child process) from "
           "n = 10^3 to %zu; slope = d log(time) / d log(n) from the previous n (1.00: linear)\n\n",
           max);
    printf("| job | n | CPU s | us / item | slope | peak RSS MB | bytes / item |\n"
           "|---|---|---|---|---|---|---|\n");
    for (int j = 0; j < J_COUNT; j++) {
        double prev_t = 0, base_rss = 0;
        size_t prev_n = 0;
        for (size_t n = 1000; n <= max; n *= 10) {
            double rss, t = measure(j, n, &rss);
            if (n == 1000)
                base_rss = rss;
            printf("| %s | %zu | ", job_name[j], n);
            if (t < 0) {
                printf("failed | | | | |\n");
                continue;
            }
            printf("%.4f | %.3f | ", t, 1e6 * t / (double)n);
            if (prev_n && prev_t > 0 && t > 0)
                printf("%.2f", log(t / prev_t) / log((double)n / (double)prev_n));
            printf(" | %.1f | %.0f |\n", rss,
                   n > 1000 ? (rss - base_rss) * 1048576.0 / (double)(n - 1000) : 0.0);
            prev_t = t;
            prev_n = n;
        }
    }
    printf("\n(bytes / item: the growth of the peak RSS over the n = 10^3 run, per item)\n");
    return 0;
}

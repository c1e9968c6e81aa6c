/* SPDX-License-Identifier: MIT */
/* Benchmark of conica_subdivide() (issue 3): speed in microseconds per edge
 * point for the three cases of REFERENCE.md section 1, and the conic
 * reproduction error E, E_max (CONIS, eqs. (13)-(14)) beside the paper's
 * Table 1. Prints tables; never asserts.
 *
 *   bench_subdiv                 all tables
 *   bench_subdiv --case circle   one run of one case (for /usr/bin/time -v)
 *   bench_subdiv --case ellipse|rose [--precise]
 *   bench_subdiv --repeats 50    best of 50 instead of 5 (on a loaded machine)
 *
 * Then rounded input (settings.noise): the 1000-point convex spline of
 * bench/bench_blender.py's make_curve rounded to float32 at k = 3 (the
 * add-on's edit-mode Conic Subdivide, best of at least 50), and 20 000
 * points of the unit circle rounded to float32 or to 7 significant digits,
 * unrotated and rotated (best of at most 3).
 *   bench_subdiv --case blender  the spline's row alone (--case noisy: the
 *                                circles' rows alone)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "conica/subdiv.h"
#include "fidelity.h"

#define PI_L 3.14159265358979323846264338327950288L
static int repeats = 5; /* best of 5 (issue 3); --repeats N under load */

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ------------------------------------------------------------ cases */

enum { C_CIRCLE, C_ELLIPSE, C_HYPERBOLA, C_PARABOLA, C_COUNT };
static const char *const conic_name[C_COUNT] = {"x^2+y^2=25", "4x^2+9y^2=36", "y^2-4x^2=4",
                                                "y=x^2"};
/* CONIS Table 1 (= the reference's measurements): E, E_max at k=4,8,12. */
static const double table1[C_COUNT][2][3] = {
    {{1.97e-18, 4.70e-17, 1.57e-14}, {8.67e-18, 1.35e-15, 1.04e-13}},
    {{1.37e-18, 6.54e-17, 3.46e-15}, {6.17e-18, 1.10e-15, 1.53e-13}},
    {{1.14e-17, 4.67e-15, 4.55e-13}, {5.97e-16, 3.54e-13, 2.31e-12}},
    {{3.54e-16, 4.05e-15, 3.83e-13}, {3.53e-15, 1.13e-12, 8.09e-12}},
};

/* The reference's samples (REFERENCE.md section 1), exact in long double,
 * moved by (cx, cy) and scaled by sc (circle placement table). */
static void conic_samples(int c, long double sc, long double cx, long double cy, conica_curvel *o)
{
    int i;
    o->n = 6;
    o->closed = c == C_CIRCLE || c == C_ELLIPSE;
    for (i = 0; i < 6; i++) {
        long double x, y, gx, gy, len, t = 2 * PI_L * i / 6;
        switch (c) {
        case C_CIRCLE: x = 5 * cosl(t); y = 5 * sinl(t); gx = 2 * x; gy = 2 * y; break;
        case C_ELLIPSE: x = 3 * cosl(t); y = 2 * sinl(t); gx = 8 * x; gy = 18 * y; break;
        case C_HYPERBOLA: x = -4 + 8.0L * i / 5; y = 2 * sqrtl(1 + x * x); gx = -8 * x; gy = 2 * y; break;
        default: x = -4 + 8.0L * i / 6; y = x * x; gx = 2 * x; gy = -1; break;
        }
        len = sqrtl(gx * gx + gy * gy);
        o->xy[2 * i] = cx + sc * x;
        o->xy[2 * i + 1] = cy + sc * y;
        o->nxy[2 * i] = gx / len;
        o->nxy[2 * i + 1] = gy / len;
    }
}

/* |f| / |grad f| in the conic's own (unmoved, unscaled) coordinates. */
static long double conic_err(int c, long double x, long double y)
{
    long double f, gx, gy;
    switch (c) {
    case C_CIRCLE: f = x * x + y * y - 25; gx = 2 * x; gy = 2 * y; break;
    case C_ELLIPSE: f = 4 * x * x + 9 * y * y - 36; gx = 8 * x; gy = 18 * y; break;
    case C_HYPERBOLA: f = y * y - 4 * x * x - 4; gx = -8 * x; gy = 2 * y; break;
    default: f = x * x - y; gx = 2 * x; gy = -1; break;
    }
    return fabsl(f) / sqrtl(gx * gx + gy * gy);
}

/* E and E_max (eqs. (13)-(14)) of conic c at level k. precise: long double
 * input and output; else the samples rounded to double, double mode. */
static void accuracy(int c, int k, int precise, int ref, long double sc, long double cx,
                     long double cy, long double *E, long double *Emax)
{
    long double sxy[12], snn[12], sum = 0, mx = 0;
    conica_curvel in = {0, 0, sxy, snn, 0}, outl;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_status st;
    size_t i;

    conic_samples(c, sc, cx, cy, &in);
    s.levels = k;
    s.reference_compatible = ref;
    conica_curvel_init(&outl);
    if (precise) {
        if (conica_subdivide_curvel(&in, &s, &outl, NULL, &st) != CONICA_OK) {
            printf("error: %s\n", st.message);
            *E = *Emax = NAN;
            return;
        }
    } else {
        double dxy[12], dn[12];
        conica_curve din = {6, 6, dxy, dn, in.closed}, dout;
        for (i = 0; i < 12; i++) {
            dxy[i] = (double)sxy[i];
            dn[i] = (double)snn[i];
        }
        conica_curve_init(&dout);
        if (conica_subdivide(&din, &s, &dout, NULL, &st) != CONICA_OK) {
            printf("error: %s\n", st.message);
            *E = *Emax = NAN;
            return;
        }
        outl.n = dout.n;
        outl.xy = malloc(2 * dout.n * sizeof *outl.xy);
        if (!outl.xy)
            exit(1);
        for (i = 0; i < 2 * dout.n; i++)
            outl.xy[i] = dout.xy[i];
        conica_curve_free(&dout);
    }
    for (i = 0; i < outl.n; i++) {
        long double e = conic_err(c, (outl.xy[2 * i] - cx) / sc, (outl.xy[2 * i + 1] - cy) / sc);
        sum += e;
        if (e > mx)
            mx = e;
    }
    *E = sum / (long double)outl.n;
    *Emax = mx;
    conica_curvel_free(&outl);
}

/* ------------------------------------------------------------ speed cases */

enum { S_CIRCLE, S_ELLIPSE, S_ROSE, S_COUNT };
static const char *const speed_name[S_COUNT] = {"circle 6 pts r=5, k=12", "ellipse 1000 pts, k=6",
                                                "r=1+0.3cos5t 200 pts est. normals, k=6"};
static const double speed_ref[S_COUNT] = {29.8, 32.3, 36.4};

static void speed_input(int which, conica_curve *c, int *levels)
{
    size_t i, n = which == S_CIRCLE ? 6 : which == S_ELLIPSE ? 1000 : 200;
    double *xy = malloc(2 * n * sizeof *xy), *nn = malloc(2 * n * sizeof *nn);
    if (!xy || !nn)
        exit(1);
    for (i = 0; i < n; i++) {
        double t = 2 * (double)PI_L * (double)i / (double)n, x, y, gx, gy, r;
        if (which == S_CIRCLE) {
            x = 5 * cos(t); y = 5 * sin(t); gx = x; gy = y;
        } else if (which == S_ELLIPSE) {
            x = 3 * cos(t); y = 2 * sin(t); gx = 8 * x; gy = 18 * y;
        } else {
            r = 1 + 0.3 * cos(5 * t);
            x = r * cos(t); y = r * sin(t); gx = gy = 0;
        }
        xy[2 * i] = x;
        xy[2 * i + 1] = y;
        r = sqrt(gx * gx + gy * gy);
        nn[2 * i] = r > 0 ? gx / r : 0;
        nn[2 * i + 1] = r > 0 ? gy / r : 0;
    }
    conica_curve_init(c);
    if (conica_curve_set(xy, which == S_ROSE ? NULL : nn, n, 1, c, NULL) != CONICA_OK)
        exit(1);
    free(xy);
    free(nn);
    *levels = which == S_CIRCLE ? 12 : 6;
}

/* Best of repeats runs; microseconds per edge point. */
static double speed(int which, int precise, int force_svd, size_t *points, size_t *infl)
{
    conica_curve in, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_subdiv_info info;
    conica_status st;
    double best = 1e300;
    int r;

    speed_input(which, &in, &s.levels);
    s.precise = precise;
    s.force_svd = force_svd;
    conica_curve_init(&out);
    conica_subdiv_info_init(&info);
    for (r = 0; r < repeats; r++) {
        double t0 = now(), t;
        if (conica_subdivide(&in, &s, &out, &info, &st) != CONICA_OK) {
            printf("error: %s\n", st.message);
            return NAN;
        }
        t = now() - t0;
        if (t < best)
            best = t;
    }
    *points = out.n;
    *infl = info.inflections;
    best = best * 1e6 / (double)info.edge_points;
    conica_subdiv_info_free(&info);
    conica_curve_free(&in);
    conica_curve_free(&out);
    return best;
}

static int one_case(const char *name, int precise)
{
    conica_curve in, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_status st;
    int which = strcmp(name, "circle") == 0 ? S_CIRCLE
                : strcmp(name, "ellipse") == 0 ? S_ELLIPSE
                : strcmp(name, "rose") == 0 ? S_ROSE : -1;
    if (which < 0) {
        fprintf(stderr, "bench_subdiv: unknown case '%s' (circle, ellipse, rose, blender, noisy)\n",
                name);
        return 2;
    }
    speed_input(which, &in, &s.levels);
    s.precise = precise;
    conica_curve_init(&out);
    if (conica_subdivide(&in, &s, &out, NULL, &st) != CONICA_OK) {
        fprintf(stderr, "bench_subdiv: %s\n", st.message);
        return 1;
    }
    printf("%s: %zu output points (x4 x sizeof(real) = %.1f MiB)\n", name, out.n,
           (double)out.n * 4.0 * (precise ? sizeof(long double) : sizeof(double)) / 1048576.0);
    conica_curve_free(&in);
    conica_curve_free(&out);
    return 0;
}

/* ------------------------------------------------------ rounded input */

static double round_f32(double x)
{
    volatile float f = (float)x; /* a store: gcc 12 -O2 has dropped a plain cast */
    return f;
}

static double round_dec7(double x)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%.7g", x);
    return strtod(buf, NULL);
}

/* Largest | |p| - 1 | over n points (the test support's radial error). */
static double radial_max(const double *xy, size_t n)
{
    static const double origin[2] = {0, 0};
    return ts_ellipse_radial_error(xy, n, origin, 1, 1, 0, NULL);
}

/* One row: which 0 the Blender spline, 1 the float32 circle, 2 the 7-digit
 * circle; angle rotates the circle (before the 7-digit rounding, after the
 * float32 one: the add-on rotates float32 points into their plane). */
static void noisy_row(int which, double angle, int levels, double noise, int reps)
{
    size_t n = which == 0 ? 1000 : 20000, i;
    double *xy = malloc(2 * n * sizeof *xy), c = cos(angle), sn = sin(angle), best = 1e300;
    conica_curve in, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_subdiv_info info;
    conica_status st;
    int r;
    if (!xy)
        exit(1);
    for (i = 0; i < n; i++) {
        double t = 2 * (double)PI_L * (double)i / (double)n, x, y;
        if (which == 0) {
            x = round_f32(3.0 * cos(t));
            y = round_f32(2.0 * sin(t) + 0.2 * pow(sin(t), 3));
        } else {
            x = cos(t);
            y = sin(t);
            if (which == 1) {
                x = round_f32(x);
                y = round_f32(y);
            }
            xy[2 * i] = c * x - sn * y;
            y = sn * x + c * y;
            x = xy[2 * i];
            if (which == 2) {
                x = round_dec7(x);
                y = round_dec7(y);
            }
        }
        xy[2 * i] = x;
        xy[2 * i + 1] = y;
    }
    in.n = in.cap = n;
    in.xy = xy;
    in.nxy = NULL;
    in.closed = 1;
    s.levels = levels;
    s.noise = noise;
    s.estimate_normals = 1;
    s.normal_method = CONICA_NORMALS_CIRCLE; /* as the curve front end (path.c) */
    conica_curve_init(&out);
    conica_subdiv_info_init(&info);
    for (r = 0; r < reps; r++) {
        double t0 = now(), t;
        if (conica_subdivide(&in, &s, &out, &info, &st) != CONICA_OK) {
            printf("error: %s\n", st.message);
            exit(1);
        }
        t = now() - t0;
        best = t < best ? t : best;
    }
    if (which == 0)
        printf("| 1000-point convex spline (float32), k=%d, noise %.3g | %zu | %.3f ms | %.3f | "
               "%zu / %zu / %zu | - |\n",
               levels, noise, out.n, best * 1e3, best * 1e6 / (double)info.edge_points,
               info.patch_grown, info.midpoint_fallbacks, info.inflections);
    else
        printf("| circle 20 000 pts (%s), rotated %.4g, k=%d, noise %.3g | %zu | %.3f s | %.3f | "
               "%zu / %zu / %zu | %.3g / %.3g |\n",
               which == 1 ? "float32" : "7 digits", angle, levels, noise, out.n, best,
               best * 1e6 / (double)info.edge_points, info.patch_grown, info.midpoint_fallbacks,
               info.inflections, radial_max(out.xy, out.n), radial_max(xy, n));
    conica_subdiv_info_free(&info);
    conica_curve_free(&out);
    free(xy);
}

static void noisy_tables(int rows)
{
    /* The add-on's rotation of a circle in Blender's XY plane into its
     * best-fit plane (the basis u = (-0.0792, 0.9969), v = (-0.9969,
     * -0.0792) that _conica computes for it). */
    double add_on = atan2(-0.99685585384298858, -0.079236397311880383);
    int big = repeats < 3 ? repeats : 3;
    printf("\nRounded input (settings.noise): best of %d (the spline: of %d), estimated circle "
           "normals\n",
           big, repeats > 50 ? repeats : 50);
    printf("| case | output points | time | us per edge point | grown / last resorts / "
           "inflections | radial error max: output / input |\n|---|---|---|---|---|---|\n");
    if (rows & 1)
        noisy_row(0, 0, 3, ldexp(1.0, -23), repeats > 50 ? repeats : 50);
    if (rows & 2) {
        noisy_row(1, 0, 7, 6e-8, big);
        noisy_row(1, add_on, 7, 6e-8, big);
        noisy_row(2, 0, 6, 5e-8, big);
        noisy_row(2, add_on, 6, 5e-8, big);
    }
}

int main(int argc, char **argv)
{
    int i, c, k, m;
    int precise = 0;
    const char *one = NULL;

    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--case") == 0 && i + 1 < argc)
            one = argv[++i];
        else if (strcmp(argv[i], "--precise") == 0)
            precise = 1;
        else if (strcmp(argv[i], "--repeats") == 0 && i + 1 < argc && atoi(argv[i + 1]) > 0)
            repeats = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_subdiv [--case circle|ellipse|rose|blender|noisy] "
                            "[--precise] [--repeats N]\n");
            return 2;
        }
    }
    if (one && (strcmp(one, "blender") == 0 || strcmp(one, "noisy") == 0)) {
        noisy_tables(strcmp(one, "blender") == 0 ? 1 : 2);
        return 0;
    }
    if (one)
        return one_case(one, precise);

    printf("Speed: microseconds per edge point, single thread, best of %d (conica_subdivide only)\n",
           repeats);
    printf("| case | output points | default | precise | SVD path (double) | reference |\n");
    printf("|---|---|---|---|---|---|\n");
    for (i = 0; i < S_COUNT; i++) {
        size_t pts = 0, infl = 0;
        double d = speed(i, 0, 0, &pts, &infl), p = speed(i, 1, 0, &pts, &infl);
        double v = speed(i, 0, 1, &pts, &infl);
        printf("| %s | %zu (%zu inflections) | %.3f (%.0fx) | %.3f (%.0fx) | %.2f | %.1f |\n",
               speed_name[i], pts, infl, d, speed_ref[i] / d, p, speed_ref[i] / p, v, speed_ref[i]);
    }

    for (m = 0; m < 2; m++) {
        printf("\nAccuracy, %s mode (%s input): E / E_max, Table 1 beside\n",
               m ? "precise" : "default", m ? "long double" : "double");
        printf("| conic | k | E | Table 1 E | E_max | Table 1 E_max |\n|---|---|---|---|---|---|\n");
        for (c = 0; c < C_COUNT; c++)
            for (k = 0; k < 3; k++) {
                long double E, Em;
                accuracy(c, 4 + 4 * k, m, 0, 1, 0, 0, &E, &Em);
                printf("| %s | %d | %.3Le | %.2e | %.3Le | %.2e |\n", conic_name[c], 4 + 4 * k, E,
                       table1[c][0][k], Em, table1[c][1][k]);
            }
    }
    printf("\nCircle moved to (1e4, 1e4) and scaled to radius 5e5 (errors relative to the scale)\n");
    printf("| mode | k | E | E_max | origin E | origin E_max |\n|---|---|---|---|---|---|\n");
    for (m = 0; m < 4; m++)
        for (k = 0; k < 3; k++) {
            long double E, Em, E0, Em0;
            accuracy(C_CIRCLE, 4 + 4 * k, m & 1, m >> 1, 1e5L, 1e4L, 1e4L, &E, &Em);
            accuracy(C_CIRCLE, 4 + 4 * k, m & 1, m >> 1, 1, 0, 0, &E0, &Em0);
            printf("| %s%s | %d | %.3Le | %.3Le | %.3Le | %.3Le |\n", m & 1 ? "precise" : "default",
                   m >> 1 ? ", reference-compatible" : "", 4 + 4 * k, E, Em, E0, Em0);
        }
    printf("(the reference itself: relative max error 3.4e-2 / 4.0e-2 at k = 4 / 12 for r = 5e5)\n");
    noisy_tables(3);
    return 0;
}

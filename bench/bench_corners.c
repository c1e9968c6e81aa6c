/* SPDX-License-Identifier: MIT */
/* The corner-knot scaling of issue 33 (prints figures, asserts nothing):
 * conica_plot on splines whose every interior knot is a corner
 * (multiplicity = degree), 10^3..10^6 of them: degree 1 with the uniform
 * baseline and the default (guaranteed) method, and cubic Bézier chains.
 * Before the fix the corners were raised to multiplicity p + 1 one
 * insertion at a time (each shifting the arrays) and the uniform share of
 * points summed all pieces for each piece: both quadratic. The CPU time
 * per corner should stay flat. Calls the public API only. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "conica/bspline.h"
#include "conica/plot.h"

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A degree-p spline of n pieces, every interior knot of multiplicity p:
 * n*p + 1 control points on a wavy line. */
static int corner_spline(int p, size_t n, conica_bspline *s)
{
    size_t nc = n * (size_t)p + 1, nk = nc + (size_t)p + 1, k = 0;
    double *knots = malloc(nk * sizeof *knots), *ctrl = malloc(2 * nc * sizeof *ctrl);
    conica_status st;
    int rc = 1;
    if (knots && ctrl) {
        for (int r = 0; r <= p; r++)
            knots[k++] = 0;
        for (size_t i = 1; i < n; i++)
            for (int r = 0; r < p; r++)
                knots[k++] = (double)i;
        for (int r = 0; r <= p; r++)
            knots[k++] = (double)n;
        for (size_t i = 0; i < nc; i++) {
            ctrl[2 * i] = 0.5 * (double)i;
            ctrl[2 * i + 1] = sin(0.7 * (double)i);
        }
        rc = conica_bspline_set(p, 2, knots, nk, ctrl, nc, NULL, s, &st) != CONICA_OK;
    }
    free(knots);
    free(ctrl);
    return rc;
}

int main(void)
{
    static const struct {
        int p;
        conica_plot_method m;
        const char *what;
    } runs[] = {{1, CONICA_PLOT_UNIFORM, "degree 1, --method uniform"},
                {1, CONICA_PLOT_GUARANTEED, "degree 1, default (guaranteed)"},
                {3, CONICA_PLOT_GUARANTEED, "cubic Bezier chain, default"}};
    printf("corner knots | method | points | CPU s | us per corner\n");
    printf("---|---|---|---|---\n");
    for (size_t r = 0; r < sizeof runs / sizeof runs[0]; r++)
        for (size_t n = 1000; n <= 1000000; n *= 10) {
            conica_bspline s;
            conica_polyline pl;
            conica_plot_settings set = conica_plot_defaults();
            conica_status st;
            conica_bspline_init(&s);
            conica_polyline_init(&pl);
            if ((size_t)runs[r].p * n + 1 > CONICA_BSPLINE_MAX_CTRL || corner_spline(runs[r].p, n, &s)) {
                conica_bspline_free(&s);
                continue;
            }
            set.method = runs[r].m;
            set.points = 2 * n + 1 < set.max_points ? 2 * n + 1 : set.max_points;
            double t0 = cpu_now();
            conica_code rc = conica_plot(&s, &set, &pl, NULL, &st);
            double t = cpu_now() - t0;
            if (rc == CONICA_OK)
                printf("%zu | %s | %zu | %.3f | %.2f\n", n - 1, runs[r].what, pl.n, t,
                       1e6 * t / (double)(n - 1));
            else
                printf("%zu | %s | error: %s | %.3f | -\n", n - 1, runs[r].what, st.message, t);
            conica_polyline_free(&pl);
            conica_bspline_free(&s);
        }
    return 0;
}

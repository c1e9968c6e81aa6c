/* SPDX-License-Identifier: MIT */
/* Plot a NURBS circle (radius 50 about (100, 100), as examples/nurbs-circle.spl)
 * with the guaranteed plotter to 0.01 and check the result: every vertex on
 * the circle, every chord within 0.01 of it. Build: see docs/library.md. */
#include <math.h>
#include <stdio.h>

#include <conica/plot.h>

int main(void)
{
    const double h = 0.70710678118654752; /* cos 45 degrees */
    double knots[12] = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
    double ctrl[18] = {150, 100, 150, 150, 100, 150, 50, 150, 50, 100,
                       50,  50,  100, 50,  150, 50,  150, 100};
    double w[9] = {1, h, 1, h, 1, h, 1, h, 1};

    conica_bspline s;
    conica_bspline_init(&s);
    conica_polyline pl;
    conica_polyline_init(&pl);
    conica_status st;
    int rc = 1;

    if (conica_bspline_set(2, 2, knots, 12, ctrl, 9, w, &s, &st) != CONICA_OK) {
        fprintf(stderr, "conica_bspline_set: %s\n", st.message);
        goto done;
    }
    conica_plot_settings set = conica_plot_defaults(); /* guaranteed method */
    set.abs_tolerance = 0.01;
    conica_plot_stats stats;
    if (conica_plot(&s, &set, &pl, &stats, &st) != CONICA_OK) {
        fprintf(stderr, "conica_plot: %s\n", st.message);
        goto done;
    }
    double off = 0.0, sagitta = 0.0;
    for (size_t i = 0; i < pl.n; i++) {
        const double *a = pl.xy + i * 2, *b = pl.xy + ((i + 1) % pl.n) * 2;
        off = fmax(off, fabs(hypot(a[0] - 100, a[1] - 100) - 50));
        if (i + 1 < pl.n) /* chord a-b: its midpoint is the farthest from the arc */
            sagitta = fmax(sagitta, 50 - hypot((a[0] + b[0]) / 2 - 100, (a[1] + b[1]) / 2 - 100));
    }
    printf("%zu points in %zu piece(s)\n", pl.n, pl.npieces);
    printf("vertices on the circle to 1e-9: %s\n", off < 1e-9 ? "yes" : "no");
    printf("largest chord sagitta %.4f (tolerance %.2f)\n", sagitta, stats.tolerance);
    rc = off < 1e-9 && sagitta <= 0.01 ? 0 : 1;
done:
    conica_polyline_free(&pl);
    conica_bspline_free(&s);
    return rc;
}

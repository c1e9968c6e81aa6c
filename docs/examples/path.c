/* SPDX-License-Identifier: MIT */
/* The curve front end (conica/path.h): a closed path of a quarter circle and
 * two straight edges, smoothed and flattened within the fidelity tolerance.
 * The corners stay sharp, the edges straight, the arc on its circle.
 * Build: see docs/library.md. */
#include <math.h>
#include <stdio.h>

#include <conica/path.h>

static int report(const char *what, const conica_path_result *r)
{
    const conica_path_polyline *l = &r->lines[0];
    double off = 0.0; /* distance from the unit circle of the points on the arc */
    for (size_t i = 0; i < l->n; i++)
        if (l->seg[i] == 0)
            off = fmax(off, fabs(hypot(l->xy[2 * i], l->xy[2 * i + 1]) - 1.0));
    printf("%s: %zu points, %zu corners, deviation %.2f of the tolerance, "
           "arc points on the circle to 1e-9: %s\n",
           what, l->n, r->corners, r->worst_ratio, off < 1e-9 ? "yes" : "no");
    return off < 1e-9 && r->worst_ratio <= 1.0;
}

int main(void)
{
    double quarter[4] = {1, 1, 0, 1};            /* control point, end point */
    double w[3] = {1, 0.70710678118654752, 1};   /* weights: a circular arc */
    conica_path p;
    conica_path_result r;
    conica_path_settings s = conica_path_defaults();
    conica_status st;
    int ok = 1;

    conica_path_init(&p);
    conica_path_result_init(&r);
    if (conica_path_move_to(&p, 1, 0, 0, &st) != CONICA_OK ||
        conica_path_bezier_to(&p, 2, quarter, w, 1, &st) != CONICA_OK ||
        conica_path_line_to(&p, 0, 0, 2, &st) != CONICA_OK ||
        conica_path_close(&p, &st) != CONICA_OK) {
        fprintf(stderr, "building the path: %s\n", st.message);
        ok = 0;
    }
    if (ok && conica_path_smooth(&p, &s, &r, &st) == CONICA_OK)
        ok = report("smooth", &r);
    else if (ok)
        ok = 0, fprintf(stderr, "conica_path_smooth: %s\n", st.message);
    if (ok && conica_path_flatten(&p, &s, &r, &st) == CONICA_OK)
        ok = report("flatten", &r);
    else if (ok)
        ok = 0, fprintf(stderr, "conica_path_flatten: %s\n", st.message);
    conica_path_result_free(&r);
    conica_path_free(&p);
    return ok ? 0 : 1;
}

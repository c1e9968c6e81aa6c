/* SPDX-License-Identifier: MIT */
/* Discrete curvature fairness of a polyline (see ts_fairness.h). */
#include "ts_fairness.h"

#include <math.h>
#include <stdlib.h>

double ts_circle_curvature(const double a[2], const double b[2], const double c[2])
{
    /* 1/R = 2 sin(angle at b) / |ac| = 2 cross(b-a, c-b) / (|b-a| |c-b| |c-a|). */
    double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
    double wx = c[0] - a[0], wy = c[1] - a[1];
    double d = sqrt((ux * ux + uy * uy) * (vx * vx + vy * vy) * (wx * wx + wy * wy));
    if (!(d > 0))
        return 0;
    return 2 * (ux * vy - uy * vx) / d;
}

int ts_fairness_measure(const double *xy, size_t n, int closed, ts_fairness *out)
{
    size_t i, first, last;
    double *k, zero;
    int prev = 0, sgn0 = 0;
    if (n < 3 || (!closed && n < 4))
        return -1;
    k = malloc(n * sizeof *k);
    if (!k)
        return -1;
    first = closed ? 0 : 1;
    last = closed ? n : n - 1; /* vertices first..last-1 have a curvature */
    out->tv = 0;
    out->kmax = 0;
    out->sign_changes = 0;
    for (i = first; i < last; i++) {
        size_t a = i == 0 ? n - 1 : i - 1, c = i + 1 == n ? 0 : i + 1;
        k[i] = ts_circle_curvature(xy + 2 * a, xy + 2 * i, xy + 2 * c);
        if (fabs(k[i]) > out->kmax)
            out->kmax = fabs(k[i]);
    }
    for (i = first; i + 1 < last; i++)
        out->tv += fabs(k[i + 1] - k[i]);
    if (closed)
        out->tv += fabs(k[0] - k[n - 1]);
    zero = TS_FAIR_ZERO_REL * out->kmax;
    for (i = first; i < last; i++) {
        int s = k[i] > zero ? 1 : (k[i] < -zero ? -1 : 0);
        if (s == 0)
            continue;
        if (prev != 0 && s != prev)
            out->sign_changes++;
        if (sgn0 == 0)
            sgn0 = s;
        prev = s;
    }
    if (closed && prev != 0 && sgn0 != 0 && prev != sgn0)
        out->sign_changes++;
    free(k);
    return 0;
}

int ts_normal_outside_cone(const double a[2], const double b[2], const double c[2],
                           const double nrm[2])
{
    double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
    double tx = -nrm[1], ty = nrm[0], lu = hypot(ux, uy), lv = hypot(vx, vy);
    double lt = hypot(tx, ty), turn, c1, c2;
    if (!(lu > 0) || !(lv > 0) || !(lt > 0))
        return 0;
    ux /= lu, uy /= lu, vx /= lv, vy /= lv, tx /= lt, ty /= lt;
    if (tx * (ux + vx) + ty * (uy + vy) < 0) /* orient along the travel */
        tx = -tx, ty = -ty;
    turn = ux * vy - uy * vx;
    c1 = ux * ty - uy * tx; /* incoming edge -> tangent */
    c2 = tx * vy - ty * vx; /* tangent -> outgoing edge */
    if (fabs(turn) <= TS_FAIR_CONE_TOL)
        return 0; /* collinear edges: no cone to leave */
    if (turn > 0)
        return c1 < -TS_FAIR_CONE_TOL || c2 < -TS_FAIR_CONE_TOL;
    return c1 > TS_FAIR_CONE_TOL || c2 > TS_FAIR_CONE_TOL;
}

size_t ts_normals_outside_cone(const double *xy, const double *nxy, size_t n, int closed,
                               size_t *first)
{
    size_t i, count = 0;
    if (!nxy || n < 3)
        return 0;
    for (i = closed ? 0 : 1; i < (closed ? n : n - 1); i++) {
        size_t a = i == 0 ? n - 1 : i - 1, c = i + 1 == n ? 0 : i + 1;
        if (ts_normal_outside_cone(xy + 2 * a, xy + 2 * i, xy + 2 * c, nxy + 2 * i)) {
            if (count == 0 && first)
                *first = i;
            count++;
        }
    }
    return count;
}

/* SPDX-License-Identifier: MIT */
/* Exact orientation of three points (Shewchuk's adaptive predicate, its
 * error-bound filter and an exact expansion behind it): the one test of
 * which side of a line a point lies on, shared by the curve front end's
 * fold repair and the OpenSCAD writer's simplicity check. */
#include "internal.h"

#include <math.h>
#include <stddef.h>

/* Knuth's TwoSum: s + e == a + b exactly. */
static void two_sum(double a, double b, double *s, double *e)
{
    double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* Shewchuk's grow-expansion with zero elimination, in place: adds b to the
 * non-overlapping expansion e[0..m) (increasing magnitude). */
static size_t grow(double *e, size_t m, double b)
{
    double q = b;
    size_t k = 0;
    for (size_t i = 0; i < m; i++) {
        double h;
        two_sum(q, e[i], &q, &h);
        if (h != 0.0)
            e[k++] = h;
    }
    if (q != 0.0 || k == 0)
        e[k++] = q;
    return k;
}

/* Underflow: products below the normal range lose up to half a unit of
 * the smallest subnormal each; a few such units cover both. */
#define CONICA__ORIENT_TINY 0x1p-1070

double conica__orient2d_approx(const double *a, const double *b, const double *c, double *err)
{
    /* det = (ax-cx)(by-cy) - (ay-cy)(bx-cx); Shewchuk's ccwerrboundA
     * (3 + 16 eps) eps bounds the error of all five roundings. */
    double l = (a[0] - c[0]) * (b[1] - c[1]);
    double r = (a[1] - c[1]) * (b[0] - c[0]);
    *err = 3.3306690738754716e-16 * (fabs(l) + fabs(r)) + CONICA__ORIENT_TINY;
    return l - r;
}

int conica__orient2d(const double *a, const double *b, const double *c)
{
    double bound, det = conica__orient2d_approx(a, b, c, &bound);
    if (det > bound)
        return 1;
    if (-det > bound)
        return -1;
    /* Exact: det = ax by - ax cy - cx by - ay bx + ay cx + cy bx, each
     * product split into hi + lo with fma (exact for finite, non-underflowing
     * values), the twelve terms summed as an expansion; its sign is the sign
     * of its largest component. */
    const double pa[6] = {a[0], -a[0], -c[0], -a[1], a[1], c[1]};
    const double pb[6] = {b[1], c[1], b[1], b[0], c[0], b[0]};
    double e[12];
    size_t m = 0;
    for (int i = 0; i < 6; i++) {
        double hi = pa[i] * pb[i];
        double lo = fma(pa[i], pb[i], -hi);
        m = grow(e, m, hi);
        m = grow(e, m, lo);
    }
    double top = e[m - 1];
    return (top > 0) - (top < 0);
}


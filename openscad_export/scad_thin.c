/* SPDX-License-Identifier: MIT */
/* Fewest points for a tolerance: a dense polyline whose vertices lie on the
 * curve, then the greedy longest chords that stay within the tolerance. */
#include "scad_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>


/* Closed curves: greedy runs from this many starting points spread over the
 * first chord; the fewest points win (the greedy count from one start is at
 * most one above the optimum for a convex closed curve). */
#define THIN_STARTS 8

double conica__scad_seg_dist2(const double *p, const double *a, const double *b)
{
    double ex = b[0] - a[0], ey = b[1] - a[1];
    double px = p[0] - a[0], py = p[1] - a[1];
    double l2 = ex * ex + ey * ey;
    double t = l2 > 0 ? (px * ex + py * ey) / l2 : 0.0;
    if (t < 0)
        t = 0;
    else if (t > 1)
        t = 1;
    double dx = px - t * ex, dy = py - t * ey;
    return dx * dx + dy * dy;
}

typedef struct thinner {
    const double *xy;
    size_t n;
    double tol2;
} thinner;

static const double *at(const thinner *t, size_t i)
{
    return &t->xy[2 * (i % t->n)];
}

/* Every vertex strictly between i and j (indices unwrapped) within tol of
 * the chord i-j. */
static int feasible(const thinner *t, size_t i, size_t j)
{
    const double *a = at(t, i), *b = at(t, j);
    for (size_t k = i + 1; k < j; k++)
        if (conica__scad_seg_dist2(at(t, k), a, b) > t->tol2)
            return 0;
    return 1;
}

/* Farthest j in (cur, limit] with a feasible chord: gallop, then bisect.
 * Feasibility is not monotone in general, so this may stop short of the
 * true farthest; every chord it returns has been checked in full. */
static size_t reach(const thinner *t, size_t cur, size_t limit)
{
    size_t lo = cur + 1, hi = SIZE_MAX, step = 1;
    while (lo < limit) {
        size_t cand = cur + 2 * step;
        if (cand >= limit)
            cand = limit;
        if (feasible(t, cur, cand)) {
            lo = cand;
            step *= 2;
        } else {
            hi = cand;
            break;
        }
    }
    if (hi != SIZE_MAX) {
        while (hi - lo > 1) {
            size_t mid = lo + (hi - lo) / 2;
            if (feasible(t, cur, mid))
                lo = mid;
            else
                hi = mid;
        }
    }
    return lo;
}

/* Greedy from `start`; writes indices to idx (may be NULL) and returns the count. */
static size_t greedy(const thinner *t, size_t start, size_t end, size_t maxspan, size_t *idx)
{
    size_t m = 0, cur = start;
    while (cur < end) {
        if (idx)
            idx[m] = cur % t->n;
        m++;
        size_t limit = cur + maxspan < end ? cur + maxspan : end;
        cur = reach(t, cur, limit);
    }
    return m;
}

conica_code conica_scad_thin(const double *xy, size_t n, int closed, double tol, double **out,
                             size_t *nout, conica_status *st)
{
    thinner t;
    size_t *idx, m, best_start = 0;
    if (!xy || !out || !nout || n == 0 || !(tol > 0) || !isfinite(tol))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid argument");
    t.xy = xy;
    t.n = n;
    t.tol2 = tol * tol;
    idx = malloc((n + 1) * sizeof *idx);
    if (!idx)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    if (closed && n > 3) {
        /* spans of at most n/3 keep at least three points */
        size_t maxspan = n / 3, first, best = SIZE_MAX;
        first = reach(&t, 0, maxspan);
        for (size_t s = 0; s < THIN_STARTS; s++) {
            size_t start = first * s / THIN_STARTS;
            if (s > 0 && start == first * (s - 1) / THIN_STARTS)
                continue;
            size_t cnt = greedy(&t, start, start + n, maxspan, NULL);
            if (cnt < best) {
                best = cnt;
                best_start = start;
            }
        }
        m = greedy(&t, best_start, best_start + n, maxspan, idx);
    } else if (closed) {
        for (m = 0; m < n; m++)
            idx[m] = m;
    } else {
        m = greedy(&t, 0, n - 1, n > 1 ? n - 1 : 1, idx);
        idx[m++] = n - 1;
        if (n == 1)
            m = 1;
    }
    double *res = malloc(2 * m * sizeof *res);
    if (!res) {
        free(idx);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    for (size_t i = 0; i < m; i++) {
        res[2 * i] = xy[2 * idx[i]];
        res[2 * i + 1] = xy[2 * idx[i] + 1];
    }
    free(idx);
    *out = res;
    *nout = m;
    conica__ok(st);
    return CONICA_OK;
}


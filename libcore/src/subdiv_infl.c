/* SPDX-License-Identifier: MIT */
/* Inflection edges of subdivision's input (CONIS, before eq. (9)) read
 * at the coordinates' own rounding, so that where a curve sits does not
 * change how many inflection points it gets. Called by subdiv_impl.h's
 * SFX(count_infl) after the exact side tests; reads the input points
 * only, calls only libm.
 *
 * Why. Edge (i, i+1) needs an inflection point when p_{i-1} and p_{i+2}
 * lie on different sides of its line, i.e. when the turns
 * tau_j = (p_j - p_{j-1}) x (p_{j+1} - p_j) at its two end vertices have
 * different signs. Near a true inflection (and on any nearly straight
 * run) |tau_j| falls to the rounding of the coordinates, which grows with
 * their magnitude: the same 10^6-point blob gave 6 sign changes at the
 * origin and 252 at (5000, 3000), each an extra inflection point, grown
 * patch and fallback. The sign of a turn within rounding of zero is noise;
 * only the signs of the turns outside it say which way the curve bends.
 * So between two consecutive vertices with a certain turn, the exact
 * sign changes (k of them) are replaced by their parity: one inflection
 * edge (the middle one of the k) when the certain turns differ in sign,
 * none when they agree. Where k <= 1 nothing changes, so exact data (the
 * seed's cases, the reference's outputs) keep their points bit for bit.
 *
 * A turn is uncertain when it is within INFL_NOISE_SIDE rounding units of
 * zero: |tau_j| <= INFL_NOISE_SIDE nu (|e_{j-1}| + |e_j|), the change three
 * points moved by up to nu can make, with nu the larger of settings.noise
 * and INFL_ULPS units in the last place of the three points' largest
 * coordinate magnitude (the data's own rounding, relative to where it
 * sits, as conica/path.h's precision is for the front end). */
#include <float.h>
#include <math.h>
#include <stddef.h>

#include "internal.h"

/* The data's own rounding: this many ulps of the largest |coordinate| of a turn's three points. */
#define INFL_ULPS 4.0
/* A turn this many rounding units (times the edge lengths) from zero is
 * uncertain (as CONICA__NOISE_SIDE for settings.noise). */
#define INFL_NOISE_SIDE 4.0

typedef struct pts {
    const double *d;
    const long double *l;
} pts;

static void pt(const pts *p, size_t k, long double *x, long double *y)
{
    if (p->d) {
        *x = p->d[2 * k];
        *y = p->d[2 * k + 1];
    } else {
        *x = p->l[2 * k];
        *y = p->l[2 * k + 1];
    }
}

/* Sign of the turn at vertex j (-1, 1), 0 when uncertain (see the top).
 * In long double whatever the mode, so that both modes decide alike (its
 * rounding is far below the threshold). */
static int turn_sign(const pts *p, size_t n, int closed, size_t j, long double noise)
{
    size_t a = closed ? (j + n - 1) % n : j - 1, c = closed ? (j + 1) % n : j + 1;
    long double x0, y0, x1, y1, x2, y2, big = 0, nu;
    pt(p, a, &x0, &y0);
    pt(p, j, &x1, &y1);
    pt(p, c, &x2, &y2);
    const long double v[6] = {x0, y0, x1, y1, x2, y2};
    for (int k = 0; k < 6; k++)
        big = fabsl(v[k]) > big ? fabsl(v[k]) : big;
    nu = INFL_ULPS * DBL_EPSILON * big; /* the three points' own rounding */
    nu = noise > nu ? noise : nu;
    long double ux = x1 - x0, uy = y1 - y0, vx = x2 - x1, vy = y2 - y1;
    long double t = ux * vy - uy * vx;
    long double lim = INFL_NOISE_SIDE * nu * (sqrtl(ux * ux + uy * uy) + sqrtl(vx * vx + vy * vy));
    if (fabsl(t) <= lim)
        return 0;
    return t > 0 ? 1 : -1;
}

/* The len edges e0, e0 + 1, ... (mod n) between two certain turns: k >= 2
 * exact sign changes become one (the middle one) when `differ`, else none. */
static void parity_run(unsigned char *need, size_t n, size_t e0, size_t len, int differ)
{
    size_t k = 0, seen = 0;
    for (size_t i = 0; i < len; i++)
        k += need[(e0 + i) % n];
    if (k < 2)
        return;
    for (size_t i = 0; i < len; i++) {
        unsigned char *e = &need[(e0 + i) % n];
        if (*e) {
            *e = (unsigned char)(differ && seen == (k - 1) / 2);
            seen++;
        }
    }
}

size_t conica__infl_at_rounding(const double *xyd, const long double *xyl, size_t n, int closed,
                                double noise, unsigned char *need)
{
    pts p = {xyd, xyl};
    size_t ne = closed ? n : n - 1, count = 0, jfirst = (size_t)-1, jprev = (size_t)-1;
    long double nu = noise;
    int sfirst = 0, sprev = 0;
    /* vertices with a turn: 1 .. n-2 open, all closed */
    for (size_t j = closed ? 0 : 1; n >= 3 && j + (closed ? 0 : 1) < n; j++) {
        int s = turn_sign(&p, n, closed, j, nu);
        if (s == 0)
            continue;
        if (jprev != (size_t)-1)
            parity_run(need, n, jprev, j - jprev, s != sprev);
        else {
            jfirst = j;
            sfirst = s;
        }
        jprev = j;
        sprev = s;
    }
    if (closed && jprev != (size_t)-1) /* round from the last certain turn to the first */
        parity_run(need, n, jprev, (jfirst + n - jprev) % n ? (jfirst + n - jprev) % n : n,
                   sfirst != sprev);
    else if (closed) /* no certain turn: straight to within rounding all round */
        for (size_t e = 0; e < ne; e++)
            need[e] = 0;
    for (size_t e = 0; e < ne; e++)
        count += need[e];
    return count;
}

/* SPDX-License-Identifier: MIT */
/* Guaranteed plotter (beyond Dahl 2019; the default for the tools).
 *
 * Emits points ON the curve and certifies every chord: for consecutive
 * emitted parameters u_a < u_b, every point of the spline on [u_a, u_b] is
 * within tol of the chord [f(u_a), f(u_b)] and every point of the chord is
 * within tol of the spline on [u_a, u_b].
 *
 * Certificate (proof sketch).
 * 1. Restriction. Inserting u_a and u_b p times each (Böhm, Lemma 1.18;
 *    the triangular algorithm of eq. (1.11) computes exactly these
 *    coefficients on its left/right diagonals; inside one knot interval the
 *    same coefficients come from de Casteljau splits of the interval's
 *    Bézier form, the case t_mu = t_{mu+1-p}, ... of eq. (1.11)) makes the
 *    spline on [u_a, u_b] a clamped B-spline whose control points Q_0..Q_m
 *    start at Q_0 = f(u_a) and end at Q_m = f(u_b) (Lemma 1.11).
 * 2. Curve -> chord. By the convex hull property (Lemma 1.13; for a
 *    rational spline the projected point is a convex combination of the
 *    projected control points with weights N_i w_i / sum N_j w_j > 0), f(u)
 *    lies in conv{Q_i}. The distance to the chord segment S is a convex
 *    function, so its maximum over conv{Q_i} is attained at a vertex:
 *    dist(f(u), S) <= D := max_i dist(Q_i, S).
 *    Tighter, planar case: if every Q_i projects onto S (not beyond its
 *    ends), so does every f(u) (same convex combination), and then
 *    dist(f(u), S) = |s(f(u))| with s the signed distance to the chord's
 *    line, an affine function: s(f(u)) = sum_i B_i(u) w_i s_i /
 *    sum_i B_i(u) w_i for a Bézier sub-arc, s_i = s(Q_i). That scalar
 *    (rational) Bernstein form is bounded by max |s_i|, more tightly by
 *    the same bound on its two halves after a de Casteljau split at 1/2,
 *    and exactly for a polynomial of degree 2 (|s_1| / 2) or 3 (the
 *    extremum of 3u(1-u)((1-u) s_1 + u s_2), a quadratic equation).
 * 3. Chord -> curve. Let pi be the nearest-point projection onto S; it is
 *    continuous, and pi(f(u_a)) = f(u_a), pi(f(u_b)) = f(u_b) are the two
 *    ends of S. So pi(f([u_a, u_b])) is a connected subset of S holding
 *    both ends, i.e. all of S: every q in S equals pi(f(u)) for some u and
 *    |q - f(u)| = dist(f(u), S) <= D.
 * Hence D <= tol certifies both directions of the Hausdorff distance.
 * D shrinks quadratically under refinement (the control polygon converges
 * quadratically, Theorem 1.16), so the march below terminates.
 *
 * Rounding. The interval's Bézier form comes from two triangular
 * algorithms on the input coefficients; the remainder of the interval is
 * re-split from it every G_RESET emitted points, so every certified
 * sub-arc is at most G_RESET + 1 convex de Casteljau splits (3p ulps of the
 * coordinates' magnitude each) away from exact data, and the margin
 * G_ULPS (p + 2) ulps (twice for rational input, whose homogeneous
 * coordinates are divided once more) covers the emitted vertices' error
 * and the certificate's arithmetic.
 *
 * The march, per knot interval: convert the interval to Bézier form once
 * (O(p^2)); keep the remainder [u_a, t_{mu+1}] as a Bézier curve; each
 * trial chord [u_a, x] is one de Casteljau split of the remainder at a
 * fixed ratio (no divisions, no span search), its left part is certified
 * and its right part is the next remainder when the trial is accepted.
 * Trials follow the D ~ C h^k model (k = 2 ahead, k fitted to a pass/fail
 * bracket), grow while D is well under tol, and the longest certified
 * chord is taken. When the chord reaching the interval's end was certified with
 * D < G_CROSS tol, longer chords across the knot are tried on the chain of
 * the following intervals' Bézier polygons (loaded as the trials reach
 * them, at most G_CHAIN_MAX intervals): the curve on [u_a, x] lies in the
 * union of the sub-arcs' hulls, and in the planar case with every control
 * point projecting onto the chord its distance is the largest of the
 * sub-arcs' signed-distance forms -- so short knot intervals do not force
 * extra vertices.
 *
 * Planar polynomial cubics (p = 3, d = 2, no weights: the thesis's test
 * curves sptest3/4, SVG and OpenSCAD Bézier paths) take c3_march, the same
 * march and the same certificate specialised, because at p = 3 uniform de
 * Boor sampling costs only about 54 flops per point (eq. (1.14) of
 * Dahl 2019: R(3) = 18 per coordinate, plus the parameter and the span
 * search) and needs only 3.2x-3.5x more points than this plotter, so a
 * certificate must cost a few dozen flops to win. Three things make it so.
 * (a) Everything lives on the stack (no allocation per call) and an
 * interval's Bézier form comes from blossoming: a and b inserted three
 * times each (Lemma 1.18) take 6 convex combinations, not two triangular
 * algorithms. (b) Cheap bounds decide most certificates without a square
 * root on the critical path: the signed-distance form (step 2) is bounded
 * above by its two halves' Bernstein coefficients after a split at 1/2 (at
 * most 1.125 times its maximum) and below by its values at 1/3, 1/2, 2/3;
 * only when tol lies between the two is the exact cubic extremum (a
 * quadratic equation) computed. (c) The first trial from a new point is
 * predicted from the remainder's own cubic (c3_step: the chord deviation
 * of a polynomial cubic in closed form up to a 3% overestimate near an
 * inflection, solved for 0.99 tol), so it mostly passes just under tol
 * and is taken: about 1.01-1.03 certificates per point, and within
 * 1.01x-1.02x of the greedy reference's points on single cubic pieces
 * (bench_flatten); a step that would pass a knot is tried across it.
 *
 * general_march predicts the first trial of planar polynomial splines
 * from the remainder's parabola (q2_step, exact, p = 2) or its Taylor
 * cubic at the start (model_lam, c3_step's model, p >= 4: 1.39 -> 1.05
 * trials per point on sptest2, p = 25); any other spline (dimension 3,
 * weights) follows D ~ K h^2 (Theorem 1.16) with K extrapolated linearly
 * from the chord just taken (its mean D / h^2) and the curvature at the
 * start of the remainder (start_k, from its first three homogeneous
 * control points; also the first trial of a piece; G_EXTRAP), so the
 * step anticipates a rising curvature instead of failing first. A piece
 * ends with two chords when the whole rest misses tol by a small factor
 * (G_HALVE). None of this changes the certificate. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bspline_internal.h"
#include "internal.h"
#include "plot_internal.h"

#define MAXP CONICA_BSPLINE_MAX_DEGREE
#define HD CONICA__HDIM_MAX
/* Step model D ~ C h^k: aim at this fraction of tol. */
#define G_TARGET 0.95
/* The first trial from a new point aims at this fraction of tol (the
 * curvature ahead may be larger than behind). */
#define G_NEXT 0.8
/* Grow a certified chord while D is below this fraction of tol. */
#define G_GROW_BELOW 0.55
#define G_MAX_GROW 3
/* A certified chord with D >= G_GOOD * tol is taken without searching on. */
#define G_GOOD 0.6
/* The general march of degrees G_CLOSE_MIN_P..G_CLOSE_MAX_P aims closer
 * (first trial at G_CLOSE_NEXT tol, search on below G_CLOSE_GOOD tol; the
 * planar polynomial ones at Q_AIM and Q_GOOD with model_lam): on the
 * random B-splines of degrees 4-7 of bench_flatten this brings the points
 * closer to the greedy reference of the true deviation. Rational
 * quadratics (circular arcs, whose chords conica/path.h's fit modes
 * offset) and high degrees (sptest2, where uniform de Boor is the
 * yardstick: model_lam aims at G_NEXT there) keep the faster
 * constants. */
#define G_CLOSE_MIN_P 4
#define G_CLOSE_MAX_P 8
#define G_CLOSE_NEXT 0.92
#define G_CLOSE_GOOD 0.85
/* Planar polynomial quadratics predict their next chord from the exact
 * deviation of the remainder's own parabola (q2_step) aiming at Q_AIM
 * tol_eff, so the rigorous trial that follows mostly passes close to tol:
 * it is taken from Q_GOOD tol on. Inside a knot interval the chords are
 * then within about 1% of the longest ones (D ~ h^2), the greedy
 * reference's, in about one certificate per point. Planar polynomial
 * cubics (and single quadratic pieces, raised to cubics) do the same with
 * c3_step, and planar polynomial splines of degrees
 * G_CLOSE_MIN_P..G_CLOSE_MAX_P with model_lam, the cubic model of the
 * remainder at its start (their certificate, the signed-distance form's
 * coefficients refined on halves, exceeds the true deviation by a few per
 * cent, so their chords stay a little further from tol). */
#define Q_AIM 0.99
#define Q_GOOD 0.9
#define Q_SHRINK 0.995
/* model_lam: at most C3_ITER steps, ending when one changes the step by
 * less than C3_STEP_STOP of it (c3_step, planar cubics) or C3_ITER_STOP
 * (general_march, degrees >= 4); C3_LAM_MAX (times the remainder) stands
 * for "no failing step known"; the largest |v (1 - v) (al + be v)| over
 * [0, 1] with an inflection inside (|2 al + be| < |be|) taken as
 * C3_INFL0 |be| + C3_INFL1 |2 al + be| (exact at both ends of that range,
 * at most 3% high between). */
#define C3_ITER 8
#define C3_ITER_STOP 0.01
#define C3_STEP_STOP 0.04
#define C3_LAM_MAX 4.0
#define C3_INFL0 0.0481125224324688 /* 1 / (12 sqrt 3) */
#define C3_INFL1 0.1000356257527164 /* 4 / 27 - C3_INFL0 */
/* Trials per emitted point and relative bracket width that end the search. */
#define G_MAX_TRIES 8
#define G_BRACKET 0.03
/* Range of the exponent k of the step model D ~ C h^k fitted to a
 * bracket. */
#define G_K_MIN 1.5
#define G_K_MAX 6.0
/* Least D (fraction of tol) the bracket model works with. */
#define G_DEV_FLOOR 1e-3
/* Up to this degree the tight (halves) certificate also steers growth. */
#define G_REFINE_MAX_P 8
/* When the hull bound misses tol by at most this factor (the hull of a
 * degree-p control polygon over-estimates a parabola-like arc by up to
 * p/(p-1)), certify again with the two halves' control polygons: the curve
 * on each half lies in that half's hull, and the distance to the chord is
 * convex, so the largest vertex distance over both halves is also a valid
 * bound -- a much tighter one (exact for a parabola). */
#define G_REFINE_RATIO 2.1
/* Rounding margin in units of DBL_EPSILON * (p + 2) * coordinate scale
 * (doubled for rational input). */
#define G_ULPS 64.0
/* Re-split the interval's remainder from its Bézier form after this many
 * accepted splits (bounds the accumulated rounding, see the top). */
#define G_RESET 4
/* Try a chord across the knot when the chord reaching the knot was
 * certified with D below this fraction of tol, with at most this many
 * trials. */
#define G_CROSS 0.8
#define G_CROSS_TRIES 4
/* When the chord over the whole rest of a piece fails with D at most
 * this multiple of G_TARGET tol, the rest takes two chords (D ~ h^2: each
 * half has about a quarter of D): a certified first chord reaching at
 * least half of the rest, else the half, then the whole remainder --
 * instead of searching for the longest first chord and then a short last
 * one. The same number of points in fewer trials. */
#define G_HALVE 3.0
/* A trial this close to the end of the remainder or chain it is tried on
 * (relative to that remainder's or trial chord's own parameter length,
 * never to the whole piece: on a long spline G_SNAP times the domain can
 * exceed a failed step's shrink, Q_SHRINK, and the search would retry the
 * same snapped trial for ever) ends there. */
#define G_SNAP 1e-9
/* Least trial step, relative to the knot interval it lies in; at least
 * G_MIN_STEP_ULPS ulps of the parameter, so a trial always moves. */
#define G_MIN_STEP 1e-13
#define G_MIN_STEP_ULPS 16.0
/* Knot intervals one chord may span. */
#define G_CHAIN_MAX 64
#define BZ ((MAXP + 1) * HD)

typedef struct march {
    int p, h, d;
    const double *T;
    size_t nk, n;
    double *H; /* homogeneous control points n * h */
    /* the remaining B-spline from ua (ua inserted p times): head, then the
     * input's control points from mua + 1 on (for the triangles) */
    double head[(MAXP + 1) * HD];
    double ua;
    size_t mua;
    /* diagonals of the last triangle */
    double le[(MAXP + 1) * HD], re[(MAXP + 1) * HD];
    double flops;
    /* Bézier march: interval [ba, bb] of span mu in Bézier form *B (the
     * remainder on [ua, bb] in *R; trial
     * halves *Lt, *Rt; the best certified trial's halves *Lb, *Rb
     * (pointers swap, no copies) */
    size_t mu;
    double ba, bb;
    double buf[6][BZ];
    double *B, *R, *Lt, *Rt, *Lb, *Rb;
    double tol, tol_eff;
    /* G_GOOD and G_NEXT, or their G_CLOSE_ values; model_lam's target */
    double good, next, aim;
    /* a failed first trial shrinks to D = shrink_aim tol by D ~ h^2, by a
     * factor of at most shrink_max (G_TARGET and 0.8; Q_AIM and Q_SHRINK
     * after q2_step's exact prediction, which fails only just) */
    double shrink_aim, shrink_max;
    /* chain for chords across knots: Bézier forms of the intervals
     * cmu[1..] after the current one, at C + k (p+1) h (allocated when a
     * chord first crosses a knot) */
    double *C;
    size_t *cmu, ccap;
} march;

static const double *rem_ctrl(const march *m, size_t i)
{
    size_t p = (size_t)m->p;
    return i <= p ? m->head + i * (size_t)m->h : m->H + (m->mua + i - p) * (size_t)m->h;
}

static double rem_knot(const march *m, size_t i)
{
    size_t p = (size_t)m->p;
    return i <= p ? m->ua : m->T[m->mua + i - p];
}

static void proj(const march *m, const double *hp, double *out)
{
    if (m->h > m->d) {
        for (int c = 0; c < m->d; c++)
            out[c] = hp[c] / hp[m->d];
    } else {
        for (int c = 0; c < m->d; c++)
            out[c] = hp[c];
    }
}

/* Squared distances to one chord [a, b], set up once per certificate. */
typedef struct chord {
    double a[3], ab[3], ab2;
    int d;
} chord;

static void chord_init(chord *c, const double *a, const double *b, int d)
{
    c->d = d;
    c->ab2 = 0;
    for (int k = 0; k < d; k++) {
        c->a[k] = a[k];
        c->ab[k] = b[k] - a[k];
        c->ab2 += c->ab[k] * c->ab[k];
    }
}

static double chord_d2(const chord *c, const double *q)
{
    double t = 0, qa2 = 0;
    for (int k = 0; k < c->d; k++) {
        double e = q[k] - c->a[k];
        t += e * c->ab[k];
        qa2 += e * e;
    }
    if (t <= 0 || c->ab2 <= 0)
        return qa2;
    if (t >= c->ab2) {
        double r = 0;
        for (int k = 0; k < c->d; k++) {
            double e = q[k] - c->a[k] - c->ab[k];
            r += e * e;
        }
        return r;
    }
    double r = qa2 - t * t / c->ab2;
    return r > 0 ? r : 0;
}

/* Largest squared distance of n homogeneous points to the chord. */
static double max_d2(const march *m, const chord *c, const double *hp, size_t n, double cur)
{
    size_t h = (size_t)m->h;
    double q[3];
    for (size_t i = 0; i < n; i++) {
        const double *x = hp + i * h;
        if (m->h > m->d) {
            for (int k = 0; k < m->d; k++)
                q[k] = x[k] / x[m->d];
            x = q;
        }
        double e = chord_d2(c, x);
        cur = e > cur ? e : cur;
    }
    return cur;
}

/* Triangle at x on the remaining spline with original span mu (left or
 * right convention chosen by the caller); fills m->le / m->re. */
static void triangle(march *m, double x, size_t mu)
{
    size_t p = (size_t)m->p, h = (size_t)m->h;
    size_t nu = p + mu - m->mua;
    double kl[2 * MAXP + 2];
    double dd[(MAXP + 1) * HD];
    for (size_t i = 0; i <= 2 * p; i++)
        kl[i] = rem_knot(m, nu - p + i);
    kl[2 * p + 1] = kl[2 * p];
    for (size_t k = 0; k <= p; k++)
        memcpy(dd + k * h, rem_ctrl(m, nu - p + k), h * sizeof *dd);
    m->flops += conica__deboor(kl, p, m->p, x, m->h, dd, m->le, m->re);
}

static void swap_ptr(double **x, double **y)
{
    double *t = *x;
    *x = *y;
    *y = t;
}

/* Start the remaining spline at u in span mu of the input: head = the
 * right diagonal of the triangle at u (u inserted p times). */
static void set_head(march *m, double u, size_t mu)
{
    size_t p = (size_t)m->p, h = (size_t)m->h;
    double dd[BZ];
    memcpy(dd, m->H + (mu - p) * h, (p + 1) * h * sizeof *dd);
    m->flops += conica__deboor(m->T, mu, m->p, u, m->h, dd, NULL, m->head);
    m->ua = u;
    m->mua = mu;
}

/* Bézier form of knot interval mu into dst: insert t_mu, then t_{mu+1},
 * p times each (two triangles; the second's left diagonal is the Bézier
 * polygon). */
static void load_bezier(march *m, size_t mu, double *dst)
{
    size_t p = (size_t)m->p, h = (size_t)m->h;
    double ua = m->ua;
    size_t mua = m->mua;
    set_head(m, m->T[mu], mu);
    triangle(m, m->T[mu + 1], mu);
    memcpy(dst, m->le, (p + 1) * h * sizeof *dst);
    m->ua = ua;
    m->mua = mua;
}

/* Make interval mu current (its Bézier form copied from `form` when not
 * NULL, else computed), the remainder being the whole interval. */
static void enter_interval(march *m, size_t mu, const double *form)
{
    size_t nb = (size_t)(m->p + 1) * (size_t)m->h;
    if (form)
        memcpy(m->B, form, nb * sizeof *m->B);
    else
        load_bezier(m, mu, m->B);
    memcpy(m->R, m->B, nb * sizeof *m->R);
    m->mu = mu;
    m->ba = m->T[mu];
    m->bb = m->T[mu + 1];
    m->ua = m->ba;
}

static inline void put3(double *o, double x, double y, double w)
{
    o[0] = x;
    o[1] = y;
    o[2] = w;
}

/* De Casteljau split of the Bézier polygon P (p+1 points of H values) at
 * lam in [0, 1]: L gets the polygon of [0, lam], Rr that of [lam, 1]
 * (Rr is the working array; its last point is P's exactly). H is a
 * constant at each call site below, so the inner loops unroll. */
static inline void casteljau(const double *P, int p, int H, double lam, double *L, double *Rr)
{
    if (p == 3 && H == 2) {
        /* the planar cubic written out, the same operations: every load
         * before every store, since the compiler must assume L and Rr may
         * alias P (a loop over the two coordinates reloaded P after each
         * store, 7% of the instructions of the split) */
        double x0 = P[0], x1 = P[2], x2 = P[4], x3 = P[6];
        double y0 = P[1], y1 = P[3], y2 = P[5], y3 = P[7];
        double ax = x0 + lam * (x1 - x0), bx = x1 + lam * (x2 - x1), ex = x2 + lam * (x3 - x2);
        double ay = y0 + lam * (y1 - y0), by = y1 + lam * (y2 - y1), ey = y2 + lam * (y3 - y2);
        double fx = ax + lam * (bx - ax), gx = bx + lam * (ex - bx), qx = fx + lam * (gx - fx);
        double fy = ay + lam * (by - ay), gy = by + lam * (ey - by), qy = fy + lam * (gy - fy);
        L[0] = x0;
        L[1] = y0;
        L[2] = ax;
        L[3] = ay;
        L[4] = fx;
        L[5] = fy;
        L[6] = qx;
        L[7] = qy;
        Rr[0] = qx;
        Rr[1] = qy;
        Rr[2] = gx;
        Rr[3] = gy;
        Rr[4] = ex;
        Rr[5] = ey;
        Rr[6] = x3;
        Rr[7] = y3;
        return;
    }
    if (p == 2 && H == 3) {
        /* the conic arc (homogeneous quadratic) written out likewise: the
         * loop over H was not unrolled, and a third of the arcs' and
         * circles' instructions were this split */
        double x0 = P[0], y0 = P[1], w0 = P[2], x1 = P[3], y1 = P[4], w1 = P[5];
        double x2 = P[6], y2 = P[7], w2 = P[8];
        double ax = x0 + lam * (x1 - x0), ay = y0 + lam * (y1 - y0), aw = w0 + lam * (w1 - w0);
        double bx = x1 + lam * (x2 - x1), by = y1 + lam * (y2 - y1), bw = w1 + lam * (w2 - w1);
        double fx = ax + lam * (bx - ax), fy = ay + lam * (by - ay), fw = aw + lam * (bw - aw);
        put3(L, x0, y0, w0);
        put3(L + 3, ax, ay, aw);
        put3(L + 6, fx, fy, fw);
        put3(Rr, fx, fy, fw);
        put3(Rr + 3, bx, by, bw);
        put3(Rr + 6, x2, y2, w2);
        return;
    }
    size_t hh = (size_t)H, pp = (size_t)p;
    for (size_t c = 0; c < hh; c++) {
        L[c] = P[c];
        Rr[pp * hh + c] = P[pp * hh + c];
    }
    for (size_t k = 0; k < pp; k++) /* first level straight from P */
        for (size_t c = 0; c < hh; c++)
            Rr[k * hh + c] = P[k * hh + c] + lam * (P[(k + 1) * hh + c] - P[k * hh + c]);
    for (size_t c = 0; c < hh; c++)
        L[hh + c] = Rr[c];
    for (size_t r = 2; r <= pp; r++) {
        for (size_t k = 0; k <= pp - r; k++) {
            double *q = Rr + k * hh;
            for (size_t c = 0; c < hh; c++)
                q[c] += lam * (q[c + hh] - q[c]);
        }
        for (size_t c = 0; c < hh; c++)
            L[r * hh + c] = Rr[c];
    }
}

static void split(march *m, const double *P, double lam, double *L, double *Rr)
{
    switch (m->h * 8 + (m->p <= 3 ? m->p : 0)) { /* unrolled for p <= 3 */
    case 2 * 8 + 2: casteljau(P, 2, 2, lam, L, Rr); break;
    case 2 * 8 + 3: casteljau(P, 3, 2, lam, L, Rr); break;
    case 3 * 8 + 2: casteljau(P, 2, 3, lam, L, Rr); break;
    case 3 * 8 + 3: casteljau(P, 3, 3, lam, L, Rr); break;
    case 2 * 8 + 0: case 2 * 8 + 1: casteljau(P, m->p, 2, lam, L, Rr); break;
    case 3 * 8 + 0: case 3 * 8 + 1: casteljau(P, m->p, 3, lam, L, Rr); break;
    default: casteljau(P, m->p, 4, lam, L, Rr); break;
    }
    m->flops += 1.5 * (double)(m->p * (m->p + 1)) * (double)m->h;
}

/* Value at u of the scalar Bézier polynomial s_0..s_p, p <= 3. */
static double bern_eval(const double *s, int p, double u)
{
    double v = 1.0 - u;
    switch (p) {
    case 1: return v * s[0] + u * s[1];
    case 2: return v * v * s[0] + 2.0 * u * v * s[1] + u * u * s[2];
    default: return v * v * v * s[0] + 3.0 * u * v * (v * s[1] + u * s[2]) + u * u * u * s[3];
    }
}

/* max over [0,1] of |3u(1-u)((1-u) s1 + u s2)|, the cubic Bézier
 * (0, s1, s2, 0) of a single sub-arc: the extrema are the roots of
 * g'(u) = s1 + 2(k - s1) u - 3k u^2, k = s2 - s1, whose discriminant
 * 4(k^2 + k s1 + s1^2) is never negative; both roots are evaluated,
 * clamped to [0, 1] (a root outside, infinite or NaN when k = 0 gives
 * an end, where the cubic vanishes, or 1/2 for k = 0 and s1 != 0). */
static inline double cubic_max(double s1, double s2)
{
    double k = s2 - s1, A = -3.0 * k, Bq = 2.0 * (k - s1);
    double sq = sqrt(4.0 * (k * k + k * s1 + s1 * s1));
    double q = -0.5 * (Bq + copysign(sq, Bq));
    double u1 = q / A, u2 = s1 / q;
    u1 = u1 > 0.0 ? (u1 < 1.0 ? u1 : 1.0) : 0.0;
    u2 = u2 > 0.0 ? (u2 < 1.0 ? u2 : 1.0) : 0.0;
    double v1 = fabs(3.0 * u1 * (1.0 - u1) * ((1.0 - u1) * s1 + u1 * s2));
    double v2 = fabs(3.0 * u2 * (1.0 - u2) * ((1.0 - u2) * s1 + u2 * s2));
    return v1 > v2 ? v1 : v2;
}

/* Parts of an arc piece beyond a chord end bounded by their own hulls in
 * seg_exact (the hull over-estimates a part's distance by O(part^2)). */
#define SEG_PARTS 8

/* Roots in (0, 1) of the Bernstein polynomial b_0..b_q, q <= 2, appended
 * to u[*n]. */
static void bern_roots(const double *b, int q, double *u, int *n)
{
    double r[2];
    int nr = 0;
    if (q == 1) {
        if (b[0] != b[1])
            r[nr++] = b[0] / (b[0] - b[1]);
    } else if (q == 2) {
        double A = b[0] - 2.0 * b[1] + b[2], B = 2.0 * (b[1] - b[0]), C = b[0];
        if (A == 0.0) {
            if (B != 0.0)
                r[nr++] = -C / B;
        } else {
            double disc = B * B - 4.0 * A * C;
            if (disc >= 0.0) {
                double qq = -0.5 * (B + copysign(sqrt(disc), B));
                r[nr++] = qq / A;
                if (qq != 0.0)
                    r[nr++] = C / qq;
            }
        }
    }
    for (int i = 0; i < nr; i++)
        if (r[i] > 0.0 && r[i] < 1.0)
            u[(*n)++] = r[i];
}

/* Least and largest value over [u0, u1] within [0, 1] of
 * sum B_i^p(u) s_i for 1 <= p <= 3, exactly, and where (ulo, uhi may be
 * NULL): the ends and the roots of the derivative inside, whose Bernstein
 * coefficients are the differences D_i = s_{i+1} - s_i. Shared with the
 * curve front end's chord distances (path.c). */
void conica__bern_range(const double *s, int p, double u0, double u1, double *lo, double *ulo,
                        double *hi, double *uhi)
{
    double a = bern_eval(s, p, u0), b = bern_eval(s, p, u1);
    double l = a, g = a, tl = u0, tg = u0, d[3], u[2];
    int nu = 0;
    if (b < l) {
        l = b;
        tl = u1;
    }
    if (b > g) {
        g = b;
        tg = u1;
    }
    for (int i = 0; i < p; i++)
        d[i] = s[i + 1] - s[i];
    bern_roots(d, p - 1, u, &nu);
    for (int i = 0; i < nu; i++)
        if (u[i] > u0 && u[i] < u1) {
            double v = bern_eval(s, p, u[i]);
            if (v < l) {
                l = v;
                tl = u[i];
            }
            if (v > g) {
                g = v;
                tg = u[i];
            }
        }
    *lo = l;
    *hi = g;
    if (ulo)
        *ulo = tl;
    if (uhi)
        *uhi = tg;
}

static void bern_range_on(const double *s, int p, double u0, double u1, double *lo, double *hi)
{
    conica__bern_range(s, p, u0, u1, lo, NULL, hi, NULL);
}

static void bern_range(const double *s, int p, double *lo, double *hi)
{
    bern_range_on(s, p, 0.0, 1.0, lo, hi);
}

/* Largest |sum B_i^p s_i| over [u0, u1] within [0, 1], p <= 3. */
static double bern_max_on(const double *s, int p, double u0, double u1)
{
    double lo, hi;
    bern_range_on(s, p, u0, u1, &lo, &hi);
    return -lo > hi ? -lo : hi;
}

/* max over [0,1] of |sum B_i^p(u) s_i| for p <= 3, exactly. */
static double bern_max(const double *s, int p)
{
    double lo, hi;
    bern_range(s, p, &lo, &hi);
    return -lo > hi ? -lo : hi;
}

/* Whether the polynomial sub-arc of degree p <= 3 whose control points
 * project to t_0..t_p (times |c|) on the chord's line projects onto the
 * chord [0, c2] at every u -- exactly, from the range of its projection
 * polynomial sum B_i t_i, not from the control points (which may project
 * beyond an end while the arc does not: a tight bend near a chord end).
 * Step 2 of the certificate needs exactly this: then the distance of
 * every arc point to the segment is |s(f(u))|. */
static int proj_inside(const double *t, int p, double c2)
{
    double lo, hi;
    bern_range(t, p, &lo, &hi);
    return lo >= 0.0 && hi <= c2;
}

/* Certified distance bound of a planar polynomial Bézier arc P of degree
 * p <= 3 (p + 1 points x y) to its chord segment S = [P_0, P_p] when the
 * arc's projection runs past an end of S (proj_inside fails: a hook near
 * a chord end), for step 2 of the certificate. The projection polynomial
 * t(u) (times |c|) vanishes at 0 and equals c2 at 1, so t = u q(u) and
 * t - c2 = (u - 1) r(u) with q, r of degree p - 1 (Bernstein
 * coefficients p t_{i+1} / (i + 1) and their mirror): their roots split
 * [0, 1] into pieces on which the arc projects onto S (distance |s(u)| / |c|,
 * its exact maximum there) or beyond one end (distance to that end, a
 * convex function: bounded by the control points of SEG_PARTS parts of
 * the piece, two de Casteljau splits each). Returns a negative value when the chord is
 * degenerate. */
static double seg_exact(const double *P, int p)
{
    double ax = P[0], ay = P[1], cx = P[2 * p] - ax, cy = P[2 * p + 1] - ay;
    double c2 = cx * cx + cy * cy, t[4], sd[4], q[3], r[3], u[6];
    if (!(c2 > 0) || p < 2 || p > 3)
        return -1.0;
    for (int i = 0; i <= p; i++) {
        double ex = P[2 * i] - ax, ey = P[2 * i + 1] - ay;
        t[i] = ex * cx + ey * cy;
        sd[i] = ex * cy - ey * cx;
    }
    t[0] = sd[0] = sd[p] = 0.0;
    t[p] = c2;
    for (int i = 0; i < p; i++) {
        q[i] = (double)p * t[i + 1] / (double)(i + 1);
        r[i] = (double)p * (c2 - t[p - 1 - i]) / (double)(i + 1);
    }
    int nu = 1, nr0;
    u[0] = 0.0;
    bern_roots(q, p - 1, u, &nu);
    nr0 = nu;
    bern_roots(r, p - 1, u, &nu);
    for (int i = nr0; i < nu; i++)
        u[i] = 1.0 - u[i];
    u[nu++] = 1.0;
    for (int i = 1; i < nu; i++) /* insertion sort of at most 6 */
        for (int j = i; j > 0 && u[j] < u[j - 1]; j--) {
            double x = u[j];
            u[j] = u[j - 1];
            u[j - 1] = x;
        }
    double inv = 1.0 / sqrt(c2), best = 0.0;
    for (int k = 0; k + 1 < nu; k++) {
        double u0 = u[k], u1 = u[k + 1];
        if (!(u1 > u0))
            continue;
        double tm = bern_eval(t, p, 0.5 * (u0 + u1)), e;
        if (tm >= 0.0 && tm <= c2) {
            e = bern_max_on(sd, p, u0, u1) * inv;
        } else { /* beyond an end: the hulls of SEG_PARTS parts, distance to that end */
            const double *end = tm < 0.0 ? P : P + 2 * p;
            double d2 = 0.0, A[8], B[8], C[8], *part = A, *rest = B;
            /* the arc of [u0, u1], then its parts off its front in turn:
             * part j ends where 1 / (SEG_PARTS - j) of the rest does (one
             * split per part, not two from P) */
            if (p == 2) {
                casteljau(P, 2, 2, u1, A, B);
                casteljau(A, 2, 2, u1 > 0 ? u0 / u1 : 0.0, C, rest);
            } else {
                casteljau(P, 3, 2, u1, A, B);
                casteljau(A, 3, 2, u1 > 0 ? u0 / u1 : 0.0, C, rest);
            }
            for (int j = 0; j < SEG_PARTS; j++) {
                double *next = rest == B ? C : B;
                if (j + 1 < SEG_PARTS) {
                    double v = 1.0 / (double)(SEG_PARTS - j);
                    if (p == 2)
                        casteljau(rest, 2, 2, v, part, next);
                    else
                        casteljau(rest, 3, 2, v, part, next);
                } else {
                    memcpy(part, rest, (size_t)(2 * p + 2) * sizeof *part);
                }
                for (int i = 0; i <= p; i++) {
                    double ex = part[2 * i] - end[0], ey = part[2 * i + 1] - end[1];
                    double v = ex * ex + ey * ey;
                    d2 = v > d2 ? v : d2;
                }
                rest = next;
            }
            e = sqrt(d2);
        }
        best = e > best ? e : best;
    }
    return best;
}

/* Bound of the scalar rational Bernstein form sum B_i a_i / sum B_i w_i
 * (w == NULL: polynomial) by its halves' coefficients after a split at
 * 1/2. */
static double scalar_halves(march *m, const double *a, const double *w, int p)
{
    double la[MAXP + 1], lw[MAXP + 1], ra[MAXP + 1], rw[MAXP + 1];
    memcpy(ra, a, (size_t)(p + 1) * sizeof *ra);
    if (w)
        memcpy(rw, w, (size_t)(p + 1) * sizeof *rw);
    la[0] = ra[0];
    lw[0] = w ? rw[0] : 1.0;
    for (int r = 1; r <= p; r++) {
        for (int k = 0; k <= p - r; k++)
            ra[k] = 0.5 * (ra[k] + ra[k + 1]);
        la[r] = ra[0];
        if (w) {
            for (int k = 0; k <= p - r; k++)
                rw[k] = 0.5 * (rw[k] + rw[k + 1]);
            lw[r] = rw[0];
        }
    }
    double best = 0.0;
    for (int i = 0; i <= p; i++) {
        double x = w ? fabs(la[i]) / lw[i] : fabs(la[i]);
        double y = w ? fabs(ra[i]) / rw[i] : fabs(ra[i]);
        best = x > best ? x : best;
        best = y > best ? y : best;
    }
    m->flops += (double)(p * (p + 1)) * (w ? 3.0 : 1.5) + (w ? 2.0 * (p + 1) : 0.0);
    return best;
}

/* The planar chord from a with direction (cx, cy), |c|^2 = c2: signed
 * distances times |c| of the points i0..i1 of polygon P into s[i], their
 * projections on the chord's line times |c| into t[i] (and their weights
 * into w[i] when rational). Returns 0 when a point projects beyond the
 * chord's ends (step 2 then needs proj_inside, when `exact`: all points
 * are computed for it, or the hull bound: the first such point ends). */
static int signed_dists(const march *m, const double *P, int i0, int i1, const double *a, double cx,
                        double cy, double c2, int exact, double *s, double *t, double *w,
                        double *smax)
{
    size_t hh = (size_t)m->h;
    int rational = m->h > m->d, in = 1;
    for (int i = i0; i <= i1; i++) {
        const double *q = P + (size_t)i * hh;
        double x = q[0], y = q[1];
        if (rational) {
            w[i] = q[2];
            x /= q[2];
            y /= q[2];
        }
        double ex = x - a[0], ey = y - a[1];
        t[i] = ex * cx + ey * cy;
        in = in && t[i] >= 0 && t[i] <= c2;
        if (!in && !exact)
            return 0; /* no proj_inside to follow: the hull bound */
        s[i] = ex * cy - ey * cx;
        double v = fabs(s[i]);
        *smax = v > *smax ? v : *smax;
    }
    return in;
}

/* Certified bound D for the chord from the first point of P1 to the last
 * point of the Bézier sub-arc (P2 == NULL: P1 alone; else the curve is P1
 * followed by P2, which starts where P1 ends, across a knot). Planar: the
 * signed-distance form of step 2 when every control point projects onto
 * the chord (exact for polynomial degree <= 3, else max |s_i|, tightened
 * by halves near tol); otherwise the hull bound (tightened by halves for
 * a single sub-arc). `steer` asks for the tight value also when D is
 * under tol (growth decisions). */
/* bez_cert for one planar conic sub-arc (p = 2, h = 3, no P2, positive
 * weights) whose middle control point projects onto the chord: the
 * signed-distance form's exact maximum |s_1| w_1 / (w_1 + sqrt(w_0 w_2))
 * over |c| (conica__r2_absmax with s_0 = s_2 = 0), in the homogeneous
 * points A, M, B themselves. With C = B w_0 - A w_2 and E = M w_0 - A w_1
 * (the chord and the middle point's offset times w_0 w_2 and w_0 w_1), it
 * is |E x C| / (w_0 (w_1 + sqrt(w_0 w_2)) |C|): one division instead of
 * the eight of the general code below, whose chain of divisions and
 * square roots bounded the arcs' and circles' speed. Returns -1 when the
 * middle point projects beyond the chord or a weight is not positive (the
 * general code decides then). */
static double conic_cert(march *m, const double *P)
{
    double w0 = P[2], w1 = P[5], w2 = P[8];
    if (!(w0 > 0 && w1 > 0 && w2 > 0))
        return -1.0;
    double Cx = P[6] * w0 - P[0] * w2, Cy = P[7] * w0 - P[1] * w2;
    double Ex = P[3] * w0 - P[0] * w1, Ey = P[4] * w0 - P[1] * w1;
    double c2 = Cx * Cx + Cy * Cy, t = Ex * Cx + Ey * Cy;
    /* 0 <= e.c <= |c|^2 for e = E / (w0 w1), c = C / (w0 w2) */
    if (!(c2 > 0) || !(t >= 0 && t * w2 <= c2 * w1))
        return -1.0;
    m->flops += 30.0;
    return fabs(Ex * Cy - Ey * Cx) / (w0 * (w1 + sqrt(w0 * w2)) * sqrt(c2));
}

static double bez_cert(march *m, const double *P1, const double *P2, int steer)
{
    int p = m->p, d = m->d, h = m->h;
    size_t hh = (size_t)h, pp = (size_t)p;
    int rational = h > d;
    const double *Pe = P2 ? P2 : P1;
    double a[3], b[3];
    if (p == 2 && h == 3 && d == 2 && !P2) {
        double D = conic_cert(m, P1);
        if (D >= 0.0)
            return D;
    }
    proj(m, P1, a);
    proj(m, Pe + pp * hh, b);
    int near_tol_check = 0;
    if (d == 2) {
        double cx = b[0] - a[0], cy = b[1] - a[1], c2 = cx * cx + cy * cy;
        double s1[MAXP + 1], w1[MAXP + 1], s2[MAXP + 1], w2[MAXP + 1], t1[MAXP + 1],
            t2[MAXP + 1], smax = 0.0;
        int inside = c2 > 0, exact = !rational && p <= 3;
        s1[0] = t1[0] = 0.0;
        w1[0] = rational ? P1[2] : 1.0;
        if (inside && !P2) {
            s1[p] = 0.0;
            t1[p] = c2;
            w1[p] = rational ? P1[pp * hh + 2] : 1.0;
            inside = signed_dists(m, P1, 1, p - 1, a, cx, cy, c2, exact, s1, t1, w1, &smax) ||
                     (exact && proj_inside(t1, p, c2));
        } else if (inside) {
            s2[p] = 0.0;
            t2[p] = c2;
            w2[p] = rational ? P2[pp * hh + 2] : 1.0;
            int in1 = signed_dists(m, P1, 1, p, a, cx, cy, c2, exact, s1, t1, w1, &smax);
            int in2 = (in1 || exact) &&
                      signed_dists(m, P2, 0, p - 1, a, cx, cy, c2, exact, s2, t2, w2, &smax);
            inside = (in1 || (exact && proj_inside(t1, p, c2))) &&
                     (in2 || (exact && proj_inside(t2, p, c2)));
        }
        m->flops += 10.0 + (double)(P2 ? 2 * p : p - 1) * (rational ? 12.0 : 10.0);
        if (inside) {
            double inv = 1.0 / sqrt(c2);
            double D = smax * inv;
            if (!rational && p == 3 && !P2) {
                D = cubic_max(s1[1], s1[2]) * inv;
                m->flops += 30.0;
            } else if (!rational && p <= 3) {
                double e = bern_max(s1, p);
                if (P2) {
                    double e2 = bern_max(s2, p);
                    e = e2 > e ? e2 : e;
                }
                D = e * inv;
                m->flops += P2 ? 60.0 : 30.0;
            } else if (rational && p == 2) { /* exact, plot_conic.c */
                double e = conica__r2_absmax(s1, w1);
                if (P2) {
                    double e2 = conica__r2_absmax(s2, w2);
                    e = e2 > e ? e2 : e;
                }
                D = e * inv;
                m->flops += P2 ? 80.0 : 12.0;
            } else if (D > m->tol_eff ? D <= G_REFINE_RATIO * m->tol_eff
                                      : (steer && D >= G_GROW_BELOW * m->tol &&
                                         p <= G_REFINE_MAX_P)) {
                if (rational)
                    for (int i = 0; i <= p; i++) {
                        s1[i] *= w1[i];
                        s2[i] *= P2 ? w2[i] : 0.0;
                    }
                double e = scalar_halves(m, s1, rational ? w1 : NULL, p);
                if (P2) {
                    double e2 = scalar_halves(m, s2, rational ? w2 : NULL, p);
                    e = e2 > e ? e2 : e;
                }
                D = e * inv < D ? e * inv : D;
            }
            return D;
        }
    }
    chord c;
    chord_init(&c, a, b, d);
    double d2 = max_d2(m, &c, P1 + hh, P2 ? pp : pp - 1, 0.0);
    if (P2)
        d2 = max_d2(m, &c, P2, pp, d2);
    double D = sqrt(d2);
    m->flops += (double)(P2 ? 2 * p + 2 : p + 1) * (12.0 + 3.0 * (double)d);
    if (!P2 && d == 2 && !rational && p <= 3 && D > m->good * m->tol) {
        double De = seg_exact(P1, p);
        m->flops += 200.0;
        if (De >= 0.0 && De < D)
            return De;
    }
    near_tol_check = D > m->tol_eff ? D <= G_REFINE_RATIO * m->tol_eff
                                    : (steer && D >= G_GROW_BELOW * m->tol && p <= G_REFINE_MAX_P);
    if (!P2 && p > 1 && near_tol_check) {
        double l2[BZ], r2[BZ];
        split(m, P1, 0.5, l2, r2);
        d2 = max_d2(m, &c, l2 + hh, pp, 0.0);
        d2 = max_d2(m, &c, r2, pp, d2);
        m->flops += (double)(2 * p + 2) * (12.0 + 3.0 * (double)d);
        double D2 = sqrt(d2);
        D = D2 < D ? D2 : D;
    }
    return D;
}

static conica_code too_many(size_t max_iter, conica_plot_stats *stats, conica_status *st)
{
    if (stats->iterations >= max_iter)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "guaranteed plot needs more than %zu trial steps "
                            "(max_iterations)",
                            max_iter);
    stats->iterations++;
    return CONICA_OK;
}

/* Next step length from a bracket [hp passing with D = dp, hf failing
 * with df]: D ~ C h^k through both (k from the pair, kept in
 * [G_K_MIN, G_K_MAX]; k = 2 for a smooth arc, larger near a feature),
 * solved for D = G_TARGET tol, kept inside the bracket. */
static double secant(double hp, double dp, double hf, double df, double tol)
{
    double h;
    /* a straight passing chord (dp = 0 up to rounding) counts as
     * G_DEV_FLOOR tol, so the step does not jump between this model and
     * bisection on rounding noise */
    dp = dp > G_DEV_FLOOR * tol ? dp : G_DEV_FLOOR * tol;
    if (df > dp && hf > hp) {
        double k = log(df / dp) / log(hf / hp);
        k = k < G_K_MIN ? G_K_MIN : (k > G_K_MAX ? G_K_MAX : k);
        h = hp * pow(G_TARGET * tol / dp, 1.0 / k);
    } else {
        h = 0.5 * (hp + hf);
    }
    double lo = hp + 0.1 * (hf - hp), hi = hp + 0.9 * (hf - hp);
    return h < lo ? lo : (h > hi ? hi : h);
}

/* Least trial step from ua in the knot interval [ba, bb], see G_MIN_STEP. */
static double min_step_in(double ua, double ba, double bb)
{
    double h = G_MIN_STEP * (bb - ba), u = G_MIN_STEP_ULPS * DBL_EPSILON * fabs(ua);
    return h > u ? h : u;
}

/* Longest certified chord from m->ua inside the current interval (trial
 * steps *hs from ua, at most to bb): on return *xo and *devo, the halves
 * of the accepted split in m->Lb / m->Rb (unless *xo == bb: then the
 * chord is the whole remainder m->R). *halved is set when the rest of the
 * piece (ending at b_end) is to take one more chord, see G_HALVE. */
static conica_code bez_search(march *m, double *hs, double b_end, size_t max_iter,
                              conica_plot_stats *stats, double *xo, double *devo, int *halved,
                              conica_status *st)
{
    double ua = m->ua, bb = m->bb, tol = m->tol;
    double snap = G_SNAP * (bb - ua), min_step = min_step_in(ua, m->ba, bb);
    int have = 0, have_fail = 0, grows = 0, tries = 0;
    *halved = 0;
    double best_dev = 0, best_x = bb, fail_x = bb, fail_dev = 0;
    for (;;) {
        double x = ua + *hs;
        if (!(x < bb) || bb - x < snap)
            x = bb;
        conica_code rc = too_many(max_iter, stats, st);
        if (rc != CONICA_OK)
            return rc;
        tries++;
        double dev;
        if (x == bb) { /* the whole remainder */
            dev = bez_cert(m, m->R, NULL, 0);
        } else {
            split(m, m->R, (x - ua) / (bb - ua), m->Lt, m->Rt);
            dev = bez_cert(m, m->Lt, NULL, 1);
        }
        if (dev <= m->tol_eff) {
            have = 1;
            best_dev = dev;
            best_x = x;
            if (x < bb) {
                swap_ptr(&m->Lt, &m->Lb);
                swap_ptr(&m->Rt, &m->Rb);
            }
            if (x >= bb || dev >= m->good * tol || *halved)
                break;
        } else {
            have_fail = 1;
            *halved = 0; /* the half failed too: search as usual */
            fail_x = x;
            fail_dev = dev;
        }
        double hp = best_x - ua, hf = fail_x - ua;
        if (x == bb && bb >= b_end && dev <= G_HALVE * G_TARGET * tol) {
            /* the rest of the piece needs two chords (D ~ h^2): take a
             * certified one reaching at least half of it, else try the
             * half, instead of searching for the longest first chord and
             * a short last one */
            *halved = 1;
            if (have && hp >= 0.5 * hf)
                break;
            *hs = 0.5 * hf;
            continue;
        }
        if (have && have_fail) {
            if (tries >= G_MAX_TRIES || hf - hp < G_BRACKET * hp)
                break;
            *hs = secant(hp, best_dev, hf, fail_dev, tol);
        } else if (have) {
            if (grows++ >= G_MAX_GROW)
                break;
            double f = dev > 0 ? sqrt(G_TARGET * tol / dev) : 4.0;
            f = f < 1.15 ? 1.15 : (f > 4.0 ? 4.0 : f);
            *hs = hp * f;
        } else {
            double f = sqrt(m->shrink_aim * tol / dev); /* D ~ h^2 */
            f = f < 0.1 ? 0.1 : (f > m->shrink_max ? m->shrink_max : f);
            *hs = hf * f;
            if (*hs < min_step)
                return conica__fail(st, CONICA_ERR_NUMERIC, 0, 0,
                                    "cannot certify tolerance %.3g near parameter %.17g", tol,
                                    ua);
        }
    }
    *xo = best_x;
    *devo = best_dev;
    return CONICA_OK;
}

/* First non-empty knot interval at or after span mu. */
static size_t next_span(const march *m, size_t mu)
{
    while (mu + 1 < m->n && !(m->T[mu] < m->T[mu + 1]))
        mu++;
    return mu;
}

/* Certified bound for the chord from the first point of R to the last of
 * `last` over the chain R, C[1..j-1], last of Bézier sub-arcs of
 * consecutive knot intervals (step 2 on each sub-arc: the curve lies in
 * the union of their hulls; planar: the signed-distance form on each,
 * exact per sub-arc for polynomial degree <= 3, else max |s_i|). */
static double chain_cert(march *m, const double *last, size_t j)
{
    int p = m->p, d = m->d, h = m->h;
    size_t hh = (size_t)h, pp = (size_t)p, bz = (pp + 1) * hh;
    int rational = h > d;
    double a[3], b[3];
    proj(m, m->R, a);
    proj(m, last + pp * hh, b);
    if (d == 2) {
        double cx = b[0] - a[0], cy = b[1] - a[1], c2 = cx * cx + cy * cy;
        double s[MAXP + 1], t[MAXP + 1], w[MAXP + 1], D = 0.0;
        double cn = sqrt(c2), lim = m->tol_eff * cn;
        int inside = c2 > 0, exact = !rational && p <= 3;
        for (size_t k = 0; k <= j && inside; k++) {
            const double *P = k == 0 ? m->R : (k == j ? last : m->C + k * bz);
            double smax = 0.0;
            s[0] = s[p] = 0.0;
            t[0] = 0.0;
            t[p] = c2;
            w[0] = rational ? P[2] : 1.0;
            w[p] = rational ? P[pp * hh + 2] : 1.0;
            inside = signed_dists(m, P, k == 0 ? 1 : 0, k == j ? p - 1 : p, a, cx, cy, c2, exact,
                                  s, t, w, &smax) ||
                     (exact && proj_inside(t, p, c2));
            int r2 = rational && p == 2; /* exact, plot_conic.c */
            double e = exact ? bern_max(s, p) : (r2 && inside ? conica__r2_absmax(s, w) : smax);
            if (inside && !exact && !r2 && e > lim && e <= G_REFINE_RATIO * lim) {
                /* near tol: the sub-arc's form on its two halves, as in
                 * bez_cert (the coefficients alone over-estimate a bump of
                 * degree p by up to p / (p - 1)) */
                if (rational)
                    for (int i = 0; i <= p; i++)
                        s[i] *= w[i];
                double e2 = scalar_halves(m, s, rational ? w : NULL, p);
                e = e2 < e ? e2 : e;
            }
            D = e > D ? e : D;
        }
        m->flops += 10.0 + (double)((j + 1) * pp) * (rational ? 12.0 : 10.0) +
                    (!rational && p <= 3 ? 30.0 * (double)(j + 1) : 0.0);
        if (inside)
            return D / cn;
    }
    chord c;
    chord_init(&c, a, b, d);
    double d2 = max_d2(m, &c, m->R + hh, pp, 0.0);
    for (size_t k = 1; k < j; k++)
        d2 = max_d2(m, &c, m->C + k * bz, pp + 1, d2);
    d2 = max_d2(m, &c, last, pp, d2);
    m->flops += (double)((j + 1) * (pp + 1)) * (12.0 + 3.0 * (double)d);
    return sqrt(d2);
}

/* Load the Bézier form of the interval after chain element nc as element
 * nc + 1 (element 0 is the current interval). 0 when the chain is full,
 * the piece ends there, or memory runs out (then no longer chord). */
static int chain_grow(march *m, size_t nc)
{
    size_t bz = (size_t)(m->p + 1) * (size_t)m->h;
    size_t prev = nc == 0 ? m->mu : m->cmu[nc];
    if (nc + 1 >= G_CHAIN_MAX || m->T[prev + 1] >= m->T[m->n])
        return 0;
    if (nc + 2 > m->ccap) {
        size_t cap = m->ccap ? 2 * m->ccap : 8;
        cap = cap > G_CHAIN_MAX ? G_CHAIN_MAX : cap;
        double *C = realloc(m->C, cap * bz * sizeof *C);
        if (!C)
            return 0;
        m->C = C;
        size_t *cm = realloc(m->cmu, cap * sizeof *cm);
        if (!cm)
            return 0;
        m->cmu = cm;
        m->ccap = cap;
    }
    size_t mu = next_span(m, prev + 1);
    load_bezier(m, mu, m->C + (nc + 1) * bz);
    m->cmu[nc + 1] = mu;
    return 1;
}

/* A cross search's trial chord end x, snapped to the chain's end `end`
 * and to the piece's end b_end when within `snap` of them (NaN goes to
 * the end), never past `end`: a chain that could not grow (full, or the
 * knots end first) can stop short of b_end, and the search for the
 * trial's chain element relies on x <= end. */
static double cross_trial_end(double x, double end, double b_end, double snap)
{
    if (!(x < end) || end - x < snap)
        x = end;
    if (!(x < b_end) || b_end - x < snap)
        x = b_end;
    return x > end ? end : x;
}

/* The chord from m->ua to the interval's end bb is certified with dev0:
 * try longer chords across the knot into the following intervals
 * (loaded into the chain as the trials reach them). *found tells whether
 * one, ending at *xo in chain interval *jo, passed; that interval's
 * split halves are then in m->Lb / m->Rb (m->Lb its whole polygon when
 * *xo is its end). *nco gets the number of intervals loaded. */
static conica_code cross_search(march *m, double dev0, double hs0, double b_end,
                                size_t max_iter,
                                conica_plot_stats *stats, int *found, double *xo, double *devo,
                                size_t *jo, size_t *nco, conica_status *st)
{
    double ua = m->ua, bb = m->bb, tol = m->tol;
    size_t bz = (size_t)(m->p + 1) * (size_t)m->h;
    size_t nc = 0;
    double best_x = bb, best_dev = dev0, fail_x = b_end, fail_dev = 0;
    int have_fail = 0, grows = 0, tries = 0;
    double f = dev0 > 0 ? sqrt(G_TARGET * tol / dev0) : 4.0;
    f = f < 1.15 ? 1.15 : (f > 4.0 ? 4.0 : f);
    double hs = hs0 > bb - ua ? hs0 : (bb - ua) * f;
    *found = 0;
    for (;;) {
        double x = ua + hs;
        while (nc == 0 || x > m->T[m->cmu[nc] + 1]) {
            if (!chain_grow(m, nc))
                break;
            nc++;
        }
        if (nc == 0)
            break;
        double end = m->T[m->cmu[nc] + 1];
        x = cross_trial_end(x, end, b_end, G_SNAP * (x - ua));
        if (x <= best_x)
            break;
        conica_code rc = too_many(max_iter, stats, st);
        if (rc != CONICA_OK)
            return rc;
        tries++;
        size_t j = 1;
        while (x > m->T[m->cmu[j] + 1])
            j++;
        double t0 = m->T[m->cmu[j]], t1 = m->T[m->cmu[j] + 1];
        const double *Cj = m->C + j * bz;
        double dev;
        if (x >= t1) {
            dev = chain_cert(m, Cj, j);
        } else {
            split(m, Cj, (x - t0) / (t1 - t0), m->Lt, m->Rt);
            dev = chain_cert(m, m->Lt, j);
        }
        if (dev <= m->tol_eff) {
            *found = 1;
            best_dev = dev;
            best_x = x;
            *jo = j;
            if (x < t1) {
                swap_ptr(&m->Lt, &m->Lb);
                swap_ptr(&m->Rt, &m->Rb);
            } else {
                memcpy(m->Lb, Cj, bz * sizeof *m->Lb);
            }
            if (x >= b_end || dev >= m->good * tol)
                break;
        } else {
            have_fail = 1;
            fail_x = x;
            fail_dev = dev;
        }
        if (tries >= G_CROSS_TRIES)
            break;
        double hp = best_x - ua, hf = fail_x - ua;
        if (have_fail) {
            if (hf - hp < G_BRACKET * hp)
                break;
            hs = secant(hp, best_dev, hf, fail_dev, tol);
        } else {
            if (grows++ >= G_MAX_GROW)
                break;
            double g = dev > 0 ? sqrt(G_TARGET * tol / dev) : 4.0;
            g = g < 1.15 ? 1.15 : (g > 4.0 ? 4.0 : g);
            hs = hp * g;
        }
    }
    *xo = best_x;
    *devo = best_dev;
    *nco = nc;
    return CONICA_OK;
}

static CONICA__HOT_INLINE conica_code push_param(double **params, size_t *np, size_t *cap,
                                                 double u, conica_status *st)
{
    if (!params)
        return CONICA_OK;
    if (*np == *cap) {
        size_t nc = *cap ? 2 * *cap : 64;
        double *v = realloc(*params, nc * sizeof *v);
        if (!v)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        *params = v;
        *cap = nc;
    }
    (*params)[(*np)++] = u;
    return CONICA_OK;
}

/* ------------------------------------------------------------------
 * Planar polynomial cubics (p = 3, d = 2, no weights: the thesis's test
 * curves, SVG and OpenSCAD Bézier paths). The same march and the same
 * certificate as above, specialised: every array lives on the stack (no
 * allocation per call), a Bézier polygon is 8 interleaved doubles, and an
 * interval's Bézier form comes from blossoming (6 convex combinations
 * instead of two triangular algorithms). */

/* Coordinates below which a polynomial cubic's de Casteljau points cannot
 * overflow (conica_plot_bezier). */
#define CONICA__FINITE_SCALE 1e300

#define C3 8 /* doubles of a planar cubic Bézier polygon */
/* Step model of general_march for the next chord: D(h) ~ K h^2 with K
 * extrapolated linearly from the previous chord's mean K_p = D / h^2
 * (about the value at its middle) and the value at its end K_s, from the
 * quadratic model of the remainder R at its start (start_k).
 * K = G_EXTRAP K_s + (1 - G_EXTRAP) K_p, at least K_s / 2. */
#define G_EXTRAP 2.0

/* First trial after a chord of parameter length step certified with dev:
 * with a curvature estimate Ks at the new start (use_k), the extrapolated
 * model above, kept within [step / 2, 2 step]; without one, D ~ h^2 from
 * the chord alone. */
static double next_step(int use_k, double Ks, double dev, double step, double tol, double next)
{
    if (use_k) {
        double Ka = G_EXTRAP * Ks + (1.0 - G_EXTRAP) * dev / (step * step);
        Ka = Ka < 0.5 * Ks ? 0.5 * Ks : Ka;
        double h2 = Ka > 0 ? sqrt(next * tol / Ka) : 2.0 * step;
        return h2 < 0.5 * step ? 0.5 * step : (h2 > 2.0 * step ? 2.0 * step : h2);
    }
    double f = dev > 0 ? sqrt(next * tol / dev) : 2.0;
    f = f < 0.7 ? 0.7 : (f > 2.0 ? 2.0 : f);
    return step * f;
}

typedef struct c3m {
    const double *T, *d; /* knots, control points (x y interleaved) */
    size_t n;            /* control points */
    double tol, tol_eff;
    /* operations, summed as an integer: every count here is a whole
     * number, and an integer add through memory is a shorter chain than
     * a floating-point one */
    size_t flops;
    /* current interval [ba, bb] = [t_mu, t_mu+1], its Bézier form B, the
     * remainder R on [ua, bb]; trial halves Lt / Rt, best certified
     * trial's halves Lb / Rb (pointers swap, no copies) */
    size_t mu;
    double ba, bb, ua, inv; /* inv = 1 / (bb - ua) */
    double bend;            /* the piece's end */
    double B[C3];
    double buf[5][C3];
    double *R, *Lt, *Rt, *Lb, *Rb;
    /* chain for chords across knots: element k >= 1 is the Bézier form of
     * interval cmu[k] in C[k] (element 0 is the current interval) */
    double C[G_CHAIN_MAX][C3];
    size_t cmu[G_CHAIN_MAX], nc; /* elements 1..nc loaded */
} c3m;

/* Bézier polygon P of knot interval mu (t_mu < t_mu+1) of the planar cubic:
 * the blossoms f(a,a,a), f(a,a,b), f(a,b,b), f(b,b,b), a = t_mu,
 * b = t_mu+1, i.e. a and b inserted three times each (Lemma 1.18): the
 * first level of the triangular algorithm (eq. (1.11)) at a and at b
 * gives f(a,a,b) = E_a[mu-1] and f(a,b,b) = E_b[mu-1] directly (the
 * later levels' weights are 0 or 1 there), and one more convex
 * combination each gives the ends. Every weight lies in [0, 1] (each
 * denominator spans [t_mu, t_mu+1]). */
static void c3_form(const double *T, const double *d, size_t mu, double *P)
{
    double a = T[mu], b = T[mu + 1];
    const double *d0 = d + 2 * (mu - 3), *d1 = d0 + 2, *d2 = d0 + 4, *d3 = d0 + 6;
    double al0 = (a - T[mu - 2]) / (T[mu + 1] - T[mu - 2]);
    double al1 = (a - T[mu - 1]) / (T[mu + 2] - T[mu - 1]);
    double be1 = (b - T[mu - 1]) / (T[mu + 2] - T[mu - 1]);
    double be2 = (b - T[mu]) / (T[mu + 3] - T[mu]);
    double g0 = (a - T[mu - 1]) / (T[mu + 1] - T[mu - 1]);
    double g3 = (b - T[mu]) / (T[mu + 2] - T[mu]);
    for (int c = 0; c < 2; c++) {
        double ea0 = d0[c] + al0 * (d1[c] - d0[c]), ea1 = d1[c] + al1 * (d2[c] - d1[c]);
        double eb1 = d1[c] + be1 * (d2[c] - d1[c]), eb2 = d2[c] + be2 * (d3[c] - d2[c]);
        P[c] = ea0 + g0 * (ea1 - ea0);
        P[2 + c] = ea1;
        P[4 + c] = eb1;
        P[6 + c] = eb1 + g3 * (eb2 - eb1);
    }
}

/* Hull bound of step 2 for the chord of the cubic sub-arc L (a control
 * point projects beyond the chord's ends), refined on the halves near tol
 * as bez_cert does. */
static double c3_hull(c3m *m, const double *L)
{
    double De = seg_exact(L, 3);
    m->flops += 200;
    if (De >= 0.0)
        return De;
    chord c;
    chord_init(&c, L, L + 6, 2);
    double d2 = chord_d2(&c, L + 2), e = chord_d2(&c, L + 4);
    d2 = e > d2 ? e : d2;
    double D = sqrt(d2);
    m->flops += 2 * 18 + 6;
    if (D > m->tol_eff ? D <= G_REFINE_RATIO * m->tol_eff : D >= G_GROW_BELOW * m->tol) {
        double l[C3], r[C3];
        casteljau(L, 3, 2, 0.5, l, r);
        d2 = 0.0;
        for (int i = 1; i < 4; i++) {
            e = chord_d2(&c, l + 2 * i);
            d2 = e > d2 ? e : d2;
        }
        for (int i = 1; i < 3; i++) {
            e = chord_d2(&c, r + 2 * i);
            d2 = e > d2 ? e : d2;
        }
        double D2 = sqrt(d2);
        D = D2 < D ? D2 : D;
        m->flops += 36 + 5 * 18;
    }
    return D;
}

/* proj_inside for a cubic sub-arc whose inner control points project to
 * t1, t2 (the ends to 0 and c2). */
static int c3_inside(c3m *m, double t1, double t2, double c2)
{
    double t[4] = {0.0, t1, t2, c2};
    m->flops += 40;
    return proj_inside(t, 3, c2);
}

/* Certified bound D for the chord of the single cubic sub-arc L (step 2)
 * when both inner control points project onto the chord: the signed-
 * distance form g(u) = 3u(1-u)((1-u) s1 + u s2) / |c| is bounded above by
 * its two halves' Bernstein coefficients (split at 1/2: s1/2,
 * (2 s1 + s2)/4, 3 (s1 + s2)/8, (s1 + 2 s2)/4, s2/2; at most 1.125 times
 * the true maximum) and below by its values at 1/3, 1/2, 2/3; only when
 * tol lies between the two is the exact extremum (cubic_max, a square
 * root and divisions on the critical path) computed. The value returned
 * is a valid bound when it passes (the upper bound, or the exact value)
 * and a value above tol_eff when it fails. Otherwise the hull bound. */
static double c3_cert1(c3m *m, const double *L)
{
    double ax = L[0], ay = L[1];
    double cx = L[6] - ax, cy = L[7] - ay, c2 = cx * cx + cy * cy;
    double e1x = L[2] - ax, e1y = L[3] - ay, e2x = L[4] - ax, e2y = L[5] - ay;
    double t1 = e1x * cx + e1y * cy, t2 = e2x * cx + e2y * cy;
    m->flops += 17;
    if (c2 > 0 && ((t1 >= 0 && t1 <= c2 && t2 >= 0 && t2 <= c2) || c3_inside(m, t1, t2, c2))) {
        double s1 = e1x * cy - e1y * cx, s2 = e2x * cy - e2y * cx;
        double inv = 1.0 / sqrt(c2); /* in parallel with the bounds */
        double a1 = fabs(s1), a2 = fabs(s2);
        double mid = fabs(s1 + s2), q1 = fabs(s1 + s1 + s2), q2 = fabs(s1 + s2 + s2);
        double up = 0.5 * (a1 > a2 ? a1 : a2), uq = 0.25 * (q1 > q2 ? q1 : q2);
        double lo = (1.0 / 4.5) * (q1 > q2 ? q1 : q2); /* |g(1/3)|, |g(2/3)| */
        up = up > uq ? up : uq;
        up = up > 0.375 * mid ? up : 0.375 * mid;
        lo = lo > 0.375 * mid ? lo : 0.375 * mid;
        double Du = up * inv, Dl = lo * inv;
        m->flops += 6 + 20 + 4;
        if (Du <= m->tol_eff || Dl > m->tol_eff)
            return Du <= m->tol_eff ? Du : Dl;
        /* tol_eff itself (a valid bound) on a pass and Dl's least value
         * on a failure keep the value continuous in the data, so rounding
         * cannot swing the step model by the bounds' gap */
        m->flops += 32;
        return cubic_max(s1, s2) * inv <= m->tol_eff ? m->tol_eff : nextafter(m->tol_eff, INFINITY);
    }
    return c3_hull(m, L);
}

/* Certified bound for the chord from the first point of arcs[0] to the
 * last of arcs[k-1], consecutive cubic sub-arcs across knots (as
 * chain_cert: the curve lies in the union of their hulls; when every
 * control point projects onto the chord, the exact extremum of each
 * sub-arc's signed-distance form). */
static double c3_cert_chain(c3m *m, const double *const *arcs, size_t k)
{
    const double *A = arcs[0], *E = arcs[k - 1] + 6;
    double ax = A[0], ay = A[1], cx = E[0] - ax, cy = E[1] - ay, c2 = cx * cx + cy * cy;
    double D = 0.0, s[4];
    int inside = c2 > 0;
    for (size_t j = 0; j < k && inside; j++) {
        const double *P = arcs[j];
        double t[4] = {0.0, 0.0, 0.0, c2};
        int in = 1;
        s[0] = s[3] = 0.0;
        for (int i = j == 0 ? 1 : 0; i <= (j + 1 == k ? 2 : 3); i++) {
            double ex = P[2 * i] - ax, ey = P[2 * i + 1] - ay;
            t[i] = ex * cx + ey * cy;
            in = in && t[i] >= 0 && t[i] <= c2;
            s[i] = ex * cy - ey * cx;
        }
        inside = in || proj_inside(t, 3, c2);
        if (inside) {
            double e = bern_max(s, 3);
            D = e > D ? e : D;
        }
    }
    m->flops += 10 + (4 * k) * 10 + 30 * k;
    if (inside)
        return D / sqrt(c2);
    chord c;
    chord_init(&c, A, E, 2);
    double d2 = 0.0;
    for (size_t j = 0; j < k; j++)
        for (int i = 0; i < 4; i++) {
            double e = chord_d2(&c, arcs[j] + 2 * i);
            d2 = e > d2 ? e : d2;
        }
    m->flops += (4 * k) * 18;
    return sqrt(d2);
}

static size_t c3_next_span(const c3m *m, size_t mu)
{
    while (mu + 1 < m->n && !(m->T[mu] < m->T[mu + 1]))
        mu++;
    return mu;
}

/* Make interval mu current, the remainder being the whole interval. Its
 * Bézier form is chain element k when 1 <= k <= nc (the elements after
 * it move down to 1, 2, ...), else computed (the chain is then empty). */
static void c3_enter(c3m *m, size_t mu, size_t k)
{
    if (k >= 1 && k <= m->nc) {
        memcpy(m->B, m->C[k], sizeof m->B);
        memmove(m->C[1], m->C[k + 1], (m->nc - k) * sizeof m->C[0]);
        memmove(m->cmu + 1, m->cmu + k + 1, (m->nc - k) * sizeof m->cmu[0]);
        m->nc -= k;
    } else if (m->n == 4 && m->T[0] == m->T[3] && m->T[4] == m->T[7]) {
        /* one clamped Bézier piece: its Bézier form is its control
         * polygon (c3_form's weights are 0 or 1 there, but d1 + 1 (d2 -
         * d1) need not round to d2) */
        memcpy(m->B, m->d, sizeof m->B);
        m->nc = 0;
    } else {
        c3_form(m->T, m->d, mu, m->B);
        m->flops += 6 * 3 + 12 * 3;
        m->nc = 0;
    }
    memcpy(m->R, m->B, sizeof m->B);
    m->mu = mu;
    m->ba = m->T[mu];
    m->bb = m->T[mu + 1];
    m->ua = m->ba;
    m->inv = 1.0 / (m->bb - m->ba);
}

/* bez_search on the current interval of a cubic. */
static conica_code c3_search(c3m *m, size_t max_iter, double *hs, conica_plot_stats *stats,
                             double *xo, double *devo, conica_status *st)
{
    double ua = m->ua, bb = m->bb, tol = m->tol;
    double snap = G_SNAP * (bb - ua), min_step = min_step_in(ua, m->ba, bb);
    int have = 0, have_fail = 0, grows = 0, tries = 0;
    double best_dev = 0, best_x = bb, fail_x = bb, fail_dev = 0;
    for (;;) {
        double x = ua + *hs;
        if (!(x < bb) || bb - x < snap)
            x = bb;
        conica_code rc = too_many(max_iter, stats, st);
        if (rc != CONICA_OK)
            return rc;
        tries++;
        double dev;
        if (x == bb) {
            dev = c3_cert1(m, m->R);
        } else {
            casteljau(m->R, 3, 2, (x - ua) * m->inv, m->Lt, m->Rt);
            m->flops += 38;
            dev = c3_cert1(m, m->Lt);
        }
        /* 97% of trials: the first one passes and is good enough (the
         * straight layout of this path, 2.5% of a cubic piece's time) */
        if (CONICA__LIKELY(dev <= m->tol_eff)) {
            have = 1;
            best_dev = dev;
            best_x = x;
            if (x < bb) {
                swap_ptr(&m->Lt, &m->Lb);
                swap_ptr(&m->Rt, &m->Rb);
            }
            if (CONICA__LIKELY(x >= bb || dev >= Q_GOOD * tol))
                break;
        } else {
            have_fail = 1;
            fail_x = x;
            fail_dev = dev;
        }
        double hp = best_x - ua, hf = fail_x - ua;
        if (have && have_fail) {
            if (tries >= G_MAX_TRIES || hf - hp < G_BRACKET * hp)
                break;
            *hs = secant(hp, best_dev, hf, fail_dev, tol);
        } else if (have) {
            if (grows++ >= G_MAX_GROW)
                break;
            double f = dev > 0 ? sqrt(G_TARGET * tol / dev) : 4.0;
            f = f < 1.15 ? 1.15 : (f > 4.0 ? 4.0 : f);
            *hs = hp * f;
        } else {
            double f = sqrt(Q_AIM * tol / dev);
            f = f < 0.1 ? 0.1 : (f > Q_SHRINK ? Q_SHRINK : f);
            *hs = hf * f;
            if (*hs < min_step)
                return conica__fail(st, CONICA_ERR_NUMERIC, 0, 0,
                                    "cannot certify tolerance %.3g near parameter %.17g", tol,
                                    ua);
        }
    }
    *xo = best_x;
    *devo = best_dev;
    return CONICA_OK;
}

/* a b + c for model_lam: fused where the hardware has it (3% of a cubic
 * piece's time), as written where fma() would be a library call. */
#ifdef FP_FAST_FMA
#define MODEL_FMA(a, b, c) fma(a, b, c)
#else
#define MODEL_FMA(a, b, c) ((a) * (b) + (c))
#endif

/* Step (in units of R's parameter) from the start of the planar
 * polynomial Bézier remainder R of degree p to the chord end where the
 * deviation is about T, from the cubic model of R at its start (R itself
 * when p = 3; p >= 4 drops O(lam^4) terms; C = 0 for p = 2). In
 * power form R(s) = R0 + A s + B s^2 + C s^3 (for p = 3: A = 3 (R1 - R0),
 * B = 3 (R2 - 2 R1 + R0), C = R3 - 3 R2 + 3 R1 - R0; s in [0, 1] over
 * the remainder) the arc minus the chord [0, lam] is s (s - lam) (B + C (s +
 * lam)), so with s = lam v its distance across the chord's direction
 * c = A + B lam + C lam^2 is lam^2 |v (1 - v) (al + be v)| / |c|, with
 * al + be / 2 = w / 2, w = 2 kAB + 3 lam kAC + lam^2 kBC, be = lam kAC +
 * lam^2 kBC (kXY = X x Y). Its largest value over v is w / 8 + be^2 /
 * (32 w) up to O(be^4 / w^3) (Taylor at the middle, where the
 * derivative is be / 4): the deviation is about
 * lam^2 (4 w^2 + be^2) / (32 |w| |c|) (never below the true value: at
 * most 1.06 times it; with an inflection inside, |w| < |be|, see
 * C3_INFL0). The squared ratio rho = (D / T)^2 grows about as lam^4, so
 * lam rho^(-1/4), in its Padé form lam (5 + 3 rho) / (3 + 5 rho) (one
 * division, no root, a factor within [3/5, 5/3]), converges to D = T from
 * lam (the previous chord's length: the same curvature ahead) or, when
 * lam <= 0, the small-step value sqrt(4 T |A| / |kAB|); a step leaving the
 * bracket of known passing and failing lam bisects it (a sharp bend ahead,
 * where D rises much faster than lam^2). Only steers the next trial (the
 * certificate decides); returns at least 1 when `last` (R ends the piece)
 * and the whole rest is predicted to pass, 2 when R is straight. */
static CONICA__HOT_INLINE double model_lam(const double *R, int p, double T, double lam,
                                          int last, double stop, size_t *flops)
{
    /* the Taylor cubic at the start: A = p D1, B = C(p,2) D2, C = C(p,3) D3
     * (forward differences of the polygon; the remainder itself for p = 3) */
    double c1 = (double)p, c2 = 0.5 * c1 * (double)(p - 1), c3 = c2 * (double)(p - 2) / 3.0;
    double ax = c1 * (R[2] - R[0]), ay = c1 * (R[3] - R[1]);
    double bx = c2 * (R[4] - 2.0 * R[2] + R[0]), by = c2 * (R[5] - 2.0 * R[3] + R[1]);
    double cx = 0.0, cy = 0.0;
    if (p >= 3) {
        cx = c3 * (R[6] - R[0] - 3.0 * (R[4] - R[2]));
        cy = c3 * (R[7] - R[1] - 3.0 * (R[5] - R[3]));
    }
    double kab = ax * by - ay * bx, kac = ax * cy - ay * cx, kbc = bx * cy - by * cx;
    double A2 = ax * ax + ay * ay, t2 = T * T, lo = 0.0, hi = C3_LAM_MAX;
    *flops += 40;
    if (!(fabs(kab) + fabs(kac) > 0) || !(A2 > 0))
        return 2.0;
    if (!(lam > 0.0) && kab != 0.0) /* the small-step value */
        lam = sqrt(4.0 * T * sqrt(A2) / fabs(kab));
    lam = lam > 0.0 && lam < 1.0 ? lam : 1.0;
    for (int it = 0; it < C3_ITER; it++) {
        /* fused multiply-adds (MODEL_FMA): this loop is the latency
         * chain of the march, each step waiting for its lam, and a model
         * that only steers the trial may round as it likes */
        double w = MODEL_FMA(lam, MODEL_FMA(lam, kbc, 3.0 * kac), 2.0 * kab);
        double be = lam * MODEL_FMA(lam, kbc, kac);
        double dx = MODEL_FMA(lam, MODEL_FMA(lam, cx, bx), ax);
        double dy = MODEL_FMA(lam, MODEL_FMA(lam, cy, by), ay);
        double Q = MODEL_FMA(dx, dx, dy * dy), N, M;
        if (fabs(w) >= fabs(be)) { /* the largest |v (1 - v) (al + be v)| is N / M */
            N = MODEL_FMA(4.0 * w, w, be * be);
            M = 32.0 * w;
        } else { /* an inflection inside */
            N = C3_INFL0 * fabs(be) + C3_INFL1 * fabs(w);
            M = 1.0;
        }
        /* rho = (D / T)^2 = lam^4 N^2 / (T^2 |c|^2 M^2) ~ lam^4: lam rho^(-1/4)
         * by its Padé form, within [3/5, 5/3] lam */
        double u = lam * lam * N, num = u * u, ref = t2 * Q * M * M;
        double f = MODEL_FMA(5.0, ref, 3.0 * num) / MODEL_FMA(3.0, ref, 5.0 * num), nl = lam * f;
        *flops += 45;
        if (!(f > 0)) /* not a number: keep lam */
            break;
        if (lam >= 1.0 && num <= ref && last) { /* the whole rest of the piece */
            lam = nl;
            break;
        }
        if (num < ref)
            lo = lam;
        else
            hi = lam;
        /* D may rise much faster than lam^2 (a sharp bend ahead): then the
         * step leaves the bracket and bisects it instead */
        lam = nl > lo && nl < hi ? nl : (hi < C3_LAM_MAX ? 0.5 * (lo + hi) : nl);
        if (fabs(f - 1.0) < stop)
            break;
    }
    return lam;
}

/* c3_march's next trial: model_lam on the remainder from the previous
 * chord's length h0 (0: none) in parameter length. */
static CONICA__HOT_INLINE double c3_step(c3m *m, double T, double h0)
{
    double L = m->bb - m->ua;
    return model_lam(m->R, 3, T, h0 * m->inv, m->bb >= m->bend, C3_STEP_STOP, &m->flops) * L;
}

/* Load the Bézier form of the interval after the last chain element as
 * a new element. 0 when the chain is full or the piece ends there. */
static int c3_chain_grow(c3m *m)
{
    size_t nc = m->nc, prev = nc == 0 ? m->mu : m->cmu[nc];
    if (nc + 1 >= G_CHAIN_MAX || m->T[prev + 1] >= m->T[m->n])
        return 0;
    size_t mu = c3_next_span(m, prev + 1);
    c3_form(m->T, m->d, mu, m->C[nc + 1]);
    m->flops += 6 * 3 + 12 * 3;
    m->cmu[nc + 1] = mu;
    m->nc = nc + 1;
    return 1;
}

/* cross_search for a cubic, in two modes. dev0 >= 0: the chord to the
 * interval's end bb is certified with dev0, the first trial follows from
 * it. dev0 < 0 ("direct"): nothing is certified yet, the first trial is
 * ua + hs0 beyond bb, and a failure ends the search (the caller then
 * searches inside the interval). *xf / *df: a known failing chord end
 * (*xf <= ua: none) on entry, the last failing one on return. */
static conica_code c3_cross(c3m *m, double dev0, double hs0, double b_end,
                            size_t max_iter, conica_plot_stats *stats, int *found,
                            double *xo, double *devo, size_t *jo, double *xf, double *df,
                            conica_status *st)
{
    double ua = m->ua, bb = m->bb, tol = m->tol;
    const double *arcs[G_CHAIN_MAX + 1];
    int direct = dev0 < 0;
    double best_x = bb, best_dev = dev0, fail_x = b_end, fail_dev = 0;
    int have_fail = *xf > ua, grows = 0, tries = 0;
    if (have_fail) {
        fail_x = *xf;
        fail_dev = *df;
    }
    double hs = hs0;
    if (!direct) {
        double f = dev0 > 0 ? sqrt(G_TARGET * tol / dev0) : 4.0;
        f = f < 1.15 ? 1.15 : (f > 4.0 ? 4.0 : f);
        hs = (bb - ua) * f;
        if (have_fail)
            hs = secant(bb - ua, dev0, fail_x - ua, fail_dev, tol);
    }
    *found = 0;
    arcs[0] = m->R;
    for (size_t k = 1; k <= m->nc; k++)
        arcs[k] = m->C[k];
    for (;;) {
        double x = ua + hs;
        while (m->nc == 0 || x > m->T[m->cmu[m->nc] + 1]) {
            if (!c3_chain_grow(m))
                break;
            arcs[m->nc] = m->C[m->nc];
        }
        if (m->nc == 0)
            break;
        double end = m->T[m->cmu[m->nc] + 1];
        x = cross_trial_end(x, end, b_end, G_SNAP * (x - ua));
        if (x <= best_x || (have_fail && x >= fail_x))
            break;
        conica_code rc = too_many(max_iter, stats, st);
        if (rc != CONICA_OK)
            return rc;
        tries++;
        size_t j = 1;
        while (x > m->T[m->cmu[j] + 1])
            j++;
        double t0 = m->T[m->cmu[j]], t1 = m->T[m->cmu[j] + 1];
        double dev;
        if (x >= t1) {
            dev = c3_cert_chain(m, arcs, j + 1);
        } else {
            casteljau(m->C[j], 3, 2, (x - t0) / (t1 - t0), m->Lt, m->Rt);
            m->flops += 39;
            const double *keep = arcs[j];
            arcs[j] = m->Lt;
            dev = c3_cert_chain(m, arcs, j + 1);
            arcs[j] = keep;
        }
        if (dev <= m->tol_eff) {
            *found = 1;
            best_dev = dev;
            best_x = x;
            *jo = j;
            if (x < t1) {
                swap_ptr(&m->Lt, &m->Lb);
                swap_ptr(&m->Rt, &m->Rb);
            } else {
                memcpy(m->Lb, m->C[j], sizeof m->B);
            }
            if (x >= b_end || dev >= Q_GOOD * tol)
                break;
        } else {
            have_fail = 1;
            fail_x = x;
            fail_dev = dev;
            if (!*found && direct)
                break;
        }
        if (tries >= G_CROSS_TRIES)
            break;
        double hp = best_x - ua, hf = fail_x - ua;
        if (have_fail) {
            if (hf - hp < G_BRACKET * hp)
                break;
            hs = secant(hp, best_dev, hf, fail_dev, tol);
        } else {
            if (grows++ >= G_MAX_GROW)
                break;
            double g = dev > 0 ? sqrt(G_TARGET * tol / dev) : 4.0;
            g = g < 1.15 ? 1.15 : (g > 4.0 ? 4.0 : g);
            hs = hp * g;
        }
    }
    if (have_fail) {
        *xf = fail_x;
        *df = fail_dev;
    }
    *xo = best_x;
    *devo = best_dev;
    return CONICA_OK;
}

/* Take the certified chord [ua, x] that ends in chain element j (an
 * interval after the current one): its end point goes to pt; then either x
 * lies inside that interval, whose right part goes on, or x is the piece's
 * end (returns 1), or x is that interval's end and the next one is entered.
 * *splits counts the de Casteljau splits since the last exact Bézier form. */
static int c3_take_chain(c3m *m, const conica_bspline *g, size_t j, double x, double b,
                         double *pt, size_t *splits)
{
    size_t muj = m->cmu[j];
    memcpy(pt, m->Lb + 6, 2 * sizeof *pt);
    if (x < m->T[muj + 1]) {
        c3_enter(m, muj, j);
        swap_ptr(&m->R, &m->Rb);
        m->ua = x;
        m->inv = 1.0 / (m->bb - x);
        *splits = 1;
        return 0;
    }
    if (m->T[muj + 1] >= b) {
        memcpy(pt, g->ctrl + 2 * (g->n - 1), 2 * sizeof *pt);
        return 1;
    }
    c3_enter(m, c3_next_span(m, muj + 1), j + 1);
    *splits = 0;
    return 0;
}

/* The march of conica__guaranteed_piece for a planar polynomial cubic;
 * the first point is already out. *maxdev gets the largest certified
 * bound. A step that would pass the interval's end is first tried as a
 * chord across the knot (one trial; when it fails the search goes on
 * inside the interval, bracketed by it). */
static conica_code c3_march(const conica_bspline *g, double tol, double tol_eff,
                            size_t max_iter, conica__out *o, double **params,
                            size_t *np, size_t *cap, conica_plot_stats *stats, double *maxdev,
                            conica_status *st)
{
    c3m mm, *m = &mm;
    m->T = g->knots;
    m->d = g->ctrl;
    m->n = g->n;
    m->tol = tol;
    m->tol_eff = tol_eff;
    m->flops = 0;
    m->nc = 0;
    m->R = m->buf[0];
    m->Lt = m->buf[1];
    m->Rt = m->buf[2];
    m->Lb = m->buf[3];
    m->Rb = m->buf[4];
    double b = g->knots[g->n], pt[2], hs;
    m->bend = b;
    size_t splits = 0;
    conica_code rc = CONICA_OK;
    c3_enter(m, c3_next_span(m, 3), 0);
    hs = c3_step(m, Q_AIM * tol_eff, 0.0);
    for (;;) {
        double x = b, dev = 0.0, xf = m->ua, df = 0.0, step;
        int found = 0, last = 0;
        size_t j = 0;
        if (m->bb < b && m->ua + hs > m->bb + G_SNAP * hs) {
            rc = c3_cross(m, -1.0, hs, b, max_iter, stats, &found, &x, &dev, &j, &xf, &df, st);
            if (rc != CONICA_OK)
                break;
            if (!found && xf > m->ua) { /* shrink from the failed trial, D ~ h^2 */
                double f = sqrt(G_TARGET * tol / df);
                f = f < 0.1 ? 0.1 : (f > 0.8 ? 0.8 : f);
                hs = (xf - m->ua) * f;
            }
        }
        if (!found) {
            rc = c3_search(m, max_iter, &hs, stats, &x, &dev, st);
            if (rc != CONICA_OK)
                break;
        }
        step = x - m->ua;
        if (found) { /* a chord across the knot(s), ending in chain element j */
            last = c3_take_chain(m, g, j, x, b, pt, &splits);
        } else if (x < m->bb) { /* inside the interval: the right half goes on */
            memcpy(pt, m->Lb + 6, sizeof pt);
            swap_ptr(&m->R, &m->Rb);
            m->ua = x;
            m->inv = 1.0 / (m->bb - x);
            if (++splits >= G_RESET) { /* re-split from the Bézier form */
                casteljau(m->B, 3, 2, (x - m->ba) / (m->bb - m->ba), m->Lt, m->R);
                m->flops += 39;
                splits = 0;
            }
        } else if (m->bb >= b) { /* the end point of the piece exactly */
            memcpy(pt, g->ctrl + 2 * (g->n - 1), sizeof pt);
            last = 1;
        } else {
            double x2 = x, dev2 = dev;
            if (dev < G_CROSS * tol) { /* try a longer chord across the knot */
                rc = c3_cross(m, dev, 0.0, b, max_iter, stats, &found, &x2, &dev2, &j, &xf, &df,
                              st);
                if (rc != CONICA_OK)
                    break;
            }
            if (found) {
                step = x2 - m->ua;
                x = x2;
                dev = dev2;
                last = c3_take_chain(m, g, j, x, b, pt, &splits);
            } else { /* the knot itself, exactly as the interval's end */
                memcpy(pt, m->R + 6, sizeof pt);
                c3_enter(m, c3_next_span(m, m->mu + 1), 1);
                splits = 0;
            }
        }
        *maxdev = dev > *maxdev ? dev : *maxdev;
        rc = conica__out_push(o, pt, x, st);
        if (rc == CONICA_OK)
            rc = push_param(params, np, cap, x, st);
        if (rc != CONICA_OK || last)
            break;
        hs = c3_step(m, Q_AIM * tol_eff, step);
    }
    stats->flops += (double)m->flops;
    return rc;
}

/* K_s of the step model D(h) ~ K h^2 at the start ua of the remainder R
 * (parameter length L = bb - ua): the quadratic model of the curve there
 * deviates from the chord of [ua, ua + h] by about
 * |f' x f''| h^2 / (8 |f'| L^2), f' and f'' the derivatives in R's own
 * parameter at 0: X' = p dX_0, X'' = p (p - 1) d2X_0 of the homogeneous
 * polygon (X, W), f = X / W, f' = (X' - f W') / W,
 * f'' = (X'' - 2 f' W' - f W'') / W (for p = 3 and no weights this is the
 * estimate of G_EXTRAP). Only steers the next trial; 0 when degenerate. */
static double start_k(march *m)
{
    int p = m->p, d = m->d, h = m->h;
    const double *X = m->R;
    double L = m->bb - m->ua;
    if (p < 2 || !(L > 0))
        return 0.0;
    double c1 = (double)p, c2 = (double)p * (double)(p - 1);
    double w0 = 1.0, w1 = 0.0, w2 = 0.0;
    if (h > d) {
        w0 = X[d];
        w1 = c1 * (X[h + d] - X[d]);
        w2 = c2 * (X[2 * h + d] - 2.0 * X[h + d] + X[d]);
    }
    double f1[3], f2[3], aa = 0.0, bb = 0.0, ab = 0.0;
    for (int c = 0; c < d; c++) {
        double f0 = X[c] / w0;
        f1[c] = (c1 * (X[h + c] - X[c]) - f0 * w1) / w0;
        f2[c] = (c2 * (X[2 * h + c] - 2.0 * X[h + c] + X[c]) - 2.0 * f1[c] * w1 - f0 * w2) / w0;
        aa += f1[c] * f1[c];
        bb += f2[c] * f2[c];
        ab += f1[c] * f2[c];
    }
    m->flops += 20.0 + 16.0 * (double)d;
    double cr2 = aa * bb - ab * ab;
    if (!(aa > 0) || !(cr2 > 0))
        return 0.0;
    return sqrt(cr2 / aa) / (8.0 * L * L);
}

/* Step (parameter length) from the start of the remainder R of a planar
 * polynomial quadratic to the chord end where the deviation is T, within
 * the remainder's parabola f(s) = R0 + f' s + C s^2 (f' = 2 (R1 - R0),
 * C = R2 - 2 R1 + R0, s in [0, 1] over [ua, bb]): the chord [0, lam]
 * deviates from the arc by exactly |C x f'| lam^2 / (4 |f' + C lam|) (the
 * arc minus the chord is C u (u - lam), largest at lam / 2, seen across
 * the chord's direction f' + C lam), solved for lam by two Newton steps
 * from its small-step value sqrt(4 T |f'| / |C x f'|). Only
 * steers the next trial (the certificate decides); a straight remainder
 * gives twice its length (the whole rest is tried). */
static double q2_step(march *m, double T)
{
    const double *R = m->R;
    double fx = 2.0 * (R[2] - R[0]), fy = 2.0 * (R[3] - R[1]);
    double cx = R[4] - 2.0 * R[2] + R[0], cy = R[5] - 2.0 * R[3] + R[1];
    double k = fabs(cx * fy - cy * fx), L = m->bb - m->ua;
    double A = fx * fx + fy * fy, B = fx * cx + fy * cy, E = cx * cx + cy * cy;
    m->flops += 22.0;
    if (!(k > 0))
        return 2.0 * L;
    /* the small-step value, then two Newton steps on the squared equation
     * k^2 lam^4 = 16 T^2 (A + 2 B lam + E lam^2) */
    double lam = sqrt(4.0 * T * sqrt(A) / k), t2 = 16.0 * T * T;
    for (int it = 0; it < 2; it++) {
        double l2 = lam * lam;
        double phi = k * k * l2 * l2 - t2 * (A + lam * (2.0 * B + E * lam));
        double dphi = 4.0 * k * k * l2 * lam - t2 * (2.0 * B + 2.0 * E * lam);
        if (!(dphi > 0) || !(phi < 0.5 * dphi * lam))
            break;
        lam -= phi / dphi;
    }
    m->flops += 60.0;
    return lam * L;
}

/* general_march's trial for a planar rational quadratic (a conic arc):
 * the longest chord within T of the remainder's own conic, exactly
 * (plot_conic.c), from lam0, the previous chord in units of the
 * remainder (0: none); twice the remainder when all of it is within T. */
static double r2_trial(march *m, double T, double lam0)
{
    size_t ev = 0;
    double lam = conica__r2_step(m->R, T, lam0, &ev);
    m->flops += 12.0 + 22.0 * (double)ev;
    return lam * (m->bb - m->ua);
}

/* general_march's model_lam trial (planar polynomial, degree >= 4): the
 * step in parameter length from the remainder's start, lam0 in units of
 * the remainder as for model_lam. */
static double march_model_step(march *m, double tol_eff, double lam0, int last)
{
    size_t flops = 0;
    double lam = model_lam(m->R, m->p, m->aim * tol_eff, lam0, last, C3_ITER_STOP, &flops);
    m->flops += (double)flops;
    return lam * (m->bb - m->ua);
}

/* The march of conica__guaranteed_piece for any other spline (degree,
 * dimension, weights); the first point is already out. *maxdev gets the
 * largest certified bound. */

static conica_code general_march(const conica_bspline *g, double tol, double tol_eff,
                                 size_t max_iter, conica__out *o,
                                 double **params, size_t *np, size_t *cap,
                                 conica_plot_stats *stats, double *maxdev, conica_status *st)
{
    march *m = malloc(sizeof *m);
    if (!m)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    m->p = g->degree;
    m->d = g->dim;
    m->h = conica__hdim(g);
    m->T = g->knots;
    m->n = g->n;
    m->nk = g->n + (size_t)g->degree + 1;
    m->flops = 0;
    m->B = m->buf[0];
    m->C = NULL;
    m->cmu = NULL;
    m->ccap = 0;
    m->R = m->buf[1];
    m->Lt = m->buf[2];
    m->Rt = m->buf[3];
    m->Lb = m->buf[4];
    m->Rb = m->buf[5];
    m->H = malloc(g->n * (size_t)m->h * sizeof *m->H);
    if (!m->H) {
        free(m);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    conica__homog(g, 0, g->n, m->H);
    size_t p = (size_t)m->p, h = (size_t)m->h;
    double a = g->knots[p], b = g->knots[g->n], pt[3];
    m->ua = a;
    m->mua = p;
    m->tol = tol;
    m->tol_eff = tol_eff;
    int close = m->p <= G_CLOSE_MAX_P && m->p >= G_CLOSE_MIN_P;
    int q2 = m->p == 2 && m->d == 2 && m->h == 2; /* see q2_step */
    int r2 = m->p == 2 && m->d == 2 && m->h == 3; /* see r2_trial */
    /* planar polynomial degree >= 4: model_lam predicts, aiming at Q_AIM
     * (degrees up to G_CLOSE_MAX_P, see Q_AIM) or G_NEXT */
    int pm = m->p >= G_CLOSE_MIN_P && m->d == 2 && m->h == 2, pq = pm && close;
    m->aim = pq ? Q_AIM : G_NEXT;
    m->good = q2 || r2 || pq ? Q_GOOD : (close ? G_CLOSE_GOOD : G_GOOD);
    m->shrink_aim = q2 || r2 || pq ? Q_AIM : G_TARGET;
    m->shrink_max = q2 || r2 || pq ? Q_SHRINK : 0.8;
    m->next = close ? G_CLOSE_NEXT : G_NEXT;
    conica_code rc = CONICA_OK;
    double hs = b - a; /* first guess: the whole piece */
    size_t splits = 0;
    enter_interval(m, next_span(m, p), 0);
    double K0 = start_k(m); /* the first trial follows the curvature at a */
    if (K0 > 0 && sqrt(m->next * tol / K0) < hs)
        hs = sqrt(m->next * tol / K0);
    if (q2)
        hs = q2_step(m, Q_AIM * tol_eff);
    if (r2)
        hs = r2_trial(m, Q_AIM * tol_eff, 0.0);
    if (pm)
        hs = march_model_step(m, tol_eff, 0.0, m->bb >= b);
    for (;;) {
        double x = b, dev = 0.0;
        int halved = 0;
        rc = bez_search(m, &hs, b, max_iter, stats, &x, &dev, &halved, st);
        if (rc != CONICA_OK)
            goto done;
        double step = x - m->ua;
        int last = 0;
        if (x < m->bb) { /* inside the interval: the split's right half goes on */
            proj(m, m->Lb + p * h, pt);
            swap_ptr(&m->R, &m->Rb);
            m->ua = x;
            if (++splits >= G_RESET) { /* re-split from the Bézier form */
                split(m, m->B, (x - m->ba) / (m->bb - m->ba), m->Lt, m->R);
                splits = 0;
            }
        } else if (m->bb >= b) { /* the end point of the piece exactly */
            proj(m, m->H + (g->n - 1) * h, pt);
            last = 1;
        } else {
            int found = 0;
            size_t nc = 0, j = 0, bz = (p + 1) * h;
            double x2 = x, dev2 = dev;
            if (dev < G_CROSS * tol) { /* try a longer chord across the knot */
                /* the first trial: the remainder's cubic model continued
                 * past the knot (a C^(p-1) join) when planar polynomial */
                double hs0 = pm ? march_model_step(m, tol_eff, 1.0, 0) : 0.0;
                rc = cross_search(m, dev, hs0, b, max_iter, stats, &found, &x2, &dev2, &j, &nc,
                                  st);
                if (rc != CONICA_OK)
                    goto done;
            }
            if (found) { /* interval cmu[j] becomes current */
                step = x2 - m->ua;
                x = x2;
                dev = dev2;
                proj(m, m->Lb + p * h, pt);
                size_t muj = m->cmu[j];
                if (x < m->T[muj + 1]) {
                    enter_interval(m, muj, m->C + j * bz);
                    swap_ptr(&m->R, &m->Rb);
                    m->ua = x;
                    splits = 1;
                } else if (m->T[muj + 1] >= b) {
                    proj(m, m->H + (g->n - 1) * h, pt); /* the end point exactly */
                    last = 1;
                } else {
                    enter_interval(m, next_span(m, muj + 1), j < nc ? m->C + (j + 1) * bz : NULL);
                    splits = 0;
                }
            } else { /* the knot itself, exactly as the interval's end */
                proj(m, m->R + p * h, pt);
                enter_interval(m, next_span(m, m->mu + 1), nc ? m->C + bz : NULL);
                splits = 0;
            }
        }
        *maxdev = dev > *maxdev ? dev : *maxdev;
        rc = conica__out_push(o, pt, x, st);
        if (rc == CONICA_OK)
            rc = push_param(params, np, cap, x, st);
        if (rc != CONICA_OK || last)
            break;
        if (halved && x < b) { /* the second half of the rest */
            hs = b - x;
            continue;
        }
        /* predict, see G_EXTRAP and start_k (a polynomial parabola has one
         * K per interval: the chord-only rule is exact there) */
        int use_k = m->ua == x && dev > 0 && (m->p > 2 || m->h > m->d);
        if (pm) {
            hs = march_model_step(m, tol_eff, m->ua == x ? step / (m->bb - m->ua) : 0.0,
                                  m->bb >= b);
        } else {
            hs = q2   ? q2_step(m, Q_AIM * tol_eff)
                 : r2 ? r2_trial(m, Q_AIM * tol_eff, m->ua == x ? step / (m->bb - m->ua) : 0.0)
                      : next_step(use_k, use_k ? start_k(m) : 0.0, dev, step, tol, m->next);
        }
    }
done:
    stats->flops += m->flops;
    free(m->H);
    free(m->C);
    free(m->cmu);
    free(m);
    return rc;
}

/* conica__guaranteed_piece with the one setting the march reads, the
 * trial limit. */
static conica_code guaranteed_piece(const conica_bspline *g, double tol, size_t max_iter,
                                    int first_is_join, conica__out *o, double **params,
                                    size_t *np, conica_plot_stats *stats, conica_status *st)
{
    double ek[8], ec[8];
    conica_bspline e;
    if (g->degree == 2 && g->dim == 2 && !g->w && g->n == 3) {
        /* One planar polynomial quadratic Bézier piece (SVG's Q, TrueType
         * outlines) raised to degree 3: the same curve and parametrisation,
         * so c3_march takes it (no allocation; its cubic model is exact
         * for a parabola). The raised inner points are one rounding of a
         * convex combination away from exact, far inside the margin of
         * degree 3 below (G_ULPS); the end points are the input's. */
        const double *q = g->ctrl;
        for (int i = 0; i < 4; i++) {
            ek[i] = g->knots[0];
            ek[4 + i] = g->knots[3];
        }
        for (int c = 0; c < 2; c++) {
            ec[c] = q[c];
            ec[2 + c] = q[c] + (2.0 / 3.0) * (q[2 + c] - q[c]);
            ec[4 + c] = q[4 + c] + (2.0 / 3.0) * (q[2 + c] - q[4 + c]);
            ec[6 + c] = q[4 + c];
        }
        e.degree = 3;
        e.dim = 2;
        e.n = 4;
        e.knots = ek;
        e.ctrl = ec;
        e.w = NULL;
        g = &e;
    }
    size_t p = (size_t)g->degree, d = (size_t)g->dim;
    double a = g->knots[p];
    /* rounding margin from the magnitude of the coordinates */
    double scale = 0.0;
    for (size_t i = 0; i < g->n * d; i++)
        scale = fabs(g->ctrl[i]) > scale ? fabs(g->ctrl[i]) : scale;
    double margin = G_ULPS * (g->w ? 2.0 : 1.0) * (double)(p + 2) * DBL_EPSILON * scale;
    double tol_eff = tol - margin, maxdev = 0.0, pt[3];
    conica_code rc = CONICA_OK;
    size_t cap = 0;
    if (params)
        *np = 0;
    if (!(tol_eff > 0.5 * tol))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "tolerance %.3g is below the floating-point resolution of "
                            "coordinates of magnitude %.3g",
                            tol, scale);
    if (!first_is_join) {
        memcpy(pt, g->ctrl, d * sizeof *pt);
        rc = conica__out_push(o, pt, a, st);
    }
    if (rc == CONICA_OK)
        rc = push_param(params, np, &cap, a, st);
    if (rc != CONICA_OK)
        return rc;
    if (p == 3 && d == 2 && !g->w)
        rc = c3_march(g, tol, tol_eff, max_iter, o, params, np, &cap, stats, &maxdev, st);
    else
        rc = general_march(g, tol, tol_eff, max_iter, o, params, np, &cap, stats, &maxdev, st);
    if (rc == CONICA_OK && maxdev + margin > stats->bound)
        stats->bound = maxdev + margin;
    return rc;
}

conica_code conica__guaranteed_piece(const conica_bspline *g, double tol,
                                     const conica_plot_settings *set, int first_is_join,
                                     conica__out *o, double **params, size_t *np,
                                     conica_plot_stats *stats, conica_status *st)
{
    return guaranteed_piece(g, tol, set->max_iterations, first_is_join, o, params, np, stats,
                            st);
}

conica_code conica__plot_guaranteed(const conica__pieces *pc, const conica_plot_settings *set,
                                    double tol, conica__out *o, conica_plot_stats *stats,
                                    conica_status *st)
{
    for (size_t k = 0; k < pc->count; k++) {
        conica_code rc = CONICA_OK;
        if (!pc->joined[k])
            rc = conica__out_piece(o, st);
        if (rc == CONICA_OK)
            rc = conica__guaranteed_piece(&pc->sp[k], tol, set, pc->joined[k], o, NULL, NULL,
                                          stats, st);
        if (rc != CONICA_OK)
            return rc;
    }
    return CONICA_OK;
}

conica_code conica_plot_bezier(int degree, const double *ctrl, const double *w, double tol,
                               size_t max_iterations, double *xy, double *t, size_t cap,
                               size_t *n, conica_status *st)
{
    /* the spline conica_bspline_from_bezier makes, on the stack */
    double knots[2 * (MAXP + 1)], c[2 * (MAXP + 1)], wc[MAXP + 1];
    if (!ctrl || !xy || !n)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL argument");
    if (degree < 1 || degree > MAXP)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "degree %d outside 1..%d", degree, MAXP);
    if (!(tol > 0) || !isfinite(tol))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "tolerance must be > 0 and finite");
    if (cap < 2)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "room for %zu points, 2 at least needed",
                            cap);
    size_t np = (size_t)degree + 1;
    double scale = 0.0;
    for (size_t i = 0; i < np; i++) {
        knots[i] = 0.0;
        knots[np + i] = 1.0;
        c[2 * i] = ctrl[2 * i];
        c[2 * i + 1] = ctrl[2 * i + 1];
        if (!isfinite(c[2 * i]) || !isfinite(c[2 * i + 1]))
            return conica__fail(st, CONICA_ERR_ARG, 0, i, "control point %zu is not finite", i);
        scale = fabs(c[2 * i]) > scale ? fabs(c[2 * i]) : scale;
        scale = fabs(c[2 * i + 1]) > scale ? fabs(c[2 * i + 1]) : scale;
        if (w) {
            wc[i] = w[i];
            if (!(wc[i] > 0) || !isfinite(wc[i]))
                return conica__fail(st, CONICA_ERR_ARG, 0, i,
                                    "weight %zu must be > 0 and finite", i);
        }
    }
    conica_bspline g = {degree, 2, np, knots, c, w ? wc : NULL};
    /* the march reads no other setting: conica_plot_defaults(), filling
     * every field, was 1% of a cubic piece's instructions */
    size_t max_iter = max_iterations ? max_iterations : CONICA_PLOT_MAX_ITERATIONS_DEFAULT;
    conica_plot_stats stats;
    memset(&stats, 0, sizeof stats);
    conica__out o;
    conica__out_init(&o, 2, cap);
    o.fixed = 1;
    o.pl.xy = xy;
    o.pl.t = t;
    o.pl.cap = cap;
    conica_code rc = guaranteed_piece(&g, tol, max_iter, 0, &o, NULL, NULL, &stats, st);
    if (rc != CONICA_OK)
        return rc;
    /* As conica_plot: never a NaN or Inf as a result. A polynomial piece of
     * degree <= 3 with coordinates below CONICA__FINITE_SCALE cannot give
     * one: its points are de Casteljau's convex combinations a + t (b - a),
     * t in [0, 1], of finite points (|b - a| <= 2 scale, no overflow). */
    int sure = !w && degree <= 3 && scale < CONICA__FINITE_SCALE;
    for (size_t i = 0; !sure && i < 2 * o.pl.n; i++)
        if (!isfinite(xy[i]))
            return conica__fail(st, CONICA_ERR_NUMERIC, 0, i / 2,
                                "point %zu of the plot is not finite: the piece cannot be "
                                "evaluated in double there",
                                i / 2);
    *n = o.pl.n;
    conica__ok(st);
    return CONICA_OK;
}

/* SPDX-License-Identifier: MIT */
/* One-sided fits of drawn subpaths (path_fit.h): polygons that keep to one
 * side of the drawn curve by construction.
 *
 * A curve that turns one way lies on one side of each of its chords (the
 * side its centre of curvature is on) and on the other side of each of its
 * tangent lines. So on every stretch between inflections the polygon of
 * chords lies on the concave side and the polygon of tangent lines on the
 * convex side; which of the two keeps the polygon inside (or outside) the
 * painted region depends on which side of the curve is painted there,
 * which the caller says. A tangent polygon between the tangents at u and v
 * is the two legs of the triangle P(u) X P(v), X where they meet; the arc
 * lies in that triangle (it turns less than a half turn), so the legs are
 * within dist(X, arc) of it and it within the same of them. Chords are
 * within their largest distance from the arc both ways. Each stretch is
 * cut greedily: the longest piece whose error is within the tolerance
 * (bisection on its end), which is the fewest pieces when the error grows
 * with the piece (Dahl 2019, §3.4 takes the same greedy view of
 * flattening).
 *
 * Calls only libcore's path storage (path.h) and the status helpers. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "path_fit.h"

/* Samples of the distance along a piece (then a golden-section search
 * round the best); bisection steps for the end of a piece. */
#define FIT_SAMPLES 32
#define FIT_GOLDEN 24
#define FIT_BISECT 48
/* A piece turns by at most this (radians): tangent lines of a piece that
 * turns near a half turn meet far away. */
#define FIT_MAX_TURN 1.2
/* Control points within this fraction of the chord's length of it: the
 * segment is straight. */
#define FIT_STRAIGHT_REL 1e-12
/* Tangents closer to parallel than this (radians): the piece is straight to
 * rounding; its chord is exact. */
#define FIT_PARALLEL 1e-10
/* CONICA__FIT_CHORDS through conica__path_fit() (a dense reference):
 * each piece is the longest within the tolerance to this fraction of its
 * length, not to the bisection's last step. */
#define FIT_COARSE_REL (1.0 / 64)
/* The painted side is sampled at this many points of each stretch, for
 * where another subpath crosses it. */
#define FIT_SIDE_SAMPLES 8

/* A segment's curve in homogeneous form: position and first two
 * derivatives at t. */
typedef struct seg_eval {
    int d;
    double h[CONICA_PATH_MAX_DEGREE + 1][3]; /* (w x, w y, w) */
} seg_eval;

static void seg_load(const conica_path *p, size_t s, seg_eval *e)
{
    const conica_path_seg *g = &p->seg[s];
    const double *q = p->pt + 3 * g->first;
    e->d = g->degree;
    for (int i = 0; i <= e->d; i++) {
        e->h[i][0] = q[3 * i] * q[3 * i + 2];
        e->h[i][1] = q[3 * i + 1] * q[3 * i + 2];
        e->h[i][2] = q[3 * i + 2];
    }
}

/* P(t), P'(t), P''(t) of the rational curve (any may be NULL). */
static void seg_at(const seg_eval *e, double t, double P[2], double D1[2], double D2[2])
{
    double r[CONICA_PATH_MAX_DEGREE + 1][3], A[3], A1[3], A2[3] = {0, 0, 0}, u = 1 - t;
    int d = e->d, m = d, k, i, c;
    memcpy(r, e->h, sizeof r);
    /* de Casteljau down to three points (or two for a line) */
    for (k = 0; k < d - 2; k++, m--)
        for (i = 0; i < m; i++)
            for (c = 0; c < 3; c++)
                r[i][c] = u * r[i][c] + t * r[i + 1][c];
    if (d >= 2) {
        for (c = 0; c < 3; c++)
            A2[c] = (double)d * (d - 1) * (r[0][c] - 2 * r[1][c] + r[2][c]);
        for (i = 0; i < 2; i++)
            for (c = 0; c < 3; c++)
                r[i][c] = u * r[i][c] + t * r[i + 1][c];
    }
    for (c = 0; c < 3; c++) {
        A1[c] = (double)d * (r[1][c] - r[0][c]);
        A[c] = u * r[0][c] + t * r[1][c];
    }
    {
        double W = A[2], p0 = A[0] / W, p1 = A[1] / W;
        double q0 = (A1[0] - p0 * A1[2]) / W, q1 = (A1[1] - p1 * A1[2]) / W;
        if (P) {
            P[0] = p0;
            P[1] = p1;
        }
        if (D1) {
            D1[0] = q0;
            D1[1] = q1;
        }
        if (D2) {
            D2[0] = (A2[0] - 2 * q0 * A1[2] - p0 * A2[2]) / W;
            D2[1] = (A2[1] - 2 * q1 * A1[2] - p1 * A2[2]) / W;
        }
    }
}

static double cross(const double a[2], const double b[2])
{
    return a[0] * b[1] - a[1] * b[0];
}

/* Sign of the turning at t (0 where it vanishes to rounding). */
static int turn_sign(const seg_eval *e, double t)
{
    double d1[2], d2[2], k, s;
    seg_at(e, t, NULL, d1, d2);
    k = cross(d1, d2);
    s = hypot(d1[0], d1[1]) * hypot(d2[0], d2[1]);
    if (!(fabs(k) > 1e-12 * s))
        return 0;
    return k > 0 ? 1 : -1;
}

/* Unit tangent at t; at a stationary point the second derivative's
 * direction (the limit from after t when dir > 0, before when < 0). */
static void tangent(const seg_eval *e, double t, int dir, double out[2])
{
    double d1[2], d2[2], h;
    seg_at(e, t, NULL, d1, d2);
    h = hypot(d1[0], d1[1]);
    if (!(h > 1e-12 * hypot(d2[0], d2[1]))) {
        d1[0] = dir * d2[0];
        d1[1] = dir * d2[1];
        h = hypot(d1[0], d1[1]);
    }
    if (!(h > 0)) {
        out[0] = 1;
        out[1] = 0;
        return;
    }
    out[0] = d1[0] / h;
    out[1] = d1[1] / h;
}

static int seg_is_straight(const conica_path *p, size_t s)
{
    const conica_path_seg *g = &p->seg[s];
    const double *q = p->pt + 3 * g->first;
    int d = g->degree;
    double ex = q[3 * d] - q[0], ey = q[3 * d + 1] - q[1], l = hypot(ex, ey);
    if (d == 1)
        return 1;
    if (!(l > 0))
        return 0;
    for (int i = 1; i < d; i++) {
        double px = q[3 * i] - q[0], py = q[3 * i + 1] - q[1];
        double along = (px * ex + py * ey) / l, off = fabs(px * ey - py * ex) / l;
        if (off > FIT_STRAIGHT_REL * l || along < 0 || along > l)
            return 0;
    }
    return 1;
}

/* Largest of f over [u, v]: samples, then golden section round the best. */
typedef double (*piece_fn)(const seg_eval *e, double t, const void *arg);

static double piece_max(const seg_eval *e, double u, double v, piece_fn f, const void *arg)
{
    double best = -INFINITY, tb = u;
    for (int i = 0; i <= FIT_SAMPLES; i++) {
        double t = u + (v - u) * i / FIT_SAMPLES, y = f(e, t, arg);
        if (y > best) {
            best = y;
            tb = t;
        }
    }
    {
        double h = (v - u) / FIT_SAMPLES, a = fmax(u, tb - h), b = fmin(v, tb + h);
        const double g = 0.6180339887498949;
        double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = f(e, x1, arg), f2 = f(e, x2, arg);
        for (int k = 0; k < FIT_GOLDEN; k++) {
            if (f1 > f2) {
                b = x2;
                x2 = x1;
                f2 = f1;
                x1 = b - g * (b - a);
                f1 = f(e, x1, arg);
            } else {
                a = x1;
                x1 = x2;
                f1 = f2;
                x2 = a + g * (b - a);
                f2 = f(e, x2, arg);
            }
        }
        best = fmax(best, fmax(f1, f2));
    }
    return best;
}

/* |distance| of P(t) from the line through a with unit normal n */
typedef struct line_arg {
    double a[2], n[2];
} line_arg;

static double off_line(const seg_eval *e, double t, const void *arg)
{
    const line_arg *L = arg;
    double P[2];
    seg_at(e, t, P, NULL, NULL);
    return fabs((P[0] - L->a[0]) * L->n[0] + (P[1] - L->a[1]) * L->n[1]);
}

/* minus the distance of P(t) from x: piece_max gives minus the nearest */
static double near_pt(const seg_eval *e, double t, const void *arg)
{
    const double *x = arg;
    double P[2];
    seg_at(e, t, P, NULL, NULL);
    return -hypot(P[0] - x[0], P[1] - x[1]);
}

/* Where the tangent lines at u and v meet (0: they are parallel). */
static int tangent_meet(const seg_eval *e, double u, double v, double X[2])
{
    double Pu[2], Pv[2], tu[2], tv[2], den, s;
    seg_at(e, u, Pu, NULL, NULL);
    seg_at(e, v, Pv, NULL, NULL);
    tangent(e, u, 1, tu);
    tangent(e, v, -1, tv);
    den = cross(tu, tv);
    if (fabs(den) < FIT_PARALLEL)
        return 0;
    s = ((Pv[0] - Pu[0]) * tv[1] - (Pv[1] - Pu[1]) * tv[0]) / den;
    X[0] = fma(s, tu[0], Pu[0]);
    X[1] = fma(s, tu[1], Pu[1]);
    return 1;
}

/* Error of the piece [u, v] as a chord (tangents 0) or as two tangent legs
 * (tangents 1); INFINITY where it turns too far. */
static double piece_error(const seg_eval *e, double u, double v, int tangents, double max_turn)
{
    double tu[2], tv[2], Pu[2], Pv[2];
    tangent(e, u, 1, tu);
    tangent(e, v, -1, tv);
    if (fabs(atan2(cross(tu, tv), tu[0] * tv[0] + tu[1] * tv[1])) > max_turn)
        return INFINITY;
    seg_at(e, u, Pu, NULL, NULL);
    seg_at(e, v, Pv, NULL, NULL);
    if (tangents) {
        double X[2];
        if (!tangent_meet(e, u, v, X))
            tangents = 0; /* straight to rounding: the chord */
        else
            return -piece_max(e, u, v, near_pt, X);
    }
    {
        line_arg L;
        double dx = Pv[0] - Pu[0], dy = Pv[1] - Pu[1], l = hypot(dx, dy);
        if (!(l > 0))
            return 0;
        L.a[0] = Pu[0];
        L.a[1] = Pu[1];
        L.n[0] = -dy / l;
        L.n[1] = dx / l;
        return piece_max(e, u, v, off_line, &L);
    }
}

typedef struct out_buf {
    double **xy;
    size_t *n, *cap, max;
    conica_status *st;
} out_buf;

static conica_code put(out_buf *o, double x, double y)
{
    if (*o->n >= o->max)
        return conica__fail(o->st, CONICA_ERR_LIMIT, 0, 0,
                            "the polygon would need more than %zu points", o->max);
    if (*o->n >= *o->cap) {
        size_t nc = *o->cap ? 2 * *o->cap : 64;
        double *nx = realloc(*o->xy, 2 * nc * sizeof *nx);
        if (!nx)
            return conica__fail(o->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        *o->xy = nx;
        *o->cap = nc;
    }
    (*o->xy)[2 * *o->n] = x;
    (*o->xy)[2 * *o->n + 1] = y;
    (*o->n)++;
    return CONICA_OK;
}

/* The vertices of stretch [a, b] after P(a) (which is out already), up to
 * and with P(b) unless b is the segment's end. */
static conica_code stretch(const seg_eval *e, double a, double b, int tangents, double tol,
                           double max_turn, int coarse, out_buf *o)
{
    double u = a;
    conica_code rc = CONICA_OK;
    while (u < b && rc == CONICA_OK) {
        double v = b;
        if (!(piece_error(e, u, b, tangents, max_turn) <= tol)) {
            double lo = u, hi = b;
            for (int k = 0; k < FIT_BISECT; k++) {
                double mid = 0.5 * (lo + hi);
                if (piece_error(e, u, mid, tangents, max_turn) <= tol)
                    lo = mid;
                else
                    hi = mid;
                if (coarse && hi - lo <= FIT_COARSE_REL * (lo - u))
                    break; /* within tol is all a reference needs */
            }
            v = lo > u ? lo : hi; /* no progress: a piece too small to matter */
        }
        if (tangents) {
            double X[2];
            if (tangent_meet(e, u, v, X))
                rc = put(o, X[0], X[1]);
        }
        if (rc == CONICA_OK && v < 1.0) {
            double P[2];
            if (v < b && tangents) {
                u = v;
                continue; /* the next leg starts on the same tangent */
            }
            seg_at(e, v, P, NULL, NULL);
            rc = put(o, P[0], P[1]);
        }
        u = v;
    }
    return rc;
}

/* Painted side of stretch [a, b]: the caller's answer at its middle. */
static int stretch_side(const seg_eval *e, double a, double b, conica__painted_fn painted,
                        void *ctx)
{
    double P[2], t[2], m = 0.5 * (a + b);
    if (!painted)
        return 0;
    seg_at(e, m, P, NULL, NULL);
    tangent(e, m, 1, t);
    return painted(ctx, P, t);
}

/* Where the painted side changes within [a, b] (another subpath of the
 * region crosses the curve there, as two overlapping contours filled
 * even-odd do): the side sampled at FIT_SIDE_SAMPLES points, each change
 * between two samples found by bisection. At most cap parameters,
 * ascending, into out; their number. A change missed between two samples
 * (two crossings close together) leaves a stretch on the wrong side, which
 * the caller's check against the drawn region finds. */
static size_t side_changes(const seg_eval *e, double a, double b, conica__painted_fn painted,
                           void *ctx, double *out, size_t cap)
{
    size_t n = 0;
    double tp = a;
    int sp = 0;
    if (!painted)
        return 0;
    for (int i = 0; i <= FIT_SIDE_SAMPLES; i++) {
        double t = a + (b - a) * (i + 0.5) / (FIT_SIDE_SAMPLES + 1), P[2], d[2];
        seg_at(e, t, P, NULL, NULL);
        tangent(e, t, 1, d);
        int si = painted(ctx, P, d);
        if (i > 0 && si != sp && n < cap) {
            double lo = tp, hi = t;
            for (int k = 0; k < FIT_BISECT; k++) {
                double mid = 0.5 * (lo + hi);
                seg_at(e, mid, P, NULL, NULL);
                tangent(e, mid, 1, d);
                if (painted(ctx, P, d) == sp)
                    lo = mid;
                else
                    hi = mid;
            }
            out[n++] = 0.5 * (lo + hi);
        }
        tp = t;
        sp = si;
    }
    return n;
}

/* Strokes: a point this far along each curved segment's end tangents, so
 * that the caps and the joins at corners of the polyline's stroke are
 * square to the exact tangents as the curve's own are: where the tangent
 * line leaves the curve by tol (sqrt(2 tol / curvature)), at most this
 * fraction of the segment's chord. */
#define FIT_END_TANGENT_CHORD 0.01

/* How far along the tangent at end `end` (0 or 1) the stroke's extra point
 * goes. */
static double end_reach(const seg_eval *e, int end, double tol, double chord)
{
    double d1[2], d2[2], v, k, r = FIT_END_TANGENT_CHORD * chord;
    seg_at(e, (double)end, NULL, d1, d2);
    v = hypot(d1[0], d1[1]);
    k = v > 0 ? fabs(cross(d1, d2)) / (v * v * v) : 0;
    return k > 0 ? fmin(r, sqrt(2 * tol / k)) : r;
}

/* After the vertices of a curved segment from q (at index i0) on, a point
 * along each end tangent, each at most half way to its neighbour so the
 * polyline never turns back. */
static conica_code add_end_tangents(const seg_eval *e, double tol, double chord, const double *q,
                                    const double *qe, size_t i0, out_buf *o)
{
    double t0[2], t1[2], *xy, nx[2], e0, e1;
    conica_code rc;
    tangent(e, 0.0, 1, t0);
    tangent(e, 1.0, -1, t1);
    /* the start's: before the first inner vertex (or the end) */
    xy = *o->xy;
    nx[0] = *o->n > i0 + 1 ? xy[2 * (i0 + 1)] : qe[0];
    nx[1] = *o->n > i0 + 1 ? xy[2 * (i0 + 1) + 1] : qe[1];
    e0 = fmin(end_reach(e, 0, tol, chord), 0.5 * hypot(nx[0] - q[0], nx[1] - q[1]));
    if (e0 > 0) {
        rc = put(o, 0, 0); /* room; then shift the inner vertices up one */
        if (rc != CONICA_OK)
            return rc;
        xy = *o->xy;
        memmove(xy + 2 * (i0 + 2), xy + 2 * (i0 + 1), 2 * (*o->n - i0 - 2) * sizeof *xy);
        xy[2 * (i0 + 1)] = fma(e0, t0[0], q[0]);
        xy[2 * (i0 + 1) + 1] = fma(e0, t0[1], q[1]);
    }
    xy = *o->xy;
    e1 = fmin(end_reach(e, 1, tol, chord),
              0.5 * hypot(qe[0] - xy[2 * (*o->n - 1)], qe[1] - xy[2 * (*o->n - 1) + 1]));
    if (e1 > 0)
        return put(o, fma(-e1, t1[0], qe[0]), fma(-e1, t1[1], qe[1]));
    return CONICA_OK;
}

static conica_code walk(const conica_path *p, size_t sub, double tol, conica__fit_side side,
                        conica__painted_fn painted, void *ctx, out_buf *o, int tangent_ends,
                        double max_turn)
{
    const conica_path_subpath *sp;
    conica_code rc = CONICA_OK;
    if (!p || sub >= p->nsub || !(tol > 0) || !isfinite(tol))
        return conica__fail(o->st, CONICA_ERR_ARG, 0, 0, "conica__path_fit: bad argument");
    sp = &p->sub[sub];
    if (sp->kind != CONICA_PATH_DRAWN)
        return conica__fail(o->st, CONICA_ERR_ARG, 0, 0, "conica__path_fit: not a drawn subpath");
    if (sp->n == 0)
        return put(o, sp->x0, sp->y0);
    for (size_t j = 0; j < sp->n && rc == CONICA_OK; j++) {
        size_t s = sp->first + j;
        const double *q = p->pt + 3 * p->seg[s].first;
        seg_eval e;
        double cut[8];
        size_t nc;
        rc = put(o, q[0], q[1]); /* the segment's start, exactly as drawn */
        if (rc != CONICA_OK || seg_is_straight(p, s))
            continue;
        seg_load(p, s, &e);
        nc = conica__path_seg_inflections(p, s, cut, 6);
        const double *qe = q + 3 * p->seg[s].degree;
        double chord = hypot(qe[0] - q[0], qe[1] - q[1]);
        size_t i0 = *o->n - 1; /* where the segment's start went */
        for (size_t k = 0; k <= nc && rc == CONICA_OK; k++) {
            double a = k ? cut[k - 1] : 0.0, b = k < nc ? cut[k] : 1.0;
            double sc[FIT_SIDE_SAMPLES + 2];
            size_t ns = 0;
            if (side != CONICA__FIT_CHORDS)
                ns = side_changes(&e, a, b, painted, ctx, sc, FIT_SIDE_SAMPLES);
            sc[ns] = b;
            /* each piece between changes of the painted side on its own */
            for (size_t h = 0; h <= ns && rc == CONICA_OK; h++) {
                double pa = h ? sc[h - 1] : a, pb = sc[h];
                int tangents = 0;
                if (side != CONICA__FIT_CHORDS) {
                    int ps = stretch_side(&e, pa, pb, painted, ctx);
                    int ts = turn_sign(&e, 0.5 * (pa + pb));
                    /* the painted region is convex here when the curve
                     * turns towards the painted side; chords then lie
                     * inside it */
                    int convex = ps != 0 && ts == ps;
                    tangents = ps != 0 && ts != 0 &&
                               ((side == CONICA__FIT_IN && !convex) ||
                                (side == CONICA__FIT_OUT && convex));
                }
                rc = stretch(&e, pa, pb, tangents, tol, fmin(max_turn, FIT_MAX_TURN),
                             side == CONICA__FIT_CHORDS && !tangent_ends, o);
            }
        }
        if (rc == CONICA_OK && tangent_ends)
            rc = add_end_tangents(&e, tol, chord, q, qe, i0, o);
    }
    if (rc == CONICA_OK && !sp->closed) { /* its end; a fill closes it straight */
        const conica_path_seg *z = &p->seg[sp->first + sp->n - 1];
        const double *e = p->pt + 3 * (z->first + (size_t)z->degree);
        rc = put(o, e[0], e[1]);
    }
    return rc;
}

/* walk() into the caller's buffer; on failure the buffer keeps its points. */
static conica_code run(const conica_path *p, size_t sub, double tol, conica__fit_side side,
                       conica__painted_fn painted, void *ctx, int tangent_ends, double max_turn,
                       size_t max_points, double **xy, size_t *n, size_t *cap, conica_status *st)
{
    out_buf o;
    size_t n0 = *n;
    conica_code rc;
    o.xy = xy;
    o.n = n;
    o.cap = cap;
    o.max = max_points;
    o.st = st;
    rc = walk(p, sub, tol, side, painted, ctx, &o, tangent_ends, max_turn);
    if (rc != CONICA_OK)
        *n = n0;
    else
        conica__ok(st);
    return rc;
}

conica_code conica__path_fit(const conica_path *p, size_t sub, double tol, conica__fit_side side,
                             conica__painted_fn painted, void *ctx, size_t max_points,
                             double **xy, size_t *n, size_t *cap, conica_status *st)
{
    return run(p, sub, tol, side, painted, ctx, 0, FIT_MAX_TURN, max_points, xy, n, cap, st);
}

conica_code conica__path_chords(const conica_path *p, size_t sub, double tol, double max_turn,
                                size_t max_points, double **xy, size_t *n, size_t *cap,
                                conica_status *st)
{
    return run(p, sub, tol, CONICA__FIT_CHORDS, NULL, NULL, 1,
               max_turn > 0 ? fmin(max_turn, FIT_MAX_TURN) : FIT_MAX_TURN, max_points, xy, n, cap,
               st);
}

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

/* How the pieces of a stretch are cut: tangent legs or chords, within tol,
 * turning at most max_turn; where `painted` is set, the polygon's edge
 * must also lie on the side `want` (1 painted, 0 not): a feature thinner
 * than the tolerance has another edge of the outline within reach, and an
 * edge moved by the full tolerance would cross it. */
typedef struct piece_rule {
    int tangents;
    double tol, max_turn;
    conica__painted_fn painted;
    void *ctx;
    int want;
} piece_rule;

/* Points of the polygon's edge for [u, v] nearer the curve than this
 * fraction of the tolerance are not tested for their side: the caller's
 * region is only that exact, and they cannot cross an edge by more. */
#define FIT_SIDE_MARGIN (1.0 / 64.0)
/* Points tested on each leg (a chord: twice as many, less one). */
#define FIT_SIDE_POINTS 2

/* Does the polygon's edge for [u, v] (chord, or legs through X) keep to
 * r->want? Points along it are tested. */
static int piece_sided(const seg_eval *e, double u, double v, const piece_rule *r)
{
    double Pu[2], Pv[2], X[2], Y[2 * FIT_SIDE_POINTS][2];
    int n = 0;
    seg_at(e, u, Pu, NULL, NULL);
    seg_at(e, v, Pv, NULL, NULL);
    if (r->tangents && tangent_meet(e, u, v, X)) {
        for (int k = 1; k <= FIT_SIDE_POINTS; k++, n += 2) {
            double f = (double)k / FIT_SIDE_POINTS;
            Y[n][0] = Pu[0] + f * (X[0] - Pu[0]);
            Y[n][1] = Pu[1] + f * (X[1] - Pu[1]);
            Y[n + 1][0] = Pv[0] + f * (X[0] - Pv[0]);
            Y[n + 1][1] = Pv[1] + f * (X[1] - Pv[1]);
        }
    } else {
        for (n = 0; n < 2 * FIT_SIDE_POINTS - 1; n++) {
            double f = (n + 1.0) / (2 * FIT_SIDE_POINTS);
            Y[n][0] = Pu[0] + f * (Pv[0] - Pu[0]);
            Y[n][1] = Pu[1] + f * (Pv[1] - Pu[1]);
        }
    }
    for (int k = 0; k < n; k++)
        if ((r->painted(r->ctx, Y[k], NULL) != 0) != r->want &&
            -piece_max(e, u, v, near_pt, Y[k]) > FIT_SIDE_MARGIN * r->tol)
            return 0;
    return 1;
}

/* Is [u, v] one piece within tol: its error, its side (sided: when the
 * rule has one), and where the piece ends at a tip (leg0: at u, leg1: at
 * v) the tangent leg ending there within tol of it too (at a tip the next
 * edge runs back along that leg, the two cancel in the fill, and the
 * polygon must still reach within tol of the tip). */
static int piece_ok(const seg_eval *e, double u, double v, const piece_rule *r, int leg0,
                    int leg1, int sided)
{
    double X[2], P[2];
    if (!(piece_error(e, u, v, r->tangents, r->max_turn) <= r->tol))
        return 0;
    if (r->tangents && (leg0 || leg1) && tangent_meet(e, u, v, X)) {
        if (leg0) {
            seg_at(e, u, P, NULL, NULL);
            if (!(hypot(X[0] - P[0], X[1] - P[1]) <= r->tol))
                return 0;
        }
        if (leg1) {
            seg_at(e, v, P, NULL, NULL);
            if (!(hypot(X[0] - P[0], X[1] - P[1]) <= r->tol))
                return 0;
        }
    }
    return !sided || !r->painted || piece_sided(e, u, v, r);
}

/* The longest [u, v], v in (u, hi], that piece_ok() takes, by bisection
 * (hi itself when no shorter one is taken: a piece too small to matter). */
static double bisect_end(const seg_eval *e, double u, double hi, const piece_rule *r, int l0,
                         int sided)
{
    double lo = u;
    for (int k = 0; k < FIT_BISECT; k++) {
        double mid = 0.5 * (lo + hi);
        if (piece_ok(e, u, mid, r, l0, 0, sided))
            lo = mid;
        else
            hi = mid;
    }
    return lo > u ? lo : hi;
}

/* The longest piece from u towards `end` that piece_ok() takes: by its
 * error first, then (rarely needed, and costlier) by its side. */
static double piece_end(const seg_eval *e, double u, double end, const piece_rule *r, int l0,
                        int l1)
{
    double v = end;
    if (!piece_ok(e, u, end, r, l0, l1, 0))
        v = bisect_end(e, u, end, r, l0, 0);
    if (r->painted && v > u && !piece_sided(e, u, v, r))
        v = bisect_end(e, u, v, r, l0, 1);
    return v;
}

/* The vertices of stretch [a, b] after P(a) (which is out already), up to
 * and with P(b) unless b is the segment's end. tip0 / tip1: the segment's
 * start / end is a tip (the polygon turns back there). */
static conica_code stretch(const seg_eval *e, double a, double b, const piece_rule *r, int tip0,
                           int tip1, out_buf *o)
{
    double u = a, end = b;
    int leg0 = tip0 && a == 0.0, leg1 = tip1 && b == 1.0 && r->tangents;
    conica_code rc = CONICA_OK;
    if (leg1 && !piece_ok(e, a, b, r, leg0, 1, 0)) {
        /* the last piece first: the longest [t, b] whose leg reaches the tip */
        double lo = a, hi = b;
        for (int k = 0; k < FIT_BISECT; k++) {
            double mid = 0.5 * (lo + hi);
            if (piece_ok(e, mid, b, r, 0, 1, 0))
                hi = mid;
            else
                lo = mid;
        }
        end = hi;
    }
    while (u < b && rc == CONICA_OK) {
        double v = piece_end(e, u, end, r, leg0 && u == a, leg1 && end == b);
        if (r->tangents) {
            double X[2];
            if (tangent_meet(e, u, v, X))
                rc = put(o, X[0], X[1]);
        }
        if (rc == CONICA_OK && v < 1.0) {
            double P[2];
            if (v < b && r->tangents) {
                u = v;
                if (u >= end)
                    end = b;
                continue; /* the next leg starts on the same tangent */
            }
            seg_at(e, v, P, NULL, NULL);
            rc = put(o, P[0], P[1]);
        }
        u = v;
        if (u >= end)
            end = b;
    }
    return rc;
}

/* Painted side at t: the caller's answer there. */
static int side_at(const seg_eval *e, double t, conica__painted_fn painted, void *ctx)
{
    double P[2], d[2];
    if (!painted)
        return 0;
    seg_at(e, t, P, NULL, NULL);
    tangent(e, t, 1, d);
    return painted(ctx, P, d);
}

/* The parts of a segment that each turn one way and have one painted
 * side: its inflections (cut[0..nc)) and where the painted side changes,
 * because another outline of the same fill crosses the curve there (the
 * fill rule resolves overlaps and self-crossings, so one curve can bound
 * the region, lie inside it and bound it from the other side in turn).
 * The side is read at points no farther apart than FIT_SIDE_SPACING
 * tolerances along the control polygon (at least FIT_SIDE_SAMPLES, at most
 * FIT_SIDE_MAX_SAMPLES per stretch between inflections) and each change
 * located by bisection, so that a piece never straddles a crossing it
 * could cross to the wrong side of (two crossings closer than the spacing
 * can still be missed: the piece's side test and the caller's check catch
 * what that leaves). part gets the ends of the parts (the last is 1), side
 * each part's side; returns the number of parts. */
#define FIT_SIDE_SAMPLES 8
#define FIT_SIDE_MAX_SAMPLES 64
#define FIT_SIDE_SPACING 16.0
#define FIT_SIDE_BISECT 30
#define FIT_SIDE_END (1.0 / 16.0)
#define FIT_MAX_INFLECTIONS 6
#define FIT_MAX_PARTS ((FIT_MAX_INFLECTIONS + 1) * (FIT_SIDE_MAX_SAMPLES + 3))

static size_t seg_parts(const seg_eval *e, const double *cut, size_t nc, double tol, int tip0,
                        int tip1, conica__painted_fn painted, void *ctx, double *part, int *side)
{
    double len = 0;
    for (int k = 0; k < e->d; k++) {
        double x0 = e->h[k][0] / e->h[k][2], y0 = e->h[k][1] / e->h[k][2];
        double x1 = e->h[k + 1][0] / e->h[k + 1][2], y1 = e->h[k + 1][1] / e->h[k + 1][2];
        len += hypot(x1 - x0, y1 - y0);
    }
    double t[FIT_MAX_PARTS], sc[FIT_MAX_PARTS];
    int sd[FIT_MAX_PARTS], sn[FIT_MAX_PARTS];
    size_t ns = 0, nsc = 0, np = 0, i = 0, j = 0;
    for (size_t k = 0; k <= nc; k++) {
        double a = k ? cut[k - 1] : 0.0, b = k < nc ? cut[k] : 1.0;
        double want = ceil((b - a) * len / (FIT_SIDE_SPACING * tol));
        int m = !(want > FIT_SIDE_SAMPLES) ? FIT_SIDE_SAMPLES
                : want < FIT_SIDE_MAX_SAMPLES ? (int)want
                                              : FIT_SIDE_MAX_SAMPLES;
        /* the middles of m equal parts, and near both ends (a crossing
         * close to a corner) */
        for (int q = -1; q <= m; q++, ns++) {
            double f = q < 0 ? FIT_SIDE_END / m : q == m ? 1 - FIT_SIDE_END / m : (q + 0.5) / m;
            t[ns] = a + (b - a) * f;
            sd[ns] = side_at(e, t[ns], painted, ctx);
        }
    }
    for (size_t q = 1; q < ns; q++) {
        if (sd[q] == sd[q - 1])
            continue;
        double lo = t[q - 1], hi = t[q];
        for (int k = 0; k < FIT_SIDE_BISECT; k++) {
            double mid = 0.5 * (lo + hi);
            if (side_at(e, mid, painted, ctx) == sd[q - 1])
                lo = mid;
            else
                hi = mid;
        }
        sc[nsc] = 0.5 * (lo + hi);
        sn[nsc++] = sd[q];
    }
    /* merge the inflections and the side changes */
    side[0] = sd[0];
    while (i < nc || j < nsc) {
        int take_side = j < nsc && (i >= nc || sc[j] <= cut[i]);
        double c = take_side ? sc[j] : cut[i];
        if (c > 0.0 && c < 1.0 && (np == 0 || c > part[np - 1])) {
            part[np] = c;
            side[np + 1] = side[np];
            np++;
        }
        if (take_side) {
            if (np > 0)
                side[np] = sn[j];
            else
                side[0] = sn[j];
            j++;
        } else {
            i++;
        }
    }
    part[np++] = 1.0;
    /* at a tip the outline is thinner than the probes reach: the part
     * there has the side of the part before it (after it, at the start) */
    if (tip1 && np > 1 && side[np - 1] == 0) {
        part[np - 2] = 1.0;
        np--;
    }
    if (tip0 && np > 1 && side[0] == 0) {
        memmove(part, part + 1, (np - 1) * sizeof *part);
        memmove(side, side + 1, (np - 1) * sizeof *side);
        np--;
    }
    return np;
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

/* Unit direction of drawn segment s at its start (end 0) or end (end 1),
 * in the direction of travel. */
static void seg_dir(const conica_path *p, size_t s, int end, double out[2])
{
    if (seg_is_straight(p, s)) {
        const conica_path_seg *g = &p->seg[s];
        const double *q = p->pt + 3 * g->first, *r = q + 3 * g->degree;
        double dx = r[0] - q[0], dy = r[1] - q[1], l = hypot(dx, dy);
        out[0] = l > 0 ? dx / l : 1;
        out[1] = l > 0 ? dy / l : 0;
        return;
    }
    seg_eval e;
    seg_load(p, s, &e);
    tangent(&e, (double)end, end ? -1 : 1, out);
}

/* Tips: the polygon turns back by more than pi - FIT_TIP_ANGLE where two
 * drawn pieces meet. */
#define FIT_TIP_ANGLE 1e-3

/* Does the fill's outline turn back at the start (end 0) or end (end 1) of
 * segment j of subpath sp: the neighbour (the segment before or after; an
 * open subpath is closed by a straight edge) leaves along the same line? */
static int is_tip(const conica_path *p, const conica_path_subpath *sp, size_t j, int end)
{
    size_t s = sp->first + j, nb;
    double d0[2], d1[2];
    int last = j + 1 == sp->n, first = j == 0;
    seg_dir(p, s, end, d0);
    if (!sp->closed && (end ? last : first)) {
        /* the closing edge, from the subpath's end to its start */
        const conica_path_seg *z = &p->seg[sp->first + sp->n - 1];
        const double *ze = p->pt + 3 * (z->first + (size_t)z->degree);
        double dx = sp->x0 - ze[0], dy = sp->y0 - ze[1], l = hypot(dx, dy);
        if (l > 0) {
            d1[0] = dx / l;
            d1[1] = dy / l;
            return d0[0] * d1[0] + d0[1] * d1[1] < -cos(FIT_TIP_ANGLE);
        }
    }
    nb = end ? (last ? sp->first : s + 1) : (first ? sp->first + sp->n - 1 : s - 1);
    if (nb == s)
        return 0;
    seg_dir(p, nb, !end, d1);
    return d0[0] * d1[0] + d0[1] * d1[1] < -cos(FIT_TIP_ANGLE);
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
        double cut[FIT_MAX_INFLECTIONS];
        size_t nc;
        rc = put(o, q[0], q[1]); /* the segment's start, exactly as drawn */
        if (rc != CONICA_OK || seg_is_straight(p, s))
            continue;
        seg_load(p, s, &e);
        nc = conica__path_seg_inflections(p, s, cut, FIT_MAX_INFLECTIONS);
        const double *qe = q + 3 * p->seg[s].degree;
        double chord = hypot(qe[0] - q[0], qe[1] - q[1]);
        size_t i0 = *o->n - 1; /* where the segment's start went */
        int tip0 = side != CONICA__FIT_CHORDS && is_tip(p, sp, j, 0);
        int tip1 = side != CONICA__FIT_CHORDS && is_tip(p, sp, j, 1);
        double pc[FIT_MAX_PARTS];
        int ps[FIT_MAX_PARTS];
        size_t np;
        if (side != CONICA__FIT_CHORDS && painted) {
            np = seg_parts(&e, cut, nc, tol, tip0, tip1, painted, ctx, pc, ps);
        } else { /* the inflections alone */
            for (np = 0; np < nc; np++) {
                pc[np] = cut[np];
                ps[np] = 0;
            }
            pc[np] = 1.0;
            ps[np++] = 0;
        }
        for (size_t k = 0; k < np && rc == CONICA_OK; k++) {
            double a = k ? pc[k - 1] : 0.0, b = pc[k];
            int pside = ps[k];
            /* the painted region is convex here when the curve turns
             * towards the painted side; chords then lie inside it */
            int ts = turn_sign(&e, 0.5 * (a + b));
            int convex = pside != 0 && ts == pside;
            piece_rule r;
            r.tangents = side != CONICA__FIT_CHORDS && pside != 0 && ts != 0 &&
                         ((side == CONICA__FIT_IN && !convex) ||
                          (side == CONICA__FIT_OUT && convex));
            r.tol = tol;
            r.max_turn = fmin(max_turn, FIT_MAX_TURN);
            r.painted = side != CONICA__FIT_CHORDS && pside != 0 ? painted : NULL;
            r.ctx = ctx;
            r.want = side == CONICA__FIT_IN;
            rc = stretch(&e, a, b, &r, tip0, tip1, o);
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

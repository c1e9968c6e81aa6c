/* SPDX-License-Identifier: MIT */
/* The independent fidelity checker (fidelity.h). Nothing here comes from
 * libcore: Bezier evaluation, distances, areas and crossings are written out
 * from their textbook definitions. */
#include "fidelity.h"

#include <math.h>
#include <stdlib.h>

/* Golden-section steps: the bracket shrinks by 0.618 per step, so 60 steps
 * take a bracket of 2/per_seg below 1e-13 of the parameter range. */
#define TS_GOLDEN_STEPS 60
/* An edge or segment is refined when its sampled worst reaches this
 * fraction of the running worst (refining can only raise a value, and a
 * smooth distance rarely rises by half between dense samples). */
#define TS_REFINE_FRACTION 0.5
/* Gauss-Legendre pieces per rational arc in the area integral. */
#define TS_AREA_PIECES 16

ts_sampling ts_sampling_defaults(void)
{
    ts_sampling s = {64, 8};
    return s;
}

static double weight(const ts_seg *s)
{
    return s->w > 0.0 ? s->w : 1.0;
}

void ts_seg_eval(const ts_seg *s, double t, double out[2])
{
    const double u = 1.0 - t;
    int k;
    for (k = 0; k < 2; k++) {
        switch (s->degree) {
        case 2: {
            double w = weight(s), b0 = u * u, b1 = 2.0 * w * u * t, b2 = t * t;
            out[k] = (b0 * s->p[0][k] + b1 * s->p[1][k] + b2 * s->p[2][k]) / (b0 + b1 + b2);
            break;
        }
        case 3:
            out[k] = u * u * u * s->p[0][k] + 3.0 * u * u * t * s->p[1][k] +
                     3.0 * u * t * t * s->p[2][k] + t * t * t * s->p[3][k];
            break;
        default:
            out[k] = u * s->p[0][k] + t * s->p[1][k];
            break;
        }
    }
}

void ts_seg_deriv(const ts_seg *s, double t, double out[2])
{
    const double u = 1.0 - t;
    int k;
    for (k = 0; k < 2; k++) {
        switch (s->degree) {
        case 2: { /* quotient rule on N(t) / D(t) */
            double w = weight(s), b0 = u * u, b1 = 2.0 * w * u * t, b2 = t * t;
            double d0 = -2.0 * u, d1 = 2.0 * w * (u - t), d2 = 2.0 * t;
            double num = b0 * s->p[0][k] + b1 * s->p[1][k] + b2 * s->p[2][k];
            double dnum = d0 * s->p[0][k] + d1 * s->p[1][k] + d2 * s->p[2][k];
            double den = b0 + b1 + b2, dden = d0 + d1 + d2;
            out[k] = (dnum * den - num * dden) / (den * den);
            break;
        }
        case 3:
            out[k] = 3.0 * (u * u * (s->p[1][k] - s->p[0][k]) + 2.0 * u * t * (s->p[2][k] - s->p[1][k]) +
                            t * t * (s->p[3][k] - s->p[2][k]));
            break;
        default:
            out[k] = s->p[1][k] - s->p[0][k];
            break;
        }
    }
}

static int contours_ok(const ts_contour *c, size_t nc)
{
    size_t i, j, segs = 0;
    for (i = 0; i < nc; i++)
        for (j = 0; j < c[i].n; j++, segs++)
            if (c[i].seg[j].degree < 1 || c[i].seg[j].degree > 3 || c[i].seg[j].w < 0.0)
                return 0;
    return segs > 0;
}

static double dist2(const double a[2], const double b[2])
{
    double dx = a[0] - b[0], dy = a[1] - b[1];
    return dx * dx + dy * dy;
}

/* ------------------------------------------------------------ 1-D search */

typedef double (*ts_fn)(const void *ctx, double t);

/* Minimise f on [a, b] by golden section; returns the argmin, *fmin its value. */
static double golden_min(ts_fn f, const void *ctx, double a, double b, double *fmin)
{
    const double g = 0.6180339887498949;
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = f(ctx, x1), f2 = f(ctx, x2);
    int i;
    for (i = 0; i < TS_GOLDEN_STEPS; i++) {
        if (f1 <= f2) {
            b = x2, x2 = x1, f2 = f1;
            x1 = b - g * (b - a), f1 = f(ctx, x1);
        } else {
            a = x1, x1 = x2, f1 = f2;
            x2 = a + g * (b - a), f2 = f(ctx, x2);
        }
    }
    *fmin = f1 <= f2 ? f1 : f2;
    return f1 <= f2 ? x1 : x2;
}

/* The bracket around sample j of 0..n (fractions j/n). */
static void bracket(size_t j, size_t n, double *lo, double *hi)
{
    *lo = j > 0 ? (double)(j - 1) / (double)n : 0.0;
    *hi = j < n ? (double)(j + 1) / (double)n : 1.0;
}

/* ------------------------------------------------------------ distances */

typedef struct seg_q {
    const ts_seg *s;
    const double *q;
} seg_q;

static double seg_q_d2(const void *ctx, double t)
{
    const seg_q *c = ctx;
    double p[2];
    ts_seg_eval(c->s, t, p);
    return dist2(p, c->q);
}

/* Squared distance from q to the edge a-b; *u the nearest fraction. */
static double edge_d2(const double a[2], const double b[2], const double q[2], double *u)
{
    double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy, f = 0.0, p[2];
    if (l2 > 0.0) {
        f = ((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / l2;
        f = f < 0.0 ? 0.0 : f > 1.0 ? 1.0 : f;
    }
    p[0] = a[0] + f * dx;
    p[1] = a[1] + f * dy;
    *u = f;
    return dist2(p, q);
}

/* Squared distance from q to one segment, *t the nearest parameter. Every
 * local minimum of the samples is refined, not only the least: a curve
 * that doubles back (a hook, a cusp's overshoot) passes q twice, and the
 * sample nearest to q may lie on the far pass. */
static double seg_nearest(const ts_seg *s, const double q[2], size_t n, double *t)
{
    seg_q ctx = {s, q};
    double best = INFINITY, lo, hi, tg, fg, prev = INFINITY, cur, next;
    size_t j;
    if (s->degree == 1)
        return edge_d2(s->p[0], s->p[1], q, t);
    cur = seg_q_d2(&ctx, 0.0);
    for (j = 0; j <= n; j++) {
        next = j < n ? seg_q_d2(&ctx, (double)(j + 1) / (double)n) : INFINITY;
        if (cur <= prev && cur <= next) {
            if (cur < best)
                best = cur, *t = (double)j / (double)n;
            bracket(j, n, &lo, &hi);
            tg = golden_min(seg_q_d2, &ctx, lo, hi, &fg);
            if (fg < best)
                best = fg, *t = tg;
        }
        prev = cur;
        cur = next;
    }
    return best;
}

/* Squared distance from q to the control-point box (the curve lies inside:
 * convex hull property, weights >= 0). */
static double box_d2(const ts_seg *s, const double q[2])
{
    double r = 0.0;
    int k, i;
    for (k = 0; k < 2; k++) {
        double lo = s->p[0][k], hi = lo, d = 0.0;
        for (i = 1; i <= s->degree; i++) {
            lo = fmin(lo, s->p[i][k]);
            hi = fmax(hi, s->p[i][k]);
        }
        if (q[k] < lo)
            d = lo - q[k];
        else if (q[k] > hi)
            d = q[k] - hi;
        r += d * d;
    }
    return r;
}

double ts_dist_to_curve(const ts_contour *c, size_t nc, const double q[2], size_t per_seg,
                        ts_curve_place *where)
{
    ts_curve_place w = {0, 0, 0.0};
    double best = INFINITY, t = 0.0;
    size_t i, j;
    if (per_seg < 2)
        per_seg = 2;
    for (i = 0; i < nc; i++)
        for (j = 0; j < c[i].n; j++) {
            double d;
            if (box_d2(&c[i].seg[j], q) >= best)
                continue;
            d = seg_nearest(&c[i].seg[j], q, per_seg, &t);
            if (d < best) {
                best = d;
                w.contour = i, w.seg = j, w.t = t;
            }
        }
    if (where && best < INFINITY)
        *where = w;
    return sqrt(best);
}

static size_t edge_count(const ts_poly *p)
{
    return p->n < 2 ? p->n : p->closed ? p->n : p->n - 1;
}

static const double *vtx(const ts_poly *p, size_t i)
{
    return p->xy + 2 * (i % p->n);
}

double ts_dist_to_poly(const ts_poly *p, size_t np, const double q[2], ts_poly_place *where)
{
    ts_poly_place w = {0, 0, 0.0};
    double best = INFINITY, u;
    size_t k, e;
    for (k = 0; k < np; k++)
        for (e = 0; e < edge_count(&p[k]); e++) {
            double d = edge_d2(vtx(&p[k], e), vtx(&p[k], e + 1), q, &u);
            if (d < best) {
                best = d;
                w.poly = k, w.edge = e, w.u = u;
            }
        }
    if (where && best < INFINITY)
        *where = w;
    return sqrt(best);
}

/* ------------------------------------------------------------ Hausdorff */

typedef struct edge_ctx { /* a point on a polyline edge vs the curves */
    const ts_contour *c;
    size_t nc, per_seg;
    const double *a, *b;
} edge_ctx;

static double edge_neg_dist(const void *ctx, double u)
{
    const edge_ctx *e = ctx;
    double q[2];
    q[0] = e->a[0] + u * (e->b[0] - e->a[0]);
    q[1] = e->a[1] + u * (e->b[1] - e->a[1]);
    return -ts_dist_to_curve(e->c, e->nc, q, e->per_seg, NULL);
}

typedef struct curve_ctx { /* a point on a segment vs the polylines */
    const ts_seg *s;
    const ts_poly *p;
    size_t np;
} curve_ctx;

static double curve_neg_dist(const void *ctx, double t)
{
    const curve_ctx *c = ctx;
    double q[2];
    ts_seg_eval(c->s, t, q);
    return -ts_dist_to_poly(c->p, c->np, q, NULL);
}

/* Max of -f over samples j/n, j = 0..n, refined when it can matter. */
static double worst_on(ts_fn f, const void *ctx, size_t n, double running, double *where)
{
    double best = -1.0, lo, hi, xg, fg;
    size_t j, bj = 0;
    for (j = 0; j <= n; j++) {
        double d = -f(ctx, (double)j / (double)n);
        if (d > best)
            best = d, bj = j;
    }
    *where = (double)bj / (double)n;
    if (best > 0.0 && best >= TS_REFINE_FRACTION * running) {
        bracket(bj, n, &lo, &hi);
        xg = golden_min(f, ctx, lo, hi, &fg);
        if (-fg > best)
            best = -fg, *where = xg;
    }
    return best;
}

ts_code ts_hausdorff_measure(const ts_contour *c, size_t nc, const ts_poly *p, size_t np,
                             const ts_sampling *s, ts_hausdorff *out)
{
    ts_sampling smp = s ? *s : ts_sampling_defaults();
    ts_hausdorff h = {0.0, {0, 0, 0.0}, {0, 0, 0.0}, 0.0, {0, 0, 0.0}, {0, 0, 0.0}, 0.0};
    size_t i, j;
    double q[2];
    if (!contours_ok(c, nc) || np == 0 || smp.per_seg < 2 || smp.per_edge < 1 ||
        smp.per_seg > TS_MAX_SAMPLES || smp.per_edge > TS_MAX_SAMPLES)
        return TS_ERR_ARG;
    for (i = 0; i < np; i++)
        if (p[i].n == 0)
            return TS_ERR_ARG;
    /* polylines -> curves: vertices and per_edge points inside each edge */
    for (i = 0; i < np; i++) {
        edge_ctx e = {c, nc, smp.per_seg, p[i].xy, p[i].xy};
        double d, u;
        /* a single vertex counts as one edge of length 0 (edge_count) */
        for (j = 0; j < edge_count(&p[i]); j++) {
            e.a = vtx(&p[i], j);
            e.b = vtx(&p[i], j + 1);
            d = worst_on(edge_neg_dist, &e, smp.per_edge + 1, h.poly_to_curve, &u);
            if (d > h.poly_to_curve) {
                h.poly_to_curve = d;
                h.poly_worst.poly = i, h.poly_worst.edge = j, h.poly_worst.u = u;
            }
        }
    }
    {
        const ts_poly *w = &p[h.poly_worst.poly];
        const double *a = vtx(w, h.poly_worst.edge), *b = vtx(w, h.poly_worst.edge + 1);
        q[0] = a[0] + h.poly_worst.u * (b[0] - a[0]);
        q[1] = a[1] + h.poly_worst.u * (b[1] - a[1]);
        h.poly_to_curve = ts_dist_to_curve(c, nc, q, smp.per_seg, &h.poly_nearest);
    }
    /* curves -> polylines */
    for (i = 0; i < nc; i++)
        for (j = 0; j < c[i].n; j++) {
            curve_ctx cc = {&c[i].seg[j], p, np};
            double t, d = worst_on(curve_neg_dist, &cc, smp.per_seg, h.curve_to_poly, &t);
            if (d > h.curve_to_poly) {
                h.curve_to_poly = d;
                h.curve_worst.contour = i, h.curve_worst.seg = j, h.curve_worst.t = t;
            }
        }
    ts_seg_eval(&c[h.curve_worst.contour].seg[h.curve_worst.seg], h.curve_worst.t, q);
    h.curve_to_poly = ts_dist_to_poly(p, np, q, &h.curve_nearest);
    h.max = fmax(h.poly_to_curve, h.curve_to_poly);
    *out = h;
    return TS_OK;
}

ts_code ts_contour_sample(const ts_contour *c, size_t per_seg, double **xy, size_t *n)
{
    size_t m, i, j, k = 0;
    double *v;
    if (!contours_ok(c, 1) || per_seg == 0 || per_seg > TS_MAX_SAMPLES)
        return TS_ERR_ARG;
    m = c->n * per_seg + (c->closed ? 0 : 1);
    v = malloc(2 * m * sizeof *v);
    if (!v)
        return TS_ERR_NOMEM;
    for (i = 0; i < c->n; i++)
        for (j = 0; j < per_seg; j++, k++)
            ts_seg_eval(&c->seg[i], (double)j / (double)per_seg, v + 2 * k);
    if (!c->closed) {
        const ts_seg *s = &c->seg[c->n - 1];
        v[2 * k] = s->p[s->degree][0];
        v[2 * k + 1] = s->p[s->degree][1];
    }
    *xy = v;
    *n = m;
    return TS_OK;
}

/* ------------------------------------------------------------ areas */

/* (1/2) * integral of x y' - y x' over one segment (Green's theorem). The
 * integrand of a cubic has degree 4, within the 5-point rule's degree 9. */
static double seg_area(const ts_seg *s)
{
    static const double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                   0.5384693101056831, 0.9061798459386640};
    static const double wt[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                 0.4786286704993665, 0.2369268850561891};
    int pieces = (s->degree == 2 && weight(s) != 1.0) ? TS_AREA_PIECES : 1, i, k;
    double sum = 0.0, h = 1.0 / pieces;
    if (s->degree == 1)
        return 0.5 * (s->p[0][0] * s->p[1][1] - s->p[0][1] * s->p[1][0]);
    for (i = 0; i < pieces; i++)
        for (k = 0; k < 5; k++) {
            double t = h * (i + 0.5 * (node[k] + 1.0)), p[2], d[2];
            ts_seg_eval(s, t, p);
            ts_seg_deriv(s, t, d);
            sum += 0.5 * h * wt[k] * (p[0] * d[1] - p[1] * d[0]);
        }
    return 0.5 * sum;
}

double ts_contour_area(const ts_contour *c)
{
    double a = 0.0;
    size_t i;
    if (c->n == 0)
        return 0.0;
    for (i = 0; i < c->n; i++)
        a += seg_area(&c->seg[i]);
    { /* the closing chord, zero when the ends meet */
        const ts_seg *l = &c->seg[c->n - 1];
        const double *e = l->p[l->degree], *s = c->seg[0].p[0];
        a += 0.5 * (e[0] * s[1] - e[1] * s[0]);
    }
    return a;
}

double ts_outline_area(const ts_outline *o)
{
    double a = 0.0;
    size_t i;
    for (i = 0; i < o->n; i++)
        a += ts_contour_area(&o->c[i]);
    return a;
}

double ts_poly_area(const double *xy, size_t n)
{
    double a = 0.0;
    size_t i;
    for (i = 0; i < n; i++) {
        const double *p = xy + 2 * i, *q = xy + 2 * ((i + 1) % n);
        a += p[0] * q[1] - p[1] * q[0];
    }
    return 0.5 * a;
}

/* ------------------------------------------------------------ crossings */

typedef struct eref {
    double x0, x1, y0, y1;
    size_t poly, edge;
} eref;

static int cmp_x0(const void *a, const void *b)
{
    double u = ((const eref *)a)->x0, v = ((const eref *)b)->x0;
    return (u > v) - (u < v);
}

static double orient(const double a[2], const double b[2], const double c[2])
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int opposite(double a, double b)
{
    return (a > 0.0 && b < 0.0) || (a < 0.0 && b > 0.0);
}

ts_code ts_poly_crossings(const ts_poly *p, size_t np, int within, size_t *count,
                          ts_crossing *first)
{
    size_t m = 0, i, j, found = 0;
    eref *e;
    for (i = 0; i < np; i++)
        m += edge_count(&p[i]);
    e = malloc((m ? m : 1) * sizeof *e);
    if (!e)
        return TS_ERR_NOMEM;
    for (i = 0, m = 0; i < np; i++)
        for (j = 0; j < edge_count(&p[i]); j++, m++) {
            const double *a = vtx(&p[i], j), *b = vtx(&p[i], j + 1);
            e[m].x0 = fmin(a[0], b[0]), e[m].x1 = fmax(a[0], b[0]);
            e[m].y0 = fmin(a[1], b[1]), e[m].y1 = fmax(a[1], b[1]);
            e[m].poly = i, e[m].edge = j;
        }
    qsort(e, m, sizeof *e, cmp_x0);
    for (i = 0; i < m; i++)
        for (j = i + 1; j < m && e[j].x0 <= e[i].x1; j++) {
            const eref *f = &e[i], *g = &e[j];
            const double *a, *b, *c, *d;
            double d1, d2, d3, d4;
            if ((f->poly == g->poly && !within) || g->y0 > f->y1 || g->y1 < f->y0)
                continue;
            if (g->poly < f->poly || (g->poly == f->poly && g->edge < f->edge))
                f = &e[j], g = &e[i];
            a = vtx(&p[f->poly], f->edge), b = vtx(&p[f->poly], f->edge + 1);
            c = vtx(&p[g->poly], g->edge), d = vtx(&p[g->poly], g->edge + 1);
            d1 = orient(c, d, a), d2 = orient(c, d, b);
            d3 = orient(a, b, c), d4 = orient(a, b, d);
            if (!opposite(d1, d2) || !opposite(d3, d4))
                continue;
            if (found++ == 0 && first) {
                double u = d1 / (d1 - d2);
                first->a.poly = f->poly, first->a.edge = f->edge, first->a.u = u;
                first->b.poly = g->poly, first->b.edge = g->edge, first->b.u = d3 / (d3 - d4);
                first->p[0] = a[0] + u * (b[0] - a[0]);
                first->p[1] = a[1] + u * (b[1] - a[1]);
            }
        }
    free(e);
    *count = found;
    return TS_OK;
}

/* ------------------------------------------------------------ corners */

/* Tangent direction at the start (at_end 0) or end of a segment, from the
 * nearest control point that differs from the end point. */
static int end_dir(const ts_seg *s, int at_end, double d[2])
{
    const int n = s->degree;
    int k;
    for (k = 1; k <= n; k++) {
        const double *e = at_end ? s->p[n] : s->p[0], *o = at_end ? s->p[n - k] : s->p[k];
        if (o[0] != e[0] || o[1] != e[1]) {
            d[0] = at_end ? e[0] - o[0] : o[0] - e[0];
            d[1] = at_end ? e[1] - o[1] : o[1] - e[1];
            return 1;
        }
    }
    return 0;
}

ts_code ts_contour_corners(const ts_contour *c, double min_turn, ts_corner **out, size_t *n)
{
    size_t joins, i, k = 0;
    ts_corner *r;
    if (c->n && !contours_ok(c, 1))
        return TS_ERR_ARG;
    joins = c->n == 0 ? 0 : c->closed ? c->n : c->n - 1;
    r = malloc((joins ? joins : 1) * sizeof *r);
    if (!r)
        return TS_ERR_NOMEM;
    for (i = 0; i < joins; i++) {
        const ts_seg *s = &c->seg[i], *t = &c->seg[(i + 1) % c->n];
        double din[2], dout[2], turn;
        if (!end_dir(s, 1, din) || !end_dir(t, 0, dout))
            continue;
        turn = atan2(din[0] * dout[1] - din[1] * dout[0], din[0] * dout[0] + din[1] * dout[1]);
        if (fabs(turn) > min_turn) {
            r[k].seg = i;
            r[k].p[0] = s->p[s->degree][0];
            r[k].p[1] = s->p[s->degree][1];
            r[k].turn = turn;
            k++;
        }
    }
    if (k == 0) {
        free(r);
        r = NULL;
    }
    *out = r;
    *n = k;
    return TS_OK;
}

/* Neighbour of vertex v farther than tol, walking by step (+1 or -1);
 * NULL at the end of an open polyline or when every vertex is that close. */
static const double *neighbour(const ts_poly *p, size_t v, int step, double tol)
{
    size_t i, j = v;
    for (i = 1; i < p->n; i++) {
        if (!p->closed && ((step < 0 && j == 0) || (step > 0 && j == p->n - 1)))
            return NULL;
        j = step > 0 ? (j + 1) % p->n : (j + p->n - 1) % p->n;
        if (dist2(vtx(p, j), vtx(p, v)) > tol * tol)
            return vtx(p, j);
    }
    return NULL;
}

ts_code ts_corners_kept(const ts_corner *k, size_t nk, const ts_poly *p, size_t np,
                        double pos_tol, double slack, ts_corner_check *out)
{
    ts_corner_check r = {0, 0, 0, 0.0};
    size_t i, a, v;
    if (!(pos_tol >= 0.0))
        return TS_ERR_ARG;
    for (i = 0; i < nk; i++) {
        double best = INFINITY, turn = NAN;
        size_t bp = 0, bv = 0;
        for (a = 0; a < np; a++)
            for (v = 0; v < p[a].n; v++) {
                double d = dist2(vtx(&p[a], v), k[i].p);
                if (d <= pos_tol * pos_tol && d < best)
                    best = d, bp = a, bv = v;
            }
        if (best < INFINITY) {
            const double *o = vtx(&p[bp], bv), *pr = neighbour(&p[bp], bv, -1, pos_tol),
                         *nx = neighbour(&p[bp], bv, 1, pos_tol);
            turn = 0.0;
            if (pr && nx) {
                double din[2] = {o[0] - pr[0], o[1] - pr[1]}, dout[2] = {nx[0] - o[0], nx[1] - o[1]};
                turn = fabs(atan2(din[0] * dout[1] - din[1] * dout[0],
                                  din[0] * dout[0] + din[1] * dout[1]));
            }
            if (turn >= fabs(k[i].turn) - slack) {
                r.kept++;
                continue;
            }
        }
        if (r.missing++ == 0)
            r.first_missing = i, r.first_missing_turn = turn;
    }
    *out = r;
    return TS_OK;
}

/* ------------------------------------------------------------ circles */

double ts_ellipse_radial_error(const double *xy, size_t n, const double center[2], double rx,
                               double ry, double rot, size_t *worst)
{
    const double cr = cos(rot), sr = sin(rot);
    double best = 0.0;
    size_t i, w = 0;
    for (i = 0; i < n; i++) {
        double dx = xy[2 * i] - center[0], dy = xy[2 * i + 1] - center[1];
        double x = (cr * dx + sr * dy) / rx, y = (-sr * dx + cr * dy) / ry;
        double e = fabs(hypot(x, y) - 1.0);
        if (e > best || i == 0)
            best = e, w = i;
    }
    if (worst)
        *worst = w;
    return best;
}

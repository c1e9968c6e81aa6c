/* SPDX-License-Identifier: MIT */
/* Measured deviation between a spline and a polyline (tests, benchmarks):
 * when the polyline carries parameters, chord by chord (deviation_local);
 * otherwise dense samples of the curve against the polyline and
 * polyline points against the curve. Nearest items are found exactly with
 * a uniform grid on the first two coordinates (ring search with a distance
 * lower bound), so the measure is linear in practice and exact:
 * - curve -> polyline: each sample's distance to the nearest segment;
 * - polyline -> curve: each vertex and segment quarter point: nearest
 *   sample, then a golden-section search of |f(t) - q| between the
 *   neighbouring samples' parameters (never above the sample distance). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bspline_internal.h"
#include "internal.h"
#include "plot_internal.h"

#define GRID_MAX 1024
/* Samples of one measure: per chord (local) or in all (global); above it
 * CONICA_ERR_LIMIT, never a wrapped allocation size. */
#define DEVIATION_MAX_SAMPLES ((size_t)1 << 26)
#define GOLDEN_STEPS 30

typedef struct grid {
    double lo[2], cw, ch, cs;
    size_t G;
    size_t *start, *item;
} grid;

static void cell_of(const grid *g, double x, double y, size_t *cx, size_t *cy)
{
    double fx = (x - g->lo[0]) / g->cw, fy = (y - g->lo[1]) / g->ch;
    /* !(f > 0): a NaN (point at infinity) lands in cell 0 instead of
     * being cast to size_t (undefined; found by fuzz_plot) */
    *cx = !(fx > 0) ? 0 : (fx >= (double)g->G ? g->G - 1 : (size_t)fx);
    *cy = !(fy > 0) ? 0 : (fy >= (double)g->G ? g->G - 1 : (size_t)fy);
}

/* Items are boxes [bx0,bx1]x[by0,by1] (points or segment bounding boxes). */
static int grid_build(grid *g, const double *lo, const double *hi, size_t nitems,
                      const double *boxes /* 4 per item */)
{
    size_t G = (size_t)sqrt((double)nitems) + 1;
    g->G = G > GRID_MAX ? GRID_MAX : G;
    g->lo[0] = lo[0];
    g->lo[1] = lo[1];
    g->cw = (hi[0] - lo[0]) / (double)g->G;
    g->ch = (hi[1] - lo[1]) / (double)g->G;
    if (!(g->cw > 0))
        g->cw = 1.0;
    if (!(g->ch > 0))
        g->ch = 1.0;
    g->cs = g->cw < g->ch ? g->cw : g->ch;
    size_t cells = g->G * g->G;
    g->start = calloc(cells + 1, sizeof *g->start);
    if (!g->start)
        return 0;
    for (int pass = 0; pass < 2; pass++) {
        size_t *fill = NULL;
        if (pass == 1) {
            for (size_t c = 0; c < cells; c++)
                g->start[c + 1] += g->start[c];
            g->item = malloc((g->start[cells] + 1) * sizeof *g->item);
            fill = malloc(cells * sizeof *fill);
            if (!g->item || !fill) {
                free(fill);
                return 0;
            }
            memcpy(fill, g->start, cells * sizeof *fill);
        }
        for (size_t i = 0; i < nitems; i++) {
            size_t x0, y0, x1, y1;
            cell_of(g, boxes[4 * i], boxes[4 * i + 2], &x0, &y0);
            cell_of(g, boxes[4 * i + 1], boxes[4 * i + 3], &x1, &y1);
            for (size_t y = y0; y <= y1; y++)
                for (size_t x = x0; x <= x1; x++) {
                    if (pass == 0)
                        g->start[y * g->G + x + 1]++;
                    else
                        g->item[fill[y * g->G + x]++] = i;
                }
        }
        free(fill);
    }
    return 1;
}

static void grid_free(grid *g)
{
    free(g->start);
    free(g->item);
}

typedef double (*dist_fn)(const void *ctx, size_t item, const double *q);

/* Exact nearest item (squared distance) to q; *which gets its index. */
static double grid_nearest(const grid *g, const double *q, dist_fn f, const void *ctx,
                           size_t *which)
{
    size_t cx, cy;
    cell_of(g, q[0], q[1], &cx, &cy);
    double best = INFINITY;
    *which = 0;
    for (size_t r = 0; r <= g->G; r++) {
        size_t x0 = cx >= r ? cx - r : 0, x1 = cx + r < g->G ? cx + r : g->G - 1;
        size_t y0 = cy >= r ? cy - r : 0, y1 = cy + r < g->G ? cy + r : g->G - 1;
        for (size_t y = y0; y <= y1; y++)
            for (size_t x = x0; x <= x1; x++) {
                if (!(x + r == cx || x == cx + r || y + r == cy || y == cy + r))
                    continue;
                for (size_t e = g->start[y * g->G + x]; e < g->start[y * g->G + x + 1]; e++) {
                    double d = f(ctx, g->item[e], q);
                    if (d < best) {
                        best = d;
                        *which = g->item[e];
                    }
                }
            }
        double reach = (double)r * g->cs;
        if (best <= reach * reach)
            break;
    }
    return best;
}

static double seg_d2(const double *p, const double *a, const double *b, int d)
{
    double ab2 = 0, t = 0;
    for (int c = 0; c < d; c++) {
        ab2 += (b[c] - a[c]) * (b[c] - a[c]);
        t += (p[c] - a[c]) * (b[c] - a[c]);
    }
    double u = ab2 > 0 ? t / ab2 : 0.0;
    u = u < 0 ? 0 : (u > 1 ? 1 : u);
    double r = 0;
    for (int c = 0; c < d; c++) {
        double e = p[c] - (a[c] + u * (b[c] - a[c]));
        r += e * e;
    }
    return r;
}

typedef struct segctx {
    const conica_polyline *pl;
    const size_t *seg_a, *seg_b;
} segctx;

static double seg_item(const void *ctx, size_t i, const double *q)
{
    const segctx *c = ctx;
    size_t d = (size_t)c->pl->dim;
    return seg_d2(q, c->pl->xy + c->seg_a[i] * d, c->pl->xy + c->seg_b[i] * d, c->pl->dim);
}

typedef struct ptctx {
    const double *pts;
    int d;
} ptctx;

static double pt_item(const void *ctx, size_t i, const double *q)
{
    const ptctx *c = ctx;
    double r = 0;
    for (int k = 0; k < c->d; k++)
        r += (q[k] - c->pts[3 * i + (size_t)k]) * (q[k] - c->pts[3 * i + (size_t)k]);
    return r;
}

static double curve_d2(const conica_bspline *s, double t, const double *q, int d)
{
    double x[3];
    conica__plot_point(s, t, x);
    double r = 0;
    for (int c = 0; c < d; c++)
        r += (q[c] - x[c]) * (q[c] - x[c]);
    return r;
}

/* Golden-section search of |f(t) - q|^2 on [lo, hi]; returns the smaller
 * of the value found and `best`. */
static double golden_min(const conica_bspline *s, double lo, double hi, const double *q, int d,
                         double best)
{
    const double gr = 0.5 * (sqrt(5.0) - 1.0);
    double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
    double f1 = curve_d2(s, x1, q, d), f2 = curve_d2(s, x2, q, d);
    for (int it = 0; it < GOLDEN_STEPS; it++) {
        if (f1 < f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - gr * (hi - lo);
            f1 = curve_d2(s, x1, q, d);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + gr * (hi - lo);
            f2 = curve_d2(s, x2, q, d);
        }
    }
    best = f1 < best ? f1 : best;
    return f2 < best ? f2 : best;
}

typedef struct p2cctx {
    const conica_bspline *s;
    const grid *g;
    const ptctx *pc;
    const double *ts;
    size_t m;
    int d;
} p2cctx;

/* Squared distance from q to the curve: nearest sample, then a
 * golden-section search between the neighbouring samples' parameters. */
static double p2c_query(const p2cctx *c, const double *q)
{
    size_t j;
    double best = grid_nearest(c->g, q, pt_item, c->pc, &j);
    double a = c->ts[j > 0 ? j - 1 : 0], b = c->ts[j + 1 < c->m ? j + 1 : c->m - 1];
    return golden_min(c->s, a, b, q, c->d, best);
}

/* Local measure when every polyline point has a parameter: each chord
 * [f(t_i), f(t_{i+1})] against the curve on [t_i, t_{i+1}] only (samples
 * per chord; a restriction can only over-estimate both distances). */
static conica_code deviation_local(const conica_bspline *s, const conica_polyline *pl,
                                   size_t samples, double *c2p_out, double *p2c_out,
                                   conica_status *st)
{
    size_t d = (size_t)pl->dim, S = samples < 2 ? 2 : samples;
    if (S > DEVIATION_MAX_SAMPLES)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "%zu samples per chord exceed the limit of %zu", samples,
                            (size_t)DEVIATION_MAX_SAMPLES);
    double *ts = malloc((S + 1) * sizeof *ts), *pts = malloc((S + 1) * 3 * sizeof *pts);
    if (!ts || !pts) {
        free(ts);
        free(pts);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    double c2p = 0, p2c = 0;
    for (size_t k = 0; k < pl->npieces; k++) {
        size_t a = pl->piece_start[k], b = k + 1 < pl->npieces ? pl->piece_start[k + 1] : pl->n;
        for (size_t i = a; i + 1 < b; i++) {
            double t0 = pl->t[i], t1 = pl->t[i + 1];
            const double *A = pl->xy + i * d, *B = pl->xy + (i + 1) * d;
            for (size_t j = 0; j <= S; j++) {
                ts[j] = j == S ? t1 : t0 + (t1 - t0) * (double)j / (double)S;
                conica__plot_point(s, ts[j], pts + 3 * j);
                double e = seg_d2(pts + 3 * j, A, B, pl->dim);
                c2p = e > c2p ? e : c2p;
            }
            for (int qn = 0; qn <= 4 && p2c_out; qn++) {
                double q[3] = {0, 0, 0};
                for (size_t c = 0; c < d; c++)
                    q[c] = A[c] + 0.25 * qn * (B[c] - A[c]);
                size_t bj = 0;
                double best = INFINITY;
                for (size_t j = 0; j <= S; j++) {
                    double e = 0;
                    for (size_t c = 0; c < d; c++)
                        e += (q[c] - pts[3 * j + c]) * (q[c] - pts[3 * j + c]);
                    if (e < best) {
                        best = e;
                        bj = j;
                    }
                }
                best = golden_min(s, ts[bj > 0 ? bj - 1 : 0], ts[bj < S ? bj + 1 : S], q,
                                  pl->dim, best);
                p2c = best > p2c ? best : p2c;
            }
        }
    }
    free(ts);
    free(pts);
    if (c2p_out)
        *c2p_out = sqrt(c2p);
    if (p2c_out)
        *p2c_out = sqrt(p2c);
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_plot_deviation(const conica_bspline *s, const conica_polyline *pl,
                                  size_t samples, double *curve_to_poly, double *poly_to_curve,
                                  conica_status *st)
{
    if (!s || !pl || samples < 1 || pl->n == 0 || pl->npieces == 0)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid spline, polyline or samples");
    int pd = conica_bspline_point_dim(s);
    if (pd != pl->dim)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "polyline dimension %d, spline %d",
                            pl->dim, pd);
    if (pl->t)
        return deviation_local(s, pl, samples, curve_to_poly, poly_to_curve, st);
    size_t p = (size_t)s->degree, spans = conica_bspline_bezier_count(s);
    if (samples > DEVIATION_MAX_SAMPLES / (spans + 1))
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "%zu samples on each of %zu pieces exceed the limit of %zu", samples,
                            spans, (size_t)DEVIATION_MAX_SAMPLES);
    size_t total = spans * samples + 1, d = (size_t)pl->dim;
    double *pts = malloc(total * 3 * sizeof *pts), *ts = malloc(total * sizeof *ts);
    size_t nseg_cap = pl->n;
    size_t *sa = malloc(nseg_cap * sizeof *sa), *sb = malloc(nseg_cap * sizeof *sb);
    double *boxes = malloc(4 * (total > nseg_cap ? total : nseg_cap) * sizeof *boxes);
    conica_code rc = CONICA_OK;
    grid gs = {{0, 0}, 0, 0, 0, 0, NULL, NULL}, gp = gs;
    if (!pts || !ts || !sa || !sb || !boxes) {
        rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        goto done;
    }
    size_t m = 0;
    for (size_t mu = p; mu < s->n; mu++) {
        double a = s->knots[mu], b = s->knots[mu + 1];
        if (!(a < b))
            continue;
        for (size_t i = 0; i < samples; i++) {
            ts[m] = a + (b - a) * (double)i / (double)samples;
            conica__plot_point(s, ts[m], pts + 3 * m);
            m++;
        }
    }
    ts[m] = s->knots[s->n];
    conica__plot_point(s, ts[m], pts + 3 * m);
    m++;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t j = 0; j < m; j++)
        for (size_t c = 0; c < 2; c++) {
            lo[c] = pts[3 * j + c] < lo[c] ? pts[3 * j + c] : lo[c];
            hi[c] = pts[3 * j + c] > hi[c] ? pts[3 * j + c] : hi[c];
        }
    for (size_t i = 0; i < pl->n; i++)
        for (size_t c = 0; c < 2; c++) {
            lo[c] = pl->xy[i * d + c] < lo[c] ? pl->xy[i * d + c] : lo[c];
            hi[c] = pl->xy[i * d + c] > hi[c] ? pl->xy[i * d + c] : hi[c];
        }
    /* segments of every piece (a one-point piece is a degenerate segment) */
    size_t nseg = 0;
    for (size_t k = 0; k < pl->npieces; k++) {
        size_t a = pl->piece_start[k], b = k + 1 < pl->npieces ? pl->piece_start[k + 1] : pl->n;
        if (b == a)
            continue;
        if (b == a + 1) {
            sa[nseg] = a;
            sb[nseg++] = a;
        }
        for (size_t i = a; i + 1 < b; i++) {
            sa[nseg] = i;
            sb[nseg++] = i + 1;
        }
    }
    if (curve_to_poly) {
        for (size_t i = 0; i < nseg; i++) {
            const double *A = pl->xy + sa[i] * d, *B = pl->xy + sb[i] * d;
            boxes[4 * i] = A[0] < B[0] ? A[0] : B[0];
            boxes[4 * i + 1] = A[0] < B[0] ? B[0] : A[0];
            boxes[4 * i + 2] = A[1] < B[1] ? A[1] : B[1];
            boxes[4 * i + 3] = A[1] < B[1] ? B[1] : A[1];
        }
        if (!grid_build(&gs, lo, hi, nseg, boxes)) {
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            goto done;
        }
        segctx sc = {pl, sa, sb};
        double c2p = 0;
        for (size_t j = 0; j < m; j++) {
            size_t w;
            double q[3] = {pts[3 * j], pts[3 * j + 1], pts[3 * j + 2]};
            double dd = grid_nearest(&gs, q, seg_item, &sc, &w);
            c2p = dd > c2p ? dd : c2p;
        }
        *curve_to_poly = sqrt(c2p);
    }
    if (poly_to_curve) {
        for (size_t j = 0; j < m; j++) {
            boxes[4 * j] = boxes[4 * j + 1] = pts[3 * j];
            boxes[4 * j + 2] = boxes[4 * j + 3] = pts[3 * j + 1];
        }
        if (!grid_build(&gp, lo, hi, m, boxes)) {
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            goto done;
        }
        ptctx pc = {pts, pl->dim};
        p2cctx qc = {s, &gp, &pc, ts, m, pl->dim};
        double p2c = 0;
        for (size_t i = 0; i < nseg; i++) {
            const double *A = pl->xy + sa[i] * d, *B = pl->xy + sb[i] * d;
            for (int qn = 0; qn < 4; qn++) {
                if (qn > 0 && sa[i] == sb[i])
                    break;
                double q[3] = {0, 0, 0};
                for (size_t c = 0; c < d; c++)
                    q[c] = A[c] + 0.25 * qn * (B[c] - A[c]);
                double best = p2c_query(&qc, q);
                p2c = best > p2c ? best : p2c;
            }
        }
        /* the last vertex of each piece is covered by the segments' ends
         * only through quarter points; check it explicitly */
        for (size_t k = 0; k < pl->npieces; k++) {
            size_t e = (k + 1 < pl->npieces ? pl->piece_start[k + 1] : pl->n);
            if (e == 0)
                continue;
            double best = p2c_query(&qc, pl->xy + (e - 1) * d);
            p2c = best > p2c ? best : p2c;
        }
        *poly_to_curve = sqrt(p2c);
    }
done:
    grid_free(&gs);
    grid_free(&gp);
    free(pts);
    free(ts);
    free(sa);
    free(sb);
    free(boxes);
    if (rc == CONICA_OK)
        conica__ok(st);
    return rc;
}

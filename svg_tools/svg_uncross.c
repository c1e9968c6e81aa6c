/* SPDX-License-Identifier: MIT */
/* New crossings of simplified subpaths (svgsmooth --simplify): the smoothed
 * polylines of one element are searched for proper crossings (a uniform
 * grid over their edges, each edge entered in the cells it passes through),
 * and each crossing that involves an arc of a simplified subpath is judged
 * against what was drawn: the input vertices around that arc (one kept
 * vertex further on each side) and, on the other side, the same input
 * piece or, for a subpath not simplified, its own polyline around the
 * crossing. Where the drawn pieces do not cross, the crossing is new and
 * the dropped input vertex nearest to it is marked to be kept; svg_geom.c
 * simplifies again with those kept and repeats. Called by svg_geom.c only;
 * calls libcore's exact orientation test. */
#include "svg_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cells per edge of the grid, and the cap on cell entries per edge: past
 * it (edges much longer than the cells) the grid is made coarser, at most
 * UNCROSS_COARSER times. */
#define UNCROSS_CELLS_PER_EDGE 2.0
/* A segment is entered in the cells within this fraction of a cell of it
 * (rounding at cell borders never loses a pair). */
#define UNCROSS_CELL_MARGIN 1e-6
#define UNCROSS_ENTRIES_PER_EDGE 8
#define UNCROSS_COARSER 6
/* Cap on the edge pairs tested, per edge and in all; past it the element
 * is not judged (the caller keeps every vertex of its simplified subpaths). */
#define UNCROSS_PAIRS_PER_EDGE 256
/* Cap on the edge pairs compared when judging one crossing against the
 * drawn pieces; past it the crossing counts as new (a vertex comes back). */
#define UNCROSS_JUDGE_PAIRS ((size_t)1 << 20)
/* Points of a polyline that is not simplified, each way from a crossing,
 * at most, taken as its drawn piece. */
#define UNCROSS_REACH 4096
/* Cap on the crossings judged in one element and round; past it the
 * element is not judged. */
#define UNCROSS_MAX_CROSSINGS ((size_t)1 << 16)

typedef struct edge_ref {
    size_t line, i; /* edge i of polyline `line`: point i to point i + 1 (mod n) */
} edge_ref;

typedef struct xpair {
    edge_ref e, f;
} xpair;

static int cmp_ref(const void *pa, const void *pb)
{
    const edge_ref *a = pa, *b = pb;
    if (a->line != b->line)
        return a->line < b->line ? -1 : 1;
    return a->i < b->i ? -1 : a->i > b->i;
}

static int cmp_pair(const void *pa, const void *pb)
{
    const xpair *a = pa, *b = pb;
    int c = cmp_ref(&a->e, &b->e);
    return c ? c : cmp_ref(&a->f, &b->f);
}

typedef struct grid {
    double x0, y0, cw, ch;
    size_t gx, gy;
} grid;

static size_t edge_count(const conica_path_polyline *L)
{
    return L->n < 2 ? 0 : L->closed ? L->n : L->n - 1;
}

static const double *pt_of(const conica_path_polyline *L, size_t i)
{
    return L->xy + 2 * (i % L->n);
}

/* Proper crossing of segments a-b and c-d (a single point inside both). */
static int proper(const double *a, const double *b, const double *c, const double *d)
{
    int k;
    for (k = 0; k < 2; k++) { /* boxes apart: no crossing */
        double lo1 = a[k] < b[k] ? a[k] : b[k], hi1 = a[k] < b[k] ? b[k] : a[k];
        double lo2 = c[k] < d[k] ? c[k] : d[k], hi2 = c[k] < d[k] ? d[k] : c[k];
        if (hi1 < lo2 || hi2 < lo1)
            return 0;
    }
    int o1 = conica__orient2d(a, b, c), o2 = conica__orient2d(a, b, d);
    int o3 = conica__orient2d(c, d, a), o4 = conica__orient2d(c, d, b);
    return o1 * o2 < 0 && o3 * o4 < 0;
}

/* The cells segment a-b passes through: for each column it spans, the rows
 * its y-extent covers within that column. Returns how many; with store,
 * ref goes to store[fill[cell]++], else with fill, fill[cell] counts. */
static size_t visit(const grid *g, const double *a, const double *b, size_t *fill, edge_ref *store,
                    edge_ref ref)
{
    size_t count = 0;
    double xa = fmin(a[0], b[0]), xb = fmax(a[0], b[0]);
    double c0 = floor((xa - g->x0) / g->cw - UNCROSS_CELL_MARGIN);
    double c1 = floor((xb - g->x0) / g->cw + UNCROSS_CELL_MARGIN), cx;
    c0 = fmax(c0, 0);
    c1 = fmin(c1, (double)g->gx - 1);
    for (cx = c0; cx <= c1; cx++) {
        double lo = g->x0 + cx * g->cw, hi = lo + g->cw, ylo, yhi, r0, r1, cy;
        if (!(xb > xa)) {
            ylo = fmin(a[1], b[1]);
            yhi = fmax(a[1], b[1]);
        } else {
            double t0 = (fmax(lo, xa) - a[0]) / (b[0] - a[0]);
            double t1 = (fmin(hi, xb) - a[0]) / (b[0] - a[0]);
            double y0 = a[1] + fmin(fmax(t0, 0), 1) * (b[1] - a[1]);
            double y1 = a[1] + fmin(fmax(t1, 0), 1) * (b[1] - a[1]);
            ylo = fmin(y0, y1);
            yhi = fmax(y0, y1);
        }
        r0 = fmax(floor((ylo - g->y0) / g->ch - UNCROSS_CELL_MARGIN), 0);
        r1 = fmin(floor((yhi - g->y0) / g->ch + UNCROSS_CELL_MARGIN), (double)g->gy - 1);
        for (cy = r0; cy <= r1; cy++) {
            size_t cell = (size_t)cy * g->gx + (size_t)cx;
            if (store)
                store[fill[cell]++] = ref;
            else if (fill)
                fill[cell]++;
            count++;
        }
    }
    return count;
}

/* The local index (arc) of polyline point i of subpath k: the segment or
 * sample edge it belongs to, counted from the subpath's first. */
static size_t arc_of(const conica_path *cp, const conica_path_polyline *L, size_t i)
{
    size_t first = cp->sub[L->subpath].first;
    return L->seg[i % L->n] >= first ? L->seg[i % L->n] - first : 0;
}

/* A simplified subpath's input vertices around kept arc j: from the kept
 * vertex before its start to the one after its end (vertex indices; a
 * wrapping list goes on past n). */
static void drawn_range(const conica_svg__simp *sm, size_t j, size_t *lo, size_t *hi)
{
    size_t nk = sm->nkeep;
    if (sm->wrap) {
        size_t a = (j + nk - 1) % nk, b = (j + 2) % nk;
        *lo = sm->keep[a];
        *hi = sm->keep[b];
        while (*hi <= *lo || (nk <= 3 && *hi < *lo + sm->n))
            *hi += sm->n; /* a small loop: all of it */
        if (*hi > *lo + sm->n)
            *hi = *lo + sm->n;
    } else {
        *lo = sm->keep[j > 0 ? j - 1 : 0];
        *hi = sm->keep[j + 2 < nk ? j + 2 : nk - 1];
    }
}

/* One side of a crossing, as drawn: points p[k], k = lo..hi of the list
 * (indices mod n when it wraps). */
typedef struct piece {
    const double *xy;
    size_t n, lo, hi;
    int wrap;
    const conica_path_polyline *L; /* not simplified: the polyline */
    size_t line;
} piece;

static const double *piece_pt(const piece *p, size_t k)
{
    return p->xy + 2 * (k % p->n);
}

/* Whether the drawn pieces cross (1), do not (0), or are too large to
 * compare (-1). Two pieces of one list that overlap are one piece, tested
 * against itself. */
static int pieces_cross(const piece *a, const piece *b)
{
    size_t i, j, na = a->hi - a->lo, nb = b->hi - b->lo;
    if (a->xy == b->xy && a->n == b->n) {
        size_t lo = a->lo < b->lo ? a->lo : b->lo, hi = a->hi > b->hi ? a->hi : b->hi;
        int overlap = !(a->hi < b->lo || b->hi < a->lo);
        if (a->wrap && hi - lo > a->n)
            overlap = 1, lo = 0, hi = a->n;
        if (overlap) {
            size_t ne = hi - lo;
            if (ne > 0 && ne * ne / 2 > UNCROSS_JUDGE_PAIRS)
                return -1;
            for (i = lo; i < hi; i++)
                for (j = i + 2; j < hi; j++)
                    if (proper(piece_pt(a, i), piece_pt(a, i + 1), piece_pt(a, j),
                               piece_pt(a, j + 1)))
                        return 1;
            return 0;
        }
    }
    if (na * nb > UNCROSS_JUDGE_PAIRS)
        return -1;
    for (i = a->lo; i < a->hi; i++)
        for (j = b->lo; j < b->hi; j++)
            if (proper(piece_pt(a, i), piece_pt(a, i + 1), piece_pt(b, j), piece_pt(b, j + 1)))
                return 1;
    return 0;
}

/* The drawn piece of edge e: a simplified subpath's input vertices around
 * its arc, else the polyline itself around the edge (its arc and the
 * neighbouring ones, at most UNCROSS_REACH points each way). */
static void piece_of(const conica_path *cp, const conica_path_result *r,
                     conica_svg__simp *const *simp, edge_ref e, piece *p)
{
    const conica_path_polyline *L = &r->lines[e.line];
    const conica_svg__simp *sm = simp[e.line];
    p->line = e.line;
    if (sm) {
        size_t j = arc_of(cp, L, e.i);
        if (j >= sm->nkeep)
            j = sm->nkeep - 1;
        p->xy = sm->xy;
        p->n = sm->n;
        p->wrap = sm->wrap;
        p->L = NULL;
        drawn_range(sm, j, &p->lo, &p->hi);
        return;
    }
    {
        size_t arc = arc_of(cp, L, e.i), k, lo = e.i, hi = e.i + 1, ne = edge_count(L);
        for (k = 0; k < UNCROSS_REACH && (L->closed || lo > 0); k++) {
            size_t prev = (lo + L->n - 1) % L->n, pa = arc_of(cp, L, prev);
            if (pa + 1 < arc || pa > arc + 1 || hi - (lo - 1) > ne)
                break;
            lo = L->closed && lo == 0 ? L->n - 1 : lo - 1;
            if (L->closed && lo > e.i) { /* wrapped: index upwards from here */
                hi += L->n;
                e.i += L->n;
            }
        }
        for (k = 0; k < UNCROSS_REACH && (L->closed || hi + 1 < L->n) && hi - lo < ne; k++) {
            size_t pa = arc_of(cp, L, hi + 1);
            if (pa + 1 < arc || pa > arc + 1)
                break;
            hi++;
        }
        p->xy = L->xy;
        p->n = L->n;
        p->wrap = L->closed;
        p->L = L;
        p->lo = lo;
        p->hi = hi;
    }
}

static int is_kept(const conica_svg__simp *sm, size_t v)
{
    size_t lo = 0, hi = sm->nkeep;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (sm->keep[mid] < v)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < sm->nkeep && sm->keep[lo] == v;
}

/* Mark the dropped vertex of sm's piece nearest to x (none dropped: 0). */
static size_t force_nearest(conica_svg__simp *sm, const piece *p, const double *x)
{
    size_t k, best = SIZE_MAX;
    double bd = HUGE_VAL;
    for (k = p->lo; k <= p->hi; k++) {
        size_t v = k % sm->n;
        double d;
        if (sm->force[v] || is_kept(sm, v))
            continue;
        d = hypot(sm->xy[2 * v] - x[0], sm->xy[2 * v + 1] - x[1]);
        if (d < bd) {
            bd = d;
            best = v;
        }
    }
    if (best == SIZE_MAX)
        return 0;
    sm->force[best] = 1;
    return 1;
}

/* Whether a simplified subpath dropped any vertex (else it is as drawn). */
static int dropped_any(const conica_svg__simp *sm)
{
    return sm && sm->nkeep < sm->n;
}

/* A crossing of edges e and f of the output: judged, and vertices marked. */
static size_t judge(const conica_path *cp, const conica_path_result *r,
                    conica_svg__simp *const *simp, edge_ref e, edge_ref f)
{
    piece pe, pf;
    const double *a = pt_of(&r->lines[e.line], e.i), *b = pt_of(&r->lines[e.line], e.i + 1);
    const double *c = pt_of(&r->lines[f.line], f.i), *d = pt_of(&r->lines[f.line], f.i + 1);
    double x[2];
    size_t marked = 0;
    piece_of(cp, r, simp, e, &pe);
    piece_of(cp, r, simp, f, &pf);
    if (pieces_cross(&pe, &pf) == 1)
        return 0; /* drawn so */
    {
        double ex = b[0] - a[0], ey = b[1] - a[1], fx = d[0] - c[0], fy = d[1] - c[1];
        double den = ex * fy - ey * fx;
        double t = den != 0 ? ((c[0] - a[0]) * fy - (c[1] - a[1]) * fx) / den : 0.5;
        x[0] = a[0] + t * ex;
        x[1] = a[1] + t * ey;
    }
    if (dropped_any(simp[e.line]))
        marked += force_nearest(simp[e.line], &pe, x);
    if (dropped_any(simp[f.line]))
        marked += force_nearest(simp[f.line], &pf, x);
    return marked;
}

conica_code conica_svg__uncross(const conica_path *cp, const conica_path_result *r,
                                conica_svg__simp *const *simp, size_t *marked, int *judged,
                                conica_status *st)
{
    size_t ne = 0, k, i, ncell, entries = 0, pairs = 0, cap;
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    size_t *start = NULL, *fill = NULL;
    edge_ref *cells = NULL;
    xpair *xs = NULL;
    size_t nx = 0, xcap = 0;
    grid g;
    int any = 0, round;
    *marked = 0;
    *judged = 1;
    for (k = 0; k < r->n; k++) {
        const conica_path_polyline *L = &r->lines[k];
        if (L->subpath != k || k >= cp->nsub)
            return conica__fail(st, CONICA_ERR_ARG, 0, 0, "uncross: polylines out of order");
        ne += edge_count(L);
        any |= dropped_any(simp[k]) && edge_count(L) > 0;
        for (i = 0; i < L->n; i++) {
            lo[0] = fmin(lo[0], L->xy[2 * i]);
            lo[1] = fmin(lo[1], L->xy[2 * i + 1]);
            hi[0] = fmax(hi[0], L->xy[2 * i]);
            hi[1] = fmax(hi[1], L->xy[2 * i + 1]);
        }
    }
    if (!any || ne < 2)
        return CONICA_OK;
    for (round = 0;; round++) {
        double w = hi[0] - lo[0], h = hi[1] - lo[1], want;
        if (!(w > 0))
            w = h > 0 ? h : 1;
        if (!(h > 0))
            h = w;
        want = fmax((double)ne * UNCROSS_CELLS_PER_EDGE / pow(4.0, round), 1);
        g.gx = (size_t)fmin(fmax(ceil(sqrt(want * w / h)), 1), want);
        g.gy = (size_t)fmin(fmax(ceil(want / (double)g.gx), 1), want);
        g.x0 = lo[0];
        g.y0 = lo[1];
        g.cw = w / (double)g.gx;
        g.ch = h / (double)g.gy;
        ncell = g.gx * g.gy;
        entries = 0;
        for (k = 0; k < r->n && entries <= UNCROSS_ENTRIES_PER_EDGE * ne; k++)
            for (i = 0; i < edge_count(&r->lines[k]); i++) {
                edge_ref e = {k, i};
                entries += visit(&g, pt_of(&r->lines[k], i), pt_of(&r->lines[k], i + 1), NULL,
                                 NULL, e);
            }
        if (entries <= UNCROSS_ENTRIES_PER_EDGE * ne)
            break;
        if (round == UNCROSS_COARSER) {
            *judged = 0;
            return CONICA_OK;
        }
    }
    start = calloc(ncell + 1, sizeof *start);
    fill = malloc((ncell + 1) * sizeof *fill);
    cells = malloc(entries * sizeof *cells);
    if (!start || !fill || !cells) {
        free(start);
        free(fill);
        free(cells);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    /* counts per cell (into start[cell + 1]), then the entries */
    for (k = 0; k < r->n; k++)
        for (i = 0; i < edge_count(&r->lines[k]); i++) {
            edge_ref e = {k, i};
            visit(&g, pt_of(&r->lines[k], i), pt_of(&r->lines[k], i + 1), start + 1, NULL, e);
        }
    for (i = 0; i < ncell; i++)
        start[i + 1] += start[i];
    memcpy(fill, start, (ncell + 1) * sizeof *fill);
    for (k = 0; k < r->n; k++)
        for (i = 0; i < edge_count(&r->lines[k]); i++) {
            edge_ref e = {k, i};
            visit(&g, pt_of(&r->lines[k], i), pt_of(&r->lines[k], i + 1), fill, cells, e);
        }
    /* the crossing pairs (a pair sharing several cells is found in each:
     * sorted and judged once) */
    cap = UNCROSS_PAIRS_PER_EDGE * ne + ((size_t)1 << 20);
    for (i = 0; i < ncell && *judged; i++) {
        size_t u, v;
        for (u = start[i]; u < start[i + 1] && *judged; u++)
            for (v = u + 1; v < start[i + 1]; v++) {
                edge_ref e = cells[u], f = cells[v];
                const conica_path_polyline *Le = &r->lines[e.line], *Lf = &r->lines[f.line];
                if (!dropped_any(simp[e.line]) && !dropped_any(simp[f.line]))
                    continue;
                if (++pairs > cap) {
                    *judged = 0;
                    break;
                }
                if (!proper(pt_of(Le, e.i), pt_of(Le, e.i + 1), pt_of(Lf, f.i), pt_of(Lf, f.i + 1)))
                    continue;
                if (nx == xcap) {
                    size_t nc = xcap ? 2 * xcap : 64;
                    xpair *t = nx < UNCROSS_MAX_CROSSINGS ? realloc(xs, nc * sizeof *xs) : NULL;
                    if (!t) {
                        *judged = 0; /* too many to judge: none taken */
                        break;
                    }
                    xs = t;
                    xcap = nc;
                }
                if (cmp_ref(&e, &f) > 0) {
                    edge_ref t = e;
                    e = f;
                    f = t;
                }
                xs[nx].e = e;
                xs[nx++].f = f;
            }
    }
    if (*judged && nx) {
        qsort(xs, nx, sizeof *xs, cmp_pair);
        for (i = 0; i < nx; i++)
            if (i == 0 || cmp_pair(&xs[i - 1], &xs[i]) != 0)
                *marked += judge(cp, r, simp, xs[i].e, xs[i].f);
    }
    free(xs);
    free(start);
    free(fill);
    free(cells);
    return CONICA_OK;
}

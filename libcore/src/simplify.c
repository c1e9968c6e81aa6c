/* SPDX-License-Identifier: MIT */
/* Fewer samples for traced outlines (conica/simplify.h): Douglas–Peucker
 * seeds, then the subdivision itself decides. Each round smooths the kept
 * vertices exactly as the tools will (conica_path_samples() and
 * conica_path_smooth(): normals estimated from the samples, corners split,
 * the CONIS subdivision of Bügel, Romani and Kosinka), measures every
 * original vertex against the piece of the smoothed polyline between its
 * two kept neighbours (a piece, not the whole curve: stricter, and linear
 * work) and puts back the worst vertex of each arc that strays. The
 * smoothed curve is not the chord polygon, so the seeds alone do not decide:
 * a kept vertex moves the curve on both sides of it. */
#include "conica/simplify.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define SIMPLIFY_MAX_ROUNDS 1024
#define SIMPLIFY_DEFAULT_WORK ((size_t)1 << 24)
/* Corners are judged at the scale of the tolerance: the turn at a vertex is
 * measured towards the nearest vertices farther than this many tolerances
 * on each side (jitter within the tolerance makes no corner), at most
 * SIMPLIFY_CORNER_WINDOW vertices away; with the tolerance below the
 * spacing of the vertices it is conica/path.h's rule on the neighbours. */
#define SIMPLIFY_CORNER_SCALE 2.0
/* Dropping a vertex is judged on this many kept vertices on each side of
 * it, measuring SIMPLIFY_REACH arcs on each side; the whole curve is
 * checked again at the end. */
#define SIMPLIFY_WINDOW 10
#define SIMPLIFY_REACH 4
#define SIMPLIFY_CORNER_WINDOW 256

conica_simplify_settings conica_simplify_defaults(void)
{
    conica_simplify_settings s;
    s.tolerance = 0.0;
    s.rel_tolerance = CONICA_PATH_DEFAULT_REL_TOLERANCE;
    s.path = conica_path_defaults();
    s.max_rounds = CONICA_SIMPLIFY_DEFAULT_ROUNDS;
    s.max_work = SIMPLIFY_DEFAULT_WORK;
    s.keep_mask = NULL;
    return s;
}

typedef struct sctx {
    const double *P;        /* m distinct consecutive vertices, interleaved */
    size_t m;
    int closed;
    const conica_path_settings *ps;
    double tol;
    unsigned char *fixed;   /* corners and open ends: always kept */
    unsigned char *forced;  /* the caller's keep_mask: always kept, no corner */
    unsigned char *kept;
    size_t *K, nk;          /* kept vertices, ascending (or, in check_near, its window) */
    size_t *Kall;           /* the array gather() fills */
    size_t win[2 * SIMPLIFY_WINDOW + 2]; /* check_near's window of kept vertices */
    size_t nkept;           /* kept vertices in all */
    double *kxy;            /* their points */
    size_t *pos;            /* output index of kept vertex j in the smoothed polyline */
    size_t *add;            /* per arc: vertex to insert, or SIZE_MAX */
    double deviation;       /* largest distance measured in the last check */
    size_t work;            /* vertex measurements so far */
} sctx;

/* Turn (radians, 0..pi) from direction a->b to direction b->c. */
static double turn_at(const double *a, const double *b, const double *c)
{
    double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
    return fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy));
}

static double seg_dist(const double *p, const double *a, const double *b)
{
    double ex = b[0] - a[0], ey = b[1] - a[1], l2 = ex * ex + ey * ey, t = 0;
    if (l2 > 0) {
        t = ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / l2;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
    }
    return hypot(p[0] - a[0] - t * ex, p[1] - a[1] - t * ey);
}

/* The vertices at which the turn towards the nearest vertices farther than
 * `reach` on each side is above `angle`, and the largest such turn among
 * the vertices between those two (one corner, not the run of vertices
 * around it that see it too). fixed[i] set for each; returns how many.
 * turn[] is scratch of m doubles. */
static size_t find_corners(const double *P, size_t m, int closed, double angle, double reach,
                           unsigned char *fixed, double *turn, size_t *lo, size_t *hi)
{
    size_t i, k, count = 0, wmax = closed ? (m - 1) / 2 : m;
    if (wmax > SIMPLIFY_CORNER_WINDOW)
        wmax = SIMPLIFY_CORNER_WINDOW;
    for (i = 0; i < m; i++) {
        size_t b = 1, f = 1;
        turn[i] = 0;
        lo[i] = hi[i] = 0;
        if (!closed && (i == 0 || i + 1 == m))
            continue;
        /* k steps back / forward: index (i - k) mod m, (i + k) mod m */
        while (b < wmax && (closed || b < i) &&
               hypot(P[2 * ((i + m - b) % m)] - P[2 * i], P[2 * ((i + m - b) % m) + 1] - P[2 * i + 1]) <= reach)
            b++;
        while (f < wmax && (closed || i + f + 1 < m) &&
               hypot(P[2 * ((i + f) % m)] - P[2 * i], P[2 * ((i + f) % m) + 1] - P[2 * i + 1]) <= reach)
            f++;
        lo[i] = b;
        hi[i] = f;
        turn[i] = turn_at(P + 2 * ((i + m - b) % m), P + 2 * i, P + 2 * ((i + f) % m));
    }
    for (i = 0; i < m; i++) {
        int best = turn[i] > angle;
        for (k = 1; best && k < lo[i]; k++) {
            size_t j = (i + m - k) % m;
            if (turn[j] >= turn[i]) /* ties: the earlier vertex */
                best = 0;
        }
        for (k = 1; best && k < hi[i]; k++) {
            size_t j = (i + k) % m;
            if (turn[j] > turn[i])
                best = 0;
        }
        if (best) {
            fixed[i] = 1;
            count++;
        }
    }
    return count;
}

/* Douglas–Peucker on the vertices strictly between a and b (indices mod m,
 * b reached from a going forward): keep the farthest from the chord while
 * it is over the tolerance. Explicit stack of at most m ranges. */
static int seed_dp(sctx *c, size_t a, size_t b, size_t *stack)
{
    size_t top = 0, m = c->m;
    stack[top++] = a;
    stack[top++] = b < a || (c->closed && b == a) ? b + m : b;
    while (top) {
        size_t hi = stack[--top], lo = stack[--top], i, far = SIZE_MAX;
        double best = c->tol;
        const double *pa = c->P + 2 * (lo % m), *pb = c->P + 2 * (hi % m);
        for (i = lo + 1; i < hi; i++) {
            double d = seg_dist(c->P + 2 * (i % m), pa, pb);
            if (d > best) {
                best = d;
                far = i;
            }
        }
        if (far == SIZE_MAX)
            continue;
        c->kept[far % m] = 1;
        if (top + 4 > 2 * m + 2)
            return 0;
        stack[top++] = lo;
        stack[top++] = far;
        stack[top++] = far;
        stack[top++] = hi;
    }
    return 1;
}

/* The kept vertices, ascending, into c->K (c->nk of them). */
static void gather(sctx *c)
{
    size_t i, nk = 0;
    c->K = c->Kall;
    for (i = 0; i < c->m; i++)
        if (c->kept[i])
            c->K[nk++] = i;
    c->nk = nk;
    c->nkept = nk;
}

/* Smooth `cnt` consecutive kept vertices from kept position `from` (mod nk;
 * a closed run when `closed`) and measure the arcs from local positions
 * `alo` to `ahi` (exclusive): c->add[global arc] gets the vertex to insert
 * there, or stays SIZE_MAX. Returns CONICA_OK, CONICA_ERR_DEGENERATE when
 * the run cannot be judged (the caller keeps more), or an error. */
static conica_code measure(sctx *c, size_t from, size_t cnt, int closed, size_t alo, size_t ahi,
                           conica_status *st)
{
    conica_path p;
    conica_path_result r;
    conica_code rc;
    size_t i, t, m = c->m, nk = c->nk;
    const conica_path_polyline *L;
    if (cnt < (closed ? 3u : 2u))
        return CONICA_ERR_DEGENERATE;
    for (t = 0; t < cnt; t++) {
        size_t v = c->K[(from + t) % nk];
        c->kxy[2 * t] = c->P[2 * v];
        c->kxy[2 * t + 1] = c->P[2 * v + 1];
    }
    conica_path_init(&p);
    conica_path_result_init(&r);
    rc = conica_path_samples(&p, c->kxy, NULL, cnt, closed, 0, st);
    if (rc == CONICA_OK && (p.nsub != 1 || p.sub[0].n != cnt))
        rc = CONICA_ERR_DEGENERATE; /* kept vertices merged: judged with more */
    if (rc == CONICA_OK)
        rc = conica_path_smooth(&p, c->ps, &r, st);
    if (rc != CONICA_OK || r.n != 1) {
        conica_path_result_free(&r);
        conica_path_free(&p);
        return rc == CONICA_ERR_NOMEM || rc == CONICA_ERR_LIMIT ? rc : CONICA_ERR_DEGENERATE;
    }
    L = &r.lines[0];
    for (t = 0; t < cnt; t++)
        c->pos[t] = SIZE_MAX;
    for (i = 0; i < L->n; i++)
        if ((L->flags[i] & CONICA_PATH_PT_VERTEX) && L->seg[i] < cnt && c->pos[L->seg[i]] == SIZE_MAX)
            c->pos[L->seg[i]] = i;
    for (t = 0; t < cnt; t++)
        if (c->pos[t] == SIZE_MAX)
            rc = CONICA_ERR_DEGENERATE;
    for (t = alo; t < ahi && rc == CONICA_OK; t++) {
        size_t g = (from + t) % nk, a = c->K[g], b = g + 1 < nk ? c->K[g + 1] : c->K[0] + m;
        if (b <= a)
            b += m; /* check_near's window of a closed curve wraps */
        size_t pa = c->pos[t], pb = c->pos[t + 1 < cnt ? t + 1 : 0];
        size_t worst = SIZE_MAX, k;
        double wd = c->tol;
        if (pb <= pa)
            pb += L->n; /* a closed polyline may start at any corner */
        for (i = a + 1; i < b; i++) {
            const double *q = c->P + 2 * (i % m);
            double d = HUGE_VAL;
            for (k = pa; k < pb; k++)
                d = fmin(d, seg_dist(q, L->xy + 2 * (k % L->n), L->xy + 2 * ((k + 1) % L->n)));
            c->work += pb - pa + 1;
            c->deviation = fmax(c->deviation, d);
            if (d > wd) {
                wd = d;
                worst = i % m;
            }
        }
        if (worst == SIZE_MAX && b > a + 1) {
            /* and the other way: the smoothed arc within the tolerance of
             * the traced polygon it replaces (a long edge must not bulge
             * out of it); where it strays, the vertex there comes back */
            for (k = pa; k + 1 < pb && worst == SIZE_MAX; k++) {
                const double *q = L->xy + 2 * ((k + 1) % L->n);
                double d = HUGE_VAL;
                size_t near = a + (b - a) / 2;
                for (i = a; i < b; i++) {
                    double e = seg_dist(q, c->P + 2 * (i % m), c->P + 2 * ((i + 1) % m));
                    if (e < d) {
                        d = e;
                        near = i > a ? i : i + 1;
                    }
                }
                c->work += b - a;
                if (d > c->tol)
                    worst = near % m;
            }
        }
        c->add[g] = worst;
    }
    conica_path_result_free(&r);
    conica_path_free(&p);
    if (rc != CONICA_OK)
        return rc;
    /* corners: the kept polygon turns sharply exactly at the input's corners
     * (conica_path_smooth() splits there by the same rule) */
    for (t = alo; t <= ahi && t < cnt && c->ps->corner_angle < M_PI; t++) {
        size_t g = (from + t) % nk, v = c->K[g], pg = (g + nk - 1) % nk, ng = (g + 1) % nk;
        size_t near[2], arcs[2], k;
        int sharp;
        if ((!closed && (t == 0 || t + 1 == cnt)) || (!c->closed && (g == 0 || g + 1 == nk)))
            continue;
        sharp = turn_at(c->P + 2 * c->K[pg], c->P + 2 * v, c->P + 2 * c->K[ng]) >
                c->ps->corner_angle;
        if (sharp == (c->fixed[v] != 0))
            continue;
        /* a lost corner gets its neighbours back; a new one, the middles */
        arcs[0] = pg;
        arcs[1] = g;
        near[0] = (v + m - 1) % m;
        near[1] = (v + 1) % m;
        for (k = 0; k < 2; k++) {
            size_t arc = arcs[k], a = c->K[arc];
            size_t b = arc + 1 < nk ? c->K[arc + 1] : c->K[0] + m;
            if (b <= a)
                b += m;
            if (b < a + 2 || c->add[arc] != SIZE_MAX)
                continue; /* no vertex between them, or one already coming */
            c->add[arc] = c->fixed[v] ? near[k] : (a + (b - a) / 2) % m;
        }
    }
    return CONICA_OK;
}

/* Smooth all kept vertices and measure every arc. */
static conica_code check(sctx *c, conica_status *st)
{
    size_t j;
    gather(c);
    for (j = 0; j < c->nk; j++)
        c->add[j] = SIZE_MAX;
    c->deviation = 0;
    if (c->nk < (c->closed ? 3u : 2u))
        return CONICA_ERR_DEGENERATE;
    return measure(c, 0, c->nk, c->closed, 0, c->closed ? c->nk : c->nk - 1, st);
}

/* After kept vertex v was dropped: smooth only the SIMPLIFY_WINDOW kept
 * vertices on each side of the gap and measure the SIMPLIFY_REACH arcs on
 * each side (the subdivision is local: a kept vertex moves the curve only
 * a few arcs away, through the normals estimated from its neighbours), or
 * everything when there are few. The window is found by walking from v,
 * so each try costs the span of its window, not the whole curve: over a
 * dropping pass every vertex is walked over by about 2 SIMPLIFY_WINDOW
 * tries (linear work where a gather() per try was quadratic). */
static conica_code check_near(sctx *c, size_t v, conica_status *st)
{
    size_t j, m = c->m, nb = 0, na = 0, nk, from, cnt, alo, ahi;
    size_t back[SIMPLIFY_WINDOW];
    if (c->nkept <= 2 * SIMPLIFY_WINDOW + 2)
        return check(c, st);
    /* W kept vertices before the gap (nearest first) and W from it on */
    for (j = 1; j < m && nb < SIMPLIFY_WINDOW; j++) {
        size_t i;
        if (!c->closed && j > v)
            break;
        i = (v + m - j) % m;
        if (c->kept[i])
            back[nb++] = i;
    }
    for (j = 0; j < nb; j++)
        c->win[j] = back[nb - 1 - j];
    for (j = 1; j < m && na < SIMPLIFY_WINDOW; j++) {
        size_t i;
        if (!c->closed && v + j >= m)
            break;
        i = (v + j) % m;
        if (c->kept[i])
            c->win[nb + na++] = i;
    }
    nk = nb + na;
    c->K = c->win;
    c->nk = nk;
    for (j = 0; j < nk; j++)
        c->add[j] = SIZE_MAX;
    c->deviation = 0;
    from = 0;
    cnt = nk;
    if (c->closed) {
        alo = SIMPLIFY_WINDOW - SIMPLIFY_REACH;
        ahi = SIMPLIFY_WINDOW + SIMPLIFY_REACH - 1;
    } else {
        /* q: the window's first kept vertex after the gap; the curve's
         * ends (its first and last vertex, always kept) bound the arcs
         * measured, the window's own ends are not the curve's */
        size_t q = nb, mlo = q >= SIMPLIFY_REACH ? q - SIMPLIFY_REACH : 0;
        size_t mhi = q + SIMPLIFY_REACH - 1 < nk - 1 ? q + SIMPLIFY_REACH - 1 : nk - 1;
        alo = mlo;
        ahi = mhi;
        if (c->win[0] > 0 && alo == 0)
            alo = 1;
        if (c->win[nk - 1] + 1 < m && ahi + 1 >= cnt)
            ahi = cnt - 2;
    }
    return measure(c, from, cnt, 0, alo, ahi, st);
}

static int passed(const sctx *c)
{
    size_t j;
    for (j = 0; j < c->nk; j++)
        if (c->add[j] != SIZE_MAX)
            return 0;
    return 1;
}

conica_code conica_simplify(const double *xy, size_t n, int closed,
                            const conica_simplify_settings *s, size_t *keep, size_t *nkeep,
                            conica_simplify_info *info, conica_status *st)
{
    conica_simplify_settings def = conica_simplify_defaults();
    conica_simplify_info inf;
    sctx c;
    size_t i, m = 0, *u = NULL, *stack = NULL, nfixed = 0, rounds = 0;
    double *P = NULL, lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    conica_code rc = CONICA_OK;
    int all = 0, dropping_done = 0;
    if (!xy || !keep || !nkeep)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_simplify: NULL argument");
    if (!s)
        s = &def;
    if (n < 2)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_simplify: fewer than 2 points");
    if (n > CONICA_SIMPLIFY_MAX_POINTS)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "conica_simplify: more than %zu points", CONICA_SIMPLIFY_MAX_POINTS);
    if (!(s->tolerance >= 0) || !(s->rel_tolerance >= 0) || s->max_rounds < 1 ||
        s->max_rounds > SIMPLIFY_MAX_ROUNDS || (s->tolerance == 0 && !(s->rel_tolerance > 0)))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "conica_simplify: tolerance >= 0, rel_tolerance > 0 when it is 0, "
                            "rounds in 1..%d", SIMPLIFY_MAX_ROUNDS);
    for (i = 0; i < 2 * n; i++)
        if (!isfinite(xy[i]))
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, i / 2,
                                "conica_simplify: point %zu is not finite", i / 2 + 1);
    memset(&c, 0, sizeof c);
    memset(&inf, 0, sizeof inf);
    u = malloc(n * sizeof *u);
    P = malloc(2 * n * sizeof *P);
    c.fixed = calloc(n, 1);
    c.forced = calloc(n, 1);
    c.kept = calloc(n, 1);
    c.K = c.Kall = malloc(n * sizeof *c.K);
    c.kxy = malloc(2 * n * sizeof *c.kxy);
    c.pos = malloc(n * sizeof *c.pos);
    c.add = malloc(n * sizeof *c.add);
    stack = malloc((2 * n + 2) * sizeof *stack);
    if (!u || !P || !c.fixed || !c.forced || !c.kept || !c.K || !c.kxy || !c.pos || !c.add || !stack) {
        rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        goto done;
    }
    /* distinct consecutive vertices (as conica_path_samples() merges them) */
    for (i = 0; i < n; i++) {
        if (m && xy[2 * i] == P[2 * (m - 1)] && xy[2 * i + 1] == P[2 * (m - 1) + 1]) {
            if (s->keep_mask && s->keep_mask[i])
                c.forced[m - 1] = 1; /* a repeat: its first copy */
            continue;
        }
        c.forced[m] = s->keep_mask && s->keep_mask[i];
        u[m] = i;
        P[2 * m] = xy[2 * i];
        P[2 * m + 1] = xy[2 * i + 1];
        lo[0] = fmin(lo[0], xy[2 * i]);
        lo[1] = fmin(lo[1], xy[2 * i + 1]);
        hi[0] = fmax(hi[0], xy[2 * i]);
        hi[1] = fmax(hi[1], xy[2 * i + 1]);
        m++;
    }
    if (closed && m > 1 && P[0] == P[2 * (m - 1)] && P[1] == P[2 * (m - 1) + 1]) {
        m--;
        c.forced[0] |= c.forced[m]; /* the closing copy of the first vertex */
    }
    inf.tolerance = s->tolerance > 0 ? s->tolerance
                                      : s->rel_tolerance * hypot(hi[0] - lo[0], hi[1] - lo[1]);
    c.P = P;
    c.m = m;
    c.closed = closed != 0;
    c.ps = &s->path;
    c.tol = inf.tolerance;
    if (m <= (closed ? 3u : 2u) || !(c.tol > 0)) {
        all = 1;
        goto out;
    }
    /* fixed: the open ends and the corners (conica/path.h's rule, at the
     * scale of the tolerance) */
    if (s->path.corner_angle < M_PI) {
        /* scratch borrowed: kxy holds 2m doubles, pos and add m sizes each */
        nfixed = find_corners(P, m, c.closed, s->path.corner_angle,
                              SIMPLIFY_CORNER_SCALE * c.tol, c.fixed, c.kxy, c.pos, c.add);
    }
    if (!closed) {
        c.fixed[0] = c.fixed[m - 1] = 1;
        nfixed += 2;
    }
    memcpy(c.kept, c.fixed, m);
    for (i = 0; i < m; i++)
        c.kept[i] |= c.forced[i];
    if (nfixed == 0) {
        /* a smooth closed curve: seeded at its first vertex and the one
         * farthest from it */
        size_t far = 1;
        double best = -1;
        for (i = 1; i < m; i++) {
            double d = hypot(P[2 * i] - P[0], P[2 * i + 1] - P[1]);
            if (d > best) {
                best = d;
                far = i;
            }
        }
        c.kept[0] = c.kept[far] = 1;
    }
    {
        size_t first = SIZE_MAX, prev = SIZE_MAX;
        for (i = 0; i < m; i++)
            if (c.kept[i]) {
                if (prev != SIZE_MAX && !seed_dp(&c, prev, i, stack))
                    all = 1;
                if (first == SIZE_MAX)
                    first = i;
                prev = i;
            }
        if (closed && !seed_dp(&c, prev, first, stack))
            all = 1;
    }
    {
        /* a closed curve needs three vertices */
        size_t nk = 0, first = SIZE_MAX;
        for (i = 0; i < m; i++)
            if (c.kept[i]) {
                nk++;
                first = first == SIZE_MAX ? i : first;
            }
        if (closed && nk < 3) {
            c.kept[(first + m / 3) % m] = 1;
            c.kept[(first + 2 * m / 3) % m] = 1;
        }
    }
    for (;;) {
        /* insertion rounds */
        while (!all) {
            size_t j;
            rc = check(&c, st);
            if (rc == CONICA_ERR_DEGENERATE) {
                all = 1;
                rc = CONICA_OK;
                break;
            }
            if (rc != CONICA_OK)
                goto done;
            if (passed(&c))
                break;
            if (++rounds > (size_t)s->max_rounds) {
                all = 1;
                break;
            }
            for (j = 0; j < c.nk; j++)
                if (c.add[j] != SIZE_MAX)
                    c.kept[c.add[j]] = 1;
        }
        if (all || dropping_done)
            break;
        inf.deviation = c.deviation;
        /* dropping pass: single vertices whose removal still passes near
         * them; then the rounds again check the whole curve */
        dropping_done = 1;
        for (i = 0; i < m && c.work < s->max_work; i++) {
            if (!c.kept[i] || c.fixed[i] || c.forced[i])
                continue;
            c.kept[i] = 0;
            c.nkept--;
            rc = check_near(&c, i, st);
            if (rc == CONICA_ERR_NOMEM || rc == CONICA_ERR_LIMIT)
                goto done;
            if (rc == CONICA_OK && passed(&c)) {
                inf.dropped++;
            } else {
                c.kept[i] = 1;
                c.nkept++;
            }
            rc = CONICA_OK;
        }
    }
    inf.deviation = c.deviation;
out:
    *nkeep = 0;
    for (i = 0; i < m; i++)
        if (all || c.kept[i])
            keep[(*nkeep)++] = u[i];
    inf.kept = *nkeep;
    inf.corners = nfixed;
    inf.rounds = rounds;
    inf.kept_all = all;
    if (all)
        inf.deviation = 0;
    if (info)
        *info = inf;
    conica__ok(st);
done:
    free(u);
    free(P);
    free(c.fixed);
    free(c.forced);
    free(c.kept);
    free(c.Kall);
    free(c.kxy);
    free(c.pos);
    free(c.add);
    free(stack);
    return rc;
}

/* SPDX-License-Identifier: MIT */
/* DXF pieces joined into closed contours: CAD files draw an outline as
 * separate LINEs, ARCs, SPLINEs and open polylines that meet end to end,
 * in any order and direction. Ends within the gap tolerance are joined
 * (the next piece starts exactly where the last ended, so a join moves a
 * point by at most the gap); nearest end first; an outline closes when its
 * end comes back within the gap of its start. What does not close is an
 * error naming where it stops, or (CONICA_DXF_OPEN_CLOSE) closed by a
 * straight edge with a warning. Calls path only. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dxf_internal.h"
#include "internal.h"

typedef struct endpt {
    double x, y;
    size_t piece;
    int end; /* 0: start, 1: end */
} endpt;

typedef struct link {
    size_t piece;
    int rev;
} link;

typedef struct chainer {
    const conica__dxf_geom *g;
    const conica__dxf_chain_opts *o;
    endpt *ep;      /* sorted by x */
    size_t nep;
    unsigned char *used;
    link *chain;    /* the outline being built, head at chain[head] */
    size_t head, len, cap;
} chainer;

static const double *seg_pt(const conica__dxf_geom *g, size_t seg, int k)
{
    return g->pt + 3 * (g->sg[seg].pt + (size_t)k);
}

static const double *piece_end(const conica__dxf_geom *g, size_t p, int end)
{
    const conica__dxf_piece *pc = &g->pc[p];
    if (!end)
        return seg_pt(g, pc->seg, 0);
    size_t s = pc->seg + pc->nseg - 1;
    return seg_pt(g, s, g->sg[s].degree);
}

static int cmp_x(const void *a, const void *b)
{
    const endpt *p = a, *q = b;
    return p->x < q->x ? -1 : p->x > q->x ? 1 : (p->piece > q->piece) - (p->piece < q->piece);
}

/* The nearest free end within the gap of (x, y) in `group`: its index in
 * ep, or nep. */
static size_t nearest(const chainer *c, double x, double y, size_t group, double gap)
{
    size_t lo = 0, hi = c->nep, best = c->nep;
    double bd = INFINITY;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (c->ep[mid].x < x - gap)
            lo = mid + 1;
        else
            hi = mid;
    }
    for (size_t i = lo; i < c->nep && c->ep[i].x <= x + gap; i++) {
        const endpt *e = &c->ep[i];
        if (c->used[e->piece] || c->g->pc[e->piece].group != group)
            continue;
        double d = hypot(e->x - x, e->y - y);
        if (d <= gap && d < bd) {
            bd = d;
            best = i;
        }
    }
    return best;
}

/* The chain as a ring buffer would be overkill: it grows at both ends in
 * an array twice the pieces' count, the head starting in the middle. */
static const double *chain_point(const chainer *c, int tail)
{
    const link *l = tail ? &c->chain[c->head + c->len - 1] : &c->chain[c->head];
    /* the tail of a forward piece is its end; of a reversed one its start */
    return piece_end(c->g, l->piece, tail ? !l->rev : l->rev);
}

static int is_open_piece(const conica__dxf_geom *g, size_t p, double gap)
{
    const conica__dxf_piece *pc = &g->pc[p];
    if (pc->closed)
        return 0;
    const double *a = piece_end(g, p, 0), *b = piece_end(g, p, 1);
    /* a single straight segment never closes on itself */
    if (pc->nseg == 1 && g->sg[pc->seg].degree == 1)
        return 1;
    return !(hypot(a[0] - b[0], a[1] - b[1]) <= gap);
}

/* Emit the current chain into the path, closed: its last segment ends
 * exactly at its start when it came back there within the gap (snap),
 * else conica_path_close() draws the straight edge back. */
static conica_code emit(const chainer *c, int snap, conica_path *path, conica_status *st)
{
    const conica__dxf_geom *g = c->g;
    const double *s = chain_point(c, 0);
    double x0 = s[0], y0 = s[1];
    conica_code rc = conica_path_move_to(path, x0, y0, c->g->pc[c->chain[c->head].piece].line, st);
    for (size_t k = 0; k < c->len && rc == CONICA_OK; k++) {
        const link *l = &c->chain[c->head + k];
        const conica__dxf_piece *pc = &g->pc[l->piece];
        for (size_t j = 0; j < pc->nseg && rc == CONICA_OK; j++) {
            size_t sg = l->rev ? pc->seg + pc->nseg - 1 - j : pc->seg + j;
            int d = g->sg[sg].degree;
            double ctrl[2 * (CONICA_PATH_MAX_DEGREE + 1)], w[CONICA_PATH_MAX_DEGREE + 1];
            int rational = 0;
            for (int i = 0; i <= d; i++) {
                const double *q = seg_pt(g, sg, l->rev ? d - i : i);
                if (i > 0) {
                    ctrl[2 * (i - 1)] = q[0];
                    ctrl[2 * (i - 1) + 1] = q[1];
                }
                w[i] = q[2];
                rational |= q[2] != 1.0;
            }
            if (snap && k + 1 == c->len && j + 1 == pc->nseg) { /* back to the start exactly */
                ctrl[2 * (d - 1)] = x0;
                ctrl[2 * (d - 1) + 1] = y0;
            }
            if (d == 1)
                rc = conica_path_line_to(path, ctrl[0], ctrl[1], pc->line, st);
            else
                rc = conica_path_bezier_to(path, d, ctrl, rational ? w : NULL, pc->line, st);
        }
    }
    if (rc == CONICA_OK)
        rc = conica_path_close(path, st);
    return rc;
}

static const char *layer_of(const chainer *c, size_t piece)
{
    return c->o->layer_names ? c->o->layer_names[c->g->pc[piece].layer] : "0";
}

/* Where an open outline stops, as an error or (OPEN_CLOSE) a warning. */
static conica_code open_outline(chainer *c, conica_status *st)
{
    const link *l = &c->chain[c->head + c->len - 1];
    const conica__dxf_piece *pc = &c->g->pc[l->piece];
    const double *t = chain_point(c, 1), *h = chain_point(c, 0);
    double best = INFINITY;
    for (size_t i = 0; i < c->nep; i++) {
        const endpt *e = &c->ep[i];
        int mine = 0;
        for (size_t k = 0; k < c->len && !mine; k++)
            mine = c->chain[c->head + k].piece == e->piece;
        if (!mine)
            best = fmin(best, hypot(e->x - t[0], e->y - t[1]));
    }
    char near[96];
    if (isfinite(best))
        snprintf(near, sizeof near, "the nearest other end is %.6g away", best);
    else
        snprintf(near, sizeof near, "no other open end");
    if (c->o->open_mode == CONICA_DXF_OPEN_ERROR)
        return conica__fail(st, CONICA_ERR_PARSE, pc->line, l->piece,
                            "an outline does not close: it stops at (%.9g, %.9g), an end of %s%s%s "
                            "on layer '%.60s', %.6g from where it starts; %s (gap tolerance %.3g)",
                            t[0], t[1], pc->type, pc->handle[0] ? " handle " : "", pc->handle,
                            layer_of(c, l->piece), hypot(t[0] - h[0], t[1] - h[1]), near,
                            c->o->gap);
    if (c->o->warn) {
        char m[320];
        const conica__dxf_piece *p0 = &c->g->pc[c->chain[c->head].piece];
        snprintf(m, sizeof m,
                 "an outline from %s at line %zu does not close: closed by a straight edge of "
                 "length %.6g from (%.9g, %.9g) to (%.9g, %.9g)",
                 p0->type, p0->line, hypot(t[0] - h[0], t[1] - h[1]), t[0], t[1], h[0], h[1]);
        c->o->warn(c->o->warn_ctx, pc->line, m);
    }
    return CONICA_OK;
}

/* Grow the chain at its tail (tail = 1) or head by the nearest free end. */
static int extend(chainer *c, int tail, size_t group)
{
    const double *p = chain_point(c, tail);
    size_t i = nearest(c, p[0], p[1], group, c->o->gap);
    if (i == c->nep)
        return 0;
    const endpt *e = &c->ep[i];
    link l;
    l.piece = e->piece;
    /* at the tail the matching end comes first; at the head it comes last */
    l.rev = tail ? e->end == 1 : e->end == 0;
    c->used[e->piece] = 1;
    if (tail)
        c->chain[c->head + c->len] = l;
    else
        c->chain[--c->head] = l;
    c->len++;
    return 1;
}

static int closes(const chainer *c)
{
    const double *a = chain_point(c, 0), *b = chain_point(c, 1);
    if (c->len == 1 && !is_open_piece(c->g, c->chain[c->head].piece, c->o->gap))
        return 1;
    return c->len > 1 && hypot(a[0] - b[0], a[1] - b[1]) <= c->o->gap;
}

conica_code conica__dxf_chain(const conica__dxf_geom *g, const conica__dxf_chain_opts *o,
                              conica_path *path, size_t **lines, size_t *joined,
                              size_t *closed_open, conica_status *st)
{
    chainer c;
    conica_code rc = CONICA_OK;
    size_t nlines = 0;
    memset(&c, 0, sizeof c);
    c.g = g;
    c.o = o;
    *joined = *closed_open = 0;
    c.ep = malloc((2 * g->npc + 1) * sizeof *c.ep);
    c.used = calloc(g->npc + 1, 1);
    c.chain = malloc((2 * g->npc + 2) * sizeof *c.chain);
    *lines = malloc((g->npc + 1) * sizeof **lines);
    if (!c.ep || !c.used || !c.chain || !*lines) {
        rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        goto done;
    }
    for (size_t p = 0; p < g->npc; p++) {
        if (!is_open_piece(g, p, o->gap))
            continue;
        for (int end = 0; end < 2; end++) {
            const double *q = piece_end(g, p, end);
            endpt *e = &c.ep[c.nep++];
            e->x = q[0];
            e->y = q[1];
            e->piece = p;
            e->end = end;
        }
    }
    qsort(c.ep, c.nep, sizeof *c.ep, cmp_x);
    for (size_t p = 0; p < g->npc && rc == CONICA_OK; p++) {
        if (c.used[p])
            continue;
        c.used[p] = 1;
        c.head = g->npc;
        c.len = 1;
        c.chain[c.head].piece = p;
        c.chain[c.head].rev = 0;
        int closed = closes(&c);
        while (!closed && extend(&c, 1, g->pc[p].group))
            closed = closes(&c);
        while (!closed && extend(&c, 0, g->pc[p].group))
            closed = closes(&c);
        if (!closed) {
            if ((rc = open_outline(&c, st)) != CONICA_OK)
                break;
            (*closed_open)++;
        }
        if (c.len > 1)
            (*joined)++;
        (*lines)[nlines++] = g->pc[c.chain[c.head].piece].line;
        rc = emit(&c, closed, path, st);
    }
done:
    free(c.ep);
    free(c.used);
    free(c.chain);
    if (rc != CONICA_OK) {
        free(*lines);
        *lines = NULL;
    }
    return rc;
}

/* SPDX-License-Identifier: MIT */
/* Absolute SVG segments -> polylines through libcore's curve front end
 * (conica/path.h), which owns every rule: what a corner is, that straight
 * segments stay straight, how a Bézier or an arc becomes point-normal
 * samples, and that the result stays within the fidelity tolerance of the
 * drawn curve. This file only maps SVG's segments onto it:
 *
 *  - path data: M/L/H/V/Q/T/C/S/A/Z as drawn segments (arcs as exact
 *    rational quadratics), each subpath open or closed as written;
 *  - polygon and polyline elements (and, with lines_as_samples or
 *    simplify, path subpaths made only of straight segments): samples to
 *    interpolate, first simplified (conica/simplify.h) when asked;
 *  - the precision the numbers were written with judges tangency,
 *    straightness and rounding noise. */
#include "svg_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "conica/path.h"
#include "conica/simplify.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double conica_svg__text_precision(const char *text, size_t len)
{
    size_t i = 0;
    int best = -1000, seen = 0;
    while (i < len) {
        int dec = 0, exp10 = 0, digits = 0, esign = 1;
        if (!((text[i] >= '0' && text[i] <= '9') || text[i] == '.')) {
            i++;
            continue;
        }
        while (i < len && text[i] >= '0' && text[i] <= '9')
            i++, digits++;
        if (i < len && text[i] == '.') {
            i++;
            while (i < len && text[i] >= '0' && text[i] <= '9')
                i++, dec++, digits++;
        }
        if (i < len && (text[i] == 'e' || text[i] == 'E')) {
            size_t j = i + 1;
            if (j < len && (text[j] == '+' || text[j] == '-'))
                esign = text[j++] == '-' ? -1 : 1;
            if (j < len && text[j] >= '0' && text[j] <= '9') {
                while (j < len && text[j] >= '0' && text[j] <= '9') {
                    if (exp10 < 1000)
                        exp10 = 10 * exp10 + (text[j] - '0');
                    j++;
                }
                i = j;
            }
        }
        if (!digits)
            continue;
        seen = 1;
        dec -= esign * exp10;
        if (dec > best)
            best = dec;
        if (best > 340)
            best = 340;
    }
    return seen ? 0.5 * pow(10.0, -(double)best) : 0.0;
}

/* Append one output subpath, taking over *xy (2n coordinates, malloc'd;
 * *xy is set to NULL once taken): the polylines of a large document are
 * most of its memory, and a copy of each would touch as many fresh pages
 * again. On failure *xy stays the caller's. */
static conica_code push_subpath(conica_svg_shapes *out, size_t element, int closed, double **xy,
                                size_t n, conica_status *st)
{
    conica_svg_subpath *sp;
    if ((out->nsubpaths & (out->nsubpaths - 1)) == 0) { /* grow at powers of two */
        size_t cap = out->nsubpaths ? 2 * out->nsubpaths : 1;
        conica_svg_subpath *t = realloc(out->subpaths, cap * sizeof *t);
        if (!t)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        out->subpaths = t;
    }
    sp = &out->subpaths[out->nsubpaths];
    sp->element = element;
    sp->closed = closed;
    sp->n = n;
    sp->xy = NULL;
    if (n) {
        /* the producer's array may have room to spare: give it back (a
         * shrinking realloc stays in place) */
        double *t = realloc(*xy, 2 * n * sizeof **xy);
        sp->xy = t ? t : *xy;
        *xy = NULL;
    }
    out->nsubpaths++;
    return CONICA_OK;
}

/* Subpath boundaries: the index after the last segment of the subpath
 * starting at segment i (a MOVE, or drawing after Z), and whether it is
 * closed and made only of straight segments. */
static size_t subpath_end(const conica_svg_path *p, size_t i, int *closed, int *lines)
{
    size_t j = i;
    *closed = 0;
    *lines = 1;
    if (j < p->n && p->seg[j].type == CONICA_SVG_SEG_MOVE)
        j++;
    for (; j < p->n; j++) {
        conica_svg_seg_type t = p->seg[j].type;
        if (t == CONICA_SVG_SEG_MOVE)
            break;
        if (t == CONICA_SVG_SEG_CLOSE) {
            *closed = 1;
            return j + 1;
        }
        if (t != CONICA_SVG_SEG_LINE)
            *lines = 0;
    }
    return j;
}

/* The on-curve vertices of segments [a, b) into xy (room for b - a + 1
 * points); returns how many. */
static size_t subpath_vertices(const conica_svg_path *p, size_t a, size_t b, double *xy)
{
    size_t i, n = 0;
    for (i = a; i < b; i++) {
        const conica_svg_seg *g = &p->seg[i];
        if (g->type == CONICA_SVG_SEG_CLOSE)
            continue;
        if (n == 0 && g->type != CONICA_SVG_SEG_MOVE) {
            xy[0] = g->x0;
            xy[1] = g->y0;
            n = 1;
        }
        xy[2 * n] = g->x1;
        xy[2 * n + 1] = g->y1;
        n++;
    }
    return n;
}

/* How one SVG subpath goes into the path model: drawn as it is, its
 * vertices as samples to smooth through (a polygon, a polyline, a path of
 * lines with lines_as_samples), or a path of lines kept straight under
 * --simplify. Under --simplify a plan holds its input vertices and the
 * kept ones, simplified again when svg_uncross.c marks vertices to keep. */
enum { PLAN_DRAWN, PLAN_SAMPLES, PLAN_LINES };
typedef struct sub_plan {
    size_t a, b; /* its segments [a, b) */
    int closed, how;
    double *xy;  /* under --simplify: the input vertices (sm.n), else NULL */
    size_t *keep;
    size_t nforced; /* vertices marked to keep when last simplified */
    conica_svg__simp sm;
} sub_plan;

/* A plan's vertices simplified: every vertex it marks to keep kept. A
 * polygon kept straight (PLAN_LINES) is simplified at 0 levels as the open
 * polyline from its start round to it again: Douglas-Peucker seeds, corners
 * kept, its start kept. Within the tolerance both ways: every dropped
 * vertex is within it of the chord that replaces its run, and that run, a
 * path from the chord's one end to the other inside the band, passes
 * within it of every point of the chord. */
static conica_code plan_simplify(sub_plan *pl, double tolerance, const conica_path_settings *ps,
                                 conica_status *st)
{
    conica_simplify_settings ss = conica_simplify_defaults();
    size_t i;
    if (pl->sm.n < 3) {
        for (i = 0; i < pl->sm.n; i++)
            pl->keep[i] = i;
        pl->sm.nkeep = pl->sm.n;
        return CONICA_OK;
    }
    ss.tolerance = tolerance;
    ss.path = *ps;
    ss.keep_mask = pl->sm.force;
    if (pl->how == PLAN_LINES) {
        ss.path.levels = 0;
        ss.path.level_tolerance = 0;
    }
    return conica_simplify(pl->xy, pl->sm.n, pl->sm.wrap, &ss, pl->keep, &pl->sm.nkeep, NULL, st);
}

/* The plan's input vertices (under --simplify), simplified once. */
static conica_code plan_prepare(sub_plan *pl, const conica_svg_path *p, double tolerance,
                                const conica_path_settings *ps, conica_status *st)
{
    size_t n, room = pl->b - pl->a + 2;
    pl->xy = malloc(2 * room * sizeof *pl->xy);
    pl->keep = malloc(room * sizeof *pl->keep);
    pl->sm.force = calloc(room, 1);
    if (!pl->xy || !pl->keep || !pl->sm.force)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    n = subpath_vertices(p, pl->a, pl->b, pl->xy);
    if (pl->how == PLAN_LINES && pl->closed && n > 1 &&
        (pl->xy[2 * n - 2] != pl->xy[0] || pl->xy[2 * n - 1] != pl->xy[1])) {
        pl->xy[2 * n] = pl->xy[0]; /* round to the start again */
        pl->xy[2 * n + 1] = pl->xy[1];
        n++;
    }
    pl->sm.xy = pl->xy;
    pl->sm.n = n;
    pl->sm.wrap = pl->how == PLAN_SAMPLES && pl->closed;
    pl->sm.keep = pl->keep;
    return plan_simplify(pl, tolerance, ps, st);
}

static void plan_free(sub_plan *pl)
{
    free(pl->xy);
    free(pl->keep);
    free(pl->sm.force);
}

/* The on-curve vertices of segments [a, b) as samples (a polygon, a
 * polyline, or a subpath of straight segments taken as samples), or under
 * --simplify the plan's kept vertices. */
static conica_code add_samples(conica_path *cp, const conica_svg_path *p, const sub_plan *pl,
                               conica_status *st)
{
    size_t n, i;
    double *xy = malloc(2 * (pl->b - pl->a + 1) * sizeof *xy);
    conica_code rc;
    if (!xy)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    if (pl->xy) {
        for (i = 0, n = pl->sm.nkeep; i < n; i++) {
            xy[2 * i] = pl->xy[2 * pl->keep[i]];
            xy[2 * i + 1] = pl->xy[2 * pl->keep[i] + 1];
        }
    } else
        n = subpath_vertices(p, pl->a, pl->b, xy);
    rc = conica_path_samples(cp, xy, NULL, n, pl->closed, pl->a, st);
    if (rc == CONICA_ERR_DEGENERATE) {
        /* one point (or one repeated): kept as the point it is */
        rc = conica_path_move_to(cp, xy[0], xy[1], pl->a, st);
    }
    free(xy);
    return rc;
}

/* A subpath of straight segments under --simplify: the plan's kept
 * vertices as a polygon (its edges stay straight). */
static conica_code add_simplified_lines(conica_path *cp, const sub_plan *pl, conica_status *st)
{
    size_t i, n = pl->sm.nkeep;
    const double *xy = pl->xy;
    const size_t *k = pl->keep;
    conica_code rc = conica_path_move_to(cp, xy[2 * k[0]], xy[2 * k[0] + 1], pl->a, st);
    for (i = 1; i < n && rc == CONICA_OK; i++)
        if (!(pl->closed && i + 1 == n)) /* the closing edge is the close's */
            rc = conica_path_line_to(cp, xy[2 * k[i]], xy[2 * k[i] + 1], pl->a, st);
    if (rc == CONICA_OK && pl->closed)
        rc = conica_path_close(cp, st);
    return rc;
}

conica_code conica_svg__seg_to_path(conica_path *cp, const conica_svg_seg *g, size_t tag,
                                   conica_status *st)
{
    switch (g->type) {
    case CONICA_SVG_SEG_LINE:
        return conica_path_line_to(cp, g->x1, g->y1, tag, st);
    case CONICA_SVG_SEG_QUAD: {
        double c[4] = {g->c[0], g->c[1], g->x1, g->y1};
        return conica_path_bezier_to(cp, 2, c, NULL, tag, st);
    }
    case CONICA_SVG_SEG_CUBIC: {
        double c[6] = {g->c[0], g->c[1], g->c[2], g->c[3], g->x1, g->y1};
        return conica_path_bezier_to(cp, 3, c, NULL, tag, st);
    }
    case CONICA_SVG_SEG_ARC:
        return conica_path_arc_to(cp, g->cx, g->cy, g->rx, g->ry, g->phi, g->theta1, g->dtheta,
                                  g->x1, g->y1, tag, st);
    case CONICA_SVG_SEG_MOVE:
    case CONICA_SVG_SEG_CLOSE:
        break;
    }
    return CONICA_OK;
}

/* Segments [a, b) as drawn: one subpath. */
static conica_code add_drawn(conica_path *cp, const conica_svg_path *p, size_t a, size_t b,
                             int close, conica_status *st)
{
    size_t i;
    conica_code rc = CONICA_OK;
    for (i = a; i < b && rc == CONICA_OK; i++) {
        const conica_svg_seg *g = &p->seg[i];
        if (i == a && g->type != CONICA_SVG_SEG_MOVE)
            rc = conica_path_move_to(cp, g->x0, g->y0, i, st);
        if (rc != CONICA_OK)
            break;
        if (g->type == CONICA_SVG_SEG_MOVE)
            rc = conica_path_move_to(cp, g->x1, g->y1, i, st);
        else
            rc = conica_svg__seg_to_path(cp, g, i, st);
    }
    if (rc == CONICA_OK && close)
        rc = conica_path_close(cp, st);
    return rc;
}

static void free_plans(sub_plan *plans, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        plan_free(&plans[i]);
    free(plans);
}

/* The path model of the plans, one subpath each. */
static conica_code build_path(conica_path *cp, const conica_svg_path *p, const sub_plan *plans,
                              size_t n, conica_status *st)
{
    conica_code rc = CONICA_OK;
    size_t i;
    for (i = 0; i < n && rc == CONICA_OK; i++) {
        const sub_plan *pl = &plans[i];
        if (pl->xy && pl->sm.nkeep == 0) /* no vertex (a lone move): as drawn */
            rc = add_drawn(cp, p, pl->a, pl->b, pl->closed, st);
        else if (pl->how == PLAN_SAMPLES)
            rc = add_samples(cp, p, pl, st);
        else if (pl->how == PLAN_LINES)
            rc = add_simplified_lines(cp, pl, st);
        else
            rc = add_drawn(cp, p, pl->a, pl->b, pl->closed, st);
    }
    if (rc == CONICA_OK && cp->nsub != n)
        rc = conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0, "a subpath made %zu", cp->nsub);
    return rc;
}

/* Smoothing under --simplify: smoothed, then searched for crossings the
 * simplification made (svg_uncross.c); while there are, the vertices there
 * are kept, the marked plans simplified again and the element smoothed
 * again, at most UNCROSS_ROUNDS times. Past the rounds, or when the element
 * is too large to judge, its simplified subpaths keep every vertex (what
 * the drawing has, nothing new). */
#define UNCROSS_ROUNDS 16
static conica_code smooth_uncrossed(conica_path *cp, const conica_svg_path *p, sub_plan *plans,
                                    size_t nplan, double tolerance, const conica_path_settings *ps,
                                    conica_path_result *r, conica_status *st)
{
    conica_svg__simp **view = malloc((nplan ? nplan : 1) * sizeof *view);
    conica_code rc;
    size_t i, k, round;
    if (!view)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    for (i = 0; i < nplan; i++)
        view[i] = plans[i].xy ? &plans[i].sm : NULL;
    for (round = 0;; round++) {
        size_t marked = 0;
        int judged = 1, last = round == UNCROSS_ROUNDS;
        rc = conica_path_smooth(cp, ps, r, st);
        if (rc == CONICA_OK && !last)
            rc = conica_svg__uncross(cp, r, view, &marked, &judged, st);
        if (rc != CONICA_OK || last || (judged && marked == 0))
            break;
        for (i = 0; i < nplan && rc == CONICA_OK; i++) {
            sub_plan *pl = &plans[i];
            size_t nf = 0;
            if (!pl->xy)
                continue;
            for (k = 0; k < pl->sm.n; k++)
                nf += pl->sm.force[k];
            if (nf > 0 && (!judged || round + 1 == UNCROSS_ROUNDS)) {
                for (k = 0; k < pl->sm.n; k++) /* as drawn: every vertex */
                    pl->sm.force[k] = 1;
                nf = pl->sm.n;
            }
            if (!judged && nf == 0)
                memset(pl->sm.force, 1, pl->sm.n), nf = pl->sm.n;
            if (nf != pl->nforced)
                rc = plan_simplify(pl, tolerance, ps, st);
            pl->nforced = nf;
        }
        conica_path_result_free(r);
        conica_path_result_init(r);
        conica_path_free(cp);
        conica_path_init(cp);
        if (rc == CONICA_OK)
            rc = build_path(cp, p, plans, nplan, st);
        if (rc != CONICA_OK)
            break;
        if (!judged)
            round = UNCROSS_ROUNDS - 1; /* smoothed once more, not judged */
    }
    free(view);
    return rc;
}

/* The front end's settings for s at the numbers' precision, and the share
 * of the tolerance the geometry keeps. */
static void front_settings(const conica_svg_settings *s, double precision, size_t budget,
                           conica_path_settings *ps, double *geom_share)
{
    *ps = conica_path_defaults();
    ps->corner_angle = s->corner_angle_deg >= 180.0 ? M_PI : s->corner_angle_deg * M_PI / 180.0;
    ps->precision = precision;
    ps->max_points = budget;
    ps->rough_t = 1; /* SVG has no use for the points' parameters */
    /* digits from the tolerance (precision 0): the geometry keeps
     * CONICA_SVG_ROUNDING_SHARE of it for the rounding of what is written */
    *geom_share = s->precision == 0 ? 1.0 - CONICA_SVG_ROUNDING_SHARE : 1.0;
    if (s->mode == CONICA_SVG_SMOOTH) {
        ps->tolerance = s->fidelity * *geom_share;
        ps->rel_tolerance *= *geom_share;
        ps->levels = s->levels;
        ps->level_tolerance = s->tolerance;
    }
}

/* After the subpaths were added (rc their result): cp flattened, smoothed
 * (under --simplify through smooth_uncrossed() with the plans of path p;
 * plans NULL: none was simplified) or kept per s->mode into *out; frees
 * cp, not the plans. */
static conica_code front_polylines(conica_path *cp, conica_code rc, conica_path_settings *ps,
                                   double geom_share, const conica_svg_settings *s,
                                   const conica_svg_path *p, sub_plan *plans, size_t nplan,
                                   const char *what, size_t element, size_t *budget,
                                   conica_svg_shapes *out, conica_status *st)
{
    conica_path_result r;
    size_t i;
    conica_path_result_init(&r);
    if (rc != CONICA_OK) {
        char why[sizeof st->message];
        snprintf(why, sizeof why, "%s", st ? st->message : "bad geometry");
        conica_path_free(cp);
        return conica__fail(st, rc, 0, 0, "%s: %s", what, why);
    }
    if (s->mode == CONICA_SVG_FLATTEN) {
        ps->tolerance = s->tolerance * geom_share;
        ps->fit = (conica_path_fit)s->fit;
        rc = conica_path_flatten(cp, ps, &r, st);
    } else if (s->mode == CONICA_SVG_SMOOTH && plans && s->simplify > 0) {
        rc = smooth_uncrossed(cp, p, plans, nplan, s->simplify, ps, &r, st);
    } else if (s->mode == CONICA_SVG_SMOOTH) {
        rc = conica_path_smooth(cp, ps, &r, st);
    } else {
        /* KEEP: the on-curve vertices (flattening within an infinite
         * tolerance would be the same, less directly) */
        for (i = 0; i < cp->nsub && rc == CONICA_OK; i++) {
            const conica_path_subpath *sp = &cp->sub[i];
            size_t n = sp->kind == CONICA_PATH_SAMPLES ? sp->n : sp->n + 1, k;
            double *xy = malloc(2 * n * sizeof *xy);
            if (!xy) {
                rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
                break;
            }
            xy[0] = sp->x0;
            xy[1] = sp->y0;
            for (k = 1; k < n; k++) {
                const double *q = sp->kind == CONICA_PATH_SAMPLES
                                      ? cp->smp + 4 * (sp->first + k)
                                      : cp->pt + 3 * (cp->seg[sp->first + k - 1].first +
                                                      (size_t)cp->seg[sp->first + k - 1].degree);
                xy[2 * k] = q[0];
                xy[2 * k + 1] = q[1];
            }
            if (sp->kind == CONICA_PATH_DRAWN && sp->closed && n > 1)
                n--;
            if (n > *budget)
                rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                  "%s: output would exceed the limit of %zu points (--max-points)",
                                  what, s->limits.max_points);
            else {
                *budget -= n;
                rc = push_subpath(out, element, sp->closed, &xy, n, st);
            }
            free(xy);
        }
        conica_path_free(cp);
        return rc;
    }
    /* the input is no longer needed: its memory back before the output's copy */
    conica_path_free(cp);
    if (rc == CONICA_ERR_LIMIT)
        rc = conica__fail(st, rc, 0, 0,
                          "%s: output would exceed the limit of %zu points (--max-points)", what,
                          s->limits.max_points);
    else if (rc != CONICA_OK) {
        char why[sizeof st->message];
        snprintf(why, sizeof why, "%s", st ? st->message : "failed");
        rc = conica__fail(st, rc, 0, 0, "%s: %s", what, why);
    }
    for (i = 0; i < r.n && rc == CONICA_OK; i++) {
        conica_path_polyline *l = &r.lines[i]; /* its xy taken over: the result frees the rest */
        *budget -= l->n <= *budget ? l->n : *budget;
        rc = push_subpath(out, element, l->closed, &l->xy, l->n, st);
    }
    conica_path_result_free(&r);
    return rc;
}

conica_code conica_svg__path_polylines(const conica_svg_path *p, const conica_svg_settings *s,
                                       const char *what, size_t line, size_t element, int kind,
                                       double precision, size_t *budget, size_t *in_vertices,
                                       conica_svg_shapes *out, conica_status *st)
{
    return conica_svg__path_polylines_progress(p, s, what, line, element, kind, precision, budget,
                                               in_vertices, out, NULL, NULL, st);
}

conica_code conica_svg__path_polylines_progress(
    const conica_svg_path *p, const conica_svg_settings *s, const char *what, size_t line,
    size_t element, int kind, double precision, size_t *budget, size_t *in_vertices,
    conica_svg_shapes *out, conica_progress_fn pf, void *pctx, conica_status *st)
{
    conica_path cp;
    conica_path_settings ps;
    conica_code rc = CONICA_OK;
    size_t i, nplan = 0;
    double geom_share;
    int closed, lines, simplifying = s->mode == CONICA_SVG_SMOOTH && s->simplify > 0;
    sub_plan *plans;
    (void)line;
    conica_path_init(&cp);
    front_settings(s, precision, *budget, &ps, &geom_share);
    ps.progress = pf;
    ps.progress_ctx = pctx;
    /* the subpaths, as drawn or as samples */
    for (i = 0; i < p->n; nplan++)
        i = subpath_end(p, i, &closed, &lines);
    plans = calloc(nplan ? nplan : 1, sizeof *plans);
    if (!plans)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "%s: out of memory", what);
    for (i = 0, nplan = 0; i < p->n && rc == CONICA_OK; nplan++) {
        sub_plan *pl = &plans[nplan];
        size_t j = subpath_end(p, i, &closed, &lines), k;
        if (kind == 1 || s->close_open)
            closed = 1;
        for (k = i; k < j; k++)
            if (p->seg[k].type != CONICA_SVG_SEG_CLOSE)
                (*in_vertices)++;
        if (closed && j > i + 1 && p->seg[j - 1].type == CONICA_SVG_SEG_CLOSE &&
            p->seg[j - 1].x0 == p->seg[j - 1].x1 && p->seg[j - 1].y0 == p->seg[j - 1].y1)
            (*in_vertices)--; /* it returned to its start: that vertex is the first */
        pl->a = i;
        pl->b = j;
        pl->closed = closed;
        pl->how = PLAN_DRAWN;
        if (kind == 1 || kind == 2 ||
            (lines && s->lines_as_samples && s->mode == CONICA_SVG_SMOOTH))
            pl->how = PLAN_SAMPLES;
        else if (lines && simplifying)
            pl->how = PLAN_LINES;
        if (pl->how != PLAN_DRAWN && simplifying)
            rc = plan_prepare(pl, p, s->simplify, &ps, st);
        i = j;
    }
    if (rc == CONICA_OK)
        rc = build_path(&cp, p, plans, nplan, st);
    rc = front_polylines(&cp, rc, &ps, geom_share, s, p, plans, nplan, what, element, budget, out,
                         st);
    free_plans(plans, nplan);
    return rc;
}

conica_code conica_svg__points_polylines(double **xy, size_t np, int kind,
                                         const conica_svg_settings *s, const char *what,
                                         size_t element, double precision, size_t *budget,
                                         size_t *in_vertices, conica_svg_shapes *out,
                                         conica_status *st)
{
    conica_path cp;
    conica_path_settings ps;
    conica_code rc = CONICA_OK;
    double geom_share, *v = *xy;
    int closed = kind == 1 || s->close_open;
    if (s->mode == CONICA_SVG_SMOOTH && s->simplify > 0) {
        /* --simplify and its crossing checks work on a path's plans */
        conica_svg_path p;
        conica_svg_path_init(&p);
        if (!conica_svg__points_path(v, np, kind == 1, &p)) {
            conica_svg_path_free(&p);
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "%s: out of memory", what);
        }
        free(v);
        *xy = NULL;
        rc = conica_svg__path_polylines(&p, s, what, 0, element, kind, precision, budget,
                                        in_vertices, out, st);
        conica_svg_path_free(&p);
        return rc;
    }
    conica_path_init(&cp);
    front_settings(s, precision, *budget, &ps, &geom_share);
    /* counted as conica_svg__path_polylines counts the points' path: a
     * polygon that returns to its start has that vertex once */
    *in_vertices += np;
    if (kind == 1 && np && v[2 * np - 2] == v[0] && v[2 * np - 1] == v[1])
        (*in_vertices)--;
    if (np) {
        rc = conica_path_samples(&cp, v, NULL, np, closed, 0, st);
        if (rc == CONICA_ERR_DEGENERATE) /* one point (or one repeated): kept as it is */
            rc = conica_path_move_to(&cp, v[0], v[1], 0, st);
    }
    free(v); /* copied into cp: its memory back before the result's */
    *xy = NULL;
    return front_polylines(&cp, rc, &ps, geom_share, s, NULL, NULL, 0, what, element, budget, out,
                           st);
}

conica_code conica_svg_path_polylines(const conica_svg_path *p, const conica_svg_settings *s,
                                      conica_svg_shapes *out, conica_status *st)
{
    size_t budget, inv = 0;
    conica_svg_settings def = conica_svg_defaults();
    if (!p || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_path_polylines: NULL argument");
    if (!s)
        s = &def;
    if (s->mode == CONICA_SVG_FLATTEN && !(s->tolerance > 0.0))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "flattening needs a tolerance > 0");
    budget = s->limits.max_points;
    return conica_svg__path_polylines(p, s, "path", 0, 0, 0, 0.0, &budget, &inv, out, st);
}

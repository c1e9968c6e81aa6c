/* SPDX-License-Identifier: MIT */
/* Validation of a profile before it is written: OpenSCAD itself renders a
 * self-intersecting polygon silently (REFERENCE.md section 2), so simplicity
 * is checked here, with exact orientation tests, on a uniform grid. */
#include "scad_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Grid cells per segment (about one segment per cell for evenly spread
 * segments) and the cap on cell entries, a multiple of the segments. */
#define GRID_CELLS_PER_SEGMENT 1.0
#define GRID_MAX_ENTRIES_PER_SEGMENT 64
/* Fraction of a cell added around a segment's extent in a column, so a
 * segment lying on a cell boundary is entered into both cells. */
#define GRID_MARGIN 1e-7

typedef struct seg_ref {
    uint32_t contour;
    uint32_t index;
} seg_ref;

static const double *pt(const conica_scad_profile *p, size_t c, size_t i)
{
    const conica_scad_contour *k = &p->contours[c];
    return &k->xy[2 * (i % k->n)];
}

size_t conica_scad_describe(const conica_scad_profile *p, size_t c, char *buf, size_t cap)
{
    int len;
    if (!buf || cap == 0)
        return 0;
    if (!p || c >= p->ncontours || p->contours[c].group >= p->ngroups)
        len = snprintf(buf, cap, "a contour");
    else if (!p->groups[p->contours[c].group].name[0])
        len = p->ncontours == 1 ? snprintf(buf, cap, "the contour")
                                : snprintf(buf, cap, "contour %zu", p->contours[c].subpath);
    else
        len = snprintf(buf, cap, "%s: subpath %zu", p->groups[p->contours[c].group].name,
                       p->contours[c].subpath);
    return len < 0 ? 0 : (size_t)len;
}

/* The second contour of a message about two: "subpath 3" in the first's
 * group, else its full name with its group's line when that differs. */
static void describe_other(const conica_scad_profile *p, size_t first, size_t c, char *buf,
                           size_t cap)
{
    const conica_scad_group *ga = &p->groups[p->contours[first].group];
    const conica_scad_group *gb = &p->groups[p->contours[c].group];
    if (ga == gb && gb->name[0]) {
        snprintf(buf, cap, "subpath %zu", p->contours[c].subpath);
    } else {
        size_t len = conica_scad_describe(p, c, buf, cap);
        if (gb->line && gb->line != ga->line && len < cap)
            snprintf(buf + len, cap - len, " (line %zu)", gb->line);
    }
}

static conica_code report(const conica_scad_profile *p, conica_scad_violation *v,
                          conica_status *st, conica_scad_problem what, size_t ca, size_t sa,
                          size_t cb, size_t sb, double x, double y)
{
    char da[CONICA_SCAD_MAX_GROUP_NAME + 64], db[CONICA_SCAD_MAX_GROUP_NAME + 80];
    char xs[40], ys[40], lim[40];
    size_t na = p->contours[ca].n, nb = p->contours[cb].n;
    conica_scad_describe(p, ca, da, sizeof da);
    describe_other(p, ca, cb, db, sizeof db);
    conica_scad_format_double(x, xs, sizeof xs);
    conica_scad_format_double(y, ys, sizeof ys);
    if (v) {
        v->problem = what;
        v->contour_a = ca;
        v->segment_a = sa;
        v->contour_b = cb;
        v->segment_b = sb;
        v->x = x;
        v->y = y;
    }
    switch (what) {
    case CONICA_SCAD_OUT_OF_RANGE:
        snprintf(lim, sizeof lim, "%g", CONICA_SCAD_MAX_COORD);
        return conica__fail(st, CONICA_ERR_LIMIT, 0, ca,
                            "%s: point %zu (%s, %s) is out of range: coordinates must lie "
                            "within +-%s (OpenSCAD ignores points beyond about 1e15)",
                            da, sa + 1, xs, ys, lim);
    case CONICA_SCAD_TOO_FEW_POINTS:
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, ca, "%s has %zu point%s (a polygon needs 3)",
                                 da, na, na == 1 ? "" : "s");
    case CONICA_SCAD_DUPLICATE_POINT:
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, ca,
                                 "%s: points %zu and %zu are equal (%s, %s)", da, sa + 1,
                                 (sa + 1) % na + 1, xs, ys);
    case CONICA_SCAD_ZERO_AREA:
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, ca,
                            "%s has zero area (its points are collinear or it encloses no area)",
                            da);
    case CONICA_SCAD_NEGATIVE_X:
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, ca,
                                 "%s: point %zu (%s, %s) has x < 0; rotate_extrude needs the "
                                 "whole profile at x >= 0",
                                 da, sa + 1, xs, ys);
    case CONICA_SCAD_SELF_INTERSECTION:
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, ca,
                                 "%s intersects itself: segment %zu (points %zu-%zu) and segment "
                                 "%zu (points %zu-%zu) meet near (%s, %s)",
                                 da, sa + 1, sa + 1, (sa + 1) % na + 1, sb + 1, sb + 1,
                                 (sb + 1) % nb + 1, xs, ys);
    case CONICA_SCAD_CONTOURS_CROSS:
    default:
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, ca,
                                 "%s and %s meet: segment %zu (points %zu-%zu) and segment %zu "
                                 "(points %zu-%zu) near (%s, %s)",
                                 da, db, sa + 1, sa + 1, (sa + 1) % na + 1, sb + 1, sb + 1,
                                 (sb + 1) % nb + 1, xs, ys);
    }
}

/* q on the closed segment a-b, given that the three are collinear. */
static int on_segment(const double *a, const double *b, const double *q)
{
    return fmin(a[0], b[0]) <= q[0] && q[0] <= fmax(a[0], b[0]) && fmin(a[1], b[1]) <= q[1] &&
           q[1] <= fmax(a[1], b[1]);
}

/* Do the closed segments a-b and c-d share a point? Sets (*x, *y) near it. */
static int segments_meet(const double *a, const double *b, const double *c, const double *d,
                         double *x, double *y)
{
    int o1 = conica__orient2d(a, b, c), o2 = conica__orient2d(a, b, d);
    int o3 = conica__orient2d(c, d, a), o4 = conica__orient2d(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) {
        /* proper crossing: the point itself only for the message */
        double ex = b[0] - a[0], ey = b[1] - a[1], fx = d[0] - c[0], fy = d[1] - c[1];
        double den = ex * fy - ey * fx;
        double t = den != 0 ? ((c[0] - a[0]) * fy - (c[1] - a[1]) * fx) / den : 0.5;
        *x = a[0] + t * ex;
        *y = a[1] + t * ey;
        return 1;
    }
    if (o1 == 0 && on_segment(a, b, c)) {
        *x = c[0], *y = c[1];
        return 1;
    }
    if (o2 == 0 && on_segment(a, b, d)) {
        *x = d[0], *y = d[1];
        return 1;
    }
    if (o3 == 0 && on_segment(c, d, a)) {
        *x = a[0], *y = a[1];
        return 1;
    }
    if (o4 == 0 && on_segment(c, d, b)) {
        *x = b[0], *y = b[1];
        return 1;
    }
    return 0;
}

/* Segments a-b and b-c share b; they overlap elsewhere only when c runs
 * back along a-b (collinear, same side of b as a). */
static int adjacent_overlap(const double *a, const double *b, const double *c)
{
    if (conica__orient2d(a, b, c) != 0)
        return 0;
    int sx = (a[0] > b[0]) - (a[0] < b[0]), tx = (c[0] > b[0]) - (c[0] < b[0]);
    int sy = (a[1] > b[1]) - (a[1] < b[1]), ty = (c[1] > b[1]) - (c[1] < b[1]);
    return (sx != 0 && sx == tx) || (sx == 0 && tx == 0 && sy != 0 && sy == ty);
}

typedef struct grid {
    double x0, y0, cw, ch;
    size_t gx, gy;
} grid;

/* Visit the cells a segment passes through (conservatively): for each
 * column it spans, the rows covered by its y-extent inside that column. */
static size_t visit(const grid *g, const double *a, const double *b, size_t *start, seg_ref *cells,
                    seg_ref ref, int fill)
{
    size_t count = 0;
    double xa = fmin(a[0], b[0]), xb = fmax(a[0], b[0]);
    long c0 = (long)floor((xa - g->x0) / g->cw - GRID_MARGIN);
    long c1 = (long)floor((xb - g->x0) / g->cw + GRID_MARGIN);
    if (c0 < 0)
        c0 = 0;
    if (c1 > (long)g->gx - 1)
        c1 = (long)g->gx - 1;
    for (long cx = c0; cx <= c1; cx++) {
        double lo = g->x0 + (double)cx * g->cw, hi = lo + g->cw;
        double ylo, yhi;
        if (xb - xa <= 0) {
            ylo = fmin(a[1], b[1]);
            yhi = fmax(a[1], b[1]);
        } else {
            double s0 = fmax(lo, xa), s1 = fmin(hi, xb);
            if (s0 > s1)
                s0 = s1 = fmin(fmax(s0, xa), xb);
            double t0 = (s0 - a[0]) / (b[0] - a[0]), t1 = (s1 - a[0]) / (b[0] - a[0]);
            t0 = fmin(fmax(t0, 0.0), 1.0);
            t1 = fmin(fmax(t1, 0.0), 1.0);
            double y0 = a[1] + t0 * (b[1] - a[1]), y1 = a[1] + t1 * (b[1] - a[1]);
            ylo = fmin(y0, y1);
            yhi = fmax(y0, y1);
        }
        long r0 = (long)floor((ylo - g->y0) / g->ch - GRID_MARGIN);
        long r1 = (long)floor((yhi - g->y0) / g->ch + GRID_MARGIN);
        if (r0 < 0)
            r0 = 0;
        if (r1 > (long)g->gy - 1)
            r1 = (long)g->gy - 1;
        for (long cy = r0; cy <= r1; cy++) {
            size_t cell = (size_t)cy * g->gx + (size_t)cx;
            if (fill)
                cells[start[cell]++] = ref;
            else
                start[cell]++;
            count++;
        }
    }
    return count;
}

static conica_code check_crossings(const conica_scad_profile *p, conica_scad_violation *v,
                                   conica_status *st)
{
    size_t nseg = 0, entries = 0;
    double xmin = INFINITY, ymin = INFINITY, xmax = -INFINITY, ymax = -INFINITY;
    grid g;
    for (size_t c = 0; c < p->ncontours; c++) {
        const conica_scad_contour *k = &p->contours[c];
        nseg += k->n;
        for (size_t i = 0; i < k->n; i++) {
            xmin = fmin(xmin, k->xy[2 * i]);
            xmax = fmax(xmax, k->xy[2 * i]);
            ymin = fmin(ymin, k->xy[2 * i + 1]);
            ymax = fmax(ymax, k->xy[2 * i + 1]);
        }
    }
    if (nseg == 0)
        return CONICA_OK;
    if (nseg > UINT32_MAX)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "too many segments to check");
    {
        double w = xmax - xmin, h = ymax - ymin, cells;
        if (!(w > 0))
            w = h > 0 ? h : 1;
        if (!(h > 0))
            h = w;
        /* about nseg square cells, never more columns or rows than that
         * (a very flat profile gets one row) */
        cells = fmin((double)nseg * GRID_CELLS_PER_SEGMENT, 1 << 26);
        g.gx = (size_t)fmin(fmax(ceil(sqrt(cells * w / h)), 1), cells);
        g.gy = (size_t)fmin(fmax(ceil(cells / (double)g.gx), 1), cells);
        g.x0 = xmin;
        g.y0 = ymin;
        g.cw = w / (double)g.gx;
        g.ch = h / (double)g.gy;
    }
    size_t ncell = g.gx * g.gy;
    size_t *start = calloc(ncell + 1, sizeof *start);
    if (!start)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    /* pass 1: count entries per cell (in start[cell + 1]) */
    for (size_t c = 0; c < p->ncontours; c++)
        for (size_t i = 0; i < p->contours[c].n; i++) {
            seg_ref r = {(uint32_t)c, (uint32_t)i};
            entries += visit(&g, pt(p, c, i), pt(p, c, i + 1), start + 1, NULL, r, 0);
            if (entries > GRID_MAX_ENTRIES_PER_SEGMENT * nseg + 4096) {
                free(start);
                return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                         "segments too long for the intersection grid");
            }
        }
    for (size_t i = 0; i < ncell; i++)
        start[i + 1] += start[i];
    seg_ref *cells = malloc((entries ? entries : 1) * sizeof *cells);
    size_t *fillp = malloc((ncell + 1) * sizeof *fillp);
    if (!cells || !fillp) {
        free(cells);
        free(fillp);
        free(start);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    memcpy(fillp, start, (ncell + 1) * sizeof *fillp);
    for (size_t c = 0; c < p->ncontours; c++)
        for (size_t i = 0; i < p->contours[c].n; i++) {
            seg_ref r = {(uint32_t)c, (uint32_t)i};
            visit(&g, pt(p, c, i), pt(p, c, i + 1), fillp, cells, r, 1);
        }
    free(fillp);
    /* pass 2: every pair sharing a cell (a pair in several cells is tested
     * again there; harmless) */
    conica_code rc = CONICA_OK;
    for (size_t cell = 0; cell < ncell && rc == CONICA_OK; cell++) {
        for (size_t u = start[cell]; u < start[cell + 1] && rc == CONICA_OK; u++) {
            for (size_t w = u + 1; w < start[cell + 1]; w++) {
                seg_ref s = cells[u], t = cells[w];
                double x, y;
                if (s.contour > t.contour || (s.contour == t.contour && s.index > t.index)) {
                    seg_ref tmp = s;
                    s = t;
                    t = tmp;
                }
                size_t n = p->contours[s.contour].n;
                if (s.contour == t.contour) {
                    if (s.index == t.index)
                        continue;
                    if ((s.index + 1) % n == t.index || (t.index + 1) % n == s.index) {
                        /* adjacent: share one vertex */
                        size_t first = (s.index + 1) % n == t.index ? s.index : t.index;
                        const double *a = pt(p, s.contour, first);
                        const double *b = pt(p, s.contour, first + 1);
                        const double *cc = pt(p, s.contour, first + 2);
                        if (adjacent_overlap(a, b, cc)) {
                            rc = report(p, v, st, CONICA_SCAD_SELF_INTERSECTION, s.contour,
                                        first, s.contour, (first + 1) % n, b[0], b[1]);
                            break;
                        }
                        /* a triangle's other pair is adjacent through the other vertex */
                        continue;
                    }
                }
                if (segments_meet(pt(p, s.contour, s.index), pt(p, s.contour, s.index + 1),
                                  pt(p, t.contour, t.index), pt(p, t.contour, t.index + 1), &x,
                                  &y)) {
                    rc = report(p, v, st,
                                s.contour == t.contour ? CONICA_SCAD_SELF_INTERSECTION
                                                       : CONICA_SCAD_CONTOURS_CROSS,
                                s.contour, s.index, t.contour, t.index, x, y);
                    break;
                }
            }
        }
    }
    free(cells);
    free(start);
    return rc;
}

/* The first point of contour c with a coordinate beyond
 * CONICA_SCAD_MAX_COORD, or SIZE_MAX. */
static size_t out_of_range(const conica_scad_contour *k)
{
    for (size_t i = 0; i < k->n; i++)
        if (!(fabs(k->xy[2 * i]) <= CONICA_SCAD_MAX_COORD) ||
            !(fabs(k->xy[2 * i + 1]) <= CONICA_SCAD_MAX_COORD))
            return i;
    return SIZE_MAX;
}

conica_code conica_scad_check_range(const conica_scad_profile *p, conica_scad_violation *v,
                                    conica_status *st)
{
    if (!p)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "no profile");
    for (size_t c = 0; c < p->ncontours; c++) {
        size_t i = out_of_range(&p->contours[c]);
        if (i != SIZE_MAX)
            return report(p, v, st, CONICA_SCAD_OUT_OF_RANGE, c, i, c, i,
                          p->contours[c].xy[2 * i], p->contours[c].xy[2 * i + 1]);
    }
    if (v)
        memset(v, 0, sizeof *v);
    conica__ok(st);
    return CONICA_OK;
}

/* Are all points of k on one line (exact)? The line runs through the
 * first point and the first point that differs from it; a contour of one
 * repeated point is on every line. */
static int collinear(const conica_scad_contour *k)
{
    size_t j = 1;
    while (j < k->n && k->xy[2 * j] == k->xy[0] && k->xy[2 * j + 1] == k->xy[1])
        j++;
    for (size_t i = j + 1; i < k->n; i++)
        if (conica__orient2d(k->xy, k->xy + 2 * j, k->xy + 2 * i) != 0)
            return 0;
    return 1;
}

/* Is k's signed area negligible against its box (rounding noise of a
 * polygon folded onto a line)? */
static int tiny_area(const conica_scad_contour *k)
{
    double xmin = INFINITY, ymin = INFINITY, xmax = -INFINITY, ymax = -INFINITY;
    for (size_t i = 0; i < k->n; i++) {
        xmin = fmin(xmin, k->xy[2 * i]);
        xmax = fmax(xmax, k->xy[2 * i]);
        ymin = fmin(ymin, k->xy[2 * i + 1]);
        ymax = fmax(ymax, k->xy[2 * i + 1]);
    }
    double diag2 = (xmax - xmin) * (xmax - xmin) + (ymax - ymin) * (ymax - ymin);
    return !(fabs(0.5 * conica__scad_area2(k->xy, k->n)) > CONICA_SCAD_ZERO_AREA_REL * diag2);
}

conica_code conica_scad_drop_empty(conica_scad_profile *p, conica_scad_drop_fn fn, void *ctx,
                                   size_t *dropped, conica_status *st)
{
    size_t w = 0, nd = 0;
    if (!p)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "no profile");
    for (size_t c = 0; c < p->ncontours; c++) {
        conica_scad_contour *k = &p->contours[c];
        conica_scad_problem what = CONICA_SCAD_OK;
        if (out_of_range(k) != SIZE_MAX) {
            what = CONICA_SCAD_OK; /* conica_scad_validate() names it */
        } else if (k->n < 3) {
            what = CONICA_SCAD_TOO_FEW_POINTS;
        } else if (collinear(k)) {
            what = CONICA_SCAD_ZERO_AREA;
        } else if (tiny_area(k)) {
            /* a bowtie's lobes cancel as well: that one crosses itself */
            conica_scad_profile one = *p;
            conica_status cst;
            one.ncontours = 1;
            one.contours = k;
            conica_code rc = check_crossings(&one, NULL, &cst);
            if (rc == CONICA_ERR_NOMEM) {
                memmove(p->contours + w, p->contours + c, (p->ncontours - c) * sizeof *k);
                p->ncontours = w + p->ncontours - c;
                return conica__fail(st, rc, 0, 0, "out of memory");
            }
            if (rc == CONICA_OK)
                what = CONICA_SCAD_ZERO_AREA;
        }
        if (what == CONICA_SCAD_OK) {
            p->contours[w++] = *k;
            continue;
        }
        if (fn) {
            conica_scad_violation v;
            conica_status msg;
            report(p, &v, &msg, what, c, 0, c, 0, k->xy[0], k->xy[1]);
            fn(ctx, p, c, &v, msg.message);
        }
        p->npoints -= k->n;
        free(k->xy);
        k->xy = NULL;
        nd++;
    }
    p->ncontours = w;
    if (dropped)
        *dropped = nd;
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_scad_validate(const conica_scad_profile *p, int rotate_extrude,
                                 conica_scad_violation *v, conica_status *st)
{
    if (!p || p->ncontours == 0)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "empty profile");
    /* range first: a triangle at 1e200 is out of range, its area (an
     * overflow) says nothing */
    conica_code rc = conica_scad_check_range(p, v, st);
    if (rc != CONICA_OK)
        return rc;
    for (size_t c = 0; c < p->ncontours; c++) {
        const conica_scad_contour *k = &p->contours[c];
        if (k->n < 3)
            return report(p, v, st, CONICA_SCAD_TOO_FEW_POINTS, c, 0, c, 0, k->xy[0], k->xy[1]);
        for (size_t i = 0; i < k->n; i++) {
            const double *a = &k->xy[2 * i], *b = pt(p, c, i + 1);
            if (a[0] == b[0] && a[1] == b[1])
                return report(p, v, st, CONICA_SCAD_DUPLICATE_POINT, c, i, c, i, a[0], a[1]);
            if (rotate_extrude && a[0] < 0)
                return report(p, v, st, CONICA_SCAD_NEGATIVE_X, c, i, c, i, a[0], a[1]);
        }
    }
    /* A contour whose points all lie on one line (exact orientation
     * tests) encloses no area; it would otherwise be reported as running
     * back over itself. */
    for (size_t c = 0; c < p->ncontours; c++) {
        const conica_scad_contour *k = &p->contours[c];
        if (collinear(k))
            return report(p, v, st, CONICA_SCAD_ZERO_AREA, c, 0, c, 0, k->xy[0], k->xy[1]);
    }
    /* crossings next: a bowtie's lobes cancel to zero signed area */
    rc = check_crossings(p, v, st);
    if (rc != CONICA_OK)
        return rc;
    for (size_t c = 0; c < p->ncontours; c++) {
        const conica_scad_contour *k = &p->contours[c];
        if (tiny_area(k))
            return report(p, v, st, CONICA_SCAD_ZERO_AREA, c, 0, c, 0, k->xy[0], k->xy[1]);
    }
    if (v)
        memset(v, 0, sizeof *v);
    conica__ok(st);
    return CONICA_OK;
}

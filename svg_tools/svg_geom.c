/* Absolute segments -> polylines: conic-preserving smoothing with corners
 * kept, flattening by the guaranteed plotter, or the vertices as they are.
 *
 * Smoothing (issue 6): each subpath becomes a point-normal curve whose
 * vertices are the on-curve points (seed 000 subdivides point-normal
 * pairs, Section 1.1, and reproduces a conic when the pairs are sampled
 * from it). Normals come exactly from Bézier control points and arcs;
 * between two straight segments they are estimated. Vertices where the
 * tangent turns by more than the corner angle split the curve into open
 * pieces that meet there, so corners stay sharp; a piece made only of
 * collinear straight segments is written unchanged, so straight edges stay
 * straight. Arcs longer than 90 degrees are cut into equal parametric parts
 * of at most 90 degrees, each end an on-curve vertex with its exact normal
 * (a full circle written as two arcs gets four vertices). More exact
 * samples where the vertices alone say too little: curves that change their
 * turning direction (split_inflections) and a curve alone between two
 * breaks (two point-normal pairs do not fix a conic). README.md
 * describes the whole procedure. */
#include "svg_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "conica/bspline.h"
#include "conica/curve.h"
#include "conica/plot.h"
#include "conica/subdiv.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A straight segment meets a curve "smoothly" (and is then kept straight as
 * its own piece) when their tangents agree within this angle (radians);
 * 1e-3 rad absorbs the rounding of coordinates written with 7 digits. */
#define SVG_G1_ANGLE 1e-3
/* Points of a run of straight segments count as collinear when they lie
 * within this fraction of the run's extent from the line through its ends. */
#define SVG_COLLINEAR_REL 1e-12
/* A closed subpath's last vertex this close to its first (relative to the
 * subpath's extent) is the first: rounding, not a real edge. */
#define SVG_MERGE_REL 1e-12
/* Largest arc part between two vertices (radians). */
#define SVG_MAX_ARC_PART (0.5 * M_PI)
/* Three points closer to a line than this sine of their angle give no circle. */
#define SVG_CIRCLE_COLLINEAR_SIN 1e-9
/* Cross product of two unit tangents below this: the curve does not turn. */
#define SVG_TURN_EPS 1e-9
/* Parts a curve is cut into where the turning direction changes. */
#define SVG_INFLECTION_PARTS 4
/* Level cap for --tolerance smoothing (each level doubles the points). */
#define SVG_TOL_MAX_LEVELS 16

typedef struct edge {
    const conica_svg_seg *seg; /* NULL: the straight closing edge of Z */
    double t0, t1;             /* parameter range of seg */
    int curve;                 /* 0: straight */
    double ta[2], tb[2];       /* unit tangents at start and end */
} edge;

typedef struct sub {
    double *xy;  /* nv vertices */
    edge *e;     /* ne edges; edge i runs from vertex i to i+1 (mod nv if closed) */
    size_t nv, ne, capv, cape;
    int closed;
} sub;

typedef struct geom_ctx {
    const conica_svg_settings *s;
    size_t budget;   /* output points left */
    const char *what; /* element name for messages */
    size_t line;      /* its XML line (0 unknown) */
    conica_status *st;
} geom_ctx;

static int unit(double x, double y, double out[2])
{
    double h = hypot(x, y);
    if (!(h > 0.0) || !isfinite(h))
        return 0;
    out[0] = x / h;
    out[1] = y / h;
    return 1;
}

static int sub_vertex(sub *b, double x, double y)
{
    if (b->nv == b->capv) {
        size_t cap = b->capv ? 2 * b->capv : 16;
        double *t = realloc(b->xy, 2 * cap * sizeof *t);
        if (!t)
            return 0;
        b->xy = t;
        b->capv = cap;
    }
    b->xy[2 * b->nv] = x;
    b->xy[2 * b->nv + 1] = y;
    b->nv++;
    return 1;
}

static int sub_edge(sub *b, const edge *e)
{
    if (b->ne == b->cape) {
        size_t cap = b->cape ? 2 * b->cape : 16;
        edge *t = realloc(b->e, cap * sizeof *t);
        if (!t)
            return 0;
        b->e = t;
        b->cape = cap;
    }
    b->e[b->ne++] = *e;
    return 1;
}

/* Unit tangents at the ends of a Bézier from its control polygon, skipping
 * control points that coincide with the end point. */
static void bezier_tangents(const conica_svg_seg *g, edge *e)
{
    double p[4][2];
    int n = g->type == CONICA_SVG_SEG_CUBIC ? 4 : 3, i;
    p[0][0] = g->x0;
    p[0][1] = g->y0;
    p[1][0] = g->c[0];
    p[1][1] = g->c[1];
    if (n == 4) {
        p[2][0] = g->c[2];
        p[2][1] = g->c[3];
    }
    p[n - 1][0] = g->x1;
    p[n - 1][1] = g->y1;
    for (i = 1; i < n; i++)
        if (unit(p[i][0] - p[0][0], p[i][1] - p[0][1], e->ta))
            break;
    for (i = n - 2; i >= 0; i--)
        if (unit(p[n - 1][0] - p[i][0], p[n - 1][1] - p[i][1], e->tb))
            break;
}

/* Parts of at most 90 degrees for an arc sweeping dtheta (|dtheta| <= 2 pi,
 * so 1..4; the tiny slack keeps an exact 90 degrees in one part). */
static size_t arc_parts(double dtheta)
{
    double parts = ceil(fabs(dtheta) / SVG_MAX_ARC_PART - 1e-9);
    return parts >= 1.0 && parts <= 4.0 ? (size_t)parts : parts > 4.0 ? 4 : 1;
}

static int add_line(sub *b, const conica_svg_seg *g, double x, double y)
{
    edge e;
    double px = b->xy[2 * (b->nv - 1)], py = b->xy[2 * (b->nv - 1) + 1];
    if (px == x && py == y)
        return 1; /* zero length: no vertex (it would be a double point) */
    memset(&e, 0, sizeof e);
    e.seg = g;
    e.t0 = 0.0;
    e.t1 = 1.0;
    unit(x - px, y - py, e.ta);
    e.tb[0] = e.ta[0];
    e.tb[1] = e.ta[1];
    return sub_edge(b, &e) && sub_vertex(b, x, y);
}

/* Append segment g (its start is the last vertex). split_arcs: cut arcs in
 * parts of at most 90 degrees (smoothing), else one edge per segment. */
static int add_seg(sub *b, const conica_svg_seg *g, int split_arcs)
{
    edge e;
    if (g->type == CONICA_SVG_SEG_LINE)
        return add_line(b, g, g->x1, g->y1);
    memset(&e, 0, sizeof e);
    e.seg = g;
    e.curve = 1;
    if (g->type == CONICA_SVG_SEG_QUAD || g->type == CONICA_SVG_SEG_CUBIC) {
        if (g->x0 == g->x1 && g->y0 == g->y1 && g->c[0] == g->x0 && g->c[1] == g->y0 &&
            (g->type == CONICA_SVG_SEG_QUAD || (g->c[2] == g->x0 && g->c[3] == g->y0)))
            return 1; /* a curve of one point */
        e.t0 = 0.0;
        e.t1 = 1.0;
        bezier_tangents(g, &e);
        return sub_edge(b, &e) && sub_vertex(b, g->x1, g->y1);
    }
    if (g->type == CONICA_SVG_SEG_ARC) {
        size_t m = 1, k;
        if (split_arcs) {
            m = arc_parts(g->dtheta);
        }
        for (k = 0; k < m; k++) {
            double p[2], d[2];
            e.t0 = (double)k / (double)m;
            e.t1 = k + 1 == m ? 1.0 : (double)(k + 1) / (double)m;
            conica_svg__seg_eval(g, e.t0, p, d);
            unit(d[0], d[1], e.ta);
            conica_svg__seg_eval(g, e.t1, p, d);
            unit(d[0], d[1], e.tb);
            if (!sub_edge(b, &e) || !sub_vertex(b, p[0], p[1]))
                return 0;
        }
        return 1;
    }
    return 1;
}

/* Cut edge i into parts[i] equal parametric parts (straight edges are never
 * cut), each new vertex an exact point of the curve with its exact tangent. */
static int split_edges(sub *b, const size_t *parts)
{
    sub nb;
    size_t i, k;
    memset(&nb, 0, sizeof nb);
    nb.closed = b->closed;
    if (!sub_vertex(&nb, b->xy[0], b->xy[1]))
        goto fail;
    for (i = 0; i < b->ne; i++) {
        edge e = b->e[i];
        size_t to = (i + 1) % b->nv, m = e.curve ? parts[i] : 1;
        for (k = 0; k < m; k++) {
            edge c = e;
            double p[2], d[2];
            c.t0 = e.t0 + (e.t1 - e.t0) * (double)k / (double)m;
            c.t1 = k + 1 == m ? e.t1 : e.t0 + (e.t1 - e.t0) * (double)(k + 1) / (double)m;
            if (k > 0) {
                conica_svg__seg_eval(e.seg, c.t0, p, d);
                unit(d[0], d[1], c.ta);
            }
            if (k + 1 < m) {
                conica_svg__seg_eval(e.seg, c.t1, p, d);
                unit(d[0], d[1], c.tb);
            }
            if (!sub_edge(&nb, &c))
                goto fail;
            if (k + 1 < m && !sub_vertex(&nb, p[0], p[1]))
                goto fail;
        }
        if (i + 1 < b->ne || !b->closed)
            if (!sub_vertex(&nb, b->xy[2 * to], b->xy[2 * to + 1]))
                goto fail;
    }
    free(b->xy);
    free(b->e);
    *b = nb;
    return 1;
fail:
    free(nb.xy);
    free(nb.e);
    return 0;
}

static double turn_angle(const double a[2], const double b[2]);

/* Does the curve split at vertex i (an interior vertex, or any vertex of a
 * closed subpath)? At a corner (the tangent turns by more than `corner`),
 * and where a straight segment meets a curve tangentially, so the straight
 * part stays straight. */
static int is_break(const sub *b, size_t i, double corner)
{
    const edge *ein = &b->e[(i + b->ne - 1) % b->ne], *eout = &b->e[i % b->ne];
    double a = turn_angle(ein->tb, eout->ta);
    return a > corner || (ein->curve != eout->curve && a <= SVG_G1_ANGLE);
}

/* Which way a curved edge turns: +1 left, -1 right, 0 not measurably. */
static int edge_turn(const edge *e)
{
    double c = e->ta[0] * e->tb[1] - e->ta[1] * e->tb[0];
    return c > SVG_TURN_EPS ? 1 : c < -SVG_TURN_EPS ? -1 : 0;
}

/* A cubic whose inner control points lie on opposite sides of its chord has
 * an inflection inside. */
static int s_shaped(const edge *e)
{
    const conica_svg_seg *g = e->seg;
    double dx = g->x1 - g->x0, dy = g->y1 - g->y0, a, c;
    if (g->type != CONICA_SVG_SEG_CUBIC)
        return 0;
    a = dx * (g->c[1] - g->y0) - dy * (g->c[0] - g->x0);
    c = dx * (g->c[3] - g->y0) - dy * (g->c[2] - g->x0);
    return (a > 0.0 && c < 0.0) || (a < 0.0 && c > 0.0);
}

/* The vertices of a subpath say too little where its curves change their
 * turning direction: an S-shaped cubic, or two curves turning opposite ways
 * at a smooth join (a wave "C..S.." whose on-curve points are collinear).
 * Such points with their normals are no sample of one conic, and collinear
 * points can even make the fit a straight line. Cut those curves into
 * SVG_INFLECTION_PARTS parts at exact points, so the curve carries its
 * shape into the subdivision. Convex runs (every arc, a conic written as
 * Béziers with exact tangents) are left alone and still reproduce exactly. */
static int split_inflections(sub *b, double corner)
{
    size_t i, n = b->ne, flagged = 0;
    size_t *parts;
    if (n == 0)
        return 1;
    parts = malloc(n * sizeof *parts);
    if (!parts)
        return 0;
    for (i = 0; i < n; i++) {
        const edge *e = &b->e[i];
        int t = edge_turn(e), flag = 0, side;
        parts[i] = 1;
        if (!e->curve)
            continue;
        flag = s_shaped(e);
        for (side = 0; side < 2 && !flag && t != 0; side++) {
            const edge *o;
            if (!b->closed && ((side == 0 && i == 0) || (side == 1 && i + 1 == n)))
                continue;
            o = &b->e[side == 0 ? (i + n - 1) % n : (i + 1) % n];
            if (o->curve && edge_turn(o) == -t &&
                turn_angle(side == 0 ? o->tb : e->tb, side == 0 ? e->ta : o->ta) <= corner)
                flag = 1;
        }
        if (flag) {
            parts[i] = SVG_INFLECTION_PARTS;
            flagged++;
        } else if ((!b->closed && i == 0) || is_break(b, i, corner)) {
            /* A curve alone between two breaks (or ends) would be a piece of
             * two point-normal pairs: four conditions cannot fix a conic
             * (five degrees of freedom), so a quarter arc between two
             * straight sides would not come out circular. Its exact middle
             * makes three pairs, which do. */
            size_t j = (i + 1) % b->nv;
            if ((!b->closed && i + 1 == n) || is_break(b, j, corner)) {
                parts[i] = 2;
                flagged++;
            }
        }
    }
    i = flagged ? (size_t)split_edges(b, parts) : 1;
    free(parts);
    return (int)i;
}

/* ------------------------------------------------------------ output */

/* Growable point list. */
typedef struct pts {
    double *xy;
    size_t n, cap;
} pts;

/* Append a subpath to *out, taking over o's array (o is left empty). A
 * list more than an eighth larger than its points is trimmed first. */
static conica_code push_subpath(conica_svg_shapes *out, size_t element, int closed, pts *o,
                                conica_status *st)
{
    conica_svg_subpath *sp;
    if ((out->nsubpaths & (out->nsubpaths - 1)) == 0) { /* grow at powers of two */
        size_t cap = out->nsubpaths ? 2 * out->nsubpaths : 1;
        conica_svg_subpath *t = realloc(out->subpaths, cap * sizeof *t);
        if (!t)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        out->subpaths = t;
    }
    if (o->n && o->cap - o->n > o->n / 8) {
        double *t = realloc(o->xy, 2 * o->n * sizeof *t);
        if (t) {
            o->xy = t;
            o->cap = o->n;
        }
    }
    sp = &out->subpaths[out->nsubpaths];
    sp->element = element;
    sp->closed = closed;
    sp->n = o->n;
    sp->xy = o->n ? o->xy : NULL;
    if (!o->n)
        free(o->xy);
    o->xy = NULL;
    o->n = o->cap = 0;
    out->nsubpaths++;
    return CONICA_OK;
}

/* Room for `more` points in *p; 0 when out of memory. */
static int pts_reserve(pts *p, size_t more)
{
    size_t need = p->n + more, cap;
    double *t;
    if (need <= p->cap)
        return 1;
    cap = p->cap ? 2 * p->cap : 64;
    while (cap < need)
        cap *= 2;
    t = realloc(p->xy, 2 * cap * sizeof *t);
    if (!t)
        return 0;
    p->xy = t;
    p->cap = cap;
    return 1;
}

static int pts_add(pts *p, double x, double y)
{
    if (p->n == p->cap && !pts_reserve(p, 1))
        return 0;
    p->xy[2 * p->n] = x;
    p->xy[2 * p->n + 1] = y;
    p->n++;
    return 1;
}

static conica_code take_budget(geom_ctx *g, size_t n)
{
    if (n > g->budget)
        return conica__fail(g->st, CONICA_ERR_LIMIT, 0, 0,
                                "%s: output would exceed the limit of %zu points (--max-points)",
                                g->what, g->s->limits.max_points);
    g->budget -= n;
    return CONICA_OK;
}

/* ------------------------------------------------------------ smoothing */

static double turn_angle(const double a[2], const double b[2])
{
    return fabs(atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]));
}

/* Largest distance of an odd-indexed (newly inserted) point from the chord
 * of its two neighbours: how far the last level moved the polyline. */
static double last_level_move(const conica_curve *c)
{
    size_t i, n = c->n;
    double worst = 0.0;
    for (i = 1; i < n; i += 2) {
        size_t a = i - 1, b = (i + 1) % n;
        double ax = c->xy[2 * a], ay = c->xy[2 * a + 1];
        double bx = c->xy[2 * b], by = c->xy[2 * b + 1];
        double px = c->xy[2 * i] - ax, py = c->xy[2 * i + 1] - ay;
        double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy, t, d;
        if (i + 1 >= n && !c->closed)
            break;
        t = l2 > 0.0 ? (px * dx + py * dy) / l2 : 0.0;
        t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
        d = hypot(px - t * dx, py - t * dy);
        if (d > worst)
            worst = d;
    }
    return worst;
}

/* Subdivide one piece (points + normals, some normals unknown) and append
 * the result to *o (skipping its first point when skip_first). */
static conica_code smooth_piece(geom_ctx *g, const double *xy, double *nxy, const int *known,
                                size_t n, int closed, int skip_first, pts *o)
{
    const conica_svg_settings *s = g->s;
    conica_curve in, out;
    conica_subdiv_settings ss = conica_subdiv_defaults();
    conica_subdiv_info info;
    conica_status est;
    conica_code rc;
    size_t i, nknown = 0;

    for (i = 0; i < n; i++)
        nknown += known[i] != 0;
    conica_curve_init(&in);
    conica_curve_init(&out);
    conica_subdiv_info_init(&info);
    rc = conica_curve_set(xy, NULL, n, closed, &in, &est);
    if (rc == CONICA_OK && nknown < n) {
        /* Estimate where the path has no tangent; keep the exact ones but
         * orient them like the estimate so the field is consistent. */
        rc = conica_curve_estimate_normals(&in, CONICA_NORMALS_CIRCLE, &est);
        if (rc == CONICA_OK && nknown) {
            double agree = 0.0;
            for (i = 0; i < n; i++)
                if (known[i])
                    agree += nxy[2 * i] * in.nxy[2 * i] + nxy[2 * i + 1] * in.nxy[2 * i + 1];
            for (i = 0; i < n; i++)
                if (known[i]) {
                    in.nxy[2 * i] = agree < 0.0 ? -nxy[2 * i] : nxy[2 * i];
                    in.nxy[2 * i + 1] = agree < 0.0 ? -nxy[2 * i + 1] : nxy[2 * i + 1];
                }
        }
    } else if (rc == CONICA_OK) {
        rc = conica_curve_set(xy, nxy, n, closed, &in, &est);
    }
    if (rc == CONICA_OK) {
        ss.max_points = g->budget;
        if (s->tolerance > 0.0) {
            int k;
            for (k = 1; k <= SVG_TOL_MAX_LEVELS; k++) {
                ss.levels = k;
                rc = conica_subdivide(&in, &ss, &out, &info, &est);
                conica_subdiv_info_free(&info);
                if (rc != CONICA_OK || last_level_move(&out) <= s->tolerance)
                    break;
            }
        } else {
            ss.levels = s->levels;
            rc = conica_subdivide(&in, &ss, &out, &info, &est);
            conica_subdiv_info_free(&info);
        }
    }
    if (rc == CONICA_ERR_NOMEM || rc == CONICA_ERR_LIMIT) {
        conica_curve_free(&in);
        conica_curve_free(&out);
        if (rc == CONICA_ERR_LIMIT)
            return conica__fail(g->st, rc, 0, 0,
                                    "%s: output would exceed the limit of %zu points (--max-points)",
                                    g->what, s->limits.max_points);
        return conica__fail(g->st, rc, 0, 0, "out of memory");
    }
    if (rc != CONICA_OK) {
        /* Degenerate or numerically hopeless data: keep the vertices. */
        if (s->warn) {
            char msg[400];
            snprintf(msg, sizeof msg, "%s: a piece of %zu points was kept as is: %s", g->what, n,
                     est.message);
            s->warn(s->warn_ctx, g->line, msg);
        }
        conica_curve_free(&out);
        conica_curve_set(xy, NULL, n, closed, &out, NULL);
    }
    conica_curve_free(&in);
    if ((rc = take_budget(g, out.n - (skip_first && out.n ? 1 : 0))) != CONICA_OK) {
        conica_curve_free(&out);
        return rc;
    }
    if (o->n == 0 && !skip_first && out.n && !o->xy) {
        /* the usual case, one piece: take the engine's array over */
        o->xy = out.xy;
        o->n = o->cap = out.n;
        out.xy = NULL;
    } else if (out.n > (size_t)(skip_first != 0)) {
        size_t from = skip_first ? 1 : 0, m = out.n - from;
        if (!pts_reserve(o, m)) {
            conica_curve_free(&out);
            return conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        }
        memcpy(o->xy + 2 * o->n, out.xy + 2 * from, 2 * m * sizeof *o->xy);
        o->n += m;
    }
    conica_curve_free(&out);
    return CONICA_OK;
}

static int collinear_lines(const sub *b, size_t first, size_t count)
{
    size_t i;
    double ax, ay, dx, dy, len;
    for (i = 0; i + 1 < count; i++)
        if (b->e[(first + i) % b->ne].curve)
            return 0;
    ax = b->xy[2 * first];
    ay = b->xy[2 * first + 1];
    {
        size_t last = (first + count - 1) % b->nv;
        dx = b->xy[2 * last] - ax;
        dy = b->xy[2 * last + 1] - ay;
    }
    len = hypot(dx, dy);
    if (!(len > 0.0))
        return 0;
    for (i = 1; i + 1 < count; i++) {
        size_t v = (first + i) % b->nv;
        double px = b->xy[2 * v] - ax, py = b->xy[2 * v + 1] - ay;
        if (fabs(px * dy - py * dx) / len > SVG_COLLINEAR_REL * len)
            return 0;
        if (px * dx + py * dy < 0.0 || px * dx + py * dy > len * len)
            return 0; /* doubles back: not a straight run */
    }
    return 1;
}

/* Replace the normal n at p0 by the normal at p0 of the circle through
 * p0, p1, p2 (same side as n); n stays when the points are collinear. */
static void end_circle_normal(const double *p0, const double *p1, const double *p2, double *n)
{
    double ax = p1[0] - p0[0], ay = p1[1] - p0[1], bx = p2[0] - p0[0], by = p2[1] - p0[1];
    double aa = ax * ax + ay * ay, bb = bx * bx + by * by, d = 2.0 * (ax * by - ay * bx);
    double cx, cy, m[2];
    if (!(fabs(d) > SVG_CIRCLE_COLLINEAR_SIN * 2.0 * sqrt(aa) * sqrt(bb)))
        return;
    cx = (by * aa - ay * bb) / d; /* centre relative to p0 */
    cy = (ax * bb - bx * aa) / d;
    if (!unit(-cx, -cy, m))
        return;
    if (m[0] * n[0] + m[1] * n[1] < 0.0) {
        m[0] = -m[0];
        m[1] = -m[1];
    }
    n[0] = m[0];
    n[1] = m[1];
}

static conica_code smooth_sub(geom_ctx *g, sub *b, pts *o)
{
    const conica_svg_settings *s = g->s;
    double corner = s->corner_angle_deg >= 180.0 ? 4.0 : s->corner_angle_deg * (M_PI / 180.0);
    size_t nv = b->nv, i, nbreak = 0, first_break = 0;
    int *brk = NULL, *known = NULL;
    double *nxy = NULL, *pxy = NULL;
    conica_code rc = CONICA_OK;

    int refine = s->levels > 0 || s->tolerance > 0.0;

    if (refine && !split_inflections(b, corner))
        return conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    if (refine && b->closed && b->nv < 3 && b->ne) {
        /* the engine needs 3 points on a closed curve: halve the curves */
        size_t *two = malloc(b->ne * sizeof *two), k;
        int ok = two != NULL;
        for (k = 0; ok && k < b->ne; k++)
            two[k] = 2;
        ok = ok && split_edges(b, two);
        free(two);
        if (!ok)
            return conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    nv = b->nv;
    if (b->ne == 0 || !refine || (b->closed && nv < 3)) {
        for (i = 0; i < nv; i++)
            if (!pts_add(o, b->xy[2 * i], b->xy[2 * i + 1]))
                return conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        return take_budget(g, nv);
    }
    brk = calloc(nv, sizeof *brk);
    known = calloc(nv + 1, sizeof *known);
    nxy = calloc(2 * (nv + 1), sizeof *nxy);
    pxy = malloc(2 * (nv + 1) * sizeof *pxy);
    if (!brk || !known || !nxy || !pxy) {
        rc = conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        goto done;
    }
    /* Corners (and straight/curve tangent joins) split the curve. */
    for (i = 0; i < nv; i++) {
        if (!b->closed && (i == 0 || i == nv - 1))
            continue;
        if (is_break(b, i, corner)) {
            brk[i] = 1;
            if (!nbreak)
                first_break = i;
            nbreak++;
        }
    }
    if (b->closed && nbreak == 0) {
        /* One closed curve through every vertex. */
        for (i = 0; i < nv; i++) {
            const edge *ein = &b->e[(i + nv - 1) % nv], *eout = &b->e[i];
            double t[2];
            pxy[2 * i] = b->xy[2 * i];
            pxy[2 * i + 1] = b->xy[2 * i + 1];
            known[i] = 1;
            if (ein->curve && eout->curve)
                known[i] = unit(ein->tb[0] + eout->ta[0], ein->tb[1] + eout->ta[1], t);
            else if (ein->curve)
                t[0] = ein->tb[0], t[1] = ein->tb[1];
            else if (eout->curve)
                t[0] = eout->ta[0], t[1] = eout->ta[1];
            else
                known[i] = 0;
            if (known[i]) {
                nxy[2 * i] = t[1];
                nxy[2 * i + 1] = -t[0];
            }
        }
        rc = smooth_piece(g, pxy, nxy, known, nv, 1, 0, o);
        goto done;
    }
    {
        /* Open pieces from break to break; a closed subpath starts at its
         * first break and wraps round to it. */
        size_t start = b->closed ? first_break : 0, done_v = 0, total = b->closed ? nv : nv - 1;
        int first_piece = 1;
        while (done_v < total) {
            size_t cnt = 1, j;
            /* extend until the next break (or the end) */
            while (done_v + cnt <= total) {
                size_t v = (start + cnt) % nv;
                cnt++;
                if (done_v + cnt - 1 == total || brk[v])
                    break;
            }
            for (j = 0; j < cnt; j++) {
                size_t v = (start + j) % nv;
                const edge *ein = j > 0 ? &b->e[(start + j - 1) % b->ne] : NULL;
                const edge *eout = j + 1 < cnt ? &b->e[(start + j) % b->ne] : NULL;
                double t[2];
                pxy[2 * j] = b->xy[2 * v];
                pxy[2 * j + 1] = b->xy[2 * v + 1];
                known[j] = 1;
                if (!ein)
                    t[0] = eout->ta[0], t[1] = eout->ta[1];
                else if (!eout)
                    t[0] = ein->tb[0], t[1] = ein->tb[1];
                else if (ein->curve && eout->curve)
                    known[j] = unit(ein->tb[0] + eout->ta[0], ein->tb[1] + eout->ta[1], t);
                else if (ein->curve)
                    t[0] = ein->tb[0], t[1] = ein->tb[1];
                else if (eout->curve)
                    t[0] = eout->ta[0], t[1] = eout->ta[1];
                else
                    known[j] = 0;
                if (known[j]) {
                    nxy[2 * j] = t[1];
                    nxy[2 * j + 1] = -t[0];
                }
            }
            /* A run of straight segments ending at a corner: the normal at
             * that end from the circle through the three end points (exact
             * for a polygon sampled from a circle) instead of the end chord. */
            if (cnt >= 3) {
                if (!b->e[start % b->ne].curve && !b->e[(start + 1) % b->ne].curve)
                    end_circle_normal(pxy, pxy + 2, pxy + 4, nxy);
                if (!b->e[(start + cnt - 2) % b->ne].curve && !b->e[(start + cnt - 3) % b->ne].curve)
                    end_circle_normal(pxy + 2 * (cnt - 1), pxy + 2 * (cnt - 2), pxy + 2 * (cnt - 3),
                                      nxy + 2 * (cnt - 1));
            }
            if (collinear_lines(b, start, cnt)) {
                /* straight edges stay straight: the vertices as they are */
                for (j = first_piece ? 0 : 1; j < cnt; j++)
                    if (!pts_add(o, pxy[2 * j], pxy[2 * j + 1])) {
                        rc = conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
                        goto done;
                    }
                rc = take_budget(g, first_piece ? cnt : cnt - 1);
            } else {
                rc = smooth_piece(g, pxy, nxy, known, cnt, 0, !first_piece, o);
            }
            if (rc != CONICA_OK)
                goto done;
            first_piece = 0;
            done_v += cnt - 1;
            start = (start + cnt - 1) % nv;
        }
        if (b->closed && o->n > 1) {
            /* the last piece ends on the first point: drop the repeat, then
             * rotate so the output starts where the input did */
            size_t k, at = 0;
            o->n--;
            for (k = 0; k < o->n; k++)
                if (o->xy[2 * k] == b->xy[0] && o->xy[2 * k + 1] == b->xy[1]) {
                    at = k;
                    break;
                }
            if (at) {
                double *r = malloc(2 * o->n * sizeof *r);
                if (!r) {
                    rc = conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
                    goto done;
                }
                memcpy(r, o->xy + 2 * at, 2 * (o->n - at) * sizeof *r);
                memcpy(r + 2 * (o->n - at), o->xy, 2 * at * sizeof *r);
                free(o->xy);
                o->xy = r;
                o->cap = o->n;
            }
        }
    }
done:
    free(brk);
    free(known);
    free(nxy);
    free(pxy);
    return rc;
}

/* ------------------------------------------------------------ flattening */

static conica_code plot_append(geom_ctx *g, const conica_bspline *bs, double ex, double ey, pts *o)
{
    conica_plot_settings ps = conica_plot_defaults();
    conica_polyline pl;
    conica_status est;
    conica_code rc;
    ps.method = CONICA_PLOT_GUARANTEED;
    ps.abs_tolerance = g->s->tolerance;
    ps.max_points = g->budget;
    conica_polyline_init(&pl);
    rc = conica_plot(bs, &ps, &pl, NULL, &est);
    if (rc != CONICA_OK) {
        conica_polyline_free(&pl);
        if (rc == CONICA_ERR_LIMIT)
            return conica__fail(g->st, rc, 0, 0,
                                    "%s: output would exceed the limit of %zu points (--max-points)",
                                    g->what, g->s->limits.max_points);
        return conica__fail(g->st, rc, 0, 0, "%s: plotting failed: %s", g->what, est.message);
    }
    if ((rc = take_budget(g, pl.n ? pl.n - 1 : 0)) != CONICA_OK) {
        conica_polyline_free(&pl);
        return rc;
    }
    if (pl.n > 1) {
        if (!pts_reserve(o, pl.n - 1)) {
            conica_polyline_free(&pl);
            return conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        }
        memcpy(o->xy + 2 * o->n, pl.xy + 2, 2 * (pl.n - 1) * sizeof *o->xy);
        o->n += pl.n - 1;
        /* the curve's end point exactly, whatever the evaluation rounded */
        o->xy[2 * o->n - 2] = ex;
        o->xy[2 * o->n - 1] = ey;
    }
    conica_polyline_free(&pl);
    return CONICA_OK;
}

static conica_code flatten_edge(geom_ctx *g, const edge *e, double ex, double ey, pts *o)
{
    const conica_svg_seg *s = e->seg;
    conica_bspline bs;
    conica_status est;
    conica_code rc;
    conica_bspline_init(&bs);
    if (s->type == CONICA_SVG_SEG_QUAD || s->type == CONICA_SVG_SEG_CUBIC) {
        double c[8];
        int deg = s->type == CONICA_SVG_SEG_CUBIC ? 3 : 2;
        c[0] = s->x0;
        c[1] = s->y0;
        memcpy(c + 2, s->c, (size_t)(2 * (deg - 1)) * sizeof *c);
        c[2 * deg] = s->x1;
        c[2 * deg + 1] = s->y1;
        rc = conica_bspline_from_bezier(deg, 2, c, NULL, &bs, &est);
    } else {
        /* An elliptic arc exactly: rational quadratic pieces of at most 90
         * degrees, middle weight cos(half angle), joined with double knots. */
        size_t m = arc_parts(s->dtheta), k, nk = 2 * m + 4, nc = 2 * m + 1;
        double *buf = malloc((nk + 3 * nc) * sizeof *buf), *kn, *cp, *w;
        double h = 0.5 * s->dtheta / (double)m, cphi = cos(s->phi), sphi = sin(s->phi);
        if (!buf)
            return conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        kn = buf;
        cp = buf + nk;
        w = cp + 2 * nc;
        kn[0] = kn[1] = kn[2] = 0.0;
        for (k = 1; k < m; k++)
            kn[2 * k + 1] = kn[2 * k + 2] = (double)k;
        kn[nk - 3] = kn[nk - 2] = kn[nk - 1] = (double)m;
        for (k = 0; k < nc; k++) {
            double th = s->theta1 + (double)k * h, r = (k % 2) ? 1.0 / cos(h) : 1.0;
            double ex2 = s->rx * r * cos(th), ey2 = s->ry * r * sin(th);
            cp[2 * k] = s->cx + cphi * ex2 - sphi * ey2;
            cp[2 * k + 1] = s->cy + sphi * ex2 + cphi * ey2;
            w[k] = (k % 2) ? cos(h) : 1.0;
        }
        cp[0] = s->x0;
        cp[1] = s->y0;
        cp[2 * nc - 2] = s->x1;
        cp[2 * nc - 1] = s->y1;
        rc = conica_bspline_set(2, 2, kn, nk, cp, nc, w, &bs, &est);
        free(buf);
    }
    if (rc != CONICA_OK) {
        conica_bspline_free(&bs);
        return conica__fail(g->st, rc, 0, 0, "%s: %s", g->what, est.message);
    }
    rc = plot_append(g, &bs, ex, ey, o);
    conica_bspline_free(&bs);
    return rc;
}

static conica_code flatten_sub(geom_ctx *g, const sub *b, pts *o)
{
    size_t i;
    conica_code rc;
    if (!pts_add(o, b->xy[0], b->xy[1]))
        return conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    if ((rc = take_budget(g, 1)) != CONICA_OK)
        return rc;
    for (i = 0; i < b->ne; i++) {
        size_t to = (i + 1) % b->nv;
        double ex = b->xy[2 * to], ey = b->xy[2 * to + 1];
        if (b->e[i].curve) {
            if ((rc = flatten_edge(g, &b->e[i], ex, ey, o)) != CONICA_OK)
                return rc;
        } else {
            if (!pts_add(o, ex, ey))
                return conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            if ((rc = take_budget(g, 1)) != CONICA_OK)
                return rc;
        }
    }
    if (b->closed && o->n > 1)
        o->n--; /* the closing edge ends on the first point */
    return CONICA_OK;
}

/* ------------------------------------------------------------ driver */

/* Vertices i and j coincide up to SVG_MERGE_REL of the subpath's extent. */
static int same_point(const sub *b, size_t i, size_t j)
{
    double lo[2] = {b->xy[0], b->xy[1]}, hi[2] = {b->xy[0], b->xy[1]};
    size_t k;
    if (b->xy[2 * i] == b->xy[2 * j] && b->xy[2 * i + 1] == b->xy[2 * j + 1])
        return 1;
    for (k = 1; k < b->nv; k++) {
        int c;
        for (c = 0; c < 2; c++) {
            double v = b->xy[2 * k + (size_t)c];
            lo[c] = v < lo[c] ? v : lo[c];
            hi[c] = v > hi[c] ? v : hi[c];
        }
    }
    return hypot(b->xy[2 * i] - b->xy[2 * j], b->xy[2 * i + 1] - b->xy[2 * j + 1]) <=
           SVG_MERGE_REL * hypot(hi[0] - lo[0], hi[1] - lo[1]);
}

static conica_code finish_sub(geom_ctx *g, sub *b, size_t element, conica_svg_shapes *out,
                              size_t *in_vertices)
{
    pts o = {NULL, 0, 0};
    conica_code rc = CONICA_OK;
    if (b->nv == 0)
        return CONICA_OK;
    /* A closed subpath that returns to its start: the last vertex is the
     * first (also when rounding left it a hair away, e.g. sin(2 pi)). */
    if (b->closed && b->nv > 1 && same_point(b, b->nv - 1, 0))
        b->nv--;
    else if (b->closed && b->nv > 1) {
        /* Z draws a straight edge back to the start */
        edge e;
        memset(&e, 0, sizeof e);
        e.t1 = 1.0;
        unit(b->xy[0] - b->xy[2 * (b->nv - 1)], b->xy[1] - b->xy[2 * (b->nv - 1) + 1], e.ta);
        e.tb[0] = e.ta[0];
        e.tb[1] = e.ta[1];
        if (!sub_edge(b, &e))
            return conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    if (b->closed && b->nv == 1) {
        b->ne = 0;
    }
    *in_vertices += b->nv;
    if (g->s->mode == CONICA_SVG_FLATTEN && b->ne)
        rc = flatten_sub(g, b, &o);
    else if (g->s->mode == CONICA_SVG_SMOOTH)
        rc = smooth_sub(g, b, &o);
    else {
        size_t i;
        for (i = 0; i < b->nv && rc == CONICA_OK; i++)
            if (!pts_add(&o, b->xy[2 * i], b->xy[2 * i + 1]))
                rc = conica__fail(g->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        if (rc == CONICA_OK)
            rc = take_budget(g, b->nv);
    }
    if (rc == CONICA_OK)
        rc = push_subpath(out, element, b->closed, &o, g->st);
    free(o.xy);
    return rc;
}

conica_code conica_svg__path_polylines(const conica_svg_path *p, const conica_svg_settings *s,
                                       const char *what, size_t line, size_t element,
                                       int force_closed, size_t *budget, size_t *in_vertices,
                                       conica_svg_shapes *out, conica_status *st)
{
    geom_ctx g;
    sub b;
    size_t i;
    int open = 0; /* a subpath is being built */
    double sx = 0, sy = 0;
    conica_code rc = CONICA_OK;
    int split = s->mode == CONICA_SVG_SMOOTH;

    g.s = s;
    g.budget = *budget;
    g.what = what;
    g.line = line;
    g.st = st;
    memset(&b, 0, sizeof b);
    for (i = 0; i < p->n && rc == CONICA_OK; i++) {
        const conica_svg_seg *sg = &p->seg[i];
        switch (sg->type) {
        case CONICA_SVG_SEG_MOVE:
            if (open)
                rc = finish_sub(&g, &b, element, out, in_vertices);
            b.nv = b.ne = 0;
            b.closed = 0;
            sx = sg->x1;
            sy = sg->y1;
            open = 1;
            if (rc == CONICA_OK && !sub_vertex(&b, sx, sy))
                rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            break;
        case CONICA_SVG_SEG_CLOSE:
            if (open) {
                b.closed = 1;
                rc = finish_sub(&g, &b, element, out, in_vertices);
                b.nv = b.ne = 0;
                open = 0;
            }
            break;
        default:
            if (!open) { /* drawing after Z starts at the previous start */
                b.nv = b.ne = 0;
                b.closed = 0;
                open = 1;
                if (!sub_vertex(&b, sx, sy)) {
                    rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
                    break;
                }
            }
            if (!add_seg(&b, sg, split))
                rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            break;
        }
    }
    if (open && rc == CONICA_OK) {
        b.closed = force_closed;
        rc = finish_sub(&g, &b, element, out, in_vertices);
    }
    free(b.xy);
    free(b.e);
    *budget = g.budget;
    return rc;
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
    return conica_svg__path_polylines(p, s, "path", 0, 0, 0, &budget, &inv, out, st);
}

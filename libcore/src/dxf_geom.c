/* SPDX-License-Identifier: MIT */
/* DXF pieces: each entity as a chain of exact segments (lines, rational
 * quadratic arcs, a spline's Bézier pieces) under an affine transform (the
 * OCS, the INSERTs above it, the unit scale). An affine map takes a
 * rational Bézier to the rational Bézier of the mapped control points with
 * the same weights, so every transform stays exact. Calls bspline only. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dxf_internal.h"
#include "internal.h"

#define HALF_PI 1.57079632679489661923
#define PI 3.14159265358979323846

void conica__dxf_geom_init(conica__dxf_geom *g, size_t max_points)
{
    memset(g, 0, sizeof *g);
    g->max_points = max_points;
}

void conica__dxf_geom_free(conica__dxf_geom *g)
{
    free(g->pc);
    free(g->sg);
    free(g->pt);
    memset(g, 0, sizeof *g);
}

void conica__dxf_xf_apply(const conica__dxf_xf *xf, double x, double y, double out[2])
{
    const double *m = xf->m;
    out[0] = fma(m[0], x, fma(m[1], y, m[2]));
    out[1] = fma(m[3], x, fma(m[4], y, m[5]));
}

conica__dxf_xf conica__dxf_xf_mul(const conica__dxf_xf *a, const conica__dxf_xf *b)
{
    conica__dxf_xf r;
    const double *p = a->m, *q = b->m;
    r.m[0] = p[0] * q[0] + p[1] * q[3];
    r.m[1] = p[0] * q[1] + p[1] * q[4];
    r.m[2] = p[0] * q[2] + p[1] * q[5] + p[2];
    r.m[3] = p[3] * q[0] + p[4] * q[3];
    r.m[4] = p[3] * q[1] + p[4] * q[4];
    r.m[5] = p[3] * q[2] + p[4] * q[5] + p[5];
    return r;
}

void conica__dxf_sincos_deg(double deg, double *c, double *s)
{
    double r = fmod(deg, 360.0);
    if (r < 0)
        r += 360.0;
    if (r == 0 || r == 90 || r == 180 || r == 270) {
        static const double cs[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
        int k = (int)(r / 90);
        *c = cs[k][0];
        *s = cs[k][1];
        return;
    }
    *c = cos(r * (PI / 180));
    *s = sin(r * (PI / 180));
}

conica_code conica__dxf_begin(conica__dxf_geom *g, const conica__dxf_piece *info,
                              conica_status *st)
{
    if (g->npc == g->pccap) {
        size_t nc = g->pccap ? 2 * g->pccap : 64;
        conica__dxf_piece *q = realloc(g->pc, nc * sizeof *q);
        if (!q)
            return conica__fail(st, CONICA_ERR_NOMEM, info->line, 0, "out of memory");
        g->pc = q;
        g->pccap = nc;
    }
    g->pc[g->npc] = *info;
    g->pc[g->npc].seg = g->nsg;
    g->pc[g->npc].nseg = 0;
    g->pc[g->npc].closed = 0;
    g->open = 1;
    return CONICA_OK;
}

void conica__dxf_end(conica__dxf_geom *g, int closed)
{
    if (!g->open)
        return;
    g->open = 0;
    conica__dxf_piece *p = &g->pc[g->npc];
    p->nseg = g->nsg - p->seg;
    p->closed = closed;
    if (p->nseg > 0)
        g->npc++;
}

/* Append a segment of `degree` with control points xy (degree + 1 points,
 * already transformed) and weights w (or NULL). */
static conica_code add_seg(conica__dxf_geom *g, int degree, const double *xy, const double *w,
                           size_t line, conica_status *st)
{
    size_t k = (size_t)degree + 1;
    for (size_t i = 0; i < 2 * k; i++)
        if (!(fabs(xy[i]) <= CONICA_DXF_MAX_COORD))
            return conica__fail(st, isfinite(xy[i]) ? CONICA_ERR_LIMIT : CONICA_ERR_NONFINITE,
                                line, 0,
                                "a coordinate (%g) is beyond +-%g: not a drawing this reader takes",
                                xy[i], CONICA_DXF_MAX_COORD);
    if (g->npt + k > g->max_points)
        return conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                            "the drawing has more than %zu control points (max_points)",
                            g->max_points);
    if (g->nsg == g->sgcap) {
        size_t nc = g->sgcap ? 2 * g->sgcap : 256;
        conica__dxf_seg *q = realloc(g->sg, nc * sizeof *q);
        if (!q)
            return conica__fail(st, CONICA_ERR_NOMEM, line, 0, "out of memory");
        g->sg = q;
        g->sgcap = nc;
    }
    if (g->npt + k > g->ptcap) {
        size_t nc = g->ptcap ? 2 * g->ptcap : 1024;
        while (nc < g->npt + k)
            nc *= 2;
        double *q = realloc(g->pt, 3 * nc * sizeof *q);
        if (!q)
            return conica__fail(st, CONICA_ERR_NOMEM, line, 0, "out of memory");
        g->pt = q;
        g->ptcap = nc;
    }
    g->sg[g->nsg].degree = degree;
    g->sg[g->nsg].pt = g->npt;
    for (size_t i = 0; i < k; i++) {
        g->pt[3 * (g->npt + i)] = xy[2 * i];
        g->pt[3 * (g->npt + i) + 1] = xy[2 * i + 1];
        g->pt[3 * (g->npt + i) + 2] = w ? w[i] : 1.0;
    }
    g->npt += k;
    g->nsg++;
    return CONICA_OK;
}

conica_code conica__dxf_line(conica__dxf_geom *g, const conica__dxf_xf *xf, double x0, double y0,
                             double x1, double y1, size_t line, conica_status *st)
{
    double xy[4];
    if (x0 == x1 && y0 == y1)
        return CONICA_OK; /* a line of no length draws nothing */
    conica__dxf_xf_apply(xf, x0, y0, xy);
    conica__dxf_xf_apply(xf, x1, y1, xy + 2);
    return add_seg(g, 1, xy, NULL, line, st);
}

conica_code conica__dxf_arc(conica__dxf_geom *g, const conica__dxf_xf *xf, const double c[2],
                            const double M[2], const double m[2], double t0, double t1,
                            const double *p0, const double *p1, size_t line, conica_status *st)
{
    double sweep = t1 - t0;
    if (!isfinite(sweep) || !isfinite(c[0]) || !isfinite(c[1]))
        return conica__fail(st, CONICA_ERR_NONFINITE, line, 0, "an arc is not finite");
    if (sweep == 0)
        return CONICA_OK;
    /* pieces of at most 90 degrees: positive weights far from 0 */
    int k = (int)ceil(fabs(sweep) / HALF_PI * (1 - 1e-12));
    if (k < 1)
        k = 1;
    double h = sweep / (2.0 * k), ch = cos(h), prev[2] = {0, 0};
    for (int i = 0; i < k; i++) {
        double a = t0 + sweep * i / k, b = i + 1 == k ? t1 : t0 + sweep * (i + 1) / k;
        double mid = a + h, xy[6], w[3] = {1, ch, 1}, q[2];
        if (i == 0) {
            if (p0) {
                q[0] = p0[0];
                q[1] = p0[1];
            } else {
                q[0] = c[0] + M[0] * cos(a) + m[0] * sin(a);
                q[1] = c[1] + M[1] * cos(a) + m[1] * sin(a);
            }
            conica__dxf_xf_apply(xf, q[0], q[1], xy);
        } else {
            xy[0] = prev[0];
            xy[1] = prev[1];
        }
        /* the tangents' intersection: the mid point pushed out by 1/cos(h) */
        q[0] = c[0] + (M[0] * cos(mid) + m[0] * sin(mid)) / ch;
        q[1] = c[1] + (M[1] * cos(mid) + m[1] * sin(mid)) / ch;
        conica__dxf_xf_apply(xf, q[0], q[1], xy + 2);
        if (i + 1 == k && p1) {
            q[0] = p1[0];
            q[1] = p1[1];
        } else {
            q[0] = c[0] + M[0] * cos(b) + m[0] * sin(b);
            q[1] = c[1] + M[1] * cos(b) + m[1] * sin(b);
        }
        conica__dxf_xf_apply(xf, q[0], q[1], xy + 4);
        prev[0] = xy[4];
        prev[1] = xy[5];
        conica_code rc = add_seg(g, 2, xy, w, line, st);
        if (rc != CONICA_OK)
            return rc;
    }
    return CONICA_OK;
}

conica_code conica__dxf_bulge(conica__dxf_geom *g, const conica__dxf_xf *xf, const double p0[2],
                              const double p1[2], double b, size_t line, conica_status *st)
{
    double dx = p1[0] - p0[0], dy = p1[1] - p0[1], d = hypot(dx, dy);
    if (b == 0 || d == 0)
        return conica__dxf_line(g, xf, p0[0], p0[1], p1[0], p1[1], line, st);
    if (!isfinite(b) || fabs(b) > 1e8)
        return conica__fail(st, CONICA_ERR_PARSE, line, 0,
                            "bulge %g is out of range (an arc of nearly 360 degrees)", b);
    /* included angle 4 atan(b); the centre lies (d/2) cot(angle/2) to the
     * left of the chord, cot(angle/2) = (1 - b^2) / (2 b) */
    double theta = 4 * atan(b), cot = (1 - b * b) / (2 * b), r = d * (1 + b * b) / (4 * fabs(b));
    double c[2] = {0.5 * (p0[0] + p1[0]) - 0.5 * dy * cot, 0.5 * (p0[1] + p1[1]) + 0.5 * dx * cot};
    double M[2] = {r, 0}, m[2] = {0, r};
    double a0 = atan2(p0[1] - c[1], p0[0] - c[0]);
    return conica__dxf_arc(g, xf, c, M, m, a0, a0 + theta, p0, p1, line, st);
}

conica_code conica__dxf_spline_pieces(conica__dxf_geom *g, const conica__dxf_xf *xf,
                                      const conica_bspline *bs, size_t line, conica_status *st)
{
    conica_bspline bz;
    conica_code rc;
    double c[2 * (CONICA_PATH_MAX_DEGREE + 1)], w[CONICA_PATH_MAX_DEGREE + 1];
    double xy[2 * (CONICA_PATH_MAX_DEGREE + 1)];
    if (bs->degree > CONICA_PATH_MAX_DEGREE)
        return conica__fail(st, CONICA_ERR_UNSUPPORTED, line, 0, "spline of degree %d (at most %d)",
                            bs->degree, CONICA_PATH_MAX_DEGREE);
    conica_bspline_init(&bz);
    if ((rc = conica_bspline_to_bezier(bs, &bz, st)) != CONICA_OK) {
        if (st)
            st->line = line;
        return rc;
    }
    size_t nb = conica_bspline_bezier_count(&bz);
    for (size_t k = 0; k < nb && rc == CONICA_OK; k++) {
        rc = conica_bspline_bezier_piece(&bz, k, c, bz.w ? w : NULL, NULL, NULL, st);
        if (rc != CONICA_OK)
            break;
        for (int i = 0; i <= bz.degree; i++)
            conica__dxf_xf_apply(xf, c[2 * i], c[2 * i + 1], xy + 2 * i);
        if (k > 0) { /* pieces share end points exactly */
            const double *prev = g->pt + 3 * (g->npt - 1);
            xy[0] = prev[0];
            xy[1] = prev[1];
        }
        rc = add_seg(g, bz.degree, xy, bz.w ? w : NULL, line, st);
    }
    conica_bspline_free(&bz);
    return rc;
}

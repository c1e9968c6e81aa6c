/* SPDX-License-Identifier: MIT */
/* One builder per DXF entity the reader draws (the table `builders`):
 * LINE, ARC, CIRCLE, ELLIPSE, LWPOLYLINE, POLYLINE (2D, with its VERTEXes),
 * SPLINE and HATCH boundary paths, each into pieces (dxf_geom.c) under the
 * entity's OCS and the transform of the INSERTs above it. Group codes as in
 * the DXF reference of each entity. Calls dxf_geom and bspline. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dxf_internal.h"
#include "internal.h"

#define PI 3.14159265358979323846
/* An extrusion within this of +-z (after normalising) is the drawing plane. */
#define OCS_PLANE_EPS 1e-12

/* The number of the first group `code` in e (from index `from`), or dflt. */
static double num(const conica__dxf_ent *e, int code, double dflt)
{
    for (size_t i = 1; i < e->n; i++)
        if (e->p[i].code == code)
            return e->p[i].num;
    return dflt;
}

static void warn(conica__dxf_ctx *c, const char *msg)
{
    if (c->warn)
        c->warn(c->warn_ctx, c->info.line, msg);
}

int conica__dxf_ocs(const conica__dxf_ent *e, conica__dxf_xf *ocs)
{
    double nx = num(e, 210, 0), ny = num(e, 220, 0), nz = num(e, 230, 1);
    double l = sqrt(nx * nx + ny * ny + nz * nz);
    static const conica__dxf_xf id = {{1, 0, 0, 0, 1, 0}}, mirror = {{-1, 0, 0, 0, 1, 0}};
    if (!(l > 0) || fabs(nx) > OCS_PLANE_EPS * l || fabs(ny) > OCS_PLANE_EPS * l)
        return 0;
    /* the arbitrary axis algorithm for N = (0, 0, -1): Ax = Wy x N = (-1, 0, 0),
     * Ay = N x Ax = (0, 1, 0): OCS x is WCS -x */
    *ocs = nz > 0 ? id : mirror;
    return 1;
}

/* The piece of the entity begins (every builder calls this first). */
static conica_code begin(conica__dxf_ctx *c, conica_status *st)
{
    return conica__dxf_begin(c->geom, &c->info, st);
}

static conica_code build_line(conica__dxf_ctx *c, const conica__dxf_ent *e,
                              const conica__dxf_xf *xf, conica_status *st)
{
    conica_code rc = begin(c, st);
    if (rc == CONICA_OK)
        rc = conica__dxf_line(c->geom, xf, num(e, 10, 0), num(e, 20, 0), num(e, 11, 0),
                              num(e, 21, 0), c->info.line, st);
    conica__dxf_end(c->geom, 0);
    return rc;
}

/* ARC and CIRCLE: centre and radius in the OCS, angles counter-clockwise
 * in degrees (ARC: from 50 to 51, CIRCLE: the whole turn from 0). */
static conica_code build_arc(conica__dxf_ctx *c, const conica__dxf_ent *e,
                             const conica__dxf_xf *xf, int full, conica_status *st)
{
    double r = num(e, 40, 0), cen[2] = {num(e, 10, 0), num(e, 20, 0)};
    double a0 = full ? 0 : num(e, 50, 0), a1 = full ? 360 : num(e, 51, 0);
    double c0, s0, c1, s1, p0[2], p1[2];
    conica_code rc;
    if (!(r > 0))
        return conica__fail(st, CONICA_ERR_PARSE, c->info.line, 0, "%s radius %g is not positive",
                            c->info.type, r);
    if (!full) {
        a0 = fmod(a0, 360.0);
        a1 = fmod(a1, 360.0);
        if (a1 <= a0)
            a1 += 360;
    }
    conica__dxf_sincos_deg(a0, &c0, &s0);
    conica__dxf_sincos_deg(a1, &c1, &s1);
    p0[0] = cen[0] + r * c0;
    p0[1] = cen[1] + r * s0;
    p1[0] = full ? p0[0] : cen[0] + r * c1;
    p1[1] = full ? p0[1] : cen[1] + r * s1;
    double M[2] = {r, 0}, m[2] = {0, r};
    if ((rc = begin(c, st)) == CONICA_OK)
        rc = conica__dxf_arc(c->geom, xf, cen, M, m, a0 * (PI / 180), a1 * (PI / 180), p0, p1,
                             c->info.line, st);
    conica__dxf_end(c->geom, full);
    return rc;
}

/* ELLIPSE: centre and major axis in the WCS, the minor axis ratio * (N x
 * major), parameters 41..42 in radians. */
static conica_code build_ellipse(conica__dxf_ctx *c, const conica__dxf_ent *e,
                                 const conica__dxf_xf *xf, double nz, conica_status *st)
{
    double cen[2] = {num(e, 10, 0), num(e, 20, 0)}, M[2] = {num(e, 11, 0), num(e, 21, 0)};
    double ratio = num(e, 40, 1), t0 = num(e, 41, 0), t1 = num(e, 42, 2 * PI), m[2];
    conica_code rc;
    if (!(ratio > 0 && ratio <= 1e6) || (M[0] == 0 && M[1] == 0))
        return conica__fail(st, CONICA_ERR_PARSE, c->info.line, 0,
                            "ELLIPSE with axis ratio %g or a zero major axis", ratio);
    m[0] = nz > 0 ? -ratio * M[1] : ratio * M[1];
    m[1] = nz > 0 ? ratio * M[0] : -ratio * M[0];
    int full = fabs(t1 - t0 - 2 * PI) < 1e-12 || (t0 == 0 && t1 == 2 * PI) || t1 == t0;
    if (full) {
        t1 = t0 + 2 * PI;
    } else {
        while (t1 <= t0)
            t1 += 2 * PI;
    }
    if ((rc = begin(c, st)) == CONICA_OK) {
        if (full) {
            /* exact quarter points: the ends of the axes */
            double p[2] = {cen[0] + M[0], cen[1] + M[1]};
            rc = conica__dxf_arc(c->geom, xf, cen, M, m, 0, 2 * PI, p, p, c->info.line, st);
        } else {
            rc = conica__dxf_arc(c->geom, xf, cen, M, m, t0, t1, NULL, NULL, c->info.line, st);
        }
    }
    conica__dxf_end(c->geom, full);
    return rc;
}

static void note_width(conica__dxf_ctx *c, double w)
{
    if (w != 0 && c->widths_warned++ == 0)
        warn(c, "polyline widths are not supported: the centre line is read (further widths "
                "not reported)");
}

/* The vertices (code 10/20, bulge 42) of a polyline as its pieces. */
typedef struct vtx {
    double x, y, b;
} vtx;

static conica_code poly_pieces(conica__dxf_ctx *c, const vtx *v, size_t n, int closed,
                               const conica__dxf_xf *xf, conica_status *st)
{
    conica_code rc = begin(c, st);
    for (size_t i = 0; rc == CONICA_OK && i + 1 < n + (closed ? 1 : 0); i++) {
        const vtx *a = &v[i], *b = &v[(i + 1) % n];
        double p0[2] = {a->x, a->y}, p1[2] = {b->x, b->y};
        rc = conica__dxf_bulge(c->geom, xf, p0, p1, a->b, c->info.line, st);
    }
    conica__dxf_end(c->geom, closed);
    return rc;
}

static conica_code vtx_push(conica__dxf_ctx *c, vtx **v, size_t *n, size_t *cap, double x,
                            double y, conica_status *st)
{
    if (*n >= c->lim->max_vertices)
        return conica__fail(st, CONICA_ERR_LIMIT, c->info.line, 0,
                            "%s has more than %zu vertices (max_vertices)", c->info.type,
                            c->lim->max_vertices);
    if (*n == *cap) {
        size_t nc = *cap ? 2 * *cap : 16;
        vtx *q = realloc(*v, nc * sizeof *q);
        if (!q)
            return conica__fail(st, CONICA_ERR_NOMEM, c->info.line, 0, "out of memory");
        *v = q;
        *cap = nc;
    }
    (*v)[*n].x = x;
    (*v)[*n].y = y;
    (*v)[*n].b = 0;
    (*n)++;
    return CONICA_OK;
}

static conica_code build_lwpolyline(conica__dxf_ctx *c, const conica__dxf_ent *e,
                                    const conica__dxf_xf *xf, conica_status *st)
{
    vtx *v = NULL;
    size_t n = 0, cap = 0;
    conica_code rc = CONICA_OK;
    note_width(c, num(e, 43, 0));
    for (size_t i = 1; i < e->n && rc == CONICA_OK; i++) {
        const conica__dxf_pair *p = &e->p[i];
        if (p->code == 10)
            rc = vtx_push(c, &v, &n, &cap, p->num, 0, st);
        else if (p->code == 20 && n)
            v[n - 1].y = p->num;
        else if (p->code == 42 && n)
            v[n - 1].b = p->num;
        else if ((p->code == 40 || p->code == 41) && n)
            note_width(c, p->num);
    }
    if (rc == CONICA_OK)
        rc = poly_pieces(c, v, n, ((long long)num(e, 70, 0) & 1) != 0, xf, st);
    free(v);
    return rc;
}

/* POLYLINE with its VERTEX entities up to SEQEND. 3D polylines and meshes
 * are not drawn (*is3d). */
static conica_code build_polyline(conica__dxf_ctx *c, const conica__dxf_ent *e,
                                  const conica__dxf_xf *xf, int *is3d, conica_status *st)
{
    long long flags = (long long)num(e, 70, 0);
    vtx *v = NULL;
    size_t n = 0, cap = 0;
    conica_code rc = CONICA_OK;
    *is3d = (flags & (8 | 16 | 64)) != 0;
    if (*is3d)
        return CONICA_OK;
    note_width(c, num(e, 40, 0));
    note_width(c, num(e, 41, 0));
    for (size_t i = 1; i < e->n && rc == CONICA_OK; i++) {
        if (!conica__dxf_is(&e->p[i], 0, "VERTEX"))
            continue;
        double x = 0, y = 0, b = 0;
        long long vf = 0;
        size_t j;
        for (j = i + 1; j < e->n && e->p[j].code != 0; j++) {
            const conica__dxf_pair *p = &e->p[j];
            if (p->code == 10)
                x = p->num;
            else if (p->code == 20)
                y = p->num;
            else if (p->code == 42)
                b = p->num;
            else if (p->code == 70)
                vf = (long long)p->num;
            else if (p->code == 40 || p->code == 41)
                note_width(c, p->num);
        }
        /* a spline frame's control points are not on the curve drawn */
        if (!(vf & 16)) {
            rc = vtx_push(c, &v, &n, &cap, x, y, st);
            if (rc == CONICA_OK)
                v[n - 1].b = b;
        }
        i = j - 1;
    }
    if (rc == CONICA_OK)
        rc = poly_pieces(c, v, n, (flags & 1) != 0, xf, st);
    free(v);
    return rc;
}

conica_code conica__dxf_spline_of(const conica__dxf_ent *e, const conica_dxf_limits *lim,
                                  const char *handle, conica_bspline *out, conica_status *st)
{
    size_t nk = 0, nc = 0, nw = 0, nfit = 0, line = e->n ? e->p[0].line : 0;
    int degree = (int)num(e, 71, 3);
    for (size_t i = 1; i < e->n; i++) {
        int k = e->p[i].code;
        nk += k == 40;
        nc += k == 10;
        nw += k == 41;
        nfit += k == 11;
    }
    if (nc == 0)
        return conica__fail(st, nfit ? CONICA_ERR_UNSUPPORTED : CONICA_ERR_PARSE, line, 0,
                            nfit ? "SPLINE (handle %s) has fit points only; this reader takes "
                                   "splines with control points (save it with control points, "
                                   "or convert it to a polyline)"
                                 : "SPLINE (handle %s) has no control points",
                            handle[0] ? handle : "none");
    if (nc > lim->max_vertices)
        return conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                            "SPLINE (handle %s) has more than %zu control points (max_vertices)",
                            handle[0] ? handle : "none", lim->max_vertices);
    if (nk > lim->max_knots)
        return conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                            "SPLINE (handle %s) has more than %zu knots (max_knots)",
                            handle[0] ? handle : "none", lim->max_knots);
    if (degree < 1 || degree > CONICA_BSPLINE_MAX_DEGREE || nk != nc + (size_t)degree + 1 ||
        (nw != 0 && nw != nc))
        return conica__fail(st, CONICA_ERR_PARSE, line, 0,
                            "SPLINE (handle %s): degree %d, %zu control points, %zu knots and %zu "
                            "weights do not fit (knots = control points + degree + 1)",
                            handle[0] ? handle : "none", degree, nc, nk, nw);
    double *kn = malloc(nk * sizeof *kn), *xyz = malloc(3 * nc * sizeof *xyz);
    double *w = nw ? malloc(nw * sizeof *w) : NULL;
    conica_code rc;
    if (!kn || !xyz || (nw && !w)) {
        free(kn);
        free(xyz);
        free(w);
        return conica__fail(st, CONICA_ERR_NOMEM, line, 0, "out of memory");
    }
    size_t ik = 0, ic = 0, iw = 0;
    int flat = 1;
    for (size_t i = 1; i < e->n; i++) {
        const conica__dxf_pair *p = &e->p[i];
        if (p->code == 40)
            kn[ik++] = p->num;
        else if (p->code == 41)
            w[iw++] = p->num;
        else if (p->code == 10) {
            xyz[3 * ic] = p->num;
            xyz[3 * ic + 1] = xyz[3 * ic + 2] = 0;
            ic++;
        } else if (p->code == 20 && ic)
            xyz[3 * ic - 2] = p->num;
        else if (p->code == 30 && ic)
            xyz[3 * ic - 1] = p->num;
    }
    for (size_t i = 1; i < nc; i++)
        flat &= xyz[3 * i + 2] == xyz[2];
    if (flat)
        for (size_t i = 0; i < nc; i++) {
            xyz[2 * i] = xyz[3 * i];
            xyz[2 * i + 1] = xyz[3 * i + 1];
        }
    rc = conica_bspline_set(degree, flat ? 2 : 3, kn, nk, xyz, nc, w, out, st);
    if (rc != CONICA_OK && st) {
        char m[sizeof st->message];
        snprintf(m, sizeof m, "SPLINE (handle %.20s): %.200s", handle[0] ? handle : "none",
                 st->message);
        memcpy(st->message, m, sizeof m);
        st->line = line;
    }
    free(kn);
    free(xyz);
    free(w);
    return rc;
}

static conica_code build_spline(conica__dxf_ctx *c, const conica__dxf_ent *e,
                                const conica__dxf_xf *xf, int *is3d, conica_status *st)
{
    conica_bspline bs;
    conica_code rc;
    conica_bspline_init(&bs);
    rc = conica__dxf_spline_of(e, c->lim, c->info.handle, &bs, st);
    *is3d = rc == CONICA_OK && bs.dim != 2;
    if (rc == CONICA_OK && !*is3d) {
        if ((rc = begin(c, st)) == CONICA_OK)
            rc = conica__dxf_spline_pieces(c->geom, xf, &bs, c->info.line, st);
        conica__dxf_end(c->geom, 0);
    }
    conica_bspline_free(&bs);
    return rc;
}

/* ------------------------------------------------------------ HATCH */

/* A cursor over the pairs of a HATCH: its boundary data come in a fixed
 * order, with codes that mean different things in different places. */
typedef struct hcur {
    const conica__dxf_ent *e;
    size_t i;
} hcur;

/* The value of the next pair if it has `code` (consumed), else dflt. */
static double take(hcur *h, int code, double dflt, int *found)
{
    if (h->i < h->e->n && h->e->p[h->i].code == code) {
        if (found)
            *found = 1;
        return h->e->p[h->i++].num;
    }
    if (found)
        *found = 0;
    return dflt;
}

/* The next pair with `code` (consumed) within the entity: 0 if none. */
static int seek(hcur *h, int code)
{
    while (h->i < h->e->n && h->e->p[h->i].code != code)
        h->i++;
    return h->i < h->e->n;
}

static conica_code hatch_count(conica__dxf_ctx *c, double v, size_t *n, conica_status *st)
{
    if (!(v >= 0) || v > (double)c->lim->max_vertices)
        return conica__fail(st, CONICA_ERR_LIMIT, c->info.line, 0,
                            "HATCH count %g is beyond max_vertices (%zu)", v, c->lim->max_vertices);
    *n = (size_t)v;
    return CONICA_OK;
}

/* One edge of an edge boundary path as a piece of its own (chained later
 * with the other edges of the path). */
static conica_code hatch_edge(conica__dxf_ctx *c, hcur *h, const conica__dxf_xf *xf,
                              conica_status *st)
{
    int type = (int)take(h, 72, 0, NULL);
    conica_code rc = begin(c, st);
    if (rc != CONICA_OK)
        return rc;
    if (type == 1) {
        double x0 = take(h, 10, 0, NULL), y0 = take(h, 20, 0, NULL);
        double x1 = take(h, 11, 0, NULL), y1 = take(h, 21, 0, NULL);
        rc = conica__dxf_line(c->geom, xf, x0, y0, x1, y1, c->info.line, st);
    } else if (type == 2 || type == 3) {
        double cen[2], M[2] = {0, 0}, m[2], r, a0, a1, ratio = 1;
        cen[0] = take(h, 10, 0, NULL);
        cen[1] = take(h, 20, 0, NULL);
        if (type == 3) {
            M[0] = take(h, 11, 0, NULL);
            M[1] = take(h, 21, 0, NULL);
        }
        r = take(h, 40, 0, NULL);
        a0 = take(h, 50, 0, NULL);
        a1 = take(h, 51, 360, NULL);
        int ccw = (int)take(h, 73, 1, NULL);
        if (type == 2) {
            M[0] = r;
            ratio = 1;
        } else {
            ratio = r;
        }
        if (!(hypot(M[0], M[1]) > 0) || !(ratio > 0))
            return conica__fail(st, CONICA_ERR_PARSE, c->info.line, 0,
                                "HATCH arc edge with a radius or axis of zero");
        m[0] = -ratio * M[1];
        m[1] = ratio * M[0];
        /* clockwise edges store the complements of their angles (360 - a) */
        if (!ccw) {
            double t = a0;
            a0 = 360 - a1;
            a1 = 360 - t;
        }
        if (a1 - a0 >= 360)
            a1 = a0 + 360;
        while (a1 <= a0)
            a1 += 360;
        double t0 = a0 * (PI / 180), t1 = a1 * (PI / 180);
        if (type == 3) { /* angles to the ellipse's parameters */
            double c0, s0, c1, s1;
            conica__dxf_sincos_deg(a0, &c0, &s0);
            conica__dxf_sincos_deg(a1, &c1, &s1);
            double u0 = atan2(s0 / ratio, c0), u1 = atan2(s1 / ratio, c1);
            while (u1 <= u0)
                u1 += 2 * PI;
            if (a1 - a0 >= 360)
                u1 = u0 + 2 * PI;
            t0 = u0;
            t1 = u1;
        }
        rc = conica__dxf_arc(c->geom, xf, cen, M, m, t0, t1, NULL, NULL, c->info.line, st);
    } else if (type == 4) {
        int degree = (int)take(h, 94, 3, NULL), rational = (int)take(h, 73, 0, NULL);
        size_t nk = 0, nc = 0;
        (void)take(h, 74, 0, NULL);
        if ((rc = hatch_count(c, take(h, 95, 0, NULL), &nk, st)) != CONICA_OK ||
            (rc = hatch_count(c, take(h, 96, 0, NULL), &nc, st)) != CONICA_OK)
            return rc;
        double *kn = malloc((nk + 1) * sizeof *kn), *xy = malloc((2 * nc + 1) * sizeof *xy);
        double *w = malloc((nc + 1) * sizeof *w);
        if (!kn || !xy || !w) {
            free(kn);
            free(xy);
            free(w);
            return conica__fail(st, CONICA_ERR_NOMEM, c->info.line, 0, "out of memory");
        }
        int ok = 1, f;
        for (size_t i = 0; i < nk && ok; i++)
            kn[i] = take(h, 40, 0, &ok);
        for (size_t i = 0; i < nc && ok; i++) {
            xy[2 * i] = take(h, 10, 0, &ok);
            if (ok)
                xy[2 * i + 1] = take(h, 20, 0, &ok);
            w[i] = take(h, 42, 1, &f);
        }
        size_t nfit = 0;
        if (ok && (rc = hatch_count(c, take(h, 97, 0, NULL), &nfit, st)) == CONICA_OK) {
            for (size_t i = 0; i < nfit; i++) {
                take(h, 11, 0, NULL);
                take(h, 21, 0, NULL);
            }
            take(h, 12, 0, NULL);
            take(h, 22, 0, NULL);
            take(h, 13, 0, NULL);
            take(h, 23, 0, NULL);
        }
        if (rc == CONICA_OK && !ok)
            rc = conica__fail(st, CONICA_ERR_PARSE, c->info.line, 0,
                              "HATCH spline edge: fewer knots or control points than its counts");
        if (rc == CONICA_OK) {
            conica_bspline bs;
            conica_bspline_init(&bs);
            rc = conica_bspline_set(degree, 2, kn, nk, xy, nc, rational ? w : NULL, &bs, st);
            if (rc == CONICA_OK)
                rc = conica__dxf_spline_pieces(c->geom, xf, &bs, c->info.line, st);
            else if (st)
                st->line = c->info.line;
            conica_bspline_free(&bs);
        }
        free(kn);
        free(xy);
        free(w);
    } else {
        rc = conica__fail(st, CONICA_ERR_PARSE, c->info.line, 0, "HATCH edge of unknown type %d",
                          type);
    }
    conica__dxf_end(c->geom, 0);
    return rc;
}

static conica_code build_hatch(conica__dxf_ctx *c, const conica__dxf_ent *e,
                               const conica__dxf_xf *xf, conica_status *st)
{
    hcur h = {e, 1};
    size_t npaths = 0;
    conica_code rc = CONICA_OK;
    if (!seek(&h, 91))
        return CONICA_OK;
    if ((rc = hatch_count(c, take(&h, 91, 0, NULL), &npaths, st)) != CONICA_OK)
        return rc;
    for (size_t k = 0; k < npaths && rc == CONICA_OK; k++) {
        if (!seek(&h, 92))
            return conica__fail(st, CONICA_ERR_PARSE, c->info.line, 0,
                                "HATCH: %zu boundary paths announced, %zu found", npaths, k);
        long long flags = (long long)take(&h, 92, 0, NULL);
        size_t n = 0;
        c->info.group = ++c->hatch_group;
        if (flags & 2) { /* a polyline */
            int bulges = (int)take(&h, 72, 0, NULL), closed = (int)take(&h, 73, 1, NULL), ok = 1;
            vtx *v = NULL;
            size_t nv = 0, cap = 0;
            if ((rc = hatch_count(c, take(&h, 93, 0, NULL), &n, st)) != CONICA_OK)
                return rc;
            for (size_t i = 0; i < n && ok && rc == CONICA_OK; i++) {
                double x = take(&h, 10, 0, &ok), y = ok ? take(&h, 20, 0, &ok) : 0;
                double b = bulges ? take(&h, 42, 0, NULL) : 0;
                if (ok && (rc = vtx_push(c, &v, &nv, &cap, x, y, st)) == CONICA_OK)
                    v[nv - 1].b = b;
            }
            if (rc == CONICA_OK && !ok)
                rc = conica__fail(st, CONICA_ERR_PARSE, c->info.line, 0,
                                  "HATCH polyline path: fewer vertices than its count %zu", n);
            (void)closed; /* a boundary path is closed whatever the flag says */
            if (rc == CONICA_OK)
                rc = poly_pieces(c, v, nv, 1, xf, st);
            free(v);
        } else {
            if ((rc = hatch_count(c, take(&h, 93, 0, NULL), &n, st)) != CONICA_OK)
                return rc;
            for (size_t i = 0; i < n && rc == CONICA_OK; i++) {
                if (h.i >= e->n || e->p[h.i].code != 72)
                    return conica__fail(st, CONICA_ERR_PARSE, c->info.line, 0,
                                        "HATCH edge path: %zu edges announced, %zu found", n, i);
                rc = hatch_edge(c, &h, xf, st);
            }
        }
    }
    c->info.group = 0;
    return rc;
}

conica_code conica__dxf_entity(conica__dxf_ctx *c, const conica__dxf_ent *e,
                               const conica__dxf_xf *xf, int *known, conica_status *st)
{
    static const char *const types[] = {"LINE",       "ARC",      "CIRCLE", "ELLIPSE",
                                        "LWPOLYLINE", "POLYLINE", "SPLINE", "HATCH"};
    conica__dxf_xf ocs, full;
    int t = -1, is3d = 0;
    conica_code rc = CONICA_OK;
    for (int k = 0; k < (int)(sizeof types / sizeof types[0]); k++)
        if (conica__dxf_is(&e->p[0], 0, types[k]))
            t = k;
    *known = t >= 0;
    if (t < 0)
        return CONICA_OK;
    c->info.type = types[t];
    /* LINE and SPLINE are in the WCS; the others in their OCS */
    if (t != 0 && t != 6 && !conica__dxf_ocs(e, &ocs)) {
        *known = 0;
        return CONICA_OK; /* not in the drawing plane: reported as skipped */
    }
    full = t == 0 || t == 6 || t == 3 ? *xf : conica__dxf_xf_mul(xf, &ocs);
    switch (t) {
    case 0: rc = build_line(c, e, &full, st); break;
    case 1: rc = build_arc(c, e, &full, 0, st); break;
    case 2: rc = build_arc(c, e, &full, 1, st); break;
    case 3: rc = build_ellipse(c, e, &full, ocs.m[0], st); break;
    case 4: rc = build_lwpolyline(c, e, &full, st); break;
    case 5: rc = build_polyline(c, e, &full, &is3d, st); break;
    case 6: rc = build_spline(c, e, &full, &is3d, st); break;
    default: rc = build_hatch(c, e, &full, st); break;
    }
    if (is3d)
        *known = 0;
    return rc;
}

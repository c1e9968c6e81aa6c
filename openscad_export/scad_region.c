/* SPDX-License-Identifier: MIT */
/* The region an SVG scene paints (scad_region.h), for scadprofile.
 *
 * Per item: its path as drawn (libcore's conica_path: lines, Béziers, arcs
 * as exact rational quadratics), mapped to the output frame exactly (an
 * affine map moves control points and keeps weights). Its fill is the
 * one-sided fit of every subpath (path_fit.h; the painted side of each
 * stretch read from a dense polygon of the item's own fill) resolved under
 * its fill rule by Clipper; its stroke the Clipper offset of its centre
 * line, in the item's user space (then mapped: a non-uniform transform
 * strokes exactly as SVG defines it) or, for vector-effect
 * non-scaling-stroke, in the output frame, dashes split first. Each item is
 * clipped by its viewports and the items unioned. A fit that keeps to one
 * side of each item's region keeps to it for the union too: if every
 * A'_i lies in A_i and A_i within T of A'_i, the same holds for the unions.
 *
 * The same construction with dense two-sided chords gives the reference;
 * the fit is then checked against it with Clipper differences of offset
 * regions before anything is written.
 *
 * A drawing already in the path model (a DXF's contours) takes the same
 * fill construction and the same check (conica__scad_region_path): one
 * fit-and-verify rule for every input.
 *
 * Calls: libcore (path storage, path_fit.h, status helpers), the SVG
 * layer's scene types, scad_clip.h. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "path_fit.h"
#include "scad_region.h"
#include "scad_stroke.h"
#include "svg_internal.h"

typedef struct item_paths {
    conica_path local; /* in the item's user space */
    conica_path out;   /* in the output frame, y up */
} item_paths;

/* flip(ctm): user space -> output frame, y up */
static conica_svg_matrix out_map(const conica_svg_item *it, double height)
{
    conica_svg_matrix m = it->ctm;
    m.b = -m.b;
    m.d = -m.d;
    m.f = height - m.f;
    return m;
}

static void map_pt(const conica_svg_matrix *m, double x, double y, double *o)
{
    o[0] = fma(m->a, x, fma(m->c, y, m->e));
    o[1] = fma(m->b, x, fma(m->d, y, m->f));
}

/* Largest stretch of the linear part (its largest singular value). */
static double map_stretch(const conica_svg_matrix *m)
{
    double a = m->a, b = m->b, c = m->c, d = m->d;
    double s = a * a + b * b + c * c + d * d, det = a * d - b * c;
    double r = sqrt(fmax(0.0, s * s - 4 * det * det));
    return sqrt(0.5 * (s + r));
}

/* The SVG path data as a conica_path in user space. */
static conica_code build_local(const conica_svg_path *p, conica_path *cp, conica_status *st)
{
    conica_code rc = CONICA_OK;
    for (size_t i = 0; i < p->n && rc == CONICA_OK; i++) {
        const conica_svg_seg *g = &p->seg[i];
        if (g->type == CONICA_SVG_SEG_MOVE) {
            rc = conica_path_move_to(cp, g->x1, g->y1, i, st);
            continue;
        }
        if (!cp->open)
            rc = conica_path_move_to(cp, g->x0, g->y0, i, st);
        if (rc != CONICA_OK)
            break;
        switch (g->type) {
        case CONICA_SVG_SEG_CLOSE:
            /* the closing line as drawn: conica_path_close() would take an
             * end within 1e-12 of the subpath's extent for its start, which
             * on a 1e12 x 1 rectangle is a corner */
            if (g->x0 != g->x1 || g->y0 != g->y1)
                rc = conica_path_line_to(cp, g->x1, g->y1, i, st);
            if (rc == CONICA_OK)
                rc = conica_path_close(cp, st);
            break;
        default:
            rc = conica_svg__seg_to_path(cp, g, i, st);
            break;
        }
    }
    return rc;
}

/* A copy of src with every control point mapped by m (weights kept: the
 * image of a rational Bézier under an affine map is the rational Bézier of
 * the mapped control points). */
static conica_code map_path(const conica_path *src, const conica_svg_matrix *m, conica_path *dst,
                            conica_status *st)
{
    conica_code rc = CONICA_OK;
    for (size_t i = 0; i < src->nsub && rc == CONICA_OK; i++) {
        const conica_path_subpath *sp = &src->sub[i];
        double o[2];
        if (sp->kind != CONICA_PATH_DRAWN)
            continue;
        map_pt(m, sp->x0, sp->y0, o);
        rc = conica_path_move_to(dst, o[0], o[1], 0, st);
        for (size_t j = 0; j < sp->n && rc == CONICA_OK; j++) {
            const conica_path_seg *g = &src->seg[sp->first + j];
            const double *q = src->pt + 3 * g->first;
            double c[2 * CONICA_PATH_MAX_DEGREE], w[CONICA_PATH_MAX_DEGREE + 1];
            for (int k = 1; k <= g->degree; k++)
                map_pt(m, q[3 * k], q[3 * k + 1], c + 2 * (k - 1));
            for (int k = 0; k <= g->degree; k++)
                w[k] = q[3 * k + 2];
            if (g->degree == 1)
                rc = conica_path_line_to(dst, c[0], c[1], g->tag, st);
            else
                rc = conica_path_bezier_to(dst, g->degree, c, g->rational ? w : NULL, g->tag, st);
        }
        if (rc == CONICA_OK && sp->closed)
            rc = conica_path_close(dst, st);
    }
    return rc;
}

/* ------------------------------------------------------------ fills */

/* The dense fill's edges in horizontal bands, so that a winding number
 * reads only the edges of its point's band (the fit asks for thousands).
 * Each entry is an edge by the index of its first point and of its second. */
typedef struct wind_index {
    const conica__polys *p;
    double y0, h;
    size_t nb;
    size_t *first; /* nb + 1 offsets into edge */
    size_t *edge;  /* pairs */
} wind_index;

static size_t band_of(const wind_index *w, double y)
{
    double b = floor((y - w->y0) / w->h);
    return b < 0 ? 0 : b >= (double)w->nb ? w->nb - 1 : (size_t)b;
}

/* 0, or -1 out of memory (w is then empty: winding reads every edge). */
static int wind_index_build(wind_index *w, const conica__polys *p)
{
    double lo = INFINITY, hi = -INFINITY;
    size_t ne = 0;
    memset(w, 0, sizeof *w);
    w->p = p;
    for (size_t k = 0; k < p->npts; k++) {
        lo = fmin(lo, p->xy[2 * k + 1]);
        hi = fmax(hi, p->xy[2 * k + 1]);
    }
    if (p->npts < 64 || !(hi > lo))
        return 0;
    w->nb = (size_t)sqrt((double)p->npts);
    w->y0 = lo;
    w->h = (hi - lo) / (double)w->nb;
    w->first = calloc(w->nb + 1, sizeof *w->first);
    if (!w->first)
        goto fail;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < p->n; i++) {
            size_t a = p->start[i], n = p->start[i + 1] - a;
            for (size_t k = 0; k < n; k++) {
                double ya = p->xy[2 * (a + k) + 1], yb = p->xy[2 * (a + (k + 1) % n) + 1];
                if (ya == yb)
                    continue; /* never counted */
                for (size_t b = band_of(w, fmin(ya, yb)); b <= band_of(w, fmax(ya, yb)); b++) {
                    if (pass == 0) {
                        w->first[b + 1]++;
                        ne++;
                    } else {
                        size_t at = w->first[b]++;
                        w->edge[2 * at] = a + k;
                        w->edge[2 * at + 1] = a + (k + 1) % n;
                    }
                }
            }
        }
        if (pass == 0) {
            for (size_t b = 0; b < w->nb; b++)
                w->first[b + 1] += w->first[b];
            w->edge = malloc(2 * (ne ? ne : 1) * sizeof *w->edge);
            if (!w->edge)
                goto fail;
        } else { /* each first[b] moved to first[b + 1]: shift back */
            memmove(w->first + 1, w->first, w->nb * sizeof *w->first);
            w->first[0] = 0;
        }
    }
    return 0;
fail:
    free(w->first);
    free(w->edge);
    memset(w, 0, sizeof *w);
    w->p = p;
    return -1;
}

static void wind_index_free(wind_index *w)
{
    free(w->first);
    free(w->edge);
}

/* conica__polys_winding(w->p, x, y), by the band of y. */
static int wind_at(const wind_index *w, double x, double y)
{
    int c = 0;
    if (!w->nb)
        return conica__polys_winding(w->p, x, y);
    if (y < w->y0 || y > w->y0 + w->h * (double)w->nb)
        return 0;
    size_t b = band_of(w, y);
    for (size_t i = w->first[b]; i < w->first[b + 1]; i++)
        c += conica__winding_step(w->p->xy + 2 * w->edge[2 * i], w->p->xy + 2 * w->edge[2 * i + 1],
                                  x, y);
    return c;
}

typedef struct side_ctx {
    wind_index dense;
    double eps;
} side_ctx;

/* Painted side from the item's dense fill: probes either side of the curve
 * (dir NULL: is pt itself painted). */
static int painted_side(void *ctx, const double pt[2], const double dir[2])
{
    const side_ctx *c = ctx;
    if (!dir)
        return wind_at(&c->dense, pt[0], pt[1]) != 0;
    double n[2] = {-dir[1], dir[0]};
    for (int k = 0; k < 2; k++) {
        double e = k ? c->eps : c->eps / 16; /* near first: a thin feature is not jumped */
        int l = wind_at(&c->dense, pt[0] + e * n[0], pt[1] + e * n[1]) != 0;
        int r = wind_at(&c->dense, pt[0] - e * n[0], pt[1] - e * n[1]) != 0;
        if (l != r)
            return l ? 1 : -1;
    }
    return 0;
}

typedef struct buf {
    double *xy;
    size_t n, cap;
} buf;

/* Does the polygon enclose no area: fewer than 3 distinct points, or all
 * on one line (exact orientation tests)? *distinct gets its point count
 * without repeats. */
static int encloses_nothing(const double *xy, size_t n, size_t *distinct)
{
    size_t m = 0, a = 0, b = SIZE_MAX;
    for (size_t k = 0; k < n; k++)
        if (k == 0 || xy[2 * k] != xy[2 * k - 2] || xy[2 * k + 1] != xy[2 * k - 1]) {
            m++;
            if (b == SIZE_MAX && (xy[2 * k] != xy[0] || xy[2 * k + 1] != xy[1]))
                b = k;
        }
    if (m > 1 && xy[2 * n - 2] == xy[0] && xy[2 * n - 1] == xy[1])
        m--;
    *distinct = m;
    if (m < 3)
        return 1;
    for (size_t k = 0; k < n; k++)
        if (conica__orient2d(xy + 2 * a, xy + 2 * b, xy + 2 * k) != 0)
            return 0;
    return 1;
}

/* The input line of subpath i of a source (its own line when it has none
 * per subpath). */
static size_t source_line(const conica__region_source *w, size_t i)
{
    return w->sub_line && i < w->nsub_line ? w->sub_line[i] : w->line;
}

/* Every subpath of path as a polygon (fit per side; CHORDS: dense) into raw.
 * w: warn (s->warn) about the subpaths that enclose no area, naming them
 * (NULL: quiet); an error names the subpath's line when w has them. */
static conica_code fill_polys(const conica_path *path, double tol, conica__fit_side side,
                              const conica__polys *dense, double eps, size_t max_points,
                              const conica__region_source *w, const conica__region_settings *s,
                              conica__polys *raw, conica_status *st)
{
    buf b = {NULL, 0, 0};
    side_ctx sc;
    conica_code rc = CONICA_OK;
    if (dense && wind_index_build(&sc.dense, dense) != 0)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    if (!dense)
        memset(&sc.dense, 0, sizeof sc.dense);
    sc.eps = eps;
    for (size_t i = 0; i < path->nsub && rc == CONICA_OK; i++) {
        if (path->sub[i].kind != CONICA_PATH_DRAWN)
            continue;
        size_t line = w ? source_line(w, i) : 0;
        if (path->sub[i].n == 0) { /* a lone point */
            if (w && s->warn) {
                char msg[256];
                snprintf(msg, sizeof msg, "%.100s: %s %zu has 1 point (a polygon needs 3); "
                         "skipped", w->name, w->part, i + 1);
                s->warn(s->warn_ctx, line, msg);
            }
            continue;
        }
        b.n = 0;
        rc = conica__path_fit(path, i, tol, side, dense ? painted_side : NULL, &sc, max_points,
                              &b.xy, &b.n, &b.cap, st);
        if (rc != CONICA_OK && st && line)
            st->line = line;
        size_t m;
        if (rc == CONICA_OK && w && s->warn && b.n && encloses_nothing(b.xy, b.n, &m)) {
            char msg[256];
            if (m < 3)
                snprintf(msg, sizeof msg, "%.100s: %s %zu has %zu point%s (a polygon needs 3); "
                         "skipped", w->name, w->part, i + 1, m, m == 1 ? "" : "s");
            else
                snprintf(msg, sizeof msg, "%.100s: %s %zu has zero area (its points are "
                         "collinear or it encloses no area); skipped", w->name, w->part, i + 1);
            s->warn(s->warn_ctx, line, msg);
        }
        if (rc == CONICA_OK && b.n >= 3 && conica__polys_add(raw, b.xy, b.n) != 0)
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    free(b.xy);
    wind_index_free(&sc.dense);
    return rc;
}

/* MIDDLE: the engine's straddling chords (conica_path_flatten). */
static conica_code fill_middle(const conica_path *path, double tol, size_t max_points,
                               conica__polys *raw, conica_status *st)
{
    conica_path_settings ps = conica_path_defaults();
    conica_path_result r;
    conica_code rc;
    ps.tolerance = tol;
    ps.fit = CONICA_PATH_FIT_MIDDLE;
    ps.max_points = max_points;
    conica_path_result_init(&r);
    rc = conica_path_flatten(path, &ps, &r, st);
    for (size_t i = 0; i < r.n && rc == CONICA_OK; i++)
        if (r.lines[i].n >= 3 && conica__polys_add(raw, r.lines[i].xy, r.lines[i].n) != 0)
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    conica_path_result_free(&r);
    return rc;
}

/* ------------------------------------------------------------ strokes */

/* Split the polyline xy (n points; closed: back to its start) into the
 * dashes of the pattern, each appended to out as an open polyline. */
static int add_dashes(const double *xy, size_t n, int closed, const conica_svg_stroke *sk,
                      conica__polys *out)
{
    double total = 0, period = 0, pos, *tmp;
    size_t nseg = closed ? n : n - 1, di = 0, m = 0;
    int on = 1;
    if (n < 2)
        return 0;
    for (size_t k = 0; k < sk->ndash; k++)
        period += sk->dash[k];
    if (!(period > 0))
        return 0;
    tmp = malloc(2 * (n + 2) * sizeof *tmp);
    if (!tmp)
        return -1;
    /* where in the pattern the start is */
    pos = fmod(sk->dashoffset, period);
    if (pos < 0)
        pos += period;
    while (pos >= sk->dash[di]) {
        pos -= sk->dash[di];
        di = (di + 1) % sk->ndash;
        on = !on;
    }
    double left = sk->dash[di] - pos; /* of the current dash or gap */
    if (on) {
        tmp[0] = xy[0];
        tmp[1] = xy[1];
        m = 1;
    }
    for (size_t s = 0; s < nseg; s++) {
        const double *a = xy + 2 * s, *b = xy + 2 * ((s + 1) % n);
        double len = hypot(b[0] - a[0], b[1] - a[1]), at = 0;
        total += len;
        while (len - at > left) {
            double u = (at + left) / len, p[2] = {a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])};
            at += left;
            if (on) {
                tmp[2 * m] = p[0];
                tmp[2 * m + 1] = p[1];
                m++;
                if (m >= 2 && conica__polys_add(out, tmp, m) != 0) {
                    free(tmp);
                    return -1;
                }
                m = 0;
            } else {
                tmp[0] = p[0];
                tmp[1] = p[1];
                m = 1;
            }
            on = !on;
            di = (di + 1) % sk->ndash;
            left = sk->dash[di];
            if (!(left > 0)) /* a zero-length dash or gap */
                left = 0;
        }
        left -= len - at;
        if (on) {
            if (m + 1 > n + 1) { /* cannot happen: one point per vertex */
                free(tmp);
                return -1;
            }
            tmp[2 * m] = b[0];
            tmp[2 * m + 1] = b[1];
            m++;
        }
    }
    if (on && m >= 2 && conica__polys_add(out, tmp, m) != 0) {
        free(tmp);
        return -1;
    }
    free(tmp);
    (void)total;
    return 0;
}

/* The stroke of one item: centre lines within line_tol, offset by
 * width/2 + bias (output units; in user space divided by the map's
 * stretch), round parts within arc_tol, into region (output frame). */
static conica_code stroke_region(const conica_svg_item *it, const item_paths *ip,
                                 const conica_svg_matrix *m, double line_tol, double arc_tol,
                                 double bias, double scale, size_t max_points,
                                 conica__polys *region, conica_status *st)
{
    const conica_svg_stroke *sk = &it->st;
    int local = !sk->non_scaling;
    const conica_path *path = local ? &ip->local : &ip->out;
    double k = local ? map_stretch(m) : 1.0;
    conica__polys closed, open, off;
    buf b = {NULL, 0, 0};
    conica_code rc = CONICA_OK;
    double max_turn;
    double delta = 0.5 * sk->width + bias / k;
    /* Between the chords of a curve a miter or square join overshoots the
     * exact offset by delta (1 / cos(turn / 2) - 1): keep that within the
     * centre line's share (a round join stays within the stroke) */
    max_turn = 2 * acos(fmin(1.0, (delta * k) / (delta * k + line_tol)));
    if (!(k > 0) || !isfinite(k) || !(delta > 0)) {
        conica__ok(st);
        return CONICA_OK; /* a degenerate map draws nothing */
    }
    conica__polys_init(&closed);
    conica__polys_init(&open);
    conica__polys_init(&off);
    for (size_t i = 0; i < path->nsub && rc == CONICA_OK; i++) {
        const conica_path_subpath *sp = &path->sub[i];
        if (sp->kind != CONICA_PATH_DRAWN || sp->n == 0)
            continue;
        b.n = 0;
        rc = conica__path_chords(path, i, line_tol / k,
                                 sk->join == CONICA_SVG_JOIN_ROUND ? 0.0 : max_turn, max_points,
                                 &b.xy, &b.n,
                                 &b.cap, st);
        if (rc != CONICA_OK)
            break;
        if (sk->ndash > 0) {
            if (add_dashes(b.xy, b.n, sp->closed, sk, &open) != 0)
                rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        } else if (conica__polys_add(sp->closed ? &closed : &open, b.xy, b.n) != 0) {
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        }
    }
    free(b.xy);
    for (int pass = 0; pass < 2 && rc == CONICA_OK; pass++) {
        const conica__polys *src = pass ? &open : &closed;
        conica__stroke_style ss;
        ss.half_width = delta;
        ss.join = sk->join == CONICA_SVG_JOIN_ROUND   ? CONICA__JOIN_ROUND
                  : sk->join == CONICA_SVG_JOIN_BEVEL ? CONICA__JOIN_BEVEL
                                                      : CONICA__JOIN_MITER;
        ss.cap = sk->cap == CONICA_SVG_CAP_ROUND    ? CONICA__CAP_ROUND
                 : sk->cap == CONICA_SVG_CAP_SQUARE ? CONICA__CAP_SQUARE
                                                    : CONICA__CAP_BUTT;
        ss.miterlimit = sk->miterlimit;
        ss.arctol = arc_tol / k;
        ss.max_turn = max_turn;
        off.n = off.npts = 0;
        for (size_t i = 0; i < src->n && rc == CONICA_OK; i++)
            if (conica__scad_stroke(src->xy + 2 * src->start[i], src->start[i + 1] - src->start[i],
                                    !pass, &ss, &off) != 0)
                rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        if (rc == CONICA_OK && local)
            for (size_t q = 0; q < off.npts; q++) {
                double o[2];
                map_pt(m, off.xy[2 * q], off.xy[2 * q + 1], o);
                off.xy[2 * q] = o[0];
                off.xy[2 * q + 1] = o[1];
            }
        /* the pieces' union (a map with negative determinant turns them
         * clockwise: nonzero fills them all the same) */
        if (rc == CONICA_OK && off.n) {
            conica__polys u;
            conica__polys_init(&u);
            rc = conica__clip_fill_region(&off, CONICA__CLIP_NONZERO, scale, 0, &u, st);
            if (rc == CONICA_OK && conica__polys_append(region, &u) != 0)
                rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            conica__polys_free(&u);
        }
    }
    conica__polys_free(&closed);
    conica__polys_free(&open);
    conica__polys_free(&off);
    return rc;
}

/* ------------------------------------------------------------ items */

/* One item's material in the output frame: fit (fitted) and reference
 * (dense), each resolved and clipped. */
/* The fill of path (output frame) under rule: its one-sided fit into
 * fitted and its dense reference into dense, each resolved by Clipper.
 * w: who warns about subpaths without area (NULL: quiet). */
static conica_code fill_region(const conica_path *path, conica__clip_fill rule,
                               const conica__region_source *w, const conica__region_settings *s,
                               double scale, conica__polys *fitted, conica__polys *dense,
                               conica_status *st)
{
    double T = s->tolerance, dT = T * CONICA__REGION_DENSE_FRACTION;
    /* the fit's share: what the booleans' grid and the written digits leave */
    double fT = T * (1 - CONICA__REGION_GRID_FRACTION - 2e-3);
    conica__polys raw, res;
    conica_code rc;
    conica__polys_init(&raw);
    conica__polys_init(&res);
    /* the reference fill first: the fit reads its painted sides from it */
    rc = fill_polys(path, dT, CONICA__FIT_CHORDS, NULL, 0, s->max_points, w, s, &raw, st);
    if (rc == CONICA_OK)
        rc = conica__clip_fill_region(&raw, rule, scale, 0, &res, st);
    raw.n = raw.npts = 0;
    if (rc == CONICA_OK) {
        if (s->fit == CONICA__REGION_MIDDLE)
            rc = fill_middle(path, fT, s->max_points, &raw, st);
        else
            rc = fill_polys(path, fT,
                            s->fit == CONICA__REGION_INSIDE ? CONICA__FIT_IN : CONICA__FIT_OUT,
                            &res, 0.25 * T, s->max_points, NULL, s, &raw, st);
    }
    if (rc == CONICA_OK && conica__polys_append(dense, &res) != 0)
        rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    if (rc == CONICA_OK)
        rc = conica__clip_fill_region(&raw, rule, scale, 0, &res, st);
    if (rc == CONICA_OK && conica__polys_append(fitted, &res) != 0)
        rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    conica__polys_free(&raw);
    conica__polys_free(&res);
    return rc;
}

static conica_code item_region(const conica_svg_item *it, int fill, int stroke,
                               const conica__region_settings *s, double height, double scale,
                               conica__polys *fitted, conica__polys *dense, conica_status *st)
{
    item_paths ip;
    conica_svg_matrix m = out_map(it, height);
    double T = s->tolerance, dT = T * CONICA__REGION_DENSE_FRACTION;
    conica_code rc;
    conica_path_init(&ip.local);
    conica_path_init(&ip.out);
    rc = build_local(&it->path, &ip.local, st);
    if (rc == CONICA_OK)
        rc = map_path(&ip.local, &m, &ip.out, st);
    if (rc == CONICA_OK && fill) {
        conica__region_source w;
        memset(&w, 0, sizeof w);
        w.name = it->name;
        w.part = "subpath";
        w.line = it->line;
        /* a stroked item's subpaths without area still draw: quiet */
        rc = fill_region(&ip.out,
                         it->fill_rule == CONICA_SVG_EVENODD ? CONICA__CLIP_EVENODD
                                                             : CONICA__CLIP_NONZERO,
                         stroke ? NULL : &w, s, scale, fitted, dense, st);
    }
    if (rc == CONICA_OK && stroke && it->st.width > 0) {
        /* the stroke is moved by (lt + at) towards the fit's side; at a miter
         * the tip moves by that times the miter ratio (up to the limit) */
        double mk = it->st.join == CONICA_SVG_JOIN_MITER ? 1.0 / fmax(1.0, it->st.miterlimit) : 1.0;
        double lt = T * CONICA__REGION_STROKE_LINE * mk, at = T * CONICA__REGION_STROKE_ARC * mk;
        double bias = s->fit == CONICA__REGION_INSIDE    ? -(lt + at)
                      : s->fit == CONICA__REGION_OUTSIDE ? lt + at
                                                         : 0.0;
        rc = stroke_region(it, &ip, &m, lt, at, bias, scale, s->max_points, fitted, st);
        if (rc == CONICA_OK)
            rc = stroke_region(it, &ip, &m, dT, dT, 0.0, scale, s->max_points, dense, st);
    }
    conica_path_free(&ip.local);
    conica_path_free(&ip.out);
    return rc;
}

/* Clip the item's region (polygons from `from` on) by its viewports. */
static conica_code clip_item(const conica_svg_item *it, double height, double scale,
                             conica__polys *set, size_t from, conica_status *st)
{
    conica__polys part, clip, res;
    conica_code rc = CONICA_OK;
    if (it->nclip < 3 || set->n == from)
        return CONICA_OK;
    conica__polys_init(&part);
    conica__polys_init(&clip);
    conica__polys_init(&res);
    for (size_t i = from; i < set->n && rc == CONICA_OK; i++)
        if (conica__polys_add(&part, set->xy + 2 * set->start[i],
                              set->start[i + 1] - set->start[i]) != 0)
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    if (rc == CONICA_OK) {
        double *c = malloc(2 * it->nclip * sizeof *c);
        if (!c)
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        for (size_t k = 0; c && k < it->nclip; k++) {
            c[2 * k] = it->clip[2 * k];
            c[2 * k + 1] = height - it->clip[2 * k + 1];
        }
        if (c && conica__polys_add(&clip, c, it->nclip) != 0)
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        free(c);
        /* y flipped: the clip turns clockwise now; nonzero fills it either way */
    }
    if (rc == CONICA_OK)
        rc = conica__clip_bool(CONICA__CLIP_INTERSECTION, &part, &clip, scale, &res, st);
    if (rc == CONICA_OK) {
        set->n = from;
        set->npts = from ? set->start[from] : 0;
        if (conica__polys_append(set, &res) != 0)
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    conica__polys_free(&part);
    conica__polys_free(&clip);
    conica__polys_free(&res);
    return rc;
}

/* ------------------------------------------------------------ the check */

/* Is anything of a left when b is grown by `grow`? *where gets a point of
 * the largest piece left. */
static conica_code left_over(const conica__polys *a, const conica__polys *b, double grow,
                             double scale, int *any, double where[2], conica_status *st)
{
    conica__polys g, d;
    conica_code rc;
    conica__polys_init(&g);
    conica__polys_init(&d);
    *any = 0;
    rc = conica__clip_offset(b, CONICA__CLIP_END_POLYGON, CONICA__CLIP_JOIN_ROUND, 2.0, grow,
                             0.125 * grow, scale, &g, st);
    if (rc == CONICA_OK)
        rc = conica__clip_bool(CONICA__CLIP_DIFFERENCE, a, &g, scale, &d, st);
    if (rc == CONICA_OK) {
        double best = 0;
        for (size_t i = 0; i < d.n; i++) {
            double ar = fabs(conica__polys_area2(&d, i));
            if (ar > best) {
                best = ar;
                where[0] = d.xy[2 * d.start[i]];
                where[1] = d.xy[2 * d.start[i] + 1];
                *any = 1;
            }
        }
    }
    conica__polys_free(&g);
    conica__polys_free(&d);
    return rc;
}

static conica_code check(const conica__polys *fit, const conica__polys *ref,
                         const conica__region_settings *s, double scale, conica_status *st)
{
    double T = s->tolerance, w[2] = {0, 0};
    double slack = fmax(T * CONICA__REGION_CHECK_SLACK, CONICA__REGION_CHECK_STEPS / scale);
    double in_grow = s->fit == CONICA__REGION_INSIDE ? slack : T + slack;  /* fit beyond ref */
    double out_grow = s->fit == CONICA__REGION_OUTSIDE ? slack : T + slack; /* ref beyond fit */
    int any;
    conica_code rc = left_over(fit, ref, in_grow, scale, &any, w, st);
    if (rc == CONICA_OK && any)
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0,
                            "the fitted polygon adds material %s the drawn region near "
                            "(%.6g, %.6g); nothing written",
                            s->fit == CONICA__REGION_INSIDE ? "outside" : "more than the tolerance beyond",
                            w[0], w[1]);
    if (rc == CONICA_OK)
        rc = left_over(ref, fit, out_grow, scale, &any, w, st);
    if (rc == CONICA_OK && any)
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0,
                            "the fitted polygon loses material %s the drawn region near "
                            "(%.6g, %.6g); nothing written",
                            s->fit == CONICA__REGION_OUTSIDE ? "of" : "more than the tolerance inside",
                            w[0], w[1]);
    return rc;
}

/* ------------------------------------------------------------ touching */

static int cmp_pt(const void *a, const void *b)
{
    const double *p = a, *q = b;
    if (p[0] != q[0])
        return p[0] < q[0] ? -1 : 1;
    if (p[1] != q[1])
        return p[1] < q[1] ? -1 : 1;
    return 0;
}

/* Clipper's strictly simple output can still have contours meet at a
 * vertex (two squares corner to corner, a hole touching its outline, three
 * triangles at one apex), which OpenSCAD's polygon() and a later extrusion
 * must not be given. Around such a point the edges of every visit (the
 * edge in and the edge out of each copy of the vertex) divide the plane
 * into sectors; material is to the left of travel (outlines run
 * counter-clockwise, holes clockwise), so each material sector runs
 * counter-clockwise from some visit's edge out to the next edge, which is
 * some visit's edge in. Each such sector gets its own copy of the point,
 * moved along the sector's bisector by CONICA__REGION_TOUCH_FRACTION of
 * the tolerance, and the edge in and the edge out that bound it are joined
 * there: the contours no longer meet, none crosses another (each new edge
 * stays in its own sector), and where a hole touched its outline the two
 * become one contour with a notch. Returns how many moved, SIZE_MAX when
 * out of memory; r is rebuilt when contours were joined. */
#define REGION_PI 3.14159265358979323846

typedef struct visit {
    size_t k;         /* index of this copy of the point */
    double in, out;   /* angles of the edges to the previous and next vertex */
} visit;

/* the counter-clockwise turn from angle a to angle b, in (0, 2 pi] */
static double ccw(double a, double b)
{
    double d = b - a;
    while (d <= 0)
        d += 2 * REGION_PI;
    while (d > 2 * REGION_PI)
        d -= 2 * REGION_PI;
    return d;
}

static size_t separate_touching(conica__polys *r, double tol)
{
    size_t np = r->npts, moved = 0;
    if (np == 0) /* nothing left to separate (and no arrays to copy) */
        return 0;
    double *key = malloc(3 * (np ? np : 1) * sizeof *key), *nxy = NULL;
    size_t *next = malloc((np ? np : 1) * sizeof *next), *prev = malloc((np ? np : 1) * sizeof *prev);
    visit *vs = NULL;
    size_t nvs = 0, vcap = 0;
    int relinked = 0;
    if (!key || !next || !prev)
        goto nomem;
    for (size_t c = 0; c < r->n; c++)
        for (size_t k = r->start[c]; k < r->start[c + 1]; k++) {
            size_t n = r->start[c + 1] - r->start[c];
            next[k] = r->start[c] + (k - r->start[c] + 1) % n;
            prev[k] = r->start[c] + (k - r->start[c] + n - 1) % n;
        }
    nxy = malloc(2 * (np ? np : 1) * sizeof *nxy);
    if (!nxy)
        goto nomem;
    memcpy(nxy, r->xy, 2 * np * sizeof *nxy);
    for (size_t k = 0; k < np; k++) {
        key[3 * k] = r->xy[2 * k];
        key[3 * k + 1] = r->xy[2 * k + 1];
        key[3 * k + 2] = (double)k;
    }
    qsort(key, np, 3 * sizeof *key, cmp_pt);
    {
        size_t *nnext = malloc((np ? np : 1) * sizeof *nnext);
        if (!nnext)
            goto nomem;
        memcpy(nnext, next, np * sizeof *nnext);
        for (size_t i = 0; i + 1 < np; i++) {
            if (cmp_pt(key + 3 * i, key + 3 * (i + 1)) != 0)
                continue;
            size_t j = i;
            while (j + 1 < np && cmp_pt(key + 3 * j, key + 3 * (j + 1)) == 0)
                j++;
            nvs = 0;
            if (j - i + 1 > vcap) {
                visit *nv = realloc(vs, (j - i + 1) * sizeof *nv);
                if (!nv) {
                    free(nnext);
                    goto nomem;
                }
                vs = nv;
                vcap = j - i + 1;
            }
            const double *o = key + 3 * i;
            for (size_t g = i; g <= j; g++) {
                size_t k = (size_t)key[3 * g + 2];
                const double *pv = r->xy + 2 * prev[k], *nx = r->xy + 2 * next[k];
                if ((pv[0] == o[0] && pv[1] == o[1]) || (nx[0] == o[0] && nx[1] == o[1]))
                    continue; /* a repeated point within one contour: leave it */
                vs[nvs].k = k;
                vs[nvs].in = atan2(pv[1] - o[1], pv[0] - o[0]);
                vs[nvs].out = atan2(nx[1] - o[1], nx[0] - o[0]);
                nvs++;
            }
            /* each visit's edge out opens a sector that the nearest edge
             * counter-clockwise closes: an edge in (of visit m) */
            for (size_t a = 0; a < nvs; a++) {
                double best = INFINITY;
                size_t m = SIZE_MAX;
                for (size_t b = 0; b < nvs; b++) {
                    double din = ccw(vs[a].out, vs[b].in);
                    if (din < best) {
                        best = din;
                        m = b;
                    }
                }
                for (size_t b = 0; b < nvs && m != SIZE_MAX; b++)
                    if (b != a && ccw(vs[a].out, vs[b].out) < best)
                        m = SIZE_MAX; /* an edge out first: overlapping, leave it */
                if (m == SIZE_MAX || !(best < 2 * REGION_PI))
                    continue;
                size_t km = vs[m].k, ka = vs[a].k;
                double th = vs[a].out + 0.5 * best;
                const double *pv = r->xy + 2 * prev[km], *nx = r->xy + 2 * next[ka];
                double l0 = hypot(pv[0] - o[0], pv[1] - o[1]), l1 = hypot(nx[0] - o[0], nx[1] - o[1]);
                double step = fmin(tol * CONICA__REGION_TOUCH_FRACTION, 0.25 * fmin(l0, l1));
                /* the copy that closes the sector (visit m's) is the point
                 * there; it goes on along visit a's edge out */
                nxy[2 * km] = o[0] + step * cos(th);
                nxy[2 * km + 1] = o[1] + step * sin(th);
                nnext[km] = next[ka];
                if (ka != km)
                    relinked = 1;
                moved++;
            }
            i = j;
        }
        memcpy(next, nnext, np * sizeof *next);
        free(nnext);
    }
    if (relinked) { /* trace the joined contours */
        conica__polys out;
        unsigned char *seen = calloc(np ? np : 1, 1);
        double *tmp = malloc(2 * (np ? np : 1) * sizeof *tmp);
        conica__polys_init(&out);
        if (!seen || !tmp) {
            free(seen);
            free(tmp);
            goto nomem;
        }
        for (size_t s0 = 0; s0 < np; s0++) {
            size_t m = 0, k = s0;
            if (seen[s0])
                continue;
            while (!seen[k] && m < np) {
                seen[k] = 1;
                tmp[2 * m] = nxy[2 * k];
                tmp[2 * m + 1] = nxy[2 * k + 1];
                m++;
                k = next[k];
            }
            if (conica__polys_add(&out, tmp, m) != 0) {
                free(seen);
                free(tmp);
                conica__polys_free(&out);
                goto nomem;
            }
        }
        free(seen);
        free(tmp);
        conica__polys_free(r);
        *r = out;
    } else {
        memcpy(r->xy, nxy, 2 * np * sizeof *nxy);
    }
    free(key);
    free(next);
    free(prev);
    free(nxy);
    free(vs);
    return moved;
nomem:
    free(key);
    free(next);
    free(prev);
    free(nxy);
    free(vs);
    return SIZE_MAX;
}

/* ------------------------------------------------------------ driver */

static double scene_max_abs(const conica_svg_scene *sc, double height)
{
    double m = fabs(height);
    for (size_t i = 0; i < sc->n; i++) {
        const conica_svg_item *it = &sc->items[i];
        conica_svg_matrix mm = out_map(it, height);
        double grow = it->stroke ? it->st.width * (it->st.non_scaling ? 1 : map_stretch(&mm)) *
                                       fmax(it->st.miterlimit, 2.0)
                                 : 0;
        for (size_t k = 0; k < it->path.n; k++) {
            const conica_svg_seg *g = &it->path.seg[k];
            double o[2], xs[5] = {g->x0, g->x1, g->c[0], g->c[2], g->cx},
                         ys[5] = {g->y0, g->y1, g->c[1], g->c[3], g->cy};
            for (int j = 0; j < 5; j++) {
                map_pt(&mm, xs[j], ys[j], o);
                m = fmax(m, fmax(fabs(o[0]), fabs(o[1])) + grow);
            }
            if (g->type == CONICA_SVG_SEG_ARC)
                m = fmax(m, fmax(fabs(o[0]), fabs(o[1])) + map_stretch(&mm) * fmax(g->rx, g->ry));
        }
    }
    return m;
}

/* The booleans' grid for coordinates up to mx: fine where they leave room
 * (0 when even the coarsest grid cannot hold them). */
static double region_scale(double tol, double mx)
{
    double scale = conica__clip_scale(tol, CONICA__REGION_GRID_FINE, mx);
    return scale > 0 ? scale : conica__clip_scale(tol, CONICA__REGION_GRID_FRACTION, mx);
}

static conica_code too_large(conica_status *st)
{
    return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                        "the drawing is too large for the tolerance: the polygon booleans "
                        "work on a grid of 1/100 of it and take at most 2.3e18 steps");
}

/* Every part's fit and reference resolved and oriented: nonzero unions
 * them; the fit's touching vertices separated, then checked against the
 * reference; on success the fit moves to out and sx to *stats. */
static conica_code finish_region(const conica__polys *fitted, const conica__polys *dense,
                                 const conica__region_settings *s, double scale,
                                 conica__region_stats *sx, conica__polys *out,
                                 conica__region_stats *stats, conica_status *st)
{
    conica__polys ufit, uref;
    conica_code rc;
    conica__polys_init(&ufit);
    conica__polys_init(&uref);
    rc = conica__clip_fill_region(fitted, CONICA__CLIP_NONZERO, scale, 1, &ufit, st);
    if (rc == CONICA_OK)
        rc = conica__clip_fill_region(dense, CONICA__CLIP_NONZERO, scale, 0, &uref, st);
    if (rc == CONICA_OK && separate_touching(&ufit, s->tolerance) == SIZE_MAX)
        rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    if (rc == CONICA_OK)
        rc = check(&ufit, &uref, s, scale, st);
    if (rc == CONICA_OK) {
        sx->fit_points = ufit.npts;
        sx->dense_points = uref.npts;
        conica__polys_free(out);
        *out = ufit;
        conica__polys_init(&ufit);
        if (stats)
            *stats = *sx;
        conica__ok(st);
    }
    conica__polys_free(&ufit);
    conica__polys_free(&uref);
    return rc;
}

conica_code conica__scad_region(const conica_svg_scene *sc, const conica__region_settings *s,
                                conica__polys *out, conica__region_stats *stats,
                                conica_status *st)
{
    double height, scale;
    conica__polys fitted, dense;
    conica_code rc = CONICA_OK;
    conica__region_stats sx;
    memset(&sx, 0, sizeof sx);
    if (!sc || !s || !out || !(s->tolerance > 0))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica__scad_region: bad argument");
    height = sc->has_size ? sc->height : 0.0;
    scale = region_scale(s->tolerance, scene_max_abs(sc, height));
    if (!(scale > 0))
        return too_large(st);
    conica__polys_init(&fitted);
    conica__polys_init(&dense);
    for (size_t i = 0; i < sc->n && rc == CONICA_OK; i++) {
        const conica_svg_item *it = &sc->items[i];
        int fill = s->paint == CONICA__PAINT_AS_DRAWN ? it->fill
                                                       : s->paint != CONICA__PAINT_STROKE;
        int stroke = s->paint == CONICA__PAINT_AS_DRAWN ? it->stroke
                                                         : s->paint != CONICA__PAINT_FILL;
        size_t f0 = fitted.n, d0 = dense.n;
        if (stroke && !(it->st.width > 0))
            stroke = 0;
        if (!fill && !stroke)
            continue;
        sx.fills += (size_t)(fill != 0);
        sx.strokes += (size_t)(stroke != 0);
        for (size_t k = 0; k < it->path.n; k++)
            sx.subpaths += it->path.seg[k].type == CONICA_SVG_SEG_MOVE;
        rc = item_region(it, fill, stroke, s, height, scale, &fitted, &dense, st);
        if (rc == CONICA_OK)
            rc = clip_item(it, height, scale, &fitted, f0, st);
        if (rc == CONICA_OK)
            rc = clip_item(it, height, scale, &dense, d0, st);
        if (rc != CONICA_OK && st && st->line == 0)
            st->line = it->line;
        if (rc != CONICA_OK && st) {
            char msg[sizeof st->message];
            snprintf(msg, sizeof msg, "%.95s: %.158s", it->name, st->message);
            memcpy(st->message, msg, sizeof msg);
        }
    }
    if (rc == CONICA_OK)
        rc = finish_region(&fitted, &dense, s, scale, &sx, out, stats, st);
    conica__polys_free(&fitted);
    conica__polys_free(&dense);
    return rc;
}

conica_code conica__scad_region_path(const conica__region_source *src,
                                     const conica__region_settings *s, conica__polys *out,
                                     conica__region_stats *stats, conica_status *st)
{
    double mx = 0, scale;
    conica__polys fitted, dense;
    conica_code rc;
    conica__region_stats sx;
    memset(&sx, 0, sizeof sx);
    if (!src || !src->path || !s || !out || !(s->tolerance > 0))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica__scad_region_path: bad argument");
    /* the curves lie in the hull of their control points */
    for (size_t k = 0; k < src->path->npt; k++)
        mx = fmax(mx, fmax(fabs(src->path->pt[3 * k]), fabs(src->path->pt[3 * k + 1])));
    for (size_t i = 0; i < src->path->nsub; i++)
        mx = fmax(mx, fmax(fabs(src->path->sub[i].x0), fabs(src->path->sub[i].y0)));
    scale = region_scale(s->tolerance, mx);
    if (!(scale > 0))
        return too_large(st);
    for (size_t i = 0; i < src->path->nsub; i++)
        sx.subpaths += src->path->sub[i].kind == CONICA_PATH_DRAWN;
    sx.fills = 1;
    conica__polys_init(&fitted);
    conica__polys_init(&dense);
    rc = fill_region(src->path, src->rule, src, s, scale, &fitted, &dense, st);
    if (rc == CONICA_OK)
        rc = finish_region(&fitted, &dense, s, scale, &sx, out, stats, st);
    conica__polys_free(&fitted);
    conica__polys_free(&dense);
    return rc;
}

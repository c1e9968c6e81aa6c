/* SPDX-License-Identifier: MIT */
/* The curve front end (conica/path.h): drawn segments to point-normal
 * samples, smoothed by conic-preserving subdivision (CONIS §1.1)
 * or flattened by the guaranteed plotter (Dahl 2019), always checked
 * against the drawn curve itself.
 *
 * Smoothing works segment by segment. A curved segment becomes an open
 * point-normal polygon of exact samples of the segment (its ends, its
 * inflection points, its middle: CONIS reproduces a conic from exact
 * point-normal samples, so a conic segment needs no more). At the ends the
 * normals come from the join rules: a corner keeps each side's own
 * tangent, a smooth join (up to the corner angle) gives both sides the mean
 * tangent, a line next to a curve gives the curve the line's. Segments
 * that meet share the end point and its normal, so the pieces join with
 * the tangent they were given. The subdivision of the samples is then
 * compared with the segment (check_edges: every limit point at a check
 * level against the segment, every dense point of the segment against the
 * limit polyline); a sample edge that strays further than the tolerance is
 * sampled again at its middle, up to PATH_MAX_ROUNDS times, and a segment
 * that still strays is written flattened (within the tolerance too). */
#include "conica/path.h"

#include <float.h>
#include <stdio.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "conica/curve.h"
#include "conica/plot.h"
#include "conica/subdiv.h"
#include "internal.h"
#include "path_fit.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A closed subpath whose end is this close to its start (relative to its
 * extent) ends there: rounding (sin(2 pi)), not a closing edge. */
#define PATH_MERGE_REL 1e-12
/* Tangency is judged to PATH_G1_FACTOR times the angle the input's
 * precision can turn a tangent vector of length l by (precision / l), and
 * never finer than PATH_G1_MIN radians. */
#define PATH_G1_FACTOR 2.0
#define PATH_G1_MIN 1e-9
#define PATH_G1_MAX (2.0 * M_PI / 180.0)
/* Straightness is judged to the precision, but never to more than this
 * fraction of the fidelity tolerance (a straight output must stay within). */
#define PATH_STRAIGHT_TOL_FRACTION 0.25
/* A Bézier is straight when its control points lie within the input's
 * precision (at least this fraction of its chord) of the chord. */
#define PATH_STRAIGHT_REL 1e-12
/* Initial samples: sample edges turn by at most this (radians). */
#define PATH_MAX_EDGE_TURN (0.5 * M_PI * (1 + 1e-6))
/* Inflections: sign changes of the curvature searched on this grid; a
 * polynomial cubic whose turning keeps one sign by this margin (relative
 * to its control polygon's size squared) has none without the search. */
#define PATH_INFL_GRID 32
#define PATH_INFL_MARGIN 1e-12
/* Rounds of resampling where the subdivision strays, and samples per
 * segment at most, before the segment is written flattened instead. */
#define PATH_MAX_ROUNDS 20
#define PATH_MAX_SEG_SAMPLES 4096
/* Check levels: at least PATH_CHECK_MIN_LEVEL, at most PATH_CHECK_MAX_LEVEL,
 * deep enough that the limit polyline's chords bulge by at most
 * PATH_CHECK_SAG of the tolerance. Output at fewer levels is checked at
 * its own level first (smooth_piece: PATH_CHECK_NEXT_BULGE). */
#define PATH_CHECK_MIN_LEVEL 4
#define PATH_CHECK_MAX_LEVEL 9
#define PATH_CHECK_SAG 0.05
/* A check at fewer levels than PATH_CHECK_MIN_LEVEL (smooth_piece) keeps
 * this many times its last level's measured bulge off the tolerance:
 * twice the quarter the next level adds. */
#define PATH_CHECK_NEXT_BULGE 0.5
/* Dense points per chord when the polyline that is written is measured
 * against its segment (check_edge's `written`): its chords may be long
 * and the curve may turn back between two dense points (a hook's tip).
 * A dense point lies within 1/32 of a chord from the chord's farthest
 * point, which under-states a bulge by at most 1 - (2/32)^2 = 0.4 %; the
 * written polyline must pass at PATH_WRITTEN_FRACTION of the tolerance,
 * which covers that and the rounding of the written digits (1 %). */
#define PATH_WRITTEN_DENSE 16
#define PATH_WRITTEN_FRACTION 0.985
/* Newton steps when projecting a point onto a segment, and the step (a
 * fraction of the search interval) after which it has settled. */
#define PATH_NEWTON_STEPS 6
#define PATH_NEWTON_SETTLED 1e-9
/* Fit modes: dense samples per chord when measuring how far the curve
 * bulges from it, and the flattening tolerance as a fraction of the
 * fidelity tolerance (OUTSIDE: the shifted vertices sit about a chord's
 * bulge off the curve; MIDDLE: half of it either way). */
#define PATH_FIT_SAMPLES 16
/* Flattening plots this many times finer than the tolerance, then keeps
 * the longest chords that stay within it (near the fewest points). */
#define PATH_FLAT_DENSE 8
/* Bisection steps of a chord's end parameter between two plotted points
 * (2^-12 of their spacing, plotted at an eighth of the tolerance: the
 * chord uses the tolerance to about 1e-4 of itself). */
#define PATH_FLAT_BISECT 12
/* Golden-section steps refining a chord's largest distance from the best
 * of its samples: the bracket shrinks to 0.618^24 = 1e-5 of two sample
 * spacings, where the distance is flat to 1e-10 of itself. */
#define PATH_CHORD_GOLDEN 24
/* A run reaches its subpath's bounding box where it comes within this
 * fraction of the box's coordinate (plus the tolerance's) of it; an extreme
 * this close to a segment's end (in its parameter) is that end. */
#define PATH_EXT_REL 1e-12
#define PATH_EXT_SNAP 1e-9
/* The plotter's trial steps per allowed point (a bound on its time that
 * the budget sets; a curve that needs more is refused as too large). */
#define PATH_FLAT_TRIALS 64
/* Flattening tolerance / tolerance per fit mode. The chords use their
 * tolerance to the last bit, so INSIDE keeps 1% of it for what comes after:
 * the writers' rounding (scadprofile and svgsmooth write each point within
 * 1/1000 of the tolerance of its exact value, Blender stores float32) and
 * the sampled bulge of a chord; OUTSIDE shifts vertices by up to the
 * bulge and MIDDLE by half of it, inside the same budget. */
#define PATH_FIT_INSIDE_FRACTION 0.99
#define PATH_FIT_OUTSIDE_FRACTION 0.99
/* A straight edge's end slides along its line (OUTSIDE, MIDDLE) only where
 * the next chord turns from it by less than this (radians): a tangent join
 * seen through its first chord. */
#define PATH_FIT_SLIDE_MAX_ANGLE 0.35
#define PATH_FIT_MIDDLE_FRACTION 1.98
/* A fold of moved chords (OUTSIDE, in a notch) spans at most this many
 * segments: the loop between two crossing segments this close is removed. */
#define PATH_FIT_FOLD_SPAN 8
/* Flattenings of one subpath that MIDDLE may try (each with shorter chords)
 * to keep its moved vertices within the tolerance. */
#define PATH_FIT_RETRIES 4
/* Most levels that settings.level_tolerance may choose for a piece. */
#define PATH_LEVELS_MAX 16

/* ------------------------------------------------------------ storage */

conica_path_settings conica_path_defaults(void)
{
    conica_path_settings s;
    memset(&s, 0, sizeof s);
    s.rel_tolerance = CONICA_PATH_DEFAULT_REL_TOLERANCE;
    s.corner_angle = CONICA_PATH_DEFAULT_CORNER_DEG * M_PI / 180.0;
    s.levels = CONICA_PATH_DEFAULT_LEVELS;
    s.max_points = CONICA_PATH_DEFAULT_MAX_POINTS;
    return s;
}

double conica_path_float32_precision(double max_abs)
{
    int e;
    if (!(max_abs > 0) || !isfinite(max_abs))
        return 0.0;
    frexp(max_abs, &e);
    /* float32 has 24 significant bits: half a unit is 2^(e - 25) */
    return ldexp(1.0, e - 25);
}

void conica_path_init(conica_path *p)
{
    if (p)
        memset(p, 0, sizeof *p);
}

void conica_path_free(conica_path *p)
{
    if (!p)
        return;
    free(p->sub);
    free(p->seg);
    free(p->pt);
    free(p->smp);
    free(p->smptag);
    memset(p, 0, sizeof *p);
}

/* Room for `more` items of `size` bytes in *arr (count *n, capacity *cap). */
static int grow(void **arr, size_t *cap, size_t n, size_t more, size_t size)
{
    size_t need, c;
    void *t;
    if (more > CONICA_PATH_MAX_ITEMS - n)
        return 0;
    need = n + more;
    if (need <= *cap)
        return 1;
    c = *cap ? *cap : 16;
    while (c < need)
        c *= 2;
    t = realloc(*arr, c * size);
    if (!t)
        return 0;
    *arr = t;
    *cap = c;
    return 1;
}

static conica_code nomem(conica_status *st, const conica_path *p)
{
    if (p->nseg >= CONICA_PATH_MAX_ITEMS || p->npt >= CONICA_PATH_MAX_ITEMS ||
        p->nsmp >= CONICA_PATH_MAX_ITEMS || p->nsub >= CONICA_PATH_MAX_ITEMS)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "path larger than %zu items",
                            (size_t)CONICA_PATH_MAX_ITEMS);
    return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
}

conica_code conica_path_move_to(conica_path *p, double x, double y, size_t tag,
                                conica_status *st)
{
    (void)tag;
    if (!p)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_path_move_to: NULL path");
    if (!isfinite(x) || !isfinite(y))
        return conica__fail(st, CONICA_ERR_NONFINITE, 0, 0, "point (%g, %g) is not finite", x, y);
    if (!grow((void **)&p->sub, &p->subcap, p->nsub, 1, sizeof *p->sub))
        return nomem(st, p);
    p->sub[p->nsub].kind = CONICA_PATH_DRAWN;
    p->sub[p->nsub].closed = 0;
    p->sub[p->nsub].first = p->nseg;
    p->sub[p->nsub].n = 0;
    p->sub[p->nsub].x0 = x;
    p->sub[p->nsub].y0 = y;
    p->nsub++;
    p->open = 1;
    p->cur[0] = p->start[0] = x;
    p->cur[1] = p->start[1] = y;
    conica__ok(st);
    return CONICA_OK;
}

/* Append a segment of degree d: the current point, then ctrl (d points). */
static conica_code add_seg(conica_path *p, int d, const double *ctrl, const double *w, size_t tag,
                           conica_status *st)
{
    conica_path_seg *g;
    double *q;
    int i, rational = 0, same = 1;
    if (!p || !ctrl || d < 1 || d > CONICA_PATH_MAX_DEGREE)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "segment of degree %d (1..%d)", d,
                            CONICA_PATH_MAX_DEGREE);
    if (!p->open)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "segment without a current point");
    for (i = 0; i < 2 * d; i++)
        if (!isfinite(ctrl[i]))
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, 0,
                                "control point %d of a segment is not finite", i / 2 + 1);
    if (w)
        for (i = 0; i <= d; i++) {
            if (!(w[i] > 0) || !isfinite(w[i]))
                return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                                    "weight %d of a segment is not a positive number", i + 1);
            if (w[i] != w[0])
                rational = 1;
        }
    for (i = 0; i < d; i++)
        if (ctrl[2 * i] != p->cur[0] || ctrl[2 * i + 1] != p->cur[1])
            same = 0;
    if (same) { /* a segment of one point: nothing drawn */
        conica__ok(st);
        return CONICA_OK;
    }
    if (!grow((void **)&p->seg, &p->segcap, p->nseg, 1, sizeof *p->seg) ||
        !grow((void **)&p->pt, &p->ptcap, p->npt, (size_t)d + 1, 3 * sizeof *p->pt))
        return nomem(st, p);
    g = &p->seg[p->nseg];
    g->degree = d;
    g->rational = rational;
    g->first = p->npt;
    g->tag = tag;
    q = p->pt + 3 * p->npt;
    q[0] = p->cur[0];
    q[1] = p->cur[1];
    q[2] = rational ? w[0] : 1.0;
    for (i = 1; i <= d; i++) {
        q[3 * i] = ctrl[2 * (i - 1)];
        q[3 * i + 1] = ctrl[2 * (i - 1) + 1];
        q[3 * i + 2] = rational ? w[i] : 1.0;
    }
    p->npt += (size_t)d + 1;
    p->nseg++;
    p->sub[p->nsub - 1].n++;
    p->cur[0] = ctrl[2 * d - 2];
    p->cur[1] = ctrl[2 * d - 1];
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_path_line_to(conica_path *p, double x, double y, size_t tag,
                                conica_status *st)
{
    double c[2] = {x, y};
    return add_seg(p, 1, c, NULL, tag, st);
}

conica_code conica_path_bezier_to(conica_path *p, int degree, const double *ctrl,
                                  const double *w, size_t tag, conica_status *st)
{
    return add_seg(p, degree, ctrl, w, tag, st);
}

conica_code conica_path_arc_to(conica_path *p, double cx, double cy, double rx, double ry,
                               double phi, double theta1, double dtheta, double x1, double y1,
                               size_t tag, conica_status *st)
{
    double parts, h, cphi, sphi;
    size_t m, k;
    conica_code rc = CONICA_OK;
    if (!isfinite(cx) || !isfinite(cy) || !isfinite(rx) || !isfinite(ry) || !isfinite(phi) ||
        !isfinite(theta1) || !isfinite(dtheta) || !isfinite(x1) || !isfinite(y1))
        return conica__fail(st, CONICA_ERR_NONFINITE, 0, 0, "arc with a value that is not finite");
    if (fabs(dtheta) > 2 * M_PI * (1 + 1e-12)) /* the rounding of a full turn passes */
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "arc sweep %g rad exceeds a full turn (|dtheta| <= 2 pi)", dtheta);
    if (!(rx > 0) || !(ry > 0))
        return conica_path_line_to(p, x1, y1, tag, st);
    /* Parts of at most 90 degrees (a rational quadratic with weight
     * cos(half angle) is the exact arc); the slack keeps 90 degrees in one. */
    parts = ceil(fabs(dtheta) / (0.5 * M_PI) - 1e-9);
    m = parts < 1 ? 1 : parts > 4 ? 4 : (size_t)parts;
    h = 0.5 * dtheta / (double)m;
    cphi = cos(phi);
    sphi = sin(phi);
    for (k = 0; k < m && rc == CONICA_OK; k++) {
        double c[4], w[3], th = theta1 + (double)(2 * k + 1) * h, r = 1.0 / cos(h);
        double ex = rx * r * cos(th), ey = ry * r * sin(th);
        c[0] = cx + cphi * ex - sphi * ey;
        c[1] = cy + sphi * ex + cphi * ey;
        if (k + 1 == m) {
            c[2] = x1;
            c[3] = y1;
        } else {
            double te = theta1 + (double)(2 * k + 2) * h;
            double fx = rx * cos(te), fy = ry * sin(te);
            c[2] = cx + cphi * fx - sphi * fy;
            c[3] = cy + sphi * fx + cphi * fy;
        }
        w[0] = w[2] = 1.0;
        w[1] = cos(h);
        rc = add_seg(p, 2, c, w, tag, st);
    }
    return rc;
}

conica_code conica_path_bspline(conica_path *p, const conica_bspline *bs, size_t tag,
                                conica_status *st)
{
    size_t k, nb;
    double c[2 * (CONICA_PATH_MAX_DEGREE + 1)], w[CONICA_PATH_MAX_DEGREE + 1];
    conica_bspline bz;
    conica_code rc;
    if (!p || !bs || bs->dim != 2)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_path_bspline: a 2D spline is needed");
    if (bs->degree > CONICA_PATH_MAX_DEGREE)
        return conica__fail(st, CONICA_ERR_UNSUPPORTED, 0, 0, "spline of degree %d (at most %d)",
                            bs->degree, CONICA_PATH_MAX_DEGREE);
    conica_bspline_init(&bz);
    if ((rc = conica_bspline_to_bezier(bs, &bz, st)) != CONICA_OK)
        return rc;
    nb = conica_bspline_bezier_count(&bz);
    for (k = 0; k < nb && rc == CONICA_OK; k++) {
        int d = bz.degree;
        rc = conica_bspline_bezier_piece(&bz, k, c, bz.w ? w : NULL, NULL, NULL, st);
        if (rc != CONICA_OK)
            break;
        if (k == 0 && (!p->open || p->cur[0] != c[0] || p->cur[1] != c[1]))
            rc = conica_path_move_to(p, c[0], c[1], tag, st);
        if (rc == CONICA_OK) {
            /* pieces share end points exactly */
            c[0] = p->cur[0];
            c[1] = p->cur[1];
            rc = add_seg(p, d, c + 2, bz.w ? w : NULL, tag, st);
        }
    }
    conica_bspline_free(&bz);
    return rc;
}

/* Bounding-box diagonal of control points (x, y, w triples) pt[a..b). */
static double pt_extent(const double *pt, size_t a, size_t b)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    size_t i;
    for (i = a; i < b; i++) {
        int c;
        for (c = 0; c < 2; c++) {
            double v = pt[3 * i + (size_t)c];
            lo[c] = v < lo[c] ? v : lo[c];
            hi[c] = v > hi[c] ? v : hi[c];
        }
    }
    return b > a ? hypot(hi[0] - lo[0], hi[1] - lo[1]) : 0.0;
}

conica_code conica_path_close(conica_path *p, conica_status *st)
{
    conica_path_subpath *sp;
    if (!p)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_path_close: NULL path");
    if (!p->open) {
        conica__ok(st);
        return CONICA_OK;
    }
    sp = &p->sub[p->nsub - 1];
    if (sp->n && (p->cur[0] != p->start[0] || p->cur[1] != p->start[1])) {
        const conica_path_seg *a = &p->seg[sp->first], *z = &p->seg[sp->first + sp->n - 1];
        double ext = pt_extent(p->pt, a->first, z->first + (size_t)z->degree + 1);
        if (hypot(p->cur[0] - p->start[0], p->cur[1] - p->start[1]) <= PATH_MERGE_REL * ext) {
            double *e = p->pt + 3 * (z->first + (size_t)z->degree);
            e[0] = p->start[0];
            e[1] = p->start[1];
            p->cur[0] = p->start[0];
            p->cur[1] = p->start[1];
        } else {
            conica_code rc = conica_path_line_to(p, p->start[0], p->start[1], z->tag, st);
            if (rc != CONICA_OK)
                return rc;
        }
    }
    sp->closed = 1;
    p->open = 0;
    p->cur[0] = p->start[0];
    p->cur[1] = p->start[1];
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_path_samples(conica_path *p, const double *xy, const double *nxy, size_t n,
                                int closed, size_t first_tag, conica_status *st)
{
    size_t i, m = 0;
    if (!p || (!xy && n))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_path_samples: NULL argument");
    /* the cap before anything is read (2 n would wrap for a huge n) */
    if (n > CONICA_PATH_MAX_ITEMS - p->nsmp)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "%zu samples exceed the path's limit of %zu items", n,
                            (size_t)CONICA_PATH_MAX_ITEMS);
    for (i = 0; i < 2 * n; i++)
        if (!isfinite(xy[i]) || (nxy && !isfinite(nxy[i])))
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, i / 2, "sample %zu is not finite",
                                i / 2 + 1);
    if (!grow((void **)&p->sub, &p->subcap, p->nsub, 1, sizeof *p->sub) ||
        !grow((void **)&p->smp, &p->smpcap, p->nsmp, n, 4 * sizeof *p->smp))
        return nomem(st, p);
    if (p->smpcap) {
        /* (never realloc to 0 bytes: that frees the list and returns NULL,
         * which read as out of memory left a dangling pointer behind:
         * fuzz_svgsmooth, two empty sample subpaths in a row) */
        size_t *t = realloc(p->smptag, p->smpcap * sizeof *t);
        if (!t)
            return nomem(st, p);
        p->smptag = t;
    }
    p->open = 0;
    for (i = 0; i < n; i++) {
        double *s = p->smp + 4 * (p->nsmp + m);
        if (m && s[-4] == xy[2 * i] && s[-3] == xy[2 * i + 1])
            continue; /* the same point again */
        s[0] = xy[2 * i];
        s[1] = xy[2 * i + 1];
        s[2] = nxy ? nxy[2 * i] : 0.0;
        s[3] = nxy ? nxy[2 * i + 1] : 0.0;
        p->smptag[p->nsmp + m] = first_tag + i;
        m++;
    }
    if (closed && m > 1) {
        const double *a = p->smp + 4 * p->nsmp, *z = p->smp + 4 * (p->nsmp + m - 1);
        if (a[0] == z[0] && a[1] == z[1])
            m--;
    }
    if (m < 2)
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0,
                            "fewer than 2 distinct samples (%zu given)", n);
    p->sub[p->nsub].kind = CONICA_PATH_SAMPLES;
    p->sub[p->nsub].closed = closed != 0 && m > 2;
    p->sub[p->nsub].first = p->nsmp;
    p->sub[p->nsub].n = m;
    p->sub[p->nsub].x0 = p->smp[4 * p->nsmp];
    p->sub[p->nsub].y0 = p->smp[4 * p->nsmp + 1];
    p->nsub++;
    p->nsmp += m;
    conica__ok(st);
    return CONICA_OK;
}

/* ------------------------------------------------------------ evaluation */

/* Point c, first and second derivative of a rational Bézier of degree d
 * with control points q (x, y, w triples) at t: de Casteljau on the
 * homogeneous points and their hodographs, then the quotient rule. */
/* One coordinate of a polynomial cubic in Bernstein form (u = 1 - t): the
 * point, first and second derivative. The formulas live here once, so the
 * check's unrolled cubic loops give bez_eval's values bit for bit. */
static inline double bern3(const double *p, double u, double t)
{
    return u * u * (u * p[0] + 3 * t * p[3]) + t * t * (3 * u * p[6] + t * p[9]);
}

static inline double bern3_d1(const double *p, double u, double t)
{
    return 3 * (u * u * (p[3] - p[0]) + 2 * u * t * (p[6] - p[3]) + t * t * (p[9] - p[6]));
}

static inline double bern3_d2(const double *p, double u, double t)
{
    return 6 * (u * (p[6] - 2 * p[3] + p[0]) + t * (p[9] - 2 * p[6] + p[3]));
}

/* Polynomial Bézier of degree 1..3 in Bernstein form (the common case of
 * lines, quadratic and cubic segments): no homogeneous detour. */
static inline void bez_eval_poly3(const double *q, int d, double t, double c[2], double d1[2],
                                  double d2[2])
{
    double u = 1.0 - t;
    int k;
    if (d == 3) {
        for (k = 0; k < 2; k++) {
            c[k] = bern3(q + k, u, t);
            if (d1)
                d1[k] = bern3_d1(q + k, u, t);
            if (d2)
                d2[k] = bern3_d2(q + k, u, t);
        }
        return;
    }
    for (k = 0; k < 2; k++) {
        double p0 = q[k], p1 = q[3 + k];
        if (d == 1) {
            c[k] = u * p0 + t * p1;
            if (d1)
                d1[k] = p1 - p0;
            if (d2)
                d2[k] = 0;
        } else {
            double p2 = q[6 + k];
            c[k] = u * u * p0 + 2 * u * t * p1 + t * t * p2;
            if (d1)
                d1[k] = 2 * (u * (p1 - p0) + t * (p2 - p1));
            if (d2)
                d2[k] = 2 * (p2 - 2 * p1 + p0);
        }
    }
}

static void bez_eval(const double *q, int d, double t, double c[2], double d1[2], double d2[2])
{
    double h[CONICA_PATH_MAX_DEGREE + 1][3];
    if (d <= 3 && q[2] == 1.0 && q[5] == 1.0 && (d < 2 || q[8] == 1.0) &&
        (d < 3 || q[11] == 1.0)) {
        bez_eval_poly3(q, d, t, c, d1, d2);
        return;
    }
    double a[3][3] = {{0}}; /* A, A', A'' (homogeneous) */
    double u = 1.0 - t, W, W1, W2;
    int i, k, r;
    for (i = 0; i <= d; i++) {
        h[i][0] = q[3 * i] * q[3 * i + 2];
        h[i][1] = q[3 * i + 1] * q[3 * i + 2];
        h[i][2] = q[3 * i + 2];
    }
    /* de Casteljau down to three points; their differences give the
     * derivatives (standard identities of the last steps). */
    for (r = d; r > 2; r--)
        for (i = 0; i < r; i++)
            for (k = 0; k < 3; k++)
                h[i][k] = u * h[i][k] + t * h[i + 1][k];
    if (d >= 2) {
        for (k = 0; k < 3; k++) {
            double b0 = u * h[0][k] + t * h[1][k], b1 = u * h[1][k] + t * h[2][k];
            a[0][k] = u * b0 + t * b1;
            a[1][k] = (double)d * (b1 - b0);
            a[2][k] = (double)d * (double)(d - 1) * (h[2][k] - 2 * h[1][k] + h[0][k]);
        }
    } else {
        for (k = 0; k < 3; k++) {
            a[0][k] = u * h[0][k] + t * h[1][k];
            a[1][k] = h[1][k] - h[0][k];
            a[2][k] = 0;
        }
    }
    W = a[0][2];
    W1 = a[1][2];
    W2 = a[2][2];
    c[0] = a[0][0] / W;
    c[1] = a[0][1] / W;
    if (d1 || d2) {
        double e[2];
        for (k = 0; k < 2; k++)
            e[k] = (a[1][k] - W1 * c[k]) / W;
        if (d1) {
            d1[0] = e[0];
            d1[1] = e[1];
        }
        if (d2)
            for (k = 0; k < 2; k++)
                d2[k] = (a[2][k] - 2 * W1 * e[k] - W2 * c[k]) / W;
    }
}

static const double *seg_pts(const conica_path *p, size_t s)
{
    return p->pt + 3 * p->seg[s].first;
}

void conica_path_seg_eval(const conica_path *p, size_t seg, double t, double pt[2], double d1[2])
{
    double c[2], d[2];
    if (!p || seg >= p->nseg)
        return;
    bez_eval(seg_pts(p, seg), p->seg[seg].degree, t, c, d, NULL);
    if (pt) {
        pt[0] = c[0];
        pt[1] = c[1];
    }
    if (d1) {
        d1[0] = d[0];
        d1[1] = d[1];
    }
}

/* (x, y) / |(x, y)| into out, and the length into *len when len is not
 * NULL; 0 for a zero or non-finite vector. */
static int unit2_len(double x, double y, double out[2], double *len)
{
    double h = hypot(x, y);
    if (!(h > 0) || !isfinite(h))
        return 0;
    out[0] = x / h;
    out[1] = y / h;
    if (len)
        *len = h;
    return 1;
}

static int unit2(double x, double y, double out[2])
{
    return unit2_len(x, y, out, NULL);
}

/* Unit tangent at an end of a segment (end 0 or 1) from its control
 * polygon, skipping control points on the end point; *len gets the length
 * of the vector it came from (how far rounding can turn it). */
static void end_tangent(const double *q, int d, int end, double t[2], double *len)
{
    int i;
    t[0] = 1;
    t[1] = 0;
    *len = 0;
    if (end == 0) {
        for (i = 1; i <= d; i++)
            if (unit2(q[3 * i] - q[0], q[3 * i + 1] - q[1], t)) {
                *len = hypot(q[3 * i] - q[0], q[3 * i + 1] - q[1]);
                return;
            }
    } else {
        const double *e = q + 3 * d;
        for (i = d - 1; i >= 0; i--)
            if (unit2(e[0] - q[3 * i], e[1] - q[3 * i + 1], t)) {
                *len = hypot(e[0] - q[3 * i], e[1] - q[3 * i + 1]);
                return;
            }
    }
}

/* Unit tangent of a segment at an inner parameter; at a stationary point
 * (a cusp) the limit from the side of `dir` (+1 after, -1 before). */
static void inner_tangent(const double *q, int d, double t, int dir, double out[2])
{
    double c[2], d1[2], d2[2];
    bez_eval(q, d, t, c, d1, d2);
    if (hypot(d1[0], d1[1]) > 1e-9 * (fabs(d2[0]) + fabs(d2[1])) && unit2(d1[0], d1[1], out))
        return;
    if (unit2((double)dir * d2[0], (double)dir * d2[1], out))
        return;
    out[0] = 1;
    out[1] = 0;
}

/* Is the segment straight: every control point within tol of its chord and
 * between its ends? */
static int seg_straight(const double *q, int d, double precision)
{
    double ex = q[3 * d] - q[0], ey = q[3 * d + 1] - q[1], l = hypot(ex, ey), tol;
    int i;
    if (d == 1)
        return 1;
    if (!(l > 0))
        return 0;
    tol = fmax(precision, PATH_STRAIGHT_REL * l);
    for (i = 1; i < d; i++) {
        double px = q[3 * i] - q[0], py = q[3 * i + 1] - q[1];
        double along = (px * ex + py * ey) / l, off = fabs(px * ey - py * ex) / l;
        if (off > tol || along < -tol || along > l + tol)
            return 0;
    }
    return 1;
}

/* Curvature numerator cross(C', C'') (its sign is the turning direction). */
static double turning(const double *q, int d, double t)
{
    double c[2], d1[2], d2[2];
    bez_eval(q, d, t, c, d1, d2);
    return d1[0] * d2[1] - d1[1] * d2[0];
}

/* Parameters in (0, 1) where the segment changes its turning direction
 * (inflections, and cusps), ascending; at most cap of them. */
/* Does a polynomial cubic turn one way throughout, by a margin its
 * evaluation cannot blur? Its turning cross(C', C'') is 18 times the
 * quadratic with Bernstein coefficients cross(A, B), cross(A, C) / 2,
 * cross(B, C) for the control polygon's legs A, B, C, so it keeps one
 * strict sign on [0, 1] when they do (convex hull property). The margin,
 * PATH_INFL_MARGIN times S^2 with S the legs' summed size, is far above
 * the rounding of these coefficients and of turning()'s own value (a few
 * units of 1e-16 S^2), so the grid search below could not see a sign
 * change either: no inflection, with the same answer, without its 33
 * evaluations. */
static int cubic_turns_one_way(const double *q)
{
    double ax = q[3] - q[0], ay = q[4] - q[1], bx = q[6] - q[3], by = q[7] - q[4];
    double cx = q[9] - q[6], cy = q[10] - q[7];
    double S = fabs(ax) + fabs(ay) + fabs(bx) + fabs(by) + fabs(cx) + fabs(cy);
    double k0 = ax * by - ay * bx, k1 = 0.5 * (ax * cy - ay * cx), k2 = bx * cy - by * cx;
    double m = PATH_INFL_MARGIN * S * S;
    if (!isfinite(m))
        return 0;
    return (k0 > m && k1 > m && k2 > m) || (k0 < -m && k1 < -m && k2 < -m);
}

static size_t find_inflections(const double *q, int d, double *out, size_t cap)
{
    size_t n = 0, i;
    double prev, tp = 0.0;
    if (d < 3)
        return 0; /* a line, or a quadratic with positive weights (a conic
                   * arc: a parabola, an ellipse's or a hyperbola's) turns
                   * one way; sampling its turning at coordinates near 1e44
                   * found rounding noise instead */
    if (d == 3 && q[2] == 1.0 && q[5] == 1.0 && q[8] == 1.0 && q[11] == 1.0 &&
        cubic_turns_one_way(q))
        return 0;
    prev = turning(q, d, 0.0);
    for (i = 1; i <= PATH_INFL_GRID && n < cap; i++) {
        double t = (double)i / PATH_INFL_GRID, f = turning(q, d, t);
        if ((prev < 0 && f > 0) || (prev > 0 && f < 0)) {
            double lo = tp, hi = t, flo = prev;
            int k;
            for (k = 0; k < 60; k++) {
                double mid = 0.5 * (lo + hi), fm = turning(q, d, mid);
                if ((fm < 0) == (flo < 0) && fm != 0) {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            if (lo > 1e-9 && hi < 1 - 1e-9)
                out[n++] = 0.5 * (lo + hi);
        }
        if (f != 0) {
            prev = f;
            tp = t;
        }
    }
    return n;
}

/* For the one-sided fits (path_fit.c): the same inflections. */
size_t conica__path_seg_inflections(const conica_path *p, size_t seg, double *out, size_t cap)
{
    return find_inflections(seg_pts(p, seg), p->seg[seg].degree, out, cap);
}

/* Angle between unit vectors. */
static double angle_between(const double a[2], const double b[2])
{
    return fabs(atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]));
}

/* ------------------------------------------------------------ results */

void conica_path_result_init(conica_path_result *r)
{
    if (r)
        memset(r, 0, sizeof *r);
}

static void line_free(conica_path_polyline *l)
{
    free(l->xy);
    free(l->nxy);
    free(l->seg);
    free(l->t);
    free(l->flags);
}

void conica_path_result_free(conica_path_result *r)
{
    size_t i;
    if (!r)
        return;
    for (i = 0; i < r->n; i++)
        line_free(&r->lines[i]);
    free(r->lines);
    memset(r, 0, sizeof *r);
}

/* ------------------------------------------------------------ context */

typedef struct ctx {
    const conica_path *p;
    conica_path_settings s;
    conica_path_result *r;
    conica_status *st;
    size_t budget;   /* points left */
    size_t subpath;  /* index of the subpath at work */
    double tol;      /* its fidelity tolerance */
    double flat_fraction; /* flattening tolerance / tol (the fit mode's) */
    /* flattening: the subpath's extent along +x, -x, +y, -y (coordinates
     * times the sign); the points where a run reaches it become vertices */
    double ext[4];
    int use_ext;
    conica_path_polyline *L; /* its polyline */
    size_t lcap;     /* capacity of L's arrays */
    /* one segment's samples */
    double *par, *sxy, *snxy;
    size_t scap;
    /* settings.progress: segments and samples of the subpaths before this
     * one, of all, and the count at which the next report is due */
    size_t prog_base, prog_total, prog_next;
} ctx;

/* Report `done` segments of the current subpath to settings.progress when
 * the next ~1/256 of the path is reached (or at the end). */
static void progress_at(ctx *c, size_t done)
{
    size_t at = c->prog_base + done;
    if (!c->s.progress || (at < c->prog_next && at < c->prog_total))
        return;
    c->s.progress(c->s.progress_ctx, at, c->prog_total);
    c->prog_next = at + (c->prog_total / 256 > 1 ? c->prog_total / 256 : 1);
}

static conica_code fail_nomem(ctx *c)
{
    return conica__fail(c->st, CONICA_ERR_NOMEM, 0, c->subpath, "out of memory");
}

static conica_code take(ctx *c, size_t n)
{
    if (n > c->budget)
        return conica__fail(c->st, CONICA_ERR_LIMIT, 0, c->subpath,
                            "subpath %zu: the result would exceed the limit of %zu points",
                            c->subpath + 1, c->s.max_points);
    c->budget -= n;
    return CONICA_OK;
}

/* Room for `more` points on the current polyline (its five arrays grown
 * together, at least doubling). */
static int reserve(ctx *c, size_t more)
{
    conica_path_polyline *l = c->L;
    if (l->n + more > c->lcap) {
        size_t cap = c->lcap ? 2 * c->lcap : 16;
        double *x;
        size_t *s;
        unsigned char *f;
        if (cap < l->n + more)
            cap = l->n + more;
        if (!(x = realloc(l->xy, 2 * cap * sizeof *x)))
            return 0;
        l->xy = x;
        if (!(x = realloc(l->nxy, 2 * cap * sizeof *x)))
            return 0;
        l->nxy = x;
        if (!(x = realloc(l->t, cap * sizeof *x)))
            return 0;
        l->t = x;
        if (!(s = realloc(l->seg, cap * sizeof *s)))
            return 0;
        l->seg = s;
        if (!(f = realloc(l->flags, cap)))
            return 0;
        l->flags = f;
        c->lcap = cap;
    }
    return 1;
}

/* Append a point to the current polyline (its budget already taken). */
static int add_pt(ctx *c, const double xy[2], const double nxy[2], size_t seg, double t,
                  unsigned flags)
{
    conica_path_polyline *l = c->L;
    if (l->n == c->lcap && !reserve(c, 1))
        return 0;
    l->xy[2 * l->n] = xy[0];
    l->xy[2 * l->n + 1] = xy[1];
    l->nxy[2 * l->n] = nxy[0];
    l->nxy[2 * l->n + 1] = nxy[1];
    l->seg[l->n] = seg;
    l->t[l->n] = t;
    l->flags[l->n] = (unsigned char)flags;
    l->n++;
    return 1;
}

/* Room for n samples of one segment. */
static int scratch(ctx *c, size_t n)
{
    if (n <= c->scap)
        return 1;
    {
        size_t cap = c->scap ? c->scap : 64;
        double *a;
        while (cap < n)
            cap *= 2;
        if (!(a = realloc(c->par, cap * sizeof *a)))
            return 0;
        c->par = a;
        if (!(a = realloc(c->sxy, 2 * cap * sizeof *a)))
            return 0;
        c->sxy = a;
        if (!(a = realloc(c->snxy, 2 * cap * sizeof *a)))
            return 0;
        c->snxy = a;
        c->scap = cap;
    }
    return 1;
}

static void normal_of(const double t[2], double n[2])
{
    /* to the right of the direction of travel, as conica_curve's normals */
    n[0] = t[1];
    n[1] = -t[0];
}

/* ------------------------------------------------------------ joins */

/* What the join rules give at the start of segment j of a subpath. */
typedef struct join {
    int corner;
    double t_prev[2]; /* unit tangent the previous segment ends with */
    double t_next[2]; /* unit tangent segment j starts with */
} join;

/* How far a control point may lie off the chord of a straight segment. */
static double straight_tol(const ctx *c)
{
    return fmin(c->s.precision, PATH_STRAIGHT_TOL_FRACTION * c->tol);
}

/* Unit tangent of segment s at an end, and the length it is known over. */
static void seg_end_tangent(const ctx *c, size_t s, int end, double t[2], double *len)
{
    const double *q = seg_pts(c->p, s);
    int d = c->p->seg[s].degree;
    if (seg_straight(q, d, straight_tol(c))) {
        /* a straight Bézier's tangent is its chord's */
        *len = hypot(q[3 * d] - q[0], q[3 * d + 1] - q[1]);
        unit2(q[3 * d] - q[0], q[3 * d + 1] - q[1], t);
        return;
    }
    end_tangent(q, d, end, t, len);
}

static join join_at(const ctx *c, const conica_path_subpath *sp, size_t j)
{
    join J;
    size_t a, b = sp->first + j;
    double la, lb, g1;
    int a_line, b_line;
    memset(&J, 0, sizeof J);
    seg_end_tangent(c, b, 0, J.t_next, &lb);
    if (j == 0 && !sp->closed) {
        memcpy(J.t_prev, J.t_next, sizeof J.t_next);
        return J;
    }
    a = j == 0 ? sp->first + sp->n - 1 : b - 1;
    seg_end_tangent(c, a, 1, J.t_prev, &la);
    a_line = seg_straight(seg_pts(c->p, a), c->p->seg[a].degree, straight_tol(c));
    b_line = seg_straight(seg_pts(c->p, b), c->p->seg[b].degree, straight_tol(c));
    /* tangency to the precision the input was written with */
    g1 = fmax(PATH_G1_MIN, fmin(PATH_G1_MAX, PATH_G1_FACTOR * c->s.precision *
                                                 (1.0 / fmax(la, DBL_MIN) + 1.0 / fmax(lb, DBL_MIN))));
    J.corner = angle_between(J.t_prev, J.t_next) > fmax(c->s.corner_angle, g1);
    if (!J.corner) {
        double m[2];
        if (a_line && !b_line)
            memcpy(J.t_next, J.t_prev, sizeof m); /* lines stay straight: the curve follows */
        else if (b_line && !a_line)
            memcpy(J.t_prev, J.t_next, sizeof m);
        else if (!a_line && !b_line && unit2(J.t_prev[0] + J.t_next[0],
                                             J.t_prev[1] + J.t_next[1], m)) {
            memcpy(J.t_prev, m, sizeof m);
            memcpy(J.t_next, m, sizeof m);
        }
    }
    return J;
}

/* Normal written at a join vertex: the segment it starts at a corner, the
 * shared (or mean) tangent elsewhere. */
static void join_normal(const join *J, double n[2])
{
    double m[2];
    if (J->corner || !unit2(J->t_prev[0] + J->t_next[0], J->t_prev[1] + J->t_next[1], m))
        normal_of(J->t_next, n);
    else
        normal_of(m, n);
}

/* ------------------------------------------------------------ flattening */

static double bulge(const conica_path *p, size_t s, double ta, double tb, const double a[2],
                    const double n[2], int sign);
static double chord_line_dev(const conica_path *p, size_t s, double ta, double tb,
                             const double a[2], const double n[2], double stop);


/* The four directions of the bounding box: +x, -x, +y, -y. */
static const double box_dir[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};

/* Largest and smallest (B(t) - a) . n of a polynomial Bézier q of degree
 * 2 or 3 on [ta, tb], exactly, and where: the distance is the Bézier
 * g_k = (Q_k - a) . n (taken from a, so where the curve sits does not
 * matter), whose range conica__bern_range gives. */
static void poly_range(const double *q, int d, double ta, double tb, const double a[2],
                       const double n[2], double *vmax, double *tmax, double *vmin, double *tmin)
{
    double g[4];
    int k;
    for (k = 0; k <= d; k++)
        g[k] = (q[3 * k] - a[0]) * n[0] + (q[3 * k + 1] - a[1]) * n[1];
    conica__bern_range(g, d, ta, tb, vmin, tmin, vmax, tmax);
}

/* A polynomial Bézier of degree 2 or 3 (poly_range's exact extremes). */
static int poly23(const double *q, int d)
{
    return d >= 2 && d <= 3 && q[2] == 1.0 && q[5] == 1.0 && q[8] == 1.0 &&
           (d < 3 || q[11] == 1.0);
}

/* (C(t) - a) . dir at t, from C evaluated in full (bez_eval). */
static double along_at(const double *q, int d, double t, const double a[2], const double dir[2])
{
    double pt[2];
    bez_eval(q, d, t, pt, NULL, NULL);
    return (pt[0] - a[0]) * dir[0] + (pt[1] - a[1]) * dir[1];
}

/* Largest and smallest (C(t) - a) . dir of a rational quadratic q (an
 * arc's conic piece) on [ta, tb], exactly, and where; 0 when the
 * coefficients overflow (the caller samples instead). With
 * g_k = (Q_k - a) . dir the value is N / W, N = sum B_k w_k g_k and
 * W = sum B_k w_k in power form A0 + A1 t + A2 t^2 and B0 + B1 t + B2 t^2;
 * the numerator of its derivative, N' W - N W', is the quadratic
 * (A1 B0 - A0 B1) + 2 (A2 B0 - A0 B2) t + (A2 B1 - A1 B2) t^2 (the cubic
 * terms cancel), so the extremes are at the ends or at its roots. */
static int rat2_range(const double *q, double ta, double tb, const double a[2],
                      const double dir[2], double *vmax, double *tmax, double *vmin,
                      double *tmin)
{
    double n[3], w[3], r[2], A0, A1, A2, B0, B1, B2, c0, c1, c2;
    int k, nr = 0;
    for (k = 0; k < 3; k++) {
        w[k] = q[3 * k + 2];
        n[k] = w[k] * ((q[3 * k] - a[0]) * dir[0] + (q[3 * k + 1] - a[1]) * dir[1]);
    }
    A0 = n[0];
    A1 = 2.0 * (n[1] - n[0]);
    A2 = n[0] - 2.0 * n[1] + n[2];
    B0 = w[0];
    B1 = 2.0 * (w[1] - w[0]);
    B2 = w[0] - 2.0 * w[1] + w[2];
    c0 = A1 * B0 - A0 * B1;
    c1 = 2.0 * (A2 * B0 - A0 * B2);
    c2 = A2 * B1 - A1 * B2;
    if (!isfinite(c0) || !isfinite(c1) || !isfinite(c2))
        return 0;
    if (c2 != 0.0) {
        double disc = c1 * c1 - 4.0 * c2 * c0;
        if (!isfinite(disc))
            return 0;
        if (disc >= 0.0) { /* the stable pair of roots */
            double h = -0.5 * (c1 + copysign(sqrt(disc), c1));
            if (h != 0.0) {
                r[nr++] = h / c2;
                r[nr++] = c0 / h;
            } else {
                r[nr++] = 0.0; /* c1 = c0 = 0: a double root at 0 */
            }
        }
    } else if (c1 != 0.0) {
        r[nr++] = -c0 / c1;
    }
    *vmax = *vmin = along_at(q, 2, ta, a, dir);
    *tmax = *tmin = ta;
    for (k = -1; k < nr; k++) {
        double t = k < 0 ? tb : r[k], v;
        if (k >= 0 && !(t > ta && t < tb))
            continue;
        v = along_at(q, 2, t, a, dir);
        if (v > *vmax) {
            *vmax = v;
            *tmax = t;
        }
        if (v < *vmin) {
            *vmin = v;
            *tmin = t;
        }
    }
    return 1;
}

/* Largest and smallest (C(t) - a) . dir of the Bézier q (degree d) on
 * [ta, tb] and where: exact for polynomial quadratics and cubics and for
 * rational quadratics (returns 1), else the best of PATH_FIT_SAMPLES + 1
 * samples (returns 0; a golden section refines them). */
static int seg_range(const double *q, int d, double ta, double tb, const double a[2],
                     const double dir[2], double *vmax, double *tmax, double *vmin, double *tmin)
{
    int k;
    if (poly23(q, d)) {
        poly_range(q, d, ta, tb, a, dir, vmax, tmax, vmin, tmin);
        return 1;
    }
    if (d == 2 && rat2_range(q, ta, tb, a, dir, vmax, tmax, vmin, tmin))
        return 1;
    *vmax = -INFINITY;
    *vmin = INFINITY;
    *tmax = *tmin = ta;
    for (k = 0; k <= PATH_FIT_SAMPLES; k++) {
        double t = ta + (tb - ta) * k / PATH_FIT_SAMPLES, v = along_at(q, d, t, a, dir);
        if (v > *vmax) {
            *vmax = v;
            *tmax = t;
        }
        if (v < *vmin) {
            *vmin = v;
            *tmin = t;
        }
    }
    return 0;
}

/* Golden-section search for the largest (C(t) - a) . dir of the Bézier
 * q (degree d) on [lo, hi], from *best at *bt up (a sample inside the
 * bracket): one evaluation per step, the other interior point kept. Stops
 * early once *best exceeds stop. */
static void golden_max(const double *q, int d, double lo, double hi, const double a[2],
                       const double dir[2], int iters, double stop, double *best, double *bt)
{
    const double g = 0.6180339887498949;
    double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    double v1 = along_at(q, d, m1, a, dir), v2 = along_at(q, d, m2, a, dir);
    int it;
    for (it = 0; it < iters && *best <= stop; it++) {
        if (fmax(v1, v2) > *best) {
            *best = fmax(v1, v2);
            *bt = v1 > v2 ? m1 : m2;
        }
        if (v1 > v2) { /* the peak is in [lo, m2]: m1 becomes its upper point */
            hi = m2;
            m2 = m1;
            v2 = v1;
            m1 = hi - g * (hi - lo);
            v1 = along_at(q, d, m1, a, dir);
        } else {
            lo = m1;
            m1 = m2;
            v1 = v2;
            m2 = lo + g * (hi - lo);
            v2 = along_at(q, d, m2, a, dir);
        }
    }
    if (fmax(v1, v2) > *best) {
        *best = fmax(v1, v2);
        *bt = v1 > v2 ? m1 : m2;
    }
}

/* Largest (C(t) - a) . dir of segment s over [ta, tb], from best0 up, and
 * where (*targ): dense samples, then golden section (iters steps) round
 * the best one. The one search behind bulge() and seg_extreme(). */
static double seg_max_along(const conica_path *p, size_t s, double ta, double tb, const double a[2],
                            const double dir[2], double best0, int iters, double *targ)
{
    const double *q = seg_pts(p, s);
    int d = p->seg[s].degree;
    double best = best0, bt = ta;
    double vmax, tmax, vmin, tmin;
    int exact = seg_range(q, d, ta, tb, a, dir, &vmax, &tmax, &vmin, &tmin);
    if (vmax > best) {
        best = vmax;
        bt = tmax;
    }
    if (!exact && d > 1) {
        double h = (tb - ta) / PATH_FIT_SAMPLES;
        golden_max(q, d, fmax(ta, bt - h), fmin(tb, bt + h), a, dir, iters, INFINITY, &best, &bt);
    }
    *targ = bt;
    return best;
}



/* How far segment s on [ta, tb] reaches past the ends of the chord a b
 * along its direction u (|b - a| = len): a hook's tip or a hairpin beyond
 * the chord's end, which the distance from the chord's line misses. */
static double chord_overshoot(const conica_path *p, size_t s, double ta, double tb,
                              const double a[2], const double u[2], double len)
{
    const double *q = seg_pts(p, s);
    int d = p->seg[s].degree;
    double vmax, tmax, vmin, tmin, m[2] = {-u[0], -u[1]}, h = (tb - ta) / PATH_FIT_SAMPLES;
    if (!seg_range(q, d, ta, tb, a, u, &vmax, &tmax, &vmin, &tmin)) {
        vmin = -vmin;
        golden_max(q, d, fmax(ta, tmax - h), fmin(tb, tmax + h), a, u, PATH_CHORD_GOLDEN,
                   INFINITY, &vmax, &tmax);
        golden_max(q, d, fmax(ta, tmin - h), fmin(tb, tmin + h), a, m, PATH_CHORD_GOLDEN,
                   INFINITY, &vmin, &tmin);
        vmin = -vmin;
    }
    return fmax(0.0, fmax(vmax - len, -vmin));
}

/* A chord a b as chord_dev() reads it: its unit normal n (n = perp(b -
 * a) / |b - a|), unit direction u and length; ok = 0 for a = b. Set up
 * once per chord, not per segment it covers (hypot was a tenth of a long
 * path's flattening). */
typedef struct chord_frame {
    double n[2], u[2], len;
    int ok;
} chord_frame;

static void chord_frame_init(chord_frame *f, const double a[2], const double b[2])
{
    f->ok = unit2(b[1] - a[1], a[0] - b[0], f->n);
    f->ok = f->ok && unit2_len(b[0] - a[0], b[1] - a[1], f->u, &f->len);
}

/* Largest distance of segment s on [ta, tb] from the chord segment a b
 * (frame f): the distance from its line (both sides), and where the curve
 * reaches past an end, sqrt(line^2 + overshoot^2), which bounds the
 * distance from the segment with its end caps from above. */
static double chord_dev(const conica_path *p, size_t s, double ta, double tb, const double a[2],
                        const chord_frame *f, double stop)
{
    double line, over;
    if (!f->ok)
        return INFINITY;
    line = chord_line_dev(p, s, ta, tb, a, f->n, stop);
    if (!(line <= stop) || p->seg[s].degree == 1 || !(tb > ta))
        return line;
    over = chord_overshoot(p, s, ta, tb, a, f->u, f->len);
    return over > 0 ? hypot(line, over) : line;
}

/* Largest distance of segment s on [ta, tb] from the chord a b's line
 * (both sides). */
static double chord_line_dev(const conica_path *p, size_t s, double ta, double tb,
                             const double a[2], const double n[2], double stop)
{
    /* both sides from one set of samples; the golden section only on a
     * side the curve reaches, and not once the answer is known to exceed
     * stop (the greedy chord search asks only whether a chord fits) */
    const double *q = seg_pts(p, s);
    int d = p->seg[s].degree;
    double m[2], hi = 0, lo = 0, thi = ta, tlo = ta, h;
    if (d == 1 || !(tb > ta))
        return 0.0;
    {
        double vmax, tmax, vmin, tmin;
        if (seg_range(q, d, ta, tb, a, n, &vmax, &tmax, &vmin, &tmin))
            return fmax(0.0, fmax(vmax, -vmin));
        if (vmax > 0) {
            hi = vmax;
            thi = tmax;
        }
        if (-vmin > 0) {
            lo = -vmin;
            tlo = tmin;
        }
    }
    if (fmax(hi, lo) > stop)
        return fmax(hi, lo);
    h = (tb - ta) / PATH_FIT_SAMPLES;
    if (hi > 0)
        golden_max(q, d, fmax(ta, thi - h), fmin(tb, thi + h), a, n, PATH_CHORD_GOLDEN, stop, &hi, &thi);
    m[0] = -n[0];
    m[1] = -n[1];
    if (lo > 0 && hi <= stop)
        golden_max(q, d, fmax(ta, tlo - h), fmin(tb, tlo + h), a, m, PATH_CHORD_GOLDEN, stop, &lo, &tlo);
    return fmax(hi, lo);
}

/* Largest value of C(t) . dir over segment s, and where. */
static double seg_extreme(const conica_path *p, size_t s, const double dir[2], double *targ)
{
    const double *q = seg_pts(p, s), zero[2] = {0, 0};
    int d = p->seg[s].degree;
    double bt, best = seg_max_along(p, s, 0.0, 1.0, zero, dir, -INFINITY, 60, &bt);
    { /* an end that is as high to rounding is the extreme (a flat top
       * drawn as a join is reached at the join itself) */
        double v0 = q[0] * dir[0] + q[1] * dir[1], v1 = q[3 * d] * dir[0] + q[3 * d + 1] * dir[1];
        double tiny = PATH_EXT_REL * (fabs(best) + fabs(v0) + fabs(v1));
        if (v1 >= best - tiny && v1 >= v0) {
            bt = 1.0;
            best = fmax(best, v1);
        } else if (v0 >= best - tiny) {
            bt = 0.0;
            best = fmax(best, v0);
        }
    }
    *targ = bt;
    return best;
}

/* Segment s plotted with the guaranteed plotter at a fraction of the
 * flattening tolerance (its points on the segment, with parameters). */
/* Points a segment's dense plot may write straight into arrays of this
 * size before conica_plot (which grows its own) takes over. */
#define PATH_DENSE_CAP 1024

static conica_code dense_seg(ctx *c, size_t s, conica_polyline *pl, conica_status *est)
{
    const conica_path *p = c->p;
    const double *q = seg_pts(p, s);
    int d = p->seg[s].degree, k;
    conica_bspline bs;
    conica_plot_settings ps = conica_plot_defaults();
    conica_plot_stats pst;
    conica_code rc;
    double ctrl[2 * (CONICA_PATH_MAX_DEGREE + 1)], w[CONICA_PATH_MAX_DEGREE + 1];
    for (k = 0; k <= d; k++) {
        ctrl[2 * k] = q[3 * k];
        ctrl[2 * k + 1] = q[3 * k + 1];
        w[k] = q[3 * k + 2];
    }
    {
        /* The piece straight into arrays of PATH_DENSE_CAP points (the same
         * points as conica_plot gives), conica_plot below when it needs more */
        size_t cap = c->budget + 1 < PATH_DENSE_CAP ? c->budget + 1 : PATH_DENSE_CAP, n = 0;
        double tol = c->tol * c->flat_fraction / (double)PATH_FLAT_DENSE;
        size_t iters = PATH_FLAT_TRIALS * cap;
        pl->xy = malloc(2 * cap * sizeof *pl->xy);
        pl->t = malloc(cap * sizeof *pl->t);
        pl->piece_start = malloc(sizeof *pl->piece_start);
        if (!pl->xy || !pl->t || !pl->piece_start) {
            conica_polyline_free(pl);
            conica_polyline_init(pl);
            return conica__fail(est, CONICA_ERR_NOMEM, 0, s, "out of memory");
        }
        rc = conica_plot_bezier(d, ctrl, p->seg[s].rational ? w : NULL, tol, iters, pl->xy, pl->t,
                                cap, &n, est);
        if (rc == CONICA_OK) {
            pl->n = n;
            pl->cap = cap;
            pl->dim = 2;
            pl->npieces = 1;
            pl->piece_start[0] = 0;
            return CONICA_OK;
        }
        conica_polyline_free(pl);
        conica_polyline_init(pl);
        if (rc != CONICA_ERR_LIMIT)
            return rc;
    }
    conica_bspline_init(&bs);
    rc = conica_bspline_from_bezier(d, 2, ctrl, p->seg[s].rational ? w : NULL, &bs, est);
    if (rc == CONICA_OK) {
        ps.method = CONICA_PLOT_GUARANTEED;
        /* plotted finer, then the longest chords within the tolerance
         * (the plotter's own chords stay well inside it) */
        ps.abs_tolerance = c->tol * c->flat_fraction / (double)PATH_FLAT_DENSE;
        ps.max_points = c->budget + 1; /* the work stays bounded by the budget */
        ps.max_iterations = PATH_FLAT_TRIALS * ps.max_points < ps.max_iterations
                                ? PATH_FLAT_TRIALS * ps.max_points
                                : ps.max_iterations;
        rc = conica_plot(&bs, &ps, pl, &pst, est);
        if (rc == CONICA_ERR_LIMIT) {
            /* too many dense points for the budget: the chords at T itself */
            conica_polyline_free(pl);
            conica_polyline_init(pl);
            ps.abs_tolerance = c->tol * c->flat_fraction;
            rc = conica_plot(&bs, &ps, pl, &pst, est);
        }
        if (rc == CONICA_OK && !pl->t)
            rc = conica__fail(est, CONICA_ERR_NUMERIC, 0, s, "the plotter gave no parameters");
    }
    conica_bspline_free(&bs);
    return rc;
}

/* A run of segments flattened as one curve: the parameter u = k + t runs
 * over segment segs[k] for u in [k, k + 1]. */
typedef struct run {
    const conica_path *p;
    const size_t *segs;
    size_t m;
} seg_run;

static void run_eval(const seg_run *R, double u, double pt[2])
{
    size_t k = conica__size_clamp(u, R->m - 1); /* NaN or below 0: the first */
    size_t s = R->segs[k];
    bez_eval(seg_pts(R->p, s), R->p->seg[s].degree, u - (double)k, pt, NULL, NULL);
}

/* Largest distance of the run on [u0, u1] from the chord a b. */
static double run_dev(const seg_run *R, double u0, double u1, const double a[2], const double b[2],
                      double stop)
{
    size_t k0 = (size_t)u0, k1;
    double worst = 0;
    chord_frame f;
    chord_frame_init(&f, a, b);
    if (k0 >= R->m)
        k0 = R->m - 1;
    k1 = u1 >= (double)R->m ? R->m - 1 : (size_t)u1;
    if (k1 > k0 && u1 == (double)k1)
        k1--; /* u1 is the start of segment k1: nothing of it */
    for (size_t k = k0; k <= k1; k++) {
        double ta = k == k0 ? u0 - (double)k : 0.0, tb = k == k1 ? u1 - (double)k : 1.0;
        double dv = chord_dev(R->p, R->segs[k], ta, tb, a, &f, stop);
        worst = dv > worst ? dv : worst;
        if (worst > stop)
            break; /* the chord does not fit: how far it misses is not asked */
    }
    return worst;
}

/* Room for need points in the parallel lists U (parameters) and X (x, y
 * pairs) of flatten_run(); 0 when out of memory (the lists stay valid). */
static int grow_ux(double **U, double **X, size_t *cap, size_t need)
{
    double *u2, *x2;
    if (need <= *cap)
        return 1;
    u2 = realloc(*U, need * sizeof **U);
    if (!u2)
        return 0;
    *U = u2;
    x2 = realloc(*X, 2 * need * sizeof **X);
    if (!x2)
        return 0;
    *X = x2;
    *cap = need;
    return 1;
}

/*
 * Append the run of segments segs[0..m) flattened within the tolerance (its
 * first point is there already) as one curve, so that chords may pass over
 * the joins between them (the joins are tangent: the caller breaks runs at
 * corners and straight segments). jn[2k] is the normal at the join after
 * segs[k] (k < m - 1; NULL when m = 1), written when a vertex falls on it;
 * the run's end point gets nend and endflags. *bound grows to the largest
 * chord deviation.
 */
static conica_code flatten_run(ctx *c, const size_t *segs, size_t m, const double *jn,
                               const double nend[2], unsigned endflags, double *bound)
{
    const conica_path *p = c->p;
    seg_run R;
    conica_status est;
    conica_code rc = CONICA_OK;
    double *U = NULL, *X = NULL, thr = c->tol * c->flat_fraction, worst = 0, fz[4 * 8];
    size_t n = 0, cap = 0, k, i, nfz = 0;
    R.p = p;
    R.segs = segs;
    R.m = m;
    /* 1. the dense points of every segment, one list over u */
    for (k = 0; k < m && rc == CONICA_OK; k++) {
        conica_polyline pl;
        conica_polyline_init(&pl);
        rc = dense_seg(c, segs[k], &pl, &est);
        if (rc == CONICA_OK) {
            size_t from = k == 0 ? 0 : 1; /* a join once */
            if (n + pl.n > cap && !grow_ux(&U, &X, &cap, 2 * (n + pl.n))) {
                conica_polyline_free(&pl);
                free(U);
                free(X);
                return fail_nomem(c);
            }
            for (i = from; i < pl.n; i++) {
                U[n] = (double)k + pl.t[i];
                X[2 * n] = pl.xy[2 * i];
                X[2 * n + 1] = pl.xy[2 * i + 1];
                if (i + 1 == pl.n) { /* the segment's end, exactly (a join: u = k + 1) */
                    const double *qe = seg_pts(p, segs[k]);
                    int de = p->seg[segs[k]].degree;
                    U[n] = (double)(k + 1);
                    X[2 * n] = qe[3 * de];
                    X[2 * n + 1] = qe[3 * de + 1];
                }
                n++;
            }
            if (k == 0)
                U[0] = 0.0;
        }
        conica_polyline_free(&pl);
    }
    if (rc != CONICA_OK) {
        free(U);
        free(X);
        if (rc == CONICA_ERR_LIMIT)
            return take(c, c->budget + 1);
        return conica__fail(c->st, rc, 0, c->subpath, "subpath %zu: %s", c->subpath + 1,
                            est.message);
    }
    /* 1b. where the run reaches the subpath's bounding box, a vertex: the
     * part's extent is as drawn (an inscribed polygon would lose up to the
     * tolerance there). Inserted into the list and marked: no chord passes
     * over one. */
    if (c->use_ext && n > 1) {
        double fu[4 * 8];
        size_t nf = 0, f;
        for (k = 0; k < m; k++)
            for (int dd = 0; dd < 4 && nf < sizeof fu / sizeof *fu; dd++) {
                double t, v = seg_extreme(p, segs[k], box_dir[dd], &t);
                double tiny = PATH_EXT_REL * (fabs(c->ext[dd]) + c->tol);
                if (v >= c->ext[dd] - tiny) {
                    double u = (double)k + t;
                    if (t >= 1.0 - PATH_EXT_SNAP)
                        u = (double)(k + 1); /* the drawn end point */
                    else if (t <= PATH_EXT_SNAP)
                        u = (double)k;
                    if (u > U[0] && u < U[n - 1])
                        fu[nf++] = u;
                }
            }
        if (!grow_ux(&U, &X, &cap, n + nf)) {
            free(U);
            free(X);
            return fail_nomem(c);
        }
        for (f = 0; f < nf; f++) {
            size_t at = 0, j;
            double pt[2];
            while (at < n && U[at] < fu[f])
                at++;
            if (at < n && U[at] == fu[f]) { /* a dense point already */
                fz[nfz++] = U[at];
                continue;
            }
            for (j = n; j > at; j--) {
                U[j] = U[j - 1];
                X[2 * j] = X[2 * j - 2];
                X[2 * j + 1] = X[2 * j - 1];
            }
            if (fu[f] == floor(fu[f]) && fu[f] > 0) { /* a join: its drawn point */
                const double *qp = seg_pts(p, segs[(size_t)fu[f] - 1]);
                int dp = p->seg[segs[(size_t)fu[f] - 1]].degree;
                pt[0] = qp[3 * dp];
                pt[1] = qp[3 * dp + 1];
            } else {
                run_eval(&R, fu[f], pt);
            }
            U[at] = fu[f];
            X[2 * at] = pt[0];
            X[2 * at + 1] = pt[1];
            n++;
            fz[nfz++] = fu[f];
        }
    }
    /* 2. greedy longest chords: from the current start, gallop and bisect
     * over the dense points for the last end that keeps the chord within
     * the tolerance, then bisect the parameter between it and the first
     * one that does not, so that every chord uses the whole tolerance (on a
     * circle this gives the fewest points any inscribed polygon can have).
     * Every chord is measured against the segments themselves. The chosen
     * points overwrite the list in place (each is at or past its slot). */
    {
        double u0 = U[0], p0[2] = {X[0], X[1]};
        size_t i0 = 0, nk = 1, last = 0;
        while (n > 1) {
            size_t best = i0, step = 1, lo, hi, f;
            double dv, ulo, uhi, u1, p1[2], stop = U[n - 1];
            int it;
            for (f = 0; f < nfz; f++) /* the next vertex that must be */
                if (fz[f] > u0 && fz[f] < stop)
                    stop = fz[f];
            /* the end is already chosen when the last chord went to it
             * point by point (coordinates near 1e176 make even the chord
             * from a point to itself measure inf) */
            if (i0 + 1 >= n)
                break;
            /* the last dense point at or before stop: stop never
             * decreases (u0 only grows, the list past i0 is as built), so
             * the search goes on from the previous one instead of from the
             * list's end (quadratic in the points of a long run) */
            last = last > i0 + 1 ? last : i0 + 1;
            while (last + 1 < n && U[last + 1] <= stop)
                last++;
            dv = run_dev(&R, u0, U[last], p0, X + 2 * last, thr);
            if (dv <= thr) { /* the rest, up to the next forced vertex, in one chord */
                worst = dv > worst ? dv : worst;
                U[nk] = U[last];
                X[2 * nk] = X[2 * last];
                X[2 * nk + 1] = X[2 * last + 1];
                nk++;
                if (last == n - 1)
                    break;
                u0 = U[last];
                p0[0] = X[2 * last];
                p0[1] = X[2 * last + 1];
                i0 = last;
                continue;
            }
            while (best + step < last &&
                   run_dev(&R, u0, U[best + step], p0, X + 2 * (best + step), thr) <= thr) {
                best += step;
                step *= 2;
            }
            lo = best;
            hi = best + step < last ? best + step : last;
            while (hi - lo > 1) {
                size_t mid = lo + (hi - lo) / 2;
                if (run_dev(&R, u0, U[mid], p0, X + 2 * mid, thr) <= thr)
                    lo = mid;
                else
                    hi = mid;
            }
            /* feasible at ulo (the start itself when no dense point is),
             * not at uhi = the next dense point */
            ulo = lo > i0 ? U[lo] : u0;
            uhi = U[lo + 1];
            for (it = 0; it < PATH_FLAT_BISECT; it++) {
                double um = 0.5 * (ulo + uhi), pm[2];
                run_eval(&R, um, pm);
                if (run_dev(&R, u0, um, p0, pm, thr) <= thr)
                    ulo = um;
                else
                    uhi = um;
            }
            /* the end moves past the start's dense point (lo > i0), so
             * the chosen points never outrun the list they overwrite: where
             * not even the next dense point is within reach (rounding at
             * coordinates of 1e48), the chord goes to it all the same */
            if (lo > i0 && ulo >= U[lo]) {
                u1 = ulo;
                if (u1 == U[lo]) {
                    p1[0] = X[2 * lo];
                    p1[1] = X[2 * lo + 1];
                } else {
                    run_eval(&R, u1, p1);
                }
            } else { /* no room at all: the next dense point */
                lo++;
                u1 = U[lo];
                p1[0] = X[2 * lo];
                p1[1] = X[2 * lo + 1];
            }
            dv = run_dev(&R, u0, u1, p0, p1, INFINITY);
            worst = dv > worst ? dv : worst;
            U[nk] = u1;
            X[2 * nk] = p1[0];
            X[2 * nk + 1] = p1[1];
            nk++;
            u0 = u1;
            p0[0] = p1[0];
            p0[1] = p1[1];
            i0 = lo;
        }
        n = nk;
    }
    if (worst > *bound)
        *bound = worst;
    /* 3. the points, with the normals of the curve there */
    rc = n > 1 ? take(c, n - 1) : CONICA_OK;
    for (i = 1; i < n && rc == CONICA_OK; i++) {
        double u = U[i], tg[2], nn[2], pt[2], t;
        size_t kk = conica__size_clamp(u, m - 1), s = segs[kk];
        const double *q = seg_pts(p, s);
        int d = p->seg[s].degree;
        if (i + 1 == n) { /* the run's end point exactly */
            const double *qe = seg_pts(p, segs[m - 1]);
            int de = p->seg[segs[m - 1]].degree;
            pt[0] = qe[3 * de];
            pt[1] = qe[3 * de + 1];
            if (!add_pt(c, pt, nend, segs[m - 1], 1.0, endflags))
                rc = fail_nomem(c);
            break;
        }
        t = u - (double)kk;
        if (t == 0.0 && kk > 0) { /* exactly on a join: the drawn end point */
            const double *qp = seg_pts(p, segs[kk - 1]);
            int dp = p->seg[segs[kk - 1]].degree;
            pt[0] = qp[3 * dp];
            pt[1] = qp[3 * dp + 1];
            if (!add_pt(c, pt, jn + 2 * (kk - 1), segs[kk - 1], 1.0, CONICA_PATH_PT_VERTEX))
                rc = fail_nomem(c);
            continue;
        }
        pt[0] = X[2 * i];
        pt[1] = X[2 * i + 1];
        inner_tangent(q, d, t, 1, tg);
        normal_of(tg, nn);
        if (!add_pt(c, pt, nn, s, t, 0))
            rc = fail_nomem(c);
    }
    free(U);
    free(X);
    return rc;
}

/* One segment flattened within the tolerance (its first point is there
 * already); its end point gets normal nend and the flags. */
static conica_code flatten_seg(ctx *c, size_t s, const double nend[2], unsigned endflags,
                               double *bound)
{
    return flatten_run(c, &s, 1, NULL, nend, endflags, bound);
}

/* ------------------------------------------------------------ smoothing */

/* A segment prepared for the many evaluations of one check: polynomial
 * pieces of degree <= 3 (weights 1, the SVG and glyph case) go straight to
 * bez_eval_poly3's Bernstein formulas (bez_eval takes the same branch, so
 * the values are bit for bit those of bez_eval); others through bez_eval. */
typedef struct seg_fn {
    const double *q;
    int d, poly, cubic;
} seg_fn;

static seg_fn seg_fn_of(const double *q, int d)
{
    seg_fn f;
    f.q = q;
    f.d = d;
    f.poly = d <= 3 && q[2] == 1.0 && q[5] == 1.0 && (d < 2 || q[8] == 1.0) &&
             (d < 3 || q[11] == 1.0);
    f.cubic = f.poly && d == 3;
    return f;
}

/* The point and both derivatives (the polynomial cubic, SVG's common case,
 * unrolled in place: bern3* are bez_eval_poly3's own formulas). */
static CONICA__HOT_INLINE void seg_fn_eval(const seg_fn *f, double t, double c[2], double d1[2],
                                           double d2[2])
{
    if (f->cubic) {
        double u = 1.0 - t;
        c[0] = bern3(f->q, u, t);
        c[1] = bern3(f->q + 1, u, t);
        d1[0] = bern3_d1(f->q, u, t);
        d1[1] = bern3_d1(f->q + 1, u, t);
        d2[0] = bern3_d2(f->q, u, t);
        d2[1] = bern3_d2(f->q + 1, u, t);
    } else if (f->poly) {
        bez_eval_poly3(f->q, f->d, t, c, d1, d2);
    } else {
        bez_eval(f->q, f->d, t, c, d1, d2);
    }
}

/* The point alone. */
static CONICA__HOT_INLINE void seg_fn_point(const seg_fn *f, double t, double c[2])
{
    if (f->cubic) {
        double u = 1.0 - t;
        c[0] = bern3(f->q, u, t);
        c[1] = bern3(f->q + 1, u, t);
    } else if (f->poly) {
        bez_eval_poly3(f->q, f->d, t, c, NULL, NULL);
    } else {
        bez_eval(f->q, f->d, t, c, NULL, NULL);
    }
}

/* Closest point of segment f to x for t in [lo, hi], from the guess t0:
 * Newton on |C(t) - x|^2, clamped, keeping the best. Newton converges
 * quadratically from the dense grid's guess, so once a step is below
 * PATH_NEWTON_SETTLED of [lo, hi] the point it lands on is the foot to
 * rounding and the search ends there (further steps only move t by the
 * rounding of C(t) - x, which at coordinates far from the origin never
 * falls below the 1e-14 stop). */
static double project(const seg_fn *f, const double x[2], double t0, double lo, double hi,
                      double *dist)
{
    double best = t0, bd, t = t0, c[2], d1[2], d2[2];
    int k;
    seg_fn_eval(f, t, c, d1, d2);
    bd = (c[0] - x[0]) * (c[0] - x[0]) + (c[1] - x[1]) * (c[1] - x[1]);
    for (k = 0; k < PATH_NEWTON_STEPS; k++) {
        double ex = c[0] - x[0], ey = c[1] - x[1];
        double g = ex * d1[0] + ey * d1[1];
        double h = d1[0] * d1[0] + d1[1] * d1[1] + ex * d2[0] + ey * d2[1], dd, tn;
        if (!(h > 0))
            h = d1[0] * d1[0] + d1[1] * d1[1];
        if (!(h > 0))
            break;
        tn = t - g / h;
        tn = tn < lo ? lo : tn > hi ? hi : tn;
        if (fabs(tn - t) <= 1e-14 * (hi - lo))
            break; /* converged */
        dd = fabs(tn - t);
        t = tn;
        if (dd <= PATH_NEWTON_SETTLED * (hi - lo) || k + 1 == PATH_NEWTON_STEPS) {
            /* settled (or out of steps): this evaluation is the last, and
             * only its point is wanted */
            seg_fn_point(f, t, c);
            k = PATH_NEWTON_STEPS;
        } else {
            seg_fn_eval(f, t, c, d1, d2);
        }
        dd = (c[0] - x[0]) * (c[0] - x[0]) + (c[1] - x[1]) * (c[1] - x[1]);
        if (dd < bd) {
            bd = dd;
            best = t;
        }
    }
    *dist = sqrt(bd);
    return best;
}

static CONICA__HOT_INLINE double dist2(const double *a, const double *b)
{
    double dx = a[0] - b[0], dy = a[1] - b[1];
    return dx * dx + dy * dy;
}

/* Searches of the nearest dense point / chord start this far round the
 * previous best (back w, ahead 2w) and double while the best is on the
 * window's edge (the correspondence is monotone; a miss can only
 * over-state a distance). With two dense points per limit chord the next
 * limit point's dense point lies about 2 ahead (3 keeps room for uneven
 * limit points), the next dense point's chord 0 or 1 ahead. */
#define PATH_WINDOW_DENSE 3
#define PATH_WINDOW_CHORD 1
/* Dense points and chords of one check on the stack up to this many. */
#define PATH_CHECK_STACK 1024

/* Largest |C''| of a polynomial piece of degree <= 3 on [ta, tb]: C'' is
 * linear in t there (constant for a quadratic), so its length, a convex
 * function, peaks at an end. */
static double poly_d2_max(const seg_fn *f, double ta, double tb)
{
    double c[2], d1[2], a[2], b[2];
    if (f->d < 2)
        return 0;
    seg_fn_eval(f, ta, c, d1, a);
    seg_fn_eval(f, tb, c, d1, b);
    return sqrt(fmax(a[0] * a[0] + a[1] * a[1], b[0] * b[0] + b[1] * b[1]));
}

/* Safety factor on a bound before it may stand in for a measurement (its
 * own rounding: a handful of operations, each within 2^-53). */
#define PATH_BOUND_MARGIN (1 + 1e-12)

/* The bound of check_edge's comment from the points' parameters tau[0..m]
 * and their distances F[i] = |C(tau_i) - v_i|, the limit chords' bulge
 * and the largest point distance added; INFINITY when tau is out of order. */
static double feet_bound(const double *tau, const double *F, size_t m, double d2max, double sag,
                         double worst2)
{
    double bound = 0;
    size_t i;
    for (i = 0; i < m; i++) {
        double dt = tau[i + 1] - tau[i], b;
        if (!(dt >= 0))
            return INFINITY;
        b = (F[i] > F[i + 1] ? F[i] : F[i + 1]) + 0.125 * dt * dt * d2max;
        bound = b > bound ? b : bound;
    }
    bound += 1.6 * 0.125 * sqrt(sag);
    return bound > sqrt(worst2) ? bound : sqrt(worst2);
}

/*
 * Compare the limit polyline v[0..m] (v[0], v[m] the samples at ta, tb) of
 * one sample edge with the segment on [ta, tb]; returns the largest
 * distance in either direction, the chords' own bulge counted against us.
 * tau[i] gets the parameter of point i (its foot on the segment) where
 * i % keep == 0 (keep 0: none wanted; the others may get any parameter).
 *
 * need: the caller needs the exact figure only where it exceeds need
 * (the largest already measured, at most the tolerance; INFINITY: only
 * tau is wanted). Where a rigorous bound of it does not exceed need, the
 * bound is returned instead, and the search of the dense points against
 * the polyline is skipped: for a polynomial piece and any parameters
 * tau_0 <= ... <= tau_m with F_i = |C(tau_i) - v_i|, C on [tau_i, tau_i+1]
 * lies within max(F_i, F_i+1) + (tau_i+1 - tau_i)^2 / 8 max|C''| of chord
 * i (the chord of C(tau_i), C(tau_i+1) is that close to chord i, C within
 * the linear interpolation error of that chord), which bounds every dense
 * point's distance from the polyline, and F_i bounds point i's distance
 * from the segment. So the points whose parameter is not wanted first get
 * the point of the dense polyline nearest to them, mapped to its
 * parameter, instead of Newton's foot, and get Newton's only when the bound
 * does not do. The verdict against the tolerance and the largest value
 * over a piece are those of the full search.
 *
 * written: v is the polyline that is written (not a limit polyline that
 * stands for the limit curve): PATH_WRITTEN_DENSE dense points per chord,
 * and no limit-curve bulge added, so the figure is the distance of the
 * polyline itself (its chords, end caps included) from the segment.
 */
static double check_edge(const double *q, int d, double ta, double tb, const double *v, size_t m,
                         double *tau, size_t keep, double need, int written)
{
    size_t per = written ? PATH_WRITTEN_DENSE : 2, M = per * m, i, j, prev, nskip = 0;
    double worst2 = 0, wb2 = 0, sag = 0, *heap = NULL, span = (tb - ta) / (double)M;
    double dense[2 * (2 * PATH_CHECK_STACK + 1)], chord[3 * PATH_CHECK_STACK],
           foot[PATH_CHECK_STACK + 1], *D = dense, *E = chord, *F = foot;
    size_t nearest[PATH_CHECK_STACK + 1], *N = nearest;
    seg_fn f = seg_fn_of(q, d);
    int bounded = f.poly && need < INFINITY;
    if (m > PATH_CHECK_STACK || M > 2 * PATH_CHECK_STACK) {
        heap = malloc((2 * (M + 1) + 3 * m + m + 1) * sizeof *heap + (m + 1) * sizeof *N);
        if (!heap)
            return INFINITY;
        D = heap;
        E = heap + 2 * (M + 1);
        F = E + 3 * m;
        N = (size_t *)(void *)(F + m + 1);
    }
    for (j = 0; j <= M; j++)
        seg_fn_point(&f, ta + (tb - ta) * (double)j / (double)M, D + 2 * j);
    tau[0] = ta;
    tau[m] = tb;
    /* limit points -> segment: the nearest dense point, searched from the
     * previous point's (the correspondence is monotone), the window doubled
     * while the best lies on its edge */
    for (i = 1, prev = 0; i < m; i++) {
        size_t w = PATH_WINDOW_DENSE * per / 2, lo, hi, bj;
        double bd, dist, t0, tlo, thi, sx, sy;
        for (;;) {
            lo = prev > w ? prev - w : 0;
            hi = prev + 2 * w < M ? prev + 2 * w : M;
            bd = INFINITY;
            for (j = lo, bj = lo; j <= hi; j++) {
                double dd = dist2(D + 2 * j, v + 2 * i);
                if (dd < bd) {
                    bd = dd;
                    bj = j;
                }
            }
            if ((bj == lo && lo > 0) || (bj == hi && hi < M)) {
                w *= 2;
                continue;
            }
            break;
        }
        prev = bj;
        sx = v[2 * i - 2] - 2 * v[2 * i] + v[2 * i + 2];
        sy = v[2 * i - 1] - 2 * v[2 * i + 1] + v[2 * i + 3];
        sx = sx * sx + sy * sy;
        sag = sx > sag ? sx : sag;
        N[i] = bj;
        if (bounded && (keep == 0 || i % keep != 0)) {
            /* the nearer dense chord at bj, the point of it nearest to v_i */
            size_t k2 = bj == 0 ? 1
                        : bj == M || dist2(D + 2 * (bj - 1), v + 2 * i) <
                                           dist2(D + 2 * (bj + 1), v + 2 * i)
                            ? bj - 1
                            : bj + 1;
            double ex = D[2 * k2] - D[2 * bj], ey = D[2 * k2 + 1] - D[2 * bj + 1];
            double el = ex * ex + ey * ey, c[2], sp;
            sp = el > 0 ? ((v[2 * i] - D[2 * bj]) * ex + (v[2 * i + 1] - D[2 * bj + 1]) * ey) / el
                        : 0;
            sp = sp > 0 ? sp : 0;
            sp = sp < 1 ? sp : 1;
            t0 = ta + (tb - ta) * (double)bj / (double)M +
                 sp * span * (k2 > bj ? 1.0 : -1.0);
            seg_fn_point(&f, t0, c);
            tau[i] = t0;
            F[i] = sqrt(dist2(c, v + 2 * i));
            worst2 = F[i] * F[i] > worst2 ? F[i] * F[i] : worst2;
            nskip++;
            continue;
        }
        t0 = ta + (tb - ta) * (double)bj / (double)M;
        tlo = ta + (tb - ta) * (double)(bj ? bj - 1 : 0) / (double)M;
        thi = ta + (tb - ta) * (double)(bj < M ? bj + 1 : M) / (double)M;
        t0 = project(&f, v + 2 * i, t0, tlo, thi, &dist);
        tau[i] = t0;
        F[i] = dist;
        worst2 = dist * dist > worst2 ? dist * dist : worst2;
    }
    if (bounded) {
        /* the bound of the polyline's distance from the segment (above) */
        double c[2], d2max = poly_d2_max(&f, ta, tb);
        seg_fn_point(&f, ta, c);
        F[0] = sqrt(dist2(c, v));
        seg_fn_point(&f, tb, c);
        F[m] = sqrt(dist2(c, v + 2 * m));
        for (;;) {
            double bound = feet_bound(tau, F, m, d2max, written ? 0.0 : sag, worst2);
            if (bound * PATH_BOUND_MARGIN <= need) {
                free(heap);
                return bound;
            }
            if (!nskip)
                break;
            /* Newton's feet for the points that went without, the largest
             * distance measured again, and the bound tried once more */
            worst2 = 0;
            for (i = 1; i < m; i++) {
                if (keep == 0 || i % keep != 0) {
                    size_t bj = N[i];
                    double t0 = ta + (tb - ta) * (double)bj / (double)M;
                    double tlo = ta + (tb - ta) * (double)(bj ? bj - 1 : 0) / (double)M;
                    double thi = ta + (tb - ta) * (double)(bj < M ? bj + 1 : M) / (double)M;
                    tau[i] = project(&f, v + 2 * i, t0, tlo, thi, F + i);
                }
                worst2 = F[i] * F[i] > worst2 ? F[i] * F[i] : worst2;
            }
            nskip = 0;
        }
    }
    if (need == INFINITY) {
        free(heap);
        return sqrt(worst2);
    }
    /* segment -> limit polyline, likewise; each chord's direction and
     * squared length once */
    for (i = 0; i < m; i++) {
        E[3 * i] = v[2 * i + 2] - v[2 * i];
        E[3 * i + 1] = v[2 * i + 3] - v[2 * i + 1];
        E[3 * i + 2] = E[3 * i] * E[3 * i] + E[3 * i + 1] * E[3 * i + 1];
    }
    for (j = 0, prev = 0; j <= M; j++) {
        size_t w = PATH_WINDOW_CHORD, lo, hi, bi;
        double bd;
        for (;;) {
            lo = prev > w ? prev - w : 0;
            hi = prev + 2 * w < m - 1 ? prev + 2 * w : m - 1;
            bd = INFINITY;
            for (i = lo, bi = lo; i <= hi; i++) {
                /* squared distance of D_j from chord i (v_i + s e, s in [0, 1]) */
                const double *e = E + 3 * i;
                double px = D[2 * j] - v[2 * i], py = D[2 * j + 1] - v[2 * i + 1];
                double s = e[2] > 0 ? (px * e[0] + py * e[1]) / e[2] : 0, dx, dy, dd;
                /* clamped to [0, 1] in the max/min form, which compiles
                 * without branches (which way it goes is a coin toss) */
                s = s > 0 ? s : 0;
                s = s < 1 ? s : 1;
                dx = px - s * e[0];
                dy = py - s * e[1];
                dd = dx * dx + dy * dy;
                if (dd < bd) {
                    bd = dd;
                    bi = i;
                }
            }
            if ((bi == lo && lo > 0) || (bi == hi && hi < m - 1)) {
                w *= 2;
                continue;
            }
            break;
        }
        prev = bi;
        wb2 = bd > wb2 ? bd : wb2;
    }
    free(heap);
    /* distance to a chord over-states the distance to the limit curve by
     * at most the chord's bulge (|second difference| / 8); the dense
     * points' own bulge is a quarter of it */
    {
        double wb = sqrt(wb2) + (written ? 0.0 : 1.6 * 0.125 * sqrt(sag)), wa = sqrt(worst2);
        return wb > wa ? wb : wa;
    }
}

/* Levels at which the limit polyline's chords of sample edges (chord len,
 * turn angle) bulge by at most `limit`: chord * turn / (8 * 4^L). */
static double sag0(const double *xy, const double *nxy, size_t n, int closed)
{
    double worst = 0;
    size_t i, ne = closed ? n : n - 1;
    for (i = 0; i < ne; i++) {
        size_t k = (i + 1) % n;
        double len = hypot(xy[2 * k] - xy[2 * i], xy[2 * k + 1] - xy[2 * i + 1]);
        double turn = angle_between(nxy + 2 * i, nxy + 2 * k);
        double b = len * fmax(turn, 1e-3) / 8.0;
        worst = b > worst ? b : worst;
    }
    return worst;
}

/* The estimate sag0() / 4^L of the level-L chords' bulge. */
static double sag_at(double s0, int L)
{
    return s0 / ldexp(1.0, 2 * L);
}

/* The fewest levels in [lo, hi] whose chords bulge by at most `limit`
 * (by sag_at: each level halves the edges and their turning, which
 * quarters a chord's bulge). */
static int level_for_sag(double s0, double limit, int lo, int hi)
{
    int L;
    for (L = lo; L < hi && sag_at(s0, L) > limit; L++)
        ;
    return L;
}

static int levels_for(const double *xy, const double *nxy, size_t n, int closed, double limit,
                      int lo, int hi)
{
    return level_for_sag(sag0(xy, nxy, n, closed), limit, lo, hi);
}

/* The largest distance of an odd point of the edges' sub-polylines (the
 * last subdivision level's new points) from the chord of its two
 * neighbours, over sample edges idx[i]..idx[i + 1] of `per` points each
 * (closed: the last runs back to point 0); -1 when an edge has another
 * count (an inflection point inserted). */
static double last_level_bulge(const conica_curve *o, const size_t *idx, size_t ne, size_t per)
{
    double worst = 0;
    size_t i, j;
    for (i = 0; i < ne; i++) {
        if (idx[i + 1] - idx[i] != per)
            return -1.0;
        for (j = 1; j < per; j += 2) {
            size_t a = idx[i] + j - 1, m = a + 1, b = a + 2 < o->n ? a + 2 : 0;
            double ex = o->xy[2 * b] - o->xy[2 * a], ey = o->xy[2 * b + 1] - o->xy[2 * a + 1];
            double px = o->xy[2 * m] - o->xy[2 * a], py = o->xy[2 * m + 1] - o->xy[2 * a + 1];
            double el = ex * ex + ey * ey, sp = el > 0 ? (px * ex + py * ey) / el : 0, dx, dy;
            sp = sp < 0 ? 0 : sp > 1 ? 1 : sp;
            dx = px - sp * ex;
            dy = py - sp * ey;
            dx = sqrt(dx * dx + dy * dy);
            worst = dx > worst ? dx : worst;
        }
    }
    return worst;
}

/* Subdivide an open or closed point-normal polygon. */
static conica_code run_subdiv(ctx *c, const double *xy, const double *nxy, size_t n, int closed,
                              int levels, double noise, conica_curve *out, size_t *ninfl)
{
    conica_curve in;
    conica_subdiv_settings ss = conica_subdiv_defaults();
    conica_subdiv_info info;
    conica_status est;
    conica_code rc;
    conica_subdiv_info_init(&info);
    conica_curve_init(&in);
    rc = conica_curve_set(xy, nxy, n, closed, &in, &est);
    if (rc == CONICA_OK && !nxy)
        rc = conica_curve_estimate_normals(&in, CONICA_NORMALS_CIRCLE, &est);
    if (rc == CONICA_OK) {
        ss.levels = levels;
        ss.noise = noise;
        ss.max_points = c->budget + 2;
        rc = conica_subdivide(&in, &ss, out, &info, &est);
    }
    if (ninfl)
        *ninfl = info.inflections;
    conica_subdiv_info_free(&info);
    conica_curve_free(&in);
    if (rc == CONICA_ERR_LIMIT)
        return take(c, c->budget + 1);
    if (rc == CONICA_ERR_NOMEM)
        return fail_nomem(c);
    if (rc != CONICA_OK && c->st)
        *c->st = est;
    return rc;
}

/* Positions of the samples in a subdivision output (old points are kept
 * bit for bit, in order): idx[k] for sample k. */
static int locate(const double *sxy, size_t ns, const conica_curve *o, size_t *idx)
{
    size_t k = 0, i;
    for (i = 0; i < o->n && k < ns; i++)
        if (o->xy[2 * i] == sxy[2 * k] && o->xy[2 * i + 1] == sxy[2 * k + 1])
            idx[k++] = i;
    return k == ns;
}

/* One sample of a piece: segment k of the piece at parameter t. */
typedef struct smp {
    size_t k;
    double t;
} smp;

/* A piece: consecutive curved segments joined smoothly, between breaks
 * (corners, straight segments, open ends), or a whole closed subpath. */
typedef struct piece {
    const size_t *seg;   /* its segments (indices into path.seg) */
    size_t m;
    int closed;
    const double *tan;   /* 2(m+1) unit tangents at its joins: tan[k] where segment k starts,
                            tan[m] where the last ends (closed: tan[m] = tan[0]) */
    const double *nend;  /* normal written at the end point (open) */
    unsigned endflags;
} piece;

/* Parameter range of sample edge i: its segment and [t0, t1]. */
static void edge_range(const smp *S, size_t ns, int closed, size_t i, size_t *k, double *t0,
                       double *t1)
{
    size_t j = i + 1 < ns ? i + 1 : 0;
    *k = S[i].k;
    *t0 = S[i].t;
    *t1 = (j != 0 || !closed) && S[j].k == S[i].k && S[j].t > S[i].t ? S[j].t : 1.0;
}

static const double *piece_q(const ctx *c, const piece *P, size_t k, int *d)
{
    *d = c->p->seg[P->seg[k]].degree;
    return seg_pts(c->p, P->seg[k]);
}

/* The polyline of the edge from output index a to b (b may be out.n on a
 * closed curve: the first point again), contiguous in *buf if it wraps. */
static const double *edge_points(const conica_curve *o, size_t a, size_t b, double **buf)
{
    size_t m = b - a;
    *buf = NULL;
    if (b < o->n)
        return o->xy + 2 * a;
    *buf = malloc(2 * (m + 1) * sizeof **buf);
    if (!*buf)
        return NULL;
    memcpy(*buf, o->xy + 2 * a, 2 * m * sizeof **buf);
    (*buf)[2 * m] = o->xy[0];
    (*buf)[2 * m + 1] = o->xy[1];
    return *buf;
}

/* Whether the written polyline v[0..m] of one sample edge stays within the
 * tolerance of the segment on [ta, tb] both ways (tau as check_edge's,
 * every point's when want); *deviation grows to the figure when it does. */
static int written_fits(const ctx *c, const double *q, int d, double ta, double tb,
                        const double *v, size_t m, double *tau, unsigned want, double *deviation)
{
    double lim = PATH_WRITTEN_FRACTION * c->tol;
    if (c->s.exact_levels) { /* the count is the caller's: only the feet */
        (void)check_edge(q, d, ta, tb, v, m, tau, want, INFINITY, 1);
        return 1;
    }
    double e = check_edge(q, d, ta, tb, v, m, tau, want, fmin(lim, *deviation), 1);
    if (!(e <= lim))
        return 0;
    *deviation = e > *deviation ? e : *deviation;
    return 1;
}

/* Append a piece smoothed (its first point is there already). */
static conica_code smooth_piece(ctx *c, const piece *P, double *deviation)
{
    int ok = 0, round, lev, L = 0, d, low = 0, low_failed = 0;
    size_t ns = 0, cap, i, k, ne, *idx = NULL, *fidx = NULL, ninfl = 0, step = 1, keep = 1;
    smp *S = NULL;
    double *T = NULL; /* parameters of the check output's points */
    const double *q;
    double worst = 0, s0, strict;
    conica_curve out, fin;
    conica_code rc = CONICA_OK;
    unsigned char *bad = NULL;

    conica_curve_init(&out);
    conica_curve_init(&fin);
    /* each segment's start and at most 3 CONICA_PATH_MAX_DEGREE
     * inflections (find_inflections' cap), and the end */
    cap = (1 + 3 * CONICA_PATH_MAX_DEGREE) * P->m + 16;
    S = malloc(cap * sizeof *S);
    if (!S)
        return fail_nomem(c);
    /* Samples: each segment's start, its inflections, and (open) the last
     * end; edges turning by more than PATH_MAX_EDGE_TURN are halved, and a
     * piece gets at least three (two point-normal pairs do not fix a conic). */
    for (k = 0; k < P->m; k++) {
        double infl[3 * CONICA_PATH_MAX_DEGREE];
        size_t ni;
        q = piece_q(c, P, k, &d);
        ni = find_inflections(q, d, infl, sizeof infl / sizeof *infl);
        c->r->inflections += ni;
        S[ns].k = k;
        S[ns++].t = 0.0;
        for (i = 0; i < ni; i++) {
            S[ns].k = k;
            S[ns++].t = infl[i];
        }
    }
    if (!P->closed) {
        S[ns].k = P->m - 1;
        S[ns++].t = 1.0;
    }
    for (;;) {
        size_t add = 0;
        if (2 * ns + 2 > cap) {
            smp *grown;
            cap = 2 * ns + 2;
            if (!(grown = realloc(S, cap * sizeof *S))) {
                free(S);
                return fail_nomem(c);
            }
            S = grown;
        }
        ne = P->closed ? ns : ns - 1;
        for (i = ne; i-- > 0;) {
            size_t kk;
            double t0, t1, a[2], b[2];
            edge_range(S, ns + add, P->closed, i, &kk, &t0, &t1);
            q = piece_q(c, P, kk, &d);
            if (t0 == 0.0)
                memcpy(a, P->tan + 2 * kk, sizeof a);
            else
                inner_tangent(q, d, t0, 1, a);
            if (t1 == 1.0)
                memcpy(b, P->tan + 2 * (kk + 1), sizeof b);
            else
                inner_tangent(q, d, t1, -1, b);
            if ((angle_between(a, b) > PATH_MAX_EDGE_TURN && ns + add < 64 * P->m) ||
                ns + add < 3) {
                memmove(S + i + 2, S + i + 1, (ns + add - i - 1) * sizeof *S);
                S[i + 1].k = kk;
                S[i + 1].t = 0.5 * (t0 + t1);
                add++;
            }
        }
        ns += add;
        if (!add)
            break;
    }
    for (round = 0; round <= PATH_MAX_ROUNDS && rc == CONICA_OK; round++) {
        size_t nbad = 0;
        ne = P->closed ? ns : ns - 1;
        if (!scratch(c, ns + 1)) {
            rc = fail_nomem(c);
            break;
        }
        free(idx);
        free(bad);
        idx = malloc((ns + 1) * sizeof *idx);
        bad = calloc(ns + 1, 1);
        if (!idx || !bad) {
            rc = fail_nomem(c);
            break;
        }
        for (i = 0; i < ns; i++) {
            double pt[2], tg[2];
            q = piece_q(c, P, S[i].k, &d);
            if (S[i].t == 0.0) {
                pt[0] = q[0];
                pt[1] = q[1];
                memcpy(tg, P->tan + 2 * S[i].k, sizeof tg);
            } else if (S[i].t == 1.0) {
                pt[0] = q[3 * d];
                pt[1] = q[3 * d + 1];
                memcpy(tg, P->tan + 2 * (S[i].k + 1), sizeof tg);
            } else {
                bez_eval(q, d, S[i].t, pt, NULL, NULL);
                inner_tangent(q, d, S[i].t, 1, tg);
            }
            c->sxy[2 * i] = pt[0];
            c->sxy[2 * i + 1] = pt[1];
            normal_of(tg, c->snxy + 2 * i);
        }
        /* the output levels, and so the check points whose parameters the
         * output takes: every step-th (below), all, or none (the output
         * comes from a subdivision of its own) */
        s0 = sag0(c->sxy, c->snxy, ns, P->closed);
        lev = c->s.level_tolerance > 0
                  ? level_for_sag(s0, c->s.level_tolerance, 0, PATH_LEVELS_MAX)
                  : c->s.levels;
        L = level_for_sag(s0, PATH_CHECK_SAG * c->tol, PATH_CHECK_MIN_LEVEL,
                          PATH_CHECK_MAX_LEVEL);
        strict = c->tol;
        low = 0;
        if (lev >= 1 && lev < L && !low_failed && !(sag_at(s0, lev) > PATH_CHECK_SAG * c->tol)) {
            /* Fewer levels written than the check's floor L, and the
             * written level's chords already within PATH_CHECK_SAG of the
             * tolerance by the estimate: the written level is checked
             * first (below), so that its subdivision is both the check and
             * the output. */
            L = lev;
            low = 1;
        }
        if (lev > L)
            L = lev; /* more levels written than the floor: checked as written */
        conica_curve_free(&out);
        rc = run_subdiv(c, c->sxy, c->snxy, ns, P->closed, L, 0.0, &out, &ninfl);
        if (rc == CONICA_ERR_LIMIT || rc == CONICA_ERR_NOMEM)
            break;
        free(T);
        T = malloc((out.n + 1) * sizeof *T);
        if (!T) {
            rc = fail_nomem(c);
            break;
        }
        if (rc != CONICA_OK || !locate(c->sxy, ns, &out, idx)) {
            rc = CONICA_OK; /* the samples defeat the subdivision: flatten */
            break;
        }
        idx[ns] = out.n; /* closed: the last edge runs to the first point again */
        if (low) {
            /* A pass at the written level must be a pass at the floor
             * level: the floor's polyline lies within the next level's
             * bulge of this one, about a quarter of this level's own bulge
             * over the level before, measured here (the largest distance
             * of a last-level point from its parent chord). Twice that
             * quarter comes off the tolerance; an edge short of it sends
             * the round back to the floor level, whose verdicts are then
             * the ones taken. */
            double b = last_level_bulge(&out, idx, ne, (size_t)1 << L);
            if (b < 0) { /* this round again at the floor level */
                low_failed = 1;
                round--;
                continue;
            }
            strict = c->tol - PATH_CHECK_NEXT_BULGE * b;
        }
        keep = c->s.rough_t                 ? 0
               : lev < L && ninfl == 0 ? (size_t)1 << (L - lev)
               : lev == L              ? 1
                                       : 0;
        worst = 0;
        for (i = 0; i < ne; i++) {
            size_t kk;
            double t0, t1, e, *buf;
            const double *v = edge_points(&out, idx[i], idx[i + 1], &buf);
            if (!v) {
                rc = fail_nomem(c);
                break;
            }
            edge_range(S, ns, P->closed, i, &kk, &t0, &t1);
            q = piece_q(c, P, kk, &d);
            /* tau[idx[i] + j]: parameters of the edge's points (its end
             * point's is overwritten by the next edge's start) */
            e = check_edge(q, d, t0, t1, v, idx[i + 1] - idx[i], T + idx[i], keep,
                           fmin(strict, fmax(*deviation, worst)), 0);
            free(buf);
            if (!(e <= strict)) {
                if (low)
                    break;
                bad[i] = 1;
                nbad++;
            }
            worst = e > worst ? e : worst;
        }
        if (rc != CONICA_OK)
            break;
        if (low && i < ne) { /* this round again at the floor level */
            low_failed = 1;
            round--;
            continue;
        }
        low_failed = 0;
        if (!nbad) {
            ok = 1;
            break;
        }
        if (ns + nbad > PATH_MAX_SEG_SAMPLES * P->m)
            break;
        if (ns + nbad > cap) {
            smp *grown;
            cap = 2 * (ns + nbad);
            if (!(grown = realloc(S, cap * sizeof *S))) {
                rc = fail_nomem(c);
                break;
            }
            S = grown;
        }
        for (i = ne; i-- > 0;)
            if (bad[i]) {
                size_t kk;
                double t0, t1;
                edge_range(S, ns, P->closed, i, &kk, &t0, &t1);
                memmove(S + i + 2, S + i + 1, (ns - i - 1) * sizeof *S);
                S[i + 1].k = kk;
                S[i + 1].t = 0.5 * (t0 + t1);
                ns++;
                c->r->refinements++;
            }
    }
    if (rc != CONICA_OK || !ok) {
        conica_curve_free(&out);
        free(idx);
        free(bad);
        free(S);
        free(T);
        if (rc != CONICA_OK)
            return rc;
        /* written flattened, segment by segment (within the tolerance) */
        c->r->fallbacks++;
        for (k = 0; k < P->m && rc == CONICA_OK; k++) {
            double nn[2];
            if (k + 1 == P->m && !P->closed) {
                rc = flatten_seg(c, P->seg[k], P->nend, P->endflags, deviation);
            } else {
                normal_of(P->tan + 2 * (k + 1), nn);
                rc = flatten_seg(c, P->seg[k], nn, CONICA_PATH_PT_VERTEX, deviation);
            }
        }
        return rc;
    }
    c->r->samples += ns;
    if (worst > *deviation)
        *deviation = worst;
    if (lev < L && ninfl == 0) {
        /* The scheme keeps every point of a level in the next one, so with
         * no inflection point inserted the level-lev points are every
         * 2^(L - lev)-th of the check output: no second subdivision. */
        step = (size_t)1 << (L - lev);
    } else if (lev != L) {
        /* fewer levels with inflection points inserted (the levels do not
         * nest): a subdivision of its own, each edge measured below */
        rc = run_subdiv(c, c->sxy, c->snxy, ns, P->closed, lev, 0.0, &fin, NULL);
        if (rc == CONICA_OK && !(fidx = malloc((ns + 1) * sizeof *fidx)))
            rc = fail_nomem(c);
        if (rc == CONICA_OK && !locate(c->sxy, ns, &fin, fidx))
            rc = conica__fail(c->st, CONICA_ERR_NUMERIC, 0, c->subpath,
                              "subpath %zu: the subdivision lost a sample", c->subpath + 1);
        if (rc == CONICA_OK)
            fidx[ns] = fin.n;
    }
    /* What is written is measured (check_edge's `written`): where a chord
     * at the written level strays beyond the tolerance (it cuts more of
     * the curve than the limit polyline checked above does), it is split
     * at the next level's point between its ends, down to the check's
     * own level, which passed. Level 0 is the samples' polygon as asked. */
    for (i = 0; i < ne && rc == CONICA_OK; i++) {
        size_t kk, m = idx[i + 1] - idx[i], ms = 0, j, es = 1, *sel = NULL;
        const conica_curve *src = &out;
        const size_t *sidx = idx;
        const double *tt = NULL;
        double t0, t1, *tau = NULL, *buf = NULL;
        const double *v;
        /* every written point's foot (Newton): the figures, and so the
         * verdicts, do not depend on rough_t */
        unsigned want = 1u;
        edge_range(S, ns, P->closed, i, &kk, &t0, &t1);
        q = piece_q(c, P, kk, &d);
        if (fidx) { /* the written level's own subdivision, as a whole */
            size_t mf = fidx[i + 1] - fidx[i];
            v = edge_points(&fin, fidx[i], fidx[i + 1], &buf);
            tau = v ? malloc((mf + 1) * sizeof *tau) : NULL;
            if (tau && (lev == 0 || written_fits(c, q, d, t0, t1, v, mf, tau, want, deviation))) {
                src = &fin;
                sidx = fidx;
                tt = tau;
            }
            free(buf);
        } else if (step > 1) { /* every step-th point of the check output */
            ms = m / step;
            buf = malloc(2 * (ms + 1) * sizeof *buf);
            tau = malloc((m + 1) * sizeof *tau);
            if (buf && tau) {
                for (j = 0; j <= ms; j++) {
                    size_t o = idx[i] + j * step;
                    o = o < out.n ? o : 0;
                    buf[2 * j] = out.xy[2 * o];
                    buf[2 * j + 1] = out.xy[2 * o + 1];
                }
                if (lev == 0 || written_fits(c, q, d, t0, t1, buf, ms, tau, want, deviation)) {
                    for (j = ms; j > 0; j--) /* tau[j] is point j * step's */
                        tau[j * step] = tau[j];
                    tt = tau;
                    es = step;
                }
            }
            free(buf);
        } else {
            tt = T + idx[i];
        }
        if (!tau && !tt) {
            rc = fail_nomem(c);
            break;
        }
        if (!tt) { /* chords split where they stray */
            size_t top = 0, *stk;
            free(tau);
            v = edge_points(&out, idx[i], idx[i + 1], &buf);
            sel = malloc((2 * m + 2) * sizeof *sel);
            tau = malloc((m + 1) * sizeof *tau);
            if (!v || !sel || !tau) {
                free(buf);
                free(sel);
                free(tau);
                rc = fail_nomem(c);
                break;
            }
            if (T && keep == 1 && !c->s.rough_t)
                memcpy(tau, T + idx[i], (m + 1) * sizeof *tau);
            else
                check_edge(q, d, t0, t1, v, m, tau, 1, INFINITY, 0);
            tau[0] = t0;
            tau[m] = t1;
            stk = sel + m + 1;
            for (j = m; j >= step; j -= step)
                stk[top++] = j; /* chords [j - step, j], the last on top */
            {
                size_t at = 0;
                ms = 0;
                while (top > 0) {
                    size_t hi = stk[--top], lo = at, span = hi - lo;
                    double ends[4] = {v[2 * lo], v[2 * lo + 1], v[2 * hi], v[2 * hi + 1]}, tj[2];
                    if (span > 1 &&
                        !written_fits(c, q, d, tau[lo], tau[hi], ends, 1, tj, 0u, deviation)) {
                        stk[top++] = hi;
                        stk[top++] = lo + span / 2;
                        continue;
                    }
                    sel[ms++] = hi;
                    at = hi;
                }
            }
            free(buf);
            tt = tau;
        }
        if (!sel)
            ms = (sidx[i + 1] - sidx[i]) / es;
        rc = take(c, ms);
        for (j = 1; j <= ms && rc == CONICA_OK; j++) {
            size_t jj = sel ? sel[j - 1] : j * es;
            size_t o = sidx[i] + jj;
            int is_end = !P->closed && i + 1 == ne && j == ms;
            int is_vertex = j == ms && (i + 1 == ns || S[i + 1].t == 0.0 || is_end);
            const double *pt = o < src->n ? src->xy + 2 * o : src->xy;
            const double *nn = o < src->n ? src->nxy + 2 * o : src->nxy;
            /* a point at a segment's end belongs to the next segment at 0 */
            size_t sg = P->seg[kk];
            double tv = j == ms ? t1 : tt[jj];
            if (j == ms && !is_end && S[(i + 1) % ns].t == 0.0) {
                sg = P->seg[S[(i + 1) % ns].k];
                tv = 0.0;
            }
            if (!add_pt(c, pt, is_end ? P->nend : nn, sg, tv,
                        is_end ? P->endflags : is_vertex ? CONICA_PATH_PT_VERTEX : 0u))
                rc = fail_nomem(c);
        }
        free(sel);
        free(tau);
    }
    conica_curve_free(&out);
    conica_curve_free(&fin);
    free(idx);
    free(fidx);
    free(bad);
    free(S);
    free(T);
    return rc;
}

/* ------------------------------------------------------------ fit */

/* Largest signed distance (along unit normal n) of segment s on [ta, tb]
 * from the line through a: dense samples, then golden section round the
 * best one. */
static double bulge(const conica_path *p, size_t s, double ta, double tb, const double a[2],
                    const double n[2], int sign)
{
    double dir[2] = {sign * n[0], sign * n[1]}, t;
    if (p->seg[s].degree == 1 || !(tb > ta))
        return 0.0;
    return seg_max_along(p, s, ta, tb, a, dir, 0.0, 40, &t);
}

/* Move the chords of the closed polyline L (flattened within tol_plot)
 * outward by their own bulge (OUTSIDE) or half way (MIDDLE): each chord's
 * line is shifted along its outer normal and the vertices become the
 * intersections of consecutive shifted lines (a bevel where they meet too
 * far away). Returns the largest deviation it leaves (chords and vertices). */
/* Largest signed distance along n of the drawn curve between two points of
 * a flattened subpath, (sk, tk) to (sj, tj): the chord may pass over the
 * tangent joins of a run, so the span runs over every segment in between,
 * in the subpath's order (round its start when it is closed). */
static double span_bulge(const conica_path *p, const conica_path_subpath *sp, size_t sk,
                         double tk, size_t sj, double tj, const double a[2], const double n[2],
                         int sign)
{
    double best = 0, ta = tk;
    size_t s = sk, guard;
    for (guard = 0; guard <= sp->n; guard++) {
        if (s == sj && (guard > 0 || tj >= ta)) {
            best = fmax(best, bulge(p, s, ta, tj, a, n, sign));
            break;
        }
        best = fmax(best, bulge(p, s, ta, 1.0, a, n, sign));
        s = s + 1 < sp->first + sp->n ? s + 1 : sp->first;
        ta = 0.0;
    }
    return best;
}

/* Does segment a-b cross segment c-d (or touch it away from their shared
 * ends)? The crossing point goes to x. Exact orientation tests. */
static int seg_cross(const double *a, const double *b, const double *c, const double *d,
                     double x[2])
{
    int o1 = conica__orient2d(a, b, c), o2 = conica__orient2d(a, b, d);
    int o3 = conica__orient2d(c, d, a), o4 = conica__orient2d(c, d, b);
    double ex = b[0] - a[0], ey = b[1] - a[1], fx = d[0] - c[0], fy = d[1] - c[1], den, u;
    if ((o1 == 0 && o2 == 0) || o1 * o2 > 0 || o3 * o4 > 0)
        return 0; /* apart, or on one line (no fold makes that) */
    den = ex * fy - ey * fx;
    u = den != 0.0 ? ((c[0] - a[0]) * fy - (c[1] - a[1]) * fx) / den : 0.0;
    u = fmin(fmax(u, 0.0), 1.0);
    x[0] = fma(u, ex, a[0]);
    x[1] = fma(u, ey, a[1]);
    return 1;
}

/* Under OUTSIDE the chords on the two sides of a narrow notch all move
 * into it, and where the notch is narrower than their moves the two moved
 * sides cross near its tip (the waist of a glyph's '8' at a tolerance of
 * 0.001 mm): a small loop of reversed orientation. Where segment i crosses
 * segment i + d (2 <= d <= PATH_FIT_FOLD_SPAN), the crossing becomes the
 * vertex and the loop's vertices go. The polygon then runs along the outer
 * of the two moved sides, which still encloses the curve: the notch's tip
 * fills in by less than the moves themselves. Removes vertices from L;
 * returns how many. */
static size_t untangle_folds(conica_path_polyline *L)
{
    size_t n = L->n, i, removed = 0, k, w;
    unsigned char *gone;
    if (n < 2 * PATH_FIT_FOLD_SPAN + 2 || !(gone = calloc(n, 1)))
        return 0;
    for (i = 0; i < n; i++) {
        size_t a = i, b, d;
        if (gone[a])
            continue;
        b = (a + 1) % n;
        while (gone[b])
            b = (b + 1) % n;
        for (d = 2; d <= PATH_FIT_FOLD_SPAN; d++) {
            /* the d-th live segment after a's: c-e */
            size_t cidx = b, e, m, steps;
            double x[2];
            for (m = 1; m < d; m++) {
                cidx = (cidx + 1) % n;
                while (gone[cidx])
                    cidx = (cidx + 1) % n;
            }
            e = (cidx + 1) % n;
            while (gone[e])
                e = (e + 1) % n;
            if (e == a || cidx == a)
                break;
            if (!seg_cross(L->xy + 2 * a, L->xy + 2 * b, L->xy + 2 * cidx, L->xy + 2 * e, x))
                continue;
            /* b becomes the crossing; b's successors up to cidx go */
            L->xy[2 * b] = x[0];
            L->xy[2 * b + 1] = x[1];
            L->flags[b] &= (unsigned char)~CONICA_PATH_PT_CORNER;
            for (k = (b + 1) % n, steps = 0; steps < d - 1; k = (k + 1) % n) {
                if (gone[k])
                    continue;
                gone[k] = 1;
                removed++;
                steps++;
            }
            i = a == 0 ? (size_t)-1 : a - 1; /* look at segment a again */
            break;
        }
    }
    for (k = 0, w = 0; k < n && removed; k++) {
        if (gone[k])
            continue;
        L->xy[2 * w] = L->xy[2 * k];
        L->xy[2 * w + 1] = L->xy[2 * k + 1];
        L->nxy[2 * w] = L->nxy[2 * k];
        L->nxy[2 * w + 1] = L->nxy[2 * k + 1];
        L->seg[w] = L->seg[k];
        L->t[w] = L->t[k];
        L->flags[w] = L->flags[k];
        w++;
    }
    if (removed)
        L->n = w;
    free(gone);
    return removed;
}

static int apply_fit(ctx *c, const conica_path_subpath *sp, conica_path_polyline *L,
                     conica_path_fit fit, double *dev)
{
    const conica_path *p = c->p;
    size_t n = L->n, k, i;
    double area = 0, *sh = NULL, *nrm = NULL, *oi = NULL, worst = 0;
    int orient;
    if (n < 3)
        return 1;
    for (k = 0; k < n; k++) {
        size_t j = (k + 1) % n;
        area += L->xy[2 * k] * L->xy[2 * j + 1] - L->xy[2 * j] * L->xy[2 * k + 1];
    }
    orient = area > 0 ? 1 : -1; /* +1: the enclosed side is to the left */
    sh = malloc(n * sizeof *sh);
    nrm = malloc(2 * n * sizeof *nrm);
    oi = malloc(2 * n * sizeof *oi);
    if (!sh || !nrm || !oi) {
        free(sh);
        free(nrm);
        free(oi);
        return 0;
    }
    for (k = 0; k < n; k++) {
        size_t j = (k + 1) % n;
        const double *a = L->xy + 2 * k, *b = L->xy + 2 * j;
        double out, in, dx = b[0] - a[0], dy = b[1] - a[1], len = hypot(dx, dy);
        nrm[2 * k] = len > 0 ? orient * dy / len : 0;
        nrm[2 * k + 1] = len > 0 ? -orient * dx / len : 0;
        out = span_bulge(p, sp, L->seg[k], L->t[k], L->seg[j], L->t[j], a, nrm + 2 * k, 1);
        in = span_bulge(p, sp, L->seg[k], L->t[k], L->seg[j], L->t[j], a, nrm + 2 * k, -1);
        sh[k] = fit == CONICA_PATH_FIT_OUTSIDE ? out : 0.5 * (out - in);
        if (out == 0.0 && in == 0.0)
            sh[k] = -0.0; /* a drawn straight edge: it stays on its line */
        oi[2 * k] = out;
        oi[2 * k + 1] = in;
    }
    {
        /* Each vertex moves along the bisector m of its two chords' outer
         * normals; a chord whose both ends moved by d has moved by d (m.n)
         * along its own normal, so d = shift / (m.n) covers it (OUTSIDE:
         * the larger need of its two chords, so a short chord next to a
         * long one cannot leave the long one short of its shift). */
        double *nv = malloc(2 * n * sizeof *nv);
        if (!nv) {
            free(sh);
            free(nrm);
            free(oi);
            return 0;
        }
        for (i = 0; i < n; i++) {
            size_t pv = (i + n - 1) % n;
            const double *n0 = nrm + 2 * pv, *n1 = nrm + 2 * i;
            double m[2], c0, c1, d0, d1, dd;
            if (!unit2(n0[0] + n1[0], n0[1] + n1[1], m))
                m[0] = n1[0], m[1] = n1[1];
            c0 = m[0] * n0[0] + m[1] * n0[1];
            c1 = m[0] * n1[0] + m[1] * n1[1];
            {
                /* a straight edge next to a shifted chord: the vertex slides
                 * along the straight edge's line to where the shifted chord
                 * meets it, so the edge keeps its drawn line */
                int s0 = signbit(sh[pv]) && sh[pv] == 0.0, s1 = signbit(sh[i]) && sh[i] == 0.0;
                /* only where the edge meets the curve tangentially: at a
                 * corner the edge's line leaves the curve, and the vertex
                 * moves by the bisector rule below */
                if (s0 != s1 && !(L->flags[i] & CONICA_PATH_PT_CORNER) &&
                    nrm[2 * pv] * nrm[2 * i] + nrm[2 * pv + 1] * nrm[2 * i + 1] >=
                        cos(fmin(c->s.corner_angle, PATH_FIT_SLIDE_MAX_ANGLE))) {
                    size_t ln = s0 ? pv : i, cv = s0 ? i : pv;
                    const double *nl = nrm + 2 * ln, *nc = nrm + 2 * cv;
                    double dl[2] = {-nl[1], nl[0]}, den = nc[0] * dl[0] + nc[1] * dl[1];
                    double sl = fabs(den) > 1e-12 ? sh[cv] / den : INFINITY;
                    size_t cj = (cv + 1) % n;
                    double clen = hypot(L->xy[2 * cj] - L->xy[2 * cv], L->xy[2 * cj + 1] - L->xy[2 * cv + 1]);
                    if (fabs(sl) <= clen && sh[cv] <= c->tol) {
                        nv[2 * i] = L->xy[2 * i] + sl * dl[0];
                        nv[2 * i + 1] = L->xy[2 * i + 1] + sl * dl[1];
                        continue;
                    }
                }
            }
            d0 = c0 > 0.1 ? sh[pv] / c0 : sh[pv];
            d1 = c1 > 0.1 ? sh[i] / c1 : sh[i];
            dd = fmax(d0, d1);
            if (dd > c->tol)
                dd = c->tol; /* an acute curved corner: stay within the tolerance */
            nv[2 * i] = L->xy[2 * i] + dd * m[0];
            nv[2 * i + 1] = L->xy[2 * i + 1] + dd * m[1];
        }
        /* What the moves leave: a vertex is off the curve by at most its
         * move; chord k's ends moved by ea and eb along its normal, so the
         * curve is at most out - min(ea, eb) beyond it and in + max(ea, eb)
         * inside it (the chord's offset is linear between its ends). */
        for (k = 0; k < n; k++) {
            size_t j = (k + 1) % n;
            const double *nk = nrm + 2 * k;
            double ea = (nv[2 * k] - L->xy[2 * k]) * nk[0] + (nv[2 * k + 1] - L->xy[2 * k + 1]) * nk[1];
            double eb = (nv[2 * j] - L->xy[2 * j]) * nk[0] + (nv[2 * j + 1] - L->xy[2 * j + 1]) * nk[1];
            double beyond = oi[2 * k] - fmin(ea, eb), inside = oi[2 * k + 1] + fmax(ea, eb);
            worst = fmax(worst, fmax(hypot(nv[2 * k] - L->xy[2 * k], nv[2 * k + 1] - L->xy[2 * k + 1]),
                                     fmax(beyond, inside)));
        }
        memcpy(L->xy, nv, 2 * n * sizeof *nv);
        free(nv);
    }
    if (fit == CONICA_PATH_FIT_OUTSIDE)
        untangle_folds(L);
    free(sh);
    free(nrm);
    free(oi);
    *dev = worst;
    return 1;
}

/* ------------------------------------------------------------ drivers */

static double seg_extent_all(const conica_path *p, const conica_path_subpath *sp)
{
    const conica_path_seg *a = &p->seg[sp->first], *z = &p->seg[sp->first + sp->n - 1];
    return pt_extent(p->pt, a->first, z->first + (size_t)z->degree + 1);
}

/* Rotate the polyline so that it starts at point `at`. */
static int rotate_line(conica_path_polyline *l, size_t at)
{
    size_t n = l->n, i;
    double *x = malloc(5 * n * sizeof *x);
    size_t *sg = malloc(n * sizeof *sg);
    unsigned char *fl = malloc(n);
    if (!x || !sg || !fl) {
        free(x);
        free(sg);
        free(fl);
        return 0;
    }
    for (i = 0; i < n; i++) {
        size_t j = (i + at) % n;
        x[2 * i] = l->xy[2 * j];
        x[2 * i + 1] = l->xy[2 * j + 1];
        x[2 * n + 2 * i] = l->nxy[2 * j];
        x[2 * n + 2 * i + 1] = l->nxy[2 * j + 1];
        x[4 * n + i] = l->t[j];
        sg[i] = l->seg[j];
        fl[i] = l->flags[j];
    }
    memcpy(l->xy, x, 2 * n * sizeof *x);
    memcpy(l->nxy, x + 2 * n, 2 * n * sizeof *x);
    memcpy(l->t, x + 4 * n, n * sizeof *x);
    memcpy(l->seg, sg, n * sizeof *sg);
    memcpy(l->flags, fl, n);
    free(x);
    free(sg);
    free(fl);
    return 1;
}

static conica_code drawn_subpath(ctx *c, const conica_path_subpath *sp, int smooth)
{
    const conica_path *p = c->p;
    size_t j, n = sp->n, start = 0, done;
    join *J;
    unsigned char *line, *brk;
    size_t *order;
    double *tan, nrm[2], dev = 0;
    conica_code rc = CONICA_OK;
    int any_break = 0;
    if (n == 0) { /* a lone move: its point */
        double pt[2] = {sp->x0, sp->y0}, nn[2] = {0, 0};
        rc = take(c, 1);
        if (rc == CONICA_OK && !add_pt(c, pt, nn, 0, 0.0, CONICA_PATH_PT_VERTEX))
            rc = fail_nomem(c);
        return rc;
    }
    J = malloc(n * sizeof *J);
    line = malloc(2 * n);
    order = malloc(n * sizeof *order);
    tan = malloc(2 * (n + 1) * sizeof *tan);
    if (!J || !line || !order || !tan) {
        free(J);
        free(line);
        free(order);
        free(tan);
        return fail_nomem(c);
    }
    brk = line + n;
    c->use_ext = !smooth;
    if (!smooth) { /* the subpath's bounding box, from its segments */
        for (int dd = 0; dd < 4; dd++) {
            c->ext[dd] = -INFINITY;
            for (j = 0; j < n; j++) {
                double t, v = seg_extreme(p, sp->first + j, box_dir[dd], &t);
                c->ext[dd] = v > c->ext[dd] ? v : c->ext[dd];
            }
        }
    }
    for (j = 0; j < n; j++) {
        size_t s = sp->first + j;
        J[j] = join_at(c, sp, j);
        c->r->corners += (size_t)J[j].corner;
        line[j] = (unsigned char)seg_straight(seg_pts(p, s), p->seg[s].degree, straight_tol(c));
    }
    /* join j (where segment j starts) breaks the smoothing: a corner, a
     * straight segment on either side, the start of an open subpath */
    for (j = 0; j < n; j++) {
        size_t pv = (j + n - 1) % n;
        brk[j] = (unsigned char)(J[j].corner || line[j] || (line[pv] && (sp->closed || j > 0)) ||
                                 (j == 0 && !sp->closed) || (!smooth && c->s.vertex_joins));
        any_break |= brk[j];
    }
    if (!smooth && c->s.fit == CONICA_PATH_FIT_MIDDLE && any_break)
        c->flat_fraction = PATH_FIT_INSIDE_FRACTION; /* see below */
    if (!smooth && sp->closed && any_break)
        brk[0] = 1; /* no flattened run passes over the drawn start: it stays a vertex */
    if (sp->closed && any_break && !brk[0])
        for (start = 1; start < n && !brk[start]; start++)
            ;
    for (j = 0; j < n; j++)
        order[j] = sp->first + (start + j) % n;
    join_normal(&J[start], nrm);
    rc = take(c, 1);
    if (rc == CONICA_OK &&
        !add_pt(c, seg_pts(p, order[0]), nrm, order[0], 0.0,
                CONICA_PATH_PT_VERTEX | (J[start].corner ? CONICA_PATH_PT_CORNER : 0u)))
        rc = fail_nomem(c);
    for (done = 0; done < n && rc == CONICA_OK;) {
        size_t jj = (start + done) % n, s = order[done], m, k;
        progress_at(c, done);
        double nend[2], len;
        unsigned fl = CONICA_PATH_PT_VERTEX;
        if (!line[jj] && !smooth) {
            /* flattened: the curved segments up to the next break as one
             * run, chords passing over its tangent joins */
            for (m = 1; done + m < n && !brk[(jj + m) % n]; m++)
                ;
            for (k = 0; k + 1 < m; k++)
                join_normal(&J[(jj + k + 1) % n], tan + 2 * k);
            if (done + m < n || sp->closed) {
                const join *N = &J[(jj + m) % n];
                join_normal(N, nend);
                if (N->corner)
                    fl |= CONICA_PATH_PT_CORNER;
            } else {
                double tout[2];
                seg_end_tangent(c, order[done + m - 1], 1, tout, &len);
                normal_of(tout, nend);
            }
            rc = flatten_run(c, order + done, m, tan, nend, fl, &dev);
            done += m;
            continue;
        }
        if (line[jj] || !smooth) {
            /* one segment: straight, or flattened */
            if (done + 1 < n || sp->closed) {
                const join *N = &J[(jj + 1) % n];
                join_normal(N, nend);
                if (N->corner)
                    fl |= CONICA_PATH_PT_CORNER;
            } else {
                double tout[2];
                seg_end_tangent(c, s, 1, tout, &len);
                normal_of(tout, nend);
            }
            if (line[jj]) {
                const double *q = seg_pts(p, s);
                int d = p->seg[s].degree;
                double e[2] = {q[3 * d], q[3 * d + 1]};
                rc = take(c, 1);
                if (rc == CONICA_OK && !add_pt(c, e, nend, s, 1.0, fl))
                    rc = fail_nomem(c);
            } else {
                rc = flatten_seg(c, s, nend, fl, &dev);
            }
            done++;
            continue;
        }
        /* a piece: curved segments up to the next break */
        for (m = 1; done + m < n && !brk[(jj + m) % n]; m++)
            ;
        for (k = 0; k < m; k++)
            memcpy(tan + 2 * k, J[(jj + k) % n].t_next, 2 * sizeof *tan);
        if (done + m < n || sp->closed) {
            const join *N = &J[(jj + m) % n];
            memcpy(tan + 2 * m, N->t_prev, 2 * sizeof *tan);
            join_normal(N, nend);
            if (N->corner)
                fl |= CONICA_PATH_PT_CORNER;
        } else {
            seg_end_tangent(c, order[done + m - 1], 1, tan + 2 * m, &len);
            normal_of(tan + 2 * m, nend);
        }
        {
            piece P;
            P.seg = order + done;
            P.m = m;
            P.closed = sp->closed && !any_break;
            P.tan = tan;
            P.nend = nend;
            P.endflags = fl;
            rc = smooth_piece(c, &P, &dev);
        }
        done += m;
    }
    if (rc == CONICA_OK && sp->closed && c->L->n > 1) {
        c->L->n--; /* the last point is the first */
        c->budget++;
    }
    /* MIDDLE straddles smooth closed contours (circles, ellipses, round
     * holes) only: at a corner or a straight edge the two chords meeting
     * there need shifts no one vertex move gives, and a drawn corner would
     * leave its place; such contours are written as INSIDE. */
    if (rc == CONICA_OK && !smooth && sp->closed && c->s.fit != CONICA_PATH_FIT_INSIDE &&
        !(c->s.fit == CONICA_PATH_FIT_MIDDLE && any_break)) {
        double fdev = 0;
        if (!apply_fit(c, sp, c->L, c->s.fit, &fdev))
            rc = fail_nomem(c);
        dev = fdev;
    }
    if (rc == CONICA_OK && start != 0) {
        /* start the polyline where the subpath starts: the end of its last segment */
        size_t at = 0, i;
        for (i = 0; i < c->L->n; i++)
            if (c->L->seg[i] == sp->first + n - 1 && c->L->t[i] == 1.0) {
                at = (i + 1) % c->L->n;
                break;
            }
        for (i = 0; i < c->L->n && at == 0; i++)
            if (c->L->seg[i] == sp->first && c->L->t[i] == 0.0) {
                at = i;
                break;
            }
        if (at && !rotate_line(c->L, at))
            rc = fail_nomem(c);
    }
    free(J);
    free(line);
    free(order);
    free(tan);
    c->L->deviation = dev;
    return rc;
}

/* Do the n points lie on the line through the first and the last (within
 * the precision, or rounding of their extent)? */
static int collinear(const double *xy, size_t n, double precision)
{
    double ex = xy[2 * n - 2] - xy[0], ey = xy[2 * n - 1] - xy[1], l = hypot(ex, ey), tol;
    size_t i;
    if (n <= 2)
        return 1;
    if (!(l > 0))
        return 0;
    tol = fmax(precision, PATH_STRAIGHT_REL * l);
    for (i = 1; i + 1 < n; i++)
        if (fabs((xy[2 * i] - xy[0]) * ey - (xy[2 * i + 1] - xy[1]) * ex) / l > tol)
            return 0;
    return 1;
}

/* Samples: split where the polygon turns by more than the corner angle
 * (when no normals are given), each piece subdivided as it is. */
static conica_code samples_subpath(ctx *c, const conica_path_subpath *sp, int smooth)
{
    const conica_path *p = c->p;
    const double *S = p->smp + 4 * sp->first;
    size_t n = sp->n, i, nc = 0, *cor = NULL, start, done = 0, total;
    unsigned char *isc = NULL; /* isc[i]: sample i is a corner */
    int have_n = 1, closed = sp->closed;
    double *xy = NULL, *nxy = NULL;
    conica_code rc = CONICA_OK;
    for (i = 0; i < n; i++)
        if (S[4 * i + 2] == 0 && S[4 * i + 3] == 0)
            have_n = 0;
    if (!smooth) {
        rc = take(c, n);
        for (i = 0; i < n && rc == CONICA_OK; i++) {
            double nn[2] = {S[4 * i + 2], S[4 * i + 3]};
            if (!add_pt(c, S + 4 * i, nn, sp->first + i, 0.0, CONICA_PATH_PT_VERTEX))
                rc = fail_nomem(c);
        }
        return rc;
    }
    xy = malloc(2 * (n + 1) * sizeof *xy);
    nxy = malloc(2 * (n + 1) * sizeof *nxy);
    cor = malloc((n + 1) * sizeof *cor);
    isc = calloc(n + 1, 1);
    if (!xy || !nxy || !cor || !isc) {
        rc = fail_nomem(c);
        goto done;
    }
    /* corners of the polygon (the samples' normals, when given, say the
     * curve is smooth at every sample) */
    for (i = 0; i < n && !have_n && c->s.corner_angle < M_PI; i++) {
        double a[2], b[2];
        size_t pv = (i + n - 1) % n, nx = (i + 1) % n;
        if (!closed && (i == 0 || i + 1 == n))
            continue;
        if (unit2(S[4 * i] - S[4 * pv], S[4 * i + 1] - S[4 * pv + 1], a) &&
            unit2(S[4 * nx] - S[4 * i], S[4 * nx + 1] - S[4 * i + 1], b) &&
            angle_between(a, b) > c->s.corner_angle) {
            cor[nc++] = i;
            isc[i] = 1;
        }
    }
    c->r->corners += nc;
    if (closed && nc == 0) {
        start = 0;
        total = n;
    } else {
        start = closed ? cor[0] : 0;
        total = closed ? n : n - 1;
    }
    {
        int first = 1;
        while (done < total && rc == CONICA_OK) {
            size_t cnt = 1, k, from;
            conica_curve o;
            int piece_closed = closed && nc == 0, lev;
            /* a piece runs from start to the next corner (or the end) */
            if (piece_closed) {
                cnt = n;
            } else {
                while (done + cnt <= total) {
                    size_t v = (start + cnt) % n;
                    cnt++;
                    if (done + cnt - 1 == total)
                        break;
                    if (isc[v])
                        break;
                }
            }
            for (k = 0; k < cnt; k++) {
                size_t v = (start + k) % n;
                xy[2 * k] = S[4 * v];
                xy[2 * k + 1] = S[4 * v + 1];
                nxy[2 * k] = S[4 * v + 2];
                nxy[2 * k + 1] = S[4 * v + 3];
            }
            conica_curve_init(&o);
            {
                conica_curve tmp;
                conica_curve_init(&tmp);
                if (!have_n) {
                    /* estimated here so that the level choice can see them */
                    if (conica_curve_set(xy, NULL, cnt, piece_closed, &tmp, NULL) == CONICA_OK &&
                        conica_curve_estimate_normals(&tmp, CONICA_NORMALS_CIRCLE, NULL) ==
                            CONICA_OK)
                        memcpy(nxy, tmp.nxy, 2 * cnt * sizeof *nxy);
                    else
                        for (k = 0; k < 2 * cnt; k++)
                            nxy[k] = 0;
                }
                conica_curve_free(&tmp);
            }
            lev = c->s.level_tolerance > 0
                      ? levels_for(xy, nxy, cnt, piece_closed, c->s.level_tolerance, 0,
                                   PATH_LEVELS_MAX)
                      : c->s.levels;
            if (!piece_closed && collinear(xy, cnt, c->s.precision))
                lev = 0; /* a straight run between corners stays as it is */
            rc = run_subdiv(c, xy, have_n || nxy[0] != 0 || nxy[1] != 0 ? nxy : NULL, cnt,
                            piece_closed, lev, c->s.precision, &o, NULL);
            if (rc != CONICA_OK) {
                conica_curve_free(&o);
                if (rc != CONICA_ERR_LIMIT && rc != CONICA_ERR_NOMEM) {
                    char why[sizeof c->st->message];
                    snprintf(why, sizeof why, "%s", c->st ? c->st->message : "subdivision failed");
                    rc = conica__fail(c->st, rc, 0, c->subpath, "subpath %zu: %s", c->subpath + 1,
                                      why);
                }
                break;
            }
            /* map output points to sample edges; the polyline sized once
             * for the piece, and the first piece's points and normals taken
             * over as the subdivision wrote them */
            from = first ? 0 : 1;
            rc = take(c, o.n - from);
            if (rc == CONICA_OK) {
                conica_path_polyline *l = c->L;
                size_t e = 0, last_i = 0, at;
                double inv = ldexp(1.0, -lev); /* 2^-lev: t = steps / 2^lev exactly */
                int own = 0;
                if (!l->xy && !l->nxy && from == 0 && o.nxy) {
                    l->seg = malloc(o.n * sizeof *l->seg);
                    l->t = malloc(o.n * sizeof *l->t);
                    l->flags = malloc(o.n ? o.n : 1);
                    if (l->seg && l->t && l->flags) {
                        l->xy = o.xy;
                        l->nxy = o.nxy;
                        o.xy = o.nxy = NULL;
                        c->lcap = o.n;
                        own = 1;
                    }
                }
                if (!own && !reserve(c, o.n - from))
                    rc = fail_nomem(c);
                /* ve: the sample the next vertex is, vcur: the last one's */
                size_t ve = start % n, vcur = ve;
                for (k = 0, at = l->n; k < o.n && rc == CONICA_OK; k++) {
                    size_t v;
                    unsigned fl = 0;
                    double t = 0;
                    const double *pk = own ? l->xy + 2 * k : o.xy + 2 * k;
                    if (e < cnt && pk[0] == xy[2 * e] && pk[1] == xy[2 * e + 1]) {
                        fl = CONICA_PATH_PT_VERTEX;
                        v = vcur = ve;
                        ve = ve + 1 == n ? 0 : ve + 1;
                        last_i = k;
                        e++;
                    } else {
                        v = vcur;
                        t = (double)(k - last_i) * inv;
                        t = t > 1 ? 1 : t;
                    }
                    if (fl && !piece_closed && (k == 0 || k + 1 == o.n) && nc)
                        fl |= CONICA_PATH_PT_CORNER;
                    if (k < from)
                        continue;
                    if (!own) {
                        memcpy(l->xy + 2 * at, o.xy + 2 * k, 2 * sizeof *l->xy);
                        memcpy(l->nxy + 2 * at, o.nxy + 2 * k, 2 * sizeof *l->nxy);
                    }
                    l->seg[at] = sp->first + v;
                    l->t[at] = t;
                    l->flags[at] = (unsigned char)fl;
                    at++;
                }
                if (rc == CONICA_OK)
                    l->n = at;
            }
            conica_curve_free(&o);
            first = 0;
            done += cnt - 1;
            if (piece_closed)
                break;
            start = (start + cnt - 1) % n;
        }
    }
    if (rc == CONICA_OK && closed && nc > 0 && c->L->n > 1) {
        /* the last piece ended on the first point */
        c->L->n--;
        c->budget++;
    }
done:
    free(xy);
    free(nxy);
    free(cor);
    free(isc);
    return rc;
}

static conica_code run(const conica_path *p, const conica_path_settings *s, int smooth,
                       conica_path_result *out, conica_status *st)
{
    ctx c;
    conica_path_result r;
    size_t i;
    conica_code rc = CONICA_OK;
    if (!p || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_path: NULL argument");
    memset(&c, 0, sizeof c);
    c.s = s ? *s : conica_path_defaults();
    if (!(c.s.tolerance >= 0) || !isfinite(c.s.tolerance) || !(c.s.rel_tolerance >= 0) ||
        !isfinite(c.s.rel_tolerance) || (c.s.tolerance == 0 && c.s.rel_tolerance == 0))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "the fidelity tolerance must be a positive finite number");
    if (!(c.s.corner_angle >= 0) || !(c.s.precision >= 0) || !isfinite(c.s.precision) ||
        !(c.s.level_tolerance >= 0) || !isfinite(c.s.level_tolerance))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "corner angle, precision and level tolerance must be >= 0");
    if (c.s.levels < 0 || c.s.levels > CONICA_SUBDIV_MAX_LEVELS)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "levels must be 0..%d",
                            CONICA_SUBDIV_MAX_LEVELS);
    conica_path_result_init(&r);
    if (p->nsub) {
        r.lines = calloc(p->nsub, sizeof *r.lines);
        if (!r.lines)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    c.p = p;
    c.r = &r;
    c.st = st;
    c.budget = c.s.max_points;
    for (i = 0; i < p->nsub; i++)
        c.prog_total += p->sub[i].n;
    progress_at(&c, 0);
    for (i = 0; i < p->nsub && rc == CONICA_OK; i++) {
        const conica_path_subpath *sp = &p->sub[i];
        double ext;
        if (i > 0)
            c.prog_base += p->sub[i - 1].n;
        progress_at(&c, 0);
        c.subpath = i;
        c.L = &r.lines[i];
        c.lcap = 0;
        r.n = i + 1;
        c.L->subpath = i;
        c.L->closed = sp->closed;
        if (sp->kind == CONICA_PATH_SAMPLES) {
            c.tol = c.s.tolerance;
            rc = samples_subpath(&c, sp, smooth);
        } else {
            ext = sp->n ? seg_extent_all(p, sp) : 0.0;
            c.tol = c.s.tolerance > 0 ? c.s.tolerance : c.s.rel_tolerance * ext;
            if (!(c.tol > 0)) /* a subpath of one point */
                c.tol = DBL_MIN;
            c.L->tolerance = c.tol;
            c.flat_fraction = smooth ? 1.0 : PATH_FIT_INSIDE_FRACTION;
            if (!smooth && sp->closed && c.s.fit == CONICA_PATH_FIT_OUTSIDE)
                c.flat_fraction = PATH_FIT_OUTSIDE_FRACTION;
            else if (!smooth && sp->closed && c.s.fit == CONICA_PATH_FIT_MIDDLE)
                c.flat_fraction = PATH_FIT_MIDDLE_FRACTION;
            {
                /* MIDDLE: a vertex moves by its chords' shift over the cosine
                 * of half its turn, so where the chords turn sharply (a small
                 * bowl at a coarse tolerance: 1.08 T in '%' at 0.1 mm) the
                 * moved vertices go beyond what the chords were given:
                 * flatten that subpath again with chords cut down in
                 * proportion. (OUTSIDE caps its moves at the tolerance.) */
                size_t budget0 = c.budget, corners0 = r.corners;
                int attempt;
                for (attempt = 0;; attempt++) {
                    double over;
                    rc = drawn_subpath(&c, sp, smooth);
                    over = c.L->deviation / c.tol;
                    if (rc != CONICA_OK || smooth || !sp->closed ||
                        c.s.fit != CONICA_PATH_FIT_MIDDLE || attempt == PATH_FIT_RETRIES ||
                        !(over > 1))
                        break;
                    c.flat_fraction *= over > 1 ? PATH_FIT_INSIDE_FRACTION / over : 0.5;
                    c.L->n = 0;
                    c.budget = budget0;
                    r.corners = corners0;
                }
            }
            if (c.L->deviation / c.tol > r.worst_ratio)
                r.worst_ratio = c.L->deviation / c.tol;
        }
        r.points += c.L->n;
    }
    if (rc == CONICA_OK && p->nsub)
        progress_at(&c, p->sub[p->nsub - 1].n);
    free(c.par);
    free(c.sxy);
    free(c.snxy);
    if (rc != CONICA_OK) {
        conica_path_result_free(&r);
        return rc;
    }
    r.n = p->nsub;
    conica_path_result_free(out);
    *out = r;
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_path_flatten(const conica_path *p, const conica_path_settings *s,
                                conica_path_result *out, conica_status *st)
{
    return run(p, s, 0, out, st);
}

conica_code conica_path_smooth(const conica_path *p, const conica_path_settings *s,
                               conica_path_result *out, conica_status *st)
{
    return run(p, s, 1, out, st);
}

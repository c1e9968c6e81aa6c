/* SPDX-License-Identifier: MIT */
/* The stroke of a polyline as SVG defines it (SVG 1.1 §11.4, SVG 2
 * "stroke shape"), as a set of convex pieces whose union (nonzero) is the
 * stroke: a rectangle per edge, a join piece per vertex on the outer side
 * of its turn (miter within the miter limit, else bevel; bevel; round), a
 * cap piece per open end (butt: none; square; round).
 *
 * Why not Clipper's own offset of an open line: where the half-width
 * exceeds a curve's radius its inner side turns inside out and Clipper's
 * positive-fill union leaves a hole where the stroke covers everything
 * (a tabler icon's dot, r = 0.5 stroked 2 wide); and it squares off a
 * miter beyond its limit where SVG bevels. The pieces need no such care:
 * each is convex and counter-clockwise, and their union is the stroke.
 *
 * Vertices whose edges turn by at most max_turn are the chords of one
 * curve (the caller flattened it so): they get a round piece whatever the
 * join, which is what the curve's own stroke has there.
 *
 * Calls only scad_clip.h's polygon set. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scad_stroke.h"

#define PI 3.14159265358979323846

/* Points on an arc of radius d from angle a0 turning by da (|da| < 2 pi),
 * chords within arctol of it, appended to buf (ends included). */
static size_t arc_pts(const double c[2], double d, double a0, double da, double arctol,
                      double *buf, size_t cap)
{
    double step = arctol < d ? 2 * acos(1 - arctol / d) : PI / 2;
    size_t n = (size_t)ceil(fabs(da) / step), k;
    if (n < 1)
        n = 1;
    if (n + 1 > cap)
        n = cap - 1;
    for (k = 0; k <= n; k++) {
        double a = a0 + da * (double)k / (double)n;
        buf[2 * k] = c[0] + d * cos(a);
        buf[2 * k + 1] = c[1] + d * sin(a);
    }
    return n + 1;
}

/* Add polygon xy (n points) counter-clockwise. */
static int add_ccw(conica__polys *out, double *xy, size_t n)
{
    double s = 0;
    for (size_t k = 0; k < n; k++) {
        size_t j = (k + 1) % n;
        s += (xy[2 * k] - xy[0]) * (xy[2 * j + 1] - xy[1]) -
             (xy[2 * j] - xy[0]) * (xy[2 * k + 1] - xy[1]);
    }
    if (s == 0)
        return 0; /* nothing to fill */
    if (s < 0)
        for (size_t a = 0, b = n - 1; a < b; a++, b--) {
            double t0 = xy[2 * a], t1 = xy[2 * a + 1];
            xy[2 * a] = xy[2 * b];
            xy[2 * a + 1] = xy[2 * b + 1];
            xy[2 * b] = t0;
            xy[2 * b + 1] = t1;
        }
    return conica__polys_add(out, xy, n);
}

#define ARC_CAP 4096 /* points of one round piece (a disc within 1e-7 of its radius) */

int conica__scad_stroke(const double *xy, size_t n, int closed, const conica__stroke_style *s,
                        conica__polys *out)
{
    double *buf = malloc((2 * ARC_CAP + 8) * sizeof *buf);
    double d = s->half_width;
    size_t m = 0, k;
    int rc = 0;
    if (!buf)
        return -1;
    /* drop repeated points (an edge of no length has no direction) */
    double *p = malloc(2 * (n ? n : 1) * sizeof *p);
    if (!p) {
        free(buf);
        return -1;
    }
    for (k = 0; k < n; k++)
        if (m == 0 || xy[2 * k] != p[2 * m - 2] || xy[2 * k + 1] != p[2 * m - 1]) {
            p[2 * m] = xy[2 * k];
            p[2 * m + 1] = xy[2 * k + 1];
            m++;
        }
    if (closed && m > 1 && p[0] == p[2 * m - 2] && p[1] == p[2 * m - 1])
        m--;
    if (m < 2 || !(d > 0)) {
        /* a lone point: a round cap draws a dot, a square cap a square */
        if (m >= 1 && d > 0 && !closed && s->cap != CONICA__CAP_BUTT) {
            size_t q;
            if (s->cap == CONICA__CAP_ROUND) {
                q = arc_pts(p, d, 0, 2 * PI, s->arctol, buf, ARC_CAP);
                rc = add_ccw(out, buf, q - 1);
            } else {
                double sq[8] = {p[0] - d, p[1] - d, p[0] + d, p[1] - d,
                                p[0] + d, p[1] + d, p[0] - d, p[1] + d};
                rc = add_ccw(out, sq, 4);
            }
        }
        free(p);
        free(buf);
        return rc;
    }
    size_t ne = closed ? m : m - 1;
    /* each edge's left normal times d, computed once: the rectangles and
     * the pieces at their ends share these corner points exactly, so the
     * union has no slivers between them */
    double *nrm = malloc(2 * ne * sizeof *nrm);
    if (!nrm) {
        free(p);
        free(buf);
        return -1;
    }
    for (k = 0; k < ne; k++) {
        const double *a = p + 2 * k, *b = p + 2 * ((k + 1) % m);
        double dx = b[0] - a[0], dy = b[1] - a[1], l = hypot(dx, dy);
        nrm[2 * k] = -dy / l * d;
        nrm[2 * k + 1] = dx / l * d;
    }
    /* edges */
    for (k = 0; k < ne && rc == 0; k++) {
        const double *a = p + 2 * k, *b = p + 2 * ((k + 1) % m), *N = nrm + 2 * k;
        double q[8] = {a[0] + N[0], a[1] + N[1], a[0] - N[0], a[1] - N[1],
                       b[0] - N[0], b[1] - N[1], b[0] + N[0], b[1] + N[1]};
        rc = add_ccw(out, q, 4);
    }
    /* joins */
    for (k = closed ? 0 : 1; k < (closed ? m : m - 1) && rc == 0; k++) {
        const double *v = p + 2 * k, *N0 = nrm + 2 * ((k + ne - 1) % ne), *N1 = nrm + 2 * k;
        double cr = N0[0] * N1[1] - N0[1] * N1[0], dt = N0[0] * N1[0] + N0[1] * N1[1];
        double turn = atan2(cr, dt); /* the normals turn as the edges do */
        if (turn == 0)
            continue;
        /* the outer side of the turn: the right of travel for a left turn */
        double sg = turn > 0 ? -1.0 : 1.0;
        double p0[2] = {v[0] + sg * N0[0], v[1] + sg * N0[1]};
        double p1[2] = {v[0] + sg * N1[0], v[1] + sg * N1[1]};
        /* the piece's apex: half way to the inner side, inside both
         * rectangles, so the piece overlaps them instead of meeting them
         * along a line that rounding to the booleans' grid opens */
        double ap[2] = {v[0] - 0.25 * sg * (N0[0] + N1[0]), v[1] - 0.25 * sg * (N0[1] + N1[1])};
        conica__stroke_join j = fabs(turn) <= s->max_turn ? CONICA__JOIN_ROUND : s->join;
        if (j == CONICA__JOIN_ROUND) {
            /* the fan: v, then the arc from p0 to p1 the short way */
            double a0 = atan2(sg * N0[1], sg * N0[0]);
            size_t q = arc_pts(v, d, a0, turn, s->arctol, buf + 2, ARC_CAP);
            buf[0] = ap[0];
            buf[1] = ap[1];
            buf[2] = p0[0], buf[3] = p0[1];
            buf[2 * q] = p1[0], buf[2 * q + 1] = p1[1];
            rc = add_ccw(out, buf, q + 1);
        } else {
            /* miter length / stroke width = 1 / sin(theta / 2), theta the
             * angle between the segments (SVG 1.1 §11.4) */
            double theta = PI - fabs(turn);
            int miter = j == CONICA__JOIN_MITER && sin(0.5 * theta) > 0 &&
                        1.0 / sin(0.5 * theta) <= s->miterlimit;
            if (miter) {
                /* the tip: where the two outer edges' lines meet */
                double bx = p0[0] + p1[0] - 2 * v[0], by = p0[1] + p1[1] - 2 * v[1];
                double bl = hypot(bx, by), r = d / cos(0.5 * fabs(turn));
                double q[8] = {ap[0], ap[1], p0[0], p0[1], v[0] + r * bx / bl, v[1] + r * by / bl,
                               p1[0], p1[1]};
                rc = add_ccw(out, q, 4);
            } else {
                double q[6] = {ap[0], ap[1], p0[0], p0[1], p1[0], p1[1]};
                rc = add_ccw(out, q, 3);
            }
        }
    }
    /* caps */
    for (int end = 0; end < 2 && !closed && rc == 0 && s->cap != CONICA__CAP_BUTT; end++) {
        const double *v = end ? p + 2 * (m - 1) : p, *N = nrm + 2 * (end ? ne - 1 : 0);
        /* outward along the line, and the corners on its left and right */
        double tx = (end ? 1 : -1) * N[1] / d, ty = (end ? -1 : 1) * N[0] / d;
        double L[2] = {v[0] + N[0], v[1] + N[1]}, R[2] = {v[0] - N[0], v[1] - N[1]};
        if (s->cap == CONICA__CAP_SQUARE) {
            double q[8] = {L[0], L[1], R[0], R[1], R[0] + d * tx, R[1] + d * ty,
                           L[0] + d * tx, L[1] + d * ty};
            rc = add_ccw(out, q, 4);
        } else {
            /* half disc from one corner round the outside to the other */
            const double *c0 = end ? R : L, *c1 = end ? L : R;
            double a0 = atan2(c0[1] - v[1], c0[0] - v[0]);
            size_t q = arc_pts(v, d, a0, PI, s->arctol, buf, ARC_CAP);
            buf[0] = c0[0], buf[1] = c0[1];
            buf[2 * q - 2] = c1[0], buf[2 * q - 1] = c1[1];
            rc = add_ccw(out, buf, q);
        }
    }
    free(nrm);
    free(p);
    free(buf);
    return rc;
}

/* SPDX-License-Identifier: MIT */
/* Point-normal curves: storage, normal estimation, and the reference
 * implementation's text format (`v x y` / `vn nx ny` lines). */
#include "conica/curve.h"

#include <float.h>
#include <locale.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/subdiv.h"
#include "internal.h"
#include "numparse.h"

/* CONICA_NORMALS_CIRCLE falls back to the area-weighted normal when the
 * three points are this close to collinear: |cross(a, b)| <= tol*|a||b|,
 * i.e. the sine of the turning angle is below tol (the circle's radius is
 * then beyond ~1/tol edge lengths and its centre is mostly rounding). */
#define CONICA__CIRCLE_COLLINEAR_SIN 1e-12

void conica_curve_init(conica_curve *c)
{
    if (!c)
        return;
    c->n = 0;
    c->cap = 0;
    c->xy = NULL;
    c->nxy = NULL;
    c->closed = 0;
}

void conica_curve_free(conica_curve *c)
{
    if (!c)
        return;
    free(c->xy);
    free(c->nxy);
    conica_curve_init(c);
}

/* Replace *out's arrays by xy/nxy (taken over). */
static void curve_take(conica_curve *out, double *xy, double *nxy, size_t n, int closed)
{
    free(out->xy);
    free(out->nxy);
    out->xy = xy;
    out->nxy = nxy;
    out->n = n;
    out->cap = n;
    out->closed = closed;
}

conica_code conica_curve_set(const double *xy, const double *nxy, size_t n, int closed,
                             conica_curve *out, conica_status *st)
{
    double *pxy = NULL, *pn = NULL;

    if (!out || (n > 0 && !xy))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_curve_set: NULL argument");
    if (n > ((size_t)-1) / (2 * sizeof(double)))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_curve_set: %zu points is too many", n);
    if (n > 0) {
        pxy = malloc(2 * n * sizeof *pxy);
        if (!pxy)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory for %zu points", n);
        memcpy(pxy, xy, 2 * n * sizeof *pxy);
        if (nxy) {
            pn = malloc(2 * n * sizeof *pn);
            if (!pn) {
                free(pxy);
                return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory for %zu normals", n);
            }
            memcpy(pn, nxy, 2 * n * sizeof *pn);
        }
    }
    curve_take(out, pxy, pn, n, closed != 0);
    conica__ok(st);
    return CONICA_OK;
}

/* ------------------------------------------------------------------ normals */

static int same_point(const double *xy, size_t i, size_t j)
{
    return xy[2 * i] == xy[2 * j] && xy[2 * i + 1] == xy[2 * j + 1];
}

/* Nearest vertex before (dir = -1) or after (dir = +1) i that differs from
 * it, skipping zero-length edges; wraps on closed curves. Returns n when
 * there is none (an open end, or every point coincides). */
static size_t distinct_neighbour(const conica_curve *c, size_t i, int dir)
{
    size_t n = c->n, j = i, steps;
    for (steps = 1; steps < n; steps++) {
        if (dir < 0) {
            if (j == 0) {
                if (!c->closed)
                    return n;
                j = n - 1;
            } else
                j--;
        } else {
            if (j == n - 1) {
                if (!c->closed)
                    return n;
                j = 0;
            } else
                j++;
        }
        if (!same_point(c->xy, i, j))
            return j;
    }
    return n;
}

/* Twice the signed area of the polygon (closed by the chord for an open
 * curve), taken about the first point so that the result does not depend
 * on where the curve sits. Positive = counter-clockwise = turns left. */
static double signed_area2(const conica_curve *c, double sc)
{
    double ox = c->xy[0] * sc, oy = c->xy[1] * sc, a = 0.0;
    size_t i;
    for (i = 1; i + 1 < c->n; i++) {
        double x0 = c->xy[2 * i] * sc - ox, y0 = c->xy[2 * i + 1] * sc - oy;
        double x1 = c->xy[2 * i + 2] * sc - ox, y1 = c->xy[2 * i + 3] * sc - oy;
        a += x0 * y1 - x1 * y0;
    }
    return a;
}

/* Normal at the origin of the circle through the origin, (ax, ay) and
 * (bx, by) (points relative to the vertex): its centre is (cx, cy)/d; the
 * normal points from it to the vertex, oriented like (*mx, *my). Leaves
 * the outputs alone when the three points are collinear (to
 * CONICA__CIRCLE_COLLINEAR_SIN). */
static void circle_normal(double ax, double ay, double bx, double by, double *mx, double *my,
                          double *len)
{
    double aa = ax * ax + ay * ay, bb = bx * bx + by * by;
    double d = 2.0 * (ax * by - ay * bx);
    if (fabs(d) > 2.0 * CONICA__CIRCLE_COLLINEAR_SIN * sqrt(aa) * sqrt(bb)) {
        double cx = (by * aa - ay * bb) / d, cy = (ax * bb - bx * aa) / d;
        double cl = hypot(cx, cy);
        if (cl > 0.0 && isfinite(cl)) {
            double ux = -cx / cl, uy = -cy / cl;
            /* Keep the orientation chosen by the caller. */
            if (ux * *mx + uy * *my < 0.0) {
                ux = -ux;
                uy = -uy;
            }
            *mx = ux;
            *my = uy;
            *len = 1.0;
        }
    }
}

/* A power of two that brings the largest coordinate into [1, 2): normals
 * only depend on directions, and working on scaled coordinates keeps the
 * differences and products below from overflowing (curves near 1e308) or
 * underflowing (curves near 1e-300). Exact, so nothing else changes. */
static double unit_scale(const conica_curve *c)
{
    double m = 0.0;
    size_t i;
    int e;
    for (i = 0; i < 2 * c->n; i++)
        if (fabs(c->xy[i]) > m)
            m = fabs(c->xy[i]);
    if (m == 0.0)
        return 1.0;
    e = -ilogb(m);
    if (e > DBL_MAX_EXP - 1)
        e = DBL_MAX_EXP - 1;
    return ldexp(1.0, e);
}

conica_code conica_curve_estimate_normals(conica_curve *c, conica_normal_method method,
                                          conica_status *st)
{
    double *nn, orient, sc;
    size_t i, n;

    if (!c || (c->n > 0 && !c->xy))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "estimate_normals: NULL curve");
    if (method != CONICA_NORMALS_AREA && method != CONICA_NORMALS_CIRCLE)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "estimate_normals: unknown method %d",
                            (int)method);
    n = c->n;
    if (n < 2)
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0,
                            "a curve needs at least 2 points to estimate normals (it has %zu)", n);
    for (i = 0; i < 2 * n; i++)
        if (!isfinite(c->xy[i]))
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, i / 2,
                                "point %zu is not finite", i / 2 + 1);
    if (distinct_neighbour(c, 0, +1) == n && distinct_neighbour(c, 0, -1) == n)
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0,
                            "all %zu points coincide: no normals can be estimated", n);

    /* One orientation for the whole curve: edge perpendiculars (e.y, -e.x)
     * point to the right of travel, which is outward for a counter-clockwise
     * curve; flip them all for a clockwise one (the reference does the same:
     * its ExStep example is clockwise and gets outward normals). */
    sc = unit_scale(c);
    orient = signed_area2(c, sc) < 0.0 ? -1.0 : 1.0;

    nn = malloc(2 * n * sizeof *nn);
    if (!nn)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory for %zu normals", n);

    for (i = 0; i < n; i++) {
        size_t p = distinct_neighbour(c, i, -1), q = distinct_neighbour(c, i, +1);
        double px = c->xy[2 * i] * sc, py = c->xy[2 * i + 1] * sc;
        double ax = 0, ay = 0, bx = 0, by = 0, mx, my, len;
        if (p < n) {
            ax = c->xy[2 * p] * sc - px;
            ay = c->xy[2 * p + 1] * sc - py;
        }
        if (q < n) {
            bx = c->xy[2 * q] * sc - px;
            by = c->xy[2 * q + 1] * sc - py;
        }
        /* Area weighting: the sum of the two unnormalised edge normals is
         * perp(next - prev); an open end has only its one edge. */
        mx = orient * (by - ay);
        my = -orient * (bx - ax);
        len = hypot(mx, my);
        if (!(len > 0.0)) {
            /* A hairpin (prev == next): the tip's normal is along the
             * incoming edge. */
            mx = -ax;
            my = -ay;
            len = hypot(mx, my);
        }
        if ((p < n) != (q < n)) {
            /* Open end: the normal of its one edge would make the chord the
             * curve's tangent there, which no convex curve has (the first
             * and last edges of every refined arc then wiggle,
             * README.md). Take the circle through the end point and its
             * next two distinct points instead (the circle method's rule
             * one point further in); collinear points keep the edge
             * normal. */
            size_t r = p < n ? distinct_neighbour(c, p, -1) : distinct_neighbour(c, q, +1);
            if (r < n && r != i) {
                double rx = c->xy[2 * r] * sc - px, ry = c->xy[2 * r + 1] * sc - py;
                double ex = p < n ? ax : bx, ey = p < n ? ay : by;
                circle_normal(rx, ry, ex, ey, &mx, &my, &len);
            }
        } else if (method == CONICA_NORMALS_CIRCLE && p < n && q < n) {
            circle_normal(ax, ay, bx, by, &mx, &my, &len);
        }
        nn[2 * i] = mx / len;
        nn[2 * i + 1] = my / len;
    }
    free(c->nxy);
    c->nxy = nn;
    conica__ok(st);
    return CONICA_OK;
}

/* ------------------------------------------------------------------ parser */

static int is_blank(char ch)
{
    return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f';
}

/* One line of input: [b, e) without its newline. */
typedef struct line_view {
    const char *b, *e;
    size_t no;      /* 1-based line number */
    size_t offset;  /* byte offset of b in the buffer */
} line_view;

enum line_kind { LINE_SKIP, LINE_V, LINE_VN, LINE_OTHER };

/* Classify a line by its first word; *rest points after the keyword. */
static enum line_kind classify(const line_view *ln, const char **rest)
{
    const char *p = ln->b;
    while (p < ln->e && is_blank(*p))
        p++;
    if (p == ln->e || *p == '#' || *p == '%')
        return LINE_SKIP;
    if (*p == 'v') {
        if (p + 1 == ln->e || is_blank(p[1])) {
            *rest = p + 1;
            return LINE_V;
        }
        if (p[1] == 'n' && (p + 2 == ln->e || is_blank(p[2]))) {
            *rest = p + 2;
            return LINE_VN;
        }
    }
    *rest = p;
    return LINE_OTHER;
}

/* Where the text starts: after a UTF-8 byte order mark, which some Windows
 * editors put in front of plain text files. */
static size_t text_start(const char *buf, size_t len)
{
    return len >= 3 && (unsigned char)buf[0] == 0xEF && (unsigned char)buf[1] == 0xBB &&
                   (unsigned char)buf[2] == 0xBF
               ? 3
               : 0;
}

/* Advance *ln to the next line of buf; returns 0 at the end. */
static int next_line(const char *buf, size_t len, size_t *pos, line_view *ln)
{
    const char *nl;
    if (*pos >= len)
        return 0;
    ln->b = buf + *pos;
    ln->offset = *pos;
    nl = memchr(ln->b, '\n', len - *pos);
    ln->e = nl ? nl : buf + len;
    *pos = (size_t)(ln->e - buf) + (nl ? 1 : 0);
    ln->no++;
    return 1;
}

/* Parse exactly two numbers from [p, ln->e) into v[0..1], or in long
 * double into vl[0..1] when vl is not NULL (then v is unused). */
static conica_code parse_pair(const line_view *ln, const char *p, const char *what, double *v,
                              long double *vl, conica_status *st)
{
    int k;
    for (k = 0; k < 2; k++) {
        const char *tok;
        size_t used = 0;
        int r;
        double x = 0.0;
        long double xl = 0.0L;
        if (p < ln->e && !is_blank(*p))
            goto junk;
        while (p < ln->e && is_blank(*p))
            p++;
        if (p == ln->e)
            return conica__fail(st, CONICA_ERR_PARSE, ln->no, (size_t)(p - ln->b) + ln->offset,
                                "'%s' line has %d number%s, expected 2", what, k,
                                k == 1 ? "" : "s");
        tok = p;
        if (vl) {
            r = conica__parse_long_double(p, (size_t)(ln->e - p), &xl, &used);
            /* The same numbers as the double reader accepts: normals are
             * estimated from the points rounded to double. */
            if (r == CONICA__NUM_OK && fabsl(xl) > (long double)DBL_MAX)
                r = CONICA__NUM_NONFINITE;
        } else
            r = conica__parse_double(p, (size_t)(ln->e - p), &x, &used);
        if (r == CONICA__NUM_NONFINITE)
            return conica__fail(st, CONICA_ERR_NONFINITE, ln->no, (size_t)(tok - ln->b) + ln->offset,
                                "'%.*s' is not a finite number", (int)(used < 40 ? used : 40), tok);
        if (r != CONICA__NUM_OK)
            goto junk;
        p += used;
        if (p < ln->e && !is_blank(*p))
            goto junk;
        if (vl)
            vl[k] = xl;
        else
            v[k] = x;
        continue;
    junk: {
            const char *q = p;
            while (q > ln->b && !is_blank(q[-1]))
                q--;
            p = q;
            while (q < ln->e && !is_blank(*q))
                q++;
            return conica__fail(st, CONICA_ERR_PARSE, ln->no, (size_t)(p - ln->b) + ln->offset,
                                "'%.*s' is not a number", (int)((q - p) < 40 ? (q - p) : 40), p);
        }
    }
    while (p < ln->e && is_blank(*p))
        p++;
    if (p != ln->e)
        return conica__fail(st, CONICA_ERR_PARSE, ln->no, (size_t)(p - ln->b) + ln->offset,
                            "'%s' line has more than 2 numbers (3D data is not supported)", what);
    return CONICA_OK;
}

conica_code conica_curve_parse(const char *buf, size_t len, conica_curve *out, conica_status *st)
{
    return conica_curve_parse_ex(buf, len, 0, out, st);
}

/* The reader behind conica_curve_parse_ex (out) and conica_curvel_parse_ex
 * (outl): exactly one of them is not NULL. */
static conica_code parse_any(const char *buf, size_t len, size_t max_points, conica_curve *out,
                             conica_curvel *outl, conica_status *st)
{
    line_view ln;
    size_t pos, nv = 0, nvn = 0, iv = 0, ivn = 0, last_vn_line = 0;
    size_t elem = outl ? sizeof(long double) : sizeof(double);
    double *xy = NULL, *nxy = NULL;
    long double *xyl = NULL, *nxyl = NULL;
    void *pxy, *pnxy = NULL;
    conica_code rc;

    if ((!out && !outl) || (len > 0 && !buf))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_curve_parse: NULL argument");
    if (max_points == 0)
        max_points = CONICA_CURVE_MAX_INPUT_POINTS;

    /* Pass 1: classify every line and count, so that the arrays are
     * allocated once and the point cap is checked before any allocation. */
    pos = text_start(buf, len);
    memset(&ln, 0, sizeof ln);
    while (next_line(buf, len, &pos, &ln)) {
        const char *rest;
        switch (classify(&ln, &rest)) {
        case LINE_SKIP:
            break;
        case LINE_V:
            if (++nv > max_points)
                return conica__fail(st, CONICA_ERR_LIMIT, ln.no, ln.offset,
                                    "more than %zu points (the reader's max_points)",
                                    max_points);
            break;
        case LINE_VN:
            if (++nvn > max_points)
                return conica__fail(st, CONICA_ERR_LIMIT, ln.no, ln.offset,
                                    "more than %zu normals (the reader's max_points)",
                                    max_points);
            last_vn_line = ln.no;
            break;
        case LINE_OTHER: {
            /* The reference skips such lines silently; we say so instead,
             * because a mistyped line would otherwise vanish from the curve. */
            const char *q = rest;
            while (q < ln.e && !is_blank(*q))
                q++;
            return conica__fail(st, CONICA_ERR_PARSE, ln.no, (size_t)(rest - ln.b) + ln.offset,
                                "unknown line starting with '%.*s' (expected 'v x y', 'vn nx ny', "
                                "or a '#'/'%%' comment)",
                                (int)((q - rest) < 20 ? (q - rest) : 20), rest);
        }
        }
    }
    if (nv == 0)
        return conica__fail(st, CONICA_ERR_PARSE, ln.no, len, "no 'v x y' lines: the input has no points");
    if (nvn != 0 && nvn != nv)
        return conica__fail(st, CONICA_ERR_PARSE, last_vn_line, 0,
                            "%zu 'vn' lines for %zu 'v' lines (normals pair with points by order: "
                            "give one per point, or none)",
                            nvn, nv);

    pxy = malloc(2 * nv * elem);
    if (nvn)
        pnxy = malloc(2 * nvn * elem);
    if (!pxy || (nvn && !pnxy)) {
        free(pxy);
        free(pnxy);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory for %zu points", nv);
    }
    if (outl) {
        xyl = pxy;
        nxyl = pnxy;
    } else {
        xy = pxy;
        nxy = pnxy;
    }

    /* Pass 2: read the numbers. */
    pos = text_start(buf, len);
    memset(&ln, 0, sizeof ln);
    while (next_line(buf, len, &pos, &ln)) {
        const char *rest;
        enum line_kind k = classify(&ln, &rest);
        if (k == LINE_V) {
            rc = parse_pair(&ln, rest, "v", xy ? xy + 2 * iv : NULL, xyl ? xyl + 2 * iv : NULL,
                            st);
            if (rc != CONICA_OK)
                goto fail;
            iv++;
        } else if (k == LINE_VN) {
            int zero;
            rc = parse_pair(&ln, rest, "vn", nxy ? nxy + 2 * ivn : NULL,
                            nxyl ? nxyl + 2 * ivn : NULL, st);
            if (rc != CONICA_OK)
                goto fail;
            zero = nxyl ? nxyl[2 * ivn] == 0.0L && nxyl[2 * ivn + 1] == 0.0L
                        : nxy[2 * ivn] == 0.0 && nxy[2 * ivn + 1] == 0.0;
            if (zero) {
                rc = conica__fail(st, CONICA_ERR_DEGENERATE, ln.no, ln.offset,
                                  "zero normal 'vn 0 0' has no direction");
                goto fail;
            }
            ivn++;
        }
    }
    if (outl) {
        conica_curvel_free(outl);
        outl->xy = xyl;
        outl->nxy = nxyl;
        outl->n = outl->cap = nv;
        outl->closed = 1;
    } else
        curve_take(out, xy, nxy, nv, 1);
    conica__ok(st);
    return CONICA_OK;

fail:
    free(pxy);
    free(pnxy);
    return rc;
}

conica_code conica_curve_parse_ex(const char *buf, size_t len, size_t max_points,
                                  conica_curve *out, conica_status *st)
{
    if (!out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_curve_parse: NULL argument");
    return parse_any(buf, len, max_points, out, NULL, st);
}

conica_code conica_curvel_parse_ex(const char *buf, size_t len, size_t max_points,
                                   conica_curvel *out, conica_status *st)
{
    if (!out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_curvel_parse_ex: NULL argument");
    return parse_any(buf, len, max_points, NULL, out, st);
}

size_t conica_curve_line_of_point(const char *buf, size_t len, size_t index, int normal)
{
    line_view ln;
    size_t pos, seen = 0;
    enum line_kind want = normal ? LINE_VN : LINE_V;
    if (!buf)
        return 0;
    pos = text_start(buf, len);
    memset(&ln, 0, sizeof ln);
    while (next_line(buf, len, &pos, &ln)) {
        const char *rest;
        if (classify(&ln, &rest) == want && seen++ == index)
            return ln.no;
    }
    return 0;
}

/* ------------------------------------------------------------------ writer */

/* "%.17g" of x into buf with '.' as the decimal point whatever LC_NUMERIC
 * says: printf obeys the locale, and a library caller (a GUI, Python) may
 * have set one with a decimal comma. */
static void format_double(char *buf, size_t size, double x)
{
    const char *dp = localeconv()->decimal_point;
    char *p;
    snprintf(buf, size, "%.17g", x);
    if (!dp || (dp[0] == '.' && dp[1] == '\0') || dp[0] == '\0')
        return;
    p = strstr(buf, dp);
    if (p) {
        size_t dl = strlen(dp);
        *p = '.';
        memmove(p + 1, p + dl, strlen(p + dl) + 1);
    }
}

static int write_pair(FILE *f, const char *key, const double *v)
{
    char a[64], b[64];
    format_double(a, sizeof a, v[0]);
    format_double(b, sizeof b, v[1]);
    return fprintf(f, "%s %s %s\n", key, a, b) < 0;
}

conica_code conica_curve_write(FILE *f, const conica_curve *c, conica_status *st)
{
    size_t i;
    if (!f || !c || (c->n > 0 && !c->xy))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_curve_write: NULL argument");
    /* %.17g: 17 significant digits identify every double exactly. */
    for (i = 0; i < c->n; i++)
        if (write_pair(f, "v", c->xy + 2 * i))
            return conica__fail(st, CONICA_ERR_IO, 0, i, "write error");
    if (c->nxy)
        for (i = 0; i < c->n; i++)
            if (write_pair(f, "vn", c->nxy + 2 * i))
                return conica__fail(st, CONICA_ERR_IO, 0, i, "write error");
    /* flushed: a full disk (/dev/full) shows only when the buffer goes out */
    if (fflush(f) != 0 || ferror(f))
        return conica__fail(st, CONICA_ERR_IO, 0, 0, "write error: %s", strerror(errno));
    conica__ok(st);
    return CONICA_OK;
}

/* SPDX-License-Identifier: MIT */
/*
 * svgpath.c - SVG path data as ts_contour curves for the checkers (tests
 * only; see ts_svgpath.h). Calls nothing of libcore or svg_tools.
 */
#include "ts_svgpath.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct sp_list {
    ts_svg_subpath *s;
    size_t n, cap, segcap; /* segcap: of the last subpath's segments */
} sp_list;

/* Room for one more of *n elements of `size` bytes in *arr (capacity *cap). */
static int room(void **arr, size_t *cap, size_t n, size_t size)
{
    void *g;
    if (n < *cap)
        return 1;
    g = realloc(*arr, (*cap ? 2 * *cap : 8) * size);
    if (!g)
        return 0;
    *arr = g;
    *cap = *cap ? 2 * *cap : 8;
    return 1;
}

static int new_subpath(sp_list *L, double x, double y)
{
    void *a = L->s;
    int ok = room(&a, &L->cap, L->n, sizeof *L->s);
    L->s = a;
    if (!ok)
        return 0;
    memset(&L->s[L->n], 0, sizeof L->s[L->n]);
    L->s[L->n].start[0] = x;
    L->s[L->n].start[1] = y;
    L->n++;
    L->segcap = 0;
    return 1;
}

static int add_seg(sp_list *L, const ts_seg *g)
{
    ts_contour *c = &L->s[L->n - 1].c;
    void *a = c->seg;
    int ok = room(&a, &L->segcap, c->n, sizeof *c->seg);
    c->seg = a;
    if (!ok)
        return 0;
    c->seg[c->n++] = *g;
    return 1;
}

static int line(sp_list *L, const double a[2], const double b[2])
{
    ts_seg g;
    memset(&g, 0, sizeof g);
    if (a[0] == b[0] && a[1] == b[1])
        return 1; /* nothing drawn */
    g.degree = 1;
    g.p[0][0] = a[0];
    g.p[0][1] = a[1];
    g.p[1][0] = b[0];
    g.p[1][1] = b[1];
    return add_seg(L, &g);
}

/* Skip white space and at most one comma. */
static const char *sep(const char *p, const char *e)
{
    while (p < e && isspace((unsigned char)*p))
        p++;
    if (p < e && *p == ',')
        p++;
    while (p < e && isspace((unsigned char)*p))
        p++;
    return p;
}

static int number(const char **pp, const char *e, double *v)
{
    const char *p = sep(*pp, e);
    char buf[64], *end;
    size_t k = 0;
    int dot = 0, exp = 0;
    if (p < e && (*p == '+' || *p == '-'))
        buf[k++] = *p++;
    while (p < e && k < sizeof buf - 2) {
        char ch = *p;
        if (isdigit((unsigned char)ch)) {
            buf[k++] = ch;
        } else if (ch == '.' && !dot && !exp) {
            dot = 1;
            buf[k++] = ch;
        } else if ((ch == 'e' || ch == 'E') && !exp && k > 0) {
            exp = 1;
            buf[k++] = ch;
            if (p + 1 < e && (p[1] == '+' || p[1] == '-'))
                buf[k++] = *++p;
        } else {
            break;
        }
        p++;
    }
    buf[k] = 0;
    *v = strtod(buf, &end);
    if (end == buf || *end)
        return 0;
    *pp = p;
    return 1;
}

static int flag(const char **pp, const char *e, int *f)
{
    const char *p = sep(*pp, e);
    if (p >= e || (*p != '0' && *p != '1'))
        return 0;
    *f = *p == '1';
    *pp = p + 1;
    return 1;
}

/* The elliptic arc from a to b (SVG 2 implementation notes B.2.4) as
 * rational quadratics of at most 90 degrees each. */
static int arc(sp_list *L, const double a[2], double rx, double ry, double phi_deg, int large,
               int sweep, const double b[2])
{
    double phi = phi_deg * M_PI / 180.0, cp = cos(phi), sn = sin(phi);
    double dx = 0.5 * (a[0] - b[0]), dy = 0.5 * (a[1] - b[1]);
    double x1 = cp * dx + sn * dy, y1 = -sn * dx + cp * dy, lam, num, co, cxp, cyp, cx, cy;
    double t1, dt, ux, uy, vx, vy;
    int k, pieces;
    rx = fabs(rx);
    ry = fabs(ry);
    if (rx == 0 || ry == 0)
        return line(L, a, b);
    if (a[0] == b[0] && a[1] == b[1])
        return 1;
    lam = x1 * x1 / (rx * rx) + y1 * y1 / (ry * ry);
    if (lam > 1) {
        rx *= sqrt(lam);
        ry *= sqrt(lam);
    }
    num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
    co = num > 0 ? sqrt(num / (rx * rx * y1 * y1 + ry * ry * x1 * x1)) : 0;
    if (large == sweep)
        co = -co;
    cxp = co * rx * y1 / ry;
    cyp = -co * ry * x1 / rx;
    cx = cp * cxp - sn * cyp + 0.5 * (a[0] + b[0]);
    cy = sn * cxp + cp * cyp + 0.5 * (a[1] + b[1]);
    ux = (x1 - cxp) / rx;
    uy = (y1 - cyp) / ry;
    vx = (-x1 - cxp) / rx;
    vy = (-y1 - cyp) / ry;
    t1 = atan2(uy, ux);
    dt = atan2(ux * vy - uy * vx, ux * vx + uy * vy);
    if (!sweep && dt > 0)
        dt -= 2 * M_PI;
    else if (sweep && dt < 0)
        dt += 2 * M_PI;
    pieces = (int)ceil(fabs(dt) / (0.5 * M_PI) - 1e-9);
    if (pieces < 1)
        pieces = 1;
    for (k = 0; k < pieces; k++) {
        double h = 0.5 * dt / pieces, m = t1 + (2 * k + 1) * h, r = 1.0 / cos(h);
        double e[3][2] = {{cos(m - h), sin(m - h)}, {r * cos(m), r * sin(m)}, {cos(m + h), sin(m + h)}};
        ts_seg g;
        int j;
        memset(&g, 0, sizeof g);
        g.degree = 2;
        g.w = cos(h);
        for (j = 0; j < 3; j++) {
            double ex = rx * e[j][0], ey = ry * e[j][1];
            g.p[j][0] = cx + cp * ex - sn * ey;
            g.p[j][1] = cy + sn * ex + cp * ey;
        }
        if (k == 0) {
            g.p[0][0] = a[0];
            g.p[0][1] = a[1];
        }
        if (k + 1 == pieces) {
            g.p[2][0] = b[0];
            g.p[2][1] = b[1];
        }
        if (!add_seg(L, &g))
            return 0;
    }
    return 1;
}

ts_code ts_svg_path_parse(const char *d, size_t len, ts_svg_subpath **out, size_t *n)
{
    const char *p = d, *e = d + len;
    sp_list L = {NULL, 0, 0, 0};
    double cur[2] = {0, 0}, start[2] = {0, 0}, ctl[2] = {0, 0};
    char cmd = 0, prev = 0;
    int ok = 1;
    for (;;) {
        double v[7];
        int rel, k, nargs, f1 = 0, f2 = 0;
        const char *save;
        p = sep(p, e);
        while (p < e && isspace((unsigned char)*p))
            p++;
        if (p >= e)
            break;
        if (isalpha((unsigned char)*p) && *p != 'e' && *p != 'E') {
            cmd = *p++;
        } else if (!cmd || cmd == 'Z' || cmd == 'z') {
            break; /* a number with no command */
        } else if (cmd == 'M') {
            cmd = 'L';
        } else if (cmd == 'm') {
            cmd = 'l';
        }
        rel = islower((unsigned char)cmd);
        switch (toupper((unsigned char)cmd)) {
        case 'Z':
            if (L.n) {
                ok = line(&L, cur, start);
                L.s[L.n - 1].c.closed = 1;
            }
            cur[0] = start[0];
            cur[1] = start[1];
            prev = 'Z';
            /* a command after Z without M starts a new subpath there */
            continue;
        case 'M': nargs = 2; break;
        case 'L': case 'T': nargs = 2; break;
        case 'H': case 'V': nargs = 1; break;
        case 'C': nargs = 6; break;
        case 'S': case 'Q': nargs = 4; break;
        case 'A': nargs = 7; break;
        default: ok = 0; nargs = 0; break;
        }
        if (!ok)
            break;
        save = p;
        for (k = 0; k < nargs && ok; k++) {
            if (toupper((unsigned char)cmd) == 'A' && (k == 3 || k == 4))
                ok = flag(&p, e, k == 3 ? &f1 : &f2);
            else
                ok = number(&p, e, &v[k]);
        }
        if (!ok) {
            p = save;
            break;
        }
        if (toupper((unsigned char)cmd) != 'M' && (prev == 'Z' || L.n == 0)) {
            if (!new_subpath(&L, cur[0], cur[1]))
                goto nomem;
            start[0] = cur[0];
            start[1] = cur[1];
        }
        {
            double b[2], c1[2], c2[2], ox = rel ? cur[0] : 0, oy = rel ? cur[1] : 0;
            char U = (char)toupper((unsigned char)cmd);
            ts_seg g;
            memset(&g, 0, sizeof g);
            switch (U) {
            case 'M':
                cur[0] = ox + v[0];
                cur[1] = oy + v[1];
                start[0] = cur[0];
                start[1] = cur[1];
                if (!new_subpath(&L, cur[0], cur[1]))
                    goto nomem;
                ctl[0] = cur[0];
                ctl[1] = cur[1];
                break;
            case 'L': case 'H': case 'V':
                b[0] = U == 'V' ? cur[0] : ox + v[0];
                b[1] = U == 'H' ? cur[1] : U == 'V' ? (rel ? cur[1] : 0) + v[0] : oy + v[1];
                if (!line(&L, cur, b))
                    goto nomem;
                cur[0] = ctl[0] = b[0];
                cur[1] = ctl[1] = b[1];
                break;
            case 'C': case 'S': case 'Q': case 'T': {
                /* c1: the first control point, given or reflected; c2 the
                 * cubic's second; b the end */
                int cubic = U == 'C' || U == 'S', given = U == 'C' || U == 'Q';
                int refl = cubic ? prev == 'C' || prev == 'S' : prev == 'Q' || prev == 'T';
                const double *w = v;
                if (given) {
                    c1[0] = ox + w[0];
                    c1[1] = oy + w[1];
                    w += 2;
                } else {
                    c1[0] = refl ? 2 * cur[0] - ctl[0] : cur[0];
                    c1[1] = refl ? 2 * cur[1] - ctl[1] : cur[1];
                }
                if (cubic) {
                    c2[0] = ox + w[0];
                    c2[1] = oy + w[1];
                    w += 2;
                }
                b[0] = ox + w[0];
                b[1] = oy + w[1];
                g.degree = cubic ? 3 : 2;
                g.p[0][0] = cur[0];
                g.p[0][1] = cur[1];
                g.p[1][0] = c1[0];
                g.p[1][1] = c1[1];
                if (cubic) {
                    g.p[2][0] = c2[0];
                    g.p[2][1] = c2[1];
                }
                g.p[g.degree][0] = b[0];
                g.p[g.degree][1] = b[1];
                if (!add_seg(&L, &g))
                    goto nomem;
                ctl[0] = cubic ? c2[0] : c1[0];
                ctl[1] = cubic ? c2[1] : c1[1];
                cur[0] = b[0];
                cur[1] = b[1];
                break;
            }
            case 'A':
                b[0] = ox + v[5];
                b[1] = oy + v[6];
                if (!arc(&L, cur, v[0], v[1], v[2], f1, f2, b))
                    goto nomem;
                cur[0] = ctl[0] = b[0];
                cur[1] = ctl[1] = b[1];
                break;
            default:
                break;
            }
            prev = U;
        }
    }
    if (!ok && L.n == 0) {
        *out = NULL;
        *n = 0;
        return TS_OK;
    }
    *out = L.s;
    *n = L.n;
    return TS_OK;
nomem:
    ts_svg_subpaths_free(L.s, L.n);
    return TS_ERR_NOMEM;
}

ts_code ts_svg_points_parse(const char *d, size_t len, int closed, ts_svg_subpath **out,
                            size_t *n)
{
    const char *p = d, *e = d + len;
    sp_list L = {NULL, 0, 0, 0};
    double xy[2], first[2], cur[2];
    int have = 0;
    while (number(&p, e, &xy[0]) && number(&p, e, &xy[1])) {
        if (!have) {
            if (!new_subpath(&L, xy[0], xy[1]))
                goto nomem;
            first[0] = xy[0];
            first[1] = xy[1];
            have = 1;
        } else if (!line(&L, cur, xy)) {
            goto nomem;
        }
        cur[0] = xy[0];
        cur[1] = xy[1];
    }
    if (have && closed) {
        if (!line(&L, cur, first))
            goto nomem;
        L.s[0].c.closed = 1;
    }
    *out = L.s;
    *n = L.n;
    return TS_OK;
nomem:
    ts_svg_subpaths_free(L.s, L.n);
    return TS_ERR_NOMEM;
}

void ts_svg_subpaths_free(ts_svg_subpath *s, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        free(s[i].c.seg);
    free(s);
}

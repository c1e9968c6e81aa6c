/* SPDX-License-Identifier: MIT */
/*
 * svgcheck - measure an svgsmooth output against its input, with no code
 * of svgsmooth's or libcore's: path data read by tests/support/svgpath.c,
 * distances by tests/support/fidelity.c (dense samples on both sides, the
 * worst refined by golden section).
 *
 *   svgcheck [--tol T | --rel R] [--lines-tol L] [--samples-too] [--corner DEG] IN OUT
 *   svgcheck [OPTIONS] --list FILE
 *
 * Pairs the `d` of every <path> (and, with --samples-too, the `points` of
 * <polygon>/<polyline>: straight edges, as --flatten reads them) of IN and
 * OUT in document order, subpath by subpath, and prints one line:
 *
 *   ratio=R over=N subpaths=S starts=K corners=M/C crossings=X self=Y points=P
 *
 * R: the largest Hausdorff distance (both ways) over the tolerance: T, or
 * R times the subpath's control-point bounding-box diagonal (svgsmooth's
 * default fidelity), at least L for a subpath made only of lines (what
 * --simplify L may move); N: subpaths over it; K: subpaths whose first output
 * point (and, open, last) is not the drawn one (within 2 % of the
 * tolerance); M of C corners (joins turning by more than DEG, default 45,
 * between segments longer than twice the tolerance, with handles at the
 * join none or longer than the tolerance) with no output vertex within
 * 2 % of the tolerance of them (corners are vertices); X: crossings
 * between different subpaths of one element in the output beyond those of
 * the input (lines by their ends, curves sampled 64 per segment); Y: the
 * same within single subpaths (each subpath's own crossings, output beyond
 * input); P: output vertices. Exit 0 when measured, 2 on a usage or read
 * error (a pairing mismatch is an error).
 *
 * --list FILE: many pairs in one process (no start-up per file): each line
 * of FILE is IN, a tab, OUT; each gives one line "IN<TAB>ratio=..." or
 * "IN<TAB>error: why" (the run goes on; exit 1 when any pair failed).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fidelity.h"
#include "ts_svgpath.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    size_t cap = 0, n = 0, got;
    if (!f)
        return NULL;
    do {
        if (n + 65536 > cap) {
            char *g = realloc(buf, cap = 2 * cap + 65536);
            if (!g) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = g;
        }
        got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
    } while (got > 0);
    fclose(f);
    buf[n] = 0;
    *len = n;
    return buf;
}

/* The next geometry value: kind 'd' (path), 'g' (polygon), 'l' (polyline). */
typedef struct value {
    const char *v;
    size_t len;
    char kind;
} value;

static const char *find_attr(const char *tag, const char *end, const char *name, size_t *len)
{
    size_t nl = strlen(name);
    const char *p = tag;
    char q = 0;
    for (; p < end; p++) {
        if (q) {
            if (*p == q)
                q = 0;
            continue;
        }
        if (*p == '"' || *p == '\'') {
            q = *p;
            continue;
        }
        if ((p[-1] == ' ' || p[-1] == '\t' || p[-1] == '\n' || p[-1] == '\r') &&
            (size_t)(end - p) > nl + 1 && !strncmp(p, name, nl)) {
            const char *r = p + nl, *s;
            while (r < end && (*r == ' ' || *r == '\t' || *r == '\n' || *r == '\r'))
                r++;
            if (*r != '=')
                continue;
            r++;
            while (r < end && (*r == ' ' || *r == '\t' || *r == '\n' || *r == '\r'))
                r++;
            if (*r != '"' && *r != '\'')
                continue;
            s = memchr(r + 1, *r, (size_t)(end - r - 1));
            if (!s)
                return NULL;
            *len = (size_t)(s - r - 1);
            return r + 1;
        }
    }
    return NULL;
}

static size_t values(const char *doc, size_t n, value **out)
{
    const char *p = doc, *e = doc + n;
    size_t k = 0, cap = 0;
    *out = NULL;
    while ((p = memchr(p, '<', (size_t)(e - p))) != NULL) {
        const char *t = p + 1, *end;
        char kind = 0, q = 0;
        if (!strncmp(t, "path", 4) && strchr(" \t\r\n/>", t[4]))
            kind = 'd';
        else if (!strncmp(t, "polygon", 7) && strchr(" \t\r\n/>", t[7]))
            kind = 'g';
        else if (!strncmp(t, "polyline", 8) && strchr(" \t\r\n/>", t[8]))
            kind = 'l';
        for (end = t; end < e && (q || *end != '>'); end++)
            if (q && *end == q)
                q = 0;
            else if (!q && (*end == '"' || *end == '\''))
                q = *end;
        if (kind) {
            size_t len = 0;
            const char *v = find_attr(t, end, kind == 'd' ? "d" : "points", &len);
            if (v) {
                if (k == cap) {
                    value *g = realloc(*out, (cap = 2 * cap + 16) * sizeof *g);
                    if (!g)
                        exit(2);
                    *out = g;
                }
                (*out)[k].v = v;
                (*out)[k].len = len;
                (*out)[k++].kind = kind;
            }
        }
        p = end;
    }
    return k;
}

static ts_code parse(const value *v, ts_svg_subpath **s, size_t *n)
{
    if (v->kind == 'd')
        return ts_svg_path_parse(v->v, v->len, s, n);
    return ts_svg_points_parse(v->v, v->len, v->kind == 'g', s, n);
}

/* The output subpath (made of lines) as a polyline: its vertices. */
static double *poly_of(const ts_svg_subpath *s, ts_poly *p)
{
    size_t i, n = s->c.n;
    double *xy = malloc(2 * (n + 1) * sizeof *xy);
    if (!xy)
        exit(2);
    xy[0] = s->start[0];
    xy[1] = s->start[1];
    for (i = 0; i < n; i++) {
        xy[2 * i + 2] = s->c.seg[i].p[s->c.seg[i].degree][0];
        xy[2 * i + 3] = s->c.seg[i].p[s->c.seg[i].degree][1];
    }
    p->xy = xy;
    p->n = n + 1;
    p->closed = s->c.closed;
    if (s->c.closed && n > 0)
        p->n = n; /* the closing line's end is the start */
    return xy;
}

static double diag(const ts_svg_subpath *s)
{
    double lo[2] = {s->start[0], s->start[1]}, hi[2] = {s->start[0], s->start[1]};
    size_t i;
    int k, j;
    for (i = 0; i < s->c.n; i++)
        for (k = 0; k <= s->c.seg[i].degree; k++)
            for (j = 0; j < 2; j++) {
                lo[j] = fmin(lo[j], s->c.seg[i].p[k][j]);
                hi[j] = fmax(hi[j], s->c.seg[i].p[k][j]);
            }
    return hypot(hi[0] - lo[0], hi[1] - lo[1]);
}

typedef struct opts {
    double tol, rel, corner, lines_tol;
    int samples_too;
} opts;

/* The crossings of polylines p[0..np): between different ones (*between)
 * and within single ones (*self). */
static int crossings(const ts_poly *p, size_t np, size_t *between, size_t *self)
{
    size_t all = 0;
    if (ts_poly_crossings(p, np, 0, between, NULL) != TS_OK ||
        ts_poly_crossings(p, np, 1, &all, NULL) != TS_OK)
        return 0;
    *self = all - *between;
    return 1;
}

/* Measure OUT against IN: one line on stdout (no newline); 0 when
 * measured, else 2 with the reason in why. */
static int check_pair(const opts *o, const char *in, const char *outp, char *why, size_t wlen)
{
    double worst = 0;
    size_t over = 0, nsub = 0, starts = 0, ncorner = 0, missing = 0, cross = 0, selfx = 0;
    size_t points = 0, nin, nout, lin, lout, i;
    char *din, *dout;
    value *vin = NULL, *vout = NULL;
    int rc = 0;
    din = slurp(in, &lin);
    dout = slurp(outp, &lout);
    if (!din || !dout) {
        snprintf(why, wlen, "cannot read %s", din ? outp : in);
        free(din);
        free(dout);
        return 2;
    }
    nin = values(din, lin, &vin);
    nout = values(dout, lout, &vout);
    if (nin != nout) {
        snprintf(why, wlen, "%s: %zu geometry values in, %zu out", in, nin, nout);
        rc = 2;
        nin = 0;
    }
    for (i = 0; i < nin && rc == 0; i++) {
        ts_svg_subpath *si = NULL, *so = NULL;
        size_t ni = 0, no = 0, k;
        ts_poly *polys, *dense;
        double **bufs;
        size_t cin = 0, cout = 0, sin = 0, sout = 0;
        if (vin[i].kind != 'd' && !o->samples_too)
            continue;
        if (parse(&vin[i], &si, &ni) != TS_OK || parse(&vout[i], &so, &no) != TS_OK) {
            snprintf(why, wlen, "%s: element %zu: not parsed", in, i + 1);
            ts_svg_subpaths_free(si, ni);
            rc = 2;
            break;
        }
        if (ni != no) {
            snprintf(why, wlen, "%s: element %zu: %zu subpaths in, %zu out", in, i + 1, ni, no);
            ts_svg_subpaths_free(si, ni);
            ts_svg_subpaths_free(so, no);
            rc = 2;
            break;
        }
        polys = calloc(no + 1, sizeof *polys);
        dense = calloc(no + 1, sizeof *dense);
        bufs = calloc(2 * no + 1, sizeof *bufs);
        if (!polys || !dense || !bufs)
            exit(2);
        for (k = 0; k < ni && rc == 0; k++) {
            double t = o->tol > 0 ? o->tol : o->rel * diag(&si[k]);
            ts_hausdorff h;
            ts_sampling smp;
            ts_corner *cs = NULL;
            size_t nc = 0;
            bufs[k] = poly_of(&so[k], &polys[k]);
            points += polys[k].n;
            if (si[k].c.n == 0)
                continue;
            nsub++;
            if (o->lines_tol > t) {
                size_t q;
                for (q = 0; q < si[k].c.n && si[k].c.seg[q].degree == 1; q++)
                    ;
                if (q == si[k].c.n)
                    t = o->lines_tol;
            }
            if (!(t > 0))
                t = 1e-300;
            smp = ts_sampling_defaults();
            if (polys[k].n > 2000)
                smp.per_edge = 2; /* dense output: its edges are short */
            if (ts_hausdorff_measure(&si[k].c, 1, &polys[k], 1, &smp, &h) != TS_OK) {
                snprintf(why, wlen, "%s: element %zu subpath %zu: not measured", in, i + 1, k + 1);
                rc = 2;
                break;
            }
            if (h.max / t > worst)
                worst = h.max / t;
            if (h.max > t) {
                over++;
                const double *wa = polys[k].xy + 2 * (h.poly_worst.edge % polys[k].n);
                const double *wb = polys[k].xy + 2 * ((h.poly_worst.edge + 1) % polys[k].n);
                double u = h.poly_worst.u;
                if (getenv("SVGCHECK_VERBOSE"))
                    fprintf(stderr, "element %zu subpath %zu: %g times the tolerance %g "
                            "(written point %.17g %.17g; %s, segment %zu t %g)\n", i + 1, k + 1,
                            h.max / t, t, wa[0] + u * (wb[0] - wa[0]), wa[1] + u * (wb[1] - wa[1]),
                            h.curve_to_poly >= h.poly_to_curve ? "drawn to written"
                                                               : "written to drawn",
                            (h.curve_to_poly >= h.poly_to_curve ? h.curve_worst.seg
                                                                : h.poly_nearest.seg) + 1,
                            h.curve_to_poly >= h.poly_to_curve ? h.curve_worst.t
                                                               : h.poly_nearest.t);
            }
            {
                const double *f = polys[k].xy, *l = polys[k].xy + 2 * (polys[k].n - 1);
                const ts_seg *ls = &si[k].c.seg[si[k].c.n - 1];
                double lim = 0.02 * t;
                int bad = hypot(f[0] - si[k].start[0], f[1] - si[k].start[1]) > lim;
                if (!si[k].c.closed)
                    bad |= hypot(l[0] - ls->p[ls->degree][0], l[1] - ls->p[ls->degree][1]) > lim;
                starts += (size_t)bad;
            }
            if (ts_contour_corners(&si[k].c, o->corner * M_PI / 180, &cs, &nc) == TS_OK && nc) {
                ts_corner_check cc;
                size_t q, kept = 0;
                /* a join next to a segment shorter than 2T has no turn at
                 * the scale of T (the checker's turn is measured there):
                 * left out */
                for (q = 0; q < nc; q++) {
                    size_t a0 = cs[q].seg, a1 = (a0 + 1) % si[k].c.n;
                    const ts_seg *g0 = &si[k].c.seg[a0], *g1 = &si[k].c.seg[a1];
                    double l0 = hypot(g0->p[g0->degree][0] - g0->p[0][0],
                                      g0->p[g0->degree][1] - g0->p[0][1]);
                    double l1 = hypot(g1->p[g1->degree][0] - g1->p[0][0],
                                      g1->p[g1->degree][1] - g1->p[0][1]);
                    /* and a handle shorter than T: a kink below the
                     * tolerance's scale, no corner there */
                    double h0 = hypot(g0->p[g0->degree][0] - g0->p[g0->degree - 1][0],
                                      g0->p[g0->degree][1] - g0->p[g0->degree - 1][1]);
                    double h1 = hypot(g1->p[1][0] - g1->p[0][0], g1->p[1][1] - g1->p[0][1]);
                    if (l0 > 2 * t && l1 > 2 * t && (h0 == 0 || h0 > t) && (h1 == 0 || h1 > t))
                        cs[kept++] = cs[q];
                }
                nc = kept;
                /* kept: an output vertex at the corner (to the rounding of
                 * the digits written, 2 % of T); how the output turns there
                 * is the chords' business, not asked */
                if (nc && ts_corners_kept(cs, nc, &polys[k], 1, 0.02 * t, 4 * M_PI, &cc) == TS_OK) {
                    ncorner += nc;
                    missing += cc.missing;
                    if (cc.missing && getenv("SVGCHECK_VERBOSE"))
                        fprintf(stderr, "element %zu subpath %zu: corner at %g %g (turn %g deg) "
                                "lost (output turn %g deg)\n", i + 1, k + 1,
                                cs[cc.first_missing].p[0], cs[cc.first_missing].p[1],
                                cs[cc.first_missing].turn * 180 / M_PI,
                                cc.first_missing_turn * 180 / M_PI);
                }
            }
            free(cs);
            { /* the input for its crossings: lines by their ends (as
               * written), curves by 64 samples each */
                size_t dn = 0, q, j;
                double *dxy = malloc((64 * si[k].c.n + 1) * 2 * sizeof *dxy);
                if (!dxy)
                    exit(2);
                for (q = 0; q < si[k].c.n; q++) {
                    const ts_seg *g = &si[k].c.seg[q];
                    size_t per = g->degree == 1 ? 1 : 64;
                    for (j = 0; j < per; j++)
                        ts_seg_eval(g, (double)j / (double)per, dxy + 2 * dn++);
                }
                if (!si[k].c.closed) {
                    const ts_seg *g = &si[k].c.seg[si[k].c.n - 1];
                    dxy[2 * dn] = g->p[g->degree][0];
                    dxy[2 * dn + 1] = g->p[g->degree][1];
                    dn++;
                }
                bufs[no + k] = dxy;
                dense[k].xy = dxy;
                dense[k].n = dn;
                dense[k].closed = si[k].c.closed;
            }
        }
        if (rc == 0) {
            size_t m = 0;
            for (k = 0; k < no; k++) /* lone moves and empty samples left out */
                if (dense[k].n > 1 && polys[k].n > 1) {
                    dense[m] = dense[k];
                    polys[m++] = polys[k];
                }
            if (m > 0 && crossings(dense, m, &cin, &sin) && crossings(polys, m, &cout, &sout)) {
                cross += cout > cin ? cout - cin : 0;
                selfx += sout > sin ? sout - sin : 0;
            }
        }
        for (k = 0; k < 2 * no; k++)
            free(bufs[k]);
        free(bufs);
        free(polys);
        free(dense);
        ts_svg_subpaths_free(si, ni);
        ts_svg_subpaths_free(so, no);
    }
    if (rc == 0)
        printf("ratio=%.4f over=%zu subpaths=%zu starts=%zu corners=%zu/%zu crossings=%zu "
               "self=%zu points=%zu", worst, over, nsub, starts, missing, ncorner, cross, selfx,
               points);
    free(vin);
    free(vout);
    free(din);
    free(dout);
    return rc;
}

/* --list: "IN<TAB>OUT" per line. */
static int check_list(const opts *o, const char *list)
{
    FILE *f = strcmp(list, "-") ? fopen(list, "r") : stdin;
    char line[8192], why[512];
    int bad = 0;
    if (!f) {
        fprintf(stderr, "svgcheck: cannot read %s\n", list);
        return 2;
    }
    while (fgets(line, sizeof line, f)) {
        char *tab = strchr(line, '\t'), *nl;
        if ((nl = strchr(line, '\n')) != NULL)
            *nl = 0;
        if (!tab) {
            if (line[0])
                printf("%s\terror: no tab\n", line), bad = 1;
            continue;
        }
        *tab = 0;
        printf("%s\t", line);
        why[0] = 0;
        if (check_pair(o, line, tab + 1, why, sizeof why) != 0) {
            printf("error: %s", why);
            bad = 1;
        }
        printf("\n");
        fflush(stdout);
    }
    if (f != stdin)
        fclose(f);
    return bad;
}

int main(int argc, char **argv)
{
    opts o = {0, 1e-3, 45, 0, 0};
    const char *list = NULL;
    char why[512];
    int a, rc;
    for (a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "--tol") && a + 1 < argc)
            o.tol = atof(argv[++a]);
        else if (!strcmp(argv[a], "--rel") && a + 1 < argc)
            o.rel = atof(argv[++a]);
        else if (!strcmp(argv[a], "--lines-tol") && a + 1 < argc)
            o.lines_tol = atof(argv[++a]);
        else if (!strcmp(argv[a], "--corner") && a + 1 < argc)
            o.corner = atof(argv[++a]);
        else if (!strcmp(argv[a], "--list") && a + 1 < argc)
            list = argv[++a];
        else if (!strcmp(argv[a], "--samples-too"))
            o.samples_too = 1;
        else if (argv[a][0] == '-' && argv[a][1] == '-') {
            fprintf(stderr, "svgcheck: unknown option %s\n", argv[a]);
            return 2;
        } else
            break;
    }
    if (list && a == argc)
        return check_list(&o, list);
    if (list || a != argc - 2) {
        fprintf(stderr, "usage: svgcheck [--tol T | --rel R] [--lines-tol L] [--samples-too] "
                        "[--corner DEG] (IN OUT | --list FILE)\n");
        return 2;
    }
    rc = check_pair(&o, argv[a], argv[a + 1], why, sizeof why);
    if (rc != 0) {
        fprintf(stderr, "svgcheck: %s\n", why);
        return rc;
    }
    printf("\n");
    return 0;
}

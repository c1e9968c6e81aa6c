/* SPDX-License-Identifier: MIT */
#include "plotsvg.h"

#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int plotsvg_load_curve(const char *prog, const char *path, int closed, conica_curve *c)
{
    char *buf;
    size_t len;
    conica_status st;
    if (cli_read_file(prog, path, cli_max_input(prog), &buf, &len))
        return 1;
    if (conica_curve_parse(buf, len, c, &st) != CONICA_OK) {
        char where[1100];
        const char *name = strcmp(path, "-") ? path : "<stdin>";
        /* errors about the whole file (empty, too many points) have no line */
        if (st.line > 0)
            snprintf(where, sizeof where, "%s:%zu", name, st.line);
        else
            snprintf(where, sizeof where, "%s", name);
        free(buf);
        return cli_error(prog, where, "%s", st.message);
    }
    free(buf);
    c->closed = closed;
    return 0;
}

/* ------------------------------------------------------------ curvature */

double plotsvg_curvature(const double a[2], const double b[2], const double c[2])
{
    /* CONIS, Code 3: |ab x cb| / (|ab| |cb| |ac|) = sin(angle at b) / |ac|,
     * and the circumradius is R = |ac| / (2 sin(angle at b)), so 1/R is twice
     * what Code 3 returns (a constant factor its comb scale absorbs; we want
     * the true curvature so that --scale and the tests mean what they say). */
    double abx = a[0] - b[0], aby = a[1] - b[1];
    double cbx = c[0] - b[0], cby = c[1] - b[1];
    double acx = a[0] - c[0], acy = a[1] - c[1];
    double denom = (abx * abx + aby * aby) * (cbx * cbx + cby * cby) * (acx * acx + acy * acy);
    double t;
    if (denom == 0.0)
        return 0.0;
    t = abx * cby - aby * cbx;
    return 2.0 * sqrt(t * t / denom);
}

double plotsvg_curvatures(const double *xy, const double *nxy, size_t n, int closed,
                          int signed_comb, double *kappa)
{
    double kmax = 0.0;
    for (size_t i = 0; i < n; i++) {
        size_t ia, ic;
        double k, cross;
        if (!closed && (i == 0 || i + 1 == n)) {
            kappa[i] = NAN;
            continue;
        }
        if (n < 3) {
            kappa[i] = NAN;
            continue;
        }
        ia = (i + n - 1) % n;
        ic = (i + 1) % n;
        k = plotsvg_curvature(xy + 2 * ia, xy + 2 * i, xy + 2 * ic);
        if (signed_comb && nxy) {
            /* The circle's centre lies left of the travel direction when the
             * turn a->b->c is counter-clockwise; teeth point away from it. */
            double tx = xy[2 * ic] - xy[2 * ia], ty = xy[2 * ic + 1] - xy[2 * ia + 1];
            cross = (xy[2 * i] - xy[2 * ia]) * (xy[2 * ic + 1] - xy[2 * i + 1]) -
                    (xy[2 * i + 1] - xy[2 * ia + 1]) * (xy[2 * ic] - xy[2 * i]);
            if ((cross > 0.0 ? 1.0 : -1.0) * (-ty * nxy[2 * i] + tx * nxy[2 * i + 1]) > 0.0)
                k = -k;
        }
        kappa[i] = k;
        if (isfinite(k) && fabs(k) > kmax)
            kmax = fabs(k);
    }
    return kmax;
}

double plotsvg_size(const double *xy, size_t n)
{
    double box[4];
    plotsvg_box_empty(box);
    plotsvg_box_add(box, xy, n);
    if (!(box[2] >= box[0]))
        return 0.0;
    return fmax(box[2] - box[0], box[3] - box[1]);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double plotsvg_comb_scale(const double *kappa, size_t n, double size, double *tmp,
                          double *max_len)
{
    size_t m = 0, at;
    double kref;
    for (size_t i = 0; i < n; i++)
        if (isfinite(kappa[i]))
            tmp[m++] = fabs(kappa[i]);
    *max_len = PLOTSVG_COMB_CLIP * PLOTSVG_COMB_FRACTION * size;
    if (m == 0)
        return 0.0;
    qsort(tmp, m, sizeof *tmp, cmp_double);
    at = (size_t)floor((1.0 - PLOTSVG_COMB_OUTLIERS) * (double)(m - 1));
    kref = tmp[at] > 0.0 ? tmp[at] : tmp[m - 1];
    return kref > 0.0 ? PLOTSVG_COMB_FRACTION * size / kref : 0.0;
}

void plotsvg_comb_tips(const double *xy, const double *nxy, const double *kappa, size_t n,
                       double scale, double max_len, double *tips)
{
    for (size_t i = 0; i < n; i++) {
        double len = scale * kappa[i];
        double nx = nxy[2 * i], ny = nxy[2 * i + 1], nl = hypot(nx, ny);
        if (!isfinite(len) || !(nl > 0.0)) {
            tips[2 * i] = tips[2 * i + 1] = NAN;
            continue;
        }
        if (max_len > 0.0 && fabs(len) > max_len)
            len = len > 0.0 ? max_len : -max_len;
        /* unit normal: the scheme's normals are unit already, but an input
         * curve's may not be */
        tips[2 * i] = xy[2 * i] + len * nx / nl;
        tips[2 * i + 1] = xy[2 * i + 1] + len * ny / nl;
    }
}

static double median(double *v, size_t m)
{
    if (m == 0)
        return 0.0;
    qsort(v, m, sizeof *v, cmp_double);
    return m % 2 ? v[m / 2] : 0.5 * (v[m / 2 - 1] + v[m / 2]);
}

double plotsvg_comb_roughness(const double *kappa, size_t n, int closed, double *tmp)
{
    size_t m = 0;
    double mk, md;
    for (size_t i = 0; i < n; i++)
        if (isfinite(kappa[i]))
            tmp[m++] = fabs(kappa[i]);
    mk = median(tmp, m);
    m = 0;
    for (size_t i = closed ? 0 : 1; i + (closed ? 0 : 1) < n; i++) {
        double a = kappa[(i + n - 1) % n], b = kappa[i], c = kappa[(i + 1) % n];
        if (isfinite(a) && isfinite(b) && isfinite(c))
            tmp[m++] = fabs(a - 2.0 * b + c);
    }
    md = median(tmp, m);
    return mk > 0.0 ? md / mk : 0.0;
}

/* --------------------------------------------------------------- errors */

/* |f| / |grad f| at one point (eqs. (13)-(14)), in long double with FMA so
 * the metric itself adds no error near the level of double rounding. */
static long double conic_dist(const plotsvg_conic *q, long double x, long double y)
{
    long double q20 = q->q20, q02 = q->q02, q11 = q->q11, q10 = q->q10, q01 = q->q01;
    long double gx = fmal(q20, x, fmal(q11, y, q10)); /* half the gradient */
    long double gy = fmal(q11, x, fmal(q02, y, q01));
    /* f = x (q20 x + q11 y + q10) + y (q11 x + q02 y + q01) + q10 x + q01 y + q00 */
    long double f = fmal(x, gx, fmal(y, gy, fmal(q10, x, fmal(q01, y, (long double)q->q00))));
    long double g = 2.0L * hypotl(gx, gy);
    if (g == 0.0L)
        return INFINITY;
    return fabsl(f) / g;
}

/* One loop for both point types: exactly one of xyd, xyl is non-NULL. */
static void conic_error(const plotsvg_conic *q, const double *xyd, const long double *xyl,
                        size_t n, double *mean, double *max)
{
    long double sum = 0.0L, mx = 0.0L;
    for (size_t i = 0; i < n; i++) {
        long double x = xyd ? xyd[2 * i] : xyl[2 * i];
        long double y = xyd ? xyd[2 * i + 1] : xyl[2 * i + 1];
        long double e = conic_dist(q, x, y);
        sum += e;
        if (e > mx)
            mx = e;
    }
    *mean = n ? (double)(sum / (long double)n) : 0.0;
    *max = (double)mx;
}

void plotsvg_conic_error(const plotsvg_conic *q, const double *xy, size_t n, double *mean,
                         double *max)
{
    conic_error(q, xy, NULL, n, mean, max);
}

void plotsvg_conic_errorl(const plotsvg_conic *q, const long double *xy, size_t n, double *mean,
                          double *max)
{
    conic_error(q, NULL, xy, n, mean, max);
}

int plotsvg_normal_error(const conica_curve *c, double *mean_deg, double *max_deg)
{
    conica_curve est;
    double dots = 0.0, sum = 0.0, mx = 0.0;
    const double deg = 180.0 / 3.14159265358979323846;
    conica_curve_init(&est);
    if (!c->nxy || conica_curve_set(c->xy, NULL, c->n, c->closed, &est, NULL) != CONICA_OK ||
        conica_curve_estimate_normals(&est, CONICA_NORMALS_AREA, NULL) != CONICA_OK) {
        conica_curve_free(&est);
        return -1;
    }
    for (size_t i = 0; i < c->n; i++)
        dots += c->nxy[2 * i] * est.nxy[2 * i] + c->nxy[2 * i + 1] * est.nxy[2 * i + 1];
    for (size_t i = 0; i < c->n; i++) {
        double ax = c->nxy[2 * i], ay = c->nxy[2 * i + 1];
        double bx = est.nxy[2 * i], by = est.nxy[2 * i + 1];
        double a;
        if (dots < 0.0) {
            bx = -bx;
            by = -by;
        }
        /* atan2 of cross and dot: accurate for tiny angles, unlike acos */
        a = fabs(atan2(ax * by - ay * bx, ax * bx + ay * by)) * deg;
        sum += a;
        if (a > mx)
            mx = a;
    }
    *mean_deg = c->n ? sum / (double)c->n : 0.0;
    *max_deg = mx;
    conica_curve_free(&est);
    return 0;
}

int plotsvg_variant(const char *name, conica_subdiv_settings *s)
{
    conica_subdiv_settings d = conica_subdiv_defaults();
    d.levels = s->levels;
    if (!strcmp(name, "base")) {
        d.normalize_normals = 1;
        d.plain_quadratic = 1;
    } else if (!strcmp(name, "norm-skip")) {
        d.normalize_normals = 0;
        d.plain_quadratic = 1;
    } else if (!strcmp(name, "precise")) {
        d.precise = 1;
    } else if (strcmp(name, "final") != 0) {
        return -1;
    }
    *s = d;
    return 0;
}

conica_code plotsvg_measure(const conica_curve *in, const conica_subdiv_settings *s,
                            const plotsvg_conic *q, plotsvg_errors *e, conica_status *st)
{
    conica_curve out;
    conica_code rc;
    conica_curve_init(&out);
    e->e_mean = e->e_max = e->n_mean = e->n_max = NAN;
    if (s->precise) {
        /* keep every bit of the long double result for eqs. (13)-(14) */
        conica_curvel outl;
        conica_curvel_init(&outl);
        rc = conica_subdividel(in, s, &outl, NULL, st);
        if (rc == CONICA_OK && q)
            plotsvg_conic_errorl(q, outl.xy, outl.n, &e->e_mean, &e->e_max);
        if (rc == CONICA_OK) {
            rc = CONICA_ERR_NOMEM;
            out.xy = malloc(2 * outl.n * sizeof *out.xy);
            out.nxy = malloc(2 * outl.n * sizeof *out.nxy);
            if (out.xy && out.nxy && outl.nxy) {
                for (size_t i = 0; i < 2 * outl.n; i++) {
                    out.xy[i] = (double)outl.xy[i];
                    out.nxy[i] = (double)outl.nxy[i];
                }
                out.n = out.cap = outl.n;
                out.closed = outl.closed;
                rc = CONICA_OK;
            }
        }
        conica_curvel_free(&outl);
    } else {
        rc = conica_subdivide(in, s, &out, NULL, st);
        if (rc == CONICA_OK && q)
            plotsvg_conic_error(q, out.xy, out.n, &e->e_mean, &e->e_max);
    }
    if (rc == CONICA_OK) {
        e->points = out.n;
        if (plotsvg_normal_error(&out, &e->n_mean, &e->n_max) != 0)
            e->n_mean = e->n_max = NAN;
    }
    conica_curve_free(&out);
    return rc;
}

/* ------------------------------------------------------------ SVG writer */

/* Fixed-point with two decimals, trailing zeros dropped, written with
 * integer conversions only (no locale). Picture coordinates are px, so two
 * decimals are far below what a renderer resolves. */
static void put_num(FILE *f, double v)
{
    long long q, ip, fr;
    if (!isfinite(v) || fabs(v) > 1e12)
        v = 0.0;
    q = llround(v * 100.0);
    if (q < 0) {
        fputc('-', f);
        q = -q;
    }
    ip = q / 100;
    fr = q % 100;
    fprintf(f, "%lld", ip);
    if (fr % 10 == 0 && fr)
        fprintf(f, ".%lld", fr / 10);
    else if (fr)
        fprintf(f, ".%02lld", fr);
}

static void put_escaped(FILE *f, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '&': fputs("&amp;", f); break;
        case '"': fputs("&quot;", f); break;
        default:
            /* control characters are not allowed in XML 1.0 */
            if ((unsigned char)*s >= 0x20 || *s == '\t' || *s == '\n')
                fputc(*s, f);
        }
    }
}

void plotsvg_box_empty(double box[4])
{
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
}

void plotsvg_box_add(double box[4], const double *xy, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double x = xy[2 * i], y = xy[2 * i + 1];
        if (!isfinite(x) || !isfinite(y))
            continue;
        box[0] = fmin(box[0], x);
        box[1] = fmin(box[1], y);
        box[2] = fmax(box[2], x);
        box[3] = fmax(box[3], y);
    }
}

plotsvg_frame plotsvg_fit(const double box[4], double px, double py, double pw, double ph)
{
    plotsvg_frame fr;
    double w = box[2] - box[0], h = box[3] - box[1];
    if (!(w >= 0.0) || !(h >= 0.0)) { /* empty box */
        fr.s = 1.0;
        fr.x0 = px + 0.5 * pw;
        fr.y0 = py + 0.5 * ph;
        return fr;
    }
    if (w == 0.0 && h == 0.0)
        fr.s = 1.0;
    else if (w * ph >= h * pw)
        fr.s = pw / w;
    else
        fr.s = ph / h;
    /* centre: px + pw/2 = x0 + s (minx + w/2); py + ph/2 = y0 - s (miny + h/2) */
    fr.x0 = px + 0.5 * pw - fr.s * (box[0] + 0.5 * w);
    fr.y0 = py + 0.5 * ph + fr.s * (box[1] + 0.5 * h);
    return fr;
}

void plotsvg_begin(FILE *f, double width, double height, const char *title)
{
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"", f);
    put_num(f, width);
    fputs("\" height=\"", f);
    put_num(f, height);
    fputs("\" viewBox=\"0 0 ", f);
    put_num(f, width);
    fputc(' ', f);
    put_num(f, height);
    fputs("\" font-family=\"sans-serif\">\n", f);
    if (title && *title) {
        fputs("<title>", f);
        put_escaped(f, title);
        fputs("</title>\n", f);
    }
    fputs("<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n", f);
}

void plotsvg_end(FILE *f)
{
    fputs("</svg>\n", f);
}

static void map(const plotsvg_frame *fr, double x, double y, double *px, double *py)
{
    *px = fr->x0 + fr->s * x;
    *py = fr->y0 - fr->s * y;
}

/* Is every point strictly between a and b (indices, picture space via fr)
 * within PLOTSVG_SIMPLIFY_PX of the segment a-b? */
static int chord_covers(const plotsvg_frame *fr, const double *xy, size_t a, size_t b)
{
    double ax, ay, bx, by, dx, dy, len2;
    map(fr, xy[2 * a], xy[2 * a + 1], &ax, &ay);
    map(fr, xy[2 * b], xy[2 * b + 1], &bx, &by);
    dx = bx - ax;
    dy = by - ay;
    len2 = dx * dx + dy * dy;
    for (size_t i = a + 1; i < b; i++) {
        double px, py, t, ex, ey;
        map(fr, xy[2 * i], xy[2 * i + 1], &px, &py);
        t = len2 > 0.0 ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.0;
        t = fmin(fmax(t, 0.0), 1.0);
        ex = ax + t * dx - px;
        ey = ay + t * dy - py;
        if (ex * ex + ey * ey > PLOTSVG_SIMPLIFY_PX * PLOTSVG_SIMPLIFY_PX)
            return 0;
    }
    return 1;
}

static void put_vertex(FILE *f, const plotsvg_frame *fr, const double *xy, size_t i, int *pen)
{
    double x, y;
    map(fr, xy[2 * i], xy[2 * i + 1], &x, &y);
    fputc(*pen ? (*pen == 1 ? 'L' : ' ') : 'M', f);
    put_num(f, x);
    fputc(' ', f);
    put_num(f, y);
    /* one L, then implicit repeats: compact path data */
    *pen = *pen ? 2 : 1;
}

void plotsvg_path(FILE *f, const plotsvg_frame *fr, const double *xy, size_t n, int closed,
                  const char *attrs)
{
    int pen = 0, broken = 0;
    size_t drawn = 0, last = 0;
    fputs("<path fill=\"none\" ", f);
    fputs(attrs, f);
    fputs(" d=\"", f);
    for (size_t i = 0; i < n; i++) {
        int finite = isfinite(xy[2 * i]) && isfinite(xy[2 * i + 1]);
        if (!finite) {
            pen = 0;
            broken = 1;
            continue;
        }
        /* Thin the polyline where it is straight to within a fraction of a
         * pixel: a level-12 curve has far more vertices than pixels. The
         * vertex is kept when the run from the last kept vertex to the next
         * one would stray, at run ends, and at breaks. */
        if (pen && i + 1 < n && i - last < PLOTSVG_SIMPLIFY_RUN &&
            isfinite(xy[2 * i + 2]) && isfinite(xy[2 * i + 3]) &&
            chord_covers(fr, xy, last, i + 1))
            continue;
        put_vertex(f, fr, xy, i, &pen);
        last = i;
        drawn++;
    }
    if (closed && !broken && drawn > 2)
        fputc('Z', f);
    fputs("\"/>\n", f);
}

void plotsvg_teeth(FILE *f, const plotsvg_frame *fr, const double *base, const double *tips,
                   size_t n, size_t max_teeth, const char *attrs)
{
    size_t stride = 1;
    if (max_teeth == 0 || n == 0)
        return;
    if (n > max_teeth)
        stride = (n + max_teeth - 1) / max_teeth;
    fputs("<path fill=\"none\" ", f);
    fputs(attrs, f);
    fputs(" d=\"", f);
    for (size_t i = 0; i < n; i += stride) {
        double bx, by, tx, ty;
        if (!isfinite(tips[2 * i]) || !isfinite(tips[2 * i + 1]))
            continue;
        map(fr, base[2 * i], base[2 * i + 1], &bx, &by);
        map(fr, tips[2 * i], tips[2 * i + 1], &tx, &ty);
        fputc('M', f);
        put_num(f, bx);
        fputc(' ', f);
        put_num(f, by);
        fputc('l', f); /* relative: shorter */
        put_num(f, tx - bx);
        fputc(' ', f);
        put_num(f, ty - by);
    }
    fputs("\"/>\n", f);
}

void plotsvg_text(FILE *f, double x, double y, double size, const char *anchor,
                  const char *text)
{
    fputs("<text x=\"", f);
    put_num(f, x);
    fputs("\" y=\"", f);
    put_num(f, y);
    fputs("\" font-size=\"", f);
    put_num(f, size);
    fprintf(f, "\" text-anchor=\"%s\">", anchor);
    put_escaped(f, text);
    fputs("</text>\n", f);
}

void plotsvg_comb_panel(FILE *f, double px, double py, double pw, double ph,
                        const conica_curve *control, const conica_curve *refined,
                        const double *tips, size_t max_teeth, const char *title)
{
    double box[4], pad = 0.04 * fmin(pw, ph), top = title ? 24.0 : 0.0;
    plotsvg_frame fr;
    plotsvg_box_empty(box);
    plotsvg_box_add(box, control->xy, control->n);
    plotsvg_box_add(box, refined->xy, refined->n);
    if (tips)
        plotsvg_box_add(box, tips, refined->n);
    fr = plotsvg_fit(box, px + pad, py + pad + top, pw - 2 * pad, ph - 2 * pad - top);
    if (title)
        plotsvg_text(f, px + 0.5 * pw, py + 18.0, 15.0, "middle", title);
    if (tips) {
        plotsvg_teeth(f, &fr, refined->xy, tips, refined->n, max_teeth,
                      "stroke=\"#d9534f\" stroke-width=\"0.5\" stroke-opacity=\"0.8\"");
        /* the joined comb outline: tips connected, as the reference GUI draws */
        plotsvg_path(f, &fr, tips, refined->n, refined->closed,
                     "stroke=\"#c9302c\" stroke-width=\"1\"");
    }
    plotsvg_path(f, &fr, control->xy, control->n, control->closed,
                 "stroke=\"#888\" stroke-width=\"1\" stroke-dasharray=\"5 4\"");
    plotsvg_path(f, &fr, refined->xy, refined->n, refined->closed,
                 "stroke=\"#1f3b73\" stroke-width=\"1.6\"");
}

static void tick_label(char *buf, size_t len, int decade)
{
    snprintf(buf, len, "1e%d", decade);
}

void plotsvg_logchart(FILE *f, double px, double py, double pw, double ph, const char *title,
                      const char *xlabel, const char *ylabel, const plotsvg_series *s,
                      size_t ns)
{
    double ymin = INFINITY, ymax = -INFINITY, xmin = INFINITY, xmax = -INFINITY;
    double l = px + 70.0, r = px + pw - 150.0, t = py + 30.0, b = py + ph - 45.0;
    int d0, d1, step;
    char buf[64];

    for (size_t k = 0; k < ns; k++)
        for (size_t i = 0; i < s[k].n; i++) {
            double y = s[k].y[i], x = s[k].x[i];
            if (isfinite(x)) {
                xmin = fmin(xmin, x);
                xmax = fmax(xmax, x);
            }
            if (isfinite(y) && y > 0.0) {
                ymin = fmin(ymin, y);
                ymax = fmax(ymax, y);
            }
        }
    if (!(xmax >= xmin)) {
        xmin = 0.0;
        xmax = 1.0;
    }
    if (xmax == xmin)
        xmax = xmin + 1.0;
    if (!(ymax >= ymin)) {
        ymin = 1e-20;
        ymax = 1.0;
    }
    d0 = (int)floor(log10(ymin));
    d1 = (int)ceil(log10(ymax));
    if (d1 == d0)
        d1 = d0 + 1;
    step = (d1 - d0 + 9) / 10; /* at most ~10 labelled decades */

    if (title)
        plotsvg_text(f, 0.5 * (l + r), py + 20.0, 15.0, "middle", title);
    /* grid and ticks */
    for (int d = d0; d <= d1; d++) {
        double y = b - (b - t) * (d - d0) / (double)(d1 - d0);
        fputs("<path stroke=\"#ddd\" d=\"M", f);
        put_num(f, l);
        fputc(' ', f);
        put_num(f, y);
        fputc('H', f);
        put_num(f, r);
        fputs("\"/>\n", f);
        if ((d - d0) % step == 0) {
            tick_label(buf, sizeof buf, d);
            plotsvg_text(f, l - 6.0, y + 4.0, 11.0, "end", buf);
        }
    }
    {
        int x0 = (int)ceil(xmin), x1 = (int)floor(xmax), xs = (x1 - x0 + 14) / 15;
        if (xs < 1)
            xs = 1;
        for (int xi = x0; xi <= x1; xi += xs) {
            double x = l + (r - l) * (xi - xmin) / (xmax - xmin);
            snprintf(buf, sizeof buf, "%d", xi);
            plotsvg_text(f, x, b + 16.0, 11.0, "middle", buf);
            fputs("<path stroke=\"#eee\" d=\"M", f);
            put_num(f, x);
            fputc(' ', f);
            put_num(f, t);
            fputc('V', f);
            put_num(f, b);
            fputs("\"/>\n", f);
        }
    }
    fputs("<path fill=\"none\" stroke=\"#000\" d=\"M", f);
    put_num(f, l);
    fputc(' ', f);
    put_num(f, t);
    fputc('V', f);
    put_num(f, b);
    fputc('H', f);
    put_num(f, r);
    fputs("\"/>\n", f);
    if (xlabel)
        plotsvg_text(f, 0.5 * (l + r), b + 36.0, 13.0, "middle", xlabel);
    if (ylabel) {
        fputs("<g transform=\"rotate(-90)\">", f);
        plotsvg_text(f, -0.5 * (t + b), px + 16.0, 13.0, "middle", ylabel);
        fputs("</g>\n", f);
    }
    /* series, in a frame mapping (x, log10 y) onto the plot area */
    for (size_t k = 0; k < ns; k++) {
        int pen = 0;
        fprintf(f, "<path fill=\"none\" stroke=\"%s\" stroke-width=\"1.8\"%s d=\"",
                s[k].color ? s[k].color : "#000",
                s[k].dashed ? " stroke-dasharray=\"6 4\"" : "");
        for (size_t i = 0; i < s[k].n; i++) {
            double y = s[k].y[i], x = s[k].x[i];
            if (!isfinite(x) || !isfinite(y) || y <= 0.0) {
                pen = 0;
                continue;
            }
            fputc(pen ? 'L' : 'M', f);
            put_num(f, l + (r - l) * (x - xmin) / (xmax - xmin));
            fputc(' ', f);
            put_num(f, b - (b - t) * (log10(y) - d0) / (double)(d1 - d0));
            pen = 1;
        }
        fputs("\"/>\n", f);
        /* legend */
        {
            double ly = t + 10.0 + 20.0 * (double)k;
            fprintf(f, "<path stroke=\"%s\" stroke-width=\"1.8\"%s d=\"M",
                    s[k].color ? s[k].color : "#000",
                    s[k].dashed ? " stroke-dasharray=\"6 4\"" : "");
            put_num(f, r + 10.0);
            fputc(' ', f);
            put_num(f, ly);
            fputs("h24\"/>\n", f);
            plotsvg_text(f, r + 40.0, ly + 4.0, 12.0, "start", s[k].label ? s[k].label : "");
        }
    }
}

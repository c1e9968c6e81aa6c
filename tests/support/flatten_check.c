/* SPDX-License-Identifier: MIT */
/* The independent flattening checker and greedy reference (flatten_check.h). */
#include "flatten_check.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Golden-section iterations of a refinement (the bracket of two sample
 * steps shrinks by 0.618 each: 40 of them reach 1e-8 of a step). */
#define FC_GOLDEN_ITERS 40
/* Positions on a chord whose distance to the arc is measured. */
#define FC_BACK_POSITIONS 24
/* Relative precision of the greedy's bisection (of the domain). */
#define FC_BISECT_REL 1e-9

void fc_point(const conica_bspline *s, double t, double *out)
{
    out[2] = 0.0;
    if (s->dim == 1) {
        out[0] = t;
        conica_bspline_eval(s, t, out + 1, NULL);
    } else {
        conica_bspline_eval(s, t, out, NULL);
    }
}

double fc_dist_seg(const double *q, const double *a, const double *b)
{
    double ab[3], aq[3], l2 = 0, t = 0, r = 0;
    for (int k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        aq[k] = q[k] - a[k];
        l2 += ab[k] * ab[k];
        t += aq[k] * ab[k];
    }
    t = l2 > 0 ? t / l2 : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    for (int k = 0; k < 3; k++) {
        double e = aq[k] - t * ab[k];
        r += e * e;
    }
    return sqrt(r);
}

double fc_curve_to_polyline(const conica_bspline *s, const double *xy, size_t n, int samples)
{
    double a, b, worst = 0;
    conica_bspline_domain(s, &a, &b);
    for (int k = 0; k <= samples; k++) {
        double x[3], best = INFINITY;
        fc_point(s, a + (b - a) * k / samples, x);
        for (size_t i = 0; i + 1 < n; i++) {
            double p[3] = {xy[2 * i], xy[2 * i + 1], 0}, q[3] = {xy[2 * i + 2], xy[2 * i + 3], 0};
            double d = fc_dist_seg(x, p, q);
            best = d < best ? d : best;
        }
        worst = best > worst ? best : worst;
    }
    return worst;
}

static double dist_pt(const double *q, const double *p)
{
    double r = 0;
    for (int k = 0; k < 3; k++)
        r += (q[k] - p[k]) * (q[k] - p[k]);
    return sqrt(r);
}

/* f(u) -> value to maximise (sign > 0) or minimise (sign < 0) over
 * [lo, hi] by golden section; returns the best value found (the caller's
 * sample value included). */
typedef struct fc_fn {
    const conica_bspline *s;
    const double *a, *b; /* chord (forward) */
    const double *q;     /* point (backward) */
} fc_fn;

static double fc_eval(const fc_fn *f, double u)
{
    double x[3];
    fc_point(f->s, u, x);
    return f->q ? -dist_pt(f->q, x) : fc_dist_seg(x, f->a, f->b);
}

static double golden_max(const fc_fn *f, double lo, double hi, double best)
{
    const double g = 0.6180339887498949;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = fc_eval(f, x1), f2 = fc_eval(f, x2);
    for (int it = 0; it < FC_GOLDEN_ITERS; it++) {
        if (f1 > f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = fc_eval(f, x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = fc_eval(f, x2);
        }
        best = f1 > best ? f1 : best;
        best = f2 > best ? f2 : best;
    }
    return best;
}

/* Dense maximum of f over [ua, ub]: FC_SAMPLES + 1 samples, then the two
 * best refined over their neighbouring steps. */
static double dense_max(const fc_fn *f, double ua, double ub)
{
    double v[FC_SAMPLES + 1], h = (ub - ua) / FC_SAMPLES;
    int i1 = 0, i2 = -1;
    for (int i = 0; i <= FC_SAMPLES; i++) {
        v[i] = fc_eval(f, i == FC_SAMPLES ? ub : ua + h * i);
        if (v[i] > v[i1]) {
            i2 = i1;
            i1 = i;
        } else if (i2 < 0 || v[i] > v[i2]) {
            i2 = i;
        }
    }
    double best = v[i1];
    int idx[2] = {i1, i2};
    for (int k = 0; k < 2; k++) {
        int i = idx[k];
        if (i < 0)
            continue;
        double lo = ua + h * (i > 0 ? i - 1 : 0), hi = ua + h * (i < FC_SAMPLES ? i + 1 : i);
        best = golden_max(f, lo, hi, best);
    }
    return best;
}

static double dev_ab(const conica_bspline *s, double ua, double ub, const double *a,
                     const double *b)
{
    fc_fn f = {s, a, b, NULL};
    return dense_max(&f, ua, ub);
}

static double back_ab(const conica_bspline *s, double ua, double ub, const double *a,
                      const double *b)
{
    double worst = 0;
    for (int j = 1; j < FC_BACK_POSITIONS; j++) {
        double q[3], l = (double)j / FC_BACK_POSITIONS;
        for (int k = 0; k < 3; k++)
            q[k] = a[k] + l * (b[k] - a[k]);
        fc_fn f = {s, NULL, NULL, q};
        double d = -dense_max(&f, ua, ub);
        worst = d > worst ? d : worst;
    }
    return worst;
}

double fc_chord_dev(const conica_bspline *s, double ua, double ub)
{
    double a[3], b[3];
    fc_point(s, ua, a);
    fc_point(s, ub, b);
    return dev_ab(s, ua, ub, a, b);
}

double fc_chord_dev_back(const conica_bspline *s, double ua, double ub)
{
    double a[3], b[3];
    fc_point(s, ua, a);
    fc_point(s, ub, b);
    return back_ab(s, ua, ub, a, b);
}

size_t fc_greedy(const conica_bspline *s, double tol)
{
    double a, b;
    conica_bspline_domain(s, &a, &b);
    double eps = FC_BISECT_REL * (b - a), u = a, step = (b - a) / 64;
    size_t count = 1;
    while (u < b) {
        if (fc_chord_dev(s, u, b) <= tol) {
            count++;
            break;
        }
        /* bracket [lo passes, hi fails] by doubling from the last step */
        double lo = u, hi = u + step;
        if (hi > b)
            hi = b;
        while (hi < b && fc_chord_dev(s, u, hi) <= tol) {
            lo = hi;
            hi = u + 2 * (hi - u);
            if (hi > b)
                hi = b;
        }
        while (hi - lo > eps) {
            double mid = 0.5 * (lo + hi);
            if (fc_chord_dev(s, u, mid) <= tol)
                lo = mid;
            else
                hi = mid;
        }
        if (lo <= u) /* a chord shorter than eps: take it */
            lo = u + eps;
        step = lo - u;
        u = lo;
        count++;
    }
    return count;
}

double fc_plot_dev(const conica_bspline *s, const conica_polyline *pl, double *worst_back)
{
    double worst = 0, back = 0;
    if (!pl->t)
        return -1;
    for (size_t k = 0; k < pl->npieces; k++) {
        size_t i0 = pl->piece_start[k], i1 = k + 1 < pl->npieces ? pl->piece_start[k + 1] : pl->n;
        for (size_t i = i0; i + 1 < i1; i++) {
            /* the emitted vertices, not the curve points at their parameters */
            double ua = pl->t[i], ub = pl->t[i + 1], a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
            for (int c = 0; c < pl->dim && c < 3; c++) {
                a[c] = pl->xy[i * (size_t)pl->dim + (size_t)c];
                b[c] = pl->xy[(i + 1) * (size_t)pl->dim + (size_t)c];
            }
            double d = dev_ab(s, ua, ub, a, b);
            worst = d > worst ? d : worst;
            if (worst_back) {
                double e = back_ab(s, ua, ub, a, b);
                back = e > back ? e : back;
            }
        }
    }
    if (worst_back)
        *worst_back = back;
    return worst;
}

conica_code fc_plot(const conica_bspline *s, double tol, conica_polyline *pl)
{
    conica_plot_settings ps = conica_plot_defaults();
    ps.abs_tolerance = tol;
    return conica_plot(s, &ps, pl, NULL, NULL);
}

/* ------------------------------------------------------------ curve set */

static uint64_t fc_rng = 0x2545F4914F6CDD1Dull;
static double fc_urand(void)
{
    fc_rng ^= fc_rng << 13;
    fc_rng ^= fc_rng >> 7;
    fc_rng ^= fc_rng << 17;
    return (double)(fc_rng >> 11) / 9007199254740992.0;
}

static int load_spl(const char *path, conica_bspline *s)
{
    static char buf[1 << 16];
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    size_t len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    return conica_bspline_parse(buf, len, s, NULL) == CONICA_OK;
}

static void add(fc_set *set, const char *name)
{
    snprintf(set->name[set->n], sizeof set->name[0], "%s", name);
    set->n++;
}

/* Random clamped B-spline of degree p with n control points in [0, 10]^2
 * (weights in [0.2, 5] when rational). */
static int random_curve(int p, size_t n, int rational, conica_bspline *s)
{
    double k[64], c[2 * 40], w[40];
    size_t nk = n + (size_t)p + 1;
    if (nk > 64 || n > 40)
        return 0;
    for (size_t i = 0; i <= (size_t)p; i++) {
        k[i] = 0;
        k[nk - 1 - i] = 10;
    }
    for (size_t i = (size_t)p + 1; i < n; i++)
        k[i] = 10 * fc_urand();
    for (size_t a = (size_t)p + 1; a < n; a++) /* sort the interior knots */
        for (size_t b = a + 1; b < n; b++)
            if (k[b] < k[a]) {
                double t = k[a];
                k[a] = k[b];
                k[b] = t;
            }
    for (size_t i = 0; i < 2 * n; i++)
        c[i] = 10 * fc_urand();
    for (size_t i = 0; i < n; i++)
        w[i] = 0.2 + 4.8 * fc_urand();
    return conica_bspline_set(p, 2, k, nk, c, n, rational ? w : NULL, s, NULL) == CONICA_OK;
}

void fc_set_make(fc_set *set, const char *splines_dir, const char *examples_dir, size_t nrandom)
{
    static const char *const ex[] = {"helix", "nurbs-circle", "s-curve", "wave-function"};
    char path[2048], name[40];
    set->n = set->thesis = 0;
    fc_rng = 0x2545F4914F6CDD1Dull;
    for (int i = 0; splines_dir && i <= 4; i++) {
        snprintf(path, sizeof path, "%s/sptest%d.spl", splines_dir, i);
        conica_bspline_init(&set->s[set->n]);
        if (load_spl(path, &set->s[set->n])) {
            snprintf(name, sizeof name, "sptest%d", i);
            add(set, name);
            set->thesis++;
        }
    }
    for (size_t i = 0; i < sizeof ex / sizeof ex[0]; i++) {
        snprintf(path, sizeof path, "%s/%s.spl", examples_dir, ex[i]);
        conica_bspline_init(&set->s[set->n]);
        if (load_spl(path, &set->s[set->n]))
            add(set, ex[i]);
    }
    for (size_t r = 0; r < nrandom && set->n < FC_SET_MAX - 5; r++) {
        int p = 2 + (int)(r % 6);
        size_t n = (size_t)p + 1 + (size_t)(fc_urand() * 10);
        conica_bspline_init(&set->s[set->n]);
        if (random_curve(p, n, 0, &set->s[set->n])) {
            snprintf(name, sizeof name, "random%zu-p%d", r, p);
            add(set, name);
        }
    }
    for (int r = 0; r < 3; r++) {
        int p = 2 + r;
        conica_bspline_init(&set->s[set->n]);
        if (random_curve(p, (size_t)p + 4, 1, &set->s[set->n])) {
            snprintf(name, sizeof name, "rational-p%d", p);
            add(set, name);
        }
    }
    for (int r = 0; r < 2; r++) {
        /* (0,0), (10,10), (0,10), (10,0) has a cusp at t = 1/2; moving
         * the third point by delta leaves a near-cusp */
        double delta = r == 0 ? 1e-2 : 1e-1;
        double c[8] = {0, 0, 10, 10, delta, 10, 10, 0};
        conica_bspline_init(&set->s[set->n]);
        if (conica_bspline_from_bezier(3, 2, c, NULL, &set->s[set->n], NULL) == CONICA_OK) {
            snprintf(name, sizeof name, "near-cusp-%g", delta);
            add(set, name);
        }
    }
}

void fc_set_free(fc_set *set)
{
    for (size_t i = 0; i < set->n; i++)
        conica_bspline_free(&set->s[i]);
    set->n = 0;
}

/* SPDX-License-Identifier: MIT */
/* B-spline machinery of Dahl 2019, Ch. 1: validation and the
 * preprocessing of Section 1.1.2, evaluation by the triangular algorithm
 * (eq. (1.10)-(1.11)) and derivatives (eq. (1.13)), Böhm's knot insertion
 * (Lemma 1.18), Bézier conversion, knot averages and the control polygon.
 * Rational splines are handled in homogeneous coordinates (w*c, w). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bspline_internal.h"
#include "internal.h"

void conica_bspline_init(conica_bspline *s)
{
    if (!s)
        return;
    s->degree = 0;
    s->dim = 0;
    s->n = 0;
    s->knots = NULL;
    s->ctrl = NULL;
    s->w = NULL;
}

void conica_bspline_free(conica_bspline *s)
{
    if (!s)
        return;
    free(s->knots);
    free(s->ctrl);
    free(s->w);
    conica_bspline_init(s);
}

conica_code conica__bspline_check(int degree, int dim, const double *knots, size_t nknots,
                                  const double *ctrl, size_t n, const double *w,
                                  int allow_high_mult, int *where, size_t *index,
                                  conica_status *st)
{
    *where = CONICA__AT_NONE;
    *index = 0;
    if (degree < 1 || degree > CONICA_BSPLINE_MAX_DEGREE)
        return conica__fail(st, degree > CONICA_BSPLINE_MAX_DEGREE ? CONICA_ERR_LIMIT : CONICA_ERR_ARG,
                            0, 0, "degree %d outside 1..%d", degree, CONICA_BSPLINE_MAX_DEGREE);
    if (dim < 1 || dim > 3)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "dimension %d outside 1..3", dim);
    if (n > CONICA_BSPLINE_MAX_CTRL)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "%zu control points exceed the limit %zu",
                            n, (size_t)CONICA_BSPLINE_MAX_CTRL);
    size_t p = (size_t)degree;
    if (n < p + 1)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "degree %d needs at least %d control points, got %zu", degree,
                            degree + 1, n);
    if (nknots != n + p + 1)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "%zu control points of degree %d need %zu knots, got %zu", n, degree,
                            n + p + 1, nknots);
    if (!knots || !ctrl)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL knots or control points");
    for (size_t i = 0; i < nknots; i++) {
        if (!isfinite(knots[i])) {
            *where = CONICA__AT_KNOT;
            *index = i;
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, i, "knot %zu is not finite", i + 1);
        }
        if (i > 0 && knots[i] < knots[i - 1]) {
            *where = CONICA__AT_KNOT;
            *index = i;
            return conica__fail(st, CONICA_ERR_ARG, 0, i, "knot %zu decreases (%.17g < %.17g)",
                                i + 1, knots[i], knots[i - 1]);
        }
    }
    if (!allow_high_mult) {
        size_t run = 1;
        for (size_t i = 1; i < nknots; i++) {
            run = knots[i] == knots[i - 1] ? run + 1 : 1;
            if (run > p + 1) {
                *where = CONICA__AT_KNOT;
                *index = i;
                return conica__fail(st, CONICA_ERR_ARG, 0, i,
                                    "knot %.17g has multiplicity > degree + 1 = %zu", knots[i],
                                    p + 1);
            }
        }
        if (!(knots[p] < knots[n]))
            return conica__fail(st, CONICA_ERR_ARG, 0, 0, "empty domain [t_p, t_n]");
    } else if (!(knots[0] < knots[nknots - 1])) {
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "all knots are equal");
    }
    for (size_t i = 0; i < n * (size_t)dim; i++)
        if (!isfinite(ctrl[i])) {
            *where = CONICA__AT_CTRL;
            *index = i / (size_t)dim;
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, *index,
                                "control point %zu is not finite", *index + 1);
        }
    if (w)
        for (size_t i = 0; i < n; i++)
            if (!isfinite(w[i]) || !(w[i] > 0)) {
                *where = CONICA__AT_WEIGHT;
                *index = i;
                return conica__fail(st, isfinite(w[i]) ? CONICA_ERR_ARG : CONICA_ERR_NONFINITE,
                                    0, i, "weight %zu (%.17g) is not a positive finite number",
                                    i + 1, w[i]);
            }
    return CONICA_OK;
}

/* Allocate and fill *out (freeing its previous contents only on success). */
static conica_code store(int degree, int dim, const double *knots, const double *ctrl, size_t n,
                         const double *w, conica_bspline *out, conica_status *st)
{
    size_t nk = n + (size_t)degree + 1;
    double *k = malloc(nk * sizeof *k);
    double *c = malloc(n * (size_t)dim * sizeof *c);
    double *ww = w ? malloc(n * sizeof *ww) : NULL;
    if (!k || !c || (w && !ww)) {
        free(k);
        free(c);
        free(ww);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory for %zu control points", n);
    }
    memcpy(k, knots, nk * sizeof *k);
    memcpy(c, ctrl, n * (size_t)dim * sizeof *c);
    if (w)
        memcpy(ww, w, n * sizeof *ww);
    conica_bspline_free(out);
    out->degree = degree;
    out->dim = dim;
    out->n = n;
    out->knots = k;
    out->ctrl = c;
    out->w = ww;
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_bspline_set(int degree, int dim, const double *knots, size_t nknots,
                               const double *ctrl, size_t n, const double *w,
                               conica_bspline *out, conica_status *st)
{
    int where;
    size_t idx;
    if (!out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL output");
    conica_code rc = conica__bspline_check(degree, dim, knots, nknots, ctrl, n, w, 0, &where,
                                           &idx, st);
    if (rc != CONICA_OK)
        return rc;
    return store(degree, dim, knots, ctrl, n, w, out, st);
}

conica_code conica__bspline_copy(const conica_bspline *s, conica_bspline *out, conica_status *st)
{
    return store(s->degree, s->dim, s->knots, s->ctrl, s->n, s->w, out, st);
}

/* Section 1.1.2, check_regular: trim knots of multiplicity > p+1 (dropping
 * the coefficients of B-splines with empty support) and extend the ends to
 * multiplicity p+1 with zero coefficients. */
conica_code conica_bspline_make_regular(int degree, int dim, const double *knots,
                                        size_t nknots, const double *ctrl, size_t n,
                                        const double *w, conica_bspline *out, conica_status *st)
{
    int where;
    size_t idx;
    if (!out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL output");
    conica_code rc = conica__bspline_check(degree, dim, knots, nknots, ctrl, n, w, 1, &where,
                                           &idx, st);
    if (rc != CONICA_OK)
        return rc;
    size_t p = (size_t)degree, d = (size_t)dim;
    size_t cap = n + 2 * p + 2;
    double *k = malloc((cap + p + 1) * sizeof *k);
    double *c = malloc(cap * d * sizeof *c);
    double *ww = malloc(cap * sizeof *ww);
    if (!k || !c || !ww) {
        free(k);
        free(c);
        free(ww);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    /* Front extension: B-splines on new knots t0 repeated, coefficient 0. */
    size_t m0 = 1;
    while (m0 < nknots && knots[m0] == knots[0])
        m0++;
    size_t nn = 0, kk = 0;
    if (m0 < p + 1) {
        for (size_t e = 0; e < p + 1 - m0; e++) {
            k[kk++] = knots[0];
            for (size_t j = 0; j < d; j++)
                c[nn * d + j] = 0.0;
            ww[nn++] = 1.0;
        }
    }
    /* Copy, skipping B-splines j with empty support (t_j == t_{j+p+1}),
     * which exist exactly where a knot has multiplicity > p+1. */
    for (size_t i = 0; i < n; i++) {
        int empty = knots[i] == knots[i + p + 1];
        if (empty)
            continue;
        k[kk++] = knots[i];
        for (size_t j = 0; j < d; j++)
            c[nn * d + j] = ctrl[i * d + j];
        ww[nn++] = w ? w[i] : 1.0;
    }
    /* Remaining knots: the last p+1 of the kept B-splines' supports. The
     * last kept B-spline i_last contributes knots up to i_last + p + 1; we
     * rebuild the tail from the original knot vector, trimming runs. */
    {
        size_t i_last = n;
        while (i_last > 0 && knots[i_last - 1] == knots[i_last - 1 + p + 1])
            i_last--;
        /* knots after the kept starts: indices i_last .. nknots-1 of the
         * original, trimmed to multiplicity p+1 */
        for (size_t i = i_last; i < nknots; i++)
            k[kk++] = knots[i];
    }
    /* Trim runs longer than p+1 in the assembled knot vector (the kept
     * starts removed the empty B-splines; the tail may still hold long
     * runs at the end). */
    {
        size_t wpos = 0, run = 0;
        for (size_t i = 0; i < kk; i++) {
            run = (wpos > 0 && k[i] == k[wpos - 1]) ? run + 1 : 1;
            if (run <= p + 1)
                k[wpos++] = k[i];
        }
        kk = wpos;
    }
    /* Back extension. */
    {
        size_t m1 = 1;
        while (m1 < kk && k[kk - 1 - m1] == k[kk - 1])
            m1++;
        for (size_t e = m1; e < p + 1; e++) {
            k[kk] = k[kk - 1];
            kk++;
            for (size_t j = 0; j < d; j++)
                c[nn * d + j] = 0.0;
            ww[nn++] = 1.0;
        }
    }
    if (kk != nn + p + 1) {
        free(k);
        free(c);
        free(ww);
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "knot vector cannot be made (p+1)-regular (%zu knots for %zu "
                            "coefficients)", kk, nn);
    }
    conica_bspline tmp;
    conica_bspline_init(&tmp);
    rc = conica_bspline_set(degree, dim, k, kk, c, nn, w ? ww : NULL, &tmp, st);
    free(k);
    free(c);
    free(ww);
    if (rc != CONICA_OK)
        return rc;
    conica_bspline_free(out);
    *out = tmp;
    return CONICA_OK;
}

conica_code conica_bspline_from_bezier(int degree, int dim, const double *ctrl, const double *w,
                                       conica_bspline *out, conica_status *st)
{
    if (degree < 1 || degree > CONICA_BSPLINE_MAX_DEGREE)
        return conica__fail(st, degree > CONICA_BSPLINE_MAX_DEGREE ? CONICA_ERR_LIMIT : CONICA_ERR_ARG,
                            0, 0, "degree %d outside 1..%d", degree, CONICA_BSPLINE_MAX_DEGREE);
    double knots[2 * CONICA_BSPLINE_MAX_DEGREE + 2];
    size_t p = (size_t)degree;
    for (size_t i = 0; i <= p; i++) {
        knots[i] = 0.0;
        knots[p + 1 + i] = 1.0;
    }
    return conica_bspline_set(degree, dim, knots, 2 * p + 2, ctrl, p + 1, w, out, st);
}

/* ------------------------------------------------------------ spans, eval */

size_t conica__find_span(const double *knots, size_t nk, int degree, double x, int left)
{
    size_t p = (size_t)degree, n = nk - p - 1;
    size_t lo = p, hi = n; /* answer in [p, n-1] */
    if (!(x > knots[p]) || (!left && x == knots[p])) {
        while (lo + 1 < n && !(knots[lo] < knots[lo + 1]))
            lo++;
        return lo;
    }
    if (left ? x > knots[n] : x >= knots[n]) {
        size_t mu = n - 1;
        while (mu > p && !(knots[mu] < knots[mu + 1]))
            mu--;
        return mu;
    }
    if (left && x == knots[n]) {
        size_t mu = n - 1;
        while (mu > p && !(knots[mu] < knots[mu + 1]))
            mu--;
        return mu;
    }
    /* invariant: knots[lo] (<= or <) x, x (< or <=) knots[hi] */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (left ? knots[mid] < x : knots[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static int valid(const conica_bspline *s);

size_t conica_bspline_find_span(const conica_bspline *s, double t)
{
    if (!valid(s))
        return 0; /* documented: NULL or an empty spline */
    return conica__find_span(s->knots, s->n + (size_t)s->degree + 1, s->degree, t, 0);
}

double conica__deboor(const double *knots, size_t mu, int degree, double x, int hd, double *d,
                      double *left_edge, double *right_edge)
{
    size_t p = (size_t)degree, h = (size_t)hd;
    if (left_edge)
        memcpy(left_edge, d, h * sizeof *d);
    if (right_edge)
        memcpy(right_edge + p * h, d + p * h, h * sizeof *d);
    for (size_t r = 1; r <= p; r++) {
        for (size_t k = p; k >= r; k--) {
            size_t j = mu - p + k;
            double a = (x - knots[j]) / (knots[j + p + 1 - r] - knots[j]);
            double *dk = d + k * h, *dm = d + (k - 1) * h;
            for (size_t c = 0; c < h; c++)
                dk[c] = dm[c] + a * (dk[c] - dm[c]);
        }
        if (left_edge)
            memcpy(left_edge + r * h, d + r * h, h * sizeof *d);
        if (right_edge)
            memcpy(right_edge + (p - r) * h, d + p * h, h * sizeof *d);
    }
    return (double)(p * (p + 1) / 2) * (3.0 + 3.0 * (double)h);
}

int conica__hdim(const conica_bspline *s)
{
    return s->dim + (s->w ? 1 : 0);
}

void conica__homog(const conica_bspline *s, size_t i0, size_t cnt, double *out)
{
    size_t d = (size_t)s->dim, h = (size_t)conica__hdim(s);
    for (size_t i = 0; i < cnt; i++) {
        double wi = s->w ? s->w[i0 + i] : 1.0;
        for (size_t c = 0; c < d; c++)
            out[i * h + c] = s->ctrl[(i0 + i) * d + c] * wi;
        if (s->w)
            out[i * h + d] = wi;
    }
}

static int valid(const conica_bspline *s)
{
    return s && s->knots && s->ctrl && s->degree >= 1 && s->degree <= CONICA_BSPLINE_MAX_DEGREE &&
           s->dim >= 1 && s->dim <= 3 && s->n >= (size_t)s->degree + 1;
}

void conica_bspline_domain(const conica_bspline *s, double *a, double *b)
{
    if (!valid(s)) {
        if (a)
            *a = NAN;
        if (b)
            *b = NAN;
        return;
    }
    if (a)
        *a = s->knots[s->degree];
    if (b)
        *b = s->knots[s->n];
}

conica_code conica_bspline_eval(const conica_bspline *s, double t, double *out, conica_status *st)
{
    if (!valid(s) || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid spline or output");
    if (!isfinite(t))
        return conica__fail(st, CONICA_ERR_NONFINITE, 0, 0, "parameter is not finite");
    double a = s->knots[s->degree], b = s->knots[s->n];
    t = t < a ? a : (t > b ? b : t);
    size_t p = (size_t)s->degree, h = (size_t)conica__hdim(s), d = (size_t)s->dim;
    size_t mu = conica_bspline_find_span(s, t);
    double buf[(CONICA_BSPLINE_MAX_DEGREE + 1) * CONICA__HDIM_MAX];
    conica__homog(s, mu - p, p + 1, buf);
    conica__deboor(s->knots, mu, s->degree, t, (int)h, buf, NULL, NULL);
    double *v = buf + p * h;
    double wv = s->w ? v[d] : 1.0;
    for (size_t c = 0; c < d; c++)
        out[c] = v[c] / wv;
    conica__ok(st);
    return CONICA_OK;
}

/* r-th derivative of the homogeneous polynomial piece mu at x (eq. (1.13)):
 * r difference steps DR_p..DR_{p-r+1}, then p-r convex steps, times p!/(p-r)!. */
static void deriv_homog(const conica_bspline *s, size_t mu, double x, int r, double *out)
{
    size_t p = (size_t)s->degree, h = (size_t)conica__hdim(s);
    double v[(CONICA_BSPLINE_MAX_DEGREE + 1) * CONICA__HDIM_MAX];
    conica__homog(s, mu - p, p + 1, v);
    const double *t = s->knots;
    double fac = 1.0;
    size_t k = p;
    for (int q = 0; q < r; q++, k--) {
        /* DR_k: k+1 entries -> k entries */
        for (size_t i = 1; i <= k; i++) {
            double den = t[mu + i] - t[mu + i - k];
            for (size_t c = 0; c < h; c++)
                v[(i - 1) * h + c] = (v[i * h + c] - v[(i - 1) * h + c]) / den;
        }
        fac *= (double)k;
    }
    for (; k >= 1; k--) {
        for (size_t i = 1; i <= k; i++) {
            double den = t[mu + i] - t[mu + i - k];
            double a = (x - t[mu + i - k]) / den;
            for (size_t c = 0; c < h; c++)
                v[(i - 1) * h + c] = v[(i - 1) * h + c] + a * (v[i * h + c] - v[(i - 1) * h + c]);
        }
    }
    for (size_t c = 0; c < h; c++)
        out[c] = fac * v[c];
}

conica_code conica_bspline_eval_deriv(const conica_bspline *s, double t, int r, double *out,
                                      conica_status *st)
{
    if (!valid(s) || !out || r < 0 || r > s->degree)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid spline, output or order");
    if (!isfinite(t))
        return conica__fail(st, CONICA_ERR_NONFINITE, 0, 0, "parameter is not finite");
    double a = s->knots[s->degree], b = s->knots[s->n];
    t = t < a ? a : (t > b ? b : t);
    size_t mu = conica_bspline_find_span(s, t);
    size_t d = (size_t)s->dim, h = (size_t)conica__hdim(s);
    if (!s->w) {
        deriv_homog(s, mu, t, r, out);
        conica__ok(st);
        return CONICA_OK;
    }
    /* Rational: C = A / W, C^(r) = (A^(r) - sum_{i=1}^r binom(r,i) W^(i) C^(r-i)) / W. */
    double hd[CONICA_BSPLINE_MAX_DEGREE + 1][CONICA__HDIM_MAX];
    double cd[CONICA_BSPLINE_MAX_DEGREE + 1][3];
    for (int q = 0; q <= r; q++)
        deriv_homog(s, mu, t, q, hd[q]);
    for (int q = 0; q <= r; q++) {
        double binom = 1.0;
        for (size_t c = 0; c < d; c++)
            cd[q][c] = hd[q][c];
        for (int i = 1; i <= q; i++) {
            binom = binom * (double)(q - i + 1) / (double)i;
            for (size_t c = 0; c < d; c++)
                cd[q][c] -= binom * hd[i][d] * cd[q - i][c];
        }
        for (size_t c = 0; c < d; c++)
            cd[q][c] /= hd[0][d];
    }
    (void)h;
    for (size_t c = 0; c < d; c++)
        out[c] = cd[r][c];
    conica__ok(st);
    return CONICA_OK;
}

/* ------------------------------------------------------------ knot insertion */

conica_code conica__insert_raw(conica_bspline *s, double z, size_t count, conica_status *st)
{
    if (count == 0)
        return CONICA_OK;
    size_t p = (size_t)s->degree, d = (size_t)s->dim, n = s->n;
    size_t nk = n + p + 1;
    if (n + count > CONICA_BSPLINE_MAX_CTRL)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "knot insertion would exceed %zu control points",
                            (size_t)CONICA_BSPLINE_MAX_CTRL);
    double *k = realloc(s->knots, (nk + count) * sizeof *k);
    if (!k)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    s->knots = k;
    double *c = realloc(s->ctrl, (n + count) * d * sizeof *c);
    if (!c)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    s->ctrl = c;
    if (s->w) {
        double *ww = realloc(s->w, (n + count) * sizeof *ww);
        if (!ww)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        s->w = ww;
    }
    size_t h = (size_t)conica__hdim(s);
    for (size_t rep = 0; rep < count; rep++) {
        n = s->n;
        nk = n + p + 1;
        size_t mu = conica__find_span(s->knots, nk, s->degree, z, 0);
        /* Lemma 1.18 (0-based): cbar_j = a_j c_j + (1-a_j) c_{j-1},
         * a_j = (z - t_j)/(t_{j+p} - t_j), j = mu-p+1..mu. */
        double loc[(CONICA_BSPLINE_MAX_DEGREE + 1) * CONICA__HDIM_MAX];
        conica__homog(s, mu - p, p + 1, loc);
        double nw[(CONICA_BSPLINE_MAX_DEGREE) * CONICA__HDIM_MAX];
        for (size_t j = mu - p + 1; j <= mu; j++) {
            double a = (z - s->knots[j]) / (s->knots[j + p] - s->knots[j]);
            size_t l = j - (mu - p);
            for (size_t q = 0; q < h; q++)
                nw[(l - 1) * h + q] = loc[(l - 1) * h + q] + a * (loc[l * h + q] - loc[(l - 1) * h + q]);
        }
        /* shift control points mu..n-1 right by one, knots mu+1.. by one */
        memmove(s->ctrl + (mu + 1) * d, s->ctrl + mu * d, (n - mu) * d * sizeof *s->ctrl);
        if (s->w)
            memmove(s->w + mu + 1, s->w + mu, (n - mu) * sizeof *s->w);
        memmove(s->knots + mu + 2, s->knots + mu + 1, (nk - mu - 1) * sizeof *s->knots);
        s->knots[mu + 1] = z;
        for (size_t l = 0; l < p; l++) {
            size_t j = mu - p + 1 + l;
            double wj = s->w ? nw[l * h + d] : 1.0;
            for (size_t q = 0; q < d; q++)
                s->ctrl[j * d + q] = nw[l * h + q] / wj;
            if (s->w)
                s->w[j] = wj;
        }
        s->n = n + 1;
    }
    return CONICA_OK;
}

static size_t multiplicity(const conica_bspline *s, double z)
{
    size_t m = 0, nk = s->n + (size_t)s->degree + 1;
    for (size_t i = 0; i < nk; i++)
        m += s->knots[i] == z;
    return m;
}

conica_code conica_bspline_insert_knots(conica_bspline *s, const double *z, size_t k,
                                        conica_status *st)
{
    if (!valid(s) || (k && !z))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid spline or knots");
    double a = s->knots[s->degree], b = s->knots[s->n];
    for (size_t i = 0; i < k; i++) {
        if (!isfinite(z[i]))
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, i, "knot to insert is not finite");
        if (z[i] < a || z[i] > b)
            return conica__fail(st, CONICA_ERR_ARG, 0, i,
                                "knot %.17g outside the domain [%.17g, %.17g]", z[i], a, b);
    }
    if (s->n + k > CONICA_BSPLINE_MAX_CTRL)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "knot insertion would exceed %zu control points",
                            (size_t)CONICA_BSPLINE_MAX_CTRL);
    conica_bspline tmp;
    conica_bspline_init(&tmp);
    conica_code rc = conica__bspline_copy(s, &tmp, st);
    if (rc != CONICA_OK)
        return rc;
    for (size_t i = 0; i < k; i++) {
        if (multiplicity(&tmp, z[i]) + 1 > (size_t)s->degree + 1) {
            conica_bspline_free(&tmp);
            return conica__fail(st, CONICA_ERR_ARG, 0, i,
                                "inserting %.17g would exceed multiplicity degree + 1", z[i]);
        }
        rc = conica__insert_raw(&tmp, z[i], 1, st);
        if (rc != CONICA_OK) {
            conica_bspline_free(&tmp);
            return rc;
        }
    }
    conica_bspline_free(s);
    *s = tmp;
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_bspline_insert_knot(conica_bspline *s, double z, conica_status *st)
{
    return conica_bspline_insert_knots(s, &z, 1, st);
}

/* ------------------------------------------------------------ clamping, Bézier */

conica_code conica__bspline_clamp(const conica_bspline *s, conica_bspline *out, conica_status *st)
{
    conica_bspline tmp;
    conica_bspline_init(&tmp);
    conica_code rc = conica__bspline_copy(s, &tmp, st);
    if (rc != CONICA_OK)
        return rc;
    size_t p = (size_t)s->degree, d = (size_t)s->dim;
    double a = s->knots[p], b = s->knots[s->n];
    size_t ma = multiplicity(&tmp, a), mb = multiplicity(&tmp, b);
    if (ma < p + 1)
        rc = conica__insert_raw(&tmp, a, p + 1 - ma, st);
    if (rc == CONICA_OK && mb < p + 1)
        rc = conica__insert_raw(&tmp, b, p + 1 - mb, st);
    if (rc != CONICA_OK) {
        conica_bspline_free(&tmp);
        return rc;
    }
    /* drop knots before the first a and after the last b with their
     * B-splines (their support ends at a / starts at b) */
    size_t nk = tmp.n + p + 1, first = 0, last = nk - 1;
    while (tmp.knots[first] < a)
        first++;
    while (tmp.knots[last] > b)
        last--;
    size_t nn = (last - first + 1) - p - 1;
    memmove(tmp.knots, tmp.knots + first, (last - first + 1) * sizeof *tmp.knots);
    memmove(tmp.ctrl, tmp.ctrl + first * d, nn * d * sizeof *tmp.ctrl);
    if (tmp.w)
        memmove(tmp.w, tmp.w + first, nn * sizeof *tmp.w);
    tmp.n = nn;
    conica_bspline_free(out);
    *out = tmp;
    conica__ok(st);
    return CONICA_OK;
}

size_t conica_bspline_bezier_count(const conica_bspline *s)
{
    size_t cnt = 0;
    if (!valid(s))
        return 0;
    for (size_t i = (size_t)s->degree; i < s->n; i++)
        cnt += s->knots[i] < s->knots[i + 1];
    return cnt;
}

conica_code conica_bspline_to_bezier(const conica_bspline *s, conica_bspline *out,
                                     conica_status *st)
{
    if (!valid(s) || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid spline or output");
    conica_bspline tmp;
    conica_bspline_init(&tmp);
    conica_code rc = conica__bspline_clamp(s, &tmp, st);
    if (rc != CONICA_OK)
        return rc;
    size_t p = (size_t)s->degree;
    size_t pieces = conica_bspline_bezier_count(&tmp);
    if (pieces * (p + 1) > CONICA_BSPLINE_MAX_CTRL) {
        conica_bspline_free(&tmp);
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "Bézier form exceeds %zu control points",
                            (size_t)CONICA_BSPLINE_MAX_CTRL);
    }
    /* raise every interior knot to multiplicity p+1 */
    size_t i = p + 1;
    while (i < tmp.n) {
        double z = tmp.knots[i];
        size_t m = 0;
        while (i + m < tmp.n + p + 1 && tmp.knots[i + m] == z)
            m++;
        if (z >= tmp.knots[tmp.n])
            break;
        if (m < p + 1) {
            rc = conica__insert_raw(&tmp, z, p + 1 - m, st);
            if (rc != CONICA_OK) {
                conica_bspline_free(&tmp);
                return rc;
            }
        }
        i += p + 1;
    }
    conica_bspline_free(out);
    *out = tmp;
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_bspline_bezier_piece(const conica_bspline *s, size_t k, double *ctrl,
                                        double *w, double *a, double *b, conica_status *st)
{
    if (!valid(s) || !ctrl)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid spline or output");
    size_t p = (size_t)s->degree, d = (size_t)s->dim, h = (size_t)conica__hdim(s);
    size_t mu = p, cnt = 0;
    for (; mu < s->n; mu++)
        if (s->knots[mu] < s->knots[mu + 1]) {
            if (cnt == k)
                break;
            cnt++;
        }
    if (mu >= s->n)
        return conica__fail(st, CONICA_ERR_ARG, 0, k, "piece %zu out of range", k);
    double ta = s->knots[mu], tb = s->knots[mu + 1];
    /* Bézier points of piece mu: left edge of the triangle at tb applied to
     * the right edge of the triangle at ta (blossoms f(ta^{p-i}, tb^i)). */
    double d0[(CONICA_BSPLINE_MAX_DEGREE + 1) * CONICA__HDIM_MAX];
    double re[(CONICA_BSPLINE_MAX_DEGREE + 1) * CONICA__HDIM_MAX];
    double le[(CONICA_BSPLINE_MAX_DEGREE + 1) * CONICA__HDIM_MAX];
    conica__homog(s, mu - p, p + 1, d0);
    conica__deboor(s->knots, mu, s->degree, ta, (int)h, d0, NULL, re);
    /* re: control points of piece mu with ta p-fold; knots ta^p, t_{mu+1}.. */
    double kn[2 * CONICA_BSPLINE_MAX_DEGREE + 2];
    for (size_t i = 0; i <= p; i++)
        kn[i] = ta;
    for (size_t i = 1; i <= p; i++)
        kn[p + i] = s->knots[mu + i];
    kn[2 * p + 1] = kn[2 * p];
    conica__deboor(kn, p, s->degree, tb, (int)h, re, le, NULL);
    for (size_t i = 0; i <= p; i++) {
        double wi = s->w ? le[i * h + d] : 1.0;
        for (size_t c = 0; c < d; c++)
            ctrl[i * d + c] = le[i * h + c] / wi;
        if (w && s->w)
            w[i] = wi;
    }
    if (a)
        *a = ta;
    if (b)
        *b = tb;
    conica__ok(st);
    return CONICA_OK;
}

void conica_bspline_knot_averages(const conica_bspline *s, double *out)
{
    if (!valid(s) || !out)
        return;
    size_t p = (size_t)s->degree;
    for (size_t j = 0; j < s->n; j++) {
        double sum = 0.0;
        for (size_t i = 1; i <= p; i++)
            sum += s->knots[j + i];
        out[j] = sum / (double)p;
    }
}

int conica_bspline_point_dim(const conica_bspline *s)
{
    if (!s)
        return 0;
    return s->dim == 1 ? 2 : s->dim;
}

void conica_bspline_control_polygon(const conica_bspline *s, double *out)
{
    if (!valid(s) || !out)
        return;
    if (s->dim == 1) {
        size_t p = (size_t)s->degree;
        for (size_t j = 0; j < s->n; j++) {
            double sum = 0.0;
            for (size_t i = 1; i <= p; i++)
                sum += s->knots[j + i];
            out[2 * j] = sum / (double)p;
            out[2 * j + 1] = s->ctrl[j];
        }
        return;
    }
    memcpy(out, s->ctrl, s->n * (size_t)s->dim * sizeof *out);
}

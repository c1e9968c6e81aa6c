/* Guaranteed plotter (beyond the seed; the default for the tools).
 *
 * Emits points ON the curve and certifies every chord: for consecutive
 * emitted parameters u_a < u_b, every point of the spline on [u_a, u_b] is
 * within tol of the chord [f(u_a), f(u_b)] and every point of the chord is
 * within tol of the spline on [u_a, u_b].
 *
 * Certificate (proof sketch).
 * 1. Restriction. Inserting u_a and u_b p times each (Böhm, Lemma 1.18;
 *    the triangular algorithm of eq. (1.11) computes exactly these
 *    coefficients on its left/right diagonals) makes the spline on
 *    [u_a, u_b] a clamped B-spline whose control points Q_0..Q_m start at
 *    Q_0 = f(u_a) and end at Q_m = f(u_b) (Lemma 1.11).
 * 2. Curve -> chord. By the convex hull property (Lemma 1.13; for a
 *    rational spline the projected point is a convex combination of the
 *    projected control points with weights N_i w_i / sum N_j w_j > 0), f(u)
 *    lies in conv{Q_i}. The distance to the chord segment S is a convex
 *    function, so its maximum over conv{Q_i} is attained at a vertex:
 *    dist(f(u), S) <= D := max_i dist(Q_i, S).
 * 3. Chord -> curve. Let pi be the nearest-point projection onto S; it is
 *    continuous, and pi(f(u_a)) = f(u_a), pi(f(u_b)) = f(u_b) are the two
 *    ends of S. So pi(f([u_a, u_b])) is a connected subset of S holding
 *    both ends, i.e. all of S: every q in S equals pi(f(u)) for some u and
 *    |q - f(u)| = dist(f(u), S) <= D.
 * Hence D <= tol certifies both directions of the Hausdorff distance.
 * D shrinks quadratically under refinement (the control polygon converges
 * quadratically, Theorem 1.16), so the march below terminates; a margin of
 * a few ulps of the coordinates' magnitude covers rounding.
 *
 * The march: from u_a, guess u_b (the whole piece first, then from the
 * D ~ h^2 model), compute D for [u_a, u_b] with one triangular algorithm
 * (Bézier-like restriction across any number of knot intervals: the
 * control points strictly between stay untouched), shrink on failure, grow
 * while D is well under tol, accept the longest certified chord. Cost per
 * trial: one de Boor evaluation, 3/2 p(p+1) flops per homogeneous
 * coordinate (eq. (1.14)) plus the hull test, linear in the number of
 * control points spanned. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bspline_internal.h"
#include "internal.h"
#include "plot_internal.h"

#define MAXP CONICA_BSPLINE_MAX_DEGREE
#define HD CONICA__HDIM_MAX
/* Step model D ~ h^2: aim at this fraction of tol. */
#define G_TARGET 0.95
/* Grow a certified chord while D is below this fraction of tol. */
#define G_GROW_BELOW 0.55
#define G_MAX_GROW 3
/* A certified chord with D >= G_GOOD * tol is taken without searching on. */
#define G_GOOD 0.7
/* Trials per emitted point and relative bracket width that end the search. */
#define G_MAX_TRIES 8
#define G_BRACKET 0.03
/* Up to this degree the tight (halves) certificate also steers growth. */
#define G_REFINE_MAX_P 8
/* When the hull bound misses tol by at most this factor (the hull of a
 * degree-p control polygon over-estimates a parabola-like arc by up to
 * p/(p-1)), certify again with the two halves' control polygons: the curve
 * on each half lies in that half's hull, and the distance to the chord is
 * convex, so the largest vertex distance over both halves is also a valid
 * bound -- a much tighter one (exact for a parabola). */
#define G_REFINE_RATIO 2.1
/* Rounding margin in units of DBL_EPSILON * (p + 2) * coordinate scale. */
#define G_ULPS 64.0

typedef struct march {
    int p, h, d;
    const double *T;
    size_t nk, n;
    double *H; /* homogeneous control points n * h */
    double head[(MAXP + 1) * HD];
    double ua;
    size_t mua;
    /* last trial */
    double le[(MAXP + 1) * HD], re[(MAXP + 1) * HD];
    size_t mu_o;
    double x;
    double flops;
    /* scratch for the refined certificate: restricted spline */
    double *rk, *rc;
} march;

static const double *rem_ctrl(const march *m, size_t i)
{
    size_t p = (size_t)m->p;
    return i <= p ? m->head + i * (size_t)m->h : m->H + (m->mua + i - p) * (size_t)m->h;
}

static double rem_knot(const march *m, size_t i)
{
    size_t p = (size_t)m->p;
    return i <= p ? m->ua : m->T[m->mua + i - p];
}

static void proj(const march *m, const double *hp, double *out)
{
    if (m->h > m->d) {
        for (int c = 0; c < m->d; c++)
            out[c] = hp[c] / hp[m->d];
    } else {
        for (int c = 0; c < m->d; c++)
            out[c] = hp[c];
    }
}

/* Squared distances to one chord [a, b], set up once per certificate. */
typedef struct chord {
    double a[3], ab[3], ab2;
    int d;
} chord;

static void chord_init(chord *c, const double *a, const double *b, int d)
{
    c->d = d;
    c->ab2 = 0;
    for (int k = 0; k < d; k++) {
        c->a[k] = a[k];
        c->ab[k] = b[k] - a[k];
        c->ab2 += c->ab[k] * c->ab[k];
    }
}

static double chord_d2(const chord *c, const double *q)
{
    double t = 0, qa2 = 0;
    for (int k = 0; k < c->d; k++) {
        double e = q[k] - c->a[k];
        t += e * c->ab[k];
        qa2 += e * e;
    }
    if (t <= 0 || c->ab2 <= 0)
        return qa2;
    if (t >= c->ab2) {
        double r = 0;
        for (int k = 0; k < c->d; k++) {
            double e = q[k] - c->a[k] - c->ab[k];
            r += e * e;
        }
        return r;
    }
    double r = qa2 - t * t / c->ab2;
    return r > 0 ? r : 0;
}

/* Largest squared distance of n homogeneous points to the chord. */
static double max_d2(const march *m, const chord *c, const double *hp, size_t n, double cur)
{
    size_t h = (size_t)m->h;
    double q[3];
    for (size_t i = 0; i < n; i++) {
        const double *x = hp + i * h;
        if (m->h > m->d) {
            for (int k = 0; k < m->d; k++)
                q[k] = x[k] / x[m->d];
            x = q;
        }
        double e = chord_d2(c, x);
        cur = e > cur ? e : cur;
    }
    return cur;
}

/* Triangle at x on the remaining spline with original span mu (left or
 * right convention chosen by the caller); fills m->le / m->re. */
static void triangle(march *m, double x, size_t mu)
{
    size_t p = (size_t)m->p, h = (size_t)m->h;
    size_t nu = p + mu - m->mua;
    double kl[2 * MAXP + 2];
    double dd[(MAXP + 1) * HD];
    for (size_t i = 0; i <= 2 * p; i++)
        kl[i] = rem_knot(m, nu - p + i);
    kl[2 * p + 1] = kl[2 * p];
    for (size_t k = 0; k <= p; k++)
        memcpy(dd + k * h, rem_ctrl(m, nu - p + k), h * sizeof *dd);
    m->flops += conica__deboor(kl, p, m->p, x, m->h, dd, m->le, m->re);
}

/* Certified deviation D of the chord [f(ua), f(x)]. */
static double trial(march *m, double x)
{
    size_t p = (size_t)m->p, h = (size_t)m->h;
    size_t mu = conica__find_span(m->T, m->nk, m->p, x, 1);
    if (mu < m->mua)
        mu = m->mua;
    m->mu_o = mu;
    m->x = x;
    triangle(m, x, mu);
    size_t nu = p + mu - m->mua;
    double a[3], b[3];
    proj(m, m->head, a);
    proj(m, m->le + p * h, b);
    chord c;
    chord_init(&c, a, b, m->d);
    double d2 = 0.0;
    /* untouched control points between the two triangles: the head, then
     * the original ones */
    size_t mid = nu > p ? nu - p : 0; /* remaining indices 1 .. mid-1 */
    size_t nhead = mid > p + 1 ? p + 1 : mid;
    if (nhead > 1)
        d2 = max_d2(m, &c, m->head + h, nhead - 1, d2);
    if (mid > p + 1)
        d2 = max_d2(m, &c, m->H + (m->mua + 1) * h, mid - (p + 1), d2);
    d2 = max_d2(m, &c, m->le, p, d2);
    double dev = sqrt(d2);
    m->flops += (double)(nu + 1) * (12.0 + 3.0 * (double)m->d);
    return dev;
}

/* Tighter certificate for the last trial: split the restriction to
 * [ua, x] at its middle and take the vertex distances of both halves. */
static double refine(march *m)
{
    size_t p = (size_t)m->p, h = (size_t)m->h;
    size_t nu = p + m->mu_o - m->mua;
    size_t M = nu; /* control points 0..M */
    for (size_t i = 0; i + p < nu; i++)
        memcpy(m->rc + i * h, rem_ctrl(m, i), h * sizeof *m->rc);
    memcpy(m->rc + (nu - p) * h, m->le, (p + 1) * h * sizeof *m->rc);
    size_t nk = 0;
    for (size_t i = 0; i <= p; i++)
        m->rk[nk++] = m->ua;
    for (size_t i = p + 1; i <= nu; i++)
        m->rk[nk++] = rem_knot(m, i);
    for (size_t i = 0; i <= p; i++)
        m->rk[nk++] = m->x;
    double xm = 0.5 * (m->ua + m->x);
    size_t mu = conica__find_span(m->rk, nk, m->p, xm, 0);
    double dd[(MAXP + 1) * HD], le2[(MAXP + 1) * HD], re2[(MAXP + 1) * HD];
    memcpy(dd, m->rc + (mu - p) * h, (p + 1) * h * sizeof *dd);
    m->flops += conica__deboor(m->rk, mu, m->p, xm, m->h, dd, le2, re2);
    double a[3], b[3];
    proj(m, m->rc, a);
    proj(m, m->rc + M * h, b);
    chord c;
    chord_init(&c, a, b, m->d);
    double d2 = 0.0;
    if (mu > p + 1)
        d2 = max_d2(m, &c, m->rc + h, mu - p - 1, d2);
    d2 = max_d2(m, &c, le2, p + 1, d2);
    d2 = max_d2(m, &c, re2, p + 1, d2);
    if (M > mu + 1)
        d2 = max_d2(m, &c, m->rc + (mu + 1) * h, M - mu - 1, d2);
    double dev = sqrt(d2);
    m->flops += (double)(M + p + 3) * (12.0 + 3.0 * (double)m->d);
    return dev;
}

/* Move the start of the remaining spline to the last trial's x. */
static void commit(march *m)
{
    size_t p = (size_t)m->p, h = (size_t)m->h;
    double x = m->x;
    if (!(m->T[m->mu_o + 1] == x)) {
        memcpy(m->head, m->re, (p + 1) * h * sizeof *m->head);
        m->mua = m->mu_o;
    } else {
        /* x is a knot: the right half needs the span to the right of x */
        size_t mu = conica__find_span(m->T, m->nk, m->p, x, 0);
        triangle(m, x, mu);
        memcpy(m->head, m->re, (p + 1) * h * sizeof *m->head);
        m->mua = mu;
    }
    m->ua = x;
}

static conica_code push_param(double **params, size_t *np, size_t *cap, double u,
                              conica_status *st)
{
    if (!params)
        return CONICA_OK;
    if (*np == *cap) {
        size_t nc = *cap ? 2 * *cap : 64;
        double *v = realloc(*params, nc * sizeof *v);
        if (!v)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        *params = v;
        *cap = nc;
    }
    (*params)[(*np)++] = u;
    return CONICA_OK;
}

conica_code conica__guaranteed_piece(const conica_bspline *g, double tol,
                                     const conica_plot_settings *set, int first_is_join,
                                     conica__out *o, double **params, size_t *np,
                                     conica_plot_stats *stats, conica_status *st)
{
    march *m = malloc(sizeof *m);
    if (!m)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    m->p = g->degree;
    m->d = g->dim;
    m->h = conica__hdim(g);
    m->T = g->knots;
    m->n = g->n;
    m->nk = g->n + (size_t)g->degree + 1;
    m->flops = 0;
    m->H = malloc(g->n * (size_t)m->h * sizeof *m->H);
    m->rk = malloc((g->n + 2 * (size_t)g->degree + 4) * sizeof *m->rk);
    m->rc = malloc((g->n + (size_t)g->degree + 2) * (size_t)m->h * sizeof *m->rc);
    if (!m->H || !m->rk || !m->rc) {
        free(m->H);
        free(m->rk);
        free(m->rc);
        free(m);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    conica__homog(g, 0, g->n, m->H);
    size_t p = (size_t)m->p, h = (size_t)m->h;
    memcpy(m->head, m->H, (p + 1) * h * sizeof *m->head);
    m->ua = g->knots[p];
    m->mua = p;
    double a = g->knots[p], b = g->knots[g->n];

    /* rounding margin from the magnitude of the coordinates */
    double scale = 0.0, pt[3];
    for (size_t i = 0; i < g->n; i++) {
        proj(m, m->H + i * h, pt);
        for (int c = 0; c < m->d; c++)
            scale = fabs(pt[c]) > scale ? fabs(pt[c]) : scale;
    }
    double margin = G_ULPS * (double)(p + 2) * DBL_EPSILON * scale;
    double tol_eff = tol - margin;
    conica_code rc = CONICA_OK;
    size_t cap = 0;
    if (params)
        *np = 0;
    if (!(tol_eff > 0.5 * tol)) {
        rc = conica__fail(st, CONICA_ERR_ARG, 0, 0,
                          "tolerance %.3g is below the floating-point resolution of "
                          "coordinates of magnitude %.3g",
                          tol, scale);
        goto done;
    }
    if (!first_is_join) {
        proj(m, m->head, pt);
        rc = conica__out_push(o, pt, a, st);
        if (rc == CONICA_OK)
            rc = push_param(params, np, &cap, a, st);
        if (rc != CONICA_OK)
            goto done;
    } else if (params) {
        rc = push_param(params, np, &cap, a, st);
        if (rc != CONICA_OK)
            goto done;
    }
    double hs = b - a; /* first guess: the whole piece */
    double min_step = (b - a) * 1e-13;
    double maxdev = 0.0;
    double save_le[(MAXP + 1) * HD], save_re[(MAXP + 1) * HD];
    while (m->ua < b) {
        /* Search for the longest certified chord from ua: shrink until a
         * trial passes, grow while it passes comfortably, then narrow the
         * bracket [pass, fail] with the sqrt(D) ~ h model. */
        int have = 0, have_fail = 0, grows = 0, tries = 0;
        double best_dev = 0, best_x = b, fail_x = b, fail_dev = 0;
        size_t best_mu = 0;
        for (;;) {
            double x = m->ua + hs;
            if (!(x < b) || b - x < 1e-9 * (b - a))
                x = b;
            if (stats->iterations >= set->max_iterations) {
                rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                  "guaranteed plot needs more than %zu trial steps "
                                  "(max_iterations)",
                                  set->max_iterations);
                goto done;
            }
            stats->iterations++;
            tries++;
            double dev = trial(m, x);
            if (dev > tol_eff && dev <= G_REFINE_RATIO * tol_eff) {
                double d2 = refine(m);
                dev = d2 < dev ? d2 : dev;
            } else if (dev <= tol_eff && dev >= G_GROW_BELOW * tol && m->p <= G_REFINE_MAX_P &&
                       x < b) {
                /* cheap at low degree: the tight value decides growth */
                double d2 = refine(m);
                dev = d2 < dev ? d2 : dev;
            }
            if (dev <= tol_eff) {
                have = 1;
                best_dev = dev;
                best_x = x;
                best_mu = m->mu_o;
                memcpy(save_le, m->le, (p + 1) * h * sizeof *save_le);
                memcpy(save_re, m->re, (p + 1) * h * sizeof *save_re);
                if (x >= b || dev >= G_GOOD * tol)
                    break;
            } else {
                have_fail = 1;
                fail_x = x;
                fail_dev = dev;
            }
            double hp = best_x - m->ua, hf = fail_x - m->ua;
            if (have && have_fail) {
                if (tries >= G_MAX_TRIES || hf - hp < G_BRACKET * hp)
                    break;
                double sp = sqrt(best_dev), sf = sqrt(fail_dev), sg = sqrt(G_TARGET * tol);
                double fr = sf > sp ? (sg - sp) / (sf - sp) : 0.5;
                fr = fr < 0.1 ? 0.1 : (fr > 0.9 ? 0.9 : fr);
                hs = hp + fr * (hf - hp);
            } else if (have) {
                if (grows++ >= G_MAX_GROW)
                    break;
                double f = dev > 0 ? sqrt(G_TARGET * tol / dev) : 4.0;
                f = f < 1.15 ? 1.15 : (f > 4.0 ? 4.0 : f);
                hs = hp * f;
            } else {
                double f = 0.9 * sqrt(tol / dev);
                f = f < 0.1 ? 0.1 : (f > 0.8 ? 0.8 : f);
                hs = hf * f;
                if (hs < min_step) {
                    rc = conica__fail(st, CONICA_ERR_NUMERIC, 0, 0,
                                      "cannot certify tolerance %.3g near parameter %.17g",
                                      tol, m->ua);
                    goto done;
                }
            }
        }
        /* accept the longest certified chord */
        memcpy(m->le, save_le, (p + 1) * h * sizeof *save_le);
        memcpy(m->re, save_re, (p + 1) * h * sizeof *save_re);
        m->x = best_x;
        m->mu_o = best_mu;
        maxdev = best_dev > maxdev ? best_dev : maxdev;
        proj(m, m->le + p * h, pt);
        if (best_x >= b) /* the end point of the piece exactly */
            proj(m, m->H + (g->n - 1) * h, pt);
        rc = conica__out_push(o, pt, best_x, st);
        if (rc == CONICA_OK)
            rc = push_param(params, np, &cap, best_x, st);
        if (rc != CONICA_OK)
            goto done;
        double step = best_x - m->ua;
        if (best_x >= b)
            break;
        commit(m);
        double f = best_dev > 0 ? sqrt(G_TARGET * tol / best_dev) : 2.0;
        f = f < 0.7 ? 0.7 : (f > 2.0 ? 2.0 : f);
        hs = step * f;
    }
    if (maxdev + margin > stats->bound)
        stats->bound = maxdev + margin;
done:
    stats->flops += m->flops;
    free(m->H);
    free(m->rk);
    free(m->rc);
    free(m);
    return rc;
}

conica_code conica__plot_guaranteed(const conica__pieces *pc, const conica_plot_settings *set,
                                    double tol, conica__out *o, conica_plot_stats *stats,
                                    conica_status *st)
{
    for (size_t k = 0; k < pc->count; k++) {
        conica_code rc = CONICA_OK;
        if (!pc->joined[k])
            rc = conica__out_piece(o, st);
        if (rc == CONICA_OK)
            rc = conica__guaranteed_piece(&pc->sp[k], tol, set, pc->joined[k], o, NULL, NULL,
                                          stats, st);
        if (rc != CONICA_OK)
            return rc;
    }
    return CONICA_OK;
}

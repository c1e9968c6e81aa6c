/* SPDX-License-Identifier: MIT */
/* Tensor-product B-spline surfaces (seed 004, Section 4.1): validation,
 * evaluation, and the two-phase quad-grid plot of Section 4.1.2. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bspline_internal.h"
#include "internal.h"
#include "plot_internal.h"

void conica_bspline_surface_init(conica_bspline_surface *s)
{
    if (s)
        memset(s, 0, sizeof *s);
}

void conica_bspline_surface_free(conica_bspline_surface *s)
{
    if (!s)
        return;
    free(s->knots_u);
    free(s->knots_v);
    free(s->ctrl);
    free(s->w);
    conica_bspline_surface_init(s);
}

conica_code conica_bspline_surface_set(int degree_u, int degree_v, int dim,
                                       const double *knots_u, size_t nknots_u,
                                       const double *knots_v, size_t nknots_v,
                                       const double *ctrl, size_t nu, size_t nv, const double *w,
                                       conica_bspline_surface *out, conica_status *st)
{
    if (!out || !ctrl)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL argument");
    if (dim != 1 && dim != 3)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "surface dimension must be 1 or 3");
    if (nu == 0 || nv == 0 || nu > CONICA_BSPLINE_MAX_CTRL / nv)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "control net %zu x %zu empty or above %zu points", nu, nv,
                            (size_t)CONICA_BSPLINE_MAX_CTRL);
    /* each direction is validated as a spline function with dummy
     * coefficients; then the net itself */
    int where;
    size_t idx;
    size_t mx = nu > nv ? nu : nv;
    double *zero = calloc(mx, sizeof *zero);
    if (!zero)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    conica_code rc = conica__bspline_check(degree_u, 1, knots_u, nknots_u, zero, nu, NULL, 0,
                                           &where, &idx, st);
    if (rc == CONICA_OK)
        rc = conica__bspline_check(degree_v, 1, knots_v, nknots_v, zero, nv, NULL, 0, &where,
                                   &idx, st);
    free(zero);
    if (rc != CONICA_OK)
        return rc;
    size_t n = nu * nv;
    for (size_t i = 0; i < n * (size_t)dim; i++)
        if (!isfinite(ctrl[i]))
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, i / (size_t)dim,
                                "control point %zu is not finite", i / (size_t)dim + 1);
    if (w)
        for (size_t i = 0; i < n; i++)
            if (!isfinite(w[i]) || !(w[i] > 0))
                return conica__fail(st, CONICA_ERR_ARG, 0, i, "weight %zu is not positive",
                                    i + 1);
    conica_bspline_surface t;
    conica_bspline_surface_init(&t);
    t.knots_u = malloc(nknots_u * sizeof *t.knots_u);
    t.knots_v = malloc(nknots_v * sizeof *t.knots_v);
    t.ctrl = malloc(n * (size_t)dim * sizeof *t.ctrl);
    t.w = w ? malloc(n * sizeof *t.w) : NULL;
    if (!t.knots_u || !t.knots_v || !t.ctrl || (w && !t.w)) {
        conica_bspline_surface_free(&t);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    memcpy(t.knots_u, knots_u, nknots_u * sizeof *t.knots_u);
    memcpy(t.knots_v, knots_v, nknots_v * sizeof *t.knots_v);
    memcpy(t.ctrl, ctrl, n * (size_t)dim * sizeof *t.ctrl);
    if (w)
        memcpy(t.w, w, n * sizeof *t.w);
    t.degree_u = degree_u;
    t.degree_v = degree_v;
    t.dim = dim;
    t.nu = nu;
    t.nv = nv;
    conica_bspline_surface_free(out);
    *out = t;
    conica__ok(st);
    return CONICA_OK;
}

static double avg(const double *k, size_t j, int p)
{
    double s = 0;
    for (int i = 1; i <= p; i++)
        s += k[j + (size_t)i];
    return s / (double)p;
}

/* Homogeneous 3-D control point (i, j): a height surface becomes
 * (u*_i, v*_j, c_ij) by linear precision. */
static void net_point(const conica_bspline_surface *s, size_t i, size_t j, double *out)
{
    size_t id = i * s->nv + j;
    double wt = s->w ? s->w[id] : 1.0;
    if (s->dim == 1) {
        out[0] = avg(s->knots_u, i, s->degree_u) * wt;
        out[1] = avg(s->knots_v, j, s->degree_v) * wt;
        out[2] = s->ctrl[id] * wt;
    } else {
        for (int c = 0; c < 3; c++)
            out[c] = s->ctrl[id * 3 + (size_t)c] * wt;
    }
    out[3] = wt;
}

/* Homogeneous isocurve coefficient: direction 0 fixes u (returns the
 * coefficient j of the v-curve), direction 1 fixes v (coefficient i). */
static double iso_coef(const conica_bspline_surface *s, int fix_v, double x, size_t idx,
                       double *out)
{
    int p = fix_v ? s->degree_v : s->degree_u;
    size_t n = fix_v ? s->nv : s->nu;
    const double *k = fix_v ? s->knots_v : s->knots_u;
    size_t nk = n + (size_t)p + 1;
    double a = k[p], b = k[n];
    x = x < a ? a : (x > b ? b : x);
    size_t mu = conica__find_span(k, nk, p, x, 0);
    double d[(CONICA_BSPLINE_MAX_DEGREE + 1) * 4];
    for (size_t q = 0; q <= (size_t)p; q++) {
        size_t o = mu - (size_t)p + q;
        if (fix_v)
            net_point(s, idx, o, d + q * 4);
        else
            net_point(s, o, idx, d + q * 4);
    }
    double fl = conica__deboor(k, mu, p, x, 4, d, NULL, NULL);
    memcpy(out, d + (size_t)p * 4, 4 * sizeof *out);
    return fl;
}

conica_code conica_bspline_surface_eval(const conica_bspline_surface *s, double u, double v,
                                        double *out, conica_status *st)
{
    if (!s || !s->ctrl || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid surface or output");
    if (!isfinite(u) || !isfinite(v))
        return conica__fail(st, CONICA_ERR_NONFINITE, 0, 0, "parameter is not finite");
    int q = s->degree_v;
    const double *kv = s->knots_v;
    size_t nkv = s->nv + (size_t)q + 1;
    double va = kv[q], vb = kv[s->nv];
    v = v < va ? va : (v > vb ? vb : v);
    size_t mu = conica__find_span(kv, nkv, q, v, 0);
    double d[(CONICA_BSPLINE_MAX_DEGREE + 1) * 4];
    for (size_t j = 0; j <= (size_t)q; j++)
        iso_coef(s, 0, u, mu - (size_t)q + j, d + j * 4); /* column j at u */
    conica__deboor(kv, mu, q, v, 4, d, NULL, NULL);
    double *r = d + (size_t)q * 4;
    for (int c = 0; c < 3; c++)
        out[c] = r[c] / r[3];
    conica__ok(st);
    return CONICA_OK;
}

void conica_quadgrid_init(conica_quadgrid *g)
{
    if (g)
        memset(g, 0, sizeof *g);
}

void conica_quadgrid_free(conica_quadgrid *g)
{
    if (!g)
        return;
    free(g->u);
    free(g->v);
    free(g->xyz);
    conica_quadgrid_init(g);
}

typedef struct pset {
    double *v;
    size_t n, cap;
} pset;

static int pset_add(pset *ps, const double *x, size_t k)
{
    if (ps->n + k > ps->cap) {
        size_t nc = (ps->n + k) * 2;
        double *v = realloc(ps->v, nc * sizeof *v);
        if (!v)
            return 0;
        ps->v = v;
        ps->cap = nc;
    }
    memcpy(ps->v + ps->n, x, k * sizeof *x);
    ps->n += k;
    return 1;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y);
}

static void pset_unique(pset *ps, double range)
{
    if (ps->n == 0)
        return;
    qsort(ps->v, ps->n, sizeof *ps->v, cmp_d);
    size_t m = 1;
    for (size_t i = 1; i < ps->n; i++)
        if (ps->v[i] - ps->v[m - 1] > 1e-12 * range)
            ps->v[m++] = ps->v[i];
    ps->n = m;
}

/* Plot the isocurve (fixed u = x when fix_v == 0, else fixed v = x) with
 * the guaranteed plotter and add its parameters to ps. */
static conica_code iso_plot(const conica_bspline_surface *s, int fix_v, double x, double tol,
                            const conica_plot_settings *set, pset *ps, conica_plot_stats *stats,
                            conica_status *st)
{
    /* fix u -> a curve in v with nv coefficients, and vice versa */
    int deg = fix_v ? s->degree_u : s->degree_v;
    size_t n = fix_v ? s->nu : s->nv;
    const double *knots = fix_v ? s->knots_u : s->knots_v;
    double *ctrl = malloc(n * 3 * sizeof *ctrl), *w = malloc(n * sizeof *w);
    if (!ctrl || !w) {
        free(ctrl);
        free(w);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    int rational = s->w != NULL;
    for (size_t i = 0; i < n; i++) {
        double hp[4];
        stats->flops += iso_coef(s, fix_v, x, i, hp);
        for (int c = 0; c < 3; c++)
            ctrl[i * 3 + (size_t)c] = hp[c] / hp[3];
        w[i] = hp[3];
    }
    conica_bspline curve;
    conica_bspline_init(&curve);
    conica_code rc = conica_bspline_set(deg, 3, knots, n + (size_t)deg + 1, ctrl, n,
                                        rational ? w : NULL, &curve, st);
    free(ctrl);
    free(w);
    if (rc != CONICA_OK)
        return rc;
    conica__pieces pc = {0, NULL, NULL};
    rc = conica__pieces_make(&curve, 0, &pc, st);
    conica_bspline_free(&curve);
    if (rc != CONICA_OK)
        return rc;
    for (size_t k = 0; k < pc.count && rc == CONICA_OK; k++) {
        conica__out o;
        conica__out_init(&o, 3, set->max_points);
        double *params = NULL;
        size_t np = 0;
        rc = conica__guaranteed_piece(&pc.sp[k], tol, set, 0, &o, &params, &np, stats, st);
        if (rc == CONICA_OK && !pset_add(ps, params, np))
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        free(params);
        conica_polyline_free(&o.pl);
    }
    conica__pieces_free(&pc);
    return rc;
}

/* One isocurve's plot parameters (sorted, unique) per entry, for the
 * envelope merge. */
typedef struct psets {
    pset *v;
    size_t n, cap;
} psets;

static void psets_free(psets *S)
{
    for (size_t k = 0; k < S->n; k++)
        free(S->v[k].v);
    free(S->v);
    S->v = NULL;
    S->n = S->cap = 0;
}

/* A new empty set at the end of S; NULL when out of memory. */
static pset *psets_push(psets *S)
{
    if (S->n == S->cap) {
        size_t nc = S->cap ? 2 * S->cap : 16;
        pset *v = realloc(S->v, nc * sizeof *v);
        if (!v)
            return NULL;
        S->v = v;
        S->cap = nc;
    }
    pset *ps = &S->v[S->n++];
    ps->v = NULL;
    ps->n = ps->cap = 0;
    return ps;
}

/* Index j of the certified interval [P[j], P[j+1]] of P that holds t
 * (the last one for t at or past its end). P->n >= 2. The envelope asks
 * for s + eps: a step start that equals a point of P up to the union's
 * grain belongs to the interval that starts there. */
static size_t pset_interval(const pset *P, double t)
{
    size_t lo = 0, hi = P->n - 1; /* P[lo] <= t < P[hi] once narrowed */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (P->v[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Share of an envelope step kept at least when its end moves back onto a
 * parameter of the union. */
#define ENVELOPE_SNAP 0.9

/* The envelope of the isocurves' parameter sets S over [a, b]: from s = a,
 * the next grid parameter e is as far as every isocurve allows: no
 * certified interval of any of them that [s, e] overlaps is shorter than
 * e - s, and no distinct knot lies inside (s, e). Each grid step is thus
 * at most each isocurve's own certified step where it lies, instead of the
 * union of all their parameters, which grows with the number of
 * isocurves when their parameters do not line up (a rational sphere's
 * meridians). Returns 0 when out of memory or past cap parameters. */
static int pset_envelope(const psets *S, const double *knots, size_t nk, double a, double b,
                         size_t cap, pset *out)
{
    double range = b - a, eps = 1e-12 * range;
    /* the union of the sets: a step may end on one of its parameters */
    pset all = {NULL, 0, 0};
    for (size_t k = 0; k < S->n; k++)
        if (!pset_add(&all, S->v[k].v, S->v[k].n)) {
            free(all.v);
            return 0;
        }
    pset_unique(&all, range);
    if (!pset_add(out, &a, 1)) {
        free(all.v);
        return 0;
    }
    double s = a;
    while (s < b - eps) {
        double e = b;
        for (size_t k = 0; k < S->n; k++) {
            const pset *P = &S->v[k];
            if (P->n < 2)
                continue;
            size_t j = pset_interval(P, s + eps);
            double h = P->v[j + 1] - P->v[j];
            if (s + h < e)
                e = s + h;
        }
        /* shrink until no overlapped certified interval is shorter */
        for (int changed = 1; changed;) {
            changed = 0;
            for (size_t k = 0; k < S->n; k++) {
                const pset *P = &S->v[k];
                if (P->n < 2)
                    continue;
                for (size_t j = pset_interval(P, s + eps); j + 1 < P->n && P->v[j] < e - eps; j++) {
                    double h = P->v[j + 1] - P->v[j];
                    if (h < e - s - eps) {
                        e = s + h;
                        changed = 1;
                    }
                }
            }
        }
        for (size_t i = 0; i < nk; i++)
            if (knots[i] > s + eps && knots[i] < e - eps)
                e = knots[i];
        if (all.n >= 2) { /* end on an isocurve's parameter when that costs
                             * little of the step: aligned sets stay aligned */
            size_t j = pset_interval(&all, e + eps);
            if (all.v[j] > s + eps && all.v[j] <= e + eps &&
                all.v[j] >= s + ENVELOPE_SNAP * (e - s))
                e = all.v[j];
        }
        if (!(e > s + eps))
            e = s + eps > b ? b : s + eps; /* no step below the uniqueness grain */
        if (out->n >= cap || !pset_add(out, &e, 1)) {
            free(all.v);
            return 0;
        }
        s = e;
    }
    out->v[out->n - 1] = b;
    free(all.v);
    return 1;
}

static double surf_diag(const conica_bspline_surface *s)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < s->nu; i++)
        for (size_t j = 0; j < s->nv; j++) {
            double hp[4];
            net_point(s, i, j, hp);
            for (int c = 0; c < 3; c++) {
                double x = hp[c] / hp[3];
                lo[c] = x < lo[c] ? x : lo[c];
                hi[c] = x > hi[c] ? x : hi[c];
            }
        }
    double d2 = 0;
    for (int c = 0; c < 3; c++)
        d2 += (hi[c] - lo[c]) * (hi[c] - lo[c]);
    return sqrt(d2);
}

/* One direction's isocurves, each plotted into a set of its own (merge:
 * for the envelope) or all into `all` (the union of Section 4.1.2). */
static conica_code iso_plot_into(const conica_bspline_surface *s, int fix_v, double x, double tol,
                                 const conica_plot_settings *set, int merge, pset *all,
                                 psets *each, conica_plot_stats *stats, conica_status *st)
{
    if (!merge)
        return iso_plot(s, fix_v, x, tol, set, all, stats, st);
    pset *ps = psets_push(each);
    if (!ps)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    conica_code rc = iso_plot(s, fix_v, x, tol, set, ps, stats, st);
    if (rc == CONICA_OK)
        pset_unique(ps, fix_v ? s->knots_u[s->nu] - s->knots_u[s->degree_u]
                              : s->knots_v[s->nv] - s->knots_v[s->degree_v]);
    return rc;
}

static conica_code plot_surface(const conica_bspline_surface *s, const conica_plot_settings *set,
                                int merge, conica_quadgrid *out, conica_plot_stats *stats,
                                conica_status *st);

conica_code conica_plot_surface(const conica_bspline_surface *s, const conica_plot_settings *set,
                                conica_quadgrid *out, conica_plot_stats *stats,
                                conica_status *st)
{
    return plot_surface(s, set, 0, out, stats, st);
}

conica_code conica_plot_surface_envelope(const conica_bspline_surface *s,
                                         const conica_plot_settings *set, conica_quadgrid *out,
                                         conica_plot_stats *stats, conica_status *st)
{
    return plot_surface(s, set, 1, out, stats, st);
}

static conica_code plot_surface(const conica_bspline_surface *s, const conica_plot_settings *set,
                                int merge, conica_quadgrid *out, conica_plot_stats *stats,
                                conica_status *st)
{
    if (!s || !s->ctrl || !set || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL argument");
    if (set->method != CONICA_PLOT_GUARANTEED)
        return conica__fail(st, CONICA_ERR_UNSUPPORTED, 0, 0,
                            "surfaces are plotted with the guaranteed method only");
    if (s->dim == 1 && s->w)
        return conica__fail(st, CONICA_ERR_UNSUPPORTED, 0, 0,
                            "rational height surfaces are not supported");
    double t0 = conica__now();
    double tol = set->abs_tolerance;
    if (!(tol > 0)) {
        double rho = sqrt(set->viewport_w * set->viewport_w + set->viewport_h * set->viewport_h);
        tol = set->pixel_tolerance / rho * surf_diag(s);
    }
    if (!(tol > 0) || !isfinite(tol))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "tolerance must be positive");
    conica_plot_stats sx;
    memset(&sx, 0, sizeof sx);
    sx.tolerance = tol;
    pset vs = {NULL, 0, 0}, us = {NULL, 0, 0};
    psets each = {NULL, 0, 0};
    conica_code rc = CONICA_OK;
    const double *ku = s->knots_u, *kv = s->knots_v;
    double ua = ku[s->degree_u], ub = ku[s->nu], va = kv[s->degree_v], vb = kv[s->nv];
    /* phase 1: u = every distinct knot in the domain -> v parameters */
    for (size_t i = (size_t)s->degree_u; i <= s->nu && rc == CONICA_OK; i++) {
        if (i > (size_t)s->degree_u && ku[i] == ku[i - 1])
            continue;
        rc = iso_plot_into(s, 0, ku[i], tol, set, merge, &vs, &each, &sx, st);
    }
    if (rc == CONICA_OK && merge &&
        !pset_envelope(&each, kv + s->degree_v, s->nv - (size_t)s->degree_v + 1, va, vb,
                       set->max_points, &vs))
        rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "v grid exceeds %zu lines (max_points)",
                          set->max_points);
    psets_free(&each);
    if (rc == CONICA_OK) {
        pset_unique(&vs, vb - va);
        /* phase 2: v = every refined v parameter -> u parameters */
        for (size_t j = 0; j < vs.n && rc == CONICA_OK; j++)
            rc = iso_plot_into(s, 1, vs.v[j], tol, set, merge, &us, &each, &sx, st);
    }
    if (rc == CONICA_OK && merge &&
        !pset_envelope(&each, ku + s->degree_u, s->nu - (size_t)s->degree_u + 1, ua, ub,
                       set->max_points, &us))
        rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "u grid exceeds %zu lines (max_points)",
                          set->max_points);
    psets_free(&each);
    if (rc == CONICA_OK) {
        pset_unique(&us, ub - ua);
        if (us.n == 0 || vs.n == 0 || us.n > set->max_points / vs.n)
            rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                              "quad grid %zu x %zu exceeds %zu points (max_points)", us.n, vs.n,
                              set->max_points);
    }
    double *xyz = NULL;
    if (rc == CONICA_OK) {
        xyz = malloc(us.n * vs.n * 3 * sizeof *xyz);
        if (!xyz)
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    if (rc == CONICA_OK) {
        double fl = (double)(s->degree_u * (s->degree_u + 1) / 2) * 15.0 *
                        (double)(s->degree_v + 1) +
                    (double)(s->degree_v * (s->degree_v + 1) / 2) * 15.0;
        for (size_t i = 0; i < us.n; i++)
            for (size_t j = 0; j < vs.n; j++) {
                conica_bspline_surface_eval(s, us.v[i], vs.v[j], xyz + (i * vs.n + j) * 3, NULL);
                sx.flops += fl;
            }
        conica_quadgrid_free(out);
        out->nu = us.n;
        out->nv = vs.n;
        out->u = us.v;
        out->v = vs.v;
        out->xyz = xyz;
        sx.points = us.n * vs.n;
        sx.seconds = conica__now() - t0;
        if (stats)
            *stats = sx;
        conica__ok(st);
        return CONICA_OK;
    }
    free(xyz);
    free(us.v);
    free(vs.v);
    return rc;
}

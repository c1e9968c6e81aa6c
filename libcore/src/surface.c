/* SPDX-License-Identifier: MIT */
/* Tensor-product B-spline surfaces (Dahl 2019, §4.1): validation,
 * evaluation, and the two-phase quad-grid plot of Section 4.1.2. */
#include <float.h>
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
    rc = conica__pieces_make(&curve, 0, 0, &pc, st);
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

/* The least tolerance a surface plot takes, in units of the net's largest
 * coordinate: twice the certified grid's rounding slack (CERT_ROUND_SLACK,
 * below). A finer tolerance asks for differences the coordinates cannot
 * resolve (no bound can certify it, and the cell counts that chase it
 * overflow), so it is refused at once, as the Blender add-on's float32
 * rule (conica_path_float32_precision) refuses digits a float cannot hold. */
#define SURF_MIN_REL_TOLERANCE (128 * DBL_EPSILON)

/* Largest |coordinate| of the net's points (projected when rational). */
static double surf_max_abs(const conica_bspline_surface *s)
{
    double m = 0;
    for (size_t k = 0; k < s->nu * s->nv; k++) {
        double hp[4];
        net_point(s, k / s->nv, k % s->nv, hp);
        for (int x = 0; x < 3; x++)
            m = fmax(m, fabs(hp[x] / hp[3]));
    }
    return m;
}

/* The arguments every surface plotter checks, and the absolute tolerance
 * of the settings for s: abs_tolerance, else the pixel tolerance scaled
 * from the viewport diagonal to the net's extent; never below what the
 * coordinates resolve (SURF_MIN_REL_TOLERANCE). */
static conica_code surf_args(const conica_bspline_surface *s, const conica_plot_settings *set,
                             const conica_quadgrid *out, double *tol, conica_status *st)
{
    if (!s || !s->ctrl || !set || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL argument");
    if (s->dim == 1 && s->w)
        return conica__fail(st, CONICA_ERR_UNSUPPORTED, 0, 0,
                            "rational height surfaces are not supported");
    *tol = set->abs_tolerance;
    if (!(*tol > 0)) {
        double rho = sqrt(set->viewport_w * set->viewport_w + set->viewport_h * set->viewport_h);
        *tol = set->pixel_tolerance / rho * surf_diag(s);
    }
    if (!(*tol > 0) || !isfinite(*tol))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "tolerance must be positive");
    double floor_tol = SURF_MIN_REL_TOLERANCE * surf_max_abs(s);
    if (!(*tol >= floor_tol))
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "tolerance %g is below what the coordinates resolve: at least %g "
                            "(128 ulp of the largest coordinate, %g)",
                            *tol, floor_tol, floor_tol / SURF_MIN_REL_TOLERANCE);
    return CONICA_OK;
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
    if (set && set->method != CONICA_PLOT_GUARANTEED)
        return conica__fail(st, CONICA_ERR_UNSUPPORTED, 0, 0,
                            "surfaces are plotted with the guaranteed method only");
    double t0 = conica__now(), tol;
    conica_code rc0 = surf_args(s, set, out, &tol, st);
    if (rc0 != CONICA_OK)
        return rc0;
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

/* ------------------------------------------------- certified quad grid */

/* Each cell of conica_plot_surface_certified is split into this many
 * parameter intervals per direction for its bound: the Bézier net of a
 * sub-patch converges to the patch quadratically, so the bound's excess
 * over the true deviation falls by about 16x per doubling. */
#define CELL_SPLITS 4

/* Splits of block_bound's first, coarse look at a cell (CELL_SPLITS must
 * be a multiple): a quarter of the sub-patches, enough to pass over the
 * cells that cannot be a block's worst. */
#define COARSE_SPLITS 2

/* Relative size (to the squared corner extent) below which the turn of a
 * quad's projected corners counts as zero (a pole's collapsed edge). */
#define QUAD_FLAT_EPS 1e-12

/* Floating-point slack added to every cell bound, in units of the net's
 * largest coordinate: the blossoms, the corner points the mesh gets from
 * conica_bspline_surface_eval and the bound itself round by a few ulps. */
#define CERT_ROUND_SLACK (64 * DBL_EPSILON)

/* Share of the estimated missing cells one refinement step adds (1: all
 * that a bound falling as 1/cells^2 in that direction would need; the
 * removal pass takes back any overshoot, and on Blender's primitives the
 * grids come out the same as with single steps, 2-4x faster). */
#define CERT_JUMP 1.0

/* Cap on the refinement steps (one grid line each; max_points caps the
 * grid long before on any surface that is not degenerate). */
#define CERT_MAX_ROUNDS 100000

/* Blossom of the degree-p B-spline coefficients d (p+1 points of hd
 * values, overwritten) on span mu at the arguments t[0..p): the de Boor
 * triangle (eq. (1.11)) with argument t[r-1] at level r. With every
 * argument equal it is the point at that parameter; with p - k arguments
 * a and k arguments b it is the Bézier coefficient k of the span's piece
 * restricted to [a, b]. The result is left in d + p*hd. */
static void blossom(const double *knots, size_t mu, int p, const double *t, int hd, double *d)
{
    for (int r = 1; r <= p; r++)
        for (int j = p; j >= r; j--) {
            size_t i = mu - (size_t)p + (size_t)j;
            double a = (t[r - 1] - knots[i]) / (knots[i + (size_t)(p + 1 - r)] - knots[i]);
            for (int c = 0; c < hd; c++)
                d[j * hd + c] = (1 - a) * d[(j - 1) * hd + c] + a * d[j * hd + c];
        }
}

/* Work space of one block (a knot span in u times one in v). */
typedef struct cert_block {
    const conica_bspline_surface *s;
    int p, q;
    size_t mu, mv;    /* spans */
    double *net;      /* (p+1)(q+1) homogeneous points of the span pair */
    double *row;      /* (p+1)(q+1) x 4: u-blossoms per net column */
    double *rows;     /* CELL_SPLITS such row sets: a cell column's (cell_rows) */
    double *rows2;    /* COARSE_SPLITS such row sets */
    double *fu, *fv;  /* subpatch_bound's degree-elevation factors, (p+2) x 2, (q+2) x 2 */
    double *h;        /* (p+1)(q+1) x 4: the sub-patch's Bézier net */
    double *tmp;      /* max(p,q)+1 x 4 */
    double *args;     /* max(p,q) */
    double slack;     /* CERT_ROUND_SLACK times the largest coordinate */
    double flops;
} cert_block;

/* The u half of a sub-patch's net: row k, column j is the blossom in u
 * at a0 (p - k times) and a1 (k times) of the block's net column j. */
static void subpatch_rows(cert_block *B, double a0, double a1, int kmax, double *row)
{
    int p = B->p, q = B->q;
    for (int k = 0; k <= kmax; k++) {
        for (int r = 0; r < p; r++)
            B->args[r] = r < p - k ? a0 : a1;
        for (int j = 0; j <= q; j++) {
            for (int i = 0; i <= p; i++)
                memcpy(B->tmp + i * 4, B->net + ((size_t)i * (size_t)(q + 1) + (size_t)j) * 4,
                       4 * sizeof(double));
            blossom(B->s->knots_u, B->mu, p, B->args, 4, B->tmp);
            memcpy(row + ((size_t)k * (size_t)(q + 1) + (size_t)j) * 4, B->tmp + p * 4,
                   4 * sizeof(double));
        }
    }
    B->flops += (double)((kmax + 1) * (q + 1)) * (double)(p * (p + 1)) * 6.0;
}

/* The v half: the homogeneous Bézier net h of the sub-patch [a0,a1] x
 * [b0,b1] from the rows `row` of subpatch_rows(a0, a1), rows 0..kmax and
 * columns 0..lmax. */
static void subpatch_cols(cert_block *B, const double *row, double b0, double b1, int kmax,
                          int lmax)
{
    int q = B->q;
    for (int l = 0; l <= lmax; l++) {
        for (int r = 0; r < q; r++)
            B->args[r] = r < q - l ? b0 : b1;
        for (int k = 0; k <= kmax; k++) {
            memcpy(B->tmp, row + (size_t)k * (size_t)(q + 1) * 4,
                   (size_t)(q + 1) * 4 * sizeof(double));
            blossom(B->s->knots_v, B->mv, q, B->args, 4, B->tmp);
            memcpy(B->h + ((size_t)k * (size_t)(q + 1) + (size_t)l) * 4, B->tmp + q * 4,
                   4 * sizeof(double));
        }
    }
    B->flops += (double)((kmax + 1) * (lmax + 1)) * (double)(q * (q + 1)) * 6.0;
}

/* Bound of |S - Q| on a sub-patch, S the (rational) surface with
 * homogeneous Bézier net h of degree (p, q), Q the bilinear map with
 * values c[a][b] (3 values each) at the sub-patch's corners. With W the
 * weight function, S - Q = (H - W Q) / W; H - W Q and W written in the
 * Bernstein basis of degree (p+1, q+1) (H degree-elevated, W Q by the
 * product rule B^p_i B^1_a = C(p,i) C(1,a) / C(p+1,i+a) B^{p+1}_{i+a},
 * which gives the same factors) have coefficients D_KL and W_KL > 0, so
 * |S - Q| <= max |D_KL| / W_KL by the convex hull property. */
static double subpatch_bound(const cert_block *B, double c[2][2][3])
{
    const double *h = B->h;
    int p = B->p, q = B->q;
    double worst2 = 0;
    for (int K = 0; K <= p + 1; K++)
        for (int L = 0; L <= q + 1; L++) {
            double D[3] = {0, 0, 0}, W = 0;
            for (int a = 0; a <= 1; a++) {
                int i = K - a;
                if (i < 0 || i > p)
                    continue;
                double fa = B->fu[2 * K + a];
                for (int b = 0; b <= 1; b++) {
                    int j = L - b;
                    if (j < 0 || j > q)
                        continue;
                    double f = fa * B->fv[2 * L + b];
                    const double *hp = h + ((size_t)i * (size_t)(q + 1) + (size_t)j) * 4;
                    for (int x = 0; x < 3; x++)
                        D[x] += f * (hp[x] - hp[3] * c[a][b][x]);
                    W += f * hp[3];
                }
            }
            /* |D| / W > sqrt(worst2), without a root or a division when not */
            double dd = D[0] * D[0] + D[1] * D[1] + D[2] * D[2];
            if (dd > worst2 * (W * W))
                worst2 = dd / (W * W);
        }
    return sqrt(worst2);
}

static void sub3(const double *a, const double *b, double *r)
{
    for (int x = 0; x < 3; x++)
        r[x] = a[x] - b[x];
}

static void cross3(const double *a, const double *b, double *r)
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Largest distance between the bilinear quad with corners c[a][b] and
 * either of its triangulations (both ways, Hausdorff). Parametrically the
 * difference is s t T (or a like product) with T = c00 - c10 - c01 + c11,
 * so |T| / 4. Geometrically: with n the unit normal of both diagonals,
 * the quad's convex hull (a tetrahedron, which holds the bilinear quad)
 * lies in a slab of width d = |(c10 - c00) . n| whose two faces hold one
 * diagonal each; when the corners projected along n form a convex
 * quadrilateral, each triangulation covers that projection, so a line
 * along n through a point of the hull meets both triangulations and the
 * bilinear quad (its projection is the 2-D bilinear map of a convex
 * quadrilateral, onto it) within the slab: every such point is within d
 * of each of them. A planar quad (a surface of revolution's) gives 0. */
static double quad_term(double c[2][2][3])
{
    double T[3], e[4][3], d1[3], d2[3], n[3];
    for (int x = 0; x < 3; x++)
        T[x] = c[0][0][x] - c[1][0][x] - c[0][1][x] + c[1][1][x];
    double best = 0.25 * sqrt(dot3(T, T));
    const double *P[4] = {c[0][0], c[1][0], c[1][1], c[0][1]}; /* around the quad */
    sub3(c[1][1], c[0][0], d1);
    sub3(c[0][1], c[1][0], d2);
    cross3(d1, d2, n);
    double nn = sqrt(dot3(n, n)), ext = dot3(d1, d1) + dot3(d2, d2);
    if (!(nn > QUAD_FLAT_EPS * ext))
        return best;
    for (int x = 0; x < 3; x++)
        n[x] /= nn;
    for (int k = 0; k < 4; k++)
        sub3(P[(k + 1) % 4], P[k], e[k]);
    int pos = 0, neg = 0;
    for (int k = 0; k < 4; k++) {
        double z[3];
        cross3(e[k], e[(k + 1) % 4], z);
        double t = dot3(z, n);
        pos += t > QUAD_FLAT_EPS * ext;
        neg += t < -QUAD_FLAT_EPS * ext;
    }
    if (pos && neg) /* a reflex corner in projection: the slab does not apply */
        return best;
    if (!pos && !neg)
        return best;
    double d = fabs(dot3(e[0], n));
    return d < best ? d : best;
}

/* Point of the surface at (u, v) in the block's spans (the blossom with
 * every argument equal), 3 values. */
static void block_point(cert_block *B, double u, double v, double *out)
{
    subpatch_rows(B, u, u, 0, B->row);
    subpatch_cols(B, B->row, v, v, 0, 0);
    const double *h = B->h;
    for (int x = 0; x < 3; x++)
        out[x] = h[x] / h[3];
}

/* The u halves of the `splits` sub-patch columns of the cell column
 * [u0,u1] (subpatch_rows of each u sub-interval), into rows: every cell
 * of that column shares them. */
static void cell_rows(cert_block *B, double u0, double u1, int splits, double *rows)
{
    size_t np4 = (size_t)(B->p + 1) * (size_t)(B->q + 1) * 4;
    for (int a = 0; a < splits; a++) {
        double s0 = (double)a / splits, s1 = (double)(a + 1) / splits;
        subpatch_rows(B, u0 + s0 * (u1 - u0), u0 + s1 * (u1 - u0), B->p,
                      rows + (size_t)a * np4);
    }
}

/* The surface's corner points of the cell [u0,u1] x [v0,v1]. */
static void cell_corners(cert_block *B, double u0, double u1, double v0, double v1,
                         double C[2][2][3])
{
    block_point(B, u0, v0, C[0][0]);
    block_point(B, u1, v0, C[1][0]);
    block_point(B, u0, v1, C[0][1]);
    block_point(B, u1, v1, C[1][1]);
}

/* Largest sub-patch bound of the cell [v0,v1] of a cell column whose
 * rows (cell_rows with the same splits) are given, over splits^2
 * sub-patches, against the bilinear quad through the corners C. */
static double cell_subpatches(cert_block *B, const double *rows, int splits, double v0,
                              double v1, double C[2][2][3])
{
    size_t np4 = (size_t)(B->p + 1) * (size_t)(B->q + 1) * 4;
    double worst = 0;
    for (int a = 0; a < splits; a++) {
        double s0 = (double)a / splits, s1 = (double)(a + 1) / splits;
        for (int b = 0; b < splits; b++) {
            double t0 = (double)b / splits, t1 = (double)(b + 1) / splits;
            double c[2][2][3];
            for (int x = 0; x < 3; x++)
                for (int ia = 0; ia <= 1; ia++)
                    for (int ib = 0; ib <= 1; ib++) {
                        double sl = ia ? s1 : s0, tl = ib ? t1 : t0;
                        c[ia][ib][x] = (1 - sl) * (1 - tl) * C[0][0][x] +
                                       sl * (1 - tl) * C[1][0][x] + (1 - sl) * tl * C[0][1][x] +
                                       sl * tl * C[1][1][x];
                    }
            subpatch_cols(B, rows + (size_t)a * np4, v0 + t0 * (v1 - v0),
                          v0 + t1 * (v1 - v0), B->p, B->q);
            double d = subpatch_bound(B, c);
            worst = d > worst ? d : worst;
        }
    }
    return worst;
}

/* Bound of the cell [u0,u1] x [v0,v1] of the block: its bilinear quad
 * through the surface's corner points against the surface, over
 * CELL_SPLITS^2 sub-patches, plus the quad's triangulation term.
 * cell_rows(B, u0, u1, CELL_SPLITS, B->rows) must have filled B->rows. */
static double cell_bound(cert_block *B, double u0, double u1, double v0, double v1)
{
    double C[2][2][3];
    cell_corners(B, u0, u1, v0, v1, C);
    return cell_subpatches(B, B->rows, CELL_SPLITS, v0, v1, C) + quad_term(C) + B->slack;
}

/* Distinct knots of the domain knots[p..n]: their count, written to out
 * (room for n - p + 1) with the span index mu of each but the last. */
static size_t breakpoints(const double *knots, int p, size_t n, double *out, size_t *mu)
{
    size_t m = 0;
    for (size_t i = (size_t)p; i <= n; i++) {
        if (m > 0 && knots[i] == out[m - 1]) {
            mu[m - 1] = i; /* the last index of a repeated knot starts the span */
            continue;
        }
        out[m] = knots[i];
        mu[m] = i;
        m++;
    }
    return m;
}

typedef struct cert_grid {
    cert_block B;
    size_t nsu, nsv;       /* spans per direction */
    double *bu, *bv;       /* breakpoints, nsu + 1 and nsv + 1 */
    size_t *mu, *mv;       /* span index per span */
    size_t *cu, *cv;       /* cells per span */
    double *bb;            /* bound per block, i * nsv + j */
    double *wc;            /* centre (u, v) of each block's worst cell */
} cert_grid;

/* Load block (i, j)'s net into G->B. */
static void block_load(cert_grid *G, size_t i, size_t j)
{
    cert_block *B = &G->B;
    const conica_bspline_surface *s = B->s;
    B->mu = G->mu[i];
    B->mv = G->mv[j];
    for (int a = 0; a <= B->p; a++)
        for (int b = 0; b <= B->q; b++)
            net_point(s, B->mu - (size_t)B->p + (size_t)a, B->mv - (size_t)B->q + (size_t)b,
                      B->net + ((size_t)a * (size_t)(B->q + 1) + (size_t)b) * 4);
}

/* Parameter interval of cell a of the n equal cells of [lo, hi]. */
static void cell_range(double lo, double hi, size_t n, size_t a, double *c0, double *c1)
{
    double d = (hi - lo) / (double)n;
    *c0 = lo + (double)a * d;
    *c1 = a + 1 == n ? hi : *c0 + d;
}

/* Largest cell bound of block (i, j) with cu x cv equal cells; the first
 * one above limit once there is one. wc (may be NULL) receives the centre
 * (u, v) of the worst cell. hint (may be NULL): a point (u, v) whose cell
 * is bounded first; a cell whose coarse bound (COARSE_SPLITS^2
 * sub-patches, never below its CELL_SPLITS^2 bound: the finer nets are
 * subdivisions of the coarser ones, and |sum l D| / sum l W <= max |D| / W)
 * stays below that one by more than the rounding slack cannot be the worst
 * and is not bounded finely. The result and wc are those of bounding every
 * cell: only cells below the maximum are skipped. */
static double block_bound(cert_grid *G, size_t i, size_t j, size_t cu, size_t cv, double limit,
                          double *wc, const double *hint)
{
    cert_block *B = &G->B;
    block_load(G, i, j);
    double lu = G->bu[i], hu = G->bu[i + 1], lv = G->bv[j], hv = G->bv[j + 1];
    double T = 0;
    if (hint && hint[0] >= lu && hint[0] <= hu && hint[1] >= lv && hint[1] <= hv) {
        size_t a = (size_t)((hint[0] - lu) / (hu - lu) * (double)cu);
        size_t b = (size_t)((hint[1] - lv) / (hv - lv) * (double)cv);
        double ua, ub, va, vb;
        a = a < cu ? a : cu - 1;
        b = b < cv ? b : cv - 1;
        cell_range(lu, hu, cu, a, &ua, &ub);
        cell_range(lv, hv, cv, b, &va, &vb);
        cell_rows(B, ua, ub, CELL_SPLITS, B->rows);
        T = cell_bound(B, ua, ub, va, vb);
        if (T > limit)
            return T; /* the block's bound is at least that */
    }
    double worst = 0;
    int first = 1;
    for (size_t a = 0; a < cu; a++) {
        double ua, ub;
        cell_range(lu, hu, cu, a, &ua, &ub);
        int fine_rows = 0;
        if (T > 0)
            cell_rows(B, ua, ub, COARSE_SPLITS, B->rows2);
        for (size_t b = 0; b < cv; b++) {
            double va, vb, C[2][2][3];
            cell_range(lv, hv, cv, b, &va, &vb);
            cell_corners(B, ua, ub, va, vb, C);
            double extra = quad_term(C) + B->slack;
            if (T > 0 &&
                cell_subpatches(B, B->rows2, COARSE_SPLITS, va, vb, C) + extra + B->slack < T)
                continue;
            if (!fine_rows) {
                cell_rows(B, ua, ub, CELL_SPLITS, B->rows);
                fine_rows = 1;
            }
            double d = cell_subpatches(B, B->rows, CELL_SPLITS, va, vb, C) + extra;
            if (d > worst || first) {
                worst = d;
                first = 0;
                if (wc) {
                    wc[0] = 0.5 * (ua + ub);
                    wc[1] = 0.5 * (va + vb);
                }
            }
            if (worst > limit)
                return worst;
        }
    }
    return worst;
}

/* Bound of the cell of block (i, j), cut into cu x cv equal cells, that
 * holds the point (u, v). */
static double cell_at(cert_grid *G, size_t i, size_t j, size_t cu, size_t cv, double u, double v)
{
    double lu = G->bu[i], hu = G->bu[i + 1], lv = G->bv[j], hv = G->bv[j + 1];
    size_t a = (size_t)((u - lu) / (hu - lu) * (double)cu), b = (size_t)((v - lv) / (hv - lv) * (double)cv);
    double ua, ub, va, vb;
    a = a < cu ? a : cu - 1;
    b = b < cv ? b : cv - 1;
    cell_range(lu, hu, cu, a, &ua, &ub);
    cell_range(lv, hv, cv, b, &va, &vb);
    block_load(G, i, j);
    cell_rows(&G->B, ua, ub, CELL_SPLITS, G->B.rows);
    return cell_bound(&G->B, ua, ub, va, vb);
}

static void column_bounds(cert_grid *G, size_t i)
{
    for (size_t j = 0; j < G->nsv; j++)
        G->bb[i * G->nsv + j] =
            block_bound(G, i, j, G->cu[i], G->cv[j], INFINITY, G->wc + 2 * (i * G->nsv + j),
                        G->wc + 2 * (i * G->nsv + j));
}

static void row_bounds(cert_grid *G, size_t j)
{
    for (size_t i = 0; i < G->nsu; i++)
        G->bb[i * G->nsv + j] =
            block_bound(G, i, j, G->cu[i], G->cv[j], INFINITY, G->wc + 2 * (i * G->nsv + j),
                        G->wc + 2 * (i * G->nsv + j));
}

static size_t sum_sz(const size_t *c, size_t n)
{
    size_t t = 0;
    for (size_t k = 0; k < n; k++)
        t += c[k];
    return t;
}

/* Drop one cell from span k of direction dir (0: u) when every block of
 * that column or row still passes; returns 1 when it did. */
static int cert_try_drop(cert_grid *G, int dir, size_t k, double tol)
{
    size_t *c = dir ? G->cv : G->cu;
    if (c[k] < 2)
        return 0;
    size_t other = dir ? G->nsu : G->nsv;
    double *nb = malloc(3 * other * sizeof *nb), *nc = nb + other;
    if (!nb)
        return 0;
    int ok = 1;
    for (size_t m = 0; m < other && ok; m++) {
        size_t i = dir ? m : k, j = dir ? k : m;
        nb[m] = block_bound(G, i, j, dir ? G->cu[i] : G->cu[i] - 1, dir ? G->cv[j] - 1 : G->cv[j],
                            tol, nc + 2 * m, G->wc + 2 * (i * G->nsv + j));
        ok = nb[m] <= tol;
    }
    if (ok) {
        c[k]--;
        for (size_t m = 0; m < other; m++) {
            size_t at = dir ? m * G->nsv + k : k * G->nsv + m;
            G->bb[at] = nb[m];
            memcpy(G->wc + 2 * at, nc + 2 * m, 2 * sizeof *nc);
        }
    }
    free(nb);
    return ok;
}

static void cert_grid_free(cert_grid *G)
{
    free(G->B.net);
    free(G->B.row);
    free(G->B.rows);
    free(G->B.rows2);
    free(G->B.fu);
    free(G->B.h);
    free(G->B.tmp);
    free(G->B.args);
    free(G->bu);
    free(G->bv);
    free(G->mu);
    free(G->mv);
    free(G->cu);
    free(G->cv);
    free(G->bb);
    free(G->wc);
}

/* nu x nv grid points within max (the product checked, never wrapped). */
static int grid_fits(size_t nu, size_t nv, size_t max)
{
    size_t n;
    return !conica__mul_size(nu, nv, &n) && n <= max;
}

conica_code conica_plot_surface_certified(const conica_bspline_surface *s,
                                          const conica_plot_settings *set, conica_quadgrid *out,
                                          conica_plot_stats *stats, conica_status *st)
{
    double t0 = conica__now(), tol;
    conica_code rc0 = surf_args(s, set, out, &tol, st);
    if (rc0 != CONICA_OK)
        return rc0;
    int p = s->degree_u, q = s->degree_v, pq = p > q ? p : q;
    size_t np = (size_t)(p + 1) * (size_t)(q + 1);
    cert_grid G;
    memset(&G, 0, sizeof G);
    G.B.s = s;
    G.B.p = p;
    G.B.q = q;
    G.B.slack = CERT_ROUND_SLACK * surf_max_abs(s);
    G.B.net = malloc(np * 4 * sizeof(double));
    G.B.row = malloc(np * 4 * sizeof(double));
    G.B.h = malloc(np * 4 * sizeof(double));
    G.B.rows = malloc(CELL_SPLITS * np * 4 * sizeof(double));
    G.B.rows2 = malloc(COARSE_SPLITS * np * 4 * sizeof(double));
    G.B.fu = malloc((size_t)(2 * (p + 2) + 2 * (q + 2)) * sizeof(double));
    if (G.B.fu) {
        /* B^p_i B^1_a = C(p,i) C(1,a) / C(p+1,i+a) B^{p+1}_{i+a}: K = i + a */
        G.B.fv = G.B.fu + 2 * (p + 2);
        for (int K = 0; K <= p + 1; K++) {
            G.B.fu[2 * K] = (double)(p + 1 - K) / (p + 1);
            G.B.fu[2 * K + 1] = (double)K / (p + 1);
        }
        for (int L = 0; L <= q + 1; L++) {
            G.B.fv[2 * L] = (double)(q + 1 - L) / (q + 1);
            G.B.fv[2 * L + 1] = (double)L / (q + 1);
        }
    }
    G.B.tmp = malloc((size_t)(pq + 1) * 4 * sizeof(double));
    G.B.args = malloc((size_t)(pq + 1) * sizeof(double));
    size_t mxu = s->nu - (size_t)p + 1, mxv = s->nv - (size_t)q + 1;
    G.bu = malloc(mxu * sizeof *G.bu);
    G.bv = malloc(mxv * sizeof *G.bv);
    G.mu = malloc(mxu * sizeof *G.mu);
    G.mv = malloc(mxv * sizeof *G.mv);
    G.cu = malloc(mxu * sizeof *G.cu);
    G.cv = malloc(mxv * sizeof *G.cv);
    G.bb = malloc(mxu * mxv * sizeof *G.bb);
    G.wc = calloc(2 * mxu * mxv, sizeof *G.wc); /* block_bound's first hints */
    if (!G.B.net || !G.B.row || !G.B.rows || !G.B.rows2 || !G.B.fu || !G.B.h || !G.B.tmp || !G.B.args || !G.bu || !G.bv || !G.mu ||
        !G.mv || !G.cu || !G.cv || !G.bb || !G.wc) {
        cert_grid_free(&G);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    G.nsu = breakpoints(s->knots_u, p, s->nu, G.bu, G.mu) - 1;
    G.nsv = breakpoints(s->knots_v, q, s->nv, G.bv, G.mv) - 1;
    if ((G.nsu + 1) * (G.nsv + 1) > set->max_points) {
        cert_grid_free(&G);
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "quad grid of the knots %zu x %zu exceeds %zu points (max_points)",
                            G.nsu + 1, G.nsv + 1, set->max_points);
    }
    for (size_t i = 0; i < G.nsu; i++)
        G.cu[i] = 1;
    for (size_t j = 0; j < G.nsv; j++)
        G.cv[j] = 1;
    for (size_t i = 0; i < G.nsu; i++)
        column_bounds(&G, i);
    /* refine: the worst block gets one more cell in the direction that
     * lowers its bound most per vertex added (a u line costs a vertex on
     * every v line and vice versa) */
    conica_code rc = CONICA_OK;
    size_t rounds = 0;
    for (;; rounds++) {
        size_t wi = 0, wj = 0;
        double wb = 0;
        for (size_t k = 0; k < G.nsu * G.nsv; k++)
            if (G.bb[k] > wb) {
                wb = G.bb[k];
                wi = k / G.nsv;
                wj = k % G.nsv;
            }
        if (!(wb > tol))
            break;
        size_t nlu = sum_sz(G.cu, G.nsu) + 1, nlv = sum_sz(G.cv, G.nsv) + 1;
        if (rounds >= CERT_MAX_ROUNDS || !grid_fits(nlu + 1, nlv, set->max_points) ||
            !grid_fits(nlu, nlv + 1, set->max_points)) {
            /* the count that would meet the tolerance, predicted from the
             * worst bound: it falls as 1/cells^2 per direction, so both
             * directions need sqrt(wb / tol) times the lines */
            double need = (double)nlu * (double)nlv * (wb / tol);
            rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                              "quad grid %zu x %zu within %g exceeds %zu points (max_points); "
                              "about %.3g points would meet the tolerance",
                              nlu, nlv, tol, set->max_points, need);
            break;
        }
        /* the gain of a cell more either way, judged on the worst cell
         * (the cell of the finer grid that holds its centre) */
        const double *c = G.wc + 2 * (wi * G.nsv + wj);
        double bu = cell_at(&G, wi, wj, G.cu[wi] + 1, G.cv[wj], c[0], c[1]);
        double bv = cell_at(&G, wi, wj, G.cu[wi], G.cv[wj] + 1, c[0], c[1]);
        double gu = (wb - bu) / (double)nlv, gv = (wb - bv) / (double)nlu;
        /* far from the tolerance, several cells at once (CERT_JUMP) */
        double jump = CERT_JUMP * (sqrt(wb / tol) - 1);
        if (gu > gv || (gu == gv && bu <= bv)) {
            size_t k = conica__size_clamp(jump * (double)G.cu[wi], set->max_points);
            k = k < 1 ? 1 : k;
            while (k > 1 && !grid_fits(nlu + k, nlv, set->max_points))
                k /= 2;
            G.cu[wi] += k;
            column_bounds(&G, wi);
        } else {
            size_t k = conica__size_clamp(jump * (double)G.cv[wj], set->max_points);
            k = k < 1 ? 1 : k;
            while (k > 1 && !grid_fits(nlu, nlv + k, set->max_points))
                k /= 2;
            G.cv[wj] += k;
            row_bounds(&G, wj);
        }
    }
    /* greedy removal: a cell fewer wherever its column or row still passes */
    for (int changed = rc == CONICA_OK; changed;) {
        changed = 0;
        for (size_t i = 0; i < G.nsu; i++)
            changed |= cert_try_drop(&G, 0, i, tol);
        for (size_t j = 0; j < G.nsv; j++)
            changed |= cert_try_drop(&G, 1, j, tol);
    }
    conica_quadgrid g;
    conica_quadgrid_init(&g);
    if (rc == CONICA_OK) {
        g.nu = sum_sz(G.cu, G.nsu) + 1;
        g.nv = sum_sz(G.cv, G.nsv) + 1;
        g.u = malloc(g.nu * sizeof *g.u);
        g.v = malloc(g.nv * sizeof *g.v);
        g.xyz = malloc(g.nu * g.nv * 3 * sizeof *g.xyz);
        if (!g.u || !g.v || !g.xyz)
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    if (rc == CONICA_OK) {
        size_t m = 0;
        for (size_t i = 0; i < G.nsu; i++)
            for (size_t a = 0; a < G.cu[i]; a++)
                g.u[m++] = G.bu[i] + (double)a * (G.bu[i + 1] - G.bu[i]) / (double)G.cu[i];
        g.u[m] = G.bu[G.nsu];
        m = 0;
        for (size_t j = 0; j < G.nsv; j++)
            for (size_t b = 0; b < G.cv[j]; b++)
                g.v[m++] = G.bv[j] + (double)b * (G.bv[j + 1] - G.bv[j]) / (double)G.cv[j];
        g.v[m] = G.bv[G.nsv];
        for (size_t i = 0; i < g.nu; i++)
            for (size_t j = 0; j < g.nv; j++)
                conica_bspline_surface_eval(s, g.u[i], g.v[j], g.xyz + (i * g.nv + j) * 3, NULL);
        double worst = 0;
        for (size_t k = 0; k < G.nsu * G.nsv; k++)
            worst = G.bb[k] > worst ? G.bb[k] : worst;
        conica_quadgrid_free(out);
        *out = g;
        if (stats) {
            memset(stats, 0, sizeof *stats);
            stats->points = g.nu * g.nv;
            stats->flops = G.B.flops;
            stats->iterations = rounds;
            stats->tolerance = tol;
            stats->bound = worst;
            stats->seconds = conica__now() - t0;
        }
        conica__ok(st);
    } else {
        conica_quadgrid_free(&g);
    }
    cert_grid_free(&G);
    return rc;
}

/* SPDX-License-Identifier: MIT */
/* Plotter front end: settings, names, polylines, the preprocessing of
 * Section 1.1.2 (clamp to the domain, split at knots of multiplicity >= p
 * into continuous pieces), dispatch to the methods, and a dense-sampling
 * deviation measure for tests and benchmarks. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bspline_internal.h"
#include "internal.h"
#include "plot_internal.h"

conica_plot_settings conica_plot_defaults(void)
{
    conica_plot_settings s;
    memset(&s, 0, sizeof s);
    s.method = CONICA_PLOT_GUARANTEED;
    s.abs_tolerance = 0.0;
    s.pixel_tolerance = CONICA_PLOT_DEFAULT_PIXEL_TOLERANCE;
    s.viewport_w = 1000.0;
    s.viewport_h = 1000.0;
    s.criterion = CONICA_CRIT_LENGTH_RATIO;
    s.rule = CONICA_RULE_MIDPOINT;
    s.rule_ratio = 0.5;
    s.stop = CONICA_STOP_MOVEMENT;
    s.threshold = 0.0;
    s.skip = 1;
    s.consec = 5;
    s.knot_budget = CONICA_PLOT_DEFAULT_KNOT_BUDGET;
    s.prephase_knots = 0;
    s.output = CONICA_OUTPUT_CONTROL_POLYGON;
    s.points = CONICA_PLOT_DEFAULT_UNIFORM_POINTS;
    s.local_min_points = 2;
    s.local_weight = CONICA_LOCAL_BOTH;
    s.local_omega = 0.5;
    s.math_initial_points = 50;
    s.math_angle = 5.0 * 3.14159265358979323846 / 180.0;
    s.math_max_recursion = 6;
    s.max_points = CONICA_PLOT_MAX_POINTS_DEFAULT;
    s.max_knots = CONICA_PLOT_MAX_KNOTS_DEFAULT;
    s.max_iterations = CONICA_PLOT_MAX_ITERATIONS_DEFAULT;
    return s;
}

static const char *const method_names[CONICA_PLOT_METHOD_COUNT_] = {
    "guaranteed", "adaptive", "uniform", "local-uniform", "chaikin", "lane-riesenfeld",
    "mathematica"};
static const char *const crit_names[CONICA_CRIT_COUNT_] = {
    "simplified-length", "length", "length-ratio", "simplified-angle", "angle", "base-line",
    "extended-base-line"};
static const char *const rule_names[CONICA_RULE_COUNT_] = {"midpoint", "knot-average",
                                                           "chaikin"};

const char *conica_plot_method_name(conica_plot_method m)
{
    return (unsigned)m < CONICA_PLOT_METHOD_COUNT_ ? method_names[m] : NULL;
}
const char *conica_plot_criterion_name(conica_plot_criterion c)
{
    return (unsigned)c < CONICA_CRIT_COUNT_ ? crit_names[c] : NULL;
}
const char *conica_plot_rule_name(conica_plot_rule r)
{
    return (unsigned)r < CONICA_RULE_COUNT_ ? rule_names[r] : NULL;
}

static int lookup(const char *const *names, int count, const char *name)
{
    if (!name)
        return -1;
    for (int i = 0; i < count; i++)
        if (strcmp(names[i], name) == 0)
            return i;
    return -1;
}
int conica_plot_method_from_name(const char *name)
{
    return lookup(method_names, CONICA_PLOT_METHOD_COUNT_, name);
}
int conica_plot_criterion_from_name(const char *name)
{
    return lookup(crit_names, CONICA_CRIT_COUNT_, name);
}
int conica_plot_rule_from_name(const char *name)
{
    return lookup(rule_names, CONICA_RULE_COUNT_, name);
}

void conica_polyline_init(conica_polyline *p)
{
    if (!p)
        return;
    memset(p, 0, sizeof *p);
}

void conica_polyline_free(conica_polyline *p)
{
    if (!p)
        return;
    free(p->xy);
    free(p->piece_start);
    free(p->t);
    conica_polyline_init(p);
}

double conica__now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ------------------------------------------------------------ output */

void conica__out_init(conica__out *o, int dim, size_t max_points)
{
    conica_polyline_init(&o->pl);
    o->pl.dim = dim;
    o->max_points = max_points;
    o->fixed = 0;
}

conica_code conica__out_piece(conica__out *o, conica_status *st)
{
    size_t *ps = realloc(o->pl.piece_start, (o->pl.npieces + 1) * sizeof *ps);
    if (!ps)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    o->pl.piece_start = ps;
    ps[o->pl.npieces++] = o->pl.n;
    return CONICA_OK;
}

conica_code conica__out_grow(conica__out *o, const double *pt, double t, conica_status *st)
{
    if (o->pl.n >= o->max_points)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "plot needs more than %zu points (max_points / --max-points)",
                            o->max_points);
    size_t d = (size_t)o->pl.dim;
    if (!o->fixed && o->pl.n == o->pl.cap) {
        size_t nc = o->pl.cap ? 2 * o->pl.cap : 256;
        if (nc > o->max_points)
            nc = o->max_points;
        double *xy = realloc(o->pl.xy, nc * d * sizeof *xy);
        if (!xy)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        o->pl.xy = xy;
        double *tt = realloc(o->pl.t, nc * sizeof *tt);
        if (!tt)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        o->pl.t = tt;
        o->pl.cap = nc;
    }
    memcpy(o->pl.xy + o->pl.n * d, pt, d * sizeof *pt);
    if (o->pl.t)
        o->pl.t[o->pl.n] = t;
    o->pl.n++;
    return CONICA_OK;
}

void conica__plot_point(const conica_bspline *s, double t, double *out)
{
    /* An evaluation that fails (a parameter the knot vector cannot place,
     * e.g. knots near DBL_MAX whose differences overflow) yields NaN, never
     * the caller's uninitialised buffer: conica_plot() refuses any
     * non-finite point with CONICA_ERR_NUMERIC. */
    if (s->dim == 1) {
        double v;
        if (conica_bspline_eval(s, t, &v, NULL) != CONICA_OK)
            v = NAN;
        out[0] = t;
        out[1] = v;
    } else if (conica_bspline_eval(s, t, out, NULL) != CONICA_OK) {
        for (int i = 0; i < s->dim; i++)
            out[i] = NAN;
    }
}

/* ------------------------------------------------------------ pieces */

void conica__pieces_free(conica__pieces *pc)
{
    if (!pc)
        return;
    for (size_t k = 0; k < pc->count; k++)
        conica_bspline_free(&pc->sp[k]);
    free(pc->sp);
    free(pc->joined);
    pc->sp = NULL;
    pc->joined = NULL;
    pc->count = 0;
}

/* Function -> planar graph curve with control points (t*_j, c_j). */
static conica_code to_graph(conica_bspline *s, conica_status *st)
{
    double *c = malloc(s->n * 2 * sizeof *c);
    if (!c)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    conica_bspline_control_polygon(s, c);
    free(s->ctrl);
    s->ctrl = c;
    s->dim = 2;
    return CONICA_OK;
}

static void proj_point(const conica_bspline *s, size_t i, double *out)
{
    for (int c = 0; c < s->dim; c++)
        out[c] = s->ctrl[i * (size_t)s->dim + (size_t)c];
}

/* A join at knot run start i (multiplicity p) where the tangent turns by
 * less than this angle, in radians, counts as tangent-continuous. */
#define CONICA__G1_SIN 1e-9

/* Whether the clamped curve is tangent-continuous (G1) at the knot of
 * multiplicity p starting at index i: the curve point there is control
 * point i - 1, the one-sided tangents point along P_{i-1} - P_{i-2} and
 * P_i - P_{i-1} (Böhm's end-tangent property of the restricted pieces;
 * for a rational spline the same differences of the projected points). */
static int g1_join(const conica_bspline *s, size_t i)
{
    size_t d = (size_t)s->dim;
    const double *a = s->ctrl + (i - 2) * d, *b = a + d, *c = b + d;
    double l2 = 0, r2 = 0, dot = 0, crs2 = 0;
    for (size_t k = 0; k < d; k++) {
        double l = b[k] - a[k], r = c[k] - b[k];
        l2 += l * l;
        r2 += r * r;
        dot += l * r;
    }
    if (!(l2 > 0) || !(r2 > 0) || !(dot > 0))
        return 0;
    crs2 = l2 * r2 - dot * dot; /* |l x r|^2 by Lagrange's identity */
    return crs2 <= CONICA__G1_SIN * CONICA__G1_SIN * l2 * r2;
}

/* Raise every interior knot of multiplicity p to p + 1 (but, with keep_g1,
 * those where the curve is tangent-continuous), so that every
 * split of conica__pieces_make is a plain cut. At such a knot z (the run
 * t_{i..i+p-1}) Boehm's insertion (Lemma 1.18 of Dahl 2019) has every
 * a_j = (z - t_j) / (t_{j+p} - t_j) = 0: the new control points are
 * c_{i-1}, c_{i-1}, c_i, ..., so an insertion duplicates c_{i-1} (and its
 * weight) and z, exactly. Done for all corners in one pass: inserting
 * them one at a time shifted the arrays each time, quadratic in the
 * corners (100 000 corner knots: 64 s with --method uniform). */
/* Whether the run of m knots starting at i is raised: multiplicity p,
 * unless keep_g1 and the curve is tangent-continuous there (g1_join). */
static int raise_here(const conica_bspline *cl, size_t i, size_t m, int keep_g1)
{
    return m == (size_t)cl->degree && !(keep_g1 && cl->dim >= 2 && g1_join(cl, i));
}

static conica_code raise_corners(conica_bspline *cl, int keep_g1, conica_status *st)
{
    size_t p = (size_t)cl->degree, d = (size_t)cl->dim, n = cl->n, nk = n + p + 1, K = 0;
    if (p == 0)
        return CONICA_OK;
    for (size_t i = p + 1; i < n;) {
        size_t m = 0;
        while (cl->knots[i + m] == cl->knots[i])
            m++;
        if (raise_here(cl, i, m, keep_g1))
            K++;
        i += m;
    }
    if (K == 0)
        return CONICA_OK;
    if (n + K > CONICA_BSPLINE_MAX_CTRL)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "knot insertion would exceed %zu control points",
                            (size_t)CONICA_BSPLINE_MAX_CTRL);
    double *kn = malloc((nk + K) * sizeof *kn), *cn = malloc((n + K) * d * sizeof *cn);
    double *wn = cl->w ? malloc((n + K) * sizeof *wn) : NULL;
    if (!kn || !cn || (cl->w && !wn)) {
        free(kn);
        free(cn);
        free(wn);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    /* source cursors sk (knots), sc (control points); destination ok, oc */
    size_t sk = 0, sc = 0, ok = 0, oc = 0;
    for (size_t i = p + 1; i < n;) {
        size_t m = 0;
        while (cl->knots[i + m] == cl->knots[i])
            m++;
        if (raise_here(cl, i, m, keep_g1)) {
            memcpy(kn + ok, cl->knots + sk, (i + p - sk) * sizeof *kn);
            ok += i + p - sk;
            kn[ok++] = cl->knots[i];
            sk = i + p;
            memcpy(cn + oc * d, cl->ctrl + sc * d, (i - sc) * d * sizeof *cn);
            if (wn)
                memcpy(wn + oc, cl->w + sc, (i - sc) * sizeof *wn);
            oc += i - sc;
            memcpy(cn + oc * d, cl->ctrl + (i - 1) * d, d * sizeof *cn);
            if (wn)
                wn[oc] = cl->w[i - 1];
            oc++;
            sc = i;
        }
        i += m;
    }
    memcpy(kn + ok, cl->knots + sk, (nk - sk) * sizeof *kn);
    memcpy(cn + oc * d, cl->ctrl + sc * d, (n - sc) * d * sizeof *cn);
    if (wn)
        memcpy(wn + oc, cl->w + sc, (n - sc) * sizeof *wn);
    free(cl->knots);
    free(cl->ctrl);
    free(cl->w);
    cl->knots = kn;
    cl->ctrl = cn;
    cl->w = wn;
    cl->n = n + K;
    return CONICA_OK;
}

conica_code conica__pieces_make(const conica_bspline *s, int graph, int keep_g1,
                                conica__pieces *out, conica_status *st)
{
    int where;
    size_t idx;
    if (!s)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL spline");
    conica_code rc = conica__bspline_check(s->degree, s->dim, s->knots,
                                           s->n + (size_t)s->degree + 1, s->ctrl, s->n, s->w, 0,
                                           &where, &idx, st);
    if (rc != CONICA_OK)
        return rc;
    if (graph && s->dim == 1 && s->w)
        return conica__fail(st, CONICA_ERR_UNSUPPORTED, 0, 0,
                            "rational spline functions are not supported by this method "
                            "(use uniform, local-uniform or mathematica)");
    conica_bspline cl;
    conica_bspline_init(&cl);
    rc = conica__bspline_clamp(s, &cl, st);
    if (rc != CONICA_OK)
        return rc;
    size_t p = (size_t)cl.degree;
    rc = raise_corners(&cl, keep_g1, st);
    if (rc != CONICA_OK) {
        conica_bspline_free(&cl);
        return rc;
    }
    /* cut points: starts i of runs of p+1 interior knots */
    size_t ncut = 0;
    for (size_t i = p + 1; i < cl.n; i++)
        if (cl.knots[i] == cl.knots[i + p] && cl.knots[i] > cl.knots[i - 1])
            ncut++;
    out->count = ncut + 1;
    out->sp = calloc(ncut + 1, sizeof *out->sp);
    out->joined = calloc(ncut + 1, sizeof *out->joined);
    if (!out->sp || !out->joined) {
        free(out->sp);
        free(out->joined);
        conica_bspline_free(&cl);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    size_t start = 0, k = 0;
    size_t nk = cl.n + p + 1;
    for (size_t i = p + 1; i <= cl.n; i++) {
        int cut = i == cl.n ||
                  (cl.knots[i] == cl.knots[i + p] && cl.knots[i] > cl.knots[i - 1]);
        if (!cut)
            continue;
        /* piece: knots [start, i+p], control points [start, i) */
        size_t end_k = i == cl.n ? nk - 1 : i + p;
        size_t np = i - start;
        conica_bspline_init(&out->sp[k]);
        rc = conica_bspline_set(cl.degree, cl.dim, cl.knots + start, end_k - start + 1,
                                cl.ctrl + start * (size_t)cl.dim, np, cl.w ? cl.w + start : NULL,
                                &out->sp[k], st);
        if (rc == CONICA_OK && graph && cl.dim == 1)
            rc = to_graph(&out->sp[k], st);
        if (rc != CONICA_OK) {
            out->count = k;
            conica__pieces_free(out);
            conica_bspline_free(&cl);
            return rc;
        }
        if (k > 0) {
            /* joined when the previous piece ends where this one starts */
            double a[3], b[3];
            const conica_bspline *prev = &out->sp[k - 1], *cur = &out->sp[k];
            if (cur->dim == 1) {
                out->joined[k] = prev->ctrl[prev->n - 1] == cur->ctrl[0];
            } else {
                proj_point(prev, prev->n - 1, a);
                proj_point(cur, 0, b);
                out->joined[k] = memcmp(a, b, (size_t)cur->dim * sizeof *a) == 0;
            }
        }
        k++;
        start = i;
    }
    out->count = k;
    conica_bspline_free(&cl);
    return CONICA_OK;
}

/* ------------------------------------------------------------ tolerance */

double conica__ctrl_diagonal(const conica_bspline *s)
{
    int pd = conica_bspline_point_dim(s);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double pt[3];
    double tsum = 0.0;
    size_t p = (size_t)s->degree;
    for (size_t j = 0; j < s->n; j++) {
        if (s->dim == 1) {
            tsum = 0.0;
            for (size_t i = 1; i <= p; i++)
                tsum += s->knots[j + i];
            pt[0] = tsum / (double)p;
            pt[1] = s->ctrl[j];
        } else {
            for (int c = 0; c < s->dim; c++)
                pt[c] = s->ctrl[j * (size_t)s->dim + (size_t)c];
        }
        for (int c = 0; c < pd; c++) {
            lo[c] = pt[c] < lo[c] ? pt[c] : lo[c];
            hi[c] = pt[c] > hi[c] ? pt[c] : hi[c];
        }
    }
    /* scaled by the largest side: the squares of sides beyond 1.3e154
     * would overflow although the diagonal itself is finite */
    double m = 0.0, d2 = 0.0;
    for (int c = 0; c < pd; c++)
        m = hi[c] - lo[c] > m ? hi[c] - lo[c] : m;
    if (!(m > 0.0) || !isfinite(m))
        return m;
    for (int c = 0; c < pd; c++)
        d2 += ((hi[c] - lo[c]) / m) * ((hi[c] - lo[c]) / m);
    return m * sqrt(d2);
}

double conica_plot_extent(const conica_bspline *s)
{
    return s ? conica__ctrl_diagonal(s) : 0.0;
}

double conica_plot_tolerance(const conica_bspline *s, const conica_plot_settings *set)
{
    if (!s || !set)
        return NAN;
    if (set->abs_tolerance > 0)
        return set->abs_tolerance;
    /* eq. (3.26): eps = delta / rho * Delta c */
    double rho = sqrt(set->viewport_w * set->viewport_w + set->viewport_h * set->viewport_h);
    return set->pixel_tolerance / rho * conica__ctrl_diagonal(s);
}

static conica_code check_settings(const conica_plot_settings *set, conica_status *st)
{
    if ((unsigned)set->method >= CONICA_PLOT_METHOD_COUNT_)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "unknown plot method %d", (int)set->method);
    if ((unsigned)set->criterion >= CONICA_CRIT_COUNT_ || (unsigned)set->rule >= CONICA_RULE_COUNT_ ||
        (unsigned)set->stop >= CONICA_STOP_COUNT_)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "unknown criterion, rule or stop");
    if (!(set->abs_tolerance >= 0) || !isfinite(set->abs_tolerance))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "absolute tolerance must be >= 0");
    if (set->abs_tolerance == 0 &&
        (!(set->pixel_tolerance > 0) || !(set->viewport_w > 0) || !(set->viewport_h > 0) ||
         !isfinite(set->pixel_tolerance) || !isfinite(set->viewport_w) ||
         !isfinite(set->viewport_h)))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "pixel tolerance and viewport must be positive");
    if (!(set->rule_ratio > 0 && set->rule_ratio < 1))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "rule ratio R must be in (0, 1)");
    if (set->skip == 0 || set->consec == 0)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "skip and consec must be >= 1");
    if (set->max_points < 2)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "max_points must be >= 2");
    if (set->points < 2 && (set->method == CONICA_PLOT_UNIFORM ||
                            set->method == CONICA_PLOT_LOCAL_UNIFORM ||
                            set->method == CONICA_PLOT_CHAIKIN ||
                            set->method == CONICA_PLOT_LANE_RIESENFELD))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "number of points must be >= 2");
    if (set->points > set->max_points)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "%zu points exceed max_points %zu",
                            set->points, set->max_points);
    if (set->method == CONICA_PLOT_MATHEMATICA && set->math_initial_points > set->max_points)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "%zu initial points (Mathematica N0) exceed max_points %zu",
                            set->math_initial_points, set->max_points);
    if (set->knot_budget > set->max_knots || set->prephase_knots > set->max_knots)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "knot budget %zu / pre-phase %zu exceed max_knots %zu",
                            set->knot_budget, set->prephase_knots, set->max_knots);
    if (set->local_omega < 0 || set->local_omega > 1 || set->local_min_points < 2)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "local omega in [0,1], N_min >= 2");
    if (set->method == CONICA_PLOT_MATHEMATICA &&
        (set->math_initial_points < 2 || !(set->math_angle > 0) || set->math_max_recursion > 60))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "Mathematica settings: N0 >= 2, angle > 0, recursion <= 60");
    return CONICA_OK;
}

conica_code conica_plot(const conica_bspline *s, const conica_plot_settings *set,
                        conica_polyline *out, conica_plot_stats *stats, conica_status *st)
{
    if (!s || !set || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL argument");
    conica_code rc = check_settings(set, st);
    if (rc != CONICA_OK)
        return rc;
    double t0 = conica__now();
    int geometric = set->method == CONICA_PLOT_GUARANTEED || set->method == CONICA_PLOT_ADAPTIVE;
    conica__pieces pc = {0, NULL, NULL};
    rc = conica__pieces_make(s, geometric, set->method == CONICA_PLOT_GUARANTEED, &pc, st);
    if (rc != CONICA_OK)
        return rc;
    double tol = conica_plot_tolerance(s, set);
    conica_plot_stats sx;
    memset(&sx, 0, sizeof sx);
    sx.tolerance = tol;
    conica__out o;
    conica__out_init(&o, conica_bspline_point_dim(s), set->max_points);
    if (!isfinite(tol) || (!(tol > 0) && !isfinite(conica__ctrl_diagonal(s)))) {
        /* the extent overflowed: control points near +-DBL_MAX */
        rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                          "the control point values are too large: the extent of the control "
                          "polygon overflows (%g); scale the spline down",
                          conica__ctrl_diagonal(s));
    } else if (!(tol > 0)) {
        rc = conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0,
                          "tolerance is zero: the control points span no area "
                          "(give an absolute tolerance)");
    } else if (set->method == CONICA_PLOT_GUARANTEED) {
        rc = conica__plot_guaranteed(&pc, set, tol, &o, &sx, st);
    } else if (set->method == CONICA_PLOT_ADAPTIVE) {
        rc = conica__plot_adaptive(&pc, set, tol, &o, &sx, st);
    } else {
        rc = conica__plot_baseline(&pc, set, tol, &o, &sx, st);
    }
    conica__pieces_free(&pc);
    if (rc == CONICA_OK) {
        /* A rational spline whose weights underflow (denormal weights, found
         * by fuzz_plot) evaluates to 0/0, and a failed evaluation gives NaN
         * (conica__plot_point): never hand NaN or Inf to a caller as a
         * result; every method goes through here. */
        size_t nv = o.pl.n * (size_t)o.pl.dim;
        for (size_t i = 0; i < nv; i++)
            if (!isfinite(o.pl.xy[i])) {
                rc = conica__fail(st, CONICA_ERR_NUMERIC, 0, i / (size_t)o.pl.dim,
                                  "point %zu of the plot is not finite: the spline "
                                  "cannot be evaluated in double there (weights "
                                  "too small or too different, or knots near the "
                                  "overflow limit)",
                                  i / (size_t)o.pl.dim);
                break;
            }
    }
    if (rc != CONICA_OK) {
        conica_polyline_free(&o.pl);
        return rc;
    }
    /* parameters only when every point has one */
    for (size_t i = 0; i < o.pl.n; i++)
        if (isnan(o.pl.t[i])) {
            free(o.pl.t);
            o.pl.t = NULL;
            break;
        }
    sx.points = o.pl.n;
    sx.seconds = conica__now() - t0;
    conica_polyline_free(out);
    *out = o.pl;
    if (stats)
        *stats = sx;
    conica__ok(st);
    return CONICA_OK;
}


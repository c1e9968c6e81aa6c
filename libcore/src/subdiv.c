/* SPDX-License-Identifier: MIT */
/* Conic-preserving interpolatory subdivision (CONIS): public entry
 * points, argument checks, and the two instantiations (double, long double)
 * of the one type-generic implementation in subdiv_impl.h. */
#include "conica/subdiv.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "conic_fit.h"
#include "internal.h"

/* Reference-compatible mode: the reference's absolute tolerances (its
 * SubdivisionSettings::epsilon = 1e-40 for |a| in eq. (12) and the half-plane
 * tests, Eigen's isZero() precision 1e-15 for an all-zero conic). */
#define CONICA__REF_A_EPS 1e-40
#define CONICA__REF_EPS 1e-40
/* A neighbour within this many times settings.noise of an edge line (three
 * rounded points: the distance moves by up to about 3 noise) is on no side. */
#define CONICA__NOISE_SIDE 4.0
#define CONICA__REF_ZERO 1e-15
/* Fast path: an end normal whose component along the chord (the sine of
 * the angle between tangent and chord) is below this makes the pencil
 * L0*L1, y^2 degenerate (the tangent runs through the other end point, as
 * on collinear runs); such patches use the general fit. */
#define CONICA__FAST_MIN_SINE 1e-13
/* ... and with settings.noise > 0 below this many rounding units of the
 * patch's coordinates against the half edge (SFX(make_frame)). */
#define CONICA__STRAIGHT_ULPS 4
/* Irregular patches (S-shaped, or end normals that do not tilt apart):
 * the new point may lie at most this many edge lengths from the edge's
 * midpoint along its normal. Regular (convex) patches, which every conic
 * produces, are not limited. */
#define CONICA__IRREGULAR_MAX_T 1.0
/* A vertex's normal counts as inside the cone of its edges' normals to
 * within this sine (SFX(outside_cone)). */
#define CONICA__CONE_SINE 1e-9
/* Outer neighbours within this many rounding units of an edge line count
 * as on it (see SFX(line_class)). The unit is DBL_EPSILON in both modes: the
 * points collinear by construction (an inflection point (9), the S-shaped
 * edges' midpoints and the midpoints next to them) are off their line by
 * the rounding of the working type, which a double's unit covers in either
 * mode, and precise mode must take the same branches as default mode (it
 * only computes the same choices more exactly). */
#define CONICA__ON_LINE_ULPS 64
#define CONICA__ON_LINE_EPS DBL_EPSILON
/* Threads: at most this many, and only with at least this many edges
 * each (below that, thread start-up costs more than it saves). */
#define CONICA__MAX_THREADS 16
#define CONICA__THREAD_MIN_EDGES 4096
/* Edges per batch of SFX(level) (prepare, fit, finish: see SFX(edge_prep)). */
#define CONICA__EDGE_BATCH 8
/* One-sided Jacobi: sweeps before giving up (converges in < 10 here). */
#define CONICA__JACOBI_MAX_SWEEPS 60
/* Dekker's splitter for the 64-bit significand of x87 long double: 2^32+1. */
#define CONICA__DEKKER_SPLIT 4294967297.0L
#define CONICA__PI 3.14159265358979323846264338327950288L

/* Exact product a*b = *p + *e by Dekker's splitting (the x87 has no fused
 * multiply-add: glibc's fmal is emulated in software and made precise mode
 * 100x slower). */
static void conica__two_prodl(long double a, long double b, long double *p, long double *e)
{
    long double ca = CONICA__DEKKER_SPLIT * a, cb = CONICA__DEKKER_SPLIT * b;
    long double ah = ca - (ca - a), al = a - ah, bh = cb - (cb - b), bl = b - bh;
    *p = a * b;
    *e = ((ah * bh - *p) + ah * bl + al * bh) + al * bl;
}

/* a*b - c*d as Kahan's algorithm (CONIS, Code 4) computes it, with the
 * exact product errors from conica__two_prodl in place of the FMAs. The
 * long double instance's diffprod, and in both instances the inflection
 * test of the input (SFX(needs_infl)), so that both modes decide it alike. */
static long double conica__diffprodl(long double a, long double b, long double c, long double d)
{
    long double w, ew, p, ep;
    conica__two_prodl(d, c, &w, &ew);
    conica__two_prodl(a, b, &p, &ep);
    return ((p - w) + ep) - ew;
}

/* Which side of the edge line p -> q the point r lies on, as the long
 * double test of SFX(needs_infl) decides it, from the double filter of
 * conica__orient2d_approx where its error bound allows: +1 / -1 (left /
 * right, farther than lim from the line times |q - p|), 0 within lim
 * (only for lim > 0), 2 when the filter cannot tell (then the long double
 * test decides). The long double determinant is within a rounding unit of
 * the exact one, far below the filter's bound, and lim here within
 * CONICA__SIDE_MARGIN of the long double one. */
#define CONICA__SIDE_MARGIN 0x1p-45
#define CONICA__SIDE_TINY 0x1p-1060
static int conica__side_filter(const double *p, const double *q, const double *r, double lim)
{
    double err, e = conica__orient2d_approx(p, q, r, &err), mag = fabs(e);
    if (!(err < INFINITY) || !(lim < INFINITY))
        return 2;
    if (lim > 0 && mag + 2 * err < lim * (1 - CONICA__SIDE_MARGIN) - CONICA__SIDE_TINY)
        return 0;
    if (mag - 2 * err > lim * (1 + CONICA__SIDE_MARGIN) + CONICA__SIDE_TINY)
        return e > 0 ? 1 : -1;
    return 2;
}

/* 2^-ilogb(mag) for a finite mag > 0 (the frame's scale, SFX(make_frame)):
 * built from mag's exponent bits where both are normal doubles, which is
 * exactly what ldexp(1, -ilogb(mag)) gives, without its two library calls
 * per edge point; elsewhere (subnormal mag, or a scale below the normal
 * range) through them. */
static double conica__inv_pow2(double mag)
{
    uint64_t bits;
    int biased;
    memcpy(&bits, &mag, sizeof bits);
    biased = (int)((bits >> 52) & 0x7ff);
    if (biased < 1 || biased > 2045)
        return ldexp(1.0, -ilogb(mag));
    bits = (uint64_t)(2046 - biased) << 52;
    memcpy(&mag, &bits, sizeof bits);
    return mag;
}

/* ---------------------------------------------------- double instance */
#define REAL double
#define SFX(name) name##_d
#define M(fn) fn
#define FMA(a, b, c) fma(a, b, c)
#define RC(x) ((double)(x))
#define R_EPSILON DBL_EPSILON
#define REAL_IS_DOUBLE 1
#include "subdiv_impl.h"

/* ----------------------------------------------- long double instance */
#define REAL long double
#define SFX(name) name##_l
#define M(fn) fn##l
#define FMA(a, b, c) ((a) * (b) + (c))
#define RC(x) ((long double)(x))
#define R_EPSILON LDBL_EPSILON
#define REAL_IS_DOUBLE 0
#include "subdiv_impl.h"

/* ------------------------------------------------------------- public */

conica_subdiv_settings conica_subdiv_defaults(void)
{
    conica_subdiv_settings s;
    memset(&s, 0, sizeof s);
    s.levels = 4;
    s.w_edge_point = 1e5;
    s.w_edge_normal = 1e5;
    s.w_outer_normal = 1.0;
    s.tau = 10.0;
    s.patch_grow = 4;
    s.insert_inflections = 1;
    s.normal_method = CONICA_NORMALS_AREA;
    s.max_points = CONICA_SUBDIV_DEFAULT_MAX_POINTS;
    s.threads = 1;
    return s;
}

void conica_subdiv_info_init(conica_subdiv_info *info)
{
    if (!info)
        return;
    memset(info, 0, sizeof *info);
}

void conica_subdiv_info_free(conica_subdiv_info *info)
{
    if (!info)
        return;
    free(info->inflection_index);
    conica_subdiv_info_init(info);
}

size_t conica_subdiv_count(size_t n, int closed, int levels)
{
    size_t f;
    if (levels < 0 || levels > CONICA_SUBDIV_MAX_LEVELS || n == 0)
        return 0;
    f = (size_t)1 << levels;
    if (closed) {
        if (n > ((size_t)-1) / f)
            return 0;
        return n * f;
    }
    if (n - 1 > (((size_t)-1) - 1) / f)
        return 0;
    return (n - 1) * f + 1;
}

void conica_curvel_init(conica_curvel *c)
{
    if (!c)
        return;
    memset(c, 0, sizeof *c);
}

void conica_curvel_free(conica_curvel *c)
{
    if (!c)
        return;
    free(c->xy);
    free(c->nxy);
    conica_curvel_init(c);
}

static int positive_finite(double v)
{
    return isfinite(v) && v > 0;
}

static conica_code check_settings(const conica_subdiv_settings *s, conica_status *st)
{
    if (s->levels < 0)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "levels must be >= 0 (got %d)", s->levels);
    if (s->levels > CONICA_SUBDIV_MAX_LEVELS)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "levels %d exceeds the maximum of %d",
                            s->levels, CONICA_SUBDIV_MAX_LEVELS);
    if (!positive_finite(s->w_edge_point) || !positive_finite(s->w_edge_normal) ||
        !positive_finite(s->w_outer_normal) || !positive_finite(s->tau) ||
        !positive_finite(s->tau * s->w_outer_normal))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "weights and tau must be positive and finite");
    if (s->patch_grow < 1 || s->patch_grow > 4)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "patch_grow must be 1..4 (got %d)",
                            s->patch_grow);
    if (s->max_points < 1)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "max_points must be at least 1");
    if (s->normal_method != CONICA_NORMALS_AREA && s->normal_method != CONICA_NORMALS_CIRCLE)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "unknown normal_method %d",
                            (int)s->normal_method);
    return CONICA_OK;
}

/* Input checks on double or long double arrays (one of xyd / xyl). An edge
 * of zero length has no perpendicular bisector (eq. (7)), so duplicate
 * consecutive points are an error rather than being skipped silently. */
static conica_code check_input(const double *xyd, const double *nd, const long double *xyl,
                               const long double *nl, size_t n, int closed, int need_normals,
                               conica_status *st)
{
    size_t i;
    if (n < 2 || (closed && n < 3))
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0,
                            "a%s curve needs at least %d points (got %zu)",
                            closed ? " closed" : "n open", closed ? 3 : 2, n);
    for (i = 0; i < n; i++) {
        long double x = xyd ? xyd[2 * i] : xyl[2 * i], y = xyd ? xyd[2 * i + 1] : xyl[2 * i + 1];
        if (!isfinite(x) || !isfinite(y))
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, i, "point %zu is not finite", i);
    }
    for (i = 0; i < n; i++) {
        size_t k = i + 1 == n ? 0 : i + 1;
        if (k == 0 && !closed)
            break;
        if (xyd ? (xyd[2 * i] == xyd[2 * k] && xyd[2 * i + 1] == xyd[2 * k + 1])
                : (xyl[2 * i] == xyl[2 * k] && xyl[2 * i + 1] == xyl[2 * k + 1]))
            return conica__fail(st, CONICA_ERR_DEGENERATE, 0, i,
                                "points %zu and %zu coincide (an edge of zero length)", i, k);
    }
    if (!need_normals)
        return CONICA_OK;
    for (i = 0; i < n; i++) {
        long double x = nd ? nd[2 * i] : nl[2 * i], y = nd ? nd[2 * i + 1] : nl[2 * i + 1];
        if (!isfinite(x) || !isfinite(y))
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, i, "normal %zu is not finite", i);
        if (x == 0 && y == 0)
            return conica__fail(st, CONICA_ERR_DEGENERATE, 0, i, "normal %zu is zero", i);
    }
    return CONICA_OK;
}

/* Everything both entry points share: checks, normal estimation, and the
 * run in the requested type. Exactly one of res_d / res_l is non-NULL. */
typedef struct subdiv_result {
    size_t n;
    double *xyd, *nd;
    long double *xyl, *nl;
    size_t *infl;
    size_t ninfl;
} subdiv_result;

/* Reference-compatible mode: an open curve's estimated end normals are
 * its end edges' normals, as the reference estimates them (curve.c takes
 * the circle through the end's three points instead). Orientation kept.
 * Consecutive points are distinct (check_input). */
static void reference_end_normals(conica_curve *c)
{
    size_t e[2], k;
    e[0] = 0;
    e[1] = c->n - 1;
    for (k = 0; k < 2; k++) {
        size_t a = e[k], b = k == 0 ? 1 : c->n - 2;
        double dx = c->xy[2 * b] - c->xy[2 * a], dy = c->xy[2 * b + 1] - c->xy[2 * a + 1];
        double mag = fabs(dx) > fabs(dy) ? fabs(dx) : fabs(dy), len, nx, ny;
        dx /= mag;
        dy /= mag;
        len = sqrt(dx * dx + dy * dy);
        nx = -dy / len;
        ny = dx / len;
        if (nx * c->nxy[2 * a] + ny * c->nxy[2 * a + 1] < 0) {
            nx = -nx;
            ny = -ny;
        }
        c->nxy[2 * a] = nx;
        c->nxy[2 * a + 1] = ny;
    }
}

/* Normals whose larger component lies outside [2^-400, 2^400]: their
 * squares would overflow or underflow in the fit. */
#define NORMAL_SAFE_EXP 400
static int normals_out_of_range(const double *nd, const long double *nl, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        long double x = nd ? nd[2 * i] : nl[2 * i], y = nd ? nd[2 * i + 1] : nl[2 * i + 1];
        long double m = fabsl(x) > fabsl(y) ? fabsl(x) : fabsl(y);
        if (m > 0x1p400L || m < 0x1p-400L)
            return 1;
    }
    return 0;
}

/* The curve with every normal scaled by a power of two to a larger
 * component in [1, 2) (exact, the direction unchanged), in *est. */
static conica_code scaled_normals(const double *xyd, const double *nd, const long double *xyl,
                                  const long double *nl, size_t n, int closed, conica_curve *est,
                                  conica_status *st)
{
    double *tmp = malloc(4 * n * sizeof *tmp), *txy = tmp, *tn = tmp ? tmp + 2 * n : NULL;
    conica_code code;
    if (!tmp)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    for (size_t i = 0; i < n; i++) {
        long double x = nd ? nd[2 * i] : nl[2 * i], y = nd ? nd[2 * i + 1] : nl[2 * i + 1];
        long double m = fabsl(x) > fabsl(y) ? fabsl(x) : fabsl(y);
        int e = ilogbl(m);
        txy[2 * i] = xyd ? xyd[2 * i] : (double)xyl[2 * i];
        txy[2 * i + 1] = xyd ? xyd[2 * i + 1] : (double)xyl[2 * i + 1];
        tn[2 * i] = (double)scalbnl(x, -e);
        tn[2 * i + 1] = (double)scalbnl(y, -e);
    }
    code = conica_curve_set(txy, tn, n, closed, est, st);
    free(tmp);
    return code;
}

static conica_code subdivide_any(const double *xyd, const double *nd, const long double *xyl,
                                 const long double *nl, size_t n, int closed,
                                 const conica_subdiv_settings *s_in, int want_long,
                                 subdiv_result *res, conica_subdiv_info *info, conica_status *st)
{
    conica_subdiv_settings s = s_in ? *s_in : conica_subdiv_defaults();
    conica_subdiv_info stats;
    conica_curve est;
    conica_code code;
    int estimate = s.estimate_normals || (xyd ? !nd : !nl);

    conica_curve_init(&est);
    conica_subdiv_info_init(&stats);
    if ((code = check_settings(&s, st)) != CONICA_OK)
        return code;
    if ((code = check_input(xyd, nd, xyl, nl, n, closed, !estimate, st)) != CONICA_OK)
        return code;
    if (!estimate && normals_out_of_range(nd, nl, n)) {
        /* only the normals' directions enter the fit: huge or tiny ones
         * (vn 1e308 0.65, 5e-324) scaled by a power of two, exactly,
         * instead of overflowing in the fit and blaming the output */
        if ((code = scaled_normals(xyd, nd, xyl, nl, n, closed, &est, st)) != CONICA_OK)
            return code;
        estimate = 1; /* the fit reads est.nxy */
    } else if (estimate) {
        /* Normals from the points (curve.c), in double: only their
         * directions enter the fit. */
        if (xyd) {
            code = conica_curve_set(xyd, NULL, n, closed, &est, st);
        } else {
            size_t i;
            double *tmp = malloc(2 * n * sizeof *tmp);
            if (!tmp)
                return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            for (i = 0; i < 2 * n; i++)
                tmp[i] = (double)xyl[i];
            code = conica_curve_set(tmp, NULL, n, closed, &est, st);
            free(tmp);
        }
        if (code == CONICA_OK)
            code = conica_curve_estimate_normals(&est, s.normal_method, st);
        if (code != CONICA_OK) {
            conica_curve_free(&est);
            return code;
        }
        if (s.reference_compatible && !closed)
            reference_end_normals(&est);
    }
    if (want_long || s.precise) {
        input_l in;
        long double *rx = NULL, *rn = NULL;
        in.xyd = xyd;
        in.xyl = xyl;
        in.nd = estimate ? est.nxy : nd;
        in.nl = estimate ? NULL : nl;
        in.n = n;
        in.closed = closed != 0;
        in.noise = s.noise;
        code = run_l(&in, &s, &rx, &rn, &res->n, &res->infl, &res->ninfl, &stats, st);
        if (code == CONICA_OK && !want_long) {
            size_t i;
            res->xyd = malloc(2 * res->n * sizeof *res->xyd);
            res->nd = malloc(2 * res->n * sizeof *res->nd);
            if (!res->xyd || !res->nd) {
                free(res->xyd);
                free(res->nd);
                free(res->infl);
                code = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            } else {
                for (i = 0; i < 2 * res->n; i++) {
                    res->xyd[i] = (double)rx[i];
                    res->nd[i] = (double)rn[i];
                    if (code == CONICA_OK && (!isfinite(res->xyd[i]) || !isfinite(res->nd[i])))
                        code = conica__fail(st, CONICA_ERR_NUMERIC, 0, i / 2,
                                            "point %zu of the output is beyond the range of "
                                            "double",
                                            i / 2);
                }
                if (code != CONICA_OK) {
                    /* A long double edge point past DBL_MAX (found by
                     * fuzz_subdivide): no inf in a double result. */
                    free(res->xyd);
                    free(res->nd);
                    free(res->infl);
                    res->xyd = res->nd = NULL;
                    res->infl = NULL;
                }
            }
            free(rx);
            free(rn);
        } else if (code == CONICA_OK) {
            res->xyl = rx;
            res->nl = rn;
        }
    } else {
        input_d in;
        in.xyd = xyd;
        in.xyl = NULL;
        in.nd = estimate ? est.nxy : nd;
        in.nl = NULL;
        in.n = n;
        in.closed = closed != 0;
        in.noise = s.noise;
        code = run_d(&in, &s, &res->xyd, &res->nd, &res->n, &res->infl, &res->ninfl, &stats, st);
    }
    conica_curve_free(&est);
    if (code != CONICA_OK)
        return code;
    if (info) {
        conica_subdiv_info_free(info);
        stats.inflection_index = res->infl;
        res->infl = NULL;
        *info = stats;
    } else {
        free(res->infl);
        res->infl = NULL;
    }
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_subdivide(const conica_curve *in, const conica_subdiv_settings *s,
                             conica_curve *out, conica_subdiv_info *info, conica_status *st)
{
    subdiv_result r;
    conica_code code;
    if (!in || !out || (in->n > 0 && !in->xy))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_subdivide: NULL argument");
    memset(&r, 0, sizeof r);
    code = subdivide_any(in->xy, in->nxy, NULL, NULL, in->n, in->closed, s, 0, &r, info, st);
    if (code != CONICA_OK)
        return code;
    {
        int closed = in->closed != 0; /* `in` may alias `out` */
        conica_curve_free(out);
        out->xy = r.xyd;
        out->nxy = r.nd;
        out->n = r.n;
        out->cap = r.n;
        out->closed = closed;
    }
    return CONICA_OK;
}

conica_code conica_subdividel(const conica_curve *in, const conica_subdiv_settings *s,
                              conica_curvel *out, conica_subdiv_info *info, conica_status *st)
{
    subdiv_result r;
    conica_code code;
    if (!in || !out || (in->n > 0 && !in->xy))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_subdividel: NULL argument");
    memset(&r, 0, sizeof r);
    code = subdivide_any(in->xy, in->nxy, NULL, NULL, in->n, in->closed, s, 1, &r, info, st);
    if (code != CONICA_OK)
        return code;
    conica_curvel_free(out);
    out->xy = r.xyl;
    out->nxy = r.nl;
    out->n = r.n;
    out->cap = r.n;
    out->closed = in->closed != 0;
    return CONICA_OK;
}

conica_code conica_subdivide_curvel(const conica_curvel *in, const conica_subdiv_settings *s,
                                    conica_curvel *out, conica_subdiv_info *info,
                                    conica_status *st)
{
    subdiv_result r;
    conica_code code;
    int closed;
    if (!in || !out || (in->n > 0 && !in->xy))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_subdivide_curvel: NULL argument");
    memset(&r, 0, sizeof r);
    closed = in->closed != 0;
    code = subdivide_any(NULL, NULL, in->xy, in->nxy, in->n, closed, s, 1, &r, info, st);
    if (code != CONICA_OK)
        return code;
    conica_curvel_free(out);
    out->xy = r.xyl;
    out->nxy = r.nl;
    out->n = r.n;
    out->cap = r.n;
    out->closed = closed;
    return CONICA_OK;
}

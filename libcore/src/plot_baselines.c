/* SPDX-License-Identifier: MIT */
/* Baselines the thesis compares against (Dahl 2019, §2.3 and 3.1):
 * global uniform sampling (eq. (2.3)-(2.4), MATLAB fnplt's N = 101), local
 * uniform sampling per knot interval weighted by control polygon length,
 * angle or both (eqs. (3.10), (3.17), (3.18)), Chaikin's corner cutting
 * (eqs. (3.1)-(3.2)), Lane-Riesenfeld midpoint refinement (Fig. 12) and
 * Mathematica-style adaptive sampling (Section 2.3.3). Sampling methods
 * evaluate with the triangular algorithm; the corner cutting methods work
 * on the control polygon and keep its end points (on the curve for a
 * clamped spline). The N points of a setting are shared among the
 * continuous pieces in proportion to their parameter length. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bspline_internal.h"
#include "internal.h"
#include "plot_internal.h"

#define PI_ 3.14159265358979323846

static double eval_flops(const conica_bspline *s)
{
    size_t p = (size_t)s->degree;
    return (double)(p * (p + 1) / 2) * (3.0 + 3.0 * (double)conica__hdim(s));
}

/* Parameter length of piece k. */
static double piece_len(const conica__pieces *pc, size_t k)
{
    const conica_bspline *s = &pc->sp[k];
    return s->knots[s->n] - s->knots[s->degree];
}

/* Share of n points for piece k (at least 2), of the pieces' total
 * parameter length (summed once by the caller: per piece it made many
 * corners quadratic). */
static size_t share(const conica__pieces *pc, size_t k, size_t n, double total)
{
    double mine = piece_len(pc, k);
    /* mine / total first: n * mine overflows for knots near 1e308, and an
     * infinite or NaN share must not reach the size_t cast (fuzz_plot) */
    double v = total > 0 ? (double)n * (mine / total) : (double)n;
    size_t r = conica__size_clamp(v + 0.5, n); /* (double)SIZE_MAX is 2^64 */
    return r < 2 ? 2 : r;
}

static conica_code emit_param(const conica_bspline *s, double t, int skip, conica__out *o,
                              conica_plot_stats *stats, conica_status *st)
{
    if (skip)
        return CONICA_OK;
    double buf[3];
    conica__plot_point(s, t, buf);
    stats->flops += eval_flops(s);
    return conica__out_push(o, buf, t, st);
}

static conica_code uniform_piece(const conica_bspline *s, size_t n, int join, conica__out *o,
                                 conica_plot_stats *stats, conica_status *st)
{
    double a = s->knots[s->degree], b = s->knots[s->n];
    conica_code rc = CONICA_OK;
    for (size_t i = 0; i < n && rc == CONICA_OK; i++) {
        /* eq. (2.3)-(2.4): x_i = a + (i-1) h, h = (b-a)/(N-1) */
        double t = i + 1 == n ? b : a + (b - a) * (double)i / (double)(n - 1);
        rc = emit_param(s, t, join && i == 0, o, stats, st);
    }
    return rc;
}

double conica__turn_angle(const double *a, const double *q, const double *b, int d)
{
    double dot = 0, la = 0, lb = 0;
    for (int c = 0; c < d; c++) {
        double u = q[c] - a[c], v = b[c] - q[c];
        dot += u * v;
        la += u * u;
        lb += v * v;
    }
    if (la <= 0 || lb <= 0)
        return 0.0;
    double x = dot / sqrt(la * lb);
    x = x > 1 ? 1 : (x < -1 ? -1 : x);
    return acos(x);
}

static double seglen(const double *a, const double *b, int d)
{
    double r = 0;
    for (int c = 0; c < d; c++)
        r += (b[c] - a[c]) * (b[c] - a[c]);
    return sqrt(r);
}

/* Local uniform sampling: the subintervals are the knot intervals; the
 * local control polygon of interval mu is P_{mu-p} .. P_mu. */
static conica_code local_uniform(const conica__pieces *pc, const conica_plot_settings *set,
                                 conica__out *o, conica_plot_stats *stats, conica_status *st)
{
    size_t S = 0;
    for (size_t k = 0; k < pc->count; k++)
        S += conica_bspline_bezier_count(&pc->sp[k]);
    double *L = malloc(S * sizeof *L), *A = malloc(S * sizeof *A);
    if (!L || !A) {
        free(L);
        free(A);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    double Lsum = 0, Asum = 0;
    size_t idx = 0;
    for (size_t k = 0; k < pc->count; k++) {
        const conica_bspline *s = &pc->sp[k];
        int pd = conica_bspline_point_dim(s);
        size_t p = (size_t)s->degree;
        double *P = malloc(s->n * (size_t)pd * sizeof *P);
        if (!P) {
            free(L);
            free(A);
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        }
        conica_bspline_control_polygon(s, P);
        for (size_t mu = p; mu < s->n; mu++) {
            if (!(s->knots[mu] < s->knots[mu + 1]))
                continue;
            double l = 0, an = 0;
            for (size_t i = mu - p; i < mu; i++) {
                l += seglen(P + i * (size_t)pd, P + (i + 1) * (size_t)pd, pd);
                /* eq. (3.14)-(3.15), alpha_1 = alpha_n = pi/2 */
                an += (i == 0 || i + 1 == s->n)
                          ? 0.5 * PI_
                          : conica__turn_angle(P + (i - 1) * (size_t)pd, P + i * (size_t)pd,
                                 P + (i + 1) * (size_t)pd, pd);
            }
            stats->flops += (double)p * (5.0 + 40.0);
            L[idx] = l;
            A[idx] = an;
            Lsum += l;
            Asum += an;
            idx++;
        }
        free(P);
    }
    double Lbar = Lsum / (double)S, Abar = Asum / (double)S, Nbar = (double)set->points / (double)S;
    double om = set->local_weight == CONICA_LOCAL_LENGTH ? 1.0
                : set->local_weight == CONICA_LOCAL_ANGLE ? 0.0 : set->local_omega;
    conica_code rc = CONICA_OK;
    idx = 0;
    for (size_t k = 0; k < pc->count && rc == CONICA_OK; k++) {
        const conica_bspline *s = &pc->sp[k];
        size_t p = (size_t)s->degree;
        if (!pc->joined[k])
            rc = conica__out_piece(o, st);
        int first = 1;
        for (size_t mu = p; mu < s->n && rc == CONICA_OK; mu++) {
            double a = s->knots[mu], b = s->knots[mu + 1];
            if (!(a < b))
                continue;
            /* eq. (3.18) (omega = 1: (3.10), omega = 0: (3.17)) */
            double wl = Lbar > 0 ? L[idx] / Lbar : 1.0, wa = Abar > 0 ? A[idx] / Abar : 1.0;
            double v = floor(Nbar * (om * wl + (1 - om) * wa));
            size_t Ni = conica__size_clamp(v, set->max_points);
            if (Ni < set->local_min_points)
                Ni = set->local_min_points;
            idx++;
            /* eq. (2.5): h_i = (t_{i+1} - t_i) / (N_i - 1); shared ends once */
            for (size_t i = first ? 0 : 1; i < Ni && rc == CONICA_OK; i++) {
                double t = i + 1 == Ni ? b : a + (b - a) * (double)i / (double)(Ni - 1);
                rc = emit_param(s, t, pc->joined[k] && first && i == 0, o, stats, st);
            }
            first = 0;
        }
    }
    free(L);
    free(A);
    return rc;
}

/* Corner cutting on a polygon (Chaikin or Lane-Riesenfeld) until it has at
 * least `want` points; ends kept. */
static conica_code cut_corners(const conica_bspline *s, int lr, size_t want, int join,
                               const conica_plot_settings *set, conica__out *o,
                               conica_plot_stats *stats, conica_status *st)
{
    int d = conica_bspline_point_dim(s);
    size_t n = s->n, ud = (size_t)d;
    size_t p = (size_t)s->degree;
    double *P = malloc(n * ud * sizeof *P);
    if (!P)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    conica_bspline_control_polygon(s, P);
    conica_code rc = CONICA_OK;
    while (n < want) {
        size_t nn;
        if (!lr) {
            /* eqs. (3.1)-(3.2): N_{k+1} = 2 N_k - 2, ends kept */
            nn = 2 * n - 2;
        } else {
            /* Lane-Riesenfeld of degree p: double, then p averaging passes */
            size_t dbl = 2 * n;
            size_t passes = p < dbl - 1 ? p : dbl - 1;
            nn = dbl - passes + 2;
        }
        if (nn <= n) /* a single segment: nothing to cut */
            break;
        if (nn > set->max_points) {
            rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                              "corner cutting exceeds %zu points (max_points)", set->max_points);
            break;
        }
        double *Q = malloc((2 * n + 2) * ud * sizeof *Q);
        if (!Q) {
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            break;
        }
        if (!lr) {
            size_t m = 0;
            memcpy(Q, P, ud * sizeof *Q);
            m = 1;
            for (size_t i = 0; i + 1 < n; i++) {
                for (int q = 0; q < 2; q++) {
                    if ((i == 0 && q == 0) || (i + 2 == n && q == 1))
                        continue;
                    for (size_t c = 0; c < ud; c++) {
                        double x0 = P[i * ud + c], x1 = P[(i + 1) * ud + c];
                        Q[m * ud + c] = q == 0 ? 0.25 * (3 * x0 + x1) : 0.25 * (x0 + 3 * x1);
                    }
                    m++;
                }
            }
            memcpy(Q + m * ud, P + (n - 1) * ud, ud * sizeof *Q);
            m++;
            stats->flops += 3.0 * (double)d * (double)(m - 2);
            nn = m;
        } else {
            size_t dbl = 2 * n;
            double *D = Q + ud; /* leave room for the kept start point */
            for (size_t i = 0; i < n; i++) {
                memcpy(D + (2 * i) * ud, P + i * ud, ud * sizeof *D);
                memcpy(D + (2 * i + 1) * ud, P + i * ud, ud * sizeof *D);
            }
            size_t cnt = dbl;
            size_t passes = p < dbl - 1 ? p : dbl - 1;
            for (size_t r = 0; r < passes; r++) {
                for (size_t i = 0; i + 1 < cnt; i++)
                    for (size_t c = 0; c < ud; c++)
                        D[i * ud + c] = 0.5 * (D[i * ud + c] + D[(i + 1) * ud + c]);
                stats->flops += 2.0 * (double)d * (double)(cnt - 1);
                cnt--;
            }
            memcpy(Q, P, ud * sizeof *Q);
            memcpy(Q + (cnt + 1) * ud, P + (n - 1) * ud, ud * sizeof *Q);
            nn = cnt + 2;
        }
        free(P);
        P = Q;
        n = nn;
    }
    for (size_t i = join ? 1 : 0; i < n && rc == CONICA_OK; i++)
        rc = conica__out_push(o, P + i * ud, NAN, st);
    free(P);
    return rc;
}

/* Mathematica: N0 uniform samples, then split both intervals around every
 * vertex whose turning angle exceeds the threshold, up to max recursion. */
typedef struct msamp {
    double t;
    double xy[3];
    unsigned depth; /* of the interval to the right */
} msamp;

static conica_code mathematica_piece(const conica_bspline *s, const conica_plot_settings *set,
                                     size_t n0, int join, conica__out *o,
                                     conica_plot_stats *stats, conica_status *st)
{
    int d = conica_bspline_point_dim(s);
    double a = s->knots[s->degree], b = s->knots[s->n];
    size_t n = n0 < 2 ? 2 : n0, cap = n, bytes;
    if (conica__mul_size(cap, sizeof(msamp), &bytes))
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "%zu initial points exceed max_points",
                            n0);
    msamp *v = malloc(bytes);
    if (!v)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    for (size_t i = 0; i < n; i++) {
        v[i].t = i + 1 == n ? b : a + (b - a) * (double)i / (double)(n - 1);
        conica__plot_point(s, v[i].t, v[i].xy);
        v[i].depth = 0;
        stats->flops += eval_flops(s);
    }
    conica_code rc = CONICA_OK;
    for (size_t pass = 0; pass < set->math_max_recursion; pass++) {
        unsigned char *mark = calloc(n, 1);
        if (!mark) {
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            break;
        }
        size_t add = 0;
        for (size_t i = 1; i + 1 < n; i++) {
            double ang = conica__turn_angle(v[i - 1].xy, v[i].xy, v[i + 1].xy, d);
            stats->flops += 40;
            if (ang > set->math_angle) {
                if (v[i - 1].depth < set->math_max_recursion && !mark[i - 1]) {
                    mark[i - 1] = 1;
                    add++;
                }
                if (v[i].depth < set->math_max_recursion && !mark[i]) {
                    mark[i] = 1;
                    add++;
                }
            }
        }
        if (add == 0) {
            free(mark);
            break;
        }
        if (n + add > set->max_points) {
            free(mark);
            rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                              "Mathematica refinement exceeds %zu points (max_points)",
                              set->max_points);
            break;
        }
        cap = n + add;
        msamp *w = malloc(cap * sizeof *w);
        if (!w) {
            free(mark);
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            break;
        }
        size_t m = 0;
        for (size_t i = 0; i < n; i++) {
            w[m] = v[i];
            if (i + 1 < n && mark[i]) {
                w[m].depth = v[i].depth + 1;
                m++;
                w[m].t = 0.5 * (v[i].t + v[i + 1].t);
                conica__plot_point(s, w[m].t, w[m].xy);
                stats->flops += eval_flops(s);
                w[m].depth = v[i].depth + 1;
            }
            m++;
        }
        free(mark);
        free(v);
        v = w;
        n = m;
        stats->iterations++;
    }
    for (size_t i = join ? 1 : 0; i < n && rc == CONICA_OK; i++)
        rc = conica__out_push(o, v[i].xy, v[i].t, st);
    free(v);
    return rc;
}

conica_code conica__plot_baseline(const conica__pieces *pc, const conica_plot_settings *set,
                                  double tol, conica__out *o, conica_plot_stats *stats,
                                  conica_status *st)
{
    (void)tol;
    if (set->method == CONICA_PLOT_LOCAL_UNIFORM)
        return local_uniform(pc, set, o, stats, st);
    double total = 0;
    for (size_t k = 0; k < pc->count; k++)
        total += piece_len(pc, k);
    for (size_t k = 0; k < pc->count; k++) {
        conica_code rc = CONICA_OK;
        const conica_bspline *s = &pc->sp[k];
        int join = pc->joined[k];
        if (!join)
            rc = conica__out_piece(o, st);
        if (rc != CONICA_OK)
            return rc;
        switch (set->method) {
        case CONICA_PLOT_UNIFORM:
            rc = uniform_piece(s, share(pc, k, set->points, total), join, o, stats, st);
            break;
        case CONICA_PLOT_CHAIKIN:
            rc = cut_corners(s, 0, share(pc, k, set->points, total), join, set, o, stats, st);
            break;
        case CONICA_PLOT_LANE_RIESENFELD:
            rc = cut_corners(s, 1, share(pc, k, set->points, total), join, set, o, stats, st);
            break;
        default:
            rc = mathematica_piece(s, set, share(pc, k, set->math_initial_points, total), join, o,
                                   stats, st);
            break;
        }
        if (rc != CONICA_OK)
            return rc;
    }
    return CONICA_OK;
}

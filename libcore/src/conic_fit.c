/* SPDX-License-Identifier: MIT */
/* The general conic fit's smallest right singular vector in double (see
 * conic_fit.h): Householder QR and inverse iteration in-house, LAPACK's
 * dgesvd as the fallback. The long double (precise) mode uses the one-sided
 * Jacobi SVD in subdiv_impl.h instead, since LAPACK has no
 * extended-precision routines. */
#include "conic_fit.h"

#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Inverse iteration: steps before giving up (LAPACK then decides). It
 * contracts by (s_n / s_n-1)^2 a step, so settling within 8 steps means a
 * clear gap below the next singular value; patches without one (two
 * conics fit about equally well) keep LAPACK's choice. Then the
 * convergence test: the unit iterate moves by at most this many rounding
 * units per component from one step to the next. */
#define CONICA__INVIT_MAX_STEPS 8
#define CONICA__INVIT_TOL_ULPS 64
/* ... or it moves by at most this and no less than the step before: the
 * iterate has reached the rounding level of the patch's own conditioning
 * (weights 1e5 : 1 put it near 1e-11), where LAPACK's vector is no more
 * accurate. */
#define CONICA__INVIT_FLOOR 1e-10
/* A pivot of R below this many rounding units of the largest counts as
 * that size (inverse iteration's usual shift off an exact singularity). */
#define CONICA__INVIT_PIVOT_ULPS 1
/* Downdated column norms (householder_r) are accurate to about
 * DBL_EPSILON / sqrt(DBL_EPSILON) relative; candidates within this
 * relative distance of the largest are compared by their exact norms, so
 * the pivot order is the one exact norms give. */
#define CONICA__QR_TIE 1e-6

void conica__svdws_init(conica__svdws *ws)
{
    ws->work = NULL;
    ws->lwork = 0;
    ws->inverse = 0;
    ws->lapack = 0;
}

/* LAPACK's workspace, sized for every patch size at the first call that
 * needs it (most conica_subdivide() calls never do). */
static int lapack_workspace(conica__svdws *ws)
{
    double q, dummy = 0;
    int p, lwork = 1;

    if (ws->work)
        return 0;
    for (p = 2; p <= CONICA__FIT_MAX_PAIRS; p++) {
        lapack_int m = 3 * p, n = 6 + p;
        q = 0;
        if (LAPACKE_dgesvd_work(LAPACK_COL_MAJOR, 'N', 'A', m, n, &dummy, m, ws->s, NULL, 1,
                                ws->vt, n, &q, -1) != 0)
            q = 0;
        if ((int)q > lwork)
            lwork = (int)q;
    }
    /* dgesvd's documented minimum, in case a query under-reports. */
    if (lwork < 5 * CONICA__FIT_MAX_ROWS + CONICA__FIT_MAX_COLS)
        lwork = 5 * CONICA__FIT_MAX_ROWS + CONICA__FIT_MAX_COLS;
    ws->work = malloc((size_t)lwork * sizeof *ws->work);
    if (!ws->work)
        return -1;
    ws->lwork = lwork;
    return 0;
}

void conica__svdws_free(conica__svdws *ws)
{
    if (!ws)
        return;
    free(ws->work);
    ws->work = NULL;
    ws->lwork = 0;
}

/* Householder QR with column pivoting (Businger-Golub) of the m x n
 * column-major a (m >= n) in place: R in the upper triangle (reflectors not
 * kept), column k of R is column perm[k] of a. The pivoting makes R graded
 * (|r_kk| non-increasing), so that the triangular solves of the inverse
 * iteration stay accurate under the weights' 1e5 : 1 scaling. Norms are
 * scaled, so entries near the overflow threshold square safely. The
 * candidates' norms are downdated after each step (the norm of rows k+1..
 * of column j is that of rows k.. less the new r_kj), and recomputed where
 * the downdate has cancelled more than half the digits, as LAPACK's dlaqp2
 * does. Near ties (CONICA__QR_TIE) and the pivot column's own norm, which
 * the reflection uses, are computed afresh, so R is what recomputing every
 * norm at every step gave. */
static double col_norm(const double *x, int lo, int hi)
{
    double scale = 0, ss = 0;
    int i;
    for (i = lo; i < hi; i++)
        scale = fabs(x[i]) > scale ? fabs(x[i]) : scale;
    if (scale == 0 || !isfinite(scale))
        return scale;
    for (i = lo; i < hi; i++) {
        double t = x[i] / scale;
        ss += t * t;
    }
    return scale * sqrt(ss);
}

static void householder_r(double *a, int m, int n, int *perm)
{
    /* a downdate keeping less than this share of the last computed norm
     * squared is recomputed (dlaqp2's tol3z, sqrt of the rounding unit) */
    const double redo = sqrt(DBL_EPSILON);
    double cn[CONICA__FIT_MAX_COLS], cn0[CONICA__FIT_MAX_COLS];
    int i, j, k;
    for (j = 0; j < n; j++) {
        perm[j] = j;
        cn[j] = cn0[j] = col_norm(a + (size_t)j * (size_t)m, 0, m);
    }
    for (k = 0; k < n; k++) {
        double *ak, norm = -1, alpha, beta;
        int best = k, tie = 0;
        for (j = k; j < n; j++)
            if (cn[j] > norm) {
                norm = cn[j];
                best = j;
            }
        for (j = k; j < n && !tie; j++)
            tie = j != best && cn[j] >= norm * (1 - CONICA__QR_TIE);
        if (tie) { /* a near tie: choose by the exact norms */
            norm = -1;
            for (j = k; j < n; j++) {
                cn[j] = cn0[j] = col_norm(a + (size_t)j * (size_t)m, k, m);
                if (cn[j] > norm) {
                    norm = cn[j];
                    best = j;
                }
            }
        }
        if (best != k) {
            double *x = a + (size_t)k * (size_t)m, *y = a + (size_t)best * (size_t)m, u;
            int t = perm[k];
            perm[k] = perm[best];
            perm[best] = t;
            for (i = 0; i < m; i++) {
                u = x[i];
                x[i] = y[i];
                y[i] = u;
            }
            u = cn[k];
            cn[k] = cn[best];
            cn[best] = u;
            u = cn0[k];
            cn0[k] = cn0[best];
            cn0[best] = u;
        }
        ak = a + (size_t)k * (size_t)m;
        norm = col_norm(ak, k, m);
        if (!(norm > 0))
            continue;
        alpha = ak[k] >= 0 ? -norm : norm;
        /* v = x - alpha e1, v'v = 2 norm (norm + |x_k|) */
        beta = 1 / (norm * (norm + fabs(ak[k])));
        ak[k] -= alpha;
        for (j = k + 1; j < n; j++) {
            double *aj = a + (size_t)j * (size_t)m, s = 0;
            for (i = k; i < m; i++)
                s += ak[i] * aj[i];
            s *= beta;
            for (i = k; i < m; i++)
                aj[i] -= s * ak[i];
            if (cn[j] > 0 && isfinite(cn[j])) { /* rows k+1.. of column j */
                double r = fabs(aj[k]) / cn[j], keep = 1 - r * r, q = cn[j] / cn0[j];
                keep = keep > 0 ? keep : 0;
                if (keep * q * q <= redo) {
                    cn[j] = col_norm(aj, k + 1, m);
                    cn0[j] = cn[j];
                } else {
                    cn[j] *= sqrt(keep);
                }
            }
        }
        ak[k] = alpha;
    }
}

/* Scale x[0..n-1] to unit length (max-abs first); 0, or -1 if x is zero or
 * not finite. */
static int unit(double *x, int n)
{
    double mag = 0, ss = 0;
    int i;
    for (i = 0; i < n; i++)
        mag = fabs(x[i]) > mag ? fabs(x[i]) : mag;
    if (!(mag > 0) || !isfinite(mag))
        return -1;
    for (i = 0; i < n; i++) {
        x[i] /= mag;
        ss += x[i] * x[i];
    }
    ss = 1 / sqrt(ss);
    for (i = 0; i < n; i++)
        x[i] *= ss;
    return 0;
}

/*
 * Right singular vector of the smallest singular value of the n x n upper
 * triangular R (leading dimension m) by inverse iteration on R'R:
 * x <- R^-1 R^-T x, each step two triangular solves (2 n^2 flops, against
 * some 10^4 for an SVD of the patch). It converges at the rate
 * (s_n / s_n-1)^2, at once for the patches of exact conic data (s_n ~ 0);
 * the solves are backward stable in R, so the iterate is as accurate as the
 * QR, i.e. as the data. Returns 0, or -1 when it does not settle within
 * CONICA__INVIT_MAX_STEPS (then LAPACK decides).
 */
static int inverse_iteration(const double *r, int m, int n, double *v)
{
    double d[CONICA__FIT_MAX_COLS], x[CONICA__FIT_MAX_COLS], y[CONICA__FIT_MAX_COLS];
    double dmax = 0, floor, tol = CONICA__INVIT_TOL_ULPS * DBL_EPSILON, prev = INFINITY;
    int i, k, step;

    for (i = 0; i < n; i++) {
        d[i] = r[(size_t)i + (size_t)i * (size_t)m];
        dmax = fabs(d[i]) > dmax ? fabs(d[i]) : dmax;
    }
    if (!(dmax > 0) || !isfinite(dmax))
        return -1;
    floor = CONICA__INVIT_PIVOT_ULPS * DBL_EPSILON * dmax;
    for (i = 0; i < n; i++)
        if (fabs(d[i]) < floor)
            d[i] = d[i] < 0 ? -floor : floor;
    for (i = 0; i < n; i++)
        x[i] = 1;
    (void)unit(x, n);
    for (step = 0; step < CONICA__INVIT_MAX_STEPS; step++) {
        double dot = 0, change = 0;
        /* R' y = x (forward), then R y' = y (backward), rescaled between */
        for (i = 0; i < n; i++) {
            double s = x[i];
            for (k = 0; k < i; k++)
                s -= r[(size_t)k + (size_t)i * (size_t)m] * y[k];
            y[i] = s / d[i];
        }
        if (unit(y, n) != 0)
            return -1;
        for (i = n; i-- > 0;) {
            double s = y[i];
            for (k = i + 1; k < n; k++)
                s -= r[(size_t)i + (size_t)k * (size_t)m] * y[k];
            y[i] = s / d[i];
        }
        if (unit(y, n) != 0)
            return -1;
        for (i = 0; i < n; i++)
            dot += x[i] * y[i];
        for (i = 0; i < n; i++) {
            double yi = dot < 0 ? -y[i] : y[i], c = fabs(yi - x[i]);
            change = c > change ? c : change;
            x[i] = yi;
        }
        if (step > 0 && (change <= tol || (change <= CONICA__INVIT_FLOOR && change >= prev))) {
            memcpy(v, x, (size_t)n * sizeof *v);
            return 0;
        }
        prev = change;
    }
    return -1;
}

int conica__svd_min_right(conica__svdws *ws, double *a, int m, int n, double *v)
{
    lapack_int info;
    int j;

    if (m >= n) {
        double r[CONICA__FIT_MAX_ROWS * CONICA__FIT_MAX_COLS], x[CONICA__FIT_MAX_COLS];
        int perm[CONICA__FIT_MAX_COLS];
        memcpy(r, a, (size_t)m * (size_t)n * sizeof *r);
        householder_r(r, m, n, perm);
        if (inverse_iteration(r, m, n, x) == 0) {
            for (j = 0; j < n; j++)
                v[perm[j]] = x[j];
            ws->inverse++;
            return 0;
        }
    }
    if (lapack_workspace(ws) != 0)
        return -1;
    ws->lapack++;
    /* jobvt = 'A': for m < n (a 2-pair patch) the null space is only in the
     * full V^T; its last row belongs to the smallest singular value. */
    info = LAPACKE_dgesvd_work(LAPACK_COL_MAJOR, 'N', 'A', m, n, a, m, ws->s, NULL, 1, ws->vt, n,
                               ws->work, ws->lwork);
    if (info != 0)
        return -1;
    for (j = 0; j < n; j++)
        v[j] = ws->vt[(size_t)(n - 1) + (size_t)j * (size_t)n];
    return 0;
}

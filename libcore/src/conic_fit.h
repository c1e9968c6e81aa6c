/* SPDX-License-Identifier: MIT */
/* Weighted conic fit of CONIS §1.1 step 2 (matrix (2)), general
 * path: smallest right singular vector of W*A' by Householder QR and
 * inverse iteration, with LAPACK's dgesvd as the fallback (its workspace
 * allocated at the first call that needs it, once per conica_subdivide()
 * call; no allocation per edge point). Internal to libcore. */
#ifndef CONICA_CONIC_FIT_H
#define CONICA_CONIC_FIT_H

#include <stddef.h>

/* Largest patch: 2 edge pairs + 4 outer neighbours per side (the growth
 * limit of the reference, REFERENCE.md section 1). */
#define CONICA__FIT_MAX_PAIRS 10
/* Matrix (2) generalised: 3 rows (point, normal x, normal y) and one alpha
 * column per pair, plus the 6 conic coefficients. */
#define CONICA__FIT_MAX_ROWS (3 * CONICA__FIT_MAX_PAIRS)
#define CONICA__FIT_MAX_COLS (6 + CONICA__FIT_MAX_PAIRS)

typedef struct conica__svdws {
    double *work; /* LAPACK workspace, lwork doubles (NULL until needed) */
    int lwork;
    size_t inverse, lapack; /* fits solved by inverse iteration / by LAPACK */
    double s[CONICA__FIT_MAX_COLS];
    double vt[CONICA__FIT_MAX_COLS * CONICA__FIT_MAX_COLS];
} conica__svdws;

/* An empty workspace (LAPACK's part is sized and allocated at the first
 * fit that needs it); always safe to free. */
void conica__svdws_init(conica__svdws *ws);
void conica__svdws_free(conica__svdws *ws);

/* Right singular vector of the m x n column-major matrix a (leading
 * dimension m, destroyed) for its smallest singular value, into v[0..n-1].
 * m <= CONICA__FIT_MAX_ROWS, n <= CONICA__FIT_MAX_COLS. Returns 0 on
 * success, -1 if out of memory or LAPACK reports a failure. */
int conica__svd_min_right(conica__svdws *ws, double *a, int m, int n, double *v);

#endif

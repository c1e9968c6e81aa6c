/* SPDX-License-Identifier: MIT */
/* LAPACK side of the general conic fit (see conic_fit.h). The long double
 * (precise) mode uses the one-sided Jacobi SVD in subdiv_impl.h instead,
 * since LAPACK has no extended-precision routines. */
#include "conic_fit.h"

#include <lapacke.h>
#include <stdlib.h>

int conica__svdws_init(conica__svdws *ws)
{
    double q, dummy = 0;
    int p, lwork = 1;

    ws->work = NULL;
    ws->lwork = 0;
    /* Workspace query for every patch size (2..MAX pairs), keep the max. */
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

int conica__svd_min_right(conica__svdws *ws, double *a, int m, int n, double *v)
{
    lapack_int info;
    int j;

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

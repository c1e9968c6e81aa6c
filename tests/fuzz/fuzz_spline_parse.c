/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the spline-file reader conica_bspline_parse() (.spl),
 * then the cheap operations every accepted spline must survive:
 * evaluation at the domain ends and middle, derivatives, knot insertion and
 * the Bezier form. */
#include "fuzz_common.h"

#include "conica/bspline.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *buf = fz_copy(data, size);
    conica_bspline s;
    conica_status st;
    conica_code rc;
    if (!buf)
        return 0;
    memset(&st, 0, sizeof st);
    conica_bspline_init(&s);
    rc = conica_bspline_parse(buf, size, &s, &st);
    fz_check_status(rc, &st);
    if (rc == CONICA_OK) {
        double a, b, pt[3], t[3];
        FZ_ASSERT(s.degree >= 1 && s.degree <= CONICA_BSPLINE_MAX_DEGREE);
        FZ_ASSERT(s.dim >= 1 && s.dim <= 3);
        FZ_ASSERT(s.n >= (size_t)s.degree + 1 && s.n <= CONICA_BSPLINE_MAX_CTRL);
        conica_bspline_domain(&s, &a, &b);
        FZ_ASSERT(isfinite(a) && isfinite(b) && a < b);
        t[0] = a;
        t[1] = b;
        t[2] = a + (b - a) * 0.5;
        for (int k = 0; k < 3; k++) {
            conica_code e = conica_bspline_eval(&s, t[k], pt, &st);
            fz_check_status(e, &st);
            e = conica_bspline_eval_deriv(&s, t[k], 1, pt, &st);
            fz_check_status(e, &st);
            size_t mu = conica_bspline_find_span(&s, t[k]);
            FZ_ASSERT(mu >= (size_t)s.degree && mu <= s.n - 1);
        }
        if (s.n <= 256) {
            conica_bspline bz;
            conica_bspline_init(&bz);
            rc = conica_bspline_to_bezier(&s, &bz, &st);
            fz_check_status(rc, &st);
            if (rc == CONICA_OK)
                FZ_ASSERT(bz.n == conica_bspline_bezier_count(&s) * (size_t)(s.degree + 1));
            conica_bspline_free(&bz);
            size_t n0 = s.n;
            rc = conica_bspline_insert_knot(&s, t[2], &st);
            fz_check_status(rc, &st);
            FZ_ASSERT(rc != CONICA_OK || s.n == n0 + 1);
        }
    }
    conica_bspline_free(&s);
    free(buf);
    return 0;
}
